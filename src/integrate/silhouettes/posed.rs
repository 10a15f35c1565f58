//! An articulated mesh's silhouette structures, built once per request for what moves
//! as one and carried to each pose.
//!
//! The body and each articulated link (a *group*) move rigidly, so what lies within one
//! group — its faces' polygons in their own plane coordinates, its edges, valleys and
//! open pieces, its patches and the contacts between its own pieces — is built once, in
//! the reference pose, and each pose only moves it: points moved, normals, bases and
//! cones turned. What crosses groups is found per pose: the contacts between a link and
//! the body or another link ([`GroupContacts`]), the patches' boxes and the rays' hierarchy.
//! This holds while no two groups share a vertex (the caller checks each pose: a hinge
//! welded to its parent along its line shares edges with it, and is prepared whole).

use super::contacts::GroupContacts;
use super::patches::Patches;
use super::polygons::Polygons;
use super::rays::Rays;
use super::topology::Topology;
use super::{face_tables, Silhouettes};
use crate::geometry::articulation::Motion;
use crate::geometry::{Faces, Mesh};
use crate::scene::Scene;
use glam::DVec3;

/// What each group carries from pose to pose (see the module doc).
pub struct Reference {
    tri_face: Vec<u32>,
    /// Per face and per patch: its group (an index into a pose's motions).
    group_of_face: Vec<u32>,
    group_of_patch: Vec<u32>,
    polys: Polygons,
    /// Its contacts only those within a group.
    topo: Topology,
    patches: Patches,
    across: GroupContacts,
}

impl Reference {
    /// `scene`'s mesh in the reference pose, `faces` merged within the groups
    /// ([`Faces::build_within`]); `group`: per triangle, its group (0 the body, which
    /// never moves), `groups` of them.
    pub fn build(scene: &Scene, faces: &Faces, group: &[u32], groups: usize) -> Reference {
        let mesh = &scene.mesh;
        let (tri_face, two_sided) = face_tables(scene, faces);
        let eps = mesh.tolerance();
        let topo =
            Topology::build_within(mesh, faces, &tri_face, &two_sided, Some(group), eps, None);
        let polys = Polygons::build(mesh, faces, two_sided, eps);
        let patches = Patches::build(&polys, &topo);
        let group_of_face: Vec<u32> = faces
            .faces
            .iter()
            .map(|f| group[f.triangles[0] as usize])
            .collect();
        // a patch grows across edges, which join no two groups
        let group_of_patch = (0..patches.len())
            .map(|p| group_of_face[patches.faces_of(p)[0] as usize])
            .collect();
        Reference {
            across: GroupContacts::build(mesh, group, groups, eps),
            tri_face,
            group_of_face,
            group_of_patch,
            polys,
            topo,
            patches,
        }
    }

    /// The silhouettes of one pose: `mesh` the posed mesh, `faces` the reference's moved
    /// to it ([`Faces::moved`]), `motions` each group's (the body's the identity). No two
    /// groups may share a vertex in this pose.
    pub fn pose<'a>(&self, mesh: &'a Mesh, faces: &Faces, motions: &[Motion]) -> Silhouettes<'a> {
        let of_face = |f: usize| motions[self.group_of_face[f] as usize];
        let eps = mesh.tolerance();
        let polys = self.polys.moved(of_face);
        let corners: Vec<[DVec3; 3]> = (0..mesh.triangles.len()).map(|t| mesh.corners(t)).collect();
        let across = self.across.contacts(&corners, &self.tri_face, eps);
        let topo = self.topo.moved(|f| of_face(f as usize), across);
        let patches = self.patches.moved(&polys, &topo, |p| {
            motions[self.group_of_patch[p] as usize].rot
        });
        let rays = Rays::build(&polys, &topo.open);
        Silhouettes::assemble(mesh, faces, (polys, topo, patches, rays), eps)
    }
}
