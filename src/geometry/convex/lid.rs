//! Lids: the open side of a convex cap (a dish's rim) as a convex polygon. A ray from the
//! cap into its hull passes the cap unblocked exactly when it leaves through the lid, so
//! what a dish's faces see of the sky is decided by one point-in-polygon test per ray;
//! the centre, circles and pseudo-angles kept with the outline make that test a lookup
//! rather than a pass over the edges.

use crate::geometry::mesh::Mesh;

/// The open side of a convex cap: a convex polygon. A ray from a face of the cap into the
/// cap's hull leaves the hull once, and passes the cap unblocked exactly when it leaves
/// through the lid: a dish's faces see out only through its rim.
#[derive(Debug, Clone)]
pub struct Lid {
    /// Its corners in order, m.
    pub corners: Vec<glam::DVec3>,
    /// Unit normal pointing out of the hull.
    pub normal: glam::DVec3,
    /// In-plane axes (u × w = normal) and origin of `outline`, m.
    pub u: glam::DVec3,
    pub w: glam::DVec3,
    pub origin: glam::DVec3,
    /// The corners in (u, w) coordinates, counter-clockwise, m.
    pub outline: Vec<glam::DVec2>,
    /// A point inside the outline (the corners' mean), the radius of the circle about it
    /// that the outline contains, and of the one that contains the outline, m: most
    /// points are decided by these two without visiting the edges.
    pub(super) centre: glam::DVec2,
    pub(super) inner: f64,
    pub(super) outer: f64,
    /// The corners' pseudo-angles about `centre` ([`pseudo_angle`]), increasing
    /// (unwrapped by 4 a turn): the edge a ray from the centre leaves through is found by
    /// bisection.
    pub(super) angles: Vec<f64>,
}

impl Lid {
    /// Does the ray from `p` along unit `d` leave through the lid (within `tol`, m)? `p`
    /// must lie on the hull's side of the lid's plane.
    pub fn passes(&self, p: glam::DVec3, d: glam::DVec3, tol: f64) -> bool {
        self.along(d).is_some_and(|view| view.passes(p, tol))
    }

    /// The edge (index of its first corner) that the ray from the centre through `q`
    /// (outline coordinates) leaves the outline by.
    pub(super) fn sector(&self, q: glam::DVec2) -> usize {
        let mut phi = pseudo_angle(q - self.centre);
        let start = self.angles[0];
        while phi < start {
            phi += TURN;
        }
        while phi >= start + TURN {
            phi -= TURN;
        }
        self.angles.partition_point(|&a| a <= phi).saturating_sub(1)
    }

    /// When the points `poly` (outline coordinates) lie within a wedge about the centre of
    /// less than half a turn: the sectors ([`Lid::sector`]) of its first and last corner
    /// counter-clockwise. `None` when they spread wider, or a point is at the centre.
    fn wedge(&self, poly: &[glam::DVec2]) -> Option<(usize, usize)> {
        let at = |q: glam::DVec2| {
            let r = q - self.centre;
            (r.length_squared() > 1e-24 * self.outer * self.outer).then(|| pseudo_angle(r))
        };
        let a0 = at(*poly.first()?)?;
        let (mut lo, mut hi) = ((0.0, 0), (0.0, 0));
        for (i, q) in poly.iter().enumerate().skip(1) {
            // angle from the first point, within half a turn either way
            let mut t = at(*q)? - a0;
            if t > 0.5 * TURN {
                t -= TURN;
            } else if t <= -0.5 * TURN {
                t += TURN;
            }
            if t < lo.0 {
                lo = (t, i);
            }
            if t > hi.0 {
                hi = (t, i);
            }
        }
        // a margin below half a turn: the wrap above must not be in doubt
        if hi.0 - lo.0 >= 0.45 * TURN {
            return None;
        }
        Some((self.sector(poly[lo.1]), self.sector(poly[hi.1])))
    }

    /// Edge `i` (< the number of corners): its first and second corner.
    pub(super) fn edge(&self, i: usize) -> (glam::DVec2, glam::DVec2) {
        let next = if i + 1 == self.outline.len() {
            0
        } else {
            i + 1
        };
        (self.outline[i], self.outline[next])
    }

    /// Where the ray from `p` along unit `d` meets the lid's plane, in the outline's
    /// coordinates (m); `d` must not be parallel to the plane.
    pub fn meet(&self, p: glam::DVec3, d: glam::DVec3) -> glam::DVec2 {
        let hit = p + d * (self.normal.dot(self.origin - p) / d.dot(self.normal)) - self.origin;
        glam::DVec2::new(hit.dot(self.u), hit.dot(self.w))
    }

