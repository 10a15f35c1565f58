//! Patches: spatial groups of consecutive faces (in their spatial order), with bounding
//! spheres and normal cones, so that whole groups of occluders are dismissed at once —
//! once per request by their planes ([`candidates`]), per direction by reach and normal
//! cone ([`Visibility::flag_patches`]).

use super::face::{sort_dedup, FaceGeom};
use super::proofs::{may_block, reaches, Side};
use super::Visibility;
use crate::geometry::convex::ConvexPart;
use crate::geometry::mesh::Points;
use glam::DVec3;
use rayon::prelude::*;
use std::ops::Range;

/// A spatial group of consecutive faces.
pub(super) struct Patch {
    pub(super) centre: DVec3,
    pub(super) radius: f64,
    /// Normal cone: axis and sin of its half-angle (> 1 when the cone is too wide to use).
    pub(super) axis: DVec3,
    pub(super) sin_half: f64,
    pub(super) faces: Range<u32>,
}

fn patch_of(faces: &[FaceGeom], range: Range<u32>) -> Patch {
    let pts = || {
        faces.iter().flat_map(|f| {
            [
                f.centroid - DVec3::splat(f.radius),
                f.centroid + DVec3::splat(f.radius),
            ]
        })
    };
    let (lo, hi) = pts().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    let centre = 0.5 * (lo + hi);
    let radius = faces
        .iter()
        .map(|f| f.centroid.distance(centre) + f.radius)
        .fold(0.0, f64::max);
    let sum: DVec3 = faces.iter().map(|f| f.normal).sum();
    let (axis, sin_half) = if sum.length_squared() < 1e-12 {
        (DVec3::Z, 2.0)
    } else {
        let axis = sum.normalize();
        let min_cos = faces.iter().map(|f| f.normal.dot(axis)).fold(1.0, f64::min);
        if min_cos <= 0.0 {
            (axis, 2.0) // half-angle of 90° or more: the cone proves nothing
        } else {
            // sin of the half-angle, padded by a hair for rounding
            (axis, (1.0 - min_cos * min_cos).max(0.0).sqrt() + 1e-12)
        }
    };
    Patch {
        centre,
        radius,
        axis,
        sin_half,
        faces: range,
    }
}

/// The distinct vertices of a patch's faces.
fn patch_points(geoms: &[FaceGeom], patch: &Patch) -> Points {
    let mut v: Vec<DVec3> = patch
        .faces
        .clone()
        .flat_map(|f| geoms[f as usize].vertices.iter().copied())
        .collect();
    sort_dedup(&mut v);
    Points::new(&v)
}

/// Per patch: the convex part all its faces belong to, and whether the part lies in
/// front of every one of them (`hull_ahead`, a dish's concave side) or behind every one.
struct PatchWithinPart(Vec<Option<(u32, bool)>>);

impl PatchWithinPart {
    fn new(patches: &[Patch], parts: &[ConvexPart], faces: usize) -> PatchWithinPart {
        let mut of = vec![None; faces];
        for (k, part) in parts.iter().enumerate() {
            for (&f, &ahead) in part.faces.iter().zip(&part.hull_ahead) {
                of[f as usize] = Some((k as u32, ahead));
            }
        }
        PatchWithinPart(
            patches
                .iter()
                .map(|p| {
                    let first = of[p.faces.start as usize]?;
                    p.faces
                        .clone()
                        .all(|f| of[f as usize] == Some(first))
                        .then_some(first)
                })
                .collect(),
        )
    }

    /// [`relation`] of patch `q` to the planes of patch `p` where both lie in one convex
    /// part in front of all of p's faces: every vertex of the part lies in front of or
    /// within the tolerance of each of its faces' planes (what [`crate::geometry::convex::convex_parts`] checked,
    /// by the same test), so q's do, and q is in front. (Behind would need one vertex
    /// beyond the tolerance, which the check does not record.)
    fn relation(&self, q: usize, p: usize) -> Option<Side> {
        match (self.0[q], self.0[p]) {
            (Some((a, true)), Some((b, true))) if a == b => Some(Side::Front),
            _ => None,
        }
    }
}

/// The faces (in their spatial order) in groups of `per_patch`, as patches.
pub(super) fn group(geoms: &[FaceGeom], per_patch: usize) -> Vec<Patch> {
    let nf = geoms.len();
    (0..nf.div_ceil(per_patch))
        .map(|p| {
            let range = (p * per_patch) as u32..((p + 1) * per_patch).min(nf) as u32;
            patch_of(&geoms[range.start as usize..range.end as usize], range)
        })
        .collect()
}

/// Per receiver patch: the occluder patches that may block it ([`may_block`]), with
/// their [`Side`].
pub(super) fn candidates(
    geoms: &[FaceGeom],
    patches: &[Patch],
    parts: &[ConvexPart],
    tol: f64,
) -> Vec<Vec<(u32, Side)>> {
    let within_part = PatchWithinPart::new(patches, parts, geoms.len());
    // Relations test each patch's distinct vertices: no more memory than the
    // faces' own vertex lists, and no more work than their bounding spheres.
    let patch_vertices: Vec<Points> = patches.par_iter().map(|p| patch_points(geoms, p)).collect();
    (0..patches.len())
        .into_par_iter()
        .map(|q| {
            (0..patches.len() as u32)
                .filter_map(|p| {
                    let (q_faces, p_faces) = (&patches[q].faces, &patches[p as usize].faces);
                    if !may_block(geoms, q_faces, p_faces, tol) {
                        return None;
                    }
                    let q_vertices = &patch_vertices[q];
                    if let Some(side) = within_part.relation(q, p as usize) {
                        return Some((p, side));
                    }
                    Some((p, relation(geoms, &patches[q], q_vertices, p_faces, tol)))
                })
                .collect()
        })
        .collect()
}

