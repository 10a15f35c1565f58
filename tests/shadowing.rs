//! Partial shadowing and occlusion by other parts of the mesh, against areas known from
//! the geometry: a horizontal occluder casts a translated copy of itself.

mod common;

use common::*;
use glam::DVec3;
use glint::geometry::builtin::{icosphere, plate, push_box, push_quad};
use glint::geometry::Mesh;
use std::f64::consts::PI;

const RANGE: f64 = 3.6e7;
/// Height of the occluder above the plate, m.
const H: f64 = 1.5;
/// In-plane rotation of the occluder: its shadow's edges cross the plate's triangles
/// and their subdivisions at no special angle.
const GAMMA: f64 = 0.3;

#[derive(Clone, Copy, Debug)]
enum Occluder {
    FacingUp,
    FacingDown,
    TwoSided,
}

/// A 2 m × 2 m plate (normal +z, `cells`² cells, albedo `a`) and, `H` above it, a black
/// square of side √2 (half the plate's area) turned by `GAMMA`, placed so that its
/// projection along `dir` falls on the plate's centre. Its projection along any other
/// direction used here misses the plate entirely.
fn half_scene(
    dir: DVec3,
    cells: u32,
    a: f64,
    occ: Occluder,
) -> (Mesh, Vec<glint::scene::Material>) {
    let mut mesh = plate(2.0, 2.0, cells);
    let centre = DVec3::new(dir.x / dir.z * H, dir.y / dir.z * H, H);
    let half = 0.5 * 2f64.sqrt();
    let (c, s) = (GAMMA.cos(), GAMMA.sin());
    let corner = |x: f64, y: f64| centre + DVec3::new(c * x - s * y, s * x + c * y, 0.0);
    let mut q = [
        corner(-half, -half),
        corner(half, -half),
        corner(half, half),
        corner(-half, half),
    ];
    if matches!(occ, Occluder::FacingDown) {
        q.reverse();
    }
    push_quad(&mut mesh, q, 1);
    let materials = vec![
        lambert("plate", a, false),
        lambert("occluder", 0.0, matches!(occ, Occluder::TwoSided)),
    ];
    (mesh, materials)
}

/// Directions of the test: one at 60° elevation (the occluder's side), one at 35° from
/// the opposite azimuth, whose projection of the occluder lands 3 m off the plate centre
/// (beyond the plate's 1.41 m reach in that direction plus the occluder's 1 m).
fn dirs() -> (DVec3, DVec3) {
    let az = 0.7;
    (
        dir(60f64.to_radians(), az),
        dir(35f64.to_radians(), az + PI),
    )
}

/// Irradiance and lit-and-seen area of the half-covered plate at tolerance `tol`, by the
/// `adaptive` method with shadows clipped exactly (`clip`) or sampled by rays.
fn half_result(l: DVec3, v: DVec3, cells: u32, occ: Occluder, tol: f64, clip: bool) -> (f64, f64) {
    let (mesh, mats) = half_scene(if l.z > v.z { l } else { v }, cells, 0.5, occ);
    let mut sc = scene(mesh, mats, vec![epoch(l, v * RANGE)]);
    sc.method = glint::scene::Method::Adaptive;
    sc.tolerance = tol;
    sc.clip_shadows = clip;
    let r = glint::simulate(&sc);
    assert_sane(&r);
    (r.epochs[0].irradiance_w_m2, r.epochs[0].lit_visible_area_m2)
}

/// What half the plate gives: E_s (a/π) (A/2) cosθi cosθr / R².
fn half_exact(l: DVec3, v: DVec3) -> f64 {
    es_default() * 0.5 / PI * 2.0 * l.z * v.z / (RANGE * RANGE)
}

