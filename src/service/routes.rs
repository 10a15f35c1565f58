//! The HTTP handlers. Each one is thin: check the input, hand the work to the engine (off
//! the async runtime) or to the job manager, shape the answer.

use super::errors::{ApiError, ErrorBody};
use super::jobs::{no_such_job, Deleted, JobState, JobStatus};
use super::metrics::Gauges;
use super::scenes::{self, SceneSummary};
use super::AppState;
use crate::fit::brdf::{self as fit_brdf, BrdfFit, BrdfFitRequest};
use crate::integrate::Progress;
use crate::report::csv::to_csv;
use crate::scene::{validate, Request, Response, Scene};
use axum::body::Bytes;
use axum::extract::rejection::QueryRejection;
use axum::extract::{FromRequest, Path, Query, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response as HttpResponse};
use axum::Json;
use base64::Engine as _;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use utoipa::{IntoParams, ToSchema};

/// A small valid request, used as the example of the request bodies in the spec.
pub fn example_request() -> serde_json::Value {
    serde_json::json!({
        "object": {
            "mesh": { "builtin": "plate" },
            "materials": [ { "name": "surface", "model": "lambert", "albedo": 0.5 } ]
        },
        "epochs": [
            { "t": 0.0, "sun": [0.0, 0.0, 1.0], "observer": [0.0, 0.0, 1.0e6], "earth": [0.0, 0.0, -7.0e6] },
            { "t": 60.0, "sun": [1.0, 0.0, 1.0], "observer": [0.0, 0.0, 1.0e6], "earth": [0.0, 0.0, -7.0e6] }
        ]
    })
}

/// The raw body of a JSON request, after checking its `Content-Type`. The body size limit
/// (`DefaultBodyLimit`) applies; both failures become [`ErrorBody`] answers (415, 413).
pub struct JsonBody(pub Bytes);

impl<S: Send + Sync> FromRequest<S> for JsonBody {
    type Rejection = ApiError;

    async fn from_request(req: axum::extract::Request, state: &S) -> Result<Self, ApiError> {
        let ct = req
            .headers()
            .get(header::CONTENT_TYPE)
            .and_then(|v| v.to_str().ok())
            .unwrap_or("");
        let essence = ct
            .split(';')
            .next()
            .unwrap_or("")
            .trim()
            .to_ascii_lowercase();
        if essence != "application/json" && !essence.ends_with("+json") {
            let got = if ct.is_empty() {
                "none".to_string()
            } else {
                format!("`{ct}`")
            };
            return Err(ApiError::new(
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                format!("expected `Content-Type: application/json`, got {got}"),
            )
            .with_field("Content-Type"));
        }
        let body = Bytes::from_request(req, state).await?;
        if body.iter().all(u8::is_ascii_whitespace) {
            return Err(ApiError::bad_request("the request body is empty").with_field("body"));
        }
        Ok(JsonBody(body))
    }
}

/// Whether the client prefers CSV: `text/csv` is named in `Accept`, before any JSON type.
fn wants_csv(headers: &HeaderMap) -> bool {
    let accept = headers
        .get(header::ACCEPT)
        .and_then(|v| v.to_str().ok())
        .unwrap_or("")
        .to_ascii_lowercase();
    match (accept.find("text/csv"), accept.find("json")) {
        (Some(c), Some(j)) => c < j,
        (Some(_), None) => true,
        _ => false,
    }
}

fn body_response(bytes: Vec<u8>, csv: bool) -> HttpResponse {
    let ct = if csv {
        "text/csv; charset=utf-8"
    } else {
        "application/json"
    };
    (
        [(header::CONTENT_TYPE, HeaderValue::from_static(ct))],
        bytes,
    )
        .into_response()
}

