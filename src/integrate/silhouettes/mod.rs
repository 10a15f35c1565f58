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
//! Built once per request: the faces as convex polygons in their planes ([`polygons`]),
//! the edges, adjacency and contacts ([`topology`]), connected patches of faces with
//! the cones of their normals ([`patches`]), and a hierarchy of the polygons for rays
//! ([`rays`]).
//!
//! Per epoch and direction ([`Silhouettes::prepare`]):
//! 1. each patch's cone says whether it faces along d, away, or both ways;
//! 2. the folds are found inside the patches that face both ways and on the rims
//!    between patches that face differently ([`folds`]);
//! 3. the folds are binned across d, and each patch with faces to decide asks for the
//!    folds above its box: a patch that faces along d and that none reaches is *clean*
//!    (one count for all its faces); in the others each face is tested against the
//!    folds found, and each fold that crosses it becomes a line in its plane
//!    ([`lines`]);
//! 4. one ray counts the sheets above the first unit of each connected region, and the
//!    count floods the rest across edges, through crossed faces by the jumps of the
//!    lines a path crosses ([`counts`]).
//!
//! A crossed face ([`Silhouettes::areas`]) is cut by its lines (and its contacts) into
//! convex cells ([`cells`]); a cell's count along each direction is its face's
//! reference count plus the jumps of the lines between them: no ray. Only the cells of a
//! face a contact runs through are decided by rays (the count does not follow the
//! sheets there). Nothing is recognised by shape: a convex mesh has no fold above any
//! face and is one clean region (one ray a direction); a dish, a bell in a skirt or a
//! crumpled fragment cost what their fold lines cost. The areas are exact up to
//! rounding (the tolerance does not enter), except on a face so many lines cross that
//! its cells would exceed [`MAX_CELLS`]: that face is sampled on a fixed grid of
//! points instead.

mod cells;
mod counts;
mod folds;
mod lines;
mod patches;
mod polygons;
mod rays;
mod topology;

use crate::geometry::{Faces, Mesh};
use crate::scene::Scene;
use cells::{area_centroid, Cells, Cutter};
use folds::Fold;
use glam::{DVec2, DVec3};
use lines::{Across, Line, LineGrid};
use patches::{Facing, Patches};
use polygons::Polygons;
use rays::Rays;
use topology::Topology;

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

/// A patch's state along one direction.
const OFF: u8 = 0; // no face of it to decide along d
const CLEAN: u8 = 1; // faces along d as a whole and no fold is above it: one count
const DIRTY: u8 = 2; // decided face by face

/// A face's state along one direction, in a dirty patch.
const NOT_RECEIVER: u8 = 0; // not asked about, or faces away along d
const UNCROSSED: u8 = 1; // no line crosses it: one count
const CROSSED: u8 = 2; // lines cross it: a reference count, cells
const RAYS: u8 = 3; // a contact runs through it (or no count could be had): rays per cell

/// A count not known yet.
const UNKNOWN: i32 = i32::MIN;
/// Dark, by a ray that could not count the sheets.
const DARK_ONLY: i32 = i32::MIN + 1;

/// One direction's state in an epoch (kept for the next epoch when the direction is the
/// same: a Sun fixed in the body frame).
#[derive(Default)]
pub struct Direction {
    d: Option<DVec3>,
    across: Across,
    /// Per patch: its facing, state, and count (clean patches).
    facing: Vec<Facing>,
    patch: Vec<u8>,
    patch_count: Vec<i32>,
    /// Per face (meaningful in dirty patches): state, count (at the reference point of
    /// a crossed face, in its plane), and its range of `lines`.
    face: Vec<u8>,
    face_count: Vec<i32>,
    face_ref: Vec<DVec2>,
    face_lines: Vec<(u32, u32)>,
    lines: Vec<Line>,
    folds: Vec<Fold>,
    grid: LineGrid,
    /// Per fold: the last patch query that met it (candidates once per patch).
    stamp: Vec<u32>,
    query: u32,
    /// The folds above the patch being decided, with their boxes across d and tops;
    /// its receivers' footprints, and their corners across d.
    near: Vec<Near>,
    footprint: Vec<Footprint>,
    corners: Vec<DVec2>,
    queue: Vec<counts::Unit>,
    /// Per face: asked about when the direction was last prepared.
    asked: Vec<bool>,
    /// Rays cast for this direction's counts, and whether this epoch asked for the
    /// direction (its rays count for the epoch even when kept from the last, so the
    /// count does not depend on which thread ran which epoch).
    rays: u64,
    used: bool,
}