    /// The point of the lid's plane at outline coordinates `q`, m.
    pub fn at(&self, q: glam::DVec2) -> glam::DVec3 {
        self.origin + self.u * q.x + self.w * q.y
    }

    /// Clips the convex polygon `poly` (outline coordinates) to the outline; `scratch` is
    /// a buffer. Only edges that some corner lies outside of cut, so a small polygon near
    /// the rim costs one pass over the edges and a cut or two.
    pub fn clip(
        &self,
        poly: &mut Vec<glam::DVec2>,
        edges: &mut Vec<usize>,
        scratch: &mut Vec<glam::DVec2>,
    ) {
        // The edges that some corner lies outside of: for a corner outside the outline,
        // a run of edges about the one its ray from the centre leaves by. Cutting by
        // those alone is exact: the polygon lies inside every other edge already.
        let n = self.outline.len();
        let outside = |i: usize, q: glam::DVec2| {
            let (a, b) = self.edge(i);
            (b - a).perp_dot(q - a) < 0.0
        };
        edges.clear();
        if let Some((first, last)) = self.wedge(poly) {
            // The polygon lies in a wedge about the centre of less than half a turn, where
            // the outline is bounded by the edges from the sector of its first corner to
            // that of its last: only those can cut it (a small face near the rim meets one
            // or two, where a corner far outside lies outside of many edges).
            let mut i = first;
            loop {
                if poly.iter().any(|&q| outside(i, q)) {
                    edges.push(i);
                }
                if i == last {
                    break;
                }
                i = if i + 1 == n { 0 } else { i + 1 };
            }
        } else {
            for &q in poly.iter() {
                if q.distance(self.centre) <= self.inner {
                    continue;
                }
                let j = self.sector(q);
                if !outside(j, q) {
                    continue;
                }
                edges.push(j);
                for step in 1..n {
                    let i = if j + step >= n {
                        j + step - n
                    } else {
                        j + step
                    };
                    if !outside(i, q) {
                        break;
                    }
                    edges.push(i);
                }
                for step in 1..n {
                    let i = if j >= step { j - step } else { j + n - step };
                    if !outside(i, q) {
                        break;
                    }
                    edges.push(i);
                }
            }
        }
        edges.sort_unstable();
        edges.dedup();
        for &i in edges.iter() {
            let (a, b) = self.edge(i);
            let e = b - a;
            let side = |q: glam::DVec2| e.perp_dot(q - a);
            scratch.clear();
            for j in 0..poly.len() {
                let (p, q) = (poly[j], poly[(j + 1) % poly.len()]);
                let (sp, sq) = (side(p), side(q));
                if sp >= 0.0 {
                    scratch.push(p);
                }
                if (sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0) {
                    scratch.push(p + (q - p) * (sp / (sp - sq)));
                }
            }
            std::mem::swap(poly, scratch);
            if poly.len() < 3 {
                poly.clear();
                return;
            }
        }
    }

    /// [`LidView::classify`] along unit `d`.
    pub fn classify(&self, c: glam::DVec3, r: f64, d: glam::DVec3, tol: f64) -> Option<bool> {
        match self.along(d) {
            None => Some(false),
            Some(view) => view.classify(c, r, tol),
        }
    }
}

/// The lid of a cap whose open edges (directed, welded ids) lie in the plane of unit
/// normal `n`: `None` unless they chain into one convex loop. `inside` points from the
/// plane into the hull.
pub(super) fn lid_of(
    open: &[(u32, u32)],
    mesh: &Mesh,
    inside: glam::DVec3,
    n: glam::DVec3,
    tol: f64,
) -> Option<Lid> {
    let mut next: Vec<(u32, u32)> = open.to_vec();
    next.sort_unstable();
    if next.windows(2).any(|w| w[0].0 == w[1].0) {
        return None; // the boundary passes a vertex twice
    }
    let mut ring = vec![next[0].0];
    loop {
        let last = *ring.last().expect("not empty");
        let k = next.binary_search_by_key(&last, |e| e.0).ok()?;
        if next[k].1 == ring[0] {
            break;
        }
        ring.push(next[k].1);
        if ring.len() > next.len() {
            return None;
        }
    }
    if ring.len() != next.len() {
        return None; // more than one loop
    }
    let normal = if n.dot(inside) > 0.0 { -n } else { n };
    let (u, w) = crate::geometry::orthonormal_basis(normal);
    let corners: Vec<glam::DVec3> = ring.iter().map(|&v| mesh.vertices[v as usize]).collect();
    let origin = corners[0];
    let mut outline: Vec<glam::DVec2> = corners
        .iter()
        .map(|c| glam::DVec2::new((*c - origin).dot(u), (*c - origin).dot(w)))
        .collect();
    if crate::geometry::polygon::twice_signed_area(&outline) < 0.0 {
        outline.reverse();
    }
    // convex: no corner turns clockwise by more than `tol`, and the turns add up to one
    // full turn (a star polygon turns one way everywhere but winds more than once)
    let m = outline.len();
    let mut turning = 0.0;
    let convex = (0..m).all(|i| {
        let (a, b, c) = (outline[i], outline[(i + 1) % m], outline[(i + 2) % m]);
        let (e1, e2) = (b - a, c - b);
        turning += e1.perp_dot(e2).atan2(e1.dot(e2));
        e1.perp_dot(e2) >= -tol * e1.length().max(e2.length())
    });
    if !(convex && (turning - std::f64::consts::TAU).abs() < 1e-6) {
        return None;
    }
    Some(Lid::new(corners, normal, (u, w, origin), outline))
}

