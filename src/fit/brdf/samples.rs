//! BRDF samples: one measurement's angles and value, their checks, the CSV they are read
//! from and written to, and synthetic samples of a known model.

use super::geometry::evaluate_at;
use crate::brdf::Brdf;
use crate::scene::ValidationError;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// One BRDF measurement.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Sample {
    /// Incidence zenith angle θi, degrees, 0 ≤ θi < 90.
    pub theta_i_deg: f64,
    /// Reflection (detector) zenith angle θr, degrees, 0 ≤ θr < 90.
    pub theta_r_deg: f64,
    /// Relative azimuth φ, degrees, −360..360; 180 is the forward side of the plane of
    /// incidence (the mirror direction at θr = θi), 0 the backward side.
    pub phi_deg: f64,
    /// The measured BRDF, sr⁻¹ (≥ 0).
    pub brdf_sr: f64,
    /// Relative weight (> 0; default 1): its squared residual counts this many times
    /// (1/σ² for a known error σ in the residual space).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weight: Option<f64>,
    /// Wavelength, µm (> 0), informative: every model here is grey.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wavelength_um: Option<f64>,
}

/// The BRDF f (sr⁻¹) of `brdf` at sample `s`'s angles: the model's f·cosθi·cosθr over the
/// two cosines (both positive: the angles are below 90°).
pub fn evaluate(brdf: &Brdf, s: &Sample) -> f64 {
    evaluate_at(brdf, s.theta_i_deg, s.theta_r_deg, s.phi_deg)
}

/// Checks every sample, naming the first bad field as `samples[i].name`.
pub fn validate_samples(samples: &[Sample]) -> Result<(), ValidationError> {
    for (i, s) in samples.iter().enumerate() {
        let f = |name: &str| format!("samples[{i}].{name}");
        let check = |name: &str, v: f64, lo: f64, hi: f64, hi_open: bool| {
            if !v.is_finite() {
                return Err(ValidationError::new(f(name), "must be a finite number"));
            }
            let above = if hi_open { v >= hi } else { v > hi };
            if v < lo || above {
                let close = if hi_open { ")" } else { "]" };
                return Err(ValidationError::new(
                    f(name),
                    format!("{v} is out of range [{lo}, {hi}{close}"),
                ));
            }
            Ok(())
        };
        check("theta_i_deg", s.theta_i_deg, 0.0, 90.0, true)?;
        check("theta_r_deg", s.theta_r_deg, 0.0, 90.0, true)?;
        check("phi_deg", s.phi_deg, -360.0, 360.0, false)?;
        check("brdf_sr", s.brdf_sr, 0.0, f64::MAX, false)?;
        if let Some(w) = s.weight {
            if !(w.is_finite() && w > 0.0) {
                return Err(ValidationError::new(
                    f("weight"),
                    "must be a finite number > 0",
                ));
            }
        }
        if let Some(w) = s.wavelength_um {
            if !(w.is_finite() && w > 0.0) {
                return Err(ValidationError::new(
                    f("wavelength_um"),
                    "must be a finite number > 0",
                ));
            }
        }
    }
    Ok(())
}

