//! Observations: one observed magnitude, the CSV they are read from, and the request's
//! epochs they were observed at.

use crate::scene::{Epoch, Scene, ValidationError};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// One observation of the object's apparent magnitude.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Observation {
    /// Time, seconds: the `t` of one of the request's epochs (Unix seconds for ISO times).
    pub t: f64,
    /// Apparent magnitude (the band of the request's illumination).
    pub magnitude: f64,
    /// 1σ error of the magnitude (> 0).
    pub sigma: f64,
}

/// Reads observations from CSV: a header with `t` and `magnitude` (or `mag`) and an error
/// column `sigma` (or `mag_err`, `magnitude_err`, `sigma_mag`); other columns are ignored,
/// so `glint simulate`'s CSV with an error column added is accepted. Without an error
/// column every row takes `default_sigma`, if given. Rows with an empty magnitude (no
/// detection) are skipped. Errors name `observed[i].column` and the line.
pub fn parse_observed_csv(
    text: &str,
    default_sigma: Option<f64>,
) -> Result<Vec<Observation>, ValidationError> {
    let (header, lines) =
        crate::fit::csv::header_and_rows(text, "observed", "the file has no header and no rows")?;
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |names: &[&str]| columns.iter().position(|c| names.contains(c));
    let t_col = find(&["t", "t_s"]).ok_or_else(|| {
        ValidationError::new("observed.t", format!("no `t` column (header: {header})"))
    })?;
    let m_col = find(&["magnitude", "mag"]).ok_or_else(|| {
        ValidationError::new(
            "observed.magnitude",
            format!("no `magnitude` column (header: {header})"),
        )
    })?;
    let s_col = find(&["sigma", "mag_err", "magnitude_err", "sigma_mag"]);
    if s_col.is_none() && default_sigma.is_none() {
        return Err(ValidationError::new(
            "observed.sigma",
            "no error column (`sigma`, `mag_err`) and no default σ given",
        ));
    }
    let mut out = Vec::new();
    for (i, (line, row)) in lines.enumerate() {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        let cell = |c: usize, name: &str| -> Result<&str, ValidationError> {
            cells.get(c).copied().ok_or_else(|| {
                ValidationError::new(
                    format!("observed[{i}].{name}"),
                    format!("line {line} has no `{name}` cell"),
                )
            })
        };
        let num = |c: usize, name: &str| -> Result<f64, ValidationError> {
            let s = cell(c, name)?;
            let v: f64 = s.parse().map_err(|_| {
                ValidationError::new(
                    format!("observed[{i}].{name}"),
                    format!("line {line}: `{s}` is not a number"),
                )
            })?;
            if !v.is_finite() {
                return Err(ValidationError::new(
                    format!("observed[{i}].{name}"),
                    format!("line {line}: must be a finite number"),
                ));
            }
            Ok(v)
        };
        if cell(m_col, "magnitude")?.is_empty() {
            continue;
        }
        let sigma = match s_col {
            Some(c) => num(c, "sigma")?,
            None => default_sigma.unwrap_or(f64::NAN),
        };
        if !(sigma > 0.0 && sigma.is_finite()) {
            return Err(ValidationError::new(
                format!("observed[{i}].sigma"),
                format!("line {line}: must be a finite number > 0, got {sigma}"),
            ));
        }
        out.push(Observation {
            t: num(t_col, "t")?,
            magnitude: num(m_col, "magnitude")?,
            sigma,
        });
    }
    Ok(out)
}

/// The epochs of `scene` that were observed, in the order observed; each observation
/// checked, errors on `observed[i].t` (no epoch at that time), `.magnitude`, `.sigma`.
pub(super) fn observed_epochs(
    scene: &Scene,
    observed: &[Observation],
) -> Result<Vec<Epoch>, ValidationError> {
    let times: Vec<f64> = scene.epochs.iter().map(|e| e.t).collect();
    let mut epochs = Vec::with_capacity(observed.len());
    for (i, o) in observed.iter().enumerate() {
        let f = |name: &str| format!("observed[{i}].{name}");
        if !o.t.is_finite() {
            return Err(ValidationError::new(f("t"), "must be a finite number"));
        }
        if !o.magnitude.is_finite() {
            return Err(ValidationError::new(
                f("magnitude"),
                "must be a finite number",
            ));
        }
        if !(o.sigma.is_finite() && o.sigma > 0.0) {
            return Err(ValidationError::new(
                f("sigma"),
                "must be a finite number > 0",
            ));
        }
        let tol = 1e-6 * o.t.abs().max(1.0);
        let Some(j) = times.iter().position(|&t| (t - o.t).abs() <= tol) else {
            return Err(ValidationError::new(
                f("t"),
                format!("t = {} s is not the time of any epoch of the request", o.t),
            ));
        };
        epochs.push(scene.epochs[j]);
    }
    Ok(epochs)
}
