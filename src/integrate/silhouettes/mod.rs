//! Which part of each face is lit and seen, from the mesh's fold lines: exact, for any
//! mesh, at a cost that follows the shadow and outline lines rather than the faces.
//!
//! Along a direction d (to the observer, the Sun or the Earth), a point of a face sees
//! out when no sheet of the surface lies above it. How many do (its *count*) changes
//! only across
//! - the shadow of a *fold* edge: where the surface folds over as seen along d (one
//!   side faces along d, the other away), an open surface's border, or where more than
//!   two sheets meet; the count jumps there by the sheets on one side less those on the
//!   other ([`topology::Edge::jump`]), or
//! - a line where another piece of the mesh meets the face inside it (a *contact*: a
//!   boom's foot on the bus), fixed in the body frame ([`topology`]).
//!
//! Built once per request: the faces as convex polygons in their planes ([`polygons`];
//! a face of many, as a tree of their boxes: [`polygon_tree`]),
//! the edges and adjacency ([`topology`]), where separate pieces meet ([`contacts`];
//! never between two triangles of one [`sheets`] sheet, proven to cross nowhere),
//! connected patches of faces with the cones of their normals ([`patches`]) and each
//! patch's form Σ A n nᵀ for summing it whole ([`sums`]), and a hierarchy of the
//! polygons for rays ([`rays`]). An articulated mesh builds all but
//! the last once per part and moves them to each pose ([`posed`]). Before the build,
//! [`Silhouettes::build_ordered`] puts the faces in patch order, so that each
//! direction reads a patch's faces from one run of every per-face table.
//!
//! Per epoch and direction ([`Silhouettes::prepare`]):
//! 1. each patch's cone says whether it faces along d, away, or both ways;
//! 2. the folds are found inside the patches that face both ways and on the rims
//!    between patches that face differently ([`folds`]);
//! 3. the folds are put in a tree of their boxes across d ([`fold_tree`]), and each
//!    patch with faces to decide asks it for the folds above its box (a flat one keeps
//!    those that may shade its [`slab`]): a patch that faces along d and that none
//!    reaches is *clean* (one count for all its faces), and so is one whose faces no
//!    fold crosses; in the others each face is tested against the folds found, and each
//!    fold that crosses it becomes a line in its plane ([`direction`], [`lines`]);
//! 4. one ray counts the sheets above the first unit of each connected region, and the
//!    count floods the rest across edges, through crossed faces by the jumps of the
//!    lines a path crosses ([`counts`]).
//!
//! A patch of one material whose lights are linear over its normals' cone and that no
//! direction decides face by face is summed whole from its form, with no BRDF or area
//! per face ([`sums`]; the caller lists it, `integrate::eq12`).
//!
//! A crossed face ([`Silhouettes::areas`], in [`areas`]) is cut by its lines into convex
//! cells ([`cells`]); a cell's count along each direction is its face's reference count
//! plus the jumps of the lines between them: no ray (the view's lines cut first, and only
//! the cells seen cut by the lights'). A contact on a face is one of its lines, with the
//! jump of the other piece's sheet across it ([`contacts::Contact::jump`]), its ends
//! joined to the lines of the other piece's folds that pierce the face there
//! ([`lines::join_at_contacts`]). Only the cells of a crossed face that is not convex (a
//! path between two of its points may leave it) are decided by rays, cut along every
//! contact, one ray per region of each direction's own lines and the face's contacts
//! ([`ray_memo`]). Nothing is
//! recognised by shape: a convex mesh has no fold above any face and is one clean
//! region (one ray a direction); a dish, a bell in a skirt or a crumpled fragment cost
//! what their fold lines cost. The areas are exact up to
//! rounding (the tolerance does not enter), except on a face so many lines cross that
//! its cells would exceed [`MAX_CELLS`]: that face is sampled on a fixed grid of
//! points instead.

mod areas;
mod cells;
mod contacts;
mod counts;
mod direction;
mod fan;
mod fold_tree;
mod folds;
mod level_grid;
mod lines;
mod patches;
mod polygon_tree;
mod polygons;
pub mod posed;
mod ray_memo;
mod rays;
mod sheets;
mod slab;
mod sums;
pub mod tally;
mod topology;

