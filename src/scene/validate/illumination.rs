//! `illumination`: the Sun's band and temperature, and the earthshine model and albedo.

use super::values::{err, finite, in_range};
use super::ValidationError;
use crate::radiometry::bands::{self, SolarSpectrum};
use crate::radiometry::{planck, sun, AU_M, SUN_RADIUS_M};
use crate::scene::request::{IlluminationSpec, Request};
use crate::scene::{EarthshineModel, Illumination, SolarSpectrumChoice};

/// The least band irradiance of the Sun at 1 AU a request may ask for, W/m²: a scene's
/// geometry (albedo × area / range²) can take another hundred decades off it before f64
/// underflows, where a magnitude would turn `null` although light arrives.
pub const MIN_SUN_BAND_1AU_W_M2: f64 = 1e-200;

/// The request's illumination, the defaults filled in; checked in the order of its
/// fields' use: the band, the Sun, the sunlight in the band, the earthshine.
pub(super) fn illumination(req: &Request) -> Result<Illumination, ValidationError> {
    let mut out = Illumination::default();
    let Some(spec) = &req.illumination else {
        return Ok(out);
    };
    band(spec, &mut out)?;
    sun(spec, &mut out)?;
    out.sun_1au_w_m2 = sun_1au(&out)?;
    enough_sunlight(&out)?;
    earthshine(spec, &mut out)?;
    Ok(out)
}

/// The band: an interval `band_um` or a named passband (its range and the Sun's
/// magnitude in it), not both.
fn band(spec: &IlluminationSpec, out: &mut Illumination) -> Result<(), ValidationError> {
    if let Some([a, b]) = spec.band_um {
        finite("illumination.band_um[0]", a)?;
        finite("illumination.band_um[1]", b)?;
        if a < 0.0 || b <= a {
            return err(
                "illumination.band_um",
                format!("must be [λ1, λ2] in µm with 0 <= λ1 < λ2, got [{a}, {b}]"),
            );
        }
        out.band_um = [a, b];
    }
    if let Some(name) = &spec.band {
        if spec.band_um.is_some() {
            return err(
                "illumination.band",
                "give either `band` (a named passband) or `band_um` (an interval), not both",
            );
        }
        let Some(p) = bands::find(name) else {
            return err(
                "illumination.band",
                format!(
                    "unknown band `{name}`; expected one of {}",
                    bands::names().join(", ")
                ),
            );
        };
        out.passband = Some(p);
        out.band_um = p.range_um();
        out.sun_magnitude = p.sun_magnitude;
    }
    Ok(())
}

/// The Sun: its temperature (for Planck) and which solar spectrum.
fn sun(spec: &IlluminationSpec, out: &mut Illumination) -> Result<(), ValidationError> {
    if let Some(t) = spec.sun_temperature_k {
        out.sun_temperature_k = in_range("illumination.sun_temperature_k", t, 100.0, 100_000.0)?;
    }
    if let Some(s) = &spec.solar_spectrum {
        out.solar_spectrum = match s.as_str() {
            "planck" => SolarSpectrumChoice::Planck,
            "calspec" => SolarSpectrumChoice::Calspec,
            other => {
                return err(
                    "illumination.solar_spectrum",
                    format!("unknown spectrum `{other}`; expected planck or calspec"),
                )
            }
        };
    }
    Ok(())
}

/// The Sun's irradiance in the band at 1 AU, W/m²; an interval outside the CALSPEC
/// spectrum's range is refused.
fn sun_1au(out: &Illumination) -> Result<f64, ValidationError> {
    let [a, b] = out.band_um;
    let t = out.sun_temperature_k;
    Ok(match (out.passband, out.solar_spectrum) {
        (None, SolarSpectrumChoice::Planck) => sun::band_irradiance_1au(out.band_um, t),
        (Some(p), SolarSpectrumChoice::Planck) => SolarSpectrum::Planck(t).band_1au(p),
        (Some(p), SolarSpectrumChoice::Calspec) => SolarSpectrum::Calspec.band_1au(p),
        (None, SolarSpectrumChoice::Calspec) => {
            let Some(e) = SolarSpectrum::calspec_interval_1au(out.band_um) else {
                let [lo, hi] = bands::calspec_range_um();
                return err(
                    "illumination.band_um",
                    format!(
                        "[{a}, {b}] µm leaves the CALSPEC solar spectrum ({lo}–{hi} µm); choose a band within it or `solar_spectrum: planck`"
                    ),
                );
            };
            e
        }
    })
}

