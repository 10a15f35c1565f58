//! A material's parameters from measured BRDF samples (the paper's §5.1 step, its Fig. 2).
//!
//! **Angles.** A sample gives the incidence zenith θi, the reflection zenith θr and the
//! relative azimuth φ between the two directions' planes, in degrees, with φ = 180° the
//! forward side of the plane of incidence, where the mirror direction lies. In the face
//! frame (normal z, tangent x), the direction towards the light is
//! l = (sin θi, 0, cos θi) and towards the detector v = (sin θr cos φ, sin θr sin φ, cos θr):
//! θr = θi at φ = 180° is the mirror direction (−l_x, −l_y, l_z) — the specular peak.
//!
//! **Residuals.** In `log` space (the default) r = ln(f_model + f₀) − ln(f_meas + f₀), f₀ a
//! thousandth of the smallest positive measurement (so a zero measurement is usable): a
//! BRDF spans five decades between its diffuse floor and a glossy peak, and a relative error
//! is what a goniometer's is. In `linear` space r = f_model − f_meas (sr⁻¹). Either is
//! multiplied by √weight.

use super::params::{Bound, Named, SolverReport};
use super::solve::{self, Loss, Residuals, Scale, Settings};
use crate::brdf::{AshikhminShirley, Brdf, Frame, Lambert, RoughConductor, SeedMicrofacet};
use crate::scene::ValidationError;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
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

/// The body of `POST /v1/fits/brdf`: what `glint fit-brdf` takes as a CSV file and options.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BrdfFitRequest {
    /// `seed-microfacet`, `rough-conductor`, `ashikhmin-shirley` or `lambert`.
    pub model: String,
    /// The measurements; at least one more than the free parameters.
    pub samples: Vec<Sample>,
    /// Parameters held at a value instead of fitted, by name (e.g. `{"n": 0.18, "k": 3.6}`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fixed: Option<BTreeMap<String, f64>>,
    /// `huber` (default), `cauchy` or `l2`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loss: Option<String>,
    /// Residual space: `log` (default) or `linear`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub space: Option<String>,
    /// Include the Fig. 2-style plot as SVG text in `plot_svg`. Default false.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plot: Option<bool>,
}

/// The result of a BRDF fit.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct BrdfFit {
    /// The model fitted.
    pub model: String,
    /// Every parameter of the model, fitted or fixed, under the name a request's material
    /// takes (paste them into `object.materials[..]` with this `model`).
    #[schema(value_type = Object)]
    pub parameters: Named,
    /// 1σ of each fitted parameter (same units), from s²(JᵀJ)⁻¹ at the optimum; `null`
    /// where the samples do not determine it.
    #[schema(value_type = Object)]
    pub uncertainty: BTreeMap<String, Option<f64>>,
    /// The parameters held fixed.
    #[schema(value_type = Object)]
    pub fixed: Named,
    /// Fitted parameters that ended on a bound (their uncertainty is then one-sided).
    pub at_bound: Vec<String>,
    /// A material object ready for a request (named `fitted`).
    #[schema(value_type = Object)]
    pub material: serde_json::Value,
    /// RMS of f_model − f_meas over the samples, sr⁻¹ (unweighted).
    pub rms: f64,
    /// RMS of ln(f_model / f_meas) over the samples where both are positive (≈ relative
    /// RMS); `null` when there is none.
    pub rms_log: Option<f64>,
    /// Residual standard deviation per degree of freedom in the fit's space, s.
    pub residual_sd: f64,
    /// Samples used.
    pub samples: usize,
    /// Degrees of freedom: samples − fitted parameters.
    pub dof: usize,
    /// Samples the robust loss weighted below ½ (outliers).
    pub outliers: usize,
    /// Residual space: `log` or `linear`.
    pub space: String,
    /// Directional-hemispherical albedo of the fitted material at normal incidence.
    pub albedo: f64,
    /// Correlations of the fitted parameters, in the order of `correlation_order`.
    pub correlation: Vec<Vec<Option<f64>>>,
    pub correlation_order: Vec<String>,
    /// Distinct wavelengths in the samples, µm.
    pub wavelengths_um: Vec<f64>,
    /// Things to know about this fit.
    pub warnings: Vec<String>,
    pub solver: SolverReport,
    /// The plot (SVG text) when the request asked for it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plot_svg: Option<String>,
}

