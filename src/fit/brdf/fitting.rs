//! The fit itself: which parameters are free, the residuals of the samples, every start
//! solved and the best polished.

use super::model::{Model, ParamSpec};
use super::report::{BrdfFit, Fitted};
use super::request::{Options, Space};
use super::samples::{evaluate, validate_samples, Sample};
use crate::fit::params::{check_in_bound, Bound};
use crate::fit::solve::{self, Loss, Residuals, Scale, Settings, Solution};
use crate::scene::ValidationError;

pub(super) struct Problem<'a> {
    model: Model,
    samples: &'a [Sample],
    /// Index of each free parameter in the model's list.
    free: Vec<usize>,
    /// Every parameter's value; the free ones are overwritten per evaluation.
    base: Vec<f64>,
    space: Space,
    floor: f64,
    /// The normalised seed form with kd and km both free: their places in the solver's
    /// vector, which holds there their sum a = kd + km ∈ [0, 1] and kd's share
    /// s = kd/a ∈ [0, 1] (kd = a·s, km = a·(1 − s)): the box a solver keeps is then
    /// kd + km ≤ 1. `None`: the solver's values are the free parameters themselves.
    sum: Option<(usize, usize)>,
}

impl Problem<'_> {
    /// Every model parameter's value for the solver's values `p`.
    fn full(&self, p: &[f64]) -> Vec<f64> {
        let mut all = self.base.clone();
        for (&i, &v) in self.free.iter().zip(p) {
            all[i] = v;
        }
        if let Some((ia, is)) = self.sum {
            let (a, share) = (p[ia], p[is]);
            all[self.free[ia]] = a * share;
            all[self.free[is]] = a * (1.0 - share);
        }
        all
    }

    /// The solver's values for the model's values `all` ([`Problem::full`] undone).
    fn solver_values(&self, all: &[f64]) -> Vec<f64> {
        let mut p: Vec<f64> = self.free.iter().map(|&i| all[i]).collect();
        if let Some((ia, is)) = self.sum {
            let (kd, km) = (p[ia], p[is]);
            let a = kd + km;
            p[ia] = a;
            p[is] = if a > 0.0 { kd / a } else { 0.5 };
        }
        p
    }
}

impl Residuals for Problem<'_> {
    fn count(&self) -> usize {
        self.samples.len()
    }

    fn eval(&self, p: &[f64], out: &mut [f64]) -> bool {
        let Some(brdf) = self.model.try_build(&self.full(p)) else {
            return false;
        };
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
/// `fixed.<name>` (or `fixed` for kd + km above 1 in the normalised form), or `samples`
/// when there are too few.
pub fn fit(samples: &[Sample], opts: &Options) -> Result<BrdfFit, ValidationError> {
    let started = std::time::Instant::now();
    validate_samples(samples)?;
    let specs = opts.model.params();
    let fixed = fixed_values(specs, opts)?;
    let free: Vec<usize> = (0..specs.len()).filter(|&i| fixed[i].is_none()).collect();
    check_counts(samples, &free, opts.model)?;
    let floor = log_floor(samples, opts.space)?;
    // the free parameters' ranges in the model's own terms (km ≤ 1 − kd with kd fixed in
    // the normalised form), and the solver's (kd + km and kd's share for both free)
    let model_bounds = free_bounds(opts.model, specs, &free, &fixed)?;
    let sum = albedo_sum(opts.model, &free);
    let mut bounds = model_bounds.clone();
    if let Some((ia, is)) = sum {
        (bounds[ia], bounds[is]) = (Bound::new(0.0, 1.0), Bound::new(0.0, 1.0));
    }
    let starts = opts.model.starts(samples, &fixed);
    if starts.is_empty() {
        return Err(ValidationError::new(
            "fixed",
            "with the n and k fixed the lobe reflects nothing: its km cannot be an albedo",
        ));
    }
    let mut problem = Problem {
        model: opts.model,
        samples,
        free: free.clone(),
        base: with_fixed(&starts[0], &fixed),
        space: opts.space,
        floor,
        sum,
    };
    let settings = Settings {
        loss: opts.loss,
        scale: Scale::Mad,
        ..Settings::default()
    };
    let (solutions, best, mut evaluations) =
        solve_starts(&problem, &bounds, &starts, &fixed, &settings, opts.loss);
    let all = problem.full(&best.p);
    let mut at_bound: Vec<String> = Vec::new();
    if let Some((ia, _)) = sum {
        if bounds[ia].at_bound(best.p[ia]) {
            at_bound.push("kd + km".into());
        }
    }
    // the uncertainties in the model's own parameters: the same residuals, solved for
    // kd and km themselves (a change of variables moves no minimum)
    let best = Solution {
        p: free.iter().map(|&i| all[i]).collect(),
        ..best
    };
    problem.sum = None;
    let cov = solve::covariance(&problem, &model_bounds, &best);
    evaluations += cov.evaluations;
    problem.base = all.clone();
    let brdf = opts.model.try_build(&all).ok_or_else(|| {
        ValidationError::new("samples", "the fitted lobe reflects nothing (n ≈ 1, k ≈ 0)")
    })?;
    at_bound.extend(
        free.iter()
            .zip(&best.p)
            .zip(&model_bounds)
            .filter(|((_, &p), b)| b.at_bound(p))
            .map(|((&i, _), _)| specs[i].name.to_string()),
    );
    Ok(BrdfFit::from_fitted(Fitted {
        opts,
        samples,
        specs,
        free: &free,
        fixed: &fixed,
        all: &all,
        brdf: &brdf,
        best: &best,
        at_bound,
        cov,
        solutions: &solutions,
        starts: starts.len(),
        evaluations,
        started,
    }))
}

/// The range of each free parameter (in `free`'s order): its own, except in the normalised
/// seed form with one of kd and km fixed, where the other may take only what is left of 1.
/// Errors name `fixed` when the fixed kd and km add up to more than 1, or leave nothing.
fn free_bounds(
    model: Model,
    specs: &[ParamSpec],
    free: &[usize],
    fixed: &[Option<f64>],
) -> Result<Vec<Bound>, ValidationError> {
    let mut bounds: Vec<Bound> = free.iter().map(|&i| specs[i].bound).collect();
    if !model.is_normalised() {
        return Ok(bounds);
    }
    // kd (0) and km (1): the albedo at normal incidence is their sum, at most 1
    let too_much = |sum: f64| {
        ValidationError::new(
            "fixed",
            format!(
                "kd + km = {sum} leaves nothing of the albedo 1 (the normalised form's kd + km \
                 is the albedo at normal incidence)"
            ),
        )
    };
    match (fixed[0], fixed[1]) {
        (Some(kd), Some(km)) if kd + km > 1.0 => return Err(too_much(kd + km)),
        (Some(v), None) | (None, Some(v)) => {
            if v >= 1.0 {
                return Err(too_much(v));
            }
            let other = free.iter().position(|&i| i <= 1).expect("kd or km is free");
            bounds[other].hi = 1.0 - v;
        }
        _ => {}
    }
    Ok(bounds)
}

/// Where kd and km sit in the solver's vector when the normalised form has both free
/// (solved as their sum and kd's share, [`Problem::sum`]).
fn albedo_sum(model: Model, free: &[usize]) -> Option<(usize, usize)> {
    let kd = free.iter().position(|&i| i == 0)?;
    let km = free.iter().position(|&i| i == 1)?;
    model.is_normalised().then_some((kd, km))
}

/// The values `opts.fixed` holds, in the model's parameter order (`None`: free). Errors
/// name `fixed.<name>`.
fn fixed_values(specs: &[ParamSpec], opts: &Options) -> Result<Vec<Option<f64>>, ValidationError> {
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
        check_in_bound(field, v, specs[i].bound)?;
        fixed[i] = Some(v);
    }
    Ok(fixed)
}

