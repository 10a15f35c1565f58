//! The fit itself: everything checked before the first light curve ([`prepare`]), the
//! starts screened and solved within the budget, the uncertainties, and the report.

use super::free::{resolve, Resolved, Target};
use super::observed::{observed_epochs, Observation};
use super::report::{Fitted, LightcurveFit};
use super::residuals::Problem;
use super::{Options, Run, SOLVED_STARTS};
use crate::fit::params::Bound;
use crate::fit::solve::{self, Residuals, Scale, Settings, Solution};
use crate::integrate::{Cancelled, Progress};
use crate::scene::{Limits, Request, Scene, ValidationError};
use std::cell::{Cell, RefCell};
use std::sync::atomic::AtomicUsize;

/// Why a fit gave no result.
#[derive(Debug, Clone, PartialEq)]
pub enum FitError {
    /// A field of the input, named.
    Invalid(ValidationError),
    /// Its [`Run::progress`] was cancelled.
    Cancelled,
}

impl From<ValidationError> for FitError {
    fn from(e: ValidationError) -> Self {
        FitError::Invalid(e)
    }
}

impl From<Cancelled> for FitError {
    fn from(_: Cancelled) -> Self {
        FitError::Cancelled
    }
}

/// A fit checked and ready to run: what [`fit_with`] needs before its first light
/// curve, and what a service checks before it accepts a fit job.
pub struct Prepared {
    request: Request,
    observed: Vec<Observation>,
    opts: Options,
    /// The request's scene, cut to the observed epochs, without thumbnails.
    scene: Scene,
    resolved: Resolved,
}

impl Prepared {
    /// Triangles of the mesh and light-curve epochs of one evaluation: with
    /// [`Options::max_evaluations`], what the whole fit may cost.
    pub fn size(&self) -> (usize, usize) {
        (self.scene.mesh.triangles.len(), self.scene.epochs.len())
    }

    /// The most light curves the fit may evaluate.
    pub fn max_evaluations(&self) -> usize {
        self.opts.max_evaluations
    }