/// One parameter of a model.
#[derive(Debug, Clone, Copy)]
pub struct ParamSpec {
    /// Its name in a request's material.
    pub name: &'static str,
    pub bound: Bound,
}

/// The models that can be fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    Lambert,
    SeedMicrofacet,
    RoughConductor,
    AshikhminShirley,
}

/// Upper bound of a refractive index's parts, as the request's validation takes them.
const INDEX_MAX: f64 = 1e3;

const LAMBERT: &[ParamSpec] = &[ParamSpec {
    name: "albedo",
    bound: Bound::new(0.0, 1.0),
}];
const SEED: &[ParamSpec] = &[
    ParamSpec {
        name: "kd",
        bound: Bound::new(0.0, 1.0),
    },
    ParamSpec {
        name: "km",
        bound: Bound::new(0.0, 1e3),
    },
    ParamSpec {
        name: "slope_rms",
        bound: Bound::new(1e-6, 10.0),
    },
    ParamSpec {
        name: "n",
        bound: Bound::new(1e-6, INDEX_MAX),
    },
    ParamSpec {
        name: "k",
        bound: Bound::new(0.0, INDEX_MAX),
    },
];
const ROUGH: &[ParamSpec] = &[
    ParamSpec {
        name: "alpha",
        bound: Bound::new(1e-6, 10.0),
    },
    ParamSpec {
        name: "n",
        bound: Bound::new(1e-6, INDEX_MAX),
    },
    ParamSpec {
        name: "k",
        bound: Bound::new(0.0, INDEX_MAX),
    },
    ParamSpec {
        name: "kd",
        bound: Bound::new(0.0, 1.0),
    },
];
/// Ashikhmin–Shirley with nu = nv: the samples' relative azimuth cannot tell a lobe's
/// orientation on the face, so the exponent is fitted once and reported as both.
const ASHIKHMIN: &[ParamSpec] = &[
    ParamSpec {
        name: "rd",
        bound: Bound::new(0.0, 1.0),
    },
    ParamSpec {
        name: "rs",
        bound: Bound::new(0.0, 1.0),
    },
    ParamSpec {
        name: "nu",
        bound: Bound::new(0.0, 1e7),
    },
];

impl Model {
    pub const NAMES: &'static str =
        "seed-microfacet, rough-conductor, ashikhmin-shirley or lambert";

    pub fn parse(name: &str) -> Option<Model> {
        match name {
            "lambert" => Some(Model::Lambert),
            "seed-microfacet" => Some(Model::SeedMicrofacet),
            "rough-conductor" => Some(Model::RoughConductor),
            "ashikhmin-shirley" => Some(Model::AshikhminShirley),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Model::Lambert => "lambert",
            Model::SeedMicrofacet => "seed-microfacet",
            Model::RoughConductor => "rough-conductor",
            Model::AshikhminShirley => "ashikhmin-shirley",
        }
    }

