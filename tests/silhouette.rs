//! The silhouette method (the default for non-convex meshes) on every object class of
//! the suite, against the exact clipping of `adaptive`, a different algorithm (per face:
//! every possible blocker projected onto its plane and subtracted), and at the places
//! where methods break: the Sun in a face's plane, grazing views, phase 0° and 180°.

mod common;

use glam::{DQuat, DVec3};
use glint::{simulate, Limits, Response, Scene};
use serde_json::{json, Value};

const CLASSES: [&str; 5] = [
    "rocket-body",
    "fragment",
    "dish-sat",
    "cubesat",
    "box-wing-tumbling",
];

fn request(class: &str) -> Value {
    let path = format!("{}/scenes/{class}.json", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).expect("scene file")).expect("json")
}

fn run(v: &Value) -> Response {
    let scene = Scene::from_json(&v.to_string(), &Limits::unlimited()).expect("valid request");
    let r = simulate(&scene);
    common::assert_sane(&r);
    r
}

/// The class's request at coarse detail, with `epochs` and method settings `patch`.
fn coarse(class: &str, epochs: Vec<Value>, patch: Value) -> Value {
    at_detail(class, "coarse", epochs, patch)
}

/// The class's request at `detail`, with `epochs` and method settings `patch`.
fn at_detail(class: &str, detail: &str, epochs: Vec<Value>, patch: Value) -> Value {
    let mut v = request(class);
    v["object"]["mesh"]["detail"] = json!(detail);
    v["epochs"] = Value::Array(epochs);
    for (k, x) in patch.as_object().expect("object") {
        v[k] = x.clone();
    }
    v
}

/// Worst difference between two curves relative to the brighter curve's maximum.
fn worst(a: &Response, b: &Response) -> f64 {
    let scale = b
        .epochs
        .iter()
        .map(|e| e.irradiance_w_m2)
        .fold(0.0, f64::max);
    assert!(scale > 0.0);
    a.epochs
        .iter()
        .zip(&b.epochs)
        .map(|(x, y)| (x.irradiance_w_m2 - y.irradiance_w_m2).abs() / scale)
        .fold(0.0, f64::max)
}

/// Both methods are exact: they differ by rounding, and by `adaptive`'s ray sampling of
/// faces its clipping would cut into too many pieces, which at tolerance 1e-7 is held to
/// 1e-7 of the signal. 1e-6 of the curve's maximum leaves room for both.
const EXACT: f64 = 1e-6;

fn agree(class: &str, epochs: Vec<Value>) -> (Response, Response) {
    agree_at(class, "coarse", epochs)
}

/// [`agree`] at `detail`.
fn agree_at(class: &str, detail: &str, epochs: Vec<Value>) -> (Response, Response) {
    let s = run(&at_detail(
        class,
        detail,
        epochs.clone(),
        json!({ "method": "silhouette" }),
    ));
    let a = run(&at_detail(
        class,
        detail,
        epochs,
        json!({ "method": "adaptive", "tolerance": 1e-7 }),
    ));
    let w = worst(&s, &a);
    assert!(
        w <= EXACT,
        "{class}: silhouette vs adaptive differ by {w:e} of the maximum"
    );
    (s, a)
}

#[test]
fn every_class_matches_exact_clipping_over_its_tumbling_light_curve() {
    for class in CLASSES {
        let v = request(class);
        let all = v["epochs"].as_array().expect("epochs");
        // every 13th epoch: the tumble's attitudes and the whole phase sweep
        let epochs: Vec<Value> = all.iter().step_by(13).cloned().collect();
        let (s, _) = agree(class, epochs);
        assert!(
            s.summary.method.contains("silhouette"),
            "{}",
            s.summary.method
        );
    }
}

/// `mesh` as a request's inline mesh: its vertices (m) and triangles.
fn inline_mesh(mesh: &glint::geometry::Mesh) -> Value {
    json!({
        "vertices": mesh.vertices.iter().map(|v| v.to_array()).collect::<Vec<_>>(),
        "triangles": mesh.triangles,
    })
}

