//! Identities of Eq. 12 (PHYSICS.md §5), as property tests: linearity in the BRDF,
//! E ∝ E_s, mesh scaling by s gives s², rotating everything changes nothing, 1/R².

mod common;

use common::*;
use glam::{DQuat, DVec3};
use glint::brdf::{AshikhminShirley, Brdf, RoughConductor, SeedMicrofacet};
use glint::geometry::builtin::{box_wing, icosphere, push_quad};
use glint::geometry::Mesh;
use glint::scene::{EarthshineModel, Epoch, Material};
use glint::Scene;
use proptest::prelude::*;

const GEO: f64 = 4.2164e7;

/// Box-wing materials: body, panel, dish (names as the built-in needs), lobes wide enough
/// (≥ 0.05) that the Sun's finite disk plays no part.
fn box_wing_materials(slope: f64) -> Vec<Material> {
    vec![
        material(
            "body",
            Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.5, slope, 0.18, 3.6)),
            false,
        ),
        Material {
            // anisotropic along a body direction far from every face's normal: the fixed
            // perpendicular a face near its axis takes does not turn with a rotation
            tangent: DVec3::new(0.6, 0.64, 0.48).normalize(),
            ..material(
                "panel",
                Brdf::AshikhminShirley(AshikhminShirley::new(0.3, 0.2, 50.0, 200.0)),
                true,
            )
        },
        material(
            "dish",
            Brdf::RoughConductor(RoughConductor::new(slope, 0.2, 2.5, 0.3)),
            true,
        ),
    ]
}

/// A concave mesh that shadows itself: a V-shaped trough (two 2 m × 1 m plates at 90°)
/// with an end wall, one-sided, normals into the valley.
fn trough() -> Mesh {
    let mut m = Mesh::default();
    let (a, b, c) = (
        DVec3::new(-1.0, 0.0, 1.0),
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 1.0),
    );
    let y = DVec3::new(0.0, 2.0, 0.0);
    push_quad(&mut m, [a, a + y, b + y, b], 0);
    push_quad(&mut m, [b, b + y, c + y, c], 0);
    // end wall at y = 0, facing +y (into the trough)
    let base = m.vertices.len() as u32;
    m.vertices.extend([a, b, c]);
    m.triangles.push([base, base + 2, base + 1]);
    m.material_ids.push(0);
    m
}

/// Sun/observer/Earth directions from proptest's unit-cube samples.
fn unit(v: [f64; 3]) -> DVec3 {
    let d = DVec3::from_array(v);
    if d.length_squared() < 1e-6 {
        DVec3::Z
    } else {
        d.normalize()
    }
}

fn one_epoch(sun: DVec3, obs: DVec3, earth: Option<DVec3>) -> Epoch {
    Epoch {
        earth,
        ..epoch(sun, obs * GEO)
    }
}

fn with_earthshine(mut s: Scene, model: EarthshineModel) -> Scene {
    s.illumination.earthshine = model;
    s
}

