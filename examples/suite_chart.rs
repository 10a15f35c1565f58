//! Charts the object suite: time per epoch against triangle count, both on log scales, one
//! colour per class; glint a solid line with filled dots, the peer (Mitsuba 3) dashed with
//! open circles. In the house style of `glint tradeoff`'s chart: its palette, axes, legend
//! and note come from `glint::report::chart`.
//!
//! `cargo run --release --example suite_chart -- SUITE.csv [PEER.csv] [--out docs/suite.svg]`
//!
//! SUITE.csv is `--example suite --earthshine off --out` (sunlight alone, what the peer
//! renders; `benches/suite.sh` passes that run's table); PEER.csv the rows that
//! `benches/peer/mitsuba_lightcurve.py --summary` appends. Both are read by their header:
//! `class`, `triangles`, `ms_per_epoch`.

use glint::report::chart::{draw_legend, draw_mesh, draw_note, plain_decimals, PALETTE, SIZE};
use plotters::prelude::*;
use std::collections::BTreeMap;

const CLASSES: [&str; 5] = ["box-wing", "rocket-body", "fragment", "dish-sat", "cubesat"];

/// class → (triangles, ms per epoch), sorted by triangles.
type Points = BTreeMap<String, Vec<(f64, f64)>>;

fn read(path: &str) -> Result<Points, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<&str> = lines
        .next()
        .ok_or(format!("{path}: empty"))?
        .split(',')
        .collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h.trim() == name)
            .ok_or(format!("{path}: no `{name}` column"))
    };
    let (c, t, m) = (col("class")?, col("triangles")?, col("ms_per_epoch")?);
    let mut out = Points::new();
    for (n, line) in lines.enumerate() {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() == 1 && f[0] == header.join(",") {
            continue;
        }
        let num = |i: usize| -> Result<f64, String> {
            f.get(i).and_then(|v| v.parse().ok()).ok_or(format!(
                "{path}:{}: bad number in column {}",
                n + 2,
                i + 1
            ))
        };
        if f.get(c).is_some_and(|v| *v == "class") {
            continue; // a header repeated by appending runs
        }
        out.entry(f[c].to_string())
            .or_default()
            .push((num(t)?, num(m)?));
    }
    for v in out.values_mut() {
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    Ok(out)
}

fn colour(class: &str, others: &mut Vec<String>) -> RGBColor {
    let i = CLASSES.iter().position(|c| *c == class).unwrap_or_else(|| {
        if !others.iter().any(|o| o == class) {
            others.push(class.to_string());
        }
        CLASSES.len() + others.iter().position(|o| o == class).unwrap()
    });
    PALETTE[i % PALETTE.len()]
}

fn draw(glint: &Points, peer: &Points, out: &str) -> Result<(), String> {
    let root = SVGBackend::new(out, SIZE).into_drawing_area();
    let e = |x: DrawingAreaErrorKind<_>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let all = glint.values().chain(peer.values()).flatten();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(x, y) in all.filter(|p| p.0 > 0.0 && p.1 > 0.0) {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if !(x0.is_finite() && y0.is_finite()) {
        return Err("no points to plot".into());
    }
    let font = |px: u32| ("sans-serif", px as f64);
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Time per epoch against mesh size, sunlight alone: glint and Mitsuba 3",
            font(20),
        )
        .margin(14)
        .margin_bottom(30)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d(
            (x0 / 2.0..x1 * 2.0).log_scale(),
            (y0 / 3.0..y1 * 3.0).log_scale(),
        )
        .map_err(e)?;
    draw_mesh(
        &mut chart,
        ("triangles (log)", "time per epoch (ms, log)"),
        &|v| format!("{v:.0}"),
        &plain_decimals,
        1,
    )?;
    let mut others = Vec::new();
    let mut classes: Vec<&String> = glint.keys().chain(peer.keys()).collect();
    classes.sort_by_key(|c| {
        (
            CLASSES.iter().position(|k| k == c).unwrap_or(99),
            c.as_str(),
        )
    });
    classes.dedup();
    for class in classes {
        let col = colour(class, &mut others);
        if let Some(points) = glint.get(class) {
            chart
                .draw_series(LineSeries::new(points.clone(), col.stroke_width(2)))
                .map_err(e)?
                .label(class.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(2))
                });
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 4, col.filled())))
                .map_err(e)?;
        }
        if let Some(points) = peer.get(class) {
            let s = chart
                .draw_series(DashedLineSeries::new(
                    points.clone(),
                    6,
                    4,
                    col.stroke_width(1),
                ))
                .map_err(e)?;
            if !glint.contains_key(class) {
                s.label(class.clone()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(1))
                });
            }
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|&p| Circle::new(p, 4, col.stroke_width(1))),
                )
                .map_err(e)?;
        }
    }
    draw_legend(&mut chart, SeriesLabelPosition::LowerRight, 1)?;
    let note = "solid, filled: glint (whole simulate call per epoch);  dashed, open: Mitsuba 3 (LLVM, direct, 256 px, 16 spp, steady state)";
    draw_note(&root, note, 1)?;
    root.present().map_err(e)?;
    Ok(())
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let out = match args.iter().position(|a| a == "--out") {
        Some(i) => {
            let o = args.get(i + 1).cloned().expect("--out FILE");
            args.drain(i..i + 2);
            o
        }
        None => concat!(env!("CARGO_MANIFEST_DIR"), "/docs/suite.svg").to_string(),
    };
    let (Some(suite), peer) = (args.first(), args.get(1)) else {
        eprintln!("usage: suite_chart SUITE.csv [PEER.csv] [--out docs/suite.svg]");
        std::process::exit(2);
    };
    let run = || -> Result<(), String> {
        let glint = read(suite)?;
        let peer = peer.map(|p| read(p)).transpose()?.unwrap_or_default();
        draw(&glint, &peer, &out)
    };
    if let Err(e) = run() {
        eprintln!("suite_chart: {e}");
        std::process::exit(1);
    }
    eprintln!("wrote {out}");
}
