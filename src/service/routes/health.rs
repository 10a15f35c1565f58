//! Operations: `/healthz` (liveness), `/readyz` (readiness) and `/metrics` (Prometheus).
//! The OpenAPI document and `/docs` are mounted beside the routes in
//! [`crate::service::build`].

use crate::service::jobs::JobState;
use crate::service::metrics::Gauges;
use crate::service::AppState;
use axum::extract::State;
use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response as HttpResponse};
use axum::Json;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

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
    match st.jobs.check().await {
        Ok(()) => Json(Health {
            status: "ok".into(),
        })
        .into_response(),
        Err(e) => (StatusCode::SERVICE_UNAVAILABLE, Json(Health { status: e })).into_response(),
    }
}

/// Prometheus metrics: requests and latencies by route, epochs computed, jobs by state.
#[utoipa::path(get, path = "/metrics", tag = "operations",
    responses((status = 200, description = "Prometheus text format 0.0.4", content_type = "text/plain", body = String)))]
pub async fn metrics(State(st): State<AppState>) -> HttpResponse {
    let counts = match st.jobs.counts().await {
        Ok(c) => c,
        Err(e) => return e.into_response(),
    };
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
