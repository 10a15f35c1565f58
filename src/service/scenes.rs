//! The built-in objects and the example requests of `scenes/`, compiled into the binary
//! so the service needs no files beside it.

use crate::geometry::builtin::BUILTINS;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;
use utoipa::ToSchema;

/// Example requests shipped in `scenes/`, by name.
const EXAMPLES: &[(&str, &str)] = &[
    ("box-wing", include_str!("../../scenes/box-wing.json")),
    ("sphere", include_str!("../../scenes/sphere.json")),
    ("plate", include_str!("../../scenes/plate.json")),
    ("rocket-body", include_str!("../../scenes/rocket-body.json")),
    ("fragment", include_str!("../../scenes/fragment.json")),
    ("dish-sat", include_str!("../../scenes/dish-sat.json")),
    ("cubesat", include_str!("../../scenes/cubesat.json")),
    (
        "box-wing-tumbling",
        include_str!("../../scenes/box-wing-tumbling.json"),
    ),
    // requests by `geometry` (a TLE, a site, a window, an attitude law)
    ("iss-pass", include_str!("../../scenes/iss-pass.json")),
    ("geo-night", include_str!("../../scenes/geo-night.json")),
    (
        "rocket-body-tumbling-pass",
        include_str!("../../scenes/rocket-body-tumbling-pass.json"),
    ),
    (
        "box-wing-sun-tracking-pass",
        include_str!("../../scenes/box-wing-sun-tracking-pass.json"),
    ),
    ("iss-pass-v", include_str!("../../scenes/iss-pass-v.json")),
    // a tangle of sheets that shadow each other: the methods' hard case
    ("hard", include_str!("../../scenes/hard.json")),
];

/// A built-in object and its example request.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema, PartialEq)]
pub struct SceneSummary {
    /// Name, for `{"mesh": {"builtin": name}}` and `GET /v1/scenes/{name}`.
    pub name: String,
    /// What the object is (sizes in metres).
    pub description: String,
    /// Triangles in the mesh at its default detail (0 when the scene is only an example
    /// request).
    pub triangles: usize,
    /// Material names the mesh uses, in material-id order; a request's `materials` must
    /// name them.
    pub materials: Vec<String>,
    /// Epochs in the example request, when there is one.
    pub example_epochs: Option<usize>,
    /// Where to fetch the example request.
    pub example_url: Option<String>,
}

/// The example request called `name`, as JSON text.
pub fn example(name: &str) -> Option<&'static str> {
    EXAMPLES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

fn epochs_in(text: &str) -> Option<usize> {
    let v: serde_json::Value = serde_json::from_str(text).ok()?;
    v.get("epochs")?.as_array().map(Vec::len)
}

/// Every built-in object, then the example requests without an object of their name.
pub fn summaries() -> &'static [SceneSummary] {
    static CELL: OnceLock<Vec<SceneSummary>> = OnceLock::new();
    CELL.get_or_init(|| {
        let mut v: Vec<SceneSummary> = BUILTINS
            .iter()
            .map(|b| {
                let ex = example(b.name);
                SceneSummary {
                    name: b.name.to_string(),
                    description: b
                        .description
                        .split_whitespace()
                        .collect::<Vec<_>>()
                        .join(" "),
                    triangles: b.mesh().triangles.len(),
                    materials: b.material_names.iter().map(|s| s.to_string()).collect(),
                    example_epochs: ex.and_then(epochs_in),
                    example_url: ex.map(|_| format!("/v1/scenes/{}", b.name)),
                }
            })
            .collect();
        for (name, text) in EXAMPLES {
            if !v.iter().any(|s| s.name == *name) {
                v.push(SceneSummary {
                    name: name.to_string(),
                    description: if text.contains("\"geometry\"") {
                        "example request by geometry (TLE, site, time window, attitude law)"
                    } else {
                        "example request"
                    }
                    .to_string(),
                    triangles: 0,
                    materials: Vec::new(),
                    example_epochs: epochs_in(text),
                    example_url: Some(format!("/v1/scenes/{name}")),
                });
            }
        }
        v
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every request in `scenes/` is served by `GET /v1/scenes/{name}` under its file's
    /// name, listed with its URL, and is a valid request.
    #[test]
    fn every_example_in_scenes_is_listed() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let mut names = Vec::new();
        for entry in std::fs::read_dir(dir).expect("scenes/") {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "json") {
                let name = path.file_stem().unwrap().to_string_lossy().to_string();
                let text = std::fs::read_to_string(&path).expect("readable");
                assert_eq!(example(&name), Some(text.as_str()), "{name} is not served");
                let listed = summaries().iter().find(|s| s.name == name);
                let url = listed.and_then(|s| s.example_url.clone());
                assert_eq!(
                    url,
                    Some(format!("/v1/scenes/{name}")),
                    "{name} is not listed"
                );
                crate::Scene::from_json(&text, &crate::Limits::unlimited())
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                names.push(name);
            }
        }
        assert!(names.len() >= 14, "{names:?}");
    }
}
