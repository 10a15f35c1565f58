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
        let w = principal_sqrt(self.eta2 - s2);
        let rs = ratio_norm2(Complex64::new(c, 0.0) - w, Complex64::new(c, 0.0) + w);
        let e2c = self.eta2 * c;
        let rp = ratio_norm2(e2c - w, e2c + w);
        0.5 * (rs + rp)
    }
}

/// The principal square root of `z` (real part ≥ 0), algebraically: |z| and two real
/// square roots, where `Complex64::sqrt` goes through polar form (a hypot, an atan2 and a
/// sincos: three quarters of a Fresnel term's cost). The root is taken of whichever of
/// (|z| ± re z)/2 does not cancel, the other part from im z / (2·root), so neither loses
/// digits when z lies near the real axis.
#[inline]
fn principal_sqrt(z: Complex64) -> Complex64 {
    // |z| by its square: η² and sin² are far from where that over- or underflows
    let r = (z.re * z.re + z.im * z.im).sqrt();
    if r == 0.0 {
        return Complex64::new(0.0, 0.0);
    }
    if z.re >= 0.0 {
        let re = (0.5 * (r + z.re)).sqrt();
        Complex64::new(re, z.im / (2.0 * re))
    } else {
        let im = (0.5 * (r - z.re)).sqrt().copysign(z.im);
        Complex64::new(z.im / (2.0 * im), im)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_algebraic_root_is_the_principal_root() {
        // against the polar form, over the quadrants, near both axes and at the η² − sin²
        // of real indices (n < 1 too: below the critical angle's negative real part)
        let mut zs = vec![
            Complex64::new(4.0, 0.0),
            Complex64::new(-4.0, 0.0),
            Complex64::new(-4.0, -0.0),
            Complex64::new(-4.0, 1e-12),
            Complex64::new(-4.0, -1e-12),
            Complex64::new(1e-12, 3.0),
            Complex64::new(0.0, -3.0),
            Complex64::new(0.0, 0.0),
        ];
        for (n, k) in [(1.5, 0.0), (0.18, 3.6), (2.9, 3.0), (0.5, 0.0), (1.0, 1e-9)] {
            let eta2 = Complex64::new(n, k) * Complex64::new(n, k);
            for i in 0..=20 {
                let c: f64 = i as f64 / 20.0;
                zs.push(eta2 - (1.0 - c * c));
            }
        }
        for z in zs {
            let (a, b) = (principal_sqrt(z), z.sqrt());
            // both roots to a few ulps of |√z|: rounding, not a branch apart
            assert!(
                (a - b).norm() <= 4.0 * f64::EPSILON * b.norm(),
                "{z}: {a} vs {b}"
            );
            assert!(a.re >= 0.0, "{z}: {a}");
            if z.im == 0.0 && z.re < 0.0 {
                // on the negative real axis the sign of zero picks the side, as the polar
                // form's atan2 does
                assert_eq!(a.im.is_sign_negative(), z.im.is_sign_negative(), "{z}: {a}");
            }
        }
    }

    #[test]
    fn normal_incidence_matches_the_closed_form() {
        // (n − 1)² + k² over (n + 1)² + k²: the two forms differ by rounding only
        for (n, k) in [
            (1.5, 0.0),
            (0.18, 3.6),
            (2.9, 3.0),
            (0.5, 0.0),
            (1.33, 1e-3),
        ] {
            let f = Fresnel::new(n, k).reflectance(1.0);
            assert!((f - normal_incidence(n, k)).abs() < 1e-14, "{n} {k}: {f}");
        }
    }
}
