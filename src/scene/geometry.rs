//! `geometry` → epochs: the request's orbit, site, window and attitude law validated at
//! the boundary (every error naming its field) and turned into body-frame epochs by
//! [`crate::orbit`].

use super::request::{AttitudeSpec, EarthOrientationSpec, GeometrySpec, OrbitSpec, TimeSpec};
use super::{Epoch, Limits, Sky, ValidationError};
use crate::orbit::attitude::{Law, State};
use crate::orbit::frames::EarthOrientation;
use crate::orbit::pass::Orbit;
use crate::orbit::site::Site;
use crate::orbit::time::parse_utc;
use crate::orbit::tle::ElementSet;
use crate::orbit::{pass, UtcTime};
use crate::radiometry::EARTH_RADIUS_M;
use glam::{DQuat, DVec3};

/// Most epochs one `geometry` window may hold, whatever the limits (80 bytes each).
pub const MAX_GEOMETRY_EPOCHS: usize = 10_000_000;
/// How far from the element set's epoch a window may reach, days: SGP4's errors grow
/// by ~1–3 km a day in LEO, and beyond a month an element set says little.
pub const MAX_DAYS_FROM_EPOCH: f64 = 30.0;

/// Most integration steps a triaxial `tumble` may take over its window (~45 rotations
/// each: about ten seconds of one core).
pub const MAX_TUMBLE_STEPS: f64 = 5e7;

mod tumble;
use tumble::tumble;

