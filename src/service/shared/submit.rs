//! A submission to the shared queue: the body checked with the job limits and cut into
//! chunks, then the job and its chunks stored in one transaction under a lock that makes
//! the room and idempotency checks exact, and the workers woken.

use super::rows::{kind_name, status_in, status_of_row, STATUS_COLUMNS};
use super::{chunks, PgError, Shared, CHUNKS_CHANNEL};
use crate::scene::{validate, Scene};
use crate::service::errors::ApiError;
use crate::service::jobs::{now_ms, Evaluations, JobKind, JobStatus};
use crate::service::limits::ServiceLimits;
use crate::service::threads::run_blocking;
use std::sync::Arc;

/// Advisory lock key held by a submission's transaction, so that the room check and the
/// idempotency check see every other submission ("glinq" in ASCII).
const SUBMIT_LOCK: i64 = 0x0067_6c69_6e71;

/// What a submission stores: the epochs, a fit's light curves and the chunks.
struct Planned {
    epochs_total: usize,
    evaluations: Option<Evaluations>,
    chunk_epochs: usize,
    chunks: Vec<(usize, usize)>,
}

/// A body of `kind` checked with the job limits and cut into chunks (a fit is one chunk:
/// its light curves follow one another).
fn planned(
    kind: JobKind,
    text: &str,
    limits: &ServiceLimits,
    fixed: Option<usize>,
) -> Result<Planned, ApiError> {
    match kind {
        JobKind::Lightcurve => {
            let request = validate::parse_request(text)?;
            let scene = Scene::from_request(&request, &limits.job_limits())?;
            let per = chunks::chunk_epochs(&scene, fixed);
            Ok(Planned {
                epochs_total: scene.epochs.len(),
                evaluations: None,
                chunk_epochs: per,
                chunks: chunks::plan(scene.epochs.len(), per),
            })
        }
        JobKind::FitLightcurve => {
            let (epochs, evaluations) = crate::service::jobs::fit::accepted(text, limits)?;
            Ok(Planned {
                epochs_total: epochs,
                evaluations: Some(evaluations),
                chunk_epochs: epochs.max(1),
                chunks: vec![(0, epochs)],
            })
        }
    }
}

