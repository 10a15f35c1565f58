//! Which part of a face is both lit and seen: shadowing and occlusion by the mesh itself.
//!
//! Rays are cast only where a face may really be partly shadowed or hidden. Per face and
//! epoch, a direction (to the Sun, the Earth or the observer) is *clear* when no part of
//! the mesh can lie along it. Two exact tests prove a direction clear without rays:
//! - **reach**: the occluder's bounding sphere misses the half-infinite cylinder swept by
//!   the face's bounding sphere along the direction;
//! - **half-space**: if the face lies wholly in front of an occluder's plane and the
//!   direction points away from that plane (d·n > 0), a ray from the face only moves
//!   further from the plane and can never cross the occluder (likewise behind / towards).
//!   This is what keeps a concave dish lit from in front free of rays.
//!
//! Faces are grouped into spatial *patches* (with bounding spheres and normal cones), so
//! whole groups of occluders are dismissed at once. A face with an unproven direction is
//! then **clipped**: each possible blocker face, cut to the part in front of the face's
//! plane, is projected along the direction onto that plane (a convex polygon) and
//! subtracted from the face ([`crate::geometry::polygon::Region`]). That area is exact —
//! no rays, no tolerance — and costs a few polygon splits per blocker. A convex part of
//! the mesh (a box, a dish: [`crate::geometry::convex::ConvexPart`]) wholly in front of
//! the face is subtracted as one polygon, the hull of its projected vertices, instead of
//! face by face: a finely meshed dish over the bus would otherwise cut the bus's top into
//! hundreds of pieces. A face of a convex cap, on its inner side, is instead clipped to
//! the cap's lid projected back onto it (what of it looks out through the rim), and the
//! cap's own faces are not collected as blockers at all.
//!
//! Faces nearly edge-on to a direction (the projection stretches without bound) or cut
//! into too many pieces are **sampled** with rays instead, refining each triangle
//! adaptively (4-way splits) until either the samples agree or a leaf is small enough
//! that mis-classifying all of it stays within the tolerance's share of the epoch's
//! signal. The sampler has known limits that clipping does not: a shadow narrower than
//! its caster's bounding radius, or a shadow corner, can fall between agreeing samples;
//! and f32 rays at grazing incidence on a neighbour miss some hits (measured on the
//! box-wing's dish, checked against f64 intersection).

mod grid;
mod sampler;

use crate::geometry::bvh::Occluder;
use crate::geometry::convex::{convex_parts, ConvexPart};
use crate::geometry::polygon::{convex_hull, Region};
use crate::geometry::Faces;
use crate::scene::Scene;
use glam::{DVec2, DVec3};
use grid::{FaceGrid, Projection, Stamp, GRID_MIN_FACES};
use rayon::prelude::*;
use sampler::Sampler;
use std::ops::Range;

/// How faces are sampled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VisibilityMode {
    /// Clear-direction proofs, then adaptive refinement of the faces left uncertain.
    Adaptive,
    /// One ray per direction at each face's centroid (faces are single triangles).
    Centroid,
}

/// The directions of one epoch that matter for a face.
#[derive(Debug, Clone, Copy)]
pub struct Uncertain {
    /// Towards the observer (always needed).
    pub view: DVec3,
    /// Towards the Sun, when the face is sunlit.
    pub sun: Option<DVec3>,
    /// Representative earthshine direction, when earthshine reaches the face.
    pub earth: Option<DVec3>,
}

/// Per-face geometry for the tests.
struct FaceGeom {
    normal: DVec3,
    /// Point on the plane (centroid), m.
    centroid: DVec3,
    radius: f64,
    /// Area, m².
    area: f64,
    two_sided: bool,
    /// Triangles to sample: the face's own, or — when the face is a convex polygon however
    /// finely it is meshed — a fan over its outline, so sampling cost follows the face's
    /// shape, not its tessellation.
    pieces: Vec<[DVec3; 3]>,
    /// The face's outline when it is a convex polygon (else empty): one polygon to project
    /// as a shadow or to clip, however finely the face is meshed.
    outline: Vec<DVec3>,
    /// Distinct vertices of the face, for exact half-space tests.
    vertices: Vec<DVec3>,
    /// Convex parts wholly in front of the face's front side, and of its back side: their
    /// shadows on it are one hull each.
    parts_ahead: [Vec<u32>; 2],
    /// Per side (front, back): the face belongs to a cap with a lid and that side faces
    /// into the cap.
    lid_side: [bool; 2],
    patch: u32,
}

