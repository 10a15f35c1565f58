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
//!
//! | concept | file |
//! |---|---|
//! | the manager, its table and its store writes; restart | `mod.rs` |
//! | submission: idempotency keys, room for a job, the new record | `submit.rs` |
//! | the dispatcher and one job's run, its outcome stored | `worker.rs` |
//! | what a client sees: status, lists, counts, results | `status.rs` |
//! | cancellation (`DELETE`) and shutdown | `cancel.rs` |
//! | expiry of finished jobs | `expiry.rs` |
//! | a light-curve fit as a job: its body checked, its run, its progress | `fit.rs` |

mod cancel;
mod expiry;
pub(crate) mod fit;
mod status;
mod submit;
#[cfg(test)]
mod test_fixtures;
mod worker;

pub use super::record::{Evaluations, JobKind, JobRecord, JobState};
pub use cancel::Deleted;
pub(crate) use status::status_from;
pub use status::{no_such_job, rfc3339, JobStatus};

use super::limits::{ServiceLimits, Slots};
use super::metrics::Metrics;
use super::store::{Store, StoreError};
use crate::integrate::Progress;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, SystemTime, UNIX_EPOCH};
use tokio::sync::{mpsc, Notify, Semaphore};

/// One job in the live table: its record and the progress of its current run (a fit's
/// also counts its light curves).
struct Entry {
    rec: JobRecord,
    progress: Arc<Progress>,
    evaluations: Arc<AtomicUsize>,
}

impl Entry {
    /// A new entry for `rec`, its run not started.
    fn new(rec: JobRecord) -> Entry {
        Entry {
            rec,
            progress: Arc::new(Progress::new()),
            evaluations: Default::default(),
        }
    }
}

/// The job manager (one per service).
pub struct Jobs {
    store: Arc<Store>,
    slots: Arc<Slots>,
    metrics: Arc<Metrics>,
    /// The job pool (see [`crate::service::threads`]).
    pool: Arc<rayon::ThreadPool>,
    limits: ServiceLimits,
    ttl: Duration,
    engine: crate::service::Engine,
    table: Mutex<HashMap<String, Entry>>,
    /// Serialises store writes so each writes the latest in-memory record.
    write_lock: Mutex<()>,
    queue: mpsc::UnboundedSender<String>,
    job_slots: Arc<Semaphore>,
    shutting_down: AtomicBool,
    running: AtomicUsize,
    idle: Notify,
}

/// Now, in Unix milliseconds (0 if the clock is before 1970).
pub fn now_ms() -> i64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_millis() as i64)
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
        engine: crate::service::Engine,
    ) -> Result<Arc<Jobs>, StoreError> {
        let (tx, rx) = mpsc::unbounded_channel();
        let mut records = store.load_all()?;
        records.sort_by_key(|r| r.created_ms);
        let mut table = HashMap::new();
        let mut requeue = Vec::new();
        for mut rec in records {
            if requeue_interrupted(&mut rec) {
                requeue.push(rec.id.clone());
            }
            table.insert(rec.id.clone(), Entry::new(rec));
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

    /// The live table, locked.
    fn table(&self) -> MutexGuard<'_, HashMap<String, Entry>> {
        // A poisoned lock only means a panic elsewhere; the map itself stays consistent.
        self.table.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Writes the job's current in-memory record to the store (a result is written with
    /// its record, by the worker's `finish`).
    fn persist(&self, id: &str) -> Result<(), StoreError> {
        let _g = self.write_lock.lock().unwrap_or_else(|e| e.into_inner());
        let rec = self.table().get(id).map(|e| e.rec.clone());
        match rec {
            Some(rec) => self.store.update(&rec, None),
            None => Ok(()),
        }
    }

    /// Removes a job and its result from the table and the store.
    fn remove(&self, id: &str) -> Result<(), StoreError> {
        let _g = self.write_lock.lock().unwrap_or_else(|e| e.into_inner());
        self.table().remove(id);
        self.store.remove(id)
    }

    /// Whether [`Self::shutdown`] has begun (new jobs are refused, `/readyz` says so).
    pub fn is_shutting_down(&self) -> bool {
        self.shutting_down.load(Ordering::SeqCst)
    }
}

/// A record found unfinished at start (the service stopped while it was queued or
/// running): queued again to run from the start. `true` if it was.
fn requeue_interrupted(rec: &mut JobRecord) -> bool {
    if rec.state.is_final() {
        return false;
    }
    // Interrupted (crash, kill -9, shutdown): run it again from the start.
    rec.state = JobState::Queued;
    rec.epochs_done = 0;
    if let Some(ev) = rec.evaluations.as_mut() {
        ev.done = 0;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::test_fixtures::record;
    use super::*;

    #[test]
    fn an_interrupted_job_is_queued_again_from_the_start() {
        for state in [JobState::Queued, JobState::Running] {
            let mut rec = record(state);
            rec.epochs_done = 7;
            assert!(requeue_interrupted(&mut rec));
            assert_eq!((rec.state, rec.epochs_done), (JobState::Queued, 0));
            // the run count and times stay: a restart is one more attempt of the same job
            assert_eq!(rec.attempts, record(state).attempts);
        }
    }

    #[test]
    fn a_finished_job_is_left_as_it_is() {
        for state in [JobState::Done, JobState::Failed, JobState::Cancelled] {
            let mut rec = record(state);
            rec.epochs_done = 7;
            assert!(!requeue_interrupted(&mut rec));
            assert_eq!((rec.state, rec.epochs_done), (state, 7));
        }
    }
}
