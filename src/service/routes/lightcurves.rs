//! `POST /v1/lightcurves`: a light curve computed now, within the synchronous limits and
//! the request timeout, on the light-curve pool.

use super::{body_response, wants_csv, JsonBody};
use crate::integrate::Progress;
use crate::report::csv::to_csv;
use crate::scene::{validate, Request, Response, Scene};
use crate::service::errors::{ApiError, ErrorBody};
use crate::service::limits::refused;
use crate::service::threads::run_blocking;
use crate::service::AppState;
use axum::body::Bytes;
use axum::extract::{FromRequest, State};
use axum::http::{HeaderMap, StatusCode};
use axum::response::Response as HttpResponse;
use std::sync::Arc;

use super::example_request;

/// Parses and validates a body with the engine's own checks, off the async runtime
/// (a large body takes milliseconds to parse).
async fn parse_scene(body: Bytes, limits: crate::scene::Limits) -> Result<Scene, ApiError> {
    run_blocking("validating the request", move || {
        let text = std::str::from_utf8(&body)
            .map_err(|e| ApiError::bad_request(format!("request body is not UTF-8: {e}")))?;
        let request = validate::parse_request(text)?;
        Ok(Scene::from_request(&request, &limits)?)
    })
    .await?
}

/// Cancels the computation when the handler is dropped (timeout, client gone).
struct CancelOnDrop(Arc<Progress>);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.cancel();
    }
}

/// Compute a light curve now.
///
/// For requests within the synchronous limits (epochs, triangles, body size); larger ones go
/// to `POST /v1/jobs`. Answers CSV when `Accept` names `text/csv`.
#[utoipa::path(
    post, path = "/v1/lightcurves", tag = "light curves",
    request_body(content = Request, content_type = "application/json",
        description = "The light-curve request (the same JSON the command line takes).",
        example = json!(example_request())),
    responses(
        (status = 200, description = "The light curve", content(
            (Response = "application/json"),
            (String = "text/csv"))),
        (status = 400, description = "Malformed JSON or body", body = ErrorBody),
        (status = 401, description = "Missing or wrong bearer token", body = ErrorBody),
        (status = 413, description = "Body, mesh or epoch count over the limits", body = ErrorBody),
        (status = 415, description = "Content-Type is not application/json", body = ErrorBody),
        (status = 422, description = "A field has a wrong type or value; `field` names it", body = ErrorBody),
        (status = 503, description = "Busy (see `Retry-After`), or over the request timeout", body = ErrorBody),
    )
)]
pub async fn post_lightcurve(
    State(st): State<AppState>,
    headers: HeaderMap,
    req: axum::extract::Request,
) -> Result<HttpResponse, ApiError> {
    // A place before the body is read: when none is left, the 503 costs neither reading
    // nor parsing the body (which would take the cores from the requests that run)
    let Ok(_place) = st.slots.admit() else {
        return Ok(refused(ApiError::busy(1)).await);
    };
    let JsonBody(body) = JsonBody::from_request(req, &st).await?;
    let csv = wants_csv(&headers);
    let timeout = st.limits.request_timeout;
    let scene = parse_scene(body, st.limits.sync_limits()).await?;
    let progress = Arc::new(Progress::new());
    let _guard = CancelOnDrop(progress.clone());
    let work = async {
        let slot = st.slots.acquire().await.map_err(|_| ApiError::busy(1))?;
        let p = progress.clone();
        let pool = st.pools.sync.clone();
        let engine = st.engine;
        run_blocking("the computation", move || {
            let _slot = slot; // released when the computation has really ended (or unwound)
            let resp = pool.install(|| engine(&scene, &p)).ok()?;
            let n = resp.epochs.len();
            let bytes = if csv {
                to_csv(&resp).into_bytes()
            } else {
                serde_json::to_vec(&resp).ok()?
            };
            Some((bytes, n))
        })
        .await?
        .ok_or_else(|| ApiError::internal("the computation was cancelled"))
    };
    let (bytes, n) = tokio::time::timeout(timeout, work).await.map_err(|_| {
        ApiError::new(
            StatusCode::SERVICE_UNAVAILABLE,
            format!(
                "the computation took longer than the request timeout ({} s); submit it as a job (POST /v1/jobs)",
                timeout.as_secs_f64()
            ),
        )
    })??;
    st.metrics.add_epochs("sync", n as u64);
    Ok(body_response(bytes, csv))
}
