//! `fragment`: a crumpled piece of debris, about 1.8 m × 1.1 m × 0.5 m (material
//! `surface`).
//!
//! A geodesic sphere whose radius in each direction is displaced by seeded multi-octave
//! value noise (dents and bumps) and ridged noise (creases), then flattened into a slab
//! (0.85, 0.5, 0.22 m semi-axes), bent along its length and twisted about it. The
//! displacement is radial and the flattening, bend and twist are one-to-one maps, so the
//! surface stays closed, outward and free of self-intersection; nothing on it is flat and
//! no large part of it is convex. The seed is fixed: every build is the same mesh.
//!
//! Geodesic frequency 10, 32 and 100: coarse 2 000, medium (default) 20 480, fine 200 000
//! triangles.

use super::{geodesic_sphere, Builtin, Detail};
use crate::geometry::mesh::Mesh;
use glam::DVec3;

pub const BUILTIN: Builtin = Builtin {
    name: "fragment",
    description: "crumpled debris fragment, about 1.8 m x 1.1 m x 0.5 m, seeded dents, bumps \
                  and creases on every side, bent and twisted (`surface`); closed; detail \
                  coarse 2000, medium (default) 20480, fine 200000 triangles",
    material_names: &["surface"],
    default_detail: Detail::Medium,
    build,
};

const SEED: u64 = 0x5eed_f4a9_2026;

/// A value in [−1, 1] for an integer lattice point.
fn lattice(i: i64, j: i64, k: i64, octave: u64) -> f64 {
    // splitmix64 over the packed coordinates
    let mut x = SEED
        ^ (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
        ^ (j as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f)
        ^ (k as u64).wrapping_mul(0x1656_67b1_9e37_79f9)
        ^ octave.wrapping_mul(0x27d4_eb2f_1656_67c5);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^= x >> 31;
    (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// Smooth value noise in [−1, 1] (quintic interpolation of the lattice values).
fn noise(p: DVec3, octave: u64) -> f64 {
    let f = p.floor();
    let (i, j, k) = (f.x as i64, f.y as i64, f.z as i64);
    let t = p - f;
    let s = t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let mut acc = 0.0;
    for c in 0..8 {
        let (di, dj, dk) = ((c & 1) as i64, ((c >> 1) & 1) as i64, ((c >> 2) & 1) as i64);
        let w = if di == 1 { s.x } else { 1.0 - s.x }
            * if dj == 1 { s.y } else { 1.0 - s.y }
            * if dk == 1 { s.z } else { 1.0 - s.z };
        acc += w * lattice(i + di, j + dj, k + dk, octave);
    }
    acc
}

/// The relative radius in unit direction `d`: 1 plus dents, bumps and creases.
fn radius(d: DVec3) -> f64 {
    // bumps and dents: five octaves, amplitude halving, frequency doubling
    let mut fbm = 0.0;
    let (mut amp, mut freq) = (0.5, 1.6);
    for o in 0..5 {
        fbm += amp * noise(d * freq + DVec3::splat(17.3), o);
        amp *= 0.5;
        freq *= 2.03;
    }
    // creases: sharp valleys where ridged noise crosses zero
    let mut ridged = 0.0;
    let (mut amp, mut freq) = (0.5, 2.2);
    for o in 10..13 {
        ridged += amp * (1.0 - noise(d * freq - DVec3::splat(5.1), o).abs());
        amp *= 0.5;
        freq *= 2.1;
    }
    1.0 + 0.3 * fbm - 0.22 * (ridged - 0.5)
}

/// The fragment at `detail`.
pub fn build(detail: Detail) -> Mesh {
    let sphere = geodesic_sphere(detail.pick(10, 32, 100), 1.0);
    sphere.transformed(|d| {
        let p = d * radius(d) * DVec3::new(0.85, 0.5, 0.22);
        // bend along x, then twist about x
        let u = p.x / 0.85;
        let bent = DVec3::new(p.x, p.y + 0.08 * u, p.z + 0.22 * u * u - 0.1 * u * u * u);
        let (s, c) = (0.45 * u).sin_cos();
        DVec3::new(bent.x, c * bent.y - s * bent.z, s * bent.y + c * bent.z)
    })
}

#[cfg(test)]
mod tests {
    use super::super::checks::*;
    use super::*;

    #[test]
    fn three_levels_of_a_closed_outward_crumpled_slab() {
        assert_levels(&BUILTIN);
        for d in Detail::ALL {
            let mesh = build(d);
            assert_closed_outward(&mesh, d.name());
            let (c, r) = mesh.bounding_sphere();
            assert!(c.length() < 0.4 && (0.7..1.3).contains(&r), "{c} {r}");
        }
    }

    #[test]
    fn nothing_is_flat_and_it_is_far_from_convex() {
        let mesh = build(Detail::Medium);
        // neighbouring triangles' normals differ: no flat patch of merged triangles
        let (_, edges) = mesh.welded_edges();
        let normal = |t: u32| mesh.area_vector(t as usize).normalize();
        let flat = edges
            .windows(2)
            .filter(|w| (w[0].0, w[0].1) == (w[1].0, w[1].1))
            .filter(|w| normal(w[0].2).dot(normal(w[1].2)) > 1.0 - 1e-9)
            .count();
        assert!(flat * 100 < mesh.triangles.len(), "{flat} flat edges");
        // the volume is well below its convex hull's: its bounding box's is a bound
        let v = volume(&mesh);
        let hull_bound = {
            let (lo, hi) = mesh.vertices.iter().fold(
                (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                |(lo, hi), v| (lo.min(*v), hi.max(*v)),
            );
            let e = hi - lo;
            e.x * e.y * e.z
        };
        assert!(v > 0.0 && v < 0.45 * hull_bound, "{v} vs box {hull_bound}");
    }

    #[test]
    fn the_noise_is_smooth_and_bounded() {
        for i in 0..1000 {
            let p = DVec3::new(
                i as f64 * 0.137,
                i as f64 * 0.071 - 3.0,
                (i % 17) as f64 * 0.3,
            );
            let a = noise(p, 0);
            assert!((-1.0..=1.0).contains(&a));
            assert!((noise(p + DVec3::splat(1e-6), 0) - a).abs() < 1e-4);
        }
    }
}