/// Epochs in the body frame (no attitude), with an Earth far below.
fn body_epochs(pairs: &[(DVec3, DVec3)]) -> Vec<Value> {
    pairs
        .iter()
        .enumerate()
        .map(|(i, (s, o))| {
            json!({ "t": i as f64, "sun": s.to_array(), "observer": (*o * 3.6e7).to_array(),
                    "earth": [0.0, 0.0, -4.2e7] })
        })
        .collect()
}

#[test]
fn the_sun_in_a_faces_plane_and_grazing_views_match_exact_clipping() {
    // The rocket body, cubesat and dish-sat have faces along the body axes (cylinder
    // sides along z, box sides): the Sun, then the observer, within ±0.01° of the plane
    // z = 0 and exactly in it, the other vector well clear.
    let other = DVec3::new(0.6, 0.5, 0.62).normalize();
    let grazing = |deg: f64| {
        let e: f64 = deg.to_radians();
        DVec3::new(0.8 * e.cos(), 0.6 * e.cos(), e.sin())
    };
    let degs = [-0.01, -1e-4, 0.0, 1e-4, 0.01];
    for class in ["rocket-body", "cubesat", "dish-sat", "fragment"] {
        let mut pairs: Vec<(DVec3, DVec3)> = degs.iter().map(|&d| (grazing(d), other)).collect();
        pairs.extend(degs.iter().map(|&d| (other, grazing(d))));
        agree(class, body_epochs(&pairs));
    }
}

#[test]
fn phase_0_and_180_degrees_match_exact_clipping() {
    let s = DVec3::new(0.37, 0.52, 0.77).normalize();
    let axis = s.cross(DVec3::Z).normalize();
    let near = |deg: f64| DQuat::from_axis_angle(axis, deg.to_radians()) * s;
    let pairs: Vec<(DVec3, DVec3)> = [0.0, 1e-4, 1.0, 179.0, 179.9999, 180.0]
        .iter()
        .map(|&d| (s, near(d)))
        .collect();
    for class in CLASSES {
        agree(class, body_epochs(&pairs));
    }
}

#[test]
fn a_convex_mesh_is_one_group_decided_by_one_ray_per_direction() {
    let v = json!({
        "object": { "mesh": { "builtin": "sphere" },
                    "materials": [{ "name": "surface", "model": "lambert", "albedo": 0.5 }] },
        "epochs": body_epochs(&[(DVec3::X, DVec3::new(0.6, 0.8, 0.0))]),
        "illumination": { "earthshine": "off" },
        "method": "silhouette"
    });
    let s = run(&v);
    let mut c = v.clone();
    c["method"] = json!("convex");
    let convex = run(&c);
    assert_eq!(s.summary.rays, 2, "one ray for the view, one for the Sun");
    let (a, b) = (
        s.epochs[0].irradiance_w_m2,
        convex.epochs[0].irradiance_w_m2,
    );
    // the same faces summed in the same order: equal to rounding
    assert!((a - b).abs() <= 1e-12 * b, "{a:e} vs {b:e}");
}

