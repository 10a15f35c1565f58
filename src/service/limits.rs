//! The service's limits and the computation slots that enforce the concurrency limit.

use super::errors::ApiError;
use crate::scene::Limits;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::{OwnedSemaphorePermit, Semaphore};

/// Every configurable bound of the service (flags and `GLINT_…` variables in `glint serve`).
#[derive(Debug, Clone)]
pub struct ServiceLimits {
    /// Largest request body accepted, bytes.
    pub max_body_bytes: usize,
    /// Request body bytes admitted at once (counted from `Content-Length` before a byte is
    /// read; a body without one counts as `max_body_bytes`). Beyond, 503 + `Retry-After`
    /// at once: parsing a large body costs several times its size in memory.
    pub max_inflight_body_bytes: usize,
    /// Largest mesh, triangles.
    pub max_triangles: usize,
    /// Most epochs in one `POST /v1/lightcurves`.
    pub max_sync_epochs: usize,
    /// Most epochs in one job.
    pub max_job_epochs: usize,
    /// Most triangles × epochs in one `POST /v1/lightcurves` (jobs: 1000× this).
    pub max_sync_triangle_epochs: u64,
    /// Most pixel samples (the `image` method's and the thumbnails') in one
    /// `POST /v1/lightcurves` (jobs: 100× this).
    pub max_sync_pixel_samples: u64,
    /// Computations running at once (synchronous requests and jobs together).
    pub max_concurrent: usize,
    /// Synchronous requests allowed to wait for a slot; beyond this they get 503. With
    /// the slots, also the light-curve requests admitted at once (read, parsed, waiting or
    /// computing): beyond, the 503 comes before the body is read.
    pub max_queued: usize,
    /// Jobs running at once (each also takes a computation slot).
    pub max_running_jobs: usize,
    /// Jobs queued or running; beyond, a submission gets 429.
    pub max_queued_jobs: usize,
    /// Bytes of finished jobs' results kept; at or beyond, a submission gets 507.
    pub max_result_bytes: u64,
    /// Time a synchronous request may take, waiting included.
    pub request_timeout: Duration,
    /// Time a connection may take to send a request's head, or stay silent between
    /// requests, before it is closed.
    pub header_timeout: Duration,
}

impl Default for ServiceLimits {
    fn default() -> Self {
        let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
        ServiceLimits {
            max_body_bytes: 32 << 20,
            max_inflight_body_bytes: 128 << 20,
            max_triangles: 1_000_000,
            max_sync_epochs: 20_000,
            max_job_epochs: 2_000_000,
            // ~10–20 min of the silhouette method on two cores at the suite's speed: far
            // over the request timeout, but every request that could finish within it
            // passes
            max_sync_triangle_epochs: 2_000_000_000,
            // ~10 M samples/s on one core: 2.5e8 is ~25 s of one core, within the 60 s
            // request timeout; a 2048-px, 16²-sample image (1.07e9) is a job's work
            max_sync_pixel_samples: 250_000_000,
            max_concurrent: cores,
            max_queued: 64,
            max_running_jobs: 1,
            max_queued_jobs: 1000,
            max_result_bytes: 8 << 30,
            request_timeout: Duration::from_secs(60),
            header_timeout: Duration::from_secs(10),
        }
    }
}

impl ServiceLimits {
    /// Engine limits for a synchronous request.
    pub fn sync_limits(&self) -> Limits {
        Limits {
            max_triangles: self.max_triangles,
            max_epochs: self.max_sync_epochs,
            max_triangle_epochs: self.max_sync_triangle_epochs,
            max_pixel_samples: self.max_sync_pixel_samples,
        }
    }

    /// Engine limits for a job.
    pub fn job_limits(&self) -> Limits {
        Limits {
            max_triangles: self.max_triangles,
            max_epochs: self.max_job_epochs,
            max_triangle_epochs: self.max_sync_triangle_epochs.saturating_mul(1000),
            max_pixel_samples: self.max_sync_pixel_samples.saturating_mul(100),
        }
    }

