//! Times glint on the object suite: each built-in class at each level of detail, on its
//! tumbling example request, whole `simulate` calls (preparation included).
//!
//! `cargo run --release --example suite -- [--class NAME]... [--detail LEVEL]... [--epochs N]
//! [--repeat K] [--threads T] [--earthshine MODEL] [--out results.csv]`
//!
//! Classes: box-wing (`scenes/box-wing-tumbling.json`), rocket-body, fragment, dish-sat,
//! cubesat (`scenes/<class>.json`); details: coarse, medium, fine (all by default; `as-is` leaves the mesh alone). For
//! each pair the request's `object.mesh.detail` is set before it is parsed; `--epochs N`
//! keeps its first N epochs. A request that is missing or rejected is reported and its row
//! skipped. Prints class, detail, triangles, faces, epochs, best and median total ms over
//! `--repeat` runs, ms/epoch and epochs/s (of the best run), rays; `--out` writes the
//! same as CSV (read by `--example suite_chart`). Built with `--features counters`, it
//! also prints what each run's directions took (folds, lines, dirty patches, rays and the
//! nodes they visit) and the time of each step of a direction, an epoch and a preparation
//! (`glint::integrate::silhouettes::tally`); take those with `--threads 1 --repeat 1`.

use clap::Parser;
use glint::integrate::silhouettes::tally;
use glint::scene::{Limits, Scene};
use std::time::Instant;

const CLASSES: [(&str, &str); 5] = [
    ("box-wing", "box-wing-tumbling"),
    ("rocket-body", "rocket-body"),
    ("fragment", "fragment"),
    ("dish-sat", "dish-sat"),
    ("cubesat", "cubesat"),
];
const DETAILS: [&str; 3] = ["coarse", "medium", "fine"];

#[derive(Parser)]
struct Args {
    /// Object class (repeat for several; default all).
    #[arg(long = "class")]
    classes: Vec<String>,
    /// Level of detail: coarse, medium or fine (repeat for several; default all); `as-is`
    /// leaves the request's mesh as it is.
    #[arg(long = "detail")]
    details: Vec<String>,
    /// Only the first N epochs of each request (default all).
    #[arg(long)]
    epochs: Option<usize>,
    /// Runs per row; the best and the median are reported.
    #[arg(long, default_value_t = 3)]
    repeat: usize,
    /// Worker threads (default: rayon's, one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// Directory of the requests.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes"))]
    scenes: std::path::PathBuf,
    /// Write the table as CSV.
    #[arg(long)]
    out: Option<std::path::PathBuf>,
    /// Integration method for every request (default: the request's own, else auto).
    #[arg(long)]
    method: Option<String>,
    /// Earthshine model for every request: `off`, `seed` or `sphere` (default: the
    /// request's own). `off` computes what the peer renders: sunlight alone.
    #[arg(long)]
    earthshine: Option<String>,
    /// Write each row's light curve (t, irradiance, sun, earthshine in W/m²) to
    /// DIR/CLASS-DETAIL.csv, to compare methods or builds epoch by epoch.
    #[arg(long, value_name = "DIR")]
    curves: Option<std::path::PathBuf>,
}

struct Row {
    class: String,
    detail: String,
    triangles: usize,
    faces: usize,
    epochs: usize,
    load_ms: f64,
    best_ms: f64,
    median_ms: f64,
    rays: u64,
}

/// The request for `class` at `detail`, parsed and validated; the error says why not.
fn load(args: &Args, request: &str, detail: &str) -> Result<Scene, String> {
    let path = args.scenes.join(format!("{request}.json"));
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut json: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let mesh = json
        .pointer_mut("/object/mesh")
        .and_then(|m| m.as_object_mut())
        .ok_or_else(|| format!("{}: no object.mesh", path.display()))?;
    if detail != "as-is" {
        mesh.insert("detail".into(), detail.into());
    }
    if let Some(m) = &args.method {
        json["method"] = m.as_str().into();
    }
    if let Some(e) = &args.earthshine {
        json["illumination"]["earthshine"] = e.as_str().into();
    }
    if let (Some(n), Some(epochs)) = (args.epochs, json.get_mut("epochs")) {
        if let Some(list) = epochs.as_array_mut() {
            list.truncate(n);
        }
    }
    Scene::from_json(&json.to_string(), &Limits::unlimited())
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// One light curve as CSV, full precision.
fn write_curve(path: &std::path::Path, epochs: &[glint::scene::response::EpochResult]) {
    let mut csv = String::from("t,irradiance_w_m2,sun_w_m2,earthshine_w_m2\n");
    for e in epochs {
        csv += &format!(
            "{},{:e},{:e},{:e}\n",
            e.t, e.irradiance_w_m2, e.sun_w_m2, e.earthshine_w_m2
        );
    }
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).expect("curves directory");
    }
    std::fs::write(path, csv).expect("curve written");
}

