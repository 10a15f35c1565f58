//! What part of a face is seen and lit, from the directions prepared for the epoch
//! ([`Silhouettes::areas`]): whole or nothing where each direction decides the face at
//! once; else the face cut by its lines into cells, each decided by its count (or by a
//! ray where the count cannot be trusted); a face cut too finely sampled on a grid.

use super::cells::{area_centroid, crosses};
use super::direction::{Direction, FaceState, PatchState};
use super::polygon_tree::Visit;
use super::polygons::orient;
use super::{lines, Scratch, Silhouettes, FEW_LINES, MAX_CELLS, SAMPLES};
use crate::integrate::per_direction::{PerDirection, Toward};
use glam::DVec2;

/// Most lines (with contacts) a direction may cut a face by for its ray answers to be
/// shared between cells: finding a cell's region takes a test against each line, and
/// past a few hundred those cost more than the ray they might save.
const MEMO_LINES: usize = 256;

/// One direction's ray answers on one face, shared between the cells of a region.
///
/// On a convex face, the points on one side of each of the direction's bounding lines
/// (their whole lines, not only their segments) make a convex region that none of its
/// lines crosses, so they are all lit or all dark along it: one ray answers for every
/// cell whose centroid lies there. The cells are cut by the other directions' lines
/// too, so a face cut by the view and the Sun has more cells than either direction has
/// regions. (Where a boom stands on a face, the ring of its foot's contacts is as many
/// lines as the boom has sides, 96 on the dish-sat's at 200k triangles, and the cells
/// inside the ring are one region.)
#[derive(Default)]
pub(super) struct RayMemo {
    /// Whether the answers are shared on this face (convex, few enough lines).
    on: bool,
    lines: Vec<(DVec2, DVec2)>,
    /// 64-bit words a region's key takes: one bit per line, its side.
    words: usize,
    /// The key of the point asked about last.
    key: Vec<u64>,
    /// The regions answered: each key folded into one word (the key itself when it is
    /// one word), the keys in full when they are longer (`words` each), and whether the
    /// regions are open along the direction.
    folded: Vec<u64>,
    keys: Vec<u64>,
    answers: Vec<bool>,
}

/// A key of several words folded into one (FxHash's step): regions are looked up by it
/// and then compared in full.
fn fold_key(key: &[u64]) -> u64 {
    key.iter().fold(0u64, |h, &w| {
        (h.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
    })
}

impl RayMemo {
    /// Readies the memo for a face whose lines along the direction are `lines` and whose
    /// contacts are `contacts` (in its plane's coordinates, m): a region is bounded by
    /// every contact too, whether or not the count jumps across it along this direction
    /// (a ray does not know why it is blocked: a wall of another piece that faces away
    /// meets the face along a segment with no jump, and the face may be covered on one
    /// side of it and not on the other).
    fn reset<'l>(
        &mut self,
        convex: bool,
        lines: impl Iterator<Item = &'l lines::Line>,
        contacts: impl Iterator<Item = (DVec2, DVec2)>,
    ) {
        self.lines.clear();
        self.keys.clear();
        self.folded.clear();
        self.answers.clear();
        self.lines
            .extend(lines.filter(|l| l.bounds).map(|l| (l.p, l.q)));
        push_new(&mut self.lines, contacts);
        self.on = convex && self.lines.len() <= MEMO_LINES;
        self.words = self.lines.len().div_ceil(64).max(1);
    }

    /// Sets `key` to which side of each line `q` lies on.
    fn sides(&mut self, q: DVec2) {
        self.key.clear();
        for chunk in self.lines.chunks(64) {
            let word = chunk.iter().enumerate().fold(0, |m, (i, &(a, b))| {
                m | u64::from(orient(a, b, q) > 0.0) << i
            });
            self.key.push(word);
        }
        if self.key.is_empty() {
            self.key.push(0);
        }
    }

    /// The answer at `q`: remembered for its region, or `ray()`'s (then remembered).
    fn open(&mut self, q: DVec2, ray: impl FnOnce() -> bool) -> bool {
        if !self.on {
            return ray();
        }
        self.sides(q);
        // most faces have at most 64 lines: a key of one word, compared as one; longer
        // keys are sought by their folded word and then compared in full (comparing each
        // remembered key as a slice was 3 % of a box-wing run at 20k triangles, on its
        // bus faces that more than 64 lines cross)
        let words = self.words;
        let folded = if words == 1 {
            self.key[0]
        } else {
            fold_key(&self.key)
        };
        let mut from = 0;
        while let Some(i) = self.folded[from..].iter().position(|&h| h == folded) {
            let i = from + i;
            if words == 1 || self.keys[i * words..(i + 1) * words] == self.key[..] {
                return self.answers[i];
            }
            from = i + 1;
        }
        let open = ray();
        self.folded.push(folded);
        if words > 1 {
            self.keys.extend_from_slice(&self.key);
        }
        self.answers.push(open);
        open
    }
}