/// A V trough (two open, one-sided plates) with an end wall whose triangle winds the same
/// way as the plates along the edges it shares with them: the mesh's orientation flips
/// there, so the wall and a plate can both face the Sun and yet lie on one side of their
/// edge, folded over. Facing alone must not be taken to mean that nothing folds there
/// (found by `identities::linear_in_the_brdf`: the wall was handed the plate's count of
/// 0 and came out lit where it is dark). Directions from all round, with an Earth too.
#[test]
fn a_mesh_whose_winding_flips_along_an_edge_matches_exact_clipping() {
    let vertices = json!([
        [-1, 0, 1],
        [-1, 2, 1],
        [0, 2, 0],
        [0, 0, 0],
        [1, 2, 1],
        [1, 0, 1],
        [-1, 0, 1],
        [0, 0, 0],
        [1, 0, 1]
    ]);
    // plates (a, a+y, b+y, b) and (b, b+y, c+y, c); the wall (a, c, b)
    let triangles = json!([[0, 1, 2], [0, 2, 3], [3, 2, 4], [3, 4, 5], [6, 8, 7]]);
    let dir = |x: f64, y: f64, z: f64| DVec3::new(x, y, z).normalize();
    let sun = [
        dir(-0.4545, 0.6960, -0.5559),
        dir(0.3, 0.8, 0.5),
        dir(-0.7, 0.3, 0.6),
        dir(0.1, 0.9, -0.4),
    ];
    let obs = [
        dir(0.7467, 0.5899, 0.3074),
        dir(-0.2, 0.7, 0.6),
        dir(0.5, 0.5, -0.7),
    ];
    let mut pairs = Vec::new();
    for s in sun {
        for o in obs {
            pairs.push((s, o));
        }
    }
    let epochs: Vec<Value> = body_epochs(&pairs)
        .into_iter()
        .map(|mut e| {
            e["earth"] = json!([0.0, 0.0, 4.2e7]);
            e
        })
        .collect();
    let request = |method: Value| {
        json!({
            "object": { "mesh": { "vertices": vertices, "triangles": triangles },
                        "materials": [{ "name": "surface", "model": "lambert", "albedo": 0.5 }] },
            "epochs": epochs,
            "method": method,
            "tolerance": 1e-7
        })
    };
    let s = run(&request(json!("silhouette")));
    let a = run(&request(json!("adaptive")));
    let w = worst(&s, &a);
    assert!(
        w <= EXACT,
        "silhouette vs adaptive differ by {w:e} of the maximum"
    );
}

/// The rocket body's aft rings are flat faces that are not convex (kept as their
/// triangles: 160 each at medium detail), so they are trees of boxes: a shadow segment's
/// test against one opens only the boxes it comes near, and a box no line crosses is one
/// cell of known area. Seen and lit from behind, the skirt and the bell shading them,
/// against exact clipping.
#[test]
fn the_rocket_bodys_aft_rings_seen_and_lit_from_behind_match_exact_clipping() {
    let behind = |x: f64, y: f64| DVec3::new(x, y, -1.0).normalize();
    let pairs = [
        (behind(0.5, 0.2), behind(-0.3, 0.4)),
        (behind(0.9, -0.3), behind(0.2, 0.1)),
        (behind(0.1, 0.05), behind(0.6, 0.6)),
        (behind(-1.2, 0.3), behind(0.3, -0.8)),
        (behind(0.3, 0.0), behind(0.0, 0.0)),
    ];
    agree_at("rocket-body", "medium", body_epochs(&pairs));
}

/// The box-wing at medium detail, where its boom stands on the bus along a line that
/// runs through the bus side's finer grid: the meeting segments there are found once per
/// bus triangle beside the line (once was counted twice and made a whole bus side lit
/// that is dark, 1.2e-3 of the signal at these epochs), and some share a corner with the
/// bus and are not found at all. Against exact clipping, as above.
#[test]
fn the_box_wing_at_medium_detail_matches_exact_clipping_where_its_boom_meets_the_bus() {
    let v = request("box-wing-tumbling");
    let all = v["epochs"].as_array().expect("epochs");
    agree_at("box-wing-tumbling", "medium", all[121..129].to_vec());
}

/// A face another piece meets (the bus under the boom, the wings' booms, the dish's
/// struts) is counted across its contacts as across fold lines, each contact with the
/// jump of the other piece's sheet: no ray of its own. What then casts rays is the first
/// unit of each connected region of receivers: 16 (box-wing) and 36 (dish-sat) an epoch
/// at coarse detail over the tumble (along the view, the Sun and the Earth's beam), where
/// a ray for each region of a touched face's cells had cast 107 and 257. At most 60 an
/// epoch on either, and the curve within [`EXACT`] of exact clipping at the same epochs.
#[test]
fn faces_other_pieces_meet_are_counted_across_their_contacts_not_cast_rays() {
    for class in ["box-wing-tumbling", "dish-sat"] {
        let v = request(class);
        let all = v["epochs"].as_array().expect("epochs");
        let epochs: Vec<Value> = all.iter().step_by(13).cloned().collect();
        let n = epochs.len() as u64;
        let (s, _) = agree(class, epochs);
        assert!(
            s.summary.rays <= 60 * n,
            "{class}: {} rays over {n} epochs",
            s.summary.rays
        );
    }
}

