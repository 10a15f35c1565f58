//! Convex parts ([`ConvexPart`]: boxes, dishes) as whole shadow casters.
//!
//! Along a direction d a convex part hides exactly what its convex hull hides, so its
//! shadow on a face's plane is the parallel projection of the hull — of the part of the
//! hull on the face's lit side, when the plane cuts the part. That projection is a convex
//! polygon whose corners are (a) vertices on the boundary of the part's own projection
//! across d — its *silhouette*, found once per epoch and direction, whichever face it
//! falls on, since projecting along d onto any plane is an affine map of the projection
//! across d — and (b) where the part's edges cross the face's plane, found once per
//! request. Why (a) suffices: a point of the cut hull that is extreme in its projection
//! and lies off the plane is extreme for the whole hull too (the segment towards any point
//! further out would stay on the lit side for a while).
//!
//! A part cut by a face's plane is not used when it is a cap whose section by the plane
//! overlaps the face: a point of the face inside the hull may see out through the lid.

use super::face::{sort_dedup, FaceGeom, PartShadow};
use super::NO_PART;
use crate::geometry::convex::ConvexPart;
use crate::geometry::mesh::Points;
use crate::geometry::polygon::{convex_hull, HullIndices, Region};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// The bounding sphere of each part: centre and radius, m.
pub(super) fn spheres(parts: &[ConvexPart]) -> Vec<(DVec3, f64)> {
    parts
        .iter()
        .map(|p| crate::geometry::mesh::bounding_sphere(&p.vertices))
        .collect()
}

/// Each part's vertices, and each face's part (`NO_PART` for none), with what its part
/// says of its sides: facing into a cap (`lid_side`), out of the part (`own_outside`).
pub(super) fn assign(parts: &mut [ConvexPart], geoms: &mut [FaceGeom]) -> Vec<u32> {
    // A part's hull needs only its faces' corners: a subdivided side adds none.
    for part in parts.iter_mut() {
        let mut corners: Vec<DVec3> = part
            .faces
            .iter()
            .flat_map(|&f| geoms[f as usize].vertices.iter().copied())
            .collect();
        sort_dedup(&mut corners);
        part.vertices = corners;
    }
    let mut part_of = vec![NO_PART; geoms.len()];
    for (k, part) in parts.iter().enumerate() {
        for (&f, &ahead) in part.faces.iter().zip(&part.hull_ahead) {
            part_of[f as usize] = k as u32;
            let g = &mut geoms[f as usize];
            if part.lid.is_some() {
                g.lid_side = [ahead, !ahead && g.two_sided];
            }
            g.own_outside = [!ahead, ahead];
        }
    }
    part_of
}

/// Each part's bounding box as its 8 corners, m.
pub(super) fn boxes(parts: &[ConvexPart]) -> Vec<[DVec3; 8]> {
    parts
        .iter()
        .map(|p| {
            let (lo, hi) = p
                .vertices
                .iter()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(*v), hi.max(*v))
                });
            std::array::from_fn(|i| {
                let pick = |bit: usize, axis: usize| if i & bit == 0 { lo[axis] } else { hi[axis] };
                DVec3::new(pick(1, 0), pick(2, 1), pick(4, 2))
            })
        })
        .collect()
}

/// Above this many edge-against-plane tests (summed over the faces that cut parts), cut
/// parts shadow face by face instead.
const CUT_WORK_LIMIT: usize = 50_000_000;

/// Fewest faces for a part cut by a face's plane to be cast whole: a box's few faces are
/// each proven harmless or clipped for less than its hull costs (the fine dish's faces
/// cut the bus: whole, they cost a third of an epoch).
const CUT_MIN_FACES: usize = 16;

