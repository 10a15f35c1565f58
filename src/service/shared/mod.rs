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
//! | the API side: submit, status, list, cancel, results, expiry | `mod.rs` |
//! | the schema, its migrations and version check | `schema.rs` |
//! | chunk sizes, plans, and a result assembled from its chunks | `chunks.rs` |
//! | the workers: claim, lease renewal, compute, write; wake-ups | `worker.rs` |

pub mod chunks;
pub mod schema;
pub mod worker;

use super::errors::ApiError;
use super::jobs::{
    no_such_job, now_ms, status_from, Deleted, Evaluations, JobKind, JobRecord, JobState, JobStatus,
};
use super::limits::ServiceLimits;
use super::store::Form;
use super::threads::run_blocking;
use crate::scene::{validate, Scene};
use deadpool_postgres::{Manager, ManagerConfig, Pool, RecyclingMethod};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio_postgres::NoTls;

/// The channel a new (or released) chunk is announced on.
pub const CHUNKS_CHANNEL: &str = "glint_chunks";
/// The channel a cancelled job's id is announced on.
pub const CANCEL_CHANNEL: &str = "glint_cancel";

/// Advisory lock key held by a submission's transaction, so that the room check and the
/// idempotency check see every other submission ("glinq" in ASCII).
const SUBMIT_LOCK: i64 = 0x0067_6c69_6e71;

/// A database failure: never the client's fault, a `503` with `Retry-After`.
#[derive(Debug, thiserror::Error)]
pub enum PgError {
    #[error("database: {0}")]
    Db(#[from] tokio_postgres::Error),
    #[error("database: {0}")]
    Pool(#[from] deadpool_postgres::PoolError),
    #[error("database: {0}")]
    Build(#[from] deadpool_postgres::BuildError),
    #[error(
        "the database's schema is version {found}, newer than this glint's {ours}: run a \
         glint at least as new as the one that migrated it"
    )]
    SchemaNewer { found: i32, ours: i32 },
    #[error(
        "the database's schema is version {found}, older than this glint's {ours}: start it \
         without --no-migrate (or `glint serve` of this version) to migrate it"
    )]
    SchemaOlder { found: i32, ours: i32 },
    #[error("database: a stored row is not valid: {0}")]
    Corrupt(String),
}

impl From<PgError> for ApiError {
    fn from(e: PgError) -> Self {
        ApiError {
            retry_after_s: Some(2),
            ..ApiError::new(
                axum::http::StatusCode::SERVICE_UNAVAILABLE,
                format!("the job database cannot be reached or refused the query now ({e})"),
            )
        }
    }
}

/// The connection settings of `url` (`postgres://user:pass@host:port/db`), with a
/// connect timeout; the error names the flag.
pub fn parse_url(url: &str) -> anyhow::Result<tokio_postgres::Config> {
    let mut cfg: tokio_postgres::Config = url.parse().map_err(|e| {
        anyhow::anyhow!("--database-url / GLINT_DATABASE_URL: not a PostgreSQL URL ({e})")
    })?;
    if cfg.get_connect_timeout().is_none() {
        cfg.connect_timeout(Duration::from_secs(5));
    }
    if cfg.get_application_name().is_none() {
        cfg.application_name("glint");
    }
    Ok(cfg)
}

/// A pool of up to `size` connections; a broken connection (the server restarted) is
/// dropped when next taken and a new one made.
pub fn pool(cfg: tokio_postgres::Config, size: usize) -> Result<Pool, PgError> {
    let mgr = Manager::from_config(
        cfg,
        NoTls,
        ManagerConfig {
            recycling_method: RecyclingMethod::Verified,
        },
    );
    Ok(Pool::builder(mgr)
        .max_size(size.max(2))
        .runtime(deadpool_postgres::Runtime::Tokio1)
        .wait_timeout(Some(Duration::from_secs(10)))
        .create_timeout(Some(Duration::from_secs(5)))
        .recycle_timeout(Some(Duration::from_secs(5)))
        .build()?)
}

/// Connects once and applies the migrations (or checks the version), with the reason on
/// failure: a service must not start on a database it cannot use.
pub async fn prepare(cfg: &tokio_postgres::Config, apply: bool) -> anyhow::Result<()> {
    let (mut client, conn) = cfg
        .connect(NoTls)
        .await
        .map_err(|e| anyhow::anyhow!("cannot connect to the job database: {e}"))?;
    let driver = tokio::spawn(conn);
    let out = schema::migrate(&mut client, apply).await;
    drop(client);
    let _ = driver.await;
    out.map(|_| ()).map_err(anyhow::Error::from)
}

