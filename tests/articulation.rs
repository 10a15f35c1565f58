//! Articulated parts (hinges) against truths the code did not produce: the Sun's
//! projection, a flat plate's closed form, a mesh turned by hand, a shadow's area.

mod common;

use common::{dir, es_default, from_json, rel};
use glam::{DMat3, DVec3};
use serde_json::{json, Value};
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// The ISS pass of `scenes/iss-pass.json` with its box-wing's panels tracking the Sun
/// about the body y axis (the panels' long axis).
fn tracking_pass() -> Value {
    let mut v: Value =
        serde_json::from_str(include_str!("../scenes/iss-pass.json")).expect("scene");
    v["geometry"]["articulation"] = json!([{ "parts": ["panel"], "law": "sun-tracking", "axis": [0, 1, 0], "pivot": [0, 0, 0] }]);
    v
}

/// Equal to 1e-12 of the larger (zeros included).
fn close(x: f64, y: f64) -> bool {
    (x - y).abs() <= 1e-12 * x.abs().max(y.abs())
}

/// The posed normal of the first triangle of material `m`.
fn normal_of(mesh: &glint::geometry::Mesh, vertices: &[DVec3], m: u32) -> DVec3 {
    let t = mesh
        .material_ids
        .iter()
        .position(|&x| x == m)
        .expect("material");
    let [a, b, c] = mesh.triangles[t].map(|k| vertices[k as usize]);
    (b - a).cross(c - a).normalize()
}

/// A Sun-tracking array's normal lies on the Sun's projection onto the plane normal to
/// its axis, at every epoch of a pass: the angle between them below 1e-12 rad (the
/// rotation is built from one atan2 and one sin/cos pair: rounding only).
#[test]
fn a_sun_tracking_panel_faces_the_suns_projection() {
    let scene = from_json(&tracking_pass());
    let a = scene.articulation.as_ref().expect("articulated");
    let mut worst: f64 = 0.0;
    for e in &scene.epochs {
        let posed = a.pose(&scene.mesh.vertices, &a.angles(e.t, e.sun));
        let n = normal_of(&scene.mesh, &posed, 1);
        let s = DVec3::new(e.sun.x, 0.0, e.sun.z).normalize();
        assert!(n.y.abs() < 1e-12, "normal off the plane: {n}");
        worst = worst.max(n.cross(s).length()).max((n.dot(s) - 1.0).abs());
    }
    assert!(worst < 1e-12, "{worst:e}");
    let r = glint::simulate(&scene);
    common::assert_sane(&r);
    assert!(
        r.summary.method.contains("articulated"),
        "{}",
        r.summary.method
    );
}

/// A 2 m × 1 m plate (normal +x) on two nested hinges: azimuth about body z, then
/// elevation about its own y axis (body y in the mesh as given, carried by the first).
fn two_axis_plate(epochs: Value) -> Value {
    json!({
        "object": {
            "mesh": {
                "vertices": [[0, -1, -0.5], [0, 1, -0.5], [0, 1, 0.5], [0, -1, 0.5]],
                "triangles": [[0, 1, 2], [0, 2, 3]],
                "parts": [{ "name": "plate", "triangles": [0, 1] }]
            },
            "materials": [{ "name": "white", "model": "lambert", "albedo": 0.5 }]
        },
        "epochs": epochs,
        "illumination": { "earthshine": "off" },
        "articulation": [
            { "parts": ["plate"], "law": "sun-tracking", "axis": [0, 0, 1] },
            { "parts": ["plate"], "law": "sun-tracking", "axis": [0, 1, 0] }
        ]
    })
}

/// Tracked on two axes the plate faces the Sun exactly, so its light is the flat
/// Lambertian plate's closed form with cosθi = 1: E = E_s (ρ/π) A cosθr / R², cosθr the
/// Sun–observer cosine (0 behind it). Rounding only: 1e-12 relative.
#[test]
fn a_plate_tracked_on_two_axes_gives_the_flat_plate_closed_form() {
    let range = 4.0e7;
    let mut epochs = Vec::new();
    let mut truth = Vec::new();
    for (el_s, az_s) in [(10.0, 30.0), (-40.0, 200.0), (75.0, -120.0), (0.0, 90.0)] {
        for (el_v, az_v) in [(20.0, 40.0), (-10.0, 250.0), (60.0, 0.0)] {
            let s = dir(f64::to_radians(el_s), f64::to_radians(az_s));
            let v = dir(f64::to_radians(el_v), f64::to_radians(az_v));
            epochs.push(json!({ "t": epochs.len(), "sun": s.to_array(), "observer": (v * range).to_array() }));
            truth.push(es_default() * 0.5 / PI * 2.0 * s.dot(v).max(0.0) / (range * range));
        }
    }
    let scene = from_json(&two_axis_plate(Value::Array(epochs)));
    let a = scene.articulation.as_ref().expect("articulated");
    assert_eq!(a.joints[1].parent, Some(0));
    for e in &scene.epochs {
        let posed = a.pose(&scene.mesh.vertices, &a.angles(e.t, e.sun));
        let n = normal_of(&scene.mesh, &posed, 0);
        assert!(
            (n - e.sun).length() < 1e-12,
            "{n} against the Sun {}",
            e.sun
        );
    }
    let r = glint::simulate(&scene);
    for (i, (e, t)) in r.epochs.iter().zip(&truth).enumerate() {
        if *t == 0.0 {
            assert_eq!(e.irradiance_w_m2, 0.0, "epoch {i}");
        } else {
            assert!(
                rel(e.irradiance_w_m2, *t) < 1e-12,
                "epoch {i}: {} vs {t}",
                e.irradiance_w_m2
            );
        }
    }
}