/// For every face, the parts that shadow it whole (its own part excluded).
pub(super) fn part_shadows(
    geoms: &[FaceGeom],
    parts: &[ConvexPart],
    part_of: &[u32],
    spheres: &[(DVec3, f64)],
    tol: f64,
) -> Vec<Vec<PartShadow>> {
    // where each part lies against each face's plane: (part, lo, hi) heights, m
    let heights: Vec<Vec<(u32, f64, f64)>> = geoms
        .par_iter()
        .zip(part_of)
        .map(|(g, &own)| {
            let mut out = Vec::new();
            for (k, part) in parts.iter().enumerate() {
                if own == k as u32 {
                    continue;
                }
                let (c, r) = spheres[k];
                let h = g.normal.dot(c - g.centroid);
                if (h - r > tol) || (h + r < -tol) {
                    out.push((k as u32, h - r, h + r)); // the sphere decides
                    continue;
                }
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for v in &part.vertices {
                    let h = g.normal.dot(*v - g.centroid);
                    lo = lo.min(h);
                    hi = hi.max(h);
                    if lo < -tol && hi > tol {
                        break; // cut: the heights matter no further
                    }
                }
                out.push((k as u32, lo, hi));
            }
            out
        })
        .collect();
    let edges: Vec<usize> = parts
        .iter()
        .map(|p| {
            p.faces
                .iter()
                .map(|&f| geoms[f as usize].polygons().map(<[_]>::len).sum::<usize>())
                .sum()
        })
        .collect();
    let casts_cut = |k: u32| parts[k as usize].faces.len() >= CUT_MIN_FACES;
    let cut_work: usize = heights
        .iter()
        .flatten()
        .filter(|&&(k, lo, hi)| lo < -tol && hi > tol && casts_cut(k))
        .map(|&(k, _, _)| edges[k as usize])
        .sum();
    let cuts = cut_work <= CUT_WORK_LIMIT;
    geoms
        .par_iter()
        .zip(heights)
        .map(|(g, hs)| {
            hs.into_iter()
                .filter_map(|(k, lo, hi)| {
                    let part = &parts[k as usize];
                    if lo >= -tol && hi > tol {
                        return Some(whole(k, [true, false], [false, true]));
                    }
                    if hi <= tol && lo < -tol {
                        return Some(whole(k, [false, true], [true, false]));
                    }
                    if !(cuts && lo < -tol && hi > tol && casts_cut(k)) {
                        return None; // in the face's plane, too few faces, or too much work
                    }
                    let crossings = crossings(g, part, geoms, tol);
                    if part.lid.is_some() && section_meets_face(g, part, &crossings, tol) {
                        return None;
                    }
                    Some(PartShadow {
                        part: k,
                        sides: [true, g.two_sided],
                        behind: [false; 2],
                        cut: true,
                        crossings,
                    })
                })
                .collect()
        })
        .collect()
}

fn whole(part: u32, sides: [bool; 2], behind: [bool; 2]) -> PartShadow {
    PartShadow {
        part,
        sides,
        behind,
        cut: false,
        crossings: Vec::new(),
    }
}

/// Points where the edges of `part`'s faces cross the plane of `g`, m. An edge two faces
/// share is met from both, in opposite directions: its ends are taken in one order, so
/// both give the same point to the bit and it is kept once. (Computed each way, the two
/// differ in their last bits, and a convex hull of such near twins folded at them: the
/// hull of an 80-sided tube through a box's side lost 2e-3 m² of its 2.4.)
fn crossings(g: &FaceGeom, part: &ConvexPart, geoms: &[FaceGeom], tol: f64) -> Vec<DVec3> {
    let h = |p: DVec3| g.normal.dot(p - g.centroid);
    let mut out = Vec::new();
    for &f in &part.faces {
        for poly in geoms[f as usize].polygons() {
            for (i, &a) in poly.iter().enumerate() {
                let b = poly[(i + 1) % poly.len()];
                let (a, b) = if a.to_array() <= b.to_array() {
                    (a, b)
                } else {
                    (b, a)
                };
                let (ha, hb) = (h(a), h(b));
                if (ha > 0.0 && hb < -tol) || (hb > 0.0 && ha < -tol) {
                    out.push(a + (b - a) * (ha / (ha - hb)));
                }
            }
        }
    }
    sort_dedup(&mut out);
    out
}

