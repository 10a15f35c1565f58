//! The segments where pairs of triangles meet, as contacts on both faces of each pair
//! ([`join_pieces`]): a face's pieces along one other face joined where they overlap or
//! touch, so that a line through a finely meshed face is one segment, not one a triangle.

use super::meet::sin_between;
use super::Contact;
use glam::DVec3;

/// Where a triangle of one face meets another face's: the receiving face, the other face,
/// the other triangle and the receiving one, and the segment (m).
#[derive(Clone, Copy)]
struct Piece {
    face: u32,
    other_face: u32,
    other: u32,
    own: u32,
    seg: (DVec3, DVec3),
}

/// The pairs' segments as contacts, on both faces of each pair, with a face's pieces along
/// one other face joined where they overlap or touch.
pub(super) fn join_pieces(
    pairs: &[(u32, u32, (DVec3, DVec3))],
    corner: impl Fn(usize) -> [DVec3; 3],
    tri_face: &[u32],
    tol: f64,
) -> Vec<(u32, Contact)> {
    // each contact seen from both sides
    let mut seen: Vec<Piece> = Vec::with_capacity(2 * pairs.len());
    for &(s, t, seg) in pairs {
        let (fs, ft) = (tri_face[s as usize], tri_face[t as usize]);
        seen.push(Piece {
            face: fs,
            other_face: ft,
            other: t,
            own: s,
            seg,
        });
        seen.push(Piece {
            face: ft,
            other_face: fs,
            other: s,
            own: t,
            seg,
        });
    }
    // Two faces are flat: they meet along one line, found once per pair of their
    // triangles that touch. Where that line runs along an edge inside a face, both
    // triangles beside the edge find the same piece (counting it twice would double its
    // jump); and where another piece pierces a finely meshed flat face, its line comes in
    // as many pieces as triangles it crosses on either side, each a segment that the
    // face's cells are cut along and that each ray's region is keyed by (a cluster of
    // boxes through one another took ~50 a face). So the pieces of one face along one
    // other face are joined where they overlap or touch.
    seen.sort_unstable_by_key(|c| (c.face, c.other_face, c.other, c.own));
    let mut out = Vec::with_capacity(seen.len());
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for group in seen.chunk_by(|x, y| (x.face, x.other_face) == (y.face, y.other_face)) {
        let face = group[0].face;
        // the line along the longest piece
        let longest = group
            .iter()
            .map(|c| c.seg)
            .max_by(|x, y| {
                (x.1 - x.0)
                    .length_squared()
                    .total_cmp(&(y.1 - y.0).length_squared())
            })
            .unwrap_or(group[0].seg);
        let (o, e) = (longest.0, (longest.1 - longest.0).normalize_or_zero());
        // The two planes are each known to within `tol` (the faces merged triangles
        // within it), so the line where they meet is known to within about tol / sin θ
        // across it (θ between the planes); pieces found from pairs of triangles wander
        // that much about it (up to 5.3 tol / sin θ on a cluster of boxes written with
        // nine decimals).
        let own = corner(group[0].own as usize);
        let n = (own[1] - own[0]).cross(own[2] - own[0]);
        let sin = sin_between(&own, &corner(group[0].other as usize));
        let reach = 8.0 * tol / sin;
        let off_line = |x: DVec3| (x - o - e * (x - o).dot(e)).length() > reach;
        if e == DVec3::ZERO
            || sin < 1e-3
            || group.iter().any(|c| off_line(c.seg.0) || off_line(c.seg.1))
        {
            // not one line after all (faces nearly parallel, or flat only to within
            // their merging angle): the pieces along each other triangle joined
            for along in group.chunk_by(|x, y| x.other == y.other) {
                let (a, b) = along[0].seg;
                let (o, e) = (a, (b - a).normalize_or_zero());
                let other = corner(along[0].other as usize);
                let other_face = along[0].other_face;
                let made = join_spans(along, o, e, tol, &mut spans);
                out.extend(
                    made.into_iter()
                        .map(|seg| (face, contact(seg, other, other_face))),
                );
            }
            continue;
        }
        // Of the other face, its corners highest above and lowest below the receiving
        // face's plane: the other face is flat, so its part on either side of that plane
        // lies on one side of the line, as any of its points there does
        // ([`Contact::jump`] needs one on each side that has one; on a side with none,
        // a point of the plane stands in, which counts on neither).
        let height = |v: DVec3| n.dot(v - own[0]);
        let (mut top, mut bottom) = (own[0], own[0]);
        for c in group {
            for v in corner(c.other as usize) {
                if height(v) > height(top) {
                    top = v;
                }
                if height(v) < height(bottom) {
                    bottom = v;
                }
            }
        }
        let other = [top, bottom, top];
        let other_face = group[0].other_face;
        let made = join_spans(group, o, e, tol, &mut spans);
        out.extend(
            made.into_iter()
                .map(|seg| (face, contact(seg, other, other_face))),
        );
    }
    out
}

