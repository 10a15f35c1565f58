//! The flood of counts along one direction d: how many sheets of the surface lie above
//! each receiving face (0: it sees out along d).
//!
//! The count is the same on both sides of an edge between two receiving faces (nothing
//! folds there), and changes along a face only across the fold lines that cross it
//! ([`super::lines`]), by each line's jump. So one ray ([`super::rays::Rays::count`])
//! gives the count of a whole connected region of receivers, and the flood carries it:
//! a patch that no line reaches has one count; a face that lines cross keeps a point of
//! its plane with the count there (its *reference*), from which the count anywhere on
//! it is the reference's plus the jumps of the lines a straight path crosses
//! ([`super::lines::crossed`]); and the count handed across an edge is taken at a point
//! of the edge clear of the lines. No face is decided by a ray of its own unless it is
//! the first of its region.

use super::direction::{Direction, FaceState, PatchState, Unit, DARK_ONLY, UNKNOWN};
use super::lines::{clearance, crossed};
use super::Silhouettes;
use glam::DVec3;

impl Silhouettes<'_> {
    /// Gives every clean patch and every receiving face of the other patches its count
    /// (or reference) along `dir`'s direction: a ray for the first unit of each
    /// connected region, the flood for the rest. Returns the rays cast.
    pub(super) fn flood(&self, dir: &mut Direction) -> u64 {
        self.read_ahead(dir);
        let mut rays = 0;
        let np = self.patches.len();
        for p in 0..np {
            match dir.patch[p] {
                PatchState::Clean if dir.patch_count[p] == UNKNOWN => {
                    let f = self.patches.faces_of(p)[0] as usize;
                    let (count, n) = self.whole_count(dir, f);
                    rays += n;
                    dir.patch_count[p] = count;
                    if count != DARK_ONLY {
                        self.spread(dir, Unit::Patch(p as u32));
                    }
                }
                PatchState::Dirty => {
                    for &f in self.patches.faces_of(p) {
                        let f = f as usize;
                        if !matches!(dir.face[f], FaceState::Uncrossed | FaceState::Crossed)
                            || dir.face_count[f] != UNKNOWN
                        {
                            continue;
                        }
                        rays += self.seed_face(dir, f);
                        if dir.face[f] != FaceState::Rays && dir.face_count[f] != DARK_ONLY {
                            self.spread(dir, Unit::Face(f as u32));
                        }
                    }
                }
                _ => {}
            }
        }
        rays
    }

    /// Reads, face after face, what the flood will read of the patches decided face by
    /// face: each face's list of neighbours, and the edges of a crossed face (whose
    /// counts are handed over at a point of the edge). The flood reads them in the order
    /// the counts spread, each read waiting on the last; at ~200k triangles these tables
    /// are far larger than the cache and most of those reads were misses. Read ahead,
    /// the misses overlap (the flood 15–23 % faster at ~200k triangles, unchanged at
    /// ~20k: docs/performance.md, twentieth sitting).
    fn read_ahead(&self, dir: &Direction) {
        for p in 0..self.patches.len() {
            if dir.patch[p] != PatchState::Dirty {
                continue;
            }
            for &f in self.patches.faces_of(p) {
                let f = f as usize;
                let neighbours = self.topo.neighbours(f);
                std::hint::black_box(neighbours.first().copied());
                if dir.face[f] == FaceState::Crossed {
                    for &(_, e) in neighbours {
                        std::hint::black_box(self.topo.edges[e as usize].a.x);
                    }
                }
            }
        }
    }

    /// The count along `dir` at the first of `points` (in face `f`) from which a ray gives
    /// one: a ray whose hit falls on a polygon's edge is retried from the next point.
    /// [`DARK_ONLY`] when none did but the ray from the first was blocked. Returns the
    /// count, the point it holds at and the rays cast; `None` for no point.
    fn seed_count(
        &self,
        dir: &Direction,
        f: usize,
        points: impl Iterator<Item = DVec3>,
    ) -> Option<(i32, DVec3, u64)> {
        let d = dir.across.d;
        let (mut rays, mut first) = (0, None);
        for x in points {
            first.get_or_insert(x);
            rays += 1;
            if let Ok(n) = self.rays.count(
                &self.polys,
                &self.topo.open,
                x,
                d,
                f as u32,
                self.eps,
                self.eps,
            ) {
                return Some((n as i32, x, rays));
            }
        }
        let x = first?;
        rays += 1;
        let blocked = self
            .rays
            .blocked(&self.polys, &self.topo.open, x, d, f as u32, self.eps);
        Some((if blocked { DARK_ONLY } else { 0 }, x, rays))
    }

    /// A point inside face `f`'s first polygon and a few others there, to try in turn.
    fn seed_points(&self, f: usize) -> impl Iterator<Item = DVec3> + '_ {
        let k = self.polys.of(f).start;
        let c = self.polys.corners3(k);
        let centre = c.iter().copied().sum::<DVec3>() / c.len() as f64;
        std::iter::once(self.polys.inside[f])
            .chain(c.iter().take(3).map(move |&v| centre + (v - centre) * 0.37))
    }

    /// The count of a face no line crosses, the same at each of its points.
    fn whole_count(&self, dir: &Direction, f: usize) -> (i32, u64) {
        let (count, _, n) = self
            .seed_count(dir, f, self.seed_points(f))
            .expect("a point");
        (count, n)
    }

    /// A crossed or uncrossed face's count (and a crossed face's reference) by a ray;
    /// a crossed face with no point clear of its lines, or no count, is left to rays per
    /// cell. Returns the rays cast.
    fn seed_face(&self, dir: &mut Direction, f: usize) -> u64 {
        if dir.face[f] == FaceState::Uncrossed {
            let (count, n) = self.whole_count(dir, f);
            dir.face_count[f] = count;
            return n;
        }
        // only points clear of the lines: a count from a point across a line from the
        // reference would carry that line's jump
        let lines = dir.lines_of(f);
        let margin = self.margin(f);
        let clear = self
            .seed_points(f)
            .filter(|&x| clearance(lines, self.polys.to2(f, x)) > margin);
        let Some((count, x, n)) = self.seed_count(dir, f, clear) else {
            dir.face[f] = FaceState::Rays;
            return 0;
        };
        if count == DARK_ONLY {
            dir.face[f] = FaceState::Rays;
        } else {
            dir.face_count[f] = count;
            dir.face_ref[f] = self.polys.to2(f, x);
        }
        n
    }

    /// How far (m) a point must stay from a face's lines for its count to be trusted.
    pub(super) fn margin(&self, f: usize) -> f64 {
        1e-7 * self.polys.radius[f] + 10.0 * self.eps
    }

    /// Floods from `start` (whose count is known) to every unit joined to it.
    fn spread(&self, dir: &mut Direction, start: Unit) {
        let mut queue = std::mem::take(&mut dir.queue);
        queue.clear();
        queue.push(start);
        while let Some(unit) = queue.pop() {
            match unit {
                Unit::Patch(p) => {
                    let count = dir.patch_count[p as usize];
                    for link in self.patches.links_of(p as usize) {
                        let q = link.patch as usize;
                        match dir.patch[q] {
                            // a clean patch beside a clean one: both face along d with
                            // sheets of one kind (or the two-sided faces of both face
                            // one way), so nothing folds between them: any edge serves
                            PatchState::Clean => {
                                if dir.patch_count[q] != UNKNOWN {
                                    continue;
                                }
                                let &(e, _, out) = &self.patches.exits_of(link)[0];
                                if let Some(next) = self.hand_over(dir, None, count, e, out) {
                                    queue.push(next);
                                }
                            }
                            PatchState::Dirty => {
                                for &(e, _, out) in self.patches.exits_of(link) {
                                    if let Some(next) = self.hand_over(dir, None, count, e, out) {
                                        queue.push(next);
                                    }
                                }
                            }
                            _ => {}
                        }
                    }
                }
                Unit::Face(f) => {
                    let count = dir.face_count[f as usize];
                    for &(g, e) in self.topo.neighbours(f as usize) {
                        if let Some(next) = self.hand_over(dir, Some(f), count, e, g) {
                            queue.push(next);
                        }
                    }
                }
            }
        }
        dir.queue = queue;
    }

    /// Hands the count across edge `e` to face `g`'s unit when it needs one: from face
    /// `from` (a crossed face's count is taken at a point of the edge clear of its
    /// lines), or from a clean patch's uniform `count`. Returns the unit that got it.
    fn hand_over(
        &self,
        dir: &mut Direction,
        from: Option<u32>,
        count: i32,
        e: u32,
        g: u32,
    ) -> Option<Unit> {
        let g = g as usize;
        let p = self.patches.of_face[g] as usize;
        let target = match dir.patch[p] {
            PatchState::Clean if dir.patch_count[p] == UNKNOWN => Unit::Patch(p as u32),
            PatchState::Dirty
                if matches!(dir.face[g], FaceState::Uncrossed | FaceState::Crossed)
                    && dir.face_count[g] == UNKNOWN =>
            {
                Unit::Face(g as u32)
            }
            _ => return None,
        };
        let across = &dir.across;
        // the search for folds tested every edge that can be one, but for an edge whose
        // triangles wind the same way along it inside a patch that faces one way
        let flipped = self.topo.any_flipped && self.topo.edges[e as usize].flipped;
        let fold = if flipped {
            let edge = &self.topo.edges[e as usize];
            !super::folds::same_way(&self.topo, &self.polys.normal, edge, across.d)
                && edge.jump(across.u, across.w, |f| self.blocks(f as usize, across.d)) != 0
        } else {
            dir.is_fold(e)
        };
        if fold {
            return None;
        }
        let src_crossed = from.filter(|&f| dir.face[f as usize] == FaceState::Crossed);
        let dst_crossed = matches!(target, Unit::Face(_)) && dir.face[g] == FaceState::Crossed;
        if src_crossed.is_none() && !dst_crossed {
            match target {
                Unit::Patch(p) => dir.patch_count[p as usize] = count,
                Unit::Face(g) => dir.face_count[g as usize] = count,
            }
            return Some(target);
        }
        // a point of the edge clear of the lines on both sides
        let edge = &self.topo.edges[e as usize];
        let (a, b) = (edge.a, edge.b);
        let at = [0.5, 0.3, 0.7, 0.15, 0.85]
            .into_iter()
            .map(|t| a + (b - a) * t)
            .find(|&x| {
                let clear =
                    |f: usize| clearance(dir.lines_of(f), self.polys.to2(f, x)) > self.margin(f);
                src_crossed.is_none_or(|f| clear(f as usize)) && (!dst_crossed || clear(g))
            })?;
        let count = match src_crossed {
            Some(f) => {
                let f = f as usize;
                count + crossed(dir.lines_of(f), dir.face_ref[f], self.polys.to2(f, at))
            }
            None => count,
        };
        match target {
            Unit::Patch(p) => dir.patch_count[p as usize] = count,
            Unit::Face(g) => {
                dir.face_count[g as usize] = count;
                if dst_crossed {
                    dir.face_ref[g as usize] = self.polys.to2(g as usize, at);
                }
            }
        }
        Some(target)
    }
}
