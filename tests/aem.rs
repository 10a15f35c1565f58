//! CCSDS AEM attitude messages and the sun-pointing law's axes, against the laws they
//! were written from and the geometry they promise.

use glam::{DQuat, DVec3};
use glint::orbit::attitude::{Law, State};
use glint::scene::{Limits, Scene, ValidationError};
use serde_json::{json, Value};

const ISS: [&str; 2] = [
    "1 25544U 98067A   26336.50000000  .00016717  00000-0  30306-3 0  9992",
    "2 25544  51.6400 200.0000 0005000  90.0000 270.0000 15.50000000 49995",
];
const START_UNIX: i64 = 1_796_259_000; // 2026-12-03T00:50:00Z

fn request(attitude: Value) -> Value {
    json!({
        "object": { "mesh": { "builtin": "box-wing" }, "materials": [
            { "name": "body", "preset": "seed-body-wrap" },
            { "name": "panel", "model": "lambert", "albedo": 0.25, "two_sided": true },
            { "name": "dish", "preset": "seed-white-paint", "two_sided": true } ] },
        "geometry": {
            "orbit": { "tle": ISS },
            "site": { "lat_deg": 32.78, "lon_deg": -105.82, "alt_m": 2790 },
            "times": { "start": "2026-12-03T00:50:00Z", "stop": "2026-12-03T01:05:00Z", "step_s": 7.0 },
            "attitude": attitude
        },
        "illumination": { "earthshine": "off" }
    })
}

fn scene(v: &Value) -> Result<Scene, ValidationError> {
    Scene::from_json(&v.to_string(), &Limits::unlimited())
}

/// The spin law of the test: q(t) = R(axis, phase + rate·t)·q0, body → TEME.
fn spin_at(t: f64) -> DQuat {
    let axis = DVec3::new(0.3, -0.2, 0.9).normalize();
    let q0 = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 0.7);
    (DQuat::from_axis_angle(axis, (10.0 + 0.5 * t).to_radians()) * q0).normalize()
}

fn spin_law() -> Value {
    let q0 = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 0.7);
    json!({ "law": "spin", "axis": [0.3, -0.2, 0.9], "rate_deg_s": 0.5, "phase_deg": 10,
            "quaternion": [q0.w, q0.x, q0.y, q0.z] })
}

/// How a message writes its quaternions.
#[derive(Clone, Copy)]
enum Form {
    /// v1, scalar first, A = TEME, B = body, A2B (the quaternion as glint's).
    V1First,
    /// v1, scalar last, A = TEME, B = body, B2A (the inverse written).
    V1LastB2A,
    /// v2 (scalar last), A = body, B = TEME, A2B (the inverse written).
    V2BodyFirst,
}

/// An AEM of the spin law, a line every 20 s from 00:50 to 01:06 (UTC).
fn message(form: Form) -> String {
    let (vers, a, b, dir, qtype) = match form {
        Form::V1First => (
            "1.0",
            "TEME",
            "SC_BODY_1",
            "A2B",
            "QUATERNION_TYPE = FIRST\n",
        ),
        Form::V1LastB2A => (
            "1.0",
            "TEME",
            "SC_BODY_1",
            "B2A",
            "QUATERNION_TYPE = LAST\n",
        ),
        Form::V2BodyFirst => ("2.0", "SC_BODY_1", "TEME", "A2B", ""),
    };
    let mut s = format!(
        "CCSDS_AEM_VERS = {vers}\nCREATION_DATE = 2026-12-01T00:00:00\nORIGINATOR = TEST\n\n\
         META_START\nOBJECT_NAME = BOX-WING\nOBJECT_ID = 2026-001A\nCENTER_NAME = EARTH\n\
         REF_FRAME_A = {a}\nREF_FRAME_B = {b}\nATTITUDE_DIR = {dir}\nTIME_SYSTEM = UTC\n\
         START_TIME = 2026-12-03T00:50:00.000\nSTOP_TIME = 2026-12-03T01:06:00.000\n\
         ATTITUDE_TYPE = QUATERNION\n{qtype}META_STOP\n\nDATA_START\nCOMMENT spin law\n"
    );
    for k in 0..=48 {
        let t = 20.0 * k as f64;
        let q = spin_at(t);
        let q = match form {
            Form::V1First => q,
            _ => q.inverse(),
        };
        let when = chrono::DateTime::from_timestamp(START_UNIX + t as i64, 0)
            .unwrap()
            .format("%Y-%m-%dT%H:%M:%S%.3f");
        match form {
            Form::V1First => {
                s += &format!(
                    "{when} {:.17e} {:.17e} {:.17e} {:.17e}\n",
                    q.w, q.x, q.y, q.z
                )
            }
            _ => {
                s += &format!(
                    "{when} {:.17e} {:.17e} {:.17e} {:.17e}\n",
                    q.x, q.y, q.z, q.w
                )
            }
        }
    }
    s + "DATA_STOP\n"
}

