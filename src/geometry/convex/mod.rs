//! Convexity: when no part of the mesh can shadow or hide another, the two cosines
//! decide everything and no ray need be cast. When the mesh as a whole is not convex,
//! pieces of it may still be, and each such piece shadows as its convex hull does.
//!
//! - this file: [`is_convex`] (the whole mesh, by its vertices or by its edges) and
//!   [`is_planar`];
//! - [`parts`]: [`convex_parts`], the connected pieces that lie on the boundary of their own
//!   hull (a box, a dish), each checked against its faces' planes;
//! - [`cap`]: the linear-time proof, from its edges alone, that a cap open on one flat side
//!   (a dish) is such a piece;
//! - [`lid`]: [`Lid`], a cap's open side as a convex polygon, and whether a ray from the cap
//!   leaves through it; [`lid_view`]: [`LidView`], the lid seen along one direction, for
//!   testing many points at once.

use super::faces::Faces;
use super::union_find::{find, union};
use crate::geometry::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

mod cap;
mod lid;
mod lid_view;
mod parts;

pub use lid::Lid;
pub use lid_view::{LidPoint, LidView};
pub use parts::{convex_parts, ConvexPart};

/// Largest faces × vertices product checked exactly (all vertices behind every face).
const EXACT_LIMIT: usize = 400_000_000;
/// Below this faces × vertices product the exact test is cheaper than building edges.
const CHEAP_EXACT: usize = 20_000_000;

/// True when every vertex lies on or behind the plane of every face (within a tolerance
/// relative to the object's size). That is the exact condition for no self-shadowing of
/// one-sided faces. A sample of corners in front of a sample of faces proves most meshes
/// that are not convex so at once. Large meshes then try the local test — closed,
/// connected, every edge convex — which implies global convexity (Tietze's theorem) in
/// linear time; meshes failing every test are treated as non-convex, which only costs
/// rays.
pub fn is_convex(mesh: &Mesh, faces: &Faces) -> bool {
    let tol = mesh.tolerance();
    // a corner far in front of a face proves it at once (the tests below read every
    // vertex against every face, or every edge on one thread: 1–3 ms at 200k triangles,
    // before the rest of the preparation can start)
    !corner_in_front(mesh, faces, 1e3 * tol) && convex_by_every_vertex_or_edge(mesh, faces, tol)
}

/// [`is_convex`] without the sample: every vertex against every face's plane, or every
/// edge (`tol`, m).
fn convex_by_every_vertex_or_edge(mesh: &Mesh, faces: &Faces, tol: f64) -> bool {
    let work = faces.len().saturating_mul(mesh.vertices.len());
    let exact = || {
        faces.faces.par_iter().all(|f| {
            let d = f.normal.dot(f.centroid);
            mesh.vertices.iter().all(|v| f.normal.dot(*v) - d <= tol)
        })
    };
    if work <= CHEAP_EXACT {
        exact()
    } else if locally_convex_and_closed(mesh, faces, tol) {
        true
    } else {
        work <= EXACT_LIMIT && exact()
    }
}

fn locally_convex_and_closed(mesh: &Mesh, faces: &Faces, tol: f64) -> bool {
    // the welded edges sorted: the triangles sharing an edge side by side, so no hash map
    let (welded, sorted) = faces.welded_edges(mesh);
    let mut parent: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
    // every edge shared by exactly two triangles (else open or non-manifold: leave it to
    // the rays), and the second's far corner not in front of the first's plane; the first
    // edge that fails ends the test (a rocket body's open skirt, a fragment's first dent)
    for shared in sorted.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let [(wa, wb, t0), (_, _, t1)] = shared[..] else {
            return false;
        };
        let far = mesh.triangles[t1 as usize]
            .iter()
            .find(|&&v| welded[v as usize] != wa && welded[v as usize] != wb);
        let Some(&far) = far else {
            return false; // a degenerate triangle along the edge
        };
        let n = mesh.area_vector(t0 as usize).normalize();
        let p = mesh.vertices[mesh.triangles[t0 as usize][0] as usize];
        if n.dot(mesh.vertices[far as usize] - p) > tol {
            return false;
        }
        union(&mut parent, t0, t1);
    }
    // one connected surface: two convex bodies side by side can shadow each other
    (0..parent.len() as u32).all(|t| find(&mut parent, t) == 0)
}