/// Parses and validates a body with the engine's own checks, off the async runtime
/// (a large body takes milliseconds to parse).
async fn parse_scene(body: Bytes, limits: crate::scene::Limits) -> Result<Scene, ApiError> {
    tokio::task::spawn_blocking(move || {
        let text = std::str::from_utf8(&body)
            .map_err(|e| ApiError::bad_request(format!("request body is not UTF-8: {e}")))?;
        let request = validate::parse_request(text)?;
        Ok(Scene::from_request(&request, &limits)?)
    })
    .await
    .map_err(|e| ApiError::from_join("validating the request", e))?
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
    JsonBody(body): JsonBody,
) -> Result<HttpResponse, ApiError> {
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
        tokio::task::spawn_blocking(move || {
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
        .await
        .map_err(|e| ApiError::from_join("the computation", e))?
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
        tokio::task::spawn_blocking(move || -> Result<BrdfFit, ApiError> {
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
        .await
        .map_err(ApiError::internal)?
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

/// Submit a batch job.
///
/// The request is validated (with the job limits) and stored durably before the answer:
/// a `202` means the job survives a crash. Poll `Location` for its state.
#[utoipa::path(
    post, path = "/v1/jobs", tag = "jobs",
    request_body(content = Request, content_type = "application/json",
        description = "The light-curve request; may be larger than the synchronous limits.",
        example = json!(example_request())),
    responses(
        (status = 202, description = "Accepted and stored", body = JobStatus,
            headers(("Location" = String, description = "URL of the job status"))),
        (status = 400, description = "Malformed JSON or body", body = ErrorBody),
        (status = 401, description = "Missing or wrong bearer token", body = ErrorBody),
        (status = 413, description = "Body, mesh or epoch count over the job limits", body = ErrorBody),
        (status = 415, description = "Content-Type is not application/json", body = ErrorBody),
        (status = 422, description = "A field has a wrong type or value, or the `Idempotency-Key` was used with another body; `field` names it", body = ErrorBody),
        (status = 429, description = "Too many jobs queued or running (see `Retry-After`)", body = ErrorBody),
        (status = 503, description = "The job store cannot write now (see `Retry-After`)", body = ErrorBody),
        (status = 507, description = "The job store's disk is full, or stored results are over their limit", body = ErrorBody),
    ),
    params(("Idempotency-Key" = Option<String>, Header,
        description = "A client's key for this submission (1–255 visible ASCII characters). \
                       A retry with the same key and body answers the job made the first \
                       time (with `Idempotent-Replayed: true`) instead of making another, \
                       for as long as that job is kept."))
)]
pub async fn post_job(
    State(st): State<AppState>,
    headers: HeaderMap,
    JsonBody(body): JsonBody,
) -> Result<HttpResponse, ApiError> {
    let key = idempotency_key(&headers)?;
    let (status, replayed) = st.jobs.submit(body, key).await?;
    let location = format!("/v1/jobs/{}", status.id);
    let mut resp = (
        StatusCode::ACCEPTED,
        [(header::LOCATION, location)],
        Json(status),
    )
        .into_response();
    if replayed {
        resp.headers_mut()
            .insert("idempotent-replayed", HeaderValue::from_static("true"));
    }
    Ok(resp)
}

/// The `Idempotency-Key` header, checked: 1–255 visible ASCII characters.
fn idempotency_key(headers: &HeaderMap) -> Result<Option<String>, ApiError> {
    let Some(v) = headers.get("idempotency-key") else {
        return Ok(None);
    };
    let bad = || {
        ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "must be 1 to 255 visible ASCII characters",
        )
        .with_field("Idempotency-Key")
    };
    let k = v.to_str().map_err(|_| bad())?.trim();
    if k.is_empty() || k.len() > 255 || !k.bytes().all(|b| b.is_ascii_graphic()) {
        return Err(bad());
    }
    Ok(Some(k.to_string()))
}

/// Query of `GET /v1/jobs`.
#[derive(Debug, Deserialize, IntoParams)]
#[into_params(parameter_in = Query)]
pub struct ListQuery {
    /// Most jobs to list (newest first), 1–1000; default 100.
    #[param(minimum = 1, maximum = 1000)]
    pub limit: Option<usize>,
    /// Only jobs in this state.
    pub state: Option<JobState>,
}

/// List recent jobs, newest first.
#[utoipa::path(
    get, path = "/v1/jobs", tag = "jobs", params(ListQuery),
    responses(
        (status = 200, description = "Jobs, newest first", body = Vec<JobStatus>),
        (status = 400, description = "Bad query", body = ErrorBody),
    )
)]
pub async fn list_jobs(
    State(st): State<AppState>,
    query: Result<Query<ListQuery>, QueryRejection>,
) -> Result<Json<Vec<JobStatus>>, ApiError> {
    let Query(q) = query?;
    let limit = q.limit.unwrap_or(100);
    if !(1..=1000).contains(&limit) {
        return Err(ApiError::bad_request("must be between 1 and 1000").with_field("limit"));
    }
    Ok(Json(st.jobs.list(limit, q.state)))
}

