//! The Sun as a disk for narrow specular lobes (PHYSICS.md §3, "δ → 0").
//!
//! A point Sun makes the glint of a mirror-smooth face (slope_rms ~1e-4) a spike far
//! narrower than the Sun's disk (angular radius ρ ≈ 4.65e-3 rad at 1 AU): epochs either
//! miss it or hit it by luck. What an observer sees is the Sun's disk reflected by the
//! face, blurred by the lobe. So where a material's lobe is narrow (RMS slope below
//! [`WIDE_LOBE`]·ρ) and the observer is near the glint, the specular part is averaged
//! over [`DISK_POINTS`] directions spread evenly over the disk (a hexagonal pattern of
//! equal weights). Each direction's lobe is widened to [`BLOB`]·ρ when it is narrower,
//! so the samples blend into the disk's image instead of separate spikes; widening
//! keeps each lobe's normalisation, so the reflected energy is unchanged. The diffuse
//! part stays a point evaluation (exact to O(ρ²)), and a wide lobe is left exactly as it
//! is: the disk matters only where the lobe is comparable to or narrower than it.

use super::{Brdf, Frame};
use crate::radiometry::earth::orthonormal_basis;
use glam::DVec3;

/// Lobes with an RMS slope above this many solar radii see the Sun as a point.
pub const WIDE_LOBE: f64 = 4.0;
/// Rings of the hexagonal pattern of directions on the disk.
pub const RINGS: usize = 3;
/// Directions on the disk: 1 + 3·RINGS·(RINGS + 1).
pub const DISK_POINTS: usize = 1 + 3 * RINGS * (RINGS + 1);
/// Smallest lobe RMS slope used for one disk direction, in solar radii. The lobe's
/// width in the observer's angle is √2 times its slope, 0.25 ρ, about 0.8 of the pattern's
/// spacing (0.31 ρ): neighbours blend and the disk's image is flat to 1e-3 (tuned on a
/// mirror's sweep; 0.12–0.21 all keep the energy within 1 %).
pub const BLOB: f64 = 0.18;
/// The specular term is negligible (e^-36 of its peak) this many lobe slopes past the
/// disk's edge, measured in the half vector (so twice that in the Sun's direction).
const TAIL: f64 = 6.0;

/// Offsets of the disk directions in units of the disk radius: every point of a
/// hexagonal lattice within [`RINGS`] rings of the centre, the spacing d chosen so that
/// each point stands for an equal share of the disk's area (π = N·(√3/2)·d²).
fn hex_points() -> &'static [(f64, f64)] {
    static POINTS: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    POINTS.get_or_init(|| {
        let d = (2.0 * std::f64::consts::PI / (DISK_POINTS as f64 * 3f64.sqrt())).sqrt();
        let k = RINGS as i32;
        let mut p = Vec::with_capacity(DISK_POINTS);
        for i in -k..=k {
            for j in -k..=k {
                // axial hex coordinates: inside ring k when the third coordinate is too
                if (i + j).abs() <= k {
                    let x = d * (i as f64 + 0.5 * j as f64);
                    let y = d * (0.75f64.sqrt() * j as f64);
                    p.push((x, y));
                }
            }
        }
        debug_assert_eq!(p.len(), DISK_POINTS);
        p
    })
}

/// f·cosθi·cosθr (sr⁻¹) for sunlight from a disk of angular radius `sun_radius` (rad)
/// centred on `l`, averaged over the disk, towards `v`. Equals `brdf.projected(frame, l, v)`
/// for a point Sun (`sun_radius` = 0), for materials without a narrow lobe, and away
/// from the glint.
pub fn projected(brdf: &Brdf, frame: &Frame, l: DVec3, v: DVec3, sun_radius: f64) -> f64 {
    projected_with(brdf, frame, l, v, sun_radius, BLOB)
}

/// [`projected`] with the smallest lobe slope per disk direction given as `blob` solar
/// radii (for tuning and tests).
#[doc(hidden)]
pub fn projected_with(
    brdf: &Brdf,
    frame: &Frame,
    l: DVec3,
    v: DVec3,
    sun_radius: f64,
    blob: f64,
) -> f64 {
    let point = || brdf.projected(frame, l, v);
    let Some(slope) = brdf.lobe_slope() else {
        return point();
    };
    if sun_radius.is_nan() || sun_radius <= 0.0 || slope > WIDE_LOBE * sun_radius {
        return point();
    }
    let blob = slope.max(blob * sun_radius);
    // The Sun direction that would mirror into `v`; the glint lives within the disk
    // radius plus the lobe's reach of it.
    let n = frame.n;
    let mirror = 2.0 * n.dot(v) * n - v;
    let off = mirror.cross(l).length().atan2(mirror.dot(l));
    if n.dot(v) <= 0.0 || off > sun_radius + 2.0 * TAIL * blob {
        return point();
    }
    let diffuse = brdf.split(true).projected(frame, l, v);
    let spec = brdf.split(false);
    let spec = if blob > slope {
        spec.widened(blob)
    } else {
        spec
    };
    let (a, b) = orthonormal_basis(l);
    let sum: f64 = hex_points()
        .iter()
        .map(|&(x, y)| {
            // the point at angle r·ρ from the centre towards (x, y): exact on the sphere
            let r = (x * x + y * y).sqrt();
            let dir = if r == 0.0 {
                l
            } else {
                let (sr, cr) = (r * sun_radius).sin_cos();
                l * cr + (a * x + b * y) * (sr / r)
            };
            spec.projected(frame, dir, v)
        })
        .sum();
    diffuse + sum / DISK_POINTS as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_points_fill_the_disk_evenly() {
        let p = hex_points();
        assert_eq!(p.len(), DISK_POINTS);
        // mean at the centre, mean square r² = 1/2 of a uniform unit disk within 10 %
        let (mx, my) = p.iter().fold((0.0, 0.0), |a, q| (a.0 + q.0, a.1 + q.1));
        assert!(mx.abs() < 1e-12 && my.abs() < 1e-12);
        let r2 = p.iter().map(|q| q.0 * q.0 + q.1 * q.1).sum::<f64>() / DISK_POINTS as f64;
        assert!((r2 - 0.5).abs() < 0.05, "mean r² {r2}");
        assert!(p.iter().all(|q| q.0.hypot(q.1) < 1.0));
    }
}
