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
