//! Articulated meshes: each epoch's pose, and the engine run once per pose.
//!
//! ```text
//! epochs ──angles per hinge (law: Sun, fixed, series)──▶ groups of identical angles
//! once: Shared (faces merged within each part, silhouettes' structure per part)
//! each group (rayon): mesh posed ──▶ Prepared (Shared moved, contacts across parts,
//!                     rays)  ──▶ its epochs evaluated as a rigid mesh's
//! ```
//!
//! A pose is a rigid mesh: shadows cast and received follow the parts. Epochs whose
//! angles are identical (bit for bit: `fixed` hinges, a series held constant) share one
//! preparation; a Sun-tracking array, whose angle changes every epoch, prepares every
//! epoch anew. What moves as one (the body, each link: a *group*) keeps its faces and
//! its silhouettes' structure from pose to pose, so these are built once ([`Shared`])
//! and each pose only moves them and finds what crosses groups (contacts between a
//! link and the body); a pose in which two groups share a vertex (a hinge welded to
//! its parent along its line) is prepared whole, as a rigid mesh.

use super::silhouettes::posed::Reference;
use super::{
    eq12, evaluate_epochs, methods, Cancelled, Occlusion, Prepared, PreparedInfo, Progress,
};
use crate::geometry::articulation::{Articulation, Motion, BODY};
use crate::geometry::{convex, Faces, Mesh};
use crate::scene::response::Thumbnail;
use crate::scene::{EpochResult, Method, Scene};
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
        rounding: scene.mesh.rounding,
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

/// What every pose of an articulated scene shares, built once in the reference pose:
/// the faces merged within each group, and the silhouettes' structure of each group.
pub struct Shared {
    /// The reference pose's faces, merged within groups and in spatial order.
    faces: Faces,
    /// Per vertex and per face: its group (0 the body, 1 + j joint j's link).
    group_of_vertex: Vec<u32>,
    group_of_face: Vec<u32>,
    /// Some group by itself lets one face shadow another (it is not planar, or with
    /// one-sided faces not convex): then so does every pose.
    never_convex: bool,
    /// `None` for the `convex` method (no shadows asked for).
    silhouettes: Option<Reference>,
}

impl Shared {
    /// `None` when the scene's method prepares per face or per pixel (`adaptive`,
    /// `centroid`, `image`): those prepare each pose whole.
    pub fn build(scene: &Scene, a: &Articulation) -> Option<Shared> {
        if !matches!(
            scene.method,
            Method::Auto | Method::Silhouette | Method::Convex
        ) {
            return None;
        }
        let mesh = &scene.mesh;
        let group_of_vertex: Vec<u32> = a
            .link
            .iter()
            .map(|&l| if l == BODY { 0 } else { l + 1 })
            .collect();
        let group_of_tri: Vec<u32> = mesh
            .triangles
            .iter()
            .map(|t| group_of_vertex[t[0] as usize])
            .collect();
        let mut faces = Faces::build_within(mesh, true, Some(&group_of_vertex));
        faces.sort_spatially();
        let group_of_face: Vec<u32> = faces
            .faces
            .iter()
            .map(|f| group_of_tri[f.triangles[0] as usize])
            .collect();
        let groups = a.joints.len() + 1;
        let never_convex = never_convex(scene, &faces, &group_of_tri, groups);
        let silhouettes = (scene.method != Method::Convex)
            .then(|| Reference::build(scene, &faces, &group_of_tri, groups));
        Some(Shared {
            faces,
            group_of_vertex,
            group_of_face,
            never_convex,
            silhouettes,
        })
    }

