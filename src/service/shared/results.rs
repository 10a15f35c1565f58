//! A done job's result on the shared queue: its chunks' results read in epoch order and
//! assembled, served as JSON or CSV, or one of its images.

use super::rows::{kind_of, state_of};
use super::{chunks, PgError, Shared};
use crate::service::errors::ApiError;
use crate::service::jobs::{no_such_job, JobKind, JobState};
use crate::service::store::Form;
use crate::service::threads::run_blocking;

impl Shared {
    /// A done job's chunks' results in epoch order, and what it computes; 404 / 409 when
    /// it has none.
    async fn parts(&self, id: &str) -> Result<(JobKind, Vec<Vec<u8>>), ApiError> {
        let client = self.pool.get().await.map_err(PgError::from)?;
        let row = client
            .query_opt("SELECT kind, state FROM glint_jobs WHERE id = $1", &[&id])
            .await
            .map_err(PgError::from)?
            .ok_or_else(|| no_such_job(id))?;
        let kind = kind_of(row.get(0))?;
        let state = state_of(row.get(1))?;
        if state != JobState::Done {
            return Err(ApiError::conflict(format!(
                "job is {}, there is no result{}",
                state.name(),
                if state.is_final() { "" } else { " yet" }
            )));
        }
        let rows = client
            .query(
                "SELECT data FROM glint_results WHERE job_id = $1 ORDER BY idx",
                &[&id],
            )
            .await
            .map_err(PgError::from)?;
        Ok((kind, rows.into_iter().map(|r| r.get(0)).collect()))
    }

    /// A done job's result in `form`, assembled from its chunks in epoch order (a fit's
    /// is its one chunk's JSON; it has no CSV, which the route refuses).
    pub async fn result(&self, id: &str, form: Form) -> Result<(JobKind, Vec<u8>), ApiError> {
        let (kind, parts) = self.parts(id).await?;
        if kind == JobKind::FitLightcurve {
            return Ok((kind, parts.into_iter().next().unwrap_or_default()));
        }
        let bytes = run_blocking("assembling the result", move || {
            let resp = assemble(parts)?;
            Ok::<_, ApiError>(match form {
                Form::Json => serde_json::to_vec(&resp).map_err(ApiError::internal)?,
                Form::Csv => crate::report::csv::to_csv(&resp).into_bytes(),
            })
        })
        .await??;
        Ok((kind, bytes))
    }

    /// The PNG of a done job's thumbnail of `epoch`.
    pub async fn thumbnail(&self, id: &str, epoch: usize) -> Result<Vec<u8>, ApiError> {
        let (kind, parts) = self.parts(id).await?;
        if kind == JobKind::FitLightcurve {
            return Err(ApiError::not_found("a fit job renders no images").with_field("epoch"));
        }
        let none = move || {
            ApiError::not_found(format!("the job has no image for epoch {epoch}"))
                .with_field("epoch")
        };
        run_blocking("reading the image", move || {
            let resp = assemble(parts)?;
            let t = resp
                .thumbnails
                .iter()
                .flatten()
                .find(|t| t.epoch == epoch)
                .ok_or_else(none)?;
            use base64::Engine as _;
            base64::engine::general_purpose::STANDARD
                .decode(t.png_base64.as_bytes())
                .map_err(ApiError::internal)
        })
        .await?
    }
}

/// A light curve's chunk results parsed and joined in order.
fn assemble(parts: Vec<Vec<u8>>) -> Result<crate::scene::Response, ApiError> {
    let parsed: Result<Vec<crate::scene::Response>, _> =
        parts.iter().map(|p| serde_json::from_slice(p)).collect();
    let parsed = parsed.map_err(|e| ApiError::from(PgError::Corrupt(e.to_string())))?;
    chunks::assemble(parsed)
        .ok_or_else(|| ApiError::from(PgError::Corrupt("a done job without results".into())))
}
