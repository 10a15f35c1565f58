//! The sphere: an icosphere (the `sphere` object's coarse mesh) and a geodesic sphere of
//! any frequency (its medium and fine meshes, and the fragment's base).

use crate::geometry::mesh::Mesh;
use glam::DVec3;

/// Icosphere of radius `r` (m): an icosahedron subdivided `level` times (20·4^level
/// triangles), vertices on the sphere, outward winding.
pub fn icosphere(level: u32, r: f64) -> Mesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut vertices: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mut midpoint = rustc_hash::FxHashMap::default();
        let mut mid = |a: u32, b: u32, vertices: &mut Vec<DVec3>| -> u32 {
            *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                vertices.push((vertices[a as usize] + vertices[b as usize]).normalize());
                vertices.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(triangles.len() * 4);
        for [a, b, c] in triangles {
            let ab = mid(a, b, &mut vertices);
            let bc = mid(b, c, &mut vertices);
            let ca = mid(c, a, &mut vertices);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = next;
    }
    let n = triangles.len();
    Mesh {
        vertices: vertices.into_iter().map(|v| v * r).collect(),
        triangles,
        material_ids: vec![0; n],
        rounding: 0.0,
    }
}

/// The sphere of radius `r` (m) as a geodesic polyhedron of frequency `n`: each face of
/// an icosahedron split into n² triangles, vertices pushed onto the sphere (20·n²
/// triangles, outward winding, closed).
pub fn geodesic_sphere(n: u32, r: f64) -> Mesh {
    let ico = icosphere(0, 1.0);
    let n = n.max(1);
    let mut mesh = Mesh::default();
    // a point by its icosahedron corners and integer weights, sorted: the same key from
    // every face that shares it
    let mut index: rustc_hash::FxHashMap<[(u32, u32); 3], u32> = Default::default();
    for tri in &ico.triangles {
        let mut id = |i: u32, j: u32| -> u32 {
            let mut key = [(tri[0], n - i - j), (tri[1], i), (tri[2], j)].map(|(v, w)| {
                if w == 0 {
                    (u32::MAX, 0)
                } else {
                    (v, w)
                }
            });
            key.sort_unstable();
            *index.entry(key).or_insert_with(|| {
                let p = key
                    .iter()
                    .filter(|(v, _)| *v != u32::MAX)
                    .fold(DVec3::ZERO, |s, &(v, w)| {
                        s + ico.vertices[v as usize] * w as f64
                    });
                mesh.vertices.push(p.normalize() * r);
                mesh.vertices.len() as u32 - 1
            })
        };
        for i in 0..n {
            for j in 0..n - i {
                let (a, b, c) = (id(i, j), id(i + 1, j), id(i, j + 1));
                mesh.triangles.push([a, b, c]);
                if i + j + 1 < n {
                    let d = id(i + 1, j + 1);
                    mesh.triangles.push([b, d, c]);
                }
            }
        }
    }
    mesh.material_ids = vec![0; mesh.triangles.len()];
    mesh
}