impl Default for Across {
    fn default() -> Self {
        Across {
            d: DVec3::Z,
            u: DVec3::X,
            w: DVec3::Y,
            eps: 0.0,
            tol: 0.0,
        }
    }
}

/// A fold near a patch: its box across d (m), its top along d (m), its index.
#[derive(Clone, Copy)]
struct Near {
    lo: DVec2,
    hi: DVec2,
    top: f64,
    fold: u32,
}

/// Does the line through fold `f` (across d) pass through the box `lo`–`hi`?
#[inline]
fn line_meets_box(f: &Fold, lo: DVec2, hi: DVec2) -> bool {
    let e = f.pb - f.pa;
    let s = |x: f64, y: f64| e.perp_dot(DVec2::new(x, y) - f.pa);
    let c = [s(lo.x, lo.y), s(hi.x, lo.y), s(lo.x, hi.y), s(hi.x, hi.y)];
    c.iter().any(|&v| v >= 0.0) && c.iter().any(|&v| v <= 0.0)
}

/// A receiving face across d: its box (m, widened by the tolerance), its lowest point
/// along d (m, raised by the rounding height), its range of corners.
#[derive(Clone, Copy)]
struct Footprint {
    face: u32,
    corners: (u32, u32),
    lo: DVec2,
    hi: DVec2,
    bottom: f64,
}

impl Direction {
    /// Face `f`'s lines (empty unless it is crossed).
    #[inline]
    fn lines_of(&self, f: usize) -> &[Line] {
        if !matches!(self.face[f], CROSSED | RAYS) {
            return &[];
        }
        let (a, b) = self.face_lines[f];
        &self.lines[a as usize..b as usize]
    }
}

/// Per-thread buffers.
#[derive(Default)]
pub struct Scratch {
    dirs: [Direction; 3],
    /// Per face and per patch: which directions this epoch asks about (bit k: direction
    /// k). Only these faces take shadows: a face the observer does not see, or that no
    /// light reaches, needs no count along any direction.
    wanted: Vec<u8>,
    patch_wanted: Vec<u8>,
    cells: Cells,
    cutter: Cutter,
    lines: Vec<(DVec2, DVec2)>,
    polygon: Vec<DVec2>,
}

/// How one direction decides a face.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Status {
    Clear,
    Dark,
    /// By its cells' counts.
    Counted,
    /// By a ray from each cell.
    Rays,
}

