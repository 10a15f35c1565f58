//! The speed–accuracy chart of `glint tradeoff`: error against time per epoch, both on
//! log scales, one colour per method; solid lines the maximum error over epochs, dashed
//! the RMS. Physics-free: it draws the numbers it is given.
//!
//! SVG through plotters' SVG backend (text as `<text>`, no font needed). PNG through a
//! small RGB canvas implementing plotters' `DrawingBackend`, drawn at twice the size and
//! averaged down (smooth lines), its text rasterised with ab_glyph from a TrueType font
//! found on the system (DejaVu Sans by default, `GLINT_FONT` to choose another). No
//! font is shipped or downloaded: without one the PNG is skipped with an error naming
//! the paths tried, and the SVG is still written.

use ab_glyph::{Font, FontVec, PxScale, ScaleFont};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{BackendColor, BackendCoord, BackendTextStyle, DrawingErrorKind};
use std::ops::Range;

/// One method's points: (ms per epoch, max relative error, RMS relative error).
#[derive(Debug, Clone)]
pub struct Line {
    pub name: String,
    pub points: Vec<(f64, f64, f64)>,
}

/// Errors below this are drawn at it (log axes have no zero); the table has the values.
pub const ERROR_FLOOR: f64 = 1e-7;

/// The house style's colours, one a series (the trade-off chart's methods, the suite
/// chart's classes).
pub const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];

/// Chart size in pixels (PNG at this size; SVG in user units).
pub const SIZE: (u32, u32) = (960, 600);

/// A chart with log scales on both axes (here: time per epoch, ms, and relative error).
pub type LogLogChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;
type Chart<'a, DB> = LogLogChart<'a, DB>;

/// A log axis's labels as plain decimals: 0.01, 0.1, 1, 10.
pub fn plain_decimals(v: &f64) -> String {
    let digits = (-v.log10()).ceil().max(0.0) as usize;
    format!("{v:.digits$}")
}

/// The axes' descriptions (x, y), their labels by `x_label` and `y_label`, and the light
/// grid, in the house style; `k` scales every length.
pub fn draw_mesh<DB: DrawingBackend>(
    chart: &mut LogLogChart<'_, DB>,
    (x_desc, y_desc): (&str, &str),
    x_label: &dyn Fn(&f64) -> String,
    y_label: &dyn Fn(&f64) -> String,
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let font = |px: u32| ("sans-serif", (px * k) as f64);
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(x_label)
        .y_label_formatter(y_label)
        .label_style(font(13))
        .axis_desc_style(font(15))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|x| x.to_string())
}

/// The legend of the series drawn with labels, boxed, at `position`; `k` scales every
/// length.
pub fn draw_legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut LogLogChart<'a, DB>,
    position: SeriesLabelPosition,
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", (14 * k) as f64))
        .draw()
        .map_err(|x| x.to_string())
}

/// A grey note along the bottom of a [`SIZE`] chart (what the lines and marks mean);
/// `k` scales every length.
pub fn draw_note<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    note: &str,
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let kf = k as f64;
    root.draw(&Text::new(
        note,
        ((80.0 * kf) as i32, (SIZE.1 as f64 * kf - 16.0 * kf) as i32),
        ("sans-serif", (12 * k) as f64)
            .into_font()
            .color(&RGBColor(80, 80, 80)),
    ))
    .map_err(|x| x.to_string())
}

/// Draws the chart onto `root`; `k` scales every length (2 for the supersampled PNG).
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    lines: &[Line],
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (x_range, y_range) = ranges(lines)?;
    let mut chart = axes(root, title, x_range, y_range, k)?;
    for (i, line) in lines.iter().enumerate() {
        draw_line(&mut chart, PALETTE[i % PALETTE.len()], line, k)?;
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight, k)?;
    let note = "solid, filled: max error over epochs;  dashed, open: RMS error;  errors below 1e-7 (exact: 0) drawn at 1e-7";
    draw_note(root, note, k)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The axes' ranges: the points' times and errors (errors at least [`ERROR_FLOOR`]) with
