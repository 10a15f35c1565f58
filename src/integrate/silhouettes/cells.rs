//! A face cut into convex cells by lines: where every shadow or occlusion edge that can
//! cross a face lies on one of the lines, each cell is wholly lit or wholly dark along
//! every direction, and one ray from its centroid decides it.

use crate::geometry::polygon::bounds;
use glam::DVec2;

/// Convex cells in one flat buffer: `spans[i]` is cell i's range of `points`. Beside
/// them, *whole* cells: polygons of a face's tree under a box no line crosses, given by
/// their area and a point inside one of them.
#[derive(Default)]
pub struct Cells {
    pub points: Vec<DVec2>,
    pub spans: Vec<(u32, u32)>,
    /// (area, m²; a point inside, m) of each whole cell.
    pub wholes: Vec<(f64, DVec2)>,
    next_points: Vec<DVec2>,
    next_spans: Vec<(u32, u32)>,
}

impl Cells {
    pub fn clear(&mut self) {
        self.points.clear();
        self.spans.clear();
        self.wholes.clear();
    }

    /// Adds a convex polygon (counter-clockwise or clockwise).
    pub fn push(&mut self, poly: impl IntoIterator<Item = DVec2>) {
        let s = self.points.len() as u32;
        self.points.extend(poly);
        self.spans.push((s, self.points.len() as u32));
    }

    pub fn len(&self) -> usize {
        self.spans.len()
    }

    pub fn cell(&self, i: usize) -> &[DVec2] {
        let (a, b) = self.spans[i];
        &self.points[a as usize..b as usize]
    }

    /// Splits every cell that the line through `p` along `dir` crosses by more than
    /// `tol` (m) on both sides. Returns false (and leaves the cells as they were split so
    /// far) once there would be more than `max` cells.
    pub fn split(&mut self, p: DVec2, dir: DVec2, tol: f64, max: usize) -> bool {
        let len = dir.length();
        if len == 0.0 {
            return true;
        }
        let dir = dir / len;
        self.next_points.clear();
        self.next_spans.clear();
        for i in 0..self.spans.len() {
            let (a, b) = self.spans[i];
            let poly = &self.points[a as usize..b as usize];
            let side = |q: DVec2| dir.perp_dot(q - p);
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for &q in poly {
                let s = side(q);
                lo = lo.min(s);
                hi = hi.max(s);
            }
            if lo >= -tol || hi <= tol {
                let s = self.next_points.len() as u32;
                self.next_points.extend_from_slice(poly);
                self.next_spans.push((s, self.next_points.len() as u32));
                continue;
            }
            for keep_left in [true, false] {
                let s = self.next_points.len() as u32;
                let n = poly.len();
                for k in 0..n {
                    let (q0, q1) = (poly[k], poly[(k + 1) % n]);
                    let (s0, s1) = (side(q0), side(q1));
                    let in0 = if keep_left { s0 >= 0.0 } else { s0 <= 0.0 };
                    if in0 {
                        self.next_points.push(q0);
                    }
                    if (s0 > 0.0 && s1 < 0.0) || (s0 < 0.0 && s1 > 0.0) {
                        self.next_points.push(q0 + (q1 - q0) * (s0 / (s0 - s1)));
                    }
                }
                let e = self.next_points.len() as u32;
                if e - s >= 3 {
                    self.next_spans.push((s, e));
                } else {
                    self.next_points.truncate(s as usize);
                }
            }
            if self.next_spans.len() > max {
                std::mem::swap(&mut self.points, &mut self.next_points);
                std::mem::swap(&mut self.spans, &mut self.next_spans);
                return false;
            }
        }
        std::mem::swap(&mut self.points, &mut self.next_points);
        std::mem::swap(&mut self.spans, &mut self.next_spans);
        true
    }
}

/// A convex piece still to cut: its corners (a range of [`Cutter::points`]) and the
/// segments that may cross it (a range of [`Cutter::cand`]).
#[derive(Clone, Copy)]
struct Piece {
    points: (u32, u32),
    cand: (u32, u32),
}

