//! A job's row read as its status, and the kinds and states as the rows store them.

use super::PgError;
use crate::service::jobs::{status_from, Evaluations, JobKind, JobRecord, JobState, JobStatus};
use std::time::Duration;

pub(super) const KIND_LIGHTCURVE: &str = "lightcurve";
const KIND_FIT: &str = "fit-lightcurve";

pub(super) fn kind_name(k: JobKind) -> &'static str {
    match k {
        JobKind::Lightcurve => KIND_LIGHTCURVE,
        JobKind::FitLightcurve => KIND_FIT,
    }
}

pub(super) fn kind_of(s: &str) -> Result<JobKind, PgError> {
    match s {
        KIND_LIGHTCURVE => Ok(JobKind::Lightcurve),
        KIND_FIT => Ok(JobKind::FitLightcurve),
        other => Err(PgError::Corrupt(format!("job kind `{other}`"))),
    }
}

pub(super) fn state_of(s: &str) -> Result<JobState, PgError> {
    JobState::ALL
        .into_iter()
        .find(|k| k.name() == s)
        .ok_or_else(|| PgError::Corrupt(format!("job state `{s}`")))
}

/// The columns [`status_of_row`] reads, from `glint_jobs j`; the epochs done are summed
/// from the job's done chunks.
pub(super) const STATUS_COLUMNS: &str = "j.id, j.kind, j.state, j.epochs_total, j.created_ms, \
     j.started_ms, j.finished_ms, j.error, j.attempts, j.eval_max, j.eval_done, \
     (SELECT coalesce(sum(c.epochs_computed), 0)::bigint FROM glint_chunks c \
      WHERE c.job_id = j.id AND c.state = 'done') AS epochs_done";

pub(super) fn status_of_row(
    row: &tokio_postgres::Row,
    ttl: Duration,
) -> Result<JobStatus, PgError> {
    let state = state_of(row.get("state"))?;
    let epochs_total = row.get::<_, i64>("epochs_total") as usize;
    let done = row.get::<_, i64>("epochs_done") as usize;
    let evaluations = row
        .get::<_, Option<i64>>("eval_max")
        .map(|max| Evaluations {
            done: row.get::<_, Option<i64>>("eval_done").unwrap_or(0) as usize,
            max: max as usize,
        });
    let rec = JobRecord {
        id: row.get("id"),
        state,
        epochs_total,
        epochs_done: done,
        created_ms: row.get("created_ms"),
        started_ms: row.get("started_ms"),
        finished_ms: row.get("finished_ms"),
        error: row.get("error"),
        attempts: row.get::<_, i32>("attempts") as u32,
        idempotency: None,
        kind: kind_of(row.get("kind"))?,
        evaluations,
    };
    Ok(status_from(&rec, done, evaluations, ttl))
}

/// The status of job `id`, read in `tx` (after a change it makes, before its commit).
pub(super) async fn status_in(
    tx: &deadpool_postgres::Transaction<'_>,
    id: &str,
    ttl: Duration,
) -> Result<JobStatus, PgError> {
    let row = tx
        .query_one(
            &format!("SELECT {STATUS_COLUMNS} FROM glint_jobs j WHERE j.id = $1"),
            &[&id],
        )
        .await?;
    status_of_row(&row, ttl)
}
