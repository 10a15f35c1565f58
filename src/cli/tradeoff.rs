//! `glint tradeoff`: every method over a range of its fidelity setting, error per epoch
//! against a converged reference, time per epoch; a chart (SVG + PNG) and a table.
//!
//! The reference is the finest adaptive run; it is itself checked against the `image`
//! method at a high resolution on a subset of the epochs, and their agreement printed.

use crate::integrate::methods::{self, Run, Setting};
use crate::report::chart;
use crate::scene::{Limits, Scene};
use anyhow::Context;
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct TradeoffArgs {
    /// Request JSON file.
    pub request: PathBuf,
    /// Chart file (SVG); a PNG is written beside it and the table as Markdown (`.md`).
    #[arg(long)]
    pub out: PathBuf,
    /// Use every N-th epoch of the request only (quicker runs).
    #[arg(long, default_value_t = 1)]
    pub every: usize,
    /// Tolerance of the reference adaptive run.
    #[arg(long, default_value_t = 1e-6)]
    pub reference_tolerance: f64,
    /// The reference: `adaptive` (the finest adaptive run, checked by the image method on
    /// every --check-every-th epoch) or `image` (the image method at --check-size on every
    /// epoch, the finest adaptive run checked against it) where adaptive cannot be trusted.
    #[arg(long, default_value = "adaptive", value_parser = ["adaptive", "image"])]
    pub reference: String,
    /// Pixels on a side of the image run that checks the reference.
    #[arg(long, default_value_t = 1024)]
    pub check_size: u32,
    /// Samples per pixel side of the image run that checks the reference.
    #[arg(long, default_value_t = 2)]
    pub check_samples: u32,
    /// The check uses every N-th of the (selected) epochs.
    #[arg(long, default_value_t = 8)]
    pub check_every: usize,
    /// Fewer and cheaper settings (a quick look, or CI).
    #[arg(long)]
    pub quick: bool,
    /// Minimum seconds of repeated runs per setting for its timing (best of up to 5).
    #[arg(long, default_value_t = 1.0)]
    pub min_seconds: f64,
}

/// Subsamples the scene's epochs.
fn every_nth(scene: &Scene, n: usize) -> Scene {
    Scene {
        epochs: scene.epochs.iter().step_by(n.max(1)).copied().collect(),
        sky: scene.sky.iter().step_by(n.max(1)).copied().collect(),
        ..scene.clone()
    }
}

/// The reference run, its check and the line that reports their agreement.
struct Reference {
    run: Run,
    /// `method setting` of the reference.
    label: String,
    /// Whether the reference is the image method (`--reference image`).
    image: bool,
    check_line: String,
}

pub fn run(args: &TradeoffArgs) -> anyhow::Result<()> {
    let (scene, name) = load(args)?;
    let reference = reference(args, &scene);
    let rows = sweep(args, &scene, &reference.run);
    let png_path = write_chart(args, &name, &scene, &rows)?;
    let md = table(args, &scene, &reference, &rows);
    let md_path = args.out.with_extension("md");
    std::fs::write(&md_path, &md).with_context(|| format!("cannot write {}", md_path.display()))?;
    println!("{md}");
    println!(
        "chart: {} and {}; table: {}",
        args.out.display(),
        png_path.display(),
        md_path.display()
    );
    Ok(())
}

/// The request's scene with every `--every`-th epoch, and the request's file stem.
fn load(args: &TradeoffArgs) -> anyhow::Result<(Scene, String)> {
    let text = std::fs::read_to_string(&args.request)
        .with_context(|| format!("cannot read {}", args.request.display()))?;
    let full = Scene::from_json(&text, &Limits::unlimited())
        .map_err(|e| anyhow::anyhow!("invalid request {}: {e}", args.request.display()))?;
    let scene = every_nth(&full, args.every);
    let name = args
        .request
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    eprintln!(
        "{name}: {} epochs, {} triangles",
        scene.epochs.len(),
        scene.mesh.triangles.len()
    );
    Ok((scene, name))
}

