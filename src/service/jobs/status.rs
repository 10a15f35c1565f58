//! What a client sees of the jobs: one job's status (`GET /v1/jobs/{id}`), the recent
//! jobs, the count in each state, and a finished job's stored result.

use super::{Entry, Evaluations, JobKind, JobRecord, JobState, Jobs};
use crate::service::errors::ApiError;
use crate::service::store::{Form, Store};
use crate::service::threads::run_blocking;
use axum::body::Bytes;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::sync::Arc;
use std::time::Duration;
use utoipa::ToSchema;

/// A job's status as `GET /v1/jobs/{id}` reports it.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema, PartialEq)]
pub struct JobStatus {
    /// Job id (UUID).
    pub id: String,
    pub state: JobState,
    /// What it computes: `lightcurve` (`POST /v1/jobs`) or `fit-lightcurve`
    /// (`POST /v1/fits/lightcurve`).
    pub kind: JobKind,
    /// How far it has come, 0–100: epochs computed of the total; for a fit, light curves
    /// evaluated of `evaluations_max` (100 once done).
    pub percent: f64,
    /// Epochs computed so far (a fit: over all its light curves).
    pub epochs_done: usize,
    /// Epochs in the request; for a fit, the observed epochs times `evaluations_max`, the
    /// most it may compute.
    pub epochs_total: usize,
    /// A fit: light curves evaluated so far (its result's `solver.evaluations` once done).
    pub evaluations_done: Option<usize>,
    /// A fit: the most light curves it may evaluate (its `max_evaluations`).
    pub evaluations_max: Option<usize>,
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

/// Unix milliseconds as RFC 3339 UTC text.
pub fn rfc3339(ms: i64) -> String {
    chrono::DateTime::from_timestamp_millis(ms)
        .map(|d| d.to_rfc3339_opts(chrono::SecondsFormat::Millis, true))
        .unwrap_or_default()
}

/// The status of `e`; a finished job expires `ttl` after it finished.
fn status_of(e: &Entry, ttl: Duration) -> JobStatus {
    let r = &e.rec;
    let evaluations = e.evaluations_so_far();
    let done = match (r.state, evaluations) {
        (JobState::Running, _) => e.epochs_so_far(),
        // a fit need not take all the light curves it may
        (JobState::Done, None) => r.epochs_total,
        _ => r.epochs_done,
    };
    status_from(r, done, evaluations, ttl)
}

/// The status of the job `r` with `done` epochs computed and, for a fit, its light
/// curves `evaluations`; a finished job expires `ttl` after it finished.
pub(crate) fn status_from(
    r: &JobRecord,
    done: usize,
    evaluations: Option<Evaluations>,
    ttl: Duration,
) -> JobStatus {
    let percent = match (r.state, evaluations) {
        (JobState::Done, _) => 100.0,
        (_, Some(ev)) if ev.max > 0 => 100.0 * ev.done as f64 / ev.max as f64,
        _ if r.epochs_total > 0 => 100.0 * done as f64 / r.epochs_total as f64,
        _ => 0.0,
    };
    JobStatus {
        id: r.id.clone(),
        state: r.state,
        kind: r.kind,
        percent,
        epochs_done: done,
        epochs_total: r.epochs_total,
        evaluations_done: evaluations.map(|ev| ev.done),
        evaluations_max: evaluations.map(|ev| ev.max),
        created_at: rfc3339(r.created_ms),
        started_at: r.started_ms.map(rfc3339),
        finished_at: r.finished_ms.map(rfc3339),
        expires_at: r
            .finished_ms
            .map(|f| rfc3339(f.saturating_add(ttl.as_millis() as i64))),
        error: r.error.clone(),
        attempts: r.attempts,
        result_url: (r.state == JobState::Done).then(|| format!("/v1/jobs/{}/result", r.id)),
    }
}

impl Jobs {
    /// The status of `e` as a client sees it.
    pub(super) fn status_of(&self, e: &Entry) -> JobStatus {
        status_of(e, self.ttl)
    }

