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
    let (given, sky, warnings) = match built {
        Some(b) => (Some(b.epochs), b.sky, b.warnings),
        None => (None, Vec::new(), Vec::new()),
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
