//! Bad input: every bad request gives an error naming the field, never a panic; and any
//! request that passes validation simulates to finite numbers.

mod common;

use common::*;
use glint::{Limits, Scene, ValidationError};
use proptest::prelude::*;
use serde_json::{json, Value};

/// A valid request: a one-sided triangle plus a two-sided one, two materials.
fn base() -> Value {
    json!({
        "object": {
            "mesh": {
                "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                "triangles": [[0, 1, 2], [0, 1, 3]],
                "material_ids": [0, 1]
            },
            "materials": [
                { "name": "a", "model": "lambert", "albedo": 0.3 },
                { "name": "b", "model": "seed-microfacet", "kd": 0.1, "km": 0.5, "slope_rms": 0.1, "n": 0.18, "k": 3.6, "two_sided": true }
            ]
        },
        "epochs": [
            { "t": 0.0, "sun": [1, 1, 1], "observer": [0, 3.6e7, 1e7], "earth": [0, 0, -4.2e7] },
            { "t": "2026-11-22T04:50:00Z", "sun": [1, 0, 1], "observer": [1e7, 0, 3e7] }
        ],
        "illumination": { "band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "off", "earth_albedo": 0.35 }
    })
}

fn check(v: &Value) -> Result<Scene, ValidationError> {
    Scene::from_json(&v.to_string(), &Limits::unlimited())
}

/// Applies `edit` to the base request and asserts the error names exactly `field`.
fn expect_field(edit: impl FnOnce(&mut Value), field: &str) -> ValidationError {
    let mut v = base();
    edit(&mut v);
    match check(&v) {
        Ok(_) => panic!("accepted a bad request (expected an error on `{field}`): {v}"),
        Err(e) => {
            assert_eq!(e.field, field, "wrong field in error: {e}");
            assert!(!e.message.is_empty());
            // the Display form carries both, as the CLI prints it
            let shown = e.to_string();
            assert!(
                shown.contains(field) && shown.contains(&e.message),
                "{shown}"
            );
            e
        }
    }
}

#[test]
fn base_request_is_valid_and_simulates() {
    let s = check(&base()).expect("base request must be valid");
    assert_eq!(s.mesh.triangles.len(), 2);
    assert_eq!(s.epochs.len(), 2);
    assert_sane(&glint::simulate(&s));
}

#[test]
fn text_that_is_not_json_is_an_error_not_a_panic() {
    for text in ["", "{", "nonsense", "[]", "null", "{\"object\": 3}"] {
        let e = Scene::from_json(text, &Limits::unlimited()).expect_err(text);
        assert!(!e.message.is_empty(), "{text:?}: {e:?}");
    }
}

#[test]
fn numbers_json_cannot_hold() {
    // JSON has no NaN or infinity; 1e999 is what a client sends when it tries.
    let text = base().to_string().replacen("[1,1,1]", "[1e999,1,1]", 1);
    assert!(text.contains("1e999"));
    let e = Scene::from_json(&text, &Limits::unlimited()).expect_err("1e999 accepted");
    assert!(e.field.starts_with("epochs[0].sun"), "{e}");
    let text = base()
        .to_string()
        .replacen("\"albedo\":0.3", "\"albedo\":-1e999", 1);
    assert!(text.contains("-1e999"));
    let e = Scene::from_json(&text, &Limits::unlimited()).expect_err("-1e999 accepted");
    assert_eq!(e.field, "object.materials[0].albedo", "{e}");
    // NaN spelled out is not JSON at all
    let text = base()
        .to_string()
        .replacen("\"albedo\":0.3", "\"albedo\":NaN", 1);
    assert!(Scene::from_json(&text, &Limits::unlimited()).is_err());
}

#[test]
fn zero_vectors() {
    expect_field(
        |v| v["epochs"][0]["sun"] = json!([0, 0, 0]),
        "epochs[0].sun",
    );
    expect_field(
        |v| v["epochs"][1]["observer"] = json!([0.0, -0.0, 0.0]),
        "epochs[1].observer",
    );
    expect_field(
        |v| v["epochs"][0]["earth"] = json!([0, 0, 0]),
        "epochs[0].earth",
    );
}

#[test]
fn huge_vectors_are_rejected_or_finite() {
    // |v|² overflows f64: the request must be refused with the field named, or computed
    // to finite numbers; never a NaN or a panic.
    for (i, huge) in [[1e200, 0.0, 0.0], [1e300, 1e300, 1e300], [1e-200, 0.0, 0.0]]
        .into_iter()
        .enumerate()
    {
        for key in ["sun", "observer"] {
            let mut v = base();
            v["epochs"][0][key] = json!(huge);
            match check(&v) {
                Err(e) => {
                    assert_eq!(e.field, format!("epochs[0].{key}"), "case {i}: {e}");
                    // a huge or tiny vector is not "the zero vector": say what is wrong
                    assert!(!e.message.contains("zero"), "case {i}: {e}");
                }
                Ok(s) => assert_sane(&glint::simulate(&s)),
            }
        }
    }
    // huge but finite vertex coordinates
    let mut v = base();
    v["object"]["mesh"]["vertices"] =
        json!([[1e300, 0, 0], [-1e300, 0, 0], [0, 1e300, 0], [0, 0, 1e300]]);
    match check(&v) {
        Err(e) => assert!(e.field.starts_with("object.mesh"), "{e}"),
        Ok(s) => assert_sane(&glint::simulate(&s)),
    }
}

#[test]
fn mesh_errors() {
    expect_field(
        |v| v["object"]["mesh"]["triangles"][1] = json!([0, 1, 4]),
        "object.mesh.triangles[1]",
    );
    expect_field(
        |v| v["object"]["mesh"]["material_ids"] = json!([0, 2]),
        "object.mesh.material_ids[1]",
    );
    expect_field(
        |v| v["object"]["mesh"]["material_ids"] = json!([0]),
        "object.mesh.material_ids",
    );
    expect_field(
        |v| {
            v["object"]["mesh"]["vertices"] = json!([]);
            v["object"]["mesh"]["triangles"] = json!([]);
            v["object"]["mesh"]["material_ids"] = json!([]);
        },
        "object.mesh.triangles",
    );
    // every triangle degenerate (collinear corners)
    expect_field(
        |v| v["object"]["mesh"]["vertices"] = json!([[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]),
        "object.mesh.triangles",
    );
    expect_field(
        |v| v["object"]["mesh"]["triangles"][0] = json!([0, 1, -2]),
        "object.mesh.triangles[0][2]",
    );
    expect_field(
        |v| v["object"]["mesh"]["vertices"][2] = json!([0, 1]),
        "object.mesh.vertices[2]",
    );
    expect_field(
        |v| v["object"]["mesh"]["builtin"] = json!("plate"),
        "object.mesh",
    );
    expect_field(
        |v| v["object"]["mesh"] = json!({ "builtin": "death-star" }),
        "object.mesh.builtin",
    );
    expect_field(|v| v["object"]["mesh"] = json!({}), "object.mesh");
    expect_field(
        |v| v["object"]["mesh"] = json!({ "builtin": "plate", "material_ids": [0, 0] }),
        "object.mesh.material_ids",
    );
    // a built-in whose material names are not in the request
    expect_field(
        |v| v["object"]["mesh"] = json!({ "builtin": "box-wing" }),
        "object.materials",
    );
}

#[test]
fn obj_errors() {
    let obj = |text: &str| {
        let text = text.to_string();
        move |v: &mut Value| v["object"]["mesh"] = json!({ "obj": text })
    };
    expect_field(
        obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
        "object.mesh.obj",
    );
    expect_field(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "object.mesh.obj");
    expect_field(
        obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nope\nf 1 2 3\n"),
        "object.mesh.obj",
    );
    expect_field(
        obj("v 0 0 0\nv 1 0 0\nv 0 1 zz\nf 1 2 3\n"),
        "object.mesh.obj",
    );
    expect_field(
        obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
        "object.mesh.obj",
    );
    // tobj reads these as numbers; they once reached the BVH builder and panicked (500)
    for bad in ["nan", "inf", "-inf", "NaN"] {
        expect_field(
            obj(&format!(
                "v {bad} 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 2 3 4\nf 1 3 4\n"
            )),
            "object.mesh.obj",
        );
    }
    // a valid one for contrast: materials by `usemtl` name
    let mut v = base();
    obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl b\nf 1 2 3\nusemtl a\nf 1 2 4\n")(&mut v);
    let s = check(&v).expect("valid OBJ");
    assert_eq!(s.mesh.material_ids, vec![1, 0]);
}

#[test]
fn material_errors() {
    expect_field(
        |v| v["object"]["materials"][0]["albedo"] = json!(-0.1),
        "object.materials[0].albedo",
    );
    expect_field(
        |v| v["object"]["materials"][0]["albedo"] = json!(1.5),
        "object.materials[0].albedo",
    );
    expect_field(
        |v| v["object"]["materials"][1]["slope_rms"] = json!(0.0),
        "object.materials[1].slope_rms",
    );
    expect_field(
        |v| v["object"]["materials"][1]["kd"] = json!(-1),
        "object.materials[1].kd",
    );
    expect_field(
        |v| v["object"]["materials"][1]["n"] = json!(0),
        "object.materials[1].n",
    );
    expect_field(
        |v| v["object"]["materials"][1]["k"] = json!(-3.6),
        "object.materials[1].k",
    );
    expect_field(
        |v| {
            v["object"]["materials"][1]
                .as_object_mut()
                .unwrap()
                .remove("km");
        },
        "object.materials[1].km",
    );
    // a parameter of another model
    expect_field(
        |v| v["object"]["materials"][0]["alpha"] = json!(0.1),
        "object.materials[0].alpha",
    );
    expect_field(
        |v| v["object"]["materials"][0]["model"] = json!("phong"),
        "object.materials[0].model",
    );
    expect_field(
        |v| {
            v["object"]["materials"][0]
                .as_object_mut()
                .unwrap()
                .remove("model");
        },
        "object.materials[0].model",
    );
    expect_field(
        |v| v["object"]["materials"][0] = json!("no-such-preset"),
        "object.materials[0]",
    );
    expect_field(
        |v| v["object"]["materials"][0] = json!({ "name": "a", "preset": "no-such-preset" }),
        "object.materials[0].preset",
    );
    expect_field(
        |v| v["object"]["materials"][1]["name"] = json!("a"),
        "object.materials[1].name",
    );
    expect_field(|v| v["object"]["materials"] = json!([]), "object.materials");
    expect_field(
        |v| {
            v["object"]["materials"][0] =
                json!({ "name": "a", "model": "rough-conductor", "alpha": 0.1, "n": 1.5 })
        },
        "object.materials[0].k",
    );
    // the rough conductor's Smith form: one of two names, and only for that model
    let rough =
        json!({ "name": "a", "model": "rough-conductor", "alpha": 0.1, "n": 1.5, "k": 3.0 });
    for ok in ["separable", "correlated"] {
        let mut v = base();
        v["object"]["materials"][0] = rough.clone();
        v["object"]["materials"][0]["shadowing"] = json!(ok);
        check(&v).unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
    for bad in [json!("height-correlated"), json!(1)] {
        let e = expect_field(
            |v| {
                v["object"]["materials"][0] = rough.clone();
                v["object"]["materials"][0]["shadowing"] = bad.clone();
            },
            "object.materials[0].shadowing",
        );
        assert!(
            e.message.contains("separable") || e.message.contains("invalid type"),
            "{e}"
        );
    }
    expect_field(
        |v| v["object"]["materials"][1]["shadowing"] = json!("separable"),
        "object.materials[1].shadowing",
    );
    expect_field(
        |v| {
            v["object"]["materials"][0] =
                json!({ "name": "a", "preset": "seed-body-wrap", "shadowing": "correlated" })
        },
        "object.materials[0].shadowing",
    );
    expect_field(
        |v| v["object"]["materials"][0] = json!({ "name": "a", "model": "ashikhmin-shirley", "rd": 0.3, "rs": 0.1, "nu": -5, "nv": 5 }),
        "object.materials[0].nu",
    );
    // presets work, by bare name and under a name
    let mut v = base();
    v["object"]["materials"][0] = json!("seed-body-wrap");
    v["object"]["materials"][1] =
        json!({ "name": "paint", "preset": "seed-white-paint", "two_sided": true });
    check(&v).expect("presets");
}

#[test]
fn unknown_fields_are_named() {
    expect_field(|v| v["colour"] = json!("red"), "colour");
    expect_field(
        |v| v["epochs"][1]["sun_dir"] = json!([1, 0, 0]),
        "epochs[1].sun_dir",
    );
    expect_field(
        |v| v["illumination"]["band"] = json!([0.4, 0.7]),
        "illumination.band",
    );
    expect_field(
        |v| v["object"]["mesh"]["normals"] = json!([]),
        "object.mesh.normals",
    );
    expect_field(|v| v["object"]["scale"] = json!(2), "object.scale");
    // inside a material: the field itself must be named, not just "some material"
    expect_field(
        |v| v["object"]["materials"][0]["albdo"] = json!(0.3),
        "object.materials[0].albdo",
    );
    expect_field(
        |v| v["object"]["materials"][1]["slope"] = json!(0.1),
        "object.materials[1].slope",
    );
}

#[test]
fn wrong_types_are_named() {
    expect_field(|v| v["epochs"][0]["sun"] = json!("up"), "epochs[0].sun");
    expect_field(
        |v| v["object"]["materials"][0]["albedo"] = json!("high"),
        "object.materials[0].albedo",
    );
    expect_field(|v| v["tolerance"] = json!("tight"), "tolerance");
}

#[test]
fn epoch_and_illumination_errors() {
    expect_field(|v| v["epochs"] = json!([]), "epochs");
    expect_field(|v| v["epochs"][1]["t"] = json!("yesterday"), "epochs[1].t");
    expect_field(
        |v| v["epochs"][0]["earth"] = json!([0, 0, -6.0e6]),
        "epochs[0].earth",
    );
    expect_field(
        |v| v["epochs"][0]["sun_distance_au"] = json!(0),
        "epochs[0].sun_distance_au",
    );
    expect_field(
        |v| v["epochs"][0]["attitude"] = json!([2, 0, 0, 0]),
        "epochs[0].attitude",
    );
    expect_field(
        |v| v["illumination"]["band_um"] = json!([0.7, 0.4]),
        "illumination.band_um",
    );
    expect_field(
        |v| v["illumination"]["sun_temperature_k"] = json!(-5900),
        "illumination.sun_temperature_k",
    );
    expect_field(
        |v| v["illumination"]["earth_albedo"] = json!(-0.35),
        "illumination.earth_albedo",
    );
    expect_field(
        |v| v["illumination"]["earthshine"] = json!("moon"),
        "illumination.earthshine",
    );
    expect_field(|v| v["tolerance"] = json!(0), "tolerance");
    expect_field(|v| v["tolerance"] = json!(2), "tolerance");
    expect_field(|v| v["method"] = json!("magic"), "method");
}

#[test]
fn earthshine_without_earth() {
    for model in ["seed", "sphere"] {
        let e = expect_field(
            |v| v["illumination"]["earthshine"] = json!(model),
            "epochs[1].earth",
        );
        assert!(e.message.contains("earthshine"), "{e}");
    }
    // off, or not asked for: fine without an Earth
    let mut v = base();
    v["illumination"]
        .as_object_mut()
        .unwrap()
        .remove("earthshine");
    check(&v).expect("default earthshine without earth");
}

/// The work a request asks for is bounded before any is done: triangles × epochs, and
/// the pixel samples of the `image` method and of the thumbnails, each refused as a limit
/// (HTTP 413) naming the field that makes it large.
#[test]
fn work_over_the_limits_is_refused_before_it_starts() {
    let v = base();
    let triangles = Scene::from_json(&v.to_string(), &Limits::unlimited())
        .unwrap()
        .mesh
        .triangles
        .len() as u64;
    let epochs = v["epochs"].as_array().unwrap().len() as u64;
    let at = |te: u64, px: u64| Limits {
        max_triangle_epochs: te,
        max_pixel_samples: px,
        ..Limits::unlimited()
    };
    // exactly at the limit passes, one under fails
    let n = triangles * epochs;
    Scene::from_json(&v.to_string(), &at(n, 0)).expect("at the triangle-epoch limit");
    let e = Scene::from_json(&v.to_string(), &at(n - 1, 0)).expect_err("one over");
    assert!(e.is_limit() && e.field == "epochs", "{e}");
    assert!(e.message.contains("triangle-epochs"), "{e}");

    // the image method: epochs × size² × samples²
    let mut img = v.clone();
    img["method"] = json!("image");
    img["image_size"] = json!(64);
    img["image_samples"] = json!(2);
    let px = epochs * 64 * 64 * 4;
    Scene::from_json(&img.to_string(), &at(u64::MAX, px)).expect("at the pixel limit");
    let e = Scene::from_json(&img.to_string(), &at(u64::MAX, px - 1)).expect_err("one over");
    assert!(e.is_limit() && e.field == "image_size", "{e}");

    // thumbnails count too, on top of the image method's samples
    let mut th = img.clone();
    th["thumbnails"] = json!({"size": 16, "samples": 1, "epochs": [0]});
    Scene::from_json(&th.to_string(), &at(u64::MAX, px + 256)).expect("at the limit");
    let e = Scene::from_json(&th.to_string(), &at(u64::MAX, px + 255)).expect_err("one over");
    assert!(e.is_limit() && e.field == "thumbnails", "{e}");
}

/// A fixed-length array with an element too many or too few is a wrong value of that
/// field (422), never "invalid JSON" (400).
#[test]
fn fixed_length_arrays_of_the_wrong_length_name_their_field() {
    for (bad, field) in [
        (json!([1, 0, 0, 5]), "epochs[0].sun"),
        (json!([1, 0]), "epochs[0].sun"),
    ] {
        let e = expect_field(|v| v["epochs"][0]["sun"] = bad.clone(), field);
        assert!(!e.message.starts_with("invalid JSON"), "{e}");
    }
    let e = expect_field(
        |v| v["illumination"]["band_um"] = json!([0.4, 0.7, 0.9]),
        "illumination.band_um",
    );
    assert!(e.message.contains("more elements"), "{e}");
}

#[test]
fn limits_are_reported_as_limits() {
    let limits = Limits {
        max_triangles: 1,
        max_epochs: 10,
        ..Limits::unlimited()
    };
    let e = Scene::from_json(&base().to_string(), &limits).expect_err("over the triangle limit");
    assert!(e.is_limit() && e.field == "object.mesh", "{e}");
    let limits = Limits {
        max_triangles: 10,
        max_epochs: 1,
        ..Limits::unlimited()
    };
    let e = Scene::from_json(&base().to_string(), &limits).expect_err("over the epoch limit");
    assert!(e.is_limit() && e.field == "epochs", "{e}");
    let e = expect_field(|v| v["epochs"] = json!([]), "epochs");
    assert!(!e.is_limit());
}

/// Numbers that break naive code: zero, signed zero, subnormal, huge, negative.
fn nasty() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        Just(1e-310),
        Just(1e-160),
        Just(1e150),
        Just(1e300),
        Just(-1e300),
        Just(f64::MAX),
        Just(f64::MIN_POSITIVE),
        -10.0..10.0f64,
        -1e8..1e8f64,
    ]
}

fn vec3() -> impl Strategy<Value = [f64; 3]> {
    [nasty(), nasty(), nasty()]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Random, often absurd, numbers anywhere in a request: either an error naming a
    /// field, or finite results. Never a panic, a NaN or an infinity.
    #[test]
    fn any_numbers_error_or_finite(
        verts in proptest::collection::vec(vec3(), 4),
        sun in vec3(), obs in vec3(), earth in vec3(),
        albedo in nasty(), slope in nasty(), km in nasty(), nk in (nasty(), nasty()),
        au in nasty(), tol in nasty(), band in (nasty(), nasty()), temp in nasty(),
        earthshine in prop_oneof![Just("off"), Just("seed"), Just("sphere")],
    ) {
        let v = json!({
            "object": {
                "mesh": { "vertices": verts, "triangles": [[0, 1, 2], [0, 2, 3], [0, 3, 1]], "material_ids": [0, 1, 1] },
                "materials": [
                    { "name": "a", "model": "lambert", "albedo": albedo },
                    { "name": "b", "model": "seed-microfacet", "kd": 0.1, "km": km, "slope_rms": slope, "n": nk.0, "k": nk.1, "two_sided": true }
                ]
            },
            "epochs": [ { "t": 1.0, "sun": sun, "observer": obs, "earth": earth, "sun_distance_au": au } ],
            "illumination": { "band_um": [band.0, band.1], "sun_temperature_k": temp, "earthshine": earthshine },
            "tolerance": tol
        });
        match check(&v) {
            Err(e) => prop_assert!(!e.field.is_empty() && !e.message.is_empty(), "{e:?}"),
            Ok(s) => assert_sane(&glint::simulate(&s)),
        }
    }
}

/// The shipped `scenes/objects/*.obj` files, read through `{ "obj": text }`, give the
/// built-in objects' triangles exactly (same corners, in order, and materials by
/// `usemtl` name): the files and the procedural builtins are in sync.
#[test]
fn shipped_obj_files_match_the_builtins() {
    for b in glint::geometry::builtin::BUILTINS {
        let path = format!(
            "{}/scenes/objects/{}.obj",
            env!("CARGO_MANIFEST_DIR"),
            b.name
        );
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
        let materials: Vec<Value> = b
            .material_names
            .iter()
            .map(|n| json!({ "name": n, "model": "lambert", "albedo": 0.5, "two_sided": true }))
            .collect();
        let request = |mesh: Value| json!({ "object": { "mesh": mesh, "materials": materials }, "epochs": [ { "t": 0, "sun": [1, 0, 0], "observer": [1e7, 0, 0] } ] });
        let from_obj =
            check(&request(json!({ "obj": text }))).unwrap_or_else(|e| panic!("{}: {e}", b.name));
        let from_builtin = check(&request(json!({ "builtin": b.name }))).unwrap();
        let (m1, m2) = (&from_obj.mesh, &from_builtin.mesh);
        assert_eq!(m1.triangles.len(), m2.triangles.len(), "{}", b.name);
        for i in 0..m1.triangles.len() {
            assert_eq!(m1.corners(i), m2.corners(i), "{}: triangle {i}", b.name);
        }
        assert_eq!(m1.material_ids, m2.material_ids, "{}", b.name);
        // and the same light
        let (r1, r2) = (glint::simulate(&from_obj), glint::simulate(&from_builtin));
        assert_eq!(
            r1.epochs[0].irradiance_w_m2, r2.epochs[0].irradiance_w_m2,
            "{}",
            b.name
        );
    }
}

/// Every example request in `scenes/` is valid.
#[test]
fn every_shipped_scene_validates() {
    let dir = format!("{}/scenes", env!("CARGO_MANIFEST_DIR"));
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let text = std::fs::read_to_string(&path).unwrap();
            Scene::from_json(&text, &Limits::unlimited())
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            n += 1;
        }
    }
    assert!(n >= 9, "{n} scenes");
}

