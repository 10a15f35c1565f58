//! The one error shape of the service: `{ "error": "...", "field": "..." }` with a 4xx/5xx
//! status. Every rejection (ours, the engine's validation, axum's extractors, the timeout
//! layer) ends up here, so clients parse a single format.

use crate::scene::ValidationError;
use axum::extract::rejection::{BytesRejection, PathRejection, QueryRejection};
use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use utoipa::ToSchema;

tokio::task_local! {
    /// The id of the request being handled: set by [`super::request_id::tag`] around
    /// each request, read where an error is made so that a 5xx names it.
    pub static REQUEST_ID: Arc<str>;
}

/// The id of the request this task is handling, if any.
pub fn current_request_id() -> Option<Arc<str>> {
    REQUEST_ID.try_with(|id| id.clone()).ok()
}

/// The body of every error response.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema, PartialEq)]
pub struct ErrorBody {
    /// What went wrong, for a human.
    #[schema(example = "must be a finite number")]
    pub error: String,
    /// Path of the offending field in the request (e.g. `epochs[3].sun`), when there is one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = "epochs[3].sun")]
    pub field: Option<String>,
    /// On a 5xx: the request's id (also in the `X-Request-Id` header). The service log has
    /// the fault under it; quote it when reporting the fault.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub request_id: Option<String>,
}

/// An error answer: status, body, and optionally seconds for `Retry-After`.
#[derive(Debug, Clone)]
pub struct ApiError {
    pub status: StatusCode,
    pub body: ErrorBody,
    /// Seconds after which a retry may succeed (503 only).
    pub retry_after_s: Option<u64>,
}

impl ApiError {
    pub fn new(status: StatusCode, error: impl Into<String>) -> Self {
        ApiError {
            status,
            body: ErrorBody {
                error: error.into(),
                field: None,
                request_id: None,
            },
            retry_after_s: None,
        }
    }

    pub fn with_field(mut self, field: impl Into<String>) -> Self {
        let f = field.into();
        self.body.field = (!f.is_empty()).then_some(f);
        self
    }

    pub fn bad_request(error: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, error)
    }

    pub fn not_found(error: impl Into<String>) -> Self {
        Self::new(StatusCode::NOT_FOUND, error)
    }

    pub fn conflict(error: impl Into<String>) -> Self {
        Self::new(StatusCode::CONFLICT, error)
    }

    /// Overloaded: every computation slot is taken and the wait queue is full.
    pub fn busy(retry_after_s: u64) -> Self {
        ApiError {
            retry_after_s: Some(retry_after_s),
            ..Self::new(
                StatusCode::SERVICE_UNAVAILABLE,
                "all computation slots are busy and the queue is full; retry later",
            )
        }
    }

    /// A fault on our side (storage, a task that died). Never used for bad input.
    pub fn internal(error: impl std::fmt::Display) -> Self {
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("internal error: {error}"),
        )
    }

    /// A panic (in a handler or in a computation it waited for). The client learns that it
    /// happened and under which request id, never the panic's text: that goes to the log
    /// (the panic hook of `glint serve` logs the backtrace).
    pub fn from_panic(what: &str, payload: &(dyn std::any::Any + Send)) -> Self {
        let text = payload
            .downcast_ref::<&str>()
            .copied()
            .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
            .unwrap_or("(no message)");
        let id = current_request_id();
        tracing::error!(
            request_id = id.as_deref().unwrap_or("-"),
            "{what} panicked: {text}"
        );
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!(
                "internal error: {what} failed unexpectedly; the service log has the details \
                 under request id {}",
                id.as_deref().unwrap_or("(none)")
            ),
        )
    }

    /// A blocking task that did not return: a panic (see [`Self::from_panic`]) or the
    /// runtime shutting down.
    pub fn from_join(what: &str, e: tokio::task::JoinError) -> Self {
        if e.is_panic() {
            Self::from_panic(what, &*e.into_panic())
        } else {
            Self::new(
                StatusCode::SERVICE_UNAVAILABLE,
                format!("{what} was stopped: the service is shutting down"),
            )
        }
    }

    /// Maps the engine's validation error: syntax errors are 400, size limits 413, and
    /// everything else (a wrong type, an unknown field, a bad value) 422.
    pub fn from_validation(e: ValidationError) -> Self {
        let status = if e.is_limit() {
            StatusCode::PAYLOAD_TOO_LARGE
        } else if e.message.starts_with("invalid JSON") {
            StatusCode::BAD_REQUEST
        } else {
            StatusCode::UNPROCESSABLE_ENTITY
        };
        Self::new(status, e.message).with_field(e.field)
    }
}

