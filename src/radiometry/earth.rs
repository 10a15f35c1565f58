//! Earthshine: sunlight reflected by the Earth onto the object.
//!
//! - `Seed` (the paper's Eq. 3): a parallel beam of irradiance ρE_s from the Earth's
//!   direction, whatever the distance and Earth phase.
//! - `Sphere`: the Earth as a Lambertian sphere of radius R_E, each point of its visible
//!   disk radiating ρE_s·max(0, cos z)/π (z: solar zenith angle there). The sunlit part
//!   of the visible cap (a crescent, or the whole cap) is integrated as an extended source
//!   by beams placed on it, the same rule from LEO to any distance (docs/physics.md §5);
//!   narrow specular lobes take a glint rule per face (`brdf/earth_light.rs`).

use super::EARTH_RADIUS_M;
use crate::geometry::orthonormal_basis;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// One directional piece of earthshine: light arriving from `dir` with `irradiance`
/// (W/m² on a surface facing `dir`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beam {
    pub dir: DVec3,
    pub irradiance: f64,
}

/// Earthshine as a set of beams, plus a representative direction for shadow rays
/// (the irradiance-weighted mean direction).
#[derive(Debug, Clone, Default)]
pub struct Earthshine {
    pub beams: Vec<Beam>,
    pub shadow_dir: Option<DVec3>,
    /// The sunlit Earth the beams sample (the `sphere` model), for rules that look up its
    /// radiance along other directions; `None` for the paper's single beam.
    pub sunlit: Option<SunlitEarth>,
    /// The largest extent of the sky a beam stands for, rad: the spacing of neighbouring
    /// beams along a ring or across rings, whichever is larger (0 for the paper's single
    /// beam).
    pub patch: f64,
}

/// The paper's Eq. 3: E_e = ρ E_s arriving from the Earth's centre direction.
pub fn seed(earth_dir: DVec3, albedo: f64, sun_irradiance: f64) -> Earthshine {
    Earthshine {
        beams: vec![Beam {
            dir: earth_dir,
            irradiance: albedo * sun_irradiance,
        }],
        shadow_dir: Some(earth_dir),
        sunlit: None,
        patch: 0.0,
    }
}

/// Rings (in the emission angle) of the crescent rule, per segment of the lit cap.
pub const RINGS: usize = 6;
/// Directions (in azimuth about the sub-object point) per ring.
pub const AZIMUTHS: usize = 8;
/// A crescent's arcs take up to this many times [`AZIMUTHS`] when thin.
pub const ARC_AZIMUTHS_MAX: usize = 4;

/// The sunlit Earth as seen from the object: what a face needs to look up the Earth's
/// radiance along any direction (the glint rule of `brdf/earth_light.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunlitEarth {
    /// The object's position relative to the Earth's centre, m.
    pub object: DVec3,
    /// Unit vector towards the Sun.
    pub sun_dir: DVec3,
    /// ρE_s/π: the radiance of a point with the Sun overhead, W/(m²·sr).
    pub radiance_scale: f64,
    /// cos of the visible cap's angular radius seen from the object.
    pub cos_cap: f64,
    /// Unit vector object → Earth's centre.
    pub centre_dir: DVec3,
}

impl SunlitEarth {
    /// Radiance arriving along the unit direction `dir` (0 off the Earth or from its
    /// night side), W/(m²·sr).
    #[inline]
    pub fn radiance(&self, dir: DVec3) -> f64 {
        match self.sight(dir) {
            (_, Some(cos_z)) if cos_z > 0.0 => self.radiance_scale * cos_z,
            _ => 0.0,
        }
    }

    /// Where the unit direction `dir` meets the Earth: a margin smooth in `dir` that is
    /// ≥ 0 exactly where it meets it in front (b² − c, b = o·dir < 0; −c − b² where
    /// b ≥ 0, continuous at b = 0: the limb is its root), and the cos of the Sun's zenith
    /// angle at the point met (`None` where it meets nothing).
    #[inline]
    pub fn sight(&self, dir: DVec3) -> (f64, Option<f64>) {
        let b = self.object.dot(dir);
        let c = self.object.length_squared() - EARTH_RADIUS_M * EARTH_RADIUS_M;
        if b >= 0.0 {
            return (-c - b * b, None);
        }
        let disc = b * b - c;
        if disc < 0.0 {
            return (disc, None);
        }
        let t = -b - disc.sqrt();
        let normal = (self.object + dir * t) / EARTH_RADIUS_M;
        (disc, Some(normal.dot(self.sun_dir)))
    }
}

