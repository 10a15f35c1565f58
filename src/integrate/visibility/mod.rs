//! Which part of a face is both lit and seen: shadowing and occlusion by the mesh itself.
//!
//! Rays are cast only where a face may really be partly shadowed or hidden. Per face and
//! epoch, a direction (to the Sun, the Earth or the observer) is *clear* when no part of
//! the mesh can lie along it; what is not proven clear is clipped exactly, and only what
//! clipping cannot do is sampled. [`Visibility::visible_area`] decides a face (one side,
//! one epoch) by these steps in this order, each ending the face's work when it can:
//!
//! 1. **The lid** ([`lids`]): a face of a convex cap (a dish), on its inner side, sees
//!    out only through the cap's lid (its rim): per direction the lid passes all of it,
//!    none of it, or it is clipped to the lid projected back onto it (decided for many
//!    faces at once, [`caps`]). Where nothing else can reach into the cap that decides the
//!    face — most such faces are summed for the whole epoch from one [`LidTable`] before
//!    `visible_area` is asked.
//! 2. **Whole parts** ([`settle`]): along a direction that one convex part of the mesh (a
//!    box, a dish: [`crate::geometry::convex::ConvexPart`], [`parts`]) hides the whole
//!    face from, it is dark whatever else lies there (a dish's back behind the bus); along
//!    one that every part misses, with no loose face in reach, it is lit (or seen) whole.
//! 3. **The blocker search** ([`blockers`]): the faces that may shadow it along what is
//!    left. Exact tests prove directions clear without rays ([`proofs`]):
//!    - **reach**: the occluder's bounding sphere misses the half-infinite cylinder swept
//!      by the face's bounding sphere along the direction;
//!    - **half-space**: if the face lies wholly in front of an occluder's plane and the
//!      direction points away from that plane (d·n > 0), a ray from the face only moves
//!      further from the plane and can never cross the occluder (likewise behind /
//!      towards). This is what keeps a concave dish lit from in front free of rays.
//!
//!    Faces are grouped into spatial *patches* ([`patches`], with bounding spheres and
//!    normal cones), so whole groups of occluders are dismissed at once, and binned per
//!    epoch across each direction ([`grid`]) when many are left. A part wholly behind a
//!    face, and a face's own part seen from outside, cannot block it: their faces are not
//!    searched at all; nor, for a cap's inner face, are the cap's own (only faces in front
//!    of the lid or inside the cap's hull, [`parts::lid_blockers`]). No blocker left: the
//!    face is lit and seen whole.
//! 4. **Exact clipping** ([`clip`]): each possible blocker face, cut to the part in front
//!    of the face's plane, is projected along the direction onto that plane (a convex
//!    polygon) and subtracted from the face ([`crate::geometry::polygon::Region`]). A
//!    part in front of the face, or cut by its plane (when it has many faces), is
//!    subtracted as one polygon from its silhouette instead of face by face ([`parts`]): a
//!    finely meshed dish over the bus would otherwise cut the bus's top into hundreds of
//!    pieces. That area is exact — no rays, no tolerance — and costs a few polygon splits
//!    per blocker.
//! 5. **Sampling** ([`sampler`]): faces nearly edge-on to a direction (the projection
//!    stretches without bound) or cut into too many pieces are sampled with rays instead,
//!    refining each triangle adaptively (4-way splits) until either the samples agree or a
//!    leaf is small enough that mis-classifying all of it stays within the tolerance's
//!    share of the epoch's signal. The sampler has known limits that clipping does not: a
//!    shadow narrower than its caster's bounding radius, or a shadow corner, can fall
//!    between agreeing samples; and f32 rays at grazing incidence on a neighbour miss some
//!    hits (measured on the box-wing's dish, checked against f64 intersection).
//!
//! What the steps share is built once per request ([`Visibility::build`]): each face's
//! geometry ([`face`], asked about on one [`FaceSide`] at a time), the patches and which may block which, the convex parts with their
//! shadows, planes and normal cones, the caps' trees. The tests check each step against
//! f64 rays and against plain face-by-face clipping (`oracle`, test builds only). What a
//! step holds or decides per direction (view, Sun, Earth) is a [`PerDirection`].