use super::per_direction::{PerDirection, Toward};
use crate::geometry::faces::WeldedEdge;
use crate::geometry::{Faces, Mesh};
use crate::scene::Scene;
use cells::{Cells, Cutter};
use contacts::PairSearch;
pub use contacts::TriangleGrid;
use direction::{Direction, FaceState, PatchState, UNKNOWN};
use glam::{DVec2, DVec3};
use lines::Across;
use patches::order_by_patches;
use patches::Patches;
use polygons::Polygons;
use rays::Rays;
use std::sync::atomic::{AtomicBool, Ordering};
pub use sums::PatchLight;
use tally::Tally;
use topology::{Topology, NONE};

/// Most cells a face is cut into before it is sampled instead.
const MAX_CELLS: usize = 4096;
/// Most lines a one-polygon face is split along whole (at most 2^k pieces, in practice
/// k + 1 to 2k) rather than cut where each segment reaches.
const FEW_LINES: usize = 3;
/// Points per triangle side when a face is sampled (SAMPLES² per triangle).
const SAMPLES: usize = 16;

/// What is built once per request.
pub struct Silhouettes<'a> {
    mesh: &'a Mesh,
    polys: Polygons,
    topo: Topology,
    patches: Patches,
    /// Per patch: what summing it whole takes.
    sums: sums::PatchSums,
    rays: Rays,
    /// Per face: its triangles (CSR; a face too finely cut is sampled triangle by
    /// triangle).
    triangles_at: Vec<u32>,
    triangles: Vec<u32>,
    /// Height (m) above a face that counts as in front of it: rounding, not geometry.
    eps: f64,
    /// Distance (m) within which a line counts as touching a face.
    tol: f64,
}

/// Per-thread buffers.
#[derive(Default)]
pub struct Scratch {
    dirs: PerDirection<Direction>,
    /// Per face and per patch: which directions this epoch asks about ([`Toward::bit`]s).
    /// Only these faces take shadows: a face the observer does not see, or that no light
    /// reaches, needs no count along any direction.
    wanted: Vec<u8>,
    patch_wanted: Vec<u8>,
    cells: Cells,
    cutter: Cutter,
    /// Per direction: ray answers shared between a face's cells.
    memo: PerDirection<ray_memo::RayMemo>,
    lines: Vec<(DVec2, DVec2)>,
    /// The lines near one cell of a face.
    near: Vec<(DVec2, DVec2)>,
    /// Per direction, the lines of the face being cut in buckets of angle about its
    /// reference, when it has many.
    fans: PerDirection<fan::Fan>,
}

/// Per triangle its face, and per face whether its material is two-sided.
fn face_tables(scene: &Scene, faces: &Faces) -> (Vec<u32>, Vec<bool>) {
    let tri_face = faces.triangle_faces(scene.mesh.triangles.len());
    let two_sided = faces
        .faces
        .iter()
        .map(|f| scene.materials[f.material as usize].two_sided)
        .collect();
    (tri_face, two_sided)
}

