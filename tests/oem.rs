//! CCSDS OEM ephemerides: an OEM sampled from a TLE's SGP4 propagation gives the TLE's
//! pass between its lines.

use glint::orbit::tle::ElementSet;
use glint::orbit::UtcTime;
use glint::scene::{Limits, Scene, ValidationError};
use serde_json::{json, Value};

const ISS: [&str; 2] = [
    "1 25544U 98067A   26336.50000000  .00016717  00000-0  30306-3 0  9992",
    "2 25544  51.6400 200.0000 0005000  90.0000 270.0000 15.50000000 49995",
];
/// 2026-12-03T00:40:00Z
const FIRST_UNIX: i64 = 1_796_258_400;

fn request(orbit: Value) -> Value {
    json!({
        "object": { "mesh": { "builtin": "plate" }, "materials": [ { "name": "surface", "model": "lambert", "albedo": 0.5 } ] },
        "geometry": {
            "orbit": orbit,
            "site": { "lat_deg": 32.78, "lon_deg": -105.82, "alt_m": 2790 },
            "times": { "start": "2026-12-03T00:52:00Z", "stop": "2026-12-03T01:02:00Z", "step_s": 7.0 },
            "attitude": { "law": "inertial", "quaternion": [1, 0, 0, 0] }
        }
    })
}

fn scene(v: &Value) -> Result<Scene, ValidationError> {
    Scene::from_json(&v.to_string(), &Limits::unlimited())
}

/// The TLE propagated by SGP4 every 60 s from 00:40 to 01:15, written as an OEM (km and
/// km/s with 9 decimals: micrometres) in `frame`.
fn oem(frame: &str) -> String {
    let set = ElementSet::from_tle(&ISS.map(String::from)).unwrap();
    let mut s = format!(
        "CCSDS_OEM_VERS = 2.0\nCREATION_DATE = 2026-12-01T00:00:00\nORIGINATOR = TEST\n\n\
         META_START\nOBJECT_NAME = ISS\nOBJECT_ID = 1998-067A\nCENTER_NAME = EARTH\n\
         REF_FRAME = {frame}\nTIME_SYSTEM = UTC\nSTART_TIME = 2026-12-03T00:40:00\n\
         STOP_TIME = 2026-12-03T01:15:00\nINTERPOLATION = LAGRANGE\nINTERPOLATION_DEGREE = 7\n\
         META_STOP\n\n"
    );
    for k in 0..=35 {
        let t = UtcTime::new(FIRST_UNIX + 60 * k, 0.0);
        let (r, v) = set.teme_at(t).unwrap();
        let when = chrono::DateTime::from_timestamp(t.secs, 0)
            .unwrap()
            .format("%Y-%m-%dT%H:%M:%S");
        let (r, v) = (r / 1e3, v / 1e3);
        s += &format!(
            "{when} {:.9} {:.9} {:.9} {:.12} {:.12} {:.12}\n",
            r.x, r.y, r.z, v.x, v.y, v.z
        );
    }
    s
}

/// Between the OEM's lines (epochs every 7 s, lines every 60 s) the pass is the TLE's:
/// range within 1 m and azimuth and elevation within 1″ (the bounds; a degree-7
/// Lagrange polynomial over 8 minutes of a LEO orbit errs by millimetres).
#[test]
fn an_oem_from_a_tle_gives_the_tles_pass() {
    let tle = scene(&request(json!({ "tle": ISS }))).unwrap();
    let eph = scene(&request(json!({ "oem": oem("TEME") }))).unwrap();
    assert_eq!(tle.epochs.len(), eph.epochs.len());
    let (mut range, mut angle) = (0.0f64, 0.0f64);
    for ((a, b), (sa, sb)) in tle
        .epochs
        .iter()
        .zip(&eph.epochs)
        .zip(tle.sky.iter().zip(&eph.sky))
    {
        range = range.max((a.observer.length() - b.observer.length()).abs());
        let daz = (sa.azimuth_deg - sb.azimuth_deg + 180.0).rem_euclid(360.0) - 180.0;
        let daz = daz * sa.elevation_deg.to_radians().cos();
        angle = angle
            .max(daz.abs())
            .max((sa.elevation_deg - sb.elevation_deg).abs());
    }
    println!(
        "oem against tle: range {range:.2e} m, angle {:.2e} arcsec",
        angle * 3600.0
    );
    assert!(range < 1.0, "{range}");
    assert!(angle * 3600.0 < 1.0, "{angle}");
}

/// A frame other than TEME, a window beyond the states and a bad line are refused,
/// naming the field.
#[test]
fn bad_ephemerides_are_refused() {
    let e = scene(&request(json!({ "oem": oem("EME2000") }))).unwrap_err();
    assert_eq!(e.field, "geometry.orbit.oem");
    assert!(e.message.contains("EME2000 is not supported"), "{e}");
    let mut late = request(json!({ "oem": oem("TEME") }));
    late["geometry"]["times"]["stop"] = json!("2026-12-03T01:20:00Z");
    let e = scene(&late).unwrap_err();
    assert_eq!(e.field, "geometry.times.stop");
    let bad = oem("TEME").replace("INTERPOLATION_DEGREE = 7", "INTERPOLATION_DEGREE = 99");
    let e = scene(&request(json!({ "oem": bad }))).unwrap_err();
    assert_eq!(e.field, "geometry.orbit.oem");
    let e = scene(&request(json!({ "oem": oem("TEME"), "tle": ISS }))).unwrap_err();
    assert_eq!(e.field, "geometry.orbit");
}
