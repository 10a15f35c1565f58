//! Which part of each face is lit and seen, from the mesh's silhouettes: exact, for any
//! mesh, at a cost that follows the shadow and outline edges rather than the faces.
//!
//! Along a direction d (to the observer, the Sun or the Earth), whether a point of a face
//! can see out changes only where
//! - the shadow of a *silhouette* edge falls: an edge whose two triangles face opposite
//!   ways along d, or an open surface's border (the outline of whatever lies in front,
//!   seen along d, is made of these); a *valley* of a closed piece (the surface turning
//!   inward) never counts: its shadow runs inside the solid on both sides, or
//! - another piece of the mesh meets the face's plane inside the face (a *contact*: a
//!   boom's foot on the bus), fixed in the body frame ([`topology`]).
//!
//! So per epoch and direction ([`Direction::prepare`]):
//! 1. the mesh is projected across d and binned ([`grid`]): a ray along d is a point
//!    query there;
//! 2. each silhouette edge marks the faces its shadow crosses (the grid's cells along its
//!    projection, below it): these are the *edge* faces;
//! 3. every other face is wholly clear or wholly dark along d, and so is every face
//!    joined to it across edges that no shadow crosses: the faces are flooded in
//!    connected groups and one ray decides each group;
//! 4. an edge face ([`Silhouettes::areas`]) is cut by the lines of the shadows that cross
//!    it (and its contacts) into convex cells ([`cells`]), each wholly clear or dark along
//!    every direction: one ray from each cell's centroid decides it.
//!
//! Nothing is recognised by shape: a convex mesh has no shadow edges in front of any
//! face and its faces form one group (one ray); a dish, a bell in a skirt or a crumpled
//! fragment cost what their shadow lines cost. The areas are exact up to rounding (the
//! tolerance does not enter), except on a face that so many shadows cross that its cells
//! would exceed [`MAX_CELLS`]: that face is sampled on a fixed grid of points instead.

mod cells;
mod grid;
mod topology;

use crate::geometry::{Faces, Mesh};
use crate::scene::Scene;
use cells::{area_centroid, Cells, Cutter};
use glam::{DVec2, DVec3};
use grid::{Grid, Polygons};
use topology::{Topology, NONE};

/// Most cells a face is cut into before it is sampled instead.
const MAX_CELLS: usize = 4096;
/// Points per triangle side when a face is sampled (SAMPLES² per triangle).
const SAMPLES: usize = 16;

/// What is built once per request (the mesh's own vertices are borrowed; only the
/// polygons' corners are copied).
pub struct Silhouettes<'a> {
    mesh: &'a Mesh,
    /// Per face: unit normal, a point of its plane, a basis of the plane, two-sidedness,
    /// and its first triangle (a point inside it decides its group).
    face_normal: Vec<DVec3>,
    face_point: Vec<DVec3>,
    face_basis: Vec<(DVec3, DVec3)>,
    two_sided: Vec<bool>,
    face_first: Vec<u32>,
    /// The faces as convex polygons (a face's outline when it is convex, however finely
    /// it is meshed; else its triangles): vertex indices (`spans` into `index`) and face;
    /// per face, its range of polygons.
    poly_spans: Vec<(u32, u32)>,
    poly_index: Vec<u32>,
    /// The polygons' corners (m), each once: what a direction projects. A face meshed
    /// finely but convex is its outline alone, so its inner vertices cost nothing.
    poly_vertices: Vec<DVec3>,
    poly_face: Vec<u32>,
    face_polygons: Vec<(u32, u32)>,
    topo: Topology,
    /// Height (m) above a face that counts as in front of it: rounding, not geometry.
    eps: f64,
    /// Distance (m) within which a shadow line counts as touching a face.
    tol: f64,
}