/// A band far in the Wien tail of a cold Sun (0.01–0.05 µm at 300 K: ~1e-410 W/m²)
/// holds light that no f64 can carry through a scene: say so rather than answer 0.
fn enough_sunlight(out: &Illumination) -> Result<(), ValidationError> {
    let [a, b] = out.band_um;
    let t = out.sun_temperature_k;
    let ln_es = if out.passband.is_none() && out.solar_spectrum == SolarSpectrumChoice::Planck {
        planck::ln_band_exitance(a, b, t) + 2.0 * (SUN_RADIUS_M / AU_M).ln()
    } else {
        out.sun_1au_w_m2.ln()
    };
    if ln_es.is_nan() || ln_es < MIN_SUN_BAND_1AU_W_M2.ln() {
        let field = if out.passband.is_some() {
            "illumination.band"
        } else {
            "illumination.band_um"
        };
        return err(
            field,
            format!(
                "[{a}, {b}] µm holds almost none of a {t} K Sun's light: its irradiance at \
                 1 AU would be 1e{:.0} W/m², below the {MIN_SUN_BAND_1AU_W_M2:e} W/m² that \
                 f64 radiometry carries through a scene; choose a longer band or a hotter Sun",
                ln_es / std::f64::consts::LN_10
            ),
        );
    }
    Ok(())
}

/// The earthshine model and the Earth's albedo.
fn earthshine(spec: &IlluminationSpec, out: &mut Illumination) -> Result<(), ValidationError> {
    if let Some(e) = &spec.earthshine {
        out.earthshine = match e.as_str() {
            "off" => EarthshineModel::Off,
            "seed" => EarthshineModel::Seed,
            "sphere" => EarthshineModel::Sphere,
            other => {
                return err(
                    "illumination.earthshine",
                    format!("unknown model `{other}`; expected off, seed or sphere"),
                )
            }
        };
    }
    if let Some(a) = spec.earth_albedo {
        out.earth_albedo = in_range("illumination.earth_albedo", a, 0.0, 1.0)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::{check, refused};
    use crate::scene::validate::ValidationError;
    use crate::scene::EarthshineModel;
    use serde_json::json;

    #[test]
    fn a_band_runs_from_short_to_long() {
        let e = refused(|v| v["illumination"] = json!({"band_um": [0.9, 0.4]}));
        assert_eq!(
            e,
            ValidationError::new(
                "illumination.band_um",
                "must be [λ1, λ2] in µm with 0 <= λ1 < λ2, got [0.9, 0.4]"
            )
        );
    }

    #[test]
    fn a_band_with_almost_no_sunlight_is_refused() {
        let e = refused(|v| {
            v["illumination"] = json!({"band_um": [0.01, 0.05], "sun_temperature_k": 300.0})
        });
        assert_eq!(e.field, "illumination.band_um");
        assert!(
            e.message
                .contains("holds almost none of a 300 K Sun's light"),
            "{e}"
        );
    }

    #[test]
    fn a_named_band_is_known_and_alone() {
        let e = refused(|v| v["illumination"] = json!({"band": "U"}));
        assert_eq!(e.field, "illumination.band");
        assert!(
            e.message
                .contains("unknown band `U`; expected one of V, B, R, G, g, r, i, clear"),
            "{e}"
        );
        let e = refused(|v| v["illumination"] = json!({"band": "V", "band_um": [0.4, 0.7]}));
        assert_eq!(e.field, "illumination.band");
        let e = refused(|v| v["illumination"] = json!({"band": 5}));
        assert_eq!(e.field, "illumination.band");
        let e = refused(|v| v["illumination"] = json!({"solar_spectrum": "kurucz"}));
        assert_eq!(
            e,
            ValidationError::new(
                "illumination.solar_spectrum",
                "unknown spectrum `kurucz`; expected planck or calspec"
            )
        );
        let e = refused(|v| {
            v["illumination"] = json!({"band_um": [0.05, 0.7], "solar_spectrum": "calspec"})
        });
        assert_eq!(e.field, "illumination.band_um");
        assert!(
            e.message.contains("leaves the CALSPEC solar spectrum"),
            "{e}"
        );
        let scene = check(|v| v["illumination"] = json!({"band": "g"})).expect("valid");
        let ill = scene.illumination;
        assert_eq!(ill.passband.map(|p| p.name), Some("g"));
        assert_eq!(ill.sun_magnitude, -26.46);
        assert!(ill.sun_1au_w_m2 > 0.0 && ill.sun_1au_w_m2.is_finite());
        let scene = check(|v| {
            v["illumination"] = json!({"band_um": [0.4, 0.7], "solar_spectrum": "calspec"})
        })
        .expect("valid");
        assert_eq!(scene.illumination.sun_magnitude, -26.74);
    }

    #[test]
    fn the_earthshine_model_is_named_and_defaults_apply() {
        let e = refused(|v| v["illumination"] = json!({"earthshine": "moon"}));
        assert_eq!(
            e,
            ValidationError::new(
                "illumination.earthshine",
                "unknown model `moon`; expected off, seed or sphere"
            )
        );
        let e = refused(|v| v["illumination"] = json!({"earth_albedo": -0.1}));
        assert_eq!(e.field, "illumination.earth_albedo");
        let scene = check(|v| v["illumination"] = json!({"earthshine": "off"})).expect("valid");
        assert_eq!(scene.illumination.earthshine, EarthshineModel::Off);
        assert_eq!(
            scene.illumination.band_um,
            crate::scene::Illumination::default().band_um
        );
    }
}
