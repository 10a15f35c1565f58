//! Convex parts: connected pieces of a mesh that lie on the boundary of their own convex
//! hull, so that each shadows as one convex polygon however finely it is meshed (see
//! [`ConvexPart`]). Faces are joined through shared edges into parts; each part is then
//! checked against its faces' planes, from its edges when it is a cap with a lid
//! ([`super::cap`]), else vertex by vertex.

use super::cap::Cap;
use super::lid::{lid_of, Lid};
use crate::geometry::faces::{Faces, WeldedEdge};
use crate::geometry::mesh::Mesh;
use crate::geometry::union_find::{find, union};
use rayon::prelude::*;

/// A connected piece of the mesh that lies on the boundary of its own convex hull, and
/// whose edges that no second face shares all lie in one plane: a closed convex body (a
/// box), or a convex cap open on one flat side (a dish). Along any direction it hides
/// exactly what its convex hull hides — a line that meets the hull enters and leaves it,
/// and at most once through the open side's plane — so its shadow on a plane wholly
/// behind it is the convex hull of its projected vertices: one polygon, however finely
/// the part is meshed.
#[derive(Debug, Clone)]
pub struct ConvexPart {
    /// Distinct vertices, m.
    pub vertices: Vec<glam::DVec3>,
    /// Indices of the faces (into [`Faces`]) that make up the part.
    pub faces: Vec<u32>,
    /// Per face (as in `faces`): does the part lie in front of its front side (a dish's
    /// concave side) rather than behind it (a box's outside)?
    pub hull_ahead: Vec<bool>,
    /// The open side, when it is one convex polygon.
    pub lid: Option<Lid>,
}

/// Fewest faces for a part to be worth treating whole (below, the faces' own shadows are
/// as cheap).
const MIN_PART_FACES: usize = 3;
/// Largest faces × vertices work spent proving parts convex, per request.
const PART_WORK_LIMIT: usize = 100_000_000;

/// The convex parts of a mesh (see [`ConvexPart`]): faces connected through shared edges
/// (vertices welded by position), each part checked exactly — every vertex on one side
/// of every face's plane, within `tol` (m), and its open edges in one plane. A cap with a
/// lid (a dish) is proven so from its edges in linear time ([`Cap::sides`]); other parts
/// test their vertices against each face's plane.
pub fn convex_parts(mesh: &Mesh, faces: &Faces, tol: f64) -> Vec<ConvexPart> {
    parts_of(mesh, faces, tol, true)
        .into_iter()
        .map(|(part, _)| part)
        .collect()
}

/// [`convex_parts`], each with whether its convexity was proven from its edges
/// ([`Cap::sides`]), which `by_edges = false` never tries.
pub(super) fn parts_of(
    mesh: &Mesh,
    faces: &Faces,
    tol: f64,
    by_edges: bool,
) -> Vec<(ConvexPart, bool)> {
    // the triangles' edges by their welded ends, sorted so that each edge's uses are side
    // by side (a sort, not a hash map of lists: no allocation per edge), as merging faces
    // left them; unmerged faces kept none
    let (welded, sorted) = faces.welded_edges(mesh);
    let uses = edge_uses(mesh, faces, &welded, &sorted);
    let mut parent = joined_by_shared_edges(faces.len(), &uses);
    let members = members_by_root(&mut parent);
    let edges = part_edges(&uses, &mut parent);
    let cx = Context {
        mesh,
        faces,
        welded: &welded,
    };
    let mut work = 0usize;
    let mut parts: Vec<(ConvexPart, bool)> = members
        .into_iter()
        .enumerate()
        .filter(|(root, fs)| fs.len() >= MIN_PART_FACES && !edges.non_manifold[*root])
        .filter_map(|(root, fs)| {
            let (open, inner) = (&edges.open[root], &edges.inner[root]);
            checked_part(&cx, fs, open, inner, tol, by_edges, &mut work)
        })
        .collect();
    parts.sort_by_key(|(p, _)| p.faces[0]);
    parts
}

/// One triangle's use of a welded edge: its ends (the lower first), the triangle's face,
/// whether the triangle runs from the lower end, and the triangle.
type EdgeUse = ((u32, u32), u32, bool, u32);

/// Each use of each welded edge (`sorted`, as [`Faces::welded_edges`] gives them, each
/// edge's uses side by side) with its face and its direction: a shared edge joins two
/// faces.
fn edge_uses(mesh: &Mesh, faces: &Faces, welded: &[u32], sorted: &[WeldedEdge]) -> Vec<EdgeUse> {
    let mut face_of = vec![0u32; mesh.triangles.len()];
    for (i, f) in faces.faces.iter().enumerate() {
        for &t in &f.triangles {
            face_of[t as usize] = i as u32;
        }
    }
    sorted
        .iter()
        .map(|&(a, b, t)| {
            let tri = mesh.triangles[t as usize].map(|v| welded[v as usize]);
            let forward = a < b && (0..3).any(|k| tri[k] == a && tri[(k + 1) % 3] == b);
            ((a, b), face_of[t as usize], forward, t)
        })
        .collect()
}