/// An AEM written from a spin law reproduces the spin law's light curve at epochs that
/// fall between its lines (7 s steps, lines every 20 s): SLERP between two samples of a
/// uniform turn about a fixed axis is that turn, so the attitudes agree to ~1e-15 rad
/// (the printed digits, SLERP's rounding). The light curve amplifies that where a shadow
/// line grazes a face (measured worst 1.9e-8 relative); held to 1e-6.
#[test]
fn an_aem_of_a_spin_law_gives_its_light_curve() {
    let truth = glint::simulate(&scene(&request(spin_law())).unwrap());
    assert!(truth.epochs.iter().any(|e| e.irradiance_w_m2 > 0.0));
    for form in [Form::V1First, Form::V1LastB2A, Form::V2BodyFirst] {
        let s = scene(&request(json!({ "law": "aem", "text": message(form) }))).unwrap();
        let r = glint::simulate(&s);
        let mut worst: f64 = 0.0;
        for (i, (a, b)) in r.epochs.iter().zip(&truth.epochs).enumerate() {
            let d = (a.irradiance_w_m2 - b.irradiance_w_m2).abs();
            worst = worst.max(d / b.irradiance_w_m2.abs().max(1e-300));
            assert!(
                d <= 1e-6 * b.irradiance_w_m2.abs(),
                "epoch {i}: {} vs {}",
                a.irradiance_w_m2,
                b.irradiance_w_m2
            );
        }
        println!("aem against spin: worst relative difference {worst:.1e}");
    }
}

/// What a message may not say, each refused naming `geometry.attitude.text` and the line.
#[test]
fn bad_messages_are_refused_naming_the_field() {
    let good = message(Form::V1First);
    let cases = [
        (
            good.replace("QUATERNION_TYPE = FIRST", "QUATERNION_TYPE = MIDDLE"),
            "QUATERNION_TYPE",
        ),
        (
            good.replace("QUATERNION_TYPE = FIRST\n", ""),
            "needs QUATERNION_TYPE",
        ),
        (
            good.replace("CCSDS_AEM_VERS = 1.0", "CCSDS_AEM_VERS = 2.0"),
            "not a version 2 keyword",
        ),
        (
            good.replace("REF_FRAME_A = TEME", "REF_FRAME_A = EME2000"),
            "EME2000 is not supported",
        ),
        (
            good.replace("ATTITUDE_DIR = A2B", "ATTITUDE_DIR = UP"),
            "ATTITUDE_DIR",
        ),
        // the window runs to 01:05; data to 00:55 only
        (
            good.split("2026-12-03T00:55:20")
                .next()
                .unwrap()
                .to_string()
                + "DATA_STOP\n",
            "must cover it",
        ),
    ];
    for (text, says) in cases {
        let e = scene(&request(json!({ "law": "aem", "text": text }))).unwrap_err();
        assert_eq!(e.field, "geometry.attitude.text", "{e}");
        assert!(e.message.contains(says), "{e}");
    }
    // an unnormalised quaternion: its line named
    let line = good
        .lines()
        .position(|l| l.starts_with("2026-12-03T00:51:00"))
        .unwrap()
        + 1;
    let bad: Vec<String> = good
        .lines()
        .map(|l| {
            if l.starts_with("2026-12-03T00:51:00") {
                let w: Vec<&str> = l.split_whitespace().collect();
                format!("{} 0.9 {} {} {}", w[0], w[2], w[3], w[4])
            } else {
                l.to_string()
            }
        })
        .collect();
    let e = scene(&request(json!({ "law": "aem", "text": bad.join("\n") }))).unwrap_err();
    assert_eq!(e.field, "geometry.attitude.text");
    assert!(
        e.message
            .starts_with(&format!("line {line}: the quaternion has norm")),
        "{e}"
    );
}

/// `sun-pointing` with a chosen axis: body +x on the Sun at every epoch (1e-12 rad:
/// one quaternion built and applied), and the secondary body +z towards the TEME pole,
/// in the plane of the Sun and the pole (1e-12). Defaults keep +z on the Sun.
#[test]
fn sun_pointing_points_the_chosen_axis() {
    let s = scene(&request(
        json!({ "law": "sun-pointing", "axis": [2, 0, 0], "secondary": [0, 0.1, 1] }),
    ))
    .unwrap();
    for e in &s.epochs {
        assert!(
            e.sun.cross(DVec3::X).length() < 1e-12 && e.sun.x > 0.0,
            "{}",
            e.sun
        );
    }
    let sun = DVec3::new(0.3, -0.8, 0.4).normalize();
    let law = Law::SunPointing {
        axis: DVec3::X,
        secondary: DVec3::Z,
    };
    let q = law.quaternions(&[State {
        r: DVec3::X * 7e6,
        v: DVec3::Y,
        sun,
        t: 0.0,
    }])[0];
    assert!((q * DVec3::X - sun).length() < 1e-12);
    let second = q * DVec3::Z;
    assert!(second.dot(sun).abs() < 1e-12 && second.z > 0.0);
    assert!(sun.cross(DVec3::Z).dot(second).abs() < 1e-12);
    let s = scene(&request(json!({ "law": "sun-pointing" }))).unwrap();
    assert!(s
        .epochs
        .iter()
        .all(|e| e.sun.cross(DVec3::Z).length() < 1e-12));
    let e = scene(&request(
        json!({ "law": "sun-pointing", "secondary": [0, 0, -3] }),
    ))
    .unwrap_err();
    assert_eq!(e.field, "geometry.attitude.secondary");
}
