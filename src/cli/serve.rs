//! `glint serve` (also `glint` with no arguments), `glint openapi` and `glint healthcheck`.

use crate::service::limits::ServiceLimits;
use crate::service::{self, Config};
use anyhow::Context;
use clap::Parser;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::PathBuf;
use std::time::Duration;

/// Flags of `glint serve`; each also reads a `GLINT_…` environment variable.
#[derive(Debug, Clone, clap::Args)]
pub struct ServeArgs {
    /// Address to listen on. Without a token only loopback addresses are allowed.
    #[arg(long, env = "GLINT_ADDR", default_value = "127.0.0.1:8080")]
    pub addr: SocketAddr,
    /// Directory of the job database (created if missing).
    #[arg(long, env = "GLINT_DATA_DIR", default_value = "glint-data")]
    pub data_dir: PathBuf,
    /// Bearer token required on every route but /healthz and /readyz.
    #[arg(long, env = "GLINT_API_TOKEN", hide_env_values = true)]
    pub api_token: Option<String>,
    /// Accept a non-loopback --addr without a token (behind a trusted proxy).
    #[arg(long, env = "GLINT_ALLOW_UNAUTHENTICATED")]
    pub allow_unauthenticated: bool,
    /// Largest request body, bytes.
    #[arg(long, env = "GLINT_MAX_BODY_BYTES", default_value_t = ServiceLimits::default().max_body_bytes)]
    pub max_body_bytes: usize,
    /// Request body bytes admitted at once; beyond, 503 + Retry-After before reading.
    #[arg(long, env = "GLINT_MAX_INFLIGHT_BODY_BYTES", default_value_t = ServiceLimits::default().max_inflight_body_bytes)]
    pub max_inflight_body_bytes: usize,
    /// Largest mesh, triangles.
    #[arg(long, env = "GLINT_MAX_TRIANGLES", default_value_t = ServiceLimits::default().max_triangles)]
    pub max_triangles: usize,
    /// Most epochs in one POST /v1/lightcurves.
    #[arg(long, env = "GLINT_MAX_SYNC_EPOCHS", default_value_t = ServiceLimits::default().max_sync_epochs)]
    pub max_sync_epochs: usize,
    /// Most epochs in one job.
    #[arg(long, env = "GLINT_MAX_JOB_EPOCHS", default_value_t = ServiceLimits::default().max_job_epochs)]
    pub max_job_epochs: usize,
    /// Most triangles × epochs in one POST /v1/lightcurves (a job may ask 1000× this).
    #[arg(long, env = "GLINT_MAX_SYNC_TRIANGLE_EPOCHS", default_value_t = ServiceLimits::default().max_sync_triangle_epochs)]
    pub max_sync_triangle_epochs: u64,
    /// Most pixel samples (`image` method and thumbnails) in one POST /v1/lightcurves (a
    /// job may ask 100× this).
    #[arg(long, env = "GLINT_MAX_SYNC_PIXEL_SAMPLES", default_value_t = ServiceLimits::default().max_sync_pixel_samples)]
    pub max_sync_pixel_samples: u64,
    /// Computations at once (light curves and jobs); default: the number of cores.
    #[arg(long, env = "GLINT_MAX_CONCURRENT")]
    pub max_concurrent: Option<usize>,
    /// Light-curve requests that may wait for a computation slot; more get 503. With the
    /// slots, also the light-curve requests admitted at once, before their body is read.
    #[arg(long, env = "GLINT_MAX_QUEUED", default_value_t = ServiceLimits::default().max_queued)]
    pub max_queued: usize,
    /// Jobs running at once.
    #[arg(long, env = "GLINT_MAX_RUNNING_JOBS", default_value_t = ServiceLimits::default().max_running_jobs)]
    pub max_running_jobs: usize,
    /// Jobs queued or running at once; more submissions get 429.
    #[arg(long, env = "GLINT_MAX_QUEUED_JOBS", default_value_t = ServiceLimits::default().max_queued_jobs)]
    pub max_queued_jobs: usize,
    /// Bytes of finished jobs' results kept; beyond, submissions get 507 until some are
    /// deleted or expire.
    #[arg(long, env = "GLINT_MAX_RESULT_BYTES", default_value_t = ServiceLimits::default().max_result_bytes)]
    pub max_result_bytes: u64,
    /// Time a light-curve request may take (waiting included), seconds.
    #[arg(long, env = "GLINT_REQUEST_TIMEOUT_SECS", default_value_t = 60.0)]
    pub request_timeout_secs: f64,
    /// Time a connection may take to send a request's head, or stay silent between
    /// requests, before it is closed, seconds.
    #[arg(long, env = "GLINT_HEADER_TIMEOUT_SECS", default_value_t = 10.0)]
    pub header_timeout_secs: f64,
    /// How long finished jobs and their results are kept, seconds (default 7 days).
    #[arg(long, env = "GLINT_RESULT_TTL_SECS", default_value_t = 7.0 * 86400.0)]
    pub result_ttl_secs: f64,
    #[command(flatten)]
    pub queue: QueueArgs,
}