/// Pass 1 skips a patch as unseen without reading its faces: every face of such a patch
/// must turn away from the observer (n·v < 0), on every class and along directions all
/// round it, and the skip must take effect (a closed body turns some patch away from
/// every direction).
#[test]
fn a_patch_skipped_as_unseen_turns_every_face_away_from_the_observer() {
    use glint::geometry::Faces;
    use glint::integrate::silhouettes::Silhouettes;
    for class in CLASSES {
        let v = coarse(
            class,
            request(class)["epochs"].as_array().unwrap()[..1].to_vec(),
            json!({}),
        );
        let scene = Scene::from_json(&v.to_string(), &Limits::unlimited()).expect("valid request");
        let faces = Faces::build(&scene.mesh, true);
        let sil = Silhouettes::build(&scene, &faces);
        for i in 0..64 {
            // a Fibonacci spiral of view directions
            let z = 1.0 - (2.0 * i as f64 + 1.0) / 64.0;
            let phi = i as f64 * 2.399_963_229_728_653;
            let r = (1.0 - z * z).sqrt();
            let view = DVec3::new(r * phi.cos(), r * phi.sin(), z);
            let mut skipped = 0;
            for p in 0..sil.patches() {
                if !sil.unseen(p, view) {
                    continue;
                }
                skipped += 1;
                for &f in sil.patch_faces(p) {
                    let n = faces.faces[f as usize].normal;
                    assert!(
                        n.dot(view) < 0.0,
                        "{class}: face {f} of unseen patch {p} faces {view}"
                    );
                }
            }
            assert!(skipped > 0, "{class}: no patch skipped along {view}");
        }
    }
}

/// The box-wing's boom stands on the bus side: a face another piece meets inside it is
/// decided by rays, not by counts handed across the meeting segments, because the count
/// does not follow them there (a wall of the boom that faces away from a direction meets
/// the bus along a segment the count changes across with no sheet of its own; counting
/// across the segments instead made a 0.1 m × 0.1 m piece of the bus side lit at these
/// epochs that is dark, 1.1e-4 of the signal at t = 990 s). Against exact clipping.
#[test]
fn the_box_wing_where_its_boom_stands_on_the_bus_matches_exact_clipping_at_every_epoch_of_a_stretch(
) {
    let v = request("box-wing-tumbling");
    let all = v["epochs"].as_array().expect("epochs");
    agree("box-wing-tumbling", all[28..38].to_vec());
}

/// The dish-sat at medium detail, where each wing's plate stands on the end cap of its
/// boom, the plate's edge welded to the cap's centre: the plate meets the cap along a
/// line from that shared corner, which the contact search used to pass over (it skipped
/// every pair of triangles with a corner in common), so the cap was counted lit all
/// over where the plate shades half of it (2.4e-3 of the signal at t = 60 s). Against
/// exact clipping.
#[test]
fn the_dish_sat_at_medium_detail_matches_exact_clipping_where_its_wings_stand_on_their_booms() {
    let v = request("dish-sat");
    let all = v["epochs"].as_array().expect("epochs");
    agree_at("dish-sat", "medium", all[0..3].to_vec());
}

