//! `geometry` → epochs: the request's orbit, site, window and attitude law validated at
//! the boundary (every error naming its field) and turned into body-frame epochs by
//! [`crate::orbit`].

use super::request::{
    AttitudeSpec, EarthOrientationSpec, GeometrySpec, InertiaSpec, OrbitSpec, TimeSpec,
};
use super::{Epoch, Limits, Sky, ValidationError};
use crate::orbit::attitude::{Law, State, Tumble};
use crate::orbit::frames::EarthOrientation;
use crate::orbit::site::Site;
use crate::orbit::time::parse_utc;
use crate::orbit::tle::ElementSet;
use crate::orbit::{pass, UtcTime};
use crate::radiometry::EARTH_RADIUS_M;
use glam::{DMat3, DQuat, DVec3};

/// Most epochs one `geometry` window may hold, whatever the limits (80 bytes each).
pub const MAX_GEOMETRY_EPOCHS: usize = 10_000_000;
/// How far from the element set's epoch a window may reach, days: SGP4's errors grow
/// by ~1–3 km a day in LEO, and beyond a month an element set says little.
pub const MAX_DAYS_FROM_EPOCH: f64 = 30.0;

/// Most integration steps a triaxial `tumble` may take over its window (~45 rotations
/// each: about ten seconds of one core).
pub const MAX_TUMBLE_STEPS: f64 = 5e7;

/// The epochs, what the site sees at each, and warnings for the response.
pub struct Built {
    pub epochs: Vec<Epoch>,
    pub sky: Vec<Sky>,
    pub warnings: Vec<String>,
}

fn err<T>(field: impl Into<String>, message: impl Into<String>) -> Result<T, ValidationError> {
    Err(ValidationError::new(field, message))
}

fn number(field: &str, v: f64, lo: f64, hi: f64) -> Result<f64, ValidationError> {
    if !v.is_finite() {
        return err(field, "must be a finite number");
    }
    if v < lo || v > hi {
        return err(field, format!("must be between {lo} and {hi}, got {v}"));
    }
    Ok(v)
}

fn unit_quaternion(field: &str, q: [f64; 4]) -> Result<DQuat, ValidationError> {
    let q = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
    if !q.is_finite() || (q.length() - 1.0).abs() > 1e-6 {
        return err(field, "must be a unit quaternion [w, x, y, z]");
    }
    Ok(q.normalize())
}

fn direction(field: &str, v: [f64; 3]) -> Result<DVec3, ValidationError> {
    let d = DVec3::from_array(v);
    if !d.is_finite() {
        return err(field, "must have three finite components");
    }
    let l = d.length();
    if !(l > 1e-150 && l < 1e150) {
        return err(field, "must be a direction: not zero, length below 1e150");
    }
    Ok(d / l)
}

fn element_set(spec: &OrbitSpec) -> Result<ElementSet, ValidationError> {
    match (&spec.tle, &spec.omm) {
        (Some(lines), None) => ElementSet::from_tle(lines).map_err(|e| {
            let field = match e.line {
                Some(i) => format!("geometry.orbit.tle[{i}]"),
                None => "geometry.orbit.tle".to_string(),
            };
            ValidationError::new(field, e.message)
        }),
        (None, Some(omm)) => ElementSet::from_omm_json(omm)
            .map_err(|e| ValidationError::new("geometry.orbit.omm", e.message)),
        _ => err("geometry.orbit", "give exactly one of `tle` or `omm`"),
    }
}

fn earth_orientation(
    spec: Option<&EarthOrientationSpec>,
) -> Result<EarthOrientation, ValidationError> {
    let Some(s) = spec else {
        return Ok(EarthOrientation::default());
    };
    let f = "geometry.earth_orientation";
    Ok(EarthOrientation {
        dut1_s: number(&format!("{f}.dut1_s"), s.dut1_s.unwrap_or(0.0), -1.0, 1.0)?,
        xp_arcsec: number(
            &format!("{f}.xp_arcsec"),
            s.xp_arcsec.unwrap_or(0.0),
            -2.0,
            2.0,
        )?,
        yp_arcsec: number(
            &format!("{f}.yp_arcsec"),
            s.yp_arcsec.unwrap_or(0.0),
            -2.0,
            2.0,
        )?,
    })
}

