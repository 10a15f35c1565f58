//! Runs the box-wing request on a finer mesh and more epochs, to measure time and memory
//! at scale: `cargo run --release --example scale -- FLAT_LEVELS DISH_RINGS DISH_SECTORS EPOCHS`
//! (e.g. `7 5 24 10000` gives a 0.85 M-triangle box-wing; wrap in `/usr/bin/time -v` for
//! memory). `FLAT_LEVELS` = `sphere:L` uses a convex icosphere of 20·4^L triangles instead.
//! A fifth argument names a file to write the light curve to (irradiance per epoch, one
//! per line, full precision), to compare two builds. `--sun-drift DEG` turns the Sun by
//! DEG about the body's z axis from epoch to epoch, so that no Sun direction repeats.
//! `--first K` starts at the request's epoch K (the phase angle sweeps 0.5° an epoch), to
//! measure one stretch of the light curve: `benches/instructions.sh 3 48 128 31 --first
//! 310` counts the fine dish's epochs at phase 155°–170°. `--obj PATH` also writes the mesh
//! as OBJ (materials by name), for another renderer to time on the same object.

use glint::geometry::builtin;
use glint::scene::{Limits, Scene};

fn main() {
    let mut raw: Vec<String> = std::env::args().skip(1).collect();
    // `--sun-drift DEG`: turn the Sun by DEG about the body's z axis from each epoch to the
    // next, so that no two epochs share a Sun direction (as in a real pass, where it moves
    // ~1° a day in an inertially held body frame) and no cache keyed by it is reused
    let drift = raw.iter().position(|a| a == "--sun-drift").map(|i| {
        let deg: f64 = raw
            .get(i + 1)
            .and_then(|d| d.parse().ok())
            .expect("--sun-drift DEG");
        raw.drain(i..i + 2);
        deg.to_radians()
    });
    // `--first K`: the epochs from the request's K-th on (wrapping round)
    let first = raw.iter().position(|a| a == "--first").map_or(0, |i| {
        let k: usize = raw
            .get(i + 1)
            .and_then(|k| k.parse().ok())
            .expect("--first K");
        raw.drain(i..i + 2);
        k
    });
    // `--obj PATH`: write the mesh that is run, as OBJ
    let obj = raw.iter().position(|a| a == "--obj").map(|i| {
        let path = raw.get(i + 1).expect("--obj PATH").clone();
        raw.drain(i..i + 2);
        path
    });
    let sphere = raw
        .first()
        .and_then(|a| a.strip_prefix("sphere:"))
        .map(|l| l.parse::<u32>().expect("sphere level"));
    if sphere.is_some() {
        raw[0] = "0".into();
    }
    let args: Vec<u32> = raw
        .iter()
        .take(4)
        .map(|a| a.parse().expect("integer arguments"))
        .collect();
    let out = (raw.len() == 5).then(|| raw.pop().expect("five arguments"));
    let [flat, rings, sectors, epochs] = args[..] else {
        eprintln!("usage: scale FLAT_LEVELS DISH_RINGS DISH_SECTORS EPOCHS");
        std::process::exit(2);
    };
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/box-wing.json"))
            .unwrap();
    let mut scene = Scene::from_json(&text, &Limits::unlimited()).unwrap();
    scene.mesh = match sphere {
        Some(level) => builtin::icosphere(level, 1.0),
        None => builtin::box_wing_with(rings, sectors, flat),
    };
    if let Some(path) = obj {
        let names: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
        let text = builtin::to_obj(&scene.mesh, &names, "examples/scale: the mesh it runs");
        std::fs::write(&path, text).expect("write the OBJ");
    }
    let base = scene.epochs.clone();
    scene.epochs = (first..first + epochs as usize)
        .map(|i| base[i % base.len()])
        .collect();
    if let Some(step) = drift {
        for (i, e) in scene.epochs.iter_mut().enumerate() {
            e.sun = glam::DQuat::from_rotation_z(step * i as f64) * e.sun;
        }
    }
    let r = glint::simulate(&scene);
    if let Some(path) = out {
        let lines: Vec<String> = r
            .epochs
            .iter()
            .map(|e| format!("{:e}", e.irradiance_w_m2))
            .collect();
        std::fs::write(&path, lines.join("\n") + "\n").expect("write the light curve");
    }
    let s = &r.summary;
    println!(
        "{} triangles, {} faces, {} epochs in {:.1} ms = {:.0} epochs/s, {} rays ({:.0} rays/epoch)",
        s.triangles,
        s.faces,
        s.epochs,
        s.elapsed_ms,
        s.epochs as f64 / (s.elapsed_ms / 1e3),
        s.rays,
        s.rays as f64 / s.epochs as f64
    );
}
