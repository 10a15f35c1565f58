//! The Sun's geocentric position: the low-accuracy solar coordinates of Meeus,
//! *Astronomical Algorithms* (2nd ed., ch. 25), stated there to 0.01°.
//!
//! T = (JD(TT) − 2451545.0)/36525;
//! L0 = 280.46646° + 36000.76983° T + 0.0003032° T² (mean longitude),
//! M = 357.52911° + 35999.05029° T − 0.0001537° T² (mean anomaly),
//! e = 0.016708634 − 0.000042037 T − 0.0000001267 T²,
//! C = (1.914602° − 0.004817° T − 0.000014° T²) sin M + (0.019993° − 0.000101° T) sin 2M
//!     + 0.000289° sin 3M (equation of the centre),
//! ☉ = L0 + C (true longitude, mean equinox of date), R = 1.000001018 (1 − e²)/(1 + e cos(M + C)) AU,
//! Ω = 125.04° − 1934.136° T, ε = ε0 + 0.00256° cos Ω (true obliquity, ε0 the IAU-80 mean).
//!
//! In TEME (true equator, mean equinox) the direction is that of longitude ☉ − 0.00569°
//! (the annual aberration, as the light arrives) on the ecliptic tilted by the true
//! obliquity; Meeus' −0.00478° sin Ω nutation in longitude is left out, TEME's equinox
//! being the mean one. Measured against ERFA's epv00 (VSOP2000-based) over 2025–2028:
//! ≤ 32″ (tests/orbit.rs).

use super::time::{UtcTime, TT_MINUS_UTC_S};
use crate::radiometry::AU_M;
use glam::DVec3;

/// The stated accuracy of the direction, degrees.
pub const STATED_ERROR_DEG: f64 = 0.01;

/// Geocentric Sun at UTC instant `t`: (unit vector in TEME, distance in m).
pub fn position(t: UtcTime) -> (DVec3, f64) {
    let (days, frac) = t.j2000_days_split(TT_MINUS_UTC_S);
    let tc = (days + frac) / 36_525.0;
    let l0 = 280.466_46 + 36_000.769_83 * tc + 0.000_303_2 * tc * tc;
    let m = (357.529_11 + 35_999.050_29 * tc - 0.000_153_7 * tc * tc).to_radians();
    let e = 0.016_708_634 - 0.000_042_037 * tc - 0.000_000_126_7 * tc * tc;
    let c = (1.914_602 - 0.004_817 * tc - 0.000_014 * tc * tc) * m.sin()
        + (0.019_993 - 0.000_101 * tc) * (2.0 * m).sin()
        + 0.000_289 * (3.0 * m).sin();
    let true_longitude = l0 + c;
    let nu = m + c.to_radians();
    // 1 + e cos ν ≥ 1 − 0.017 > 0
    let r_au = 1.000_001_018 * (1.0 - e * e) / (1.0 + e * nu.cos());
    let omega = (125.04 - 1_934.136 * tc).to_radians();
    let eps0 = 23.0 + 26.0 / 60.0 + 21.448 / 3600.0
        - (46.815_0 * tc + 0.000_59 * tc * tc - 0.001_813 * tc * tc * tc) / 3600.0;
    let eps = (eps0 + 0.002_56 * omega.cos()).to_radians();
    let lambda = (true_longitude - 0.005_69).rem_euclid(360.0).to_radians();
    let (sl, cl) = lambda.sin_cos();
    let (se, ce) = eps.sin_cos();
    (DVec3::new(cl, ce * sl, se * sl), r_au * AU_M)
}
