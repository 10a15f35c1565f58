//! A lid seen along one direction ([`LidView`]): where a ray along that direction meets
//! the lid's plane is an affine map of its starting point, so testing many points (a
//! face's samples, a ball's centre) costs two dot products each and a lookup.

use super::lid::Lid;

/// What the ray from a point does at the lid ([`LidView::test`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LidPoint {
    /// It leaves through the lid (within the tolerance).
    Passes,
    /// It misses, beyond the line of the outline's edge with this index.
    Beyond(u32),
    /// It misses, beyond the circle about the outline.
    Far,
    /// It passes, but only within the tolerance of the outline's boundary.
    OnEdge,
}

/// A [`Lid`] seen along one direction d (pointing out through its plane): where a ray
/// along d from a point meets the plane is an affine map of the point, two dot products.
#[derive(Debug, Clone, Copy)]
pub struct LidView<'a> {
    lid: &'a Lid,
    /// Rows of the map to outline coordinates, and its offset.
    x: glam::DVec3,
    y: glam::DVec3,
    offset: glam::DVec2,
    /// d·normal, > 0.
    dn: f64,
}

impl Lid {
    /// The lid seen along unit `d`, for testing many points along one direction; `None`
    /// when d does not point out through the lid's plane (no ray leaves through it).
    pub fn along(&self, d: glam::DVec3) -> Option<LidView<'_>> {
        let dn = d.dot(self.normal);
        if dn <= 0.0 {
            return None;
        }
        // meet(p) = u·(p − o) + (u·d)·(n·(o − p))/dn = (u − n·(u·d)/dn)·(p − o), and as
        // much for w: an affine map of p
        let x = self.u - self.normal * (self.u.dot(d) / dn);
        let y = self.w - self.normal * (self.w.dot(d) / dn);
        Some(LidView {
            lid: self,
            x,
            y,
            offset: -glam::DVec2::new(x.dot(self.origin), y.dot(self.origin)),
            dn,
        })
    }
}

impl LidView<'_> {
    /// Where the ray from `p` meets the lid's plane, in outline coordinates (m).
    #[inline]
    pub fn meet(&self, p: glam::DVec3) -> glam::DVec2 {
        glam::DVec2::new(self.x.dot(p), self.y.dot(p)) + self.offset
    }

    /// Does the ray from `p` leave through the lid (within `tol`, m)? `p` must lie on the
    /// hull's side of the lid's plane.
    pub fn passes(&self, p: glam::DVec3, tol: f64) -> bool {
        matches!(
            self.test(self.meet(p), tol),
            LidPoint::Passes | LidPoint::OnEdge
        )
    }

    /// The edge (index) that the ray from the outline's centre through `q` leaves by, how
    /// far inside its line `q` lies (twice the area it spans with the edge, m², negative
    /// outside), and the tolerance `tol` (m) as a margin in those units.
    #[inline]
    fn edge_side(&self, q: glam::DVec2, tol: f64) -> (usize, f64, f64) {
        let j = self.lid.sector(q);
        let (a, b) = self.lid.edge(j);
        let e = b - a;
        (j, e.perp_dot(q - a), tol * e.length())
    }

    /// [`LidView::passes`] for the point whose ray meets the lid's plane at `q` (outline
    /// coordinates, [`LidView::meet`]), told apart: for a point that does not pass, the
    /// outline's edge whose line it lies beyond by more than `tol` (m), when it does; for
    /// one that passes only by the tolerance, that it lies on the outline (a rim vertex of
    /// the cap itself). Points all on or beyond one line that the lid lies behind span no
    /// area that passes.
    pub fn test(&self, q: glam::DVec2, tol: f64) -> LidPoint {
        let lid = self.lid;
        let r = q.distance(lid.centre);
        if r <= lid.inner {
            return LidPoint::Passes;
        }
        if r > lid.outer + tol {
            // outside: which edge's line it lies beyond is found when asked
            return LidPoint::Far;
        }
        // inside exactly when inside the edge that the ray from the centre through q
        // leaves by (the outline is convex about the centre)
        let (j, side, margin) = self.edge_side(q, tol);
        if side < -margin {
            LidPoint::Beyond(j as u32)
        } else if side <= margin {
            LidPoint::OnEdge
        } else {
            LidPoint::Passes
        }
    }

    /// For a point [`LidView::test`] found [`LidPoint::Far`] (meeting the plane at `q`):
    /// the edge whose line it lies beyond by more than `tol` (m), `None` when not by that
    /// much.
    pub fn beyond(&self, q: glam::DVec2, tol: f64) -> Option<u32> {
        let (j, side, margin) = self.edge_side(q, tol);
        (side < -margin).then_some(j as u32)
    }

    /// A line the lid lies behind, as its unit outward normal and a point on it (outline
    /// coordinates, m): that of the outline's edge `j`, or with `corner`, the line through
    /// the corner after edge `j` square to the mean of its two edges' normals.
    pub fn support(&self, j: u32, corner: bool) -> (glam::DVec2, glam::DVec2) {
        let lid = self.lid;
        let outward = |i: usize| {
            let (a, b) = lid.edge(i);
            let e = (b - a).normalize();
            (glam::DVec2::new(e.y, -e.x), a, b)
        };
        let (n, a, b) = outward(j as usize);
        if corner {
            let (m, _, _) = outward((j as usize + 1) % lid.outline.len());
            ((n + m).normalize(), b)
        } else {
            (n, a)
        }
    }

    /// The outline's number of edges.
    pub fn edges(&self) -> u32 {
        self.lid.outline.len() as u32
    }

    /// [`LidView::passes`] for every point of the ball about `c` of radius `r` (m) at
    /// once: `Some(true)` when every ray from it leaves through the lid, `Some(false)`
    /// when none does, `None` when the ball is not decided as a whole. The rays from the
    /// ball meet the lid's plane within r/cos of the centre's ray, cos = d·normal.
    pub fn classify(&self, c: glam::DVec3, r: f64, tol: f64) -> Option<bool> {
        let reach = r / self.dn;
        if !reach.is_finite() {
            return None;
        }
        let rq = self.meet(c).distance(self.lid.centre);
        if rq + reach <= self.lid.inner {
            Some(true)
        } else if rq - reach > self.lid.outer + tol {
            Some(false)
        } else {
            None
        }
    }
}