mod blockers;
mod caps;
mod clip;
mod face;
mod grid;
mod lids;
#[cfg(test)]
mod oracle;
mod parts;
mod patches;
mod proofs;
mod sampler;
mod settle;

use crate::geometry::bvh::LazyOccluder;
use crate::geometry::convex::{convex_parts, ConvexPart};
use crate::geometry::Faces;
use crate::integrate::per_direction::{PerDirection, Toward};
use crate::scene::Scene;
use blockers::{Blocker, SearchScratch};
use caps::{CapStates, CapTree, LidState};
use clip::ClipScratch;
pub use face::FaceSide;
use face::{face_geoms, triangle_area, FaceGeom};
use glam::DVec3;
pub use lids::LidTable;
use lids::{dark, open_directions};
use parts::Silhouette;
use patches::{Patch, PatchParts};
use proofs::Side;
use rayon::prelude::*;
use sampler::Sampler;
use settle::{SettleScratch, Settled};

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

/// A face of no convex part (in [`Visibility::part_of`]).
const NO_PART: u32 = u32::MAX;

/// What every step needs of the mesh, built once per request ([`Visibility::build`]).
pub struct Visibility {
    mode: VisibilityMode,
    /// Ray casting, for the faces that clipping leaves to sampling.
    occluder: LazyOccluder,
    faces: Vec<FaceGeom>,
    patches: Vec<Patch>,
    /// Per receiver patch: the occluder patches that may block it, with their relation.
    candidates: Vec<Vec<(u32, Side)>>,
    tol: f64,
    /// Clip partly shadowed faces exactly where possible (else always sample).
    clip: bool,
    /// Cell size of the per-epoch face grids, m: the median face diameter.
    grid_cell: f64,
    /// Connected convex pieces of the mesh (boxes, dishes), each with what the steps keep
    /// of it: each casts its shadow on a face wholly behind it as the hull of its
    /// projected vertices.
    parts: Vec<PartEntry>,
    /// Each face's convex part (index into `parts`; `NO_PART` for none).
    part_of: Vec<u32>,
    /// Faces of no part (a lone plate).
    loose: Vec<u32>,
    /// Per patch: its faces grouped by part.
    patch_parts: PatchParts,
    /// Per face of a cap: its place in the cap's tree order.
    cap_slot: Vec<u32>,
}

/// One convex part and what the steps keep of it (an entry of `Visibility::parts`).
struct PartEntry {
    convex: ConvexPart,
    /// Bounding sphere (centre, radius), m.
    sphere: (DVec3, f64),
    /// Bounding box as its 8 corners, m ([`Visibility::part_cover`]).
    corners: [DVec3; 8],
    /// Planes its hull lies behind ([`parts::hull_planes`]); `None` for a part that cannot
    /// hide a face whole.
    planes: Option<Vec<(DVec3, f64)>>,
    /// Per vertex: the cone of its faces' outward normals ([`parts::normal_cones`]).
    cones: Vec<[f64; 4]>,
    /// For a cap: the faces a ray leaving it from inside can meet
    /// ([`parts::lid_blockers`]).
    lid_blockers: Option<Vec<u32>>,
    /// For a cap: its faces in a ball tree ([`caps`]).
    cap_tree: Option<CapTree>,
}