const NO_PART: u32 = u32::MAX;

/// A spatial group of consecutive faces.
struct Patch {
    centre: DVec3,
    radius: f64,
    /// Normal cone: axis and sin of its half-angle (> 1 when the cone is too wide to use).
    axis: DVec3,
    sin_half: f64,
    faces: Range<u32>,
}

/// Relation of a receiver patch to an occluder patch's planes.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    /// Every receiver vertex on or in front of every occluder face plane.
    Front,
    /// Every receiver vertex on or behind every occluder face plane.
    Behind,
    Mixed,
}

/// Ray-casting state built once per request.
pub struct Visibility {
    mode: VisibilityMode,
    occluder: Occluder,
    faces: Vec<FaceGeom>,
    patches: Vec<Patch>,
    /// Per receiver patch: the occluder patches that may block it, with their relation.
    candidates: Vec<Vec<(u32, Side)>>,
    tol: f64,
    /// Clip partly shadowed faces exactly where possible (else always sample).
    clip: bool,
    /// Cell size of the per-epoch face grids, m: the median face diameter.
    grid_cell: f64,
    /// Connected convex pieces of the mesh (boxes, dishes): each casts its shadow on a
    /// face wholly behind it as the hull of its projected vertices.
    parts: Vec<ConvexPart>,
    /// Each face's convex part (index into `parts`; `NO_PART` for none).
    part_of: Vec<u32>,
}

/// Per-thread cache of patch-level results, valid within one epoch.
#[derive(Default)]
pub struct Cache {
    key: Option<(u32, bool)>,
    /// Flagged occluder patches for view, sun, earth (None: not computed yet).
    flagged: [Option<Vec<u32>>; 3],
    exact: ExactScratch,
    /// Faces' bounding spheres seen along each direction (built on first use in an epoch).
    projections: [Projection; 3],
    /// Faces binned across each direction (built on first use in an epoch): all, and all
    /// but a cap's (for the cap's own faces, [`Visibility::collect_blockers`]).
    grids: [[FaceGrid; 2]; 3],
    /// Per face: the query that last returned it (deduplicates multi-cell faces).
    stamp: Stamp,
}

/// Buffers for [`Visibility::exact_area`].
#[derive(Default)]
struct ExactScratch {
    /// Seen (and then sunlit) part of the face.
    lit: Region,
    /// Seen and earthlit part.
    earthlit: Region,
    shadows: ShadowBuffers,
}

/// Buffers for casting one direction's shadows.
#[derive(Default)]
struct ShadowBuffers {
    /// One blocker polygon: projected vertex and height above the face's plane.
    clip_in: Vec<(DVec2, f64)>,
    shadow: Vec<DVec2>,
    /// A convex part's projected vertices, and the hull's sort order.
    part_points: Vec<DVec2>,
    hull_order: Vec<u32>,
    /// Per blocker of the current direction: its shadow already cut with its part's.
    done: Vec<bool>,
}

impl Cache {
    /// Forgets everything: call at the start of each epoch.
    pub fn reset(&mut self) {
        self.key = None;
        self.flagged = [None, None, None];
        for g in self.grids.iter_mut().flatten() {
            g.dir = None;
        }
        for p in &mut self.projections {
            p.dir = None;
        }
    }
}

/// K in the leaf size K·budget/√A (see [`Visibility::visible_area`]).
const LEAF_SIZE_FACTOR: f64 = 8.0;
/// Above this faces × convex parts, parts shadow face by face, not as one hull.
const PART_PAIRS_LIMIT: usize = 10_000_000;
/// Above this faces × vertices, patch relations come from bounding spheres (conservative)
/// instead of every vertex.
const EXACT_WORK: usize = 20_000_000;

