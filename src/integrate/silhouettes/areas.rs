//! What part of a face is seen and lit, from the directions prepared for the epoch
//! ([`Silhouettes::areas`]): whole or nothing where each direction decides the face at
//! once; else the face cut by its lines into cells, each decided by its count (or by a
//! ray where the count cannot be trusted); a face cut too finely sampled on a grid.

use super::cells::{area_centroid, crosses};
use super::direction::{Direction, FaceState, PatchState};
use super::fan::Fan;
use super::polygon_tree::Visit;
use super::ray_memo::{push_new, RayMemo};
use super::{Scratch, Silhouettes, FEW_LINES, MAX_CELLS, SAMPLES};
use crate::geometry::polygon::bounds;
use crate::integrate::per_direction::{PerDirection, Toward};
use glam::DVec2;

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

/// Lines of a face past which its cells are counted through a [`Fan`]: below, reading
/// every line costs less than building it.
const FAN_LINES: usize = 24;

/// Per direction that counts face `face` (`status`) across many lines, its lines put in
/// `fans`; says which directions have one.
fn build_fans(
    fans: &mut PerDirection<Fan>,
    dirs: &PerDirection<Direction>,
    status: &PerDirection<Status>,
    face: usize,
) -> PerDirection<bool> {
    PerDirection::from_fn(|k| {
        let many = status[k] == Status::Counted && dirs[k].lines_of(face).len() >= FAN_LINES;
        if many {
            fans[k].build(dirs[k].lines_of(face), dirs[k].face_ref[face]);
        }
        many
    })
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
        let if_wanted = |k: Toward, a: f64| if want[k] { a } else { 0.0 };
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
        if let Some((a_sun, a_earth)) = self.seen_then_lit(scratch, face, &status) {
            return (
                if_wanted(Toward::Sun, a_sun),
                if_wanted(Toward::Earth, a_earth),
                0,
            );
        }
        let whole = self.cut_into_cells(scratch, face, &status);
        let with_fan = build_fans(&mut scratch.fans, &scratch.dirs, &status, face);
        let fans = PerDirection::from_fn(|k| with_fan[k].then_some(&scratch.fans[k]));
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
        let mut decide = |q: DVec2, share: bool| {
            self.decide(dirs, (&status, &fans), face, (q, share), memo, &mut rays)
        };
        let (mut a_sun, mut a_earth) = (0.0, 0.0);
        if whole {
            // A cell's centroid lies within the margin of a line it was cut along only if
            // the cell is a sliver no wider than three margins (a convex cell's centroid
            // is a third of its width from any side at least), so no larger than three
            // margins times its box's diagonal: its ray may graze what casts the line,
            // and its answer stands for no other cell. (Only rays' answers are shared.)
            let by_rays = Toward::ALL.iter().any(|&k| status[k] == Status::Rays);
            let sliver = 3.0 * self.margin(face);
            let shaped = (0..cells.len()).map(|i| {
                let c = cells.cell(i);
                let (a, q) = area_centroid(c);
                (a, q, !by_rays || a > sliver * diagonal(c))
            });
            let wholes = cells.wholes.iter().map(|&(a, q)| (a, q, true));
            for (a, c, share) in shaped.chain(wholes) {
                if a <= 0.0 {
                    continue;
                }
                let (s, e) = decide(c, share);
                a_sun += if s { a } else { 0.0 };
                a_earth += if e { a } else { 0.0 };
            }
        } else {
            (a_sun, a_earth) = self.sampled(face, &mut |q| decide(q, true));
        }
        (
            if_wanted(Toward::Sun, a_sun),
            if_wanted(Toward::Earth, a_earth),
            rays,
        )
    }

    /// The areas (m²) of one-polygon `face` seen and sunlit, and seen and earthlit, when
    /// counts decide the view and a light cuts it too: the face is cut by the view's
    /// lines alone, and only the cells seen are cut by the lights' lines, so that the
    /// part hidden is not cut finer by shadows no one sees. `None` where this does not
    /// apply (rays decide a direction, the face has several polygons or few lines) or
    /// where the cells would exceed [`MAX_CELLS`].
    fn seen_then_lit(
        &self,
        scratch: &mut Scratch,
        face: usize,
        status: &PerDirection<Status>,
    ) -> Option<(f64, f64)> {
        let lights_cut = status.sun.cuts() || status.earth.cuts();
        if status.view != Status::Counted
            || !lights_cut
            || status.iter().any(|&s| s == Status::Rays)
            || self.polys.of(face).len() != 1
        {
            return None;
        }
        let Scratch {
            dirs,
            cells,
            cutter,
            lines,
            near,
            fans,
            ..
        } = scratch;
        lines.clear();
        lines.extend(dirs.view.bounding_lines(face));
        let seen_by = lines.len();
        for k in [Toward::Sun, Toward::Earth] {
            if status[k].cuts() {
                lines.extend(dirs[k].bounding_lines(face));
            }
        }
        // a few lines are split along whole, all at once (`cut_into_cells`)
        if lines.len() <= FEW_LINES {
            return None;
        }
        let (view_lines, light_lines) = lines.split_at(seen_by);
        let with_fan = build_fans(fans, dirs, status, face);
        let fan = |k: Toward| with_fan[k].then_some(&fans[k]);
        let open = |k: Toward, q: DVec2| match status[k] {
            Status::Clear => true,
            Status::Dark => false,
            _ => dirs[k].counts_none_via(face, q, fan(k)),
        };
        let tol = self.tol;
        cells.clear();
        let poly = self.polys.corners2(self.polys.of(face).start);
        let mut made = 0;
        let complete = cutter.cut(poly, view_lines, tol, MAX_CELLS, |c| {
            made += 1;
            let (a, q) = area_centroid(c);
            if a > 0.0 && open(Toward::View, q) {
                cells.push(c.iter().copied());
            }
        });
        if !complete {
            return None;
        }
        let (mut a_sun, mut a_earth) = (0.0, 0.0);
        for i in 0..cells.len() {
            let room = MAX_CELLS.checked_sub(made)?;
            // the light lines that reach the cell's box: the others cannot cross it, and
            // a face of hundreds of lines is cut into hundreds of seen cells
            let cell = cells.cell(i);
            let (lo, hi) = bounds(cell);
            let (lo, hi) = (lo - DVec2::splat(tol), hi + DVec2::splat(tol));
            near.clear();
            near.extend(
                light_lines
                    .iter()
                    .filter(|(a, b)| !(a.min(*b).cmpgt(hi).any() || a.max(*b).cmplt(lo).any())),
            );
            let complete = cutter.cut(cell, near, tol, room, |c| {
                made += 1;
                let (a, q) = area_centroid(c);
                if a > 0.0 {
                    a_sun += if open(Toward::Sun, q) { a } else { 0.0 };
                    a_earth += if open(Toward::Earth, q) { a } else { 0.0 };
                }
            });
            if !complete {
                return None;
            }
        }
        Some((a_sun, a_earth))
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
            scratch.lines.extend(dir.bounding_lines(face));
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
    /// no answer for `q`'s region yet, a ray's answer remembered for the region if `q`
    /// may `share` it); counts the rays cast.
    #[inline(always)]
    fn decide(
        &self,
        dirs: &PerDirection<Direction>,
        (status, fans): (&PerDirection<Status>, &PerDirection<Option<&Fan>>),
        face: usize,
        (q, share): (DVec2, bool),
        memo: &mut PerDirection<RayMemo>,
        rays: &mut u64,
    ) -> (bool, bool) {
        let mut open = PerDirection::splat(true);
        for k in Toward::ALL {
            open[k] = match status[k] {
                Status::Clear => true,
                Status::Dark => false,
                Status::Counted => dirs[k].counts_none_via(face, q, fans[k]),
                Status::Rays => memo[k].open(q, share, || {
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

/// The diagonal (m) of the box round a polygon's corners.
fn diagonal(poly: &[DVec2]) -> f64 {
    let (lo, hi) = bounds(poly);
    (hi - lo).length()
}
