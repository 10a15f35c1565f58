//! The tests' oracle: what the engine's answers are checked against — f64 rays against
//! triangles (Möller–Trumbore), random directions, the areas rays find — and the meshes
//! and visibilities the tests share.

use super::*;
use crate::geometry::builtin;
use crate::scene::Limits;

impl Visibility {
    /// The same areas as [`Visibility::visible_area`] by plain clipping: every face that
    /// may block, one by one, with no convex part cast whole and no lid.
    pub(super) fn face_by_face(
        &self,
        cache: &mut Cache,
        face: usize,
        side: FaceSide,
        dirs: &Uncertain,
    ) -> Option<(f64, f64)> {
        let n = self.faces[face].normal * side.sign();
        let earth = dirs.earth.filter(|e| n.dot(*e) > 1e-3);
        let directions = PerDirection {
            view: Some(dirs.view),
            sun: dirs.sun,
            earth,
        };
        let mut blockers: PerDirection<Vec<Blocker>> = Default::default();
        cache.settled.iter_mut().for_each(Settled::clear);
        self.collect_blockers(cache, face, side, &directions, false, &mut blockers);
        let open = PerDirection::splat(LidState::Open);
        self.exact_area(cache, face, n, &directions, &blockers, &open)
    }
}

/// The box-wing with a finer dish, a feed box over the dish (in front of its lid) and
/// a plate through the dish's rim (in front of the lid and inside its hull, and
/// cutting the dish where the dish's section meets it).
pub(super) fn cluttered_box_wing() -> crate::geometry::Mesh {
    let mut mesh = builtin::box_wing_with(8, 24, 1);
    builtin::push_box(
        &mut mesh,
        DVec3::new(-0.1, -0.1, 1.55),
        DVec3::new(0.1, 0.1, 1.65),
        0,
    );
    builtin::push_quad(
        &mut mesh,
        [
            DVec3::new(-0.3, 0.5, 1.3),
            DVec3::new(0.3, 0.5, 1.3),
            DVec3::new(0.3, 0.5, 1.6),
            DVec3::new(-0.3, 0.5, 1.6),
        ],
        1,
    );
    mesh
}

/// Adaptive visibility for `mesh` with the box-wing request's materials.
pub(super) fn visibility_of(mesh: crate::geometry::Mesh) -> Visibility {
    let text = include_str!("../../../scenes/box-wing.json");
    let mut scene = Scene::from_json(text, &Limits::unlimited()).expect("scene");
    scene.mesh = mesh;
    let mut faces = Faces::build(&scene.mesh, true);
    faces.sort_spatially();
    Visibility::build(&scene, &faces, VisibilityMode::Adaptive)
}

/// `mesh` beside a plate (z = 0, x from 1.5 to 6, |y| < 3, 27 m²) that the mesh's
/// one part is cut by and cast whole on: the visibility, and the plate's face.
pub(super) fn beside_plate(mut mesh: crate::geometry::Mesh) -> (Visibility, usize) {
    builtin::push_quad(
        &mut mesh,
        [
            DVec3::new(1.5, -3.0, 0.0),
            DVec3::new(6.0, -3.0, 0.0),
            DVec3::new(6.0, 3.0, 0.0),
            DVec3::new(1.5, 3.0, 0.0),
        ],
        0,
    );
    let vis = visibility_of(mesh);
    let plate = vis
        .faces
        .iter()
        .position(|g| g.area > 20.0)
        .expect("the plate");
    assert!(
        vis.faces[plate].part_shadows.iter().any(|p| p.cut),
        "cast whole"
    );
    (vis, plate)
}

/// The plate's sunlit area seen from straight above (m²), with parts cast whole and
/// face by face.
pub(super) fn plate_lit(vis: &Visibility, plate: usize, sun: DVec3) -> (f64, f64) {
    let dirs = Uncertain {
        view: DVec3::Z,
        sun: Some(sun),
        earth: None,
    };
    let mut cache = Cache::default();
    cache.reset();
    let (a, _, rays) = vis.visible_area(&mut cache, plate, FaceSide::Front, &dirs, 1e-6);
    let (b, _) = vis
        .face_by_face(&mut cache, plate, FaceSide::Front, &dirs)
        .expect("clipped");
    assert_eq!(rays, 0);
    (a, b)
}

