//! Unpolarised Fresnel reflectance for a complex refractive index η = n + ik.
//!
//! The paper's Eq. 8 is the real-angle form, which has no meaning for the metallic
//! indices of its own validation (n = 0.18 + 3.60i). We use the exact complex form
//! (docs/physics.md §6.1), which reduces to Eq. 8 for real η and has no 0/0 at normal incidence.

use num_complex::Complex64;

/// Precomputed η² for repeated evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fresnel {
    eta2: Complex64,
}

impl Fresnel {
    pub fn new(n: f64, k: f64) -> Self {
        let eta = Complex64::new(n, k);
        Fresnel { eta2: eta * eta }
    }

    /// The index (n, k) back from η²: the principal square root, n ≥ 0 (as requests give it).
    pub fn index(&self) -> (f64, f64) {
        let eta = self.eta2.sqrt();
        (eta.re.abs(), eta.im.abs())
    }

    /// Reflectance F = (Rs + Rp)/2 at incidence cosine `cos_b` (clamped to 0..1).
    #[inline]
    pub fn reflectance(&self, cos_b: f64) -> f64 {
        let c = cos_b.clamp(0.0, 1.0);
        let s2 = 1.0 - c * c;
        let w = (self.eta2 - s2).sqrt();
        let rs = ratio_norm2(Complex64::new(c, 0.0) - w, Complex64::new(c, 0.0) + w);
        let e2c = self.eta2 * c;
        let rp = ratio_norm2(e2c - w, e2c + w);
        0.5 * (rs + rp)
    }
}

/// |a/b|², with |b| = 0 (η = 1 at grazing: no interface) taken as total reflection.
#[inline]
fn ratio_norm2(a: Complex64, b: Complex64) -> f64 {
    let d = b.norm_sqr();
    if d < 1e-300 {
        1.0
    } else {
        (a.norm_sqr() / d).min(1.0)
    }
}

/// Normal-incidence reflectance ((n−1)² + k²)/((n+1)² + k²), a closed form to test against.
pub fn normal_incidence(n: f64, k: f64) -> f64 {
    ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k)
}