/// The segments (m) of `pieces`, all on the line through `o` along unit `e`, joined where
/// they overlap or come within `tol` (m) of each other (`spans`: scratch); a lone piece
/// as it is.
fn join_spans(
    pieces: &[Piece],
    o: DVec3,
    e: DVec3,
    tol: f64,
    spans: &mut Vec<(f64, f64)>,
) -> Vec<(DVec3, DVec3)> {
    if let [piece] = pieces {
        return vec![piece.seg];
    }
    spans.clear();
    spans.extend(pieces.iter().map(|&Piece { seg: (a, b), .. }| {
        let (s, t) = ((a - o).dot(e), (b - o).dot(e));
        (s.min(t), s.max(t))
    }));
    spans.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    let mut joined: Vec<(f64, f64)> = Vec::with_capacity(spans.len());
    for &(lo, hi) in spans.iter() {
        match joined.last_mut() {
            Some(cur) if lo <= cur.1 + tol => cur.1 = cur.1.max(hi),
            _ => joined.push((lo, hi)),
        }
    }
    joined
        .into_iter()
        .map(|(lo, hi)| (o + e * lo, o + e * hi))
        .collect()
}

/// A contact along segment `seg` with a sheet of face `face` (`other`: points of it).
fn contact(seg: (DVec3, DVec3), other: [DVec3; 3], face: u32) -> Contact {
    Contact {
        a: seg.0,
        b: seg.1,
        other,
        face,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Mesh;
    use crate::integrate::silhouettes::contacts::contact_segments;
    use crate::integrate::silhouettes::contacts::meet::meet;

    #[test]
    fn a_finely_meshed_wall_through_a_finely_meshed_plate_meets_it_along_one_segment() {
        // a 2 m plate and a 1.2 m × 1 m wall standing through it, 12 × 12 squares each
        // (the wall's line crosses a dozen of the plate's triangles and the plate's a
        // dozen of the wall's), turned off the axes and written to nine decimals, as an
        // OBJ file would hold them
        use crate::geometry::builtin::push_grid_quad;
        let mut mesh = Mesh::default();
        let (plate, wall) = (DVec3::new(-1.0, -1.0, 0.0), DVec3::new(-0.6, 0.1, -0.5));
        push_grid_quad(&mut mesh, plate, 2.0 * DVec3::X, 2.0 * DVec3::Y, 12, 12, 0);
        push_grid_quad(&mut mesh, wall, 1.2 * DVec3::X, DVec3::Z, 12, 12, 0);
        let turn = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
        let round = |x: f64| (x * 1e9).round() / 1e9;
        for v in &mut mesh.vertices {
            *v = (turn * *v).map(round);
        }
        let faces = crate::geometry::Faces::build(&mesh, true);
        assert_eq!(faces.len(), 2, "the plate and the wall, each one face");
        let tri_face = faces.triangle_faces(mesh.triangles.len());
        let (welded, edges) = mesh.welded_edges();
        let tol = 2e-9;
        let contacts = contact_segments(&mesh, (&welded, &edges), &tri_face, None, tol, None);
        // each face meets the other once, along the wall's whole width
        for f in 0..2 {
            let on: Vec<&Contact> = contacts.iter().filter(|c| c.0 == f).map(|c| &c.1).collect();
            assert_eq!(on.len(), 1, "face {f}: {on:?}");
            assert!(
                ((on[0].a - on[0].b).length() - 1.2).abs() < 1e-8,
                "{:?}",
                on[0]
            );
            assert_eq!(on[0].face, 1 - f);
        }
        // the joined contact's jump along any direction is each piece's (a piece: where
        // one triangle of the wall that reaches above the plate meets it, with that
        // triangle as the sheet)
        let plate = contacts.iter().find(|c| c.0 == 0).unwrap().1;
        let n = turn * DVec3::Z;
        let o = mesh.vertices[0];
        let (u, w) = (turn * DVec3::X, turn * DVec3::Y);
        let to2 = |x: DVec3| glam::DVec2::new((x - o).dot(u), (x - o).dot(w));
        let mesh = &mesh;
        let pieces: Vec<(DVec3, DVec3, [DVec3; 3])> = (0..mesh.triangles.len())
            .filter(|&t| tri_face[t] == 1)
            .flat_map(|t| {
                let wall = mesh.corners(t);
                (0..mesh.triangles.len())
                    .filter(|&s| tri_face[s] == 0)
                    .filter_map(move |s| {
                        meet(&mesh.corners(s), &wall, tol).map(|(a, b)| (a, b, wall))
                    })
            })
            .collect();
        assert!(pieces.len() > 12, "{} pieces", pieces.len());
        let mut checked = 0;
        for i in 0..40 {
            // directions over the sphere, those above the plate (the receiving side)
            let z = 1.0 - (2.0 * i as f64 + 1.0) / 40.0;
            let phi = i as f64 * 2.399_963_229_728_653 + 0.1;
            let r = (1.0 - z * z).sqrt();
            let d = turn * DVec3::new(r * phi.cos(), r * phi.sin(), z);
            if n.dot(d) < 0.05 {
                continue;
            }
            let joined = plate.jump(n, o, d, tol, true, to2);
            assert_ne!(
                joined, 0,
                "the wall's upper half lies on one side along {d}"
            );
            for &(a, b, other) in &pieces {
                let piece = Contact {
                    a,
                    b,
                    other,
                    face: 1,
                };
                let same_way = (b - a).dot(plate.b - plate.a).signum() as i32;
                let j = piece.jump(n, o, d, tol, true, to2);
                // (a wall triangle below the plate with an edge on it, its corners there
                // a rounding above or below, has no sheet above: not a piece to ask)
                let reaches_up = other.iter().any(|&v| n.dot(v - o) > 1e-3);
                if j != 0 && reaches_up {
                    assert_eq!(j * same_way, joined, "along {d}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 100, "{checked} pieces' jumps checked");
    }
}