/// Does the part's section by the plane of `g` overlap `g` (by more than rounding)?
fn section_meets_face(g: &FaceGeom, part: &ConvexPart, crossings: &[DVec3], tol: f64) -> bool {
    let (u, w) = crate::geometry::orthonormal_basis(g.normal);
    let plane = |p: &DVec3| {
        let r = *p - g.centroid;
        DVec2::new(r.dot(u), r.dot(w))
    };
    let on_plane = part
        .vertices
        .iter()
        .filter(|v| g.normal.dot(**v - g.centroid).abs() <= tol);
    let points: Vec<DVec2> = crossings.iter().chain(on_plane).map(plane).collect();
    let (mut order, mut section) = (Vec::new(), Vec::new());
    convex_hull(&points, &mut order, &mut section);
    if section.len() < 3 {
        return true; // a sliver of a cut, from rounding: not worth proving
    }
    let mut region = Region::default();
    region.reset(g.radius);
    let mut poly = Vec::new();
    for p in g.polygons() {
        poly.clear();
        poly.extend(p.iter().map(plane));
        region.add_convex(&poly);
    }
    region.intersect_convex(&section);
    region.area() > tol * g.radius
}

/// For each cap (a part with a lid), the faces of the rest of the mesh that a ray leaving
/// one of its faces into the cap can meet: it runs inside the hull up to the lid, then in
/// front of the lid's plane, so a face wholly behind that plane and outside the hull is
/// never met. `None` for lidless parts, and where testing would cost more than it saves.
pub(super) fn lid_blockers(
    geoms: &[FaceGeom],
    parts: &[ConvexPart],
    part_of: &[u32],
    tol: f64,
) -> Vec<Option<Vec<u32>>> {
    parts
        .iter()
        .enumerate()
        .map(|(k, part)| {
            let lid = part.lid.as_ref()?;
            if geoms.len().saturating_mul(part.vertices.len()) > LID_WORK_LIMIT {
                return None;
            }
            let height = |v: DVec3| lid.normal.dot(v - lid.origin);
            // the hull lies between its deepest point and the lid's plane
            let deepest = part.vertices.iter().map(|v| height(*v)).fold(0.0, f64::min);
            let points = Points::new(&part.vertices);
            Some(
                (0..geoms.len() as u32)
                    .into_par_iter()
                    .filter(|&g| {
                        let o = &geoms[g as usize];
                        if part_of[g as usize] == k as u32 {
                            return false;
                        }
                        if o.vertices.is_empty() {
                            return true; // nothing to prove it with
                        }
                        if o.vertices.iter().any(|v| height(*v) > tol) {
                            return true; // in front of the lid
                        }
                        if o.vertices.iter().all(|v| height(*v) <= deepest + tol) {
                            return false; // below the hull
                        }
                        // outside the hull when the face's plane has the hull on one side
                        let (ahead, behind) = points.sides(o.normal, o.centroid, tol);
                        ahead && behind
                    })
                    .collect(),
            )
        })
        .collect()
}

/// Above this many faces × cap vertices, a cap's blockers are searched per epoch instead.
const LID_WORK_LIMIT: usize = 200_000_000;

/// Per vertex of each part: a cone (unit axis, sine of its half-angle; > 1 for a cone too
/// wide to use) that holds the outward normals of every face at the vertex, the lid's
/// included. A vertex can lie on the part's silhouette along d only where some plane
/// through it parallel to d supports the hull, i.e. its cone holds a normal across d:
/// |axis·d| ≤ sin(half-angle). On a finely meshed dish that leaves a narrow band.
pub(super) fn normal_cones(
    parts: &[ConvexPart],
    indices: &[VertexIndex],
    geoms: &[FaceGeom],
    faces: &crate::geometry::Faces,
    corners: &[[DVec3; 3]],
) -> Vec<Vec<[f64; 4]>> {
    parts
        .par_iter()
        .zip(indices)
        .map(|(part, vertices)| {
            let index = |p: &DVec3| vertices.get(p);
            // (vertex, outward normal, from the lid) at every face corner, in face order
            // and then the lid's; gathered by vertex (a counting sort, which keeps that
            // order): each vertex's normals side by side in the order they were met (one
            // flat list, the corners found in parallel, where a list per vertex cost an
            // allocation each)
            let mut at: Vec<(u32, DVec3, bool)> = part
                .faces
                .par_iter()
                .zip(&part.hull_ahead)
                .flat_map_iter(|(&f, &ahead)| {
                    let g = &geoms[f as usize];
                    let out = if ahead { -g.normal } else { g.normal };
                    faces.faces[f as usize]
                        .triangles
                        .iter()
                        .flat_map(|&t| corners[t as usize].iter())
                        .filter_map(move |c| index(c).map(|i| (i as u32, out, false)))
                })
                .collect();
            if let Some(lid) = &part.lid {
                at.extend(
                    lid.corners
                        .iter()
                        .filter_map(|c| index(c).map(|i| (i as u32, lid.normal, true))),
                );
            }
            let n = part.vertices.len();
            let mut start = vec![0u32; n + 1];
            for e in &at {
                start[e.0 as usize + 1] += 1;
            }
            for i in 0..n {
                start[i + 1] += start[i];
            }
            let mut next = start.clone();
            let mut by_vertex = vec![(DVec3::ZERO, false); at.len()];
            for &(i, normal, from_lid) in &at {
                let slot = &mut next[i as usize];
                by_vertex[*slot as usize] = (normal, from_lid);
                *slot += 1;
            }
            let mut ns: Vec<DVec3> = Vec::new();
            (0..n)
                .map(|i| {
                    // each face's normal once (a face of several triangles meets a vertex
                    // more than once), the lid's always
                    ns.clear();
                    for &(normal, from_lid) in &by_vertex[start[i] as usize..start[i + 1] as usize]
                    {
                        if from_lid || !ns.contains(&normal) {
                            ns.push(normal);
                        }
                    }
                    cone_of(&ns)
                })
                .collect()
        })
        .collect()
}

