//! Fitting (issue 23) against truths the fit did not produce: samples drawn from known
//! parameters (the forward models are tested on their own elsewhere) with seeded noise of
//! a known distribution, the paper's §5.1 materials, and a light curve simulated with a
//! known albedo and yaw. Each tolerance says why it is what it is.

use glint::brdf::{Brdf, SeedMicrofacet};
use glint::fit::brdf::{self, evaluate_at, Model, Options, Sample, Space};
use glint::fit::solve::Loss;
use std::collections::BTreeMap;

/// A seeded generator: splitmix64 → uniform [0, 1), and standard normals by Box–Muller.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let u1 = self.uniform().max(1e-300);
        let u2 = self.uniform();
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    }
}

/// The paper's measurement geometry (Fig. 2): incidence 10°, 30°, 45°, 60°; in the plane
/// of incidence every 5° on both sides, densely (0.25°) within 3° of the mirror direction,
/// and a few points off the plane.
fn geometry() -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for ti in [10.0, 30.0, 45.0, 60.0] {
        for i in 0..=17 {
            let tr = 5.0 * i as f64;
            out.push((ti, tr, 180.0));
            if i % 2 == 0 {
                out.push((ti, tr, 0.0));
            }
        }
        for j in -12..=12 {
            let tr: f64 = ti + 0.25 * j as f64;
            if tr != ti && (0.0..89.0).contains(&tr) {
                out.push((ti, tr, 180.0));
            }
        }
        for phi in [150.0, 170.0, 175.0, 178.0, 179.0] {
            out.push((ti, ti, phi));
        }
    }
    out
}

/// Samples of `brdf` at `geometry()` with multiplicative log-normal noise of `sigma`
/// (f·e^{σ·N(0,1)}): a goniometer's relative error, and exactly Gaussian in the log
/// residuals the fit uses, so the 1σ coverage has a known target.
fn samples(brdf: &Brdf, sigma: f64, rng: &mut Rng) -> Vec<Sample> {
    geometry()
        .into_iter()
        .map(|(ti, tr, phi)| Sample {
            theta_i_deg: ti,
            theta_r_deg: tr,
            phi_deg: phi,
            brdf_sr: evaluate_at(brdf, ti, tr, phi) * (sigma * rng.normal()).exp(),
            weight: None,
            wavelength_um: None,
        })
        .collect()
}

fn options(model: Model, fixed: &[(&str, f64)], loss: Loss) -> Options {
    Options {
        model,
        fixed: fixed.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        loss,
        space: Space::Log,
    }
}

#[test]
fn the_specular_peak_is_at_theta_r_equal_theta_i_and_phi_180() {
    // The convention's own truth: a mirror reflects into θr = θi on the forward side
    // (φ = 180°). Scanned on a 0.5° / 5° grid, the largest value of a narrow lobe (a few
    // tenths of a degree, so the 1/cosθr of f cannot move its peak by a grid step) must
    // sit exactly there, for every model with a lobe.
    let models = [
        Model::SeedMicrofacet.build(&[0.1, 0.5, 0.005, 0.18, 3.6]),
        Model::RoughConductor.build(&[0.005, 0.2, 3.0, 0.1]),
        Model::AshikhminShirley.build(&[0.2, 0.3, 1e5]),
    ];
    for brdf in &models {
        for ti in [10.0, 30.0, 45.0, 60.0] {
            let mut best = (0.0, 0.0, f64::NEG_INFINITY);
            for i in 0..178 {
                let tr = 0.5 * i as f64;
                for j in 0..72 {
                    let phi = 5.0 * j as f64;
                    let f = evaluate_at(brdf, ti, tr, phi);
                    if f > best.2 {
                        best = (tr, phi, f);
                    }
                }
            }
            assert_eq!(
                (best.0, best.1),
                (ti, 180.0),
                "{} at θi {ti}",
                brdf.model_name()
            );
            // and the backward side at the same angle is far below it
            assert!(evaluate_at(brdf, ti, ti, 0.0) < 0.1 * best.2);
        }
    }
}

