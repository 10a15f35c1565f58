//! TEME ↔ PEF ↔ ITRF: the IAU-82 Greenwich mean sidereal time and polar motion.
//!
//! TEME (SGP4's frame: true equator, mean equinox of date) turns into the pseudo
//! Earth-fixed frame PEF by the IAU-82 GMST, r_PEF = R_z(−θ)·r_TEME (AIAA 2006-6753,
//! App. C; as skyfield's `TEME_to_ITRF`); PEF turns into ITRF by polar motion,
//! r_ITRF = R_x(y_p)·R_y(x_p)·r_PEF (small-angle rotations, right-handed matrices).

use super::time::{UtcTime, DAY_S};
use glam::{DMat3, DVec3};
use std::f64::consts::TAU;

/// Radians per arcsecond.
pub const ARCSEC: f64 = std::f64::consts::PI / (180.0 * 3600.0);

/// Earth orientation: UT1 − UTC (s) and the pole's offsets x_p, y_p (arcsec). All zero
/// when a request gives none (positions then err by ~0.5 km·|ΔUT1| s⁻¹ along the
/// equator and ~15 m per 0.5″ of pole offset at the surface).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EarthOrientation {
    pub dut1_s: f64,
    pub xp_arcsec: f64,
    pub yp_arcsec: f64,
}

/// Greenwich mean sidereal time (IAU-82, radians in [0, 2π)) at UTC instant `t` with
/// UT1 = UTC + `dut1_s`. The day's fraction is kept apart from the day count so that
/// the angle keeps full f64 precision.
pub fn gmst82(t: UtcTime, dut1_s: f64) -> f64 {
    let (days, frac) = t.j2000_days_split(dut1_s);
    let tu = (days + frac) / 36_525.0;
    // seconds of sidereal time at 0h UT1 less the whole-day count
    let g = 67_310.548_41 + (8_640_184.812_866 + (0.093_104 - 6.2e-6 * tu) * tu) * tu;
    let turns = (frac + (g / DAY_S).rem_euclid(1.0)).rem_euclid(1.0);
    turns * TAU
}

fn rot_x(a: f64) -> DMat3 {
    let (s, c) = a.sin_cos();
    DMat3::from_cols(
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, c, s),
        DVec3::new(0.0, -s, c),
    )
}

fn rot_y(a: f64) -> DMat3 {
    let (s, c) = a.sin_cos();
    DMat3::from_cols(
        DVec3::new(c, 0.0, -s),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(s, 0.0, c),
    )
}

/// R_z(a): the right-handed rotation by `a` about z (columns are the images of x, y, z).
pub fn rot_z(a: f64) -> DMat3 {
    let (s, c) = a.sin_cos();
    DMat3::from_cols(
        DVec3::new(c, s, 0.0),
        DVec3::new(-s, c, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
    )
}

/// The rotation taking TEME coordinates to ITRF at `t`.
pub fn teme_to_itrf(t: UtcTime, eop: &EarthOrientation) -> DMat3 {
    let theta = gmst82(t, eop.dut1_s);
    let w = rot_x(eop.yp_arcsec * ARCSEC) * rot_y(eop.xp_arcsec * ARCSEC);
    w * rot_z(-theta)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Vallado's example 3-5 (Fundamentals of Astrodynamics, 4th ed.): 1992-08-20
    /// 12:14 UT1 gives GMST 152.578 787 86°; tolerance 1e-8° (the book's digits).
    #[test]
    fn gmst_vallado() {
        let t = UtcTime::new(714_312_840, 0.0);
        let deg = gmst82(t, 0.0).to_degrees();
        assert!((deg - 152.578_787_86).abs() < 1e-8, "{deg}");
    }
}
