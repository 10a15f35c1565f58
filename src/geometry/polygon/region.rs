//! Exact areas of shadowed faces: a face (a union of convex polygons in its own plane)
//! minus the shadows that blockers cast on it, each shadow a convex polygon.
//!
//! A face under parallel light is a flat region and every blocker face projects onto its
//! plane as a convex polygon, so the lit part is a polygon too: its area needs no
//! sampling. [`Region`] keeps the remaining part as disjoint convex pieces; subtracting a
//! convex polygon S from a convex piece R splits R along S's edges (the parts of R outside
//! each edge, in turn, are kept; what is inside all of them is R ∩ S and is dropped). All
//! in f64, in coordinates relative to the face, so the error is rounding only.

use super::clip::{
    bounds, boxes_apart, corners_along, inward_edges, relation_to, separated_by_own_edges, split,
    Relation,
};
use super::twice_signed_area;
use glam::DVec2;

/// The part of a plane (a face) still lit and seen, as disjoint convex pieces.
#[derive(Debug, Default)]
pub struct Region {
    /// Vertices of the pieces, each piece counter-clockwise. Append-only until
    /// [`Region::reset`]: a piece that is cut leaves its old vertices unused, so pieces
    /// that a shadow misses are never copied.
    pts: Vec<DVec2>,
    pieces: Vec<Piece>,
    next_pieces: Vec<Piece>,
    // buffers for one piece being split
    cur: Vec<DVec2>,
    inside: Vec<DVec2>,
    outside: Vec<DVec2>,
    /// Edges of the polygon being subtracted: point, unit inward normal.
    edges: Vec<(DVec2, DVec2)>,
    /// Many-sided polygons removed lazily (see [`Region::subtract_convex`]): their
    /// edges as in `edges`, polygon after polygon, and where each one's run ends.
    deferred_edges: Vec<(DVec2, DVec2)>,
    deferred_ends: Vec<u32>,
    deferred_bounds: Vec<(DVec2, DVec2)>,
    /// Bounds of all pieces.
    lo: DVec2,
    hi: DVec2,
    /// Lengths below this count as zero, m.
    eps: f64,
}

/// One convex piece: its vertices `pts[start..end]` and its bounds.
#[derive(Debug, Clone, Copy)]
struct Piece {
    start: u32,
    end: u32,
    lo: DVec2,
    hi: DVec2,
}

/// Fewest edges of a polygon that [`Region::subtract_convex`] holds aside rather than
/// cuts out: a triangle or quad cuts a piece into at most a few fragments.
const DEFER_EDGES: usize = 12;
/// Most polygons held aside at once: [`Region::area`] sums 2^k terms.
const MAX_DEFERRED: usize = 3;

/// Too many pieces: the shadows cut the face up so finely that sampling is cheaper.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TooComplex;

impl Clone for Region {
    fn clone(&self) -> Region {
        let mut r = Region::default();
        r.clone_from(self);
        r
    }

    /// Copies the region into this one's buffers (no allocation once they have grown):
    /// called per face and direction. The scratch buffers are not copied.
    fn clone_from(&mut self, source: &Region) {
        self.pts.clone_from(&source.pts);
        self.pieces.clone_from(&source.pieces);
        self.deferred_edges.clone_from(&source.deferred_edges);
        self.deferred_ends.clone_from(&source.deferred_ends);
        self.deferred_bounds.clone_from(&source.deferred_bounds);
        (self.lo, self.hi, self.eps) = (source.lo, source.hi, source.eps);
    }
}

impl Region {
    /// Empties the region; `scale` (m, the face's size) sets what counts as zero length.
    pub fn reset(&mut self, scale: f64) {
        self.pts.clear();
        self.pieces.clear();
        self.deferred_edges.clear();
        self.deferred_ends.clear();
        self.deferred_bounds.clear();
        self.eps = 1e-10 * scale;
        self.lo = DVec2::splat(f64::INFINITY);
        self.hi = DVec2::splat(f64::NEG_INFINITY);
    }

