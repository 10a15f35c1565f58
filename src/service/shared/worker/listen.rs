//! The listener, on its own connection: `LISTEN` for new chunks (the idle workers are
//! woken) and cancelled jobs (their chunks here are stopped), reconnecting with backoff.

use super::{Workers, FIRST_BACKOFF, MAX_BACKOFF};
use crate::service::shared::{PgError, CANCEL_CHANNEL, CHUNKS_CHANNEL};
use futures_util::StreamExt;
use std::sync::Arc;
use std::time::Duration;
use tokio_postgres::{AsyncMessage, NoTls};

impl Workers {
    /// Listens for new chunks (wakes the idle workers) and cancelled jobs (stops their
    /// chunks here), reconnecting with backoff; after each (re)connection the workers are
    /// woken, in case a notification was missed meanwhile.
    pub(super) async fn listen(self: Arc<Self>) {
        let mut backoff = FIRST_BACKOFF;
        while !self.stopping() {
            match self.listen_once().await {
                Ok(()) => backoff = FIRST_BACKOFF,
                Err(e) => {
                    tracing::warn!("job queue listener: {e}; reconnecting in {backoff:?}");
                    tokio::time::sleep(backoff).await;
                    backoff = (backoff * 2).min(MAX_BACKOFF);
                }
            }
        }
    }

    async fn listen_once(&self) -> Result<(), PgError> {
        let (client, mut conn) = self.cfg.database.connect(NoTls).await?;
        let (tx, mut rx) = tokio::sync::mpsc::unbounded_channel();
        let driver = tokio::spawn(async move {
            let mut messages = futures_util::stream::poll_fn(move |cx| conn.poll_message(cx));
            while let Some(m) = messages.next().await {
                match m {
                    Ok(AsyncMessage::Notification(n)) => {
                        if tx.send(n).is_err() {
                            return;
                        }
                    }
                    Ok(_) => {}
                    Err(e) => {
                        tracing::warn!("job queue listener connection: {e}");
                        return;
                    }
                }
            }
        });
        client
            .batch_execute(&format!("LISTEN {CHUNKS_CHANNEL}; LISTEN {CANCEL_CHANNEL}"))
            .await?;
        self.wake.notify_waiters();
        loop {
            tokio::select! {
                n = rx.recv() => match n {
                    Some(n) if n.channel() == CANCEL_CHANNEL => {
                        for ((job, _), p) in self.lock_running().iter() {
                            if job == n.payload() {
                                p.cancel();
                            }
                        }
                    }
                    Some(_) => self.wake.notify_waiters(),
                    None => break,
                },
                _ = tokio::time::sleep(Duration::from_millis(500)) => {
                    if self.stopping() {
                        break;
                    }
                }
            }
        }
        drop(client);
        let _ = driver.await;
        Ok(())
    }
}
