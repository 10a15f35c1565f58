//! The HTTP service: light curves over REST, batch jobs that survive restarts, OpenAPI.
//!
//! ```text
//! (connection: head size ─▶ 431) request id ─▶ URI length ─▶ metrics ─▶ JSON errors ─▶ catch panic ─▶ timeout ─▶ auth ─▶ admission (body bytes) ─▶ body limit ─▶ routes
//!                                                  ├─ /v1/lightcurves: validate → slot → engine (light-curve pool)
//!                                                  ├─ /v1/jobs…: jobs (durable queue, redb store, job pool)
//!                                                  └─ /v1/scenes, /healthz, /readyz, /metrics, /docs
//! ```
//! No physics here: the engine ([`crate::simulate_with`]) and its validation
//! ([`crate::scene::validate`]) are the single source of truth.

pub mod errors;
pub mod jobs;
pub mod jobstore;
pub mod limits;
pub mod metrics;
pub mod openapi;
pub mod record;
pub mod request_id;
pub mod routes;
pub mod scenes;
pub mod server;
pub mod shared;
pub mod store;
pub mod threads;

pub use routes::api_router;

use crate::integrate::{Cancelled, Progress};
use crate::scene::Scene;
use axum::extract::{DefaultBodyLimit, Request, State};
use axum::http::{header, HeaderValue, StatusCode};
use axum::middleware::{from_fn, from_fn_with_state, Next};
use axum::response::{IntoResponse, Response};
use axum::Router;
use errors::ApiError;
use jobs::Jobs;
use limits::{ServiceLimits, Slots};
use metrics::Metrics;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;
use store::Store;
use tower_http::catch_panic::CatchPanicLayer;
use tower_http::timeout::TimeoutLayer;
use utoipa_swagger_ui::SwaggerUi;

/// Everything `glint serve` configures.
#[derive(Debug, Clone)]
pub struct Config {
    /// Address to listen on (port 0 picks a free one).
    pub addr: SocketAddr,
    /// Directory of the job database.
    pub data_dir: PathBuf,
    /// Bearer token every route but `/healthz` and `/readyz` requires, when set.
    pub token: Option<String>,
    /// Allow listening on a non-loopback address without a token.
    pub allow_unauthenticated: bool,
    pub limits: ServiceLimits,
    /// How long finished jobs and their results are kept.
    pub result_ttl: Duration,
    /// The computation behind light curves and jobs.
    pub engine: Engine,
    /// A shared PostgreSQL queue instead of the embedded store (`--database-url`).
    pub shared: Option<shared::SharedConfig>,
}

/// The computation the service runs for a light curve or a job: [`crate::simulate_with`].
/// A seam for the tests: a failing engine shows that a fault inside a computation is
/// answered as a 500 naming the request id, and that its slot comes back.
pub type Engine = fn(&Scene, &Progress) -> Result<crate::scene::Response, Cancelled>;

impl Default for Config {
    fn default() -> Self {
        Config {
            addr: SocketAddr::from(([127, 0, 0, 1], 8080)),
            data_dir: PathBuf::from("glint-data"),
            token: None,
            allow_unauthenticated: false,
            limits: ServiceLimits::default(),
            result_ttl: Duration::from_secs(7 * 24 * 3600),
            engine: crate::simulate_with,
            shared: None,
        }
    }
}

/// Shared by all handlers.
#[derive(Clone)]
pub struct AppState {
    pub limits: Arc<ServiceLimits>,
    pub slots: Arc<Slots>,
    pub jobs: jobstore::JobStore,
    pub metrics: Arc<Metrics>,
    pub pools: threads::Pools,
    pub engine: Engine,
}

/// Requires `Authorization: Bearer <token>` on everything but the health checks.
async fn auth(State(token): State<Option<Arc<str>>>, req: Request, next: Next) -> Response {
    let Some(token) = token else {
        return next.run(req).await;
    };
    let path = req.uri().path();
    if path == "/healthz" || path == "/readyz" {
        return next.run(req).await;
    }
    let given = req
        .headers()
        .get(header::AUTHORIZATION)
        .and_then(|v| v.to_str().ok())
        // The scheme is case-insensitive (RFC 9110 §11.1); the token is not
        .and_then(|v| {
            let (scheme, token) = v.trim_start().split_once(' ')?;
            scheme.eq_ignore_ascii_case("bearer").then_some(token)
        })
        .map(str::trim);
    match given {
        Some(g) if constant_time_eq(g.as_bytes(), token.as_bytes()) => next.run(req).await,
        _ => {
            let msg = if given.is_some() {
                "wrong bearer token"
            } else {
                "this service needs `Authorization: Bearer <token>`"
            };
            let mut r = ApiError::new(StatusCode::UNAUTHORIZED, msg)
                .with_field("Authorization")
                .into_response();
            r.headers_mut()
                .insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"));
            r
        }
    }
}

/// Longest request target (path and query) taken, bytes; a longer one is a `414` naming
/// `uri`. No route needs more than a few hundred; hyper's own bound is 64 KiB.
pub const MAX_URI_BYTES: usize = 8 << 10;