/// The cone of a vertex without normals: every direction.
const NO_CONE: [f64; 4] = [0.0, 0.0, 1.0, 2.0];

/// The cone (axis, sin of its half-angle; > 1 for every direction) of unit normals `ns`.
fn cone_of(ns: &[DVec3]) -> [f64; 4] {
    let sum: DVec3 = ns.iter().sum();
    if ns.is_empty() || sum.length_squared() < 1e-12 {
        return NO_CONE;
    }
    let axis = sum.normalize();
    let min_cos = ns.iter().map(|n| n.dot(axis)).fold(1.0, f64::min);
    let sin = if min_cos <= 1e-3 {
        2.0 // 90° or more: every direction
    } else {
        // padded well beyond rounding: a vertex a hair inside the boundary must still
        // count as on it
        (1.0 - min_cos * min_cos).max(0.0).sqrt() + 1e-6
    };
    [axis.x, axis.y, axis.z, sin]
}

/// A part's vertices by position, for finding where a face's corner is among them: a
/// hash of the coordinates (a bisection per corner, 36k of them on the fine dish, cost
/// its preparation 5 ms).
pub(super) struct VertexIndex(rustc_hash::FxHashMap<[u64; 3], u32>);

impl VertexIndex {
    pub(super) fn new(part: &ConvexPart) -> VertexIndex {
        VertexIndex(
            part.vertices
                .iter()
                .enumerate()
                .map(|(i, v)| (position_key(v), i as u32))
                .collect(),
        )
    }

    /// Where the point `p` is among the part's vertices, if it is one.
    #[inline]
    pub(super) fn get(&self, p: &DVec3) -> Option<usize> {
        self.0.get(&position_key(p)).map(|&i| i as usize)
    }
}

/// The coordinates' bits, −0 taken as +0: equal keys exactly for equal points.
#[inline]
fn position_key(p: &DVec3) -> [u64; 3] {
    [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits())
}

/// A part's silhouette along one direction, kept for the epoch.
#[derive(Default)]
pub(super) struct Silhouette {
    pub(super) dir: Option<DVec3>,
    /// Corners of the part's projection across `dir` and (see [`Silhouette::near`]) its
    /// vertices on or near its boundary, as indices into the part's vertices.
    pub(super) corners: Vec<u32>,
    near: Vec<u32>,
    /// The slack `near` was found with; `None` until asked for, this direction.
    near_slack: Option<f64>,
    hull: HullIndices,
    /// Vertices that may lie on the silhouette, and their projections.
    keep: Vec<u32>,
    points: Vec<DVec2>,
    /// The projection's corners on [`Silhouette::axes`] of `dir`, counter-clockwise, m.
    outline: Vec<DVec2>,
}

