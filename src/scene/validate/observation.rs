//! `observation`: a telescope, its detector and the sky (radiometry/ccd.rs).

use super::values::{err, in_range, positive};
use super::ValidationError;
use crate::radiometry::ccd::Observation;
use crate::scene::request::ObservationSpec;
use crate::scene::Illumination;

/// A number that must be ≥ 0 (and finite).
fn non_negative(field: &str, v: f64) -> Result<f64, ValidationError> {
    in_range(field, v, 0.0, f64::MAX)
}

/// A share in (0, 1].
fn share(field: &str, v: f64) -> Result<f64, ValidationError> {
    let v = in_range(field, v, 0.0, 1.0)?;
    if v == 0.0 {
        return err(field, "must be above 0 (nothing would be detected)");
    }
    Ok(v)
}

/// The request's observation, the defaults filled in.
pub(super) fn observation(
    spec: &ObservationSpec,
    illumination: &Illumination,
) -> Result<Observation, ValidationError> {
    if illumination.passband.is_none() {
        return err(
            "observation",
            "counts need a named `illumination.band` (its response and zero point): \
             e.g. \"band\": \"V\"",
        );
    }
    let f = |name: &str| format!("observation.{name}");
    let aperture_m = in_range(&f("aperture_m"), spec.aperture_m, 0.0, 50.0)?;
    if aperture_m == 0.0 {
        return err(f("aperture_m"), "must be above 0");
    }
    let exposure_s = in_range(&f("exposure_s"), spec.exposure_s, 0.0, 1e5)?;
    if exposure_s == 0.0 {
        return err(f("exposure_s"), "must be above 0");
    }
    let seeing = match spec.seeing_fwhm_arcsec {
        Some(v) => positive(&f("seeing_fwhm_arcsec"), v)?,
        None => 2.0,
    };
    let opt = |name: &str,
               v: Option<f64>,
               default: f64,
               check: fn(&str, f64) -> Result<f64, ValidationError>| {
        v.map_or(Ok(default), |v| check(&f(name), v))
    };
    Ok(Observation {
        aperture_m,
        obstruction: match spec.obstruction {
            Some(v) => in_range(&f("obstruction"), v, 0.0, 0.99)?,
            None => 0.0,
        },
        exposure_s,
        quantum_efficiency: opt("quantum_efficiency", spec.quantum_efficiency, 1.0, share)?,
        throughput: opt("throughput", spec.throughput, 1.0, share)?,
        pixel_scale_arcsec: opt("pixel_scale_arcsec", spec.pixel_scale_arcsec, 1.0, positive)?,
        seeing_fwhm_arcsec: seeing,
        aperture_radius_arcsec: opt(
            "aperture_radius_arcsec",
            spec.aperture_radius_arcsec,
            seeing,
            positive,
        )?,
        read_noise_e: opt("read_noise_e", spec.read_noise_e, 0.0, non_negative)?,
        dark_e_per_s: opt("dark_e_per_s", spec.dark_e_per_s, 0.0, non_negative)?,
        gain_e_per_adu: opt("gain_e_per_adu", spec.gain_e_per_adu, 1.0, positive)?,
        full_well_e: spec
            .full_well_e
            .map(|v| positive(&f("full_well_e"), v))
            .transpose()?,
        sky_mag_per_arcsec2: spec
            .sky_mag_per_arcsec2
            .map(|v| in_range(&f("sky_mag_per_arcsec2"), v, -10.0, 40.0))
            .transpose()?,
        airmass: match spec.airmass {
            Some(v) => in_range(&f("airmass"), v, 1.0, 40.0)?,
            None => 1.0,
        },
        extinction_mag_per_airmass: match spec.extinction_mag_per_airmass {
            Some(v) => in_range(&f("extinction_mag_per_airmass"), v, 0.0, 10.0)?,
            None => 0.0,
        },
        seed: spec.seed.unwrap_or(0),
    })
}

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::{check, refused};
    use serde_json::json;

    #[test]
    fn an_observation_is_checked_field_by_field() {
        let e = refused(|v| v["observation"] = json!({"aperture_m": 0.5, "exposure_s": 1.0}));
        assert_eq!(e.field, "observation");
        assert!(e.message.contains("named `illumination.band`"), "{e}");
        let with = |o: serde_json::Value| {
            refused(move |v| {
                v["illumination"] = json!({"band": "V"});
                v["observation"] = o.clone();
            })
        };
        assert_eq!(
            with(json!({"exposure_s": 1.0})).field,
            "observation.aperture_m"
        );
        assert_eq!(
            with(json!({"aperture_m": -1.0, "exposure_s": 1.0})).field,
            "observation.aperture_m"
        );
        assert_eq!(
            with(json!({"aperture_m": 0.5, "exposure_s": 0.0})).field,
            "observation.exposure_s"
        );
        for (name, bad) in [
            ("quantum_efficiency", json!(1.5)),
            ("throughput", json!(0.0)),
            ("obstruction", json!(1.0)),
            ("pixel_scale_arcsec", json!(0.0)),
            ("seeing_fwhm_arcsec", json!(-2.0)),
            ("aperture_radius_arcsec", json!(0.0)),
            ("read_noise_e", json!(-1.0)),
            ("dark_e_per_s", json!(-0.1)),
            ("gain_e_per_adu", json!(0.0)),
            ("full_well_e", json!(0.0)),
            ("sky_mag_per_arcsec2", json!(99.0)),
            ("airmass", json!(0.5)),
            ("extinction_mag_per_airmass", json!(-0.1)),
            ("seed", json!(-1)),
            ("apperture", json!(1.0)),
        ] {
            let mut o = json!({"aperture_m": 0.5, "exposure_s": 1.0});
            o[name] = bad;
            let e = with(o);
            assert!(e.field.starts_with("observation"), "{name}: {e}");
            if name != "apperture" && name != "seed" {
                assert_eq!(e.field, format!("observation.{name}"), "{e}");
            }
        }
        let s = check(|v| {
            v["illumination"] = json!({"band": "V"});
            v["observation"] =
                json!({"aperture_m": 0.5, "exposure_s": 2.0, "seeing_fwhm_arcsec": 3.0});
        })
        .expect("valid");
        let o = s.observation.expect("an observation");
        assert_eq!(
            (o.aperture_radius_arcsec, o.quantum_efficiency, o.airmass),
            (3.0, 1.0, 1.0)
        );
    }
}
