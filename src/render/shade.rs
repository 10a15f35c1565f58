//! Per-pixel shading: the radiance a surface point sends to the observer.
//!
//! The light curve sums dI = f·E·cosθi·cosθr·dA over the lit and seen surface (Eq. 10).
//! Under a parallel projection a surface element dA covers dA·cosθr of the image plane,
//! so the radiance a pixel must hold is
//!
//! ```text
//! L = dI / (dA·cosθr) = E·f·cosθi = E·(f·cosθi·cosθr)/cosθr      [W/(m²·sr)]
//! ```
//!
//! and Σ_pixels L·A_pixel = I (W/sr), Σ L·A_pixel / R² = the light curve's irradiance.
//! For a distant Sun and observer a flat face has one θi and one θr, so L is constant on
//! a face at one epoch: it is computed once per face, and each pixel sample only finds
//! its face (closest hit) and casts the shadow rays.

use crate::brdf::earth_light::EarthLight;
use crate::brdf::{sun_disk, Frame};
use crate::geometry::bvh::Occluder;
use crate::geometry::Faces;
use crate::light::EpochLight;
use crate::scene::Material;
use glam::DVec3;

/// Below this |cosθr| a face is seen edge-on: it covers no image area, so it gets no
/// radiance (dividing by a vanishing cosine would only add noise).
const MIN_COS_VIEW: f64 = 1e-9;

/// Earthshine's shadow direction must rise this far above a face for a shadow ray to
/// mean anything; below it the face counts as unshadowed (as in the light curve).
const MIN_COS_EARTH: f64 = 1e-3;

/// The shading of one face at one epoch.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FaceShade {
    /// Normal of the side seen by the observer (zero when the face sends nothing).
    pub normal: DVec3,
    /// Radiance from sunlight when the point is sunlit, W/(m²·sr).
    pub sun: f64,
    /// Radiance from earthshine when the point is earthlit, W/(m²·sr).
    pub earth: f64,
    /// Whether the earthshine term needs a shadow ray (false: counted unshadowed).
    pub earth_ray: bool,
}

/// Radiance of every face towards `view` (unit, object → observer) at one epoch.
/// `sun_radius` is the Sun's angular radius (rad).
pub fn face_shades(
    faces: &Faces,
    materials: &[Material],
    light: &EpochLight,
    sun: DVec3,
    sun_radius: f64,
    view: DVec3,
) -> Vec<FaceShade> {
    // as the light curve's pass 1: the earthshine's per-material part once
    let earth: Vec<EarthLight> = materials
        .iter()
        .map(|m| EarthLight::new(&m.brdf, &light.earthshine, view))
        .collect();
    faces
        .faces
        .iter()
        .map(|face| {
            let material = &materials[face.material as usize];
            let cr = face.normal.dot(view);
            let side = if cr > MIN_COS_VIEW {
                1.0
            } else if material.two_sided && cr < -MIN_COS_VIEW {
                -1.0
            } else {
                // back of a one-sided face (it still blocks rays) or edge-on
                return FaceShade::default();
            };
            let frame = Frame {
                n: face.normal * side,
                t: face.tangent,
            };
            let cr = cr.abs();
            // as the light curve's pass 1 (eq12.rs): the Sun as a disk, earthshine as beams
            // (and the glint rule)
            let sun_l = if light.sun_w_m2 > 0.0 {
                light.sun_w_m2
                    * sun_disk::projected_eclipsed(
                        &material.brdf,
                        &frame,
                        sun,
                        view,
                        sun_radius,
                        light.penumbra,
                    )
                    / cr
            } else {
                0.0
            };
            let earth_l = earth[face.material as usize].projected_given(&frame, cr) / cr;
            let earth_ray = earth_l > 0.0
                && light
                    .earthshine
                    .shadow_dir
                    .is_some_and(|d| frame.n.dot(d) > MIN_COS_EARTH);
            FaceShade {
                normal: frame.n,
                sun: sun_l,
                earth: earth_l,
                earth_ray,
            }
        })
        .collect()
}

/// The shading state of one epoch, shared by all pixels.
pub struct Shader<'a> {
    pub occluder: &'a Occluder,
    /// Face index of every triangle.
    pub face_of: &'a [u32],
    pub shades: &'a [FaceShade],
    /// Unit vector object → Sun.
    pub sun: DVec3,
    /// Representative earthshine direction for shadow rays.
    pub earth: Option<DVec3>,
    /// Ray direction (−view).
    pub dir: DVec3,
}

impl Shader<'_> {
    /// Radiance (W/(m²·sr)) seen along the ray from `origin` in direction `self.dir`,
    /// and the number of rays cast.
    #[inline]
    pub fn radiance(&self, origin: DVec3) -> (f64, u32) {
        let Some((t, tri)) = self.occluder.first_hit(origin, self.dir) else {
            return (0.0, 1);
        };
        let s = &self.shades[self.face_of[tri] as usize];
        if s.sun <= 0.0 && s.earth <= 0.0 {
            return (0.0, 1);
        }
        let p = origin + self.dir * t;
        let mut rays = 1;
        let mut l = 0.0;
        if s.sun > 0.0 {
            rays += 1;
            if self.occluder.is_clear(p, s.normal, self.sun) {
                l += s.sun;
            }
        }
        if s.earth > 0.0 {
            let lit = match (s.earth_ray, self.earth) {
                (true, Some(e)) => {
                    rays += 1;
                    self.occluder.is_clear(p, s.normal, e)
                }
                _ => true,
            };
            if lit {
                l += s.earth;
            }
        }
        (l, rays)
    }
}

/// A ray direction safe for obvhs 0.4, which misses every hit along a direction with a
/// −0.0 component (its octant test and 1/−0 = −∞ disagree): components that are or
/// would round to zero in f32 become +0.0.
pub fn ray_dir(d: DVec3) -> DVec3 {
    DVec3::from_array(d.to_array().map(|x| if x.abs() < 1e-37 { 0.0 } else { x }))
}
