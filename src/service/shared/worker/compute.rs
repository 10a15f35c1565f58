//! A claimed chunk computed: its job's input parsed once per process, the engine run on
//! the chunk's epochs (or the fit on its request) while the lease is renewed, and the
//! outcome written, given back or failed.

use super::lease::Claimed;
use super::Workers;
use crate::integrate::{Cancelled, Progress};
use crate::scene::{validate, Limits, Scene};
use crate::service::limits::ServiceLimits;
use crate::service::shared::rows::KIND_LIGHTCURVE;
use crate::service::shared::{chunks, PgError};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// A job's input, parsed once per process and job.
pub(super) struct JobInput {
    text: Arc<str>,
    scene: Option<Arc<Scene>>,
}

impl Workers {
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
        let scene = if kind == KIND_LIGHTCURVE {
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
    pub(super) async fn run(self: &Arc<Self>, name: &str, c: Claimed) {
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
}

/// A computed chunk.
pub(super) struct Done {
    pub(super) data: Vec<u8>,
    pub(super) epochs: usize,
    pub(super) evaluations: Option<usize>,
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