/// A job's state and progress.
#[utoipa::path(
    get, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "The job", body = JobStatus),
        (status = 404, description = "No such job (or it expired)", body = ErrorBody),
    )
)]
pub async fn get_job(
    State(st): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<JobStatus>, ApiError> {
    st.jobs
        .status(&id)
        .map(Json)
        .ok_or_else(|| no_such_job(&id))
}

/// Cancel a queued or running job, or remove a finished one with its result.
#[utoipa::path(
    delete, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "The job was queued or running and is now cancelled", body = JobStatus),
        (status = 204, description = "The job had finished; it and its result were removed"),
        (status = 404, description = "No such job", body = ErrorBody),
    )
)]
pub async fn delete_job(
    State(st): State<AppState>,
    Path(id): Path<String>,
) -> Result<HttpResponse, ApiError> {
    Ok(match st.jobs.delete(&id).await? {
        Deleted::Cancelled(s) => Json(s).into_response(),
        Deleted::Removed => StatusCode::NO_CONTENT.into_response(),
    })
}

/// A finished job's light curve (JSON, or CSV when `Accept` names `text/csv`).
#[utoipa::path(
    get, path = "/v1/jobs/{id}/result", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "The light curve", content(
            (Response = "application/json"),
            (String = "text/csv"))),
        (status = 404, description = "No such job", body = ErrorBody),
        (status = 409, description = "The job is not done (yet)", body = ErrorBody),
    )
)]
pub async fn get_job_result(
    State(st): State<AppState>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> Result<HttpResponse, ApiError> {
    let json = st.jobs.result(&id).await?;
    if !wants_csv(&headers) {
        return Ok(body_response(json, false));
    }
    let csv = tokio::task::spawn_blocking(move || {
        serde_json::from_slice::<Response>(&json).map(|r| to_csv(&r).into_bytes())
    })
    .await
    .map_err(|e| ApiError::from_join("converting the result", e))?
    .map_err(ApiError::internal)?;
    Ok(body_response(csv, true))
}

/// The rendered image of one epoch of a finished job (`{epoch}.png`, epoch index from 0).
#[utoipa::path(
    get, path = "/v1/jobs/{id}/thumbnails/{file}", tag = "jobs",
    params(
        ("id" = String, Path, description = "Job id"),
        ("file" = String, Path, description = "`{epoch}.png`, the epoch's index in the request", example = "0.png"),
    ),
    responses(
        (status = 200, description = "The PNG", content_type = "image/png", body = Vec<u8>),
        (status = 404, description = "No such job, or no image for that epoch", body = ErrorBody),
        (status = 409, description = "The job is not done (yet)", body = ErrorBody),
    )
)]
pub async fn get_thumbnail(
    State(st): State<AppState>,
    Path((id, file)): Path<(String, String)>,
) -> Result<HttpResponse, ApiError> {
    let epoch: usize = file
        .strip_suffix(".png")
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| ApiError::not_found("expected `{epoch}.png`").with_field("epoch"))?;
    let json = st.jobs.result(&id).await?;
    let png = tokio::task::spawn_blocking(move || -> Result<Vec<u8>, ApiError> {
        let resp: Response = serde_json::from_slice(&json).map_err(ApiError::internal)?;
        let thumb = resp
            .thumbnails
            .unwrap_or_default()
            .into_iter()
            .find(|t| t.epoch == epoch)
            .ok_or_else(|| {
                ApiError::not_found(format!("the job has no image for epoch {epoch}"))
                    .with_field("epoch")
            })?;
        base64::engine::general_purpose::STANDARD
            .decode(thumb.png_base64.as_bytes())
            .map_err(ApiError::internal)
    })
    .await
    .map_err(|e| ApiError::from_join("reading the image", e))??;
    Ok((
        [(header::CONTENT_TYPE, HeaderValue::from_static("image/png"))],
        png,
    )
        .into_response())
}

