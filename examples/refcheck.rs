//! Convergence check for the box-wing request at one epoch: the adaptive method over
//! tolerances against brute force (centroid rays on ever finer subdivisions).
//! `cargo run --release --example refcheck -- EPOCH [MATERIAL_TO_KEEP]`
use glint::geometry::builtin;
use glint::scene::{Limits, Method, Scene};

fn main() {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/box-wing.json"))
            .unwrap();
    let mut scene = Scene::from_json(&text, &Limits::unlimited()).unwrap();
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    scene.epochs = vec![scene.epochs[args[0]]];
    if let Some(&keep) = args.get(1) {
        // keep one material's triangles only
        let m = &mut scene.mesh;
        let keep_t: Vec<bool> = m
            .material_ids
            .iter()
            .map(|&id| id as usize == keep)
            .collect();
        let mut i = 0;
        m.triangles.retain(|_| {
            i += 1;
            keep_t[i - 1]
        });
        m.material_ids.retain(|&id| id as usize == keep);
    }
    for tol in [1e-2, 1e-3, 1e-4, 1e-5, 1e-6] {
        let mut s = scene.clone();
        s.tolerance = tol;
        let r = glint::simulate(&s);
        let e = &r.epochs[0];
        println!(
            "adaptive tol {tol:e}: E {:.7e} area {:.5} rays {}",
            e.irradiance_w_m2, e.lit_visible_area_m2, r.summary.rays
        );
    }
    for level in [3, 4, 5, 6] {
        let mut s = scene.clone();
        s.method = Method::Centroid;
        s.mesh = builtin::subdivide(&scene.mesh, level);
        let r = glint::simulate(&s);
        let e = &r.epochs[0];
        println!(
            "brute level {level}: E {:.7e} area {:.5} rays {}",
            e.irradiance_w_m2, e.lit_visible_area_m2, r.summary.rays
        );
    }
}