/// `detail` picks a built-in object's tessellation; the old objects keep their mesh by
/// default; a wrong level, or a level without `builtin`, is an error naming the field.
#[test]
fn builtin_detail_levels() {
    use glint::geometry::builtin;
    let mesh = |detail: Option<&str>| {
        let mut spec = json!({ "builtin": "box-wing" });
        if let Some(d) = detail {
            spec["detail"] = json!(d);
        }
        let v = json!({
            "object": { "mesh": spec, "materials": ["seed-body-wrap",
                { "name": "body", "preset": "seed-body-wrap" },
                { "name": "panel", "preset": "seed-body-wrap" },
                { "name": "dish", "preset": "seed-body-wrap" }] },
            "epochs": [ { "t": 0, "sun": [1, 0, 0], "observer": [1e7, 0, 0] } ]
        });
        check(&v).map(|s| s.mesh)
    };
    let plain = builtin::box_wing();
    assert_eq!(mesh(None).unwrap().triangles, plain.triangles);
    assert_eq!(mesh(Some("coarse")).unwrap().triangles, plain.triangles);
    let medium = builtin::box_wing_with(48, 128, 3);
    assert_eq!(mesh(Some("medium")).unwrap().triangles, medium.triangles);
    assert!(mesh(Some("fine")).unwrap().triangles.len() > 150_000);
    let e = mesh(Some("extra-fine")).unwrap_err();
    assert_eq!(e.field, "object.mesh.detail");
    let e = check(&json!({
        "object": { "mesh": { "obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "detail": "fine" },
                    "materials": ["seed-body-wrap"] },
        "epochs": [ { "t": 0, "sun": [1, 0, 0], "observer": [1e7, 0, 0] } ]
    }))
    .unwrap_err();
    assert_eq!(e.field, "object.mesh.detail");
    for b in builtin::BUILTINS {
        for d in builtin::Detail::ALL {
            assert!(
                !(b.build)(d).triangles.is_empty(),
                "{} {}",
                b.name,
                d.name()
            );
        }
    }
}

/// Eq. 12 is a far-field sum: an observer inside the object's bounding sphere (1 mm from
/// a 1 m plate, or a unit direction given where a position in metres is meant, for a mesh
/// larger than a metre) is refused, naming the epoch's field; just outside it is accepted.
#[test]
fn an_observer_inside_the_objects_bounding_sphere_is_refused() {
    // the base mesh spans the unit cube's corner: centre (0.5, 0.5, 0.5), radius √3/2
    let e = expect_field(
        |v| v["epochs"][1]["observer"] = json!([0.5, 0.5, 0.501]),
        "epochs[1].observer",
    );
    assert!(e.message.contains("bounding radius"), "{e}");
    // a unit vector where metres are meant, for a 10 m object
    expect_field(
        |v| {
            v["object"]["mesh"]["vertices"] =
                json!([[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]]);
            v["epochs"][0]["observer"] = json!([0, 0.6, 0.8]);
        },
        "epochs[0].observer",
    );
    // 1 m beyond the sphere: a position, accepted
    let mut v = base();
    v["epochs"][1]["observer"] = json!([0.5, 0.5, 0.5 + 0.75f64.sqrt() + 1.0]);
    check(&v).expect("an observer outside the bounding sphere is valid");
}

/// A mesh in metres but absurdly large (1e100 m) is refused for its size, not as "zero
/// area" through an overflow; the same triangle listed twice (same winding) is refused,
/// two triangles back to back (a thin plate) are not.
#[test]
fn huge_coordinates_and_duplicated_triangles_are_named() {
    let e = expect_field(
        |v| v["object"]["mesh"]["vertices"][1] = json!([1e100, 0, 0]),
        "object.mesh.vertices[1]",
    );
    assert!(e.message.contains("metres"), "{e}");
    // triangle 1 repeats triangle 0, rotated (same winding)
    expect_field(
        |v| {
            v["object"]["mesh"]["triangles"] = json!([[0, 1, 2], [1, 2, 0]]);
        },
        "object.mesh.triangles[1]",
    );
    // back to back: kept
    let mut v = base();
    v["object"]["mesh"]["triangles"] = json!([[0, 1, 2], [0, 2, 1]]);
    check(&v).expect("two triangles back to back are a thin plate");
}

/// One request per body: data after it is refused (it was ignored), whitespace is not.
#[test]
fn data_after_the_request_is_refused() {
    let text = base().to_string();
    assert!(glint::scene::validate::parse_request(&format!("{text} \n\t")).is_ok());
    for tail in ["{}", "x", "[1]", "0", "\"more\""] {
        let e = glint::scene::validate::parse_request(&format!("{text}{tail}"))
            .expect_err("trailing data refused");
        assert!(e.message.contains("after the request"), "{tail}: {e}");
    }
}
