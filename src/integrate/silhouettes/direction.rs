//! One direction's state in an epoch ([`Direction`]) and how a patch's receivers are
//! decided along it ([`Silhouettes::receivers`], step 3 of the map in the module above):
//! the folds above the patch, the patch clean when none reaches it, or each receiving
//! face with the fold lines that cross it.

use super::fan::Fan;
use super::fold_tree::FoldTree;
use super::folds::Fold;
use super::lines::{self, Across, Line};
use super::patches::Facing;
use super::slab::SlabAlong;
use super::tally::{self, Tally};
use super::Silhouettes;
use crate::geometry::polygon;
use glam::{DVec2, DVec3};

/// A patch's state along one direction.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum PatchState {
    /// No face of it to decide along d.
    Off,
    /// Faces along d as a whole and no fold is above it, or none that crosses one of
    /// its faces: one count.
    Clean,
    /// Decided face by face.
    Dirty,
}

/// A face's state along one direction, in a dirty patch.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum FaceState {
    /// Not asked about, or it faces away along d.
    NotReceiver,
    /// No line crosses it: one count.
    Uncrossed,
    /// Lines cross it: a reference count, cells.
    Crossed,
    /// Lines cross it and it is not convex, so a path between two of its points may
    /// leave it (or no count could be had): rays per cell.
    Rays,
}

/// A unit of the flood: a clean patch, or a receiving face of a patch lines reach.
#[derive(Clone, Copy)]
pub(super) enum Unit {
    Patch(u32),
    Face(u32),
}

/// A count not known yet.
pub(super) const UNKNOWN: i32 = i32::MIN;
/// Dark, by a ray that could not count the sheets.
pub(super) const DARK_ONLY: i32 = i32::MIN + 1;

/// One direction's state in an epoch (kept for the next epoch when the direction is the
/// same: a Sun fixed in the body frame).
#[derive(Default)]
pub struct Direction {
    pub(super) d: Option<DVec3>,
    pub(super) across: Across,
    /// Per patch: its facing, state, and count (clean patches).
    pub(super) facing: Vec<Facing>,
    pub(super) patch: Vec<PatchState>,
    pub(super) patch_count: Vec<i32>,
    /// Per face (meaningful in dirty patches): state, count (at the reference point of
    /// a crossed face, in its plane), and its range of `lines`.
    pub(super) face: Vec<FaceState>,
    pub(super) face_count: Vec<i32>,
    pub(super) face_ref: Vec<DVec2>,
    pub(super) face_lines: Vec<(u32, u32)>,
    pub(super) lines: Vec<Line>,
    pub(super) folds: Vec<Fold>,
    /// The edges the fold search found may be folds, before it reads them
    /// ([`super::folds::find`]).
    pub(super) maybe_folds: Vec<u32>,
    /// Per edge, a bit: whether it is one of `folds` (so the flood need not test it
    /// again). Bits, not a stamp per edge: at ~200k triangles a stamp per edge (1.2 MB)
    /// left the cache, and the flood asks about every edge it crosses.
    pub(super) fold_bits: Vec<u64>,
    pub(super) tree: FoldTree,
    /// The folds above the patch being decided, with their boxes across d and tops;
    /// its receivers' footprints; the corners across d of the face being tested.
    pub(super) near: Vec<Near>,
    pub(super) footprint: Vec<Footprint>,
    pub(super) corners: Vec<DVec2>,
    pub(super) queue: Vec<Unit>,
    /// Per face: asked about when the direction was last prepared.
    pub(super) asked: Vec<bool>,
    /// Rays cast for this direction's counts, and whether this epoch asked for the
    /// direction (its rays count for the epoch even when kept from the last, so the
    /// count does not depend on which thread ran which epoch).
    pub(super) rays: u64,
    pub(super) used: bool,
}

/// A fold near a patch: its box across d (m), its top along d (m), its index.
#[derive(Clone, Copy)]
pub(super) struct Near {
    lo: DVec2,
    hi: DVec2,
    top: f64,
    fold: u32,
}

