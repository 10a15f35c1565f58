//! Jobs on a shared PostgreSQL queue (`--database-url`): any number of `glint serve`
//! (API and workers) and `glint worker` (workers only) processes on any machines share
//! it. The database is the only truth; no process keeps a table of its own.
//!
//! ```text
//! POST ─validate─▶ one transaction: job row + its chunk rows + NOTIFY ─▶ 202
//! worker: claim a chunk (FOR UPDATE SKIP LOCKED, lease) ─▶ compute, renewing the lease
//!         ─▶ one transaction: job row locked, still active? chunk done + its result row
//!            (keyed by job and chunk) + the job done when it was the last
//! an expired lease returns its chunk to the queue; LISTEN/NOTIFY wakes idle workers
//! ```
//!
//! | concept | file |
//! |---|---|
//! | the API side: the queue's handle, status, list, cancel, expiry | `mod.rs` |
//! | the database: its URL, the pool, the schema prepared at start; its failures | `database.rs` |
//! | a job's row read as its status; kinds and states as stored | `rows.rs` |
//! | a submission: checked, planned, stored with its chunks, idempotent | `submit.rs` |
//! | a done job's result and images, assembled from its chunks | `results.rs` |
//! | the schema, its migrations and version check | `schema.rs` |
//! | chunk sizes, plans, and a result assembled from its chunks | `chunks.rs` |
//! | the workers: claim, lease renewal, compute, write; wake-ups | `worker/` |

pub mod chunks;
mod database;
mod results;
mod rows;
pub mod schema;
mod submit;
pub mod worker;

pub use database::{parse_url, pool, prepare, PgError};

use super::errors::ApiError;
use super::jobs::{no_such_job, now_ms, Deleted, JobState, JobStatus};
use super::limits::ServiceLimits;
use deadpool_postgres::Pool;
use rows::{state_of, status_in, status_of_row, STATUS_COLUMNS};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// The channel a new (or released) chunk is announced on.
pub const CHUNKS_CHANNEL: &str = "glint_chunks";
/// The channel a cancelled job's id is announced on.
pub const CANCEL_CHANNEL: &str = "glint_cancel";

/// The API side of the shared queue (and, in `glint serve`, its workers).
pub struct Shared {
    pool: Pool,
    limits: ServiceLimits,
    ttl: Duration,
    /// Epochs per chunk when fixed (`--chunk-epochs`); else chosen per job.
    chunk_epochs: Option<usize>,
    shutting_down: AtomicBool,
    workers: Option<Arc<worker::Workers>>,
}

/// Settings of the shared queue in `glint serve`.
#[derive(Debug, Clone)]
pub struct SharedConfig {
    pub database: tokio_postgres::Config,
    /// Epochs per chunk (`None`: about a second of work each).
    pub chunk_epochs: Option<usize>,
    /// Workers in this process (chunks computed at once); 0: API only.
    pub workers: usize,
    /// How long a claimed chunk is its worker's without a renewal.
    pub lease: Duration,
}

impl Shared {
    /// Migrates the database, and starts the expiry sweeper and `config.workers` workers.
    /// Runs inside the tokio runtime.
    pub async fn start(
        config: &SharedConfig,
        limits: ServiceLimits,
        ttl: Duration,
        engine: super::Engine,
        pool_threads: Arc<rayon::ThreadPool>,
        metrics: Arc<super::metrics::Metrics>,
    ) -> anyhow::Result<Arc<Shared>> {
        prepare(&config.database, true).await?;
        let pool = pool(config.database.clone(), 16 + 2 * config.workers)?;
        let workers = (config.workers > 0).then(|| {
            worker::Workers::start(
                worker::WorkerConfig {
                    database: config.database.clone(),
                    pool: pool.clone(),
                    workers: config.workers,
                    lease: config.lease,
                    engine,
                    threads: pool_threads,
                    metrics: Some(metrics),
                },
                worker::default_name(),
            )
        });
        let shared = Arc::new(Shared {
            pool,
            limits,
            ttl,
            chunk_epochs: config.chunk_epochs,
            shutting_down: AtomicBool::new(false),
            workers,
        });
        tokio::spawn(shared.clone().sweeper());
        Ok(shared)
    }

    /// One job's status (its epochs done summed from its done chunks).
    pub async fn status(&self, id: &str) -> Result<Option<JobStatus>, ApiError> {
        let client = self.pool.get().await.map_err(PgError::from)?;
        let row = client
            .query_opt(
                &format!("SELECT {STATUS_COLUMNS} FROM glint_jobs j WHERE j.id = $1"),
                &[&id],
            )
            .await
            .map_err(PgError::from)?;
        Ok(row.map(|r| status_of_row(&r, self.ttl)).transpose()?)
    }