    /// Whether one more job may be taken, for the embedded store and the shared queue
    /// alike: 507 while the stored results (`stored`, bytes) are at their limit, else 429
    /// while the `unfinished()` jobs (queued or running; counted only when needed) fill
    /// the queue.
    pub fn room_for_a_job(
        &self,
        stored: u64,
        unfinished: impl FnOnce() -> usize,
    ) -> Result<(), ApiError> {
        if stored >= self.max_result_bytes {
            return Err(ApiError::new(
                axum::http::StatusCode::INSUFFICIENT_STORAGE,
                format!(
                    "stored results take {stored} bytes (limit {}): fetch and DELETE \
                     finished jobs to make room",
                    self.max_result_bytes
                ),
            ));
        }
        let unfinished = unfinished();
        if unfinished >= self.max_queued_jobs {
            let mut e = ApiError::new(
                axum::http::StatusCode::TOO_MANY_REQUESTS,
                format!(
                    "{unfinished} jobs are queued or running (limit {}); retry when some \
                     have finished, or cancel some",
                    self.max_queued_jobs
                ),
            );
            e.retry_after_s = Some(10);
            return Err(e);
        }
        Ok(())
    }
}

/// Computation slots: a semaphore with a bounded number of waiters.
///
/// The engine parallelises each request over epochs with rayon, so a few concurrent
/// requests already fill the cores; more would only share them and add latency.
#[derive(Debug)]
pub struct Slots {
    semaphore: Arc<Semaphore>,
    max_waiting: usize,
    waiting: AtomicUsize,
    total: usize,
    /// Light-curve requests admitted at once, from before their body is read until their
    /// answer: the slots plus the waiting room ([`Slots::admit`]).
    places: Arc<Semaphore>,
}

/// No slot free and the wait queue full.
#[derive(Debug, Clone, Copy)]
pub struct Busy;

impl Slots {
    pub fn new(max_concurrent: usize, max_waiting: usize) -> Self {
        let total = max_concurrent.max(1);
        Slots {
            semaphore: Arc::new(Semaphore::new(total)),
            max_waiting,
            waiting: AtomicUsize::new(0),
            total,
            places: Arc::new(Semaphore::new(total.saturating_add(max_waiting))),
        }
    }

    /// A place for a light-curve request, taken before its body is read and held until
    /// it is answered; [`Busy`] when as many are admitted as there are slots and waiting
    /// places. Under overload the turned-away request then costs neither reading nor
    /// parsing its body, so the requests that do run keep the cores.
    pub fn admit(&self) -> Result<OwnedSemaphorePermit, Busy> {
        self.places.clone().try_acquire_owned().map_err(|_| Busy)
    }

    /// A slot for a synchronous request: at once if one is free, after a wait if fewer
    /// than `max_waiting` already wait, else [`Busy`].
    pub async fn acquire(&self) -> Result<OwnedSemaphorePermit, Busy> {
        if let Ok(p) = self.semaphore.clone().try_acquire_owned() {
            return Ok(p);
        }
        if self.waiting.fetch_add(1, Ordering::SeqCst) >= self.max_waiting {
            self.waiting.fetch_sub(1, Ordering::SeqCst);
            return Err(Busy);
        }
        // Decrement on every exit, also when the request is dropped while waiting.
        struct Waiting<'a>(&'a AtomicUsize);
        impl Drop for Waiting<'_> {
            fn drop(&mut self) {
                self.0.fetch_sub(1, Ordering::SeqCst);
            }
        }
        let _w = Waiting(&self.waiting);
        self.semaphore
            .clone()
            .acquire_owned()
            .await
            .map_err(|_| Busy)
    }

    /// A slot for a job: jobs wait as long as needed (they are queued on disk anyway).
    pub async fn acquire_for_job(&self) -> OwnedSemaphorePermit {
        self.semaphore
            .clone()
            .acquire_owned()
            .await
            .expect("the semaphore is never closed")
    }

    /// Computations running now.
    pub fn in_use(&self) -> usize {
        self.total - self.semaphore.available_permits()
    }

    /// Synchronous requests waiting for a slot now.
    pub fn waiting(&self) -> usize {
        self.waiting.load(Ordering::SeqCst)
    }
}