impl Silhouette {
    /// The silhouette of `part` (with its vertices' normal `cones`) along unit `d`,
    /// computed unless already held; `tol` (m) is how close to the boundary counts as on it.
    pub(super) fn along(&mut self, part: &ConvexPart, cones: &[[f64; 4]], d: DVec3, tol: f64) {
        if self.dir == Some(d) {
            return;
        }
        let (u, w) = Silhouette::axes(d);
        self.keep.clear();
        self.points.clear();
        for (i, (v, c)) in part.vertices.iter().zip(cones).enumerate() {
            if c[3] > 1.0 || (c[0] * d.x + c[1] * d.y + c[2] * d.z).abs() <= c[3] {
                self.keep.push(i as u32);
                self.points.push(DVec2::new(v.dot(u), v.dot(w)));
            }
        }
        // the near points only when a cut part asks for them ([`Silhouette::near`])
        self.hull.compute_corners(&self.points, tol);
        self.corners.clear();
        self.corners
            .extend(self.hull.corners.iter().map(|&j| self.keep[j as usize]));
        self.near.clear();
        self.near_slack = None;
        self.outline.clear();
        self.outline
            .extend(self.hull.corners.iter().map(|&j| self.points[j as usize]));
        self.dir = Some(d);
    }

    /// The part's vertices on or within `tol` (m) of its projection's boundary (indices
    /// into its vertices), found on first asking for this direction.
    pub(super) fn near(&mut self, tol: f64) -> &[u32] {
        if self.near_slack != Some(tol) {
            self.hull.compute_near(&self.points, tol);
            self.near.clear();
            self.near
                .extend(self.hull.near.iter().map(|&j| self.keep[j as usize]));
            self.near_slack = Some(tol);
        }
        &self.near
    }

    /// The (u, w) axes across `dir` that [`Silhouette::cover`]'s projected corners use.
    pub(super) fn axes(d: DVec3) -> (DVec3, DVec3) {
        crate::geometry::orthonormal_basis(d)
    }

    /// How the part (seen along `dir`, its hull behind the planes `planes`) stands to the
    /// convex hull of `corners` along `dir` (see [`Cover`]), given what its planes settled
    /// ([`Planes::settle`]); `across` holds the corners projected on [`Silhouette::axes`].
    /// Every test is by `margin` (m), beyond rounding and the hull's own slack.
    pub(super) fn cover(&self, ahead: bool, across: &[DVec2], margin: f64) -> Cover {
        let n = self.outline.len();
        if n < 3 || across.is_empty() {
            return Cover::Unknown;
        }
        let mut all_in = true;
        for i in 0..n {
            let (a, b) = (self.outline[i], self.outline[(i + 1) % n]);
            let e = b - a;
            // perp is the inward normal of a counter-clockwise outline
            let (m, len) = (e.perp(), e.length());
            let (mut any_in, mut any_out) = (false, false);
            for q in across {
                let h = m.dot(*q - a);
                any_in |= h > -margin * len;
                any_out |= h <= margin * len;
            }
            if !any_in {
                return Cover::Miss; // all beside this edge: no line meets the hull
            }
            all_in &= !any_out;
        }
        match (ahead, all_in) {
            (true, true) => Cover::Hidden,
            (true, false) => Cover::Ahead,
            _ => Cover::Unknown,
        }
    }
}

/// A part's hull as planes it lies behind ([`hull_planes`]) and its bounding sphere.
pub(super) struct Planes<'a> {
    pub(super) planes: &'a [(DVec3, f64)],
    pub(super) sphere: (DVec3, f64),
}

impl Planes<'_> {
    /// What the planes alone settle of the convex hull of `corners` along unit `d`, by
    /// `margin` (m): `None` when every line from it along d leaves a plane the hull lies
    /// behind (or the sphere about it) away from it, so none meets the hull; else whether
    /// one such plane, crossed inwards, has every corner outside it, so every line that
    /// meets the hull meets it wholly ahead.
    pub(super) fn settle(&self, corners: &[DVec3], d: DVec3, margin: f64) -> Option<bool> {
        let outside = |(m, c): (DVec3, f64)| corners.iter().all(|p| m.dot(*p) > c + margin);
        let (centre, radius) = self.sphere;
        let h = centre.dot(d);
        if outside((d, h + radius))
            || self
                .planes
                .iter()
                .any(|&(m, c)| m.dot(d) > 0.0 && outside((m, c)))
        {
            return None;
        }
        Some(
            outside((-d, radius - h))
                || self
                    .planes
                    .iter()
                    .any(|&(m, c)| m.dot(d) < 0.0 && outside((m, c))),
        )
    }
}

