//! Objects shipped with glint, built procedurally. `scenes/objects/*.obj` are exports of
//! these (a test keeps them in sync), so users can start from a file too.

use super::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::TAU;

/// A built-in object: its mesh and the material names its triangles use, in the order
/// of the mesh's material ids.
pub struct Builtin {
    pub name: &'static str,
    pub description: &'static str,
    pub material_names: &'static [&'static str],
    pub build: fn() -> Mesh,
}

/// Every built-in object.
pub const BUILTINS: &[Builtin] = &[
    Builtin {
        name: "box-wing",
        description: "2 m cube bus (material `body`), two 5 m x 2 m solar panels on booms \
                      along ±y (`panel`, thin: use two_sided), a 1.6 m parabolic dish on the +z face \
                      (`dish`, thin: use two_sided)",
        material_names: &["body", "panel", "dish"],
        build: box_wing,
    },
    Builtin {
        name: "sphere",
        description: "sphere of radius 1 m, icosphere with 1280 triangles (`surface`)",
        material_names: &["surface"],
        build: || icosphere(3, 1.0),
    },
    Builtin {
        name: "plate",
        description: "flat 1 m x 1 m plate in the x-y plane, normal +z, 2 triangles (`surface`)",
        material_names: &["surface"],
        build: || plate(1.0, 1.0, 1),
    },
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