/// The shared PostgreSQL queue's flags (`glint serve` and `glint worker`).
#[derive(Debug, Clone, clap::Args)]
pub struct QueueArgs {
    /// Keep jobs on a shared PostgreSQL queue (`postgres://user:pass@host:port/db`)
    /// instead of the embedded store in --data-dir: any number of processes share it.
    #[arg(long, env = "GLINT_DATABASE_URL", hide_env_values = true)]
    pub database_url: Option<String>,
    /// With --database-url: chunks this process computes at once (0: API only).
    #[arg(long, env = "GLINT_WORKERS", default_value_t = 1)]
    pub workers: usize,
    /// With --database-url: epochs per chunk (default: about a second of work each,
    /// estimated from the mesh).
    #[arg(long, env = "GLINT_CHUNK_EPOCHS")]
    pub chunk_epochs: Option<usize>,
    /// With --database-url: seconds a claimed chunk stays its worker's without a renewal
    /// (renewed every third); a crashed worker's chunk returns to the queue after it.
    #[arg(long, env = "GLINT_LEASE_SECS", default_value_t = 30.0)]
    pub lease_secs: f64,
}

impl QueueArgs {
    /// The shared queue's settings, `None` without a database URL.
    pub fn config(&self) -> anyhow::Result<Option<crate::service::shared::SharedConfig>> {
        let Some(url) = self.database_url.as_deref().filter(|u| !u.is_empty()) else {
            return Ok(None);
        };
        anyhow::ensure!(
            self.lease_secs.is_finite() && self.lease_secs >= 0.3 && self.lease_secs < 1e6,
            "--lease-secs must be at least 0.3 seconds, got {}",
            self.lease_secs
        );
        anyhow::ensure!(
            self.chunk_epochs != Some(0),
            "--chunk-epochs must be at least 1"
        );
        Ok(Some(crate::service::shared::SharedConfig {
            database: crate::service::shared::parse_url(url)?,
            chunk_epochs: self.chunk_epochs,
            workers: self.workers,
            lease: Duration::from_secs_f64(self.lease_secs),
        }))
    }
}

impl ServeArgs {
    /// The flags as the service's configuration; rejects nonsense values by name.
    pub fn config(&self) -> anyhow::Result<Config> {
        let secs = |name: &str, v: f64| -> anyhow::Result<Duration> {
            if v.is_finite() && v > 0.0 && v < 1e9 {
                Ok(Duration::from_secs_f64(v))
            } else {
                anyhow::bail!("--{name} must be a positive number of seconds, got {v}")
            }
        };
        for (name, v) in [
            ("max-body-bytes", self.max_body_bytes),
            ("max-inflight-body-bytes", self.max_inflight_body_bytes),
            ("max-triangles", self.max_triangles),
            ("max-sync-epochs", self.max_sync_epochs),
            ("max-job-epochs", self.max_job_epochs),
            ("max-running-jobs", self.max_running_jobs),
            ("max-queued-jobs", self.max_queued_jobs),
            ("max-result-bytes", self.max_result_bytes as usize),
            (
                "max-sync-triangle-epochs",
                self.max_sync_triangle_epochs as usize,
            ),
            (
                "max-sync-pixel-samples",
                self.max_sync_pixel_samples as usize,
            ),
        ] {
            anyhow::ensure!(v > 0, "--{name} must be at least 1");
        }
        let d = ServiceLimits::default();
        Ok(Config {
            addr: self.addr,
            data_dir: self.data_dir.clone(),
            token: self.api_token.clone().filter(|t| !t.is_empty()),
            allow_unauthenticated: self.allow_unauthenticated,
            limits: ServiceLimits {
                max_body_bytes: self.max_body_bytes,
                max_inflight_body_bytes: self.max_inflight_body_bytes,
                max_triangles: self.max_triangles,
                max_sync_epochs: self.max_sync_epochs,
                max_job_epochs: self.max_job_epochs,
                max_sync_triangle_epochs: self.max_sync_triangle_epochs,
                max_sync_pixel_samples: self.max_sync_pixel_samples,
                max_concurrent: self.max_concurrent.unwrap_or(d.max_concurrent).max(1),
                max_queued: self.max_queued,
                max_running_jobs: self.max_running_jobs,
                max_queued_jobs: self.max_queued_jobs,
                max_result_bytes: self.max_result_bytes,
                request_timeout: secs("request-timeout-secs", self.request_timeout_secs)?,
                header_timeout: secs("header-timeout-secs", self.header_timeout_secs)?,
            },
            result_ttl: secs("result-ttl-secs", self.result_ttl_secs)?,
            engine: crate::simulate_with,
            shared: self.queue.config()?,
        })
    }
}