/// The epochs, what the site sees at each, and warnings for the response.
pub struct Built {
    pub epochs: Vec<Epoch>,
    /// Unix seconds of `times.start`: what series times in seconds count from.
    pub start_unix: f64,
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

fn element_set(spec: &OrbitSpec) -> Result<Orbit, ValidationError> {
    match (&spec.tle, &spec.omm, &spec.oem) {
        (Some(lines), None, None) => ElementSet::from_tle(lines)
            .map(|s| Orbit::Sgp4(Box::new(s)))
            .map_err(|e| {
                let field = match e.line {
                    Some(i) => format!("geometry.orbit.tle[{i}]"),
                    None => "geometry.orbit.tle".to_string(),
                };
                ValidationError::new(field, e.message)
            }),
        (None, Some(omm), None) => ElementSet::from_omm_json(omm)
            .map(|s| Orbit::Sgp4(Box::new(s)))
            .map_err(|e| ValidationError::new("geometry.orbit.omm", e.message)),
        (None, None, Some(oem)) => crate::orbit::oem::parse(oem)
            .map(Orbit::Oem)
            .map_err(|m| ValidationError::new("geometry.orbit.oem", m)),
        _ => err(
            "geometry.orbit",
            "give exactly one of `tle`, `omm` or `oem`",
        ),
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
        ("text", a.text.is_some()),
        ("secondary", a.secondary.is_some()),
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

/// The attitude law of `a`, each parameter checked (errors name
/// `geometry.attitude.<parameter>`); `start` and `stop` bound the window a series must
/// cover and a tumble is integrated over.
fn attitude(a: &AttitudeSpec, start: UtcTime, stop: UtcTime) -> Result<Law, ValidationError> {
    match a.law.as_str() {
        "nadir" => {
            only(a, &["yaw_deg"])?;
            let yaw = number(&att("yaw_deg"), a.yaw_deg.unwrap_or(0.0), -360.0, 360.0)?;
            Ok(Law::Nadir {
                yaw: yaw.to_radians(),
            })
        }
        "sun-pointing" => {
            only(a, &["axis", "secondary"])?;
            let axis = direction(&att("axis"), a.axis.unwrap_or([0.0, 0.0, 1.0]))?;
            let second = direction(&att("secondary"), a.secondary.unwrap_or([1.0, 0.0, 0.0]))?;
            let across = second - axis * axis.dot(second);
            if across.length() < 1e-6 {
                return err(att("secondary"), "must not lie along `axis`");
            }
            Ok(Law::SunPointing {
                axis,
                secondary: across.normalize(),
            })
        }
        "inertial" => {
            only(a, &["quaternion"])?;
            let q = required("quaternion", a.quaternion, &a.law)?;
            Ok(Law::Inertial {
                q: unit_quaternion(&att("quaternion"), q)?,
            })
        }
        "spin" => spin(a),
        "quaternions" => quaternion_series(a, start, stop),
        "tumble" => tumble(a, start, stop),
        "aem" => aem(a, start, stop),
        other => err(
            att("law"),
            format!("unknown law `{other}`; expected nadir, sun-pointing, inertial, spin, quaternions, tumble or aem"),
        ),
    }
}

/// `geometry.attitude.<p>`: the field of an attitude parameter.
fn att(p: &str) -> String {
    format!("geometry.attitude.{p}")
}

/// The attitude's `quaternion` (checked), or the identity when it has none.
fn quaternion_or_identity(a: &AttitudeSpec) -> Result<DQuat, ValidationError> {
    a.quaternion
        .map(|q| unit_quaternion(&att("quaternion"), q))
        .transpose()
        .map(|q| q.unwrap_or(DQuat::IDENTITY))
}

/// Law `spin`: an axis, a rate and a phase from a starting attitude.
fn spin(a: &AttitudeSpec) -> Result<Law, ValidationError> {
    only(a, &["axis", "rate_deg_s", "phase_deg", "quaternion"])?;
    let axis = direction(&att("axis"), required("axis", a.axis, &a.law)?)?;
    let rate = number(
        &att("rate_deg_s"),
        required("rate_deg_s", a.rate_deg_s, &a.law)?,
        -36_000.0,
        36_000.0,
    )?;
    let phase = number(&att("phase_deg"), a.phase_deg.unwrap_or(0.0), -360.0, 360.0)?;
    Ok(Law::Spin {
        axis,
        rate: rate.to_radians(),
        phase: phase.to_radians(),
        q0: quaternion_or_identity(a)?,
    })
}

/// Law `quaternions`: samples at increasing times (seconds after `start`, or ISO times)
/// that cover the window from `start` to `stop`.
fn quaternion_series(
    a: &AttitudeSpec,
    start: UtcTime,
    stop: UtcTime,
) -> Result<Law, ValidationError> {
    only(a, &["series"])?;
    let Some(samples) = &a.series else {
        return err(att("series"), "is required by law `quaternions`");
    };
    if samples.is_empty() {
        return err(att("series"), "must hold at least one sample");
    }
    let mut series = Vec::with_capacity(samples.len());
    for (i, s) in samples.iter().enumerate() {
        let tf = att(&format!("series[{i}].t"));
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
        let q = unit_quaternion(&att(&format!("series[{i}].q")), s.q)?;
        series.push((t, q));
    }
    let span = stop.seconds_since(start);
    let (first, last) = (series[0].0, series[series.len() - 1].0);
    if first > 0.0 || last < span {
        return err(
            att("series"),
            format!(
                "covers {first} s to {last} s after times.start, but the window runs \
                 from 0 to {span} s: the series must cover it (no extrapolation)"
            ),
        );
    }
    Ok(Law::Quaternions { series })
}

/// Law `aem`: a CCSDS AEM's quaternions (body → TEME), SLERP between them, covering the
/// window from `start` to `stop`.
fn aem(a: &AttitudeSpec, start: UtcTime, stop: UtcTime) -> Result<Law, ValidationError> {
    only(a, &["text"])?;
    let Some(text) = &a.text else {
        return err(
            att("text"),
            "is required by law `aem` (the message's KVN text)",
        );
    };
    let msg = crate::orbit::aem::parse(text).map_err(|m| ValidationError::new(att("text"), m))?;
    let series: Vec<(f64, DQuat)> = msg
        .samples
        .iter()
        .map(|(t, q)| (t.seconds_since(start), *q))
        .collect();
    let span = stop.seconds_since(start);
    let (first, last) = (series[0].0, series[series.len() - 1].0);
    if first > 0.0 || last < span {
        return err(
            att("text"),
            format!(
                "the message's data cover {first} s to {last} s after times.start, but the \
                 window runs from 0 to {span} s: they must cover it (no extrapolation)"
            ),
        );
    }
    Ok(Law::Quaternions { series })
}

/// Validates `geometry` and computes its epochs (after `visible_only`).
pub fn build(g: &GeometrySpec, limits: &Limits) -> Result<Built, ValidationError> {
    let set = element_set(&g.orbit)?;
    let site = site(g)?;
    let window = window(g, &set, limits)?;
    let eop = earth_orientation(g.earth_orientation.as_ref())?;
    let law = attitude(&g.attitude, window.start, window.stop)?;
    let visible = visible_only(g)?;
    let instants = visible_instants(&set, &site, &eop, &window, visible)?;
    let (epochs, sky) = body_frame_epochs(&instants, &law, window.start);
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
        start_unix: window.start.unix(),
        sky,
        warnings,
    })
}

/// `geometry.site`, each coordinate checked.
fn site(g: &GeometrySpec) -> Result<Site, ValidationError> {
    Ok(Site {
        lat_deg: number("geometry.site.lat_deg", g.site.lat_deg, -90.0, 90.0)?,
        lon_deg: number("geometry.site.lon_deg", g.site.lon_deg, -180.0, 360.0)?,
        alt_m: number(
            "geometry.site.alt_m",
            g.site.alt_m.unwrap_or(0.0),
            -500.0,
            1e5,
        )?,
    })
}

/// The window of `geometry.times`: its ends (UTC), its step (s) and its epoch count.
struct Window {
    start: UtcTime,
    stop: UtcTime,
    step: f64,
    epochs: usize,
}

/// `geometry.times` checked: a step within bounds, `stop` not before `start`, both ends
/// within [`MAX_DAYS_FROM_EPOCH`] of the element set's epoch, and no more epochs than the
/// limits take.
fn window(g: &GeometrySpec, orbit: &Orbit, limits: &Limits) -> Result<Window, ValidationError> {
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
        let set = match orbit {
            Orbit::Sgp4(set) => set,
            Orbit::Oem(e) => {
                let (first, last) = e.span();
                if t.seconds_since(first) < 0.0 || t.seconds_since(last) > 0.0 {
                    return err(
                        field,
                        format!(
                            "lies outside the ephemeris, which covers {} to {} (Unix s): no \
                             extrapolation",
                            first.unix(),
                            last.unix()
                        ),
                    );
                }
                continue;
            }
        };
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
    Ok(Window {
        start,
        stop,
        step,
        epochs: n,
    })
}

/// `geometry.visible_only`: the least elevation of the object and the greatest of the Sun
/// (degrees) an epoch is kept at; `None` for both when it is not given.
fn visible_only(g: &GeometrySpec) -> Result<(Option<f64>, Option<f64>), ValidationError> {
    Ok(match &g.visible_only {
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
    })
}

/// The object and the site at every epoch of the window that `visible_only` keeps; an
/// error when SGP4 fails, the orbit has decayed, or no epoch is kept.
fn visible_instants(
    set: &Orbit,
    site: &Site,
    eop: &EarthOrientation,
    window: &Window,
    (min_el, max_sun_el): (Option<f64>, Option<f64>),
) -> Result<Vec<pass::Instant>, ValidationError> {
    let (start, step) = (window.start, window.step);
    let mut instants = Vec::with_capacity(window.epochs);
    for k in 0..window.epochs {
        let t = start.plus(k as f64 * step);
        let at = pass::at(set, site, eop, t).map_err(|m| {
            ValidationError::new(
                "geometry.orbit",
                format!("no state {:.0} s after times.start: {m}", k as f64 * step),
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
    Ok(instants)
}

/// Each instant as a body-frame epoch (the attitude `law` turning the Sun, observer and
/// Earth vectors into the body frame), with what the site sees there.
fn body_frame_epochs(
    instants: &[pass::Instant],
    law: &Law,
    start: UtcTime,
) -> (Vec<Epoch>, Vec<Sky>) {
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
    (epochs, sky)
}