impl Visibility {
    /// Builds the BVH and the occluder candidates. `faces` should be in spatial order
    /// ([`Faces::sort_spatially`]) so that patches are compact.
    pub fn build(scene: &Scene, faces: &Faces, mode: VisibilityMode) -> Visibility {
        let mesh = &scene.mesh;
        let occluder = Occluder::build(mesh);
        let corners: Vec<[DVec3; 3]> = (0..mesh.triangles.len()).map(|i| mesh.corners(i)).collect();
        let (_, scale) = mesh.bounding_sphere();
        let tol = 1e-9 * scale;
        let nf = faces.len();
        let k = ((nf as f64).sqrt().round() as usize).clamp(1, 1024);
        let per_patch = nf.div_ceil(k);
        let mut geoms: Vec<FaceGeom> = faces
            .faces
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let mut vertices: Vec<DVec3> = f
                    .triangles
                    .iter()
                    .flat_map(|&t| corners[t as usize])
                    .collect();
                sort_dedup(&mut vertices);
                let (pieces, outline) =
                    pieces_of(f.normal, f.area, &f.triangles, &corners, &vertices, mode);
                FaceGeom {
                    normal: f.normal,
                    centroid: f.centroid,
                    radius: f.radius,
                    area: f.area,
                    two_sided: scene.materials[f.material as usize].two_sided,
                    // a convex face's linear tests (which side of a plane) are decided by
                    // its corners: a subdivided side keeps 4 vertices, not 81
                    vertices: if outline.is_empty() {
                        vertices
                    } else {
                        outline.clone()
                    },
                    pieces,
                    outline,
                    parts_ahead: Default::default(),
                    lid_side: [false; 2],
                    patch: (i / per_patch) as u32,
                }
            })
            .collect();
        let patches: Vec<Patch> = (0..nf.div_ceil(per_patch))
            .map(|p| {
                let range = (p * per_patch) as u32..((p + 1) * per_patch).min(nf) as u32;
                patch_of(&geoms[range.start as usize..range.end as usize], range)
            })
            .collect();
        let exact = nf.saturating_mul(mesh.vertices.len()) <= EXACT_WORK;
        let candidates: Vec<Vec<(u32, Side)>> = if mode == VisibilityMode::Centroid {
            Vec::new()
        } else {
            (0..patches.len())
                .into_par_iter()
                .map(|q| {
                    (0..patches.len() as u32)
                        .filter_map(|p| {
                            let (q_faces, p_faces) =
                                (&patches[q].faces, &patches[p as usize].faces);
                            if !may_block(&geoms, q_faces, p_faces, tol) {
                                return None;
                            }
                            Some((p, relation(&geoms, q_faces, p_faces, tol, exact)))
                        })
                        .collect()
                })
                .collect()
        };
        if mode == VisibilityMode::Centroid {
            for g in &mut geoms {
                g.vertices = Vec::new();
            }
        }
        let mut parts = if mode == VisibilityMode::Adaptive && scene.clip_shadows {
            convex_parts(mesh, faces, tol)
        } else {
            Vec::new()
        };
        // A part's hull needs only its faces' corners: a subdivided side adds none.
        for part in &mut parts {
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
            }
        }
        // Which parts lie wholly in front of each face: faces × parts work, and lists that
        // grow with it, so a mesh of very many parts (a debris cloud) keeps tiles instead.
        let spheres: Vec<(DVec3, f64)> = parts
            .iter()
            .map(|p| {
                let (lo, hi) = p.vertices.iter().fold(
                    (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                    |(lo, hi), v| (lo.min(*v), hi.max(*v)),
                );
                let c = 0.5 * (lo + hi);
                (
                    c,
                    p.vertices.iter().map(|v| v.distance(c)).fold(0.0, f64::max),
                )
            })
            .collect();
        let hull_shadows = geoms.len().saturating_mul(parts.len()) <= PART_PAIRS_LIMIT;
        let ahead: Vec<[Vec<u32>; 2]> = geoms
            .par_iter()
            .zip(&part_of)
            .map(|(g, &own)| {
                let mut ahead: [Vec<u32>; 2] = Default::default();
                if !hull_shadows {
                    return ahead;
                }
                for (k, part) in parts.iter().enumerate() {
                    if own == k as u32 {
                        continue;
                    }
                    let (c, r) = spheres[k];
                    let h = g.normal.dot(c - g.centroid);
                    if h - r > tol {
                        ahead[0].push(k as u32); // its bounding sphere is: no vertex to test
                        continue;
                    }
                    if h + r < -tol {
                        ahead[1].push(k as u32);
                        continue;
                    }
                    // heights of the part's vertices above the face's plane; stop as soon
                    // as the part is known to reach both sides
                    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                    for v in &part.vertices {
                        let h = g.normal.dot(*v - g.centroid);
                        lo = lo.min(h);
                        hi = hi.max(h);
                        if lo <= tol && hi >= -tol {
                            break;
                        }
                    }
                    if lo > tol {
                        ahead[0].push(k as u32);
                    } else if hi < -tol {
                        ahead[1].push(k as u32);
                    }
                }
                ahead
            })
            .collect();
        for (g, a) in geoms.iter_mut().zip(ahead) {
            g.parts_ahead = a;
        }
        Visibility {
            mode,
            occluder,
            part_of,
            faces: geoms,
            patches,
            candidates,
            tol,
            clip: scene.clip_shadows,
            parts,
            grid_cell: {
                let mut d: Vec<f64> = faces.faces.iter().map(|f| 2.0 * f.radius).collect();
                d.sort_by(f64::total_cmp);
                d.get(d.len() / 2).copied().unwrap_or(1.0).max(1e-9 * scale)
            },
        }
    }

    /// Occluder patches that may block receiver patch `q` along `d` (patch-level proofs).
    fn flag_patches(&self, q: u32, d: DVec3) -> Vec<u32> {
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

    /// Face-level tests of face `g` as a blocker of `face` (side normal `n`) along `d`;
    /// pushes it to `out` when none proves it harmless.
    #[inline]
    fn consider_blocker(
        &self,
        face: usize,
        n: DVec3,
        g: usize,
        proj: &Projection,
        out: &mut Vec<Blocker>,
    ) {
        if g == face || !proj.reaches(face, g) {
            return;
        }
        let d = proj.dir.expect("projection built for this direction");
        let f = &self.faces[face];
        let o = &self.faces[g];
        // the occluder must reach in front of the face's lit/seen side
        if !reaches_front(o, n, f.centroid, self.tol) {
            return;
        }
        let blocker = Blocker {
            face: g as u32,
            centre: o.centroid,
            radius: o.radius,
            normal: o.normal,
            // Width of shadow to hunt for: the blocker's radius. Its true width
            // (a thin strip's) would find narrower shadows, but the small faces of
            // a curved part then force fine sampling under their joint shadow,
            // which is wide: ~6x the rays on the box-wing. Known limit: a shadow
            // narrower than its caster's radius can fall between samples.
            feature: o.radius,
            // largest shadow it can cast on this face's plane
            shadow_area: o.area * d.dot(o.normal).abs() / n.dot(d).max(1e-3),
        };
        // half-space proof with the face's own vertices
        if blocker.half_space_clear(d, &f.vertices, self.tol) {
            return;
        }
        out.push(blocker);
    }

    /// Area of `face` (m²) that is both seen and sunlit, and both seen and earthlit, on
    /// side `side` (+1 front, −1 back); plus the number of rays cast. `budget` (m²) is the
    /// area of this face whose misclassification the tolerance allows.
    pub fn visible_area(
        &self,
        cache: &mut Cache,
        face: usize,
        side: f64,
        dirs: &Uncertain,
        budget: f64,
    ) -> (f64, f64, u64) {
        let f = &self.faces[face];
        let n = f.normal * side;
        // Earthshine's representative direction may lie below the face while parts of
        // the Earth light it: no meaningful ray then; count it as unshadowed.
        let earth = dirs.earth.filter(|e| n.dot(*e) > 1e-3);
        let area_of = |t: &[DVec3; 3]| 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
        let directions = [Some(dirs.view), dirs.sun, earth];
        // A shadow edge crosses about perimeter/h leaves of size h, each misjudged by a
        // fraction of its area ~h²: the error ~ perimeter·h·c falls like h, so leaves stop
        // at h = K·budget/√A (perimeter ≈ 4√A) and the error falls like the tolerance, not
        // its square root. The corner-and-centroid estimate makes c small and the leaf
        // errors cancel in part: K = 8 keeps the measured error at about a third of the
        // tolerance (box-wing and trough against converged references).
        let min_size = LEAF_SIZE_FACTOR * budget / f.area.sqrt();
        let mut s = Sampler::new(&self.occluder, n, f.centroid, directions, min_size, budget);
        if self.mode == VisibilityMode::Centroid {
            for c in &f.pieces {
                let bits = s.eval((c[0] + c[1] + c[2]) / 3.0, [true; 3]);
                let a = area_of(c);
                s.a_sun += a * (bits & 1) as f64;
                s.a_earth += a * ((bits >> 1) & 1) as f64;
            }
            return (s.a_sun, s.a_earth, s.rays);
        }
        // A face of a convex cap, on the side facing into the cap: the cap's own faces
        // block a ray from it unless it leaves through the lid, which one clip decides
        // (`Lid`), so they are not collected one by one.
        let own_lid =
            (f.lid_side[usize::from(side < 0.0)] && self.clip).then_some(self.part_of[face]);
        let lid_clips =
            self.collect_blockers(cache, face, side, &directions, own_lid, &mut s.blockers);
        let full_area: f64 = f.pieces.iter().map(area_of).sum();
        if s.blockers.iter().all(Vec::is_empty) && lid_clips.iter().all(Option::is_none) {
            return (full_area, full_area, 0);
        }
        if self.mode == VisibilityMode::Adaptive && self.clip {
            if let Some((a_sun, a_earth)) = self.exact_area(
                &mut cache.exact,
                face,
                n,
                &directions,
                &s.blockers,
                &lid_clips,
            ) {
                return (a_sun, a_earth, 0);
            }
            if own_lid.is_some() {
                // the sampler needs every blocker, the cap's own faces too
                s.blockers.iter_mut().for_each(Vec::clear);
                self.collect_blockers(cache, face, side, &directions, None, &mut s.blockers);
            }
        }
        for piece in &f.pieces {
            s.refine(*piece, None, area_of(piece), 0, self.tol);
        }
        (s.a_sun, s.a_earth, s.rays)
    }

    /// Patch- then face-level proofs; what survives are the possible blockers of `face`
    /// (on side `side`) along each direction, into `out`. Faces of part `skip` (the cap
    /// the face belongs to, when it faces into it) are left out; returned per direction
    /// is that part where its lid may clip the face (some corner's ray misses the lid).
    fn collect_blockers(
        &self,
        cache: &mut Cache,
        face: usize,
        side: f64,
        directions: &[Option<DVec3>; 3],
        skip: Option<u32>,
        out: &mut [Vec<Blocker>; 3],
    ) -> [Option<u32>; 3] {
        let f = &self.faces[face];
        let n = f.normal * side;
        let key = (f.patch, side > 0.0);
        if cache.key != Some(key) {
            cache.key = Some(key);
            cache.flagged = [None, None, None];
        }
        let mut lid_clips = [None; 3];
        for (k, d) in directions.iter().enumerate() {
            let Some(d) = *d else { continue };
            let flagged = cache.flagged[k].get_or_insert_with(|| self.flag_patches(f.patch, d));
            let count: usize = flagged
                .iter()
                .map(|&p| self.patches[p as usize].faces.len())
                .sum();
            if count == 0 {
                continue;
            }
            if let Some(part) = skip {
                let lid = self.parts[part as usize]
                    .lid
                    .as_ref()
                    .expect("caps have lids");
                if !f.vertices.iter().all(|v| lid.passes(*v, d, self.tol)) {
                    lid_clips[k] = Some(part);
                }
            }
            let proj = &mut cache.projections[k];
            if proj.dir != Some(d) {
                proj.build(&self.faces, d);
            }
            let proj = &cache.projections[k];
            let out = &mut out[k];
            let mut consider = |g: usize| {
                if skip.is_none_or(|own| self.part_of[g] != own) {
                    self.consider_blocker(face, n, g, proj, out)
                }
            };
            if count > GRID_MIN_FACES {
                // many faces to test (a finely meshed curved part): ask the epoch's grid of
                // faces seen along d for those whose shadow can fall on this one
                // (a cap's own faces left out of the grid: there are many)
                let grid = &mut cache.grids[k][usize::from(skip.is_some())];
                if grid.dir != Some(d) || grid.excluded != skip {
                    grid.build(proj, self.grid_cell, skip, &self.part_of);
                }
                let at = &proj.at[face];
                let centre = DVec2::new(at[0], at[1]);
                grid.query(centre, at[3], &mut cache.stamp, |g| consider(g as usize));
            } else {
                for &p in flagged.iter() {
                    // the patch test was for the receiver's whole patch: this face may be
                    // out of reach
                    let pp = &self.patches[p as usize];
                    if reaches(f.centroid, f.radius, pp.centre, pp.radius, d) {
                        pp.faces.clone().for_each(|g| consider(g as usize));
                    }
                }
            }
        }
        lid_clips
    }
}

