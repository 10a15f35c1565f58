//! The dispatcher, which starts each queued job when a job permit and a computation slot
//! are free, and one job's run: the stored request parsed again, computed on the job
//! pool, and its outcome stored before it is shown.

use super::{fit, now_ms, JobKind, JobRecord, JobState, Jobs};
use crate::integrate::{Cancelled, Progress};
use crate::scene::{validate, Scene};
use crate::service::store::{Output, StoreError};
use std::sync::atomic::Ordering;
use std::sync::Arc;
use tokio::sync::mpsc;

impl Jobs {
    /// Takes queued job ids in order and starts each when a job permit and a computation
    /// slot are free; a job cancelled while it waited is skipped.
    pub(super) async fn dispatch(self: Arc<Self>, mut rx: mpsc::UnboundedReceiver<String>) {
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

    /// One run of job `id` on the job pool, holding `slot` until the computation has
    /// stopped; its outcome is stored by [`Self::finish`].
    async fn run(self: &Arc<Self>, id: &str, slot: tokio::sync::OwnedSemaphorePermit) {
        let (kind, progress, evaluations) = {
            let mut t = self.table();
            let Some(e) = t.get_mut(id) else { return };
            if e.rec.state != JobState::Queued || self.shutting_down.load(Ordering::SeqCst) {
                return;
            }
            e.rec.state = JobState::Running;
            e.rec.started_ms = Some(now_ms());
            e.rec.attempts += 1;
            e.progress = Arc::new(Progress::new());
            e.evaluations = Default::default();
            (e.rec.kind, e.progress.clone(), e.evaluations.clone())
        };
        let me = self.clone();
        let key = id.to_string();
        let outcome = tokio::task::spawn_blocking(move || {
            let _slot = slot; // held until the computation has really stopped
            me.persist(&key).map_err(|e| e.to_string())?;
            let body = me
                .store
                .request(&key)
                .map_err(|e| e.to_string())?
                .ok_or("the stored request is missing")?;
            let text = std::str::from_utf8(&body).map_err(|_| "request body is not UTF-8")?;
            if kind == JobKind::FitLightcurve {
                let run = me
                    .pool
                    .install(|| fit::run(text, &me.limits, me.engine, &progress, &evaluations));
                return run.map(|done| done.map(|(json, n)| (Output::Fit(json), n)));
            }
            let scene = validate::parse_request(text)
                .and_then(|r| Scene::from_request(&r, &me.limits.job_limits()))
                .map_err(|e| e.to_string())?;
            match me.pool.install(|| (me.engine)(&scene, &progress)) {
                Ok(resp) => {
                    let n = resp.epochs.len();
                    Ok(Some((Output::Lightcurve(resp), n)))
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
    fn finish(&self, id: &str, outcome: Result<(Output, usize), String>) -> Result<(), StoreError> {
        let _g = self.write_lock.lock().unwrap_or_else(|e| e.into_inner());
        let mut rec = match self.table().get(id) {
            // Not running any more: cancelled (and persisted) meanwhile.
            Some(e) if e.rec.state == JobState::Running => e.rec.clone(),
            _ => return Ok(()),
        };
        if let Some(e) = self.table().get(id) {
            rec.evaluations = e.evaluations_so_far();
        }
        let result = settle(&mut rec, outcome, now_ms(), || {
            self.table().get(id).map_or(0, |e| e.epochs_so_far())
        });
        self.store.update(&rec, result.as_ref())?;
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
}

/// A run's outcome written into its record at `now` (Unix ms): `done` with its epoch count
/// and the result to store, or `failed` with the message and the epochs computed so far
/// (`done_so_far`, asked only then). Returns the result, if any.
fn settle<T>(
    rec: &mut JobRecord,
    outcome: Result<(T, usize), String>,
    now: i64,
    done_so_far: impl FnOnce() -> usize,
) -> Option<T> {
    rec.finished_ms = Some(now);
    match outcome {
        Ok((result, n)) => {
            rec.state = JobState::Done;
            rec.epochs_done = n;
            Some(result)
        }
        Err(msg) => {
            rec.state = JobState::Failed;
            rec.error = Some(msg);
            rec.epochs_done = done_so_far();
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_fixtures::record;
    use super::*;

    #[test]
    fn a_successful_run_is_done_with_its_result() {
        let mut rec = record(JobState::Running);
        let result = settle(&mut rec, Ok((b"{}".to_vec(), 10)), 9_000, || {
            panic!("the progress is not asked for a done job")
        });
        assert_eq!(result.as_deref(), Some(&b"{}"[..]));
        assert_eq!((rec.state, rec.epochs_done), (JobState::Done, 10));
        assert_eq!((rec.finished_ms, rec.error), (Some(9_000), None));
    }

    #[test]
    fn a_failed_run_keeps_its_message_and_the_epochs_computed() {
        let mut rec = record(JobState::Running);
        let result = settle::<Vec<u8>>(&mut rec, Err("no disk".into()), 9_000, || 6);
        assert_eq!(result, None);
        assert_eq!((rec.state, rec.epochs_done), (JobState::Failed, 6));
        assert_eq!(rec.error.as_deref(), Some("no disk"));
        assert_eq!(rec.finished_ms, Some(9_000));
    }
}
