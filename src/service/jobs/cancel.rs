//! Cancellation: `DELETE /v1/jobs/{id}` cancels a queued or running job or removes a
//! finished one; shutdown asks the running jobs to stop at their next epoch.

use super::{no_such_job, now_ms, Entry, JobState, JobStatus, Jobs};
use crate::service::errors::ApiError;
use crate::service::threads::run_blocking;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Duration;

/// What `DELETE /v1/jobs/{id}` did.
#[derive(Debug)]
pub enum Deleted {
    /// The job was queued or running and is now cancelled.
    Cancelled(Box<JobStatus>),
    /// The job had finished; it and its result were removed.
    Removed,
}

impl Jobs {
    /// Cancels a queued or running job, or removes a finished one with its result.
    pub async fn delete(self: &Arc<Self>, id: &str) -> Result<Deleted, ApiError> {
        // The status is taken as this call cancels it: a concurrent DELETE may remove the
        // cancelled job before this one answers, and this answer must still say what it did.
        let cancelled = {
            let mut t = self.table();
            let e = t.get_mut(id).ok_or_else(|| no_such_job(id))?;
            cancel(e, now_ms()).then(|| self.status_of(e))
        };
        let me = self.clone();
        let key = id.to_string();
        let was_cancelled = cancelled.is_some();
        run_blocking("removing the job", move || {
            if was_cancelled {
                me.persist(&key)
            } else {
                me.remove(&key)
            }
        })
        .await?
        .map_err(ApiError::from)?;
        Ok(match cancelled {
            Some(s) => Deleted::Cancelled(Box::new(s)),
            None => Deleted::Removed,
        })
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
}

/// Cancels a queued or running job at `now` (Unix ms): its run is asked to stop, a running
/// job keeps the epochs it computed. `false` (and nothing changed) for a finished job.
fn cancel(e: &mut Entry, now: i64) -> bool {
    match e.rec.state {
        JobState::Queued | JobState::Running => {
            e.progress.cancel();
            if e.rec.state == JobState::Running {
                e.rec.epochs_done = e.epochs_so_far();
                e.rec.evaluations = e.evaluations_so_far();
            }
            e.rec.state = JobState::Cancelled;
            e.rec.finished_ms = Some(now);
            true
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_fixtures::entry;
    use super::*;

    #[test]
    fn a_queued_or_running_job_is_cancelled_and_its_run_asked_to_stop() {
        for state in [JobState::Queued, JobState::Running] {
            let mut e = entry(state);
            assert!(cancel(&mut e, 5_000));
            assert_eq!(e.rec.state, JobState::Cancelled);
            assert_eq!(e.rec.finished_ms, Some(5_000));
            assert!(e.progress.is_cancelled());
        }
    }

    #[test]
    fn a_running_job_keeps_the_epochs_of_its_run_and_a_queued_one_its_record() {
        let mut e = entry(JobState::Running);
        e.rec.epochs_done = 9; // stale: the run's counter (0 here) is what was computed
        cancel(&mut e, 5_000);
        assert_eq!(e.rec.epochs_done, 0);
        let mut e = entry(JobState::Queued);
        e.rec.epochs_done = 3;
        cancel(&mut e, 5_000);
        assert_eq!(e.rec.epochs_done, 3);
    }

    #[test]
    fn a_finished_job_is_not_cancelled() {
        for state in [JobState::Done, JobState::Failed, JobState::Cancelled] {
            let mut e = entry(state);
            assert!(!cancel(&mut e, 5_000));
            assert_eq!((e.rec.state, e.rec.finished_ms), (state, Some(3_000)));
            assert!(!e.progress.is_cancelled());
        }
    }
}
