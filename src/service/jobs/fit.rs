//! A light-curve fit as a job (`POST /v1/fits/lightcurve`): its body checked with the job
//! limits before it is accepted, its run on the job pool, and how far it has come. Each
//! of its evaluations is a light curve, so its progress is light curves evaluated against
//! the most it may take, and its epochs are those light curves' epochs.

use super::{Entry, Evaluations, JobKind};
use crate::fit::lightcurve::{self, FitError, LightcurveFitRequest, Options, Prepared, Run};
use crate::integrate::Progress;
use crate::scene::{validate, Scene, ValidationError};
use crate::service::errors::ApiError;
use crate::service::limits::ServiceLimits;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The fit a body asks for, checked with the job limits: errors name the body's field
/// (`request.…` for the light-curve request's own), a fit too large for the limits is a
/// 413 on `max_evaluations`.
fn prepared(text: &str, limits: &ServiceLimits) -> Result<Prepared, ValidationError> {
    let body: LightcurveFitRequest = validate::parse_json(text)?;
    let opts = Options::from_request(&body)?;
    let job_limits = limits.job_limits();
    let scene = Scene::from_request(&body.request, &job_limits).map_err(|e| {
        let field = match e.field.as_str() {
            "" => "request".to_string(),
            f => format!("request.{f}"),
        };
        ValidationError::new(field, e.message)
    })?;
    let prepared = lightcurve::prepare(&body.request, scene, &body.observed, &opts)?;
    prepared.check_work(&job_limits)?;
    Ok(prepared)
}

/// What a fit job's record holds before it runs: the epochs it may compute (observed
/// epochs × its most light curves) and its light curves (none yet).
pub(crate) fn accepted(
    text: &str,
    limits: &ServiceLimits,
) -> Result<(usize, Evaluations), ApiError> {
    let p = prepared(text, limits)?;
    let max = p.max_evaluations();
    Ok((p.size().1.saturating_mul(max), Evaluations { done: 0, max }))
}

/// Runs the fit a stored body asks for on this thread (the caller installs the job pool),
/// its light curves on `engine` under `progress` and counted in `evaluations`: the result
/// JSON and the epochs computed, `None` when cancelled, or the error's text.
pub(crate) fn run(
    text: &str,
    limits: &ServiceLimits,
    engine: crate::service::Engine,
    progress: &Progress,
    evaluations: &AtomicUsize,
) -> Result<Option<(Vec<u8>, usize)>, String> {
    let prepared = prepared(text, limits).map_err(|e| e.to_string())?;
    let run = Run {
        engine,
        progress,
        evaluations,
    };
    match lightcurve::fit_with(&prepared, &run) {
        Ok(fit) => {
            let json = serde_json::to_vec(&fit).map_err(|e| e.to_string())?;
            let epochs = prepared.size().1 * fit.solver.evaluations;
            Ok(Some((json, epochs)))
        }
        Err(FitError::Cancelled) => Ok(None),
        Err(FitError::Invalid(e)) => Err(e.to_string()),
    }
}

impl Entry {
    /// Epochs the current run has computed: a light curve's as its progress counts them;
    /// a fit's, its light curves times the epochs of each.
    pub(super) fn epochs_so_far(&self) -> usize {
        match (self.rec.kind, self.rec.evaluations) {
            (JobKind::FitLightcurve, Some(ev)) if ev.max > 0 => {
                self.evaluations.load(Ordering::Relaxed) * (self.rec.epochs_total / ev.max)
            }
            _ => self.progress.done(),
        }
    }

    /// A fit's light curves evaluated: by the current run while it runs, else as last
    /// recorded. `None` for a light-curve job.
    pub(super) fn evaluations_so_far(&self) -> Option<Evaluations> {
        let mut ev = self.rec.evaluations?;
        if self.rec.state == super::JobState::Running {
            ev.done = self.evaluations.load(Ordering::Relaxed);
        }
        Some(ev)
    }
}