    /// The preparation of `posed` (the scene posed at `angles`, [`posed`]) from the
    /// shared structure; `None` when two groups share a vertex in this pose.
    pub fn prepare<'s>(
        &self,
        posed: &'s Scene,
        a: &Articulation,
        angles: &[f64],
    ) -> Option<Prepared<'s>> {
        if !groups_apart(&posed.mesh.vertices, &self.group_of_vertex) {
            return None;
        }
        let mut motions = vec![Motion::IDENTITY];
        motions.extend(a.motions_at(angles));
        let motion = |f: usize| motions[self.group_of_face[f] as usize];
        let faces = self
            .faces
            .moved(motion, |m| posed.materials[m as usize].tangent);
        let convex = !self.never_convex && super::is_convex(posed, &faces);
        let shadows =
            posed.method == Method::Silhouette || (posed.method == Method::Auto && !convex);
        let occlusion = match &self.silhouettes {
            Some(r) if shadows => {
                Occlusion::Silhouettes(Box::new(r.pose(&posed.mesh, &faces, &motions)))
            }
            _ => Occlusion::None,
        };
        Some(Prepared::from_parts(posed, faces, convex, occlusion))
    }
}

/// Does some group by itself let one face shadow another, whatever the pose? With a
/// two-sided face: its triangles are not in one plane; else a vertex of it lies in front
/// of one of its faces (tested while faces × vertices stays small).
fn never_convex(scene: &Scene, faces: &Faces, group_of_tri: &[u32], groups: usize) -> bool {
    let mesh = &scene.mesh;
    let two_sided = faces
        .faces
        .iter()
        .any(|f| scene.materials[f.material as usize].two_sided);
    let tol = mesh.tolerance();
    (0..groups as u32).any(|g| {
        let of_group = |t: &usize| group_of_tri[*t] == g;
        let tris: Vec<usize> = (0..mesh.triangles.len()).filter(of_group).collect();
        if two_sided {
            let part = Mesh {
                vertices: mesh.vertices.clone(),
                triangles: tris.iter().map(|&t| mesh.triangles[t]).collect(),
                material_ids: tris.iter().map(|&t| mesh.material_ids[t]).collect(),
                rounding: mesh.rounding,
            };
            return !part.triangles.is_empty() && !convex::is_planar(&part);
        }
        let mut own = faces
            .faces
            .iter()
            .filter(|f| of_group(&(f.triangles[0] as usize)));
        let points: Vec<_> = tris.iter().flat_map(|&t| mesh.corners(t)).collect();
        if faces.len().saturating_mul(points.len()) > 1 << 24 {
            return false;
        }
        own.any(|f| {
            // exact: the plane's offset taken at its centroid, as convex::is_convex does
            let d = f.normal.dot(f.centroid);
            points.iter().any(|v| f.normal.dot(*v) - d > tol)
        })
    })
}

/// No two groups share a vertex position (bit for bit): the groups' edges, pieces and
/// faces are then each their own.
fn groups_apart(vertices: &[glam::DVec3], group: &[u32]) -> bool {
    let mut keyed: Vec<([u64; 3], u32)> = vertices
        .iter()
        .zip(group)
        .map(|(v, &g)| ([v.x.to_bits(), v.y.to_bits(), v.z.to_bits()], g))
        .collect();
    keyed.sort_unstable();
    keyed
        .windows(2)
        .all(|w| w[0].0 != w[1].0 || w[0].1 == w[1].1)
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
    let shared = Shared::build(scene, a);
    let per_group: Vec<PoseResults> = groups
        .par_iter()
        .enumerate()
        .map(|(g, (angles, which))| {
            if progress.is_cancelled() {
                return (Vec::new(), None);
            }
            let s = posed(scene, a, angles);
            let prepared = shared
                .as_ref()
                .and_then(|sh| sh.prepare(&s, a, angles))
                .unwrap_or_else(|| Prepared::new(&s));
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
        "{}; articulated: {} hinge(s), {} pose(s) for {} epoch(s), {}",
        info.method,
        a.joints.len(),
        groups.len(),
        scene.epochs.len(),
        if shared.is_some() {
            "each part's faces and edges prepared once and moved to each pose"
        } else {
            "each pose prepared as a rigid mesh"
        }
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
