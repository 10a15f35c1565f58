//! Lambertian reflector: f = a/π.

use std::f64::consts::FRAC_1_PI;

/// Ideal diffuse reflector with albedo `albedo` (0..1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lambert {
    pub albedo: f64,
}

impl Lambert {
    /// f·cosθi·cosθr, sr⁻¹.
    #[inline]
    pub fn projected(&self, ci: f64, cr: f64) -> f64 {
        self.albedo * FRAC_1_PI * ci * cr
    }
}