    /// The parameters, in the order [`Model::build`] takes them.
    pub fn params(self) -> &'static [ParamSpec] {
        match self {
            Model::Lambert => LAMBERT,
            Model::SeedMicrofacet => SEED,
            Model::RoughConductor => ROUGH,
            Model::AshikhminShirley => ASHIKHMIN,
        }
    }

    /// The BRDF of parameters `p` (in [`Model::params`] order): as a request's material
    /// of this model with these values builds it (seed-microfacet in the paper's form,
    /// `normalised: false`; rough-conductor with separable shadowing).
    pub fn build(self, p: &[f64]) -> Brdf {
        match self {
            Model::Lambert => Brdf::Lambert(Lambert { albedo: p[0] }),
            Model::SeedMicrofacet => {
                Brdf::SeedMicrofacet(SeedMicrofacet::new(p[0], p[1], p[2], p[3], p[4]))
            }
            Model::RoughConductor => {
                Brdf::RoughConductor(RoughConductor::new(p[0], p[1], p[2], p[3]))
            }
            Model::AshikhminShirley => {
                Brdf::AshikhminShirley(AshikhminShirley::new(p[0], p[1], p[2], p[2]))
            }
        }
    }

    /// Parameters by request name (Ashikhmin–Shirley's exponent as both `nu` and `nv`).
    fn named(self, p: &[f64]) -> Named {
        let mut out: Named = self
            .params()
            .iter()
            .zip(p)
            .map(|(s, &v)| (s.name.to_string(), v))
            .collect();
        if self == Model::AshikhminShirley {
            out.insert("nv".into(), p[2]);
        }
        out
    }

    /// Starting points: a grid over the lobe's width (and the index of refraction), with
    /// the scale of the lobe set from the data, so that a narrow specular lobe between
    /// samples is found. Values are inside the bounds; fixed ones are overwritten later.
    fn starts(self, samples: &[Sample], fixed: &[Option<f64>]) -> Vec<Vec<f64>> {
        let mut values: Vec<f64> = samples.iter().map(|s| s.brdf_sr).collect();
        values.sort_by(f64::total_cmp);
        let q25 = values[values.len() / 4];
        let diffuse = (std::f64::consts::PI * q25).clamp(1e-3, 0.95);
        let fix = |i: usize, v: f64| fixed[i].unwrap_or(v);
        match self {
            Model::Lambert => vec![vec![fix(0, diffuse.min(0.95))]],
            Model::SeedMicrofacet => {
                let kd = fix(0, diffuse);
                let mut out = Vec::new();
                for (n, k) in [(0.2, 3.0), (1.5, 0.0)] {
                    let (n, k) = (fix(3, n), fix(4, k));
                    for slope in [0.003, 0.01, 0.03, 0.1, 0.3, 1.0] {
                        let slope = fix(2, slope);
                        // k^M from the samples the unit lobe lights: the median of
                        // (f − kd/π) / f_lobe over those within a decade of its peak
                        let unit = Model::SeedMicrofacet.build(&[0.0, 1.0, slope, n, k]);
                        let lobe: Vec<f64> = samples.iter().map(|s| evaluate(&unit, s)).collect();
                        let peak = lobe.iter().copied().fold(0.0, f64::max);
                        let mut ratios: Vec<f64> = samples
                            .iter()
                            .zip(&lobe)
                            .filter(|(_, &g)| g > 0.1 * peak && g > 0.0)
                            .map(|(s, g)| (s.brdf_sr - kd / std::f64::consts::PI).max(0.0) / g)
                            .collect();
                        ratios.sort_by(f64::total_cmp);
                        let km = ratios.get(ratios.len() / 2).copied().unwrap_or(0.1);
                        let km = fix(1, km.clamp(1e-4, 900.0));
                        out.push(vec![kd, km, slope, n, k]);
                        if fixed[2].is_some() {
                            break;
                        }
                    }
                    if fixed[3].is_some() && fixed[4].is_some() {
                        break;
                    }
                }
                out
            }
            Model::RoughConductor => {
                let mut out = Vec::new();
                for (n, k) in [(0.2, 3.0), (1.5, 0.5)] {
                    for alpha in [0.01, 0.03, 0.1, 0.3, 0.8] {
                        out.push(vec![fix(0, alpha), fix(1, n), fix(2, k), fix(3, diffuse)]);
                        if fixed[0].is_some() {
                            break;
                        }
                    }
                    if fixed[1].is_some() && fixed[2].is_some() {
                        break;
                    }
                }
                out
            }
            Model::AshikhminShirley => {
                let mut out = Vec::new();
                for rs in [0.05, 0.5] {
                    for exponent in [3.0, 30.0, 300.0, 3e3, 3e4, 3e5] {
                        out.push(vec![fix(0, diffuse), fix(1, rs), fix(2, exponent)]);
                        if fixed[2].is_some() {
                            break;
                        }
                    }
                    if fixed[1].is_some() {
                        break;
                    }
                }
                out
            }
        }
    }
}

/// The face frame of every sample: normal z, tangent x.
const FRAME: Frame = Frame {
    n: DVec3::Z,
    t: DVec3::X,
};

