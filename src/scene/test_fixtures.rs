//! Test-only: a minimal valid request, and helpers that break one part of it and check
//! the result, shared by the unit tests of the request's checks.

use super::validate::{parse_request, validate, Limits, ValidationError};
use super::Scene;
use serde_json::{json, Value};

/// A minimal valid request: a 1 m square plate (two triangles, normal +z) of one
/// Lambertian material, lit and seen from 1000 km above it at one epoch.
pub fn minimal_request() -> Value {
    json!({
        "object": {
            "mesh": {
                "vertices": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
                "triangles": [[0, 1, 2], [0, 2, 3]]
            },
            "materials": [ { "name": "surface", "model": "lambert", "albedo": 0.5 } ]
        },
        "epochs": [ { "t": 0.0, "sun": [0.0, 0.0, 1.0], "observer": [0.0, 0.0, 1.0e6] } ]
    })
}

/// The minimal request after `edit`, parsed and checked within `limits`.
pub fn check_with(
    edit: impl FnOnce(&mut Value),
    limits: &Limits,
) -> Result<Scene, ValidationError> {
    let mut request = minimal_request();
    edit(&mut request);
    validate(&parse_request(&request.to_string())?, limits)
}

/// The minimal request after `edit`, checked without limits.
pub fn check(edit: impl FnOnce(&mut Value)) -> Result<Scene, ValidationError> {
    check_with(edit, &Limits::default())
}

/// Why the minimal request after `edit` is refused; panics if it is accepted.
pub fn refused(edit: impl FnOnce(&mut Value)) -> ValidationError {
    match check(edit) {
        Ok(_) => panic!("the request was accepted"),
        Err(e) => e,
    }
}

#[test]
fn the_minimal_request_is_valid() {
    let scene = check(|_| {}).expect("valid");
    assert_eq!(scene.mesh.triangles.len(), 2);
    assert_eq!(scene.epochs.len(), 1);
}