/// Admission by body size: a semaphore of KiB of request bodies in flight, taken before
/// the body is read and held until the answer is made.
#[derive(Debug, Clone)]
pub struct BodyBytes {
    kib: Arc<Semaphore>,
    max_body: usize,
}

impl BodyBytes {
    /// `max_inflight` bytes in flight at once (at least one body of `max_body` bytes).
    pub fn new(max_inflight: usize, max_body: usize) -> BodyBytes {
        let kib = max_inflight
            .max(max_body)
            .div_ceil(1024)
            .min(u32::MAX as usize);
        BodyBytes {
            kib: Arc::new(Semaphore::new(kib)),
            max_body,
        }
    }
}

/// Middleware: admits a request with a body only if its bytes fit in what is left of
/// the in-flight budget; else `503` + `Retry-After` before its body is read.
pub async fn admit(
    axum::extract::State(budget): axum::extract::State<BodyBytes>,
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> axum::response::Response {
    use axum::response::IntoResponse;
    let method = req.method();
    if method == axum::http::Method::GET
        || method == axum::http::Method::HEAD
        || method == axum::http::Method::DELETE
    {
        return next.run(req).await;
    }
    let declared = req
        .headers()
        .get(axum::http::header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.trim().parse::<usize>().ok());
    // Declared over the body limit: 413 at once. (The body-limit layer would answer only
    // after reading up to the limit, and wait as long for a body that is never sent.)
    let bytes = match declared {
        Some(n) if n > budget.max_body => {
            let mut r = super::errors::ApiError::new(
                axum::http::StatusCode::PAYLOAD_TOO_LARGE,
                format!(
                    "request body too large: {n} bytes declared, at most {}",
                    budget.max_body
                ),
            )
            .with_field("body")
            .into_response();
            // the body is left unread: the connection cannot carry another request
            r.headers_mut().insert(
                axum::http::header::CONNECTION,
                axum::http::HeaderValue::from_static("close"),
            );
            return r;
        }
        Some(n) => n,
        None => budget.max_body,
    };
    let kib = bytes.div_ceil(1024).max(1).min(u32::MAX as usize) as u32;
    match budget.kib.clone().try_acquire_many_owned(kib) {
        Ok(_permit) => next.run(req).await,
        Err(_) => {
            refused(super::errors::ApiError {
                retry_after_s: Some(1),
                ..super::errors::ApiError::new(
                    axum::http::StatusCode::SERVICE_UNAVAILABLE,
                    format!(
                        "too many request bytes in flight (this body: {bytes} bytes); retry \
                         shortly"
                    ),
                )
            })
            .await
        }
    }
}

/// How long a request turned away before its body is read waits for its `503`. A client
/// that retries at once (ignoring `Retry-After`) would otherwise spin: each refusal is
/// cheap, but thousands a second take the cores from the requests that run. Waiting
/// costs a timer and the open socket, nothing else.
pub const REFUSAL_PAUSE: Duration = Duration::from_millis(200);

/// The answer to a request turned away before its body was read, after
/// [`REFUSAL_PAUSE`]; it closes the connection, which the unread body leaves unusable.
pub async fn refused(e: super::errors::ApiError) -> axum::response::Response {
    use axum::response::IntoResponse;
    tokio::time::sleep(REFUSAL_PAUSE).await;
    let mut r = e.into_response();
    r.headers_mut().insert(
        axum::http::header::CONNECTION,
        axum::http::HeaderValue::from_static("close"),
    );
    r
}