impl<'a> Silhouettes<'a> {
    pub fn build(scene: &'a Scene, faces: &Faces) -> Silhouettes<'a> {
        let mesh = &scene.mesh;
        let mut tri_face = vec![0u32; mesh.triangles.len()];
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
        let polys = Polygons::build(mesh, faces, two_sided);
        let patches = Patches::build(&polys, &topo);
        let rays = Rays::build(&polys, &topo.open);
        let mut triangles_at = vec![0u32];
        let mut triangles = Vec::with_capacity(mesh.triangles.len());
        for f in &faces.faces {
            triangles.extend_from_slice(&f.triangles);
            triangles_at.push(triangles.len() as u32);
        }
        Silhouettes {
            mesh,
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
    /// which directions: (face, seen-and-sunlit wanted, seen-and-earthlit wanted). Call
    /// before [`Silhouettes::prepare`].
    pub fn want(&self, scratch: &mut Scratch, faces: impl Iterator<Item = (u32, bool, bool)>) {
        scratch.wanted.clear();
        scratch.wanted.resize(self.polys.faces(), 0);
        scratch.patch_wanted.clear();
        scratch.patch_wanted.resize(self.patches.len(), 0);
        for (f, sun, earth) in faces {
            let bits = 1 | (sun as u8) << 1 | (earth as u8) << 2;
            scratch.wanted[f as usize] = bits;
            scratch.patch_wanted[self.patches.of_face[f as usize] as usize] |= bits;
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
        folds::find(
            &self.patches,
            &self.topo,
            &dir.facing,
            &self.polys.normal,
            d,
            u,
            w,
            |f| self.blocks(f as usize, d),
            &mut dir.folds,
        );
        dir.grid.build(&dir.folds, self.tol);
        dir.stamp.clear();
        dir.stamp.resize(dir.folds.len(), 0);
        dir.query = 0;
        dir.patch.clear();
        dir.patch.resize(np, OFF);
        dir.patch_count.clear();
        dir.patch_count.resize(np, UNKNOWN);
        dir.face.resize(nf, NOT_RECEIVER);
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
        dir.rays = self.flood(dir);
    }

    /// Patch `p`'s receivers along the direction: the patch clean, or each face asked
    /// about with the lines that cross it.
    fn receivers(&self, dir: &mut Direction, wanted: &[u8], bit: u8, p: usize) {
        let across = dir.across;
        let (d, u, w) = (across.d, across.u, across.w);
        let facing = dir.facing[p];
        let faces = self.patches.faces_of(p);
        let whole = facing == Facing::Along
            || (facing == Facing::Away && self.polys.two_sided[faces[0] as usize]);
        // the folds above the patch's box, each once
        let (c, h) = (self.patches.centre[p], self.patches.half[p]);
        let reach = |a: DVec3| h.x * a.x.abs() + h.y * a.y.abs() + h.z * a.z.abs();
        let at = DVec2::new(c.dot(u), c.dot(w));
        let half = DVec2::new(reach(u), reach(w)) + DVec2::splat(self.tol);
        let bottom = c.dot(d) - reach(d) - self.eps;
        dir.query = dir.query.wrapping_add(1);
        let query = dir.query;
        dir.near.clear();
        {
            let (folds, stamp, near) = (&dir.folds, &mut dir.stamp, &mut dir.near);
            let (plo, phi) = (at - half, at + half);
            dir.grid.query(plo, phi, |i| {
                let iu = i as usize;
                if stamp[iu] == query {
                    return;
                }
                stamp[iu] = query;
                let fold = &folds[iu];
                if fold.top <= bottom {
                    return;
                }
                let (lo, hi) = (fold.pa.min(fold.pb), fold.pa.max(fold.pb));
                if lo.cmpgt(phi).any() || hi.cmplt(plo).any() || !line_meets_box(fold, plo, phi) {
                    return;
                }
                near.push(Near {
                    lo,
                    hi,
                    top: fold.top,
                    fold: i,
                });
            });
        }
        if whole && dir.near.is_empty() && !self.patches.contacts[p] {
            dir.patch[p] = CLEAN;
            return;
        }
        dir.patch[p] = DIRTY;
        // the receivers with their corners across d: their boxes there and their
        // bottoms along d, and the patch's own footprint, tighter than its box's
        dir.footprint.clear();
        dir.corners.clear();
        let (mut plo, mut phi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for &f in faces {
            let f = f as usize;
            dir.face_count[f] = UNKNOWN;
            if wanted[f] & bit == 0 || !self.receives(f, d) {
                dir.face[f] = NOT_RECEIVER;
                continue;
            }
            let first = dir.corners.len() as u32;
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            let mut bottom = f64::INFINITY;
            for k in self.polys.of(f) {
                for &q in self.polys.corners3(k) {
                    let a = DVec2::new(q.dot(u), q.dot(w));
                    dir.corners.push(a);
                    lo = lo.min(a);
                    hi = hi.max(a);
                    bottom = bottom.min(q.dot(d));
                }
            }
            plo = plo.min(lo);
            phi = phi.max(hi);
            dir.footprint.push(Footprint {
                face: f as u32,
                corners: (first, dir.corners.len() as u32),
                lo: lo - DVec2::splat(self.tol),
                hi: hi + DVec2::splat(self.tol),
                bottom: bottom + self.eps,
            });
        }
        plo -= DVec2::splat(self.tol);
        phi += DVec2::splat(self.tol);
        let folds = &dir.folds;
        dir.near.retain(|n| {
            !(n.lo.cmpgt(phi).any() || n.hi.cmplt(plo).any())
                && line_meets_box(&folds[n.fold as usize], plo, phi)
        });
        for i in 0..dir.footprint.len() {
            let fp = dir.footprint[i];
            let f = fp.face as usize;
            let start = dir.lines.len() as u32;
            self.face_lines(dir, &fp);
            self.contact_lines(dir, f);
            dir.face_lines[f] = (start, dir.lines.len() as u32);
            let crossed = dir.lines.len() as u32 > start;
            // A path between two points of a face that is not convex may leave it. And
            // where another piece meets a face, the meeting segments are found triangle
            // pair by pair: one whose triangles share a corner with the face's is left
            // out (it cannot be told from two neighbours meeting at that corner), so the
            // count cannot be trusted to follow the lines there: rays per cell.
            let touched = !self.topo.contacts_of(f).is_empty();
            dir.face[f] = if touched || (crossed && !self.polys.convex[f]) {
                RAYS
            } else if crossed {
                CROSSED
            } else {
                UNCROSSED
            };
        }
    }

    /// Appends to `dir.lines` the contacts on face `f` across which its count changes.
    fn contact_lines(&self, dir: &mut Direction, f: usize) {
        let d = dir.across.d;
        let (n, o) = (self.polys.normal[f], self.polys.point[f]);
        for c in self.topo.contacts_of(f) {
            let blocks = self.blocks(c.face as usize, d);
            let jump = c.jump(n, o, d, self.eps, blocks, |x| self.polys.to2(f, x));
            if jump != 0 {
                dir.lines.push(Line {
                    p: self.polys.to2(f, c.a),
                    q: self.polys.to2(f, c.b),
                    jump,
                    bounds: true,
                });
            }
        }
    }

    /// Appends to `dir.lines` the lines of the folds near its patch (`dir.near`) that
    /// cross the face of footprint `fp`.
    fn face_lines(&self, dir: &mut Direction, fp: &Footprint) {
        let across = dir.across;
        let f = fp.face as usize;
        let corners = &dir.corners[fp.corners.0 as usize..fp.corners.1 as usize];
        let one = (self.polys.of(f).len() == 1).then_some(corners);
        for near in &dir.near {
            if near.top <= fp.bottom || near.lo.cmpgt(fp.hi).any() || near.hi.cmplt(fp.lo).any() {
                continue;
            }
            let fold = &dir.folds[near.fold as usize];
            if let Some(line) = lines::crossing(&self.polys, f, fold, &across, one) {
                dir.lines.push(line);
            }
        }
    }

    /// Rays that this epoch's counts took (for the summary's count).
    pub fn group_rays(&self, scratch: &Scratch) -> u64 {
        scratch.dirs.iter().filter(|d| d.used).map(|d| d.rays).sum()
    }

    /// How direction `dir` decides face `f`.
    fn status(&self, dir: &Direction, f: usize) -> Status {
        let by_count = |c: i32| if c == 0 { Status::Clear } else { Status::Dark };
        let p = self.patches.of_face[f] as usize;
        match dir.patch[p] {
            CLEAN => by_count(dir.patch_count[p]),
            DIRTY => match dir.face[f] {
                UNCROSSED => by_count(dir.face_count[f]),
                CROSSED => {
                    let lines = dir.lines_of(f);
                    // so many sheets above its reference that its lines cannot take
                    // them all away: dark all over, nothing to cut; no line it may turn
                    // dark across: as its reference
                    let most: i32 = lines.iter().map(|l| l.jump.abs()).sum();
                    if dir.face_count[f] > most {
                        Status::Dark
                    } else if !lines.iter().any(|l| l.bounds) {
                        by_count(dir.face_count[f])
                    } else {
                        Status::Counted
                    }
                }
                RAYS => Status::Rays,
                _ => Status::Clear,
            },
            // not asked about along this direction: it faces away, so no light of it
            // needs deciding
            _ => Status::Clear,
        }
    }

    /// Areas (m²) of `face` (area `area`, m²) that are seen and sunlit, and seen and
    /// earthlit, with the directions prepared for this epoch; `sun` and `earth` say
    /// which are wanted; plus the rays cast.
    pub fn areas(
        &self,
        scratch: &mut Scratch,
        face: usize,
        area: f64,
        sun: bool,
        earth: bool,
    ) -> (f64, f64, u64) {
        let want = [true, sun, earth];
        let status: [Status; 3] = std::array::from_fn(|k| {
            if !want[k] || !scratch.dirs[k].used {
                Status::Clear
            } else {
                self.status(&scratch.dirs[k], face)
            }
        });
        if status[0] == Status::Dark {
            return (0.0, 0.0, 0);
        }
        let cut = |s: Status| matches!(s, Status::Counted | Status::Rays);
        if !status.iter().any(|&s| cut(s)) {
            let lit = |k: usize| {
                if want[k] && status[k] == Status::Clear {
                    area
                } else {
                    0.0
                }
            };
            return (lit(1), lit(2), 0);
        }
        // cut the face by the lines crossing it along the directions it is crossed
        // along, and by its contacts
        scratch.lines.clear();
        for (dir, _) in scratch.dirs.iter().zip(status).filter(|(_, s)| cut(*s)) {
            scratch.lines.extend(
                dir.lines_of(face)
                    .iter()
                    .filter(|l| l.bounds)
                    .map(|l| (l.p, l.q)),
            );
        }
        let cells = &mut scratch.cells;
        cells.clear();
        let mut whole = true;
        if scratch.lines.len() <= FEW_LINES && self.polys.of(face).len() == 1 {
            // a few lines: split along each whole line, no bookkeeping of which segment
            // reaches which piece (the pieces are finer than they need be, never
            // coarser)
            cells.push(
                self.polys
                    .corners2(self.polys.of(face).start)
                    .iter()
                    .copied(),
            );
            for &(p, q) in &scratch.lines {
                cells.split(p, q - p, self.tol, usize::MAX);
            }
        } else {
            for k in self.polys.of(face) {
                let poly = &mut scratch.polygon;
                poly.clear();
                poly.extend_from_slice(self.polys.corners2(k));
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
        }
        let dirs = &scratch.dirs;
        let mut rays = 0u64;
        // (seen and sunlit, seen and earthlit) at a point of the face (its plane's
        // coordinates)
        let mut decide = |q: DVec2| -> (bool, bool) {
            let mut open = [true; 3];
            for k in 0..3 {
                open[k] = match status[k] {
                    Status::Clear => true,
                    Status::Dark => false,
                    Status::Counted => {
                        let dir = &dirs[k];
                        dir.face_count[face]
                            + lines::crossed(dir.lines_of(face), dir.face_ref[face], q)
                            == 0
                    }
                    Status::Rays => {
                        rays += 1;
                        let d = dirs[k].across.d;
                        let x = self.polys.to3(face, q);
                        !self.rays.blocked(
                            &self.polys,
                            &self.topo.open,
                            x,
                            d,
                            face as u32,
                            self.eps,
                        )
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
                let (s, e) = decide(c);
                a_sun += if s { a } else { 0.0 };
                a_earth += if e { a } else { 0.0 };
            }
        } else {
            // too many lines for cells: a fixed grid of points on each triangle
            let (t0, t1) = (self.triangles_at[face], self.triangles_at[face + 1]);
            for &t in &self.triangles[t0 as usize..t1 as usize] {
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
                            let (s, e) = decide(self.polys.to2(face, pt));
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
        let faces = Faces::build(mesh, true);
        let mut tri_face = vec![0u32; mesh.triangles.len()];
        for (i, f) in faces.faces.iter().enumerate() {
            for &t in &f.triangles {
                tri_face[t as usize] = i as u32;
            }
        }
        let two_sided = vec![false; faces.len()];
        let topo = Topology::build(mesh, &faces, &tri_face, &two_sided, 1e-9);
        let polys = Polygons::build(mesh, &faces, two_sided);
        let patches = Patches::build(&polys, &topo);
        Built {
            polys,
            topo,
            patches,
        }
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