/// A 2 m bus (a cube about the origin) with a 2 m × 2 m one-sided panel standing on a
/// hinge along y through (0, 0, 2), 1 m above the bus's top: at angle 0 the panel is
/// upright (x = 0, z from 2 to 4, normal +x); turned by θ about y it leans over +x.
fn bus_and_panel(vertices: Vec<[f64; 3]>, articulation: Option<Value>, epochs: Value) -> Value {
    let mut v = json!({
        "object": {
            "mesh": {
                "vertices": vertices,
                "triangles": [
                    [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5], [0, 1, 5], [0, 5, 4],
                    [2, 6, 7], [2, 7, 3], [0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6],
                    [8, 9, 10], [8, 10, 11]
                ],
                "material_ids": [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1]
            },
            "materials": [
                { "name": "bus", "model": "lambert", "albedo": 0.6 },
                { "name": "panel", "model": "lambert", "albedo": 0.3 }
            ]
        },
        "epochs": epochs,
        "illumination": { "earthshine": "off" },
        "method": "silhouette"
    });
    if let Some(a) = articulation {
        v["articulation"] = a;
    }
    v
}

/// The bus's corners, then the upright panel's (counter-clockwise seen from +x).
fn bus_and_upright_panel() -> Vec<[f64; 3]> {
    let mut v: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            let c = |bit: i32| if k & bit == 0 { -1.0 } else { 1.0 };
            [c(1), c(2), c(4)]
        })
        .collect();
    v.extend([
        [0.0, -1.0, 2.0],
        [0.0, 1.0, 2.0],
        [0.0, 1.0, 4.0],
        [0.0, -1.0, 4.0],
    ]);
    v
}

/// A part turned by a `fixed` 90° gives the light curve of the mesh turned by hand (the
/// panel's corners rotated about the hinge by the exact matrix of a quarter turn about
/// y): the two differ by the rounding of cos 90° (6e-17), so 1e-12 relative.
#[test]
fn a_fixed_quarter_turn_is_the_mesh_turned_by_hand() {
    let mut epochs = Vec::new();
    for (k, (el_s, az_s, el_v, az_v)) in [
        (80.0, 10.0, 30.0, 170.0),
        (40.0, 200.0, 50.0, 20.0),
        (-20.0, 60.0, 10.0, 100.0),
        (60.0, 300.0, -30.0, 250.0),
    ]
    .into_iter()
    .enumerate()
    {
        let s = dir(f64::to_radians(el_s), f64::to_radians(az_s));
        let v = dir(f64::to_radians(el_v), f64::to_radians(az_v)) * 1e7;
        epochs.push(json!({ "t": k, "sun": s.to_array(), "observer": v.to_array() }));
    }
    let epochs = Value::Array(epochs);
    let hinge = json!([{ "parts": ["panel"], "law": "fixed", "angle_deg": 90, "axis": [0, 1, 0], "pivot": [0, 0, 2] }]);
    let turned = from_json(&bus_and_panel(
        bus_and_upright_panel(),
        Some(hinge),
        epochs.clone(),
    ));
    // R_y(90°): (x, y, z) ↦ (z, y, −x), about the pivot (0, 0, 2)
    let quarter = DMat3::from_cols(DVec3::new(0.0, 0.0, -1.0), DVec3::Y, DVec3::X);
    let pivot = DVec3::new(0.0, 0.0, 2.0);
    let mut by_hand = bus_and_upright_panel();
    for p in &mut by_hand[8..] {
        *p = (pivot + quarter * (DVec3::from_array(*p) - pivot)).to_array();
    }
    let rigid = from_json(&bus_and_panel(by_hand, None, epochs));
    let (a, b) = (glint::simulate(&turned), glint::simulate(&rigid));
    for (i, (x, y)) in a.epochs.iter().zip(&b.epochs).enumerate() {
        assert!(
            rel(x.irradiance_w_m2, y.irradiance_w_m2) < 1e-12,
            "epoch {i}: {} vs {}",
            x.irradiance_w_m2,
            y.irradiance_w_m2
        );
        assert!(
            rel(x.lit_visible_area_m2, y.lit_visible_area_m2) < 1e-12,
            "epoch {i}"
        );
    }
    assert!(a.epochs.iter().any(|e| e.irradiance_w_m2 > 0.0));
}