impl<'a> Silhouettes<'a> {
    /// [`Silhouettes::build`] after renumbering `faces` in patch order
    /// (`patches::order_by_patches`): each direction then reads a patch's faces from one
    /// run of every per-face table, not from all over them.
    /// `grid`: the scene's [`Silhouettes::contact_grid`] when built already.
    pub fn build_ordered(
        scene: &'a Scene,
        faces: &mut Faces,
        grid: Option<TriangleGrid>,
    ) -> Silhouettes<'a> {
        Silhouettes::build_with(scene, faces, grid, |faces, sorted| {
            order_by_patches(&scene.mesh, faces, sorted, |m| {
                scene.materials[m as usize].two_sided
            })
        })
    }

    /// What the search for contacts needs of the mesh alone: it may be built while the
    /// faces merge, then handed to [`Silhouettes::build_ordered`].
    pub fn contact_grid(mesh: &Mesh) -> TriangleGrid {
        TriangleGrid::build(mesh, mesh.tolerance())
    }

    pub fn build(scene: &'a Scene, faces: &Faces) -> Silhouettes<'a> {
        Silhouettes::build_with(scene, &mut faces.clone(), None, |_, _| {})
    }

    /// The silhouettes of `faces` once `arrange(faces, sorted)` has renumbered them (given
    /// the mesh's welded edges, [`Faces::welded_edges`]).
    fn build_with(
        scene: &'a Scene,
        faces: &mut Faces,
        grid: Option<TriangleGrid>,
        arrange: impl FnOnce(&mut Faces, &[WeldedEdge]) + Send,
    ) -> Silhouettes<'a> {
        tally::add(Tally::Preparations, 1);
        let mesh = &scene.mesh;
        // the height above a face that counts as in front of it: rounding, not geometry
        let eps = mesh.tolerance();
        // The contact search (a third of the work at ~200k triangles) reads only which
        // triangles share a face, not how the faces are numbered: the thread that would
        // wait while the other renumbers them starts it, and both finish it beside the
        // edges and the polygons.
        let face_as_merged = faces.triangle_faces(mesh.triangles.len());
        // the welded tables taken out of `faces` while the search reads them and the
        // faces are renumbered, and put back after (their copy was paid in page faults
        // on one thread while the other waited)
        let (welded, edges, taken) = faces.take_welded_edges(mesh);
        let mut search = PairSearch::new(mesh, (&welded, &edges), &face_as_merged, None, eps, grid);
        let renumbered = AtomicBool::new(false);
        rayon::join(
            || {
                tally::timed(Tally::RenumberNs, || arrange(faces, &edges));
                renumbered.store(true, Ordering::Relaxed);
            },
            || tally::timed(Tally::ContactSearchNs, || search.run_until(&renumbered)),
        );
        let (tri_face, two_sided) = face_tables(scene, faces);
        // the topology and the polygons need only the faces, the patches and the rays
        // only those two: built two at a time
        let ((topo, pairs), polys) = {
            let faces = &*faces;
            rayon::join(
                || {
                    rayon::join(
                        || {
                            tally::timed(Tally::TopologyNs, || {
                                let welded = (&welded[..], &edges[..]);
                                Topology::without_contacts(
                                    mesh, faces, welded, &tri_face, &two_sided, eps,
                                )
                            })
                        },
                        || tally::timed(Tally::ContactSearchNs, || search.finish()),
                    )
                },
                || {
                    tally::timed(Tally::PolygonsNs, || {
                        Polygons::build(mesh, faces, two_sided.clone(), eps)
                    })
                },
            )
        };
        faces.put_back_welded_edges((welded, edges, taken));
        let faces = &*faces;
        let topo = topo.with_contacts(pairs.on_faces(mesh, &tri_face, eps));
        let (patches, rays) = rayon::join(
            || tally::timed(Tally::PatchesNs, || Patches::build(&polys, &topo)),
            || tally::timed(Tally::RaysTreeNs, || Rays::build(&polys, &topo.open)),
        );
        Silhouettes::assemble(mesh, faces, (polys, topo, patches, rays), eps)
    }

    /// The silhouettes from their parts.
    fn assemble(
        mesh: &'a Mesh,
        faces: &Faces,
        (polys, topo, patches, rays): (Polygons, Topology, Patches, Rays),
        eps: f64,
    ) -> Silhouettes<'a> {
        let mut triangles_at = vec![0u32];
        let mut triangles = Vec::with_capacity(mesh.triangles.len());
        for f in &faces.faces {
            triangles.extend_from_slice(&f.triangles);
            triangles_at.push(triangles.len() as u32);
        }
        let sums = sums::PatchSums::build(faces, &patches);
        Silhouettes {
            mesh,
            sums,
            triangles_at,
            triangles,
            polys,
            topo,
            patches,
            rays,
            eps,
            tol: eps,
        }
    }

    /// Does face `f`'s sheet count along unit `d` (it faces along d, or it belongs to an
    /// open piece, and it is not edge-on)?
    #[inline]
    fn blocks(&self, f: usize, d: DVec3) -> bool {
        let nd = self.polys.normal[f].dot(d);
        nd.abs() > 1e-12 && (self.topo.open[f] || nd > 0.0)
    }

    /// Does face `f` take light along unit `d` on one of its sides?
    #[inline]
    fn receives(&self, f: usize, d: DVec3) -> bool {
        let nd = self.polys.normal[f].dot(d);
        nd > 1e-12 || (self.polys.two_sided[f] && nd < -1e-12)
    }

    /// Says which faces this epoch will ask [`Silhouettes::areas`] about, and along
    /// which directions: (face, seen-and-sunlit wanted, seen-and-earthlit wanted), and
    /// (patch, the same) for patches all of whose faces are asked about alike. Call
    /// before [`Silhouettes::prepare`].
    pub fn want(
        &self,
        scratch: &mut Scratch,
        faces: impl Iterator<Item = (u32, bool, bool)>,
        patches: impl Iterator<Item = (u32, bool, bool)>,
    ) {
        let bits_of = |sun: bool, earth: bool| {
            Toward::View.bit()
                | if sun { Toward::Sun.bit() } else { 0 }
                | if earth { Toward::Earth.bit() } else { 0 }
        };
        scratch.wanted.clear();
        scratch.wanted.resize(self.polys.faces(), 0);
        scratch.patch_wanted.clear();
        scratch.patch_wanted.resize(self.patches.len(), 0);
        for (f, sun, earth) in faces {
            let bits = bits_of(sun, earth);
            scratch.wanted[f as usize] = bits;
            scratch.patch_wanted[self.patches.of_face[f as usize] as usize] |= bits;
        }
        // a patch's faces noted over their run where they are one (at ~200k triangles a
        // smooth surface's patches hold most of the faces asked about)
        for (p, sun, earth) in patches {
            let (p, bits) = (p as usize, bits_of(sun, earth));
            let faces = self.patches.faces_of(p);
            match self.patches.run[p] {
                NONE => faces
                    .iter()
                    .for_each(|&f| scratch.wanted[f as usize] = bits),
                first => {
                    let first = first as usize;
                    scratch.wanted[first..first + faces.len()].fill(bits);
                }
            }
            scratch.patch_wanted[p] |= bits;
        }
    }

    /// Brings `scratch`'s direction `toward` to unit `d` (in the body frame) for this
    /// epoch, for the faces [`Silhouettes::want`] named; `None`: not asked about this
    /// epoch (the Sun in umbra, no earthshine).
    pub fn prepare(&self, scratch: &mut Scratch, toward: Toward, d: Option<DVec3>) {
        let dir = &mut scratch.dirs[toward];
        let Some(d) = d else {
            dir.used = false;
            return;
        };
        dir.used = true;
        let bit = toward.bit();
        let wanted = &scratch.wanted;
        // kept from the last epoch (a Sun fixed in the body frame) when every face asked
        // about now was asked about then
        if dir.d == Some(d)
            && dir.asked.len() == wanted.len()
            && !dir
                .asked
                .iter()
                .zip(wanted)
                .any(|(&then, &now)| now & bit != 0 && !then)
        {
            return;
        }
        dir.d = Some(d);
        dir.asked.clear();
        dir.asked.extend(wanted.iter().map(|w| w & bit != 0));
        let (u, w) = polygons::basis(d);
        dir.across = Across {
            d,
            u,
            w,
            eps: self.eps,
            tol: self.tol,
        };
        let np = self.patches.len();
        let nf = self.polys.faces();
        dir.facing.clear();
        dir.facing
            .extend((0..np).map(|p| self.patches.facing(p, d)));
        let since = tally::now();
        folds::find(
            &self.patches,
            &self.topo,
            &dir.facing,
            &self.polys.normal,
            d,
            u,
            w,
            |f| self.blocks(f as usize, d),
            (&mut dir.maybe_folds, &mut dir.folds),
        );
        tally::took(Tally::FoldSearchNs, since);
        let since = tally::now();
        dir.mark_folds(self.topo.edges.len());
        dir.tree.build(&mut dir.folds);
        tally::took(Tally::FoldTreeNs, since);
        dir.patch.clear();
        dir.patch.resize(np, PatchState::Off);
        dir.patch_count.clear();
        dir.patch_count.resize(np, UNKNOWN);
        dir.face.resize(nf, FaceState::NotReceiver);
        dir.face_count.resize(nf, UNKNOWN);
        dir.face_ref.resize(nf, DVec2::ZERO);
        dir.face_lines.resize(nf, (0, 0));
        dir.lines.clear();
        for p in 0..np {
            if scratch.patch_wanted[p] & bit == 0 {
                continue;
            }
            self.receivers(dir, wanted, bit, p);
        }
        dir.rays = tally::timed(Tally::FloodNs, || self.flood(dir));
        if tally::ON {
            self.tally(dir);
        }
    }

    /// Adds what deciding `dir` took to the counts ([`tally`]).
    fn tally(&self, dir: &Direction) {
        use tally::add;
        add(Tally::Directions, 1);
        add(Tally::Folds, dir.folds.len() as u64);
        add(Tally::Lines, dir.lines.len() as u64);
        for p in 0..self.patches.len() {
            match dir.patch[p] {
                PatchState::Clean => add(Tally::CleanPatches, 1),
                PatchState::Dirty => {
                    let faces = self.patches.faces_of(p);
                    add(Tally::DirtyPatches, 1);
                    add(Tally::DirtyFaces, faces.len() as u64);
                    let crossed = faces.iter().filter(|&&f| {
                        matches!(dir.face[f as usize], FaceState::Crossed | FaceState::Rays)
                    });
                    add(Tally::CrossedFaces, crossed.count() as u64);
                }
                PatchState::Off => {}
            }
        }
    }

    /// Rays that this epoch's counts took (for the summary's count).
    pub fn group_rays(&self, scratch: &Scratch) -> u64 {
        scratch.dirs.iter().filter(|d| d.used).map(|d| d.rays).sum()
    }
}