impl Lid {
    /// A lid from its corners (m), outward unit normal, in-plane axes and origin, and its
    /// outline (counter-clockwise, convex, in those axes): the circles and angles about
    /// the corners' mean that [`Lid::passes`] and [`Lid::clip`] decide by.
    fn new(
        corners: Vec<glam::DVec3>,
        normal: glam::DVec3,
        (u, w, origin): (glam::DVec3, glam::DVec3, glam::DVec3),
        outline: Vec<glam::DVec2>,
    ) -> Lid {
        let m = outline.len();
        let centre = outline.iter().sum::<glam::DVec2>() / m as f64;
        let inner = (0..m)
            .map(|i| {
                let (a, b) = (outline[i], outline[(i + 1) % m]);
                (b - a).perp_dot(centre - a) / (b - a).length().max(f64::MIN_POSITIVE)
            })
            .fold(f64::INFINITY, f64::min);
        let outer = outline
            .iter()
            .map(|p| p.distance(centre))
            .fold(0.0, f64::max);
        let mut angles: Vec<f64> = outline.iter().map(|p| pseudo_angle(*p - centre)).collect();
        for i in 1..angles.len() {
            while angles[i] < angles[i - 1] {
                angles[i] += TURN;
            }
        }
        Lid {
            corners,
            normal,
            u,
            w,
            origin,
            outline,
            centre,
            angles,
            // shrunk by a hair for rounding: a point this close is decided edge by edge
            inner: inner * (1.0 - 1e-9),
            outer,
        }
    }
}

/// A full turn in [`pseudo_angle`]'s units.
const TURN: f64 = 4.0;

