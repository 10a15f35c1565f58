//! `rocket-body`: a spent upper stage, 3.0 m in diameter and 9.0 m long, axis along z
//! with the nose at +z.
//!
//! From the front: an elliptical forward dome (1.2 m high) on the tank, a 5.3 m cylinder
//! (material `body`), a 1.5 m aft skirt (`skirt`) open at the back, 3 cm thick (outer and
//! inner wall joined at the rim), inside it the tank's aft bulkhead (`body`), an
//! elliptical dome 0.7 m deep, and on the bulkhead the engine (`nozzle`): a 0.3 m
//! combustion chamber, a throat of 0.14 m radius and a bell to a 0.88 m exit radius at
//! z = −1.0 m, 1 m beyond the skirt. The nozzle has a 2 cm wall: its inside is a surface of
//! its own, lit and seen through the exit, so no material needs to be two-sided.
//!
//! The whole stage is one closed surface of revolution (z from −1.0 to 8.0 m): coarse 24
//! sectors × 44 profile segments (2 064 triangles), medium 80 × 126 (20 000), fine 256 ×
//! 392 (200 192); the curved parts (domes, nozzle) get most of the profile's points.

use super::{push_revolution, sample_profile, Builtin, Detail};
use crate::geometry::mesh::Mesh;
use std::f64::consts::FRAC_PI_2;

pub const BUILTIN: Builtin = Builtin {
    name: "rocket-body",
    description: "spent upper stage, 3 m diameter x 9 m long along z (nose +z): tank with \
                  forward dome (`body`), 1.5 m aft skirt open at the back with 3 cm walls \
                  (`skirt`), aft bulkhead dome (`body`) and an engine bell with a 2 cm wall, \
                  0.88 m exit radius (`nozzle`); closed; detail coarse 2k, medium (default) \
                  20k, fine 200k triangles",
    material_names: &["body", "skirt", "nozzle"],
    default_detail: Detail::Medium,
    build,
};

const R: f64 = 1.5;
const SKIRT_T: f64 = 0.03;
const NOSE_Z: f64 = 6.8;
const NOSE_H: f64 = 1.2;
const BULKHEAD_Z: f64 = 1.5;
const BULKHEAD_DEPTH: f64 = 0.7;
const WALL: f64 = 0.02;
const CHAMBER_R: f64 = 0.35;
const THROAT_R: f64 = 0.14;
const EXIT_R: f64 = 0.88;
const EXIT_Z: f64 = -1.0;

/// Inner radius of the engine at height z, from the bulkhead down to the exit.
fn nozzle_radius(z: f64, top: f64) -> f64 {
    let chamber_end = top - 0.3;
    let throat = top - 0.5;
    if z >= chamber_end {
        CHAMBER_R
    } else if z >= throat {
        let u = (chamber_end - z) / (chamber_end - throat);
        THROAT_R + (CHAMBER_R - THROAT_R) * 0.5 * (1.0 + (std::f64::consts::PI * u).cos())
    } else {
        let u = (throat - z) / (throat - EXIT_Z);
        THROAT_R + (EXIT_R - THROAT_R) * (0.7 * (1.0 - (1.0 - u) * (1.0 - u)) + 0.3 * u)
    }
}

/// The stage at `detail`.
pub fn build(detail: Detail) -> Mesh {
    let (profile, materials, sectors) = profile(detail);
    let mut mesh = Mesh::default();
    push_revolution(&mut mesh, &profile, &materials, sectors);
    mesh
}

