//! The workers of the shared queue, in `glint worker` and `glint serve`: each claims a
//! chunk (`FOR UPDATE SKIP LOCKED`, under a lease), computes it while a task renews the
//! lease, and writes its result in the transaction that marks it done. A listener on its
//! own connection (`LISTEN`) wakes idle workers when chunks are queued and stops the
//! chunks of a cancelled job. Every database step is retried with backoff, so workers
//! ride out a restart of the database.

use super::chunks;
use super::{PgError, CANCEL_CHANNEL, CHUNKS_CHANNEL};
use crate::integrate::{Cancelled, Progress};
use crate::scene::{validate, Limits, Scene};
use crate::service::jobs::now_ms;
use crate::service::limits::ServiceLimits;
use deadpool_postgres::Pool;
use futures_util::StreamExt;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tokio::sync::Notify;
use tokio_postgres::{AsyncMessage, NoTls};

/// What the workers of one process need.
#[derive(Clone)]
pub struct WorkerConfig {
    /// For the listener's own connection.
    pub database: tokio_postgres::Config,
    pub pool: Pool,
    /// Chunks computed at once in this process.
    pub workers: usize,
    /// How long a claimed chunk is its worker's without a renewal (renewed every third).
    pub lease: Duration,
    pub engine: crate::service::Engine,
    /// The rayon pool chunks are computed on.
    pub threads: Arc<rayon::ThreadPool>,
    /// Epochs computed are counted here (in `glint serve`).
    pub metrics: Option<Arc<crate::service::metrics::Metrics>>,
}

/// This process's name in the queue (`done_by`, `worker`): host and process id.
pub fn default_name() -> String {
    let host = std::env::var("HOSTNAME")
        .ok()
        .filter(|h| !h.is_empty())
        .or_else(|| {
            std::fs::read_to_string("/etc/hostname")
                .ok()
                .map(|h| h.trim().to_string())
        })
        .unwrap_or_else(|| "localhost".into());
    format!("{host}:{}", std::process::id())
}

/// A job's input, parsed once per process and job.
struct JobInput {
    text: Arc<str>,
    scene: Option<Arc<Scene>>,
}

/// A claimed chunk.
#[derive(Debug, Clone)]
struct Claimed {
    job: String,
    idx: i32,
    first: usize,
    epochs: usize,
}

/// The workers of one process.
pub struct Workers {
    cfg: WorkerConfig,
    /// `name/n` for worker n.
    name: String,
    wake: Notify,
    stopping: AtomicBool,
    /// The progress of each chunk being computed, by (job, chunk).
    running: Mutex<HashMap<(String, i32), Arc<Progress>>>,
    inputs: Mutex<HashMap<String, Arc<JobInput>>>,
    active: AtomicUsize,
    idle: Notify,
    /// What this process's chunks took, for the queue's overhead (`glint worker` prints
    /// it when it stops).
    pub timings: Timings,
}

/// Time spent on the chunks this process claimed and wrote, in nanoseconds: the
/// queue's part (the claim's transaction, the write's) against the computation's.
#[derive(Debug, Default)]
pub struct Timings {
    pub claimed: AtomicU64,
    pub claim_ns: AtomicU64,
    pub written: AtomicU64,
    pub write_ns: AtomicU64,
    pub compute_ns: AtomicU64,
}

impl Timings {
    /// One line: chunks, and the mean claim, write and computation per chunk in ms.
    pub fn summary(&self) -> String {
        let ms = |ns: &AtomicU64, n: &AtomicU64| {
            ns.load(Ordering::Relaxed) as f64 / 1e6 / n.load(Ordering::Relaxed).max(1) as f64
        };
        let claim = ms(&self.claim_ns, &self.claimed);
        let write = ms(&self.write_ns, &self.written);
        let compute = ms(&self.compute_ns, &self.written);
        format!(
            "{} chunks written; per chunk: claim {claim:.2} ms, write {write:.2} ms, \
             compute {compute:.1} ms (queue overhead {:.2} % of the computation)",
            self.written.load(Ordering::Relaxed),
            100.0 * (claim + write) / compute.max(1e-9)
        )
    }
}

