//! Convex hulls of points in a plane by Andrew's monotone chain: a point set's hull
//! ([`convex_hull`], which first drops the points inside the octagon of the set's
//! extremes, so that a finely meshed face's hull sorts its outline only) and, by index,
//! a hull's corners and the points near its boundary ([`HullIndices`]). Both sort with
//! [`sort_by_position`] and walk [`monotone_chain`]; each keeps its own rule for which
//! turns keep a point, and so its own answer for
//! collinear points and NaN turns (a NaN coordinate): [`convex_hull`] drops a point on
//! a turn ≤ 0 and keeps it on a NaN turn, [`HullIndices`] keeps a point only on a turn
//! > 0 (corners) or ≥ −slack·|b − o| (near points), so a NaN turn drops it.
//!
//! A third chain, a face's outline in `integrate/visibility/face.rs`, sorts (x, y, index)
//! tuples with a stable sort and is not written on these: that module belongs to the
//! visibility engine's own rewrite.

use glam::DVec2;

/// Sorts `order` (indices into `points`) by x, then y (`total_cmp`, unstable): the order
/// the chain walks.
fn sort_by_position(order: &mut [u32], points: &[DVec2]) {
    order.sort_unstable_by(|&a, &b| {
        let (p, q) = (points[a as usize], points[b as usize]);
        p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y))
    });
}

/// Andrew's monotone chain over `n` items sorted by position (`item(j)` the j-th, `at(x)`
/// its point): the lower chain walked forwards, then the upper backwards, each without its
/// last item (the other chain's first), appended to `out`. Before an item `b` is pushed,
/// the chain's last item `a` (after `o`) is popped until `keeps(o, a, b)`.
fn monotone_chain<T: Copy>(
    n: usize,
    item: impl Fn(usize) -> T,
    at: impl Fn(T) -> DVec2,
    keeps: impl Fn(DVec2, DVec2, DVec2) -> bool,
    out: &mut Vec<T>,
) {
    for pass in 0..2 {
        let start = out.len();
        for j in 0..n {
            let b = item(if pass == 0 { j } else { n - 1 - j });
            while out.len() >= start + 2
                && !keeps(at(out[out.len() - 2]), at(out[out.len() - 1]), at(b))
            {
                out.pop();
            }
            out.push(b);
        }
        out.pop(); // the chain's last point starts the other chain
    }
}

/// Fewer points than this are sorted as they are: the octagon's pass would not pay.
const FEW_POINTS: usize = 64;

/// Indices of `points` that may be corners of their hull, into `order`: all of them, or,
/// for many, those not strictly inside the octagon of the points extreme along eight
/// directions (Akl–Toussaint): a point inside a polygon of the points' own cannot be a
/// corner of their hull, and a finely meshed face's points are nearly all inside, so the
/// sort that follows takes its outline, not its area. "Strictly" keeps every point within
/// 1e-9 of the octagon's size of its sides (rounding cannot drop a corner), and any with
/// a NaN coordinate.
fn candidates(points: &[DVec2], order: &mut Vec<u32>) {
    order.clear();
    if points.len() < FEW_POINTS {
        order.extend(0..points.len() as u32);
        return;
    }
    const DIRS: [(f64, f64); 8] = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
    ];
    let mut best = [(f64::NEG_INFINITY, usize::MAX); 8];
    for (i, p) in points.iter().enumerate() {
        for (k, &(a, b)) in DIRS.iter().enumerate() {
            let s = a * p.x + b * p.y;
            if s > best[k].0 {
                best[k] = (s, i);
            }
        }
    }
    // the extremes in the order of their directions run counter-clockwise round the hull
    let mut ring: Vec<DVec2> = Vec::with_capacity(8);
    for &(_, i) in &best {
        if i == usize::MAX {
            order.extend(0..points.len() as u32);
            return;
        }
        let q = points[i];
        if ring.last() != Some(&q) && ring.first() != Some(&q) {
            ring.push(q);
        }
    }
    let size = best[0].0 + best[4].0 + best[2].0 + best[6].0; // width + height
    if ring.len() < 3 || !(size > 0.0 && size.is_finite()) {
        order.extend(0..points.len() as u32);
        return;
    }
    let slack = 1e-9 * size;
    let edges: Vec<(DVec2, DVec2, f64)> = (0..ring.len())
        .map(|k| {
            let (a, b) = (ring[k], ring[(k + 1) % ring.len()]);
            (a, b - a, slack * (b - a).length())
        })
        .collect();
    order.extend((0..points.len() as u32).filter(|&i| {
        let p = points[i as usize];
        // kept unless inside every side by more than the slack (a NaN compares false)
        !edges.iter().all(|&(a, e, s)| e.perp_dot(p - a) > s)
    }));
}

