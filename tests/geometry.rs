//! `geometry` requests end to end: validation naming the field, `visible_only`, the
//! response's per-epoch view, and agreement with the same epochs given explicitly.

use glint::scene::{Limits, Scene};
use serde_json::{json, Value};

const ISS: [&str; 2] = [
    "1 25544U 98067A   26336.50000000  .00016717  00000-0  30306-3 0  9992",
    "2 25544  51.6400 200.0000 0005000  90.0000 270.0000 15.50000000 49995",
];

fn request() -> Value {
    json!({
        "object": { "mesh": { "builtin": "box-wing" }, "materials": [
            { "name": "body", "preset": "seed-body-wrap" },
            { "name": "panel", "model": "lambert", "albedo": 0.25, "two_sided": true },
            { "name": "dish", "model": "lambert", "albedo": 0.3, "two_sided": true } ] },
        "geometry": {
            "orbit": { "tle": ISS },
            "site": { "lat_deg": 32.78, "lon_deg": -105.82, "alt_m": 2790 },
            "times": { "start": "2026-12-03T00:55:00Z", "stop": "2026-12-03T01:10:00Z", "step_s": 5 },
            "attitude": { "law": "nadir", "yaw_deg": 0 }
        }
    })
}

fn field_of(v: &Value) -> String {
    Scene::from_json(&v.to_string(), &Limits::unlimited())
        .map(|_| "accepted".to_string())
        .unwrap_or_else(|e| e.field)
}

fn with(mut v: Value, path: &str, value: Value) -> Value {
    let mut at = &mut v;
    let parts: Vec<&str> = path.split('.').collect();
    for p in &parts[..parts.len() - 1] {
        at = &mut at[*p];
    }
    at[parts[parts.len() - 1]] = value;
    v
}

/// Every bad input is refused with the field that is wrong.
#[test]
fn bad_geometry_names_the_field() {
    let r = request();
    let line2_bad = ISS[1].replace("15.50000000", "15.50000001");
    let cases: Vec<(Value, &str)> = vec![
        (
            with(r.clone(), "geometry.orbit.tle", json!([ISS[0], line2_bad])),
            "geometry.orbit.tle[1]",
        ),
        (
            with(r.clone(), "geometry.orbit.tle", json!([ISS[0]])),
            "geometry.orbit.tle",
        ),
        (
            with(
                r.clone(),
                "geometry.orbit.tle",
                json!(["ISS", ISS[0], &ISS[1][..60]]),
            ),
            "geometry.orbit.tle[2]",
        ),
        (
            with(r.clone(), "geometry.orbit", json!({})),
            "geometry.orbit",
        ),
        (
            with(r.clone(), "geometry.orbit.omm", json!({ "EPOCH": "x" })),
            "geometry.orbit",
        ),
        (
            with(r.clone(), "geometry.site.lat_deg", json!(95)),
            "geometry.site.lat_deg",
        ),
        (
            with(r.clone(), "geometry.site.alt_m", json!(-1e4)),
            "geometry.site.alt_m",
        ),
        (
            with(r.clone(), "geometry.times.start", json!("yesterday")),
            "geometry.times.start",
        ),
        (
            with(
                r.clone(),
                "geometry.times.stop",
                json!("2026-12-03T00:00:00Z"),
            ),
            "geometry.times.stop",
        ),
        (
            with(
                r.clone(),
                "geometry.times.start",
                json!("2026-11-01T00:00:00Z"),
            ),
            "geometry.times.start",
        ),
        (
            with(r.clone(), "geometry.times.step_s", json!(0)),
            "geometry.times.step_s",
        ),
        (
            with(r.clone(), "geometry.attitude", json!({ "law": "wobble" })),
            "geometry.attitude.law",
        ),
        (
            with(
                r.clone(),
                "geometry.attitude",
                json!({ "law": "nadir", "rate_deg_s": 1 }),
            ),
            "geometry.attitude.rate_deg_s",
        ),
        (
            with(
                r.clone(),
                "geometry.attitude",
                json!({ "law": "inertial", "quaternion": [0.5, 0.5, 0.5, 0.6] }),
            ),
            "geometry.attitude.quaternion",
        ),
        (
            with(r.clone(), "geometry.attitude", json!({ "law": "inertial" })),
            "geometry.attitude.quaternion",
        ),
        (
            with(
                r.clone(),
                "geometry.attitude",
                json!({ "law": "spin", "axis": [0, 0, 0], "rate_deg_s": 1 }),
            ),
            "geometry.attitude.axis",
        ),
        (
            with(
                r.clone(),
                "geometry.attitude",
                json!({ "law": "tumble", "inertia_kg_m2": [1, 1, 5], "omega_deg_s": [1, 0, 0] }),
            ),
            "geometry.attitude.inertia_kg_m2",
        ),
        (
            with(
                r.clone(),
                "geometry.attitude",
                json!({ "law": "tumble", "inertia_kg_m2": [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]], "omega_deg_s": [1, 0, 0] }),
            ),
            "geometry.attitude.inertia_kg_m2",
        ),
        (
            with(
                r.clone(),
                "geometry.attitude",
                json!({ "law": "quaternions", "series": [
            { "t": 0, "q": [1, 0, 0, 0] }, { "t": 0, "q": [1, 0, 0, 0] } ] }),
            ),
            "geometry.attitude.series[1].t",
        ),
        (
            with(
                r.clone(),
                "geometry.earth_orientation",
                json!({ "dut1_s": 2 }),
            ),
            "geometry.earth_orientation.dut1_s",
        ),
        (
            with(
                with(
                    r.clone(),
                    "geometry.attitude",
                    json!({ "law": "tumble", "inertia_kg_m2": [1, 2, 2.5], "omega_deg_s": [30000, 0, 0] }),
                ),
                "geometry.times.stop",
                json!("2026-12-10T00:00:00Z"),
            ),
            "geometry.attitude.omega_deg_s",
        ),
        (
            with(
                r.clone(),
                "geometry.visible_only",
                json!({ "min_elevation_deg": 89.9 }),
            ),
            "geometry.visible_only",
        ),
        (
            with(
                r.clone(),
                "epochs",
                json!([ { "t": 0, "sun": [1, 0, 0], "observer": [0, 0, 1e7] } ]),
            ),
            "geometry",
        ),
    ];
    for (v, field) in cases {
        assert_eq!(field_of(&v), field, "{v}");
    }
    let mut none = request();
    none.as_object_mut().unwrap().remove("geometry");
    assert_eq!(field_of(&none), "epochs");
}

