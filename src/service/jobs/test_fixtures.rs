//! Test-only: job records and table entries in a given state, shared by the unit tests of
//! the job manager's concepts.

use super::{Entry, JobRecord, JobState};
use crate::integrate::Progress;
use std::sync::Arc;

/// A job of 10 epochs, accepted at t = 1 s (Unix ms 1000), started once at 2 s; a final
/// one finished at 3 s with 4 epochs done.
pub fn record(state: JobState) -> JobRecord {
    JobRecord {
        id: "job-1".to_string(),
        state,
        epochs_total: 10,
        epochs_done: if state.is_final() { 4 } else { 0 },
        created_ms: 1_000,
        started_ms: (state != JobState::Queued).then_some(2_000),
        finished_ms: state.is_final().then_some(3_000),
        error: None,
        attempts: u32::from(state != JobState::Queued),
        idempotency: None,
        kind: Default::default(),
        evaluations: None,
    }
}

/// [`record`] in the live table, with a fresh progress counter.
pub fn entry(state: JobState) -> Entry {
    Entry {
        rec: record(state),
        progress: Arc::new(Progress::new()),
        evaluations: Default::default(),
    }
}