/// Every patch's faces grouped by part: `faces` holds them patch after patch, each
/// patch's ordered by part (faces of no part last), and `runs[p]` lists patch p's groups
/// as (part, range of `faces`), so a search can pass over the parts it leaves out whole.
#[derive(Debug, Default)]
pub(super) struct PatchParts {
    pub(super) faces: Vec<u32>,
    pub(super) runs: Vec<Vec<(u32, Range<u32>)>>,
}

impl PatchParts {
    pub(super) fn new(patches: &[Patch], part_of: &[u32]) -> PatchParts {
        let mut out = PatchParts::default();
        for p in patches {
            let start = out.faces.len();
            out.faces.extend(p.faces.clone());
            // stable: faces keep their (spatial) order within a part
            out.faces[start..].sort_by_key(|&f| part_of[f as usize]);
            let mut runs: Vec<(u32, Range<u32>)> = Vec::new();
            for i in start..out.faces.len() {
                let part = part_of[out.faces[i] as usize];
                match runs.last_mut() {
                    Some((q, r)) if *q == part => r.end = i as u32 + 1,
                    _ => runs.push((part, i as u32..i as u32 + 1)),
                }
            }
            out.runs.push(runs);
        }
        out
    }

    /// Patch `p`'s faces outside the parts `left_out` says no to.
    pub(super) fn faces<'a>(
        &'a self,
        p: u32,
        left_out: impl Fn(u32) -> bool + 'a,
    ) -> impl Iterator<Item = u32> + 'a {
        self.runs[p as usize]
            .iter()
            .filter(move |(part, _)| !left_out(*part))
            .flat_map(|(_, r)| self.faces[r.start as usize..r.end as usize].iter().copied())
    }

    /// How many faces [`PatchParts::faces`] gives.
    pub(super) fn count(&self, p: u32, left_out: impl Fn(u32) -> bool) -> usize {
        self.runs[p as usize]
            .iter()
            .filter(|(part, _)| !left_out(*part))
            .map(|(_, r)| r.len())
            .sum()
    }
}

impl Visibility {
    /// Occluder patches that may block receiver patch `q` along `d` (patch-level proofs).
    pub(super) fn flag_patches(&self, q: u32, d: DVec3) -> Vec<u32> {
        let qp = &self.patches[q as usize];
        self.candidates[q as usize]
            .iter()
            .filter(|&&(p, side)| {
                let pp = &self.patches[p as usize];
                reaches(qp.centre, qp.radius, pp.centre, pp.radius, d) && !cone_clear(side, pp, d)
            })
            .map(|&(p, _)| p)
            .collect()
    }
}

/// Patch-level half-space proof: every occluder plane faces away along `d` from a
/// receiver wholly in front of them all (or towards, from one wholly behind).
#[inline]
pub(super) fn cone_clear(side: Side, p: &Patch, d: DVec3) -> bool {
    match side {
        Side::Front => d.dot(p.axis) > p.sin_half,
        Side::Behind => -d.dot(p.axis) > p.sin_half,
        Side::Mixed => false,
    }
}

/// Where the receiver faces lie relative to every plane of the occluder faces.
pub(super) fn relation(
    geoms: &[FaceGeom],
    q: &Patch,
    q_vertices: &Points,
    p_faces: &Range<u32>,
    tol: f64,
) -> Side {
    let (mut front, mut behind) = (true, true);
    for gi in p_faces.clone() {
        let g = &geoms[gi as usize];
        // The receiver patch's sphere decides this plane when it settles both flags
        // (one is usually false already): most planes of a distant patch.
        let s = g.normal.dot(q.centre - g.centroid);
        let (sphere_front, sphere_behind) = (s - q.radius >= -tol, s + q.radius <= tol);
        if (sphere_front || !front) && (sphere_behind || !behind) {
            front &= sphere_front;
            behind &= sphere_behind;
            if !front && !behind {
                return Side::Mixed;
            }
            continue;
        }
        // exact: the patch's distinct vertices (faces share theirs)
        let (ahead, back) = q_vertices.sides(g.normal, g.centroid, tol);
        front &= !back;
        behind &= !ahead;
        if !front && !behind {
            return Side::Mixed;
        }
    }
    if front {
        Side::Front
    } else if behind {
        Side::Behind
    } else {
        Side::Mixed
    }
}

#[cfg(test)]
mod tests {
    use super::super::oracle::{cluttered_box_wing, visibility_of};
    use super::*;
    use crate::geometry::builtin;

    #[test]
    fn patches_within_one_convex_part_relate_as_testing_their_vertices_says() {
        // The shortcut must give what the vertex test gives, exactly: candidates (and so
        // light curves) stay the same to the last bit.
        for mesh in [builtin::box_wing_with(8, 24, 0), cluttered_box_wing()] {
            let vis = visibility_of(mesh);
            let parts: Vec<ConvexPart> = vis.parts.iter().map(|p| p.convex.clone()).collect();
            let within = PatchWithinPart::new(&vis.patches, &parts, vis.faces.len());
            let mut shortcut = 0;
            for q in 0..vis.patches.len() {
                let points = patch_points(&vis.faces, &vis.patches[q]);
                for p in 0..vis.patches.len() {
                    if let Some(side) = within.relation(q, p) {
                        let p_faces = &vis.patches[p].faces;
                        let tested =
                            relation(&vis.faces, &vis.patches[q], &points, p_faces, vis.tol);
                        assert_eq!(side, tested, "patches {q} and {p}");
                        shortcut += 1;
                    }
                }
            }
            assert!(shortcut > 10, "{shortcut}");
        }
    }
}