/// Cuts convex polygons along segments ([`Cutter::cut`]), with its buffers kept from
/// call to call: a face crossed by shadows is cut once per epoch, and allocating per
/// piece cost as much as the cutting.
#[derive(Default)]
pub struct Cutter {
    stack: Vec<Piece>,
    /// Every piece's corners, appended as pieces are made (cleared per call).
    points: Vec<DVec2>,
    /// Every piece's candidate segments: index, and whether it is known to cross.
    cand: Vec<(u32, bool)>,
    /// The right piece's candidates while the left's are written.
    right: Vec<(u32, bool)>,
    pieces: Cells,
    /// The candidates' midpoints along an axis, for [`Cutter::halving_line`].
    mids: Vec<f64>,
}

impl Cutter {
    /// Cuts convex polygon `poly` along the segments `segs` (p, q) into cells that no
    /// segment crosses: a cell is split along a segment's line only where the segment
    /// itself crosses it, so k segments make about k cells, not k²; a piece that carries
    /// many is halved first, so that no piece carries them all. Calls `cell` with
    /// each; false when there would be more than `max` cells (the cells so far have been
    /// given).
    #[inline]
    pub fn cut(
        &mut self,
        poly: &[DVec2],
        segs: &[(DVec2, DVec2)],
        tol: f64,
        max: usize,
        mut cell: impl FnMut(&[DVec2]),
    ) -> bool {
        // Each piece carries the segments that may cross it, and whether each is known
        // to (it crossed the parent and lies wholly on this piece's side of the cut):
        // those are not tested again, so a chain of k segments costs k splits, not k²
        // tests.
        self.stack.clear();
        self.points.clear();
        self.cand.clear();
        self.points.extend_from_slice(poly);
        self.cand.extend((0..segs.len() as u32).map(|i| (i, false)));
        self.stack.push(Piece {
            points: (0, self.points.len() as u32),
            cand: (0, self.cand.len() as u32),
        });
        let mut made = 0usize;
        while let Some(piece) = self.stack.pop() {
            let (pa, pb) = (piece.points.0 as usize, piece.points.1 as usize);
            let (ca, cb) = (piece.cand.0 as usize, piece.cand.1 as usize);
            // keep the candidates that still cross, in order (as `retain`)
            let mut kept = ca;
            for k in ca..cb {
                let (i, known) = self.cand[k];
                if known || crosses(&self.points[pa..pb], segs[i as usize], tol) {
                    self.cand[kept] = (i, known);
                    kept += 1;
                }
            }
            let c = pa..pb;
            if kept == ca {
                made += 1;
                if made > max {
                    return false;
                }
                cell(&self.points[c]);
                continue;
            }
            // many segments: halved first along a line of none of them ([`FREE_SPLIT`])
            if kept - ca > FREE_SPLIT {
                if let Some((p, dir)) = self.halving_line(pa..pb, ca..kept, segs, tol) {
                    self.pieces.clear();
                    self.pieces.push(self.points[c.clone()].iter().copied());
                    self.pieces.split(p, dir, tol, usize::MAX);
                    if self.pieces.len() == 2 {
                        self.push_halves(ca..kept, segs, p, dir, tol);
                        continue;
                    }
                }
            }
            let first = self.cand[ca].0;
            let (p, q) = segs[first as usize];
            self.pieces.clear();
            self.pieces.push(self.points[c.clone()].iter().copied());
            self.pieces.split(p, q - p, tol, usize::MAX);
            if self.pieces.len() < 2 {
                // the first candidate did not cut after all: the rest, retested
                for k in ca + 1..kept {
                    self.cand[k].1 = false;
                }
                self.stack.push(Piece {
                    points: piece.points,
                    cand: (ca as u32 + 1, kept as u32),
                });
                continue;
            }
            // the pieces lie on either side of the line (left first)
            self.push_halves(ca + 1..kept, segs, p, (q - p).normalize_or_zero(), tol);
        }
        true
    }
}

