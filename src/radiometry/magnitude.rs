//! Magnitudes (docs/physics.md §10): apparent, in the request's band, and the three
//! conventions observers reduce them to — at 1000 km, the standard magnitude (1000 km and
//! 90° phase) and McCants' intrinsic magnitude (1000 km, full phase), the phase reduced
//! with the Lambert sphere's phase law.

use std::f64::consts::PI;

/// The Sun's apparent magnitude on the scale of an interval band (`band_um`): −26.74, the
/// zero point glint has always used (its V magnitude, so an interval band's magnitudes
/// read as V-like whatever the band). Named bands carry their own (`radiometry::bands`).
pub const SUN_MAGNITUDE: f64 = -26.74;

/// The range the range-normalised magnitudes are reduced to, m.
pub const STANDARD_RANGE_M: f64 = 1.0e6;

/// m = m_sun − 2.5 log10(E / E_sun): `sun_band_1au_w_m2` is the Sun's irradiance at 1 AU
/// in the same band, `sun_magnitude` its magnitude there. `None` for no light at all
/// (E ≤ 0); any positive E, however faint, gets a finite magnitude: the logarithms are
/// taken apart, since the ratio of a subnormal E (6.5e-322 W/m², an observer 3e-308 rad
/// above a plate's plane, found by the fuzz run) to E_sun underflows to 0.
pub fn apparent(irradiance_w_m2: f64, sun_band_1au_w_m2: f64, sun_magnitude: f64) -> Option<f64> {
    if irradiance_w_m2 > 0.0 && irradiance_w_m2.is_finite() {
        Some(sun_magnitude - 2.5 * (irradiance_w_m2.log10() - sun_band_1au_w_m2.log10()))
    } else {
        None
    }
}

/// Magnitude rescaled to a 1000 km range: m − 5 log10(R / 1e6 m).
pub fn at_1000km(magnitude: Option<f64>, range_m: f64) -> Option<f64> {
    magnitude.map(|m| m - 5.0 * (range_m / STANDARD_RANGE_M).log10())
}

/// The Lambert sphere's phase law, normalised to 1 at full phase:
/// F(g) = ((π − g) cos g + sin g) / π, g in rad (F(0) = 1, F(90°) = 1/π, F(180°) = 0).
/// Written in u = π − g as (sin u − u cos u)/π, by its series below u = 0.1 (the
/// difference loses the digits there), so that F is exactly 0 at g = 180° and positive
/// below it.
pub fn lambert_phase(phase_rad: f64) -> f64 {
    let u = PI - phase_rad.clamp(0.0, PI);
    if u < 0.1 {
        let u2 = u * u;
        // sin u − u cos u = u³/3 − u⁵/30 + u⁷/840 − u⁹/45360 + …
        u * u2 * (1.0 / 3.0 - u2 * (1.0 / 30.0 - u2 * (1.0 / 840.0 - u2 / 45360.0))) / PI
    } else {
        (u.sin() - u * u.cos()) / PI
    }
}

/// A 1000 km magnitude at phase g reduced to phase `to_rad` with the Lambert sphere's
/// phase law: m + 2.5 log10(F(g) / F(to)). `None` with the magnitude, or where F(g) is 0
/// (phase 180°: no sunlit part is seen, nothing to reduce).
fn reduced(m_1000km: Option<f64>, phase_rad: f64, to_rad: f64) -> Option<f64> {
    let f = lambert_phase(phase_rad);
    if f > 0.0 {
        m_1000km.map(|m| m + 2.5 * (f / lambert_phase(to_rad)).log10())
    } else {
        None
    }
}

/// The observers' standard magnitude: at 1000 km and 90° phase, the phase reduced with
/// the Lambert sphere's law (m_1000km + 2.5 log10(π F(g))).
pub fn standard(m_1000km: Option<f64>, phase_rad: f64) -> Option<f64> {
    reduced(m_1000km, phase_rad, 0.5 * PI)
}

/// McCants' intrinsic magnitude: at 1000 km and full phase (0°), the phase reduced with
/// the Lambert sphere's law (m_1000km + 2.5 log10 F(g)).
pub fn intrinsic(m_1000km: Option<f64>, phase_rad: f64) -> Option<f64> {
    reduced(m_1000km, phase_rad, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The phase law against its closed values (rounding only: 1e-15).
    #[test]
    fn the_lambert_phase_law_at_its_closed_points() {
        assert!((lambert_phase(0.0) - 1.0).abs() < 1e-15);
        assert!((lambert_phase(0.5 * PI) - 1.0 / PI).abs() < 1e-15);
        assert_eq!(lambert_phase(PI), 0.0);
        // the series and the closed form agree where they meet (u = 0.1: 1e-12 relative,
        // the closed form's cancellation there)
        let g = PI - 0.1;
        let closed = ((PI - g) * g.cos() + g.sin()) / PI;
        assert!((lambert_phase(g) / closed - 1.0).abs() < 1e-12);
        assert!((lambert_phase(g + 1e-12) / closed - 1.0).abs() < 1e-9);
        // the standard and intrinsic magnitudes differ by 2.5 log10 π at any phase
        for g in [0.1, 1.0, 2.0, 3.0] {
            let s = standard(Some(5.0), g).unwrap();
            let i = intrinsic(Some(5.0), g).unwrap();
            assert!((s - i - 2.5 * PI.log10()).abs() < 1e-12, "{g}: {s} {i}");
        }
        assert_eq!(standard(Some(5.0), 0.5 * PI), Some(5.0));
        assert_eq!(standard(None, 1.0), None);
        assert_eq!(standard(Some(5.0), 4.0), None, "clamped to 180°: F = 0");
    }

    #[test]
    fn a_subnormal_irradiance_has_a_finite_magnitude() {
        // 6.5e-322 W/m² (the fuzz run's case): E/E_sun would underflow to 0 and log10 to
        // −inf; the logarithms taken apart give m_sun − 2.5·(−321.19 − 3) = 783.72.
        let m = apparent(6.5e-322, 1.0e3, SUN_MAGNITUDE).expect("positive light");
        let want = SUN_MAGNITUDE - 2.5 * (6.5e-322f64.log10() - 3.0);
        assert!(m.is_finite() && (m - want).abs() < 1e-9, "{m} vs {want}");
        assert!((m - 783.72).abs() < 0.01, "{m}");
    }
}
