//! The result of a BRDF fit: the report assembled from the solver's best start, its
//! warnings, and the data of the Fig. 2-style plot.

use super::geometry::evaluate_at;
use super::model::{Model, ParamSpec};
use super::request::{Options, Space};
use super::samples::{evaluate, Sample};
use crate::brdf::albedo::Albedo;
use crate::brdf::Brdf;
use crate::fit::params::{Named, SolverReport};
use crate::fit::solve::{Covariance, Solution};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use utoipa::ToSchema;

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
    /// Whether the seed model was fitted in its normalised form (km the lobe's albedo at
    /// normal incidence, kd + km ≤ 1); absent when not.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub normalised: bool,
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

/// What a finished fit hands to its report.
pub(super) struct Fitted<'a> {
    pub opts: &'a Options,
    pub samples: &'a [Sample],
    pub specs: &'a [ParamSpec],
    /// Index of each free parameter in the model's list.
    pub free: &'a [usize],
    /// Each parameter's fixed value, `None` for a free one.
    pub fixed: &'a [Option<f64>],
    /// Every parameter's value at the optimum, in the model's order.
    pub all: &'a [f64],
    /// The BRDF of `all`.
    pub brdf: &'a Brdf,
    /// The best start, polished, its values those of the free parameters.
    pub best: &'a Solution,
    /// Free parameters (or `kd + km`) that ended on a bound.
    pub at_bound: Vec<String>,
    pub cov: Covariance,
    /// Each start's solution, in start order.
    pub solutions: &'a [Solution],
    pub starts: usize,
    pub evaluations: usize,
    pub started: std::time::Instant,
}

impl BrdfFit {
    /// The report of a finished fit.
    pub(super) fn from_fitted(f: Fitted) -> BrdfFit {
        let Fitted {
            opts,
            samples,
            specs,
            free,
            fixed,
            all,
            brdf,
            best,
            at_bound,
            cov,
            solutions,
            starts,
            evaluations,
            started,
        } = f;
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
        let (rms, rms_log) = misfit(samples, brdf);
        let albedo = crate::brdf::albedo::albedo(brdf);
        let mut wavelengths: Vec<f64> = samples.iter().filter_map(|s| s.wavelength_um).collect();
        wavelengths.sort_by(f64::total_cmp);
        wavelengths.dedup();
        let warnings = warnings(&wavelengths, albedo, &at_bound, best, &names, &cov.sigma);
        let parameters = opts.model.named(all);
        let mut material = serde_json::json!({ "name": "fitted", "model": opts.model.name() });
        for (k, v) in &parameters {
            material[k] = serde_json::json!(v);
        }
        if opts.model.is_normalised() {
            material["normalised"] = serde_json::json!(true);
        }
        let fixed_named: Named = free_complement(specs, fixed);
        BrdfFit {
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
            albedo: albedo.normal,
            normalised: opts.model.is_normalised(),
            correlation: cov.correlation,
            correlation_order: names,
            wavelengths_um: wavelengths,
            warnings,
            solver: SolverReport {
                algorithm: "levenberg-marquardt".into(),
                loss: opts.loss.name().into(),
                starts,
                start_rms: solutions.iter().map(|s| rms_of(&s.residuals)).collect(),
                evaluations,
                converged: best.converged,
                termination: best.termination.clone(),
                wall_time_s: started.elapsed().as_secs_f64(),
            },
            plot_svg: None,
        }
    }

    /// The fitted BRDF, rebuilt from `parameters`.
    pub fn brdf(&self) -> Option<Brdf> {
        let model = Model::parse(&self.model)?.with_normalised(self.normalised)?;
        let p: Option<Vec<f64>> = model
            .params()
            .iter()
            .map(|s| self.parameters.get(s.name).copied())
            .collect();
        model.try_build(&p?)
    }
}

/// Things to know about a fit: several wavelengths fitted as one, an albedo above 1,
/// parameters on a bound, a solver stopped short, parameters the samples do not determine
/// (`sigma` in the order of `names`).
fn warnings(
    wavelengths: &[f64],
    albedo: Albedo,
    at_bound: &[String],
    best: &Solution,
    names: &[String],
    sigma: &[Option<f64>],
) -> Vec<String> {
    let mut warnings = Vec::new();
    if wavelengths.len() > 1 {
        warnings.push(format!(
            "the samples span {} wavelengths; every model here is grey, so they were fitted together",
            wavelengths.len()
        ));
    }
    if albedo.normal > 1.0 {
        warnings.push(format!(
            "the fitted material reflects {:.2}× the light it receives at normal incidence \
             (the paper's Eq. 8 is not normalised; its own materials reflect 2.4× and 6.1×)",
            albedo.normal
        ));
    } else if albedo.max > 1.0 {
        warnings.push(format!(
            "the fitted material reflects {:.2}× the light it receives at {}° incidence \
             (at normal incidence {:.2}×): its Fresnel term rises towards grazing",
            albedo.max, albedo.max_at_deg, albedo.normal
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
        .zip(sigma)
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
    warnings
}

/// RMS of f_model − f_meas (sr⁻¹) over the samples, and of ln(f_model / f_meas) over those
/// where both are positive (`None` when there is none).
fn misfit(samples: &[Sample], brdf: &Brdf) -> (f64, Option<f64>) {
    let predicted: Vec<f64> = samples.iter().map(|s| evaluate(brdf, s)).collect();
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
    (rms, rms_log)
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
