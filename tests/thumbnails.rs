//! Thumbnails: the rendered image is the light curve seen pixel by pixel.
//!
//! The main check is radiometric: Σ radiance × pixel area / R² over the image must agree
//! with the light curve's irradiance (computed by a different route: face sums with
//! adaptive visibility) within the image's sampling error, and that error must shrink
//! as the image grows and takes more samples per pixel.

use base64::Engine as _;
use glint::render::{exposure, radiometric_image, Renderer};
use glint::scene::{Exposure, Limits, Scene, Thumbnails};
use glint::{simulate, ValidationError};
use std::f64::consts::PI;

const R: f64 = 3.6e7;

fn box_wing_file() -> serde_json::Value {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/box-wing.json"))
            .unwrap();
    serde_json::from_str(&text).unwrap()
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

fn epoch(sun: [f64; 3], view: [f64; 3], earth: [f64; 3]) -> serde_json::Value {
    let v = unit(view);
    serde_json::json!({ "t": 0.0, "sun": sun, "observer": [v[0] * R, v[1] * R, v[2] * R], "earth": earth })
}

/// The box-wing at hand-picked geometries, each exercising one part of the physics,
/// with the light curve integrated to a tolerance far below the image's error.
fn box_wing_cases() -> (Scene, Vec<&'static str>) {
    let geo = [0.0, 0.0, -4.2164e7];
    let cases = [
        (
            // Sun from +y: the body's shadow covers the inner part of the −y panel's lit
            // (+x) side, which the observer sees
            "panel partly in the body's shadow",
            epoch([0.3, 0.9, 0.3], [1.0, -0.3, 0.5], geo),
        ),
        (
            // Sun and observer mirrored about +z: the body wrap's top face glints, with the
            // dish and its mast shading part of it
            "glint on the top face, partly shaded by the dish",
            epoch([0.3, 0.2, 0.93], [-0.3, -0.2, 0.93], geo),
        ),
        (
            // half a lobe width (slope_rms 0.01) off the mirror direction of the +x face:
            // the glint's flank, beside the panels' +x sides
            "glint flank on the +x face",
            epoch([0.9, 0.35, 0.1], [0.9, -0.35, -0.09], geo),
        ),
        (
            // the Sun behind the Earth (umbra at GEO): earthshine alone, from −z, with
            // the panels and booms casting earthshine shadows
            "earthshine only, in eclipse",
            epoch([0.0, 0.1, -1.0], [0.5, 0.4, -0.8], geo),
        ),
        (
            // back-lit: the observer sees the panels' unlit sides and the body's rims
            "high phase angle",
            epoch([0.2, 0.95, 0.1], [-0.3, -0.9, 0.45], geo),
        ),
    ];
    let mut req = box_wing_file();
    req["epochs"] = serde_json::Value::Array(cases.iter().map(|c| c.1.clone()).collect());
    // the light curve to 1e-6 of each epoch's signal: its own error is then negligible
    req["tolerance"] = serde_json::json!(1e-6);
    let scene = Scene::from_json(&req.to_string(), &Limits::unlimited()).unwrap();
    (scene, cases.iter().map(|c| c.0).collect())
}

#[test]
fn image_sum_agrees_with_the_light_curve_and_converges() {
    let (scene, names) = box_wing_cases();
    let lc = simulate(&scene);
    // one epoch is in the Earth's umbra (the case exists to test earthshine alone)
    assert_eq!(lc.epochs[3].eclipse, 1.0);
    assert!(lc.epochs[3].earthshine_w_m2 > 0.0 && lc.epochs[3].sun_w_m2 == 0.0);
    let renderer = Renderer::new(&scene);
    let (mut err_lo, mut err_hi) = (0.0, 0.0);
    for (i, name) in names.iter().enumerate() {
        let e = lc.epochs[i].irradiance_w_m2;
        assert!(e > 0.0, "{name}: no light");
        let lo = renderer.render(&scene.epochs[i], 64, 1);
        let hi = renderer.render(&scene.epochs[i], 256, 4);
        let (d_lo, d_hi) = (
            (lo.irradiance_w_m2() - e).abs() / e,
            (hi.irradiance_w_m2() - e).abs() / e,
        );
        let (s_lo, s_hi) = (lo.std_error_w_m2() / e, hi.std_error_w_m2() / e);
        println!("{name}: 64 px 1 spp: rel. error {d_lo:.2e} (σ {s_lo:.1e}); 256 px 16 spp: {d_hi:.2e} (σ {s_hi:.1e})");
        // Within the estimated sampling error: 4σ (σ from each pixel's sample spread),
        // plus 1e-5 for the light curve's tolerance and f32 hit points.
        assert!(
            d_lo <= 4.0 * s_lo + 1e-5,
            "{name}: 64 px: {d_lo:e} vs σ {s_lo:e}"
        );
        assert!(
            d_hi <= 4.0 * s_hi + 1e-5,
            "{name}: 256 px: {d_hi:e} vs σ {s_hi:e}"
        );
        // Edge pixels carry the error: their number grows as the size, their area falls
        // as size⁻², and 16 stratified samples cut each one's variance at least 16-fold,
        // so σ should fall by ≳ 4^1.5·4 = 32; ask for 8.
        assert!(
            s_hi < s_lo / 8.0,
            "{name}: σ did not shrink: {s_lo:e} → {s_hi:e}"
        );
        // the 256 px image must be good in absolute terms too
        assert!(d_hi < 5e-3, "{name}: {d_hi:e}");
        err_lo += d_lo;
        err_hi += d_hi;
    }
    // The actual error shrinks too (summed over the cases, so one lucky coarse image
    // cannot decide it).
    assert!(
        err_hi < err_lo / 4.0,
        "error did not shrink: {err_lo:e} → {err_hi:e}"
    );
}

#[test]
fn image_sum_agrees_over_the_example_light_curve() {
    // The shipped request, at its own tolerance (1e-3): every 20th epoch, including
    // the partial shadows of the low phases and the glint near phase 150°.
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/box-wing.json"))
            .unwrap();
    let scene = Scene::from_json(&text, &Limits::unlimited()).unwrap();
    let lc = simulate(&scene);
    let renderer = Renderer::new(&scene);
    for i in (0..scene.epochs.len()).step_by(20) {
        let e = lc.epochs[i].irradiance_w_m2;
        let img = renderer.render(&scene.epochs[i], 192, 3);
        let d = (img.irradiance_w_m2() - e).abs() / e;
        let s = img.std_error_w_m2() / e;
        // 4σ of the image, plus twice the light curve's tolerance
        assert!(d <= 4.0 * s + 2e-3, "epoch {i}: rel. error {d:e}, σ {s:e}");
    }
}

fn plate_scene(sun: [f64; 3], view: [f64; 3], extra: serde_json::Value) -> Scene {
    let v = unit(view);
    let mut req = serde_json::json!({
        "object": { "mesh": { "builtin": "plate" }, "materials": [ { "name": "surface", "model": "lambert", "albedo": 0.3 } ] },
        "epochs": [ { "t": 0.0, "sun": sun, "observer": [v[0] * R, v[1] * R, v[2] * R] } ],
        "illumination": { "earthshine": "off" }
    });
    if let serde_json::Value::Object(m) = extra {
        for (k, val) in m {
            req[k] = val;
        }
    }
    Scene::from_json(&req.to_string(), &Limits::unlimited()).unwrap()
}

#[test]
fn lambert_plate_pixels_hold_the_analytic_radiance() {
    // A Lambertian surface lit at incidence θi has radiance ρ·E·cosθi/π whatever the
    // view direction: every pixel wholly on the plate must hold exactly that.
    let ci = 0.6f64;
    let sun = [(1.0 - ci * ci).sqrt(), 0.0, ci];
    let scene = plate_scene(sun, [0.2, -0.5, 0.8], serde_json::json!({}));
    let e_sun =
        glint::radiometry::sun::band_irradiance([0.4, 0.7], 5900.0, glint::radiometry::AU_M);
    let expected = 0.3 * e_sun * ci / PI;
    let img = radiometric_image(&scene, 0, 96, 2);
    let mut interior = 0;
    for (k, &l) in img.radiance.iter().enumerate() {
        if l == 0.0 {
            continue;
        }
        // f32 storage: 1e-6 relative; edge pixels are partly covered and smaller
        assert!(
            l as f64 <= expected * (1.0 + 1e-6),
            "pixel {k}: {l} > {expected}"
        );
        if ((l as f64) - expected).abs() <= expected * 1e-6 {
            interior += 1;
        }
    }
    // the plate (1 m², seen at cosθr = 0.8/|v|) covers most of its frame
    assert!(interior > 96 * 96 / 4, "only {interior} full pixels");
    // and the sum is the plate's intensity ρ·E·cosθi·cosθr·A/π over R²
    let cr = unit([0.2, -0.5, 0.8])[2];
    let exact = 0.3 * e_sun * ci * cr / PI / (R * R);
    let d = (img.irradiance_w_m2() - exact).abs();
    assert!(
        d <= 4.0 * img.std_error_w_m2() + 1e-9 * exact,
        "{} vs {exact}",
        img.irradiance_w_m2()
    );
}

fn decode(b64: &str) -> image::GrayImage {
    let png = base64::engine::general_purpose::STANDARD
        .decode(b64)
        .unwrap();
    image::load_from_memory(&png).unwrap().into_luma8()
}

fn thumbnail_request(spec: serde_json::Value) -> Scene {
    let mut req = box_wing_file();
    req["thumbnails"] = spec;
    Scene::from_json(&req.to_string(), &Limits::unlimited()).unwrap()
}

#[test]
fn response_carries_decodable_pngs_of_the_requested_epochs() {
    let scene = thumbnail_request(
        serde_json::json!({ "size": 48, "every": 100, "epochs": [7, 100], "samples": 2 }),
    );
    let response = simulate(&scene);
    let thumbs = response.thumbnails.expect("asked for thumbnails");
    // union of every 100th (0, 100, 200, 300) and the listed 7 and 100, ascending
    assert_eq!(
        thumbs.iter().map(|t| t.epoch).collect::<Vec<_>>(),
        vec![0, 7, 100, 200, 300]
    );
    for t in &thumbs {
        let img = decode(&t.png_base64);
        assert_eq!(img.dimensions(), (48, 48));
        assert_eq!(t.size, 48);
        assert_eq!(t.t, scene.epochs[t.epoch].t);
        // the scale is the radiometric image's (same camera)
        let r = radiometric_image(&scene, t.epoch, 48, 2);
        assert_eq!(t.metres_per_pixel, r.metres_per_pixel());
        // the object (≥ 2 m across at any angle) spans more than a third of the frame
        assert!(t.metres_per_pixel > 0.0 && t.metres_per_pixel * 48.0 < 3.0 * 13.0 + 1.0);
        assert!(
            img.pixels().any(|p| p.0[0] > 0),
            "epoch {}: black image",
            t.epoch
        );
    }
    // and none when not asked for (no cost either: the field stays absent)
    let plain = Scene::from_json(&box_wing_file().to_string(), &Limits::unlimited()).unwrap();
    assert!(plain.thumbnails.is_none());
    assert!(simulate(&plain).thumbnails.is_none());
}

#[test]
fn one_exposure_maps_every_frame_alike() {
    // Phases 0°–100° (no glint): with the `peak` exposure nothing saturates but the
    // brightest pixel, so the grey levels, linearised and scaled by the one white
    // level, give back each frame's irradiance — the frames' brightness ratios survive.
    let epochs: Vec<usize> = (0..=200).step_by(40).collect();
    let scene =
        thumbnail_request(serde_json::json!({ "size": 128, "epochs": epochs, "exposure": "peak" }));
    let response = simulate(&scene);
    let thumbs = response.thumbnails.unwrap();
    let white = thumbs[0].exposure_w_m2_sr;
    assert!(white > 0.0);
    for t in &thumbs {
        assert_eq!(t.exposure_w_m2_sr, white, "one exposure for the sequence");
        let img = decode(&t.png_base64);
        let radiometric = radiometric_image(&scene, t.epoch, 128, t_samples(&scene));
        // each grey level is the one the exposure gives the pixel's radiance
        for (g, &l) in img.pixels().zip(&radiometric.radiance) {
            assert_eq!(g.0[0], exposure::to_grey(&[l], white, false)[0]);
        }
        // inverse sRGB of the grey levels, × white × pixel area / R²
        let lin: f64 = img
            .pixels()
            .map(|p| inverse_srgb(p.0[0] as f64 / 255.0))
            .sum();
        let e = lin * white * t.metres_per_pixel.powi(2) / response.epochs[t.epoch].range_m.powi(2);
        let truth = response.epochs[t.epoch].irradiance_w_m2;
        // 8-bit quantisation: ≤ half a level per pixel, a few % of a dim frame's sum
        assert!(
            (e - truth).abs() / truth < 0.05,
            "epoch {}: {e:e} vs {truth:e}",
            t.epoch
        );
    }
}

fn t_samples(scene: &Scene) -> u32 {
    scene.thumbnails.as_ref().unwrap().samples
}

fn inverse_srgb(v: f64) -> f64 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[test]
fn default_exposure_is_one_for_the_sequence_and_survives_the_glint() {
    // The example sequence glints near phase 150° (10⁴ times the diffuse radiance):
    // the default `fixed` exposure is still one white level for all frames, and the
    // frames that do not glint are not left black.
    let scene = thumbnail_request(serde_json::json!({ "size": 64, "every": 20 }));
    let response = simulate(&scene);
    let thumbs = response.thumbnails.unwrap();
    let white = thumbs[0].exposure_w_m2_sr;
    assert!(thumbs.iter().all(|t| t.exposure_w_m2_sr == white));
    for t in &thumbs {
        let img = decode(&t.png_base64);
        let max = img.pixels().map(|p| p.0[0]).max().unwrap();
        assert!(max >= 64, "epoch {}: brightest grey level {max}", t.epoch);
    }
    // `auto` exposes each frame on its own: levels differ between frames
    let scene = thumbnail_request(
        serde_json::json!({ "size": 32, "epochs": [0, 300], "exposure": "auto" }),
    );
    let thumbs = simulate(&scene).thumbnails.unwrap();
    assert!(thumbs[1].exposure_w_m2_sr > 100.0 * thumbs[0].exposure_w_m2_sr);
}

#[test]
fn default_thumbnails_spread_about_eight_frames() {
    let t = Thumbnails::default_for(341);
    assert_eq!((t.size, t.exposure), (128, Exposure::Fixed));
    assert_eq!(t.epochs.len(), 8);
    assert_eq!(t.epochs[0], 0);
    assert!(*t.epochs.last().unwrap() < 341);
    assert_eq!(Thumbnails::default_for(3).epochs, vec![0, 1, 2]);
}

fn bad(spec: serde_json::Value) -> ValidationError {
    let mut req = box_wing_file();
    req["thumbnails"] = spec;
    match Scene::from_json(&req.to_string(), &Limits::unlimited()) {
        Ok(_) => panic!("{} must be rejected", req["thumbnails"]),
        Err(e) => e,
    }
}

#[test]
fn validation_errors_name_the_field() {
    let cases = [
        (serde_json::json!({ "size": 0 }), "thumbnails.size"),
        (serde_json::json!({ "size": 4096 }), "thumbnails.size"),
        (serde_json::json!({ "size": -5 }), "thumbnails.size"),
        (serde_json::json!({ "samples": 0 }), "thumbnails.samples"),
        (serde_json::json!({ "samples": 17 }), "thumbnails.samples"),
        (serde_json::json!({ "every": 0 }), "thumbnails.every"),
        (
            serde_json::json!({ "epochs": [0, 341] }),
            "thumbnails.epochs[1]",
        ),
        (serde_json::json!({ "epochs": [] }), "thumbnails.epochs"),
        (
            serde_json::json!({ "exposure": "bright" }),
            "thumbnails.exposure",
        ),
        (
            serde_json::json!({ "exposure": -1.0 }),
            "thumbnails.exposure",
        ),
        (
            serde_json::json!({ "exposure": true }),
            "thumbnails.exposure",
        ),
        (serde_json::json!({ "colour": "red" }), "thumbnails.colour"),
        (serde_json::json!(12), "thumbnails"),
    ];
    for (spec, field) in cases {
        let e = bad(spec.clone());
        assert_eq!(e.field, field, "{spec}: {e}");
        assert!(!e.is_limit(), "{spec}: {e}");
    }
    // size limits (HTTP 413), not bad values: 341 frames × 1024² pixels (memory), and
    // 5 frames × 1024² × 16² samples (time)
    for spec in [
        serde_json::json!({ "size": 1024, "every": 1 }),
        serde_json::json!({ "size": 1024, "epochs": [0, 1, 2, 3, 4], "samples": 16 }),
    ] {
        let e = bad(spec.clone());
        assert_eq!(e.field, "thumbnails", "{spec}");
        assert!(e.is_limit(), "{spec}: {e}");
    }
    assert!(Scene::from_json(
        &{
            let mut r = box_wing_file();
            r["thumbnails"] =
                serde_json::json!({ "size": 1024, "epochs": [0, 1, 2, 3], "samples": 8 });
            r.to_string()
        },
        &Limits::unlimited()
    )
    .is_ok());
}

#[test]
fn cli_writes_one_png_per_frame() {
    let dir = std::env::temp_dir().join(format!("glint-thumbnails-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let request = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/box-wing.json");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["simulate", request, "--quiet", "--thumbnails"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // no `thumbnails` in the request: the default, about eight 128-px frames
    let expected = Thumbnails::default_for(341).epochs;
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        expected
            .iter()
            .map(|i| format!("epoch-{i:05}.png"))
            .collect::<Vec<_>>()
    );
    let img = image::open(dir.join(&names[1])).unwrap();
    assert_eq!((img.width(), img.height()), (128, 128));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn views_along_the_body_axes_see_the_object() {
    // Directions with zero components (−0.0 once negated) must not lose hits: the
    // box-wing seen and lit along body axes, against the light curve. (The second
    // view is tilted 0.6° below the horizon: exactly level, the dish's far inner half
    // sits exactly behind its near rim, a tie the two methods break differently.)
    let mut req = box_wing_file();
    req["epochs"] = serde_json::json!([
        { "t": 0.0, "sun": [1.0, 0.0, 0.0], "observer": [R, 0.0, 0.0] },
        { "t": 1.0, "sun": [0.0, -0.6, 0.8], "observer": [0.0, -R, -0.01 * R] },
        { "t": 2.0, "sun": [-0.0, 0.6, 0.8], "observer": [0.0, 0.0, R] }
    ]);
    req["illumination"] = serde_json::json!({ "earthshine": "off" });
    req["tolerance"] = serde_json::json!(1e-6);
    let scene = Scene::from_json(&req.to_string(), &Limits::unlimited()).unwrap();
    let lc = simulate(&scene);
    let renderer = Renderer::new(&scene);
    for (i, epoch) in scene.epochs.iter().enumerate() {
        let e = lc.epochs[i].irradiance_w_m2;
        let img = renderer.render(epoch, 128, 3);
        let d = (img.irradiance_w_m2() - e).abs() / e;
        // 4σ of the image, plus 1e-4 for the light curve (tolerance 1e-6) and f32 ties
        // where rays graze the axis-aligned faces
        assert!(
            d <= 4.0 * img.std_error_w_m2() / e + 1e-4,
            "epoch {i}: {} vs {e}",
            img.irradiance_w_m2()
        );
    }
}

#[test]
fn rendering_stops_when_cancelled() {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let scene = plate_scene([0.0, 0.0, 1.0], [0.1, 0.2, 1.0], serde_json::json!({}));
    let r = Renderer::new(&scene);
    let epoch = &scene.epochs[0];
    assert!(r.render_until(epoch, 64, 1, &|| true).is_none());
    // cancelled after a few rows: the partial image is not returned
    let checks = AtomicUsize::new(0);
    let late = || checks.fetch_add(1, Ordering::Relaxed) >= 4;
    assert!(r.render_until(epoch, 64, 1, &late).is_none());
    assert!(r.render_until(epoch, 64, 1, &|| false).is_some());
}
