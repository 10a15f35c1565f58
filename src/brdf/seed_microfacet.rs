//! The paper's microfacet BRDF (Eqs. 6–8), as docs/physics.md §6.2 gives it:
//! f = k^D/π + k^M·C·V·F/(cosθi·cosθr), evaluated as the projected product
//! f·cosθi·cosθr = k^D/π·cosθi·cosθr + k^M·C·V·F, which is finite at grazing angles.

use super::fresnel::Fresnel;
use super::{beckmann, diffuse_and_lobe, Half};
use glam::DVec3;

/// Parameters of Eqs. 6–8.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeedMicrofacet {
    /// Diffuse coefficient k^D.
    pub kd: f64,
    /// Specular coefficient k^M.
    pub km: f64,
    /// RMS microfacet slope δ (> 0).
    pub slope_rms: f64,
    /// Fresnel term for the complex index n + ik.
    pub fresnel: Fresnel,
}

impl SeedMicrofacet {
    pub fn new(kd: f64, km: f64, slope_rms: f64, n: f64, k: f64) -> Self {
        SeedMicrofacet {
            kd,
            km,
            slope_rms,
            fresnel: Fresnel::new(n, k),
        }
    }

    /// What the specular term needs that depends on the directions only, not on the face.
    #[inline]
    pub fn half(&self, l: DVec3, v: DVec3) -> Option<Half> {
        Half::of_lobe(self.km, l, v, &self.fresnel)
    }

    /// f·cosθi·cosθr, sr⁻¹, given the face-independent part ([`SeedMicrofacet::half`]);
    /// `ci`, `cr` > 0 are given by the caller.
    #[inline]
    pub fn projected_fixed(&self, n: DVec3, half: &Option<Half>, ci: f64, cr: f64) -> f64 {
        diffuse_and_lobe(self.kd, n, half, ci, cr, |half, ca| {
            self.km
                * slope_distribution(ca, self.slope_rms)
                * v_cavity(ca, half.cos_b, ci, cr)
                * half.fresnel
        })
    }
}

/// Where the lobe ends: C is taken as 0 where its exponent −tan²α/δ² is below
/// −`LOBE_TAIL_EXPONENT`. There C·δ² = e^−u·(1 + δ²u)² (u = tan²α/δ²; the second factor
/// is 1/cos⁴α) is at most 1.1e−16 for every δ up to 10, the largest a request takes: the
/// dropped tail is at most ~1e−16 of the lobe's peak 1/δ², below what a sum holding the
/// peak can resolve, and with any diffuse term beside it, it rounds away (the box-wing's
/// light curve is bit-identical with a cut at −700, where exp underflows). Cutting here
/// rather than at the underflow spares most faces of a glossy object the exponential:
/// [`lobe_vanishes_below`] tells the per-face loops where (measured: 7.7 % of the
/// fine-dish box-wing's instructions per epoch).
pub const LOBE_TAIL_EXPONENT: f64 = 54.0;

/// C = exp(−tan²α/δ²)/(δ² cos⁴α): Beckmann without its 1/π (Eq. 7), 0 past the lobe's
/// tail ([`LOBE_TAIL_EXPONENT`]). tan²α is formed as (1 − cos²α)/cos²α; the exponent is
/// tested before the division so a tiny δ at a large α gives 0, never 0·∞.
#[inline]
pub fn slope_distribution(cos_a: f64, slope_rms: f64) -> f64 {
    beckmann(cos_a, slope_rms, 1.0, LOBE_TAIL_EXPONENT)
}

/// The least cos² α of the half vector below which [`slope_distribution`] is exactly
/// zero for this δ (its exponent below −[`LOBE_TAIL_EXPONENT`]), with a margin far
/// above the exponent's rounding error; 0 (never) for a δ outside (0, ∞).
pub fn lobe_vanishes_below(slope_rms: f64) -> f64 {
    let d2 = slope_rms * slope_rms;
    if !(d2 > 0.0 && d2.is_finite()) {
        return 0.0;
    }
    // exponent −(1 − c²)/(c²δ²) < −X ⟺ c² < 1/(1 + Xδ²)
    (1.0 - 1e-6) / (1.0 + LOBE_TAIL_EXPONENT * d2)
}

/// Torrance–Sparrow V-cavity masking/shadowing: min(1, 2cosα cosθr/cosβ, 2cosα cosθi/cosβ).
#[inline]
pub fn v_cavity(cos_a: f64, cos_b: f64, ci: f64, cr: f64) -> f64 {
    if cos_b <= 0.0 {
        return 0.0;
    }
    let g = 2.0 * cos_a / cos_b;
    1.0_f64.min(g * cr).min(g * ci)
}
