//! Materials' directional-hemispherical albedo (docs/physics.md §6.5): reported in the
//! summary, warned about above 1, and the normalised seed model whose k^M is its lobe's
//! albedo. The truths are closed forms, not the code's quadrature.
use glint::brdf::albedo::{albedo, directional};
use glint::brdf::Brdf;
use glint::scene::{Limits, Request};
use std::f64::consts::PI;

fn preset(name: &str) -> Brdf {
    (glint::scene::presets::find(name).expect("preset").brdf)()
}

/// Normal-incidence Fresnel reflectance of the index n + ik, written out here.
fn f0(n: f64, k: f64) -> f64 {
    ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k)
}

#[test]
fn the_papers_materials_reflect_several_times_what_they_receive() {
    // a smooth lobe at normal incidence reflects 4π·k^M·F(0) (Eq. 8 with C/π a normalised
    // Beckmann distribution, V = 1, F ≈ F(0) over a lobe of slope ≤ 0.01), the diffuse
    // part k^D: body wrap 0.1 + 5.968, white paint 0.1 + 2.252. Tolerance 2e-3: the
    // lobe's O(δ²) spread of F and the rule's own 1e-3 (see the unit tests).
    for (name, kd, km, n, k) in [
        ("seed-body-wrap", 0.1, 0.5, 0.18, 3.60),
        ("seed-white-paint", 0.1, 0.2, 0.20, 2.50),
    ] {
        let a = albedo(&preset(name));
        let truth = kd + 4.0 * PI * km * f0(n, k);
        assert!(
            (a.normal / truth - 1.0).abs() < 2e-3,
            "{name}: {a:?} vs {truth}"
        );
        assert!(a.max >= a.normal && a.max > 1.0, "{name}: {a:?}");
    }
}

fn request(material: &str) -> glint::scene::Scene {
    let json = format!(
        r#"{{"object":{{"mesh":{{"builtin":"plate"}},"materials":[{material}]}},
            "epochs":[{{"t":0,"sun":[0,0,1],"observer":[0,0.1,1e6]}}],
            "illumination":{{"earthshine":"off"}}}}"#
    );
    let req: Request = serde_json::from_str(&json).expect("request");
    glint::scene::validate::validate(&req, &Limits::default()).expect("valid")
}

#[test]
fn the_summary_reports_albedo_and_warns_above_one() {
    let scene = request(r#"{"name":"surface","preset":"seed-body-wrap"}"#);
    let r = glint::simulate(&scene);
    let m = &r.summary.materials[0];
    assert_eq!(m.name, "surface");
    assert!(
        m.albedo_normal > 6.0 && m.albedo_max >= m.albedo_normal,
        "{m:?}"
    );
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
    assert!(r.warnings[0].contains("`surface`"), "{}", r.warnings[0]);

    // a Lambertian 0.6 reflects 0.6 at every incidence: no warning
    let scene = request(r#"{"name":"surface","model":"lambert","albedo":0.6}"#);
    let r = glint::simulate(&scene);
    let m = &r.summary.materials[0];
    assert!((m.albedo_normal - 0.6).abs() < 1e-12 && (m.albedo_max - 0.6).abs() < 1e-12);
    assert!(r.warnings.is_empty());
}

#[test]
fn normalised_km_is_the_lobes_albedo() {
    // with normalised: true, kd + km is the albedo at normal incidence, for narrow and
    // wide lobes and metals and dielectrics alike (to the rule's 1e-3)
    for (km, slope, n, k) in [
        (0.5, 0.01, 0.18, 3.6),
        (0.3, 0.3, 1.5, 0.0),
        (0.8, 1e-4, 0.2, 2.5),
    ] {
        let m = format!(
            r#"{{"name":"surface","model":"seed-microfacet","kd":0.1,"km":{km},
                "slope_rms":{slope},"n":{n},"k":{k},"normalised":true}}"#
        );
        let scene = request(&m);
        let a = directional(&scene.materials[0].brdf, 0.0, 0.0);
        assert!(
            (a - (0.1 + km)).abs() < 1e-3 * (0.1 + km),
            "{km} {slope}: {a}"
        );
        // a metal's Fresnel term is nearly flat, so it stays below 1 at every incidence;
        // a dielectric's rises ~10× towards grazing (0.04 → 0.4 for n = 1.5), and so does
        // its lobe's albedo: normalising at normal incidence cannot hold it there
        let r = glint::simulate(&scene);
        assert_eq!(
            r.warnings.is_empty(),
            k > 0.0,
            "{km} {slope}: {:?}",
            r.warnings
        );
    }
}

#[test]
fn normalised_is_refused_where_it_cannot_hold() {
    let bad = |m: &str, field: &str| {
        let json = format!(
            r#"{{"object":{{"mesh":{{"builtin":"plate"}},"materials":[{m}]}},
                "epochs":[{{"t":0,"sun":[0,0,1],"observer":[0,0.1,1e6]}}]}}"#
        );
        let req: Request = serde_json::from_str(&json).expect("request");
        let e = glint::scene::validate::validate(&req, &Limits::default()).expect_err("refused");
        assert_eq!(e.field, field, "{e:?}");
    };
    // an albedo above 1
    bad(
        r#"{"name":"s","model":"seed-microfacet","kd":0,"km":1.5,"slope_rms":0.1,"n":1.5,"normalised":true}"#,
        "object.materials[0].km",
    );
    // an index that reflects nothing: no k^M makes an albedo of it
    bad(
        r#"{"name":"s","model":"seed-microfacet","kd":0,"km":0.5,"slope_rms":0.1,"n":1,"k":0,"normalised":true}"#,
        "object.materials[0].n",
    );
    // not a parameter of another model
    bad(
        r#"{"name":"s","model":"lambert","albedo":0.5,"normalised":true}"#,
        "object.materials[0].normalised",
    );
}
