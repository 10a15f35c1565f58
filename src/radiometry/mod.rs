//! Illumination and its measures: the Sun's band irradiance (Eqs. 1–2), earthshine
//! (Eq. 3 and the sunlit-sphere model), eclipses by the Earth, and magnitudes.

pub mod bands;
pub mod ccd;
pub mod earth;
pub mod eclipse;
pub mod magnitude;
pub mod planck;
pub mod sun;

/// Earth's mean radius, m.
pub const EARTH_RADIUS_M: f64 = 6.371e6;
/// Sun's radius, m (the paper's value).
pub const SUN_RADIUS_M: f64 = 6.9599e8;
/// Astronomical unit, m (the paper's value).
pub const AU_M: f64 = 1.49597892e11;
