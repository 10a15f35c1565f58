//! Expiry: finished jobs and their results are removed once older than the time to live,
//! at start and then every quarter of it (between 1 s and 1 min).

use super::now_ms;
use super::Jobs;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Duration;

impl Jobs {
    /// Removes finished jobs older than the time to live.
    pub(super) fn sweep(&self) {
        let cutoff = now_ms().saturating_sub(self.ttl.as_millis() as i64);
        let expired: Vec<String> = self
            .table()
            .values()
            .filter(|e| e.rec.state.is_final() && e.rec.finished_ms.is_some_and(|f| f <= cutoff))
            .map(|e| e.rec.id.clone())
            .collect();
        for id in expired {
            let _ = self.remove(&id);
        }
    }

    /// Sweeps every quarter of the time to live (between 1 s and 1 min) until shutdown.
    pub(super) async fn sweeper(self: Arc<Self>) {
        let every = (self.ttl / 4).clamp(Duration::from_secs(1), Duration::from_secs(60));
        loop {
            tokio::time::sleep(every).await;
            if self.shutting_down.load(Ordering::SeqCst) {
                return;
            }
            let me = self.clone();
            let _ = tokio::task::spawn_blocking(move || me.sweep()).await;
        }
    }
}