/// Rejects the attitude parameters that `law` does not take, naming the first.
fn only(a: &AttitudeSpec, allowed: &[&str]) -> Result<(), ValidationError> {
    let given = [
        ("yaw_deg", a.yaw_deg.is_some()),
        ("quaternion", a.quaternion.is_some()),
        ("axis", a.axis.is_some()),
        ("rate_deg_s", a.rate_deg_s.is_some()),
        ("phase_deg", a.phase_deg.is_some()),
        ("series", a.series.is_some()),
        ("inertia_kg_m2", a.inertia_kg_m2.is_some()),
        ("omega_deg_s", a.omega_deg_s.is_some()),
    ];
    for (name, present) in given {
        if present && !allowed.contains(&name) {
            return err(
                format!("geometry.attitude.{name}"),
                format!("is not a parameter of law `{}`", a.law),
            );
        }
    }
    Ok(())
}

fn required<T: Copy>(name: &str, v: Option<T>, law: &str) -> Result<T, ValidationError> {
    v.ok_or_else(|| {
        ValidationError::new(
            format!("geometry.attitude.{name}"),
            format!("is required by law `{law}`"),
        )
    })
}

fn attitude(a: &AttitudeSpec, start: UtcTime, stop: UtcTime) -> Result<Law, ValidationError> {
    let f = |p: &str| format!("geometry.attitude.{p}");
    let q_or_identity = |a: &AttitudeSpec| {
        a.quaternion
            .map(|q| unit_quaternion(&f("quaternion"), q))
            .transpose()
            .map(|q| q.unwrap_or(DQuat::IDENTITY))
    };
    match a.law.as_str() {
        "nadir" => {
            only(a, &["yaw_deg"])?;
            let yaw = number(&f("yaw_deg"), a.yaw_deg.unwrap_or(0.0), -360.0, 360.0)?;
            Ok(Law::Nadir {
                yaw: yaw.to_radians(),
            })
        }
        "sun-pointing" => {
            only(a, &[])?;
            Ok(Law::SunPointing)
        }
        "inertial" => {
            only(a, &["quaternion"])?;
            let q = required("quaternion", a.quaternion, &a.law)?;
            Ok(Law::Inertial {
                q: unit_quaternion(&f("quaternion"), q)?,
            })
        }
        "spin" => {
            only(a, &["axis", "rate_deg_s", "phase_deg", "quaternion"])?;
            let axis = direction(&f("axis"), required("axis", a.axis, &a.law)?)?;
            let rate = number(
                &f("rate_deg_s"),
                required("rate_deg_s", a.rate_deg_s, &a.law)?,
                -36_000.0,
                36_000.0,
            )?;
            let phase = number(&f("phase_deg"), a.phase_deg.unwrap_or(0.0), -360.0, 360.0)?;
            Ok(Law::Spin {
                axis,
                rate: rate.to_radians(),
                phase: phase.to_radians(),
                q0: q_or_identity(a)?,
            })
        }
        "quaternions" => {
            only(a, &["series"])?;
            let Some(samples) = &a.series else {
                return err(f("series"), "is required by law `quaternions`");
            };
            if samples.is_empty() {
                return err(f("series"), "must hold at least one sample");
            }
            let mut series = Vec::with_capacity(samples.len());
            for (i, s) in samples.iter().enumerate() {
                let tf = f(&format!("series[{i}].t"));
                let t = match &s.t {
                    TimeSpec::Seconds(x) => number(&tf, *x, -1e10, 1e10)?,
                    TimeSpec::Iso(text) => parse_utc(text)
                        .map_err(|m| ValidationError::new(&tf, m))?
                        .seconds_since(start),
                };
                if let Some(&(prev, _)) = series.last() {
                    if t <= prev {
                        return err(tf, "times must increase from sample to sample");
                    }
                }
                let q = unit_quaternion(&f(&format!("series[{i}].q")), s.q)?;
                series.push((t, q));
            }
            let span = stop.seconds_since(start);
            let (first, last) = (series[0].0, series[series.len() - 1].0);
            if first > 0.0 || last < span {
                return err(
                    f("series"),
                    format!(
                        "covers {first} s to {last} s after times.start, but the window runs \
                         from 0 to {span} s: the series must cover it (no extrapolation)"
                    ),
                );
            }
            Ok(Law::Quaternions { series })
        }
        "tumble" => {
            only(a, &["inertia_kg_m2", "omega_deg_s", "quaternion"])?;
            let Some(inertia) = &a.inertia_kg_m2 else {
                return err(f("inertia_kg_m2"), "is required by law `tumble`");
            };
            let tensor = match inertia {
                InertiaSpec::Principal(m) => DMat3::from_diagonal(DVec3::from_array(*m)),
                InertiaSpec::Tensor(t) => {
                    let m = DMat3::from_cols_array_2d(t).transpose();
                    let tol = 1e-9 * m.to_cols_array().iter().fold(0.0f64, |a, b| a.max(b.abs()));
                    if (m - m.transpose()).to_cols_array().iter().any(|d| d.abs() > tol) {
                        return err(f("inertia_kg_m2"), "the tensor must be symmetric");
                    }
                    m
                }
            };
            if !tensor.is_finite() {
                return err(f("inertia_kg_m2"), "must hold finite numbers");
            }
            let omega = DVec3::from_array(required("omega_deg_s", a.omega_deg_s, &a.law)?);
            if !omega.is_finite() || omega.length() > 36_000.0 {
                return err(
                    f("omega_deg_s"),
                    "must be finite and below 36000 °/s in magnitude",
                );
            }
            let tumble = Tumble::new(tensor, q_or_identity(a)?, omega * (1f64.to_radians()));
            let m = tumble.moments;
            let big = m.max_element();
            if !(m.min_element() > 1e-12 * big && big < 1e15) {
                return err(
                    f("inertia_kg_m2"),
                    format!(
                        "principal moments {:?} kg·m² must be positive (and below 1e15)",
                        m.to_array()
                    ),
                );
            }
            // a rigid body's moments obey the triangle inequality (a thin plate: equality)
            let slack = 1e-9 * big;
            if m.x + m.y < m.z - slack || m.y + m.z < m.x - slack || m.x + m.z < m.y - slack {
                return err(
                    f("inertia_kg_m2"),
                    format!(
                        "principal moments {:?} kg·m² break the triangle inequality \
                         (I_a + I_b ≥ I_c): no rigid body has them",
                        m.to_array()
                    ),
                );
            }
            let steps = tumble.steps_for(stop.seconds_since(start));
            if steps > MAX_TUMBLE_STEPS {
                return err(
                    f("omega_deg_s"),
                    format!(
                        "too large: this triaxial tumble over the window needs {steps:.2e} \
                         integration steps (limit {MAX_TUMBLE_STEPS:e}); shorten the window \
                         or slow the spin"
                    ),
                );
            }
            Ok(Law::Tumble(tumble))
        }
        other => err(
            f("law"),
            format!("unknown law `{other}`; expected nadir, sun-pointing, inertial, spin, quaternions or tumble"),
        ),
    }
}