/// Unit directions towards the light and the detector of a sample (face frame: normal z,
/// the light in the x–z plane at positive x; φ = 180° puts the detector at negative x).
pub fn directions(theta_i_deg: f64, theta_r_deg: f64, phi_deg: f64) -> (DVec3, DVec3) {
    let (ti, tr, phi) = (
        theta_i_deg.to_radians(),
        theta_r_deg.to_radians(),
        phi_deg.to_radians(),
    );
    let l = DVec3::new(ti.sin(), 0.0, ti.cos());
    let v = DVec3::new(tr.sin() * phi.cos(), tr.sin() * phi.sin(), tr.cos());
    (l, v)
}

/// The BRDF f (sr⁻¹) of `brdf` at a sample's angles: the model's f·cosθi·cosθr over the
/// two cosines (both positive: the angles are below 90°).
pub fn evaluate(brdf: &Brdf, s: &Sample) -> f64 {
    evaluate_at(brdf, s.theta_i_deg, s.theta_r_deg, s.phi_deg)
}

/// [`evaluate`] at angles in degrees.
pub fn evaluate_at(brdf: &Brdf, theta_i_deg: f64, theta_r_deg: f64, phi_deg: f64) -> f64 {
    let (l, v) = directions(theta_i_deg, theta_r_deg, phi_deg);
    let (ci, cr) = (l.z, v.z);
    if ci <= 0.0 || cr <= 0.0 {
        return 0.0;
    }
    brdf.projected(&FRAME, l, v) / (ci * cr)
}

/// Residual space.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Space {
    Log,
    Linear,
}

/// What to fit and how.
#[derive(Debug, Clone)]
pub struct Options {
    pub model: Model,
    /// Parameters held fixed, by name.
    pub fixed: BTreeMap<String, f64>,
    pub loss: Loss,
    pub space: Space,
}

impl Options {
    /// The options of a request body, each checked and named on error.
    pub fn from_request(req: &BrdfFitRequest) -> Result<Options, ValidationError> {
        let model = Model::parse(&req.model).ok_or_else(|| {
            ValidationError::new(
                "model",
                format!("unknown model `{}`; expected {}", req.model, Model::NAMES),
            )
        })?;
        let loss = match req.loss.as_deref() {
            None => Loss::Huber,
            Some(s) => Loss::parse(s).ok_or_else(|| {
                ValidationError::new(
                    "loss",
                    format!("unknown loss `{s}`; expected huber, cauchy or l2"),
                )
            })?,
        };
        let space = match req.space.as_deref() {
            None | Some("log") => Space::Log,
            Some("linear") => Space::Linear,
            Some(s) => {
                return Err(ValidationError::new(
                    "space",
                    format!("unknown space `{s}`; expected log or linear"),
                ))
            }
        };
        Ok(Options {
            model,
            fixed: req.fixed.clone().unwrap_or_default(),
            loss,
            space,
        })
    }
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
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(ValidationError::new(
            "samples",
            "the file has no header and no samples",
        ));
    };
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

struct Problem<'a> {
    model: Model,
    samples: &'a [Sample],
    /// Index of each free parameter in the model's list.
    free: Vec<usize>,
    /// Every parameter's value; the free ones are overwritten per evaluation.
    base: Vec<f64>,
    space: Space,
    floor: f64,
}

impl Problem<'_> {
    fn full(&self, p: &[f64]) -> Vec<f64> {
        let mut all = self.base.clone();
        for (&i, &v) in self.free.iter().zip(p) {
            all[i] = v;
        }
        all
    }
}

impl Residuals for Problem<'_> {
    fn count(&self) -> usize {
        self.samples.len()
    }

    fn eval(&self, p: &[f64], out: &mut [f64]) -> bool {
        let brdf = self.model.build(&self.full(p));
        for (o, s) in out.iter_mut().zip(self.samples) {
            let f = evaluate(&brdf, s);
            let r = match self.space {
                Space::Log => (f + self.floor).ln() - (s.brdf_sr + self.floor).ln(),
                Space::Linear => f - s.brdf_sr,
            };
            *o = r * s.weight.unwrap_or(1.0).sqrt();
            if !o.is_finite() {
                return false;
            }
        }
        true
    }
}

