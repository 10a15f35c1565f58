//! What the objects are built from: flat plates and grids, boxes, quads, tubes, surfaces of
//! revolution from a sampled profile, and the subdivision of a mesh's triangles. Each
//! `push_*` appends to a mesh with outward winding and one material.

use crate::geometry::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::TAU;

/// Flat `w` x `h` (m) plate centred at the origin in the x-y plane, normal +z, each
/// side split into `cells` so that it has 2·cells² triangles (all one face).
pub fn plate(w: f64, h: f64, cells: u32) -> Mesh {
    let mut mesh = Mesh::default();
    let c = cells.max(1);
    for j in 0..=c {
        for i in 0..=c {
            mesh.vertices.push(DVec3::new(
                w * (i as f64 / c as f64 - 0.5),
                h * (j as f64 / c as f64 - 0.5),
                0.0,
            ));
        }
    }
    for j in 0..c {
        for i in 0..c {
            let a = j * (c + 1) + i;
            let b = a + 1;
            let d = a + c + 1;
            let e = d + 1;
            mesh.triangles.push([a, b, e]);
            mesh.triangles.push([a, e, d]);
        }
    }
    mesh.material_ids = vec![0; mesh.triangles.len()];
    mesh
}

/// Appends an axis-aligned box from `lo` to `hi` (m), outward winding, material `m`.
pub fn push_box(mesh: &mut Mesh, lo: DVec3, hi: DVec3, m: u32) {
    let base = mesh.vertices.len() as u32;
    for k in 0..8u32 {
        mesh.vertices.push(DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        ));
    }
    // quads (counter-clockwise from outside) as corner bit patterns
    const QUADS: [[u32; 4]; 6] = [
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
    ];
    for q in QUADS {
        mesh.triangles.push([base + q[0], base + q[1], base + q[2]]);
        mesh.triangles.push([base + q[0], base + q[2], base + q[3]]);
        mesh.material_ids.extend([m, m]);
    }
}

/// Appends a planar quad with corners `p` (counter-clockwise seen from the side the
/// normal points to), material `m`.
pub fn push_quad(mesh: &mut Mesh, p: [DVec3; 4], m: u32) {
    let base = mesh.vertices.len() as u32;
    mesh.vertices.extend(p);
    mesh.triangles.push([base, base + 1, base + 2]);
    mesh.triangles.push([base, base + 2, base + 3]);
    mesh.material_ids.extend([m, m]);
}

/// Splits every triangle into four, `levels` times (4^levels as many triangles, same
/// surface). Flat faces stay flat, so they still merge into the same faces.
pub fn subdivide(mesh: &Mesh, levels: u32) -> Mesh {
    let mut out = mesh.clone();
    for _ in 0..levels {
        let mut next = Mesh {
            vertices: out.vertices.clone(),
            triangles: Vec::with_capacity(out.triangles.len() * 4),
            material_ids: Vec::with_capacity(out.triangles.len() * 4),
            rounding: out.rounding,
        };
        let mut midpoint = rustc_hash::FxHashMap::default();
        let mut mid = |a: u32, b: u32, v: &mut Vec<DVec3>| -> u32 {
            *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(0.5 * (v[a as usize] + v[b as usize]));
                v.len() as u32 - 1
            })
        };
        for (&[a, b, c], &m) in out.triangles.iter().zip(&out.material_ids) {
            let ab = mid(a, b, &mut next.vertices);
            let bc = mid(b, c, &mut next.vertices);
            let ca = mid(c, a, &mut next.vertices);
            next.triangles
                .extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
            next.material_ids.extend([m; 4]);
        }
        out = next;
    }
    out
}

/// Appends a planar grid: the parallelogram `origin + s·u + t·v` (s, t in [0, 1]) split
/// into `nu` × `nv` cells, 2·nu·nv triangles, normal along u × v, material `m`.
pub fn push_grid_quad(
    mesh: &mut Mesh,
    origin: DVec3,
    u: DVec3,
    v: DVec3,
    nu: u32,
    nv: u32,
    m: u32,
) {
    let (nu, nv) = (nu.max(1), nv.max(1));
    let base = mesh.vertices.len() as u32;
    for j in 0..=nv {
        for i in 0..=nu {
            mesh.vertices
                .push(origin + u * (i as f64 / nu as f64) + v * (j as f64 / nv as f64));
        }
    }
    let at = |i: u32, j: u32| base + j * (nu + 1) + i;
    for j in 0..nv {
        for i in 0..nu {
            mesh.triangles
                .push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            mesh.triangles
                .push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            mesh.material_ids.extend([m, m]);
        }
    }
}

