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
//! Where things are: `observed` (the observations and their CSV), `free` (the free
//! parameters' paths, bounds and starts, and the fitted request), `residuals` (one
//! evaluation: the parameters put into the scene, a light curve simulated), `fitting`
//! (the fit), `report` (its result and plot data).

mod fitting;
mod free;
mod observed;
mod report;
mod residuals;

pub use fitting::fit;
pub use observed::{parse_observed_csv, Observation};
pub use report::{FittedEpoch, LightcurveFit};

use crate::fit::solve::Loss;
use std::collections::BTreeMap;

/// The path of the yaw offset among the free parameters.
pub const YAW: &str = "attitude.yaw_deg";

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
}