/// Fits `opts.model` to `samples`. Errors name the field: a sample's (`samples[3].phi_deg`),
/// `fixed.<name>`, or `samples` when there are too few.
pub fn fit(samples: &[Sample], opts: &Options) -> Result<BrdfFit, ValidationError> {
    let started = std::time::Instant::now();
    validate_samples(samples)?;
    let specs = opts.model.params();
    let mut fixed = vec![None; specs.len()];
    for (name, &v) in &opts.fixed {
        let field = format!("fixed.{name}");
        let Some(i) = specs.iter().position(|s| s.name == name) else {
            let names: Vec<&str> = specs.iter().map(|s| s.name).collect();
            return Err(ValidationError::new(
                field,
                format!(
                    "`{name}` is not a parameter of model `{}` ({})",
                    opts.model.name(),
                    names.join(", ")
                ),
            ));
        };
        if !v.is_finite() || !specs[i].bound.contains(v) {
            return Err(ValidationError::new(
                field,
                format!("{v} is out of range {}", specs[i].bound.describe()),
            ));
        }
        fixed[i] = Some(v);
    }
    let free: Vec<usize> = (0..specs.len()).filter(|&i| fixed[i].is_none()).collect();
    if free.is_empty() {
        return Err(ValidationError::new(
            "fixed",
            "every parameter is fixed: nothing to fit",
        ));
    }
    if samples.len() <= free.len() {
        return Err(ValidationError::new(
            "samples",
            format!(
                "too few samples: {} for {} free parameters of `{}` (need at least {})",
                samples.len(),
                free.len(),
                opts.model.name(),
                free.len() + 1
            ),
        ));
    }
    let min_positive = samples
        .iter()
        .map(|s| s.brdf_sr)
        .filter(|&v| v > 0.0)
        .fold(f64::INFINITY, f64::min);
    if opts.space == Space::Log && !min_positive.is_finite() {
        return Err(ValidationError::new(
            "samples",
            "every brdf_sr is 0: nothing to fit in log space",
        ));
    }
    let floor = if min_positive.is_finite() {
        1e-3 * min_positive
    } else {
        0.0
    };
    let starts = opts.model.starts(samples, &fixed);
    let base = |start: &[f64]| -> Vec<f64> {
        start
            .iter()
            .enumerate()
            .map(|(i, &v)| fixed[i].unwrap_or(v))
            .collect()
    };
    let mut problem = Problem {
        model: opts.model,
        samples,
        free: free.clone(),
        base: base(&starts[0]),
        space: opts.space,
        floor,
    };
    let bounds: Vec<Bound> = free.iter().map(|&i| specs[i].bound).collect();
    let settings = Settings {
        loss: opts.loss,
        scale: Scale::Mad,
        ..Settings::default()
    };
    let mut solutions = Vec::new();
    let mut evaluations = 0;
    for start in &starts {
        let full = base(start);
        let p0: Vec<f64> = free.iter().map(|&i| full[i]).collect();
        let sol = solve::solve(&problem, &bounds, &p0, &settings);
        evaluations += sol.evaluations;
        solutions.push(sol);
    }
    // compare the minima at one scale: the smallest any start reached
    let scale = solutions
        .iter()
        .map(|s| solve::mad(&s.residuals))
        .filter(|s| *s > 0.0)
        .fold(f64::INFINITY, f64::min);
    let best = solutions
        .iter()
        .min_by(|a, b| {
            let oa = solve::objective(opts.loss, &a.residuals, scale);
            let ob = solve::objective(opts.loss, &b.residuals, scale);
            oa.total_cmp(&ob)
        })
        .expect("at least one start")
        .clone();
    // polish: restart from the best minimum (a fresh trust region) while that lowers
    // the objective; a flat valley (n, k against k^M) can stop a run short
    let mut best = best;
    for _ in 0..4 {
        let again = solve::solve(&problem, &bounds, &best.p, &settings);
        evaluations += again.evaluations;
        let (old, new) = (
            solve::objective(opts.loss, &best.residuals, scale),
            solve::objective(opts.loss, &again.residuals, scale),
        );
        if new < old {
            let gain = (old - new) / old.max(1e-300);
            best = again;
            if gain < 1e-3 {
                break;
            }
        } else {
            break;
        }
    }
    let cov = solve::covariance(&problem, &bounds, &best);
    evaluations += cov.evaluations;
    problem.base = problem.full(&best.p);
    let all = problem.base.clone();
    let brdf = opts.model.build(&all);

    let names: Vec<String> = free.iter().map(|&i| specs[i].name.to_string()).collect();
    let mut uncertainty: BTreeMap<String, Option<f64>> = names
        .iter()
        .cloned()
        .zip(cov.sigma.iter().copied())
        .collect();
    if opts.model == Model::AshikhminShirley {
        if let Some(s) = uncertainty.get("nu").copied() {
            uncertainty.insert("nv".into(), s);
        }
    }
    let at_bound: Vec<String> = free
        .iter()
        .zip(&best.p)
        .filter(|(&i, &p)| specs[i].bound.at_bound(p))
        .map(|(&i, _)| specs[i].name.to_string())
        .collect();
    let predicted: Vec<f64> = samples.iter().map(|s| evaluate(&brdf, s)).collect();
    let rms = (samples
        .iter()
        .zip(&predicted)
        .map(|(s, f)| (f - s.brdf_sr).powi(2))
        .sum::<f64>()
        / samples.len() as f64)
        .sqrt();
    let logs: Vec<f64> = samples
        .iter()
        .zip(&predicted)
        .filter(|(s, f)| s.brdf_sr > 0.0 && **f > 0.0)
        .map(|(s, f)| (f / s.brdf_sr).ln())
        .collect();
    let rms_log = (!logs.is_empty())
        .then(|| (logs.iter().map(|x| x * x).sum::<f64>() / logs.len() as f64).sqrt());
    let albedo = crate::brdf::albedo::directional(&brdf, 0.0, 0.0);
    let mut wavelengths: Vec<f64> = samples.iter().filter_map(|s| s.wavelength_um).collect();
    wavelengths.sort_by(f64::total_cmp);
    wavelengths.dedup();
    let mut warnings = Vec::new();
    if wavelengths.len() > 1 {
        warnings.push(format!(
            "the samples span {} wavelengths; every model here is grey, so they were fitted together",
            wavelengths.len()
        ));
    }
    if albedo > 1.0 {
        warnings.push(format!(
            "the fitted material reflects {albedo:.2}× the light it receives at normal incidence \
             (the paper's Eq. 8 is not normalised; its own materials reflect 2.4× and 6.1×)"
        ));
    }
    if !at_bound.is_empty() {
        warnings.push(format!(
            "{} ended on a bound: its uncertainty is one-sided",
            at_bound.join(", ")
        ));
    }
    if !best.converged {
        warnings.push(format!(
            "the solver stopped before converging: {}",
            best.termination
        ));
    }
    let none: Vec<&String> = names
        .iter()
        .zip(&cov.sigma)
        .filter(|(_, s)| s.is_none())
        .map(|(n, _)| n)
        .collect();
    if !none.is_empty() {
        warnings.push(format!(
            "the samples do not determine {} (no uncertainty): fix it with `fixed`",
            none.iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let parameters = opts.model.named(&all);
    let mut material = serde_json::json!({ "name": "fitted", "model": opts.model.name() });
    for (k, v) in &parameters {
        material[k] = serde_json::json!(v);
    }
    let fixed_named: Named = free_complement(specs, &fixed);
    Ok(BrdfFit {
        model: opts.model.name().into(),
        parameters,
        uncertainty,
        fixed: fixed_named,
        at_bound,
        material,
        rms,
        rms_log,
        residual_sd: cov.s2.sqrt(),
        samples: samples.len(),
        dof: samples.len() - free.len(),
        outliers: best.weights.iter().filter(|&&w| w < 0.5).count(),
        space: match opts.space {
            Space::Log => "log".into(),
            Space::Linear => "linear".into(),
        },
        albedo,
        correlation: cov.correlation,
        correlation_order: names,
        wavelengths_um: wavelengths,
        warnings,
        solver: SolverReport {
            algorithm: "levenberg-marquardt".into(),
            loss: opts.loss.name().into(),
            starts: starts.len(),
            start_rms: solutions.iter().map(|s| rms_of(&s.residuals)).collect(),
            evaluations,
            converged: best.converged,
            termination: best.termination.clone(),
            wall_time_s: started.elapsed().as_secs_f64(),
        },
        plot_svg: None,
    })
}

fn rms_of(r: &[f64]) -> f64 {
    (r.iter().map(|x| x * x).sum::<f64>() / r.len().max(1) as f64).sqrt()
}

fn free_complement(specs: &[ParamSpec], fixed: &[Option<f64>]) -> Named {
    specs
        .iter()
        .zip(fixed)
        .filter_map(|(s, v)| v.map(|v| (s.name.to_string(), v)))
        .collect()
}

impl BrdfFit {
    /// The fitted BRDF, rebuilt from `parameters`.
    pub fn brdf(&self) -> Option<Brdf> {
        let model = Model::parse(&self.model)?;
        let p: Option<Vec<f64>> = model
            .params()
            .iter()
            .map(|s| self.parameters.get(s.name).copied())
            .collect();
        Some(model.build(&p?))
    }
}

/// What the Fig. 2-style plot draws, per incidence angle: the samples and the model's
/// curve, both against the signed reflection angle (+θr on the forward side of the plane
/// of incidence, −θr on the backward side).
pub fn plot_data(samples: &[Sample], brdf: &Brdf) -> Vec<crate::report::fit_plot::Incidence> {
    use crate::report::fit_plot::Incidence;
    let mut incidences: Vec<f64> = samples
        .iter()
        .map(|s| (s.theta_i_deg * 10.0).round() / 10.0)
        .collect();
    incidences.sort_by(f64::total_cmp);
    incidences.dedup();
    incidences
        .iter()
        .map(|&ti| {
            let mut points = Vec::new();
            let mut off_plane = Vec::new();
            for s in samples
                .iter()
                .filter(|s| ((s.theta_i_deg * 10.0).round() / 10.0) == ti)
            {
                let c = s.phi_deg.to_radians().cos();
                let x = if c <= 0.0 {
                    s.theta_r_deg
                } else {
                    -s.theta_r_deg
                };
                let in_plane = s.phi_deg.to_radians().sin().abs() < 0.05;
                if in_plane {
                    points.push((x, s.brdf_sr));
                } else {
                    off_plane.push((x, s.brdf_sr));
                }
            }
            // the curve, dense enough to draw a lobe of a few tenths of a degree
            let mut xs: Vec<f64> = (-890..=890).map(|i| i as f64 * 0.1).collect();
            // and through the mirror direction, where a narrow lobe peaks
            xs.push(ti);
            xs.sort_by(f64::total_cmp);
            let curve = xs
                .into_iter()
                .map(|x| {
                    let phi = if x >= 0.0 { 180.0 } else { 0.0 };
                    (x, evaluate_at(brdf, ti, x.abs(), phi))
                })
                .collect();
            Incidence {
                theta_i_deg: ti,
                points,
                off_plane,
                curve,
            }
        })
        .collect()
}

/// The measurement geometry of the paper's Fig. 2, as `glint sample-brdf` lays it out:
/// incidence 10°, 30°, 45°, 60°; in the plane of incidence every 5° forward (φ = 180°) and
/// every 10° backward (φ = 0°), every 0.25° within 3° of the mirror direction, and five
/// points off the plane at θr = θi. (θi, θr, φ) in degrees.
pub fn paper_geometry() -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for ti in [10.0, 30.0, 45.0, 60.0] {
        for i in 0..=17 {
            let tr = 5.0 * i as f64;
            out.push((ti, tr, 180.0));
            if i % 2 == 0 {
                out.push((ti, tr, 0.0));
            }
        }
        for j in -12..=12 {
            let tr: f64 = ti + 0.25 * j as f64;
            if tr != ti && (0.0..89.0).contains(&tr) {
                out.push((ti, tr, 180.0));
            }
        }
        for phi in [150.0, 170.0, 175.0, 178.0, 179.0] {
            out.push((ti, ti, phi));
        }
    }
    out
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
