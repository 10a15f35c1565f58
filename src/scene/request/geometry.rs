//! The `geometry` part of a request: an orbit, a site, a window, an attitude law and
//! articulated parts, from which glint computes the epochs (`crate::scene::geometry`).

use super::TimeSpec;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Epochs from an orbit, a site and a window: for each time, SGP4 gives the object's
/// TEME state, Meeus' low-accuracy series (0.01°) the Sun, and the attitude law the body
/// frame; the engine then sees the Sun, the site and the Earth's centre in the body
/// frame as with explicit epochs. Positions are geometric (no refraction, no light
/// time). The inertial frame of attitudes is TEME (true equator, mean equinox of date).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct GeometrySpec {
    pub orbit: OrbitSpec,
    pub site: SiteSpec,
    pub times: TimesSpec,
    pub attitude: AttitudeSpec,
    /// UT1 − UTC and polar motion for TEME → ITRF. Absent: all zero (the response then
    /// carries a warning).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub earth_orientation: Option<EarthOrientationSpec>,
    /// Keep only the epochs the site can observe: the object at least
    /// `min_elevation_deg` above the horizon while the Sun is at most
    /// `max_sun_elevation_deg`. Absent: every epoch of the window.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub visible_only: Option<VisibleOnlySpec>,
    /// Parts of the mesh that turn about hinges each epoch (solar arrays). Absent: the
    /// mesh is rigid.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub articulation: Option<Vec<ArticulationSpec>>,
}

/// A hinge: `parts` (names of triangle groups: an OBJ `g`/`o` group, an inline mesh's
/// `parts`, or else a material name) turn about the line through `pivot` along `axis`
/// (body frame, the mesh as given), right-handed, by an angle each epoch. The angle 0 is
/// the mesh as given. `law`:
/// - `sun-tracking`: the angle that turns `normal` (default: the part's area-weighted
///   normal, its front face) onto the Sun's projection on the plane normal to the axis;
///   0 when the Sun lies along the axis.
/// - `fixed`: `angle_deg`.
/// - `angles`: a `series` of `{ "t": ..., "angle_deg": ... }`, linear between samples,
///   covering every epoch (t in ISO UTC or seconds: after `times.start` in `geometry`,
///   on the epochs' own scale with explicit `epochs`).
///
/// A hinge whose parts lie within an earlier hinge's parts is nested in it: its axis and
/// pivot (given in the mesh as given) turn with that parent (two-axis tracking).
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ArticulationSpec {
    #[schema(example = json!(["panel"]))]
    pub parts: Vec<String>,
    #[schema(example = "sun-tracking")]
    pub law: String,
    /// Hinge direction, body frame (any length, not zero).
    #[schema(example = json!([0.0, 1.0, 0.0]))]
    pub axis: [f64; 3],
    /// A point of the hinge line, m, body frame. Default [0, 0, 0].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pivot: Option<[f64; 3]>,
    /// `sun-tracking`: the body-frame direction (the mesh as given) that follows the Sun.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<[f64; 3]>,
    /// `fixed`: the angle, degrees (−360 to 360).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<f64>,
    /// `angles`: the angle against time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub series: Option<Vec<AngleSample>>,
}

/// One sample of a hinge angle.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct AngleSample {
    #[schema(value_type = f64, example = 0.0)]
    pub t: TimeSpec,
    pub angle_deg: f64,
}

/// The orbit: a TLE (2 lines, or 3 with the name first), a CCSDS OMM in its JSON form, or
/// a CCSDS OEM ephemeris. Exactly one. Propagated by SGP4 (AFSPC-compatible mode, WGS-72); times must lie
/// within 30 days of the element set's epoch.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct OrbitSpec {
    /// The lines of a two- or three-line element set (69 characters per data line,
    /// checksums validated).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tle: Option<Vec<String>>,
    /// A CCSDS OMM as JSON (CelesTrak's / Space-Track's keys: `EPOCH`,
    /// `MEAN_MOTION`, `ECCENTRICITY`, `INCLINATION`, `RA_OF_ASC_NODE`,
    /// `ARG_OF_PERICENTER`, `MEAN_ANOMALY`, `BSTAR`, `MEAN_MOTION_DOT`,
    /// `MEAN_MOTION_DDOT`, `NORAD_CAT_ID`, …). `EPOCH` is UTC without a zone suffix.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<Object>)]
    pub omm: Option<serde_json::Value>,
    /// A CCSDS OEM (KVN text) instead of an element set, for precise orbits: states in
    /// TEME (EME2000/GCRF/ICRF are refused), interpolated by Lagrange polynomials of its
    /// `INTERPOLATION_DEGREE` (default 7); the window must lie within its states.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub oem: Option<String>,
}