/// Per-thread scratch, and what one step hands the next for the face at hand. Each step
/// keeps its own buffers in it ([`Cache::reset`] at the start of each epoch).
#[derive(Default)]
pub struct Cache {
    /// The blocker search's ([`Visibility::collect_blockers`]).
    search: SearchScratch,
    /// Per direction: what the face's cover candidates settle ([`Visibility::settle_by_parts`]).
    settled: PerDirection<Settled>,
    /// Buffers for [`Visibility::settle_by_parts`].
    settle: SettleScratch,
    /// Per direction: the parts that may shadow the current face whole (indices into
    /// its `part_shadows`), from [`Visibility::collect_blockers`].
    part_hits: PerDirection<Vec<u32>>,
    /// Per direction, per part: its silhouette this epoch.
    silhouettes: PerDirection<Vec<Silhouette>>,
    /// Buffers for [`Visibility::exact_area`].
    clip: ClipScratch,
    /// Per direction, per part: a cap's face states along it (built on first use).
    cap_states: PerDirection<Vec<CapStates>>,
    /// Buffers for a face's possible blockers per direction (see [`Sampler`]).
    blockers: PerDirection<Vec<Blocker>>,
}

impl Cache {
    /// Forgets what belongs to one epoch: call at the start of each. What is keyed by a
    /// direction alone (parts' silhouettes, caps' face states, projections and grids of
    /// the faces) is kept for the next epoch along the same direction: one request's
    /// mesh, so the same answer (a Sun fixed in the body frame, an Earth at nadir).
    pub fn reset(&mut self) {
        self.search.reset();
    }
}

/// K in the leaf size K·budget/√A (see [`Visibility::visible_area`]).
const LEAF_SIZE_FACTOR: f64 = 8.0;
/// Above this faces × convex parts, parts shadow face by face, not as one hull.
const PART_PAIRS_LIMIT: usize = 10_000_000;

impl Visibility {
    /// Builds the BVH and the occluder candidates. `faces` should be in spatial order
    /// ([`Faces::sort_spatially`]) so that patches are compact.
    pub fn build(scene: &Scene, faces: &Faces, mode: VisibilityMode) -> Visibility {
        let mesh = &scene.mesh;
        let occluder = LazyOccluder::new(mesh);
        let corners: Vec<[DVec3; 3]> = (0..mesh.triangles.len()).map(|i| mesh.corners(i)).collect();
        let (_, scale) = mesh.bounding_sphere();
        let tol = mesh.tolerance_at(scale);
        let nf = faces.len();
        let k = ((nf as f64).sqrt().round() as usize).clamp(1, 1024);
        let per_patch = nf.div_ceil(k);
        // The convex parts (with sequential stretches: welding, sorting edges, building
        // point trees) alongside the faces' own geometry, which is parallel throughout.
        let (mut geoms, mut parts) = rayon::join(
            || face_geoms(scene, faces, &corners, mode, per_patch),
            || {
                if mode == VisibilityMode::Adaptive && scene.clip_shadows {
                    convex_parts(mesh, faces, tol)
                } else {
                    Vec::new()
                }
            },
        );
        let patches = patches::group(&geoms, per_patch);
        let candidates = if mode == VisibilityMode::Centroid {
            Vec::new()
        } else {
            patches::candidates(&geoms, &patches, &parts, tol)
        };
        if mode == VisibilityMode::Centroid {
            for g in &mut geoms {
                g.vertices = Vec::new();
            }
        }
        let part_of = parts::assign(&mut parts, &mut geoms);
        // Which parts shadow each face whole: faces × parts work, and lists that grow with
        // it, so a mesh of very many parts (a debris cloud) keeps tiles instead.
        let part_spheres = parts::spheres(&parts);
        let indices: Vec<parts::VertexIndex> =
            parts.par_iter().map(parts::VertexIndex::new).collect();
        let part_cones = parts::normal_cones(&parts, &indices, &geoms, faces, &corners);
        // the caps' trees (one sequential build each) alongside the parallel part shadows
        let (shadows, cap_trees) = rayon::join(
            || {
                (geoms.len().saturating_mul(parts.len()) <= PART_PAIRS_LIMIT)
                    .then(|| parts::part_shadows(&geoms, &parts, &part_of, &part_spheres, tol))
            },
            || -> Vec<Option<CapTree>> {
                parts
                    .par_iter()
                    .zip(&indices)
                    .map(|(p, index)| p.lid.is_some().then(|| CapTree::new(p, index, &geoms)))
                    .collect()
            },
        );
        for (g, a) in geoms.iter_mut().zip(shadows.into_iter().flatten()) {
            g.part_shadows = a;
        }
        let part_planes = parts::hull_planes(&parts, &geoms);
        if geoms.len().saturating_mul(parts.len()) <= PART_PAIRS_LIMIT {
            let covers =
                parts::cover_candidates(&geoms, &part_of, &part_spheres, &part_planes, tol);
            for (g, c) in geoms.iter_mut().zip(covers) {
                g.covers = c;
            }
        }
        let lid_blockers = parts::lid_blockers(&geoms, &parts, &part_of, tol);
        lids::mark_lid_only(&mut geoms, &part_of, &lid_blockers);
        let cap_slot = caps::slots(&cap_trees, geoms.len());
        let patch_parts = PatchParts::new(&patches, &part_of);
        let part_boxes = parts::boxes(&parts);
        let loose = (0..geoms.len() as u32)
            .filter(|&g| part_of[g as usize] == NO_PART)
            .collect();
        let parts = part_table(
            parts,
            part_spheres,
            part_boxes,
            part_planes,
            part_cones,
            lid_blockers,
            cap_trees,
        );
        Visibility {
            mode,
            occluder,
            part_of,
            loose,
            patch_parts,
            cap_slot,
            faces: geoms,
            patches,
            candidates,
            tol,
            clip: scene.clip_shadows,
            parts,
            grid_cell: grid::cell_size(faces, scale),
        }
    }

