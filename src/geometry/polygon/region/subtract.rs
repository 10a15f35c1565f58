//! A convex polygon subtracted from a region: each piece it crosses split along its
//! edges (the parts outside each edge kept in turn), or, for a many-sided polygon, held
//! aside for [`Region::area`].

use super::super::clip::{
    bounds, boxes_apart, relation_to, separated_by_own_edges, split, Relation,
};
use super::super::twice_signed_area;
use super::{Piece, Region, TooComplex};
use glam::DVec2;

/// Fewest edges of a polygon that [`Region::subtract_convex`] holds aside rather than
/// cuts out: a triangle or quad cuts a piece into at most a few fragments.
const DEFER_EDGES: usize = 12;
/// Most polygons held aside at once: [`Region::area`] sums 2^k terms.
const MAX_DEFERRED: usize = 3;

impl Region {
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
    use super::super::test_fixtures::{random_convex, square, unit_region};
    use super::*;

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
