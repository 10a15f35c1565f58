//! Proofs that a direction is clear, without rays: of one face or patch by another.
//!
//! - **reach** ([`reaches`]): the occluder's bounding sphere misses the half-infinite
//!   cylinder swept by the receiver's bounding sphere along the direction;
//! - **half-space**: a receiver wholly in front of an occluder's plane, along a direction
//!   pointing away from it, never meets it ([`reaches_front`], [`relation`] and
//!   [`super::patches::cone_clear`] for patches, [`super::blockers::Blocker::half_space_clear`] for faces);
//! - **outline** ([`outline_clear`]): every line from the receiver meets a large plate's
//!   plane beyond one edge of its outline.

use super::face::FaceGeom;
use glam::DVec3;
use std::ops::Range;

/// Relation of a receiver patch to an occluder patch's planes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Side {
    /// Every receiver vertex on or in front of every occluder face plane.
    Front,
    /// Every receiver vertex on or behind every occluder face plane.
    Behind,
    Mixed,
}

/// Does the sphere (c_o, r_o) meet the half-infinite cylinder swept by the sphere
/// (c_f, r_f) along unit `d`?
#[inline]
pub(super) fn reaches(c_f: DVec3, r_f: f64, c_o: DVec3, r_o: f64, d: DVec3) -> bool {
    let w = c_o - c_f;
    let t = w.dot(d).max(0.0);
    let reach = r_f + r_o;
    (w - d * t).length_squared() < reach * reach
}

/// Can some face of `p_faces` reach the lit/seen side of some face of `q_faces`?
pub(super) fn may_block(
    geoms: &[FaceGeom],
    q_faces: &Range<u32>,
    p_faces: &Range<u32>,
    tol: f64,
) -> bool {
    q_faces.clone().any(|fi| {
        let f = &geoms[fi as usize];
        p_faces.clone().any(|gi| {
            if gi == fi {
                return false;
            }
            let g = &geoms[gi as usize];
            let s = f.normal.dot(g.centroid - f.centroid);
            if s.abs() >= g.radius + tol {
                return s > 0.0 || f.two_sided; // wholly on one side: the sphere decides
            }
            reaches_front(g, f.normal, f.centroid, tol)
                || (f.two_sided && reaches_front(g, -f.normal, f.centroid, tol))
        })
    })
}

/// Does some vertex of `o` lie strictly in front of the plane (`n`, through `p`)? Exact,
/// so the neighbours of a face on a convex part are not taken for occluders.
#[inline]
pub(super) fn reaches_front(o: &FaceGeom, n: DVec3, p: DVec3, tol: f64) -> bool {
    if n.dot(o.centroid - p) + o.radius <= tol {
        return false;
    }
    if o.vertices.is_empty() {
        return true; // no vertex list (centroid mode): the sphere's answer
    }
    o.vertices.iter().any(|v| n.dot(*v - p) > tol)
}

/// How many times a face's radius a blocker's must be for [`outline_clear`] to be tried:
/// for a blocker of about the face's size, the reach and half-space tests already decide.
pub(super) const LARGE_BLOCKER: f64 = 4.0;

/// Does no line from `points` along `d` meet the convex face `o`? True when every line
/// meets `o`'s plane beyond one edge of its outline, by `tol` (m). False for a face of
/// more than 8 corners, or `d` within 1e-6 of its plane, where it does not try.
pub(super) fn outline_clear(o: &FaceGeom, d: DVec3, points: &[DVec3], tol: f64) -> bool {
    let corners = o.convex();
    let dn = d.dot(o.normal);
    if corners.len() < 3 || corners.len() > 8 || dn.abs() < 1e-6 || points.len() > 8 {
        return false;
    }
    let mut meets = [DVec3::ZERO; 8];
    for (m, p) in meets.iter_mut().zip(points) {
        *m = *p + d * (o.normal.dot(o.centroid - *p) / dn);
    }
    let meets = &meets[..points.len()];
    (0..corners.len()).any(|i| {
        let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
        let mut out = (b - a).cross(o.normal);
        if out.dot(o.centroid - a) > 0.0 {
            out = -out; // away from the outline's inside, whichever way it runs
        }
        let slack = tol * out.length();
        meets.iter().all(|q| out.dot(*q - a) > slack)
    })
}

#[cfg(test)]
mod tests {
    use super::super::oracle::{random_unit, ray_meets_triangle};
    use super::*;

    #[test]
    fn a_plate_said_clear_of_a_face_meets_no_line_from_it() {
        // `outline_clear` against f64 lines (rays both ways) from 32 points of a small
        // triangle to a 2 m square plate, its outline running either way, for random
        // placements and directions; the claim must hold for every line, and be made
        // often enough to matter.
        for clockwise in [false, true] {
            plate_clear_against_rays(clockwise);
        }
    }

    fn plate_clear_against_rays(clockwise: bool) {
        let mut rnd = crate::test_rng(11);
        let mut corners = [
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
        ];
        if clockwise {
            corners.reverse();
        }
        let plate = FaceGeom {
            area: 4.0,
            two_sided: true,
            pieces: vec![
                [corners[0], corners[1], corners[2]],
                [corners[0], corners[2], corners[3]],
            ],
            pieces_area: 4.0,
            outline: corners.to_vec(),
            vertices: corners.to_vec(),
            ..FaceGeom::bare(DVec3::Z, DVec3::ZERO, 2f64.sqrt())
        };
        let (mut clear, mut tried) = (0, 0);
        for _ in 0..2000 {
            let centre = DVec3::new(6.0 * rnd() - 3.0, 6.0 * rnd() - 3.0, 4.0 * rnd() - 2.0);
            let tri: [DVec3; 3] = [0, 1, 2].map(|_| centre + 0.3 * random_unit(&mut rnd));
            let d = random_unit(&mut rnd);
            tried += 1;
            if !outline_clear(&plate, d, &tri, 1e-9) {
                continue;
            }
            clear += 1;
            for _ in 0..32 {
                let (mut a, mut b) = (rnd(), rnd());
                if a + b > 1.0 {
                    (a, b) = (1.0 - a, 1.0 - b);
                }
                let p = tri[0] + (tri[1] - tri[0]) * a + (tri[2] - tri[0]) * b;
                for t in &plate.pieces {
                    assert!(
                        !ray_meets_triangle(p, d, t) && !ray_meets_triangle(p, -d, t),
                        "said clear, but the line from {p} along {d} meets the plate"
                    );
                }
            }
        }
        assert!(
            clear > 500 && clear < tried,
            "{clear} of {tried} said clear"
        );
    }
}
