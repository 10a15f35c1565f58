//! Geometry: the triangle mesh, OBJ parsing, coplanar faces, convexity, ray casting.

pub mod articulation;
pub mod basis;
pub mod builtin;
pub mod bvh;
pub mod cone;
pub mod convex;
pub mod csr;
pub mod faces;
pub mod mesh;
pub mod obj;
pub mod permute;
pub mod polygon;
pub mod union_find;

pub use basis::{angle_between, orthonormal_basis};
pub use cone::Cone;
pub use faces::{Face, Faces};
pub use mesh::Mesh;