/// The Earth as a sunlit Lambertian sphere, integrated over the part of its visible cap
/// that is sunlit (docs/physics.md §5). `earth` is the vector object → Earth centre (m),
/// `sun_dir` the unit vector towards the Sun, `sun_irradiance` the band irradiance at the
/// Earth (W/m²).
///
/// The lit part of the visible cap, on the Earth's surface, is the set of points at an
/// angle θ ≤ θ_v = acos(R_E/d) from the sub-object point that are on the day side:
/// whole rings about the sub-object point out to θ_f = 90° − ψ (ψ the Earth phase), and
/// beyond it (or from θ_min = ψ − 90° when ψ > 90°) arcs |φ| ≤ φ_max(θ) about the Sun's
/// azimuth, cos φ_max = −cot θ cot ψ. Rings are placed in the emission angle e (the angle
/// at the Earth's surface between its normal and the object), in which the solid angle
/// seen from the object is analytic up to the limb: γ = asin((R_E/d) sin e), θ = e − γ,
/// dΩ = sin γ (R_E/d) cos e / cos γ de dφ. Whole rings: Gauss–Legendre in e on [0, e_f],
/// even azimuths; arcs: Gauss–Legendre in t, e = e_a + (90° − e_a) t² (which takes up the
/// square-root start of a crescent), and Gauss–Legendre in φ on the arc. The same rule
/// at every distance, so a thin crescent converges as a fat one and nothing switches.
pub fn sphere(earth: DVec3, sun_dir: DVec3, albedo: f64, sun_irradiance: f64) -> Earthshine {
    sphere_with(earth, sun_dir, albedo, sun_irradiance, RINGS, AZIMUTHS)
}

/// [`sphere`] with `rings` rings per segment and `azimuths` directions per ring (for
/// the error-against-beam-count measurements).
pub fn sphere_with(
    earth: DVec3,
    sun_dir: DVec3,
    albedo: f64,
    sun_irradiance: f64,
    rings: usize,
    azimuths: usize,
) -> Earthshine {
    let cap = VisibleCap::new(earth, sun_dir, albedo * sun_irradiance / PI);
    let mut lit = LitBeams {
        beams: Vec::with_capacity(2 * rings * azimuths),
        mean: DVec3::ZERO,
        patch: 0.0,
    };
    let gauss = gauss_legendre(rings);
    cap.whole_rings(&gauss, azimuths, &mut lit);
    cap.crescent_arcs(&gauss, azimuths, &mut lit);
    let LitBeams {
        beams,
        mean,
        mut patch,
    } = lit;
    if beams.is_empty() {
        patch = 0.0;
    }
    let shadow_dir = (mean.length_squared() > 0.0).then(|| mean.normalize());
    Earthshine {
        beams,
        shadow_dir,
        sunlit: Some(cap.sunlit()),
        patch,
    }
}

/// The Earth's visible cap seen from the object, with the azimuths about the
/// sub-object point measured from the Sun's side.
struct VisibleCap {
    /// The object's position relative to the Earth's centre, m.
    object: DVec3,
    /// The object's distance from the Earth's centre, m.
    d: f64,
    /// Unit vector object → Earth's centre.
    e: DVec3,
    /// Unit vector Earth's centre → object.
    o: DVec3,
    /// Azimuth 0 (towards the Sun) and 90° about `o`.
    a: DVec3,
    b: DVec3,
    /// R_E/d, at most 1.
    k: f64,
    sun_dir: DVec3,
    /// cos ψ and ψ, the Earth phase (the Sun's angle from the sub-object point).
    cos_psi: f64,
    psi: f64,
    /// ρE_s/π, W/(m²·sr).
    radiance_scale: f64,
}

/// The beams placed so far, their irradiance-weighted direction sum and the largest
/// extent of sky one stands for (rad).
struct LitBeams {
    beams: Vec<Beam>,
    mean: DVec3,
    patch: f64,
}

impl VisibleCap {
    fn new(earth: DVec3, sun_dir: DVec3, radiance_scale: f64) -> Self {
        let d = earth.length();
        let e = earth / d;
        let o = -e; // Earth's centre → object
        let k = (EARTH_RADIUS_M / d).min(1.0);
        let cos_psi = o.dot(sun_dir).clamp(-1.0, 1.0);
        let psi = cos_psi.acos();
        let across = sun_dir - o * cos_psi;
        let a = if across.length_squared() > 1e-24 {
            across.normalize()
        } else {
            orthonormal_basis(o).0
        };
        let b = o.cross(a);
        VisibleCap {
            object: -earth,
            d,
            e,
            o,
            a,
            b,
            k,
            sun_dir,
            cos_psi,
            psi,
            radiance_scale,
        }
    }

