//! Polygons in a face's plane: their convex hulls, and the exact lit part of a face that
//! shadows cut.
//!
//! | concept | file |
//! |---|---|
//! | twice a polygon's signed area | here |
//! | convex hulls, one monotone chain: a point set's ([`convex_hull`]), and a hull's corners and near-boundary points by index ([`HullIndices`]) | `hull.rs` |
//! | the lit part of a face as disjoint convex pieces, shadows subtracted, and its area ([`Region`]) | `region/` |
//! | cutting convex polygons: inward edges, a split along a line, where a piece lies against a polygon | `clip.rs` |

mod clip;
mod hull;
mod region;

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
