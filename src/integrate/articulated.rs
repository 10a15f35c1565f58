//! Articulated meshes: each epoch's pose, and the engine run once per pose.
//!
//! ```text
//! epochs ──angles per hinge (law: Sun, fixed, series)──▶ groups of identical angles
//! each group (rayon): reference mesh posed ──▶ Prepared (faces, convexity, silhouettes)
//!                     ──▶ its epochs evaluated as a rigid mesh's
//! ```
//!
//! A pose is a rigid mesh, prepared as any: shadows cast and received follow the parts.
//! Epochs whose angles are identical (bit for bit: `fixed` hinges, a series held
//! constant) share one preparation; a Sun-tracking array, whose angle changes every
//! epoch, prepares every epoch anew.

use super::{eq12, evaluate_epochs, methods, Cancelled, Prepared, PreparedInfo, Progress};
use crate::geometry::articulation::Articulation;
use crate::geometry::Mesh;
use crate::scene::response::Thumbnail;
use crate::scene::{EpochResult, Scene};
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::AtomicU64;

/// The epochs grouped by their hinge angles: (angles, epoch indices), in order of each
/// group's first epoch.
pub fn poses(scene: &Scene, a: &Articulation) -> Vec<(Vec<f64>, Vec<usize>)> {
    let angles: Vec<Vec<f64>> = scene
        .epochs
        .par_iter()
        .map(|e| a.angles(e.t, e.sun))
        .collect();
    let mut index: HashMap<Vec<u64>, usize> = HashMap::new();
    let mut groups: Vec<(Vec<f64>, Vec<usize>)> = Vec::new();
    for (i, angle) in angles.into_iter().enumerate() {
        let key: Vec<u64> = angle.iter().map(|x| x.to_bits()).collect();
        match index.get(&key) {
            Some(&g) => groups[g].1.push(i),
            None => {
                index.insert(key, groups.len());
                groups.push((angle, vec![i]));
            }
        }
    }
    groups
}

/// `scene` with its mesh posed at `angles` (and refined for `centroid`), without its
/// epochs, thumbnails or articulation: what one pose's preparation needs.
pub fn posed(scene: &Scene, a: &Articulation, angles: &[f64]) -> Scene {
    let mesh = Mesh {
        vertices: a.pose(&scene.mesh.vertices, angles),
        triangles: scene.mesh.triangles.clone(),
        material_ids: scene.mesh.material_ids.clone(),
    };
    let s = Scene {
        mesh,
        materials: scene.materials.clone(),
        epochs: Vec::new(),
        illumination: scene.illumination,
        tolerance: scene.tolerance,
        method: scene.method,
        image_size: scene.image_size,
        image_samples: scene.image_samples,
        centroid_subdivisions: scene.centroid_subdivisions,
        thumbnails: None,
        clip_shadows: scene.clip_shadows,
        sky: Vec::new(),
        warnings: Vec::new(),
        observation: None,
        spectral: Vec::new(),
        articulation: None,
    };
    methods::refined_for_centroid(&s).unwrap_or(s)
}

/// One pose's epochs (index, result) and, for the first pose, its preparation's summary.
type PoseResults = (Vec<(usize, Option<EpochResult>)>, Option<PreparedInfo>);

type Evaluated = (
    Vec<Option<EpochResult>>,
    PreparedInfo,
    Option<Vec<Thumbnail>>,
);

/// The light curve of an articulated scene: every pose prepared and its epochs evaluated;
/// the summary's faces and method those of the first epoch's pose.
pub fn simulate(
    scene: &Scene,
    a: &Articulation,
    lightings: &[eq12::Lighting],
    progress: &Progress,
    rays: &AtomicU64,
) -> Result<Evaluated, Cancelled> {
    let groups = poses(scene, a);
    let per_group: Vec<PoseResults> = groups
        .par_iter()
        .enumerate()
        .map(|(g, (angles, which))| {
            if progress.is_cancelled() {
                return (Vec::new(), None);
            }
            let s = posed(scene, a, angles);
            let prepared = Prepared::new(&s);
            let results =
                evaluate_epochs(&prepared, lightings, &scene.epochs, which, progress, rays);
            let info = (g == 0).then(|| PreparedInfo::of(&prepared));
            (which.iter().copied().zip(results).collect(), info)
        })
        .collect();
    if progress.is_cancelled() {
        return Err(Cancelled);
    }
    let mut epochs: Vec<Option<EpochResult>> = vec![None; scene.epochs.len()];
    let mut info = None;
    for (results, i) in per_group {
        for (k, r) in results {
            epochs[k] = r;
        }
        info = info.or(i);
    }
    let mut info = info.ok_or(Cancelled)?;
    info.method = format!(
        "{}; articulated: {} hinge(s), {} pose(s) for {} epoch(s), each pose prepared \
         as a rigid mesh",
        info.method,
        a.joints.len(),
        groups.len(),
        scene.epochs.len()
    );
    let thumbnails = match &scene.thumbnails {
        None => None,
        Some(spec) => Some(thumbnails(scene, a, spec, progress)?),
    };
    Ok((epochs, info, thumbnails))
}

/// The requested thumbnails, each epoch rendered in its own pose.
fn thumbnails(
    scene: &Scene,
    a: &Articulation,
    spec: &crate::scene::Thumbnails,
    progress: &Progress,
) -> Result<Vec<Thumbnail>, Cancelled> {
    let cancelled = || progress.is_cancelled();
    let images = spec
        .epochs
        .par_iter()
        .map(|&i| {
            let epoch = &scene.epochs[i];
            let s = posed(scene, a, &a.angles(epoch.t, epoch.sun));
            crate::render::Renderer::new(&s).render_until(
                epoch,
                spec.size,
                spec.samples,
                &cancelled,
            )
        })
        .collect::<Option<Vec<_>>>()
        .ok_or(Cancelled)?;
    let times: Vec<f64> = spec.epochs.iter().map(|&i| scene.epochs[i].t).collect();
    Ok(crate::render::encode(spec, &images, &times))
}