/// The stage's profile at `detail`: (radius, z) points (m) from the nose tip round to the
/// centre of the engine's inner top plate, each segment's material, and the sectors it
/// is revolved in.
fn profile(detail: Detail) -> (Vec<(f64, f64)>, Vec<u32>, u32) {
    let (sectors, scale) = detail.pick((24, 1.0), (80, 3.0), (256, 9.4));
    let n = |w: f64| ((w * scale).round() as u32).max(1);
    let rb = R - SKIRT_T;
    // where the bulkhead meets the engine's outer wall
    let attach = (CHAMBER_R + WALL) / rb;
    let alpha = attach.acos();
    let top = BULKHEAD_Z - BULKHEAD_DEPTH * alpha.sin();
    let inner_top = top - 0.05;
    let nose = |t: f64| {
        let th = t * FRAC_PI_2;
        (R * th.sin(), NOSE_Z + NOSE_H * th.cos())
    };
    let cylinder = |t: f64| (R, NOSE_Z + (BULKHEAD_Z - NOSE_Z) * t);
    let skirt_out = |t: f64| (R, BULKHEAD_Z * (1.0 - t));
    let rim = |t: f64| (R - SKIRT_T * t, 0.0);
    let skirt_in = |t: f64| (rb, BULKHEAD_Z * t);
    let bulkhead = |t: f64| {
        let a = alpha * t;
        (rb * a.cos(), BULKHEAD_Z - BULKHEAD_DEPTH * a.sin())
    };
    // The engine's walls, sampled at the same heights below the inner wall's top, so that
    // the wall is WALL thick between the samples too: sampled at other heights, the
    // inner wall's chords cut through the outer wall's at the throat (a narrow waist a
    // chord straddles lies inside it), and the surface crossed itself there.
    let outer_top = |t: f64| (CHAMBER_R + WALL, top + (inner_top - top) * t);
    let outer = |t: f64| {
        let z = inner_top + (EXIT_Z - inner_top) * t;
        (nozzle_radius(z, top) + WALL, z)
    };
    let exit = |t: f64| (EXIT_R + WALL * (1.0 - t), EXIT_Z);
    let inner = |t: f64| {
        let z = EXIT_Z + (inner_top - EXIT_Z) * t;
        (nozzle_radius(z, top), z)
    };
    let plate = |t: f64| (CHAMBER_R * (1.0 - t), inner_top);
    let (profile, materials) = sample_profile(&[
        (&nose, n(8.0), 0),
        (&cylinder, n(4.0), 0),
        (&skirt_out, n(2.0), 1),
        (&rim, n(0.34), 1),
        (&skirt_in, n(2.0), 1),
        (&bulkhead, n(6.0), 0),
        (&outer_top, 1, 2),
        (&outer, n(8.5), 2),
        (&exit, n(0.34), 2),
        (&inner, n(8.5), 2),
        // one segment fewer than the walls' share, for the outer wall's top
        (&plate, n(2.0) - 1, 2),
    ]);
    (profile, materials, sectors)
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;
    use crate::geometry::polygon::segment_distance;
    use glam::DVec2;

    #[test]
    fn three_levels_of_a_closed_outward_stage() {
        assert_levels(&BUILTIN);
        for d in Detail::ALL {
            let mesh = build(d);
            assert_closed_outward(&mesh, d.name());
            let (lo, hi) = mesh.vertices.iter().fold(
                (
                    glam::DVec3::splat(f64::INFINITY),
                    glam::DVec3::splat(f64::NEG_INFINITY),
                ),
                |(lo, hi), v| (lo.min(*v), hi.max(*v)),
            );
            assert!((hi.z - lo.z - 9.0).abs() < 1e-9 && (hi.x - lo.x - 3.0).abs() < 1e-9);
            // the tank's volume dominates: ~π·1.5²·(5.3 + 1.5 + 0.8 − 0.47) m³
            let v = volume(&mesh);
            assert!((40.0..55.0).contains(&v), "{v}");
        }
    }

    #[test]
    fn the_surface_never_crosses_itself() {
        // A surface of revolution crosses itself exactly where its profile does: every
        // sector maps the (r, z) half-plane into the body by one scaling of r (the point
        // of its chord), one to one. So no two segments of the profile that share no
        // point may meet (within a micron). Sampled at other heights, the engine's
        // inner wall cut through its outer wall at the throat at coarse and medium detail.
        for d in Detail::ALL {
            let (profile, _, _) = profile(d);
            let p: Vec<DVec2> = profile.iter().map(|&(r, z)| DVec2::new(r, z)).collect();
            assert!(p.iter().all(|q| q.x >= 0.0), "{}", d.name());
            for i in 0..p.len() - 1 {
                for j in i + 2..p.len() - 1 {
                    let gap = segment_distance(p[i], p[i + 1], p[j], p[j + 1]);
                    assert!(
                        gap > 1e-6,
                        "{}: segments {i} and {j} are {gap:.2e} m apart",
                        d.name()
                    );
                }
            }
        }
    }

    #[test]
    fn the_nozzle_narrows_to_its_throat_and_opens_at_the_exit() {
        let top = 0.82;
        assert_eq!(nozzle_radius(top, top), CHAMBER_R);
        assert!((nozzle_radius(top - 0.5, top) - THROAT_R).abs() < 1e-12);
        assert!((nozzle_radius(EXIT_Z, top) - EXIT_R).abs() < 1e-12);
    }
}
