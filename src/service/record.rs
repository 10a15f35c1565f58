//! What the service keeps of a job: its state and the record the store writes (the
//! request and the result are stored beside it as bytes). Shared by the jobs, which make
//! and update records, and the store, which keeps them across restarts.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Where a job is in its life.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "lowercase")]
pub enum JobState {
    Queued,
    Running,
    Done,
    Failed,
    Cancelled,
}

impl JobState {
    pub const ALL: [JobState; 5] = [
        JobState::Queued,
        JobState::Running,
        JobState::Done,
        JobState::Failed,
        JobState::Cancelled,
    ];

    /// Done, failed or cancelled: the job will not run again.
    pub fn is_final(self) -> bool {
        matches!(
            self,
            JobState::Done | JobState::Failed | JobState::Cancelled
        )
    }

    pub fn name(self) -> &'static str {
        match self {
            JobState::Queued => "queued",
            JobState::Running => "running",
            JobState::Done => "done",
            JobState::Failed => "failed",
            JobState::Cancelled => "cancelled",
        }
    }
}

/// What a job computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "kebab-case")]
pub enum JobKind {
    /// A light curve (`POST /v1/jobs`); records written before fit jobs existed are these.
    #[default]
    Lightcurve,
    /// A light-curve fit (`POST /v1/fits/lightcurve`).
    FitLightcurve,
}

impl JobKind {
    pub fn is_lightcurve(&self) -> bool {
        *self == JobKind::Lightcurve
    }
}

/// A fit job's light curves: evaluated (as of the record's last write) and the most it
/// may evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Evaluations {
    pub done: usize,
    pub max: usize,
}

/// A job as stored on disk (timestamps in Unix milliseconds).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct JobRecord {
    pub id: String,
    pub state: JobState,
    pub epochs_total: usize,
    pub epochs_done: usize,
    pub created_ms: i64,
    pub started_ms: Option<i64>,
    pub finished_ms: Option<i64>,
    pub error: Option<String>,
    /// How many times the job was started (more than 1 after a restart mid-run).
    pub attempts: u32,
    /// The client's `Idempotency-Key` at submission, and the SHA-256 (hex) of the body
    /// it came with: a retry with the same key finds this job instead of making another.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub idempotency: Option<(String, String)>,
    /// What the job computes (absent: a light curve, as every record before fit jobs).
    #[serde(default, skip_serializing_if = "JobKind::is_lightcurve")]
    pub kind: JobKind,
    /// A fit's light curves; its `epochs_total` is then the observed epochs times
    /// `evaluations.max`, the most it may compute.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub evaluations: Option<Evaluations>,
}

/// A submission's idempotency key with the SHA-256 of its body (lowercase hex): a retry
/// with the key and the same body replays the job, with another body it is refused.
pub fn idempotency(key: Option<String>, body: &[u8]) -> Option<(String, String)> {
    key.map(|k| {
        use sha2::Digest;
        let digest = sha2::Sha256::digest(body);
        let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
        (k, hex)
    })
}
