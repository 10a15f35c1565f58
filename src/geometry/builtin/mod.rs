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
//!
//! | concept | file |
//! |---|---|
//! | the catalogue: [`Detail`], [`Builtin`], [`BUILTINS`], [`find`] | here |
//! | the box-wing | `box_wing.rs` |
//! | the sphere (icosphere, geodesic sphere) | `sphere.rs` |
//! | the classes of the object suite | `rocket_body.rs`, `fragment.rs`, `dish_sat.rs`, `cubesat.rs` |
//! | building blocks: plates, grids, boxes, quads, tubes, surfaces of revolution, subdivision | `parts.rs` |
//! | a mesh as OBJ text | `export.rs` |

use super::mesh::Mesh;

mod box_wing;
pub mod cubesat;
pub mod dish_sat;
mod export;
pub mod fragment;
mod parts;
pub mod rocket_body;
mod sphere;

pub use box_wing::{box_wing, box_wing_with};
pub use export::to_obj;
pub use parts::{
    plate, push_box, push_grid_box, push_grid_quad, push_quad, push_revolution, push_tube,
    sample_profile, subdivide, ProfilePiece,
};
pub use sphere::{geodesic_sphere, icosphere};

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