/// The faces joined through the edges they share: a union–find over `faces` faces.
fn joined_by_shared_edges(faces: usize, uses: &[EdgeUse]) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..faces as u32).collect();
    for adj in uses.chunk_by(|x, y| x.0 == y.0) {
        for w in adj.windows(2) {
            union(&mut parent, w[0].1, w[1].1);
        }
    }
    parent
}

/// Each part's faces under its least face, which is its root (empty for other faces).
fn members_by_root(parent: &mut [u32]) -> Vec<Vec<u32>> {
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); parent.len()];
    for f in 0..parent.len() as u32 {
        members[find(parent, f) as usize].push(f);
    }
    members
}

/// A part's edges, by the part's root face.
struct PartEdges {
    /// Open edges: an edge of a part that no other triangle of it uses the other way
    /// round (edges inside a merged face cancel like any other), in the direction its
    /// triangle runs; sorted, so the lid's corners start from the first.
    open: Vec<Vec<(u32, u32)>>,
    /// Inner edges: the two triangles that share each (for `Cap::sides`).
    inner: Vec<Vec<(u32, u32)>>,
    /// An edge used twice one way, or by three faces.
    non_manifold: Vec<bool>,
}

/// Every part's open and inner edges, and whether it is non-manifold.
fn part_edges(uses: &[EdgeUse], parent: &mut [u32]) -> PartEdges {
    let n = parent.len();
    let mut edges = PartEdges {
        open: vec![Vec::new(); n],
        inner: vec![Vec::new(); n],
        non_manifold: vec![false; n],
    };
    for adj in uses.chunk_by(|x, y| x.0 == y.0) {
        let ((a, b), face, _, _) = adj[0];
        let part = find(parent, face) as usize;
        match adj {
            [(_, _, forward, _)] => edges.open[part].push(if *forward { (a, b) } else { (b, a) }),
            [(_, _, x, s), (_, _, y, t)] if x != y => edges.inner[part].push((*s, *t)),
            _ => edges.non_manifold[part] = true,
        }
    }
    for open in &mut edges.open {
        open.sort_unstable();
    }
    edges
}

/// What every part is checked against: the mesh, its faces, each vertex's welded id.
struct Context<'a> {
    mesh: &'a Mesh,
    faces: &'a Faces,
    welded: &'a [u32],
}

/// The part of faces `fs` (with its `open` and `inner` edges) as a convex part, and whether
/// its edges proved it; `None` when it is none, or when the work spent on parts so far
/// (`work`, faces × vertices) passes [`PART_WORK_LIMIT`].
fn checked_part(
    cx: &Context,
    fs: Vec<u32>,
    open: &[(u32, u32)],
    inner: &[(u32, u32)],
    tol: f64,
    by_edges: bool,
    work: &mut usize,
) -> Option<(ConvexPart, bool)> {
    let (mesh, faces, welded) = (cx.mesh, cx.faces, cx.welded);
    let mut ids: Vec<u32> = fs
        .iter()
        .flat_map(|&f| faces.faces[f as usize].triangles.iter())
        .flat_map(|&t| mesh.triangles[t as usize].map(|v| welded[v as usize]))
        .collect();
    ids.sort_unstable();
    ids.dedup();
    let vertices: Vec<glam::DVec3> = ids.iter().map(|&v| mesh.vertices[v as usize]).collect();
    *work = work.saturating_add(fs.len().saturating_mul(vertices.len()));
    if *work > PART_WORK_LIMIT {
        return None;
    }
    let mean = vertices.iter().sum::<glam::DVec3>() / vertices.len() as f64;
    let lid = open_side(mesh, open, mean, tol)?;
    // Per face: which side the part lies on, and that no vertex lies beyond its plane on
    // the other: from a cap's edges when it has a lid, else vertex by vertex.
    let cap = lid.as_ref().filter(|_| by_edges).and_then(|lid| {
        let cap = Cap {
            mesh,
            welded,
            faces,
            part: &fs,
            ids: &ids,
            vertices: &vertices,
            open,
            inner,
        };
        cap.sides(lid, tol)
    });
    let proven = cap.is_some();
    let hull_ahead = match cap {
        Some(sides) => sides,
        None => tree_sides(faces, &fs, &vertices, mean, tol)?,
    };
    let part = ConvexPart {
        vertices,
        faces: fs,
        hull_ahead,
        lid,
    };
    Some((part, proven))
}

/// The lid of a part with open edges `open` and vertices' `mean` (m): `Some(None)` for a
/// closed part or an open side that is no convex polygon, `None` when the open side is
/// not flat (within `tol`, m), which makes the part no convex part.
fn open_side(mesh: &Mesh, open: &[(u32, u32)], mean: glam::DVec3, tol: f64) -> Option<Option<Lid>> {
    if open.is_empty() {
        return Some(None);
    }
    // the open side must be flat: Newell's normal of its edges, then distances
    let p = mesh.vertices[open[0].0 as usize];
    let n = open.iter().fold(glam::DVec3::ZERO, |acc, &(a, b)| {
        let (a, b) = (mesh.vertices[a as usize] - p, mesh.vertices[b as usize] - p);
        acc + a.cross(b)
    });
    let flat = n.length() > 0.0 && {
        let n = n.normalize();
        open.iter()
            .flat_map(|&(a, b)| [a, b])
            .all(|v| n.dot(mesh.vertices[v as usize] - p).abs() <= tol)
    };
    if !flat {
        return None;
    }
    Some(lid_of(open, mesh, mean - p, n.normalize(), tol))
}

