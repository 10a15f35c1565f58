//! The faces as convex polygons, each in its own plane: built once per request.
//!
//! A face is one polygon (its outline) when it is convex, however finely it is meshed,
//! else its triangles. The corners are kept both in the body frame (m) and in the face's
//! own plane coordinates (its basis (u, w) from a point of it), where a face is cut
//! along the lines of the shadows that cross it and a ray's hit is tested.

use super::polygon_tree::FaceTrees;
use crate::geometry::articulation::Motion;
use crate::geometry::{Faces, Mesh};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// The faces' planes and their polygons.
#[derive(Clone)]
pub struct Polygons {
    /// Per face: unit normal, a point of its plane, an orthonormal basis (u, w) of the
    /// plane with u × w = n, two-sidedness, convexity (one polygon), and a point inside
    /// it (its first triangle's centroid, m).
    pub normal: Vec<DVec3>,
    pub point: Vec<DVec3>,
    pub basis: Vec<(DVec3, DVec3)>,
    pub two_sided: Vec<bool>,
    pub convex: Vec<bool>,
    pub inside: Vec<DVec3>,
    /// Per face: its centroid and the radius of a sphere about it holding the face (m).
    pub centre: Vec<DVec3>,
    pub radius: Vec<f64>,
    /// Per face: its range of polygons.
    pub of_face: Vec<(u32, u32)>,
    /// Per polygon: its face and its range of corners.
    pub face: Vec<u32>,
    pub spans: Vec<(u32, u32)>,
    /// The corners, in the body frame (m) and in their face's plane coordinates (m).
    pub corners: Vec<DVec3>,
    pub corners2: Vec<DVec2>,
    /// The faces of many polygons as trees of boxes in their planes (unchanged when a
    /// face moves: its plane's coordinates move with it).
    pub trees: FaceTrees,
}

impl Polygons {
    /// The faces of `faces` as polygons; `eps` (m): how far a corner may lie from where
    /// it should for rounding alone (a face whose outline's hull exceeds it by no more
    /// than a strip that wide along the hull is convex).
    pub fn build(mesh: &Mesh, faces: &Faces, two_sided: Vec<bool>, eps: f64) -> Polygons {
        // Runs of faces built side by side, then joined in order: a few large faces (a
        // cubesat's ten sides of 20k triangles each) no longer take one thread while the
        // other waits (docs/performance.md, twenty-fourth sitting).
        let nf = faces.len();
        let run = (nf / 16).clamp(1, 4096);
        let parts: Vec<Polygons> = faces
            .faces
            .par_chunks(run)
            .enumerate()
            .map(|(c, run_faces)| Polygons::build_run(mesh, run_faces, c * run, eps))
            .collect();
        let mut p = Polygons {
            two_sided,
            ..Polygons::empty(nf)
        };
        // the joined tables made their full size at once: grown as the runs are
        // appended, each would be copied again at every doubling into memory not yet
        // touched (page faults are most of what appending costs: tens of MB at 200k faces)
        let total = |len: fn(&Polygons) -> usize| parts.iter().map(len).sum::<usize>();
        p.face.reserve_exact(total(|q| q.face.len()));
        p.spans.reserve_exact(total(|q| q.spans.len()));
        p.corners.reserve_exact(total(|q| q.corners.len()));
        p.corners2.reserve_exact(total(|q| q.corners2.len()));
        for part in parts {
            let (spans, corners) = (p.spans.len() as u32, p.corners.len() as u32);
            p.normal.extend(part.normal);
            p.point.extend(part.point);
            p.basis.extend(part.basis);
            p.convex.extend(part.convex);
            p.inside.extend(part.inside);
            p.centre.extend(part.centre);
            p.radius.extend(part.radius);
            p.of_face
                .extend(part.of_face.iter().map(|&(a, b)| (a + spans, b + spans)));
            p.face.extend(part.face);
            p.spans
                .extend(part.spans.iter().map(|&(a, b)| (a + corners, b + corners)));
            p.corners.extend(part.corners);
            p.corners2.extend(part.corners2);
        }
        p.trees = FaceTrees::build(&p.of_face, |k| p.corners2(k));
        p
    }