/// Half the plate in the occluder's shadow gives half its light, and half hidden from the
/// observer likewise; for an occluder facing up, down or two-sided (rays see both sides
/// of a triangle) and a plate of 2 or 18 triangles. Tolerance: clipped shadows are exact
/// polygons, so only rounding remains (1e-12); sampled ones get the request's 1e-3
/// relative, times 3 (the sampler's error is within a few tolerances, see
/// `refinement_converges_with_tolerance`).
#[test]
fn half_shadowed_and_half_hidden_plate() {
    let (near, far) = dirs();
    for (clip, bound) in [(true, 1e-12), (false, 3e-3)] {
        for occ in [Occluder::FacingUp, Occluder::FacingDown, Occluder::TwoSided] {
            for cells in [1, 3] {
                for (what, l, v) in [("shadow", near, far), ("occlusion", far, near)] {
                    let (e, area) = half_result(l, v, cells, occ, 1e-3, clip);
                    let exact = half_exact(l, v);
                    assert!(
                        rel(e, exact) < bound,
                        "{what}, {occ:?}, {cells} cells, clip {clip}: {e:e} vs {exact:e}"
                    );
                    assert!(
                        (area - 2.0).abs() < 2.0 * bound,
                        "{what}, {occ:?}: lit and seen area {area} m² of 4"
                    );
                }
            }
        }
    }
    // with the Sun and the observer both on the far side the occluder's shadow and its
    // view projection both miss the plate: all of it is lit and seen, exactly
    let v = dir(40f64.to_radians(), 0.7 + PI);
    let (mesh, mats) = half_scene(near, 1, 0.5, Occluder::FacingUp);
    let r = glint::simulate(&scene(mesh, mats, vec![epoch(far, v * RANGE)]));
    let e = &r.epochs[0];
    assert!(
        rel(e.irradiance_w_m2, 2.0 * half_exact(far, v)) < 1e-12,
        "{e:?}"
    );
    assert!((e.lit_visible_area_m2 - 4.0).abs() < 1e-12, "{e:?}");
}

/// Clipped shadows are exact at every tolerance: the tolerance only steers the sampler,
/// which clipping does not need here. Bound 1e-12: rounding of a few hundred f64
/// operations on metre-scale coordinates.
#[test]
fn clipping_is_exact_at_every_tolerance() {
    let (near, far) = dirs();
    for (what, l, v) in [("shadow", near, far), ("occlusion", far, near)] {
        let exact = half_exact(l, v);
        for t in [0.1, 1e-2, 1e-3, 1e-4, 1e-6] {
            let e = rel(half_result(l, v, 1, Occluder::FacingUp, t, true).0, exact);
            assert!(e < 1e-12, "{what}: error {e:.2e} at tolerance {t:e}");
        }
    }
}

/// The ray sampler (the fallback for faces that shadows cut too finely to clip, and what
/// `clip_shadows = false` uses everywhere) converges as the tolerance shrinks: the error against the exact
/// half falls (0.1 → 1e-2 → 1e-4) and stays within 5× the tolerance from 0.1 down to
/// 1e-4 (measured: 2.5× at 0.1, 0.1–0.8× from 3e-2
/// to 3e-4, 2.3× at 1e-4).
#[test]
fn refinement_converges_with_tolerance() {
    let (near, far) = dirs();
    for (what, l, v) in [("shadow", near, far), ("occlusion", far, near)] {
        let exact = half_exact(l, v);
        let tols = [0.1, 0.03, 0.01, 3e-3, 1e-3, 3e-4, 1e-4];
        let errs: Vec<f64> = tols
            .iter()
            .map(|&t| rel(half_result(l, v, 1, Occluder::FacingUp, t, false).0, exact))
            .collect();
        for (t, e) in tols.iter().zip(&errs) {
            assert!(
                *e <= 5.0 * t,
                "{what}: error {e:.2e} at tolerance {t:e} (all: {errs:?})"
            );
        }
        assert!(
            errs[6] < errs[2] && errs[2] < errs[0],
            "{what}: not converging: {errs:?}"
        );
    }
}

