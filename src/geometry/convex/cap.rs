//! The cap proof: a cap open on one flat side (a dish) shown convex from its edges alone,
//! in linear time, where testing every vertex against every face's plane costs a tree
//! query per face. Used by [`super::parts`] for parts with a [`Lid`].

use super::lid::Lid;
use crate::geometry::faces::Faces;
use crate::geometry::mesh::Mesh;

/// A cap's triangles and edges, for proving it convex from its edges alone.
pub(super) struct Cap<'a> {
    pub(super) mesh: &'a Mesh,
    /// Per mesh vertex: its welded id.
    pub(super) welded: &'a [u32],
    pub(super) faces: &'a Faces,
    /// The cap's faces.
    pub(super) part: &'a [u32],
    /// The cap's welded vertex ids, sorted, and their positions (m).
    pub(super) ids: &'a [u32],
    pub(super) vertices: &'a [glam::DVec3],
    /// Its open edges (welded ids) and inner edges (the two triangles sharing each).
    pub(super) open: &'a [(u32, u32)],
    pub(super) inner: &'a [(u32, u32)],
}

/// Least cosine between a cap's triangles and its lid's axis for the local proof: a
/// triangle closer to edge-on projects too thin for the error bound to be useful.
const MIN_CAP_COS: f64 = 1e-6;

