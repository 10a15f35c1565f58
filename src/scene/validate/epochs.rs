//! `epochs` (or `geometry`): each epoch's time, Sun, observer, Earth and attitude, turned
//! into the body frame; then the checks that need the object and the illumination (the
//! observer outside the object, an Earth where earthshine needs one).

use super::values::{err, finite, in_range, vector};
use super::{Limits, ValidationError};
use crate::geometry::Mesh;
use crate::orbit::time::parse_utc;
use crate::orbit::UtcTime;
use crate::radiometry::{AU_M, EARTH_RADIUS_M};
use crate::scene::request::{EpochSpec, Request, TimeSpec};
use crate::scene::{EarthshineModel, Epoch, Illumination, Sky};
use glam::DQuat;

/// A request's epochs in the body frame, with what a `geometry` adds to them.
pub(super) struct Epochs {
    pub epochs: Vec<Epoch>,
    /// What the ground site sees at each epoch (empty for explicit `epochs`).
    pub sky: Vec<Sky>,
    /// Notes for the response (from `geometry`).
    pub warnings: Vec<String>,
    /// Unix seconds of a `geometry`'s `times.start` (0 for explicit `epochs`).
    pub origin: f64,
}

/// The request's epochs, given (`epochs`) or computed (`geometry`, exactly one of the
/// two), checked against the object (`mesh`, m) and the illumination.
pub(super) fn epochs(
    req: &Request,
    limits: &Limits,
    mesh: &Mesh,
    illumination: &Illumination,
) -> Result<Epochs, ValidationError> {
    let (epoch_specs, built) = match (&req.epochs, &req.geometry) {
        (Some(_), Some(_)) => {
            return err("geometry", "give either `epochs` or `geometry`, not both")
        }
        (None, None) => return err("epochs", "is required (or give `geometry`)"),
        (Some(e), None) => (e.as_slice(), None),
        (None, Some(g)) => (&[][..], Some(crate::scene::geometry::build(g, limits)?)),
    };
    if built.is_none() && epoch_specs.is_empty() {
        return err("epochs", "must list at least one epoch");
    }
    if epoch_specs.len() > limits.max_epochs {
        return err(
            "epochs",
            format!(
                "too many epochs: {} (limit {})",
                epoch_specs.len(),
                limits.max_epochs
            ),
        );
    }
    let earthshine_explicit = req
        .illumination
        .as_ref()
        .and_then(|i| i.earthshine.as_ref())
        .is_some();
    // Eq. 12 is a far-field sum (every face seen along one direction, at one range): an
    // observer inside the object's bounding sphere is no telescope
    let (centre, radius) = mesh.bounding_sphere();
    let (given, sky, warnings, origin) = match built {
        Some(b) => (Some(b.epochs), b.sky, b.warnings, b.start_unix),
        None => (None, Vec::new(), Vec::new(), 0.0),
    };
    let from_specs = given.is_none();
    let checked: Vec<Epoch> = match given {
        Some(e) => e,
        None => epoch_specs
            .iter()
            .enumerate()
            .map(|(i, e)| epoch(&format!("epochs[{i}]"), e))
            .collect::<Result<_, _>>()?,
    };
    // a geometry's epochs are named by their index in the computed list
    let name = |i: usize| {
        if from_specs {
            format!("epochs[{i}]")
        } else {
            format!("geometry (epoch {i})")
        }
    };
    let epochs = checked
        .into_iter()
        .enumerate()
        .map(|(i, ep)| {
            let range = (ep.observer - centre).length();
            if range <= radius {
                return err(
                    format!("{}.observer", name(i)),
                    format!(
                        "the observer is {range:.3e} m from the object's centre, within its \
                         bounding radius {radius:.3e} m: give the observer's position \
                         relative to the object, in metres, from outside it"
                    ),
                );
            }
            if ep.earth.is_none()
                && earthshine_explicit
                && illumination.earthshine != EarthshineModel::Off
            {
                return err(
                    format!("{}.earth", name(i)),
                    "is required when illumination.earthshine is not \"off\"",
                );
            }
            Ok(ep)
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Epochs {
        epochs,
        sky,
        warnings,
        origin,
    })
}

/// One given epoch (`field` is its path, e.g. `epochs[3]`), its vectors turned from the
/// inertial frame into the body frame when it has an attitude.
fn epoch(field: &str, e: &EpochSpec) -> Result<Epoch, ValidationError> {
    let t = match &e.t {
        TimeSpec::Seconds(s) => finite(&format!("{field}.t"), *s)?,
        TimeSpec::Iso(s) => {
            parse_time(s).map_err(|m| ValidationError::new(format!("{field}.t"), m))?
        }
    };
    let mut sun = vector(&format!("{field}.sun"), e.sun)?.normalize();
    let mut observer = vector(&format!("{field}.observer"), e.observer)?;
    let mut earth = e
        .earth
        .map(|v| vector(&format!("{field}.earth"), v))
        .transpose()?;
    if let Some(q) = e.attitude {
        let qf = format!("{field}.attitude");
        let q = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
        if !q.is_finite() || (q.length() - 1.0).abs() > 1e-6 {
            return err(qf, "must be a unit quaternion [w, x, y, z]");
        }
        // attitude rotates body → inertial; the vectors are inertial
        let inv = q.inverse();
        sun = inv * sun;
        observer = inv * observer;
        earth = earth.map(|v| inv * v);
    }
    if let Some(d) = earth {
        if d.length() <= EARTH_RADIUS_M {
            return err(
                format!("{field}.earth"),
                format!(
                    "object is inside the Earth: |earth| = {:.0} m <= 6371 km",
                    d.length()
                ),
            );
        }
    }
    let au = match e.sun_distance_au {
        None => 1.0,
        Some(d) => in_range(&format!("{field}.sun_distance_au"), d, 0.01, 1000.0)?,
    };
    Ok(Epoch {
        t,
        sun,
        sun_distance_m: au * AU_M,
        observer,
        earth,
    })
}

/// ISO 8601 / RFC 3339 UTC time → Unix seconds. A missing zone is taken as UTC.
fn parse_time(s: &str) -> Result<f64, String> {
    parse_utc(s).map(UtcTime::unix).map_err(|_| {
        format!("`{s}` is neither seconds nor an ISO 8601 UTC time (e.g. 2026-11-22T04:50:00Z)")
    })
}

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::{check, check_with, refused};
    use crate::scene::validate::{Limits, ValidationError};
    use glam::DVec3;
    use serde_json::json;

    #[test]
    fn a_zero_sun_vector_is_named() {
        let e = refused(|v| v["epochs"][0]["sun"] = json!([0.0, 0.0, 0.0]));
        assert_eq!(
            e,
            ValidationError::new("epochs[0].sun", "must not be the zero vector")
        );
    }

    #[test]
    fn epochs_are_required_and_counted() {
        let e = refused(|v| {
            v.as_object_mut().unwrap().remove("epochs");
        });
        assert_eq!(
            e,
            ValidationError::new("epochs", "is required (or give `geometry`)")
        );
        let e = refused(|v| v["epochs"] = json!([]));
        assert_eq!(e.message, "must list at least one epoch");
        let limits = Limits {
            max_epochs: 1,
            ..Limits::default()
        };
        let two = |v: &mut serde_json::Value| {
            let e = v["epochs"][0].clone();
            v["epochs"] = json!([e.clone(), e]);
        };
        let e = check_with(two, &limits).unwrap_err();
        assert_eq!(
            e,
            ValidationError::new("epochs", "too many epochs: 2 (limit 1)")
        );
        assert!(e.is_limit());
    }

    #[test]
    fn the_observer_must_be_outside_the_object() {
        let e = refused(|v| v["epochs"][0]["observer"] = json!([0.5, 0.5, 0.1]));
        assert_eq!(e.field, "epochs[0].observer");
        assert!(e.message.contains("within its bounding radius"), "{e}");
    }

    #[test]
    fn an_earthshine_model_needs_the_earth() {
        let e = refused(|v| v["illumination"] = json!({"earthshine": "sphere"}));
        assert_eq!(e.field, "epochs[0].earth");
        let scene = check(|v| {
            v["illumination"] = json!({"earthshine": "sphere"});
            v["epochs"][0]["earth"] = json!([0.0, 0.0, -7.0e6]);
        })
        .expect("valid");
        assert_eq!(scene.epochs[0].earth, Some(DVec3::new(0.0, 0.0, -7.0e6)));
    }

    #[test]
    fn an_attitude_turns_the_vectors_into_the_body_frame() {
        // 90° about +z, body → inertial: the inertial +x is the body's -y
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let scene = check(|v| {
            v["epochs"][0]["sun"] = json!([1.0, 0.0, 1.0]);
            v["epochs"][0]["attitude"] = json!([h, 0.0, 0.0, h]);
        })
        .expect("valid");
        let sun = scene.epochs[0].sun;
        assert!((sun - DVec3::new(0.0, -h, h)).length() < 1e-12, "{sun}");
        let e = refused(|v| v["epochs"][0]["attitude"] = json!([1.0, 1.0, 0.0, 0.0]));
        assert_eq!(
            e,
            ValidationError::new(
                "epochs[0].attitude",
                "must be a unit quaternion [w, x, y, z]"
            )
        );
    }

    #[test]
    fn a_time_is_seconds_or_iso_utc() {
        let scene = check(|v| v["epochs"][0]["t"] = json!("2026-11-22T04:50:00Z")).expect("valid");
        assert_eq!(scene.epochs[0].t, 1_795_323_000.0);
        let e = refused(|v| v["epochs"][0]["t"] = json!("yesterday"));
        assert_eq!(e.field, "epochs[0].t");
        assert!(
            e.message.starts_with("`yesterday` is neither seconds"),
            "{e}"
        );
    }
}
