use glam::{DQuat, DVec3};
use glint::geometry::builtin::push_quad;
use glint::geometry::bvh::Occluder;
use glint::geometry::Mesh;
fn main() {
    let mut m = Mesh::default();
    let (a, b, c) = (DVec3::new(-1.0, 0.0, 1.0), DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 1.0));
    let y = DVec3::new(0.0, 2.0, 0.0);
    push_quad(&mut m, [a, a + y, b + y, b], 0);
    push_quad(&mut m, [b, b + y, c + y, c], 0);
    let base = m.vertices.len() as u32;
    m.vertices.extend([a, b, c]);
    m.triangles.push([base, base + 2, base + 1]);
    m.material_ids.push(0);
    let o = DVec3::new(0.9, 0.1, 0.4).normalize();
    let occ = Occluder::build(&m);
    // brute: grid over the wall triangle
    let n = 400;
    let (mut seen, mut total) = (0usize, 0usize);
    for i in 0..n {
        for j in 0..n {
            let x = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            let z = (j as f64 + 0.5) / n as f64;
            if z < x.abs() { continue; }
            total += 1;
            let sd = DVec3::new(0.3, 0.8, 0.5).normalize();
            if occ.is_clear(DVec3::new(x, 0.0, z), DVec3::Y, o) && occ.is_clear(DVec3::new(x, 0.0, z), DVec3::Y, sd) { seen += 1; }
        }
    }
    for t in [0.1, 0.3, 0.5, 0.7, 0.9] {
        let pl = a + (b - a) * t;
        let pr = c + (b - c) * t;
        let pm = (a + c) * 0.5 * t + b * (1.0 - t);
        println!("t {t}: left edge clear {} right edge clear {} middle {} top edge {}", occ.is_clear(pl, DVec3::Y, o), occ.is_clear(pr, DVec3::Y, o), occ.is_clear(pm, DVec3::Y, o), occ.is_clear(a + (c - a) * t, DVec3::Y, o));
    }
    println!("brute seen fraction {} -> area {}", seen as f64 / total as f64, seen as f64 / total as f64 * 1.0);
    let _ = DQuat::IDENTITY;
    let req = serde_json::json!({
        "object": {"mesh": {"vertices": m.vertices.iter().map(|v| v.to_array()).collect::<Vec<_>>(),
                             "triangles": m.triangles, "material_ids": [0,0,0,0,1]},
                   "materials": [{"name":"black","model":"lambert","albedo":0.0},{"name":"wall","model":"lambert","albedo":0.5}]},
        "epochs": [{"t":0.0, "sun": [0.3,0.8,0.5], "observer": (o*3.6e7).to_array()}],
        "illumination": {"earthshine":"off"},
        "tolerance": 1e-6
    });
    for tol in [1e-2, 1e-3, 1e-4, 1e-6] {
        let mut req = req.clone();
        req["tolerance"] = serde_json::json!(tol);
        let scene = glint::Scene::from_json(&req.to_string(), &glint::Limits::unlimited()).unwrap();
        let r = glint::simulate(&scene);
        println!("tol {tol}: area {} rays {}", r.epochs[0].lit_visible_area_m2, r.summary.rays);
    }
    let mut scene = glint::Scene::from_json(&req.to_string(), &glint::Limits::unlimited()).unwrap();
    scene.method = glint::scene::Method::Centroid;
    scene.mesh = glint::geometry::builtin::subdivide(&scene.mesh, 6);
    let r = glint::simulate(&scene);
    println!("centroid on subdivided: area {} rays {}", r.epochs[0].lit_visible_area_m2, r.summary.rays);
    {
        use glint::integrate::visibility::*;
        let scene = glint::Scene::from_json(&req.to_string(), &glint::Limits::unlimited()).unwrap();
        let mut faces = glint::geometry::Faces::build(&scene.mesh, true);
        faces.sort_spatially();
        for (i, f) in faces.faces.iter().enumerate() { println!("face {i}: n {:?} area {} c {:?} r {}", f.normal, f.area, f.centroid, f.radius); }
        let vis = Visibility::build(&scene, &faces, VisibilityMode::Adaptive);
        let wall = faces.faces.iter().position(|f| f.normal.y > 0.9).unwrap();
        let mut cache = Cache::default();
        for ma in [1e-2, 1e-4, 1e-6] {
            cache.reset();
            let r = vis.visible_area(&mut cache, wall, 1.0, &Uncertain { view: o, sun: None, earth: None }, ma);
            println!("view only, min_area {ma}: {:?}", r);
        }
    }
    let mut scene = glint::Scene::from_json(&req.to_string(), &glint::Limits::unlimited()).unwrap();
    scene.epochs[0].sun = scene.epochs[0].observer.normalize();
    let r = glint::simulate(&scene);
    println!("sun = observer: area {} rays {}", r.epochs[0].lit_visible_area_m2, r.summary.rays);
}

#[allow(dead_code)]
fn unused() {}