/// True when every vertex lies in one plane (a flat plate, even two-sided, cannot
/// shadow itself).
pub fn is_planar(mesh: &Mesh) -> bool {
    let (_, scale) = mesh.bounding_sphere();
    let tol = mesh.tolerance_at(scale);
    // the test below finds its plane from every triangle (a serial pass over ~200k of
    // them is ~2.5 ms, a tenth of a cubesat's preparation); a sample of corners proves
    // most meshes that are not planar so first, whatever plane the test would pick
    !too_thick_for_a_slab(mesh, tol, scale) && planar_by_every_corner(mesh, tol)
}

/// [`is_planar`] without the sample: every corner within `tol` (m) of the plane of the
/// largest triangle through the first corner.
fn planar_by_every_corner(mesh: &Mesh, tol: f64) -> bool {
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

/// Triangles sampled by [`too_thick_for_a_slab`] and [`corner_in_front`], at most.
const SAMPLED_TRIANGLES: usize = 1024;
/// Faces sampled by [`corner_in_front`], at most.
const SAMPLED_FACES: usize = 64;

/// At most [`SAMPLED_TRIANGLES`] of `mesh`'s triangles, spread evenly over its list.
fn sampled_triangles(mesh: &Mesh) -> impl Iterator<Item = &[u32; 3]> {
    let step = mesh.triangles.len().div_ceil(SAMPLED_TRIANGLES).max(1);
    mesh.triangles.iter().step_by(step)
}

/// Is a sampled triangle's first corner in front of a sampled face's plane by more than
/// `margin` (m)? That proves the mesh not convex, whichever test would have decided:
/// [`is_convex`]'s exact test compares every vertex with every face's plane, and its
/// local test would have found a fold somewhere (a margin of a thousand times the
/// tolerance is no rounding of convex edges).
fn corner_in_front(mesh: &Mesh, faces: &Faces, margin: f64) -> bool {
    let corners: Vec<DVec3> = sampled_triangles(mesh)
        .map(|t| mesh.vertices[t[0] as usize])
        .collect();
    let step = faces.len().div_ceil(SAMPLED_FACES).max(1);
    faces.faces.iter().step_by(step).any(|f| {
        let d = f.normal.dot(f.centroid);
        corners.iter().any(|v| f.normal.dot(*v) - d > margin)
    })
}

/// Does the first triangle, with a corner of one of the sampled triangles, span a
/// tetrahedron that no slab of half-width `tol` (m) holds? Every vertex lies within
/// `radius` (m) of some point, so a convex body inside such a slab has a volume of at
/// most 2·tol·π·radius² (the slab's width times the disc its projection lies in): a
/// tetrahedron larger than that (twice over, for rounding) proves that no plane lies
/// within `tol` of every vertex, whichever plane [`is_planar`] would have tested. A
/// degenerate first triangle proves nothing.
fn too_thick_for_a_slab(mesh: &Mesh, tol: f64, radius: f64) -> bool {
    let Some(first) = mesh.triangles.first() else {
        return false;
    };
    let [a, b, c] = first.map(|i| mesh.vertices[i as usize]);
    // |(b − a) × (c − a) · (v − a)| is six times the tetrahedron's volume
    let twice_area = (b - a).cross(c - a);
    let bound = 6.0 * 2.0 * (2.0 * tol * std::f64::consts::PI * radius * radius);
    sampled_triangles(mesh)
        .flatten()
        .any(|&i| twice_area.dot(mesh.vertices[i as usize] - a).abs() > bound)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::builtin;

    #[test]
    fn a_corner_in_front_of_a_face_is_found_only_where_every_vertex_or_edge_finds_one() {
        use crate::geometry::builtin::{find, Detail};
        let mut meshes: Vec<Mesh> = ["rocket-body", "fragment", "dish-sat", "box-wing"]
            .iter()
            .map(|name| (find(name).unwrap().build)(Detail::Coarse))
            .collect();
        let sphere = builtin::icosphere(4, 1.0);
        let mut dented = sphere.clone();
        dented.vertices[100] *= 0.99;
        let mut shallow = sphere.clone();
        shallow.vertices[100] *= 1.0 - 1e-7; // within the sample's margin: left to the rest
        meshes.extend([sphere, dented, shallow]);
        for (k, m) in meshes.iter().enumerate() {
            let faces = Faces::build(m, true);
            let tol = 1e-9 * m.bounding_sphere().1;
            let sampled = corner_in_front(m, &faces, 1e3 * tol);
            let every = convex_by_every_vertex_or_edge(m, &faces, tol);
            assert!(!(sampled && every), "mesh {k}");
            assert_eq!(is_convex(m, &faces), !sampled && every);
            // the four objects that shadow themselves are proved so by the sample alone
            assert!(k >= 4 || sampled, "mesh {k}");
            // the sphere is convex, its shallow dent too small for the sample
            assert!(k != 4 && k != 6 || !sampled, "mesh {k}");
        }
    }

    #[test]
    fn a_thick_sample_proves_a_mesh_not_planar_only_where_every_corner_does() {
        // a plate of 2·40² triangles (1 m), then with one vertex lifted by heights from
        // far above the tolerance (1e-9 m here) down to well within it
        let plate = builtin::plate(1.0, 1.0, 40);
        let every = |m: &Mesh| planar_by_every_corner(m, 1e-9 * m.bounding_sphere().1);
        assert!(every(&plate) && is_planar(&plate));
        let mut proved = 0;
        for (k, lift) in [1e-1, 1e-3, 1e-6, 1e-8, 2e-9, 5e-10, 1e-12]
            .into_iter()
            .enumerate()
        {
            for v in [
                0,
                1,
                7 + k,
                plate.vertices.len() / 2,
                plate.vertices.len() - 1,
            ] {
                let mut m = plate.clone();
                m.vertices[v].z += lift;
                let tol = 1e-9 * m.bounding_sphere().1;
                let thick = too_thick_for_a_slab(&m, tol, m.bounding_sphere().1);
                // the sample may miss the vertex, but what it proves holds for every plane
                assert!(!thick || !every(&m), "lift {lift} at {v}");
                assert_eq!(is_planar(&m), every(&m), "lift {lift} at {v}");
                proved += thick as usize;
            }
        }
        // and it does prove something: the lifted first corner, at least at 1 mm and 10 cm
        assert!(proved >= 2, "{proved}");
        // a box and an object of many faces: proved at once
        let mut cuboid = Mesh::default();
        builtin::push_box(
            &mut cuboid,
            glam::DVec3::ZERO,
            glam::DVec3::new(1.0, 2.0, 3.0),
            0,
        );
        for m in [cuboid, builtin::icosphere(3, 1.0)] {
            let r = m.bounding_sphere().1;
            assert!(too_thick_for_a_slab(&m, 1e-9 * r, r));
            assert!(!is_planar(&m) && !every(&m));
        }
    }

    #[test]
    fn a_finely_meshed_sphere_is_convex_by_its_edges_and_a_dent_or_a_second_one_is_not() {
        // 20·4^5 = 20,480 triangles: faces × vertices is past the exact test's cheap limit,
        // so the edge test decides
        let sphere = builtin::icosphere(5, 1.0);
        let faces = |m: &Mesh| Faces::build(m, true);
        assert!(sphere.triangles.len() * sphere.vertices.len() > CHEAP_EXACT);
        assert!(is_convex(&sphere, &faces(&sphere)));
        // one vertex pushed in by 1 % of the radius: a dent
        let mut dented = sphere.clone();
        dented.vertices[100] *= 0.99;
        assert!(!is_convex(&dented, &faces(&dented)));
        // two spheres side by side: each locally convex, together not
        let mut two = sphere.clone();
        let n = two.vertices.len() as u32;
        two.vertices
            .extend(sphere.vertices.iter().map(|v| *v + glam::DVec3::X * 3.0));
        two.triangles
            .extend(sphere.triangles.iter().map(|t| t.map(|i| i + n)));
        two.material_ids.extend(sphere.material_ids.iter().copied());
        assert!(!is_convex(&two, &faces(&two)));
    }
}
