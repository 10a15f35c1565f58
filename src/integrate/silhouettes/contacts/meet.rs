//! Where two triangles meet as separate pieces ([`meeting`]): the segment they share
//! when they cross or touch ([`meet`]), unless they are neighbours along an edge, or
//! around a corner where they touch at the corner only.

use crate::geometry::Mesh;
use glam::DVec3;

/// Where triangles `s` and `t` of `mesh` meet as separate pieces ([`meet`], within
/// `tol`, m): two that share no vertex wherever they meet; two that share one vertex
/// only where they meet beyond it (neighbours around a corner touch there and nowhere
/// else, but a plate whose edge is welded to the centre of a cap it stands on meets
/// the cap along a line from that corner); two that share an edge never (neighbours
/// along it: the topology's).
pub(super) fn meeting(
    mesh: &Mesh,
    welded: &[u32],
    s: usize,
    t: usize,
    tol: f64,
) -> Option<(DVec3, DVec3)> {
    meeting_of(&Tri::of(mesh, welded, s), &Tri::of(mesh, welded, t), tol)
}

/// A triangle as [`meeting_of`] reads it: its corners (m) and their welded ids.
#[derive(Clone, Copy)]
pub(super) struct Tri {
    pub(super) c: [DVec3; 3],
    pub(super) w: [u32; 3],
}

impl Tri {
    #[inline]
    pub(super) fn of(mesh: &Mesh, welded: &[u32], t: usize) -> Tri {
        Tri {
            c: mesh.corners(t),
            w: mesh.triangles[t].map(|v| welded[v as usize]),
        }
    }
}

/// [`meeting`] of two triangles read already.
#[inline]
pub(super) fn meeting_of(s: &Tri, t: &Tri, tol: f64) -> Option<(DVec3, DVec3)> {
    let mut shared = (0..3).filter(|&i| t.w.contains(&s.w[i]));
    let (first, second) = (shared.next(), shared.next());
    if second.is_some() {
        return None;
    }
    let (cs, ct) = (&s.c, &t.c);
    match first {
        None => meet(cs, ct, tol),
        Some(i) => {
            let at = cs[i];
            // one's other two corners on one side of the other's plane: they touch at the
            // corner only (most pairs around a corner of a smooth surface)
            let apart = |x: &[DVec3; 3], y: &[DVec3; 3]| {
                // heights times |n|, against tol times |n| (no square root)
                let n = (y[1] - y[0]).cross(y[2] - y[0]);
                let reach = tol * tol * n.length_squared();
                let mut sides = x.iter().filter(|&&v| v != at).map(|&v| n.dot(v - at));
                let (h0, h1) = (sides.next().unwrap_or(0.0), sides.next().unwrap_or(0.0));
                h0 * h1 > 0.0 && h0 * h0 > reach && h1 * h1 > reach
            };
            if apart(cs, ct) || apart(ct, cs) {
                return None;
            }
            let (p, q) = meet(cs, ct, tol)?;
            // beyond the corner by more than rounding: a thousandth of the pair's size,
            // and twice as far as two planes at θ through one corner stay within tol of
            // each other (tol / sin θ: the fans of a rounded mesh's nearly flat corners)
            let size = cs
                .iter()
                .chain(ct)
                .map(|&x| (x - at).length())
                .fold(0.0f64, f64::max);
            let far = (p - at).length().max((q - at).length());
            let sin = sin_between(cs, ct);
            let near = if sin > 0.0 { 2.0 * tol / sin } else { 0.0 };
            (far > 1e-3 * size && far > near).then_some((p, q))
        }
    }
}

/// The sine of the angle between the planes of triangles `s` and `t` (corners, m); 0
/// for a degenerate one.
pub(super) fn sin_between(s: &[DVec3; 3], t: &[DVec3; 3]) -> f64 {
    let (ns, nt) = (
        (s[1] - s[0]).cross(s[2] - s[0]),
        (t[1] - t[0]).cross(t[2] - t[0]),
    );
    let lengths = ns.length() * nt.length();
    if lengths > 0.0 {
        ns.cross(nt).length() / lengths
    } else {
        0.0
    }
}

