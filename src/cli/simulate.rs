//! `glint simulate`: request file → light curve (CSV or JSON), plot and summary.

use super::SimulateArgs;
use crate::integrate::{simulate_with, Progress};
use crate::report;
use crate::scene::response::Thumbnail;
use crate::scene::{Limits, Scene, Thumbnails};
use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::Read;
use std::time::Duration;

pub fn run(args: &SimulateArgs) -> anyhow::Result<()> {
    let text = if args.request.as_os_str() == "-" {
        let mut s = String::new();
        std::io::stdin().read_to_string(&mut s)?;
        s
    } else {
        std::fs::read_to_string(&args.request)
            .with_context(|| format!("cannot read {}", args.request.display()))?
    };
    let mut scene = Scene::from_json(&text, &Limits::unlimited())
        .map_err(|e| anyhow::anyhow!("invalid request {}: {e}", args.request.display()))?;
    if args.thumbnails.is_some() && scene.thumbnails.is_none() {
        scene.thumbnails = Some(Thumbnails::default_for(scene.epochs.len()));
    }

    let progress = Progress::new();
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        let bar = ProgressBar::new(scene.epochs.len() as u64);
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{elapsed_precise}] {wide_bar} {pos}/{len} epochs ({per_sec}, eta {eta})")
                .expect("valid template"),
        );
        bar
    };
    let response = std::thread::scope(|s| {
        let handle = s.spawn(|| simulate_with(&scene, &progress));
        while !handle.is_finished() {
            bar.set_position(progress.done() as u64);
            std::thread::sleep(Duration::from_millis(50));
        }
        handle.join().expect("simulation thread panicked")
    })?;
    bar.finish_and_clear();

    if let Some(out) = &args.out {
        let is_json = out
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"));
        let body = if is_json {
            serde_json::to_string_pretty(&response)?
        } else {
            report::csv::to_csv(&response)
        };
        std::fs::write(out, body).with_context(|| format!("cannot write {}", out.display()))?;
    }
    if let Some(dir) = &args.thumbnails {
        write_thumbnails(dir, response.thumbnails.as_deref().unwrap_or_default())?;
    }
    if let Some(plot) = &args.plot {
        let title = args
            .request
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let svg = report::plot::magnitude_svg(&response, &title).map_err(|e| anyhow::anyhow!(e))?;
        std::fs::write(plot, svg).with_context(|| format!("cannot write {}", plot.display()))?;
    }

    if !args.quiet {
        print_summary(args, &response);
    }
    Ok(())
}

/// The summary on standard output: epochs, timing, magnitudes, method, files written.
fn print_summary(args: &SimulateArgs, response: &crate::scene::Response) {
    let s = &response.summary;
    let mags: Vec<f64> = response.epochs.iter().filter_map(|e| e.magnitude).collect();
    let brightest = mags.iter().copied().fold(f64::INFINITY, f64::min);
    let faintest = mags.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    println!(
        "{} epochs in {:.1} ms ({:.0} epochs/s), {} triangles in {} faces, {} rays",
        s.epochs,
        s.elapsed_ms,
        s.epochs as f64 / (s.elapsed_ms / 1e3).max(1e-9),
        s.triangles,
        s.faces,
        s.rays
    );
    if mags.is_empty() {
        println!("no light reaches the observer at any epoch");
    } else {
        println!(
            "brightest {brightest:.3} mag, faintest {faintest:.3} mag ({} of {} epochs dark)",
            s.epochs - mags.len(),
            s.epochs
        );
    }
    println!("method: {}", s.method);
    for (what, path) in [
        ("light curve", &args.out),
        ("plot", &args.plot),
        ("thumbnails", &args.thumbnails),
    ] {
        if let Some(p) = path {
            println!("{what}: {}", p.display());
        }
    }
}

/// Writes each thumbnail as `DIR/epoch-NNNNN.png` (NNNNN: the epoch index).
fn write_thumbnails(dir: &std::path::Path, thumbnails: &[Thumbnail]) -> anyhow::Result<()> {
    use base64::Engine as _;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for t in thumbnails {
        let png = base64::engine::general_purpose::STANDARD.decode(&t.png_base64)?;
        let path = dir.join(format!("epoch-{:05}.png", t.epoch));
        std::fs::write(&path, png).with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}