/// The first wait after a database failure; it doubles up to [`MAX_BACKOFF`].
const FIRST_BACKOFF: Duration = Duration::from_millis(100);
const MAX_BACKOFF: Duration = Duration::from_secs(5);

/// How long an idle worker waits for a notification before it looks again (an expired
/// lease announces nothing).
fn poll_every(lease: Duration) -> Duration {
    (lease / 2).clamp(Duration::from_millis(200), Duration::from_secs(5))
}

impl Workers {
    /// Starts the listener and `cfg.workers` workers named after `name`. Runs inside the
    /// tokio runtime.
    pub fn start(cfg: WorkerConfig, name: String) -> Arc<Workers> {
        let w = Arc::new(Workers {
            cfg,
            name,
            wake: Notify::new(),
            stopping: AtomicBool::new(false),
            running: Mutex::new(HashMap::new()),
            inputs: Mutex::new(HashMap::new()),
            active: AtomicUsize::new(0),
            idle: Notify::new(),
            timings: Timings::default(),
        });
        tokio::spawn(w.clone().listen());
        for n in 0..w.cfg.workers.max(1) {
            w.active.fetch_add(1, Ordering::SeqCst);
            let me = w.clone();
            tokio::spawn(async move {
                me.clone().work(n).await;
                if me.active.fetch_sub(1, Ordering::SeqCst) == 1 {
                    me.idle.notify_waiters();
                }
            });
        }
        w
    }

    /// Stops claiming, stops the chunks being computed and gives them back to the queue,
    /// waiting up to `grace` for the workers to finish.
    pub async fn shutdown(&self, grace: Duration) {
        self.stopping.store(true, Ordering::SeqCst);
        for p in self.lock_running().values() {
            p.cancel();
        }
        self.wake.notify_waiters();
        let wait = async {
            loop {
                let notified = self.idle.notified();
                if self.active.load(Ordering::SeqCst) == 0 {
                    return;
                }
                notified.await;
            }
        };
        let _ = tokio::time::timeout(grace, wait).await;
    }