/// Shadows follow the part. The Sun overhead (+z), the observer 45° off towards −x (it
/// sees the bus's top past the panel). Upright (0°), the panel is edge-on to the Sun and
/// the 4 m² top is all lit; leaned by θ its shadow covers x from 0 to min(2 sin θ, 1) of
/// the 2 m-wide top: lit 4 − 2·min(2 sin θ, 1) m² (2.632 m² at 20°, 2 m² at 90°). The
/// panel's lit side faces away from the observer and no other bus face is lit, so
/// E = E_s (ρ/π) A_lit cosθr / R² with cosθr = 1/√2. The angles come from an `angles`
/// series (0° at t = 0, 20° at 3 s, 90° at 10 s). Exact clipping: 1e-12 relative.
#[test]
fn a_panel_leaned_over_the_bus_shades_it_by_its_shadows_area() {
    let range = 1e7;
    let obs = [-FRAC_1_SQRT_2 * range, 0.0, FRAC_1_SQRT_2 * range];
    let epochs = json!([
        { "t": 0, "sun": [0, 0, 1], "observer": obs },
        { "t": 3, "sun": [0, 0, 1], "observer": obs },
        { "t": 10, "sun": [0, 0, 1], "observer": obs }
    ]);
    let hinge = json!([{ "parts": ["panel"], "law": "angles", "axis": [0, 1, 0], "pivot": [0, 0, 2],
        "series": [{ "t": 0, "angle_deg": 0 }, { "t": 3, "angle_deg": 20 }, { "t": 10, "angle_deg": 90 }] }]);
    let scene = from_json(&bus_and_panel(bus_and_upright_panel(), Some(hinge), epochs));
    let r = glint::simulate(&scene);
    assert!(
        r.summary.method.contains("3 pose(s)"),
        "{}",
        r.summary.method
    );
    for (e, theta) in r.epochs.iter().zip([0.0f64, 20.0, 90.0]) {
        let lit = 4.0 - 2.0 * (2.0 * theta.to_radians().sin()).min(1.0);
        let truth = es_default() * 0.6 / PI * lit * FRAC_1_SQRT_2 / (range * range);
        assert!(
            rel(e.lit_visible_area_m2, lit) < 1e-12,
            "θ {theta}: {} vs {lit}",
            e.lit_visible_area_m2
        );
        assert!(
            rel(e.irradiance_w_m2, truth) < 1e-12,
            "θ {theta}: {} vs {truth}",
            e.irradiance_w_m2
        );
    }
}

/// Hinges whose angles repeat share one preparation: a `fixed` hinge is one pose for
/// every epoch, and its light curve is the same (to rounding) as with the poses prepared
/// one by one.
#[test]
fn identical_angles_share_one_pose() {
    let mut v = tracking_pass();
    v["geometry"]["articulation"] =
        json!([{ "parts": ["panel"], "law": "fixed", "angle_deg": 30, "axis": [0, 1, 0] }]);
    let scene = from_json(&v);
    let r = glint::simulate(&scene);
    assert!(
        r.summary.method.contains(" 1 pose(s)"),
        "{}",
        r.summary.method
    );
    let a = scene.articulation.as_ref().unwrap();
    let first = glint::integrate::articulated::posed(
        &scene,
        a,
        &a.angles(scene.epochs[0].t, scene.epochs[0].sun),
    );
    let mut one = first.clone();
    one.epochs = scene.epochs.clone();
    one.sky = scene.sky.clone();
    let rigid = glint::simulate(&one);
    // the pose from the structure the parts share, the rigid mesh prepared whole:
    // rounding apart
    for (x, y) in r.epochs.iter().zip(&rigid.epochs) {
        assert!(
            close(x.irradiance_w_m2, y.irradiance_w_m2),
            "{} vs {}",
            x.irradiance_w_m2,
            y.irradiance_w_m2
        );
    }
}

/// The bus with a 2 m × 2 m two-sided panel (material 1) hinged along y through the
/// centre of the bus's top (0, 0, 1) and sunk 0.5 m into it (z from 0.5 to 2.5): at every
/// angle the panel crosses the top along a segment through the hinge (contacts between
/// the link and the body, no vertex shared), and leaned it shades the top.
fn bus_and_sunk_panel(articulation: Value, epochs: Value) -> Value {
    let mut vertices = bus_and_upright_panel();
    for p in &mut vertices[8..] {
        p[2] -= 1.5;
    }
    let mut v = bus_and_panel(vertices, Some(articulation), epochs);
    v["object"]["materials"][1]["two_sided"] = json!(true);
    v
}