/// The convex hull of `points`, counter-clockwise without collinear points, into `out`
/// (Andrew's monotone chain); `order` is scratch.
pub fn convex_hull(points: &[DVec2], order: &mut Vec<u32>, out: &mut Vec<DVec2>) {
    candidates(points, order);
    chain_of(points, order, out);
}

/// The hull of the points `order` lists (reordered here), into `out`.
fn chain_of(points: &[DVec2], order: &mut Vec<u32>, out: &mut Vec<DVec2>) {
    sort_by_position(order, points);
    drop_near_twins(points, order);
    out.clear();
    // a turn ≤ 0 drops the middle point; a NaN turn keeps it
    let keeps = |o: DVec2, a: DVec2, b: DVec2| {
        let turn = (a - o).perp_dot(b - o);
        turn > 0.0 || turn.is_nan()
    };
    monotone_chain(
        order.len(),
        |j| points[order[j] as usize],
        |p| p,
        keeps,
        out,
    );
}

/// Drops from `order` (sorted by position) each point within 1e-9 of the points' size of
/// one kept before it. Two such near twins (one point computed two ways, as where an edge
/// two faces share crosses a plane) join by an edge whose direction is rounding, and the
/// chain's turns then kept a corner that lies inside the hull: an 80-sided tube's shadow
/// hull lost 2e-3 m² of its 2.4 to one. Dropping a twin moves the hull by no more than
/// the twins are apart.
fn drop_near_twins(points: &[DVec2], order: &mut Vec<u32>) {
    let (lo, hi) = order.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), &i| (lo.min(points[i as usize]), hi.max(points[i as usize])),
    );
    let near = 1e-9 * (hi - lo).max_element();
    if !(near > 0.0 && near.is_finite()) {
        return;
    }
    let mut kept = 0;
    for i in 0..order.len() {
        let p = points[order[i] as usize];
        // the kept points within `near` of p in x lie just before it
        let twin = order[..kept]
            .iter()
            .rev()
            .map(|&j| points[j as usize])
            .take_while(|q| p.x - q.x <= near)
            .any(|q| (p - q).length_squared() <= near * near);
        if !twin {
            order[kept] = order[i];
            kept += 1;
        }
    }
    order.truncate(kept);
}

/// Hull corners and near-boundary points of a set of points, by index.
#[derive(Debug, Default, Clone)]
pub struct HullIndices {
    /// Corners of the convex hull, counter-clockwise, without collinear points.
    pub corners: Vec<u32>,
    /// Every point within the slack of the hull's boundary (the corners among them), in
    /// no particular order: what a cut of the point set by a line can expose.
    pub near: Vec<u32>,
    order: Vec<u32>,
    /// `order` without near twins ([`drop_near_twins`]), which the corners are found over.
    twinless: Vec<u32>,
    chain: Vec<u32>,
}

impl HullIndices {
    /// Computes both lists for `points`; `slack` (m) is how far inside the boundary a
    /// point still counts as on it. Points well inside an octagon of extreme points are
    /// dropped first (Akl–Toussaint), so only a band along the boundary is sorted: a
    /// finely meshed dish projects to thousands of points, mostly inside.
    pub fn compute(&mut self, points: &[DVec2], slack: f64) {
        self.compute_corners(points, slack);
        self.compute_near(points, slack);
    }