/// Most segments a piece carries before it is halved along a line of no segment's: a
/// chain of segments along a convex curve (a fine dish's rim's shadow) leaves all the
/// others on one side of each one's line, and cut along them one after another the
/// pieces carry k, k − 1, … of them (k² work); halved, each carries about half.
const FREE_SPLIT: usize = 32;

impl Cutter {
    /// A line (a point, a direction) across the piece of corners `points` that halves
    /// its candidates `cands` (the median of their midpoints along the piece's longer
    /// side), or `None`.
    #[inline(never)]
    fn halving_line(
        &mut self,
        points: std::ops::Range<usize>,
        cands: std::ops::Range<usize>,
        segs: &[(DVec2, DVec2)],
        tol: f64,
    ) -> Option<(DVec2, DVec2)> {
        let (lo, hi) = bounds(&self.points[points]);
        let axis = if hi.x - lo.x >= hi.y - lo.y { 0 } else { 1 };
        self.mids.clear();
        self.mids
            .extend(self.cand[cands.clone()].iter().map(|&(i, _)| {
                let (a, b) = segs[i as usize];
                (a[axis] + b[axis]) * 0.5
            }));
        let mid = self.mids.len() / 2;
        let (_, &mut m, _) = self.mids.select_nth_unstable_by(mid, f64::total_cmp);
        if !(m > lo[axis] && m < hi[axis]) {
            return None;
        }
        let (p, dir) = if axis == 0 {
            (DVec2::new(m, lo.y), DVec2::Y)
        } else {
            (DVec2::new(lo.x, m), DVec2::NEG_X)
        };
        // worth it only when neither half keeps more than three quarters of them (long
        // segments across the piece would go to both halves, and halving again would not
        // end)
        let (mut left, mut right) = (0, 0);
        for &(i, _) in &self.cand[cands.clone()] {
            let (l, r) = reaches(segs[i as usize], p, dir, tol);
            left += usize::from(l);
            right += usize::from(r);
        }
        let most = 3 * cands.len() / 4;
        (left <= most && right <= most).then_some((p, dir))
    }

    /// Pushes the two halves in `self.pieces` (split along the line through `p` along
    /// unit `dir`, left first) with their candidates among `cands`: a segment wholly
    /// beyond the line on one side crosses that half (it crossed the piece) and not the
    /// other, and is not tested again; each candidate is classified once, the left half's
    /// list going straight into `cand`, the right one's after it.
    #[inline(always)]
    fn push_halves(
        &mut self,
        cands: std::ops::Range<usize>,
        segs: &[(DVec2, DVec2)],
        p: DVec2,
        dir: DVec2,
        tol: f64,
    ) {
        let left_at = self.cand.len();
        self.right.clear();
        for k in cands {
            let (i, _) = self.cand[k];
            let (left, right) = reaches(segs[i as usize], p, dir, tol);
            if !right {
                self.cand.push((i, true));
            } else if !left {
                self.right.push((i, true));
            } else {
                self.cand.push((i, false));
                self.right.push((i, false));
            }
        }
        let right_at = self.cand.len();
        self.cand.extend_from_slice(&self.right);
        let end = self.cand.len();
        for (side, cand) in [(0, (left_at, right_at)), (1, (right_at, end))] {
            let s = self.points.len();
            let (a, b) = self.pieces.spans[side];
            self.points
                .extend_from_slice(&self.pieces.points[a as usize..b as usize]);
            self.stack.push(Piece {
                points: (s as u32, self.points.len() as u32),
                cand: (cand.0 as u32, cand.1 as u32),
            });
        }
    }
}

/// Whether segment `(a, b)` reaches the left and the right of the line through `p` along
/// unit `dir` (beyond twice `tol`, m, from it on one side, it reaches only that side).
#[inline(always)]
fn reaches((a, b): (DVec2, DVec2), p: DVec2, dir: DVec2, tol: f64) -> (bool, bool) {
    let (sa, sb) = (dir.perp_dot(a - p), dir.perp_dot(b - p));
    if sa.min(sb) > 2.0 * tol {
        (true, false)
    } else if sa.max(sb) < -2.0 * tol {
        (false, true)
    } else {
        (true, true)
    }
}

