//! The fits' plots: measured BRDF samples with the fitted model's curves, one colour per
//! incidence angle (the paper's Fig. 2), and an observed light curve with the fitted one
//! and the residuals. Physics-free: they draw the numbers they are given. SVG through
//! plotters' SVG backend; PNG through the trade-off chart's canvas ([`super::chart`]).

use plotters::coord::Shift;
use plotters::prelude::*;

/// One incidence angle's samples and model curve, against the signed reflection angle
/// (degrees; + forward of the plane of incidence, − backward).
#[derive(Debug, Clone)]
pub struct Incidence {
    pub theta_i_deg: f64,
    /// In-plane samples: (signed θr, BRDF sr⁻¹).
    pub points: Vec<(f64, f64)>,
    /// Samples off the plane of incidence, at their θr signed by the side of the plane.
    pub off_plane: Vec<(f64, f64)>,
    /// The model in the plane of incidence.
    pub curve: Vec<(f64, f64)>,
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];

/// Plot size (SVG user units, PNG pixels).
pub const SIZE: (u32, u32) = (900, 560);

fn draw_brdf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    groups: &[Incidence],
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let measured = groups
        .iter()
        .flat_map(|g| g.points.iter().chain(&g.off_plane))
        .map(|p| p.1);
    let curves = groups.iter().flat_map(|g| g.curve.iter()).map(|p| p.1);
    let top = measured
        .clone()
        .chain(curves)
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    let low = measured.filter(|&v| v > 0.0).fold(f64::INFINITY, f64::min);
    if top <= 0.0 || top.is_nan() {
        return Err("nothing positive to plot".into());
    }
    // six decades at most below the top, and below the smallest sample
    let floor = (low.min(top) / 3.0).max(top * 1e-7);
    let font = |px: u32| ("sans-serif", (px * k) as f64);
    let mut chart = ChartBuilder::on(root)
        .caption(title, font(18))
        .margin(12 * k)
        .x_label_area_size(44 * k)
        .y_label_area_size(70 * k)
        .build_cartesian_2d(-90.0..90.0, (floor..top * 3.0).log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("reflection angle θr (°): + forward (φ = 180°), − backward (φ = 0°)")
        .y_desc("BRDF (sr⁻¹, log)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(font(13))
        .axis_desc_style(font(14))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(e)?;
    for (i, g) in groups.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        let curve: Vec<(f64, f64)> = g.curve.iter().map(|&(x, y)| (x, y.max(floor))).collect();
        chart
            .draw_series(LineSeries::new(curve, colour.stroke_width(2 * k)))
            .map_err(e)?
            .label(format!("θi = {}°", g.theta_i_deg))
            .legend(move |(x, y)| {
                PathElement::new(
                    vec![(x, y), (x + 20 * k as i32, y)],
                    colour.stroke_width(2 * k),
                )
            });
        chart
            .draw_series(
                g.points
                    .iter()
                    .filter(|p| p.1 > 0.0)
                    .map(|&p| Circle::new(p, 3 * k, colour.filled())),
            )
            .map_err(e)?;
        chart
            .draw_series(
                g.off_plane
                    .iter()
                    .filter(|p| p.1 > 0.0)
                    .map(|&p| Circle::new(p, 3 * k, colour.stroke_width(k))),
            )
            .map_err(e)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(font(13))
        .draw()
        .map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The BRDF fit plot as SVG text: filled points in the plane of incidence, open points off
/// it, lines the fitted model in the plane.
pub fn brdf_svg(title: &str, groups: &[Incidence]) -> Result<String, String> {
    super::chart::svg_with(SIZE, |root, k| draw_brdf(root, title, groups, k))
}

/// [`brdf_svg`] as PNG bytes (needs a system TrueType font, as the trade-off chart).
pub fn brdf_png(title: &str, groups: &[Incidence]) -> Result<Vec<u8>, String> {
    super::chart::png_with(SIZE, |root, k| draw_brdf(root, title, groups, k))
}

/// An observed light curve and the fitted one.
#[derive(Debug, Clone)]
pub struct LightcurvePlot {
    /// (t s, magnitude, 1σ mag) of each observation.
    pub observed: Vec<(f64, f64, f64)>,
    /// (t s, fitted magnitude; `None` where the model has no light).
    pub fitted: Vec<(f64, Option<f64>)>,
}

/// The observations' colour (points and error bars).
const OBSERVED: RGBColor = RGBColor(40, 40, 40);

/// Draws the light-curve plot onto `root`: the magnitudes with the fitted curve above,
/// the residuals below; `k` scales every length.
fn draw_lightcurve<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    data: &LightcurvePlot,
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    if data.observed.is_empty() {
        return Err("no observations to plot".into());
    }
    let times = time_range(data);
    let residuals = residuals(data);
    let (upper, lower) = root.split_vertically((SIZE.1 * k) * 68 / 100);
    draw_magnitudes(&upper, title, data, times, k)?;
    draw_residuals(&lower, &residuals, times, k)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The observations' times, s, widened by a second each way when there is one instant.
fn time_range(data: &LightcurvePlot) -> (f64, f64) {
    let (t0, t1) = min_max(data.observed.iter().map(|o| o.0));
    if t1 > t0 {
        (t0, t1)
    } else {
        (t0 - 1.0, t1 + 1.0)
    }
}

/// (t s, observed − fitted mag, 1σ mag) where the model has light.
fn residuals(data: &LightcurvePlot) -> Vec<(f64, f64, f64)> {
    data.observed
        .iter()
        .zip(&data.fitted)
        .filter_map(|(o, f)| f.1.map(|m| (o.0, o.1 - m, o.2)))
        .collect()
}

/// The fitted curve as runs of consecutive points with light (a gap where it has none).
fn fitted_segments(fitted: &[(f64, Option<f64>)]) -> Vec<Vec<(f64, f64)>> {
    let mut segments: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for &(t, m) in fitted {
        match m {
            Some(m) => segments.last_mut().expect("one segment").push((t, m)),
            None => segments.push(Vec::new()),
        }
    }
    segments.retain(|s| !s.is_empty());
    segments
}

/// The upper panel: the observations with their error bars and the fitted curve,
/// magnitudes bright up, with the caption and the legend.
fn draw_magnitudes<DB: DrawingBackend>(
    upper: &DrawingArea<DB, Shift>,
    title: &str,
    data: &LightcurvePlot,
    (t0, t1): (f64, f64),
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let font = |px: u32| ("sans-serif", (px * k) as f64);
    let mags = data
        .observed
        .iter()
        .flat_map(|o| [o.1 - o.2, o.1 + o.2])
        .chain(data.fitted.iter().filter_map(|f| f.1));
    let (m0, m1) = min_max(mags);
    let pad = ((m1 - m0) * 0.05).max(0.05);
    let mut top = ChartBuilder::on(upper)
        .caption(title, font(18))
        .margin(12 * k)
        .x_label_area_size(20 * k)
        .y_label_area_size(70 * k)
        .build_cartesian_2d(t0..t1, (m1 + pad)..(m0 - pad))
        .map_err(e)?;
    top.configure_mesh()
        .y_desc("magnitude")
        .label_style(font(13))
        .axis_desc_style(font(14))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(e)?;
    let obs = OBSERVED;
    let fit = PALETTE[1];
    top.draw_series(data.observed.iter().map(|&(t, m, s)| {
        PathElement::new(vec![(t, m - s), (t, m + s)], obs.mix(0.5).stroke_width(k))
    }))
    .map_err(e)?;
    top.draw_series(
        data.observed
            .iter()
            .map(|&(t, m, _)| Circle::new((t, m), 2 * k, obs.filled())),
    )
    .map_err(e)?
    .label("observed (±1σ)")
    .legend(move |(x, y)| Circle::new((x + 10 * k as i32, y), 3 * k, obs.filled()));
    let mut labelled = false;
    for s in fitted_segments(&data.fitted) {
        let series = top
            .draw_series(LineSeries::new(s, fit.stroke_width(2 * k)))
            .map_err(e)?;
        if !labelled {
            series.label("fitted").legend(move |(x, y)| {
                PathElement::new(
                    vec![(x, y), (x + 20 * k as i32, y)],
                    fit.stroke_width(2 * k),
                )
            });
            labelled = true;
        }
    }
    top.configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(font(13))
        .draw()
        .map_err(e)?;
    Ok(())
}

/// The lower panel: the residuals with their error bars about a zero line, symmetric
/// about it and at least ±0.05 mag.
fn draw_residuals<DB: DrawingBackend>(
    lower: &DrawingArea<DB, Shift>,
    residuals: &[(f64, f64, f64)],
    (t0, t1): (f64, f64),
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let font = |px: u32| ("sans-serif", (px * k) as f64);
    let rmax = residuals
        .iter()
        .map(|r| r.1.abs() + r.2)
        .fold(0.05f64, f64::max)
        * 1.1;
    let mut bottom = ChartBuilder::on(lower)
        .margin(12 * k)
        .x_label_area_size(40 * k)
        .y_label_area_size(70 * k)
        .build_cartesian_2d(t0..t1, rmax..-rmax)
        .map_err(e)?;
    bottom
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc("observed − fitted")
        .label_style(font(13))
        .axis_desc_style(font(14))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(e)?;
    let obs = OBSERVED;
    let fit = PALETTE[1];
    bottom
        .draw_series(LineSeries::new(
            vec![(t0, 0.0), (t1, 0.0)],
            fit.stroke_width(k),
        ))
        .map_err(e)?;
    bottom
        .draw_series(residuals.iter().map(|&(t, r, s)| {
            PathElement::new(vec![(t, r - s), (t, r + s)], obs.mix(0.5).stroke_width(k))
        }))
        .map_err(e)?;
    bottom
        .draw_series(
            residuals
                .iter()
                .map(|&(t, r, _)| Circle::new((t, r), 2 * k, obs.filled())),
        )
        .map_err(e)?;
    Ok(())
}

/// The light-curve fit plot as SVG text: magnitudes (bright up) with the fitted curve,
/// and the residuals below.
pub fn lightcurve_svg(title: &str, data: &LightcurvePlot) -> Result<String, String> {
    super::chart::svg_with(SIZE, |root, k| draw_lightcurve(root, title, data, k))
}

/// [`lightcurve_svg`] as PNG bytes.
pub fn lightcurve_png(title: &str, data: &LightcurvePlot) -> Result<Vec<u8>, String> {
    super::chart::png_with(SIZE, |root, k| draw_lightcurve(root, title, data, k))
}

fn min_max(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}