/// Something left to fit, and more samples than free parameters.
fn check_counts(samples: &[Sample], free: &[usize], model: Model) -> Result<(), ValidationError> {
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
                model.name(),
                free.len() + 1
            ),
        ));
    }
    Ok(())
}

/// f₀ of the log residuals: a thousandth of the smallest positive measurement (0 when
/// there is none, which only linear space can fit).
fn log_floor(samples: &[Sample], space: Space) -> Result<f64, ValidationError> {
    let min_positive = samples
        .iter()
        .map(|s| s.brdf_sr)
        .filter(|&v| v > 0.0)
        .fold(f64::INFINITY, f64::min);
    if space == Space::Log && !min_positive.is_finite() {
        return Err(ValidationError::new(
            "samples",
            "every brdf_sr is 0: nothing to fit in log space",
        ));
    }
    Ok(if min_positive.is_finite() {
        1e-3 * min_positive
    } else {
        0.0
    })
}

/// A start's values with the fixed ones in place.
fn with_fixed(start: &[f64], fixed: &[Option<f64>]) -> Vec<f64> {
    start
        .iter()
        .enumerate()
        .map(|(i, &v)| fixed[i].unwrap_or(v))
        .collect()
}

/// Every start solved, and the best of them polished: (each start's solution, the best,
/// evaluations spent).
fn solve_starts(
    problem: &Problem,
    bounds: &[Bound],
    starts: &[Vec<f64>],
    fixed: &[Option<f64>],
    settings: &Settings,
    loss: Loss,
) -> (Vec<Solution>, Solution, usize) {
    let mut solutions = Vec::new();
    let mut evaluations = 0;
    for start in starts {
        let p0 = problem.solver_values(&with_fixed(start, fixed));
        let sol = solve::solve(problem, bounds, &p0, settings);
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
            let oa = solve::objective(loss, &a.residuals, scale);
            let ob = solve::objective(loss, &b.residuals, scale);
            oa.total_cmp(&ob)
        })
        .expect("at least one start")
        .clone();
    // polish: restart from the best minimum (a fresh trust region) while that lowers
    // the objective; a flat valley (n, k against k^M) can stop a run short
    let mut best = best;
    for _ in 0..4 {
        let again = solve::solve(problem, bounds, &best.p, settings);
        evaluations += again.evaluations;
        let (old, new) = (
            solve::objective(loss, &best.residuals, scale),
            solve::objective(loss, &again.residuals, scale),
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
    (solutions, best, evaluations)
}
