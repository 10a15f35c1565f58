//! Exact areas of shadowed faces: a face (a union of convex polygons in its own plane)
//! minus the shadows that blockers cast on it, each shadow a convex polygon.
//!
//! A face under parallel light is a flat region and every blocker face projects onto its
//! plane as a convex polygon, so the lit part is a polygon too: its area needs no
//! sampling. [`Region`] keeps the remaining part as disjoint convex pieces; subtracting a
//! convex polygon S from a convex piece R splits R along S's edges (the parts of R outside
//! each edge, in turn, are kept; what is inside all of them is R ∩ S and is dropped). All
//! in f64, in coordinates relative to the face, so the error is rounding only.
//!
//! | concept | file |
//! |---|---|
//! | the region: its pieces, filled, copied, clipped to a convex polygon | `mod.rs` |
//! | a convex polygon subtracted: pieces split along its edges, or a many-sided one held aside | `subtract.rs` |
//! | the area, by inclusion–exclusion over the polygons held aside | `area.rs` |

mod area;
mod subtract;
#[cfg(test)]
mod test_fixtures;

use super::clip::{bounds, inward_edges, split};
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
}

#[cfg(test)]
mod tests {
    use super::test_fixtures::square;
    use super::*;

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
}
