//! Solar irradiance at the object (Eq. 2).

use super::{planck, AU_M, SUN_RADIUS_M};

/// Band solar irradiance at `distance_m` from the Sun, W/m²: (R_s/D)² M_s.
pub fn band_irradiance(band_um: [f64; 2], temperature_k: f64, distance_m: f64) -> f64 {
    let ratio = SUN_RADIUS_M / distance_m;
    ratio * ratio * planck::band_exitance(band_um[0], band_um[1], temperature_k)
}

/// Band solar irradiance at 1 AU, W/m²: the reference of the magnitude scale.
pub fn band_irradiance_1au(band_um: [f64; 2], temperature_k: f64) -> f64 {
    band_irradiance(band_um, temperature_k, AU_M)
}

/// Angular radius of the Sun seen from `distance_m`, rad.
pub fn angular_radius(distance_m: f64) -> f64 {
    (SUN_RADIUS_M / distance_m).min(1.0).asin()
}
