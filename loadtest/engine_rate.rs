//! The engine's own rate on a request file, in process, for comparison with the service
//! under load (loadtest/run.sh). Two numbers, each with `threads` requests in flight at
//! once (the service's computation slots):
//! - simulate only: the scene parsed once, `simulate` in a loop;
//! - per request: parse + validate + simulate + serialise the response, as the service does.
//!
//! Usage: `cargo run --release --example engine_rate -- request.json [seconds] [threads]`

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

fn rate(threads: usize, seconds: f64, work: impl Fn() -> usize + Sync) -> (f64, u64) {
    let epochs = AtomicU64::new(0);
    let requests = AtomicU64::new(0);
    let start = Instant::now();
    let until = start + Duration::from_secs_f64(seconds);
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                while Instant::now() < until {
                    epochs.fetch_add(work() as u64, Ordering::Relaxed);
                    requests.fetch_add(1, Ordering::Relaxed);
                }
            });
        }
    });
    let wall = start.elapsed().as_secs_f64();
    (epochs.into_inner() as f64 / wall, requests.into_inner())
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .ok_or_else(|| anyhow::anyhow!("usage: engine_rate request.json [seconds] [threads]"))?;
    let seconds: f64 = args.get(2).map_or(Ok(10.0), |s| s.parse())?;
    let threads: usize = args.get(3).map_or(Ok(2), |s| s.parse())?;
    let text = std::fs::read_to_string(path)?;
    let scene = glint::Scene::from_json(&text, &glint::Limits::unlimited())?;
    // Warm-up: page in, size the rayon pool.
    let _ = glint::simulate(&scene);

    let (sim, n_sim) = rate(threads, seconds, || glint::simulate(&scene).epochs.len());
    let (full, n_full) = rate(threads, seconds, || {
        let scene = glint::Scene::from_json(&text, &glint::Limits::unlimited()).expect("valid");
        let resp = glint::simulate(&scene);
        serde_json::to_vec(&resp)
            .expect("serialisable")
            .len()
            .min(1)
            * resp.epochs.len()
    });
    println!("engine_simulate_epochs_per_s {sim:.1} requests {n_sim} threads {threads} epochs_per_request {}", scene.epochs.len());
    println!("engine_full_epochs_per_s {full:.1} requests {n_full} threads {threads}");
    Ok(())
}