/// Appends an axis-aligned box from `lo` to `hi` (m) with its faces split into a grid of
/// `cells` = [nx, ny, nz] along the axes: closed (the faces' shared edges have the very
/// same vertex positions), outward winding, material `m`.
pub fn push_grid_box(mesh: &mut Mesh, lo: DVec3, hi: DVec3, cells: [u32; 3], m: u32) {
    let cells = cells.map(|c| c.max(1));
    let ticks: Vec<Vec<f64>> = (0..3)
        .map(|a| {
            (0..=cells[a])
                .map(|i| lo[a] + (hi[a] - lo[a]) * (i as f64 / cells[a] as f64))
                .collect()
        })
        .collect();
    for c in 0..3 {
        // in-plane axes a, b with e_a × e_b = e_c
        let (a, b) = ((c + 1) % 3, (c + 2) % 3);
        for side in [0, cells[c] as usize] {
            let base = mesh.vertices.len() as u32;
            let (na, nb) = (cells[a], cells[b]);
            for j in 0..=nb as usize {
                for i in 0..=na as usize {
                    let mut p = DVec3::ZERO;
                    p[a] = ticks[a][i];
                    p[b] = ticks[b][j];
                    p[c] = ticks[c][side];
                    mesh.vertices.push(p);
                }
            }
            let at = |i: u32, j: u32| base + j * (na + 1) + i;
            for j in 0..nb {
                for i in 0..na {
                    let (p, q, r, s) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    if side == 0 {
                        mesh.triangles.extend([[p, r, q], [p, s, r]]);
                    } else {
                        mesh.triangles.extend([[p, q, r], [p, r, s]]);
                    }
                    mesh.material_ids.extend([m, m]);
                }
            }
        }
    }
}

/// Appends a closed `sides`-sided prism of radius `radius` (m) from `a` to `b`, with flat
/// end caps (4·sides triangles), outward winding, material `m`.
pub fn push_tube(mesh: &mut Mesh, a: DVec3, b: DVec3, radius: f64, sides: u32, m: u32) {
    let d = (b - a).normalize();
    let u = d.any_orthonormal_vector();
    let v = d.cross(u);
    let base = mesh.vertices.len() as u32;
    mesh.vertices.extend([a, b]);
    for j in 0..sides {
        let phi = TAU * j as f64 / sides as f64;
        let off = radius * (phi.cos() * u + phi.sin() * v);
        mesh.vertices.extend([a + off, b + off]);
    }
    let (ca, cb) = (base, base + 1);
    let ra = |j: u32| base + 2 + 2 * (j % sides);
    let rb = |j: u32| base + 3 + 2 * (j % sides);
    for j in 0..sides {
        mesh.triangles.extend([
            [ra(j), ra(j + 1), rb(j + 1)],
            [ra(j), rb(j + 1), rb(j)],
            [cb, rb(j), rb(j + 1)],
            [ca, ra(j + 1), ra(j)],
        ]);
        mesh.material_ids.extend([m; 4]);
    }
}

/// Appends the surface swept by turning the profile `(r, z)` (m) about the z axis in
/// `sectors` steps: a point with r = 0 (first or last only) is a pole. Segment k (from
/// point k to k + 1) gets material `materials[k]`. The outside is on the left of the
/// profile's direction in the (r, z) plane (e.g. a profile running down the outer wall, −z
/// at r > 0, faces +r); a profile from pole to pole whose region lies on its right is a
/// closed surface with outward winding.
pub fn push_revolution(mesh: &mut Mesh, profile: &[(f64, f64)], materials: &[u32], sectors: u32) {
    assert_eq!(materials.len() + 1, profile.len());
    let trig: Vec<(f64, f64)> = (0..sectors)
        .map(|j| {
            let phi = TAU * j as f64 / sectors as f64;
            (phi.cos(), phi.sin())
        })
        .collect();
    // first vertex of each profile point (a pole has one)
    let mut first = Vec::with_capacity(profile.len());
    for &(r, z) in profile {
        first.push(mesh.vertices.len() as u32);
        if r == 0.0 {
            mesh.vertices.push(DVec3::new(0.0, 0.0, z));
        } else {
            mesh.vertices
                .extend(trig.iter().map(|&(c, s)| DVec3::new(r * c, r * s, z)));
        }
    }
    for k in 0..profile.len() - 1 {
        let m = materials[k];
        let (pa, pb) = (profile[k].0 == 0.0, profile[k + 1].0 == 0.0);
        let a = |j: u32| first[k] + if pa { 0 } else { j % sectors };
        let b = |j: u32| first[k + 1] + if pb { 0 } else { j % sectors };
        for j in 0..sectors {
            if !pa {
                mesh.triangles.push([a(j), b(j + 1), a(j + 1)]);
                mesh.material_ids.push(m);
            }
            if !pb {
                mesh.triangles.push([a(j), b(j), b(j + 1)]);
                mesh.material_ids.push(m);
            }
        }
    }
}

/// A piece of a profile: the curve `t ∈ [0, 1] → (r, z)`, its segment count and material.
pub type ProfilePiece<'a> = (&'a dyn Fn(f64) -> (f64, f64), u32, u32);

/// Samples a profile made of pieces: each piece is a curve `t ∈ [0, 1] → (r, z)` with the
/// material of its segments, taken at `n` segments; a piece starts where the last ended.
/// Gives the points and the material of each segment, for [`push_revolution`].
pub fn sample_profile(pieces: &[ProfilePiece]) -> (Vec<(f64, f64)>, Vec<u32>) {
    let mut points = Vec::new();
    let mut materials = Vec::new();
    for &(curve, n, m) in pieces {
        let n = n.max(1);
        for i in 0..n {
            points.push(curve(i as f64 / n as f64));
            materials.push(m);
        }
    }
    let &(last, _, _) = pieces.last().expect("a profile has pieces");
    points.push(last(1.0));
    (points, materials)
}