/// What a submission stores: the epochs, a fit's light curves and the chunks.
struct Planned {
    epochs_total: usize,
    evaluations: Option<Evaluations>,
    chunk_epochs: usize,
    chunks: Vec<(usize, usize)>,
}

/// A body of `kind` checked with the job limits and cut into chunks (a fit is one chunk:
/// its light curves follow one another).
fn planned(
    kind: JobKind,
    text: &str,
    limits: &ServiceLimits,
    fixed: Option<usize>,
) -> Result<Planned, ApiError> {
    match kind {
        JobKind::Lightcurve => {
            let request = validate::parse_request(text)?;
            let scene = Scene::from_request(&request, &limits.job_limits())?;
            let per = chunks::chunk_epochs(&scene, fixed);
            Ok(Planned {
                epochs_total: scene.epochs.len(),
                evaluations: None,
                chunk_epochs: per,
                chunks: chunks::plan(scene.epochs.len(), per),
            })
        }
        JobKind::FitLightcurve => {
            let (epochs, evaluations) = super::jobs::fit::accepted(text, limits)?;
            Ok(Planned {
                epochs_total: epochs,
                evaluations: Some(evaluations),
                chunk_epochs: epochs.max(1),
                chunks: vec![(0, epochs)],
            })
        }
    }
}

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

const KIND_LIGHTCURVE: &str = "lightcurve";
const KIND_FIT: &str = "fit-lightcurve";

fn kind_name(k: JobKind) -> &'static str {
    match k {
        JobKind::Lightcurve => KIND_LIGHTCURVE,
        JobKind::FitLightcurve => KIND_FIT,
    }
}

fn kind_of(s: &str) -> Result<JobKind, PgError> {
    match s {
        KIND_LIGHTCURVE => Ok(JobKind::Lightcurve),
        KIND_FIT => Ok(JobKind::FitLightcurve),
        other => Err(PgError::Corrupt(format!("job kind `{other}`"))),
    }
}

fn state_of(s: &str) -> Result<JobState, PgError> {
    JobState::ALL
        .into_iter()
        .find(|k| k.name() == s)
        .ok_or_else(|| PgError::Corrupt(format!("job state `{s}`")))
}

/// The columns [`status_of_row`] reads, from `glint_jobs j`; the epochs done are summed
/// from the job's done chunks.
const STATUS_COLUMNS: &str = "j.id, j.kind, j.state, j.epochs_total, j.created_ms, \
     j.started_ms, j.finished_ms, j.error, j.attempts, j.eval_max, j.eval_done, \
     (SELECT coalesce(sum(c.epochs_computed), 0)::bigint FROM glint_chunks c \
      WHERE c.job_id = j.id AND c.state = 'done') AS epochs_done";