/// a margin; an error when there is no point.
fn ranges(lines: &[Line]) -> Result<(Range<f64>, Range<f64>), String> {
    let all = lines.iter().flat_map(|l| l.points.iter());
    let (mut t0, mut t1, mut e0, mut e1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(t, mx, rms) in all {
        t0 = t0.min(t);
        t1 = t1.max(t);
        for v in [mx, rms] {
            let v = v.max(ERROR_FLOOR);
            e0 = e0.min(v);
            e1 = e1.max(v);
        }
    }
    if !(t0.is_finite() && t1 > 0.0 && e0.is_finite()) {
        return Err("no points to plot".into());
    }
    let x_range = (t0 / 2.0).max(1e-6)..(t1 * 2.0);
    let y_range = (e0 / 3.0)..(e1 * 3.0).max(e0 * 10.0);
    Ok((x_range, y_range))
}

/// The caption, the log axes with their labels and the grid.
fn axes<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    title: &str,
    x_range: Range<f64>,
    y_range: Range<f64>,
    k: u32,
) -> Result<Chart<'a, DB>, String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let font = |px: u32| ("sans-serif", (px * k) as f64);
    let mut chart = ChartBuilder::on(root)
        .caption(title, font(20))
        .margin(14 * k)
        .x_label_area_size(48 * k)
        .y_label_area_size(72 * k)
        .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())
        .map_err(e)?;
    let sci = |v: &f64| format!("{v:.0e}");
    draw_mesh(
        &mut chart,
        (
            "time per epoch (ms, log)",
            "relative error of the irradiance (log)",
        ),
        &plain_decimals,
        &sci,
        k,
    )?;
    Ok(chart)
}

/// One method in `colour`: its max errors a solid line with filled dots (and its legend
/// entry), its RMS errors a dashed line with open circles.
fn draw_line<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    colour: RGBColor,
    line: &Line,
    k: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let solid = colour.stroke_width(2 * k);
    let max: Vec<(f64, f64)> = line
        .points
        .iter()
        .map(|p| (p.0, p.1.max(ERROR_FLOOR)))
        .collect();
    let rms: Vec<(f64, f64)> = line
        .points
        .iter()
        .map(|p| (p.0, p.2.max(ERROR_FLOOR)))
        .collect();
    chart
        .draw_series(LineSeries::new(max.clone(), solid))
        .map_err(e)?
        .label(line.name.clone())
        .legend(move |(x, y)| {
            PathElement::new(
                vec![(x, y), (x + 20 * k as i32, y)],
                colour.stroke_width(2 * k),
            )
        });
    chart
        .draw_series(max.iter().map(|&p| Circle::new(p, 4 * k, colour.filled())))
        .map_err(e)?;
    chart
        .draw_series(DashedLineSeries::new(
            rms.clone(),
            6 * k,
            4 * k,
            colour.stroke_width(k),
        ))
        .map_err(e)?;
    chart
        .draw_series(
            rms.iter()
                .map(|&p| Circle::new(p, 3 * k, colour.stroke_width(k))),
        )
        .map_err(e)?;
    Ok(())
}

/// The chart as SVG text.
pub fn svg(title: &str, lines: &[Line]) -> Result<String, String> {
    svg_with(SIZE, |root, k| draw(root, title, lines, k))
}

/// Any chart as SVG text, `size` user units: `draw` is called with the SVG drawing area
/// and the scale 1 (the counterpart of [`png_with`]).
pub(crate) fn svg_with(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>, u32) -> Result<(), String>,
) -> Result<String, String> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        draw(&root, 1)?;
    }
    Ok(out)
}

/// The chart as PNG bytes.
pub fn png(title: &str, lines: &[Line]) -> Result<Vec<u8>, String> {
    png_with(SIZE, |root, k| draw(root, title, lines, k))
}

use image::ImageEncoder;

