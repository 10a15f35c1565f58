//! Batch jobs: accepted to disk, run one computation slot at a time, cancellable, and
//! picked up again after a restart.
//!
//! ```text
//! POST ─validate─▶ store.insert (committed) ─▶ 202 ─▶ queue ─▶ dispatcher ─▶ running
//!                                                      ▲                     │ simulate_with
//! restart: records still queued/running ───────────────┘   done / failed / cancelled ─▶ store
//! ```
//! The in-memory table is the live view (progress counters); the store is the truth after
//! a crash. Every store write takes the current in-memory record under one lock, so the
//! last write always reflects the latest state, whatever order the tasks finish in.

use super::errors::ApiError;
use super::limits::{ServiceLimits, Slots};
use super::metrics::Metrics;
pub use super::record::{JobRecord, JobState};
use super::store::{Store, StoreError};
use super::threads::run_blocking;
use crate::integrate::{Cancelled, Progress};
use crate::scene::{validate, Scene};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, SystemTime, UNIX_EPOCH};
use tokio::sync::{mpsc, Notify, Semaphore};
use utoipa::ToSchema;

/// A job's status as `GET /v1/jobs/{id}` reports it.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema, PartialEq)]
pub struct JobStatus {
    /// Job id (UUID).
    pub id: String,
    pub state: JobState,
    /// Epochs computed as a percentage of the total, 0–100.
    pub percent: f64,
    /// Epochs computed so far.
    pub epochs_done: usize,
    /// Epochs in the request.
    pub epochs_total: usize,
    /// When the job was accepted (RFC 3339, UTC).
    pub created_at: String,
    /// When the current run started (RFC 3339, UTC).
    pub started_at: Option<String>,
    /// When the job reached its final state (RFC 3339, UTC).
    pub finished_at: Option<String>,
    /// When a finished job and its result will be removed (RFC 3339, UTC).
    pub expires_at: Option<String>,
    /// Why the job failed.
    pub error: Option<String>,
    /// Times the job was started (above 1 when a restart interrupted it).
    pub attempts: u32,
    /// Where to fetch the result once `state` is `done`.
    pub result_url: Option<String>,
}

/// What `DELETE /v1/jobs/{id}` did.
#[derive(Debug)]
pub enum Deleted {
    /// The job was queued or running and is now cancelled.
    Cancelled(JobStatus),
    /// The job had finished; it and its result were removed.
    Removed,
}

struct Entry {
    rec: JobRecord,
    progress: Arc<Progress>,
}

/// The job manager (one per service).
pub struct Jobs {
    store: Arc<Store>,
    slots: Arc<Slots>,
    metrics: Arc<Metrics>,
    /// The job pool (see [`super::threads`]).
    pool: Arc<rayon::ThreadPool>,
    limits: ServiceLimits,
    ttl: Duration,
    engine: super::Engine,
    table: Mutex<HashMap<String, Entry>>,
    /// Serialises store writes so each writes the latest in-memory record.
    write_lock: Mutex<()>,
    queue: mpsc::UnboundedSender<String>,
    job_slots: Arc<Semaphore>,
    shutting_down: AtomicBool,
    running: AtomicUsize,
    idle: Notify,
}

pub fn now_ms() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_millis() as i64)
}

/// Unix milliseconds as RFC 3339 UTC text.
pub fn rfc3339(ms: i64) -> String {
    chrono::DateTime::from_timestamp_millis(ms)
        .map(|d| d.to_rfc3339_opts(chrono::SecondsFormat::Millis, true))
        .unwrap_or_default()
}