/// Does the line through fold `f` (across d) pass through the box `lo`–`hi`?
#[inline]
fn line_meets_box(f: &Fold, lo: DVec2, hi: DVec2) -> bool {
    polygon::line_meets_box(f.pa, f.pb, lo, hi)
}

/// A receiving face across d, bounded by its sphere: its box (m, widened by the
/// tolerance) and its lowest point along d (m, raised by the rounding height).
#[derive(Clone, Copy)]
pub(super) struct Footprint {
    face: u32,
    lo: DVec2,
    hi: DVec2,
    bottom: f64,
}

impl Direction {
    /// Marks the edges of `folds` (on a topology of `edges` edges).
    pub(super) fn mark_folds(&mut self, edges: usize) {
        self.fold_bits.clear();
        self.fold_bits.resize(edges.div_ceil(64), 0);
        for f in &self.folds {
            self.fold_bits[f.edge as usize / 64] |= 1 << (f.edge % 64);
        }
    }

    /// Is edge `e` one of the folds found?
    #[inline]
    pub(super) fn is_fold(&self, e: u32) -> bool {
        self.fold_bits[e as usize / 64] >> (e % 64) & 1 != 0
    }

    /// Face `f`'s lines (empty unless it is crossed).
    #[inline]
    pub(super) fn lines_of(&self, f: usize) -> &[Line] {
        if !matches!(self.face[f], FaceState::Crossed | FaceState::Rays) {
            return &[];
        }
        let (a, b) = self.face_lines[f];
        &self.lines[a as usize..b as usize]
    }

    /// Face `f`'s lines that can bound light, as segments in its plane's coordinates (m).
    #[inline]
    pub(super) fn bounding_lines(&self, f: usize) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        self.lines_of(f)
            .iter()
            .filter(|l| l.bounds)
            .map(|l| (l.p, l.q))
    }

    /// Does point `q` of crossed face `f` (its plane's coordinates) see out along this
    /// direction: its reference count plus the jumps of the lines on the way, zero?
    #[inline]
    pub(super) fn counts_none_at(&self, f: usize, q: DVec2) -> bool {
        self.face_count[f] + lines::crossed(self.lines_of(f), self.face_ref[f], q) == 0
    }

    /// [`Direction::counts_none_at`], the lines read through `fan` (built from face `f`'s
    /// lines about its reference) when there is one.
    #[inline]
    pub(super) fn counts_none_via(&self, f: usize, q: DVec2, fan: Option<&Fan>) -> bool {
        match fan {
            Some(fan) => self.face_count[f] + fan.crossed(self.lines_of(f), q) == 0,
            None => self.counts_none_at(f, q),
        }
    }
}