    /// The corners alone ([`HullIndices::compute`] without `near`, which is left empty
    /// until [`HullIndices::compute_near`] is called with the same points).
    pub fn compute_corners(&mut self, points: &[DVec2], slack: f64) {
        self.order.clear();
        if points.len() > 32 {
            let keys = |p: DVec2| [p.x, p.y, p.x + p.y, p.x - p.y];
            let (mut lo, mut hi) = ([0u32; 4], [0u32; 4]);
            let (mut lo_v, mut hi_v) = ([f64::INFINITY; 4], [f64::NEG_INFINITY; 4]);
            for (i, p) in points.iter().enumerate() {
                for (k, v) in keys(*p).into_iter().enumerate() {
                    if v < lo_v[k] {
                        (lo_v[k], lo[k]) = (v, i as u32);
                    }
                    if v > hi_v[k] {
                        (hi_v[k], hi[k]) = (v, i as u32);
                    }
                }
            }
            // the octagon (some corners may coincide), counter-clockwise: min y, max x−y,
            // max x, max x+y, max y, min x−y, min x, min x+y
            let ring = [lo[1], hi[3], hi[0], hi[2], hi[1], lo[3], lo[0], lo[2]];
            let edges: Vec<(DVec2, DVec2)> = (0..8)
                .filter_map(|i| {
                    let (a, b) = (points[ring[i] as usize], points[ring[(i + 1) % 8] as usize]);
                    let e = b - a;
                    let len = e.length();
                    (len > 0.0).then(|| (a, e.perp() / len))
                })
                .collect();
            self.order.extend((0..points.len() as u32).filter(|&i| {
                let p = points[i as usize];
                // perp is the inward normal of a counter-clockwise ring: a point is kept
                // unless it lies deeper than the slack inside every edge
                edges.len() < 3 || edges.iter().any(|&(a, m)| m.dot(p - a) <= slack)
            }));
        } else {
            self.order.extend(0..points.len() as u32);
        }
        sort_by_position(&mut self.order, points);
        self.twinless.clone_from(&self.order);
        drop_near_twins(points, &mut self.twinless);
        self.corners.clear();
        self.near.clear();
        self.chain_pass(points, slack, false);
    }

    /// `near` for the points last given to [`HullIndices::compute_corners`].
    pub fn compute_near(&mut self, points: &[DVec2], slack: f64) {
        self.near.clear();
        self.chain_pass(points, slack, true);
        self.near.sort_unstable();
        self.near.dedup();
    }

    /// Monotone chains over the sorted points: strict for the corners (a turn > 0 keeps
    /// a point), tolerant (by `slack`) for the near points; a NaN turn drops it in both.
    /// The near points are sought among all the points (twins are different vertices,
    /// perhaps at different heights), the corners among those without near twins.
    fn chain_pass(&mut self, points: &[DVec2], slack: f64, tolerant: bool) {
        self.chain.clear();
        let order = if tolerant {
            &self.order
        } else {
            &self.twinless
        };
        let item = |j: usize| order[j];
        let at = |i: u32| points[i as usize];
        if tolerant {
            let keeps =
                |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o) >= -slack * (b - o).length();
            monotone_chain(order.len(), item, at, keeps, &mut self.chain);
            self.near.extend_from_slice(&self.chain);
        } else {
            let keeps = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o) > 0.0;
            monotone_chain(order.len(), item, at, keeps, &mut self.chain);
            self.corners.extend_from_slice(&self.chain);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon::twice_signed_area;

    #[test]
    fn near_twins_do_not_fold_the_hull_flat() {
        // Four points of an 80-sided tube's shadow on a box it runs through: a far corner
        // of its end, a corner of its section by the box's side, and the section's next
        // corner met twice (from the two faces that share its edge), 6e-16 m apart. The
        // chain took the twins' rounding for a turn and folded the triangle flat.
        let far = DVec2::new(1.2083532486675592, -1.6336727316457014);
        let next = DVec2::new(0.4157457899999999, 0.1722075450000003);
        let twin = DVec2::new(0.4279754320000001, 0.1390576469999997);
        let other = DVec2::new(0.4279754319999999, 0.1390576470000003);
        let (mut order, mut hull) = (Vec::new(), Vec::new());
        convex_hull(&[far, next, twin, other], &mut order, &mut hull);
        let triangle = 0.5 * (next - far).perp_dot(twin - far).abs();
        assert!(triangle > 2e-3);
        assert_eq!(hull.len(), 3, "{hull:?}");
        let area = 0.5 * twice_signed_area(&hull);
        assert!(
            (area - triangle).abs() <= 1e-12,
            "{area} against {triangle}"
        );
        // and the corners by index, where the near points keep both twins
        let mut h = HullIndices::default();
        h.compute(&[far, next, twin, other], 1e-12);
        assert_eq!(h.corners.len(), 3, "{:?}", h.corners);
        assert_eq!(h.near, [0, 1, 2, 3]);
    }