    /// Area of `face` (m²) that is both seen and sunlit, and both seen and earthlit, on
    /// side `side`; plus the number of rays cast. `budget` (m²) is the
    /// area of this face whose misclassification the tolerance allows.
    pub fn visible_area(
        &self,
        cache: &mut Cache,
        face: usize,
        side: FaceSide,
        dirs: &Uncertain,
        budget: f64,
    ) -> (f64, f64, u64) {
        let f = &self.faces[face];
        let n = f.normal * side.sign();
        let directions = face_directions(dirs, n);
        if self.lid_decides(f, side) {
            if let Some((a_sun, a_earth)) = self.through_own_lid(cache, face, n, &directions) {
                return (a_sun, a_earth, 0);
            }
        }
        // A shadow edge crosses about perimeter/h leaves of size h, each misjudged by a
        // fraction of its area ~h²: the error ~ perimeter·h·c falls like h, so leaves stop
        // at h = K·budget/√A (perimeter ≈ 4√A) and the error falls like the tolerance, not
        // its square root. The corner-and-centroid estimate makes c small and the leaf
        // errors cancel in part: K = 8 keeps the measured error at about a third of the
        // tolerance (box-wing and trough against converged references).
        let min_size = LEAF_SIZE_FACTOR * budget / f.area.sqrt();
        // Along a direction that one part hides the whole face from, it is dark whatever
        // else lies there: no blockers to search or clip (a dish's back behind the bus).
        // Along one that nothing can shadow it from, it is lit (or seen) whole.
        cache.settled.iter_mut().for_each(Settled::clear);
        let (hidden, clear) = self.settle_by_parts(cache, face, side, &directions);
        if hidden.view {
            return (0.0, 0.0, 0);
        }
        let lit = |k: Toward, a: f64| if hidden[k] { 0.0 } else { a };
        let directions =
            PerDirection::from_fn(|k| directions[k].filter(|_| !hidden[k] && !clear[k]));
        if directions.iter().all(Option::is_none) {
            return (
                lit(Toward::Sun, f.pieces_area),
                lit(Toward::Earth, f.pieces_area),
                0,
            );
        }
        // the blocker lists' buffers are the cache's, kept from face to face
        let mut blockers = std::mem::take(&mut cache.blockers);
        blockers.iter_mut().for_each(Vec::clear);
        let mut s = Sampler::new(
            &self.occluder,
            n,
            f.centroid,
            directions,
            min_size,
            budget,
            blockers,
        );
        let (a_sun, a_earth, rays) = self.shadowed_area(cache, face, side, &directions, &mut s);
        cache.blockers = std::mem::take(&mut s.blockers);
        (lit(Toward::Sun, a_sun), lit(Toward::Earth, a_earth), rays)
    }

