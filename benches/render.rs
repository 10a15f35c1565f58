//! Thumbnail rendering: one 128×128 image of the box-wing (target: under 20 ms on the
//! 2-core machine), at 1×1, 2×2 and the default 3×3 samples per pixel, on 1 and 2
//! threads; and the PNG side (exposure + encoding) on its own.
//!
//! `cargo bench --bench render`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glint::render::{exposure, png, Renderer};
use glint::scene::{Exposure, Limits, Scene};

fn box_wing() -> Scene {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/box-wing.json"))
            .unwrap();
    Scene::from_json(&text, &Limits::unlimited()).unwrap()
}

fn render_128(c: &mut Criterion) {
    let scene = box_wing();
    let renderer = Renderer::new(&scene);
    // phase ~40°: body, dish and both panels in view, with the body's shadow on a panel
    let epoch = scene.epochs[80];
    let mut group = c.benchmark_group("box-wing 128x128");
    group.throughput(Throughput::Elements(128 * 128));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        for samples in [1, 2, 3] {
            group.bench_with_input(
                BenchmarkId::new(format!("{samples}x{samples} spp, threads"), threads),
                &samples,
                |b, &n| b.iter(|| pool.install(|| renderer.render(&epoch, 128, n))),
            );
        }
    }
    let image = renderer.render(&epoch, 128, 3);
    group.bench_function("exposure + PNG encoding", |b| {
        b.iter(|| {
            let white = exposure::white_levels(Exposure::Fixed, &[&image.radiance])[0];
            png::encode_grey(&exposure::to_grey(&image.radiance, white, false), 128)
        })
    });
    group.finish();
}

criterion_group!(benches, render_128);
criterion_main!(benches);