/// The same below 1e-4: the sampler's error should keep following the tolerance.
#[test]
#[ignore = "ray sampler only (clip_shadows = false; the default clips exactly, see clipping_is_exact_at_every_tolerance): the error stops at 3.1e-4 of the signal for every tolerance from 1e-4 down to 1e-6; not the ray offset or the edge nudge (both 1e-6 of the object). The sampler's known misses — shadow corners between agreeing samples, and f32 rays grazing a neighbour (measured on the box-wing dish against f64 intersection) — are the suspects"]
fn refinement_follows_tiny_tolerances() {
    let (near, far) = dirs();
    let errs: Vec<(f64, f64)> = [1e-4, 1e-5, 1e-6]
        .iter()
        .map(|&t| {
            (
                t,
                rel(
                    half_result(near, far, 1, Occluder::FacingUp, t, false).0,
                    half_exact(near, far),
                ),
            )
        })
        .collect();
    assert!(
        errs.iter().all(|(t, e)| *e <= 5.0 * t),
        "(tolerance, error): {errs:?}"
    );
}

/// The box-wing with a black bus and dish, lit panels (albedo 0.25, two-sided), the Sun
/// along (1, −cot ε, 0): light crosses the 2 m bus towards +y at ε to the panels' plane
/// (x = 0), so the bus's shadow covers the +y panel (y from 1.5 to 6.5 m, z from −1 to 1)
/// up to y = 1 + cot ε (the boom's shadow lies inside it; the dish is above the panels'
/// z range; the −y panel is fully lit). The observer on the +x side at 17° elevation sees
/// both panels whole. `mirror` flips x and y: Sun from −x, shadow on the −y panel.
/// `clip`: shadows clipped exactly, else sampled by rays.
/// Returns (irradiance, exact irradiance, lit area, exact lit area).
fn box_wing_panels(cot: f64, tol: f64, mirror: bool, clip: bool) -> (f64, f64, f64, f64) {
    let m = if mirror { -1.0 } else { 1.0 };
    let sun = DVec3::new(m, -m * cot, 0.0).normalize();
    let v = DVec3::new(m, 0.0, 0.3).normalize();
    let request = serde_json::json!({
        "object": { "mesh": { "builtin": "box-wing" }, "materials": [
            { "name": "body", "model": "lambert", "albedo": 0.0 },
            { "name": "panel", "model": "lambert", "albedo": 0.25, "two_sided": true },
            { "name": "dish", "model": "lambert", "albedo": 0.0, "two_sided": true }
        ] },
        "epochs": [ { "t": 0, "sun": sun.to_array(), "observer": (v * RANGE).to_array() } ],
        "illumination": { "earthshine": "off" },
        "tolerance": tol,
        "method": "adaptive"
    });
    let mut sc = from_json(&request);
    sc.clip_shadows = clip;
    let r = glint::simulate(&sc);
    assert_sane(&r);
    // clipping needs no rays here; sampling does
    assert_eq!(r.summary.rays > 0, !clip, "rays {}", r.summary.rays);
    let lit = 20.0 - 2.0 * (1.0 + cot - 1.5);
    let exact = es_default() * 0.25 / PI * lit * sun.x.abs() * v.x.abs() / (RANGE * RANGE);
    (
        r.epochs[0].irradiance_w_m2,
        exact,
        r.epochs[0].lit_visible_area_m2,
        lit,
    )
}

/// The box-wing's panel in the bus's shadow converges to the exact lit area as the
/// tolerance shrinks, for shadow edges on and off the panel's sample grid (cot ε = 3
/// puts the edge at y = 4 m, the panel's midline: exactly half the +y panel), and in the
/// mirror configuration. Bound: 2e-3 at tolerance 1e-5 (measured ~5e-5) and a fall of at
/// least 10× from tolerance 0.1 (measured 5e-2–8e-2 there).
#[test]
fn box_wing_panel_in_the_bus_shadow_converges() {
    for cot in [3.0, 2.77, 3.1] {
        let (e0, exact, _, _) = box_wing_panels(cot, 0.1, false, false);
        let (e1, _, area, lit) = box_wing_panels(cot, 1e-5, false, false);
        assert!(rel(e1, exact) < 2e-3, "cot ε {cot}: {e1:e} vs {exact:e}");
        assert!(
            rel(e1, exact) < 0.1 * rel(e0, exact).max(1e-2),
            "cot ε {cot}: {e0:e} → {e1:e} vs {exact:e}"
        );
        assert!(
            (area - lit).abs() < 2e-3 * lit,
            "cot ε {cot}: area {area} vs {lit}"
        );
    }
    let (a, _, _, _) = box_wing_panels(3.0, 1e-5, false, false);
    let (b, exact, _, _) = box_wing_panels(3.0, 1e-5, true, false);
    assert!(
        rel(b, exact) < 2e-3 && rel(a, exact) < 2e-3,
        "{a:e} {b:e} {exact:e}"
    );
}