/// `glint` with no subcommand: `glint serve` with the flags' defaults and environment.
pub fn run_default() -> anyhow::Result<()> {
    #[derive(Parser)]
    struct Defaults {
        #[command(flatten)]
        args: ServeArgs,
    }
    let d = Defaults::try_parse_from(["glint"])?;
    run(&d.args)
}

/// Runs the service until SIGTERM or Ctrl-C, then shuts down gracefully.
pub fn run(args: &ServeArgs) -> anyhow::Result<()> {
    let config = args.config()?;
    init_log()?;
    crate::service::request_id::log_panics();
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("starting the async runtime")?;
    rt.block_on(async move {
        let auth = if config.token.is_some() {
            "bearer token required"
        } else {
            "no authentication"
        };
        let store = match &config.shared {
            None => format!("data dir {}", config.data_dir.display()),
            Some(s) => format!(
                "shared PostgreSQL queue at {}:{:?}, {} worker(s)",
                s.database
                    .get_hosts()
                    .first()
                    .map(|h| format!("{h:?}"))
                    .unwrap_or_default(),
                s.database.get_ports().first().copied().unwrap_or(5432),
                s.workers
            ),
        };
        let running = service::start(config).await?;
        // Tests and scripts read this line to learn the port (with --addr …:0).
        eprintln!(
            "glint: listening on http://{} ({store}, {auth}); docs at /docs",
            running.addr
        );
        shutdown_signal().await;
        eprintln!("glint: shutting down");
        running.shutdown().await
    })
}

/// The service's log on stderr: one line a request, faults with their backtraces. Its
/// level comes from `GLINT_LOG` (`off`, `error`, `warn`, `info` — the default — `debug`,
/// `trace`).
pub(crate) fn init_log() -> anyhow::Result<()> {
    use tracing_subscriber::filter::LevelFilter;
    let level = match std::env::var("GLINT_LOG") {
        Err(_) => LevelFilter::INFO,
        Ok(v) => v.trim().parse::<LevelFilter>().map_err(|_| {
            anyhow::anyhow!(
                "GLINT_LOG must be one of off, error, warn, info, debug, trace; got `{v}`"
            )
        })?,
    };
    // A second initialisation (a test running the service twice) keeps the first.
    let _ = tracing_subscriber::fmt()
        .with_max_level(level)
        .with_writer(std::io::stderr)
        .with_ansi(false)
        .try_init();
    Ok(())
}

pub(crate) async fn shutdown_signal() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! {
        _ = ctrl_c => {}
        _ = term => {}
    }
}

/// `glint openapi`: prints the OpenAPI document (the committed openapi/openapi.json).
pub fn print_openapi() -> anyhow::Result<()> {
    std::io::stdout().write_all(service::openapi::spec_json().as_bytes())?;
    Ok(())
}

/// `glint healthcheck`: exits 0 when `GET /healthz` answers 200, else 1 with the reason on
/// stderr (the container's HEALTHCHECK, where 1 means unhealthy; no curl in the image).
pub fn healthcheck(addr: SocketAddr) -> anyhow::Result<()> {
    if let Err(e) = probe_health(addr) {
        eprintln!("unhealthy: {e:#}");
        std::process::exit(1);
    }
    Ok(())
}

fn probe_health(addr: SocketAddr) -> anyhow::Result<()> {
    let mut addr = addr;
    if addr.ip().is_unspecified() {
        // Listening on all interfaces: ask over loopback.
        addr.set_ip(std::net::Ipv4Addr::LOCALHOST.into());
    }
    let timeout = Duration::from_secs(3);
    let mut s = TcpStream::connect_timeout(&addr, timeout)
        .with_context(|| format!("connecting to {addr}"))?;
    s.set_read_timeout(Some(timeout))?;
    s.set_write_timeout(Some(timeout))?;
    write!(
        s,
        "GET /healthz HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"
    )?;
    let mut head = [0u8; 12];
    s.read_exact(&mut head).context("reading the answer")?;
    let status = String::from_utf8_lossy(&head[9..12]).to_string();
    anyhow::ensure!(status == "200", "/healthz answered {status}");
    Ok(())
}