/// How a convex part stands to a face along a direction ([`Silhouette::cover`]). A line
/// through a convex part's hull enters and leaves it, at most once through a cap's open
/// side, so a line that meets the hull wholly ahead of its point meets the part there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Cover {
    /// No ray from the face along the direction meets the part's hull.
    Miss,
    /// Every such line meets the hull, and wholly ahead: the face is dark along it.
    Hidden,
    /// The hull lies wholly ahead of every point of the face, so the part's shadow on it is
    /// its silhouette projected onto the face's plane, however the plane cuts the part.
    Ahead,
    /// None of these proved.
    Unknown,
}

/// What the other parts' cover tests settle for a whole part along one direction (the
/// direction's cache, kept while it repeats): parts that no line from it meets, or one
/// that every line from it meets wholly ahead. Valid for each face of the part.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct PartCover {
    /// The direction it was made for.
    pub(super) dir: Option<DVec3>,
    /// Parts (bit q for part q < 64) that no line from the part along it meets.
    pub(super) miss: u64,
    /// Some part hides the whole part along it.
    pub(super) hidden: bool,
}

/// Most parts' planes kept for [`Silhouette::cover`]: a finely meshed cap keeps its lid's.
const MAX_COVER_PLANES: usize = 64;

/// Per part: planes (outward unit normal m, offset c) that its hull lies behind
/// (m·x ≤ c, within the tolerance): its faces' when it has few, and its lid's. `None` for
/// a flat part of several faces: a line crosses its plane once, where an open side (a
/// hole) may be, so it does not hide its hull (one convex face does).
pub(super) fn hull_planes(
    parts: &[ConvexPart],
    geoms: &[FaceGeom],
) -> Vec<Option<Vec<(DVec3, f64)>>> {
    parts
        .iter()
        .map(|p| {
            let first = geoms[p.faces[0] as usize].normal;
            let flat = p.faces.iter().all(|&f| {
                let n = geoms[f as usize].normal;
                n.cross(first).length_squared() < 1e-18
            });
            if flat && (p.faces.len() > 1 || geoms[p.faces[0] as usize].convex().is_empty()) {
                return None;
            }
            let mut planes = Vec::new();
            if flat {
                // one convex face: its hull lies on its plane, behind it from either side
                let c = first.dot(geoms[p.faces[0] as usize].centroid);
                return Some(vec![(first, c), (-first, -c)]);
            }
            if p.faces.len() <= MAX_COVER_PLANES {
                for (&f, &ahead) in p.faces.iter().zip(&p.hull_ahead) {
                    let g = &geoms[f as usize];
                    // the hull lies behind a box's faces, in front of a dish's concave ones
                    let m = if ahead { -g.normal } else { g.normal };
                    planes.push((m, m.dot(g.centroid)));
                }
            }
            if let Some(lid) = &p.lid {
                planes.push((lid.normal, lid.normal.dot(lid.origin)));
            }
            Some(planes)
        })
        .collect()
}

/// Most parts a face is tested against for being hidden whole ([`Silhouette::cover`]).
const MAX_COVERS: usize = 8;

/// Per face, per side (front, back): the parts (its own left out, and those `planes`
/// ([`hull_planes`]) has none for) whose bounding spheres reach in front of that side —
/// those that could hide it whole — nearest first, at most [`MAX_COVERS`].
pub(super) fn cover_candidates(
    geoms: &[FaceGeom],
    part_of: &[u32],
    spheres: &[(DVec3, f64)],
    planes: &[Option<Vec<(DVec3, f64)>>],
    tol: f64,
) -> Vec<[Vec<u32>; 2]> {
    geoms
        .par_iter()
        .zip(part_of)
        .map(|(g, &own)| {
            let mut sides: [Vec<(f64, u32)>; 2] = Default::default();
            for (k, &(c, r)) in spheres.iter().enumerate() {
                if own == k as u32 || planes[k].is_none() {
                    continue;
                }
                let h = g.normal.dot(c - g.centroid);
                let distance = (c - g.centroid).length() - r;
                if h + r > tol {
                    sides[0].push((distance, k as u32));
                }
                if g.two_sided && h - r < -tol {
                    sides[1].push((distance, k as u32));
                }
            }
            sides.map(|mut s| {
                s.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                s.truncate(MAX_COVERS);
                s.into_iter().map(|(_, k)| k).collect()
            })
        })
        .collect()
}
