//! Helpers shared by the integration tests: scene builders and truths computed here,
//! independently of the engine (constants from PHYSICS.md, brute-force quadratures).
#![allow(dead_code)]

use glam::DVec3;
use glint::brdf::{Brdf, Frame, Lambert};
use glint::geometry::Mesh;
use glint::scene::{EarthshineModel, Epoch, Illumination, Material, Method};
use glint::{Limits, Response, Scene};

/// Sun's radius, m (PHYSICS.md §2, the paper's value).
pub const SUN_RADIUS: f64 = 6.9599e8;
/// Astronomical unit, m (PHYSICS.md §1).
pub const AU: f64 = 1.49597892e11;
/// Planck's constants as PHYSICS.md §2 gives them (W·µm⁴/m², µm·K).
pub const C1: f64 = 3.741844e8;
pub const C2: f64 = 14388.0;
/// Stefan–Boltzmann constant, W/(m²·K⁴).
pub const SIGMA: f64 = 5.670374e-8;
/// Earth's radius, m (PHYSICS.md §2).
pub const EARTH_RADIUS: f64 = 6.371e6;

/// Planck spectral exitance c1 λ⁻⁵ / (exp(c2/(λT)) − 1), W/(m²·µm).
pub fn planck(lambda_um: f64, t: f64) -> f64 {
    C1 / lambda_um.powi(5) / (C2 / (lambda_um * t)).exp_m1()
}

/// Brute-force composite Simpson quadrature of Planck's law over [l1, l2] µm with `n`
/// (even) intervals, W/m². Independent of the engine's series.
pub fn planck_band_simpson(l1: f64, l2: f64, t: f64, n: usize) -> f64 {
    assert!(n % 2 == 0);
    let h = (l2 - l1) / n as f64;
    let mut s = planck(l1, t) + planck(l2, t);
    for i in 1..n {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        s += w * planck(l1 + i as f64 * h, t);
    }
    s * h / 3.0
}

/// Band solar irradiance at `distance_m`, W/m²: (R_s/D)² ∫ Planck (PHYSICS.md Eq. 2), by
/// brute-force quadrature.
pub fn sun_irradiance(band: [f64; 2], t: f64, distance_m: f64) -> f64 {
    (SUN_RADIUS / distance_m).powi(2) * planck_band_simpson(band[0], band[1], t, 4000)
}

/// The default band's (0.4–0.7 µm, 5900 K) solar irradiance at 1 AU, W/m².
pub fn es_default() -> f64 {
    sun_irradiance([0.4, 0.7], 5900.0, AU)
}

/// Lambert material with albedo `a`.
pub fn lambert(name: &str, a: f64, two_sided: bool) -> Material {
    material(name, Brdf::Lambert(Lambert { albedo: a }), two_sided)
}

pub fn material(name: &str, brdf: Brdf, two_sided: bool) -> Material {
    Material {
        name: name.to_string(),
        brdf,
        two_sided,
        tangent: glam::DVec3::X,
    }
}

/// An epoch at 1 AU from the Sun, without the Earth.
pub fn epoch(sun: DVec3, observer: DVec3) -> Epoch {
    Epoch {
        t: 0.0,
        sun: sun.normalize(),
        sun_distance_m: AU,
        observer,
        earth: None,
    }
}

/// A scene with the given mesh, materials and epochs: default band and Sun, earthshine
/// off, tolerance 1e-3, method auto. Starts from a validated minimal request and replaces
/// fields, so it keeps compiling when `Scene` grows fields.
pub fn scene(mesh: Mesh, materials: Vec<Material>, epochs: Vec<Epoch>) -> Scene {
    let mut s = from_json(&serde_json::json!({
        "object": { "mesh": { "builtin": "plate" }, "materials": [ { "name": "surface", "model": "lambert", "albedo": 0.5 } ] },
        "epochs": [ { "t": 0, "sun": [0, 0, 1], "observer": [0, 0, 1e7] } ],
        "illumination": { "earthshine": "off" }
    }));
    s.mesh = mesh;
    s.materials = materials;
    s.epochs = epochs;
    s.illumination = Illumination {
        earthshine: EarthshineModel::Off,
        ..Illumination::default()
    };
    s.tolerance = 1e-3;
    s.method = Method::Auto;
    s
}

/// Parses and validates a request given as a JSON value; panics with the error.
pub fn from_json(v: &serde_json::Value) -> Scene {
    Scene::from_json(&v.to_string(), &Limits::unlimited())
        .unwrap_or_else(|e| panic!("request rejected: {e}"))
}

/// Unit vector at elevation `el` (rad) above the x-y plane and azimuth `az` (rad).
pub fn dir(el: f64, az: f64) -> DVec3 {
    DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin())
}