    /// No faces, with room for `nf`.
    fn empty(nf: usize) -> Polygons {
        Polygons {
            normal: Vec::with_capacity(nf),
            point: Vec::with_capacity(nf),
            basis: Vec::with_capacity(nf),
            two_sided: Vec::new(),
            convex: Vec::with_capacity(nf),
            inside: Vec::with_capacity(nf),
            centre: Vec::with_capacity(nf),
            radius: Vec::with_capacity(nf),
            of_face: Vec::with_capacity(nf),
            face: Vec::new(),
            spans: Vec::new(),
            corners: Vec::new(),
            corners2: Vec::new(),
            trees: FaceTrees::default(),
        }
    }

    /// Faces of at least this many triangles list each of their vertices once for their
    /// hull, not once for every triangle that has it.
    const MANY_TRIANGLES: usize = 64;

    /// The polygons of a run of faces, the first of which is face `first_face` (their
    /// ranges counted from the run's own start; no two-sidedness, no trees).
    fn build_run(
        mesh: &Mesh,
        faces: &[crate::geometry::Face],
        first_face: usize,
        eps: f64,
    ) -> Polygons {
        let mut p = Polygons::empty(faces.len());
        let (mut pts, mut ids, mut order, mut hull) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        // per mesh vertex, the last large face of the run (its place in the run + 1) that
        // listed it; made when the run meets its first large face
        let mut listed: Vec<u32> = Vec::new();
        for (i, f) in faces.iter().enumerate() {
            let i = first_face + i;
            let n = f.normal;
            let (u, w) = basis(n);
            let o = mesh.vertices[mesh.triangles[f.triangles[0] as usize][0] as usize];
            let to2 = |q: DVec3| DVec2::new((q - o).dot(u), (q - o).dot(w));
            let [a, b, c] = mesh.corners(f.triangles[0] as usize);
            p.normal.push(n);
            p.point.push(o);
            p.basis.push((u, w));
            p.inside.push((a + b + c) / 3.0);
            p.centre.push(f.centroid);
            p.radius.push(f.radius);
            let first = p.spans.len() as u32;
            let mut convex = f.triangles.len() == 1;
            if f.triangles.len() > 1 {
                // A hull needs each corner once, and a vertex of a finely meshed face is
                // a corner of about six of its triangles (a cubesat's side of 31k
                // triangles took 3 ms, most of it its 94k corners). Listed in the
                // triangles' order, each at its first, so the hull and the corners it is
                // given are the same.
                pts.clear();
                ids.clear();
                let large = f.triangles.len() >= Polygons::MANY_TRIANGLES;
                if large && listed.is_empty() {
                    listed = vec![0; mesh.vertices.len()];
                }
                let stamp = (i - first_face + 1) as u32;
                for &t in &f.triangles {
                    for v in mesh.triangles[t as usize] {
                        if large {
                            if listed[v as usize] == stamp {
                                continue;
                            }
                            listed[v as usize] = stamp;
                        }
                        pts.push(to2(mesh.vertices[v as usize]));
                        ids.push(mesh.vertices[v as usize]);
                    }
                }
                crate::geometry::polygon::convex_hull(&pts, &mut order, &mut hull);
                let (area, _) = super::cells::area_centroid(&hull);
                // Rounded corners (an OBJ file's nine decimals) leave an outline's
                // hull larger than the face by up to a strip of the rounding's width
                // along it: more than 1e-9 of a finely meshed face's area, which then
                // was not convex, and its rays went unshared (a cluster of boxes cast
                // ~14k a epoch).
                let perimeter: f64 = (0..hull.len())
                    .map(|k| hull[k].distance(hull[(k + 1) % hull.len()]))
                    .sum();
                let slack = (1e-9 * f.area).max(eps * perimeter);
                convex = hull.len() >= 3 && (area - f.area).abs() <= slack;
            }
            if convex && f.triangles.len() > 1 {
                let s = p.corners.len() as u32;
                for h in &hull {
                    let k = pts
                        .iter()
                        .position(|q| q == h)
                        .expect("a hull point is a corner");
                    p.corners.push(ids[k]);
                    p.corners2.push(*h);
                }
                p.spans.push((s, p.corners.len() as u32));
                p.face.push(i as u32);
            } else {
                for &t in &f.triangles {
                    let tri3 = mesh.corners(t as usize);
                    let tri2 = tri3.map(to2);
                    let s = p.corners.len() as u32;
                    // counter-clockwise about the face's normal, whatever the
                    // triangle's own winding (a face welded from a mesh whose
                    // triangles disagree)
                    let order = if orient(tri2[0], tri2[1], tri2[2]) < 0.0 {
                        [0, 2, 1]
                    } else {
                        [0, 1, 2]
                    };
                    p.corners.extend(order.map(|k| tri3[k]));
                    p.corners2.extend(order.map(|k| tri2[k]));
                    p.spans.push((s, p.corners.len() as u32));
                    p.face.push(i as u32);
                }
            }
            p.convex.push(convex);
            p.of_face.push((first, p.spans.len() as u32));
        }
        p
    }

