//! Ashikhmin–Shirley (2000) anisotropic Phong BRDF, the usual model in space-object
//! light-curve papers. The specular term divides by max(cosθi, cosθr); multiplied by
//! cosθi·cosθr that becomes min(cosθi, cosθr), finite everywhere.

use super::{half_vector, Frame};
use glam::DVec3;
use std::f64::consts::PI;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AshikhminShirley {
    /// Diffuse reflectance R_d.
    pub rd: f64,
    /// Specular reflectance at normal incidence R_s (Schlick).
    pub rs: f64,
    /// Phong exponent along the tangent.
    pub nu: f64,
    /// Phong exponent along the bitangent.
    pub nv: f64,
    /// Whether the specular lobe is included (false for the diffuse-only split).
    pub specular: bool,
}

impl AshikhminShirley {
    pub fn new(rd: f64, rs: f64, nu: f64, nv: f64) -> Self {
        AshikhminShirley {
            rd,
            rs,
            nu,
            nv,
            specular: true,
        }
    }

    /// f·cosθi·cosθr, sr⁻¹.
    #[inline]
    pub fn projected(&self, frame: &Frame, l: DVec3, v: DVec3, ci: f64, cr: f64) -> f64 {
        let diffuse = 28.0 * self.rd / (23.0 * PI)
            * (1.0 - self.rs)
            * (1.0 - (1.0 - 0.5 * ci).powi(5))
            * (1.0 - (1.0 - 0.5 * cr).powi(5))
            * ci
            * cr;
        if !self.specular {
            return diffuse;
        }
        let Some(h) = half_vector(l, v) else {
            return diffuse;
        };
        let nh = frame.n.dot(h);
        if nh <= 0.0 {
            return diffuse;
        }
        let kh = l.dot(h).max(1e-12);
        let b = frame.n.cross(frame.t);
        let hu = h.dot(frame.t);
        let hv = h.dot(b);
        let sin2 = (hu * hu + hv * hv).max(0.0);
        // exponent (nu cos²φ + nv sin²φ) with cos²φ sin²θh = hu²: no 0/0 at the peak.
        let exponent = if sin2 < 1e-300 {
            0.5 * (self.nu + self.nv)
        } else {
            (self.nu * hu * hu + self.nv * hv * hv) / sin2
        };
        let fresnel = self.rs + (1.0 - self.rs) * (1.0 - kh).powi(5);
        let spec = ((self.nu + 1.0) * (self.nv + 1.0)).sqrt() / (8.0 * PI) * nh.powf(exponent) / kh
            * ci.min(cr)
            * fresnel;
        diffuse + spec
    }
}
