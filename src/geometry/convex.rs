//! Convexity: when no part of the mesh can shadow or hide another, the two cosines
//! decide everything and no ray need be cast.

use super::faces::Faces;
use super::mesh::Mesh;
use rayon::prelude::*;

/// Largest faces × vertices product checked exactly (all vertices behind every face).
const EXACT_LIMIT: usize = 400_000_000;
/// Below this faces × vertices product the exact test is cheaper than building edges.
const CHEAP_EXACT: usize = 20_000_000;

/// True when every vertex lies on or behind the plane of every face (within a tolerance
/// relative to the object's size). That is the exact condition for no self-shadowing of
/// one-sided faces. Large meshes first try the local test — closed, connected, every
/// edge convex — which implies global convexity (Tietze's theorem) in linear time; meshes
/// failing every test are treated as non-convex, which only costs rays.
pub fn is_convex(mesh: &Mesh, faces: &Faces) -> bool {
    let (_, scale) = mesh.bounding_sphere();
    let tol = 1e-9 * scale;
    let work = faces.len().saturating_mul(mesh.vertices.len());
    let exact = || {
        faces.faces.par_iter().all(|f| {
            let d = f.normal.dot(f.centroid);
            mesh.vertices.iter().all(|v| f.normal.dot(*v) - d <= tol)
        })
    };
    if work <= CHEAP_EXACT {
        exact()
    } else if locally_convex_and_closed(mesh, tol) {
        true
    } else {
        work <= EXACT_LIMIT && exact()
    }
}

fn locally_convex_and_closed(mesh: &Mesh, tol: f64) -> bool {
    use std::collections::HashMap;
    let mut edges: HashMap<(u32, u32), Vec<(u32, u32)>> = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            edges
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push((t as u32, tri[(k + 2) % 3]));
        }
    }
    // one connected surface: two convex bodies side by side can shadow each other
    let mut parent: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
    fn root(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    for adj in edges.values() {
        if let [(a, _), (b, _)] = adj[..] {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
    if (0..parent.len() as u32).any(|t| root(&mut parent, t) != 0) {
        return false;
    }
    edges.values().all(|adj| {
        if adj.len() != 2 {
            return false; // open or non-manifold: leave it to the rays
        }
        let (t0, _) = adj[0];
        let (_, opposite1) = adj[1];
        let n = mesh.area_vector(t0 as usize).normalize();
        let p = mesh.vertices[mesh.triangles[t0 as usize][0] as usize];
        n.dot(mesh.vertices[opposite1 as usize] - p) <= tol
    })
}

/// True when every vertex lies in one plane (a flat plate, even two-sided, cannot
/// shadow itself).
pub fn is_planar(mesh: &Mesh) -> bool {
    let (_, scale) = mesh.bounding_sphere();
    let tol = 1e-9 * scale;
    let n = (0..mesh.triangles.len())
        .map(|i| mesh.area_vector(i))
        .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
        .map(|a| a.normalize());
    let Some(n) = n else { return true };
    let p = mesh.vertices[mesh.triangles[0][0] as usize];
    mesh.triangles
        .iter()
        .flatten()
        .all(|&i| n.dot(mesh.vertices[i as usize] - p).abs() <= tol)
}

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
}

/// Fewest faces for a part to be worth treating whole (below, the faces' own shadows are
/// as cheap).
const MIN_PART_FACES: usize = 3;
/// Largest faces × vertices work spent proving parts convex, per request.
const PART_WORK_LIMIT: usize = 100_000_000;

/// The convex parts of a mesh (see [`ConvexPart`]): faces connected through shared edges
/// (vertices welded by position), each part checked exactly — every vertex on one side
/// of every face's plane, within `tol` (m), and its open edges in one plane.
pub fn convex_parts(mesh: &Mesh, faces: &Faces, tol: f64) -> Vec<ConvexPart> {
    use std::collections::HashMap;
    let welded = mesh.welded_ids();
    let mut face_of = vec![0u32; mesh.triangles.len()];
    for (i, f) in faces.faces.iter().enumerate() {
        for &t in &f.triangles {
            face_of[t as usize] = i as u32;
        }
    }
    // directed edges by their welded ends: a shared edge joins two faces
    let mut edges: HashMap<(u32, u32), Vec<(u32, bool)>> = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (welded[tri[k] as usize], welded[tri[(k + 1) % 3] as usize]);
            edges
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push((face_of[t], a < b));
        }
    }
    let mut parent: Vec<u32> = (0..faces.len() as u32).collect();
    fn root(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    for adj in edges.values() {
        for w in adj.windows(2) {
            let (ra, rb) = (root(&mut parent, w[0].0), root(&mut parent, w[1].0));
            parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
    let mut members: HashMap<u32, Vec<u32>> = HashMap::new();
    for f in 0..faces.len() as u32 {
        members.entry(root(&mut parent, f)).or_default().push(f);
    }
    // open edges per part: an edge of a part that no other triangle of it uses the
    // other way round (edges inside a merged face cancel like any other)
    let mut open: HashMap<u32, Vec<(u32, u32)>> = HashMap::new();
    let mut manifold: HashMap<u32, bool> = HashMap::new();
    for ((a, b), adj) in &edges {
        let part = root(&mut parent, adj[0].0);
        match adj[..] {
            // in the direction its triangle runs
            [(_, forward)] => {
                open.entry(part)
                    .or_default()
                    .push(if forward { (*a, *b) } else { (*b, *a) })
            }
            [(_, x), (_, y)] if x != y => {}
            _ => {
                manifold.insert(part, false); // used twice one way, or by three faces
            }
        }
    }
    let mut work = 0usize;
    let mut parts: Vec<ConvexPart> = members
        .into_iter()
        .filter(|(root, fs)| fs.len() >= MIN_PART_FACES && manifold.get(root) != Some(&false))
        .filter_map(|(root, fs)| {
            let mut ids: Vec<u32> = fs
                .iter()
                .flat_map(|&f| faces.faces[f as usize].triangles.iter())
                .flat_map(|&t| mesh.triangles[t as usize].map(|v| welded[v as usize]))
                .collect();
            ids.sort_unstable();
            ids.dedup();
            let vertices: Vec<glam::DVec3> =
                ids.iter().map(|&v| mesh.vertices[v as usize]).collect();
            work = work.saturating_add(fs.len().saturating_mul(vertices.len()));
            if work > PART_WORK_LIMIT {
                return None;
            }
            let supporting = fs.iter().all(|&f| {
                let face = &faces.faces[f as usize];
                let (mut ahead, mut behind) = (false, false);
                for v in &vertices {
                    let h = face.normal.dot(*v - face.centroid);
                    ahead |= h > tol;
                    behind |= h < -tol;
                }
                !(ahead && behind)
            });
            if !supporting {
                return None;
            }
            if let Some(open) = open.get(&root) {
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
            }
            Some(ConvexPart {
                vertices,
                faces: fs,
            })
        })
        .collect();
    parts.sort_by_key(|p| p.faces[0]);
    parts
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
