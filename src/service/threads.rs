//! The engine's threads: one rayon pool for light-curve requests, one for jobs, both below
//! the async runtime's priority.
//!
//! Separate pools because rayon workers finish their own split work before taking new
//! work: in one shared pool, a light curve arriving during a long job waits for the job's
//! epochs. With two pools the kernel shares the cores between them, by priority:
//! async runtime (nice 0: health checks, small answers) ≫ light curves (nice 10) ≫ jobs
//! (nice 19). Nothing is lost when only one kind runs: it gets all the cores.

use super::errors::ApiError;
use std::sync::Arc;

/// Nice level of the light-curve pool's threads.
pub const SYNC_NICE: i32 = 10;
/// Nice level of the job pool's threads.
pub const JOB_NICE: i32 = 19;

/// The two pools.
#[derive(Clone)]
pub struct Pools {
    pub sync: Arc<rayon::ThreadPool>,
    pub jobs: Arc<rayon::ThreadPool>,
}

impl Pools {
    /// Pools of `threads` threads each (usually the number of cores).
    pub fn new(threads: usize) -> Result<Pools, rayon::ThreadPoolBuildError> {
        let pool = |name: &'static str, nice: i32| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads.max(1))
                .thread_name(move |i| format!("glint-{name}-{i}"))
                .start_handler(move |_| set_current_thread_nice(nice))
                .build()
                .map(Arc::new)
        };
        Ok(Pools {
            sync: pool("sync", SYNC_NICE)?,
            jobs: pool("job", JOB_NICE)?,
        })
    }
}

/// Lowers the calling thread's scheduling priority (Linux; elsewhere a no-op). Failure
/// is harmless: the thread keeps the default priority.
pub fn set_current_thread_nice(nice: i32) {
    #[cfg(target_os = "linux")]
    {
        extern "C" {
            fn setpriority(
                which: std::ffi::c_int,
                who: std::ffi::c_uint,
                prio: std::ffi::c_int,
            ) -> std::ffi::c_int;
        }
        // PRIO_PROCESS (0) with who = 0 is the calling thread on Linux.
        // SAFETY: a libc call with plain integer arguments and no memory access.
        unsafe {
            setpriority(0, 0, nice);
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = nice;
}

/// Runs `f` on tokio's blocking threads, so that parsing, computing or disk work never
/// holds up the async runtime. A task that does not return — `f` panicked, or the runtime
/// is shutting down — is answered by [`ApiError::from_join`], `what` naming the work
/// (e.g. "reading the result").
pub async fn run_blocking<T, F>(what: &str, f: F) -> Result<T, ApiError>
where
    F: FnOnce() -> T + Send + 'static,
    T: Send + 'static,
{
    tokio::task::spawn_blocking(f)
        .await
        .map_err(|e| ApiError::from_join(what, e))
}