impl From<super::store::StoreError> for ApiError {
    /// A full disk is 507 and a disk that fails otherwise 503 (both clear up by themselves:
    /// the store reopens once it can write again); anything else a 500.
    fn from(e: super::store::StoreError) -> Self {
        if e.is_full() {
            Self::new(
                StatusCode::INSUFFICIENT_STORAGE,
                format!("the job store's disk is full ({e}); retry once space is freed"),
            )
        } else if e.is_io() || matches!(e, super::store::StoreError::Missing(_)) {
            ApiError {
                retry_after_s: Some(5),
                ..Self::new(
                    StatusCode::SERVICE_UNAVAILABLE,
                    format!("the job store cannot read or write now ({e})"),
                )
            }
        } else {
            Self::internal(e)
        }
    }
}

impl From<ValidationError> for ApiError {
    fn from(e: ValidationError) -> Self {
        Self::from_validation(e)
    }
}

impl From<BytesRejection> for ApiError {
    fn from(r: BytesRejection) -> Self {
        // 413 when the body exceeds the limit, 400 when the stream broke.
        let status = r.status();
        let msg = if status == StatusCode::PAYLOAD_TOO_LARGE {
            "request body too large".to_string()
        } else {
            r.body_text()
        };
        Self::new(status, msg).with_field("body")
    }
}

impl From<PathRejection> for ApiError {
    fn from(r: PathRejection) -> Self {
        Self::new(r.status(), r.body_text())
    }
}

impl From<QueryRejection> for ApiError {
    fn from(r: QueryRejection) -> Self {
        // axum says "Failed to deserialize query string: limit: invalid digit …": the
        // parameter's name is the part before the second colon
        let text = r.body_text();
        let field = text
            .strip_prefix("Failed to deserialize query string: ")
            .and_then(|rest| rest.split_once(": "))
            .map(|(name, _)| name.to_string())
            .filter(|name| name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_'));
        let e = Self::new(StatusCode::BAD_REQUEST, text);
        match field {
            Some(f) => e.with_field(f),
            None => e,
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(mut self) -> Response {
        if self.status.is_server_error() && self.body.request_id.is_none() {
            self.body.request_id = current_request_id().map(|id| id.to_string());
        }
        let mut resp = (self.status, Json(self.body)).into_response();
        if let Some(s) = self.retry_after_s {
            resp.headers_mut()
                .insert(header::RETRY_AFTER, HeaderValue::from(s));
        }
        resp
    }
}

/// Rewrites error responses that carry no JSON body (axum's 405, the timeout layer's 408,
/// …) into [`ErrorBody`], so every 4xx/5xx has the same shape.
pub async fn json_errors(req: axum::extract::Request, next: axum::middleware::Next) -> Response {
    let resp = next.run(req).await;
    let status = resp.status();
    if !(status.is_client_error() || status.is_server_error()) {
        return resp;
    }
    let is_json = resp
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.starts_with("application/json"));
    if is_json {
        return resp;
    }
    let (parts, body) = resp.into_parts();
    // Keep the original text when it is short (axum's messages are one line).
    let text = axum::body::to_bytes(body, 4096)
        .await
        .ok()
        .and_then(|b| String::from_utf8(b.to_vec()).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| status.canonical_reason().unwrap_or("error").to_lowercase());
    let mut new = ApiError::new(status, text).into_response();
    for (name, value) in parts.headers.iter() {
        if name != header::CONTENT_TYPE && name != header::CONTENT_LENGTH {
            new.headers_mut().insert(name.clone(), value.clone());
        }
    }
    new
}