/// The built-in objects and their example requests.
#[utoipa::path(
    get, path = "/v1/scenes", tag = "scenes",
    responses((status = 200, description = "Built-in objects and example requests", body = Vec<SceneSummary>))
)]
pub async fn list_scenes() -> Json<Vec<SceneSummary>> {
    Json(scenes::summaries().to_vec())
}

/// An example request, ready to send to `POST /v1/lightcurves` or `POST /v1/jobs`.
#[utoipa::path(
    get, path = "/v1/scenes/{name}", tag = "scenes",
    params(("name" = String, Path, description = "Scene name, e.g. `box-wing`")),
    responses(
        (status = 200, description = "The example request", body = Request),
        (status = 404, description = "No such scene", body = ErrorBody),
    )
)]
pub async fn get_scene(Path(name): Path<String>) -> Result<HttpResponse, ApiError> {
    scenes::example(&name)
        .map(|text| body_response(text.as_bytes().to_vec(), false))
        .ok_or_else(|| {
            ApiError::not_found(format!("no scene `{name}`; GET /v1/scenes lists them"))
                .with_field("name")
        })
}

/// Liveness and readiness answers.
#[derive(Debug, Serialize, Deserialize, ToSchema)]
pub struct Health {
    /// `ok`, or why not.
    pub status: String,
}

/// Liveness: the process answers HTTP. No authentication.
#[utoipa::path(get, path = "/healthz", tag = "operations", security(()),
    responses((status = 200, description = "Alive", body = Health)))]
pub async fn healthz() -> Json<Health> {
    Json(Health {
        status: "ok".into(),
    })
}

/// Readiness: the store answers and the service is not shutting down. No authentication.
#[utoipa::path(get, path = "/readyz", tag = "operations", security(()),
    responses(
        (status = 200, description = "Ready", body = Health),
        (status = 503, description = "Not ready", body = Health),
    ))]
pub async fn readyz(State(st): State<AppState>) -> HttpResponse {
    if st.jobs.is_shutting_down() {
        return (
            StatusCode::SERVICE_UNAVAILABLE,
            Json(Health {
                status: "shutting down".into(),
            }),
        )
            .into_response();
    }
    let store = st.store.clone();
    match tokio::task::spawn_blocking(move || store.check()).await {
        Ok(Ok(())) => Json(Health {
            status: "ok".into(),
        })
        .into_response(),
        Ok(Err(e)) => (
            StatusCode::SERVICE_UNAVAILABLE,
            Json(Health {
                status: e.to_string(),
            }),
        )
            .into_response(),
        Err(e) => (
            StatusCode::SERVICE_UNAVAILABLE,
            Json(Health {
                status: e.to_string(),
            }),
        )
            .into_response(),
    }
}

/// Prometheus metrics: requests and latencies by route, epochs computed, jobs by state.
#[utoipa::path(get, path = "/metrics", tag = "operations",
    responses((status = 200, description = "Prometheus text format 0.0.4", content_type = "text/plain", body = String)))]
pub async fn metrics(State(st): State<AppState>) -> HttpResponse {
    let counts = st.jobs.counts();
    let gauges = Gauges {
        computations_running: st.slots.in_use(),
        requests_waiting: st.slots.waiting(),
        jobs: JobState::ALL
            .iter()
            .map(|s| (s.name(), counts.get(s).copied().unwrap_or(0)))
            .collect(),
    };
    (
        [(
            header::CONTENT_TYPE,
            HeaderValue::from_static("text/plain; version=0.0.4; charset=utf-8"),
        )],
        st.metrics.render(&gauges),
    )
        .into_response()
}

/// Any path that is not a route.
pub async fn not_found(uri: axum::http::Uri) -> ApiError {
    ApiError::not_found(format!("no route for `{}`; see /docs", uri.path()))
}
