//! Eclipse of the Sun by the Earth: the fraction of the solar disk hidden.
//!
//! Both bodies are disks on the sky of the object: the Sun with angular radius
//! a_s = asin(R_s/D), the Earth with a_e = asin(R_E/d), centres θ apart. The hidden
//! fraction is the overlap of the two disks over the Sun's disk (flat-sky overlap,
//! exact to O(a_s²) ≈ 2e-5 rad² — the Sun is tiny). Refraction in the atmosphere is ignored.

use std::f64::consts::PI;

/// Fraction (0..1) of a disk of radius `a_s` covered by a disk of radius `a_e` whose
/// centre is `theta` away (all angles in radians).
pub fn hidden_fraction(a_s: f64, a_e: f64, theta: f64) -> f64 {
    if a_s <= 0.0 {
        return if theta < a_e { 1.0 } else { 0.0 };
    }
    if theta >= a_s + a_e {
        return 0.0;
    }
    if theta <= a_e - a_s {
        return 1.0;
    }
    if theta <= a_s - a_e {
        // Earth disk entirely inside the Sun's (only possible far from the Earth)
        return (a_e * a_e) / (a_s * a_s);
    }
    let overlap = circle_overlap(a_s, a_e, theta);
    (overlap / (PI * a_s * a_s)).clamp(0.0, 1.0)
}

/// Area of the lens where circles of radius r1 and r2, centres d apart, overlap.
fn circle_overlap(r1: f64, r2: f64, d: f64) -> f64 {
    let c1 = ((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1)).clamp(-1.0, 1.0);
    let c2 = ((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2)).clamp(-1.0, 1.0);
    let k = (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
    r1 * r1 * c1.acos() + r2 * r2 * c2.acos() - 0.5 * k.max(0.0).sqrt()
}
