//! `glint worker`: computes chunks of jobs from the shared PostgreSQL queue until SIGTERM
//! or Ctrl-C (then gives its chunks in progress back to the queue). No HTTP API.

use crate::service::shared::{self, worker};
use anyhow::Context;
use std::sync::Arc;
use std::time::Duration;

/// Flags of `glint worker`; each also reads a `GLINT_…` environment variable.
#[derive(Debug, Clone, clap::Args)]
pub struct WorkerArgs {
    /// The shared queue (`postgres://user:pass@host:port/db`).
    #[arg(long, env = "GLINT_DATABASE_URL", hide_env_values = true)]
    pub database_url: String,
    /// Chunks computed at once (each on all the cores this process may use).
    #[arg(long, env = "GLINT_WORKERS", default_value_t = 1)]
    pub workers: usize,
    /// Seconds a claimed chunk stays this worker's without a renewal (renewed every
    /// third); use the same value as the other processes.
    #[arg(long, env = "GLINT_LEASE_SECS", default_value_t = 30.0)]
    pub lease_secs: f64,
    /// Do not migrate the database: refuse to start unless it is at this binary's
    /// schema version.
    #[arg(long, env = "GLINT_NO_MIGRATE")]
    pub no_migrate: bool,
    /// Computation threads (default: the cores this process may use, e.g. under taskset).
    #[arg(long, env = "GLINT_THREADS")]
    pub threads: Option<usize>,
}

/// Runs the workers until SIGTERM or Ctrl-C.
pub fn run(args: &WorkerArgs) -> anyhow::Result<()> {
    anyhow::ensure!(args.workers >= 1, "--workers must be at least 1");
    anyhow::ensure!(
        args.lease_secs.is_finite() && args.lease_secs >= 0.3 && args.lease_secs < 1e6,
        "--lease-secs must be at least 0.3 seconds, got {}",
        args.lease_secs
    );
    let database = shared::parse_url(&args.database_url)?;
    super::serve::init_log()?;
    crate::service::request_id::log_panics();
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(2, |n| n.get()));
    let pools = crate::service::threads::Pools::new(threads)?;
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("starting the async runtime")?;
    rt.block_on(async move {
        // Retried with backoff: a worker may start before its database.
        let mut backoff = Duration::from_millis(200);
        loop {
            match shared::prepare(&database, !args.no_migrate).await {
                Ok(()) => break,
                Err(e) if e.downcast_ref::<shared::PgError>().is_some() => return Err(e),
                Err(e) => {
                    eprintln!("glint worker: {e:#}; again in {backoff:?}");
                    tokio::time::sleep(backoff).await;
                    backoff = (backoff * 2).min(Duration::from_secs(5));
                }
            }
        }
        let pool = shared::pool(database.clone(), 4 + 2 * args.workers)?;
        let name = worker::default_name();
        let workers = worker::Workers::start(
            worker::WorkerConfig {
                database,
                pool,
                workers: args.workers,
                lease: Duration::from_secs_f64(args.lease_secs),
                engine: crate::simulate_with,
                threads: Arc::clone(&pools.jobs),
                metrics: None,
            },
            name.clone(),
        );
        // Tests and scripts read this line.
        eprintln!(
            "glint worker: {name} computing up to {} chunk(s) at once on {threads} thread(s)",
            args.workers
        );
        super::serve::shutdown_signal().await;
        eprintln!("glint worker: stopping; chunks in progress go back to the queue");
        workers.shutdown(Duration::from_secs(10)).await;
        // The measurement (loadtest/queue_scaling.sh) reads this line.
        eprintln!("glint worker: {}", workers.timings.summary());
        Ok(())
    })
}
