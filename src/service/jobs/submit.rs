//! Submission: a body validated with the job limits, checked against the idempotency
//! keys and the room left for jobs, and stored durably before the `202`.

use super::{now_ms, Entry, Evaluations, JobKind, JobRecord, JobState, JobStatus, Jobs};
use crate::scene::{validate, Scene};
use crate::service::errors::ApiError;
use crate::service::threads::run_blocking;
use std::collections::HashMap;
use std::sync::atomic::Ordering;
use std::sync::Arc;

impl Jobs {
    /// Validates a light-curve request body with the job limits and stores the new job;
    /// returns once the store transaction is committed. With an idempotency key already
    /// used for the same body, returns that job instead (`true`: replayed); with a
    /// different body, 422.
    pub async fn submit(
        self: &Arc<Self>,
        body: axum::body::Bytes,
        key: Option<String>,
    ) -> Result<(JobStatus, bool), ApiError> {
        self.submit_kind(JobKind::Lightcurve, body, key).await
    }

    /// [`Self::submit`] for a light-curve fit's body (`POST /v1/fits/lightcurve`).
    pub async fn submit_fit(
        self: &Arc<Self>,
        body: axum::body::Bytes,
        key: Option<String>,
    ) -> Result<(JobStatus, bool), ApiError> {
        self.submit_kind(JobKind::FitLightcurve, body, key).await
    }

    async fn submit_kind(
        self: &Arc<Self>,
        kind: JobKind,
        body: axum::body::Bytes,
        key: Option<String>,
    ) -> Result<(JobStatus, bool), ApiError> {
        if self.shutting_down.load(Ordering::SeqCst) {
            return Err(ApiError::new(
                axum::http::StatusCode::SERVICE_UNAVAILABLE,
                "shutting down",
            ));
        }
        let idempotency = crate::service::record::idempotency(key, &body);
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
                let (epochs_total, evaluations) = me.accepted(kind, text)?;
                let rec = JobRecord {
                    id: uuid::Uuid::new_v4().to_string(),
                    state: JobState::Queued,
                    epochs_total,
                    epochs_done: 0,
                    created_ms: now_ms(),
                    started_ms: None,
                    finished_ms: None,
                    error: None,
                    attempts: 0,
                    idempotency,
                    kind,
                    evaluations,
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
                    let entry = Entry::new(rec.clone());
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

    /// A body of `kind` checked with the job limits: the epochs the job may compute and, for
    /// a fit, its light curves.
    fn accepted(
        &self,
        kind: JobKind,
        text: &str,
    ) -> Result<(usize, Option<Evaluations>), ApiError> {
        match kind {
            JobKind::Lightcurve => {
                let request = validate::parse_request(text)?;
                let scene = Scene::from_request(&request, &self.limits.job_limits())?;
                Ok((scene.epochs.len(), None))
            }
            JobKind::FitLightcurve => {
                let (epochs, evaluations) = super::fit::accepted(text, &self.limits)?;
                Ok((epochs, Some(evaluations)))
            }
        }
    }

    /// The job submitted earlier with this idempotency key, if any; 422 when the key
    /// came with another body.
    fn replay(&self, key: Option<&(String, String)>) -> Result<Option<JobStatus>, ApiError> {
        self.replay_in(&self.table(), key)
    }

    /// [`Self::replay`] within the locked table `t`.
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

    /// [`Self::room_for_a_job`] within the locked table `t`; also 507 while the stored
    /// results are over their limit.
    fn room_in(&self, t: &HashMap<String, Entry>) -> Result<(), ApiError> {
        self.limits.room_for_a_job(self.store.result_bytes(), || {
            t.values().filter(|e| !e.rec.state.is_final()).count()
        })
    }
}