/// Ray–triangle intersection (Möller–Trumbore, f64, both sides): distance or None.
fn hit(o: DVec3, d: DVec3, t: [DVec3; 3]) -> Option<f64> {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-15 {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - t[0];
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let dist = e2.dot(q) * inv;
    (dist > 1e-9).then_some(dist)
}

/// Lit-and-seen area of a one-sided mesh by brute force: an n×n barycentric grid of
/// points on each triangle, each tested with f64 rays against every triangle.
fn lit_seen_area(mesh: &Mesh, s: DVec3, v: DVec3, n: usize) -> f64 {
    let tris: Vec<[DVec3; 3]> = (0..mesh.triangles.len()).map(|i| mesh.corners(i)).collect();
    let mut area = 0.0;
    for (i, t) in tris.iter().enumerate() {
        let av = (t[1] - t[0]).cross(t[2] - t[0]);
        let normal = av.normalize();
        if normal.dot(s) <= 0.0 || normal.dot(v) <= 0.0 {
            continue;
        }
        let mut count = 0usize;
        let mut total = 0usize;
        for a in 0..n {
            for b in 0..n - a {
                // centre of a small sub-triangle (upright ones only: uniform enough)
                let (u, w) = (
                    (a as f64 + 1.0 / 3.0) / n as f64,
                    (b as f64 + 1.0 / 3.0) / n as f64,
                );
                let p = t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * w;
                total += 1;
                let clear = |d: DVec3| {
                    tris.iter()
                        .enumerate()
                        .all(|(j, tj)| j == i || hit(p, d, *tj).is_none())
                };
                if clear(s) && clear(v) {
                    count += 1;
                }
            }
        }
        area += 0.5 * av.length() * count as f64 / total as f64;
    }
    area
}

/// A random rotation from four proptest numbers (a normalised quaternion).
fn rotation(q: [f64; 4]) -> DQuat {
    let q = DQuat::from_xyzw(q[0], q[1], q[2], q[3]);
    if q.length() < 1e-3 {
        DQuat::IDENTITY
    } else {
        q.normalize()
    }
}

fn irradiance(s: &Scene) -> f64 {
    let r = glint::simulate(s);
    assert_sane(&r);
    r.epochs[0].irradiance_w_m2
}

/// The signal with every face counted whole (no shadowing): the scale of the
/// visibility integration's error budget (`tolerance` is relative to it).
fn unshadowed(s: &Scene) -> f64 {
    let mut c = s.clone();
    c.method = glint::scene::Method::Convex;
    irradiance(&c)
}

/// The objects of these tests: the box-wing (self-shadowing, concave dish, two-sided
/// panels) with seed earthshine from an Earth at GEO distance, and the trough.
fn object(which: u8, slope: f64, sun: DVec3, obs: DVec3, earth: DVec3) -> Scene {
    let (mesh, mats) = match which {
        0 => (box_wing(), box_wing_materials(slope)),
        1 => (trough(), vec![box_wing_materials(slope)[0].clone()]),
        _ => (
            icosphere(2, 1.3),
            vec![box_wing_materials(slope)[2].clone()],
        ),
    };
    // keep the Earth out of the Sun's direction (the eclipse depends on the Sun's
    // angular size, hence its distance): at GEO the Earth's disk is 8.7° in radius
    let earth = if earth.dot(sun) > 0.9 { -earth } else { earth };
    with_earthshine(
        scene(mesh, mats, vec![one_epoch(sun, obs, Some(earth * GEO))]),
        EarthshineModel::Seed,
    )
}

fn dir3() -> impl Strategy<Value = DVec3> {
    [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64].prop_map(unit)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// E(f^D + f^M) = E(f^D) + E(f^M) (`Brdf::split`). Each run refines its own
    /// shadow boundaries to the tolerance of its own signal, so the sums agree within
    /// the visibility tolerance (3 × 1e-3 of the unshadowed signal); on a convex object
    /// (no rays) to rounding.
    #[test]
    fn linear_in_the_brdf(which in 0u8..3, slope in 0.05..0.5f64, sun in dir3(), obs in dir3(), earth in dir3()) {
        let both = object(which, slope, sun, obs, earth);
        let mut d = both.clone();
        d.materials.iter_mut().for_each(|m| m.brdf = m.brdf.split(true));
        let mut m = both.clone();
        m.materials.iter_mut().for_each(|x| x.brdf = x.brdf.split(false));
        let (eb, ed, em) = (irradiance(&both), irradiance(&d), irradiance(&m));
        let budget = if which == 2 { 1e-12 * eb } else { 3.0 * both.tolerance * unshadowed(&both) };
        prop_assert!((ed + em - eb).abs() <= budget + 1e-300, "{ed:e} + {em:e} vs {eb:e}");
    }

    /// E ∝ E_s: moving the Sun to `au` AU scales every term by 1/au² (lobes wide enough
    /// that the Sun's disk, which shrinks with distance, plays no part); the magnitude
    /// grows by 5 log10(au). Rounding only: nothing else depends on E_s. Rounding is
    /// relative to the object's signal scale (`signal_scale`) where the signal itself is
    /// a sliver (a shrunk case: the trough's lit wall hidden by the other but for an
    /// ulp, 2.3e-20 W/m², 1e-7 of the scale, moved by 6e-30 W/m²).
    #[test]
    fn proportional_to_solar_irradiance(which in 0u8..3, au in 0.2..40.0f64, sun in dir3(), obs in dir3(), earth in dir3()) {
        let base = object(which, 0.1, sun, obs, earth);
        let mut far = base.clone();
        far.epochs[0].sun_distance_m = au * AU;
        let (a, b) = (glint::simulate(&base).epochs[0], glint::simulate(&far).epochs[0]);
        // In the penumbra the hidden fraction depends on the Sun's angular size, which
        // changes with its distance: the identity holds outside it.
        prop_assume!((a.eclipse == 0.0 || a.eclipse == 1.0) && a.eclipse == b.eclipse);
        let budget = 1e-12 * (a.irradiance_w_m2 + signal_scale(&base));
        prop_assert!((b.irradiance_w_m2 * au * au - a.irradiance_w_m2).abs() <= budget, "{:e} × {au}² vs {:e}", b.irradiance_w_m2, a.irradiance_w_m2);
        prop_assert!((b.earthshine_w_m2 * au * au - a.earthshine_w_m2).abs() <= budget, "{:e} × {au}² vs {:e}", b.earthshine_w_m2, a.earthshine_w_m2);
        if let (Some(ma), Some(mb)) = (a.magnitude, b.magnitude) {
            prop_assert!((mb - ma - 5.0 * au.log10()).abs() < 1e-9);
        }
    }

    /// Range scaling: the observer k times farther in the same direction gives 1/k²
    /// (the same faces, the same visibility). Rounding, plus the clipper's geometric
    /// tolerance: scaling the observer moves its unit direction by an ulp, and where a
    /// shadow edge runs exactly along a face's edge (the shrunk cases put the Sun in the
    /// trough's plane) the clipper leaves a sliver whose area (~1e-9 m² on a 1 m² wall,
    /// its plane test being exact to 1e-9 of the object's radius) moves with that ulp.
    /// So the budget is 1e-12 of the signal plus 1e-8 of the unshadowed signal.
    #[test]
    fn inverse_square_of_range(which in 0u8..3, k in 1e-3..1e3f64, sun in dir3(), obs in dir3(), earth in dir3()) {
        let base = object(which, 0.1, sun, obs, earth);
        let mut far = base.clone();
        far.epochs[0].observer *= k;
        let (a, b) = (irradiance(&base), irradiance(&far));
        let budget = 1e-12 * a + 1e-8 * unshadowed(&base);
        prop_assert!((b * k * k - a).abs() <= budget, "{a:e} vs {b:e} at k = {k}");
    }

    /// Mesh scaling by s gives s², and rotating the mesh with every vector changes
    /// nothing, where no ray is needed (convex sphere; any object with method `convex`).
    /// Rounding only: 1e-12 of the signal, plus 1e-12 of the object's signal scale
    /// (`signal_scale`) for a face seen or lit edge-on, whose cosine is exactly 0
    /// before a rotation and ~1e-17 after it (CI's shrunk case: every face of the
    /// trough edge-on to the Sun or the observer, 0 W/m² against 7e-31 W/m²).
    #[test]
    fn scale_and_rotation_without_rays(which in 0u8..3, s in 0.01..100.0f64, q in [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64],
                                       sun in dir3(), obs in dir3(), earth in dir3()) {
        let mut base = object(which, 0.1, sun, obs, earth);
        base.method = glint::scene::Method::Convex;
        let e0 = irradiance(&base);
        let mut scaled = base.clone();
        scaled.mesh = scaled.mesh.transformed(|v| v * s);
        let floor = 1e-12 * signal_scale(&base);
        let es = irradiance(&scaled);
        prop_assert!((es - s * s * e0).abs() <= 1e-12 * s * s * e0 + s * s * floor, "{es:e} vs {e0:e} scaled by {s}");
        let q = rotation(q);
        let er = irradiance(&rotated(&base, q));
        prop_assert!((er - e0).abs() <= 1e-12 * e0 + floor, "{er:e} rotated vs {e0:e}");
    }
}

/// The order of an object's signal, W/m²: its whole area as a Lambertian disk of albedo
/// 1 facing Sun and observer (E_s A / (π R²)), the first epoch's range. A rounding error
/// in one face's cosine moves the irradiance by ~1e-16 of this, whatever the geometry.
fn signal_scale(s: &Scene) -> f64 {
    es_default() * s.mesh.area() / (std::f64::consts::PI * s.epochs[0].observer.length_squared())
}

/// The scene with mesh and every vector rotated by `q`.
fn rotated(s: &Scene, q: DQuat) -> Scene {
    let mut r = s.clone();
    r.mesh = r.mesh.transformed(|v| q * v);
    // an anisotropic material's direction is the body's: it turns with the mesh
    for m in &mut r.materials {
        m.tangent = q * m.tangent;
    }
    for e in &mut r.epochs {
        e.sun = q * e.sun;
        e.observer = q * e.observer;
        e.earth = e.earth.map(|x| q * x);
    }
    r
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// With shadows (box-wing, trough): scaling by s gives s² and a random rotation of
    /// everything changes nothing, within the visibility tolerance (3 × 1e-3 of the
    /// unshadowed signal).
    #[test]
    fn scale_and_rotation_with_shadows(which in 0u8..2, s in 0.01..100.0f64, q in [-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64],
                                       sun in dir3(), obs in dir3(), earth in dir3()) {
        let base = object(which, 0.1, sun, obs, earth);
        let e0 = irradiance(&base);
        let budget = 3.0 * base.tolerance * unshadowed(&base);
        let mut scaled = base.clone();
        scaled.mesh = scaled.mesh.transformed(|v| v * s);
        prop_assert!((irradiance(&scaled) / (s * s) - e0).abs() <= budget + 1e-300, "scaled by {s}");
        prop_assert!((irradiance(&rotated(&base, rotation(q))) - e0).abs() <= budget + 1e-300, "rotated");
    }
}

/// The trough's end wall (1 m², facing +y) is the only face both lit and seen with the
/// Sun along (0.3, 0.8, 0.5) and the observer along (0.9, 0.1, 0.4): the right plate
/// hides the part below the line z = 4x/9 + 5/9 (the plate's far edge projected along the
/// view), so 0.6154 m² (= (8/13)²/2 + (4/9)(18/13)²/2) is lit and seen, in any
/// orientation. Checked against brute-force f64 rays too; the engine at tolerance 1e-6.
#[test]
fn trough_wall_lit_and_seen_area_in_any_orientation() {
    let exact = (8.0f64 / 13.0).powi(2) / 2.0 + 4.0 / 9.0 * (18.0f64 / 13.0).powi(2) / 2.0;
    let (s, o) = (unit([0.3, 0.8, 0.5]), unit([0.9, 0.1, 0.4]));
    assert!(
        (lit_seen_area(&trough(), s, o, 300) - exact).abs() < 2e-3,
        "brute force disagrees with the analytic area"
    );
    for (axis, angle) in [
        ([0.3, -0.4, 0.5], 0.0),
        ([0.3, -0.4, 0.5], 1.234),
        ([0.3, -0.4, 0.5], 1e-6),
        ([1.0, 0.0, 0.0], 2.0),
    ] {
        let q = DQuat::from_axis_angle(DVec3::from_array(axis).normalize(), angle);
        let mut mesh = trough().transformed(|x| q * x);
        mesh.material_ids = vec![0, 0, 0, 0, 1];
        let mut sc = scene(
            mesh,
            vec![lambert("black", 0.0, false), lambert("wall", 0.5, false)],
            vec![epoch(q * s, q * o * GEO)],
        );
        sc.tolerance = 1e-6;
        let area = glint::simulate(&sc).epochs[0].lit_visible_area_m2;
        assert!(
            (area - exact).abs() < 1e-3,
            "rotation {angle} about {axis:?}: {area} m² vs {exact}"
        );
    }
}

/// Sun temperature: E scales with the band exitance, E(T₁)/E(T₂) = M(T₁)/M(T₂), with M
/// by brute-force quadrature here (1e-9).
#[test]
fn proportional_to_band_exitance() {
    let base = object(
        0,
        0.1,
        unit([0.3, 0.8, 0.5]),
        unit([0.9, 0.1, 0.4]),
        DVec3::NEG_Z,
    );
    let e0 = irradiance(&base);
    for t in [3000.0, 5772.0, 10000.0] {
        let mut hot = base.clone();
        hot.illumination.sun_temperature_k = t;
        let ratio =
            planck_band_simpson(0.4, 0.7, t, 4000) / planck_band_simpson(0.4, 0.7, 5900.0, 4000);
        assert!(rel(irradiance(&hot), e0 * ratio) < 1e-9, "T = {t}");
    }
}