/// Does segment (p, q) pass through the interior of convex polygon `c` (by more than
/// `tol`)? Its part inside the polygon (Cyrus–Beck) must be longer than `tol`, and the
/// polygon must lie on both sides of its line.
#[inline]
pub fn crosses(c: &[DVec2], (p, q): (DVec2, DVec2), tol: f64) -> bool {
    let d = q - p;
    let len = d.length();
    if len <= tol {
        return false;
    }
    let dir = d / len;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &v in c {
        let s = dir.perp_dot(v - p);
        lo = lo.min(s);
        hi = hi.max(s);
    }
    if lo >= -tol || hi <= tol {
        return false;
    }
    // clip the segment to the polygon: orientation-free, each edge's inward side is the
    // side the polygon's centroid lies on. The edges' normals are not normalised: where the
    // segment meets an edge's line (t, m along it) does not depend on their length, and
    // only the test for a segment parallel to an edge needs it (no square root a corner)
    let centre = c.iter().copied().sum::<DVec2>() / c.len() as f64;
    let (mut t0, mut t1) = (0.0, len);
    let n = c.len();
    let tol2 = tol * tol;
    for k in 0..n {
        let (a, b) = (c[k], c[(k + 1) % n]);
        let e = b - a;
        let el2 = e.length_squared();
        // a split can leave two corners a rounding apart: their edge has no direction
        // to speak of, and a half-plane through it would cut the segment at random
        if el2 <= tol2 {
            continue;
        }
        let normal = e.perp();
        let inward = if normal.dot(centre - a) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let dist = inward * normal.dot(p - a); // ≥ 0 inside, times the edge's length
        let rate = inward * normal.dot(dir);
        if rate == 0.0 {
            if dist < -tol * el2.sqrt() {
                return false;
            }
        } else {
            let t = -dist / rate;
            if rate > 0.0 {
                t0 = f64::max(t0, t);
            } else {
                t1 = f64::min(t1, t);
            }
        }
        if t1 - t0 <= tol {
            return false;
        }
    }
    t1 - t0 > tol
}