/// Appends to `lines` each of `more` it does not hold yet (a contact across which the
/// count jumps is one of a direction's lines already, with the same ends).
fn push_new(lines: &mut Vec<(DVec2, DVec2)>, more: impl Iterator<Item = (DVec2, DVec2)>) {
    for c in more {
        if !lines.contains(&c) {
            lines.push(c);
        }
    }
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

impl Status {
    /// Does the face need cutting along this direction?
    fn cuts(self) -> bool {
        matches!(self, Status::Counted | Status::Rays)
    }
}

impl Silhouettes<'_> {
    /// How direction `dir` decides face `f`.
    fn status(&self, dir: &Direction, f: usize) -> Status {
        let by_count = |c: i32| if c == 0 { Status::Clear } else { Status::Dark };
        let p = self.patches.of_face[f] as usize;
        match dir.patch[p] {
            PatchState::Clean => by_count(dir.patch_count[p]),
            PatchState::Dirty => match dir.face[f] {
                FaceState::Uncrossed => by_count(dir.face_count[f]),
                FaceState::Crossed => {
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
                FaceState::Rays => Status::Rays,
                _ => Status::Clear,
            },
            // not asked about along this direction: it faces away, so no light of it
            // needs deciding
            _ => Status::Clear,
        }
    }

    /// After the view direction is prepared: a face it hides whole has no area seen and
    /// lit whatever the Sun and the Earth do, so no other direction is asked about it
    /// (nor about a patch left with no face to decide). Lines and counts of the faces
    /// still asked about do not change.
    pub fn drop_hidden(&self, scratch: &mut Scratch) {
        let view = &scratch.dirs.view;
        if !view.used {
            return;
        }
        let view_only = Toward::View.bit();
        let lights = Toward::Sun.bit() | Toward::Earth.bit();
        // a patch at a time: a clean one is seen or hidden whole
        for p in 0..self.patches.len() {
            if scratch.patch_wanted[p] & lights == 0 {
                continue;
            }
            let faces = self.patches.faces_of(p);
            if view.patch[p] == PatchState::Clean {
                if view.patch_count[p] != 0 {
                    for &f in faces {
                        scratch.wanted[f as usize] &= view_only;
                    }
                    scratch.patch_wanted[p] &= view_only;
                }
                continue;
            }
            let mut bits = 0;
            for &f in faces {
                let w = &mut scratch.wanted[f as usize];
                if *w & lights != 0 && self.status(view, f as usize) == Status::Dark {
                    *w &= view_only;
                }
                bits |= *w;
            }
            scratch.patch_wanted[p] = bits;
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
        let want = PerDirection {
            view: true,
            sun,
            earth,
        };
        let status = PerDirection::from_fn(|k| {
            if !want[k] || !scratch.dirs[k].used {
                Status::Clear
            } else {
                self.status(&scratch.dirs[k], face)
            }
        });
        if status.view == Status::Dark {
            return (0.0, 0.0, 0);
        }
        if !status.iter().any(|s| s.cuts()) {
            let lit = |k: Toward| {
                if want[k] && status[k] == Status::Clear {
                    area
                } else {
                    0.0
                }
            };
            return (lit(Toward::Sun), lit(Toward::Earth), 0);
        }
        let whole = self.cut_into_cells(scratch, face, &status);
        let (cells, dirs, memo) = (&scratch.cells, &scratch.dirs, &mut scratch.memo);
        for k in Toward::ALL {
            if status[k] == Status::Rays {
                memo[k].reset(
                    self.polys.convex[face],
                    dirs[k].lines_of(face).iter(),
                    self.contact_segments(face),
                );
            }
        }
        let mut rays = 0u64;
        let mut decide = |q: DVec2| self.decide(dirs, &status, face, q, memo, &mut rays);
        let (mut a_sun, mut a_earth) = (0.0, 0.0);
        if whole {
            let shaped = (0..cells.len()).map(|i| area_centroid(cells.cell(i)));
            for (a, c) in shaped.chain(cells.wholes.iter().copied()) {
                if a <= 0.0 {
                    continue;
                }
                let (s, e) = decide(c);
                a_sun += if s { a } else { 0.0 };
                a_earth += if e { a } else { 0.0 };
            }
        } else {
            (a_sun, a_earth) = self.sampled(face, &mut decide);
        }
        let lit = |k: Toward, a: f64| if want[k] { a } else { 0.0 };
        (lit(Toward::Sun, a_sun), lit(Toward::Earth, a_earth), rays)
    }

    /// Cuts `face` into `scratch.cells` by the bounding lines of the directions that
    /// cut it (and by its contacts). False when it would take more than [`MAX_CELLS`]
    /// cells: the face is then to be sampled.
    fn cut_into_cells(
        &self,
        scratch: &mut Scratch,
        face: usize,
        status: &PerDirection<Status>,
    ) -> bool {
        scratch.lines.clear();
        for (dir, _) in scratch
            .dirs
            .iter()
            .zip(status.iter())
            .filter(|(_, s)| s.cuts())
        {
            scratch.lines.extend(
                dir.lines_of(face)
                    .iter()
                    .filter(|l| l.bounds)
                    .map(|l| (l.p, l.q)),
            );
        }
        // and along every contact of the face, whatever its jump: where rays decide the
        // cells, each must lie on one side of every place another piece meets the face
        if status.iter().any(|&s| s == Status::Rays) {
            push_new(&mut scratch.lines, self.contact_segments(face));
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
            let (lines, tol) = (&scratch.lines, self.tol);
            let cutter = &mut scratch.cutter;
            let mut wholes = std::mem::take(&mut cells.wholes);
            // the cutter copies the polygon into its own buffer
            let mut cut = |k: usize| {
                let room = MAX_CELLS.saturating_sub(cells.len());
                let poly = self.polys.corners2(k);
                whole &= cutter.cut(poly, lines, tol, room, |c| cells.push(c.iter().copied()));
                !whole
            };
            match self.polys.trees.root(face) {
                // a face of many polygons: a box no line crosses is one cell
                Some(root) => {
                    self.polys.trees.walk(
                        root,
                        |node| {
                            let corners = node.corners();
                            if lines.iter().any(|&l| crosses(&corners, l, tol)) {
                                Visit::Open
                            } else {
                                wholes.push((node.area, node.point));
                                Visit::Skip
                            }
                        },
                        &mut cut,
                    );
                }
                None => {
                    for k in self.polys.of(face) {
                        if cut(k) {
                            break;
                        }
                    }
                }
            }
            cells.wholes = wholes;
        }
        whole
    }

    /// Face `f`'s contacts as segments in its plane's coordinates (m).
    fn contact_segments(&self, f: usize) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        self.topo
            .contacts_of(f)
            .iter()
            .map(move |c| (self.polys.to2(f, c.a), self.polys.to2(f, c.b)))
    }

    /// (seen and sunlit, seen and earthlit) at point `q` of `face` (its plane's
    /// coordinates), each direction deciding as `status` says (by rays where `memo` has
    /// no answer for `q`'s region yet); counts the rays cast.
    fn decide(
        &self,
        dirs: &PerDirection<Direction>,
        status: &PerDirection<Status>,
        face: usize,
        q: DVec2,
        memo: &mut PerDirection<RayMemo>,
        rays: &mut u64,
    ) -> (bool, bool) {
        let mut open = PerDirection::splat(true);
        for k in Toward::ALL {
            open[k] = match status[k] {
                Status::Clear => true,
                Status::Dark => false,
                Status::Counted => {
                    let dir = &dirs[k];
                    dir.face_count[face] + lines::crossed(dir.lines_of(face), dir.face_ref[face], q)
                        == 0
                }
                Status::Rays => memo[k].open(q, || {
                    *rays += 1;
                    let d = dirs[k].across.d;
                    let x = self.polys.to3(face, q);
                    !self
                        .rays
                        .blocked(&self.polys, &self.topo.open, x, d, face as u32, self.eps)
                }),
            };
            // the view first: a point unseen needs no light decided
            if k == Toward::View && !open.view {
                return (false, false);
            }
        }
        (open.view && open.sun, open.view && open.earth)
    }

    /// The areas (m²) of `face` that `decide` finds (seen and sunlit, seen and earthlit)
    /// at a fixed grid of points on each of its triangles: for a face too many lines cross
    /// to be cut into cells.
    fn sampled(&self, face: usize, decide: &mut impl FnMut(DVec2) -> (bool, bool)) -> (f64, f64) {
        let (mut a_sun, mut a_earth) = (0.0, 0.0);
        let (t0, t1) = (self.triangles_at[face], self.triangles_at[face + 1]);
        for &t in &self.triangles[t0 as usize..t1 as usize] {
            let [p0, p1, p2] = self.mesh.corners(t as usize);
            let at = 0.5 * (p1 - p0).cross(p2 - p0).length();
            let per = at / (SAMPLES * SAMPLES) as f64;
            for i in 0..SAMPLES {
                for j in 0..SAMPLES - i {
                    // the sub-triangles' centroids: the upward one, and the downward one
                    // beside it where there is one
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
        (a_sun, a_earth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lines::Line;

    fn line(p: (f64, f64), q: (f64, f64), bounds: bool) -> Line {
        Line {
            p: DVec2::new(p.0, p.1),
            q: DVec2::new(q.0, q.1),
            jump: 1,
            bounds,
        }
    }

    #[test]
    fn a_ray_answers_for_every_cell_of_its_region_and_only_there() {
        // two bounding lines crossing at the origin make four regions; a third line that
        // does not bound cuts no region
        let ls = [
            line((-1.0, 0.0), (1.0, 0.0), true),
            line((0.0, -1.0), (0.0, 1.0), true),
            line((-1.0, 0.5), (1.0, 0.5), false),
        ];
        let mut memo = RayMemo::default();
        memo.reset(true, ls.iter(), std::iter::empty());
        let mut rays = 0;
        let mut ask = |memo: &mut RayMemo, x: f64, y: f64| {
            memo.open(DVec2::new(x, y), || {
                rays += 1;
                x > 0.0
            })
        };
        // two cells in each quadrant, on both sides of the line that does not bound
        for (x, y) in [(0.3, 0.2), (0.3, 0.7), (-0.3, 0.2), (-0.3, 0.7)] {
            assert_eq!(ask(&mut memo, x, y), x > 0.0);
            assert_eq!(ask(&mut memo, x, -y), x > 0.0);
        }
        assert_eq!(rays, 4, "one ray a region");
        // a face that is not convex: a region may be two pieces of it, each its own ray
        memo.reset(false, ls.iter(), std::iter::empty());
        let mut rays = 0;
        for _ in 0..3 {
            memo.open(DVec2::new(0.3, 0.2), || {
                rays += 1;
                true
            });
        }
        assert_eq!(rays, 3, "no sharing on a face that is not convex");
    }

    #[test]
    fn the_cells_inside_a_ring_of_a_hundred_contacts_share_one_ray() {
        // a boom's foot: 100 contacts round a circle on a convex face, more than one
        // 64-bit word of sides; every point inside the ring lies on the inner side of
        // each contact's whole line, one region
        let n = 100;
        let at = |i: usize| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            DVec2::new(t.cos(), t.sin())
        };
        let ring: Vec<(DVec2, DVec2)> = (0..n).map(|i| (at(i), at(i + 1))).collect();
        let mut memo = RayMemo::default();
        memo.reset(true, std::iter::empty(), ring.iter().copied());
        assert_eq!(memo.words, 2);
        let mut rays = 0;
        for k in 0..50 {
            let t = k as f64 * 0.7;
            let r = 0.9 * (k as f64 / 50.0);
            assert!(!memo.open(DVec2::new(r * t.cos(), r * t.sin()), || {
                rays += 1;
                false
            }));
        }
        assert_eq!(rays, 1, "one ray inside the ring");
        // outside it, beyond one contact (the 70th: in the second word) and beyond its
        // opposite: two more regions, each its own ray and answer
        let beyond = |i: usize| (at(i) + at(i + 1)) * 0.6;
        for (q, open) in [(beyond(70), true), (beyond(20), true), (beyond(70), true)] {
            assert_eq!(
                memo.open(q, || {
                    rays += 1;
                    true
                }),
                open
            );
        }
        assert_eq!(rays, 3);
        // past MEMO_LINES, no sharing
        let many: Vec<(DVec2, DVec2)> = (0..=MEMO_LINES)
            .map(|i| (DVec2::new(i as f64, 5.0), DVec2::new(i as f64, 6.0)))
            .collect();
        memo.reset(true, std::iter::empty(), many.into_iter());
        assert!(!memo.on);
    }

    #[test]
    fn a_contact_bounds_the_regions_a_ray_answers_for_whatever_its_jump() {
        // one bounding line along x; a contact along y with no jump along this direction
        // (another piece's wall that faces away): a piece may cover one side of it and
        // not the other, so it splits the regions as a line would
        let ls = [line((-1.0, 0.0), (1.0, 0.0), true)];
        let contact = (DVec2::new(0.0, -1.0), DVec2::new(0.0, 1.0));
        let mut memo = RayMemo::default();
        memo.reset(true, ls.iter(), std::iter::once(contact));
        let mut rays = 0;
        for (x, y) in [
            (0.3, 0.2),
            (0.6, 0.4),
            (-0.3, 0.2),
            (-0.6, 0.4),
            (0.3, -0.2),
        ] {
            let open = memo.open(DVec2::new(x, y), || {
                rays += 1;
                x > 0.0
            });
            assert_eq!(open, x > 0.0, "({x}, {y})");
        }
        assert_eq!(rays, 3, "one ray for each of the three regions asked about");
        // a contact that is also a line of the direction is one bound, not two
        memo.reset(true, ls.iter(), std::iter::once((ls[0].p, ls[0].q)));
        assert_eq!(memo.lines.len(), 1);
    }
}