/// The case at the default tolerance: a panel half in the bus's shadow gives
/// half its light, within a few tolerances of the unshadowed signal.
#[test]
fn box_wing_panel_in_the_bus_shadow_within_tolerance() {
    for cot in [3.0, 2.77, 3.1] {
        for tol in [1e-2, 1e-3] {
            let (e, exact, _, lit) = box_wing_panels(cot, tol, false, false);
            // the unshadowed signal is 20 m² of panel against `lit`
            let unshadowed = exact * 20.0 / lit;
            assert!(
                (e - exact).abs() < 3.0 * tol * unshadowed,
                "cot ε {cot}, tolerance {tol}: {e:e} vs {exact:e}"
            );
        }
    }
}
/// Clipped, the bus's shadow on the panel is exact at any tolerance, in both mirror
/// configurations, with no rays. Bound 1e-9: rounding (the exact lit area comes from the
/// builtin's dimensions, which are exact in binary only to ~1e-16 relative).
#[test]
fn box_wing_panel_in_the_bus_shadow_clipped_exactly() {
    for cot in [3.0, 2.77, 3.1] {
        for (tol, mirror) in [(1e-1, false), (1e-3, true), (1e-3, false)] {
            let (e, exact, area, lit) = box_wing_panels(cot, tol, mirror, true);
            assert!(
                rel(e, exact) < 1e-9,
                "cot ε {cot}, tolerance {tol}: {e:e} vs {exact:e}"
            );
            assert!(
                (area - lit).abs() < 1e-9 * lit,
                "cot ε {cot}: area {area} vs {lit}"
            );
        }
    }
}

/// A small black triangle far from the plate (10 m to 1 km away, below it: it casts no
/// shadow and sends no light) changes nothing about the plate's light.
#[test]
fn distant_triangle_changes_nothing() {
    let (near, far) = dirs();
    let exact = half_exact(near, far);
    for dist in [10.0, 100.0, 1000.0] {
        let (mut mesh, mats) = half_scene(near, 1, 0.5, Occluder::FacingUp);
        let b = mesh.vertices.len() as u32;
        mesh.vertices.extend([
            DVec3::new(dist, 0.0, -5.0),
            DVec3::new(dist + 0.1, 0.0, -5.0),
            DVec3::new(dist, 0.1, -5.0),
        ]);
        mesh.triangles.push([b, b + 1, b + 2]);
        mesh.material_ids.push(1);
        let e = glint::simulate(&scene(mesh, mats, vec![epoch(near, far * RANGE)])).epochs[0]
            .irradiance_w_m2;
        assert!(
            rel(e, exact) < 3e-3,
            "triangle {dist} m away: {e:e} vs {exact:e}"
        );
    }
}