/// Each pose's light curve from the structure the parts share (faces and silhouette
/// edges built once, moved to the pose, contacts between parts found per pose) against
/// the same pose prepared as a rigid mesh: rounding apart (1e-12 relative), with the
/// panel crossing the bus (contacts) and its shadow on the bus, and on the box-wing,
/// whose tracking panels cross its booms' end caps. The bus's first epoch is also held
/// to its closed form: the Sun overhead, the observer 45° off towards +x, the panel
/// leaned by θ = 20° over +x; the panel's 1.5 m above the top shades x from 0 to
/// 1.5 sin θ of it and hides x from −1.5 (cos θ − sin θ) to 0, and the panel's lit side
/// faces away: lit and seen 2 · (2 − 1.5 cos θ) m².
#[test]
fn a_pose_from_the_shared_structure_is_the_rigid_mesh_posed() {
    let range = 1e7;
    let mut epochs = vec![
        json!({ "t": 0, "sun": [0, 0, 1], "observer": [FRAC_1_SQRT_2 * range, 0.0, FRAC_1_SQRT_2 * range] }),
    ];
    for k in 1..6 {
        let s = dir(
            f64::to_radians(70.0 - 5.0 * k as f64),
            f64::to_radians(20.0 + 30.0 * k as f64),
        );
        let o = dir(
            f64::to_radians(40.0),
            f64::to_radians(150.0 + 25.0 * k as f64),
        ) * range;
        epochs.push(json!({ "t": k, "sun": s.to_array(), "observer": o.to_array() }));
    }
    let series: Vec<Value> = [20.0, -50.0, -27.0, 5.0, 42.0, 65.0]
        .iter()
        .enumerate()
        .map(|(k, a)| json!({ "t": k, "angle_deg": a }))
        .collect();
    let hinge = json!([{ "parts": ["panel"], "law": "angles", "axis": [0, 1, 0], "pivot": [0, 0, 1], "series": series }]);
    let bus = from_json(&bus_and_sunk_panel(hinge, Value::Array(epochs)));
    let mut wing: Value =
        serde_json::from_str(include_str!("../scenes/box-wing.json")).expect("scene");
    wing["epochs"] = json!([
        { "t": 0, "sun": dir(0.3, 1.4).to_array(), "observer": [1e7, 3e6, 2e6], "earth": [0, 0, -4.2e7] },
        { "t": 1, "sun": dir(-0.2, 1.5).to_array(), "observer": [-4e6, 8e6, 5e6], "earth": [3e7, 0, -3e7] },
        { "t": 2, "sun": dir(0.5, -1.3).to_array(), "observer": [2e6, -9e6, -3e6], "earth": [0, 4.2e7, 0] },
        { "t": 3, "sun": dir(0.1, 0.4).to_array(), "observer": [6e6, 1e6, 7e6], "earth": [-4.2e7, 0, 0] }
    ]);
    wing["articulation"] =
        json!([{ "parts": ["panel"], "law": "sun-tracking", "axis": [0, 1, 0] }]);
    let wing = from_json(&wing);
    for scene in [&bus, &wing] {
        let a = scene.articulation.as_ref().expect("articulated");
        let shared = glint::integrate::articulated::Shared::build(scene, a).expect("shared");
        let r = glint::simulate(scene);
        for (i, e) in scene.epochs.iter().enumerate() {
            let angles = a.angles(e.t, e.sun);
            let mut rigid = glint::integrate::articulated::posed(scene, a, &angles);
            assert!(
                shared.prepare(&rigid, a, &angles).is_some(),
                "epoch {i}: the parts share no vertex"
            );
            rigid.epochs = vec![*e];
            let want = &glint::simulate(&rigid).epochs[0];
            let got = &r.epochs[i];
            for (x, y) in [
                (got.irradiance_w_m2, want.irradiance_w_m2),
                (got.lit_visible_area_m2, want.lit_visible_area_m2),
                (got.earthshine_w_m2, want.earthshine_w_m2),
            ] {
                assert!(close(x, y), "epoch {i}: {x} vs {y}");
            }
            assert!(got.irradiance_w_m2 > 0.0, "epoch {i}");
        }
    }
    let lit = 2.0 * (2.0 - 1.5 * 20f64.to_radians().cos());
    let got = glint::simulate(&bus).epochs[0].lit_visible_area_m2;
    assert!(rel(got, lit) < 1e-12, "{got} vs {lit}");
}