/// Meshes and the structures built on them, for the unit tests of the parts.
#[cfg(test)]
mod fixtures {
    use super::*;

    /// A mesh's faces (coplanar triangles merged, all one-sided), polygons, topology and
    /// patches.
    pub struct Built {
        pub polys: Polygons,
        pub topo: Topology,
        pub patches: Patches,
    }

    pub fn build(mesh: &Mesh) -> Built {
        of_faces(mesh, &Faces::build(mesh, true))
    }

    /// [`build`] on faces already made (and perhaps reordered).
    pub fn of_faces(mesh: &Mesh, faces: &Faces) -> Built {
        let tri_face = faces.triangle_faces(mesh.triangles.len());
        let two_sided = vec![false; faces.len()];
        let topo = Topology::build_within(mesh, faces, &tri_face, &two_sided, None, 1e-9, None);
        let polys = Polygons::build(mesh, faces, two_sided, 1e-9);
        let patches = Patches::build(&polys, &topo);
        Built {
            polys,
            topo,
            patches,
        }
    }

    /// Adds to `mesh` a geodesic ball (`crate::geometry::builtin::geodesic_sphere(n, r)`)
    /// centred at `centre`, material 0.
    pub fn push_ball(mesh: &mut Mesh, n: u32, r: f64, centre: DVec3) {
        let ball = crate::geometry::builtin::geodesic_sphere(n, r);
        let base = mesh.vertices.len() as u32;
        mesh.vertices
            .extend(ball.vertices.iter().map(|v| *v + centre));
        mesh.triangles
            .extend(ball.triangles.iter().map(|t| t.map(|k| k + base)));
        mesh.material_ids.resize(mesh.triangles.len(), 0);
    }

    /// Directions spread over the sphere, none along an axis (a box's faces are never
    /// edge-on to them).
    pub fn directions() -> Vec<DVec3> {
        (0..40)
            .map(|i| {
                // a Fibonacci spiral, turned off the axes
                let z = 1.0 - (2.0 * i as f64 + 1.0) / 40.0;
                let phi = i as f64 * 2.399_963_229_728_653 + 0.1;
                let r = (1.0 - z * z).sqrt();
                DVec3::new(r * phi.cos(), r * phi.sin(), z).normalize()
            })
            .collect()
    }
}