/// The reference run (the finest adaptive run, or the image method), checked against the
/// other on a subset of the epochs; the agreement printed.
fn reference(args: &TradeoffArgs, scene: &Scene) -> Reference {
    let finest = Setting::Adaptive {
        tolerance: args.reference_tolerance,
    };
    let fine_image = Setting::Image {
        size: args.check_size,
        samples: args.check_samples,
    };
    let image_reference = args.reference == "image";
    let (reference, check_scene, check_setting) = if image_reference {
        // every epoch by image; the finest adaptive run is checked on all of them
        (methods::run(scene, fine_image, 0.0), scene.clone(), finest)
    } else {
        (
            methods::run(scene, finest, 0.0),
            every_nth(scene, args.check_every),
            fine_image,
        )
    };
    let check = methods::run(&check_scene, check_setting, 0.0);
    let step = if image_reference {
        1
    } else {
        args.check_every.max(1)
    };
    let ref_subset: Vec<f64> = reference.irradiance.iter().step_by(step).copied().collect();
    let agreement = methods::errors(&check.irradiance, &ref_subset);
    let reference_label = format!("{} {}", reference.setting.name(), reference.setting.label());
    let check_line = format!(
        "reference: {reference_label}; check: {} {} on {} epochs differs from it by max {:.2e}, RMS {:.2e} relative",
        check.setting.name(),
        check.setting.label(),
        ref_subset.len(),
        agreement.max,
        agreement.rms
    );
    eprintln!("{check_line}");
    Reference {
        run: reference,
        label: reference_label,
        image: image_reference,
        check_line,
    }
}

/// Every setting of the sweep run and its errors against `reference`, each printed.
fn sweep(args: &TradeoffArgs, scene: &Scene, reference: &Run) -> Vec<(Run, methods::Errors)> {
    let mut rows: Vec<(Run, methods::Errors)> = Vec::new();
    for setting in methods::default_sweep(args.quick) {
        let r = methods::run(scene, setting, args.min_seconds);
        let e = methods::errors(&r.irradiance, &reference.irradiance);
        eprintln!(
            "  {:<9} {:<22} max {:.2e}  rms {:.2e}  {:.4} ms/epoch",
            setting.name(),
            setting.label(),
            e.max,
            e.rms,
            r.ms_per_epoch
        );
        rows.push((r, e));
    }
    rows
}

/// The chart, SVG at `--out` and PNG beside it (skipped with a message without a font);
/// the PNG's path.
fn write_chart(
    args: &TradeoffArgs,
    name: &str,
    scene: &Scene,
    rows: &[(Run, methods::Errors)],
) -> anyhow::Result<PathBuf> {
    // One line per method, in the sweep's order.
    let mut lines: Vec<chart::Line> = Vec::new();
    for (r, e) in rows {
        let name = r.setting.name();
        let point = (r.ms_per_epoch, e.max, e.rms);
        match lines.iter_mut().find(|l| l.name == name) {
            Some(l) => l.points.push(point),
            None => lines.push(chart::Line {
                name: name.to_string(),
                points: vec![point],
            }),
        }
    }
    let title = format!(
        "{name}: error against time per epoch ({} epochs, {} triangles)",
        scene.epochs.len(),
        scene.mesh.triangles.len()
    );
    let svg = chart::svg(&title, &lines).map_err(|e| anyhow::anyhow!(e))?;
    std::fs::write(&args.out, svg)
        .with_context(|| format!("cannot write {}", args.out.display()))?;
    let png_path = args.out.with_extension("png");
    match chart::png(&title, &lines) {
        Ok(bytes) => std::fs::write(&png_path, bytes)
            .with_context(|| format!("cannot write {}", png_path.display()))?,
        Err(e) => eprintln!("PNG not written: {e}"),
    }
    Ok(png_path)
}