/// Reads samples from CSV text: a header naming `theta_i_deg`, `theta_r_deg`, `phi_deg`,
/// `brdf_sr` and optionally `weight` and `wavelength_um`, in any order; blank lines and
/// lines starting with `#` are skipped. An error names the line and the column as
/// `samples[i].column (line L)`.
pub fn parse_csv(text: &str) -> Result<Vec<Sample>, ValidationError> {
    const KNOWN: [&str; 6] = [
        "theta_i_deg",
        "theta_r_deg",
        "phi_deg",
        "brdf_sr",
        "weight",
        "wavelength_um",
    ];
    let (header, lines) =
        crate::fit::csv::header_and_rows(text, "samples", "the file has no header and no samples")?;
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    for c in &columns {
        if !KNOWN.contains(c) {
            return Err(ValidationError::new(
                format!("header.{c}"),
                format!("unknown column `{c}`; expected {}", KNOWN.join(", ")),
            ));
        }
    }
    let index = |name: &str| columns.iter().position(|c| *c == name);
    for required in &KNOWN[..4] {
        if index(required).is_none() {
            return Err(ValidationError::new(
                format!("header.{required}"),
                format!("missing column `{required}` (header: {header})"),
            ));
        }
    }
    let mut samples = Vec::new();
    for (i, (line, text)) in lines.enumerate() {
        let cells: Vec<&str> = text.split(',').map(str::trim).collect();
        if cells.len() != columns.len() {
            return Err(ValidationError::new(
                format!("samples[{i}]"),
                format!(
                    "line {line} has {} cells, the header {}",
                    cells.len(),
                    columns.len()
                ),
            ));
        }
        let get = |name: &str| -> Result<Option<f64>, ValidationError> {
            let Some(c) = index(name) else {
                return Ok(None);
            };
            let cell = cells[c];
            if cell.is_empty() && (name == "weight" || name == "wavelength_um") {
                return Ok(None);
            }
            cell.parse::<f64>().map(Some).map_err(|_| {
                ValidationError::new(
                    format!("samples[{i}].{name}"),
                    format!("line {line}: `{cell}` is not a number"),
                )
            })
        };
        let need = |name: &str| get(name).map(|v| v.unwrap_or(f64::NAN));
        samples.push(Sample {
            theta_i_deg: need("theta_i_deg")?,
            theta_r_deg: need("theta_r_deg")?,
            phi_deg: need("phi_deg")?,
            brdf_sr: need("brdf_sr")?,
            weight: get("weight")?,
            wavelength_um: get("wavelength_um")?,
        });
    }
    // a value error names the data line too
    validate_samples(&samples).map_err(|e| {
        let line = e
            .field
            .strip_prefix("samples[")
            .and_then(|r| r.split(']').next())
            .and_then(|n| n.parse::<usize>().ok())
            .and_then(|n| data_line(text, n));
        match line {
            Some(l) => ValidationError::new(e.field, format!("line {l}: {}", e.message)),
            None => e,
        }
    })?;
    Ok(samples)
}

/// The 1-based line number of data row `n` (after the header) of CSV text.
fn data_line(text: &str, n: usize) -> Option<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim().starts_with('#'))
        .nth(n + 1)
        .map(|(i, _)| i + 1)
}

/// Writes samples as CSV (the columns `parse_csv` reads), with `comment` lines first.
pub fn to_csv(samples: &[Sample], comment: &str) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    for line in comment.lines() {
        let _ = writeln!(s, "# {line}");
    }
    s.push_str("theta_i_deg,theta_r_deg,phi_deg,brdf_sr\n");
    for x in samples {
        let _ = writeln!(
            s,
            "{},{},{},{:.6e}",
            x.theta_i_deg, x.theta_r_deg, x.phi_deg, x.brdf_sr
        );
    }
    s
}

/// Synthetic samples of `brdf` at `geometry`, each multiplied by e^{σ·N(0,1)} (log-normal
/// relative noise of `noise`; 0 for none), N drawn from a generator seeded with `seed`
/// (splitmix64, Box–Muller): the same seed gives the same file on every machine.
pub fn synthetic(brdf: &Brdf, geometry: &[(f64, f64, f64)], noise: f64, seed: u64) -> Vec<Sample> {
    let mut state = seed;
    let mut uniform = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    };
    geometry
        .iter()
        .map(|&(ti, tr, phi)| {
            let u1 = uniform().max(1e-300);
            let u2 = uniform();
            let normal = (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
            Sample {
                theta_i_deg: ti,
                theta_r_deg: tr,
                phi_deg: phi,
                brdf_sr: evaluate_at(brdf, ti, tr, phi) * (noise * normal).exp(),
                weight: None,
                wavelength_um: None,
            }
        })
        .collect()
}