/// A face's state along one direction.
const OFF: u8 = 0; // faces away: nothing to decide
const CLEAR: u8 = 1;
const DARK: u8 = 2;
const EDGE: u8 = 3; // a shadow or contact line crosses it: cut into cells
const UNSET: u8 = 4;
const SKIP: u8 = 5; // faces along d, but this epoch does not ask about it

/// One direction's state in an epoch (kept for the next epoch when the direction is the
/// same: a Sun fixed in the body frame).
#[derive(Default)]
pub struct Direction {
    d: Option<DVec3>,
    grid: Grid,
    status: Vec<u8>,
    /// (face, edge) for every silhouette edge whose shadow crosses the face, sorted.
    pairs: Vec<(u32, u32)>,
    silhouette: Vec<bool>,
    /// Per face: it faces along d.
    facing: Vec<bool>,
    queue: Vec<u32>,
    /// Rays cast for this direction's groups (one per group), and whether this epoch
    /// asked for the direction (its groups' rays count for the epoch even when kept
    /// from the last, so the count does not depend on which thread ran which epoch).
    rays: u64,
    used: bool,
}

/// Per-thread buffers.
#[derive(Default)]
pub struct Scratch {
    dirs: [Direction; 3],
    /// Per face: which directions this epoch asks about (bit k: direction k). Only
    /// these faces take shadows: a face the observer does not see, or that no light
    /// reaches, needs no status along any direction.
    wanted: Vec<u8>,
    cells: Cells,
    cutter: Cutter,
    lines: Vec<(DVec2, DVec2)>,
    polygon: Vec<DVec2>,
}

impl<'a> Silhouettes<'a> {
    pub fn build(scene: &'a Scene, faces: &Faces) -> Silhouettes<'a> {
        let mesh = &scene.mesh;
        let nt = mesh.triangles.len();
        let mut tri_face = vec![0u32; nt];
        for (i, f) in faces.faces.iter().enumerate() {
            for &t in &f.triangles {
                tri_face[t as usize] = i as u32;
            }
        }
        let two_sided: Vec<bool> = faces
            .faces
            .iter()
            .map(|f| scene.materials[f.material as usize].two_sided)
            .collect();
        let (_, scale) = mesh.bounding_sphere();
        let eps = 1e-9 * scale;
        let topo = Topology::build(mesh, faces, &tri_face, &two_sided, eps);
        let face_point: Vec<DVec3> = faces
            .faces
            .iter()
            .map(|f| mesh.vertices[mesh.triangles[f.triangles[0] as usize][0] as usize])
            .collect();
        let face_basis: Vec<(DVec3, DVec3)> = faces
            .faces
            .iter()
            .map(|f| crate::geometry::orthonormal_basis(f.normal))
            .collect();
        let (mut poly_spans, mut poly_index, mut poly_face) = (Vec::new(), Vec::new(), Vec::new());
        let mut face_polygons = Vec::with_capacity(faces.len());
        let (mut pts, mut ids, mut order, mut hull) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (i, f) in faces.faces.iter().enumerate() {
            let (u, w) = face_basis[i];
            let o = face_point[i];
            let to2 = |p: DVec3| DVec2::new((p - o).dot(u), (p - o).dot(w));
            let first = poly_spans.len() as u32;
            let mut push = |corners: &[u32]| {
                let s = poly_index.len() as u32;
                poly_index.extend_from_slice(corners);
                poly_spans.push((s, poly_index.len() as u32));
                poly_face.push(i as u32);
            };
            pts.clear();
            ids.clear();
            for &t in &f.triangles {
                for v in mesh.triangles[t as usize] {
                    pts.push(to2(mesh.vertices[v as usize]));
                    ids.push(v);
                }
            }
            let mut convex = false;
            if f.triangles.len() > 1 {
                crate::geometry::polygon::convex_hull(&pts, &mut order, &mut hull);
                let (a, _) = area_centroid(&hull);
                convex = hull.len() >= 3 && (a - f.area).abs() <= 1e-9 * f.area;
            }
            if convex {
                let corners: Vec<u32> = hull
                    .iter()
                    .map(|h| {
                        ids[pts
                            .iter()
                            .position(|p| p == h)
                            .expect("a hull point is a corner")]
                    })
                    .collect();
                push(&corners);
            } else {
                for tri in ids.chunks(3) {
                    push(tri);
                }
            }
            face_polygons.push((first, poly_spans.len() as u32));
        }
        // the corners renumbered, in order of first use (neighbours stay near)
        let mut renumber = vec![u32::MAX; mesh.vertices.len()];
        let mut poly_vertices = Vec::new();
        for v in poly_index.iter_mut() {
            let r = &mut renumber[*v as usize];
            if *r == u32::MAX {
                *r = poly_vertices.len() as u32;
                poly_vertices.push(mesh.vertices[*v as usize]);
            }
            *v = *r;
        }
        Silhouettes {
            mesh,
            face_normal: faces.faces.iter().map(|f| f.normal).collect(),
            face_point,
            face_basis,
            face_polygons,
            poly_spans,
            poly_index,
            poly_vertices,
            poly_face,
            two_sided,
            face_first: faces.faces.iter().map(|f| f.triangles[0]).collect(),
            topo,
            eps,
            tol: eps,
        }
    }

    fn polygons(&self) -> Polygons<'_> {
        Polygons {
            vertices: &self.poly_vertices,
            spans: &self.poly_spans,
            index: &self.poly_index,
            face: &self.poly_face,
            normal: &self.face_normal,
            point: &self.face_point,
        }
    }

