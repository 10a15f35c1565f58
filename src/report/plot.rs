//! Magnitude against time as an SVG plot (plotters; SVG text needs no font files).

use crate::scene::Response;
use plotters::prelude::*;

/// An SVG plot of apparent magnitude (axis inverted: brighter is up) against epoch time.
/// Epochs with no light at all are left out of the line; an error only if no epoch has light.
pub fn magnitude_svg(response: &Response, title: &str) -> Result<String, String> {
    let points: Vec<(f64, f64)> = response
        .epochs
        .iter()
        .filter_map(|e| e.magnitude.map(|m| (e.t, m)))
        .collect();
    if points.is_empty() {
        return Err("no epoch has any light: nothing to plot".into());
    }
    let (t0, t1) = min_max(points.iter().map(|p| p.0));
    let (m0, m1) = min_max(points.iter().map(|p| p.1));
    let pad = ((m1 - m0) * 0.05).max(0.05);
    let (t0, t1) = if t1 > t0 {
        (t0, t1)
    } else {
        (t0 - 1.0, t1 + 1.0)
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 500)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let caption = format!(
            "{title} — {} epochs, {}",
            response.epochs.len(),
            response.summary.method.split(':').next().unwrap_or("")
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            // magnitudes: smaller is brighter, so the axis runs from faint (bottom) to bright (top)
            .build_cartesian_2d(t0..t1, (m1 + pad)..(m0 - pad))
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("t (s)")
            .y_desc("apparent magnitude")
            .draw()
            .map_err(|e| e.to_string())?;
        // Break the line where the object is dark so a gap is not drawn as a ramp.
        let mut segment: Vec<(f64, f64)> = Vec::new();
        let mut segments = Vec::new();
        for e in &response.epochs {
            match e.magnitude {
                Some(m) => segment.push((e.t, m)),
                None if !segment.is_empty() => segments.push(std::mem::take(&mut segment)),
                None => {}
            }
        }
        if !segment.is_empty() {
            segments.push(segment);
        }
        for s in segments {
            chart
                .draw_series(LineSeries::new(s, BLUE.stroke_width(2)))
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}