/// Does the ray from `p` along unit `d` meet triangle `t` at some t > 0
/// (Möller–Trumbore, f64)?
pub(super) fn ray_meets_triangle(p: DVec3, d: DVec3, t: &[DVec3; 3]) -> bool {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let q = d.cross(e2);
    let det = e1.dot(q);
    if det.abs() < 1e-300 {
        return false;
    }
    let s = p - t[0];
    let u = s.dot(q) / det;
    let r = s.cross(e1);
    let v = d.dot(r) / det;
    let along = e2.dot(r) / det;
    u >= 0.0 && v >= 0.0 && u + v <= 1.0 && along > 0.0
}

/// A direction uniform on the sphere.
pub(super) fn random_unit(rnd: &mut impl FnMut() -> f64) -> DVec3 {
    let z = 2.0 * rnd() - 1.0;
    let a = std::f64::consts::TAU * rnd();
    let s = (1.0 - z * z).sqrt();
    DVec3::new(s * a.cos(), s * a.sin(), z)
}

/// Where the engine's areas `a` and plain face-by-face clipping's `b` (sunlit,
/// earthlit, m²) disagree, rays decide: the engine's must be theirs, within 4σ of
/// 4,000 samples plus f32 rays' slack.
pub(super) fn rays_decide(
    vis: &Visibility,
    i: usize,
    side: FaceSide,
    dirs: &Uncertain,
    (a_sun, a_earth): (f64, f64),
    (b_sun, b_earth): (f64, f64),
) {
    let area = vis.faces[i].area;
    let (r_sun, r_earth) = sampled(vis, i, side, dirs, 4000);
    let sigma = |a: f64| {
        let p = (a / area).clamp(0.0, 1.0);
        4.0 * (p * (1.0 - p) / 4000.0).sqrt() * area + 2e-3 * area
    };
    assert!(
        (a_sun - r_sun).abs() <= sigma(r_sun) && (a_earth - r_earth).abs() <= sigma(r_earth),
        "face {i} side {side:?}: engine {a_sun}, {a_earth}; face by face {b_sun}, {b_earth}; \
         rays {r_sun}, {r_earth}"
    );
}

/// Seen-and-sunlit and seen-and-earthlit areas (m²) of a face from `n` random points
/// with a ray each way.
pub(super) fn sampled(
    vis: &Visibility,
    face: usize,
    side: FaceSide,
    dirs: &Uncertain,
    n: usize,
) -> (f64, f64) {
    let g = &vis.faces[face];
    let normal = g.normal * side.sign();
    let earth = dirs.earth.filter(|e| normal.dot(*e) > 1e-3);
    let total = g.pieces_area;
    let mut rnd = crate::test_rng(17 + face as u64);
    let (mut sun, mut earthlit) = (0usize, 0usize);
    for _ in 0..n {
        let mut pick = rnd() * total;
        let t = g
            .pieces
            .iter()
            .find(|t| {
                pick -= triangle_area(t);
                pick <= 0.0
            })
            .unwrap_or(&g.pieces[0]);
        let (mut a, mut b) = (rnd(), rnd());
        if a + b > 1.0 {
            (a, b) = (1.0 - a, 1.0 - b);
        }
        let p = t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b;
        let clear = |d: DVec3| vis.occluder.get().is_clear(p, normal, d);
        if !clear(dirs.view) {
            continue;
        }
        sun += usize::from(dirs.sun.is_none_or(clear));
        earthlit += usize::from(earth.is_none_or(clear));
    }
    (
        total * sun as f64 / n as f64,
        total * earthlit as f64 / n as f64,
    )
}
