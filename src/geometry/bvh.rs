//! Ray casting against the mesh: the only file that knows obvhs.
//!
//! obvhs works in f32. Vertices are stored relative to the mesh's bounding-sphere
//! centre and divided by its radius, so f32 resolution is set by the object's size,
//! never by the range to the observer, and obvhs' absolute epsilons (it skips BVH nodes
//! within 1e-4 of a ray's origin) become relative to the object: a millimetre part
//! shadows like a metre one. Ray origins are offset by a distance scaled to the object.

use super::mesh::Mesh;
use glam::{DVec3, Vec3A};
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::ray::Ray;
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use std::time::Duration;

/// A BVH over the mesh's triangles for occlusion queries.
pub struct Occluder {
    bvh: CwBvh,
    /// Triangles in BVH primitive order (so a callback's id indexes this directly).
    tris: Vec<Triangle>,
    centre: DVec3,
    /// Bounding radius, m: BVH coordinates are (x − centre)/radius.
    radius: f64,
    /// Offset of ray origins off the surface, m (scaled to the object).
    offset: f64,
}

/// An [`Occluder`] built on first use, once. Exact clipping decides most faces without
/// rays (the box-wings cast none), so many requests never need the BVH: building it
/// was a fifth of the fine-dish box-wing's preparation.
pub struct LazyOccluder {
    mesh: Mesh,
    bvh: std::sync::OnceLock<Occluder>,
}

impl LazyOccluder {
    pub fn new(mesh: &Mesh) -> LazyOccluder {
        LazyOccluder {
            mesh: mesh.clone(),
            bvh: std::sync::OnceLock::new(),
        }
    }

    /// The occluder, built now if not yet.
    #[inline]
    pub fn get(&self) -> &Occluder {
        self.bvh.get_or_init(|| Occluder::build(&self.mesh))
    }
}

impl Occluder {
    /// Builds the BVH once per request.
    pub fn build(mesh: &Mesh) -> Occluder {
        let (centre, radius) = mesh.bounding_sphere();
        let radius = radius.max(f64::MIN_POSITIVE);
        let local = |p: DVec3| to_f32((p - centre) / radius);
        let tris: Vec<Triangle> = (0..mesh.triangles.len())
            .map(|i| {
                let [a, b, c] = mesh.corners(i);
                Triangle {
                    v0: local(a),
                    v1: local(b),
                    v2: local(c),
                }
            })
            .collect();
        let mut build_time = Duration::ZERO;
        let bvh = build_cwbvh_from_tris(&tris, BvhBuildParams::medium_build(), &mut build_time);
        // The callback's id indexes bvh.primitive_indices: reorder once instead of
        // mapping on every hit test.
        let tris = bvh
            .primitive_indices
            .iter()
            .map(|&i| tris[i as usize])
            .collect();
        Occluder {
            bvh,
            tris,
            centre,
            radius,
            // f32 carries ~6e-8 of the object's size; 1e-6 (16 ulps) keeps clear of that
            // (no acne) while shifting shadow edges by no more than that.
            offset: 1e-6 * radius,
        }
    }

    /// Distance by which ray origins are pushed off the surface along its normal, m.
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// True when the ray from `origin` (on a surface with outward normal `normal`,
    /// facing `dir`) towards `dir` (unit) leaves the object without hitting anything.
    #[inline]
    pub fn is_clear(&self, origin: DVec3, normal: DVec3, dir: DVec3) -> bool {
        let o = (origin - self.centre + normal * self.offset) / self.radius;
        let ray = Ray::new(to_f32(o), dir_f32(dir), 0.0, f32::INFINITY);
        self.bvh
            .ray_traverse_miss(ray, |ray, id| self.tris[id].intersect(ray))
    }

    /// Distance to the first hit along the ray from `origin` (not offset), or `None`.
    /// Used by the renderer and tests.
    pub fn first_hit(&self, origin: DVec3, dir: DVec3) -> Option<(f64, usize)> {
        let ray = Ray::new(
            to_f32((origin - self.centre) / self.radius),
            dir_f32(dir),
            0.0,
            f32::INFINITY,
        );
        let mut hit = obvhs::ray::RayHit::none();
        if self
            .bvh
            .ray_traverse(ray, &mut hit, |ray, id| self.tris[id].intersect(ray))
        {
            let prim = self.bvh.primitive_indices[hit.primitive_id as usize] as usize;
            Some((hit.t as f64 * self.radius, prim))
        } else {
            None
        }
    }
}

/// A ray direction for obvhs. obvhs 0.4 misses every hit along a direction with a −0.0
/// component (its octant test and 1/−0 = −∞ disagree), so components that are zero in
/// f32 are handed over as +0.0.
#[inline]
fn dir_f32(d: DVec3) -> Vec3A {
    let c = |x: f64| {
        let x = x as f32;
        if x == 0.0 {
            0.0
        } else {
            x
        }
    };
    Vec3A::new(c(d.x), c(d.y), c(d.z))
}

#[inline]
fn to_f32(v: DVec3) -> Vec3A {
    Vec3A::new(v.x as f32, v.y as f32, v.z as f32)
}
