//! A request's free parameters from an observed light curve: weighted least squares on
//! magnitudes, each evaluation a full light curve of the request's epochs that were
//! observed.
//!
//! **Free parameters** are named by path:
//! - `materials.<name>.<parameter>`: a numeric parameter of the material called `<name>`
//!   (a preset is expanded into its model and values first), within the bounds the
//!   request's validation takes: `albedo`; `kd`, `km`, `slope_rms`, `n`, `k`
//!   (seed-microfacet); `alpha`, `n`, `k`, `kd` (rough-conductor); `rd`, `rs`, `nu`, `nv`
//!   (ashikhmin-shirley);
//! - `attitude.yaw_deg`: a rotation ψ (degrees, positive counter-clockwise seen from +z) of
//!   the object about its own body z axis at every epoch, before the request's attitude:
//!   attitude′ = attitude · R_z(ψ) (body → inertial; the identity when an epoch has none).
//!   In the body frame every epoch's Sun, observer and Earth vectors turn by R_z(−ψ).
//!
//! **Residuals** r = (m_obs − m_model)/σ per observation. Where the model has no light at
//! all (its magnitude is `null`) it is taken as 5 mag fainter than the faintest
//! observation, so the fit is pushed back towards light without a NaN.
//!
//! **Starts.** With the yaw free, the fit starts from [`Options::yaw_starts`] yaws spread
//! evenly round the circle from the yaw's start (the other parameters at theirs), each
//! screened by one light curve; the [`SOLVED_STARTS`] of lowest χ² are solved and the
//! lowest minimum is the fit, so a start in the basin of a local minimum in yaw (a glint
//! that lines up at the wrong angle) does not decide it. The fitted yaw is reported in
//! (−180°, 180°]; an object that looks the same after a half-turn about z fits ψ and
//! ψ + 180° equally well, and either may come back.
//!
//! **Budget.** Each evaluation is a full light curve, so a fit takes at most
//! [`Options::max_evaluations`] of them, uncertainties included: that bound is what a
//! fit job's progress is measured against. A fit that spends it reports the point of
//! lowest χ² it evaluated, with a warning.
//!
//! Where things are: `request` (the body of a fit job, and its options), `observed` (the
//! observations and their CSV), `free` (the free parameters' paths, bounds and starts,
//! and the fitted request), `residuals` (one evaluation: the parameters put into the
//! scene, a light curve simulated), `fitting` (the checks before any work, the starts,
//! the fit), `report` (its result and plot data).

mod fitting;
mod free;
mod observed;
mod report;
mod request;
mod residuals;

pub use fitting::{fit, fit_with, prepare, FitError, Prepared};
pub use observed::{parse_observed_csv, Observation};
pub use report::{FittedEpoch, LightcurveFit};
pub use request::LightcurveFitRequest;

use crate::fit::solve::Loss;
use crate::integrate::{Cancelled, Progress};
use crate::scene::{Response, Scene};
use std::collections::BTreeMap;
use std::sync::atomic::AtomicUsize;

/// The path of the yaw offset among the free parameters.
pub const YAW: &str = "attitude.yaw_deg";

/// Yaw starts screened when the yaw is free and none is asked for: every 30°.
pub const DEFAULT_YAW_STARTS: usize = 12;

/// Most light curves a fit takes when none is asked for.
pub const DEFAULT_MAX_EVALUATIONS: usize = 400;

/// Of the screened yaw starts, how many (those of lowest χ²) are solved.
pub const SOLVED_STARTS: usize = 3;

/// What to fit.
#[derive(Debug, Clone)]
pub struct Options {
    /// Free parameter paths (`materials.panel.albedo`, `attitude.yaw_deg`).
    pub free: Vec<String>,
    /// Starting values by path; a parameter not named starts at the request's value (0
    /// for the yaw).
    pub start: BTreeMap<String, f64>,
    /// `l2` (default, weighted least squares), `huber` or `cauchy` (on r = Δm/σ).
    pub loss: Loss,
    /// With the yaw free: how many yaws, evenly spread round the circle from its start,
    /// are screened ([`DEFAULT_YAW_STARTS`]); 1 solves from the start alone.
    pub yaw_starts: usize,
    /// Most light curves the fit may evaluate, uncertainties included
    /// ([`DEFAULT_MAX_EVALUATIONS`]).
    pub max_evaluations: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            free: Vec::new(),
            start: BTreeMap::new(),
            loss: Loss::L2,
            yaw_starts: DEFAULT_YAW_STARTS,
            max_evaluations: DEFAULT_MAX_EVALUATIONS,
        }
    }
}

/// How a fit computes its light curves and is watched while it runs: the engine
/// ([`crate::simulate_with`] unless a caller swaps it), the [`Progress`] every light curve
/// runs under (cancelling it stops the fit within the light curve being computed), and
/// the count of light curves evaluated so far, readable from any thread.
pub struct Run<'a> {
    pub engine: fn(&Scene, &Progress) -> Result<Response, Cancelled>,
    pub progress: &'a Progress,
    pub evaluations: &'a AtomicUsize,
}