impl Jobs {
    /// Loads the stored jobs, queues the unfinished ones again (oldest first), and starts
    /// the dispatcher and the expiry sweeper. Must run inside the tokio runtime.
    pub fn start(
        store: Arc<Store>,
        slots: Arc<Slots>,
        metrics: Arc<Metrics>,
        pool: Arc<rayon::ThreadPool>,
        limits: ServiceLimits,
        ttl: Duration,
        engine: super::Engine,
    ) -> Result<Arc<Jobs>, StoreError> {
        let (tx, rx) = mpsc::unbounded_channel();
        let mut records = store.load_all()?;
        records.sort_by_key(|r| r.created_ms);
        let mut table = HashMap::new();
        let mut requeue = Vec::new();
        for mut rec in records {
            if !rec.state.is_final() {
                // Interrupted (crash, kill -9, shutdown): run it again from the start.
                rec.state = JobState::Queued;
                rec.epochs_done = 0;
                requeue.push(rec.id.clone());
            }
            table.insert(
                rec.id.clone(),
                Entry {
                    rec,
                    progress: Arc::new(Progress::new()),
                },
            );
        }
        let jobs = Arc::new(Jobs {
            store,
            slots,
            metrics,
            pool,
            job_slots: Arc::new(Semaphore::new(limits.max_running_jobs.max(1))),
            limits,
            ttl,
            engine,
            table: Mutex::new(table),
            write_lock: Mutex::new(()),
            queue: tx,
            shutting_down: AtomicBool::new(false),
            running: AtomicUsize::new(0),
            idle: Notify::new(),
        });
        for id in requeue {
            let _ = jobs.queue.send(id);
        }
        jobs.sweep();
        tokio::spawn(jobs.clone().dispatch(rx));
        tokio::spawn(jobs.clone().sweeper());
        Ok(jobs)
    }

