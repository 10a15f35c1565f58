//! The integration methods side by side: their fidelity settings, the `centroid`
//! method's mesh refinement, and the measurement behind `glint tradeoff` (error per
//! epoch against a converged reference, and time per epoch).
//!
//! | method     | fidelity setting                          | cost grows with          |
//! |------------|-------------------------------------------|--------------------------|
//! | `silhouette` | none: exact                             | faces, and shadow lines  |
//! | `adaptive` | `tolerance` (relative)                    | partly shadowed faces    |
//! | `auto`     | none (convex: no rays; else silhouette)   | as silhouette, or faces  |
//! | `centroid` | `centroid_subdivisions` k (4^k triangles) | triangles × 4^k          |
//! | `image`    | `image_size` × `image_samples`            | pixels × samples²        |
//! | `convex`   | none                                      | faces                    |

use super::simulate;
use crate::scene::{Method, Scene};
use std::time::Instant;

/// The mesh with every triangle split into four (at its edge midpoints) `k` times:
/// 4^k triangles per triangle, same surface, same materials, same winding.
pub use crate::geometry::builtin::subdivide;

/// The scene the `centroid` method actually samples: its mesh subdivided
/// `centroid_subdivisions` times; `None` when there is nothing to refine.
pub fn refined_for_centroid(scene: &Scene) -> Option<Scene> {
    (scene.method == Method::Centroid && scene.centroid_subdivisions > 0).then(|| Scene {
        mesh: subdivide(&scene.mesh, scene.centroid_subdivisions),
        ..scene.clone()
    })
}

/// One method at one fidelity setting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Setting {
    Adaptive {
        tolerance: f64,
    },
    Auto {
        tolerance: f64,
    },
    Centroid {
        subdivisions: u32,
    },
    /// `adaptive` with every partly shadowed face sampled by rays to the tolerance
    /// instead of clipped exactly (the engine's fallback, charted on its own).
    Sampled {
        tolerance: f64,
    },
    /// Pixels on a side, samples per pixel side.
    Image {
        size: u32,
        samples: u32,
    },
    Convex,
}

impl Setting {
    pub fn method(&self) -> Method {
        match self {
            Setting::Adaptive { .. } | Setting::Sampled { .. } => Method::Adaptive,
            Setting::Auto { .. } => Method::Auto,
            Setting::Centroid { .. } => Method::Centroid,
            Setting::Image { .. } => Method::Image,
            Setting::Convex => Method::Convex,
        }
    }

    /// The line this setting belongs to on the chart: the method's name, or `sampled`.
    pub fn name(&self) -> &'static str {
        match self {
            Setting::Sampled { .. } => "sampled",
            s => s.method().name(),
        }
    }

    /// The setting as the request would say it, e.g. `tolerance 1e-3`, `256 px × 4²`.
    pub fn label(&self) -> String {
        match self {
            Setting::Adaptive { tolerance }
            | Setting::Auto { tolerance }
            | Setting::Sampled { tolerance } => {
                format!("tolerance {tolerance:e}")
            }
            Setting::Centroid { subdivisions } => format!("subdivisions {subdivisions}"),
            Setting::Image { size, samples } => format!("{size} px x {samples}x{samples}"),
            Setting::Convex => "-".to_string(),
        }
    }

    /// `base` with this method and setting.
    pub fn apply(&self, base: &Scene) -> Scene {
        let mut s = base.clone();
        s.method = self.method();
        match *self {
            Setting::Adaptive { tolerance } | Setting::Auto { tolerance } => {
                s.tolerance = tolerance
            }
            Setting::Sampled { tolerance } => {
                s.tolerance = tolerance;
                s.clip_shadows = false;
            }
            Setting::Centroid { subdivisions } => s.centroid_subdivisions = subdivisions,
            Setting::Image { size, samples } => {
                s.image_size = size;
                s.image_samples = samples;
            }
            Setting::Convex => {}
        }
        s
    }
}