    /// Does segment a–b (in face `f`'s plane, m) come within `tol` (m) of one of the
    /// face's polygons?
    #[inline]
    pub fn segment_meets_face(&self, f: usize, a: DVec2, b: DVec2, tol: f64) -> bool {
        let meets = |k: usize| segment_meets(a, b, self.corners2(k), tol, true);
        match self.trees.root(f) {
            Some(root) => self.trees.segment_meets(root, a, b, tol, meets),
            None => self.of(f).any(meets),
        }
    }

    pub fn faces(&self) -> usize {
        self.normal.len()
    }

    /// The polygons with each face moved rigidly by `motion(face)`: the plane's basis
    /// turns with it, so the corners' plane coordinates stay as they are.
    pub fn moved(&self, motion: impl Fn(usize) -> Motion) -> Polygons {
        let mut p = self.clone();
        for f in 0..self.faces() {
            let m = motion(f);
            p.normal[f] = m.rot * p.normal[f];
            p.point[f] = m.apply(p.point[f]);
            let (u, w) = p.basis[f];
            p.basis[f] = (m.rot * u, m.rot * w);
            p.inside[f] = m.apply(p.inside[f]);
            p.centre[f] = m.apply(p.centre[f]);
            let (a, b) = self.of_face[f];
            let (s, e) = (self.spans[a as usize].0, self.spans[b as usize - 1].1);
            for q in &mut p.corners[s as usize..e as usize] {
                *q = m.apply(*q);
            }
        }
        p
    }

    pub fn len(&self) -> usize {
        self.spans.len()
    }

    /// Polygon `i`'s corners in its face's plane coordinates.
    #[inline]
    pub fn corners2(&self, i: usize) -> &[DVec2] {
        let (a, b) = self.spans[i];
        &self.corners2[a as usize..b as usize]
    }

    /// Polygon `i`'s corners in the body frame.
    #[inline]
    pub fn corners3(&self, i: usize) -> &[DVec3] {
        let (a, b) = self.spans[i];
        &self.corners[a as usize..b as usize]
    }

    /// A body-frame point in face `f`'s plane coordinates.
    #[inline]
    pub fn to2(&self, f: usize, q: DVec3) -> DVec2 {
        let (u, w) = self.basis[f];
        let r = q - self.point[f];
        DVec2::new(r.dot(u), r.dot(w))
    }

    /// Face `f`'s plane coordinates back in the body frame.
    #[inline]
    pub fn to3(&self, f: usize, q: DVec2) -> DVec3 {
        let (u, w) = self.basis[f];
        self.point[f] + u * q.x + w * q.y
    }

    /// The polygons of face `f`.
    #[inline]
    pub fn of(&self, f: usize) -> std::ops::Range<usize> {
        let (a, b) = self.of_face[f];
        a as usize..b as usize
    }
}

/// An orthonormal basis (u, w) of the plane across unit `n` with u × w = n.
pub fn basis(n: DVec3) -> (DVec3, DVec3) {
    let (u, w) = crate::geometry::orthonormal_basis(n);
    if u.cross(w).dot(n) < 0.0 {
        (w, u)
    } else {
        (u, w)
    }
}