impl Cap<'_> {
    /// Per face, whether the cap lies ahead of it (its vertices all on that side of the
    /// face's plane, within `tol`, m), proven from the cap's edges; `None` when the proof
    /// does not apply (the caller then tests every face against the vertices).
    ///
    /// Linear time, where a tree query per face costs a pass near its plane: the cap is a
    /// disk (V − E + F = 1, one boundary loop: the lid's, convex and simple); every
    /// triangle projects onto the lid's plane with one orientation, and the projected
    /// angles about each inner vertex add up to one turn, so the projection is a local
    /// homeomorphism that takes the boundary once round the lid: by the degree argument it
    /// is one-to-one, and the cap is the graph of a piecewise-linear function over a
    /// convex polygon. Every inner edge bends one way, so that function is convex (or
    /// concave) and every triangle's plane supports it. Kinks the wrong way (rounding, or
    /// faces merged within the merge tolerance) are allowed while the bound they put on
    /// any vertex's distance beyond a face's plane stays within `tol`.
    pub(super) fn sides(&self, lid: &Lid, tol: f64) -> Option<Vec<bool>> {
        let triangles: Vec<u32> = self
            .part
            .iter()
            .flat_map(|&f| self.faces.faces[f as usize].triangles.iter().copied())
            .collect();
        if self.vertices.len() + triangles.len() != self.inner.len() + self.open.len() + 1 {
            return None; // not a disk (V − E + F = 1)
        }
        let local = self.local_ids();
        self.projects_once_round(lid, &triangles, &local)?;
        let (ahead, turns) = self.bends_one_way(lid, &local, tol)?;
        let (_, radius) = crate::geometry::mesh::bounding_sphere(self.vertices);
        self.face_sides(ahead, 2.0 * radius * turns, radius, &local, tol)
    }

    /// Per mesh vertex: the index of its welded id among the cap's (`u32::MAX` for
    /// vertices not in the cap).
    fn local_ids(&self) -> Vec<u32> {
        let mut local = vec![u32::MAX; self.mesh.vertices.len()];
        for (i, &v) in self.ids.iter().enumerate() {
            local[v as usize] = i as u32;
        }
        local
    }

    /// Triangle `t`'s corners as indices into the cap's vertices.
    fn corners(&self, t: u32, local: &[u32]) -> [usize; 3] {
        self.mesh.triangles[t as usize].map(|v| local[self.welded[v as usize] as usize] as usize)
    }

    /// That every triangle projects onto the lid's plane with one orientation, and the
    /// projected angles about each inner vertex add up to one turn (once round, not
    /// twice); `None` when either fails.
    fn projects_once_round(&self, lid: &Lid, triangles: &[u32], local: &[u32]) -> Option<()> {
        let (vertices, n) = (self.vertices, self.vertices.len());
        let flat = |p: glam::DVec3| glam::DVec2::new(p.dot(lid.u), p.dot(lid.w));
        let mut sign = 0.0;
        let mut turn = vec![0.0; n];
        for &t in triangles {
            let c = self.corners(t, local);
            let p = c.map(|i| vertices[i]);
            let area = (p[1] - p[0]).cross(p[2] - p[0]);
            let cos = area.dot(lid.normal) / area.length();
            // (a NaN cosine, of a degenerate triangle, fails too)
            if cos.abs().is_nan()
                || cos.abs() < MIN_CAP_COS
                || (sign != 0.0 && cos.signum() != sign)
            {
                return None;
            }
            sign = cos.signum();
            let q = p.map(flat);
            for k in 0..3 {
                let (e1, e2) = (q[(k + 1) % 3] - q[k], q[(k + 2) % 3] - q[k]);
                turn[c[k]] += (sign * e1.perp_dot(e2)).atan2(e1.dot(e2));
            }
        }
        let mut rim = vec![false; n];
        for &(a, b) in self.open {
            rim[local[a as usize] as usize] = true;
            rim[local[b as usize] as usize] = true;
        }
        // the angle sums are whole turns: once round, not twice
        let once_round = |t: f64| (t - std::f64::consts::TAU).abs() <= 0.5;
        if (0..n).any(|i| !rim[i] && !once_round(turn[i])) {
            return None;
        }
        Some(())
    }

    /// That every inner edge bends one way (within `tol`'s slack): whether the cap lies
    /// ahead of its triangles, and Σ h/(cos·d) of the kinks the other way.
    ///
    /// A kink the wrong way (by rounding, on a face merged from triangles) of normal
    /// height h, over a far corner at projected distance d from the edge, turns the
    /// function's slope by h/(cos·d); a straight path over the projection crosses each
    /// edge at most once, so over the cap's width 2r the kinks misplace a vertex by at
    /// most 2r·Σ h/(cos·d) against any triangle's plane.
    fn bends_one_way(&self, lid: &Lid, local: &[u32], tol: f64) -> Option<(bool, f64)> {
        let vertices = self.vertices;
        let flat = |p: glam::DVec3| glam::DVec2::new(p.dot(lid.u), p.dot(lid.w));
        let (mut ahead_sum, mut behind_sum) = (0.0, 0.0);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &(s, t) in self.inner {
            let (a, b) = (self.corners(s, local), self.corners(t, local));
            let far = |x: &[usize; 3], y: &[usize; 3]| {
                let mut far = x.iter().filter(|v| !y.contains(v));
                match (far.next(), far.next()) {
                    (Some(&v), None) => Some(v),
                    _ => None,
                }
            };
            let (fa, fb) = (far(&a, &b)?, far(&b, &a)?);
            // b's far corner against a's plane
            let p = a.map(|i| vertices[i]);
            let area = (p[1] - p[0]).cross(p[2] - p[0]);
            let normal = area / area.length();
            let h = normal.dot(vertices[fb] - p[0]);
            let cos = normal.dot(lid.normal).abs();
            let edge: Vec<glam::DVec2> = a
                .iter()
                .filter(|&&v| v != fa)
                .map(|&v| flat(vertices[v]))
                .collect();
            let along = edge[1] - edge[0];
            let d = along.perp_dot(flat(vertices[fb]) - edge[0]).abs() / along.length();
            lo = lo.min(h);
            hi = hi.max(h);
            let turn = h.abs() / (cos * d);
            if h > 0.0 {
                behind_sum += turn; // a wrong-way kink if the hull lies behind
            } else {
                ahead_sum += turn;
            }
        }
        let slack = 1e-4 * tol;
        if hi <= slack {
            Some((false, behind_sum))
        } else if lo >= -slack {
            Some((true, ahead_sum))
        } else {
            None
        }
    }

    /// Every face's side (`ahead`) once its plane is shown close enough to its first
    /// triangle's: every vertex within `bound` (m) of a triangle's plane on the hull's side
    /// is within `bound` + 2·`radius`·tilt + the triangle's own offset of the face's;
    /// `None` when that passes `tol` (a kinked merged face: left to the tree).
    fn face_sides(
        &self,
        ahead: bool,
        bound: f64,
        radius: f64,
        local: &[u32],
        tol: f64,
    ) -> Option<Vec<bool>> {
        let mut sides = Vec::with_capacity(self.part.len());
        for &f in self.part {
            let face = &self.faces.faces[f as usize];
            let p = self
                .corners(face.triangles[0], local)
                .map(|i| self.vertices[i]);
            let area = (p[1] - p[0]).cross(p[2] - p[0]);
            let tilt = (face.normal - area / area.length()).length();
            let off = p
                .iter()
                .map(|q| face.normal.dot(*q - face.centroid).abs())
                .fold(0.0, f64::max);
            let beyond = bound + 2.0 * radius * tilt + off;
            if beyond.is_nan() || beyond > tol {
                return None;
            }
            sides.push(ahead);
        }
        Some(sides)
    }
}

