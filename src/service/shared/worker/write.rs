//! A computed chunk written in the transaction that marks it done (the job done with its
//! last chunk), retried while the database is away; a job marked failed.

use super::compute::Done;
use super::lease::Claimed;
use super::{Workers, FIRST_BACKOFF, MAX_BACKOFF};
use crate::service::jobs::now_ms;
use crate::service::shared::PgError;

impl Workers {
    /// Writes a computed chunk, retrying with backoff while the database is away (for up
    /// to ten leases: by then another worker has long taken the chunk over). `true` when
    /// this write stored the chunk.
    pub(super) async fn write(&self, name: &str, c: &Claimed, done: Done) -> bool {
        let mut backoff = FIRST_BACKOFF;
        let give_up = tokio::time::Instant::now() + self.cfg.lease * 10;
        loop {
            match self.write_once(name, c, &done).await {
                Ok(stored) => {
                    if stored {
                        if let Some(m) = &self.cfg.metrics {
                            m.add_epochs("job", done.epochs as u64);
                        }
                    }
                    return stored;
                }
                Err(e) if tokio::time::Instant::now() < give_up => {
                    tracing::warn!(
                        job = c.job,
                        chunk = c.idx,
                        "writing the chunk: {e}; again in {backoff:?}"
                    );
                    tokio::time::sleep(backoff).await;
                    backoff = (backoff * 2).min(MAX_BACKOFF);
                }
                Err(e) => {
                    tracing::warn!(
                        job = c.job,
                        chunk = c.idx,
                        "writing the chunk: {e}; left to the queue"
                    );
                    return false;
                }
            }
        }
    }

    /// One transaction: the job row locked (a cancel commits before or after, never
    /// between); if the job is still active and the chunk not done, the chunk marked done
    /// with its result row; the job done when no chunk is left. `true` when stored.
    async fn write_once(&self, name: &str, c: &Claimed, done: &Done) -> Result<bool, PgError> {
        let mut client = self.cfg.pool.get().await?;
        let tx = client.transaction().await?;
        let state: Option<String> = tx
            .query_opt(
                "SELECT state FROM glint_jobs WHERE id = $1 FOR UPDATE",
                &[&c.job],
            )
            .await?
            .map(|r| r.get(0));
        if !matches!(state.as_deref(), Some("queued" | "running")) {
            tx.rollback().await?;
            return Ok(false);
        }
        let marked = tx
            .execute(
                "UPDATE glint_chunks SET state = 'done', done_by = $3, lease_until = NULL, \
                 epochs_computed = $4 WHERE job_id = $1 AND idx = $2 AND state <> 'done'",
                &[&c.job, &c.idx, &name, &(done.epochs as i64)],
            )
            .await?;
        if marked == 0 {
            tx.rollback().await?;
            return Ok(false);
        }
        tx.execute(
            "INSERT INTO glint_results (job_id, idx, data) VALUES ($1, $2, $3) \
             ON CONFLICT (job_id, idx) DO NOTHING",
            &[&c.job, &c.idx, &done.data],
        )
        .await?;
        tx.execute(
            "UPDATE glint_jobs SET result_bytes = result_bytes + $2, \
             eval_done = coalesce($3, eval_done) WHERE id = $1",
            &[
                &c.job,
                &(done.data.len() as i64),
                &done.evaluations.map(|e| e as i64),
            ],
        )
        .await?;
        let open: i64 = tx
            .query_one(
                "SELECT count(*) FROM glint_chunks WHERE job_id = $1 AND state <> 'done'",
                &[&c.job],
            )
            .await?
            .get(0);
        if open == 0 {
            tx.execute(
                "UPDATE glint_jobs SET state = 'done', finished_ms = $2, request = NULL \
                 WHERE id = $1",
                &[&c.job, &now_ms()],
            )
            .await?;
        }
        tx.commit().await?;
        Ok(true)
    }

    /// Marks an active job failed with `msg`.
    pub(super) async fn fail(&self, job: &str, msg: &str) -> Result<(), PgError> {
        let client = self.cfg.pool.get().await?;
        client
            .execute(
                "UPDATE glint_jobs SET state = 'failed', error = $2, finished_ms = $3, \
                 request = NULL WHERE id = $1 AND state IN ('queued', 'running')",
                &[&job, &msg, &now_ms()],
            )
            .await?;
        Ok(())
    }
}