/// Asserts every number of every epoch is finite, the parts add up, and the magnitude is
/// `null` exactly when no light arrives.
pub fn assert_sane(r: &Response) {
    for (i, e) in r.epochs.iter().enumerate() {
        for (name, x) in [
            ("t", e.t),
            ("irradiance", e.irradiance_w_m2),
            ("sun", e.sun_w_m2),
            ("earthshine", e.earthshine_w_m2),
            ("intensity", e.intensity_w_sr),
            ("phase", e.phase_angle_deg),
            ("range", e.range_m),
            ("area", e.lit_visible_area_m2),
            ("eclipse", e.eclipse),
        ] {
            assert!(x.is_finite(), "epoch {i}: {name} = {x}");
        }
        assert!(
            e.irradiance_w_m2 >= 0.0 && e.sun_w_m2 >= 0.0 && e.earthshine_w_m2 >= 0.0,
            "epoch {i}: negative light {e:?}"
        );
        assert!(
            (0.0..=1.0).contains(&e.eclipse),
            "epoch {i}: eclipse {}",
            e.eclipse
        );
        assert!(
            (0.0..=180.0).contains(&e.phase_angle_deg),
            "epoch {i}: phase {}",
            e.phase_angle_deg
        );
        match e.magnitude {
            Some(m) => {
                assert!(
                    m.is_finite() && e.irradiance_w_m2 > 0.0,
                    "epoch {i}: magnitude {m} for {e:?}"
                );
                assert!(
                    e.magnitude_1000km.is_some_and(f64::is_finite),
                    "epoch {i}: {e:?}"
                );
            }
            None => assert!(
                e.irradiance_w_m2 == 0.0
                    && e.magnitude_1000km.is_none()
                    && e.magnitude_standard.is_none()
                    && e.magnitude_intrinsic.is_none(),
                "epoch {i}: null magnitude with light: {e:?}"
            ),
        }
    }
}

/// Relative difference |a − b| / |b|.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The brute-force disk average of a narrow lobe: (1/Ω)∫ `brdf.projected` over the part
/// of the Sun's disk (`sun`: its centre's direction l and angular radius ρ) that `hidden`
/// leaves, towards `v`,
/// on a gnomonic grid about the Sun's centre. The lobe is a Gaussian in the Sun's
/// direction of widths √2·δ in the Sun–observer plane and √2·δ·cos(g/2) across it, centred
/// on the face's mirror direction; the grid covers ±9 of them (clipped to the disk; the
/// lobe is e^−40 beyond) with `cells` cells a side, each cell's midpoint tested against
/// the disk's edge and `hidden`. Where no edge cuts the lobe, 100 cells (σ/5.5) are exact
/// to ~1e−9 (the midpoint rule on a Gaussian); across an edge the error is about a cell's
/// share of the lobe.
pub fn disk_truth(
    brdf: &Brdf,
    slope: f64,
    sun: (DVec3, f64),
    v: DVec3,
    frame: &Frame,
    cells: usize,
    hidden: impl Fn(DVec3) -> bool,
) -> f64 {
    let (l, rho) = sun;
    let e_out = l.cross(v).normalize();
    let e_in = e_out.cross(l);
    let t = rho.tan();
    let n = frame.n;
    let m = 2.0 * n.dot(v) * n - v;
    // the mirror direction's gnomonic offset from the Sun's centre
    let (mx, my) = (m.dot(e_in) / m.dot(l), m.dot(e_out) / m.dot(l));
    let cos_half = n.dot(v);
    let (sx, sy) = (2f64.sqrt() * slope, 2f64.sqrt() * slope * cos_half);
    let window = |c: f64, s: f64| ((c - 9.0 * s).max(-t), (c + 9.0 * s).min(t));
    let (x0, x1) = window(mx, sx);
    let (y0, y1) = window(my, sy);
    if x0 >= x1 || y0 >= y1 {
        return 0.0;
    }
    let (dx, dy) = ((x1 - x0) / cells as f64, (y1 - y0) / cells as f64);
    let mut sum = 0.0;
    for i in 0..cells {
        let x = x0 + (i as f64 + 0.5) * dx;
        for j in 0..cells {
            let y = y0 + (j as f64 + 0.5) * dy;
            let r2 = x * x + y * y;
            if r2 >= t * t {
                continue;
            }
            let d = (l + e_in * x + e_out * y).normalize();
            if hidden(d) {
                continue;
            }
            // the gnomonic cell's solid angle
            let w = dx * dy / (1.0 + r2).powf(1.5);
            sum += brdf.projected(frame, d, v) * w;
        }
    }
    sum / (2.0 * std::f64::consts::PI * (1.0 - rho.cos()))
}