    /// Says which faces this epoch will ask [`Silhouettes::areas`] about, and along
    /// which directions: (face, seen-and-sunlit wanted, seen-and-earthlit wanted). Call
    /// before [`Silhouettes::prepare`].
    pub fn want(&self, scratch: &mut Scratch, faces: impl Iterator<Item = (u32, bool, bool)>) {
        scratch.wanted.clear();
        scratch.wanted.resize(self.face_normal.len(), 0);
        for (f, sun, earth) in faces {
            scratch.wanted[f as usize] = 1 | (sun as u8) << 1 | (earth as u8) << 2;
        }
    }

    /// Brings `scratch`'s direction `k` (0 view, 1 Sun, 2 Earth) to `d` for this epoch,
    /// for the faces [`Silhouettes::want`] named.
    pub fn prepare(&self, scratch: &mut Scratch, k: usize, d: Option<DVec3>) {
        let dir = &mut scratch.dirs[k];
        let Some(d) = d else {
            dir.used = false;
            return;
        };
        dir.used = true;
        let bit = 1u8 << k;
        let wanted = &scratch.wanted;
        // kept from the last epoch (a Sun fixed in the body frame) when every face asked
        // about now was decided then
        if dir.d == Some(d)
            && !dir
                .status
                .iter()
                .zip(wanted)
                .any(|(&s, &w)| s == SKIP && w & bit != 0)
        {
            return;
        }
        dir.d = Some(d);
        dir.rays = 0;
        let mesh = self.polygons();
        let open = &self.topo.open;
        // which faces face along d, found once for the grid, the statuses and the edges
        dir.facing.clear();
        dir.facing
            .extend(self.face_normal.iter().map(|n| n.dot(d) > 0.0));
        let facing_of = &dir.facing;
        let facing = |f: u32| facing_of[f as usize];
        // a closed piece blocks a ray only where the ray leaves it: through a face
        // facing along d
        dir.grid.build(&mesh, d, |p| {
            let f = self.poly_face[p];
            facing(f) || open[f as usize]
        });
        let nf = self.face_normal.len();
        dir.status.clear();
        dir.status.extend((0..nf).map(|f| {
            // on either side (a two-sided face's back faces along d too)
            let along = facing(f as u32) || (self.two_sided[f] && self.face_normal[f].dot(d) < 0.0);
            if !along {
                OFF
            } else if wanted[f] & bit == 0 {
                SKIP
            } else if self.topo.contacts_at[f] != self.topo.contacts_at[f + 1] {
                EDGE
            } else {
                UNSET
            }
        }));
        // silhouette edges and the faces their shadows cross
        dir.pairs.clear();
        dir.silhouette.clear();
        dir.silhouette.resize(self.topo.edges.len(), false);
        for (i, e) in self.topo.edges.iter().enumerate() {
            let fold = e.f1 == NONE || e.always || (!e.valley && facing(e.f0) != facing(e.f1));
            if !fold {
                continue;
            }
            dir.silhouette[i] = true;
            let blocks = |f: u32| f != NONE && (facing(f) || open[f as usize]);
            if !(blocks(e.f0) || blocks(e.f1)) {
                continue;
            }
            let status = &dir.status;
            let pairs = &mut dir.pairs;
            dir.grid.shadowed_by(
                &mesh,
                e.a,
                e.b,
                self.eps,
                self.tol,
                |p| !matches!(status[self.poly_face[p] as usize], OFF | SKIP),
                |p| pairs.push((self.poly_face[p as usize], i as u32)),
            );
        }
        dir.pairs.sort_unstable();
        dir.pairs.dedup();
        for &(f, _) in &dir.pairs {
            dir.status[f as usize] = EDGE;
        }
        // the rest in groups joined across edges no shadow crosses: one ray a group
        for start in 0..nf {
            if dir.status[start] != UNSET {
                continue;
            }
            let [a, b, c] = self.mesh.corners(self.face_first[start] as usize);
            let p = (a + b + c) / 3.0;
            dir.rays += 1;
            let s = if dir.grid.blocked(&mesh, p, start as u32, self.eps) {
                DARK
            } else {
                CLEAR
            };
            dir.status[start] = s;
            dir.queue.clear();
            dir.queue.push(start as u32);
            while let Some(f) = dir.queue.pop() {
                for &(g, e) in self.topo.neighbours(f as usize) {
                    if dir.status[g as usize] == UNSET && !dir.silhouette[e as usize] {
                        dir.status[g as usize] = s;
                        dir.queue.push(g);
                    }
                }
            }
        }
    }

