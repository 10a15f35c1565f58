//! What to fit and how: the body of `POST /v1/fits/brdf` and the options checked from it.

use super::model::Model;
use super::samples::Sample;
use crate::fit::solve::Loss;
use crate::scene::ValidationError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use utoipa::ToSchema;

/// The body of `POST /v1/fits/brdf`: what `glint fit-brdf` takes as a CSV file and options.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct BrdfFitRequest {
    /// `seed-microfacet`, `rough-conductor`, `ashikhmin-shirley` or `lambert`.
    pub model: String,
    /// The measurements; at least one more than the free parameters.
    pub samples: Vec<Sample>,
    /// Parameters held at a value instead of fitted, by name (e.g. `{"n": 0.18, "k": 3.6}`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fixed: Option<BTreeMap<String, f64>>,
    /// `huber` (default), `cauchy` or `l2`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loss: Option<String>,
    /// Residual space: `log` (default) or `linear`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub space: Option<String>,
    /// Include the Fig. 2-style plot as SVG text in `plot_svg`. Default false.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plot: Option<bool>,
    /// `seed-microfacet` only: fit the normalised form (a request's `"normalised": true`),
    /// where km is the lobe's albedo at normal incidence and kd + km ≤ 1 is kept. Default
    /// false (the paper's form).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normalised: Option<bool>,
}

/// Residual space.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Space {
    Log,
    Linear,
}

/// What to fit and how.
#[derive(Debug, Clone)]
pub struct Options {
    pub model: Model,
    /// Parameters held fixed, by name.
    pub fixed: BTreeMap<String, f64>,
    pub loss: Loss,
    pub space: Space,
}

impl Options {
    /// The options of a request body, each checked and named on error.
    pub fn from_request(req: &BrdfFitRequest) -> Result<Options, ValidationError> {
        let model = Model::parse(&req.model).ok_or_else(|| {
            ValidationError::new(
                "model",
                format!("unknown model `{}`; expected {}", req.model, Model::NAMES),
            )
        })?;
        let model = model
            .with_normalised(req.normalised.unwrap_or(false))
            .ok_or_else(|| {
                ValidationError::new(
                    "normalised",
                    format!(
                        "applies only to model `seed-microfacet` (the request fits `{}`)",
                        req.model
                    ),
                )
            })?;
        let loss = match req.loss.as_deref() {
            None => Loss::Huber,
            Some(s) => Loss::parse(s).ok_or_else(|| {
                ValidationError::new(
                    "loss",
                    format!("unknown loss `{s}`; expected huber, cauchy or l2"),
                )
            })?,
        };
        let space = match req.space.as_deref() {
            None | Some("log") => Space::Log,
            Some("linear") => Space::Linear,
            Some(s) => {
                return Err(ValidationError::new(
                    "space",
                    format!("unknown space `{s}`; expected log or linear"),
                ))
            }
        };
        Ok(Options {
            model,
            fixed: req.fixed.clone().unwrap_or_default(),
            loss,
            space,
        })
    }
}
