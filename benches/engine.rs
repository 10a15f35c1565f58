//! Engine throughput: epochs/s with shadows (box-wing), facet-epochs/s on the convex
//! path (no rays), and rays/s, each on 1 and 2 threads.
//!
//! `cargo bench --bench engine`. Compare ratios measured in one run: the machines are noisy.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::DVec3;
use glint::geometry::builtin;
use glint::geometry::bvh::Occluder;
use glint::scene::{Limits, Scene};

fn box_wing_request() -> Scene {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/box-wing.json"))
            .unwrap();
    Scene::from_json(&text, &Limits::unlimited()).unwrap()
}

/// A 15,488-triangle box-wing: flat parts subdivided 3 times (they merge back into
/// faces) and a finely tessellated dish (48 rings × 128 sectors: 6,144 curved faces, each
/// its own face). The hardest kind of mesh for the engine: most triangles are distinct,
/// partly self-shadowed faces.
fn box_wing_15k() -> glint::geometry::Mesh {
    builtin::box_wing_with(48, 128, 3)
}

/// A 13,528-triangle box-wing whose triangles mostly subdivide flat faces (4 times), with
/// the 5 × 24 dish: the same 146 faces as the 268-triangle one.
fn box_wing_13k_flat() -> glint::geometry::Mesh {
    builtin::box_wing_with(5, 24, 4)
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

fn epochs_per_second(c: &mut Criterion) {
    let base = box_wing_request();
    let mut group = c.benchmark_group("box-wing shadows, tolerance 1e-3");
    group.sample_size(10);
    for (label, mesh, epochs) in [
        ("268 tris", base.mesh.clone(), 341),
        ("13.5k tris flat-subdivided", box_wing_13k_flat(), 341),
        // every 10th epoch: one run takes seconds
        ("15k tris fine dish", box_wing_15k(), 35),
    ] {
        let mut scene = base.clone();
        scene.mesh = mesh;
        let step = base.epochs.len().div_ceil(epochs);
        scene.epochs = base.epochs.iter().step_by(step).copied().collect();
        group.throughput(Throughput::Elements(scene.epochs.len() as u64));
        for threads in [1, 2] {
            let p = pool(threads);
            group.bench_with_input(
                BenchmarkId::new(format!("{label}, epochs"), threads),
                &scene,
                |b, s| b.iter(|| p.install(|| glint::simulate(s))),
            );
        }
    }
    group.finish();
}

fn facet_epochs_per_second(c: &mut Criterion) {
    let mut scene = box_wing_request();
    scene.mesh = builtin::icosphere(5, 1.0); // 20480 faces, convex: no rays
    scene.materials.truncate(1); // seed-microfacet body wrap
    scene.epochs.truncate(1000);
    let faces = scene.mesh.triangles.len() as u64 * scene.epochs.len() as u64;
    let mut group = c.benchmark_group("convex sphere, seed BRDF");
    group.sample_size(10);
    group.throughput(Throughput::Elements(faces));
    for threads in [1, 2] {
        let p = pool(threads);
        group.bench_with_input(BenchmarkId::new("facet-epochs", threads), &scene, |b, s| {
            b.iter(|| p.install(|| glint::simulate(s)))
        });
    }
    group.finish();
}

fn rays_per_second(c: &mut Criterion) {
    let mesh = box_wing_15k();
    let occ = Occluder::build(&mesh);
    // Rays from points spread over a 4 m sphere around the object towards its centre
    // region, half of them blocked: a shadow-ray workload.
    let n = 100_000;
    let rays: Vec<(DVec3, DVec3)> = (0..n)
        .map(|i| {
            let f = i as f64 / n as f64;
            let z = 1.0 - 2.0 * f;
            let phi = i as f64 * 2.399963;
            let r = (1.0 - z * z).sqrt();
            let dir = DVec3::new(r * phi.cos(), r * phi.sin(), z);
            let origin = -dir * 8.0 + DVec3::new(0.3 * (i % 7) as f64, 0.2 * (i % 5) as f64, 0.0);
            (origin, dir)
        })
        .collect();
    let mut group = c.benchmark_group("shadow rays, 15k-triangle box-wing");
    group.sample_size(10);
    group.throughput(Throughput::Elements(n as u64));
    for threads in [1usize, 2] {
        let p = pool(threads);
        group.bench_function(BenchmarkId::new("rays", threads), |b| {
            b.iter(|| {
                p.install(|| {
                    use rayon::prelude::*;
                    rays.par_chunks(1024)
                        .map(|c| {
                            c.iter()
                                .filter(|(o, d)| occ.is_clear(*o, DVec3::ZERO, *d))
                                .count()
                        })
                        .sum::<usize>()
                })
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    epochs_per_second,
    facet_epochs_per_second,
    rays_per_second
);
criterion_main!(benches);
