//! The body of a light-curve fit job (`POST /v1/fits/lightcurve`): what `glint
//! fit-lightcurve` takes as files and options, and the options checked from it.

use super::observed::Observation;
use super::{Options, DEFAULT_MAX_EVALUATIONS, DEFAULT_YAW_STARTS};
use crate::fit::solve::Loss;
use crate::scene::{Request, ValidationError};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use utoipa::ToSchema;

/// Most yaw starts a fit may screen.
pub const MAX_YAW_STARTS: usize = 360;

/// The body of `POST /v1/fits/lightcurve`.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct LightcurveFitRequest {
    /// The light-curve request (as `POST /v1/lightcurves` takes it): shape, materials and
    /// the epochs' geometry. Observed times must be epochs of it.
    pub request: Request,
    /// The observed magnitudes; more than there are free parameters.
    pub observed: Vec<Observation>,
    /// Free parameters by path: `materials.<name>.<parameter>` or `attitude.yaw_deg`.
    pub free: Vec<String>,
    /// Starting values by path (default: the request's values, yaw 0°).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Object>)]
    pub start: Option<BTreeMap<String, f64>>,
    /// `l2` (default: weighted least squares on magnitudes), `huber` or `cauchy`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loss: Option<String>,
    /// With the yaw free: yaws screened, evenly round the circle from its start (1 to 360;
    /// default 12). The three of lowest χ² are solved.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yaw_starts: Option<usize>,
    /// Most light curves the fit may evaluate, uncertainties included (default 400): the
    /// bound the job's `percent` counts against.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_evaluations: Option<usize>,
}

impl Options {
    /// The options of a fit body, each checked and named on error (`loss`, `yaw_starts`,
    /// `max_evaluations`; the free paths and starts are checked against the request by
    /// [`super::prepare`]).
    pub fn from_request(req: &LightcurveFitRequest) -> Result<Options, ValidationError> {
        let loss = match req.loss.as_deref() {
            None => Loss::L2,
            Some(s) => Loss::parse(s).ok_or_else(|| {
                ValidationError::new(
                    "loss",
                    format!("unknown loss `{s}`; expected l2, huber or cauchy"),
                )
            })?,
        };
        let yaw_starts = req.yaw_starts.unwrap_or(DEFAULT_YAW_STARTS);
        if !(1..=MAX_YAW_STARTS).contains(&yaw_starts) {
            return Err(ValidationError::new(
                "yaw_starts",
                format!("must be between 1 and {MAX_YAW_STARTS}, got {yaw_starts}"),
            ));
        }
        Ok(Options {
            free: req.free.clone(),
            start: req.start.clone().unwrap_or_default(),
            loss,
            yaw_starts,
            max_evaluations: req.max_evaluations.unwrap_or(DEFAULT_MAX_EVALUATIONS),
        })
    }
}
