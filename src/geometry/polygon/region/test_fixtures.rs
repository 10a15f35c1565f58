//! Test-only shapes shared by the region's tests: squares, a unit square's region, random
//! convex polygons.

use super::Region;
use crate::geometry::polygon::convex_hull;
use glam::DVec2;

pub(super) fn square(x0: f64, y0: f64, s: f64) -> Vec<DVec2> {
    vec![
        DVec2::new(x0, y0),
        DVec2::new(x0 + s, y0),
        DVec2::new(x0 + s, y0 + s),
        DVec2::new(x0, y0 + s),
    ]
}

pub(super) fn unit_region() -> Region {
    let mut r = Region::default();
    r.reset(1.0);
    r.add_convex(&square(0.0, 0.0, 1.0));
    r
}

/// A convex polygon of up to `n` corners about `c`: corners at jittered angles and at
/// radii in [0.7 r, r], and their hull taken.
pub(super) fn random_convex(
    rnd: &mut impl FnMut() -> f64,
    c: DVec2,
    r: f64,
    n: usize,
) -> Vec<DVec2> {
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