/// A number in [0, 4) that increases with the angle of `r` from the x axis
/// (counter-clockwise) as atan2 does, one unit per quadrant: ordering by it is ordering by
/// angle, for a division instead of an arctangent. 0 for the zero vector.
fn pseudo_angle(r: glam::DVec2) -> f64 {
    let (x, y) = (r.x, r.y);
    let quarter = |a: f64, b: f64| if a + b > 0.0 { b / (a + b) } else { 0.0 };
    if y >= 0.0 {
        if x >= 0.0 {
            quarter(x, y)
        } else {
            1.0 + quarter(y, -x)
        }
    } else if x < 0.0 {
        2.0 + quarter(-x, -y)
    } else {
        3.0 + quarter(-y, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::builtin;
    use crate::geometry::convex::convex_parts;
    use crate::geometry::faces::Faces;

    /// The box-wing dish's lid, with a 7-gon squeezed off-centre for a lid whose inner
    /// and outer circles are far apart.
    fn lids() -> Vec<Lid> {
        let mesh = builtin::box_wing();
        let faces = Faces::build(&mesh, true);
        let parts = convex_parts(&mesh, &faces, 1e-9);
        let dish = parts
            .into_iter()
            .find(|p| p.lid.is_some())
            .expect("the dish");
        let mut lids = vec![dish.lid.expect("lid")];
        let base = &lids[0];
        let outline: Vec<glam::DVec2> = (0..7)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 7.0;
                glam::DVec2::new(0.9 * a.cos() + 0.2, 0.4 * a.sin() - 0.1)
            })
            .collect();
        let corners = outline.iter().map(|q| base.at(*q)).collect();
        let odd = Lid::new(corners, base.normal, (base.u, base.w, base.origin), outline);
        lids.push(odd);
        lids
    }

    /// Inside the outline, by every edge (the definition the lid's shortcuts must match).
    fn inside(lid: &Lid, q: glam::DVec2) -> bool {
        (0..lid.outline.len()).all(|i| {
            let (a, b) = lid.edge(i);
            (b - a).perp_dot(q - a) >= 0.0
        })
    }

    #[test]
    fn pseudo_angle_orders_as_the_angle_does() {
        // against atan2 over random vectors and the axes (where quadrants meet): exact
        // comparisons, since sectors are found by bisection on these keys
        let mut rnd = crate::test_rng(5);
        let angle = |r: glam::DVec2| r.y.atan2(r.x).rem_euclid(std::f64::consts::TAU);
        let mut v: Vec<glam::DVec2> = (0..2000)
            .map(|_| glam::DVec2::new(2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0))
            .collect();
        v.extend(
            [
                (1.0, 0.0),
                (0.0, 1.0),
                (-1.0, 0.0),
                (0.0, -1.0),
                (1.0, -1e-12),
            ]
            .map(|(x, y)| glam::DVec2::new(x, y)),
        );
        v.sort_by(|a, b| angle(*a).total_cmp(&angle(*b)));
        for w in v.windows(2) {
            assert!(
                pseudo_angle(w[0]) <= pseudo_angle(w[1]),
                "{} {}",
                w[0],
                w[1]
            );
            assert!((0.0..TURN).contains(&pseudo_angle(w[0])));
        }
        assert_eq!(pseudo_angle(glam::DVec2::new(0.0, 1.0)), 1.0);
        assert_eq!(pseudo_angle(glam::DVec2::new(-1.0, 0.0)), 2.0);
    }

    #[test]
    fn lid_shortcuts_agree_with_testing_every_edge() {
        // `passes` (one edge found by angle), `classify` (a ball at once) and `clip` (only
        // the edges some corner is outside of) against plain tests over all edges, for
        // random points, balls and triangles about the rim.
        let mut rnd = crate::test_rng(21);
        for lid in lids() {
            let below = lid.origin - lid.normal * 0.1;
            let (mut inside_n, mut outside_n, mut decided) = (0, 0, 0);
            let (mut wedged, mut wide) = (0, 0);
            for _ in 0..4000 {
                let d = (lid.normal * (0.2 + rnd())
                    + lid.u * (2.0 * rnd() - 1.0)
                    + lid.w * (2.0 * rnd() - 1.0))
                    .normalize();
                let p = below + lid.u * (2.0 * rnd() - 1.0) + lid.w * (2.0 * rnd() - 1.0);
                let q = lid.meet(p, d);
                let want = inside(&lid, q);
                assert_eq!(lid.passes(p, d, 0.0), want, "point {p} along {d}");
                if want {
                    inside_n += 1
                } else {
                    outside_n += 1
                }
                // a ball: its verdict must hold at its centre and at points on its surface
                let r = 0.2 * rnd();
                if let Some(all) = lid.classify(p, r, d, 0.0) {
                    decided += 1;
                    for _ in 0..20 {
                        let e = glam::DVec3::new(
                            2.0 * rnd() - 1.0,
                            2.0 * rnd() - 1.0,
                            2.0 * rnd() - 1.0,
                        );
                        let x = p + e.normalize_or_zero() * r;
                        assert_eq!(
                            inside(&lid, lid.meet(x, d)),
                            all,
                            "ball {p} r {r} along {d}"
                        );
                    }
                }
                // a triangle about q, clipped: its area against the plain clip by all edges
                // (now and then a large one, wider than a wedge of half a turn)
                let size = if rnd() < 0.25 { 3.0 } else { 0.6 };
                let tri: Vec<glam::DVec2> = (0..3)
                    .map(|_| q + glam::DVec2::new(rnd() - 0.5, rnd() - 0.5) * size)
                    .collect();
                if lid.wedge(&tri).is_some() {
                    wedged += 1;
                } else {
                    wide += 1;
                }
                let (mut poly, mut edges, mut scratch) = (tri.clone(), Vec::new(), Vec::new());
                lid.clip(&mut poly, &mut edges, &mut scratch);
                let mut region = crate::geometry::polygon::Region::default();
                region.reset(2.0);
                region.add_convex(&tri);
                region.intersect_convex(&lid.outline);
                let got = crate::geometry::polygon::twice_signed_area(&poly).abs() / 2.0;
                assert!(
                    (got - region.area()).abs() < 1e-12,
                    "{got} vs {}",
                    region.area()
                );
            }
            assert!(
                inside_n > 500 && outside_n > 500 && decided > 1000,
                "{inside_n} {outside_n} {decided}"
            );
            assert!(wedged > 1000 && wide > 200, "{wedged} {wide}");
        }
    }
}