/// The crumpled fragment at medium detail written to six decimals, at the three epochs of
/// its request where a count ray's hit fell within the tolerance (4e-6 m) of a polygon's
/// edge on a face its shadow lines cross: the ray was retried from a point on the other
/// side of a line, and that point's count taken for the reference's (5.5e-4 of the
/// maximum too bright). Only points clear of the lines are tried now. Against exact
/// clipping of the same rounded triangles: 28 pairs of them merge into faces bent by up
/// to 3e-6 m, and the two differ by 1.4e-8 of the maximum; 1e-5 holds that with room and
/// fails the retry's error fiftyfold.
#[test]
fn a_count_ray_retried_on_a_rounded_fragment_keeps_to_its_side_of_the_lines() {
    use glint::geometry::builtin::{find, Detail};
    let mut mesh = (find("fragment").expect("built in").build)(Detail::Medium);
    for v in &mut mesh.vertices {
        *v = v.map(|x| (x * 1e6).round() / 1e6);
    }
    let v = request("fragment");
    let all = v["epochs"].as_array().expect("epochs");
    let epochs: Vec<Value> = [112, 191, 246].iter().map(|&i| all[i].clone()).collect();
    let at = |method: Value| {
        let mut r = v.clone();
        r["object"]["mesh"] = inline_mesh(&mesh);
        r["epochs"] = Value::Array(epochs.clone());
        r["illumination"]["earthshine"] = json!("off");
        r["method"] = method;
        r["tolerance"] = json!(1e-7);
        run(&r)
    };
    let (s, a) = (at(json!("silhouette")), at(json!("adaptive")));
    let w = worst(&s, &a);
    assert!(
        w <= 1e-5,
        "silhouette vs adaptive differ by {w:e} of the maximum"
    );
}

/// Boxes through one another (a cluster of parts, as CAD models of satellites hold them),
/// each side a 4 × 4 grid of squares, turned off the axes and written to nine decimals as
/// an OBJ file would hold them: each side is one face, convex though its outline's hull
/// exceeds it by the rounding, and the sides that pierce it meet it along joined
/// segments. Both were found on objects outside the suite (`benches/heldout.sh`: a
/// cluster of 28 such boxes cast 14k rays an epoch, now 2k). Directions from all round,
/// against exact clipping.
#[test]
fn boxes_through_one_another_written_to_nine_decimals_match_exact_clipping() {
    let (s, a) = boxes_through_one_another(Written::Decimals(9));
    let w = worst(&s, &a);
    assert!(
        w <= EXACT,
        "silhouette vs adaptive differ by {w:e} of the maximum"
    );
    // each side convex, its rays shared by region: 971 rays (1,034 with the tolerance 1e-9
    // of the size, 4,400 with the sides kept as triangles, when the rounding made them
    // seem not convex)
    assert!(s.summary.rays < 2_000, "{} rays", s.summary.rays);
}

/// The same boxes written to six decimals, as most exporters write: the corners of a side
/// are off its plane by up to ~1e-6 m, a thousand times the 1e-9 of the object's size that
/// faces merged within before the mesh's rounding was read from its coordinates. Each
/// side is still one face (500 faces and 3,650 rays before; 970 now). Exact clipping of the
/// rounded triangles and the silhouettes of the faces they merge into then agree to what
/// the rounding leaves open: a strip of the mesh's tolerance (4e-6 m) along each side's
/// outline, whose perimeter over area is at most 11 /m: 4.4e-5 of a side's light. The
/// curve agrees with the nine-decimal one within what the rounding itself moves: a
/// side's normal turns by up to ~1e-5 rad (1e-6 m over squares of 6 to 25 cm), 1e-5 of a
/// Lambert face's light.
#[test]
fn boxes_through_one_another_written_to_six_decimals_merge_and_match_exact_clipping() {
    rounded_boxes_match(Written::Decimals(6), 4.4e-5);
}

/// The same boxes stored in single precision (a float32 array handed over as JSON numbers,
/// each an f32 printed in full): the corners are off their sides' planes by up to an f32's
/// step, 2.4e-7 m at the cluster's 2.8 m. Read as exact, the sides fall apart into their
/// triangles; read as f32s, each side is one face, the tolerance is 8 steps (1.9e-6 m),
/// and the bound on exact clipping is the six-decimal test's strip scaled to it:
/// 1.9e-6 m × 11 /m = 2.1e-5 (5.9e-6 measured, with 963 rays). Against nine decimals, a
/// side's normal turns by up to ~4e-6 rad (2.4e-7 m over 6 cm): within 1e-5 as at six
/// decimals (1.2e-7 measured).
#[test]
fn boxes_through_one_another_stored_in_single_precision_merge_and_match_exact_clipping() {
    rounded_boxes_match(Written::Single, 2.1e-5);
}

