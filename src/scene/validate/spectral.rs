//! Materials' `spectral` tables (n, k or albedo against wavelength) and the band's
//! wavelength bins they are evaluated in (docs/physics.md §8).

use super::materials::material;
use super::values::err;
use super::ValidationError;
use crate::radiometry::bands::SolarSpectrum;
use crate::radiometry::earth::gauss_legendre;
use crate::scene::request::{MaterialObject, MaterialSpec, Request, SpectralSpec};
use crate::scene::{Illumination, Material, SolarSpectrumChoice, SpectralBin};

/// Wavelength bins the band is cut into when a material depends on wavelength.
pub const BINS: usize = 16;
/// Most points of a material's table.
pub const MAX_POINTS: usize = 64;
/// The longest interval band a spectral material may be integrated over, µm.
pub const MAX_BAND_UM: f64 = 30.0;

/// The parameters a table may give, with their place in a material.
const PARAMETERS: [&str; 3] = ["n", "k", "albedo"];

fn column<'a>(s: &'a SpectralSpec, p: &str) -> Option<&'a Vec<f64>> {
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

/// Every point of a material's table validated as a material of its own; an error names
/// the table's entry (`….spectral.n[2]`).
pub(super) fn check_points(
    field: &str,
    m: &MaterialObject,
) -> Result<MaterialObject, ValidationError> {
    let s = m.spectral.as_ref().expect("a spectral material");
    let first = at(field, m, s.wavelength_um[0])?;
    for (j, &l) in s.wavelength_um.iter().enumerate() {
        let point = at(field, m, l)?;
        if let Err(e) = material(field, &MaterialSpec::Full(point)) {
            // a tabulated parameter out of its range: name the table's entry
            let named = PARAMETERS
                .iter()
                .find(|p| column(s, p).is_some() && e.field == format!("{field}.{p}"));
            return Err(match named {
                Some(p) => ValidationError::new(format!("{field}.spectral.{p}[{j}]"), e.message),
                None => e,
            });
        }
    }
    Ok(first)
}

/// The band's wavelength bins with every material in each, and the materials to report
/// (a spectral material at the bins' mean wavelength); no bins when no material has a
/// table.
pub(super) fn bins(
    req: &Request,
    materials: Vec<Material>,
    ill: &Illumination,
) -> Result<(Vec<Material>, Vec<SpectralBin>), ValidationError> {
    let spectral: Vec<(usize, &MaterialObject)> = req
        .object
        .materials
        .iter()
        .enumerate()
        .filter_map(|(i, m)| match m {
            MaterialSpec::Full(o) if o.spectral.is_some() => Some((i, o)),
            _ => None,
        })
        .collect();
    if spectral.is_empty() {
        return Ok((materials, Vec::new()));
    }
    // the band's quadrature nodes, weighted by the Sun's spectrum: g_i = w_i E_λ(λ_i)
    let sun = match ill.solar_spectrum {
        SolarSpectrumChoice::Planck => SolarSpectrum::Planck(ill.sun_temperature_k),
        SolarSpectrumChoice::Calspec => SolarSpectrum::Calspec,
    };
    let nodes: Vec<(f64, f64)> = match ill.passband {
        Some(p) => p.weights(),
        None => {
            let [a, b] = ill.band_um;
            if b - a > MAX_BAND_UM {
                return err(
                    "illumination.band_um",
                    format!(
                        "a material with a `spectral` table needs a band at most \
                         {MAX_BAND_UM} µm wide, got [{a}, {b}]"
                    ),
                );
            }
            // 8-point Gauss–Legendre on 64 equal pieces: energy-weighted, as the
            // interval band is
            let gl = gauss_legendre(8);
            let h = (b - a) / 64.0;
            (0..64)
                .flat_map(|k| {
                    gl.iter()
                        .map(move |&(x, w)| (a + h * (k as f64 + x), h * w))
                })
                .collect()
        }
    };
    let g: Vec<(f64, f64)> = nodes
        .iter()
        .map(|&(l, w)| (l, w * sun.irradiance_1au(l)))
        .filter(|&(_, x)| x > 0.0 && x.is_finite())
        .collect();
    let total: f64 = g.iter().map(|&(_, x)| x).sum();
    if g.is_empty() || total.is_nan() || total <= 0.0 {
        return err(
            "illumination",
            "the band holds no sunlight to integrate the spectral materials over",
        );
    }
    let (lo, hi) = (g[0].0, g[g.len() - 1].0);
    let width = (hi - lo) / BINS as f64;
    let mut sums = [(0.0f64, 0.0f64); BINS];
    for &(l, x) in &g {
        let k = if width > 0.0 {
            (((l - lo) / width) as usize).min(BINS - 1)
        } else {
            0
        };
        sums[k].0 += x;
        sums[k].1 += x * l;
    }
    let with_materials = |lambda: f64| -> Result<Vec<Material>, ValidationError> {
        let mut out = materials.clone();
        for &(i, m) in &spectral {
            let field = format!("object.materials[{i}]");
            let at = at(&field, m, lambda)?;
            out[i] = material(&field, &MaterialSpec::Full(at))?;
        }
        Ok(out)
    };
    let mut bins = Vec::new();
    let mut mean = 0.0;
    for &(x, xl) in sums.iter().filter(|s| s.0 > 0.0) {
        let lambda = xl / x;
        mean += xl / total;
        bins.push(SpectralBin {
            wavelength_um: lambda,
            share: x / total,
            materials: with_materials(lambda)?,
        });
    }
    Ok((with_materials(mean)?, bins))
}
