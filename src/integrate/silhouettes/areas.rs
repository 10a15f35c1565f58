//! What part of a face is seen and lit, from the directions prepared for the epoch
//! ([`Silhouettes::areas`]): whole or nothing where each direction decides the face at
//! once; else the face cut by its lines into cells, each decided by its count (or by a
//! ray where the count cannot be trusted); a face cut too finely sampled on a grid.

use super::cells::area_centroid;
use super::direction::{Direction, FaceState, PatchState};
use super::{lines, Scratch, Silhouettes, FEW_LINES, MAX_CELLS, SAMPLES};
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
        let view = &scratch.dirs[0];
        if !view.used {
            return;
        }
        let mut dropped = false;
        for (f, w) in scratch.wanted.iter_mut().enumerate() {
            if *w & 0b110 != 0 && self.status(view, f) == Status::Dark {
                *w &= 1;
                dropped = true;
            }
        }
        if dropped {
            scratch.patch_wanted.fill(0);
            for (f, &w) in scratch.wanted.iter().enumerate() {
                scratch.patch_wanted[self.patches.of_face[f] as usize] |= w;
            }
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
        if !status.iter().any(|&s| s.cuts()) {
            let lit = |k: usize| {
                if want[k] && status[k] == Status::Clear {
                    area
                } else {
                    0.0
                }
            };
            return (lit(1), lit(2), 0);
        }
        let whole = self.cut_into_cells(scratch, face, &status);
        let (cells, dirs) = (&scratch.cells, &scratch.dirs);
        let mut rays = 0u64;
        let mut decide = |q: DVec2| self.decide(dirs, &status, face, q, &mut rays);
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
            (a_sun, a_earth) = self.sampled(face, &mut decide);
        }
        let lit = |k: usize, a: f64| if want[k] { a } else { 0.0 };
        (lit(1, a_sun), lit(2, a_earth), rays)
    }

    /// Cuts `face` into `scratch.cells` by the bounding lines of the directions that
    /// cut it (and by its contacts). False when it would take more than [`MAX_CELLS`]
    /// cells: the face is then to be sampled.
    fn cut_into_cells(&self, scratch: &mut Scratch, face: usize, status: &[Status; 3]) -> bool {
        scratch.lines.clear();
        for (dir, _) in scratch.dirs.iter().zip(status).filter(|(_, s)| s.cuts()) {
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
        whole
    }

    /// (seen and sunlit, seen and earthlit) at point `q` of `face` (its plane's
    /// coordinates), each direction deciding as `status` says; counts the rays cast.
    fn decide(
        &self,
        dirs: &[Direction; 3],
        status: &[Status; 3],
        face: usize,
        q: DVec2,
        rays: &mut u64,
    ) -> (bool, bool) {
        let mut open = [true; 3];
        for k in 0..3 {
            open[k] = match status[k] {
                Status::Clear => true,
                Status::Dark => false,
                Status::Counted => {
                    let dir = &dirs[k];
                    dir.face_count[face] + lines::crossed(dir.lines_of(face), dir.face_ref[face], q)
                        == 0
                }
                Status::Rays => {
                    *rays += 1;
                    let d = dirs[k].across.d;
                    let x = self.polys.to3(face, q);
                    !self
                        .rays
                        .blocked(&self.polys, &self.topo.open, x, d, face as u32, self.eps)
                }
            };
            if k == 0 && !open[0] {
                return (false, false);
            }
        }
        (open[0] && open[1], open[0] && open[2])
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