/// The boxes written as `written`: few rays, within `exact` (of the maximum) of exact
/// clipping of the same triangles, and within 1e-5 of the nine-decimal curve.
fn rounded_boxes_match(written: Written, exact: f64) {
    let (s, a) = boxes_through_one_another(written);
    let (s9, _) = boxes_through_one_another(Written::Decimals(9));
    assert!(s.summary.rays < 2_000, "{} rays", s.summary.rays);
    let w = worst(&s, &a);
    assert!(
        w <= exact,
        "silhouette vs adaptive differ by {w:e} of the maximum"
    );
    let w = worst(&s, &s9);
    assert!(
        w <= 1e-5,
        "{written:?} against nine decimals: {w:e} of the maximum"
    );
}

/// How [`boxes_through_one_another`] writes its coordinates.
#[derive(Clone, Copy, Debug)]
enum Written {
    Decimals(i32),
    /// Each coordinate the nearest f32, read back in full.
    Single,
}

/// [`boxes_through_one_another_written_to_nine_decimals_match_exact_clipping`]'s boxes
/// written as `written` says: the silhouette method's and exact clipping's runs, after
/// checking that each box side is one face.
fn boxes_through_one_another(written: Written) -> (Response, Response) {
    use glint::geometry::mesh::written_rounding;
    use glint::geometry::{builtin::push_grid_box, Faces, Mesh};
    let boxes = [
        (
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.5, 0.3, 0.2),
            (0.3, -0.7, 1.1),
        ),
        (
            DVec3::new(0.25, 0.1, 0.05),
            DVec3::new(0.15, 0.45, 0.25),
            (-0.4, 0.2, 0.6),
        ),
        (
            DVec3::new(-0.2, -0.15, 0.1),
            DVec3::new(0.3, 0.12, 0.4),
            (1.0, 0.5, -0.3),
        ),
        (
            DVec3::new(0.05, 0.3, -0.2),
            DVec3::new(0.35, 0.2, 0.15),
            (0.7, -1.2, 0.4),
        ),
        // and one apart, 2.5 m off: the object's size (faces merge within 1e-9 of it)
        // is the whole cluster's, larger than a box's
        (
            DVec3::new(2.5, 0.0, 0.0),
            DVec3::new(0.2, 0.2, 0.2),
            (0.1, 0.2, 0.3),
        ),
    ];
    let round = |x: f64| match written {
        Written::Decimals(k) => (x * 10f64.powi(k)).round() / 10f64.powi(k),
        Written::Single => x as f32 as f64,
    };
    let mut mesh = Mesh::default();
    for (centre, half, (a, b, c)) in boxes {
        let first = mesh.vertices.len();
        push_grid_box(&mut mesh, -half, half, [4, 4, 4], 0);
        let turn = DQuat::from_euler(glam::EulerRot::XYZ, a, b, c);
        for v in &mut mesh.vertices[first..] {
            *v = (turn * *v + centre).map(round);
        }
    }
    // as the request's inline mesh (or an OBJ file) is read
    mesh.rounding = written_rounding(&mesh.vertices);
    let rounding = match written {
        Written::Decimals(k) => 0.5 * 10f64.powi(-k),
        // one step of an f32 at the largest coordinate, 2.8 m: 2¹ ≤ 2.8 < 2²
        Written::Single => 2f64.powi(1 - 23),
    };
    assert_eq!(mesh.rounding, rounding);
    assert_eq!(Faces::build(&mesh, true).len(), 30, "each side one face");
    let dir = |x: f64, y: f64, z: f64| DVec3::new(x, y, z).normalize();
    let sun = [
        dir(0.3, 0.8, 0.5),
        dir(-0.7, 0.3, 0.6),
        dir(0.1, -0.9, -0.4),
    ];
    let obs = [
        dir(0.7, 0.6, 0.3),
        dir(-0.2, 0.7, -0.6),
        dir(0.5, -0.5, 0.7),
    ];
    let pairs: Vec<(DVec3, DVec3)> = sun
        .iter()
        .flat_map(|&s| obs.iter().map(move |&o| (s, o)))
        .collect();
    let request = |method: Value| {
        json!({
            "object": { "mesh": inline_mesh(&mesh),
                        "materials": [{ "name": "surface", "model": "lambert", "albedo": 0.5 }] },
            "epochs": body_epochs(&pairs),
            "illumination": { "earthshine": "off" },
            "method": method,
            "tolerance": 1e-7
        })
    };
    let s = run(&request(json!("silhouette")));
    let a = run(&request(json!("adaptive")));
    assert_eq!(s.summary.faces, 30);
    (s, a)
}

