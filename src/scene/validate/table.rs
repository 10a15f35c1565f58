//! A material's `spectral` table (n, k or albedo against wavelength): checked, and read at
//! a wavelength as a plain material (docs/physics.md §8). Depends on no other material
//! check, so that `materials` (each point a material of its own) and `spectral` (the
//! band's bins) both stand on it.

use super::values::err;
use super::ValidationError;
use crate::scene::request::{MaterialObject, SpectralSpec};

/// Most points of a material's table.
pub const MAX_POINTS: usize = 64;

/// The parameters a table may give, with their place in a material.
pub(super) const PARAMETERS: [&str; 3] = ["n", "k", "albedo"];

pub(super) fn column<'a>(s: &'a SpectralSpec, p: &str) -> Option<&'a Vec<f64>> {
    match p {
        "n" => s.n.as_ref(),
        "k" => s.k.as_ref(),
        _ => s.albedo.as_ref(),
    }
}

fn scalar(m: &MaterialObject, p: &str) -> Option<f64> {
    match p {
        "n" => m.n,
        "k" => m.k,
        _ => m.albedo,
    }
}

fn set(m: &mut MaterialObject, p: &str, v: f64) {
    match p {
        "n" => m.n = Some(v),
        "k" => m.k = Some(v),
        _ => m.albedo = Some(v),
    }
}

/// Checks a material's table (`field` is the material's path) and returns the material
/// without it, its tabulated parameters set to their values at `lambda_um` (linear
/// between points, constant beyond the ends).
pub(super) fn at(
    field: &str,
    m: &MaterialObject,
    lambda_um: f64,
) -> Result<MaterialObject, ValidationError> {
    let s = m.spectral.as_ref().expect("a spectral material");
    let f = format!("{field}.spectral");
    let w = &s.wavelength_um;
    if w.len() < 2 || w.len() > MAX_POINTS {
        return err(
            format!("{f}.wavelength_um"),
            format!("must have 2 to {MAX_POINTS} wavelengths, got {}", w.len()),
        );
    }
    for (i, &l) in w.iter().enumerate() {
        if !(l.is_finite() && l > 0.0) || (i > 0 && l <= w[i - 1]) {
            return err(
                format!("{f}.wavelength_um[{i}]"),
                "wavelengths must be finite, positive and increasing",
            );
        }
    }
    let mut given = 0;
    let mut out = m.clone();
    out.spectral = None;
    for p in PARAMETERS {
        let Some(col) = column(s, p) else { continue };
        given += 1;
        if scalar(m, p).is_some() {
            return err(
                format!("{f}.{p}"),
                format!("give `{p}` either as a number or in `spectral`, not both"),
            );
        }
        if col.len() != w.len() {
            return err(
                format!("{f}.{p}"),
                format!(
                    "must have one value per wavelength ({}), got {}",
                    w.len(),
                    col.len()
                ),
            );
        }
        let i = w.partition_point(|&x| x < lambda_um);
        let v = if i == 0 {
            col[0]
        } else if i == w.len() {
            col[w.len() - 1]
        } else {
            let t = (lambda_um - w[i - 1]) / (w[i] - w[i - 1]);
            col[i - 1] + t * (col[i] - col[i - 1])
        };
        set(&mut out, p, v);
    }
    if given == 0 {
        return err(f, "must give at least one of `n`, `k`, `albedo`");
    }
    Ok(out)
}