/// The segment where triangles `a` and `b` meet (touching within `tol` counts), when it
/// is longer than `tol`; coplanar triangles are left out (nothing in a face's plane
/// shades it).
pub(super) fn meet(a: &[DVec3; 3], b: &[DVec3; 3], tol: f64) -> Option<(DVec3, DVec3)> {
    let na = (a[1] - a[0]).cross(a[2] - a[0]).normalize_or_zero();
    let nb = (b[1] - b[0]).cross(b[2] - b[0]).normalize_or_zero();
    // most pairs that get here are neighbours on one smooth surface, one wholly on one
    // side of the other's plane: that answer first, before the line they would share
    if beyond_plane(a, nb, b[0], tol) || beyond_plane(b, na, a[0], tol) {
        return None;
    }
    let line = na.cross(nb);
    if line.length() < 1e-9 {
        return None;
    }
    let line = line.normalize();
    let sa = cut_by_plane(a, nb, b[0], tol, line)?;
    let sb = cut_by_plane(b, na, a[0], tol, line)?;
    let lo = sa.0.max(sb.0);
    let hi = sa.1.min(sb.1);
    if hi - lo <= tol {
        return None;
    }
    // a point on the line: from a's segment
    let (p0, t0) = sa.2;
    let (p, q) = (p0 + line * (lo - t0), p0 + line * (hi - t0));
    // Where the planes are nearly parallel, corners within tol of the other's plane are
    // taken as on the line though they may lie far from it, and the overlap along the
    // line says nothing of how far apart across it the two cuts are (two slivers of a
    // finely meshed dish near its apex, sharing a corner, "met" along 5 mm): keep only
    // the part of the segment within a few tol of both triangles.
    let reach = 4.0 * tol;
    let (u0, u1) = [(a, na), (b, nb)]
        .iter()
        .try_fold((0.0, 1.0), |(u0, u1), &(t, n)| {
            within(t, n, p, q, reach, u0, u1)
        })?;
    ((u1 - u0) * (q - p).length() > tol).then(|| (p + (q - p) * u0, p + (q - p) * u1))
}

/// The part `u0..u1` (parameters along p → q) of segment p–q that lies within `reach`
/// (m) of triangle `t`'s plane (unit normal `n`, as [`meet`] found it) and of its edges'
/// lines inside it (the triangle widened by `reach`), or None when none does.
fn within(
    t: &[DVec3; 3],
    n: DVec3,
    p: DVec3,
    q: DVec3,
    reach: f64,
    u0: f64,
    u1: f64,
) -> Option<(f64, f64)> {
    // each bound as g(x) = k·(x − o) + c ≥ 0, linear along the segment
    let mut range = (u0, u1);
    let mut keep = |k: DVec3, o: DVec3, c: f64| {
        let (gp, gq) = (k.dot(p - o) + c, k.dot(q - o) + c);
        if gp < 0.0 && gq < 0.0 {
            return false;
        }
        if gp < 0.0 {
            range.0 = f64::max(range.0, gp / (gp - gq));
        } else if gq < 0.0 {
            range.1 = f64::min(range.1, gp / (gp - gq));
        }
        range.0 <= range.1
    };
    let plane = keep(n, t[0], reach) && keep(-n, t[0], reach);
    let edges = (0..3).all(|i| {
        let e = t[(i + 1) % 3] - t[i];
        // inward across the edge, in the plane (the corners turn counter-clockwise about n)
        let inward = n.cross(e).normalize_or_zero();
        keep(inward, t[i], reach)
    });
    (plane && edges).then_some(range)
}

/// Do triangle `t`'s corners all lie farther than `tol` (m) on one side of the plane
/// (unit `n`, through `p`)?
#[inline]
fn beyond_plane(t: &[DVec3; 3], n: DVec3, p: DVec3, tol: f64) -> bool {
    let s = t.map(|v| n.dot(v - p));
    s.iter().all(|&x| x > tol) || s.iter().all(|&x| x < -tol)
}