/// The cluster held out from the suite (`benches/heldout.py`: 28 boxes of random size and
/// attitude through one another, each side an 8 × 8 grid, written to nine decimals) over
/// its whole tumbling light curve, the default method against exact clipping. A rule that
/// shared a ray's answer along straight paths passed the suite's classes and the small
/// cluster above, and failed here: one epoch off by 0.6 of its light, a quarter of the
/// curve's peak (the answers of sliver cells' centroids, which lie on a line, shared with
/// cells beyond it). So the cluster stands here as a fixture: its boxes and epochs are
/// `tests/fixtures/heldout-cluster.json`, written by `benches/heldout.py --fixture`. Both
/// methods are exact, so [`EXACT`] holds them (3.5e-9 of the maximum measured); the
/// tolerance is the held-out request's (1e-3), as a user sends it.
#[test]
fn the_held_out_cluster_of_boxes_matches_exact_clipping_over_its_light_curve() {
    use glint::geometry::{builtin::push_grid_box, Mesh};
    let fixture = held_out_fixture();
    let vec3 = |v: &Value| {
        let a: Vec<f64> = serde_json::from_value(v.clone()).expect("three numbers");
        DVec3::new(a[0], a[1], a[2])
    };
    let mut mesh = Mesh::default();
    for b in fixture["boxes"].as_array().expect("boxes") {
        let (centre, half) = (vec3(&b["centre"]), vec3(&b["half"]));
        let rows: Vec<DVec3> = b["turn"]
            .as_array()
            .expect("rows")
            .iter()
            .map(vec3)
            .collect();
        let first = mesh.vertices.len();
        push_grid_box(&mut mesh, -half, half, [8, 8, 8], 0);
        for v in &mut mesh.vertices[first..] {
            let turned = DVec3::new(rows[0].dot(*v), rows[1].dot(*v), rows[2].dot(*v));
            *v = turned + centre;
        }
    }
    assert_eq!(mesh.triangles.len(), 21_504);
    held_out_matches_exact_clipping("cluster", mesh, &fixture["epochs"]);
}

/// Like the held-out truss (`benches/heldout.py`): a 2 m cube frame of 16 closed
/// ten-sided struts (its 12 edges and 4 diagonals), each running 6 cm past its nodes
/// through the struts that meet there, over the held-out epochs against exact clipping.
/// Each strut is one ring here where the held-out one has 62: its sides are one face
/// each either way.
#[test]
fn a_truss_of_struts_through_one_another_matches_exact_clipping_over_its_light_curve() {
    use glint::geometry::{builtin::push_tube, Mesh};
    let corners: Vec<DVec3> = (0..8)
        .map(|i| DVec3::new(sign(i & 4), sign(i & 2), sign(i & 1)))
        .collect();
    let mut edges: Vec<(usize, usize)> = (0..8)
        .flat_map(|i| (i + 1..8).map(move |j| (i, j)))
        .filter(|&(i, j)| (corners[i] - corners[j]).length() == 2.0)
        .collect();
    edges.extend([(0, 3), (4, 7), (0, 5), (2, 7)]);
    let mut mesh = Mesh::default();
    for (i, j) in edges {
        let d = (corners[j] - corners[i]).normalize();
        push_tube(
            &mut mesh,
            corners[i] - 0.06 * d,
            corners[j] + 0.06 * d,
            0.035,
            10,
            0,
        );
    }
    assert_eq!(mesh.triangles.len(), 16 * 40);
    held_out_matches_exact_clipping("truss", mesh, &held_out_fixture()["epochs"]);
}