    /// What job `id` computes, if it is known.
    pub fn kind(&self, id: &str) -> Option<JobKind> {
        self.table().get(id).map(|e| e.rec.kind)
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

    /// Why job `id` has no result to serve, if it has none: unknown (404) or not done (409).
    /// Returns what the job computes.
    fn check_done(&self, id: &str) -> Result<JobKind, ApiError> {
        let (state, kind) = self
            .table()
            .get(id)
            .map(|e| (e.rec.state, e.rec.kind))
            .ok_or_else(|| no_such_job(id))?;
        if state != JobState::Done {
            return Err(ApiError::conflict(format!(
                "job is {}, there is no result{}",
                state.name(),
                if state.is_final() { "" } else { " yet" }
            )));
        }
        Ok(kind)
    }

    /// The size of a finished job's stored result in `form`; `Err` says why there is none.
    pub async fn result_len(&self, id: &str, form: Form) -> Result<u64, ApiError> {
        self.check_done(id)?;
        let store = self.store.clone();
        let key = id.to_string();
        run_blocking("reading the result", move || store.result_len(&key, form))
            .await?
            .map_err(ApiError::from)?
            // Removed by expiry or a DELETE between the two looks.
            .ok_or_else(|| no_such_job(id))
    }

    /// A finished job's result in `form`, `len` bytes ([`Self::result_len`]), read from the
    /// store one chunk at a time as the client takes it: a download holds about a chunk in
    /// memory, whatever the result's size. A result removed mid-way ends the stream with an
    /// error (the connection is cut short of its `Content-Length`).
    pub fn result_stream(
        &self,
        id: &str,
        form: Form,
        len: u64,
    ) -> impl futures_util::stream::Stream<Item = std::io::Result<Bytes>> + Send + 'static {
        let store = self.store.clone();
        let id: Arc<str> = Arc::from(id);
        futures_util::stream::try_unfold((0u32, 0u64), move |(index, sent)| {
            next_chunk(store.clone(), id.clone(), form, len, index, sent)
        })
    }

    /// The PNG of epoch `epoch`'s thumbnail of a finished job; `Err` says why there is none.
    pub async fn thumbnail(&self, id: &str, epoch: usize) -> Result<Vec<u8>, ApiError> {
        if self.check_done(id)? == JobKind::FitLightcurve {
            return Err(ApiError::not_found("a fit job renders no images").with_field("epoch"));
        }
        let store = self.store.clone();
        let key = id.to_string();
        run_blocking("reading the image", move || {
            store.thumbnail(&key, epoch as u64)
        })
        .await?
        .map_err(ApiError::from)?
        .ok_or_else(|| {
            ApiError::not_found(format!("the job has no image for epoch {epoch}"))
                .with_field("epoch")
        })
    }
}

/// Chunk `index` of a result being sent, `sent` of its `len` bytes gone already; with the
/// state after it, or `None` at its end.
async fn next_chunk(
    store: Arc<Store>,
    id: Arc<str>,
    form: Form,
    len: u64,
    index: u32,
    sent: u64,
) -> std::io::Result<Option<(Bytes, (u32, u64))>> {
    if sent >= len {
        return Ok(None);
    }
    let chunk = tokio::task::spawn_blocking(move || store.result_chunk(&id, form, index))
        .await
        .map_err(std::io::Error::other)?
        .map_err(std::io::Error::other)?
        .ok_or_else(|| std::io::Error::other("the result was removed while it was being sent"))?;
    let next = (index + 1, sent + chunk.len() as u64);
    Ok(Some((Bytes::from(chunk), next)))
}

/// The 404 of a job id that is not (or no longer) known.
pub fn no_such_job(id: &str) -> ApiError {
    ApiError::not_found(format!("no job with id `{id}` (finished jobs expire)")).with_field("id")
}

#[cfg(test)]
mod tests {
    use super::super::test_fixtures::entry;
    use super::*;

    const TTL: Duration = Duration::from_secs(60);

    #[test]
    fn times_are_rfc3339_utc_to_the_millisecond() {
        assert_eq!(rfc3339(0), "1970-01-01T00:00:00.000Z");
        assert_eq!(rfc3339(1_234), "1970-01-01T00:00:01.234Z");
    }

    #[test]
    fn a_done_job_shows_all_its_epochs_its_result_and_its_expiry() {
        let s = status_of(&entry(JobState::Done), TTL);
        assert_eq!((s.epochs_done, s.percent), (10, 100.0));
        assert_eq!(s.result_url.as_deref(), Some("/v1/jobs/job-1/result"));
        assert_eq!(s.finished_at.as_deref(), Some("1970-01-01T00:00:03.000Z"));
        assert_eq!(s.expires_at.as_deref(), Some("1970-01-01T00:01:03.000Z"));
    }

    #[test]
    fn an_unfinished_job_has_no_result_and_no_expiry() {
        let s = status_of(&entry(JobState::Queued), TTL);
        assert_eq!(
            (s.state, s.epochs_done, s.percent),
            (JobState::Queued, 0, 0.0)
        );
        assert_eq!(
            (s.result_url, s.finished_at, s.expires_at),
            (None, None, None)
        );
        assert_eq!(s.created_at, "1970-01-01T00:00:01.000Z");
        // a running job counts its progress, not its record
        let mut e = entry(JobState::Running);
        e.rec.epochs_done = 9;
        assert_eq!(status_of(&e, TTL).epochs_done, 0);
    }

    #[test]
    fn a_failed_job_keeps_its_partial_count_and_says_why() {
        let mut e = entry(JobState::Failed);
        e.rec.error = Some("boom".into());
        let s = status_of(&e, TTL);
        assert_eq!((s.epochs_done, s.percent), (4, 40.0));
        assert_eq!((s.error.as_deref(), s.result_url), (Some("boom"), None));
        e.rec.epochs_total = 0;
        assert_eq!(status_of(&e, TTL).percent, 0.0);
    }
}
