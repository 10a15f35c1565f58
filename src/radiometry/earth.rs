//! Earthshine: sunlight reflected by the Earth onto the object.
//!
//! - `Seed` (the paper's Eq. 3): a parallel beam of irradiance ρE_s from the Earth's
//!   direction, whatever the distance and Earth phase.
//! - `Sphere`: the Earth as a Lambertian sphere of radius R_E, each point of its visible
//!   disk radiating ρE_s·max(0, cos z)/π (z: solar zenith angle there). The visible cap is
//!   integrated as an extended source by a quadrature uniform in solid angle, so it is
//!   right in LEO where the Earth fills much of the sky (docs/physics.md §5).

use super::EARTH_RADIUS_M;
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
}

/// The paper's Eq. 3: E_e = ρ E_s arriving from the Earth's centre direction.
pub fn seed(earth_dir: DVec3, albedo: f64, sun_irradiance: f64) -> Earthshine {
    Earthshine {
        beams: vec![Beam {
            dir: earth_dir,
            irradiance: albedo * sun_irradiance,
        }],
        shadow_dir: Some(earth_dir),
    }
}

/// Beyond this many Earth radii the sphere model uses its far-field closed form.
pub const FAR_FIELD_RADII: f64 = 50.0;

/// The Earth as a sunlit Lambertian sphere, integrated over its visible cap.
/// `earth` is the vector object → Earth centre (m), `sun_dir` the unit vector towards
/// the Sun, `sun_irradiance` the band irradiance at the Earth (W/m²).
pub fn sphere(earth: DVec3, sun_dir: DVec3, albedo: f64, sun_irradiance: f64) -> Earthshine {
    let d = earth.length();
    let e = earth / d;
    if d > FAR_FIELD_RADII * EARTH_RADIUS_M {
        // A small disk: its lit crescent would need a very fine grid, while the closed
        // form — the Lambert-sphere phase law, from the Earth's centre — is within
        // O(R_E/d) < 2 % of the exact integral (less than the grid's own error there).
        let psi = (-e).dot(sun_dir).clamp(-1.0, 1.0).acos(); // Earth→object vs Earth→Sun
        let law = 2.0 / (3.0 * PI) * ((PI - psi) * psi.cos() + psi.sin());
        let irradiance = albedo * sun_irradiance * (EARTH_RADIUS_M / d).powi(2) * law.max(0.0);
        return Earthshine {
            beams: vec![Beam { dir: e, irradiance }],
            shadow_dir: Some(e),
        };
    }
    let sin_a = (EARTH_RADIUS_M / d).min(1.0);
    let cos_a = (1.0 - sin_a * sin_a).max(0.0).sqrt();
    // Rings uniform in cosγ (equal solid angle) and sectors in azimuth; more of both
    // when the Earth looks large. The midpoint rule in cosγ integrates the cosine-
    // weighted cap exactly for uniform radiance (the view-factor check in docs/physics.md §5).
    let angular_radius = sin_a.asin();
    let rings = ((angular_radius / 0.05).ceil() as usize).clamp(4, 16);
    let sectors = (rings * 4).max(16);
    let (t1, t2) = orthonormal_basis(e);
    let p_obj = -earth; // object position relative to the Earth's centre
    let radiance_scale = albedo * sun_irradiance / PI;
    let d_omega = TAU * (1.0 - cos_a) / (rings * sectors) as f64;
    let mut beams = Vec::with_capacity(rings * sectors);
    let mut mean = DVec3::ZERO;
    for i in 0..rings {
        let u = cos_a + (1.0 - cos_a) * (i as f64 + 0.5) / rings as f64;
        let s = (1.0 - u * u).max(0.0).sqrt();
        for j in 0..sectors {
            let phi = TAU * (j as f64 + 0.5 + 0.5 * (i % 2) as f64) / sectors as f64;
            let dir = e * u + (t1 * phi.cos() + t2 * phi.sin()) * s;
            // nearest intersection of the ray p_obj + t·dir with the Earth sphere
            let b = p_obj.dot(dir);
            let c = p_obj.length_squared() - EARTH_RADIUS_M * EARTH_RADIUS_M;
            let disc = b * b - c;
            if disc < 0.0 {
                continue;
            }
            let t = -b - disc.sqrt();
            let normal = (p_obj + dir * t) / EARTH_RADIUS_M;
            let cos_z = normal.dot(sun_dir);
            if cos_z <= 0.0 {
                continue; // night side
            }
            let irradiance = radiance_scale * cos_z * d_omega;
            mean += dir * irradiance;
            beams.push(Beam { dir, irradiance });
        }
    }
    let shadow_dir = (mean.length_squared() > 0.0).then(|| mean.normalize());
    Earthshine { beams, shadow_dir }
}

/// Two unit vectors completing `n` to a right-handed orthonormal basis.
pub fn orthonormal_basis(n: DVec3) -> (DVec3, DVec3) {
    // Duff et al. 2017, branchless ONB
    let sign = 1.0_f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
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