/// A 12 m × 12 m plate (albedo 0.5) under a black 2 × 1 × 1 m box floating 1 m above it,
/// closed or open at the bottom (the open side is flat: a cap). Seen from straight
/// above, the box hides its 2 m² footprint; the Sun along (2, 0.5, 1) casts the box's
/// projection, of area (A_top·d_z + A_x·|d_x| + A_y·|d_y|)/d_z = (2 + 2 + 1) m² = 5 m²,
/// which touches the footprint only along an edge. So 144 − 2 − 5 = 137 m² are lit and
/// seen, exactly. A box is a convex part, whose shadow is cast as one polygon (the hull
/// of its projected corners) rather than face by face: this checks that path, which
/// also serves finely meshed dishes. Bound 1e-12: rounding.
#[test]
fn a_box_and_an_open_box_shadow_a_plate_by_their_projected_area() {
    for open in [false, true] {
        let mut mesh = plate(12.0, 12.0, 3);
        let base = mesh.triangles.len();
        push_box(
            &mut mesh,
            DVec3::new(-1.0, -0.5, 1.0),
            DVec3::new(1.0, 0.5, 2.0),
            1,
        );
        if open {
            // drop the bottom's two triangles (all corners at z = 1)
            let keep: Vec<bool> = (0..mesh.triangles.len())
                .map(|t| t < base || mesh.corners(t).iter().any(|c| c.z != 1.0))
                .collect();
            let mut k = keep.iter();
            mesh.triangles.retain(|_| *k.next().unwrap());
            let mut k = keep.iter();
            mesh.material_ids.retain(|_| *k.next().unwrap());
            assert_eq!(mesh.triangles.len(), base + 10);
        }
        let mats = vec![lambert("plate", 0.5, false), lambert("box", 0.0, false)];
        let sun = DVec3::new(2.0, 0.5, 1.0).normalize();
        let r = glint::simulate(&scene(mesh, mats, vec![epoch(sun, DVec3::Z * RANGE)]));
        assert_sane(&r);
        let area = r.epochs[0].lit_visible_area_m2;
        assert!(
            (area - 137.0).abs() < 1e-12 * 144.0,
            "open {open}: lit and seen {area} m², expected 137"
        );
        let exact = es_default() * 0.5 / PI * 137.0 * sun.z / (RANGE * RANGE);
        assert!(rel(r.epochs[0].irradiance_w_m2, exact) < 1e-12);
    }
}

/// A finely meshed convex part (an icosphere of 1,280 faces, radius 0.6 m, 1 m above a
/// 4 m plate) shadows and hides the plate as one hull each; the ray sampler, which knows
/// nothing of parts, integrates the same plate independently. They agree within 2e-3 of
/// the signal: the sampler's own floor (3.1e-4, see refinement_follows_tiny_tolerances)
/// and its tolerance-1e-4 error, with margin.
#[test]
fn a_finely_meshed_sphere_shadows_a_plate_as_the_sampler_finds() {
    let mut mesh = plate(4.0, 4.0, 1);
    let ball = icosphere(3, 0.6).transformed(|p| p + DVec3::new(0.2, -0.1, 1.0));
    let base = mesh.vertices.len() as u32;
    mesh.vertices.extend(&ball.vertices);
    for t in &ball.triangles {
        mesh.triangles.push(t.map(|v| v + base));
        mesh.material_ids.push(1);
    }
    let mats = vec![lambert("plate", 0.5, false), lambert("ball", 0.0, false)];
    let (sun, view) = (dir(50f64.to_radians(), 0.4), dir(70f64.to_radians(), 2.5));
    let run = |clip: bool| {
        let mut sc = scene(mesh.clone(), mats.clone(), vec![epoch(sun, view * RANGE)]);
        sc.tolerance = 1e-4;
        sc.clip_shadows = clip;
        let r = glint::simulate(&sc);
        assert_sane(&r);
        r.epochs[0].irradiance_w_m2
    };
    let (clipped, sampled) = (run(true), run(false));
    let unshadowed = es_default() * 0.5 / PI * 16.0 * sun.z * view.z / (RANGE * RANGE);
    assert!(
        clipped < 0.95 * unshadowed,
        "the ball must shadow the plate"
    );
    assert!(
        (clipped - sampled).abs() < 2e-3 * unshadowed,
        "clipped {clipped:e} vs sampled {sampled:e}"
    );
}

