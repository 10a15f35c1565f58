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
    let fixed = fixed_values(specs, opts)?;
    let free: Vec<usize> = (0..specs.len()).filter(|&i| fixed[i].is_none()).collect();
    check_counts(samples, &free, opts.model)?;
    let floor = log_floor(samples, opts.space)?;
    let starts = opts.model.starts(samples, &fixed);
    let mut problem = Problem {
        model: opts.model,
        samples,
        free: free.clone(),
        base: with_fixed(&starts[0], &fixed),
        space: opts.space,
        floor,
    };
    let bounds: Vec<Bound> = free.iter().map(|&i| specs[i].bound).collect();
    let settings = Settings {
        loss: opts.loss,
        scale: Scale::Mad,
        ..Settings::default()
    };
    let (solutions, best, mut evaluations) =
        solve_starts(&problem, &bounds, &starts, &fixed, &settings, opts.loss);
    let cov = solve::covariance(&problem, &bounds, &best);
    evaluations += cov.evaluations;
    problem.base = problem.full(&best.p);
    let all = problem.base.clone();
    let brdf = opts.model.build(&all);
    Ok(BrdfFit::from_fitted(Fitted {
        opts,
        samples,
        specs,
        free: &free,
        fixed: &fixed,
        all: &all,
        brdf: &brdf,
        best: &best,
        cov,
        solutions: &solutions,
        starts: starts.len(),
        evaluations,
        started,
    }))
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
        let full = with_fixed(start, fixed);
        let p0: Vec<f64> = problem.free.iter().map(|&i| full[i]).collect();
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
