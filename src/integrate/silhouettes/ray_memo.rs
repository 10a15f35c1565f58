//! One direction's ray answers on one face, shared between the cells that a straight
//! path joins without passing a line ([`RayMemo`]).
//!
//! Where a face is decided by rays (another piece meets it, [`super::areas`]), each cell
//! of it asks whether a point of it sees out along the direction. What a ray meets
//! changes only where the point crosses one of the direction's bounding lines or one of
//! the face's contacts, so on a convex face a point that a straight path from a point
//! answered before reaches without passing any of those segments has that point's
//! answer: no ray. Two ways to find such a point:
//! - with at most [`MEMO_LINES`] lines, each point's *key* (which side of each whole
//!   line it lies on): points of one key lie in one convex region that no line crosses,
//!   found by the key alone; a path between points of different keys can cross only
//!   the lines whose sides differ;
//! - past that, the keys cost more than the rays they save: the segments are binned in
//!   a grid ([`SegmentGrid`]) and a path is tested against those in the cells it spans.

use super::lines;
use super::polygons::orient;
use crate::geometry::csr::csr_of;
use glam::DVec2;

/// Most lines (with contacts) on a face for its regions to be keyed by their sides of
/// every line: finding a point's key takes a test against each line, and past a few
/// hundred those cost more than the ray they might save.
const MEMO_LINES: usize = 256;

/// Points answered last that a point of no region answered yet tries to reach, the
/// latest first (cells are cut and asked about in order, so a cell's neighbours are
/// mostly among the last few).
const REACH_TRIED: usize = 8;

/// Most cells of the segments' grid a path is tested in: a longer path, which likely
/// passes a line anyway, is not tried.
const REACH_CELLS: usize = 64;

/// One direction's ray answers on one face.
///
/// The cells are cut by the other directions' lines too, so a face cut by the view and
/// the Sun has more cells than either direction has regions; and where a boom stands on
/// a face, the ring of its foot's contacts (as many as the boom has sides, 96 on the
/// dish-sat's at 200k triangles), extended to whole lines, cuts the face around it into
/// hundreds of keys that its segments do not separate.
#[derive(Default)]
pub(super) struct RayMemo {
    /// Whether the answers are shared on this face (it is convex: a straight path between
    /// two of its points stays on it).
    on: bool,
    /// Whether its regions are keyed (at most [`MEMO_LINES`] lines), else its segments
    /// are binned in `grid`.
    keyed: bool,
    lines: Vec<(DVec2, DVec2)>,
    /// How near (m) a path may pass a line's segment and still count as crossing it.
    margin: f64,
    /// 64-bit words a region's key takes: one bit per line, its side.
    words: usize,
    /// The key of the point asked about last.
    key: Vec<u64>,
    /// Per point answered: its key folded into one word (the key itself when it is one
    /// word), and its key in full when it is longer (`words` each); empty unless keyed.
    folded: Vec<u64>,
    keys: Vec<u64>,
    /// Per point answered: the point, and whether it sees out along the direction.
    points: Vec<DVec2>,
    answers: Vec<bool>,
    grid: SegmentGrid,
}