/// A ground site on the WGS-84 ellipsoid.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SiteSpec {
    /// Geodetic latitude, degrees (−90 to 90).
    #[schema(example = 32.78)]
    pub lat_deg: f64,
    /// Longitude, degrees east (−180 to 360).
    #[schema(example = -105.82)]
    pub lon_deg: f64,
    /// Height above the ellipsoid, m (−500 to 100 000). Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 2790.0)]
    pub alt_m: Option<f64>,
}

/// The window: epochs at `start`, `start + step_s`, … up to `stop` inclusive.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TimesSpec {
    /// ISO 8601 UTC, e.g. `2026-12-03T01:00:00Z`.
    #[schema(example = "2026-12-03T01:00:00Z")]
    pub start: String,
    /// ISO 8601 UTC, not before `start`.
    #[schema(example = "2026-12-03T01:20:00Z")]
    pub stop: String,
    /// Seconds between epochs (≥ 0.001).
    #[schema(example = 1.0)]
    pub step_s: f64,
}

/// Earth orientation parameters (IERS Bulletin A values for the day).
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct EarthOrientationSpec {
    /// UT1 − UTC, s (−1 to 1). Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dut1_s: Option<f64>,
    /// Pole offset x_p, arcsec (−2 to 2). Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub xp_arcsec: Option<f64>,
    /// Pole offset y_p, arcsec (−2 to 2). Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yp_arcsec: Option<f64>,
}

/// Which epochs a site can observe.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct VisibleOnlySpec {
    /// Least elevation of the object, degrees (−90 to 90). Default 10.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_elevation_deg: Option<f64>,
    /// Greatest elevation of the Sun at the site, degrees (−90 to 90). Default −6
    /// (the end of civil twilight).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_sun_elevation_deg: Option<f64>,
}

/// An attitude law: body → TEME at each epoch. `law` and its parameters:
/// - `nadir`: body +z at the geocentre, +y along −(r×v), +x completing the set (along
///   the velocity on a circular orbit); optional `yaw_deg` about +z (default 0).
/// - `sun-pointing`: the body `axis` (default [0, 0, 1]) at the Sun, the body
///   `secondary` axis (default [1, 0, 0]; its part perpendicular to `axis`) towards the
///   TEME pole projected across the Sun's direction.
/// - `inertial`: a fixed `quaternion` [w, x, y, z] body → TEME.
/// - `spin`: about the TEME `axis` at `rate_deg_s`, `phase_deg` at `times.start`
///   (default 0), after the optional `quaternion` (default identity).
/// - `quaternions`: a `series` of `{ "t": ..., "q": [w, x, y, z] }` (t in ISO UTC or
///   seconds after `times.start`, increasing), SLERP between them; every epoch must lie
///   within the series.
/// - `tumble`: a torque-free rigid body: `inertia_kg_m2` (principal moments
///   [I_x, I_y, I_z] along the body axes, or a symmetric 3×3 tensor), `omega_deg_s`
///   (body-frame angular velocity at `times.start`) and `quaternion` (body → TEME
///   then, default identity). Closed form when two principal moments are equal;
///   otherwise a 6th-order splitting integrator.
/// - `aem`: a CCSDS Attitude Ephemeris Message as KVN `text` (v1 with `QUATERNION_TYPE`
///   FIRST or LAST, or v2, scalar last), quaternion data in TEME (`REF_FRAME_A`/`B`: TEME
///   and `SC_BODY_n`, either way round, `ATTITUDE_DIR` A2B or B2A; A2B turns frame A's
///   axes onto frame B's), SLERP between lines; the data must cover the window.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct AttitudeSpec {
    #[schema(example = "nadir")]
    pub law: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yaw_deg: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quaternion: Option<[f64; 4]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rate_deg_s: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase_deg: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub series: Option<Vec<QuaternionSample>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia_kg_m2: Option<InertiaSpec>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub omega_deg_s: Option<[f64; 3]>,
    /// Law `sun-pointing`: the body axis kept towards the TEME pole (default [1, 0, 0]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub secondary: Option<[f64; 3]>,
    /// Law `aem`: the CCSDS AEM, KVN text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub text: Option<String>,
}

/// One sample of an attitude series.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct QuaternionSample {
    /// ISO 8601 UTC, or seconds after `times.start`.
    #[schema(value_type = f64, example = 0.0)]
    pub t: TimeSpec,
    /// Body → TEME, [w, x, y, z], unit.
    pub q: [f64; 4],
}

/// Principal moments [I_x, I_y, I_z] (kg·m², body axes principal) or a symmetric 3×3
/// inertia tensor (kg·m², body frame).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(untagged)]
pub enum InertiaSpec {
    Principal([f64; 3]),
    Tensor([[f64; 3]; 3]),
}