impl Silhouettes<'_> {
    /// Patch `p`'s receivers along the direction: the patch clean, or each face asked
    /// about with the lines that cross it.
    pub(super) fn receivers(&self, dir: &mut Direction, wanted: &[u8], bit: u8, p: usize) {
        let facing = dir.facing[p];
        let faces = self.patches.faces_of(p);
        let whole = facing == Facing::Along
            || (facing == Facing::Away && self.polys.two_sided[faces[0] as usize]);
        // of the folds over a patch's box, a patch that faces one way keeps those that
        // may shade its slab
        let slab = match whole {
            true => self.patches.slab[p].along(dir.across.d, self.tol),
            false => None,
        };
        tally::timed(Tally::QueriesNs, || self.folds_above(dir, p, slab.as_ref()));
        if whole && dir.near.is_empty() && !self.patches.contacts[p] {
            dir.patch[p] = PatchState::Clean;
            return;
        }
        dir.patch[p] = PatchState::Dirty;
        let since = tally::now();
        let (plo, phi) = self.footprints(dir, wanted, bit, faces);
        let folds = &dir.folds;
        dir.near.retain(|n| {
            !(n.lo.cmpgt(phi).any() || n.hi.cmplt(plo).any())
                && line_meets_box(&folds[n.fold as usize], plo, phi)
        });
        tally::took(Tally::FootprintsNs, since);
        let since = tally::now();
        for i in 0..dir.footprint.len() {
            let fp = dir.footprint[i];
            self.classify(dir, &fp);
        }
        tally::took(Tally::FaceLinesNs, since);
        // Folds pass over the patch's box but no line crosses any of its faces: nothing
        // folds inside a patch that faces one way, so its count is one all over, as if
        // no fold were above it. Its faces then flood as one unit (on a tumbling box-wing,
        // three in five of the patches folds pass over).
        if whole
            && !self.patches.contacts[p]
            && dir.footprint.len() == faces.len()
            && faces
                .iter()
                .all(|&f| dir.face[f as usize] == FaceState::Uncrossed)
        {
            dir.patch[p] = PatchState::Clean;
        }
    }

    /// Fills `dir.near` with the folds above patch `p`'s box, each once (with `slab`,
    /// only those that may shade it).
    fn folds_above(&self, dir: &mut Direction, p: usize, slab: Option<&SlabAlong>) {
        let Across { d, u, w, .. } = dir.across;
        let (c, h) = (self.patches.centre[p], self.patches.half[p]);
        let reach = |a: DVec3| h.x * a.x.abs() + h.y * a.y.abs() + h.z * a.z.abs();
        let at = DVec2::new(c.dot(u), c.dot(w));
        let half = DVec2::new(reach(u), reach(w)) + DVec2::splat(self.tol);
        let bottom = c.dot(d) - reach(d) - self.eps;
        dir.near.clear();
        let (folds, near) = (&dir.folds, &mut dir.near);
        let (plo, phi) = (at - half, at + half);
        dir.tree.query(plo, phi, bottom, |i| {
            tally::add(Tally::QueryFolds, 1);
            let fold = &folds[i as usize];
            if fold.top <= bottom {
                tally::add(Tally::QueryBelow, 1);
                return;
            }
            let (lo, hi) = fold.box_across();
            if lo.cmpgt(phi).any() || hi.cmplt(plo).any() || !line_meets_box(fold, plo, phi) {
                tally::add(Tally::QueryOffBox, 1);
                return;
            }
            if slab.is_some_and(|s| !s.may_shade(fold.a, fold.b)) {
                tally::add(Tally::QueryOffSlab, 1);
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

    /// Fills `dir.footprint` with the receivers among `faces` (a dirty patch's), each
    /// bounded across d by the box of its sphere (most faces no fold comes near: their
    /// corners are projected only when one does, [`Silhouettes::face_lines`]). Returns
    /// the patch's footprint (widened by the tolerance).
    fn footprints(
        &self,
        dir: &mut Direction,
        wanted: &[u8],
        bit: u8,
        faces: &[u32],
    ) -> (DVec2, DVec2) {
        let Across { d, u, w, .. } = dir.across;
        dir.footprint.clear();
        let (mut plo, mut phi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for &f in faces {
            let f = f as usize;
            dir.face_count[f] = UNKNOWN;
            if wanted[f] & bit == 0 || !self.receives(f, d) {
                dir.face[f] = FaceState::NotReceiver;
                continue;
            }
            let (c, r) = (self.polys.centre[f], self.polys.radius[f]);
            let at = DVec2::new(c.dot(u), c.dot(w));
            let (lo, hi) = (at - DVec2::splat(r), at + DVec2::splat(r));
            plo = plo.min(lo);
            phi = phi.max(hi);
            dir.footprint.push(Footprint {
                face: f as u32,
                lo: lo - DVec2::splat(self.tol),
                hi: hi + DVec2::splat(self.tol),
                bottom: c.dot(d) - r + self.eps,
            });
        }
        (plo - DVec2::splat(self.tol), phi + DVec2::splat(self.tol))
    }

    /// Gives the receiver of footprint `fp` its lines (folds and contacts) and its state.
    fn classify(&self, dir: &mut Direction, fp: &Footprint) {
        let f = fp.face as usize;
        let start = dir.lines.len();
        self.face_lines(dir, fp);
        let folds_end = dir.lines.len();
        self.contact_lines(dir, f);
        // Another piece's fold edge pierces the face where two of its contacts meet:
        // the fold's line and the contacts end there, computed apart (the line on the
        // face's fitted plane, the contacts on its triangles'), and a path through the
        // gap between their ends would cross neither. Ends within a margin are joined:
        // the gap is the planes' rounding over the sine of the angle at which the edge
        // pierces (2.5e-9 m on the held-out truss), and no point nearer a line than the
        // margin is trusted with a count anyway.
        if folds_end < dir.lines.len() {
            lines::join_at_contacts(&mut dir.lines[start..], folds_end - start, self.margin(f));
        }
        dir.face_lines[f] = (start as u32, dir.lines.len() as u32);
        let crossed = dir.lines.len() > start;
        // A path between two points of a face that is not convex may leave it: rays per
        // cell. A contact is counted across as a fold's line is, by its jump (none
        // across the foot of a wall that faces away: near it the piece lies above the
        // face on both sides, a ray from outside entering it through the wall, one from
        // inside the foot starting in it).
        dir.face[f] = if crossed && !self.polys.convex[f] {
            FaceState::Rays
        } else if crossed {
            FaceState::Crossed
        } else {
            FaceState::Uncrossed
        };
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
    /// cross the face of footprint `fp`: its corners are projected across d once a fold
    /// reaches its sphere's box, and bound it from then on.
    fn face_lines(&self, dir: &mut Direction, fp: &Footprint) {
        let across = dir.across;
        let Across { d, u, w, .. } = across;
        let f = fp.face as usize;
        let Direction {
            near,
            folds,
            corners,
            lines,
            ..
        } = dir;
        // without short circuits: the five outcomes are hard to predict, and which one
        // rejects a fold varies from fold to fold
        let misses = |n: &Near, lo: DVec2, hi: DVec2, bottom: f64| {
            (n.top <= bottom)
                | (n.lo.x > hi.x)
                | (n.lo.y > hi.y)
                | (n.hi.x < lo.x)
                | (n.hi.y < lo.y)
        };
        tally::add(Tally::NearScanned, near.len() as u64);
        let Some(first) = near
            .iter()
            .position(|n| !misses(n, fp.lo, fp.hi, fp.bottom))
        else {
            return;
        };
        corners.clear();
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        let mut bottom = f64::INFINITY;
        for k in self.polys.of(f) {
            for &q in self.polys.corners3(k) {
                let a = DVec2::new(q.dot(u), q.dot(w));
                corners.push(a);
                lo = lo.min(a);
                hi = hi.max(a);
                bottom = bottom.min(q.dot(d));
            }
        }
        let (lo, hi) = (lo - DVec2::splat(self.tol), hi + DVec2::splat(self.tol));
        let bottom = bottom + self.eps;
        let one = (self.polys.of(f).len() == 1).then_some(&corners[..]);
        let receiver = lines::Receiver::new(&self.polys, f, d, one);
        for n in &near[first..] {
            if misses(n, lo, hi, bottom) {
                continue;
            }
            tally::add(Tally::NearTested, 1);
            if let Some(line) =
                lines::crossing(&self.polys, &receiver, &folds[n.fold as usize], &across)
            {
                lines.push(line);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fold_on(edge: u32) -> Fold {
        Fold {
            a: DVec3::ZERO,
            b: DVec3::X,
            pa: DVec2::ZERO,
            pb: DVec2::X,
            top: 0.0,
            jump: 1,
            bounds: true,
            faces: (0, 1),
            edge,
        }
    }

    #[test]
    fn the_folds_edges_are_marked_and_no_others_each_time_they_are_marked_anew() {
        let mut dir = Direction::default();
        let edges = 200;
        // across words of the bit table, at its ends, then fewer, then none
        for set in [vec![0, 63, 64, 127, 199], vec![1, 64, 128], vec![]] {
            dir.folds = set.iter().map(|&e| fold_on(e)).collect();
            dir.mark_folds(edges);
            for e in 0..edges as u32 {
                assert_eq!(dir.is_fold(e), set.contains(&e), "edge {e} of {set:?}");
            }
        }
    }
}