/// A key of several words folded into one (FxHash's step): regions are looked up by it
/// and then compared in full.
fn fold_key(key: &[u64]) -> u64 {
    key.iter().fold(0u64, |h, &w| {
        (h.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
    })
}

impl RayMemo {
    /// Readies the memo for a face (`convex` or not) whose lines along the direction are
    /// `lines` and whose contacts are `contacts` (in its plane's coordinates, m), a path
    /// within `margin` (m) of one counting as crossing it: a region is bounded by every
    /// contact too, whether or not the count jumps across it along this direction (a ray
    /// does not know why it is blocked: a wall of another piece that faces away meets the
    /// face along a segment with no jump, and the face may be covered on one side of it
    /// and not on the other).
    pub(super) fn reset<'l>(
        &mut self,
        convex: bool,
        lines: impl Iterator<Item = &'l lines::Line>,
        contacts: impl Iterator<Item = (DVec2, DVec2)>,
        margin: f64,
    ) {
        self.lines.clear();
        self.keys.clear();
        self.folded.clear();
        self.answers.clear();
        self.points.clear();
        self.margin = margin;
        self.lines
            .extend(lines.filter(|l| l.bounds).map(|l| (l.p, l.q)));
        push_new(&mut self.lines, contacts);
        self.on = convex;
        self.keyed = self.lines.len() <= MEMO_LINES;
        self.words = self.lines.len().div_ceil(64).max(1);
        if convex && !self.keyed {
            self.grid.build(&self.lines, margin);
        }
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

    /// The answer at `q`: a point's in its region or within reach of it, else `ray()`'s
    /// (then remembered).
    pub(super) fn open(&mut self, q: DVec2, ray: impl FnOnce() -> bool) -> bool {
        if !self.on {
            return ray();
        }
        let folded = if self.keyed {
            self.sides(q);
            // most faces have at most 64 lines: a key of one word, compared as one;
            // longer keys are sought by their folded word and then compared in full
            // (comparing each remembered key as a slice was 3 % of a box-wing run at 20k
            // triangles, on its bus faces that more than 64 lines cross)
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
            Some(folded)
        } else {
            None
        };
        let n = self.answers.len();
        let reached = (n.saturating_sub(REACH_TRIED)..n)
            .rev()
            .find(|&i| self.reaches(q, i));
        let open = match reached {
            Some(i) => self.answers[i],
            None => ray(),
        };
        if let Some(folded) = folded {
            self.folded.push(folded);
            if self.words > 1 {
                self.keys.extend_from_slice(&self.key);
            }
        }
        self.points.push(q);
        self.answers.push(open);
        open
    }

    /// Does the straight path from `q` (whose key is `key` when keyed) to the point
    /// answered `i`-th pass no line or contact (none within the margin)?
    fn reaches(&self, q: DVec2, i: usize) -> bool {
        let p = self.points[i];
        if !self.keyed {
            return self.grid.clear(q, p, &self.lines, self.margin);
        }
        let words = self.words;
        let theirs: &[u64] = if words == 1 {
            &self.folded[i..i + 1]
        } else {
            &self.keys[i * words..(i + 1) * words]
        };
        // only a line whose whole line the two points lie on different sides of can
        // cross the path between them
        for (w, (&a, &b)) in self.key.iter().zip(theirs).enumerate() {
            let mut differ = a ^ b;
            while differ != 0 {
                let j = w * 64 + differ.trailing_zeros() as usize;
                differ &= differ - 1;
                let (s, t) = self.lines[j];
                if segments_near(q, p, s, t, self.margin) {
                    return false;
                }
            }
        }
        true
    }
}

/// A face's segments binned in a square grid of cells over their box, each in every
/// cell its box (widened by the margin) overlaps.
#[derive(Default)]
struct SegmentGrid {
    lo: DVec2,
    /// Cells per metre, and along a side.
    per_m: f64,
    side: usize,
    /// Cell `k` holds the segments `items[start[k]..start[k + 1]]`.
    start: Vec<u32>,
    items: Vec<u32>,
    entries: Vec<(u32, u32)>,
}

impl SegmentGrid {
    fn build(&mut self, lines: &[(DVec2, DVec2)], margin: f64) {
        let (lo, hi) = lines.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), &(a, b)| (lo.min(a).min(b), hi.max(a).max(b)),
        );
        self.lo = lo;
        // about one segment a cell, for segments spread along a curve
        self.side = ((lines.len() as f64).sqrt().ceil() as usize).clamp(1, 64);
        self.per_m = self.side as f64 / (hi - lo).max_element().max(margin);
        self.entries.clear();
        for (j, &(a, b)) in lines.iter().enumerate() {
            let ([x0, y0], [x1, y1]) = self.span(a.min(b), a.max(b), margin);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    self.entries.push(((y * self.side + x) as u32, j as u32));
                }
            }
        }
        (self.start, self.items) = csr_of(self.side * self.side, self.entries.iter().copied());
    }

    /// The cells (first and last along x and y) that the box `lo`–`hi` widened by
    /// `margin` overlaps, clamped to the grid.
    fn span(&self, lo: DVec2, hi: DVec2, margin: f64) -> ([usize; 2], [usize; 2]) {
        let max = (self.side - 1) as f64;
        let cell = |p: DVec2| {
            // clamped first, the cast truncates towards zero: the floor
            let c = ((p - self.lo) * self.per_m).clamp(DVec2::ZERO, DVec2::splat(max));
            [c.x as usize, c.y as usize]
        };
        (
            cell(lo - DVec2::splat(margin)),
            cell(hi + DVec2::splat(margin)),
        )
    }

    /// Does the path `a`–`b` pass no segment of `lines` within `margin`? False too when
    /// it spans more than [`REACH_CELLS`] cells.
    fn clear(&self, a: DVec2, b: DVec2, lines: &[(DVec2, DVec2)], margin: f64) -> bool {
        let ([x0, y0], [x1, y1]) = self.span(a.min(b), a.max(b), margin);
        if (x1 - x0 + 1) * (y1 - y0 + 1) > REACH_CELLS {
            return false;
        }
        for y in y0..=y1 {
            for x in x0..=x1 {
                let k = y * self.side + x;
                let held = &self.items[self.start[k] as usize..self.start[k + 1] as usize];
                for &j in held {
                    let (s, t) = lines[j as usize];
                    if segments_near(a, b, s, t, margin) {
                        return false;
                    }
                }
            }
        }
        true
    }
}