/// Above this many convex pieces per face, shadows are sampled instead of clipped (the
/// 16×48 dish of `examples/scale` needs up to a few hundred).
const MAX_PIECES: usize = 4096;
/// Shadows along directions closer than this cosine to a face's plane are cast as if
/// from this cosine: the projection stretches by 1/cos, and 1e6 keeps f64 coordinates
/// of a few object radii exact to ~1e-10 of the face.
const MIN_COS_EXACT: f64 = 1e-6;

impl Visibility {
    /// Exact areas (m²) of `face` (side normal `n`) that are seen and sunlit, and seen
    /// and earthlit: the face minus the parallel projections onto its plane of the parts of
    /// the blockers in front of it. A point of the face is hidden along d exactly when the
    /// ray from it along d meets a blocker in front of the plane, i.e. when it lies in
    /// that projection. `None` when the shadows cut it into too many pieces (the caller
    /// samples instead).
    fn exact_area(
        &self,
        x: &mut ExactScratch,
        face: usize,
        n: DVec3,
        dirs: &[Option<DVec3>; 3],
        blockers: &[Vec<Blocker>; 3],
        lid_clips: &[Option<u32>; 3],
    ) -> Option<(f64, f64)> {
        // A direction at or below the face's horizon still lights it through the upper
        // part of the Sun's disk: its shadows are those of a direction just above the
        // horizon (the light it brings is already weighted by the BRDF's disk average).
        let dirs = dirs.map(|d| {
            d.map(|d| {
                let c = n.dot(d);
                if c >= MIN_COS_EXACT {
                    return d;
                }
                let t = d - n * c;
                let len = t.length();
                if len == 0.0 {
                    return n;
                }
                let s = MIN_COS_EXACT;
                t / len * (1.0 - s * s).sqrt() + n * s
            })
        });
        let f = &self.faces[face];
        let (u, w) = crate::radiometry::earth::orthonormal_basis(n);
        let c = f.centroid;
        let plane = |p: DVec3| {
            let r = p - c;
            DVec2::new(r.dot(u), r.dot(w))
        };
        x.lit.reset(f.radius);
        let poly = &mut x.shadows.shadow;
        if f.outline.is_empty() {
            for t in &f.pieces {
                poly.clear();
                poly.extend(t.iter().map(|p| plane(*p)));
                x.lit.add_convex(poly);
            }
        } else {
            poly.clear();
            poly.extend(f.outline.iter().map(|p| plane(*p)));
            x.lit.add_convex(poly);
        }
        // view first: both the sunlit and the earthlit parts must be seen
        let ahead = &f.parts_ahead[usize::from(n.dot(f.normal) < 0.0)];
        let shadows = |region: &mut Region, k: usize, x: &mut ShadowBuffers| -> Option<()> {
            let Some(d) = dirs[k] else { return Some(()) };
            let along = DVec2::new(d.dot(u), d.dot(w)) / n.dot(d);
            let project = |y: DVec3| {
                let h = n.dot(y - c);
                (plane(y) - along * h, h)
            };
            if let Some(part) = lid_clips[k] {
                // what of the face sees out of its own cap: the lid, projected back
                let lid = self.parts[part as usize]
                    .lid
                    .as_ref()
                    .expect("caps have lids");
                x.shadow.clear();
                x.shadow.extend(lid.corners.iter().map(|y| project(*y).0));
                region.intersect_convex(&x.shadow);
                if region.is_empty() {
                    return Some(());
                }
            }
            x.done.clear();
            x.done.resize(blockers[k].len(), false);
            // A convex part wholly in front of the face with several faces among the
            // blockers: its shadow is the hull of its projected vertices, one cut for all.
            for &part in ahead {
                let of_part = blockers[k]
                    .iter()
                    .filter(|b| self.part_of[b.face as usize] == part)
                    .count();
                if of_part < 2 {
                    continue;
                }
                let vertices = &self.parts[part as usize].vertices;
                x.part_points.clear();
                x.part_points.extend(vertices.iter().map(|y| project(*y).0));
                convex_hull(&x.part_points, &mut x.hull_order, &mut x.shadow);
                region.subtract_convex(&x.shadow, MAX_PIECES).ok()?;
                for (done, b) in x.done.iter_mut().zip(&blockers[k]) {
                    *done |= self.part_of[b.face as usize] == part;
                }
                if region.is_empty() {
                    return Some(());
                }
            }
            for (b, _) in blockers[k].iter().zip(&x.done).filter(|(_, &done)| !done) {
                let o = &self.faces[b.face as usize];
                let polys: &mut dyn Iterator<Item = &[DVec3]> = if o.outline.is_empty() {
                    &mut o.pieces.iter().map(|t| &t[..])
                } else {
                    &mut std::iter::once(&o.outline[..])
                };
                for p in polys {
                    // project each vertex along d onto the plane; h is its height above it
                    x.clip_in.clear();
                    x.clip_in.extend(p.iter().map(|y| project(*y)));
                    clip_above(&x.clip_in, self.tol, &mut x.shadow);
                    if x.shadow.len() >= 3 {
                        region.subtract_convex(&x.shadow, MAX_PIECES).ok()?;
                        if region.is_empty() {
                            return Some(());
                        }
                    }
                }
            }
            Some(())
        };
        shadows(&mut x.lit, 0, &mut x.shadows)?;
        let seen = x.lit.area();
        let a_earth = if dirs[2].is_some() {
            x.earthlit.clone_from(&x.lit);
            shadows(&mut x.earthlit, 2, &mut x.shadows)?;
            x.earthlit.area()
        } else {
            seen
        };
        let a_sun = if dirs[1].is_some() {
            shadows(&mut x.lit, 1, &mut x.shadows)?;
            x.lit.area()
        } else {
            seen
        };
        Some((a_sun, a_earth))
    }
}