    /// Refuses a fit whose work, counted before any is done, is over `limits`: each of the
    /// [`Options::max_evaluations`] light curves it may take is the observed epochs over
    /// the mesh, so triangles × epochs × light curves is held against
    /// `max_triangle_epochs`, and the `image` method's pixel samples against
    /// `max_pixel_samples`. Errors name `max_evaluations`.
    pub fn check_work(&self, limits: &Limits) -> Result<(), ValidationError> {
        let (triangles, epochs) = self.size();
        let curves = self.opts.max_evaluations as u64;
        let work = (triangles as u64)
            .saturating_mul(epochs as u64)
            .saturating_mul(curves);
        if work > limits.max_triangle_epochs {
            return Err(ValidationError::new(
                "max_evaluations",
                format!(
                    "too large a computation: {triangles} triangles × {epochs} observed epochs \
                     × {curves} light curves = {work} triangle-epochs (limit {}); allow fewer \
                     light curves, observe fewer epochs or use a coarser mesh",
                    limits.max_triangle_epochs
                ),
            ));
        }
        if self.scene.method == crate::scene::Method::Image {
            let side = |n: u32| (n as u64).pow(2);
            let samples = (epochs as u64)
                .saturating_mul(curves)
                .saturating_mul(side(self.scene.image_size))
                .saturating_mul(side(self.scene.image_samples));
            if samples > limits.max_pixel_samples {
                return Err(ValidationError::new(
                    "max_evaluations",
                    format!(
                        "too large a computation: {epochs} observed epochs × {curves} light \
                         curves of the `image` method = {samples} pixel samples (limit {})",
                        limits.max_pixel_samples
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Fits `opts.free` of `request` to `observed`, on this thread's engine
/// ([`crate::simulate_with`]). Errors name the field: `free[i]` for a path that does not
/// exist, `observed[i].t` for a time that is no epoch of the request, `start.<path>` for
/// a start outside the bounds, `max_evaluations` for a budget too small to fit with.
pub fn fit(
    request: &Request,
    observed: &[Observation],
    opts: &Options,
) -> Result<LightcurveFit, ValidationError> {
    let scene = Scene::from_request(request, &Limits::unlimited())?;
    let prepared = prepare(request, scene, observed, opts)?;
    let (progress, evaluations) = (Progress::new(), AtomicUsize::new(0));
    let run = Run {
        engine: crate::simulate_with,
        progress: &progress,
        evaluations: &evaluations,
    };
    fit_with(&prepared, &run).map_err(|e| match e {
        FitError::Invalid(e) => e,
        // nothing here cancels `progress`
        FitError::Cancelled => ValidationError::new("", "the fit was cancelled"),
    })
}

/// Checks a fit before any light curve is computed: the free paths and starts against
/// the request (`scene` is the request validated by the caller, with its own limits),
/// the observations against its epochs, their number against the free parameters, and the
/// budget against what the starts and the uncertainties need. Errors name the field.
pub fn prepare(
    request: &Request,
    mut scene: Scene,
    observed: &[Observation],
    opts: &Options,
) -> Result<Prepared, ValidationError> {
    if opts.free.is_empty() {
        return Err(ValidationError::new(
            "free",
            "name at least one free parameter",
        ));
    }
    scene.thumbnails = None;
    let resolved = resolve(request, opts)?;
    scene.epochs = observed_epochs(&scene, observed)?;
    let p = resolved.targets.len();
    if observed.len() <= p {
        return Err(ValidationError::new(
            "observed",
            format!(
                "too few observations: {} for {p} free parameters (need at least {})",
                observed.len(),
                p + 1
            ),
        ));
    }
    // the screening, a solve of a few steps, the uncertainties (2p) and the curve at the
    // optimum
    let least = screened(&resolved.targets, opts) + 4 * (p + 1) + 2 * p + 1;
    if opts.max_evaluations < least {
        return Err(ValidationError::new(
            "max_evaluations",
            format!(
                "{} light curves are too few to fit {p} parameters from these starts \
                 (at least {least})",
                opts.max_evaluations
            ),
        ));
    }
    Ok(Prepared {
        request: request.clone(),
        observed: observed.to_vec(),
        opts: opts.clone(),
        scene,
        resolved,
    })
}

/// Yaw starts screened: `opts.yaw_starts` with the yaw free, else none.
fn screened(targets: &[Target], opts: &Options) -> usize {
    if targets.iter().any(|t| matches!(t, Target::Yaw)) {
        opts.yaw_starts
    } else {
        0
    }
}

/// Runs a prepared fit: each evaluation a light curve on `run.engine` under
/// `run.progress`, counted in `run.evaluations`. `Err(Cancelled)` when the progress is
/// cancelled; the fit stops within the light curve it is computing.
pub fn fit_with(prepared: &Prepared, run: &Run) -> Result<LightcurveFit, FitError> {
    let started = std::time::Instant::now();
    let Prepared {
        request,
        observed,
        opts,
        resolved,
        ..
    } = prepared;
    let Resolved { bounds, start, .. } = resolved;
    let problem = problem(prepared, run);
    let solutions = solve_starts(&problem, bounds, &starts(&problem, start, opts), opts);
    stop_if_cancelled_or_invalid(&problem)?;
    let start_rms: Vec<f64> = solutions.iter().map(|s| rms(&s.residuals)).collect();
    let sol = best_solution(&problem, solutions, opts)?;
    // what was kept back: the uncertainties and the curve at the optimum
    problem.budget.set(opts.max_evaluations);
    let cov = solve::covariance(&problem, bounds, &sol);
    let mut r = vec![0.0; problem.count()];
    if !problem.eval(&sol.p, &mut r) {
        stop_if_cancelled_or_invalid(&problem)?;
        return Err(
            ValidationError::new("free", "the model cannot be evaluated at the optimum").into(),
        );
    }
    Ok(LightcurveFit::from_fitted(Fitted {
        request,
        observed,
        opts,
        problem: &problem,
        bounds,
        start,
        sol,
        cov,
        residuals: &r,
        start_rms,
        started,
    }))
}

/// The problem a fit solves: the scene's epochs before any yaw, the observations, the
/// magnitude taken where the model has no light (5 fainter than the faintest observed),
/// and the evaluation budget less what is kept back for the uncertainties (2p) and the
/// curve at the optimum.
fn problem<'a>(prepared: &Prepared, run: &'a Run<'a>) -> Problem<'a> {
    let Prepared {
        observed,
        opts,
        scene,
        resolved,
        ..
    } = prepared;
    let Resolved {
        targets, materials, ..
    } = resolved;
    let base = scene
        .epochs
        .iter()
        .map(|e| (e.sun, e.observer, e.earth))
        .collect();
    let dark = observed
        .iter()
        .map(|o| o.magnitude)
        .fold(f64::NEG_INFINITY, f64::max)
        + 5.0;
    let p = targets.len();
    Problem {
        scene: RefCell::new(scene.clone()),
        base,
        materials: materials.clone(),
        targets: targets.clone(),
        observed: observed.clone(),
        dark,
        run,
        budget: Cell::new(opts.max_evaluations - (2 * p + 1)),
        spent: Cell::new(false),
        cancelled: Cell::new(false),
        last: RefCell::new(Vec::new()),
        best: RefCell::new(None),
        error: RefCell::new(None),
    }
}

/// Each start solved in turn until the fit is stopped; a solve that ran out of budget
/// gives the best point evaluated so far.
fn solve_starts(
    problem: &Problem,
    bounds: &[Bound],
    starts: &[Vec<f64>],
    opts: &Options,
) -> Vec<Solution> {
    let settings = Settings {
        loss: opts.loss,
        scale: Scale::Known,
        tolerance: 1e-8,
        patience: 50,
        fd_step: 1e-5,
        max_rounds: 8,
    };
    let mut solutions = Vec::new();
    for s in starts {
        if problem.stopped() {
            break;
        }
        let sol = solve::solve(problem, bounds, s, &settings);
        solutions.push(if problem.spent.get() {
            budget_spent(problem, opts.max_evaluations)
        } else {
            sol
        });
    }
    solutions
}

/// The solution of least objective; with none, the best point evaluated before the
/// budget ran out; with no point evaluated, an error naming `max_evaluations`.
fn best_solution(
    problem: &Problem,
    solutions: Vec<Solution>,
    opts: &Options,
) -> Result<Solution, FitError> {
    solutions
        .into_iter()
        .min_by(|a, b| {
            let (oa, ob) = (
                solve::objective(opts.loss, &a.residuals, 1.0),
                solve::objective(opts.loss, &b.residuals, 1.0),
            );
            oa.total_cmp(&ob)
        })
        .or_else(|| {
            let spent = problem.best.borrow().is_some();
            spent.then(|| budget_spent(problem, opts.max_evaluations))
        })
        .ok_or_else(|| {
            ValidationError::new("max_evaluations", "no light curve could be evaluated").into()
        })
}

/// The starts to solve: with the yaw free, `opts.yaw_starts` yaws evenly round the
/// circle from its start, the others at theirs, each screened by one light curve, and
/// the [`SOLVED_STARTS`] of lowest χ² (in that order); otherwise `start` alone.
fn starts(problem: &Problem, start: &[f64], opts: &Options) -> Vec<Vec<f64>> {
    let Some(yaw) = problem
        .targets
        .iter()
        .position(|t| matches!(t, Target::Yaw))
    else {
        return vec![start.to_vec()];
    };
    if opts.yaw_starts <= 1 {
        return vec![start.to_vec()];
    }
    let step = 360.0 / opts.yaw_starts as f64;
    let mut screened: Vec<(f64, Vec<f64>)> = (0..opts.yaw_starts)
        .map(|k| {
            let mut p = start.to_vec();
            p[yaw] = start[yaw] + k as f64 * step;
            p
        })
        .map_while(|p| {
            let mut r = vec![0.0; problem.count()];
            if !problem.eval(&p, &mut r) {
                // cancelled, spent or an invalid material: each stops the fit, and the
                // caller looks which
                return None;
            }
            Some((r.iter().map(|x| x * x).sum::<f64>(), p))
        })
        .collect();
    // a stable sort: equal χ² keep the order round the circle, the given start first
    screened.sort_by(|a, b| a.0.total_cmp(&b.0));
    screened
        .into_iter()
        .take(SOLVED_STARTS)
        .map(|(_, p)| p)
        .collect()
}

/// The solution when the budget ran out: the point of lowest χ² evaluated so far.
fn budget_spent(problem: &Problem, max: usize) -> Solution {
    let (p, residuals) = problem
        .best
        .borrow()
        .clone()
        .map_or_else(Default::default, |b| (b.p, b.residuals));
    Solution {
        weights: vec![1.0; residuals.len()],
        p,
        residuals,
        scale: 1.0,
        evaluations: problem.evaluations(),
        converged: false,
        termination: format!("the budget of {max} light curves was spent"),
    }
}

/// A cancelled run, or a material error at some parameters, as the fit's error.
fn stop_if_cancelled_or_invalid(problem: &Problem) -> Result<(), FitError> {
    if problem.cancelled.get() {
        return Err(FitError::Cancelled);
    }
    if let Some(e) = problem.error.borrow_mut().take() {
        return Err(e.into());
    }
    Ok(())
}

fn rms(r: &[f64]) -> f64 {
    (r.iter().map(|x| x * x).sum::<f64>() / r.len().max(1) as f64).sqrt()
}