/// Do segments a–b and c–d cross or come within `m` (m) of each other?
fn segments_near(a: DVec2, b: DVec2, c: DVec2, d: DVec2, m: f64) -> bool {
    // boxes apart by more than m: most lines between two points pass far from the path
    let (lo, hi) = (a.min(b) - DVec2::splat(m), a.max(b) + DVec2::splat(m));
    if c.max(d).cmplt(lo).any() || c.min(d).cmpgt(hi).any() {
        return false;
    }
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if (o1 > 0.0) != (o2 > 0.0) && (o3 > 0.0) != (o4 > 0.0) {
        return true;
    }
    let near = |x: DVec2, p: DVec2, q: DVec2| {
        let e = q - p;
        let t = ((x - p).dot(e) / e.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        (p + e * t - x).length_squared() <= m * m
    };
    near(a, c, d) || near(b, c, d) || near(c, a, b) || near(d, a, b)
}

/// Appends to `lines` each of `more` it does not hold yet (a contact across which the
/// count jumps is one of a direction's lines already, with the same ends).
pub(super) fn push_new(
    lines: &mut Vec<(DVec2, DVec2)>,
    more: impl Iterator<Item = (DVec2, DVec2)>,
) {
    for c in more {
        if !lines.contains(&c) {
            lines.push(c);
        }
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
        memo.reset(true, ls.iter(), std::iter::empty(), 1e-9);
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
        memo.reset(false, ls.iter(), std::iter::empty(), 1e-9);
        let mut rays = 0;
        for _ in 0..3 {
            memo.open(DVec2::new(0.3, 0.2), || {
                rays += 1;
                true
            });
        }
        assert_eq!(rays, 3, "no sharing on a face that is not convex");
    }

    /// Corner `i` of a regular `n`-gon inscribed in the unit circle.
    fn on_circle(i: usize, n: usize) -> DVec2 {
        let t = std::f64::consts::TAU * i as f64 / n as f64;
        DVec2::new(t.cos(), t.sin())
    }

    /// The sides of that `n`-gon: a ring of contacts round a boom's foot.
    fn ring(n: usize) -> Vec<(DVec2, DVec2)> {
        (0..n)
            .map(|i| (on_circle(i, n), on_circle(i + 1, n)))
            .collect()
    }

    #[test]
    fn the_cells_inside_a_ring_of_a_hundred_contacts_share_one_ray() {
        // a boom's foot: 100 contacts round a circle on a convex face, more than one
        // 64-bit word of sides; every point inside the ring lies on the inner side of
        // each contact's whole line, one region
        let n = 100;
        let mut memo = RayMemo::default();
        memo.reset(true, std::iter::empty(), ring(n).into_iter(), 1e-9);
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
        // opposite: the ring between them, two more rays and answers
        let beyond = |i: usize| (on_circle(i, n) + on_circle(i + 1, n)) * 0.6;
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
    }

    #[test]
    fn points_round_the_outside_of_a_ring_of_contacts_share_one_ray() {
        // outside a ring of 48 contacts, the whole lines of its sides cut the plane into
        // a region between each pair of neighbouring sides' lines: stepping round the
        // ring, each point has a key of its own, yet a straight step to the last one
        // passes no contact
        let n = 48;
        let mut memo = RayMemo::default();
        memo.reset(true, std::iter::empty(), ring(n).into_iter(), 1e-9);
        let mut rays = 0;
        for k in 0..4 * n {
            let t = std::f64::consts::TAU * k as f64 / (4 * n) as f64;
            let q = DVec2::new(t.cos(), t.sin()) * 1.5;
            assert!(memo.open(q, || {
                rays += 1;
                true
            }));
        }
        assert_eq!(rays, 1, "one ray round the outside");
        // a point inside is not reached from outside: the ring lies between them
        assert!(!memo.open(DVec2::ZERO, || {
            rays += 1;
            false
        }));
        assert_eq!(rays, 2);
    }

    /// Asks `memo` at many points about a region bounded by a closed star-shaped outline
    /// of `n` segments, a ray's answer being whether the point lies inside it; checks
    /// every answer and returns the rays cast.
    fn ask_round_an_outline(n: usize) -> (usize, usize) {
        let radius = |t: f64| 1.0 + 0.3 * (5.0 * t).sin() + 0.1 * (17.0 * t).cos();
        let at = |i: usize| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            DVec2::new(t.cos(), t.sin()) * radius(t)
        };
        let outline: Vec<(DVec2, DVec2)> = (0..n).map(|i| (at(i), at(i + 1))).collect();
        let inside = |q: DVec2| {
            // crossings of a ray along +x
            let mut k = false;
            for &(a, b) in &outline {
                if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x)
                {
                    k = !k;
                }
            }
            k
        };
        let mut memo = RayMemo::default();
        memo.reset(true, std::iter::empty(), outline.iter().copied(), 1e-9);
        // points on a spiral through both sides, some near the outline's corners
        let (mut rays, asked) = (0, 3000);
        for k in 0..asked {
            let t = k as f64 * 0.0137;
            let r = 0.2 + 1.4 * ((k * 7919) % asked) as f64 / asked as f64;
            let q = DVec2::new(t.cos(), t.sin()) * r;
            let open = memo.open(q, || {
                rays += 1;
                inside(q)
            });
            assert_eq!(open, inside(q), "{n} segments, at {q}");
        }
        (rays, asked)
    }

    #[test]
    fn every_answer_is_a_rays_across_a_curved_outline_keyed_or_binned() {
        // keyed (40 segments) and binned in a grid (600, past MEMO_LINES): no answer is
        // taken across a segment, and most points are answered without a ray (25 and 9
        // rays for 3,000 points as built: one in twenty leaves room for another order of
        // the tries, not for a memo that reaches nothing)
        for n in [40, 600] {
            let (rays, asked) = ask_round_an_outline(n);
            assert!(
                rays * 20 < asked,
                "{n} segments: {rays} rays for {asked} points"
            );
        }
    }

    #[test]
    fn a_path_within_the_margin_of_a_segment_crosses_it() {
        let (c, d) = (DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0));
        let near = |a: (f64, f64), b: (f64, f64)| {
            segments_near(DVec2::new(a.0, a.1), DVec2::new(b.0, b.1), c, d, 1e-6)
        };
        assert!(near((0.5, -1.0), (0.5, 1.0)), "across");
        assert!(near((0.5, 1e-7), (0.5, 1.0)), "from within the margin");
        assert!(
            near((1.0 + 5e-7, -1.0), (1.0 + 5e-7, 1.0)),
            "past its end by less"
        );
        assert!(
            !near((1.0 + 2e-6, -1.0), (1.0 + 2e-6, 1.0)),
            "past its end by more"
        );
        assert!(!near((0.2, 0.1), (0.8, 0.1)), "beside it");
        // a path through the joint of two segments of a polyline crosses one
        let e = DVec2::new(2.0, 1.0);
        let path = (DVec2::new(1.0, -1.0), DVec2::new(1.0, 1.0));
        assert!(
            segments_near(path.0, path.1, c, d, 0.0) || segments_near(path.0, path.1, d, e, 0.0)
        );
    }

    #[test]
    fn a_contact_bounds_the_regions_a_ray_answers_for_whatever_its_jump() {
        // one bounding line along x; a contact along y with no jump along this direction
        // (another piece's wall that faces away): a piece may cover one side of it and
        // not the other, so it splits the regions as a line would
        let ls = [line((-1.0, 0.0), (1.0, 0.0), true)];
        let contact = (DVec2::new(0.0, -1.0), DVec2::new(0.0, 1.0));
        let mut memo = RayMemo::default();
        memo.reset(true, ls.iter(), std::iter::once(contact), 1e-9);
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
        memo.reset(true, ls.iter(), std::iter::once((ls[0].p, ls[0].q)), 1e-9);
        assert_eq!(memo.lines.len(), 1);
    }
}