/// Answers `414` to a request whose target is over [`MAX_URI_BYTES`].
async fn limit_uri(req: Request, next: Next) -> Response {
    let n = req.uri().path_and_query().map_or(0, |p| p.as_str().len());
    if n > MAX_URI_BYTES {
        return ApiError::new(
            StatusCode::URI_TOO_LONG,
            format!("the request target is {n} bytes, over the {MAX_URI_BYTES}-byte limit"),
        )
        .with_field("uri")
        .into_response();
    }
    next.run(req).await
}

/// Equality that takes the same time wherever the first difference is.
fn constant_time_eq(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

fn num_cores() -> usize {
    std::thread::available_parallelism().map_or(2, |n| n.get())
}

/// Opens the store (the embedded one, or the shared queue: migrated, its workers
/// started), restarts unfinished jobs and builds the router. Runs inside the tokio
/// runtime (the job manager spawns its tasks).
pub async fn build(config: &Config) -> anyhow::Result<(Router, AppState)> {
    let limits = config.limits.clone();
    let slots = Arc::new(Slots::new(limits.max_concurrent, limits.max_queued));
    let metrics = Arc::new(Metrics::default());
    let pools = threads::Pools::new(num_cores())?;
    let jobs = match &config.shared {
        None => {
            let store = Arc::new(Store::open(&config.data_dir)?);
            let jobs = Jobs::start(
                store.clone(),
                slots.clone(),
                metrics.clone(),
                pools.jobs.clone(),
                limits.clone(),
                config.result_ttl,
                config.engine,
            )?;
            jobstore::JobStore::Embedded { jobs, store }
        }
        Some(shared) => jobstore::JobStore::Shared(
            shared::Shared::start(
                shared,
                limits.clone(),
                config.result_ttl,
                config.engine,
                pools.jobs.clone(),
                metrics.clone(),
            )
            .await?,
        ),
    };
    let state = AppState {
        limits: Arc::new(limits.clone()),
        slots,
        jobs,
        metrics: metrics.clone(),
        pools,
        engine: config.engine,
    };
    let (router, spec) = api_router().split_for_parts();
    let token: Option<Arc<str>> = config
        .token
        .as_deref()
        .filter(|t| !t.is_empty())
        .map(Arc::from);
    let router = router
        .merge(SwaggerUi::new("/docs").url("/openapi.json", spec))
        .fallback(routes::not_found)
        .with_state(state.clone())
        .layer(DefaultBodyLimit::max(limits.max_body_bytes))
        .layer(from_fn_with_state(
            limits::BodyBytes::new(limits.max_inflight_body_bytes, limits.max_body_bytes),
            limits::admit,
        ))
        .layer(from_fn_with_state(token, auth))
        // A backstop for slow uploads; the light-curve handler has its own, shorter
        // deadline so its 503 names the cause.
        .layer(TimeoutLayer::with_status_code(
            StatusCode::REQUEST_TIMEOUT,
            limits.request_timeout + Duration::from_secs(5),
        ))
        .layer(CatchPanicLayer::custom(request_id::panicked))
        .layer(from_fn(errors::json_errors))
        .layer(from_fn_with_state(metrics, metrics::track))
        .layer(from_fn(limit_uri))
        .layer(from_fn(request_id::tag));
    Ok((router, state))
}

/// A started service.
pub struct Running {
    /// The address it listens on.
    pub addr: SocketAddr,
    pub state: AppState,
    stop: tokio::sync::oneshot::Sender<()>,
    task: tokio::task::JoinHandle<std::io::Result<()>>,
}

impl Running {
    /// Graceful shutdown: stop accepting, let in-flight requests finish, then stop running
    /// jobs at their next epoch (they stay queued on disk and run again on restart).
    pub async fn shutdown(self) -> anyhow::Result<()> {
        let _ = self.stop.send(());
        self.task.await??;
        self.state.jobs.shutdown(Duration::from_secs(10)).await;
        Ok(())
    }
}

/// Binds, builds and starts serving in a background task.
pub async fn start(config: Config) -> anyhow::Result<Running> {
    let has_token = config.token.as_deref().is_some_and(|t| !t.is_empty());
    if !has_token && !config.addr.ip().is_loopback() && !config.allow_unauthenticated {
        anyhow::bail!(
            "refusing to listen on {} without authentication: set GLINT_API_TOKEN (or \
             --allow-unauthenticated / GLINT_ALLOW_UNAUTHENTICATED=true to accept anyone)",
            config.addr
        );
    }
    let listener = tokio::net::TcpListener::bind(config.addr)
        .await
        .map_err(|e| {
            anyhow::anyhow!(
                "cannot listen on {}: {e} (choose another with --addr)",
                config.addr
            )
        })?;
    let addr = listener.local_addr()?;
    let (router, state) = build(&config).await?;
    let header_timeout = config.limits.header_timeout;
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let task = tokio::spawn(async move {
        server::serve(listener, router, header_timeout, async move {
            let _ = stopped.await;
        })
        .await
    });
    Ok(Running {
        addr,
        state,
        stop,
        task,
    })
}
