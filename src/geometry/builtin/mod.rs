//! Objects shipped with glint, built procedurally. `scenes/objects/*.obj` are exports of
//! these at their default detail (a test keeps them in sync), so users can start from a
//! file too.
//!
//! Every object comes at three tessellations ([`Detail`]): `coarse` (≈2k triangles),
//! `medium` (≈20k) and `fine` (≈200k). The classes of this module's submodules default to
//! `medium`; the first three objects (`box-wing`, `sphere`, `plate`) default to the mesh
//! they always had, so requests that name no detail give the same light curves as before:
//!
//! | object | coarse | medium | fine |
//! |---|---|---|---|
//! | `box-wing` | 5 × 24 dish, 268 (default) | 48 × 128 dish, flat parts subdivided 3×, 15 488 | 160 × 400 dish, flat parts 5×, 180 848 |
//! | `sphere` | icosphere, 1 280 (default) | geodesic frequency 32, 20 480 | frequency 100, 200 000 |
//! | `plate` | 2 (default) | 100 × 100 cells, 20 000 | 316 × 316 cells, 199 712 |
//!
//! and see each class's module for its own.

use super::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::TAU;

pub mod cubesat;
pub mod dish_sat;
pub mod fragment;
pub mod rocket_body;

/// How finely a built-in object is tessellated: about 2k, 20k or 200k triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Detail {
    Coarse,
    Medium,
    Fine,
}

impl Detail {
    /// The three levels, coarsest first.
    pub const ALL: [Detail; 3] = [Detail::Coarse, Detail::Medium, Detail::Fine];

    /// The level called `name` (`coarse`, `medium` or `fine`).
    pub fn parse(name: &str) -> Option<Detail> {
        Detail::ALL.into_iter().find(|d| d.name() == name)
    }

    /// Its name in requests.
    pub fn name(self) -> &'static str {
        match self {
            Detail::Coarse => "coarse",
            Detail::Medium => "medium",
            Detail::Fine => "fine",
        }
    }

    /// One of three values, by level.
    pub fn pick<T>(self, coarse: T, medium: T, fine: T) -> T {
        match self {
            Detail::Coarse => coarse,
            Detail::Medium => medium,
            Detail::Fine => fine,
        }
    }
}

/// A built-in object: its mesh at a [`Detail`] level and the material names its
/// triangles use, in the order of the mesh's material ids.
pub struct Builtin {
    pub name: &'static str,
    pub description: &'static str,
    pub material_names: &'static [&'static str],
    /// The level a request that names none gets.
    pub default_detail: Detail,
    pub build: fn(Detail) -> Mesh,
}

impl Builtin {
    /// The mesh at the default detail.
    pub fn mesh(&self) -> Mesh {
        (self.build)(self.default_detail)
    }
}

/// Every built-in object.
pub const BUILTINS: &[Builtin] = &[
    Builtin {
        name: "box-wing",
        description: "2 m cube bus (material `body`), two 5 m x 2 m solar panels on booms \
                      along ±y (`panel`, thin: use two_sided), a 1.6 m parabolic dish on the +z face \
                      (`dish`, thin: use two_sided); detail coarse (default) 268 triangles, \
                      medium 15.5k (the fine-dish box-wing), fine 181k",
        material_names: &["body", "panel", "dish"],
        default_detail: Detail::Coarse,
        build: |d| match d {
            Detail::Coarse => box_wing(),
            Detail::Medium => box_wing_with(48, 128, 3),
            Detail::Fine => box_wing_with(160, 400, 5),
        },
    },
    Builtin {
        name: "sphere",
        description: "sphere of radius 1 m (`surface`); detail coarse (default) icosphere with \
                      1280 triangles, medium 20480, fine 200000",
        material_names: &["surface"],
        default_detail: Detail::Coarse,
        build: |d| match d {
            Detail::Coarse => icosphere(3, 1.0),
            Detail::Medium => geodesic_sphere(32, 1.0),
            Detail::Fine => geodesic_sphere(100, 1.0),
        },
    },
    Builtin {
        name: "plate",
        description: "flat 1 m x 1 m plate in the x-y plane, normal +z (`surface`); detail \
                      coarse (default) 2 triangles, medium 20000, fine 199712",
        material_names: &["surface"],
        default_detail: Detail::Coarse,
        build: |d| plate(1.0, 1.0, d.pick(1, 100, 316)),
    },
    rocket_body::BUILTIN,
    fragment::BUILTIN,
    dish_sat::BUILTIN,
    cubesat::BUILTIN,
];