/// Any chart as PNG bytes, `size` pixels: `draw` is called with a canvas of twice that
/// size and the scale 2 (lengths and fonts are to be multiplied by it), and the result
/// averaged down.
pub(crate) fn png_with(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<&mut Canvas, Shift>, u32) -> Result<(), String>,
) -> Result<Vec<u8>, String> {
    let font = load_font()?;
    let k = 2;
    let mut canvas = Canvas::new(size.0 * k, size.1 * k, font);
    {
        let root = (&mut canvas).into_drawing_area();
        draw(&root, k)?;
    }
    let small = canvas.downsample(k);
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(&small, size.0, size.1, image::ExtendedColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// Where to look for a TrueType font (Debian/Ubuntu `fonts-dejavu-core`, Fedora, Arch,
/// macOS), after `GLINT_FONT`.
const FONT_PATHS: &[&str] = &[
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
    "/Library/Fonts/Arial.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
];

fn load_font() -> Result<FontVec, String> {
    let env = std::env::var("GLINT_FONT").ok();
    let paths: Vec<&str> = env
        .as_deref()
        .into_iter()
        .chain(FONT_PATHS.iter().copied())
        .collect();
    for p in &paths {
        if let Ok(bytes) = std::fs::read(p) {
            return FontVec::try_from_vec(bytes)
                .map_err(|e| format!("{p}: not a usable font: {e}"));
        }
    }
    Err(format!(
        "no TrueType font found for the PNG's text (tried {}); set GLINT_FONT or install fonts-dejavu-core",
        paths.join(", ")
    ))
}

/// An RGB image that plotters draws into; text through ab_glyph.
pub(crate) struct Canvas {
    w: u32,
    h: u32,
    rgb: Vec<f32>,
    font: FontVec,
}

impl Canvas {
    fn new(w: u32, h: u32, font: FontVec) -> Canvas {
        Canvas {
            w,
            h,
            rgb: vec![1.0; (w * h * 3) as usize],
            font,
        }
    }

    fn blend(&mut self, x: i32, y: i32, c: BackendColor, coverage: f64) {
        if x < 0 || y < 0 || x >= self.w as i32 || y >= self.h as i32 {
            return;
        }
        let a = (c.alpha * coverage).clamp(0.0, 1.0) as f32;
        let i = ((y as u32 * self.w + x as u32) * 3) as usize;
        for (j, ch) in [c.rgb.0, c.rgb.1, c.rgb.2].into_iter().enumerate() {
            let v = ch as f32 / 255.0;
            self.rgb[i + j] = self.rgb[i + j] * (1.0 - a) + v * a;
        }
    }

    /// Averages k × k blocks into 8-bit RGB.
    fn downsample(&self, k: u32) -> Vec<u8> {
        let (w, h) = (self.w / k, self.h / k);
        let mut out = vec![0u8; (w * h * 3) as usize];
        for y in 0..h {
            for x in 0..w {
                for ch in 0..3 {
                    let mut s = 0.0;
                    for dy in 0..k {
                        for dx in 0..k {
                            s += self.rgb[(((y * k + dy) * self.w + x * k + dx) * 3 + ch) as usize];
                        }
                    }
                    out[((y * w + x) * 3 + ch) as usize] =
                        (s / (k * k) as f32 * 255.0).round().clamp(0.0, 255.0) as u8;
                }
            }
        }
        out
    }

    /// Width, ascent and descent (px) of `text` at `size` px.
    fn measure(&self, text: &str, size: f64) -> (f32, f32, f32) {
        let f = self.font.as_scaled(PxScale::from(size as f32));
        let width = text.chars().map(|c| f.h_advance(f.glyph_id(c))).sum();
        (width, f.ascent(), f.descent())
    }
}

impl DrawingBackend for &mut Canvas {
    type ErrorType = std::convert::Infallible;

    fn get_size(&self) -> (u32, u32) {
        (self.w, self.h)
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        Ok(())
    }

    fn draw_pixel(
        &mut self,
        p: BackendCoord,
        c: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.blend(p.0, p.1, c, 1.0);
        Ok(())
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let size = style.size();
        let (width, ascent, descent) = self.measure(text, size);
        let height = ascent - descent;
        let dx = match style.anchor().h_pos {
            HPos::Left => 0.0,
            HPos::Right => -width,
            HPos::Center => -width / 2.0,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0.0,
            VPos::Center => -height / 2.0,
            VPos::Bottom => -height,
        };
        let trans = style.transform();
        let colour = style.color();
        let scale = PxScale::from(size as f32);
        let mut caret = 0.0f32;
        let mut coverage: Vec<(i32, i32, f32)> = Vec::new();
        {
            let f = self.font.as_scaled(scale);
            for ch in text.chars() {
                let id = f.glyph_id(ch);
                let glyph =
                    id.with_scale_and_position(scale, ab_glyph::point(caret + dx, ascent + dy));
                caret += f.h_advance(id);
                if let Some(outline) = self.font.outline_glyph(glyph) {
                    let b = outline.px_bounds();
                    outline.draw(|gx, gy, c| {
                        coverage.push((b.min.x as i32 + gx as i32, b.min.y as i32 + gy as i32, c))
                    });
                }
            }
        }
        for (x, y, c) in coverage {
            let (tx, ty) = trans.transform(x, y);
            self.blend(pos.0 + tx, pos.1 + ty, colour, c as f64);
        }
        Ok(())
    }

    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let (w, a, d) = self.measure(text, style.size());
        Ok((w.ceil() as u32, (a - d).ceil() as u32))
    }
}