#[test]
fn synthetic_seed_samples_give_back_their_parameters_within_3_sigma() {
    // kd 0.2, km 0.3, δ 0.1 and an index of 1.5 + 0.5i, 5 % log-normal noise. The fit
    // must land within 3σ of the truth for each parameter (a 0.3 % chance per parameter
    // for a correct σ) and σ must be small enough to mean something (< 20 % of the value).
    let truth = [0.2, 0.3, 0.1, 1.5, 0.5];
    let brdf = Model::SeedMicrofacet.build(&truth);
    let mut rng = Rng(7);
    let data = samples(&brdf, 0.05, &mut rng);
    let fit = brdf::fit(
        &data,
        &options(
            Model::SeedMicrofacet,
            &[("n", 1.5), ("k", 0.5)],
            Loss::Huber,
        ),
    )
    .unwrap();
    for (name, &t) in ["kd", "km", "slope_rms"].iter().zip(&truth) {
        let v = fit.parameters[*name];
        let s = fit.uncertainty[*name].expect("determined");
        assert!((v - t).abs() < 3.0 * s, "{name}: {v} ± {s} against {t}");
        assert!(s < 0.2 * t, "{name}: σ {s} of {t}");
    }
    assert!(fit.solver.converged, "{:?}", fit.solver);
    // the residual scatter is the noise put in (log space: 0.05), within 20 %
    assert!((fit.residual_sd - 0.05).abs() < 0.01, "{}", fit.residual_sd);
    println!("recovered: {:?} ± {:?}", fit.parameters, fit.uncertainty);
}

#[test]
fn one_sigma_intervals_cover_the_truth_68_percent_of_the_time() {
    // Over N = 200 seeded trials of the fit above (kd, km, δ free; 3 parameters a trial),
    // the share of true values inside the reported ±1σ must be 68.3 %. The 3N intervals are
    // correlated within a trial, so the tolerance counts N effective draws: the binomial
    // standard deviation of the share is √(0.683·0.317/N) = 3.3 %, and the test allows 3 of
    // them (58–78 %). 200 trials take ~4 s at the test profile's opt-level 1 (plain least
    // squares: the covariance s²(JᵀJ)⁻¹ is exact for it; GLINT_FIT_TRIALS sets N).
    let trials: usize = std::env::var("GLINT_FIT_TRIALS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(200);
    let truth = [0.2, 0.3, 0.1, 1.5, 0.5];
    let brdf = Model::SeedMicrofacet.build(&truth);
    let mut rng = Rng(2026);
    let (mut inside, mut total) = (0usize, 0usize);
    let mut per = BTreeMap::new();
    for _ in 0..trials {
        let data = samples(&brdf, 0.05, &mut rng);
        let fit = brdf::fit(
            &data,
            &options(Model::SeedMicrofacet, &[("n", 1.5), ("k", 0.5)], Loss::L2),
        )
        .unwrap();
        for (name, &t) in ["kd", "km", "slope_rms"].iter().zip(&truth) {
            let s = fit.uncertainty[*name].expect("determined");
            let hit = (fit.parameters[*name] - t).abs() <= s;
            inside += usize::from(hit);
            total += 1;
            *per.entry(*name).or_insert(0usize) += usize::from(hit);
        }
    }
    let share = inside as f64 / total as f64;
    let sd = (0.683 * 0.317 / trials as f64).sqrt();
    println!("coverage {share:.3} over {trials} trials ({per:?}), binomial sd {sd:.3}");
    assert!(
        (share - 0.683).abs() < 3.0 * sd,
        "coverage {share} ({per:?})"
    );
}

fn round_trip(truth: [f64; 5]) {
    // Noise-free samples at the paper's four incidences (its Fig. 2 geometry) must be
    // reproduced and the parameters given back. With all five free the index (n, k)
    // enters only through F(β), which changes by a few per cent over the angles sampled:
    // what the samples fix is k^D, δ and k^M·F — and they are held to that: k^D and δ to
    // 1e-3 relative, k^M·F(0) to 1e-2, the samples to 0.1 % RMS. (For the white paint
    // a dielectric n ≈ 3.9, k = 0 with k^M ≈ 0.51 reproduces the samples within 0.02 %:
    // the index is not identifiable from such data, which is why `fixed` exists.)
    let brdf = Model::SeedMicrofacet.build(&truth);
    let data = samples(&brdf, 0.0, &mut Rng(1));
    let fit = brdf::fit(&data, &options(Model::SeedMicrofacet, &[], Loss::Huber)).unwrap();
    let p = &fit.parameters;
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    println!("round trip {truth:?}: {p:?}, rms_log {:?}", fit.rms_log);
    assert!(rel(p["kd"], truth[0]) < 1e-3, "{p:?}");
    assert!(rel(p["slope_rms"], truth[2]) < 1e-3, "{p:?}");
    let f0 = |n: f64, k: f64| glint::brdf::fresnel::normal_incidence(n, k);
    assert!(
        rel(
            p["km"] * f0(p["n"], p["k"]),
            truth[1] * f0(truth[3], truth[4])
        ) < 1e-2,
        "{p:?}"
    );
    assert!(fit.rms_log.unwrap() < 1e-3, "{:?}", fit.rms_log);
    // with the index given, the three others to 1e-4
    let fixed = brdf::fit(
        &data,
        &options(
            Model::SeedMicrofacet,
            &[("n", truth[3]), ("k", truth[4])],
            Loss::L2,
        ),
    )
    .unwrap();
    for (name, t) in [("kd", truth[0]), ("km", truth[1]), ("slope_rms", truth[2])] {
        assert!(
            rel(fixed.parameters[name], t) < 1e-4,
            "{name}: {:?}",
            fixed.parameters
        );
    }
}

#[test]
fn the_papers_body_wrap_round_trips() {
    // §5.1: k^D 0.1, k^M 0.5, δ ("C_r") 0.01, n 0.18 + 3.60i
    round_trip([0.1, 0.5, 0.01, 0.18, 3.60]);
}

#[test]
fn the_papers_white_paint_round_trips() {
    // §5.1: k^D 0.1, k^M 0.2, δ 0.007, n 0.20 + 2.50i
    round_trip([0.1, 0.2, 0.007, 0.20, 2.50]);
}

#[test]
fn the_preset_equals_the_model_built_from_its_numbers() {
    // the round trips above are of the presets' materials
    let preset = (glint::scene::presets::find("seed-white-paint")
        .unwrap()
        .brdf)();
    assert_eq!(
        preset,
        Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.2, 0.007, 0.2, 2.5))
    );
}

