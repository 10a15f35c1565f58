//! A chunk's lease: claimed (`FOR UPDATE SKIP LOCKED`) with its job marked running,
//! renewed every third of it while the chunk is computed, and released back to the
//! queue when this process stops.

use super::Workers;
use crate::integrate::Progress;
use crate::service::jobs::now_ms;
use crate::service::shared::{PgError, CHUNKS_CHANNEL};
use std::sync::Arc;

/// A claimed chunk.
#[derive(Debug, Clone)]
pub(super) struct Claimed {
    pub(super) job: String,
    pub(super) idx: i32,
    pub(super) first: usize,
    pub(super) epochs: usize,
}

impl Workers {
    /// Claims the first open chunk of the oldest active job (queued, or running under an
    /// expired lease), skipping those other workers hold locked; marks its job running.
    pub(super) async fn claim(&self, name: &str) -> Result<Option<Claimed>, PgError> {
        let mut client = self.cfg.pool.get().await?;
        let tx = client.transaction().await?;
        let row = tx
            .query_opt(
                "WITH next AS ( \
                   SELECT ch.job_id, ch.idx FROM glint_chunks ch \
                   JOIN glint_jobs j ON j.id = ch.job_id \
                   WHERE j.state IN ('queued', 'running') AND ch.state <> 'done' \
                     AND (ch.state = 'queued' OR ch.lease_until < now()) \
                   ORDER BY j.created_ms, j.id, ch.idx \
                   LIMIT 1 FOR UPDATE OF ch SKIP LOCKED) \
                 UPDATE glint_chunks u SET state = 'running', worker = $1, \
                   claims = u.claims + 1, lease_until = now() + make_interval(secs => $2) \
                 FROM next WHERE u.job_id = next.job_id AND u.idx = next.idx \
                 RETURNING u.job_id, u.idx, u.first_epoch, u.epochs",
                &[&name, &self.cfg.lease.as_secs_f64()],
            )
            .await?;
        let Some(row) = row else {
            tx.rollback().await?;
            return Ok(None);
        };
        let c = Claimed {
            job: row.get(0),
            idx: row.get(1),
            first: row.get::<_, i64>(2) as usize,
            epochs: row.get::<_, i64>(3) as usize,
        };
        tx.execute(
            "UPDATE glint_jobs SET state = 'running', started_ms = $2, attempts = attempts + 1 \
             WHERE id = $1 AND state = 'queued'",
            &[&c.job, &now_ms()],
        )
        .await?;
        tx.commit().await?;
        Ok(Some(c))
    }

    /// Renews the chunk's lease every third of it; stops the computation when the lease
    /// is no longer this worker's or the job is no longer active.
    pub(super) async fn renew(self: Arc<Self>, name: String, c: Claimed, progress: Arc<Progress>) {
        loop {
            tokio::time::sleep(self.cfg.lease / 3).await;
            let renewed = async {
                let client = self.cfg.pool.get().await?;
                let row = client
                    .query_opt(
                        "UPDATE glint_chunks c SET lease_until = now() + make_interval(secs => $4) \
                         FROM glint_jobs j WHERE c.job_id = $1 AND c.idx = $2 AND c.worker = $3 \
                         AND c.state = 'running' AND j.id = c.job_id \
                         AND j.state IN ('queued', 'running') RETURNING 1",
                        &[&c.job, &c.idx, &name, &self.cfg.lease.as_secs_f64()],
                    )
                    .await?;
                Ok::<_, PgError>(row.is_some())
            };
            match renewed.await {
                Ok(true) => {}
                Ok(false) => {
                    progress.cancel();
                    return;
                }
                // the database is away: compute on; the write decides
                Err(e) => tracing::warn!(job = c.job, chunk = c.idx, "renewing the lease: {e}"),
            }
        }
    }

    /// Gives a chunk this worker holds back to the queue, and wakes the others.
    pub(super) async fn release(&self, name: &str, c: &Claimed) -> Result<(), PgError> {
        let client = self.cfg.pool.get().await?;
        client
            .execute(
                "UPDATE glint_chunks SET state = 'queued', worker = NULL, lease_until = NULL \
                 WHERE job_id = $1 AND idx = $2 AND worker = $3 AND state = 'running'",
                &[&c.job, &c.idx, &name],
            )
            .await?;
        client
            .execute(&format!("NOTIFY {CHUNKS_CHANNEL}"), &[])
            .await?;
        Ok(())
    }
}
