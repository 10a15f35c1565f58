//! The result of a light-curve fit: the report assembled at the optimum, and the data of
//! the observed-against-fitted plot.

use super::free::{fitted_request, Target};
use super::observed::Observation;
use super::residuals::Problem;
use super::Options;
use crate::fit::params::{Bound, Named, SolverReport};
use crate::fit::solve::{Covariance, Solution};
use crate::scene::Request;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use utoipa::ToSchema;

/// The result of a light-curve fit.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct LightcurveFit {
    /// Fitted value of each free parameter, by path.
    #[schema(value_type = Object)]
    pub parameters: Named,
    /// 1σ of each (same units), from s²(JᵀJ)⁻¹ at the optimum; `null` where the light
    /// curve does not determine it.
    #[schema(value_type = Object)]
    pub uncertainty: BTreeMap<String, Option<f64>>,
    /// Where each started.
    #[schema(value_type = Object)]
    pub start: Named,
    /// Parameters that ended on a bound.
    pub at_bound: Vec<String>,
    /// χ² = Σ ((m_obs − m_fit)/σ)².
    pub chi2: f64,
    /// Observations − free parameters.
    pub dof: usize,
    /// χ²/dof (≈ 1 when the model explains the curve within its errors).
    pub chi2_dof: f64,
    /// RMS of m_obs − m_fit, mag.
    pub rms_mag: f64,
    /// Observations used.
    pub observations: usize,
    /// Correlations of the fitted parameters, in the order of `correlation_order`.
    pub correlation: Vec<Vec<Option<f64>>>,
    pub correlation_order: Vec<String>,
    /// Per observation: t (s), observed magnitude, σ, fitted magnitude (`null`: no light).
    pub curve: Vec<FittedEpoch>,
    /// The request with the fitted values in place (materials changed; the yaw folded into
    /// every epoch's `attitude`), ready to simulate.
    #[schema(value_type = Request)]
    pub request: serde_json::Value,
    pub warnings: Vec<String>,
    /// Evaluations are full light curves: `solver.evaluations` of them in
    /// `solver.wall_time_s`.
    pub solver: SolverReport,
}

/// One observation and the fitted model there.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
pub struct FittedEpoch {
    pub t: f64,
    pub observed: f64,
    pub sigma: f64,
    pub fitted: Option<f64>,
}

/// What a finished fit hands to its report.
pub(super) struct Fitted<'a> {
    pub request: &'a Request,
    pub observed: &'a [Observation],
    pub opts: &'a Options,
    /// Evaluated last at the optimum.
    pub problem: &'a Problem<'a>,
    pub bounds: &'a [Bound],
    pub start: &'a [f64],
    pub sol: Solution,
    pub cov: Covariance,
    /// The residuals at the optimum.
    pub residuals: &'a [f64],
    /// RMS of the residuals each solved start ended with, in the order solved.
    pub start_rms: Vec<f64>,
    pub started: std::time::Instant,
}

impl LightcurveFit {
    /// The report of a finished fit.
    pub(super) fn from_fitted(f: Fitted) -> LightcurveFit {
        let Fitted {
            request,
            observed,
            opts,
            problem,
            bounds,
            start,
            sol,
            cov,
            residuals: r,
            start_rms,
            started,
        } = f;
        let dark = problem.dark;
        let fitted = problem.last.borrow().clone();
        let chi2: f64 = r.iter().map(|x| x * x).sum();
        let n = observed.len();
        let p = problem.targets.len();
        let dof = n - p;
        let rms_mag = (observed
            .iter()
            .zip(&fitted)
            .map(|(o, m)| (o.magnitude - m.unwrap_or(dark)).powi(2))
            .sum::<f64>()
            / n as f64)
            .sqrt();
        let names = opts.free.clone();
        let parameters: Named = names
            .iter()
            .zip(problem.targets.iter().zip(&sol.p))
            .map(|(n, (t, &v))| (n.clone(), reported(t, v)))
            .collect();
        let uncertainty = names
            .iter()
            .cloned()
            .zip(cov.sigma.iter().copied())
            .collect();
        let at_bound: Vec<String> = names
            .iter()
            .zip(&sol.p)
            .zip(bounds)
            .filter(|((_, &v), b)| b.at_bound(v))
            .map(|((n, _), _)| n.clone())
            .collect();
        let warnings = warnings(&sol, &at_bound, &fitted, dark);
        let request_out = fitted_request(request, &problem.materials, &problem.targets, &sol.p);
        LightcurveFit {
            parameters,
            uncertainty,
            start: names.iter().cloned().zip(start.iter().copied()).collect(),
            at_bound,
            chi2,
            dof,
            chi2_dof: chi2 / dof.max(1) as f64,
            rms_mag,
            observations: n,
            correlation: cov.correlation,
            correlation_order: names,
            curve: observed
                .iter()
                .zip(&fitted)
                .map(|(o, m)| FittedEpoch {
                    t: o.t,
                    observed: o.magnitude,
                    sigma: o.sigma,
                    fitted: *m,
                })
                .collect(),
            request: request_out,
            warnings,
            solver: SolverReport {
                algorithm: "levenberg-marquardt".into(),
                loss: opts.loss.name().into(),
                starts: start_rms.len(),
                start_rms,
                evaluations: problem.evaluations(),
                converged: sol.converged,
                termination: sol.termination,
                wall_time_s: started.elapsed().as_secs_f64(),
            },
        }
    }
}

/// A fitted value as reported: a yaw in (−180°, 180°] (a turn more or less is the same
/// attitude), anything else as it is.
fn reported(target: &Target, v: f64) -> f64 {
    match target {
        Target::Yaw => {
            let w = v.rem_euclid(360.0);
            if w > 180.0 {
                w - 360.0
            } else {
                w
            }
        }
        Target::Material { .. } => v,
    }
}

/// Things to know about a fit: a solver stopped short, parameters on a bound, observed
/// epochs where the fitted model has no light (taken as `dark` mag).
fn warnings(sol: &Solution, at_bound: &[String], fitted: &[Option<f64>], dark: f64) -> Vec<String> {
    let mut warnings = Vec::new();
    if !sol.converged {
        warnings.push(format!(
            "the solver stopped before converging: {}",
            sol.termination
        ));
    }
    if !at_bound.is_empty() {
        warnings.push(format!(
            "{} ended on a bound: its uncertainty is one-sided",
            at_bound.join(", ")
        ));
    }
    let dark_epochs = fitted.iter().filter(|m| m.is_none()).count();
    if dark_epochs > 0 {
        warnings.push(format!(
            "the fitted model has no light at {dark_epochs} observed epochs (taken as {dark:.2} mag)"
        ));
    }
    warnings
}

impl LightcurveFit {
    /// The data of the observed-against-fitted plot.
    pub fn plot_data(&self) -> crate::report::fit_plot::LightcurvePlot {
        let mut curve = self.curve.clone();
        curve.sort_by(|a, b| a.t.total_cmp(&b.t));
        crate::report::fit_plot::LightcurvePlot {
            observed: curve.iter().map(|c| (c.t, c.observed, c.sigma)).collect(),
            fitted: curve.iter().map(|c| (c.t, c.fitted)).collect(),
        }
    }
}