/// Per face of a part (`part`, with distinct `vertices` and their `mean`, m): whether the
/// part lies ahead of it, by testing the vertices against its plane (within `tol`, m), in
/// parallel; `None` when some face has vertices beyond it on both sides.
fn tree_sides(
    faces: &Faces,
    part: &[u32],
    vertices: &[glam::DVec3],
    mean: glam::DVec3,
    tol: f64,
) -> Option<Vec<bool>> {
    let points = crate::geometry::mesh::Points::new(vertices);
    let tree = crate::geometry::mesh::PointTree::new(vertices);
    // well over the rounding of a height (~1e-16 of the coordinates)
    let slack = 1e-4 * tol;
    part.par_iter()
        .map(|&f| {
            let face = &faces.faces[f as usize];
            let (n, c) = (face.normal, face.centroid);
            let h = n.dot(mean - c);
            // the mean's height is the vertices' mean height, to rounding far below the
            // tolerance: beyond twice it, some vertex is beyond it
            let (ahead, behind) = if h < -2.0 * tol {
                (tree.any_beyond(n, c, tol, slack), true)
            } else if h > 2.0 * tol {
                (true, tree.any_beyond(-n, c, tol, slack))
            } else {
                points.sides(n, c, tol)
            };
            // on its hull's boundary unless vertices lie on both sides
            (!(ahead && behind)).then_some(ahead)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::builtin;

    #[test]
    fn the_box_wings_parts_are_its_boxes_and_its_dish() {
        let mesh = builtin::box_wing();
        let faces = Faces::build(&mesh, true);
        let mut sizes: Vec<usize> = convex_parts(&mesh, &faces, 1e-9)
            .iter()
            .map(|p| p.faces.len())
            .collect();
        sizes.sort_unstable();
        // bus, two booms, mast (6 faces each); dish: 24 fan triangles + 4 × 24 quads
        assert_eq!(sizes, vec![6, 6, 6, 6, 120]);
        let parts = convex_parts(&mesh, &faces, 1e-9);
        let dish = parts.iter().find(|p| p.faces.len() == 120).unwrap();
        let lid = dish.lid.as_ref().expect("the dish's rim is its lid");
        assert_eq!(lid.corners.len(), 24);
        assert!(
            (lid.normal - glam::DVec3::Z).length() < 1e-12,
            "{}",
            lid.normal
        );
        assert!(
            dish.hull_ahead.iter().all(|&a| a),
            "the dish opens towards its normals"
        );
        // a ray from the dish's centre straight up leaves through the rim; one at 80°
        // from the axis hits the dish's side
        let centre = glam::DVec3::new(0.0, 0.0, 1.2);
        assert!(lid.passes(centre, glam::DVec3::Z, 1e-9));
        let low = glam::DVec3::new(80f64.to_radians().sin(), 0.0, 80f64.to_radians().cos());
        assert!(!lid.passes(centre, low, 1e-9));
        for p in parts.iter().filter(|p| p.faces.len() == 6) {
            assert!(
                p.lid.is_none() && p.hull_ahead.iter().all(|&a| !a),
                "boxes are closed"
            );
        }
    }

    #[test]
    fn non_convex_or_open_on_two_sides_is_no_part() {
        // a zigzag of three plates: the middle one's plane has the others' far edges on
        // both of its sides
        let mut zigzag = Mesh::default();
        let y = glam::DVec3::Y;
        let p: Vec<glam::DVec3> = [(0.0, 0.0), (1.0, 1.0), (2.0, 0.0), (3.0, 1.0)]
            .iter()
            .map(|&(x, z)| glam::DVec3::new(x, 0.0, z))
            .collect();
        for w in p.windows(2) {
            builtin::push_quad(&mut zigzag, [w[0], w[1], w[1] + y, w[0] + y], 0);
        }
        let faces = Faces::build(&zigzag, true);
        assert_eq!(faces.len(), 3);
        assert!(convex_parts(&zigzag, &faces, 1e-9).is_empty());
        // a square tube (a box without its two ends): convex, but a line along its axis
        // passes through both open ends without touching it
        let mut tube = Mesh::default();
        builtin::push_box(
            &mut tube,
            glam::DVec3::splat(-1.0),
            glam::DVec3::splat(1.0),
            0,
        );
        let keep: Vec<bool> = (0..tube.triangles.len())
            .map(|t| tube.area_vector(t).normalize().z.abs() < 0.5)
            .collect();
        let mut k = keep.iter();
        tube.triangles.retain(|_| *k.next().unwrap());
        tube.material_ids.truncate(tube.triangles.len());
        let faces = Faces::build(&tube, true);
        assert_eq!(faces.len(), 4);
        assert!(convex_parts(&tube, &faces, 1e-9).is_empty());
    }
}
