//! The workers of the shared queue, in `glint worker` and `glint serve`: each claims a
//! chunk (`FOR UPDATE SKIP LOCKED`, under a lease), computes it while a task renews the
//! lease, and writes its result in the transaction that marks it done. A listener on its
//! own connection (`LISTEN`) wakes idle workers when chunks are queued and stops the
//! chunks of a cancelled job. Every database step is retried with backoff, so workers
//! ride out a restart of the database.
//!
//! | concept | file |
//! |---|---|
//! | the workers of a process: started, stopped; a worker's loop | `mod.rs` |
//! | the listener: wake-ups for new chunks, cancels | `listen.rs` |
//! | a chunk's lease: claimed, renewed, released | `lease.rs` |
//! | a chunk computed: the job's input parsed once, the engine or the fit run | `compute.rs` |
//! | a computed chunk written in the transaction that marks it done; a job failed | `write.rs` |
//! | the time the queue's steps take against the computation's | `timings.rs` |

mod compute;
mod lease;
mod listen;
mod timings;
mod write;

pub use timings::Timings;

use crate::integrate::Progress;
use compute::JobInput;
use deadpool_postgres::Pool;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tokio::sync::Notify;

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
}
