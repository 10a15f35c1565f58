//! Faces: connected, coplanar triangles of one material merged once per request.
//!
//! For a distant Sun and observer a flat face has one θi and one θr, so its light is
//! f·E·cosθi·cosθr·A with no sampling; per-epoch work then scales with faces, not
//! triangles (a subdivided box side is one face).

use super::articulation::Motion;
use super::mesh::Mesh;
use super::union_find::{find, union};
use glam::DVec3;
use rayon::prelude::*;
use std::borrow::Cow;

/// An edge by its welded ends (lower first) and one triangle along it.
pub type WeldedEdge = (u32, u32, u32);

/// One planar face.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    /// Outward unit normal.
    pub normal: DVec3,
    /// Unit tangent (for anisotropic BRDFs): its material's body-frame axis projected onto
    /// the face ([`tangent_of`]; the body's x axis until [`Faces::set_tangents`]), not a
    /// property of vertex order: relisting a triangle's vertices changes nothing.
    pub tangent: DVec3,
    /// Area, m².
    pub area: f64,
    /// Area-weighted centroid, m.
    pub centroid: DVec3,
    /// Radius of the sphere about `centroid` holding the whole face, m.
    pub radius: f64,
    /// Index into the scene's materials.
    pub material: u32,
    /// Triangles (indices into the mesh) that make up the face.
    pub triangles: Vec<u32>,
}

/// All faces of a mesh.
#[derive(Debug, Clone, Default)]
pub struct Faces {
    pub faces: Vec<Face>,
    /// When the faces were merged (else empty): each mesh vertex's welded id (the least
    /// index at its position), and every triangle's edges by their welded ends, lower
    /// first, with the triangle, sorted — what [`super::convex::convex_parts`] joins
    /// faces by, kept rather than sorted again.
    pub welded: Vec<u32>,
    pub edges: Vec<(u32, u32, u32)>,
}

/// Cosine above which two unit normals count as the same plane's.
const SAME_NORMAL: f64 = 1.0 - 1e-9;

