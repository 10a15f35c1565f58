//! `/v1/jobs…`: submit, list, inspect, cancel or remove batch jobs, and fetch a finished
//! job's light curve and images. The handlers shape the answers; the job manager
//! ([`crate::service::jobs`]) does the work.

use super::{body_response, example_request, wants_csv, JsonBody};
use crate::fit::lightcurve::LightcurveFit;
use crate::scene::{Request, Response};
use crate::service::errors::{ApiError, ErrorBody};
use crate::service::jobs::{no_such_job, Deleted, JobKind, JobState, JobStatus};
use crate::service::jobstore::ResultBody;
use crate::service::store::Form;
use crate::service::AppState;
use axum::extract::rejection::QueryRejection;
use axum::extract::{Path, Query, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response as HttpResponse};
use axum::Json;
use serde::Deserialize;
use utoipa::IntoParams;

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
    Ok(accepted(status, replayed))
}

/// The `202` of a stored job: its status, `Location` its URL, and
/// `Idempotent-Replayed: true` when an earlier submission with the same key made it.
pub(super) fn accepted(status: JobStatus, replayed: bool) -> HttpResponse {
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
    resp
}

/// The `Idempotency-Key` header, checked: 1–255 visible ASCII characters.
pub(super) fn idempotency_key(headers: &HeaderMap) -> Result<Option<String>, ApiError> {
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
        (status = 503, description = "The job store cannot be read now (see `Retry-After`)", body = ErrorBody),
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
    Ok(Json(st.jobs.list(limit, q.state).await?))
}

/// A job's state and progress.
#[utoipa::path(
    get, path = "/v1/jobs/{id}", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "The job", body = JobStatus),
        (status = 404, description = "No such job (or it expired)", body = ErrorBody),
        (status = 503, description = "The job store cannot be read now (see `Retry-After`)", body = ErrorBody),
    )
)]
pub async fn get_job(
    State(st): State<AppState>,
    Path(id): Path<String>,
) -> Result<Json<JobStatus>, ApiError> {
    st.jobs
        .status(&id)
        .await?
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
        (status = 503, description = "The job store cannot be read or written now (see `Retry-After`)", body = ErrorBody),
    )
)]
pub async fn delete_job(
    State(st): State<AppState>,
    Path(id): Path<String>,
) -> Result<HttpResponse, ApiError> {
    Ok(match st.jobs.delete(&id).await? {
        Deleted::Cancelled(s) => Json(*s).into_response(),
        Deleted::Removed => StatusCode::NO_CONTENT.into_response(),
    })
}

/// What a finished job gives: a light curve, or a light-curve fit's result.
#[derive(serde::Serialize, utoipa::ToSchema)]
#[serde(untagged)]
#[allow(dead_code)] // a schema only: the stored JSON is served as it is
pub enum JobResult {
    Lightcurve(Box<Response>),
    Fit(Box<LightcurveFit>),
}

/// A finished job's result: a light curve (JSON, or CSV when `Accept` names `text/csv`),
/// or a fit job's result (JSON only).
#[utoipa::path(
    get, path = "/v1/jobs/{id}/result", tag = "jobs",
    params(("id" = String, Path, description = "Job id")),
    responses(
        (status = 200, description = "The light curve, or the fit", content(
            (JobResult = "application/json"),
            (String = "text/csv"))),
        (status = 404, description = "No such job", body = ErrorBody),
        (status = 406, description = "CSV asked of a fit's result, which is JSON only", body = ErrorBody),
        (status = 409, description = "The job is not done (yet)", body = ErrorBody),
        (status = 503, description = "The job store cannot be read now (see `Retry-After`)", body = ErrorBody),
    )
)]
pub async fn get_job_result(
    State(st): State<AppState>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> Result<HttpResponse, ApiError> {
    let csv = wants_csv(&headers);
    let form = if csv { Form::Csv } else { Form::Json };
    // 404 / 409 first, as for any job without a result
    let (kind, result) = st.jobs.result(&id, form).await?;
    if csv && kind == JobKind::FitLightcurve {
        return Err(ApiError::new(
            StatusCode::NOT_ACCEPTABLE,
            "a fit's result is JSON only: ask for `application/json`",
        )
        .with_field("Accept"));
    }
    let (body, len) = match result {
        ResultBody::Stream { len, stream } => (axum::body::Body::from_stream(stream), len),
        ResultBody::Whole(bytes) => {
            let len = bytes.len() as u64;
            (axum::body::Body::from(bytes), len)
        }
    };
    let mut resp = body_response(body, csv);
    resp.headers_mut()
        .insert(header::CONTENT_LENGTH, HeaderValue::from(len));
    Ok(resp)
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
        (status = 503, description = "The job store cannot be read now (see `Retry-After`)", body = ErrorBody),
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
    let png = st.jobs.thumbnail(&id, epoch).await?;
    Ok((
        [(header::CONTENT_TYPE, HeaderValue::from_static("image/png"))],
        png,
    )
        .into_response())
}