    /// The most recent jobs, newest first.
    pub async fn list(
        &self,
        limit: usize,
        state: Option<JobState>,
    ) -> Result<Vec<JobStatus>, ApiError> {
        let client = self.pool.get().await.map_err(PgError::from)?;
        let rows = client
            .query(
                &format!(
                    "SELECT {STATUS_COLUMNS} FROM glint_jobs j \
                     WHERE ($1::text IS NULL OR j.state = $1) \
                     ORDER BY j.created_ms DESC, j.id LIMIT $2"
                ),
                &[&state.map(|s| s.name()), &(limit as i64)],
            )
            .await
            .map_err(PgError::from)?;
        let out: Result<Vec<_>, _> = rows.iter().map(|r| status_of_row(r, self.ttl)).collect();
        Ok(out?)
    }

    /// Jobs in each state.
    pub async fn counts(&self) -> Result<HashMap<JobState, usize>, ApiError> {
        let client = self.pool.get().await.map_err(PgError::from)?;
        let rows = client
            .query("SELECT state, count(*) FROM glint_jobs GROUP BY state", &[])
            .await
            .map_err(PgError::from)?;
        let mut m: HashMap<JobState, usize> = JobState::ALL.iter().map(|&s| (s, 0)).collect();
        for r in rows {
            m.insert(state_of(r.get(0))?, r.get::<_, i64>(1) as usize);
        }
        Ok(m)
    }

    /// Cancels a queued or running job (`200`), or removes a finished one (`204`). The
    /// cancel commits under the job row's lock, which every chunk's write takes first:
    /// no chunk is written after it.
    pub async fn delete(&self, id: &str) -> Result<Deleted, ApiError> {
        let mut client = self.pool.get().await.map_err(PgError::from)?;
        let tx = client.transaction().await.map_err(PgError::from)?;
        let state = tx
            .query_opt(
                "SELECT state FROM glint_jobs WHERE id = $1 FOR UPDATE",
                &[&id],
            )
            .await
            .map_err(PgError::from)?
            .ok_or_else(|| no_such_job(id))?;
        let state = state_of(state.get(0))?;
        if state.is_final() {
            tx.execute("DELETE FROM glint_jobs WHERE id = $1", &[&id])
                .await
                .map_err(PgError::from)?;
            tx.commit().await.map_err(PgError::from)?;
            return Ok(Deleted::Removed);
        }
        tx.execute(
            "UPDATE glint_jobs SET state = 'cancelled', finished_ms = $2, request = NULL \
             WHERE id = $1",
            &[&id, &now_ms()],
        )
        .await
        .map_err(PgError::from)?;
        tx.execute("SELECT pg_notify($1, $2)", &[&CANCEL_CHANNEL, &id])
            .await
            .map_err(PgError::from)?;
        let status = status_in(&tx, id, self.ttl).await?;
        tx.commit().await.map_err(PgError::from)?;
        Ok(Deleted::Cancelled(Box::new(status)))
    }

    /// Whether shutdown has begun.
    pub fn is_shutting_down(&self) -> bool {
        self.shutting_down.load(Ordering::SeqCst)
    }

    /// Whether the database answers a query now.
    pub async fn check(&self) -> Result<(), PgError> {
        let client = self.pool.get().await?;
        client.query_one("SELECT 1", &[]).await?;
        Ok(())
    }

    /// Stops taking jobs and stops this process's workers: their chunks go back to the
    /// queue for any other worker.
    pub async fn shutdown(&self, grace: Duration) {
        self.shutting_down.store(true, Ordering::SeqCst);
        if let Some(w) = &self.workers {
            w.shutdown(grace).await;
        }
    }

    /// Removes finished jobs older than the time to live, every quarter of it (between
    /// 1 s and 1 min). Every process sweeps; a sweep is one idempotent DELETE.
    async fn sweeper(self: Arc<Self>) {
        let every = (self.ttl / 4).clamp(Duration::from_secs(1), Duration::from_secs(60));
        loop {
            if self.is_shutting_down() {
                return;
            }
            let cutoff = now_ms().saturating_sub(self.ttl.as_millis() as i64);
            if let Ok(client) = self.pool.get().await {
                let r = client
                    .execute(
                        "DELETE FROM glint_jobs WHERE state IN ('done', 'failed', 'cancelled') \
                         AND finished_ms <= $1",
                        &[&cutoff],
                    )
                    .await;
                if let Err(e) = r {
                    tracing::warn!("expiring finished jobs: {e}");
                }
            }
            tokio::time::sleep(every).await;
        }
    }
}