/// The default sweep of `glint tradeoff`: each method over a range of its setting,
/// cheapest first. `quick` trims the slowest settings.
pub fn default_sweep(quick: bool) -> Vec<Setting> {
    let mut v = Vec::new();
    for t in [1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4] {
        v.push(Setting::Adaptive { tolerance: t });
    }
    for t in [1e-1, 1e-2, 1e-3, 1e-4] {
        v.push(Setting::Auto { tolerance: t });
    }
    for t in [1e-1, 1e-2, 1e-3, 1e-4] {
        v.push(Setting::Sampled { tolerance: t });
    }
    for k in 0..=if quick { 2 } else { 3 } {
        v.push(Setting::Centroid { subdivisions: k });
    }
    let images: &[(u32, u32)] = if quick {
        &[(32, 1), (64, 1), (128, 1)]
    } else {
        &[(32, 1), (64, 1), (128, 1), (256, 1), (256, 2), (512, 2)]
    };
    for &(size, samples) in images {
        v.push(Setting::Image { size, samples });
    }
    v.push(Setting::Convex);
    v
}

/// Relative error of each epoch of `values` against `reference` (W/m²): |E − E_ref| over
/// max(E_ref, floor · median E_ref), so epochs where the object is nearly dark (eclipse)
/// count against the curve's typical level instead of dividing by almost nothing. The
/// median, not the maximum: a glint can be 1e5 times the rest of the curve, and measuring
/// every other epoch against it would hide their errors.
pub fn relative_errors(values: &[f64], reference: &[f64], floor: f64) -> Vec<f64> {
    let mut sorted: Vec<f64> = reference.to_vec();
    sorted.sort_by(f64::total_cmp);
    let scale = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
    values
        .iter()
        .zip(reference)
        .map(|(v, r)| {
            let denom = r.max(floor * scale);
            if denom > 0.0 {
                (v - r).abs() / denom
            } else if *v == 0.0 {
                0.0
            } else {
                1.0
            }
        })
        .collect()
}

/// Darker epochs than this fraction of the median epoch are measured against it.
pub const ERROR_FLOOR: f64 = 1e-3;

/// One run of one setting: its light curve and what it cost.
#[derive(Debug, Clone)]
pub struct Run {
    pub setting: Setting,
    /// Irradiance per epoch, W/m².
    pub irradiance: Vec<f64>,
    /// Wall-clock time per epoch, ms (best of the repeats, whole `simulate` call).
    pub ms_per_epoch: f64,
    /// Rays cast over all epochs.
    pub rays: u64,
    /// `summary.method` of the run.
    pub method: String,
}

/// Runs `setting` on `base`, repeating short runs so the time is not just noise (at
/// least `min_seconds` of total work or 5 repeats, whichever comes first; the best time).
pub fn run(base: &Scene, setting: Setting, min_seconds: f64) -> Run {
    let scene = setting.apply(base);
    let mut best = f64::INFINITY;
    let mut spent = 0.0;
    let mut out = None;
    for _ in 0..5 {
        let t0 = Instant::now();
        let r = simulate(&scene);
        let dt = t0.elapsed().as_secs_f64();
        best = best.min(dt);
        spent += dt;
        out = Some(r);
        if spent >= min_seconds {
            break;
        }
    }
    let r = out.expect("at least one run");
    Run {
        setting,
        irradiance: r.epochs.iter().map(|e| e.irradiance_w_m2).collect(),
        ms_per_epoch: best * 1e3 / scene.epochs.len().max(1) as f64,
        rays: r.summary.rays,
        method: r.summary.method,
    }
}

/// Error summary of a run against a reference curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Errors {
    pub max: f64,
    pub rms: f64,
}

/// Max and RMS over epochs of [`relative_errors`] with [`ERROR_FLOOR`].
pub fn errors(values: &[f64], reference: &[f64]) -> Errors {
    let e = relative_errors(values, reference, ERROR_FLOOR);
    let n = e.len().max(1) as f64;
    Errors {
        max: e.iter().copied().fold(0.0, f64::max),
        rms: (e.iter().map(|x| x * x).sum::<f64>() / n).sqrt(),
    }
}