/// Like the held-out station (`benches/heldout.py`): four cylindrical modules (96, 80, 64
/// and 48 sides, one ring each) crossing one another, and two panels through the ends of
/// the longest, over the held-out epochs against exact clipping. It found `adaptive` wrong where a
/// module runs through another's side (up to 3.0e-4 of the maximum, 7.5e-3 of a lit
/// epoch; glint's `image` method at 2048 px sided with the silhouette method): the hull of
/// a cut module's shadow folded flat at two corners of its section met 6e-16 m apart.
/// Mended in `geometry::polygon::hull` (near twins dropped) and in where the section's
/// corners are found (each edge's ends in one order).
#[test]
fn a_station_of_modules_through_one_another_matches_exact_clipping_over_its_light_curve() {
    use glint::geometry::{
        builtin::{push_grid_box, push_tube},
        Mesh,
    };
    let mut mesh = Mesh::default();
    let x = |a: f64, b: f64, c: f64| DVec3::new(a, b, c);
    push_tube(&mut mesh, x(-2.5, 0.0, 0.0), x(2.5, 0.0, 0.0), 0.55, 96, 0);
    push_tube(&mut mesh, x(0.0, -1.8, 0.0), x(0.0, 1.8, 0.0), 0.45, 80, 0);
    push_tube(&mut mesh, x(0.0, 0.0, -1.5), x(0.0, 0.0, 2.2), 0.4, 64, 0);
    push_tube(&mut mesh, x(1.2, -1.5, 0.0), x(1.2, 1.5, 0.0), 0.3, 48, 0);
    for c in [-2.0, 2.0] {
        let half = x(0.12, 3.0, 0.02);
        push_grid_box(
            &mut mesh,
            x(c, 0.0, 0.0) - half,
            x(c, 0.0, 0.0) + half,
            [6; 3],
            0,
        );
    }
    held_out_matches_exact_clipping("station", mesh, &held_out_fixture()["epochs"]);
}

fn sign(bit: usize) -> f64 {
    if bit == 0 {
        -1.0
    } else {
        1.0
    }
}

/// The held-out cluster's fixture: its boxes and the epochs every held-out request asks
/// for.
fn held_out_fixture() -> Value {
    let path = format!(
        "{}/tests/fixtures/heldout-cluster.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(path).expect("fixture")).expect("json")
}

/// `mesh`, written to nine decimals as the held-out OBJ files hold it, with the held-out
/// requests' material, band and tolerance (1e-3, as a user sends it) over `epochs`: the
/// default method is the silhouette method and within [`EXACT`] of exact clipping.
fn held_out_matches_exact_clipping(name: &str, mut mesh: glint::geometry::Mesh, epochs: &Value) {
    for v in &mut mesh.vertices {
        *v = v.map(|x| (x * 1e9).round() / 1e9);
    }
    let request = |method: Value, tolerance: f64| {
        json!({
            "object": { "mesh": inline_mesh(&mesh),
                        "materials": [{ "name": "surface", "model": "rough-conductor", "alpha": 0.3,
                                        "n": 1.4, "k": 7.5, "kd": 0.1 }] },
            "epochs": epochs,
            "illumination": { "band_um": [0.4, 0.7], "sun_temperature_k": 5900, "earthshine": "off" },
            "method": method,
            "tolerance": tolerance
        })
    };
    let s = run(&request(json!("auto"), 1e-3));
    let a = run(&request(json!("adaptive"), 1e-7));
    assert!(
        s.summary.method.contains("silhouette"),
        "{name}: {}",
        s.summary.method
    );
    assert_eq!(s.epochs.len(), epochs.as_array().expect("epochs").len());
    let w = worst(&s, &a);
    assert!(
        w <= EXACT,
        "{name}: silhouette vs adaptive differ by {w:e} of the maximum"
    );
}