    /// [`Visibility::visible_area`] for a face that its own cap's lid does not decide
    /// alone: blockers searched, then clipped exactly, else sampled by `s`.
    fn shadowed_area(
        &self,
        cache: &mut Cache,
        face: usize,
        side: FaceSide,
        directions: &PerDirection<Option<DVec3>>,
        s: &mut Sampler,
    ) -> (f64, f64, u64) {
        let f = &self.faces[face];
        let n = f.normal * side.sign();
        if self.mode == VisibilityMode::Centroid {
            return s.centroids(&f.pieces);
        }
        let lids = self.collect_blockers(cache, face, side, directions, true, &mut s.blockers);
        if lids.view == LidState::Closed {
            return (0.0, 0.0, 0); // the face's own cap hides it
        }
        let open = open_directions(directions, &lids);
        let full_area = f.pieces_area;
        if s.blockers.iter().all(Vec::is_empty)
            && cache.part_hits.iter().all(Vec::is_empty)
            && cache.settled.iter().all(|s| s.ahead.is_empty())
            && lids.iter().all(|l| *l != LidState::Clip)
        {
            let (a_sun, a_earth) = dark(&lids, (full_area, full_area));
            return (a_sun, a_earth, 0);
        }
        if self.mode == VisibilityMode::Adaptive && self.clip {
            if let Some(areas) = self.exact_area(cache, face, n, &open, &s.blockers, &lids) {
                let (a_sun, a_earth) = dark(&lids, areas);
                return (a_sun, a_earth, 0);
            }
            // the sampler needs every blocker face by face: the cap's own and the parts'
            s.blockers.iter_mut().for_each(Vec::clear);
            self.collect_blockers(cache, face, side, directions, false, &mut s.blockers);
        }
        for piece in &f.pieces {
            s.refine(*piece, None, triangle_area(piece), 0, self.tol);
        }
        (s.a_sun, s.a_earth, s.rays)
    }
}

/// The parts' entries from what [`Visibility::build`] made of them one list at a time.
fn part_table(
    parts: Vec<ConvexPart>,
    spheres: Vec<(DVec3, f64)>,
    boxes: Vec<[DVec3; 8]>,
    planes: Vec<Option<Vec<(DVec3, f64)>>>,
    cones: Vec<Vec<[f64; 4]>>,
    lid_blockers: Vec<Option<Vec<u32>>>,
    cap_trees: Vec<Option<CapTree>>,
) -> Vec<PartEntry> {
    parts
        .into_iter()
        .zip(spheres)
        .zip(boxes)
        .zip(planes)
        .zip(cones)
        .zip(lid_blockers)
        .zip(cap_trees)
        .map(
            |((((((convex, sphere), corners), planes), cones), lid_blockers), cap_tree)| {
                PartEntry {
                    convex,
                    sphere,
                    corners,
                    planes,
                    cones,
                    lid_blockers,
                    cap_tree,
                }
            },
        )
        .collect()
}

/// View, Sun and earthshine directions that matter for a face of side normal `n`.
/// Earthshine's representative direction may lie below the face while parts of the Earth
/// light it: no meaningful ray then; it counts as unshadowed.
#[inline]
fn face_directions(dirs: &Uncertain, n: DVec3) -> PerDirection<Option<DVec3>> {
    let earth = dirs.earth.filter(|e| n.dot(*e) > 1e-3);
    PerDirection {
        view: Some(dirs.view),
        sun: dirs.sun,
        earth,
    }
}