/// The part of a convex polygon (vertices with heights `h`) at height above `tol`, as
/// its projected vertices in `out` (the projection is affine, so clipping before or after
/// it is the same).
fn clip_above(poly: &[(DVec2, f64)], tol: f64, out: &mut Vec<DVec2>) {
    out.clear();
    let n = poly.len();
    for i in 0..n {
        let (p, hp) = poly[i];
        let (q, hq) = poly[(i + 1) % n];
        let (dp, dq) = (hp - tol, hq - tol);
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp > 0.0 && dq < 0.0) || (dp < 0.0 && dq > 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
}

/// A face that may cast a shadow on (or hide) the face being sampled.
#[derive(Debug, Clone, Copy)]
struct Blocker {
    /// Index of the blocking face.
    face: u32,
    centre: DVec3,
    radius: f64,
    normal: DVec3,
    /// Width of shadow to look for between samples, m (its bounding radius).
    feature: f64,
    /// Upper bound of its shadow's area on the face, m².
    shadow_area: f64,
}

impl Blocker {
    /// Half-space proof: all `points` lie on the side of the blocker's plane that `d`
    /// points away from, so rays from them along `d` never cross the plane.
    #[inline]
    fn half_space_clear(&self, d: DVec3, points: &[DVec3], tol: f64) -> bool {
        let dn = d.dot(self.normal);
        if dn == 0.0 {
            return false;
        }
        let s = dn.signum();
        points
            .iter()
            .all(|v| s * self.normal.dot(*v - self.centre) >= -tol)
    }
}

/// The triangles a face is sampled on, and its outline when it is a convex polygon (its
/// area equals its hull's). The triangles are a fan over that outline for a convex face
/// of more than two triangles, else the face's own. The centroid method always samples
/// the mesh's own triangles and needs no outline.
fn pieces_of(
    normal: DVec3,
    area: f64,
    triangles: &[u32],
    corners: &[[DVec3; 3]],
    vertices: &[DVec3],
    mode: VisibilityMode,
) -> (Vec<[DVec3; 3]>, Vec<DVec3>) {
    let own = || triangles.iter().map(|&t| corners[t as usize]).collect();
    if mode == VisibilityMode::Centroid {
        return (own(), Vec::new());
    }
    let (u, w) = crate::radiometry::earth::orthonormal_basis(normal);
    let origin = vertices[0];
    let plane_point = |v: &DVec3| ((*v - origin).dot(u), (*v - origin).dot(w));
    let mut pts: Vec<(f64, f64, usize)> = vertices
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let (x, y) = plane_point(v);
            (x, y, i)
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    // Andrew's monotone chain, counter-clockwise about `normal` (u × w = normal)
    let cross = |o: &(f64, f64, usize), a: &(f64, f64, usize), b: &(f64, f64, usize)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64, usize)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64, usize)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for p in iter {
            while hull.len() >= start + 2
                && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(*p);
        }
        hull.pop();
    }
    if hull.len() < 3 {
        return (own(), Vec::new());
    }
    let hull_area: f64 = (1..hull.len() - 1)
        .map(|i| 0.5 * cross(&hull[0], &hull[i], &hull[i + 1]))
        .sum();
    if (hull_area - area).abs() > 1e-9 * area {
        return (own(), Vec::new()); // not convex (or holes): the mesh's triangles
    }
    let v = |h: &(f64, f64, usize)| vertices[h.2];
    let outline = hull.iter().map(v).collect();
    if triangles.len() <= 2 {
        return (own(), outline);
    }
    let fan = (1..hull.len() - 1)
        .map(|i| [v(&hull[0]), v(&hull[i]), v(&hull[i + 1])])
        .collect();
    (fan, outline)
}