    /// Rays that deciding this epoch's groups took (for the summary's count).
    pub fn group_rays(&self, scratch: &Scratch) -> u64 {
        scratch.dirs.iter().filter(|d| d.used).map(|d| d.rays).sum()
    }

    /// Areas (m²) of `face` (area `area`, m², made of the mesh's `triangles`) that are
    /// seen and sunlit, and seen and earthlit, with the directions prepared for this epoch;
    /// `sun` and `earth` say which are wanted; plus the rays cast.
    #[allow(clippy::too_many_arguments)]
    pub fn areas(
        &self,
        scratch: &mut Scratch,
        face: usize,
        area: f64,
        triangles: &[u32],
        sun: bool,
        earth: bool,
    ) -> (f64, f64, u64) {
        let want = [true, sun, earth];
        let status: [u8; 3] = std::array::from_fn(|k| {
            if !want[k] || !scratch.dirs[k].used {
                CLEAR
            } else {
                match scratch.dirs[k].status[face] {
                    OFF => CLEAR,
                    SKIP => unreachable!("face {face} was not asked about along direction {k}"),
                    s => s,
                }
            }
        });
        if status[0] == DARK {
            return (0.0, 0.0, 0);
        }
        if !status.contains(&EDGE) {
            let lit = |k: usize| {
                if want[k] && status[k] == CLEAR {
                    area
                } else {
                    0.0
                }
            };
            return (lit(1), lit(2), 0);
        }
        // cut the face by the lines of every shadow crossing it along the directions it
        // is an edge face of, and by its contacts
        let n = self.face_normal[face];
        let (u, w) = self.face_basis[face];
        let o = self.face_point[face];
        let to2 = |p: DVec3| {
            let r = p - o;
            DVec2::new(r.dot(u), r.dot(w))
        };
        scratch.lines.clear();
        for (dir, _) in scratch.dirs.iter().zip(status).filter(|(_, s)| *s == EDGE) {
            let d = dir.d.expect("prepared");
            let nd = n.dot(d);
            let from = dir.pairs.partition_point(|p| p.0 < face as u32);
            for &(f, e) in &dir.pairs[from..] {
                if f != face as u32 {
                    break;
                }
                let e = &self.topo.edges[e as usize];
                // along d onto the face's plane
                let onto = |x: DVec3| to2(x - d * (n.dot(x - o) / nd));
                scratch.lines.push((onto(e.a), onto(e.b)));
            }
        }
        for &(a, b) in self.topo.contacts_of(face) {
            scratch.lines.push((to2(a), to2(b)));
        }
        let cells = &mut scratch.cells;
        cells.clear();
        let (first, last) = self.face_polygons[face];
        let mut whole = true;
        let poly = &mut scratch.polygon;
        for &(a, b) in &self.poly_spans[first as usize..last as usize] {
            poly.clear();
            poly.extend(
                self.poly_index[a as usize..b as usize]
                    .iter()
                    .map(|&v| to2(self.poly_vertices[v as usize])),
            );
            let room = MAX_CELLS.saturating_sub(cells.len());
            whole &= scratch
                .cutter
                .cut(poly, &scratch.lines, self.tol, room, |c| {
                    cells.push(c.iter().copied())
                });
            if !whole {
                break;
            }
        }
        let mesh = self.polygons();
        let dirs = &scratch.dirs;
        let mut rays = 0u64;
        // (seen and sunlit, seen and earthlit) at a point of the face
        let mut decide = |x: DVec3| -> (bool, bool) {
            let mut open = [true; 3];
            for k in 0..3 {
                open[k] = match status[k] {
                    CLEAR => true,
                    DARK => false,
                    _ => {
                        rays += 1;
                        !dirs[k].grid.blocked(&mesh, x, face as u32, self.eps)
                    }
                };
                if k == 0 && !open[0] {
                    return (false, false);
                }
            }
            (open[0] && open[1], open[0] && open[2])
        };
        let (mut a_sun, mut a_earth) = (0.0, 0.0);
        if whole {
            for i in 0..cells.len() {
                let (a, c) = area_centroid(cells.cell(i));
                if a <= 0.0 {
                    continue;
                }
                let (s, e) = decide(o + u * c.x + w * c.y);
                a_sun += if s { a } else { 0.0 };
                a_earth += if e { a } else { 0.0 };
            }
        } else {
            // too many shadows for cells: a fixed grid of points on each triangle
            for &t in triangles {
                let [p0, p1, p2] = self.mesh.corners(t as usize);
                let at = 0.5 * (p1 - p0).cross(p2 - p0).length();
                let per = at / (SAMPLES * SAMPLES) as f64;
                for i in 0..SAMPLES {
                    for j in 0..SAMPLES - i {
                        // the sub-triangles' centroids: the upward one, and the
                        // downward one beside it where there is one
                        let up = (i as f64 + 1.0 / 3.0, j as f64 + 1.0 / 3.0);
                        let down = (i as f64 + 2.0 / 3.0, j as f64 + 2.0 / 3.0);
                        let sub = [Some(up), (j + 1 < SAMPLES - i).then_some(down)];
                        for (x, y) in sub.into_iter().flatten() {
                            let (bx, by) = (x / SAMPLES as f64, y / SAMPLES as f64);
                            let pt = p0 + (p1 - p0) * bx + (p2 - p0) * by;
                            let (s, e) = decide(pt);
                            a_sun += if s { per } else { 0.0 };
                            a_earth += if e { per } else { 0.0 };
                        }
                    }
                }
            }
        }
        let lit = |k: usize, a: f64| if want[k] { a } else { 0.0 };
        (lit(1, a_sun), lit(2, a_earth), rays)
    }
}