/// The table as Markdown: what the errors are against, how to regenerate it, a row per
/// setting, and auto's speed-up.
fn table(
    args: &TradeoffArgs,
    scene: &Scene,
    reference: &Reference,
    rows: &[(Run, methods::Errors)],
) -> String {
    let reference_label = &reference.label;
    let check_line = &reference.check_line;
    let image_reference = reference.image;
    let mut md = String::new();
    let _ = writeln!(md, "Error against the reference ({reference_label}) per epoch, relative to the epoch's irradiance");
    let _ = writeln!(
        md,
        "(epochs darker than {:e} of the median epoch: relative to that); time per epoch is",
        methods::ERROR_FLOOR
    );
    let _ = writeln!(
        md,
        "the whole `simulate` call (preparation included) over {} epochs on this machine.",
        scene.epochs.len()
    );
    let _ = writeln!(md, "{check_line}.");
    let _ = writeln!(
        md,
        "Regenerate: `glint tradeoff {} --out {}{}{}{}`.\n",
        args.request.display(),
        args.out.display(),
        if args.every > 1 {
            format!(" --every {}", args.every)
        } else {
            String::new()
        },
        if image_reference {
            " --reference image"
        } else {
            ""
        },
        if args.quick { " --quick" } else { "" }
    );
    let _ = writeln!(
        md,
        "| method | setting | max error | RMS error | ms/epoch | rays/epoch |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    for (r, e) in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {:.2e} | {:.2e} | {:.4} | {:.0} |",
            r.setting.name(),
            r.setting.label(),
            e.max,
            e.rms,
            r.ms_per_epoch,
            r.rays as f64 / scene.epochs.len().max(1) as f64
        );
    }
    if let Some(s) = auto_speedup(rows) {
        let _ = writeln!(md, "\n{s}");
    }
    md
}

/// The speed-up of `auto` over `adaptive` at equal error: for `auto` at tolerance 1e-3
/// (the default), the cheapest adaptive run whose max error is no larger, over auto's time.
fn auto_speedup(rows: &[(Run, methods::Errors)]) -> Option<String> {
    let (auto, auto_e) = rows
        .iter()
        .find(|(r, _)| matches!(r.setting, Setting::Auto { tolerance } if tolerance == 1e-3))?;
    let cheapest = rows
        .iter()
        .filter(|(r, e)| {
            matches!(r.setting, Setting::Adaptive { .. }) && e.max <= auto_e.max.max(1e-15)
        })
        .min_by(|a, b| a.0.ms_per_epoch.total_cmp(&b.0.ms_per_epoch));
    Some(match cheapest {
        Some((a, a_e)) => format!(
            "auto (tolerance 1e-3, {}) vs adaptive at equal max error: adaptive needs {} ({:.2e} max error) at {:.4} ms/epoch, auto {:.4} ms/epoch: speed-up x{:.2}",
            auto.method.split(':').next().unwrap_or(""),
            a.setting.label(),
            a_e.max,
            a.ms_per_epoch,
            auto.ms_per_epoch,
            a.ms_per_epoch / auto.ms_per_epoch
        ),
        None => format!(
            "auto (tolerance 1e-3) reaches max error {:.2e}, which no adaptive setting of the sweep reaches",
            auto_e.max
        ),
    } + &sampler_comparison(rows, auto, auto_e).unwrap_or_default())
}

/// Auto against the ray sampler (adaptive's fallback, everywhere): the cheapest sampled
/// run at least as accurate as auto, or else the most accurate one.
fn sampler_comparison(
    rows: &[(Run, methods::Errors)],
    auto: &Run,
    auto_e: &methods::Errors,
) -> Option<String> {
    let sampled = || {
        rows.iter()
            .filter(|(r, _)| matches!(r.setting, Setting::Sampled { .. }))
    };
    let (s, s_e) = sampled()
        .filter(|(_, e)| e.max <= auto_e.max)
        .min_by(|a, b| a.0.ms_per_epoch.total_cmp(&b.0.ms_per_epoch))
        .or_else(|| sampled().min_by(|a, b| a.1.max.total_cmp(&b.1.max)))?;
    Some(format!(
        "; against the ray sampler: sampled at {} has max error {:.2e} at {:.4} ms/epoch, x{:.1} the time of auto",
        s.setting.label(),
        s_e.max,
        s.ms_per_epoch,
        s.ms_per_epoch / auto.ms_per_epoch
    ))
}