/// A nadir-pointing box-wing over a pass: the response carries the site's view per
/// epoch and the Earth-orientation warning; `visible_only` keeps exactly the epochs
/// with the object high enough and the site dark enough (checked against the full
/// window's own azimuth/elevation; exact, the same numbers filtered).
#[test]
fn a_pass_end_to_end() {
    let full =
        glint::simulate(&Scene::from_json(&request().to_string(), &Limits::unlimited()).unwrap());
    assert_eq!(full.epochs.len(), 181);
    assert!(full
        .warnings
        .iter()
        .any(|w| w.contains("earth_orientation")));
    for e in &full.epochs {
        let el = e.elevation_deg.unwrap();
        assert!((-90.0..=90.0).contains(&el));
        assert!((0.0..360.0).contains(&e.azimuth_deg.unwrap()));
        assert_eq!(e.in_earth_shadow, Some(e.eclipse > 0.0));
        // below the horizon the Earth hides the object from the site
        if el < -0.5 {
            assert!(e.earth_blocks_view);
        }
        if el > 0.5 {
            assert!(!e.earth_blocks_view);
        }
    }
    let visible = with(
        request(),
        "geometry.visible_only",
        json!({ "min_elevation_deg": 20, "max_sun_elevation_deg": -6 }),
    );
    let vis =
        glint::simulate(&Scene::from_json(&visible.to_string(), &Limits::unlimited()).unwrap());
    let expect: Vec<f64> = full
        .epochs
        .iter()
        .filter(|e| e.elevation_deg.unwrap() >= 20.0 && e.sun_elevation_deg.unwrap() <= -6.0)
        .map(|e| e.t)
        .collect();
    let got: Vec<f64> = vis.epochs.iter().map(|e| e.t).collect();
    assert!(!got.is_empty());
    assert_eq!(got, expect);
    // with Earth orientation given there is no warning
    let eop = with(
        request(),
        "geometry.earth_orientation",
        json!({ "dut1_s": 0.1 }),
    );
    let r = glint::simulate(&Scene::from_json(&eop.to_string(), &Limits::unlimited()).unwrap());
    assert!(!r.warnings.iter().any(|w| w.contains("earth_orientation")));
}

/// The same epochs given explicitly (the computed body-frame vectors written out as
/// `epochs`) give the same light curve: the geometry path feeds the engine exactly as
/// explicit epochs do (relative 1e-12: JSON's float round trip is exact, so only
/// rounding in the engine's sums could differ).
#[test]
fn geometry_equals_its_explicit_epochs() {
    let scene = Scene::from_json(&request().to_string(), &Limits::unlimited()).unwrap();
    let epochs: Vec<Value> = scene
        .epochs
        .iter()
        .map(|e| json!({ "t": e.t, "sun": e.sun.to_array(), "observer": e.observer.to_array(),
            "earth": e.earth.unwrap().to_array(), "sun_distance_au": e.sun_distance_m / glint::radiometry::AU_M }))
        .collect();
    let mut explicit = request();
    explicit.as_object_mut().unwrap().remove("geometry");
    explicit["epochs"] = Value::Array(epochs);
    let a = glint::simulate(&scene);
    let b =
        glint::simulate(&Scene::from_json(&explicit.to_string(), &Limits::unlimited()).unwrap());
    for (x, y) in a.epochs.iter().zip(&b.epochs) {
        let scale = x.irradiance_w_m2.abs().max(1e-300);
        assert!(
            (x.irradiance_w_m2 - y.irradiance_w_m2).abs() <= 1e-12 * scale,
            "{x:?} {y:?}"
        );
        assert_eq!(x.earth_blocks_view, y.earth_blocks_view);
    }
}
