//! The HTTP handlers, grouped by resource, and what they share: the router of the
//! documented routes, the JSON body extractor, content negotiation (JSON or CSV) and the
//! example bodies of the spec. Each handler is thin: check the input, hand the work to the
//! engine (off the async runtime) or to the job manager, shape the answer.
//!
//! | routes | file |
//! |---|---|
//! | `POST /v1/lightcurves` | `lightcurves.rs` |
//! | `POST /v1/fits/brdf`, `POST /v1/fits/lightcurve` (a job) | `fits.rs` |
//! | `/v1/jobs…` | `jobs.rs` |
//! | `/v1/scenes…` | `scenes.rs` |
//! | `/healthz`, `/readyz`, `/metrics` | `health.rs` |

pub mod fits;
pub mod health;
pub mod jobs;
pub mod lightcurves;
pub mod scenes;

use super::errors::ApiError;
use super::openapi::ApiDoc;
use super::AppState;
use axum::body::Bytes;
use axum::extract::FromRequest;
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response as HttpResponse};
use utoipa::OpenApi;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

/// The documented routes, with their OpenAPI paths.
pub fn api_router() -> OpenApiRouter<AppState> {
    // The spec lists the paths in this order (utoipa's `preserve_order`).
    OpenApiRouter::with_openapi(ApiDoc::openapi())
        .routes(routes!(lightcurves::post_lightcurve))
        .routes(routes!(fits::post_brdf_fit))
        .routes(routes!(fits::post_lightcurve_fit))
        .routes(routes!(jobs::post_job, jobs::list_jobs))
        .routes(routes!(jobs::get_job, jobs::delete_job))
        .routes(routes!(jobs::get_job_result))
        .routes(routes!(jobs::get_thumbnail))
        .routes(routes!(scenes::list_scenes))
        .routes(routes!(scenes::get_scene))
        .routes(routes!(health::healthz))
        .routes(routes!(health::readyz))
        .routes(routes!(health::metrics))
}

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
/// (`DefaultBodyLimit`) applies; both failures become
/// [`ErrorBody`](super::errors::ErrorBody) answers (415, 413).
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

/// A body of JSON (`application/json`) or CSV (`text/csv; charset=utf-8`).
fn body_response(body: impl Into<axum::body::Body>, csv: bool) -> HttpResponse {
    let ct = if csv {
        "text/csv; charset=utf-8"
    } else {
        "application/json"
    };
    (
        [(header::CONTENT_TYPE, HeaderValue::from_static(ct))],
        body.into(),
    )
        .into_response()
}

/// Any path that is not a route.
pub async fn not_found(uri: axum::http::Uri) -> ApiError {
    ApiError::not_found(format!("no route for `{}`; see /docs", uri.path()))
}