    fn table(&self) -> MutexGuard<'_, HashMap<String, Entry>> {
        // A poisoned lock only means a panic elsewhere; the map itself stays consistent.
        self.table.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Validates a request body with the job limits and stores the new job; returns once
    /// the store transaction is committed. With an idempotency key already used for the
    /// same body, returns that job instead (`true`: replayed); with a different body, 422.
    pub async fn submit(
        self: &Arc<Self>,
        body: axum::body::Bytes,
        key: Option<String>,
    ) -> Result<(JobStatus, bool), ApiError> {
        if self.shutting_down.load(Ordering::SeqCst) {
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
        if let Some(found) = self.replay(idempotency.as_ref())? {
            return Ok((found, true));
        }
        self.room_for_a_job()?; // before the parse: a full queue costs the client nothing
        let me = self.clone();
        let outcome = run_blocking(
            "validating the job",
            move || -> Result<(JobStatus, bool), ApiError> {
                let text = std::str::from_utf8(&body)
                    .map_err(|_| ApiError::bad_request("request body is not UTF-8"))?;
                let request = validate::parse_request(text)?;
                let scene = Scene::from_request(&request, &me.limits.job_limits())?;
                let rec = JobRecord {
                    id: uuid::Uuid::new_v4().to_string(),
                    state: JobState::Queued,
                    epochs_total: scene.epochs.len(),
                    epochs_done: 0,
                    created_ms: now_ms(),
                    started_ms: None,
                    finished_ms: None,
                    error: None,
                    attempts: 0,
                    idempotency,
                };
                let id = rec.id.clone();
                // Counted and entered under one lock, so concurrent submissions cannot
                // overshoot the limit (nor two with one key both make a job); taken out again
                // if the store refuses it.
                let status = {
                    let mut t = me.table();
                    if let Some(found) = me.replay_in(&t, rec.idempotency.as_ref())? {
                        return Ok((found, true));
                    }
                    me.room_in(&t)?;
                    let entry = Entry {
                        rec: rec.clone(),
                        progress: Arc::new(Progress::new()),
                    };
                    let s = me.status_of(&entry);
                    t.insert(id.clone(), entry);
                    s
                };
                if let Err(e) = me.store.insert(&rec, &body) {
                    me.table().remove(&id);
                    return Err(ApiError::from(e));
                }
                Ok((status, false))
            },
        )
        .await??;
        let (status, replayed) = outcome;
        if replayed {
            return Ok((status, true));
        }
        let id = status.id.clone();
        let _ = self.queue.send(id);
        Ok((status, false))
    }

    /// The job submitted earlier with this idempotency key, if any; 422 when the key
    /// came with another body.
    fn replay(&self, key: Option<&(String, String)>) -> Result<Option<JobStatus>, ApiError> {
        self.replay_in(&self.table(), key)
    }

    fn replay_in(
        &self,
        t: &HashMap<String, Entry>,
        key: Option<&(String, String)>,
    ) -> Result<Option<JobStatus>, ApiError> {
        let Some((key, digest)) = key else {
            return Ok(None);
        };
        let found = t
            .values()
            .find(|e| e.rec.idempotency.as_ref().is_some_and(|(k, _)| k == key));
        match found {
            None => Ok(None),
            Some(e) if e.rec.idempotency.as_ref().is_some_and(|(_, d)| d == digest) => {
                Ok(Some(self.status_of(e)))
            }
            Some(e) => Err(ApiError::new(
                axum::http::StatusCode::UNPROCESSABLE_ENTITY,
                format!(
                    "this Idempotency-Key was used for job {} with a different request body",
                    e.rec.id
                ),
            )
            .with_field("Idempotency-Key")),
        }
    }

    /// Refuses a new job (429) while `max_queued_jobs` jobs are unfinished.
    fn room_for_a_job(&self) -> Result<(), ApiError> {
        self.room_in(&self.table())
    }

    fn room_in(&self, t: &HashMap<String, Entry>) -> Result<(), ApiError> {
        let stored = self.store.result_bytes();
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
        let unfinished = t.values().filter(|e| !e.rec.state.is_final()).count();
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

    fn status_of(&self, e: &Entry) -> JobStatus {
        let r = &e.rec;
        let done = match r.state {
            JobState::Running => e.progress.done(),
            JobState::Done => r.epochs_total,
            _ => r.epochs_done,
        };
        let percent = if r.epochs_total == 0 {
            0.0
        } else {
            100.0 * done as f64 / r.epochs_total as f64
        };
        JobStatus {
            id: r.id.clone(),
            state: r.state,
            percent,
            epochs_done: done,
            epochs_total: r.epochs_total,
            created_at: rfc3339(r.created_ms),
            started_at: r.started_ms.map(rfc3339),
            finished_at: r.finished_ms.map(rfc3339),
            expires_at: r
                .finished_ms
                .map(|f| rfc3339(f.saturating_add(self.ttl.as_millis() as i64))),
            error: r.error.clone(),
            attempts: r.attempts,
            result_url: (r.state == JobState::Done).then(|| format!("/v1/jobs/{}/result", r.id)),
        }
    }

    /// The status of one job.
    pub fn status(&self, id: &str) -> Option<JobStatus> {
        self.table().get(id).map(|e| self.status_of(e))
    }

    /// The most recent jobs, newest first.
    pub fn list(&self, limit: usize, state: Option<JobState>) -> Vec<JobStatus> {
        let t = self.table();
        let mut v: Vec<&Entry> = t
            .values()
            .filter(|e| state.is_none_or(|s| e.rec.state == s))
            .collect();
        v.sort_by(|a, b| {
            b.rec
                .created_ms
                .cmp(&a.rec.created_ms)
                .then_with(|| a.rec.id.cmp(&b.rec.id))
        });
        v.into_iter()
            .take(limit)
            .map(|e| self.status_of(e))
            .collect()
    }

    /// Number of jobs in each state (for `/metrics`).
    pub fn counts(&self) -> HashMap<JobState, usize> {
        let mut m: HashMap<JobState, usize> = JobState::ALL.iter().map(|&s| (s, 0)).collect();
        for e in self.table().values() {
            *m.entry(e.rec.state).or_default() += 1;
        }
        m
    }

    /// The stored response JSON of a finished job; `Err` says why there is none.
    pub async fn result(&self, id: &str) -> Result<Vec<u8>, ApiError> {
        let state = self
            .table()
            .get(id)
            .map(|e| e.rec.state)
            .ok_or_else(|| no_such_job(id))?;
        if state != JobState::Done {
            return Err(ApiError::conflict(format!(
                "job is {}, there is no result{}",
                state.name(),
                if state.is_final() { "" } else { " yet" }
            )));
        }
        let store = self.store.clone();
        let key = id.to_string();
        run_blocking("reading the result", move || store.result(&key))
            .await?
            .map_err(ApiError::from)?
            // Removed by expiry between the two looks.
            .ok_or_else(|| no_such_job(id))
    }

    /// Cancels a queued or running job, or removes a finished one with its result.
    pub async fn delete(self: &Arc<Self>, id: &str) -> Result<Deleted, ApiError> {
        // The status is taken as this call cancels it: a concurrent DELETE may remove the
        // cancelled job before this one answers, and this answer must still say what it did.
        let cancelled = {
            let mut t = self.table();
            let e = t.get_mut(id).ok_or_else(|| no_such_job(id))?;
            match e.rec.state {
                JobState::Queued | JobState::Running => {
                    e.progress.cancel();
                    if e.rec.state == JobState::Running {
                        e.rec.epochs_done = e.progress.done();
                    }
                    e.rec.state = JobState::Cancelled;
                    e.rec.finished_ms = Some(now_ms());
                    Some(self.status_of(e))
                }
                _ => None,
            }
        };
        let me = self.clone();
        let key = id.to_string();
        let was_cancelled = cancelled.is_some();
        run_blocking("removing the job", move || {
            if was_cancelled {
                me.persist(&key, None)
            } else {
                me.remove(&key)
            }
        })
        .await?
        .map_err(ApiError::from)?;
        Ok(match cancelled {
            Some(s) => Deleted::Cancelled(s),
            None => Deleted::Removed,
        })
    }

    /// Writes the job's current in-memory record (and `result`, if any) to the store.
    fn persist(&self, id: &str, result: Option<&[u8]>) -> Result<(), StoreError> {
        let _g = self.write_lock.lock().unwrap_or_else(|e| e.into_inner());
        let rec = self.table().get(id).map(|e| e.rec.clone());
        match rec {
            Some(rec) => {
                let result = result.filter(|_| rec.state == JobState::Done);
                self.store.update(&rec, result)
            }
            None => Ok(()),
        }
    }

    fn remove(&self, id: &str) -> Result<(), StoreError> {
        let _g = self.write_lock.lock().unwrap_or_else(|e| e.into_inner());
        self.table().remove(id);
        self.store.remove(id)
    }

    async fn dispatch(self: Arc<Self>, mut rx: mpsc::UnboundedReceiver<String>) {
        while let Some(id) = rx.recv().await {
            let Ok(job_permit) = self.job_slots.clone().acquire_owned().await else {
                return;
            };
            if self.shutting_down.load(Ordering::SeqCst) {
                return;
            }
            let queued = self
                .table()
                .get(&id)
                .is_some_and(|e| e.rec.state == JobState::Queued);
            if !queued {
                continue;
            }
            let slot = self.slots.acquire_for_job().await;
            let me = self.clone();
            self.running.fetch_add(1, Ordering::SeqCst);
            tokio::spawn(async move {
                me.run(&id, slot).await;
                drop(job_permit);
                if me.running.fetch_sub(1, Ordering::SeqCst) == 1 {
                    me.idle.notify_waiters();
                }
            });
        }
    }

    async fn run(self: &Arc<Self>, id: &str, slot: tokio::sync::OwnedSemaphorePermit) {
        let progress = {
            let mut t = self.table();
            let Some(e) = t.get_mut(id) else { return };
            if e.rec.state != JobState::Queued || self.shutting_down.load(Ordering::SeqCst) {
                return;
            }
            e.rec.state = JobState::Running;
            e.rec.started_ms = Some(now_ms());
            e.rec.attempts += 1;
            e.progress = Arc::new(Progress::new());
            e.progress.clone()
        };
        let me = self.clone();
        let key = id.to_string();
        let outcome = tokio::task::spawn_blocking(move || {
            let _slot = slot; // held until the computation has really stopped
            me.persist(&key, None).map_err(|e| e.to_string())?;
            let body = me
                .store
                .request(&key)
                .map_err(|e| e.to_string())?
                .ok_or("the stored request is missing")?;
            let text = std::str::from_utf8(&body).map_err(|_| "request body is not UTF-8")?;
            let scene = validate::parse_request(text)
                .and_then(|r| Scene::from_request(&r, &me.limits.job_limits()))
                .map_err(|e| e.to_string())?;
            match me.pool.install(|| (me.engine)(&scene, &progress)) {
                Ok(resp) => {
                    let json = serde_json::to_vec(&resp).map_err(|e| e.to_string())?;
                    Ok(Some((json, resp.epochs.len())))
                }
                Err(Cancelled) => Ok(None),
            }
        })
        .await
        .unwrap_or_else(|e| {
            // The panic's text and backtrace go to the log, not to the job's status.
            let what = if e.is_panic() {
                "panicked"
            } else {
                "was stopped"
            };
            tracing::error!(job = id, "the job's computation {what}");
            Err(format!(
                "internal error: the computation {what}; the service log has the details \
                 under job {id}"
            ))
        });

        let outcome = match outcome {
            Ok(Some(done)) => Ok(done),
            // Stopped by shutdown: stays `running` on disk, so it runs again on restart.
            Ok(None) => return,
            Err(msg) => Err(msg),
        };
        let me = self.clone();
        let key = id.to_string();
        let written = tokio::task::spawn_blocking(move || me.finish(&key, outcome)).await;
        let failure = match written {
            Ok(Ok(())) => None,
            Ok(Err(e)) => Some(e.to_string()),
            Err(e) => Some(e.to_string()),
        };
        if let Some(e) = failure {
            // The outcome could not be stored: say so rather than serve nothing (on disk
            // the job is still `running`, so it runs again after a restart).
            if let Some(e2) = self.table().get_mut(id) {
                if e2.rec.state == JobState::Running {
                    e2.rec.state = JobState::Failed;
                    e2.rec.error = Some(format!("could not store the outcome: {e}"));
                }
            }
        }
    }

    /// Stores a run's outcome, then shows it: a job is `done` in the table only once its
    /// result is committed, so a client never sees `done` without a result to fetch.
    fn finish(
        &self,
        id: &str,
        outcome: Result<(Vec<u8>, usize), String>,
    ) -> Result<(), StoreError> {
        let _g = self.write_lock.lock().unwrap_or_else(|e| e.into_inner());
        let mut rec = match self.table().get(id) {
            // Not running any more: cancelled (and persisted) meanwhile.
            Some(e) if e.rec.state == JobState::Running => e.rec.clone(),
            _ => return Ok(()),
        };
        rec.finished_ms = Some(now_ms());
        let result = match outcome {
            Ok((json, n)) => {
                rec.state = JobState::Done;
                rec.epochs_done = n;
                Some(json)
            }
            Err(msg) => {
                rec.state = JobState::Failed;
                rec.error = Some(msg);
                rec.epochs_done = self.table().get(id).map_or(0, |e| e.progress.done());
                None
            }
        };
        self.store.update(&rec, result.as_deref())?;
        if rec.state == JobState::Done {
            self.metrics.add_epochs("job", rec.epochs_done as u64);
        }
        if let Some(e) = self.table().get_mut(id) {
            if e.rec.state == JobState::Running {
                e.rec = rec;
            }
        }
        Ok(())
    }

    /// Removes finished jobs older than the time to live.
    fn sweep(&self) {
        let cutoff = now_ms().saturating_sub(self.ttl.as_millis() as i64);
        let expired: Vec<String> = self
            .table()
            .values()
            .filter(|e| e.rec.state.is_final() && e.rec.finished_ms.is_some_and(|f| f <= cutoff))
            .map(|e| e.rec.id.clone())
            .collect();
        for id in expired {
            let _ = self.remove(&id);
        }
    }

    async fn sweeper(self: Arc<Self>) {
        let every = (self.ttl / 4).clamp(Duration::from_secs(1), Duration::from_secs(60));
        loop {
            tokio::time::sleep(every).await;
            if self.shutting_down.load(Ordering::SeqCst) {
                return;
            }
            let me = self.clone();
            let _ = tokio::task::spawn_blocking(move || me.sweep()).await;
        }
    }

    /// Stops taking jobs, asks the running ones to stop at their next epoch and waits
    /// (up to `grace`) until they have. They stay `running` on disk and run again on the
    /// next start: epochs are independent, so a rerun gives the same result.
    pub async fn shutdown(&self, grace: Duration) {
        self.shutting_down.store(true, Ordering::SeqCst);
        for e in self.table().values() {
            if e.rec.state == JobState::Running {
                e.progress.cancel();
            }
        }
        let wait = async {
            loop {
                let notified = self.idle.notified();
                if self.running.load(Ordering::SeqCst) == 0 {
                    return;
                }
                notified.await;
            }
        };
        let _ = tokio::time::timeout(grace, wait).await;
    }

    pub fn is_shutting_down(&self) -> bool {
        self.shutting_down.load(Ordering::SeqCst)
    }
}

pub fn no_such_job(id: &str) -> ApiError {
    ApiError::not_found(format!("no job with id `{id}` (finished jobs expire)")).with_field("id")
}