/// The built-in object called `name`.
pub fn find(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

/// Writes a mesh as OBJ text with `usemtl` groups named by `material_names`.
pub fn to_obj(mesh: &Mesh, material_names: &[&str], comment: &str) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    for line in comment.lines() {
        let _ = writeln!(s, "# {line}");
    }
    for v in &mesh.vertices {
        let _ = writeln!(s, "v {} {} {}", v.x, v.y, v.z);
    }
    let mut current = u32::MAX;
    for (tri, &m) in mesh.triangles.iter().zip(&mesh.material_ids) {
        if m != current {
            let _ = writeln!(s, "usemtl {}", material_names[m as usize]);
            current = m;
        }
        let _ = writeln!(s, "f {} {} {}", tri[0] + 1, tri[1] + 1, tri[2] + 1);
    }
    s
}

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
        let mut midpoint = std::collections::HashMap::new();
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
    }
}

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

/// The box-wing satellite: the usual test object of this field.
pub fn box_wing() -> Mesh {
    box_wing_with(5, 24, 0)
}

/// The box-wing with its dish tessellated into `rings` × `sectors` (curved: one face per
/// triangle) and its flat parts subdivided `flat_levels` times (they still merge into the
/// same faces). Benchmarks use this for the ~15k-triangle object of the performance targets.
pub fn box_wing_with(rings: u32, sectors: u32, flat_levels: u32) -> Mesh {
    let mut mesh = Mesh::default();
    // bus: 2 m cube
    push_box(&mut mesh, DVec3::splat(-1.0), DVec3::splat(1.0), 0);
    // booms: 0.1 m square, from the bus to the panels
    for s in [-1.0, 1.0] {
        let (y0, y1) = if s > 0.0 { (1.0, 1.5) } else { (-1.5, -1.0) };
        push_box(
            &mut mesh,
            DVec3::new(-0.05, y0, -0.05),
            DVec3::new(0.05, y1, 0.05),
            0,
        );
    }
    // panels: 5 m x 2 m in the x = 0 plane, normal +x (two-sided material)
    for s in [-1.0, 1.0] {
        let (y0, y1) = if s > 0.0 { (1.5, 6.5) } else { (-6.5, -1.5) };
        push_quad(
            &mut mesh,
            [
                DVec3::new(0.0, y0, -1.0),
                DVec3::new(0.0, y1, -1.0),
                DVec3::new(0.0, y1, 1.0),
                DVec3::new(0.0, y0, 1.0),
            ],
            1,
        );
    }
    // dish: paraboloid z = z0 + r²/(4f), rim radius 0.8 m, opening +z, on a mast
    push_box(
        &mut mesh,
        DVec3::new(-0.05, -0.05, 1.0),
        DVec3::new(0.05, 0.05, 1.2),
        0,
    );
    let mut mesh = subdivide(&mesh, flat_levels);
    let (z0, f, rim) = (1.2, 0.8, 0.8);
    let base = mesh.vertices.len() as u32;
    mesh.vertices.push(DVec3::new(0.0, 0.0, z0));
    for i in 1..=rings {
        let r = rim * i as f64 / rings as f64;
        for j in 0..sectors {
            let phi = TAU * j as f64 / sectors as f64;
            mesh.vertices.push(DVec3::new(
                r * phi.cos(),
                r * phi.sin(),
                z0 + r * r / (4.0 * f),
            ));
        }
    }
    let ring = |i: u32, j: u32| base + 1 + (i - 1) * sectors + (j % sectors);
    for j in 0..sectors {
        // concave side faces +z: counter-clockwise seen from above
        mesh.triangles.push([base, ring(1, j), ring(1, j + 1)]);
        mesh.material_ids.push(2);
    }
    for i in 1..rings {
        for j in 0..sectors {
            mesh.triangles
                .push([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)]);
            mesh.triangles
                .push([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
            mesh.material_ids.extend([2, 2]);
        }
    }
    mesh
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
        };
        let mut midpoint = std::collections::HashMap::new();
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

/// The sphere of radius `r` (m) as a geodesic polyhedron of frequency `n`: each face of
/// an icosahedron split into n² triangles, vertices pushed onto the sphere (20·n²
/// triangles, outward winding, closed).
pub fn geodesic_sphere(n: u32, r: f64) -> Mesh {
    let ico = icosphere(0, 1.0);
    let n = n.max(1);
    let mut mesh = Mesh::default();
    // a point by its icosahedron corners and integer weights, sorted: the same key from
    // every face that shares it
    let mut index: std::collections::HashMap<[(u32, u32); 3], u32> = Default::default();
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

/// Checks shared by the classes' tests.
#[cfg(test)]
pub(crate) mod checks {
    use super::*;

    /// The triangles whose material is in `materials`, as a mesh of their own.
    pub fn part(mesh: &Mesh, materials: &[u32]) -> Mesh {
        let mut out = Mesh {
            vertices: mesh.vertices.clone(),
            ..Mesh::default()
        };
        for (t, &m) in mesh.triangles.iter().zip(&mesh.material_ids) {
            if materials.contains(&m) {
                out.triangles.push(*t);
                out.material_ids.push(m);
            }
        }
        out
    }

    /// Every welded edge is used by exactly two triangles, once in each direction (a
    /// closed, consistently wound surface), and the enclosed volume is positive (outward).
    pub fn assert_closed_outward(mesh: &Mesh, what: &str) {
        let welded = mesh.welded_ids();
        let mut directed: Vec<(u32, u32)> = Vec::new();
        for tri in &mesh.triangles {
            for k in 0..3 {
                directed.push((welded[tri[k] as usize], welded[tri[(k + 1) % 3] as usize]));
            }
        }
        directed.sort_unstable();
        for w in directed.windows(2) {
            assert_ne!(
                w[0], w[1],
                "{what}: edge {:?} used twice the same way",
                w[0]
            );
        }
        for &(a, b) in &directed {
            assert!(
                directed.binary_search(&(b, a)).is_ok(),
                "{what}: edge {a}-{b} has no twin"
            );
        }
        assert!(volume(mesh) > 0.0, "{what}: inward");
    }

    /// Signed volume enclosed by the triangles, m³.
    pub fn volume(mesh: &Mesh) -> f64 {
        (0..mesh.triangles.len())
            .map(|i| {
                let [a, b, c] = mesh.corners(i);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// No triangle with a tiny area (relative to its longest edge) and no two triangles
    /// on the same three welded vertices.
    pub fn assert_clean(mesh: &Mesh, what: &str) {
        let welded = mesh.welded_ids();
        let mut seen = std::collections::HashSet::new();
        for i in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.corners(i);
            let longest = (b - a).length().max((c - b).length()).max((a - c).length());
            let area2 = mesh.area_vector(i).length();
            assert!(
                area2 > 1e-6 * longest * longest,
                "{what}: triangle {i} degenerate"
            );
            let mut key = mesh.triangles[i].map(|v| welded[v as usize]);
            key.sort_unstable();
            assert!(seen.insert(key), "{what}: triangle {i} duplicated");
        }
        assert_eq!(mesh.triangles.len(), mesh.material_ids.len());
    }

    /// The builtin's triangle count at each level is within 30 % of 2k, 20k and 200k,
    /// every level is clean and the build is deterministic.
    pub fn assert_levels(b: &Builtin) {
        for (d, want) in Detail::ALL.into_iter().zip([2_000.0, 20_000.0, 200_000.0]) {
            let mesh = (b.build)(d);
            let n = mesh.triangles.len() as f64;
            assert!(
                (n / want - 1.0).abs() < 0.3,
                "{} {}: {n} triangles",
                b.name,
                d.name()
            );
            assert_clean(&mesh, b.name);
            assert!(mesh
                .material_ids
                .iter()
                .all(|&m| (m as usize) < b.material_names.len()));
            for m in 0..b.material_names.len() as u32 {
                assert!(
                    mesh.material_ids.contains(&m),
                    "{}: material {m} unused",
                    b.name
                );
            }
            if d == Detail::Coarse {
                assert_eq!(mesh, (b.build)(d), "{}: not deterministic", b.name);
            }
        }
    }
}