    #[test]
    fn hull_indices_find_the_corners_and_every_boundary_point() {
        // Random points in a disc plus points placed on the edges of a square around it:
        // the corners must be the square's, and every point within the slack of the
        // boundary (the placed ones, exactly on it) must be among the near points.
        let mut rnd = crate::test_rng(5);
        let mut pts: Vec<DVec2> = (0..3000)
            .map(|_| {
                let (r, a) = (rnd().sqrt() * 0.9, rnd() * std::f64::consts::TAU);
                DVec2::new(r * a.cos(), r * a.sin())
            })
            .collect();
        let square = [
            DVec2::new(-1.0, -1.0),
            DVec2::new(1.0, -1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(-1.0, 1.0),
        ];
        let first_placed = pts.len();
        for k in 0..4 {
            let (a, b) = (square[k], square[(k + 1) % 4]);
            pts.extend((0..=10).map(|i| a + (b - a) * (i as f64 / 10.0)));
        }
        let mut h = HullIndices::default();
        h.compute(&pts, 1e-9);
        let mut corners: Vec<DVec2> = h.corners.iter().map(|&i| pts[i as usize]).collect();
        assert_eq!(corners.len(), 4, "{corners:?}");
        assert!(twice_signed_area(&corners) > 0.0, "counter-clockwise");
        corners.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        let mut want = square.to_vec();
        want.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        assert_eq!(corners, want);
        for (i, p) in pts.iter().enumerate().skip(first_placed) {
            let found = h.near.binary_search(&(i as u32)).is_ok();
            assert!(found, "boundary point {i} {p:?} missed");
        }
        // nothing from inside the disc (0.9 from the centre, 0.1 inside the square)
        assert!(h.near.iter().all(|&i| i as usize >= first_placed));
        // the same corners as the plain hull for points with no structure
        let mut rnd = crate::test_rng(6);
        let cloud: Vec<DVec2> = (0..500).map(|_| DVec2::new(rnd(), rnd() * rnd())).collect();
        h.compute(&cloud, 0.0);
        let (mut order, mut hull) = (Vec::new(), Vec::new());
        convex_hull(&cloud, &mut order, &mut hull);
        let got: Vec<DVec2> = h.corners.iter().map(|&i| cloud[i as usize]).collect();
        assert_eq!(got, hull);
    }

    #[test]
    fn the_octagon_drops_no_corner_the_chain_would_keep() {
        // Truth: the same chain over every point, unfiltered. Point sets: a finely
        // gridded rectangle (every side full of collinear points, as a merged face's
        // triangles give), a rotated grid, a disk of random points, a thin sliver;
        // exact equality, since the kept points are the chain's only candidates.
        let mut rnd = crate::test_rng(3);
        for case in 0..40 {
            let mut pts = Vec::new();
            let (c, s) = (0.3 * case as f64).sin_cos();
            match case % 4 {
                0 | 1 => {
                    let (nx, ny) = (20 + case, 7 + case / 2);
                    for i in 0..=nx {
                        for j in 0..=ny {
                            let (x, y) = (3.0 * i as f64 / nx as f64, j as f64 / ny as f64);
                            let p = if case % 4 == 1 {
                                DVec2::new(c * x - s * y, s * x + c * y)
                            } else {
                                DVec2::new(x, y)
                            };
                            // each corner listed by several triangles
                            pts.extend([p, p, p]);
                        }
                    }
                }
                2 => {
                    for _ in 0..500 {
                        let (r, a) = (rnd().sqrt(), std::f64::consts::TAU * rnd());
                        pts.push(DVec2::new(r * a.cos(), r * a.sin()) * 1e3);
                    }
                }
                _ => {
                    for _ in 0..300 {
                        let t = rnd();
                        pts.push(DVec2::new(1e-4 * t + 5.0, 1e-7 * rnd() - 2.0));
                    }
                }
            }
            let (mut order, mut hull) = (Vec::new(), Vec::new());
            convex_hull(&pts, &mut order, &mut hull);
            assert!(
                order.len() < pts.len() || case % 4 == 3,
                "case {case}: nothing dropped"
            );
            let mut all: Vec<u32> = (0..pts.len() as u32).collect();
            let mut want = Vec::new();
            chain_of(&pts, &mut all, &mut want);
            assert_eq!(hull, want, "case {case}");
        }
    }

    #[test]
    fn convex_hull_of_a_square_with_inner_and_edge_points() {
        let pts: Vec<DVec2> = [
            (0.0, 0.0),
            (1.0, 0.0),
            (0.5, 0.0),
            (1.0, 1.0),
            (0.3, 0.4),
            (0.0, 1.0),
            (0.5, 1.0),
        ]
        .iter()
        .map(|&(x, y)| DVec2::new(x, y))
        .collect();
        let (mut order, mut hull) = (Vec::new(), Vec::new());
        convex_hull(&pts, &mut order, &mut hull);
        assert_eq!(hull.len(), 4, "{hull:?}");
        assert!((twice_signed_area(&hull) - 2.0).abs() < 1e-15);
    }
}