fn status_of_row(row: &tokio_postgres::Row, ttl: Duration) -> Result<JobStatus, PgError> {
    let state = state_of(row.get("state"))?;
    let epochs_total = row.get::<_, i64>("epochs_total") as usize;
    let done = row.get::<_, i64>("epochs_done") as usize;
    let evaluations = row
        .get::<_, Option<i64>>("eval_max")
        .map(|max| Evaluations {
            done: row.get::<_, Option<i64>>("eval_done").unwrap_or(0) as usize,
            max: max as usize,
        });
    let rec = JobRecord {
        id: row.get("id"),
        state,
        epochs_total,
        epochs_done: done,
        created_ms: row.get("created_ms"),
        started_ms: row.get("started_ms"),
        finished_ms: row.get("finished_ms"),
        error: row.get("error"),
        attempts: row.get::<_, i32>("attempts") as u32,
        idempotency: None,
        kind: kind_of(row.get("kind"))?,
        evaluations,
    };
    Ok(status_from(&rec, done, evaluations, ttl))
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

    /// Validates and stores a new job with its chunks in one transaction, and wakes the
    /// workers. With an idempotency key already used for the same body, returns that
    /// job (`true`: replayed); with a different body, 422.
    pub async fn submit(
        self: &Arc<Self>,
        kind: JobKind,
        body: axum::body::Bytes,
        key: Option<String>,
    ) -> Result<(JobStatus, bool), ApiError> {
        if self.is_shutting_down() {
            return Err(ApiError::new(
                axum::http::StatusCode::SERVICE_UNAVAILABLE,
                "shutting down",
            ));
        }
        let idempotency = key.map(|k| {
            use sha2::Digest;
            let digest = sha2::Sha256::digest(&body);
            let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
            (k, hex)
        });
        // a retry costs no validation
        if let Some(found) = self.replay(None, idempotency.as_ref()).await? {
            return Ok((found, true));
        }
        let limits = self.limits.clone();
        let fixed = self.chunk_epochs;
        let text_body = body.clone();
        let plan = run_blocking("validating the job", move || {
            let text = std::str::from_utf8(&text_body)
                .map_err(|_| ApiError::bad_request("request body is not UTF-8"))?;
            planned(kind, text, &limits, fixed)
        })
        .await??;

        let mut client = self.pool.get().await.map_err(PgError::from)?;
        let tx = client.transaction().await.map_err(PgError::from)?;
        tx.execute("SELECT pg_advisory_xact_lock($1)", &[&SUBMIT_LOCK])
            .await
            .map_err(PgError::from)?;
        if let Some(found) = self.replay(Some(&tx), idempotency.as_ref()).await? {
            return Ok((found, true));
        }
        self.room_in(&tx).await?;
        let id = uuid::Uuid::new_v4().to_string();
        let created = now_ms();
        let (idem_key, idem_digest) = match &idempotency {
            Some((k, d)) => (Some(k.as_str()), Some(d.as_str())),
            None => (None, None),
        };
        let eval_max = plan.evaluations.map(|e| e.max as i64);
        let eval_done = plan.evaluations.map(|_| 0i64);
        tx.execute(
            "INSERT INTO glint_jobs (id, kind, state, request, epochs_total, chunk_epochs, \
             created_ms, idem_key, idem_digest, eval_max, eval_done) \
             VALUES ($1, $2, 'queued', $3, $4, $5, $6, $7, $8, $9, $10)",
            &[
                &id,
                &kind_name(kind),
                &&body[..],
                &(plan.epochs_total as i64),
                &(plan.chunk_epochs as i64),
                &created,
                &idem_key,
                &idem_digest,
                &eval_max,
                &eval_done,
            ],
        )
        .await
        .map_err(PgError::from)?;
        let idx: Vec<i32> = (0..plan.chunks.len() as i32).collect();
        let first: Vec<i64> = plan.chunks.iter().map(|c| c.0 as i64).collect();
        let epochs: Vec<i64> = plan.chunks.iter().map(|c| c.1 as i64).collect();
        tx.execute(
            "INSERT INTO glint_chunks (job_id, idx, first_epoch, epochs, state) \
             SELECT $1, i, f, n, 'queued' FROM unnest($2::int[], $3::bigint[], $4::bigint[]) \
             AS u(i, f, n)",
            &[&id, &idx, &first, &epochs],
        )
        .await
        .map_err(PgError::from)?;
        tx.execute(&format!("NOTIFY {CHUNKS_CHANNEL}"), &[])
            .await
            .map_err(PgError::from)?;
        let row = tx
            .query_one(
                &format!("SELECT {STATUS_COLUMNS} FROM glint_jobs j WHERE j.id = $1"),
                &[&id],
            )
            .await
            .map_err(PgError::from)?;
        let status = status_of_row(&row, self.ttl)?;
        tx.commit().await.map_err(PgError::from)?;
        Ok((status, false))
    }

    /// The job made earlier with this idempotency key, if any (422 when it came with
    /// another body); read in `tx` when given.
    async fn replay(
        &self,
        tx: Option<&deadpool_postgres::Transaction<'_>>,
        key: Option<&(String, String)>,
    ) -> Result<Option<JobStatus>, ApiError> {
        let Some((key, digest)) = key else {
            return Ok(None);
        };
        let sql = format!(
            "SELECT {STATUS_COLUMNS}, j.idem_digest FROM glint_jobs j WHERE j.idem_key = $1"
        );
        let row = match tx {
            Some(tx) => tx.query_opt(&sql, &[key]).await,
            None => {
                let client = self.pool.get().await.map_err(PgError::from)?;
                client.query_opt(&sql, &[key]).await
            }
        }
        .map_err(PgError::from)?;
        let Some(row) = row else { return Ok(None) };
        let status = status_of_row(&row, self.ttl)?;
        if row.get::<_, Option<String>>("idem_digest").as_deref() == Some(digest.as_str()) {
            Ok(Some(status))
        } else {
            Err(ApiError::new(
                axum::http::StatusCode::UNPROCESSABLE_ENTITY,
                format!(
                    "this Idempotency-Key was used for job {} with a different request body",
                    status.id
                ),
            )
            .with_field("Idempotency-Key"))
        }
    }

    /// 429 while `max_queued_jobs` jobs are unfinished, 507 while the stored results are
    /// over their limit (exact: read under the submission lock).
    async fn room_in(&self, tx: &deadpool_postgres::Transaction<'_>) -> Result<(), ApiError> {
        let row = tx
            .query_one(
                "SELECT count(*) FILTER (WHERE state IN ('queued', 'running')), \
                 coalesce(sum(result_bytes), 0)::bigint FROM glint_jobs",
                &[],
            )
            .await
            .map_err(PgError::from)?;
        let unfinished = row.get::<_, i64>(0) as usize;
        let stored = row.get::<_, i64>(1) as u64;
        if stored >= self.limits.max_result_bytes {
            return Err(ApiError::new(
                axum::http::StatusCode::INSUFFICIENT_STORAGE,
                format!(
                    "stored results take {stored} bytes (limit {}): fetch and DELETE \
                     finished jobs to make room",
                    self.limits.max_result_bytes
                ),
            ));
        }
        if unfinished >= self.limits.max_queued_jobs {
            let mut e = ApiError::new(
                axum::http::StatusCode::TOO_MANY_REQUESTS,
                format!(
                    "{unfinished} jobs are queued or running (limit {}); retry when some \
                     have finished, or cancel some",
                    self.limits.max_queued_jobs
                ),
            );
            e.retry_after_s = Some(10);
            return Err(e);
        }
        Ok(())
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
        let row = tx
            .query_one(
                &format!("SELECT {STATUS_COLUMNS} FROM glint_jobs j WHERE j.id = $1"),
                &[&id],
            )
            .await
            .map_err(PgError::from)?;
        let status = status_of_row(&row, self.ttl)?;
        tx.commit().await.map_err(PgError::from)?;
        Ok(Deleted::Cancelled(Box::new(status)))
    }

    /// A done job's chunks' results in epoch order, and what it computes; 404 / 409 when
    /// it has none.
    async fn parts(&self, id: &str) -> Result<(JobKind, Vec<Vec<u8>>), ApiError> {
        let client = self.pool.get().await.map_err(PgError::from)?;
        let row = client
            .query_opt("SELECT kind, state FROM glint_jobs WHERE id = $1", &[&id])
            .await
            .map_err(PgError::from)?
            .ok_or_else(|| no_such_job(id))?;
        let kind = kind_of(row.get(0))?;
        let state = state_of(row.get(1))?;
        if state != JobState::Done {
            return Err(ApiError::conflict(format!(
                "job is {}, there is no result{}",
                state.name(),
                if state.is_final() { "" } else { " yet" }
            )));
        }
        let rows = client
            .query(
                "SELECT data FROM glint_results WHERE job_id = $1 ORDER BY idx",
                &[&id],
            )
            .await
            .map_err(PgError::from)?;
        Ok((kind, rows.into_iter().map(|r| r.get(0)).collect()))
    }

    /// A done job's result in `form`, assembled from its chunks in epoch order (a fit's
    /// is its one chunk's JSON; it has no CSV, which the route refuses).
    pub async fn result(&self, id: &str, form: Form) -> Result<(JobKind, Vec<u8>), ApiError> {
        let (kind, parts) = self.parts(id).await?;
        if kind == JobKind::FitLightcurve {
            return Ok((kind, parts.into_iter().next().unwrap_or_default()));
        }
        let bytes = run_blocking("assembling the result", move || {
            let resp = assemble(parts)?;
            Ok::<_, ApiError>(match form {
                Form::Json => serde_json::to_vec(&resp).map_err(ApiError::internal)?,
                Form::Csv => crate::report::csv::to_csv(&resp).into_bytes(),
            })
        })
        .await??;
        Ok((kind, bytes))
    }

    /// The PNG of a done job's thumbnail of `epoch`.
    pub async fn thumbnail(&self, id: &str, epoch: usize) -> Result<Vec<u8>, ApiError> {
        let (kind, parts) = self.parts(id).await?;
        if kind == JobKind::FitLightcurve {
            return Err(ApiError::not_found("a fit job renders no images").with_field("epoch"));
        }
        let none = move || {
            ApiError::not_found(format!("the job has no image for epoch {epoch}"))
                .with_field("epoch")
        };
        run_blocking("reading the image", move || {
            let resp = assemble(parts)?;
            let t = resp
                .thumbnails
                .iter()
                .flatten()
                .find(|t| t.epoch == epoch)
                .ok_or_else(none)?;
            use base64::Engine as _;
            base64::engine::general_purpose::STANDARD
                .decode(t.png_base64.as_bytes())
                .map_err(ApiError::internal)
        })
        .await?
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

/// A light curve's chunk results parsed and joined in order.
fn assemble(parts: Vec<Vec<u8>>) -> Result<crate::scene::Response, ApiError> {
    let parsed: Result<Vec<crate::scene::Response>, _> =
        parts.iter().map(|p| serde_json::from_slice(p)).collect();
    let parsed = parsed.map_err(|e| ApiError::from(PgError::Corrupt(e.to_string())))?;
    chunks::assemble(parsed)
        .ok_or_else(|| ApiError::from(PgError::Corrupt("a done job without results".into())))
}