    fn lock_running(&self) -> std::sync::MutexGuard<'_, HashMap<(String, i32), Arc<Progress>>> {
        self.running.lock().unwrap_or_else(|e| e.into_inner())
    }

    fn stopping(&self) -> bool {
        self.stopping.load(Ordering::SeqCst)
    }

    /// Listens for new chunks (wakes the idle workers) and cancelled jobs (stops their
    /// chunks here), reconnecting with backoff; after each (re)connection the workers are
    /// woken, in case a notification was missed meanwhile.
    async fn listen(self: Arc<Self>) {
        let mut backoff = FIRST_BACKOFF;
        while !self.stopping() {
            match self.listen_once().await {
                Ok(()) => backoff = FIRST_BACKOFF,
                Err(e) => {
                    tracing::warn!("job queue listener: {e}; reconnecting in {backoff:?}");
                    tokio::time::sleep(backoff).await;
                    backoff = (backoff * 2).min(MAX_BACKOFF);
                }
            }
        }
    }

    async fn listen_once(&self) -> Result<(), PgError> {
        let (client, mut conn) = self.cfg.database.connect(NoTls).await?;
        let (tx, mut rx) = tokio::sync::mpsc::unbounded_channel();
        let driver = tokio::spawn(async move {
            let mut messages = futures_util::stream::poll_fn(move |cx| conn.poll_message(cx));
            while let Some(m) = messages.next().await {
                match m {
                    Ok(AsyncMessage::Notification(n)) => {
                        if tx.send(n).is_err() {
                            return;
                        }
                    }
                    Ok(_) => {}
                    Err(e) => {
                        tracing::warn!("job queue listener connection: {e}");
                        return;
                    }
                }
            }
        });
        client
            .batch_execute(&format!("LISTEN {CHUNKS_CHANNEL}; LISTEN {CANCEL_CHANNEL}"))
            .await?;
        self.wake.notify_waiters();
        loop {
            tokio::select! {
                n = rx.recv() => match n {
                    Some(n) if n.channel() == CANCEL_CHANNEL => {
                        for ((job, _), p) in self.lock_running().iter() {
                            if job == n.payload() {
                                p.cancel();
                            }
                        }
                    }
                    Some(_) => self.wake.notify_waiters(),
                    None => break,
                },
                _ = tokio::time::sleep(Duration::from_millis(500)) => {
                    if self.stopping() {
                        break;
                    }
                }
            }
        }
        drop(client);
        let _ = driver.await;
        Ok(())
    }

    /// Worker `n`: claims and computes chunks until shutdown.
    async fn work(self: Arc<Self>, n: usize) {
        let name = format!("{}/{n}", self.name);
        let mut backoff = FIRST_BACKOFF;
        while !self.stopping() {
            let notified = self.wake.notified();
            tokio::pin!(notified);
            notified.as_mut().enable();
            let began = std::time::Instant::now();
            match self.claim(&name).await {
                Ok(Some(c)) => {
                    let t = &self.timings;
                    t.claim_ns
                        .fetch_add(began.elapsed().as_nanos() as u64, Ordering::Relaxed);
                    t.claimed.fetch_add(1, Ordering::Relaxed);
                    backoff = FIRST_BACKOFF;
                    self.run(&name, c).await;
                }
                Ok(None) => {
                    backoff = FIRST_BACKOFF;
                    let _ = tokio::time::timeout(poll_every(self.cfg.lease), notified).await;
                }
                Err(e) => {
                    tracing::warn!(worker = name, "claiming a chunk: {e}; again in {backoff:?}");
                    tokio::time::sleep(backoff).await;
                    backoff = (backoff * 2).min(MAX_BACKOFF);
                }
            }
        }
    }

    /// Claims the first open chunk of the oldest active job (queued, or running under an
    /// expired lease), skipping those other workers hold locked; marks its job running.
    async fn claim(&self, name: &str) -> Result<Option<Claimed>, PgError> {
        let mut client = self.cfg.pool.get().await?;
        let tx = client.transaction().await?;
        let row = tx
            .query_opt(
                "WITH next AS ( \
                   SELECT ch.job_id, ch.idx FROM glint_chunks ch \
                   JOIN glint_jobs j ON j.id = ch.job_id \
                   WHERE j.state IN ('queued', 'running') AND ch.state <> 'done' \
                     AND (ch.state = 'queued' OR ch.lease_until < now()) \
                   ORDER BY j.created_ms, j.id, ch.idx \
                   LIMIT 1 FOR UPDATE OF ch SKIP LOCKED) \
                 UPDATE glint_chunks u SET state = 'running', worker = $1, \
                   claims = u.claims + 1, lease_until = now() + make_interval(secs => $2) \
                 FROM next WHERE u.job_id = next.job_id AND u.idx = next.idx \
                 RETURNING u.job_id, u.idx, u.first_epoch, u.epochs",
                &[&name, &self.cfg.lease.as_secs_f64()],
            )
            .await?;
        let Some(row) = row else {
            tx.rollback().await?;
            return Ok(None);
        };
        let c = Claimed {
            job: row.get(0),
            idx: row.get(1),
            first: row.get::<_, i64>(2) as usize,
            epochs: row.get::<_, i64>(3) as usize,
        };
        tx.execute(
            "UPDATE glint_jobs SET state = 'running', started_ms = $2, attempts = attempts + 1 \
             WHERE id = $1 AND state = 'queued'",
            &[&c.job, &now_ms()],
        )
        .await?;
        tx.commit().await?;
        Ok(Some(c))
    }

    /// The job's kind and request (parsed once per job in this process); `None` when the
    /// job is no longer active (cancelled, failed, removed).
    async fn input(&self, job: &str) -> Result<Option<Arc<JobInput>>, PgError> {
        if let Some(i) = self
            .inputs
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(job)
        {
            return Ok(Some(i.clone()));
        }
        let client = self.cfg.pool.get().await?;
        let row = client
            .query_opt(
                "SELECT kind, request FROM glint_jobs WHERE id = $1 \
                 AND state IN ('queued', 'running') AND request IS NOT NULL",
                &[&job],
            )
            .await?;
        let Some(row) = row else { return Ok(None) };
        let kind: String = row.get(0);
        let body: Vec<u8> = row.get(1);
        let text: Arc<str> = Arc::from(String::from_utf8_lossy(&body).as_ref());
        let scene = if kind == super::KIND_LIGHTCURVE {
            let t = text.clone();
            // Checked with the job limits at submission; here the stored body is only
            // parsed again (this worker's own limits may differ from the API's).
            let parsed = tokio::task::spawn_blocking(move || {
                validate::parse_request(&t)
                    .and_then(|r| Scene::from_request(&r, &Limits::unlimited()))
                    .map(Arc::new)
            })
            .await;
            match parsed {
                Ok(Ok(s)) => Some(s),
                Ok(Err(e)) => {
                    self.fail(job, &format!("the stored request is not valid: {e}"))
                        .await?;
                    return Ok(None);
                }
                Err(e) => return Err(PgError::Corrupt(e.to_string())),
            }
        } else {
            None
        };
        let input = Arc::new(JobInput { text, scene });
        let mut inputs = self.inputs.lock().unwrap_or_else(|e| e.into_inner());
        if inputs.len() >= 8 {
            inputs.clear();
        }
        inputs.insert(job.to_string(), input.clone());
        Ok(Some(input))
    }

    /// Computes a claimed chunk with its lease renewed meanwhile, then writes it (or gives
    /// it back when this process stops, or fails the job when the computation fails).
    async fn run(self: &Arc<Self>, name: &str, c: Claimed) {
        let input = match self.input(&c.job).await {
            Ok(Some(i)) => i,
            Ok(None) => return,
            Err(e) => {
                tracing::warn!(job = c.job, "reading the job: {e}");
                let _ = self.release(name, &c).await;
                return;
            }
        };
        let progress = Arc::new(Progress::new());
        self.lock_running()
            .insert((c.job.clone(), c.idx), progress.clone());
        let renewal = tokio::spawn(self.clone().renew(
            name.to_string(),
            c.clone(),
            progress.clone(),
        ));
        let me = self.clone();
        let chunk = c.clone();
        let p = progress.clone();
        let began = std::time::Instant::now();
        let outcome = tokio::task::spawn_blocking(move || me.compute(&input, &chunk, &p))
            .await
            .unwrap_or_else(|e| {
                tracing::error!(
                    job = c.job,
                    chunk = c.idx,
                    "the chunk's computation panicked: {e}"
                );
                Err(format!(
                    "internal error: the computation panicked; the worker's log has the \
                     details under job {}",
                    c.job
                ))
            });
        renewal.abort();
        self.lock_running().remove(&(c.job.clone(), c.idx));
        let computed = began.elapsed();
        match outcome {
            Ok(Some(done)) => {
                let began = std::time::Instant::now();
                if self.write(name, &c, done).await {
                    let t = &self.timings;
                    t.write_ns
                        .fetch_add(began.elapsed().as_nanos() as u64, Ordering::Relaxed);
                    t.compute_ns
                        .fetch_add(computed.as_nanos() as u64, Ordering::Relaxed);
                    t.written.fetch_add(1, Ordering::Relaxed);
                }
            }
            Ok(None) => {
                if self.stopping() {
                    let _ = self.release(name, &c).await;
                }
                // else: the job was cancelled, or the lease went to another worker
            }
            Err(msg) => {
                if let Err(e) = self.fail(&c.job, &msg).await {
                    tracing::warn!(job = c.job, "recording the failure: {e}");
                }
            }
        }
    }

    /// Renews the chunk's lease every third of it; stops the computation when the lease
    /// is no longer this worker's or the job is no longer active.
    async fn renew(self: Arc<Self>, name: String, c: Claimed, progress: Arc<Progress>) {
        loop {
            tokio::time::sleep(self.cfg.lease / 3).await;
            let renewed = async {
                let client = self.cfg.pool.get().await?;
                let row = client
                    .query_opt(
                        "UPDATE glint_chunks c SET lease_until = now() + make_interval(secs => $4) \
                         FROM glint_jobs j WHERE c.job_id = $1 AND c.idx = $2 AND c.worker = $3 \
                         AND c.state = 'running' AND j.id = c.job_id \
                         AND j.state IN ('queued', 'running') RETURNING 1",
                        &[&c.job, &c.idx, &name, &self.cfg.lease.as_secs_f64()],
                    )
                    .await?;
                Ok::<_, PgError>(row.is_some())
            };
            match renewed.await {
                Ok(true) => {}
                Ok(false) => {
                    progress.cancel();
                    return;
                }
                // the database is away: compute on; the write decides
                Err(e) => tracing::warn!(job = c.job, chunk = c.idx, "renewing the lease: {e}"),
            }
        }
    }

    /// The chunk's result (its response JSON, or a fit's JSON), its epochs and a fit's
    /// light curves; `None` when stopped.
    fn compute(
        &self,
        input: &JobInput,
        c: &Claimed,
        progress: &Progress,
    ) -> Result<Option<Done>, String> {
        if let Some(scene) = &input.scene {
            let sub = chunks::sub_scene(scene, c.first, c.epochs);
            return match self
                .cfg
                .threads
                .install(|| (self.cfg.engine)(&sub, progress))
            {
                Ok(resp) => Ok(Some(Done {
                    data: serde_json::to_vec(&resp).map_err(|e| e.to_string())?,
                    epochs: resp.epochs.len(),
                    evaluations: None,
                })),
                Err(Cancelled) => Ok(None),
            };
        }
        let evaluations = AtomicUsize::new(0);
        let limits = unbounded_limits();
        let run = self.cfg.threads.install(|| {
            crate::service::jobs::fit::run(
                &input.text,
                &limits,
                self.cfg.engine,
                progress,
                &evaluations,
            )
        })?;
        Ok(run.map(|(data, epochs)| Done {
            data,
            epochs,
            evaluations: Some(evaluations.load(Ordering::Relaxed)),
        }))
    }

    /// Writes a computed chunk, retrying with backoff while the database is away (for up
    /// to ten leases: by then another worker has long taken the chunk over). `true` when
    /// this write stored the chunk.
    async fn write(&self, name: &str, c: &Claimed, done: Done) -> bool {
        let mut backoff = FIRST_BACKOFF;
        let give_up = tokio::time::Instant::now() + self.cfg.lease * 10;
        loop {
            match self.write_once(name, c, &done).await {
                Ok(stored) => {
                    if stored {
                        if let Some(m) = &self.cfg.metrics {
                            m.add_epochs("job", done.epochs as u64);
                        }
                    }
                    return stored;
                }
                Err(e) if tokio::time::Instant::now() < give_up => {
                    tracing::warn!(
                        job = c.job,
                        chunk = c.idx,
                        "writing the chunk: {e}; again in {backoff:?}"
                    );
                    tokio::time::sleep(backoff).await;
                    backoff = (backoff * 2).min(MAX_BACKOFF);
                }
                Err(e) => {
                    tracing::warn!(
                        job = c.job,
                        chunk = c.idx,
                        "writing the chunk: {e}; left to the queue"
                    );
                    return false;
                }
            }
        }
    }

    /// One transaction: the job row locked (a cancel commits before or after, never
    /// between); if the job is still active and the chunk not done, the chunk marked done
    /// with its result row; the job done when no chunk is left. `true` when stored.
    async fn write_once(&self, name: &str, c: &Claimed, done: &Done) -> Result<bool, PgError> {
        let mut client = self.cfg.pool.get().await?;
        let tx = client.transaction().await?;
        let state: Option<String> = tx
            .query_opt(
                "SELECT state FROM glint_jobs WHERE id = $1 FOR UPDATE",
                &[&c.job],
            )
            .await?
            .map(|r| r.get(0));
        if !matches!(state.as_deref(), Some("queued" | "running")) {
            tx.rollback().await?;
            return Ok(false);
        }
        let marked = tx
            .execute(
                "UPDATE glint_chunks SET state = 'done', done_by = $3, lease_until = NULL, \
                 epochs_computed = $4 WHERE job_id = $1 AND idx = $2 AND state <> 'done'",
                &[&c.job, &c.idx, &name, &(done.epochs as i64)],
            )
            .await?;
        if marked == 0 {
            tx.rollback().await?;
            return Ok(false);
        }
        tx.execute(
            "INSERT INTO glint_results (job_id, idx, data) VALUES ($1, $2, $3) \
             ON CONFLICT (job_id, idx) DO NOTHING",
            &[&c.job, &c.idx, &done.data],
        )
        .await?;
        tx.execute(
            "UPDATE glint_jobs SET result_bytes = result_bytes + $2, \
             eval_done = coalesce($3, eval_done) WHERE id = $1",
            &[
                &c.job,
                &(done.data.len() as i64),
                &done.evaluations.map(|e| e as i64),
            ],
        )
        .await?;
        let open: i64 = tx
            .query_one(
                "SELECT count(*) FROM glint_chunks WHERE job_id = $1 AND state <> 'done'",
                &[&c.job],
            )
            .await?
            .get(0);
        if open == 0 {
            tx.execute(
                "UPDATE glint_jobs SET state = 'done', finished_ms = $2, request = NULL \
                 WHERE id = $1",
                &[&c.job, &now_ms()],
            )
            .await?;
        }
        tx.commit().await?;
        Ok(true)
    }

    /// Gives a chunk this worker holds back to the queue, and wakes the others.
    async fn release(&self, name: &str, c: &Claimed) -> Result<(), PgError> {
        let client = self.cfg.pool.get().await?;
        client
            .execute(
                "UPDATE glint_chunks SET state = 'queued', worker = NULL, lease_until = NULL \
                 WHERE job_id = $1 AND idx = $2 AND worker = $3 AND state = 'running'",
                &[&c.job, &c.idx, &name],
            )
            .await?;
        client
            .execute(&format!("NOTIFY {CHUNKS_CHANNEL}"), &[])
            .await?;
        Ok(())
    }

    /// Marks an active job failed with `msg`.
    async fn fail(&self, job: &str, msg: &str) -> Result<(), PgError> {
        let client = self.cfg.pool.get().await?;
        client
            .execute(
                "UPDATE glint_jobs SET state = 'failed', error = $2, finished_ms = $3, \
                 request = NULL WHERE id = $1 AND state IN ('queued', 'running')",
                &[&job, &msg, &now_ms()],
            )
            .await?;
        Ok(())
    }
}

/// A computed chunk.
struct Done {
    data: Vec<u8>,
    epochs: usize,
    evaluations: Option<usize>,
}

/// Limits that let every stored fit run: it was checked with the API's limits when it
/// was accepted, and this worker's may differ.
fn unbounded_limits() -> ServiceLimits {
    ServiceLimits {
        max_triangles: usize::MAX,
        max_job_epochs: usize::MAX,
        max_sync_triangle_epochs: u64::MAX / 1000,
        max_sync_pixel_samples: u64::MAX / 100,
        ..ServiceLimits::default()
    }
}
