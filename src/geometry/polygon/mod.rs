//! Polygons in a face's plane: their convex hulls, and the exact lit part of a face that
//! shadows cut.
//!
//! | concept | file |
//! |---|---|
//! | twice a polygon's signed area; whether a line passes through a box; the distance between two segments | here |
//! | convex hulls, one monotone chain: a point set's ([`convex_hull`]), and a hull's corners and near-boundary points by index ([`HullIndices`]) | `hull.rs` |
//! | the lit part of a face as disjoint convex pieces, shadows subtracted, and its area ([`Region`]) | `region/` |
//! | cutting convex polygons: inward edges, a split along a line, where a piece lies against a polygon | `clip.rs` |

mod clip;
mod hull;
mod region;

pub use clip::bounds;
pub use hull::{convex_hull, HullIndices};
pub use region::{Region, TooComplex};

use glam::DVec2;

/// Twice the signed area of a polygon (positive when counter-clockwise), m².
pub fn twice_signed_area(p: &[DVec2]) -> f64 {
    let n = p.len();
    if n < 3 {
        return 0.0;
    }
    let mut s = 0.0;
    for i in 0..n {
        s += p[i].perp_dot(p[(i + 1) % n]);
    }
    s
}

/// Does the line through `a` and `b` pass through the box `lo`–`hi` (touching counts)?
/// Its corners lie on both sides of the line, or on it: the box's centre lies no farther
/// from the line than the box reaches across it (one product across the line, not four).
#[inline]
pub fn line_meets_box(a: DVec2, b: DVec2, lo: DVec2, hi: DVec2) -> bool {
    let n = (b - a).perp();
    let (centre, half) = ((lo + hi) * 0.5, (hi - lo) * 0.5);
    n.dot(centre - a).abs() <= n.abs().dot(half)
}

/// The least distance between segments p0–p1 and q0–q1 (m; 0 where they cross).
pub fn segment_distance(p0: DVec2, p1: DVec2, q0: DVec2, q1: DVec2) -> f64 {
    let orient = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let (d1, d2) = (orient(p0, p1, q0), orient(p0, p1, q1));
    let (d3, d4) = (orient(q0, q1, p0), orient(q0, q1, p1));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return 0.0;
    }
    // else the nearest points include an end of one of them
    let to_segment = |x: DVec2, a: DVec2, b: DVec2| {
        let e = b - a;
        let l2 = e.length_squared();
        let t = if l2 > 0.0 {
            ((x - a).dot(e) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a + e * t - x).length()
    };
    to_segment(p0, q0, q1)
        .min(to_segment(p1, q0, q1))
        .min(to_segment(q0, p0, p1))
        .min(to_segment(q1, p0, p1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_meets_a_box_where_it_passes_through_or_touches_it() {
        let (lo, hi) = (DVec2::new(0.0, 0.0), DVec2::new(2.0, 1.0));
        let v = DVec2::new;
        // (a, b, whether the whole line through them meets the box), by construction
        let cases = [
            (v(-5.0, 0.5), v(-4.0, 0.5), true), // horizontal, through the middle
            (v(-5.0, 1.0), v(-4.0, 1.0), true), // along the top edge
            (v(-5.0, 1.5), v(-4.0, 1.5), false), // above it
            (v(3.0, -1.0), v(3.0, 7.0), false), // vertical, beside it
            (v(2.0, -1.0), v(2.0, 7.0), true),  // along the right edge
            (v(0.0, 3.0), v(3.0, 0.0), true),   // through the corner (2, 1)
            (v(0.0, 3.1), v(3.1, 0.0), false),  // just beyond that corner
            (v(-1.0, -1.0), v(-2.0, -2.0), true), // the diagonal, from outside the box
        ];
        for (a, b, meets) in cases {
            assert_eq!(line_meets_box(a, b, lo, hi), meets, "{a} → {b}");
            // the line, not the segment: its ends swapped or moved along it, the same
            assert_eq!(line_meets_box(b, a, lo, hi), meets, "{b} → {a}");
            assert_eq!(line_meets_box(a + (b - a) * 7.0, b, lo, hi), meets);
        }
    }
}