    /// Adds a convex polygon (either orientation) that overlaps no piece already held.
    pub fn add_convex(&mut self, poly: &[DVec2]) {
        let a = twice_signed_area(poly);
        if a.abs() <= self.eps * self.eps {
            return;
        }
        let start = self.pts.len() as u32;
        if a > 0.0 {
            self.pts.extend_from_slice(poly);
        } else {
            self.pts.extend(poly.iter().rev());
        }
        let (lo, hi) = bounds(poly);
        self.pieces.push(Piece {
            start,
            end: self.pts.len() as u32,
            lo,
            hi,
        });
        self.lo = self.lo.min(lo);
        self.hi = self.hi.max(hi);
    }

    /// Number of convex pieces (polygons removed lazily not counted).
    pub fn len(&self) -> usize {
        self.pieces.len()
    }

    /// No piece is left (the region may also be empty while pieces remain, wholly under
    /// polygons removed lazily).
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// Area of the region, m². With polygons D₁…D_k removed lazily, piece by piece by
    /// inclusion–exclusion over the D that cross the piece: |P \ ∪D| = Σ over subsets T
    /// of (−1)^|T| |P ∩ ⋂T|, each term the piece clipped (never split) by the D of T. A
    /// piece inside some D counts nothing; a D apart from it drops out.
    pub fn area(&mut self) -> f64 {
        let eps = self.eps;
        let mut sum = 0.0;
        for i in 0..self.pieces.len() {
            let pc = self.pieces[i];
            let piece = &self.pts[pc.start as usize..pc.end as usize];
            let mut crossing = 0u32;
            let mut covered = false;
            for k in 0..self.deferred_ends.len() {
                if boxes_apart((pc.lo, pc.hi), self.deferred_bounds[k], eps) {
                    continue;
                }
                match relation_to(piece, (pc.lo, pc.hi), self.deferred(k), eps) {
                    Relation::Apart => {}
                    Relation::Inside => covered = true,
                    Relation::Crossing => crossing |= 1 << k,
                }
                if covered {
                    break;
                }
            }
            if covered {
                continue;
            }
            let mut a = 0.5 * twice_signed_area(piece);
            // every non-empty subset of the crossing polygons
            let mut subset = crossing;
            while subset != 0 {
                let sign = if subset.count_ones() % 2 == 0 {
                    1.0
                } else {
                    -1.0
                };
                a += sign * self.clipped_area(i, subset);
                subset = (subset - 1) & crossing;
            }
            sum += a;
        }
        sum
    }

    /// Edges of the deferred polygon `k`.
    fn deferred(&self, k: usize) -> &[(DVec2, DVec2)] {
        &self.deferred_edges[self.deferred_range(k)]
    }

    /// Where the deferred polygon `k`'s edges lie in `deferred_edges`.
    fn deferred_range(&self, k: usize) -> std::ops::Range<usize> {
        let start = if k == 0 { 0 } else { self.deferred_ends[k - 1] };
        start as usize..self.deferred_ends[k] as usize
    }

    /// Area of piece `i` clipped to every deferred polygon in the bit set `subset`, m².
    /// The many-sided polygon is what gets clipped, by the piece's few edges first: a
    /// piece clipped by a 168-sided polygon would grow a vertex per edge crossed and cost
    /// each later cut that many.
    fn clipped_area(&mut self, i: usize, subset: u32) -> f64 {
        let eps = self.eps;
        let pc = self.pieces[i];
        let first = subset.trailing_zeros() as usize;
        self.cur.clear();
        let polygon = &self.deferred_edges[self.deferred_range(first)];
        self.cur.extend(polygon.iter().map(|&(a, _)| a));
        let piece = &self.pts[pc.start as usize..pc.end as usize];
        inward_edges(piece, true, eps, &mut self.edges);
        let (mut lo, mut hi) = bounds(&self.cur);
        let mut cut = |cur: &mut Vec<DVec2>,
                       inside: &mut Vec<DVec2>,
                       outside: &mut Vec<DVec2>,
                       edges: &[(DVec2, DVec2)]| {
            for &(a, m) in edges {
                // inside the edge when the bounding box's lowest corner along m is
                let corner = corners_along(m, lo, hi).0;
                if m.dot(corner - a) >= -eps || cur.iter().all(|p| m.dot(*p - a) >= -eps) {
                    continue;
                }
                split(cur, a, m, eps, inside, outside);
                std::mem::swap(cur, inside);
                if twice_signed_area(cur) <= eps * eps {
                    cur.clear();
                    return;
                }
                (lo, hi) = bounds(cur);
            }
        };
        cut(
            &mut self.cur,
            &mut self.inside,
            &mut self.outside,
            &self.edges,
        );
        for k in first + 1..self.deferred_ends.len() {
            if self.cur.is_empty() {
                return 0.0;
            }
            if subset & (1 << k) != 0 {
                let edges = &self.deferred_edges[self.deferred_range(k)];
                cut(&mut self.cur, &mut self.inside, &mut self.outside, edges);
            }
        }
        if self.cur.len() < 3 {
            return 0.0;
        }
        0.5 * twice_signed_area(&self.cur)
    }