    /// The sunlit Earth for the rules that look up its radiance along any direction.
    fn sunlit(&self) -> SunlitEarth {
        let k = self.k;
        SunlitEarth {
            object: self.object,
            sun_dir: self.sun_dir,
            radiance_scale: self.radiance_scale,
            cos_cap: (1.0 - k * k).max(0.0).sqrt(),
            centre_dir: self.e,
        }
    }

    /// The limb's angle from the sub-object point, on the Earth.
    fn limb(&self) -> f64 {
        self.k.acos()
    }

    /// The emission angle e of the point at angle θ from the sub-object point: e = θ + γ,
    /// tan γ = R sin θ / (d − R cos θ).
    fn emission_of(&self, theta: f64) -> f64 {
        theta + (EARTH_RADIUS_M * theta.sin()).atan2(self.d - EARTH_RADIUS_M * theta.cos())
    }

    /// Adds the beam from emission angle `e_ang` and azimuth `phi` with quadrature weight
    /// `w` (in e and φ), if its point is sunlit and seen.
    #[inline]
    fn push(&self, e_ang: f64, phi: f64, w: f64, lit: &mut LitBeams) {
        let k = self.k;
        let sin_g = k * e_ang.sin();
        let cos_g = (1.0 - sin_g * sin_g).max(0.0).sqrt();
        let theta = e_ang - sin_g.asin();
        let (sp, cp) = phi.sin_cos();
        let across = self.a * cp + self.b * sp;
        let n = self.o * theta.cos() + across * theta.sin();
        let cos_z = n.dot(self.sun_dir);
        if cos_z <= 0.0 || cos_g <= 0.0 {
            return;
        }
        let dir = self.e * cos_g + across * sin_g;
        let d_omega = w * sin_g * k * e_ang.cos() / cos_g;
        let irradiance = self.radiance_scale * cos_z * d_omega;
        if irradiance > 0.0 {
            lit.mean += dir * irradiance;
            lit.beams.push(Beam { dir, irradiance });
        }
    }

    /// Whole rings out to θ_f = 90° − ψ (clipped at the limb): Gauss–Legendre in e on
    /// [0, e_f], `azimuths` even azimuths, every other ring turned by half a step.
    fn whole_rings(&self, gauss: &[(f64, f64)], azimuths: usize, lit: &mut LitBeams) {
        let (k, theta_v) = (self.k, self.limb());
        let rings = gauss.len();
        let theta_f = (0.5 * PI - self.psi).min(theta_v);
        if theta_f > 0.0 {
            let e_f = if theta_f >= theta_v {
                0.5 * PI
            } else {
                self.emission_of(theta_f)
            };
            let gamma_f = (k * e_f.sin()).asin();
            lit.patch = lit.patch.max(gamma_f / rings as f64);
            for (i, &(x, wx)) in gauss.iter().enumerate() {
                let e_ang = e_f * x;
                lit.patch = lit.patch.max((k * e_ang.sin()) * TAU / azimuths as f64);
                for j in 0..azimuths {
                    let phi = TAU * (j as f64 + 0.5 * (i % 2) as f64) / azimuths as f64;
                    self.push(e_ang, phi, e_f * wx * TAU / azimuths as f64, lit);
                }
            }
        }
    }

    /// The crescent: arcs about the Sun's azimuth from θ_a = |ψ − 90°| (where the whole
    /// rings end, or the night side's edge) to the limb, when any of it is seen.
    fn crescent_arcs(&self, gauss: &[(f64, f64)], azimuths: usize, lit: &mut LitBeams) {
        let theta_a = (self.psi - 0.5 * PI).abs();
        if theta_a < self.limb() && self.psi.sin() > 0.0 {
            self.arcs_from(self.emission_of(theta_a), gauss, azimuths, lit);
        }
    }

