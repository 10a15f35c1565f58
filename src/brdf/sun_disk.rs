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

use super::{Brdf, Directions, Fixed, Frame};
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

/// The Sun (a disk) and the observer fixed for one epoch and material: [`projected`]
/// for many faces, with what does not depend on the face computed once (the Fresnel
/// terms of the point Sun and of every disk direction). Faces away from the glint
/// (almost all) cost one point-Sun evaluation.
#[derive(Debug, Clone)]
pub struct SunLight<'a> {
    point: Fixed<'a>,
    v: DVec3,
    l: DVec3,
    /// Present when the disk can matter (a narrow lobe and a Sun of some size).
    disk: Option<Disk>,
}

#[derive(Debug, Clone)]
struct Disk {
    /// cos of the angle from the mirror direction beyond which the disk cannot matter.
    cos_reach: f64,
    diffuse: Brdf,
    diffuse_dirs: Directions,
    /// The specular part, widened to the blob's slope where narrower.
    spec: Brdf,
    spec_dirs: Vec<Directions>,
}

impl<'a> SunLight<'a> {
    pub fn new(brdf: &'a Brdf, l: DVec3, v: DVec3, sun_radius: f64) -> SunLight<'a> {
        let disk = match brdf.lobe_slope() {
            Some(slope)
                if !sun_radius.is_nan() && sun_radius > 0.0 && slope <= WIDE_LOBE * sun_radius =>
            {
                let blob = slope.max(BLOB * sun_radius);
                let reach = sun_radius + 2.0 * TAIL * blob;
                let diffuse = brdf.split(true);
                let spec = brdf.split(false);
                let spec = if blob > slope {
                    spec.widened(blob)
                } else {
                    spec
                };
                let spec_dirs = disk_directions(l, sun_radius)
                    .map(|d| Directions::new(&spec, d, v))
                    .collect();
                Some(Disk {
                    cos_reach: if reach >= std::f64::consts::PI {
                        -1.0
                    } else {
                        reach.cos()
                    },
                    diffuse_dirs: Directions::new(&diffuse, l, v),
                    diffuse,
                    spec,
                    spec_dirs,
                })
            }
            _ => None,
        };
        SunLight {
            point: Fixed::new(brdf, l, v),
            v,
            l,
            disk,
        }
    }

    /// [`projected`] for a face with this frame, sr⁻¹ (the same value, computed faster).
    #[inline]
    pub fn projected(&self, frame: &Frame) -> f64 {
        self.projected_given(frame, frame.n.dot(self.v))
    }

    /// [`SunLight::projected`] given `cr` = n·v, which the caller already has.
    #[inline]
    pub fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        if let Some(disk) = &self.disk {
            let n = frame.n;
            // near the glint: the test of `projected_with`, by cosines
            if cr > 0.0 && (2.0 * cr * n - self.v).dot(self.l) >= disk.cos_reach {
                return disk.projected_given(frame, cr);
            }
        }
        self.point.projected_given(frame, cr)
    }
}

impl Disk {
    /// The disk's average near the glint, sr⁻¹.
    #[inline]
    fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        let sum: f64 = self
            .spec_dirs
            .iter()
            .map(|d| d.projected_given(&self.spec, frame, cr))
            .sum();
        self.diffuse_dirs.projected_given(&self.diffuse, frame, cr) + sum / DISK_POINTS as f64
    }
}

/// The [`DISK_POINTS`] directions spread evenly over the disk of angular radius
/// `sun_radius` (rad) about `l`.
fn disk_directions(l: DVec3, sun_radius: f64) -> impl Iterator<Item = DVec3> {
    let (a, b) = orthonormal_basis(l);
    hex_points().iter().map(move |&(x, y)| {
        // the point at angle r·ρ from the centre towards (x, y): exact on the sphere
        let r = (x * x + y * y).sqrt();
        if r == 0.0 {
            l
        } else {
            let (sr, cr) = (r * sun_radius).sin_cos();
            l * cr + (a * x + b * y) * (sr / r)
        }
    })
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
    let sum: f64 = disk_directions(l, sun_radius)
        .map(|dir| spec.projected(frame, dir, v))
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

    #[test]
    fn sun_light_is_projected_for_every_face() {
        // The per-epoch form must give the per-face function's values (bit for bit up to
        // the order of a sum): narrow and wide lobes, faces from the glint out to 0.2 rad
        // (past the disk test's reach of 0.125 rad in the mirror angle for slope 0.01).
        use crate::brdf::{Lambert, RoughConductor, SeedMicrofacet};
        let l = DVec3::new(0.3, -0.2, 0.9).normalize();
        let v = DVec3::new(-0.4, 0.1, 0.8).normalize();
        let rho = 4.65e-3;
        let glint_normal = (l + v).normalize();
        let brdfs = [
            Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.5, 0.01, 0.18, 3.6)),
            Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.5, 0.3, 0.18, 3.6)),
            Brdf::RoughConductor(RoughConductor::new(1e-4, 1.1, 6.8, 0.05)),
            Brdf::Lambert(Lambert { albedo: 0.3 }),
        ];
        for brdf in &brdfs {
            let light = SunLight::new(brdf, l, v, rho);
            for k in 0..200 {
                let t = k as f64 * 0.0137;
                let n = (glint_normal
                    + DVec3::new(t.sin(), (1.7 * t).cos() - 1.0, 0.0) * (0.001 * k as f64))
                    .normalize();
                let (tx, _) = orthonormal_basis(n);
                let frame = Frame { n, t: tx };
                let a = light.projected(&frame);
                let b = projected(brdf, &frame, l, v, rho);
                assert!(
                    (a - b).abs() <= 1e-12 * b.abs().max(1e-300),
                    "{brdf:?} face {k}: {a} vs {b}"
                );
            }
        }
    }
}