/// Sorts points and drops exact repeats (the corners that neighbouring triangles share).
fn sort_dedup(points: &mut Vec<DVec3>) {
    points.sort_by(|a, b| {
        a.to_array()
            .partial_cmp(&b.to_array())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    points.dedup();
}

/// Does the sphere (c_o, r_o) meet the half-infinite cylinder swept by the sphere
/// (c_f, r_f) along unit `d`?
#[inline]
fn reaches(c_f: DVec3, r_f: f64, c_o: DVec3, r_o: f64, d: DVec3) -> bool {
    let w = c_o - c_f;
    let t = w.dot(d).max(0.0);
    let reach = r_f + r_o;
    (w - d * t).length_squared() < reach * reach
}

/// Patch-level half-space proof: every occluder plane faces away along `d` from a
/// receiver wholly in front of them all (or towards, from one wholly behind).
#[inline]
fn cone_clear(side: Side, p: &Patch, d: DVec3) -> bool {
    match side {
        Side::Front => d.dot(p.axis) > p.sin_half,
        Side::Behind => -d.dot(p.axis) > p.sin_half,
        Side::Mixed => false,
    }
}

/// Can some face of `p_faces` reach the lit/seen side of some face of `q_faces`?
fn may_block(geoms: &[FaceGeom], q_faces: &Range<u32>, p_faces: &Range<u32>, tol: f64) -> bool {
    q_faces.clone().any(|fi| {
        let f = &geoms[fi as usize];
        p_faces.clone().any(|gi| {
            if gi == fi {
                return false;
            }
            let g = &geoms[gi as usize];
            let s = f.normal.dot(g.centroid - f.centroid);
            if s.abs() >= g.radius + tol {
                return s > 0.0 || f.two_sided; // wholly on one side: the sphere decides
            }
            reaches_front(g, f.normal, f.centroid, tol)
                || (f.two_sided && reaches_front(g, -f.normal, f.centroid, tol))
        })
    })
}

/// Does some vertex of `o` lie strictly in front of the plane (`n`, through `p`)? Exact,
/// so the neighbours of a face on a convex part are not taken for occluders.
#[inline]
fn reaches_front(o: &FaceGeom, n: DVec3, p: DVec3, tol: f64) -> bool {
    if n.dot(o.centroid - p) + o.radius <= tol {
        return false;
    }
    if o.vertices.is_empty() {
        return true; // no vertex list (centroid mode): the sphere's answer
    }
    o.vertices.iter().any(|v| n.dot(*v - p) > tol)
}

/// Where the receiver faces lie relative to every plane of the occluder faces.
fn relation(
    geoms: &[FaceGeom],
    q_faces: &Range<u32>,
    p_faces: &Range<u32>,
    tol: f64,
    exact: bool,
) -> Side {
    let (mut front, mut behind) = (true, true);
    for gi in p_faces.clone() {
        let g = &geoms[gi as usize];
        for fi in q_faces.clone() {
            let f = &geoms[fi as usize];
            if exact {
                for v in &f.vertices {
                    let s = g.normal.dot(*v - g.centroid);
                    front &= s >= -tol;
                    behind &= s <= tol;
                }
            } else {
                let s = g.normal.dot(f.centroid - g.centroid);
                front &= s - f.radius >= -tol;
                behind &= s + f.radius <= tol;
            }
            if !front && !behind {
                return Side::Mixed;
            }
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
