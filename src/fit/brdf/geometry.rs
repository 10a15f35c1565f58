//! The measurement geometry: angles as directions in the face frame, a BRDF evaluated
//! there, and the paper's Fig. 2 layout of angles.

use crate::brdf::{Brdf, Frame};
use glam::DVec3;

/// The face frame of every sample: normal z, tangent x.
const FRAME: Frame = Frame {
    n: DVec3::Z,
    t: DVec3::X,
};

/// Unit directions towards the light and the detector of a sample (face frame: normal z,
/// the light in the x–z plane at positive x; φ = 180° puts the detector at negative x).
pub fn directions(theta_i_deg: f64, theta_r_deg: f64, phi_deg: f64) -> (DVec3, DVec3) {
    let (ti, tr, phi) = (
        theta_i_deg.to_radians(),
        theta_r_deg.to_radians(),
        phi_deg.to_radians(),
    );
    let l = DVec3::new(ti.sin(), 0.0, ti.cos());
    let v = DVec3::new(tr.sin() * phi.cos(), tr.sin() * phi.sin(), tr.cos());
    (l, v)
}

/// The BRDF f (sr⁻¹) of `brdf` at angles in degrees: the model's f·cosθi·cosθr over the
/// two cosines (both positive: the angles are below 90°).
pub fn evaluate_at(brdf: &Brdf, theta_i_deg: f64, theta_r_deg: f64, phi_deg: f64) -> f64 {
    let (l, v) = directions(theta_i_deg, theta_r_deg, phi_deg);
    let (ci, cr) = (l.z, v.z);
    if ci <= 0.0 || cr <= 0.0 {
        return 0.0;
    }
    brdf.projected(&FRAME, l, v) / (ci * cr)
}

/// The measurement geometry of the paper's Fig. 2, as `glint sample-brdf` lays it out:
/// incidence 10°, 30°, 45°, 60°; in the plane of incidence every 5° forward (φ = 180°) and
/// every 10° backward (φ = 0°), every 0.25° within 3° of the mirror direction, and five
/// points off the plane at θr = θi. (θi, θr, φ) in degrees.
pub fn paper_geometry() -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for ti in [10.0, 30.0, 45.0, 60.0] {
        for i in 0..=17 {
            let tr = 5.0 * i as f64;
            out.push((ti, tr, 180.0));
            if i % 2 == 0 {
                out.push((ti, tr, 0.0));
            }
        }
        for j in -12..=12 {
            let tr: f64 = ti + 0.25 * j as f64;
            if tr != ti && (0.0..89.0).contains(&tr) {
                out.push((ti, tr, 180.0));
            }
        }
        for phi in [150.0, 170.0, 175.0, 178.0, 179.0] {
            out.push((ti, ti, phi));
        }
    }
    out
}
