//! The fit itself: the request validated once, the free parameters resolved, the observed
//! epochs simulated in each evaluation, and one start solved.

use super::free::{resolve, Resolved};
use super::observed::{observed_epochs, Observation};
use super::report::{Fitted, LightcurveFit};
use super::residuals::Problem;
use super::Options;
use crate::fit::solve::{self, Residuals, Scale, Settings};
use crate::scene::{Limits, Request, Scene, ValidationError};
use std::cell::{Cell, RefCell};

/// Fits `opts.free` of `request` to `observed`. Errors name the field: `free[i]` for a
/// path that does not exist, `observed[i].t` for a time that is no epoch of the request,
/// `start.<path>` for a start outside the bounds.
pub fn fit(
    request: &Request,
    observed: &[Observation],
    opts: &Options,
) -> Result<LightcurveFit, ValidationError> {
    let started = std::time::Instant::now();
    if opts.free.is_empty() {
        return Err(ValidationError::new(
            "free",
            "name at least one free parameter",
        ));
    }
    let mut scene = Scene::from_request(request, &Limits::unlimited())?;
    scene.thumbnails = None;
    let Resolved {
        targets,
        bounds,
        start,
        materials,
    } = resolve(request, opts)?;
    let epochs = observed_epochs(&scene, observed)?;
    if observed.len() <= targets.len() {
        return Err(ValidationError::new(
            "observed",
            format!(
                "too few observations: {} for {} free parameters (need at least {})",
                observed.len(),
                targets.len(),
                targets.len() + 1
            ),
        ));
    }
    scene.epochs = epochs;
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
    let problem = Problem {
        scene: RefCell::new(scene),
        base,
        materials,
        targets,
        observed: observed.to_vec(),
        dark,
        last: RefCell::new(Vec::new()),
        evaluations: Cell::new(0),
        error: RefCell::new(None),
    };
    let settings = Settings {
        loss: opts.loss,
        scale: Scale::Known,
        tolerance: 1e-8,
        patience: 50,
        fd_step: 1e-5,
        max_rounds: 8,
    };
    let sol = solve::solve(&problem, &bounds, &start, &settings);
    if let Some(e) = problem.error.borrow_mut().take() {
        return Err(e);
    }
    let cov = solve::covariance(&problem, &bounds, &sol);
    // the curve at the optimum (the covariance's evaluations moved the scene)
    let mut r = vec![0.0; problem.count()];
    if !problem.eval(&sol.p, &mut r) {
        return Err(ValidationError::new(
            "free",
            "the model cannot be evaluated at the optimum",
        ));
    }
    Ok(LightcurveFit::from_fitted(Fitted {
        request,
        observed,
        opts,
        problem: &problem,
        bounds: &bounds,
        start: &start,
        sol,
        cov,
        residuals: &r,
        started,
    }))
}
