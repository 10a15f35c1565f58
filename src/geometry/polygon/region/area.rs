//! The area of a region, m²: its pieces' areas, less what the polygons held aside cover
//! (by inclusion–exclusion over those that cross each piece).

use super::super::clip::{
    bounds, boxes_apart, corners_along, inward_edges, relation_to, split, Relation,
};
use super::super::twice_signed_area;
use super::Region;
use glam::DVec2;

impl Region {
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
}
