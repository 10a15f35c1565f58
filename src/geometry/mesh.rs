//! The triangle mesh in the body frame, in f64 metres.

use glam::DVec3;

/// A validated triangle mesh: every index in range, every triangle non-degenerate,
/// one material index per triangle.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, m.
    pub vertices: Vec<DVec3>,
    /// Counter-clockwise (seen from outside) vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Index into the scene's materials, one per triangle.
    pub material_ids: Vec<u32>,
}

impl Mesh {
    /// The three corners of triangle `i`, m.
    #[inline]
    pub fn corners(&self, i: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[i];
        [
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        ]
    }

    /// For each vertex, the first vertex at exactly the same position: ids that let meshes
    /// with split vertices (as OBJ exporters often write them) still share their edges.
    pub fn welded_ids(&self) -> Vec<u32> {
        let mut first = std::collections::HashMap::new();
        self.vertices
            .iter()
            .enumerate()
            .map(|(i, v)| {
                *first
                    .entry([v.x.to_bits(), v.y.to_bits(), v.z.to_bits()])
                    .or_insert(i as u32)
            })
            .collect()
    }

    /// Twice-area vector (b−a)×(c−a) of triangle `i`: its direction is the outward normal.
    #[inline]
    pub fn area_vector(&self, i: usize) -> DVec3 {
        let [a, b, c] = self.corners(i);
        (b - a).cross(c - a)
    }

    /// Centre of the axis-aligned bounding box and the radius of the sphere around it
    /// that holds every vertex, m.
    pub fn bounding_sphere(&self) -> (DVec3, f64) {
        bounding_sphere(&self.vertices)
    }

    /// Total surface area, m².
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|i| 0.5 * self.area_vector(i).length())
            .sum()
    }

    /// The same mesh with every vertex mapped by `f` (scaling, rotation in tests).
    pub fn transformed(&self, f: impl Fn(DVec3) -> DVec3) -> Mesh {
        Mesh {
            vertices: self.vertices.iter().map(|v| f(*v)).collect(),
            ..self.clone()
        }
    }
}

/// A sphere holding every point: centre (of their bounding box) and radius, m.
pub fn bounding_sphere(points: &[DVec3]) -> (DVec3, f64) {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), v| (lo.min(*v), hi.max(*v)),
    );
    let centre = 0.5 * (lo + hi);
    let radius = points
        .iter()
        .map(|v| v.distance(centre))
        .fold(0.0, f64::max);
    (centre, radius)
}

/// Points stored by coordinate (all x, then all y, then all z), for tests run against
/// many points at once: plane-side tests over them compile to vector instructions.
#[derive(Debug, Clone, Default)]
pub struct Points {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
}

impl Points {
    pub fn new(points: &[DVec3]) -> Points {
        Points {
            x: points.iter().map(|p| p.x).collect(),
            y: points.iter().map(|p| p.y).collect(),
            z: points.iter().map(|p| p.z).collect(),
        }
    }

    /// Whether some point lies more than `tol` (m) in front of the plane through `c` with
    /// unit normal `n`, and whether some point lies more than `tol` behind it. Heights are
    /// `n·(p − c)` rounded as [`DVec3::dot`] rounds them.
    pub fn sides(&self, n: DVec3, c: DVec3, tol: f64) -> (bool, bool) {
        let (mut ahead, mut behind) = (false, false);
        for ((x, y), z) in self.x.iter().zip(&self.y).zip(&self.z) {
            let h = (n.x * (x - c.x) + n.y * (y - c.y)) + n.z * (z - c.z);
            ahead |= h > tol;
            behind |= h < -tol;
        }
        (ahead, behind)
    }
}
