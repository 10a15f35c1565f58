//! `POST /v1/fits/brdf`: material parameters fitted to measured BRDF samples, within the
//! request timeout, on the light-curve pool. `POST /v1/fits/lightcurve`: a light-curve
//! fit, as a job (each evaluation is a light curve).

use super::jobs::{accepted, idempotency_key};
use super::{example_request, JsonBody};
use crate::fit::brdf::{self as fit_brdf, BrdfFit, BrdfFitRequest};
use crate::fit::lightcurve::LightcurveFitRequest;
use crate::scene::validate;
use crate::service::errors::{ApiError, ErrorBody};
use crate::service::jobs::JobStatus;
use crate::service::threads::run_blocking;
use crate::service::AppState;
use axum::extract::State;
use axum::http::{HeaderMap, StatusCode};
use axum::response::Response as HttpResponse;
use axum::Json;

/// An example body of `POST /v1/fits/brdf`: a few samples of a glossy paint.
pub fn example_brdf_fit() -> serde_json::Value {
    serde_json::json!({
        "model": "lambert",
        "samples": [
            { "theta_i_deg": 30.0, "theta_r_deg": 0.0, "phi_deg": 180.0, "brdf_sr": 0.16 },
            { "theta_i_deg": 30.0, "theta_r_deg": 30.0, "phi_deg": 180.0, "brdf_sr": 0.15 },
            { "theta_i_deg": 30.0, "theta_r_deg": 60.0, "phi_deg": 0.0, "brdf_sr": 0.17 }
        ]
    })
}

/// Fit a material model to measured BRDF samples.
///
/// What `glint fit-brdf` does with a CSV file: bounded, robust (Huber by default)
/// Levenberg–Marquardt from several starts; the parameters come back under the names a
/// request's material takes, with 1σ uncertainties from the Jacobian at the optimum.
#[utoipa::path(
    post, path = "/v1/fits/brdf", tag = "fits",
    request_body(content = BrdfFitRequest, content_type = "application/json",
        example = json!(example_brdf_fit())),
    responses(
        (status = 200, description = "The fitted parameters", body = BrdfFit),
        (status = 400, description = "Malformed JSON or body", body = ErrorBody),
        (status = 401, description = "Missing or wrong bearer token", body = ErrorBody),
        (status = 413, description = "Body over the size limit", body = ErrorBody),
        (status = 415, description = "Content-Type is not application/json", body = ErrorBody),
        (status = 422, description = "A bad sample, model or option; `field` names it (e.g. `samples[3].phi_deg`)", body = ErrorBody),
        (status = 503, description = "Busy (see `Retry-After`), or over the request timeout", body = ErrorBody),
    )
)]
pub async fn post_brdf_fit(
    State(st): State<AppState>,
    JsonBody(body): JsonBody,
) -> Result<Json<BrdfFit>, ApiError> {
    let timeout = st.limits.request_timeout;
    let work = async {
        let slot = st.slots.acquire().await.map_err(|_| ApiError::busy(1))?;
        let pool = st.pools.sync.clone();
        // a panic in the fit is answered as every other computation's: the request id,
        // never the panic's text (which `ApiError::internal` of the join error carried)
        run_blocking("the fit", move || -> Result<BrdfFit, ApiError> {
            let _slot = slot;
            let text = std::str::from_utf8(&body)
                .map_err(|e| ApiError::bad_request(format!("request body is not UTF-8: {e}")))?;
            let req: BrdfFitRequest = validate::parse_json(text)?;
            let opts = fit_brdf::Options::from_request(&req)?;
            let mut result = pool.install(|| fit_brdf::fit(&req.samples, &opts))?;
            if req.plot == Some(true) {
                let brdf = result
                    .brdf()
                    .ok_or_else(|| ApiError::internal("fitted parameters"))?;
                let groups = fit_brdf::plot_data(&req.samples, &brdf);
                let title = format!("{} fit", result.model);
                result.plot_svg = Some(
                    crate::report::fit_plot::brdf_svg(&title, &groups)
                        .map_err(ApiError::internal)?,
                );
            }
            Ok(result)
        })
        .await?
    };
    let result = tokio::time::timeout(timeout, work).await.map_err(|_| {
        ApiError::new(
            StatusCode::SERVICE_UNAVAILABLE,
            format!(
                "the fit took longer than the request timeout ({} s)",
                timeout.as_secs_f64()
            ),
        )
    })??;
    Ok(Json(result))
}

/// An example body of `POST /v1/fits/lightcurve`: the example request's plate, its albedo
/// free, two observed magnitudes.
pub fn example_lightcurve_fit() -> serde_json::Value {
    serde_json::json!({
        "request": example_request(),
        "observed": [
            { "t": 0.0, "magnitude": 4.3, "sigma": 0.02 },
            { "t": 60.0, "magnitude": 4.7, "sigma": 0.02 }
        ],
        "free": ["materials.surface.albedo"]
    })
}

/// Fit a request's parameters to an observed light curve, as a job.
///
/// What `glint fit-lightcurve` does: the named free parameters (`materials.<name>.<param>`,
/// `attitude.yaw_deg`) fitted by weighted least squares on magnitudes, every evaluation a
/// light curve of the observed epochs; with the yaw free, several yaw starts. The body is
/// checked (with the job limits, its whole work bounded by `max_evaluations`) and stored
/// before the `202`; the job's `percent` counts light curves against `max_evaluations`, and
/// its result (`GET /v1/jobs/{id}/result`) is the fit: parameters, uncertainties, χ²/dof,
/// evaluations and wall time.
#[utoipa::path(
    post, path = "/v1/fits/lightcurve", tag = "fits",
    request_body(content = LightcurveFitRequest, content_type = "application/json",
        example = json!(example_lightcurve_fit())),
    responses(
        (status = 202, description = "Accepted and stored", body = JobStatus,
            headers(("Location" = String, description = "URL of the job status"))),
        (status = 400, description = "Malformed JSON or body", body = ErrorBody),
        (status = 401, description = "Missing or wrong bearer token", body = ErrorBody),
        (status = 413, description = "Body, mesh or the fit's work over the job limits (`max_evaluations` light curves of the observed epochs)", body = ErrorBody),
        (status = 415, description = "Content-Type is not application/json", body = ErrorBody),
        (status = 422, description = "A bad field (`request.…`, `observed[3].t`, `free[1]`, `start.<path>`, `max_evaluations`), or the `Idempotency-Key` used with another body; `field` names it", body = ErrorBody),
        (status = 429, description = "Too many jobs queued or running (see `Retry-After`)", body = ErrorBody),
        (status = 503, description = "The job store cannot write now (see `Retry-After`)", body = ErrorBody),
        (status = 507, description = "The job store's disk is full, or stored results are over their limit", body = ErrorBody),
    ),
    params(("Idempotency-Key" = Option<String>, Header,
        description = "As for `POST /v1/jobs`: a retry with the same key and body answers \
                       the job made the first time."))
)]
pub async fn post_lightcurve_fit(
    State(st): State<AppState>,
    headers: HeaderMap,
    JsonBody(body): JsonBody,
) -> Result<HttpResponse, ApiError> {
    let key = idempotency_key(&headers)?;
    let (status, replayed) = st.jobs.submit_fit(body, key).await?;
    Ok(accepted(status, replayed))
}