/// The interval (along `line`) of triangle `t` where it meets the plane (`n`, through
/// `p`), with a point on it and that point's parameter; `t` is not wholly on one side
/// ([`beyond_plane`]).
fn cut_by_plane(
    t: &[DVec3; 3],
    n: DVec3,
    p: DVec3,
    tol: f64,
    line: DVec3,
) -> Option<(f64, f64, (DVec3, f64))> {
    let s = t.map(|v| n.dot(v - p));
    let mut pts: [DVec3; 4] = [DVec3::ZERO; 4];
    let mut k = 0;
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i].abs() <= tol {
            pts[k] = t[i];
            k += 1;
            if k == 4 {
                break;
            }
        }
        if (s[i] > tol && s[j] < -tol) || (s[i] < -tol && s[j] > tol) {
            let u = s[i] / (s[i] - s[j]);
            pts[k] = t[i] + (t[j] - t[i]) * u;
            k += 1;
            if k == 4 {
                break;
            }
        }
    }
    if k < 2 {
        return None;
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for q in &pts[..k] {
        let x = q.dot(line);
        lo = lo.min(x);
        hi = hi.max(x);
    }
    Some((lo, hi, (pts[0], pts[0].dot(line))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::silhouettes::contacts::contact_segments;

    #[test]
    fn a_nearly_flat_fan_written_to_six_decimals_does_not_meet_itself() {
        // its triangles around the apex share it and lie within the tolerance (4e-6 m) of
        // one another out to ~0.5 mm from it: the corner's, not a contact
        let mut mesh = crate::geometry::faces::tests::apex();
        for v in &mut mesh.vertices {
            *v = v.map(|x| (x * 1e6).round() / 1e6);
        }
        mesh.rounding = crate::geometry::mesh::written_rounding(&mesh.vertices);
        let tri_face: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
        let (welded, edges) = mesh.welded_edges();
        let pairs = contact_segments(
            &mesh,
            (&welded, &edges),
            &tri_face,
            None,
            mesh.tolerance(),
            None,
        );
        assert!(pairs.is_empty(), "{} contacts", pairs.len());
    }

    #[test]
    fn a_post_standing_on_a_plate_meets_it_along_its_foot() {
        // a vertical triangle whose bottom edge lies on the plate z = 0
        let plate = [
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let post = [
            DVec3::new(-0.2, 0.0, 0.0),
            DVec3::new(0.2, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        ];
        let (p, q) = meet(&plate, &post, 1e-9).expect("they meet");
        let (lo, hi) = (p.x.min(q.x), p.x.max(q.x));
        assert!(
            (lo + 0.2).abs() < 1e-12 && (hi - 0.2).abs() < 1e-12,
            "{p} {q}"
        );
        assert!(p.y.abs() < 1e-12 && p.z.abs() < 1e-12);
        // lifted off the plate: no contact
        let lifted = post.map(|v| v + DVec3::Z * 0.01);
        assert!(meet(&plate, &lifted, 1e-9).is_none());
        // piercing it: the segment inside the plate
        let pierce = post.map(|v| v - DVec3::Z * 0.5);
        let (p, q) = meet(&plate, &pierce, 1e-9).expect("pierces");
        assert!(((p - q).length() - 0.2).abs() < 1e-12);
    }

    #[test]
    fn two_slivers_of_a_fine_dish_near_its_apex_meet_only_at_their_shared_corner() {
        // the box-wing's dish at 200k triangles: 400 sectors, rings 5 mm apart, so the
        // triangles of the first rings are slivers 64 times longer than wide, their planes
        // within 1e-4 rad of each other. Two of neighbouring quads that share one corner
        // were found to meet along 5 mm (wrong: they touch at the corner only), which made
        // 400 of the dish's faces decided by rays.
        let (z0, f, sectors) = (1.2, 0.8, 400);
        let at = |r: f64, j: usize| {
            let phi = std::f64::consts::TAU * j as f64 / sectors as f64;
            DVec3::new(r * phi.cos(), r * phi.sin(), z0 + r * r / (4.0 * f))
        };
        let tol = 6.6e-9;
        for (r1, r2) in [(0.005, 0.01), (0.01, 0.015), (0.1, 0.105)] {
            for j in [0, 7, 100, 333] {
                let (a, b, c) = (at(r1, j), at(r2, j), at(r2, j + 1));
                let (d, e) = (at(r1, j + 1), at(r2, j + 2));
                let s = Tri {
                    c: [a, b, c],
                    w: [0, 1, 2],
                };
                let t = Tri {
                    c: [d, c, e],
                    w: [3, 2, 4],
                };
                assert!(meeting_of(&s, &t, tol).is_none(), "r {r1} sector {j}");
                // whatever meet finds lies within a few tol of both
                if let Some((p, q)) = meet(&s.c, &t.c, tol) {
                    assert!((q - p).length() < 1e-6, "r {r1} sector {j}: {p} {q}");
                }
            }
        }
        // a sliver standing across another along 3 mm still meets it there
        let flat = [at(0.005, 0), at(0.01, 0), at(0.01, 1)];
        let mid = (flat[0] + flat[1] + flat[2]) / 3.0;
        let up = [
            mid - DVec3::X * 0.0015 - DVec3::Z * 1e-3,
            mid + DVec3::X * 0.0015 - DVec3::Z * 1e-3,
            mid + DVec3::Z * 1e-3,
        ];
        let (p, q) = meet(&flat, &up, tol).expect("a sliver standing across meets");
        assert!((q - p).length() > 1e-5, "{p} {q}");
    }
}