#[test]
fn a_robust_loss_shrugs_off_outliers_that_pull_least_squares_away() {
    // 5 % of the samples multiplied by 20 (a detector glint): Huber and Cauchy must still
    // find the truth within 3σ and flag the outliers; plain least squares on the same data
    // must do visibly worse (else the test shows nothing).
    let truth = [0.2, 0.3, 0.1, 1.5, 0.5];
    let brdf = Model::SeedMicrofacet.build(&truth);
    let mut rng = Rng(99);
    let mut data = samples(&brdf, 0.05, &mut rng);
    for s in data.iter_mut().step_by(20) {
        s.brdf_sr *= 20.0;
    }
    let fixed = [("n", 1.5), ("k", 0.5)];
    let robust = brdf::fit(&data, &options(Model::SeedMicrofacet, &fixed, Loss::Huber)).unwrap();
    let cauchy = brdf::fit(&data, &options(Model::SeedMicrofacet, &fixed, Loss::Cauchy)).unwrap();
    let plain = brdf::fit(&data, &options(Model::SeedMicrofacet, &fixed, Loss::L2)).unwrap();
    for fit in [&robust, &cauchy] {
        let (v, s) = (fit.parameters["kd"], fit.uncertainty["kd"].unwrap());
        assert!(
            (v - 0.2).abs() < 3.0 * s,
            "{}: kd {v} ± {s}",
            fit.solver.loss
        );
        assert!(fit.outliers >= data.len() / 20, "{}", fit.outliers);
    }
    // least squares is pulled further from the truth and, its residuals inflated by the
    // outliers, reports a wider interval
    let err = |f: &brdf::BrdfFit| (f.parameters["kd"] - 0.2).abs();
    let sd = |f: &brdf::BrdfFit| f.uncertainty["kd"].unwrap();
    println!(
        "kd: huber {} ± {}, cauchy {} ± {}, l2 {} ± {}",
        robust.parameters["kd"],
        sd(&robust),
        cauchy.parameters["kd"],
        sd(&cauchy),
        plain.parameters["kd"],
        sd(&plain)
    );
    assert!(err(&plain) > 2.0 * err(&robust) && sd(&plain) > 2.0 * sd(&robust));
}

