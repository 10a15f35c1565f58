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

/// How two triangles along an edge are tested for one plane ([`Faces::build_within`]).
#[derive(Clone, Copy, PartialEq)]
enum Join {
    /// Within 1e-9 of the object's size, normals within [`SAME_NORMAL`].
    Exact,
    /// Within half the mesh's tolerance.
    Rounded,
    /// Within what the mesh's rounding may move the second's corners off the first's
    /// plane, through the first's corners.
    Lever,
}

/// Per triangle index, whether it roots a group of `parent` with a corner farther than
/// `tol` (m) from the group's plane (its area-weighted normal through its centroid).
fn bent_groups(mesh: &Mesh, parent: &mut [u32], tol: f64) -> Vec<bool> {
    let n = parent.len();
    let root: Vec<usize> = (0..n as u32).map(|t| find(parent, t) as usize).collect();
    // per root: area vector, area-weighted sum of centroids, area
    let mut sums = vec![(DVec3::ZERO, DVec3::ZERO, 0.0); n];
    for (t, &r) in root.iter().enumerate() {
        let av = mesh.area_vector(t);
        let a = 0.5 * av.length();
        let [p, q, c] = mesh.corners(t);
        let s = &mut sums[r];
        (s.0, s.1, s.2) = (s.0 + av, s.1 + a * (p + q + c) / 3.0, s.2 + a);
    }
    let mut bent = vec![false; n];
    for (t, &r) in root.iter().enumerate() {
        let (normal, moment, area) = sums[r];
        let (normal, centroid) = (normal.normalize_or_zero(), moment / area);
        if mesh
            .corners(t)
            .iter()
            .any(|v| normal.dot(*v - centroid).abs() > tol)
        {
            bent[r] = true;
        }
    }
    bent
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

    /// [`Faces::welded_edges`] owned, for reading while the faces change: those merging
    /// kept are taken out of the faces (a copy of them is ~7 MB at 200k triangles; give
    /// them back with [`Faces::put_back_welded_edges`]), or computed here. The flag says
    /// whether they were taken.
    pub fn take_welded_edges(&mut self, mesh: &Mesh) -> (Vec<u32>, Vec<WeldedEdge>, bool) {
        if self.edges.is_empty() {
            let (welded, edges) = mesh.welded_edges();
            (welded, edges, false)
        } else {
            let welded = std::mem::take(&mut self.welded);
            (welded, std::mem::take(&mut self.edges), true)
        }
    }

    /// Returns what [`Faces::take_welded_edges`] took (nothing when it computed them).
    pub fn put_back_welded_edges(
        &mut self,
        (welded, edges, taken): (Vec<u32>, Vec<WeldedEdge>, bool),
    ) {
        if taken {
            (self.welded, self.edges) = (welded, edges);
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
        // Within half the mesh's tolerance ([`Mesh::tolerance`]) where its rounding sets it.
        let plane_tol = (1e-9 * scale).max(4.0 * mesh.rounding).max(1e-300);
        let strict = 1e-9 * scale.max(1e-300);
        let normals: Vec<DVec3> = (0..n)
            .into_par_iter()
            .map(|i| mesh.area_vector(i).normalize())
            .collect();
        // Two triangles along an edge merge when one material, facing one way, and the
        // corners of the second lie on the first's plane: within 1e-9 of the object's
        // size (`Join::Exact`), or for a rounded mesh within what its rounding may move
        // them. Its normals then scatter by the rounding over a triangle's height (a
        // sliver's by much more) and only say which way the triangles face.
        let joins = |o: usize, t: usize, how: Join| {
            let same = if how == Join::Exact { SAME_NORMAL } else { 0.0 };
            if mesh.material_ids[o] != mesh.material_ids[t] || normals[o].dot(normals[t]) <= same {
                return false;
            }
            let [a, b, c] = mesh.corners(o);
            let area = (b - a).cross(c - a);
            mesh.corners(t).iter().all(|&v| {
                let height = normals[o].dot(v - a).abs();
                match how {
                    Join::Exact => height <= strict,
                    Join::Rounded => height <= plane_tol,
                    Join::Lever => {
                        // The height at v of a plane through three corners each moved
                        // by up to δ = √3·rounding moves by up to δ·Σ|λ| (λ: v's
                        // barycentric coordinates in the triangle, large beyond a
                        // sliver's long side), and v by δ.
                        let w = |p: DVec3, q: DVec3| (q - p).cross(v - p).dot(area).abs();
                        let lever = (w(b, c) + w(c, a) + w(a, b)) / area.length_squared();
                        height <= strict + 3f64.sqrt() * mesh.rounding * (1.0 + lever)
                    }
                }
            })
        };
        let mut parent: Vec<u32> = (0..n as u32).collect();
        let (mut welded, mut edge_list) = (Vec::new(), Vec::new());
        if merge {
            // Weld vertices by exact position so meshes with split vertices still merge;
            // the triangles sharing an edge are side by side in `edges`.
            let (canon, edges) = mesh.welded_edges_within(group);
            let pairs = || {
                edges
                    .chunk_by(|x, y| (x.0, x.1) == (y.0, y.1))
                    .flat_map(|shared| {
                        let o = shared[0].2 as usize;
                        shared[1..].iter().map(move |&(_, _, t)| (o, t as usize))
                    })
            };
            let first = if mesh.rounding > 0.0 {
                Join::Lever
            } else {
                Join::Exact
            };
            for (o, t) in pairs() {
                if joins(o, t, first) {
                    union(&mut parent, o as u32, t as u32);
                }
            }
            // Pairs within the rounding may chain along a gently curved surface (the
            // nearly flat fan at a dish's apex): a face whose corners stray from its own
            // plane by more than half the tolerance is merged again by a stricter test.
            let stricter = if mesh.rounding > 0.0 {
                &[Join::Rounded, Join::Exact][..]
            } else {
                &[]
            };
            for &how in stricter {
                let bent = bent_groups(mesh, &mut parent, plane_tol);
                if !bent.iter().any(|&b| b) {
                    break;
                }
                let root: Vec<u32> = (0..n as u32).map(|t| find(&mut parent, t)).collect();
                parent = (0..n as u32).collect();
                for (o, t) in pairs() {
                    let (r, kept) = (root[o], !bent[root[o] as usize]);
                    if r == root[t] && (kept || joins(o, t, how)) {
                        union(&mut parent, o as u32, t as u32);
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

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geometry::builtin::push_grid_quad;
    use crate::geometry::mesh::written_rounding;
    use glam::DQuat;

    /// `mesh` turned off the axes and written to `decimals`, its rounding read from them.
    fn written(mut mesh: Mesh, decimals: i32) -> Mesh {
        let (turn, s) = (
            DQuat::from_euler(glam::EulerRot::XYZ, 0.4, -0.9, 1.3),
            10f64.powi(decimals),
        );
        for v in &mut mesh.vertices {
            *v = (turn * *v + DVec3::new(0.3, -0.2, 0.1)).map(|x| (x * s).round() / s);
        }
        mesh.rounding = written_rounding(&mesh.vertices);
        mesh
    }

    /// The shallow fan at a dish's apex (48 triangles, rising 0.005 a metre out to 1.7 cm)
    /// and a ring of 48 quads beyond it (from 1.7 to 2.8 cm, rising 0.014): neighbours
    /// differ by little more than 6-decimal rounding, the whole by 2.4e-4 m.
    pub(crate) fn apex() -> Mesh {
        let mut m = Mesh::default();
        let at = |r: f64, k: u32| {
            let a = k as f64 / 48.0 * std::f64::consts::TAU;
            DVec3::new(r * a.cos(), r * a.sin(), r * r / 3.2)
        };
        m.vertices.push(DVec3::ZERO);
        m.vertices.extend((0..48).map(|k| at(0.0167, k)));
        m.vertices.extend((0..48).map(|k| at(0.0278, k)));
        for k in 0..48u32 {
            let (i, j) = (1 + k, 1 + (k + 1) % 48);
            m.triangles.push([0, i, j]);
            m.triangles.push([i, i + 48, j + 48]);
            m.triangles.push([i, j + 48, j]);
        }
        m.material_ids = vec![0; m.triangles.len()];
        m
    }

    #[test]
    fn a_plate_written_to_six_decimals_is_one_face() {
        // a 1.2 m square in 24 × 24 cells and a strip of 30 slivers 1 m by 5 mm beside it
        let mut plate = Mesh::default();
        push_grid_quad(
            &mut plate,
            DVec3::ZERO,
            1.2 * DVec3::X,
            1.2 * DVec3::Y,
            24,
            24,
            0,
        );
        push_grid_quad(
            &mut plate,
            2.0 * DVec3::X,
            DVec3::X,
            0.15 * DVec3::Y,
            1,
            30,
            0,
        );
        for decimals in [6, 7, 9] {
            let m = written(plate.clone(), decimals);
            let faces = Faces::build(&m, true);
            assert_eq!(faces.len(), 2, "{decimals} decimals");
            // its normal the true one's within the rounding over the plate's size
            let n = DQuat::from_euler(glam::EulerRot::XYZ, 0.4, -0.9, 1.3) * DVec3::Z;
            assert!(
                faces.faces[0].normal.dot(n) > 1.0 - 1e-10,
                "{decimals} decimals"
            );
        }
        // and written to significant digits (`%g`): the largest coordinates' last digit
        // rounds them most
        for digits in [6, 8] {
            let mut m = written(plate.clone(), 12);
            for v in &mut m.vertices {
                *v = v.map(|x| format!("{:.*e}", digits - 1, x).parse().expect("a number"));
            }
            m.rounding = written_rounding(&m.vertices);
            assert_eq!(Faces::build(&m, true).len(), 2, "{digits} digits");
        }
        // and stored in single precision, printed in full, shortest or to 9 digits
        for (how, print) in crate::geometry::mesh::F32_PRINTS {
            let mut m = written(plate.clone(), 12);
            for v in &mut m.vertices {
                *v = v.map(|x| print(x as f32));
            }
            m.rounding = written_rounding(&m.vertices);
            assert_eq!(Faces::build(&m, true).len(), 2, "f32 {how}");
            m.rounding = 0.0;
            assert!(
                Faces::build(&m, true).len() > 100,
                "f32 {how}, read as exact"
            );
        }
        // read as exact, the 6-decimal plate falls apart: the corners stray by 1e-6 m
        let mut exact = written(plate, 6);
        exact.rounding = 0.0;
        assert!(Faces::build(&exact, true).len() > 100);
    }

    #[test]
    fn a_surface_flat_only_within_the_rounding_between_neighbours_stays_in_flat_faces() {
        for decimals in [6, 9] {
            let m = written(apex(), decimals);
            let faces = Faces::build(&m, true);
            // every face's corners within half the tolerance of its plane
            for f in &faces.faces {
                for &t in &f.triangles {
                    for v in m.corners(t as usize) {
                        let h = f.normal.dot(v - f.centroid).abs();
                        assert!(h <= 0.5 * m.tolerance(), "{decimals}: {h:e}");
                    }
                }
            }
            assert!(faces.len() > 48, "{decimals}: {} faces", faces.len());
        }
    }
}