impl Faces {
    /// The mesh's welded ids and its welded edges, sorted (see `welded`, `edges`): those
    /// merging kept, or computed here when it kept none (faces built without merging).
    pub fn welded_edges<'a>(&'a self, mesh: &Mesh) -> (Cow<'a, [u32]>, Cow<'a, [WeldedEdge]>) {
        if self.edges.is_empty() {
            let (welded, edges) = mesh.welded_edges();
            (Cow::Owned(welded), Cow::Owned(edges))
        } else {
            (Cow::Borrowed(&self.welded), Cow::Borrowed(&self.edges))
        }
    }

    /// Gives each face its tangent from `axis(material)`, a unit body-frame direction
    /// ([`tangent_of`]).
    pub fn set_tangents(&mut self, axis: impl Fn(u32) -> DVec3) {
        for f in &mut self.faces {
            f.tangent = tangent_of(f.normal, axis(f.material));
        }
    }

    /// Groups triangles that share an edge (by vertex position), lie in one plane and
    /// use one material. `merge = false` keeps one face per triangle.
    pub fn build(mesh: &Mesh, merge: bool) -> Faces {
        Faces::build_within(mesh, merge, None)
    }

    /// [`Faces::build`], sharing edges only between vertices of one `group` (per vertex,
    /// [`Mesh::welded_ids_within`]) when given: no face spans two groups, and the kept
    /// welded edges join no two groups.
    pub fn build_within(mesh: &Mesh, merge: bool, group: Option<&[u32]>) -> Faces {
        let n = mesh.triangles.len();
        let (_, scale) = mesh.bounding_sphere();
        let plane_tol = 1e-9 * scale.max(1e-300);
        let normals: Vec<DVec3> = (0..n)
            .into_par_iter()
            .map(|i| mesh.area_vector(i).normalize())
            .collect();
        let mut parent: Vec<u32> = (0..n as u32).collect();
        let (mut welded, mut edge_list) = (Vec::new(), Vec::new());
        if merge {
            // Weld vertices by exact position so meshes with split vertices still merge;
            // the triangles sharing an edge are side by side in `edges`.
            let (canon, edges) = mesh.welded_edges_within(group);
            for shared in edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
                let o = shared[0].2 as usize;
                for &(_, _, t) in &shared[1..] {
                    let t = t as usize;
                    if mesh.material_ids[o] == mesh.material_ids[t]
                        && normals[o].dot(normals[t]) > SAME_NORMAL
                    {
                        let p = mesh.vertices[mesh.triangles[o][0] as usize];
                        let q = mesh.corners(t);
                        if q.iter().all(|v| normals[o].dot(*v - p).abs() <= plane_tol) {
                            union(&mut parent, o as u32, t as u32);
                        }
                    }
                }
            }
            (welded, edge_list) = (canon, edges);
        }
        // faces in the order of their first triangles (each root is its part's least)
        let mut index_of_root = vec![u32::MAX; n];
        let mut groups: Vec<Vec<u32>> = Vec::new();
        for t in 0..n as u32 {
            let r = find(&mut parent, t) as usize;
            if index_of_root[r] == u32::MAX {
                index_of_root[r] = groups.len() as u32;
                groups.push(Vec::new());
            }
            groups[index_of_root[r] as usize].push(t);
        }
        let faces = groups
            .into_par_iter()
            .map(|tris| Face::from_triangles(mesh, tris))
            .collect();
        Faces {
            faces,
            welded,
            edges: edge_list,
        }
    }

    /// Reorders the faces along a Morton curve of their centroids, so that runs of
    /// consecutive faces are spatially compact (visibility groups them into patches).
    pub fn sort_spatially(&mut self) {
        let n = self.faces.len();
        if n < 2 {
            return;
        }
        let lo = self
            .faces
            .iter()
            .fold(DVec3::splat(f64::INFINITY), |a, f| a.min(f.centroid));
        let hi = self
            .faces
            .iter()
            .fold(DVec3::splat(f64::NEG_INFINITY), |a, f| a.max(f.centroid));
        let ext = (hi - lo).max(DVec3::splat(1e-300));
        self.faces.par_sort_by_cached_key(|f| {
            let q = ((f.centroid - lo) / ext * 1023.0).as_uvec3();
            morton3(q.x, q.y, q.z)
        });
    }

    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// Per triangle of the mesh (`triangles` of them, each in one face): its face.
    pub fn triangle_faces(&self, triangles: usize) -> Vec<u32> {
        let mut of = vec![0u32; triangles];
        for (i, f) in self.faces.iter().enumerate() {
            for &t in &f.triangles {
                of[t as usize] = i as u32;
            }
        }
        of
    }

    /// The faces moved rigidly, each by `motion(face)` (normals turned, centroids
    /// moved; areas, radii and triangles kept), tangents taken again from `axis(material)`
    /// as [`Faces::set_tangents`] does. The welded ids and edges are kept: they stay
    /// right for the moved mesh as long as no two vertices that were apart meet.
    pub fn moved(&self, motion: impl Fn(usize) -> Motion, axis: impl Fn(u32) -> DVec3) -> Faces {
        let faces = self
            .faces
            .iter()
            .enumerate()
            .map(|(i, f)| {
                let m = motion(i);
                let normal = m.rot * f.normal;
                Face {
                    normal,
                    tangent: tangent_of(normal, axis(f.material)),
                    centroid: m.apply(f.centroid),
                    triangles: f.triangles.clone(),
                    ..*f
                }
            })
            .collect();
        Faces {
            faces,
            welded: self.welded.clone(),
            edges: self.edges.clone(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }
}

impl Face {
    fn from_triangles(mesh: &Mesh, triangles: Vec<u32>) -> Face {
        let mut area_vec = DVec3::ZERO;
        let mut area = 0.0;
        let mut centroid = DVec3::ZERO;
        for &t in &triangles {
            let av = mesh.area_vector(t as usize);
            let a = 0.5 * av.length();
            let [p, q, r] = mesh.corners(t as usize);
            area_vec += av;
            area += a;
            centroid += a * (p + q + r) / 3.0;
        }
        let centroid = centroid / area;
        let normal = area_vec.normalize();
        let radius = triangles
            .iter()
            .flat_map(|&t| mesh.corners(t as usize))
            .map(|v| v.distance(centroid))
            .fold(0.0, f64::max);
        let tangent = tangent_of(normal, DVec3::X);
        Face {
            normal,
            tangent,
            area,
            centroid,
            radius,
            material: mesh.material_ids[triangles[0] as usize],
            triangles,
        }
    }
}

/// Interleaves the low 10 bits of x, y, z.
fn morton3(x: u32, y: u32, z: u32) -> u64 {
    fn spread(v: u32) -> u64 {
        let mut x = v as u64 & 0x3ff;
        x = (x | (x << 16)) & 0x30000ff;
        x = (x | (x << 8)) & 0x300f00f;
        x = (x | (x << 4)) & 0x30c30c3;
        x = (x | (x << 2)) & 0x9249249;
        x
    }
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

/// The tangent a face of unit `normal` takes from its material's unit body-frame `axis`
/// ([`Face::tangent`]): the axis projected onto the face; where the normal lies within
/// 8.1° of ±axis (|n·axis| > 0.99), a fixed direction perpendicular to the axis instead.
/// What is projected is never shorter than 0.14, so no rounding turns the result.
pub fn tangent_of(normal: DVec3, axis: DVec3) -> DVec3 {
    let a = if normal.dot(axis).abs() > 0.99 {
        super::orthonormal_basis(axis).0
    } else {
        axis
    };
    (a - normal * normal.dot(a)).normalize()
}