/// Twice the signed area of triangle (a, b, c): positive when c is left of a → b.
#[inline]
pub fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Does segment a–b come within `tol` of convex polygon `c` (separating axes)? `ccw`:
/// whether `c` turns counter-clockwise. Knowing the winding, an edge's axis needs only
/// the edge's own corner: the polygon lies wholly on its inner side.
#[inline]
pub fn segment_meets(a: DVec2, b: DVec2, c: &[DVec2], tol: f64, ccw: bool) -> bool {
    let tol2 = tol * tol;
    // across the segment: the polygon wholly on one side, farther than tol
    let e = b - a;
    let len2 = e.length_squared();
    if len2 > 0.0 {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        // plain comparisons: f64::min's care for NaN costs here, and no corner is NaN
        for &q in c {
            let s = e.perp_dot(q - a);
            if s < lo {
                lo = s;
            }
            if s > hi {
                hi = s;
            }
        }
        let gap = lo.max(-hi);
        if gap > 0.0 && gap * gap > tol2 * len2 {
            return false;
        }
    }
    // across each edge: both ends of the segment outside it, farther than tol
    let sign = if ccw { 1.0 } else { -1.0 };
    let mut prev = c[c.len() - 1];
    for &q in c {
        let edge = q - prev;
        // distance inward, times |edge|
        let (sa, sb) = (
            sign * edge.perp_dot(a - prev),
            sign * edge.perp_dot(b - prev),
        );
        let gap = -sa.max(sb);
        if gap > 0.0 && gap * gap > tol2 * edge.length_squared() {
            return false;
        }
        prev = q;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_basis_turns_counter_clockwise_about_the_normal() {
        for n in [
            DVec3::X,
            -DVec3::Y,
            DVec3::new(0.3, -0.4, 0.866).normalize(),
        ] {
            let (u, w) = basis(n);
            assert!((u.cross(w) - n).length() < 1e-12);
        }
    }

    #[test]
    fn a_segment_meets_a_square_of_either_winding_within_the_tolerance() {
        let square = [
            DVec2::ZERO,
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(0.0, 2.0),
        ];
        let mut cw = square;
        cw.reverse();
        let p = DVec2::new;
        for (c, ccw) in [(&square, true), (&cw, false)] {
            // through it, ending inside it, wholly inside it
            assert!(segment_meets(p(-1.0, 1.0), p(3.0, 1.0), c, 0.0, ccw));
            assert!(segment_meets(p(-1.0, 1.0), p(0.5, 1.0), c, 0.0, ccw));
            assert!(segment_meets(p(0.5, 0.5), p(1.5, 1.5), c, 0.0, ccw));
            // past a corner diagonally, 0.5/sqrt(2) = 0.354 m from it: apart beyond 0.3,
            // meeting within 0.4 (only the segment's own axis separates them)
            let (a, b) = (p(2.0, 2.5), p(2.5, 2.0));
            assert!(!segment_meets(a, b, c, 0.3, ccw));
            assert!(segment_meets(a, b, c, 0.4, ccw));
            // beside an edge, 0.5 m off, along it
            let (a, b) = (p(-0.5, -1.0), p(-0.5, 3.0));
            assert!(!segment_meets(a, b, c, 0.4, ccw));
            assert!(segment_meets(a, b, c, 0.6, ccw));
            // a point
            assert!(segment_meets(p(1.0, 1.0), p(1.0, 1.0), c, 0.0, ccw));
            assert!(!segment_meets(p(2.5, 1.0), p(2.5, 1.0), c, 0.4, ccw));
        }
    }

    #[test]
    fn a_finely_meshed_square_written_to_nine_decimals_is_one_convex_polygon_and_an_l_is_not() {
        // a 0.3 m square of 12 × 12 squares, turned off the axes, its corners rounded to
        // nine decimals (an OBJ file's): its outline's hull exceeds the face by a strip
        // of the rounding's width, more than 1e-9 of its area, less than eps along it
        let turn = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
        let round = |x: f64| (x * 1e9).round() / 1e9;
        // quads of 0.025 m squares, from the origin along `size` (m), turned and rounded
        let object = |quads: &[(DVec2, DVec2)]| {
            let mut mesh = Mesh::default();
            for &(at, size) in quads {
                let (nu, nv) = (
                    (size.x / 0.025).round() as u32,
                    (size.y / 0.025).round() as u32,
                );
                let (o, u, v) = (at.extend(0.0), DVec3::X * size.x, DVec3::Y * size.y);
                crate::geometry::builtin::push_grid_quad(&mut mesh, o, u, v, nu, nv, 0);
            }
            for v in &mut mesh.vertices {
                *v = (turn * *v).map(round);
            }
            // and a triangle 3 m off: the mesh's size (what its faces merge and its
            // rounding height are measured against) is an object's, not a panel's
            let b = mesh.vertices.len() as u32;
            for v in [
                DVec3::new(3.0, 0.0, 0.0),
                DVec3::new(3.1, 0.0, 0.0),
                DVec3::new(3.0, 0.0, 0.1),
            ] {
                mesh.vertices.push(turn * v);
            }
            mesh.triangles.push([b, b + 1, b + 2]);
            mesh.material_ids = vec![0; mesh.triangles.len()];
            mesh
        };
        let square = object(&[(DVec2::ZERO, DVec2::splat(0.3))]);
        // eps as the engine takes it: the mesh's tolerance, 1e-9 of its size here
        let eps = square.tolerance();
        let faces = Faces::build(&square, true);
        assert_eq!(faces.len(), 2);
        let polys = Polygons::build(&square, &faces, vec![false; 2], eps);
        assert!(polys.convex[0]);
        assert_eq!(polys.of(0).len(), 1, "one polygon, its outline");
        // without the rounding's slack it would not be (the test's reason to be)
        let (area, hull_area) = (faces.faces[0].area, {
            let k = polys.of(0).start;
            super::super::cells::area_centroid(polys.corners2(k)).0
        });
        assert!((hull_area - area).abs() > 1e-9 * area, "{hull_area} {area}");
        // its corners: vertices of the mesh on the square's outline, the square's four
        // among them (rounding leaves the outline's other vertices a hair off its sides,
        // and some are corners of the hull too), in the plane coordinates beside them,
        // counter-clockwise: the hull of the 169 vertices of 288 triangles, each listed once
        let k = polys.of(0).start;
        let got = polys.corners3(k);
        for (x, y) in [(0.0, 0.0), (0.3, 0.0), (0.3, 0.3), (0.0, 0.3)] {
            let corner = (turn * DVec3::new(x, y, 0.0)).map(round);
            assert!(got.iter().any(|q| q.distance(corner) < 1e-12), "{got:?}");
        }
        for (i, &q) in got.iter().enumerate() {
            assert!(square.vertices.contains(&q));
            let p = turn.inverse() * q;
            let off_sides = [p.x, p.x - 0.3, p.y, p.y - 0.3].map(f64::abs);
            assert!(
                off_sides.into_iter().fold(f64::INFINITY, f64::min) < 1e-8,
                "{p}"
            );
            assert!(polys.to2(0, q).distance(polys.corners2(k)[i]) < 1e-12);
        }
        assert!(hull_area > 0.0);
        // an L (a quarter of the squares left out) keeps its notch: not convex
        let half = DVec2::new(0.15, 0.0);
        let l = object(&[
            (DVec2::ZERO, DVec2::new(0.15, 0.3)),
            (half, DVec2::splat(0.15)),
        ]);
        let faces = Faces::build(&l, true);
        assert_eq!(faces.len(), 2);
        let polys = Polygons::build(&l, &faces, vec![false; 2], eps);
        assert!(!polys.convex[0]);
        assert_eq!(polys.of(0).len(), l.triangles.len() - 1);
        // its triangles, each counter-clockwise about the face's normal
        for k in polys.of(0) {
            let c = polys.corners2(k);
            assert!(orient(c[0], c[1], c[2]) > 0.0, "{c:?}");
        }
    }
}