/// Validates `geometry` and computes its epochs (after `visible_only`).
pub fn build(g: &GeometrySpec, limits: &Limits) -> Result<Built, ValidationError> {
    let set = element_set(&g.orbit)?;
    let site = Site {
        lat_deg: number("geometry.site.lat_deg", g.site.lat_deg, -90.0, 90.0)?,
        lon_deg: number("geometry.site.lon_deg", g.site.lon_deg, -180.0, 360.0)?,
        alt_m: number(
            "geometry.site.alt_m",
            g.site.alt_m.unwrap_or(0.0),
            -500.0,
            1e5,
        )?,
    };
    let start =
        parse_utc(&g.times.start).map_err(|m| ValidationError::new("geometry.times.start", m))?;
    let stop =
        parse_utc(&g.times.stop).map_err(|m| ValidationError::new("geometry.times.stop", m))?;
    let step = number("geometry.times.step_s", g.times.step_s, 1e-3, 1e8)?;
    let span = stop.seconds_since(start);
    if span < 0.0 {
        return err("geometry.times.stop", "must not be before `start`");
    }
    for (field, t) in [
        ("geometry.times.start", start),
        ("geometry.times.stop", stop),
    ] {
        let days = t.seconds_since(set.epoch) / 86_400.0;
        if days.abs() > MAX_DAYS_FROM_EPOCH {
            return err(
                field,
                format!(
                    "is {days:.1} days from the element set's epoch ({}): SGP4 is only \
                     trusted within {MAX_DAYS_FROM_EPOCH} days of it",
                    set.elements.datetime
                ),
            );
        }
    }
    // floor(span / step) + 1 epochs; span ≤ 60 days and step ≥ 1 ms keep it finite
    let n = (span / step + 1e-9).floor() as usize + 1;
    let cap = limits.max_epochs.min(MAX_GEOMETRY_EPOCHS);
    if n > cap {
        return err(
            "geometry.times",
            format!("too many epochs: {n} (limit {cap}); widen `step_s` or shorten the window"),
        );
    }
    let eop = earth_orientation(g.earth_orientation.as_ref())?;
    let law = attitude(&g.attitude, start, stop)?;
    let (min_el, max_sun_el) = match &g.visible_only {
        None => (None, None),
        Some(v) => (
            Some(number(
                "geometry.visible_only.min_elevation_deg",
                v.min_elevation_deg.unwrap_or(10.0),
                -90.0,
                90.0,
            )?),
            Some(number(
                "geometry.visible_only.max_sun_elevation_deg",
                v.max_sun_elevation_deg.unwrap_or(-6.0),
                -90.0,
                90.0,
            )?),
        ),
    };

    let mut instants = Vec::with_capacity(n);
    for k in 0..n {
        let t = start.plus(k as f64 * step);
        let at = pass::at(&set, &site, &eop, t).map_err(|m| {
            ValidationError::new(
                "geometry.orbit",
                format!("SGP4 fails {:.0} s after times.start: {m}", k as f64 * step),
            )
        })?;
        if at.r.length() <= EARTH_RADIUS_M {
            return err(
                "geometry.orbit",
                format!(
                    "the object is inside the Earth {:.0} s after times.start (|r| = {:.0} m): \
                     the orbit has decayed",
                    k as f64 * step,
                    at.r.length()
                ),
            );
        }
        let visible = min_el.is_none_or(|m| at.elevation_deg >= m)
            && max_sun_el.is_none_or(|m| at.sun_elevation_deg <= m);
        if visible {
            instants.push(at);
        }
    }
    if instants.is_empty() {
        return err(
            "geometry.visible_only",
            format!(
                "keeps no epoch: the object is never {} degrees or more above the horizon \
                 while the Sun is {} degrees or lower",
                min_el.unwrap_or(0.0),
                max_sun_el.unwrap_or(0.0)
            ),
        );
    }
    let states: Vec<State> = instants
        .iter()
        .map(|i| State {
            r: i.r,
            v: i.v,
            sun: i.to_sun().0,
            t: i.t.seconds_since(start),
        })
        .collect();
    let quats = law.quaternions(&states);
    let mut epochs = Vec::with_capacity(instants.len());
    let mut sky = Vec::with_capacity(instants.len());
    for (i, q) in instants.iter().zip(quats) {
        let inv = q.inverse();
        let (sun, sun_distance_m) = i.to_sun();
        epochs.push(Epoch {
            t: i.t.unix(),
            sun: (inv * sun).normalize(),
            sun_distance_m,
            observer: inv * (i.site - i.r),
            earth: Some(inv * -i.r),
        });
        sky.push(Sky {
            azimuth_deg: i.azimuth_deg,
            elevation_deg: i.elevation_deg,
            sun_elevation_deg: i.sun_elevation_deg,
        });
    }
    let mut warnings = Vec::new();
    if g.earth_orientation.is_none() {
        warnings.push(
            "geometry.earth_orientation not given: UT1 − UTC and the pole offsets are taken \
             as zero (|UT1 − UTC| < 0.9 s turns the Earth by up to 13.5″; the pole moves up \
             to ~0.5″)"
                .to_string(),
        );
    }
    Ok(Built {
        epochs,
        sky,
        warnings,
    })
}
