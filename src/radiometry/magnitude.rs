//! Apparent magnitudes, band-consistent: the Sun's band irradiance at 1 AU is −26.74.

/// The Sun's apparent magnitude (V band), the zero point of glint's scale.
pub const SUN_MAGNITUDE: f64 = -26.74;

/// m = −26.74 − 2.5 log10(E / E_sun). `None` for no light at all (E ≤ 0); any positive
/// E, however faint, gets a finite magnitude.
pub fn apparent(irradiance_w_m2: f64, sun_band_1au_w_m2: f64) -> Option<f64> {
    if irradiance_w_m2 > 0.0 && irradiance_w_m2.is_finite() {
        Some(SUN_MAGNITUDE - 2.5 * (irradiance_w_m2 / sun_band_1au_w_m2).log10())
    } else {
        None
    }
}

/// Magnitude rescaled to a 1000 km range: m − 5 log10(R / 1e6 m).
pub fn standardised(magnitude: Option<f64>, range_m: f64) -> Option<f64> {
    magnitude.map(|m| m - 5.0 * (range_m / 1.0e6).log10())
}