fn main() {
    let args = Args::parse();
    if let Some(t) = args.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build_global()
            .expect("thread pool");
    }
    let classes: Vec<(&str, &str)> = if args.classes.is_empty() {
        CLASSES.to_vec()
    } else {
        args.classes
            .iter()
            .map(|c| {
                *CLASSES.iter().find(|(n, _)| n == c).unwrap_or_else(|| {
                    eprintln!("unknown class `{c}`; classes: box-wing, rocket-body, fragment, dish-sat, cubesat");
                    std::process::exit(2)
                })
            })
            .collect()
    };
    let details: Vec<&str> = if args.details.is_empty() {
        DETAILS.to_vec()
    } else {
        args.details.iter().map(String::as_str).collect()
    };
    let repeat = args.repeat.max(1);

    let mut rows = Vec::new();
    for &(class, request) in &classes {
        for &detail in &details {
            let t0 = Instant::now();
            let scene = match load(&args, request, detail) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("skipped {class} {detail}: {e}");
                    continue;
                }
            };
            let load_ms = t0.elapsed().as_secs_f64() * 1e3;
            let mut times = Vec::with_capacity(repeat);
            let mut summary = None;
            tally::reset();
            for _ in 0..repeat {
                let t = Instant::now();
                let r = glint::simulate(&scene);
                times.push(t.elapsed().as_secs_f64() * 1e3);
                if let Some(dir) = &args.curves {
                    write_curve(&dir.join(format!("{class}-{detail}.csv")), &r.epochs);
                }
                summary = Some(r.summary);
            }
            let s = summary.expect("at least one run");
            times.sort_by(f64::total_cmp);
            let row = Row {
                class: class.into(),
                detail: detail.into(),
                triangles: s.triangles,
                faces: s.faces,
                epochs: s.epochs,
                load_ms,
                best_ms: times[0],
                median_ms: times[times.len() / 2],
                rays: s.rays,
            };
            eprintln!(
                "{class} {detail}: {} triangles, {} epochs, best {:.1} ms",
                row.triangles, row.epochs, row.best_ms
            );
            if let Some(counts) = tally::report() {
                eprintln!("{counts}");
            }
            rows.push(row);
        }
    }

    println!(
        "{:<12} {:<7} {:>9} {:>8} {:>6} {:>9} {:>10} {:>10} {:>9} {:>9} {:>12}",
        "class",
        "detail",
        "triangles",
        "faces",
        "epochs",
        "load ms",
        "total ms",
        "median ms",
        "ms/epoch",
        "epochs/s",
        "rays"
    );
    for r in &rows {
        let per = r.best_ms / r.epochs.max(1) as f64;
        println!(
            "{:<12} {:<7} {:>9} {:>8} {:>6} {:>9.1} {:>10.2} {:>10.2} {:>9.4} {:>9.0} {:>12}",
            r.class,
            r.detail,
            r.triangles,
            r.faces,
            r.epochs,
            r.load_ms,
            r.best_ms,
            r.median_ms,
            per,
            1e3 / per,
            r.rays
        );
    }
    if let Some(path) = &args.out {
        let mut csv = String::from(
            "class,detail,triangles,faces,epochs,load_ms,total_ms,median_ms,ms_per_epoch,epochs_per_s,rays,repeat\n",
        );
        for r in &rows {
            let per = r.best_ms / r.epochs.max(1) as f64;
            csv += &format!(
                "{},{},{},{},{},{:.3},{:.3},{:.3},{:.6},{:.2},{},{}\n",
                r.class,
                r.detail,
                r.triangles,
                r.faces,
                r.epochs,
                r.load_ms,
                r.best_ms,
                r.median_ms,
                per,
                1e3 / per,
                r.rays,
                repeat
            );
        }
        std::fs::write(path, csv).expect("write the CSV");
        eprintln!("wrote {}", path.display());
    }
}