    /// Fills `edges` with the edges of convex `s` (counter-clockwise when `ccw`, else
    /// clockwise): a point on each and its unit inward normal; edges shorter than `eps` are
    /// left out.
    fn set_edges(&mut self, s: &[DVec2], ccw: bool) {
        inward_edges(s, ccw, self.eps, &mut self.edges);
    }

    /// Keeps only the part inside the convex polygon `s` (either orientation): each piece
    /// is clipped to it, so pieces stay convex and their number never grows.
    pub fn intersect_convex(&mut self, s: &[DVec2]) {
        let a = twice_signed_area(s);
        if s.len() < 3 || a.abs() <= self.eps * self.eps {
            self.pieces.clear();
            return;
        }
        let eps = self.eps;
        self.set_edges(s, a > 0.0);
        let mut k = 0;
        while k < self.pieces.len() {
            let pc = self.pieces[k];
            let piece = &self.pts[pc.start as usize..pc.end as usize];
            if self
                .edges
                .iter()
                .all(|&(a, m)| piece.iter().all(|p| m.dot(*p - a) >= -eps))
            {
                k += 1; // wholly inside: kept as it is
                continue;
            }
            self.cur.clear();
            self.cur.extend_from_slice(piece);
            for &(a, m) in &self.edges {
                if self.cur.iter().all(|p| m.dot(*p - a) >= -eps) {
                    continue; // inside this edge: nothing to cut (most edges of a big polygon)
                }
                split(&self.cur, a, m, eps, &mut self.inside, &mut self.outside);
                std::mem::swap(&mut self.cur, &mut self.inside);
                if twice_signed_area(&self.cur) <= eps * eps {
                    break;
                }
            }
            if twice_signed_area(&self.cur) > eps * eps {
                let start = self.pts.len() as u32;
                self.pts.extend_from_slice(&self.cur);
                let (lo, hi) = bounds(&self.cur);
                self.pieces[k] = Piece {
                    start,
                    end: self.pts.len() as u32,
                    lo,
                    hi,
                };
                k += 1;
            } else {
                self.pieces.swap_remove(k);
            }
        }
        (self.lo, self.hi) = self.pieces.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p.lo), hi.max(p.hi)),
        );
    }

    /// Removes a convex polygon `s` (either orientation). Fails when the result would
    /// need more than `max_pieces` pieces; the region is then partly cut and of no use.
    ///
    /// A many-sided polygon (a dish's silhouette) that crosses a piece is not cut out but
    /// held aside and accounted for in [`Region::area`]: cutting it out splits a piece into
    /// about one fragment per edge, and every later shadow then pays for each fragment
    /// (measured: a 168-sided silhouette left 218 pieces on the box-wing's bus top).
    pub fn subtract_convex(&mut self, s: &[DVec2], max_pieces: usize) -> Result<(), TooComplex> {
        self.subtract(s, max_pieces, true)
    }

    fn subtract(
        &mut self,
        s: &[DVec2],
        max_pieces: usize,
        may_defer: bool,
    ) -> Result<(), TooComplex> {
        let a = twice_signed_area(s);
        if s.len() < 3 || a.abs() <= self.eps * self.eps {
            return Ok(()); // an edge-on blocker casts no shadow of any area
        }
        let (lo, hi) = bounds(s);
        let eps = self.eps;
        if boxes_apart((lo, hi), (self.lo, self.hi), eps) {
            return Ok(()); // misses every piece
        }
        self.set_edges(s, a > 0.0);
        let defer =
            may_defer && self.edges.len() >= DEFER_EDGES && self.deferred_ends.len() < MAX_DEFERRED;
        // Cut pieces are swapped out of `pieces` (only the originals stay there during the
        // loop); their fragments collect in `next_pieces` and are appended at the end, so
        // pieces the shadow misses are never moved.
        self.next_pieces.clear();
        let mut k = 0;
        let mut live = self.pieces.len();
        let before = live;
        let mut crossed = false;
        while k < live {
            let pc = self.pieces[k];
            let (plo, phi) = (pc.lo, pc.hi);
            if boxes_apart((plo, phi), (lo, hi), eps) {
                k += 1;
                continue;
            }
            let piece = &self.pts[pc.start as usize..pc.end as usize];
            let relation = relation_to(piece, (plo, phi), &self.edges, eps);
            if relation == Relation::Apart || separated_by_own_edges(piece, s.iter().copied(), eps)
            {
                k += 1;
                continue;
            }
            if relation == Relation::Inside {
                // wholly in the shadow (a face under a larger blocker): no cuts needed
                self.pieces.swap_remove(k);
                live -= 1;
                continue;
            }
            if defer {
                crossed = true; // held aside below instead of cut
                k += 1;
                continue;
            }
            self.cur.clear();
            self.cur.extend_from_slice(piece);
            for &(a, m) in &self.edges {
                split(&self.cur, a, m, eps, &mut self.inside, &mut self.outside);
                if twice_signed_area(&self.outside) > self.eps * self.eps {
                    let start = self.pts.len() as u32;
                    self.pts.extend_from_slice(&self.outside);
                    let (lo, hi) = bounds(&self.outside);
                    self.next_pieces.push(Piece {
                        start,
                        end: self.pts.len() as u32,
                        lo,
                        hi,
                    });
                }
                std::mem::swap(&mut self.cur, &mut self.inside);
                if twice_signed_area(&self.cur) <= self.eps * self.eps {
                    break; // nothing of the piece is left inside the shadow
                }
            }
            self.pieces.swap_remove(k);
            live -= 1;
            if live + self.next_pieces.len() > max_pieces {
                return Err(TooComplex);
            }
        }
        if crossed {
            self.deferred_edges.extend_from_slice(&self.edges);
            self.deferred_ends.push(self.deferred_edges.len() as u32);
            self.deferred_bounds.push((lo, hi));
        }
        if live == before && self.next_pieces.is_empty() {
            return Ok(()); // the shadow missed every piece: bounds unchanged
        }
        self.pieces.append(&mut self.next_pieces);
        (self.lo, self.hi) = self.pieces.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(p.lo), hi.max(p.hi)),
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon::convex_hull;

    fn square(x0: f64, y0: f64, s: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x0, y0),
            DVec2::new(x0 + s, y0),
            DVec2::new(x0 + s, y0 + s),
            DVec2::new(x0, y0 + s),
        ]
    }

    fn unit_region() -> Region {
        let mut r = Region::default();
        r.reset(1.0);
        r.add_convex(&square(0.0, 0.0, 1.0));
        r
    }

    #[test]
    fn intersecting_keeps_the_overlap_and_never_splits() {
        let mut r = Region::default();
        r.reset(1.0);
        r.add_convex(&square(0.0, 0.0, 1.0));
        r.add_convex(&square(1.0, 0.0, 1.0));
        // a diamond over both squares' shared edge
        let diamond = [
            DVec2::new(1.0, -0.5),
            DVec2::new(1.5, 0.5),
            DVec2::new(1.0, 1.5),
            DVec2::new(0.5, 0.5),
        ];
        r.intersect_convex(&diamond);
        assert_eq!(r.len(), 2);
        // the diamond (area 1) pokes out below y = 0 and above y = 1 by triangles of
        // base 0.5 and height 0.5 (area 0.125 each)
        assert!(
            (r.area() - (1.0 - 2.0 * 0.125)).abs() < 1e-15,
            "{}",
            r.area()
        );
        r.intersect_convex(&square(5.0, 5.0, 1.0));
        assert!(r.is_empty());
    }

    #[test]
    fn half_covered_square_keeps_half() {
        let mut r = unit_region();
        r.subtract_convex(&square(0.5, -1.0, 3.0), 64).unwrap();
        assert!((r.area() - 0.5).abs() < 1e-15, "{}", r.area());
    }

    #[test]
    fn hole_in_the_middle_and_overlapping_shadows() {
        let mut r = unit_region();
        r.subtract_convex(&square(0.25, 0.25, 0.5), 64).unwrap();
        assert!((r.area() - 0.75).abs() < 1e-15);
        // a second shadow: x 0.65..1.15 meets the face over 0.35 × 0.5 = 0.175, of which
        // 0.1 × 0.5 = 0.05 is already in the hole: 0.125 more goes
        r.subtract_convex(&square(0.65, 0.25, 0.5), 64).unwrap();
        assert!((r.area() - 0.625).abs() < 1e-15, "{}", r.area());
    }

    #[test]
    fn clockwise_shadow_and_disjoint_shadow() {
        let mut r = unit_region();
        let mut s = square(-0.5, -0.5, 1.0);
        s.reverse();
        r.subtract_convex(&s, 64).unwrap();
        assert!((r.area() - 0.75).abs() < 1e-15);
        let n = r.len();
        r.subtract_convex(&square(5.0, 5.0, 1.0), 64).unwrap();
        assert_eq!(r.len(), n, "a shadow elsewhere does not split pieces");
        r.subtract_convex(&square(-1.0, -1.0, 3.0), 64).unwrap();
        assert!(r.area().abs() < 1e-15 && r.is_empty());
    }

    #[test]
    fn triangle_corner_and_degenerate_shadows() {
        let mut r = unit_region();
        let tri = [
            DVec2::new(0.0, 0.0),
            DVec2::new(0.5, 0.0),
            DVec2::new(0.0, 0.5),
        ];
        r.subtract_convex(&tri, 64).unwrap();
        assert!((r.area() - (1.0 - 0.125)).abs() < 1e-15);
        // an edge-on blocker (zero area) changes nothing
        let line = [
            DVec2::new(0.0, 0.9),
            DVec2::new(1.0, 0.9),
            DVec2::new(0.5, 0.9),
        ];
        r.subtract_convex(&line, 64).unwrap();
        assert!((r.area() - (1.0 - 0.125)).abs() < 1e-15);
    }

    #[test]
    fn many_random_shadows_match_a_fine_grid() {
        // Truth by counting grid cells: independent of the clipping code. 400×400 cell
        // centres: edges crossing cells misjudge at most half a cell each, and those errors
        // mostly cancel; 2e-3 is ~5 cells' worth per shadow edge.
        let mut r = unit_region();
        let mut shadows = Vec::new();
        let mut rnd = crate::test_rng(12345);
        for _ in 0..12 {
            let c = DVec2::new(rnd(), rnd());
            let tri = [
                c,
                c + DVec2::new(0.3 * rnd(), 0.1 * rnd()),
                c + DVec2::new(-0.1 * rnd(), 0.3 * rnd()),
            ];
            r.subtract_convex(&tri, 10_000).unwrap();
            shadows.push(tri);
        }
        let inside = |t: &[DVec2; 3], p: DVec2| {
            let s = twice_signed_area(t).signum();
            (0..3).all(|i| s * (t[(i + 1) % 3] - t[i]).perp_dot(p - t[i]) > 0.0)
        };
        let n = 400;
        let mut lit = 0;
        for i in 0..n {
            for j in 0..n {
                let p = DVec2::new((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                if !shadows.iter().any(|t| inside(t, p)) {
                    lit += 1;
                }
            }
        }
        let grid = lit as f64 / (n * n) as f64;
        assert!((r.area() - grid).abs() < 2e-3, "{} vs {grid}", r.area());
    }

    /// A convex polygon of up to `n` corners about `c`: corners at jittered angles and at
    /// radii in [0.7 r, r], and their hull taken.
    fn random_convex(rnd: &mut impl FnMut() -> f64, c: DVec2, r: f64, n: usize) -> Vec<DVec2> {
        let pts: Vec<DVec2> = (0..n)
            .map(|i| {
                let t = (i as f64 + 0.5 * rnd()) / n as f64 * std::f64::consts::TAU;
                c + DVec2::new(t.cos(), t.sin()) * r * (0.7 + 0.3 * rnd())
            })
            .collect();
        let (mut order, mut hull) = (Vec::new(), Vec::new());
        convex_hull(&pts, &mut order, &mut hull);
        hull
    }

    #[test]
    fn many_sided_shadows_held_aside_give_the_area_cutting_them_out_gives() {
        // The same shadows removed two ways: many-sided ones held aside (inclusion–exclusion
        // at the end) and every one cut out. Both are exact, so they agree to rounding
        // (1e-12 of a unit face: a few hundred cuts of ~1e-16 each); a fine grid, which
        // uses neither, checks both to its resolution (2e-3, as for the triangles above).
        let mut rnd = crate::test_rng(777);
        for trial in 0..20 {
            let mut held = Region::default();
            held.reset(1.0);
            held.add_convex(&square(0.0, 0.0, 1.0));
            held.add_convex(&square(1.0, 0.0, 1.0));
            let mut cut = held.clone();
            let mut shadows: Vec<Vec<DVec2>> = Vec::new();
            for k in 0..6 {
                let c = DVec2::new(2.0 * rnd(), rnd());
                // many-sided and large, or a small triangle
                let (r, n) = if k % 2 == 0 {
                    (0.2 + 0.4 * rnd(), 16 + (40.0 * rnd()) as usize)
                } else {
                    (0.05 + 0.2 * rnd(), 3)
                };
                let s = random_convex(&mut rnd, c, r, n);
                held.subtract_convex(&s, 100_000).unwrap();
                cut.subtract(&s, 100_000, false).unwrap();
                shadows.push(s);
            }
            if trial == 0 {
                assert!(!held.deferred_ends.is_empty(), "nothing was held aside");
                assert!(cut.deferred_ends.is_empty());
            }
            // clipping to a lid after the shadows, and a copy, keep what is held aside
            let lid = random_convex(&mut rnd, DVec2::new(1.0, 0.5), 0.9, 24);
            held.intersect_convex(&lid);
            cut.intersect_convex(&lid);
            let mut copy = Region::default();
            copy.clone_from(&held);
            let (a_held, a_cut, a_copy) = (held.area(), cut.area(), copy.area());
            assert!(
                (a_held - a_cut).abs() < 1e-12,
                "trial {trial}: {a_held} vs {a_cut}"
            );
            assert_eq!(a_held, a_copy);
            let inside = |poly: &[DVec2], p: DVec2| {
                (0..poly.len())
                    .all(|i| (poly[(i + 1) % poly.len()] - poly[i]).perp_dot(p - poly[i]) > 0.0)
            };
            let (nx, ny) = (400, 200);
            let mut lit = 0;
            for i in 0..nx {
                for j in 0..ny {
                    let p = DVec2::new((i as f64 + 0.5) / 200.0, (j as f64 + 0.5) / 200.0);
                    if inside(&lid, p) && !shadows.iter().any(|s| inside(s, p)) {
                        lit += 1;
                    }
                }
            }
            let grid = lit as f64 / (200.0 * 200.0);
            assert!(
                (a_held - grid).abs() < 2e-3,
                "trial {trial}: {a_held} vs grid {grid}"
            );
        }
    }

    #[test]
    fn too_many_pieces_is_reported() {
        let mut r = unit_region();
        assert_eq!(
            r.subtract_convex(&square(0.25, 0.25, 0.5), 2),
            Err(TooComplex)
        );
    }
}