impl Shared {
    /// Validates and stores a new job with its chunks in one transaction, and wakes the
    /// workers. With an idempotency key already used for the same body, returns that
    /// job (`true`: replayed); with a different body, 422.
    pub async fn submit(
        self: &Arc<Self>,
        kind: JobKind,
        body: axum::body::Bytes,
        key: Option<String>,
    ) -> Result<(JobStatus, bool), ApiError> {
        if self.is_shutting_down() {
            return Err(ApiError::new(
                axum::http::StatusCode::SERVICE_UNAVAILABLE,
                "shutting down",
            ));
        }
        let idempotency = crate::service::record::idempotency(key, &body);
        // a retry costs no validation
        if let Some(found) = self.replay(None, idempotency.as_ref()).await? {
            return Ok((found, true));
        }
        let limits = self.limits.clone();
        let fixed = self.chunk_epochs;
        let text_body = body.clone();
        let plan = run_blocking("validating the job", move || {
            let text = std::str::from_utf8(&text_body)
                .map_err(|_| ApiError::bad_request("request body is not UTF-8"))?;
            planned(kind, text, &limits, fixed)
        })
        .await??;

        let mut client = self.pool.get().await.map_err(PgError::from)?;
        let tx = client.transaction().await.map_err(PgError::from)?;
        tx.execute("SELECT pg_advisory_xact_lock($1)", &[&SUBMIT_LOCK])
            .await
            .map_err(PgError::from)?;
        if let Some(found) = self.replay(Some(&tx), idempotency.as_ref()).await? {
            return Ok((found, true));
        }
        self.room_in(&tx).await?;
        let id = uuid::Uuid::new_v4().to_string();
        let created = now_ms();
        let (idem_key, idem_digest) = match &idempotency {
            Some((k, d)) => (Some(k.as_str()), Some(d.as_str())),
            None => (None, None),
        };
        let eval_max = plan.evaluations.map(|e| e.max as i64);
        let eval_done = plan.evaluations.map(|_| 0i64);
        tx.execute(
            "INSERT INTO glint_jobs (id, kind, state, request, epochs_total, chunk_epochs, \
             created_ms, idem_key, idem_digest, eval_max, eval_done) \
             VALUES ($1, $2, 'queued', $3, $4, $5, $6, $7, $8, $9, $10)",
            &[
                &id,
                &kind_name(kind),
                &&body[..],
                &(plan.epochs_total as i64),
                &(plan.chunk_epochs as i64),
                &created,
                &idem_key,
                &idem_digest,
                &eval_max,
                &eval_done,
            ],
        )
        .await
        .map_err(PgError::from)?;
        let idx: Vec<i32> = (0..plan.chunks.len() as i32).collect();
        let first: Vec<i64> = plan.chunks.iter().map(|c| c.0 as i64).collect();
        let epochs: Vec<i64> = plan.chunks.iter().map(|c| c.1 as i64).collect();
        tx.execute(
            "INSERT INTO glint_chunks (job_id, idx, first_epoch, epochs, state) \
             SELECT $1, i, f, n, 'queued' FROM unnest($2::int[], $3::bigint[], $4::bigint[]) \
             AS u(i, f, n)",
            &[&id, &idx, &first, &epochs],
        )
        .await
        .map_err(PgError::from)?;
        tx.execute(&format!("NOTIFY {CHUNKS_CHANNEL}"), &[])
            .await
            .map_err(PgError::from)?;
        let status = status_in(&tx, &id, self.ttl).await?;
        tx.commit().await.map_err(PgError::from)?;
        Ok((status, false))
    }

    /// The job made earlier with this idempotency key, if any (422 when it came with
    /// another body); read in `tx` when given.
    async fn replay(
        &self,
        tx: Option<&deadpool_postgres::Transaction<'_>>,
        key: Option<&(String, String)>,
    ) -> Result<Option<JobStatus>, ApiError> {
        let Some((key, digest)) = key else {
            return Ok(None);
        };
        let sql = format!(
            "SELECT {STATUS_COLUMNS}, j.idem_digest FROM glint_jobs j WHERE j.idem_key = $1"
        );
        let row = match tx {
            Some(tx) => tx.query_opt(&sql, &[key]).await,
            None => {
                let client = self.pool.get().await.map_err(PgError::from)?;
                client.query_opt(&sql, &[key]).await
            }
        }
        .map_err(PgError::from)?;
        let Some(row) = row else { return Ok(None) };
        let status = status_of_row(&row, self.ttl)?;
        if row.get::<_, Option<String>>("idem_digest").as_deref() == Some(digest.as_str()) {
            Ok(Some(status))
        } else {
            Err(ApiError::new(
                axum::http::StatusCode::UNPROCESSABLE_ENTITY,
                format!(
                    "this Idempotency-Key was used for job {} with a different request body",
                    status.id
                ),
            )
            .with_field("Idempotency-Key"))
        }
    }

    /// 429 while `max_queued_jobs` jobs are unfinished, 507 while the stored results are
    /// over their limit (exact: read under the submission lock).
    async fn room_in(&self, tx: &deadpool_postgres::Transaction<'_>) -> Result<(), ApiError> {
        let row = tx
            .query_one(
                "SELECT count(*) FILTER (WHERE state IN ('queued', 'running')), \
                 coalesce(sum(result_bytes), 0)::bigint FROM glint_jobs",
                &[],
            )
            .await
            .map_err(PgError::from)?;
        let unfinished = row.get::<_, i64>(0) as usize;
        let stored = row.get::<_, i64>(1) as u64;
        self.limits.room_for_a_job(stored, || unfinished)
    }
}