/// Area (m², unsigned) and centroid of a convex polygon.
pub fn area_centroid(poly: &[DVec2]) -> (f64, DVec2) {
    let o = poly[0];
    let (mut a2, mut c) = (0.0, DVec2::ZERO);
    for k in 1..poly.len() - 1 {
        let (p, q) = (poly[k] - o, poly[k + 1] - o);
        let t = p.perp_dot(q);
        a2 += t;
        c += (p + q) * t;
    }
    if a2 == 0.0 {
        return (0.0, o);
    }
    (0.5 * a2.abs(), o + c / (3.0 * a2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_crossing_lines_cut_a_square_into_four_quarters() {
        let mut c = Cells::default();
        c.push([DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]);
        assert!(c.split(DVec2::splat(0.5), DVec2::X, 1e-12, 64));
        assert!(c.split(DVec2::splat(0.5), DVec2::Y, 1e-12, 64));
        assert_eq!(c.len(), 4);
        let mut total = 0.0;
        for i in 0..4 {
            let (a, centre) = area_centroid(c.cell(i));
            assert!((a - 0.25).abs() < 1e-15);
            assert!((centre - DVec2::splat(0.5)).abs().min_element() > 0.2);
            total += a;
        }
        assert!((total - 1.0).abs() < 1e-15);
        // a line along an edge cuts nothing
        assert!(c.split(DVec2::ZERO, DVec2::X, 1e-12, 64));
        assert_eq!(c.len(), 4);
        // the cap on cells
        assert!(!c.split(DVec2::new(0.3, 0.0), DVec2::new(1.0, 1.0), 1e-12, 4));
    }

    #[test]
    fn corners_a_rounding_apart_do_not_hide_a_crossing_segment() {
        // A split can leave the corner (1, 0.5) twice, a rounding apart along a direction
        // of their own, (-1, -0.5): taken as an edge, its half-plane y ≥ x/2 would cut
        // away the segment along y = 0.2, which crosses the square's lower right.
        let poly = [
            DVec2::ZERO,
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 0.5),
            DVec2::new(1.0 - 2e-16, 0.5 - 1e-16),
            DVec2::ONE,
            DVec2::Y,
        ];
        let seg = (DVec2::new(0.6, 0.2), DVec2::new(2.0, 0.2));
        assert!(crosses(&poly, seg, 1e-12));
        let mut n = 0;
        assert!(Cutter::default().cut(&poly, &[seg], 1e-12, 64, |_| n += 1));
        assert_eq!(n, 2);
    }

    #[test]
    fn a_fine_polygon_s_outline_cuts_a_square_into_cells_that_hold_its_area_exactly() {
        // A shadow's outline of 400 segments (a regular 400-gon, joints shared) and 40
        // stray segments, some across it: far more than a piece carries before it is
        // halved (FREE_SPLIT). No segment may cross a cell, the cells must tile the
        // square, and those inside the outline must add up to the 400-gon's area,
        // (n/2) r² sin(2π/n), to rounding (1e-12 of the square's area: ~1,000 cells
        // summed, each corner computed by a few products).
        let n = 400;
        let (c, r) = (DVec2::new(0.45, 0.55), 0.3);
        let at = |k: usize| {
            let t = std::f64::consts::TAU * (k % n) as f64 / n as f64;
            c + r * DVec2::new(t.cos(), t.sin())
        };
        let mut segs: Vec<(DVec2, DVec2)> = (0..n).map(|k| (at(k), at(k + 1))).collect();
        let outline = segs.len();
        for k in 0..40 {
            let t = k as f64 / 40.0;
            segs.push((
                DVec2::new(t, 0.05 + 0.5 * t),
                DVec2::new(0.1 + 0.9 * t, 0.9 - 0.2 * t),
            ));
        }
        let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let mut cells = Vec::new();
        assert!(Cutter::default().cut(&square, &segs, 1e-12, MAX, |cell| cells.push(cell.to_vec())));
        let (mut total, mut inside) = (0.0, 0.0);
        for cell in &cells {
            for &seg in &segs {
                assert!(!crosses(cell, seg, 1e-12), "{seg:?} crosses {cell:?}");
            }
            let (a, q) = area_centroid(cell);
            total += a;
            // inside the outline: on the left of every one of its segments
            if segs[..outline]
                .iter()
                .all(|&(p0, p1)| (p1 - p0).perp_dot(q - p0) > 0.0)
            {
                inside += a;
            }
        }
        let polygon = 0.5 * n as f64 * r * r * (std::f64::consts::TAU / n as f64).sin();
        assert!((total - 1.0).abs() < 1e-12, "{total}");
        assert!(
            (inside - polygon).abs() < 1e-12,
            "{inside} against {polygon}"
        );
        // about a cell per segment and crossing, not one per pair of segments
        assert!(cells.len() < 4 * segs.len(), "{} cells", cells.len());
    }

    /// Cells enough for any test here.
    const MAX: usize = 1 << 20;

    #[test]
    fn segments_cut_only_where_they_reach() {
        let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        // a segment from the left edge to the middle, and one outside: two cells; the
        // full line of the first would also cut, but its segment stops at x = 0.5
        let segs = [
            (DVec2::new(0.0, 0.5), DVec2::new(0.5, 0.5)),
            (DVec2::new(0.5, 0.5), DVec2::new(0.5, 1.0)),
            (DVec2::new(2.0, 0.0), DVec2::new(2.0, 1.0)),
        ];
        let mut areas = Vec::new();
        assert!(Cutter::default().cut(&square, &segs, 1e-12, 64, |c| areas
            .push(area_centroid(c).0)));
        areas.sort_by(f64::total_cmp);
        // the first segment halves the square; the second then cuts the upper half's
        // part it reaches (x = 0.5 up from y = 0.5): the quarter and the rest
        assert_eq!(areas.len(), 3, "{areas:?}");
        assert!((areas.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!((areas[0] - 0.25).abs() < 1e-15 && (areas[2] - 0.5).abs() < 1e-15);
    }
}