/// A cup: a 2 m × 2 m floor and four 1 m walls, open at the top, every normal pointing
/// in (Lambert, albedo 0.5). From inside, only what looks out through the rim is lit or
/// seen: a convex cap's faces are clipped by its lid in one step. With the Sun along
/// (1, 0, 2) the floor is lit for x ≤ 2 − 1·(1/2) = 1.5 m; seen straight down all of it
/// is seen, so 1.5 × 2 = 3 m² are lit and seen; seen along (−0.3, 0, 1) only x ≥ 0.3 m
/// is, leaving 1.2 × 2 = 2.4 m². No wall is both lit and seen in either case (each is
/// edge-on to, or faces away from, one of the two). Bound 1e-12: rounding.
#[test]
fn a_cup_is_lit_and_seen_only_through_its_rim() {
    let (w, h) = (2.0, 1.0);
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mut cup = Mesh::default();
    push_quad(
        &mut cup,
        [p(0., 0., 0.), p(w, 0., 0.), p(w, w, 0.), p(0., w, 0.)],
        0,
    );
    push_quad(
        &mut cup,
        [p(0., 0., 0.), p(0., w, 0.), p(0., w, h), p(0., 0., h)],
        0,
    );
    push_quad(
        &mut cup,
        [p(w, 0., 0.), p(w, 0., h), p(w, w, h), p(w, w, 0.)],
        0,
    );
    push_quad(
        &mut cup,
        [p(0., 0., 0.), p(0., 0., h), p(w, 0., h), p(w, 0., 0.)],
        0,
    );
    push_quad(
        &mut cup,
        [p(0., w, 0.), p(w, w, 0.), p(w, w, h), p(0., w, h)],
        0,
    );
    let sun = DVec3::new(1.0, 0.0, 2.0).normalize();
    for (view, expected) in [
        (DVec3::Z, 3.0),
        (DVec3::new(-0.3, 0.0, 1.0).normalize(), 2.4),
    ] {
        let sc = scene(
            cup.clone(),
            vec![lambert("cup", 0.5, false)],
            vec![epoch(sun, view * RANGE)],
        );
        let r = glint::simulate(&sc);
        assert_sane(&r);
        let area = r.epochs[0].lit_visible_area_m2;
        assert!(
            (area - expected).abs() < 1e-12 * 4.0,
            "view {view}: lit and seen {area} m², expected {expected}"
        );
        let e = es_default() * 0.5 / PI * expected * sun.z * view.z / (RANGE * RANGE);
        assert!(rel(r.epochs[0].irradiance_w_m2, e) < 1e-12, "view {view}");
    }
}

/// The same request gives the same light curve to the last bit: nothing may depend on the
/// order a hash map iterates in (each run seeds its maps afresh), nor on which thread
/// took which epoch. Caught: a cap's lid started from whichever open edge came first,
/// and its rounding moved faint epochs by 2e-16. The box-wing with a 4 × 16 dish, whose
/// lid and cut parts are all exercised, over its 341 epochs, five times (without the fix,
/// two in three runs of this test failed).
#[test]
fn the_same_request_gives_the_same_light_curve_to_the_last_bit() {
    let sc = small_dish_box_wing();
    let curve = || -> Vec<u64> {
        glint::simulate(&sc)
            .epochs
            .iter()
            .map(|e| e.irradiance_w_m2.to_bits())
            .collect()
    };
    let first = curve();
    for _ in 0..4 {
        assert!(first == curve(), "two runs of one request differ");
    }
}

/// Per-thread caches keyed by direction (parts' silhouettes, caps' face states, the face
/// grids) outlive an epoch, so an epoch whose Sun or Earth direction repeats the last
/// one's reuses them. Whatever came before it, an epoch's light must be the same to the
/// last bit: every 17th epoch of the box-wing's 341 (the Sun fixed, so reused every time),
/// run alone, against the whole run.
#[test]
fn an_epoch_gives_the_same_light_alone_as_after_others() {
    let mut sc = small_dish_box_wing();
    let all = glint::simulate(&sc);
    let epochs = sc.epochs.clone();
    for (i, epoch) in epochs.iter().enumerate().step_by(17) {
        sc.epochs = vec![*epoch];
        let alone = glint::simulate(&sc);
        assert_eq!(
            alone.epochs[0].irradiance_w_m2.to_bits(),
            all.epochs[i].irradiance_w_m2.to_bits(),
            "epoch {i}: alone {} after others {}",
            alone.epochs[0].irradiance_w_m2,
            all.epochs[i].irradiance_w_m2
        );
    }
}

/// The box-wing request (341 epochs) on the box-wing with a 4 × 16 dish.
fn small_dish_box_wing() -> glint::scene::Scene {
    let text = include_str!("../scenes/box-wing.json");
    let mut sc = glint::scene::Scene::from_json(text, &glint::scene::Limits::unlimited())
        .expect("the box-wing request");
    sc.mesh = glint::geometry::builtin::box_wing_with(4, 16, 0);
    sc
}
