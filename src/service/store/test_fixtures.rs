//! Test-only fixtures shared by the store's tests: a finished job's record, a light
//! curve with thumbnails, a fresh directory.

use crate::scene::Response;
use crate::service::record::{JobKind, JobRecord, JobState};
use std::path::PathBuf;

pub(super) fn done_record(id: &str) -> JobRecord {
    JobRecord {
        id: id.to_string(),
        state: JobState::Done,
        epochs_total: 0,
        epochs_done: 0,
        created_ms: 1,
        started_ms: Some(2),
        finished_ms: Some(3),
        error: None,
        attempts: 1,
        idempotency: None,
        kind: JobKind::Lightcurve,
        evaluations: None,
    }
}

/// A light curve of `n` epochs with two thumbnails: over a megabyte of JSON at 4000.
pub(super) fn response(n: usize) -> Response {
    let mut req = crate::service::routes::example_request();
    let epochs = req["epochs"].as_array().unwrap().clone();
    req["epochs"] = epochs.iter().cycle().take(n).cloned().collect();
    req["thumbnails"] = serde_json::json!({ "size": 8, "samples": 1, "epochs": [0, 1] });
    let scene =
        crate::Scene::from_json(&req.to_string(), &crate::scene::Limits::unlimited()).unwrap();
    crate::simulate(&scene)
}

pub(super) fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("glint-store-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}