#[test]
fn every_model_fits_its_own_samples() {
    // Each model's noise-free samples come back to 1e-3 relative (indices held, as the
    // samples barely determine them): lambert, rough-conductor, ashikhmin-shirley.
    type Case = (Model, Vec<f64>, Vec<(&'static str, f64)>);
    let cases: [Case; 3] = [
        (Model::Lambert, vec![0.35], vec![]),
        (
            Model::RoughConductor,
            vec![0.15, 0.2, 3.0, 0.05],
            vec![("n", 0.2), ("k", 3.0)],
        ),
        (Model::AshikhminShirley, vec![0.3, 0.1, 800.0], vec![]),
    ];
    for (model, truth, fixed) in cases {
        let data = samples(&model.build(&truth), 0.0, &mut Rng(3));
        let fit = brdf::fit(&data, &options(model, &fixed, Loss::Huber)).unwrap();
        for (spec, &t) in model.params().iter().zip(&truth) {
            let v = fit.parameters[spec.name];
            assert!(
                (v - t).abs() <= 1e-3 * t.abs(),
                "{}: {} = {v}, truth {t}",
                model.name(),
                spec.name
            );
        }
    }
}

#[test]
fn bad_samples_and_options_are_named() {
    let good = samples(&Model::Lambert.build(&[0.3]), 0.0, &mut Rng(5));
    let opts = options(Model::SeedMicrofacet, &[], Loss::Huber);
    // too few samples for five parameters
    let e = brdf::fit(&good[..5], &opts).unwrap_err();
    assert_eq!(e.field, "samples");
    assert!(e.message.contains("too few samples: 5 for 5"), "{e}");
    // a NaN, an angle out of range, a weight of 0
    for (i, edit, field) in [
        (
            3,
            (|s: &mut Sample| s.brdf_sr = f64::NAN) as fn(&mut Sample),
            "samples[3].brdf_sr",
        ),
        (
            4,
            |s: &mut Sample| s.theta_i_deg = 90.0,
            "samples[4].theta_i_deg",
        ),
        (
            5,
            |s: &mut Sample| s.theta_r_deg = -1.0,
            "samples[5].theta_r_deg",
        ),
        (6, |s: &mut Sample| s.phi_deg = 400.0, "samples[6].phi_deg"),
        (
            7,
            |s: &mut Sample| s.weight = Some(0.0),
            "samples[7].weight",
        ),
    ] {
        let mut bad = good.clone();
        edit(&mut bad[i]);
        let e = brdf::fit(&bad, &opts).unwrap_err();
        assert_eq!(e.field, field, "{e}");
    }
    // a fixed parameter the model does not have, or out of its bounds
    let e = brdf::fit(&good, &options(Model::Lambert, &[("kd", 0.1)], Loss::L2)).unwrap_err();
    assert_eq!(e.field, "fixed.kd");
    assert!(
        e.message.contains("not a parameter of model `lambert`"),
        "{e}"
    );
    let e = brdf::fit(
        &good,
        &options(Model::SeedMicrofacet, &[("kd", 1.5)], Loss::L2),
    )
    .unwrap_err();
    assert_eq!(e.field, "fixed.kd");
    // CSV: the line and the column are named
    let csv = "theta_i_deg,theta_r_deg,phi_deg,brdf_sr\n10,10,180,0.5\n10,95,180,0.5\n";
    let e = brdf::parse_csv(csv).unwrap_err();
    assert_eq!(e.field, "samples[1].theta_r_deg");
    assert!(e.message.contains("line 3"), "{e}");
    let e =
        brdf::parse_csv("theta_i_deg,theta_r_deg,phi_deg,brdf_sr\n10,10,180,NaN\n").unwrap_err();
    assert_eq!(e.field, "samples[0].brdf_sr");
    assert!(e.message.contains("finite"), "{e}");
    let e = brdf::parse_csv("theta_i_deg,theta_r,phi_deg,brdf_sr\n").unwrap_err();
    assert_eq!(e.field, "header.theta_r");
    let e = brdf::parse_csv("theta_i_deg,phi_deg,brdf_sr\n").unwrap_err();
    assert_eq!(e.field, "header.theta_r_deg");
}

/// The BRDF a request's material (JSON) builds, through the request's own validation: a
/// path the fit does not take to build it.
fn request_material(mut material: serde_json::Value) -> Brdf {
    material["name"] = serde_json::json!("surface"); // the plate's one material
    let request = serde_json::json!({
        "object": { "mesh": { "builtin": "plate" }, "materials": [material] },
        "epochs": [{ "t": 0.0, "sun": [0.0, 0.0, 1.0], "observer": [0.0, 0.0, 1.0e6] }]
    });
    let mut scene = glint::Scene::from_json(&request.to_string(), &glint::Limits::unlimited())
        .expect("a valid material");
    scene.materials.swap_remove(0).brdf
}

#[test]
fn the_normalised_seed_form_is_fitted_within_kd_plus_km_at_most_1() {
    // In the normalised form km is the lobe's albedo at normal incidence, so kd + km is
    // the material's, and energy conservation bounds it by 1 (docs/physics.md §6.6). The
    // truths are request materials with `"normalised": true`; their albedo at normal
    // incidence is first checked to be kd + km (to the albedo rule's 1e-3), so the bound
    // is the physical one. n and k are held (not identifiable from in-plane samples).
    let fixed = [("n", 0.2), ("k", 2.5)];
    let opts = |loss| options(Model::SeedNormalised, &fixed, loss);
    for (kd, km, delta, noise, seed) in [(0.3, 0.5, 0.05, 0.03, 3u64), (0.35, 0.65, 0.02, 0.05, 4)]
    {
        let truth = request_material(serde_json::json!({
            "name": "m", "model": "seed-microfacet", "normalised": true,
            "kd": kd, "km": km, "slope_rms": delta, "n": 0.2, "k": 2.5
        }));
        let albedo = glint::brdf::albedo::directional(&truth, 0.0, 0.0);
        assert!((albedo - (kd + km)).abs() < 1e-3, "albedo {albedo}");
        let data = samples(&truth, noise, &mut Rng(seed));
        let fit = brdf::fit(&data, &opts(Loss::Huber)).unwrap();
        let p = &fit.parameters;
        let s = |n: &str| fit.uncertainty[n].unwrap();
        println!(
            "normalised kd {kd}, km {km}: kd {:.4} ± {:.4}, km {:.4} ± {:.4}, δ {:.5} ± {:.5}, \
             kd + km {:.6}, at_bound {:?}",
            p["kd"],
            s("kd"),
            p["km"],
            s("km"),
            p["slope_rms"],
            s("slope_rms"),
            p["kd"] + p["km"],
            fit.at_bound
        );
        // never above the bound (to rounding), and the truth within 3σ
        assert!(p["kd"] + p["km"] <= 1.0 + 1e-12, "{p:?}");
        for (name, t) in [("kd", kd), ("km", km), ("slope_rms", delta)] {
            assert!(
                (p[name] - t).abs() < 3.0 * s(name),
                "{name}: {} ± {}",
                p[name],
                s(name)
            );
        }
        assert!(fit.normalised && fit.material["normalised"] == true);
        // the material it hands back builds, in a request, the BRDF it fitted
        let pasted = request_material(fit.material.clone());
        let fitted = fit.brdf().unwrap();
        for (ti, tr, phi) in [(10.0, 10.0, 180.0), (30.0, 31.0, 180.0), (60.0, 20.0, 0.0)] {
            let (a, b) = (
                evaluate_at(&pasted, ti, tr, phi),
                evaluate_at(&fitted, ti, tr, phi),
            );
            assert!(
                (a - b).abs() <= 1e-12 * a.abs().max(1e-300),
                "{a} against {b}"
            );
        }
    }
    // the bound with one of the two fixed: km ≤ 1 − kd
    let truth = request_material(serde_json::json!({
        "name": "m", "model": "seed-microfacet", "normalised": true,
        "kd": 0.4, "km": 0.6, "slope_rms": 0.03, "n": 0.2, "k": 2.5
    }));
    let data = samples(&truth, 0.05, &mut Rng(9));
    let one = brdf::fit(
        &data,
        &options(
            Model::SeedNormalised,
            &[("n", 0.2), ("k", 2.5), ("kd", 0.4)],
            Loss::Huber,
        ),
    )
    .unwrap();
    assert!(one.parameters["km"] <= 0.6 + 1e-12, "{:?}", one.parameters);
}

#[test]
fn the_normalised_form_is_named_where_it_does_not_apply() {
    let data = samples(&Model::Lambert.build(&[0.4]), 0.03, &mut Rng(2));
    let req = |model: &str, fixed: serde_json::Value| -> brdf::BrdfFitRequest {
        serde_json::from_value(serde_json::json!({
            "model": model, "samples": [], "normalised": true, "fixed": fixed
        }))
        .unwrap()
    };
    let e = brdf::Options::from_request(&req("lambert", serde_json::json!({}))).unwrap_err();
    assert_eq!(e.field, "normalised");
    let opts = brdf::Options::from_request(&req(
        "seed-microfacet",
        serde_json::json!({"kd": 0.6, "km": 0.5}),
    ))
    .unwrap();
    let e = brdf::fit(&data, &opts).unwrap_err();
    assert_eq!(e.field, "fixed", "{e}");
    assert!(e.message.contains("kd + km"), "{e}");
}

mod lightcurve {
    use super::Rng;
    use glint::fit::lightcurve::{self, Observation, Options};
    use glint::fit::solve::Loss;
    use glint::scene::validate::parse_request;
    use glint::Request;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// The tumbling box-wing of scenes/box-wing-tumbling.json (GEO, every epoch its own
    /// attitude), every 6th epoch (44), with smooth materials: a Lambert panel whose albedo is fitted, a
    /// glossy bus (δ 0.2, so no glint narrower than the epoch spacing) and a white dish.
    fn request() -> Request {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scenes/box-wing-tumbling.json"
        ))
        .unwrap();
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        let epochs: Vec<serde_json::Value> = v["epochs"]
            .as_array()
            .unwrap()
            .iter()
            .step_by(6)
            .cloned()
            .collect();
        v["epochs"] = serde_json::Value::Array(epochs);
        v["object"]["materials"] = serde_json::json!([
            { "name": "body", "model": "seed-microfacet", "kd": 0.2, "km": 0.05, "slope_rms": 0.2, "n": 1.5, "k": 0.0 },
            { "name": "panel", "model": "lambert", "albedo": 0.25, "two_sided": true },
            { "name": "dish", "model": "lambert", "albedo": 0.6, "two_sided": true }
        ]);
        parse_request(&v.to_string()).unwrap()
    }

    /// The request simulated with the panel albedo and yaw given (the yaw as attitude
    /// quaternions about z: the definition the fit must match), magnitudes noised at
    /// `sigma` mag.
    fn observe(albedo: f64, yaw_deg: f64, sigma: f64, seed: u64) -> (Request, Vec<Observation>) {
        let req = request();
        let mut truth: serde_json::Value = serde_json::to_value(&req).unwrap();
        truth["object"]["materials"][1]["albedo"] = serde_json::json!(albedo);
        // attitude · R_z(ψ), composed here by hand (Hamilton product, [w, x, y, z])
        let (c, s) = (
            (yaw_deg.to_radians() / 2.0).cos(),
            (yaw_deg.to_radians() / 2.0).sin(),
        );
        for e in truth["epochs"].as_array_mut().unwrap() {
            let q: Vec<f64> = e["attitude"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let (w, x, y, z) = (q[0], q[1], q[2], q[3]);
            // (w, x, y, z)·(c, 0, 0, s)
            e["attitude"] =
                serde_json::json!([w * c - z * s, x * c + y * s, y * c - x * s, z * c + w * s]);
        }
        let scene =
            glint::Scene::from_json(&truth.to_string(), &glint::Limits::unlimited()).unwrap();
        let response = glint::simulate(&scene);
        let mut rng = Rng(seed);
        let observed = response
            .epochs
            .iter()
            .filter_map(|e| {
                e.magnitude.map(|m| Observation {
                    t: e.t,
                    magnitude: m + sigma * rng.normal(),
                    sigma,
                })
            })
            .collect();
        (req, observed)
    }

    #[test]
    fn albedo_and_yaw_come_back_within_3_sigma_from_starts_50_percent_away() {
        // truth: panel albedo 0.25, yaw 12°; 0.02 mag noise. From (0.375, 6°) and
        // (0.125, 18°) the fit must end within 3σ of both (3σ: a 0.3 % chance each for a
        // correct σ), with χ²/dof near 1 (its sd for 42 dof is 0.22: within 0.35–1.65).
        let (req, observed) = observe(0.25, 12.0, 0.02, 11);
        let free = vec![
            "materials.panel.albedo".to_string(),
            lightcurve::YAW.to_string(),
        ];
        for (albedo0, yaw0) in [(0.375, 6.0), (0.125, 18.0)] {
            // one start: what this test shows is the solve from a start this far off
            let opts = Options {
                free: free.clone(),
                start: [(free[0].clone(), albedo0), (free[1].clone(), yaw0)]
                    .into_iter()
                    .collect(),
                loss: Loss::L2,
                yaw_starts: 1,
                ..Options::default()
            };
            let fit = lightcurve::fit(&req, &observed, &opts).unwrap();
            let (a, sa) = (fit.parameters[&free[0]], fit.uncertainty[&free[0]].unwrap());
            let (y, sy) = (fit.parameters[&free[1]], fit.uncertainty[&free[1]].unwrap());
            println!(
                "start ({albedo0}, {yaw0}°): albedo {a:.4} ± {sa:.4}, yaw {y:.3}° ± {sy:.3}°, chi2/dof {:.3}, \
                 {} light curves in {:.2} s",
                fit.chi2_dof, fit.solver.evaluations, fit.solver.wall_time_s
            );
            assert!((a - 0.25).abs() < 3.0 * sa, "albedo {a} ± {sa}");
            assert!((y - 12.0).abs() < 3.0 * sy, "yaw {y} ± {sy}");
            assert!(sa < 0.05 && sy < 5.0, "σ {sa} {sy}");
            assert!((0.35..1.65).contains(&fit.chi2_dof), "{}", fit.chi2_dof);
            // the fitted request reproduces the fitted curve
            let again: Request = serde_json::from_value(fit.request.clone()).unwrap();
            let scene = glint::Scene::from_request(&again, &glint::Limits::unlimited()).unwrap();
            let response = glint::simulate(&scene);
            for c in &fit.curve {
                let e = response.epochs.iter().find(|e| e.t == c.t).unwrap();
                let (m, f) = (e.magnitude.unwrap(), c.fitted.unwrap());
                assert!((m - f).abs() < 1e-9, "t {}: {m} against {f}", c.t);
            }
        }
    }

    /// The yaw's distance from `truth` (degrees) modulo a half-turn: the box-wing (bus,
    /// panels along ±y, dish on the z axis) looks the same after 180° about z, so ψ and
    /// ψ + 180° give the very same light curve.
    fn yaw_off(yaw: f64, truth: f64) -> f64 {
        let d = (yaw - truth).rem_euclid(180.0);
        d.min(180.0 - d)
    }

    #[test]
    fn a_start_in_a_wrong_yaw_basin_is_escaped_by_several_starts() {
        // χ²(ψ) of this curve (truth: albedo 0.25, yaw 12°), scanned every 5° with the
        // release binary before this test was written, has a local minimum near 125°
        // (χ²/dof ≈ 4300) in a basin from ~100° to ~133°, beside the true minima at 12°
        // and 192°. From 120° one solve stays in that basin (χ²/dof far above 1: asserted
        // > 100, so the trap is real); twelve screened yaws, three solved, find the truth
        // within 3σ (modulo 180°, see `yaw_off`) with χ²/dof within 0.35–1.65 (its sd
        // for 42 dof is 0.22).
        let (req, observed) = observe(0.25, 12.0, 0.02, 17);
        let free = vec![
            "materials.panel.albedo".to_string(),
            lightcurve::YAW.to_string(),
        ];
        let opts = |yaw_starts: usize| Options {
            free: free.clone(),
            start: [(free[0].clone(), 0.3), (free[1].clone(), 120.0)]
                .into_iter()
                .collect(),
            yaw_starts,
            ..Options::default()
        };
        let one = lightcurve::fit(&req, &observed, &opts(1)).unwrap();
        println!(
            "one start: yaw {:.2}°, chi2/dof {:.1}, {} light curves",
            one.parameters[&free[1]], one.chi2_dof, one.solver.evaluations
        );
        assert!(one.chi2_dof > 100.0, "{}", one.chi2_dof);
        assert!(yaw_off(one.parameters[&free[1]], 12.0) > 30.0);
        let many = lightcurve::fit(&req, &observed, &opts(12)).unwrap();
        let (a, sa) = (
            many.parameters[&free[0]],
            many.uncertainty[&free[0]].unwrap(),
        );
        let (y, sy) = (
            many.parameters[&free[1]],
            many.uncertainty[&free[1]].unwrap(),
        );
        println!(
            "12 starts: albedo {a:.4} ± {sa:.4}, yaw {y:.3}° ± {sy:.3}°, chi2/dof {:.3}, \
             {} solved, {} light curves in {:.2} s",
            many.chi2_dof, many.solver.starts, many.solver.evaluations, many.solver.wall_time_s
        );
        assert!((a - 0.25).abs() < 3.0 * sa, "albedo {a} ± {sa}");
        assert!(yaw_off(y, 12.0) < 3.0 * sy, "yaw {y} ± {sy}");
        assert!(
            (-180.0..=180.0).contains(&y),
            "reported in (−180°, 180°]: {y}"
        );
        assert!((0.35..1.65).contains(&many.chi2_dof), "{}", many.chi2_dof);
        assert_eq!(many.solver.starts, lightcurve::SOLVED_STARTS);
        assert_eq!(many.solver.start_rms.len(), lightcurve::SOLVED_STARTS);
    }

    #[test]
    fn a_fit_takes_no_more_light_curves_than_its_budget() {
        // A budget below what the fit needs: it stops at the budget exactly (counted by the
        // caller's own counter, not the report's), keeps the best point it evaluated
        // (no worse than its start), and says so; one too small to start is refused.
        let (req, observed) = observe(0.25, 12.0, 0.02, 5);
        let free = vec![
            "materials.panel.albedo".to_string(),
            lightcurve::YAW.to_string(),
        ];
        let opts = Options {
            free: free.clone(),
            start: [(free[0].clone(), 0.4), (free[1].clone(), 0.0)]
                .into_iter()
                .collect(),
            yaw_starts: 4,
            max_evaluations: 24,
            ..Options::default()
        };
        let scene = glint::Scene::from_request(&req, &glint::Limits::unlimited()).unwrap();
        let prepared = lightcurve::prepare(&req, scene, &observed, &opts).unwrap();
        let (progress, counted) = (glint::Progress::new(), AtomicUsize::new(0));
        let run = lightcurve::Run {
            engine: glint::simulate_with,
            progress: &progress,
            evaluations: &counted,
        };
        let fit = lightcurve::fit_with(&prepared, &run).unwrap();
        assert_eq!(counted.load(Ordering::Relaxed), 24);
        assert_eq!(fit.solver.evaluations, 24);
        assert!(!fit.solver.converged);
        assert!(
            fit.warnings.iter().any(|w| w.contains("budget of 24")),
            "{:?}",
            fit.warnings
        );
        // χ² at the start, from the curve simulated there without noise
        let (_, at_start) = observe(0.4, 0.0, 0.0, 1);
        // (epochs with no light at the start left out: they would only add to it)
        let chi2_start: f64 = observed
            .iter()
            .filter_map(|o| {
                let m = at_start.iter().find(|m| m.t == o.t)?;
                Some(((o.magnitude - m.magnitude) / o.sigma).powi(2))
            })
            .sum();
        assert!(fit.chi2 <= chi2_start, "{} against {chi2_start}", fit.chi2);
        let small = Options {
            max_evaluations: 10,
            ..opts.clone()
        };
        let e = lightcurve::fit(&req, &observed, &small).unwrap_err();
        assert_eq!(e.field, "max_evaluations", "{e}");
    }

    #[test]
    fn a_cancelled_fit_stops_within_a_light_curve() {
        let (req, observed) = observe(0.25, 12.0, 0.02, 3);
        let opts = Options {
            free: vec![lightcurve::YAW.to_string()],
            ..Options::default()
        };
        let scene = glint::Scene::from_request(&req, &glint::Limits::unlimited()).unwrap();
        let prepared = lightcurve::prepare(&req, scene, &observed, &opts).unwrap();
        let (progress, counted) = (glint::Progress::new(), AtomicUsize::new(0));
        let run = lightcurve::Run {
            engine: glint::simulate_with,
            progress: &progress,
            evaluations: &counted,
        };
        let got = std::thread::scope(|s| {
            s.spawn(|| {
                while counted.load(Ordering::Relaxed) < 3 {
                    std::thread::sleep(std::time::Duration::from_millis(1));
                }
                progress.cancel();
            });
            lightcurve::fit_with(&prepared, &run)
        });
        assert_eq!(got.unwrap_err(), lightcurve::FitError::Cancelled);
        // stopped at once: the light curve under way when the cancel came is the last
        assert!(counted.load(Ordering::Relaxed) <= 4);
    }

    #[test]
    fn bad_free_parameters_and_observations_are_named() {
        let (req, observed) = observe(0.25, 0.0, 0.02, 1);
        let run = |free: &[&str], obs: &[Observation]| {
            let opts = Options {
                free: free.iter().map(|s| s.to_string()).collect(),
                ..Options::default()
            };
            lightcurve::fit(&req, obs, &opts).unwrap_err()
        };
        let e = run(
            &["materials.panel.albedo", "materials.wing.albedo"],
            &observed,
        );
        assert_eq!(e.field, "free[1]");
        assert!(e.message.contains("no material named `wing`"), "{e}");
        let e = run(&["materials.panel.slope_rms"], &observed);
        assert_eq!(e.field, "free[0]");
        assert!(
            e.message.contains("not a parameter of material `panel`"),
            "{e}"
        );
        let e = run(&["attitude.roll_deg"], &observed);
        assert_eq!(e.field, "free[0]");
        let mut bad = observed.clone();
        bad[2].t += 1.0;
        let e = run(&["materials.panel.albedo"], &bad);
        assert_eq!(e.field, "observed[2].t");
        let mut bad = observed.clone();
        bad[4].magnitude = f64::NAN;
        let e = run(&["materials.panel.albedo"], &bad);
        assert_eq!(e.field, "observed[4].magnitude");
        let e = run(
            &["materials.panel.albedo", "attitude.yaw_deg"],
            &observed[..2],
        );
        assert_eq!(e.field, "observed");
        assert!(e.message.contains("too few observations"), "{e}");
    }
}
