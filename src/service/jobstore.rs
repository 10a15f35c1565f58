//! The seam between the HTTP routes and where jobs live: the embedded redb store (one
//! process owns its file; the default) or a PostgreSQL queue that any number of
//! `glint serve` and `glint worker` processes share. The routes see one API either way.

use super::errors::ApiError;
use super::jobs::{Deleted, JobKind, JobState, JobStatus, Jobs};
use super::shared::Shared;
use super::store::{Form, Store};
use std::collections::HashMap;
use std::sync::Arc;
use std::time::Duration;

/// Where the service keeps its jobs.
#[derive(Clone)]
pub enum JobStore {
    /// The embedded redb database in `--data-dir`, run by this process alone.
    Embedded { jobs: Arc<Jobs>, store: Arc<Store> },
    /// A PostgreSQL queue (`--database-url`), shared by every process pointed at it.
    Shared(Arc<Shared>),
}

/// A finished job's result, as the route sends it.
pub enum ResultBody {
    /// Streamed from the embedded store a chunk at a time, with its length.
    Stream {
        len: u64,
        stream: std::pin::Pin<
            Box<dyn futures_util::Stream<Item = std::io::Result<axum::body::Bytes>> + Send>,
        >,
    },
    /// Assembled in memory from the chunks' rows, in epoch order.
    Whole(Vec<u8>),
}

impl JobStore {
    /// Stores a new light-curve job (see [`Jobs::submit`]).
    pub async fn submit(
        &self,
        body: axum::body::Bytes,
        key: Option<String>,
    ) -> Result<(JobStatus, bool), ApiError> {
        match self {
            JobStore::Embedded { jobs, .. } => jobs.submit(body, key).await,
            JobStore::Shared(s) => s.submit(JobKind::Lightcurve, body, key).await,
        }
    }

    /// Stores a new light-curve fit job (see [`Jobs::submit_fit`]).
    pub async fn submit_fit(
        &self,
        body: axum::body::Bytes,
        key: Option<String>,
    ) -> Result<(JobStatus, bool), ApiError> {
        match self {
            JobStore::Embedded { jobs, .. } => jobs.submit_fit(body, key).await,
            JobStore::Shared(s) => s.submit(JobKind::FitLightcurve, body, key).await,
        }
    }

    /// One job's status; `Ok(None)` when there is no such job.
    pub async fn status(&self, id: &str) -> Result<Option<JobStatus>, ApiError> {
        match self {
            JobStore::Embedded { jobs, .. } => Ok(jobs.status(id)),
            JobStore::Shared(s) => s.status(id).await,
        }
    }

    /// The most recent jobs, newest first.
    pub async fn list(
        &self,
        limit: usize,
        state: Option<JobState>,
    ) -> Result<Vec<JobStatus>, ApiError> {
        match self {
            JobStore::Embedded { jobs, .. } => Ok(jobs.list(limit, state)),
            JobStore::Shared(s) => s.list(limit, state).await,
        }
    }

    /// Jobs in each state (for `/metrics`).
    pub async fn counts(&self) -> Result<HashMap<JobState, usize>, ApiError> {
        match self {
            JobStore::Embedded { jobs, .. } => Ok(jobs.counts()),
            JobStore::Shared(s) => s.counts().await,
        }
    }

    /// Cancels a queued or running job, or removes a finished one.
    pub async fn delete(&self, id: &str) -> Result<Deleted, ApiError> {
        match self {
            JobStore::Embedded { jobs, .. } => jobs.delete(id).await,
            JobStore::Shared(s) => s.delete(id).await,
        }
    }

    /// A finished job's result in `form` and what the job computes; 404 / 409 when it
    /// has none.
    pub async fn result(&self, id: &str, form: Form) -> Result<(JobKind, ResultBody), ApiError> {
        match self {
            JobStore::Embedded { jobs, .. } => {
                let len = jobs.result_len(id, form).await?;
                let kind = jobs.kind(id).ok_or_else(|| super::jobs::no_such_job(id))?;
                let stream = Box::pin(jobs.result_stream(id, form, len));
                Ok((kind, ResultBody::Stream { len, stream }))
            }
            JobStore::Shared(s) => {
                let (kind, bytes) = s.result(id, form).await?;
                Ok((kind, ResultBody::Whole(bytes)))
            }
        }
    }

    /// The PNG of a finished job's thumbnail of `epoch`.
    pub async fn thumbnail(&self, id: &str, epoch: usize) -> Result<Vec<u8>, ApiError> {
        match self {
            JobStore::Embedded { jobs, .. } => jobs.thumbnail(id, epoch).await,
            JobStore::Shared(s) => s.thumbnail(id, epoch).await,
        }
    }

    /// Whether the service is shutting down (new jobs refused, `/readyz` says so).
    pub fn is_shutting_down(&self) -> bool {
        match self {
            JobStore::Embedded { jobs, .. } => jobs.is_shutting_down(),
            JobStore::Shared(s) => s.is_shutting_down(),
        }
    }

    /// Whether the store can be read and written now (for `/readyz`); the reason if not.
    pub async fn check(&self) -> Result<(), String> {
        match self {
            JobStore::Embedded { store, .. } => {
                let store = store.clone();
                match tokio::task::spawn_blocking(move || store.check()).await {
                    Ok(Ok(())) => Ok(()),
                    Ok(Err(e)) => Err(e.to_string()),
                    Err(e) => Err(e.to_string()),
                }
            }
            JobStore::Shared(s) => s.check().await.map_err(|e| e.to_string()),
        }
    }

    /// Stops taking jobs and stops the running ones (they run again later: on the next
    /// start for the embedded store, on any worker for the shared one).
    pub async fn shutdown(&self, grace: Duration) {
        match self {
            JobStore::Embedded { jobs, .. } => jobs.shutdown(grace).await,
            JobStore::Shared(s) => s.shutdown(grace).await,
        }
    }
}