#[cfg(test)]
mod tests {
    use super::super::parts::parts_of;
    use crate::geometry::builtin;
    use crate::geometry::faces::Faces;
    use crate::geometry::mesh::Mesh;

    /// A part as its faces, their sides and its lid's corner count.
    type PartSummary = (Vec<u32>, Vec<bool>, usize);

    /// The parts, and which were proven from their edges.
    fn summary(mesh: &Mesh, by_edges: bool) -> (Vec<PartSummary>, Vec<bool>) {
        let faces = Faces::build(mesh, true);
        let (_, scale) = mesh.bounding_sphere();
        parts_of(mesh, &faces, 1e-9 * scale, by_edges)
            .into_iter()
            .map(|(p, proven)| {
                let corners = p.lid.as_ref().map_or(0, |l| l.corners.len());
                ((p.faces, p.hull_ahead, corners), proven)
            })
            .unzip()
    }

    #[test]
    fn a_caps_edges_prove_what_testing_its_vertices_says() {
        // the box-wing's dishes, coarse and fine (the fine one's quads are faces of two
        // triangles, flat to rounding: kinks the wrong way within rounding)
        for mesh in [builtin::box_wing(), builtin::box_wing_with(48, 128, 3)] {
            let (by_edges, proven) = summary(&mesh, true);
            let (by_vertices, _) = summary(&mesh, false);
            assert_eq!(by_edges, by_vertices);
            // the dish is proven from its edges; the closed boxes are not caps
            let caps: Vec<bool> = by_edges.iter().map(|(_, _, c)| *c > 0).collect();
            assert_eq!(proven, caps);
            assert_eq!(caps.iter().filter(|&&c| c).count(), 1);
        }
    }

    #[test]
    fn a_dent_in_a_cap_is_found_from_its_edges_as_from_its_vertices() {
        // Push one inner dish vertex out of the dish's hull (against its concave side)
        // by multiples of the tolerance: beyond it the dish is no convex part; well
        // within it, still one (vertex by vertex), though no longer proven from edges
        // that now bend the wrong way by more than rounding.
        let plain = builtin::box_wing_with(16, 48, 0);
        let (_, scale) = plain.bounding_sphere();
        let tol = 1e-9 * scale;
        // the dish's vertices follow everything else: centre, then 48 per ring
        let dish_start = plain.vertices.len() - (1 + 16 * 48);
        for (ring, dents) in [(3, 1e3), (8, 10.0), (5, 0.1)] {
            let mut mesh = plain.clone();
            let v = dish_start + 1 + (ring - 1) * 48 + 7;
            mesh.vertices[v].z -= dents * tol;
            let (by_edges, proven) = summary(&mesh, true);
            let (by_vertices, _) = summary(&mesh, false);
            assert_eq!(by_edges, by_vertices, "dent of {dents} tol");
            let dish_kept = by_edges.iter().any(|(_, _, c)| *c > 0);
            assert_eq!(dish_kept, dents < 1.0, "dent of {dents} tol");
            assert!(proven.iter().all(|p| !p), "dent of {dents} tol");
        }
    }
}