    /// Arcs |φ| ≤ φ_max(θ) from emission angle `e_a` to the limb: Gauss–Legendre in t
    /// with e = e_a + (90° − e_a) t² (which takes up the square-root start of a crescent),
    /// and in φ on each arc, with more azimuths (up to [`ARC_AZIMUTHS_MAX`] times) on a
    /// thin crescent, so the beams are spaced alike along and across it.
    fn arcs_from(&self, e_a: f64, gauss: &[(f64, f64)], azimuths: usize, lit: &mut LitBeams) {
        let (k, psi) = (self.k, self.psi);
        let rings = gauss.len();
        let half_pi = 0.5 * PI;
        let span = half_pi - e_a;
        let depth = k.asin() - (k * e_a.sin()).asin();
        let cot_psi = self.cos_psi / psi.sin();
        let arcs: Vec<(f64, f64, f64)> = gauss
            .iter()
            .map(|&(t, wt)| {
                let e_ang = e_a + span * t * t;
                let theta = e_ang - (k * e_ang.sin()).asin();
                let phi_max = (-cot_psi / theta.tan()).clamp(-1.0, 1.0).acos();
                (e_ang, 2.0 * span * t * wt, phi_max)
            })
            .collect();
        let length = arcs
            .iter()
            .map(|&(e_ang, _, phi_max)| 2.0 * phi_max * k * e_ang.sin())
            .fold(0.0, f64::max);
        let per_arc = ((rings as f64 * length / depth.max(1e-300)).ceil() as usize)
            .clamp(azimuths, ARC_AZIMUTHS_MAX * azimuths);
        let gauss_phi = gauss_legendre(per_arc);
        lit.patch = lit.patch.max(depth / rings as f64);
        for &(e_ang, de, phi_max) in &arcs {
            lit.patch = lit
                .patch
                .max(k * e_ang.sin() * 2.0 * phi_max / per_arc as f64);
            for &(x, wx) in gauss_phi.iter() {
                let phi = phi_max * (2.0 * x - 1.0);
                self.push(e_ang, phi, de * 2.0 * phi_max * wx, lit);
            }
        }
    }
}

/// Gauss–Legendre nodes and weights on [0, 1] (weights summing to 1), by Newton's
/// method on the Legendre polynomial.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let p = if n == 0 { 1.0 } else { p1 };
            dp = n as f64 * (x * p - p0) / (x * x - 1.0);
            let dx = p / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push((0.5 * (1.0 - x), 0.5 * w));
    }
    out.reverse();
    out
}

/// Height above the mean sphere (m) within which an observer counts as on the ground: the
/// ellipsoid departs from the sphere by up to 21 km, and sites stand up to ~5 km high.
pub const GROUND_MARGIN_M: f64 = 30e3;

/// Does the Earth hide the object from the observer? `earth` and `observer` are the
/// vectors from the object to the Earth's centre and to the observer, m. An observer on
/// the ground (within [`GROUND_MARGIN_M`] of the mean sphere, or below it) sees the object
/// when it is above the local horizon (geocentric: the sphere's normal, within 0.2° of the
/// ellipsoid's); one in space when the segment between them clears the sphere of radius
/// [`EARTH_RADIUS_M`].
pub fn hides_observer(earth: DVec3, observer: DVec3) -> bool {
    let up = observer - earth;
    if up.length() <= EARTH_RADIUS_M + GROUND_MARGIN_M {
        // towards the object from the observer is −observer
        return (-observer).dot(up) < 0.0;
    }
    let len2 = observer.length_squared();
    if len2 == 0.0 {
        return false;
    }
    let t = (earth.dot(observer) / len2).clamp(0.0, 1.0);
    (earth - observer * t).length() < EARTH_RADIUS_M
}

#[cfg(test)]
mod line_of_sight_tests {
    use super::*;

    const R: f64 = EARTH_RADIUS_M;

    #[test]
    fn the_earth_hides_an_observer_behind_it_and_below_the_horizon() {
        // an object 500 km up over the +z pole: the Earth's centre is below it
        let earth = DVec3::new(0.0, 0.0, -(R + 500e3));
        // in space: a GEO observer on the far side is hidden, one on the near side or
        // beyond the limb is not
        let geo = 42_164e3;
        assert!(hides_observer(earth, earth + DVec3::new(0.0, 0.0, -geo)));
        assert!(!hides_observer(earth, earth + DVec3::new(0.0, 0.0, geo)));
        assert!(!hides_observer(earth, earth + DVec3::new(geo, 0.0, 0.0)));
        // on the ground: the sub-object site sees it overhead; a site 10° away sees it
        // (elevation ~52°); one 30° away does not (its geometric horizon is at ~21.9°
        // from the sub-point for a 500 km orbit); the antipode does not
        let site = |deg: f64| {
            let a = deg.to_radians();
            earth + DVec3::new(a.sin(), 0.0, a.cos()) * R
        };
        assert!(!hides_observer(earth, site(0.0)));
        assert!(!hides_observer(earth, site(10.0)));
        assert!(!hides_observer(earth, site(21.0)));
        assert!(hides_observer(earth, site(23.0)));
        assert!(hides_observer(earth, site(30.0)));
        assert!(hides_observer(earth, site(180.0)));
        // a site on the ellipsoid's pole, 21 km inside the mean sphere, still sees an
        // object overhead
        assert!(!hides_observer(earth, earth + DVec3::Z * (R - 21e3)));
    }
}
