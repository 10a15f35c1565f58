//! CCSDS Orbit Ephemeris Messages (OEM, CCSDS 502.0-B), KVN text: states interpolated
//! by Lagrange polynomials.
//!
//! Data lines are `epoch x y z vx vy vz` (km, km/s; accelerations after them are
//! ignored), centred on the Earth. The frame must be TEME (glint's inertial frame):
//! EME2000, GCRF and ICRF differ from it by precession and nutation (~0.36° in 2026, some
//! 40 km at GEO) and are refused rather than silently taken for it; Earth-fixed frames
//! too. Position and velocity are each interpolated by the Lagrange polynomial through
//! the `INTERPOLATION_DEGREE` + 1 lines nearest the instant (default degree 7; a segment
//! with fewer lines uses them all). `TIME_SYSTEM` may be UTC, TAI, GPS or TT (fixed
//! offsets from UTC since 2017). Versions 1, 2 and 3.

use super::time::{parse_utc, UtcTime};
use glam::DVec3;

/// Lagrange degree when the message gives none.
pub const DEFAULT_DEGREE: usize = 7;

/// One segment: its states at increasing instants and the interpolation degree.
#[derive(Debug, Clone)]
struct Segment {
    /// (instant, TEME position m, TEME velocity m/s)
    states: Vec<(UtcTime, DVec3, DVec3)>,
    degree: usize,
}

/// A parsed message.
#[derive(Debug, Clone)]
pub struct Ephemeris {
    segments: Vec<Segment>,
}

fn line_err<T>(number: usize, message: impl Into<String>) -> Result<T, String> {
    Err(format!("line {number}: {}", message.into()))
}

/// A segment's metadata: the offset of its time system from UTC (s) and its degree.
fn meta(keys: &[(usize, String, String)], end: usize) -> Result<(f64, usize), String> {
    let get = |k: &str| keys.iter().find(|(_, key, _)| key == k);
    match get("CENTER_NAME") {
        Some((_, _, v)) if v.eq_ignore_ascii_case("EARTH") => {}
        Some((n, _, v)) => return line_err(*n, format!("CENTER_NAME = {v}: only EARTH")),
        None => return line_err(end, "the segment has no CENTER_NAME"),
    }
    match get("REF_FRAME") {
        Some((_, _, v)) if v == "TEME" => {}
        Some((n, _, v)) => {
            return line_err(
                *n,
                format!(
                    "REF_FRAME = {v} is not supported: give states in TEME (EME2000, GCRF and \
                     ICRF differ from it by precession and nutation)"
                ),
            )
        }
        None => return line_err(end, "the segment has no REF_FRAME"),
    }
    let offset = match get("TIME_SYSTEM") {
        None => 0.0,
        Some((n, _, v)) => match v.as_str() {
            "UTC" => 0.0,
            "TAI" => 37.0,
            "GPS" => 18.0,
            "TT" => 69.184,
            other => return line_err(*n, format!("TIME_SYSTEM = {other}: UTC, TAI, GPS or TT")),
        },
    };
    let degree = match get("INTERPOLATION_DEGREE") {
        None => DEFAULT_DEGREE,
        Some((n, _, v)) => match v.parse::<usize>() {
            Ok(d) if (1..=15).contains(&d) => d,
            _ => return line_err(*n, format!("INTERPOLATION_DEGREE = {v}: 1 to 15")),
        },
    };
    if let Some((n, _, v)) = get("INTERPOLATION") {
        if !v.eq_ignore_ascii_case("LAGRANGE") && !v.eq_ignore_ascii_case("HERMITE") {
            return line_err(
                *n,
                format!("INTERPOLATION = {v}: LAGRANGE (HERMITE is read as it)"),
            );
        }
    }
    Ok((offset, degree))
}

fn state(number: usize, line: &str, offset: f64) -> Result<(UtcTime, DVec3, DVec3), String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    if words.len() != 7 && words.len() != 10 {
        return line_err(number, "a state line is an epoch and 6 (or 9) numbers");
    }
    let t = parse_utc(words[0]).map_err(|m| format!("line {number}: {m}"))?;
    let mut x = [0.0; 6];
    for (k, w) in words[1..7].iter().enumerate() {
        x[k] = w
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && v.abs() < 1e9)
            .ok_or_else(|| format!("line {number}: `{w}` is not a finite number (km, km/s)"))?;
    }
    let r = DVec3::new(x[0], x[1], x[2]) * 1e3;
    let v = DVec3::new(x[3], x[4], x[5]) * 1e3;
    Ok((t.plus(-offset), r, v))
}

/// Parses OEM KVN text; errors name the line.
pub fn parse(text: &str) -> Result<Ephemeris, String> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim()));
    match lines.find(|(_, l)| !l.is_empty() && !l.starts_with("COMMENT")) {
        Some((_, l)) if l.starts_with("CCSDS_OEM_VERS") => {}
        Some((n, _)) => return line_err(n, "an OEM starts with CCSDS_OEM_VERS"),
        None => return Err("the message is empty".into()),
    }
    let mut segments: Vec<Segment> = Vec::new();
    let mut keys: Option<Vec<(usize, String, String)>> = None;
    let mut reading: Option<(f64, usize)> = None;
    let mut skipping = false;
    for (n, line) in lines {
        if line.is_empty() || line.starts_with("COMMENT") {
            continue;
        }
        match line {
            "META_START" => keys = Some(Vec::new()),
            "META_STOP" => {
                let k = keys
                    .take()
                    .ok_or_else(|| format!("line {n}: META_STOP without META_START"))?;
                reading = Some(meta(&k, n)?);
                segments.push(Segment {
                    states: Vec::new(),
                    degree: reading.map_or(DEFAULT_DEGREE, |r| r.1),
                });
            }
            "COVARIANCE_START" => skipping = true,
            "COVARIANCE_STOP" => skipping = false,
            _ if skipping => {}
            _ => {
                if let Some(k) = keys.as_mut() {
                    if let Some((key, v)) = line.split_once('=') {
                        k.push((n, key.trim().to_string(), v.trim().to_string()));
                    }
                } else if let (Some((offset, _)), false) = (reading, line.contains('=')) {
                    let s = state(n, line, offset)?;
                    let seg = segments.last_mut().expect("a segment after META_STOP");
                    if let Some(prev) = seg.states.last() {
                        if s.0.seconds_since(prev.0) <= 0.0 {
                            return line_err(n, "epochs must increase from line to line");
                        }
                    }
                    seg.states.push(s);
                }
            }
        }
    }
    segments.retain(|s| !s.states.is_empty());
    if segments.is_empty() {
        return Err("the message has no state lines".into());
    }
    Ok(Ephemeris { segments })
}

/// The Lagrange polynomial through (x_i, y_i) at x.
fn lagrange(xs: &[f64], ys: &[DVec3], x: f64) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for (i, (&xi, &yi)) in xs.iter().zip(ys).enumerate() {
        let mut w = 1.0;
        for (j, &xj) in xs.iter().enumerate() {
            if j != i {
                w *= (x - xj) / (xi - xj);
            }
        }
        sum += yi * w;
    }
    sum
}

impl Ephemeris {
    /// The first and last instants the states cover.
    pub fn span(&self) -> (UtcTime, UtcTime) {
        let first = self.segments[0].states[0].0;
        let last = &self.segments[self.segments.len() - 1].states;
        (first, last[last.len() - 1].0)
    }

    /// TEME position (m) and velocity (m/s) at `t`; an error outside every segment.
    pub fn teme_at(&self, t: UtcTime) -> Result<(DVec3, DVec3), String> {
        let seg = self
            .segments
            .iter()
            .find(|s| {
                t.seconds_since(s.states[0].0) >= 0.0
                    && t.seconds_since(s.states[s.states.len() - 1].0) <= 0.0
            })
            .ok_or_else(|| "the time lies outside the ephemeris".to_string())?;
        let n = seg.states.len();
        let k = (seg.degree + 1).min(n);
        // the k lines nearest t: a window centred on it, kept inside the segment
        let after = seg.states.partition_point(|s| t.seconds_since(s.0) > 0.0);
        let first = after.saturating_sub(k / 2).min(n - k);
        let pts = &seg.states[first..first + k];
        let t0 = pts[0].0;
        let xs: Vec<f64> = pts.iter().map(|s| s.0.seconds_since(t0)).collect();
        let rs: Vec<DVec3> = pts.iter().map(|s| s.1).collect();
        let vs: Vec<DVec3> = pts.iter().map(|s| s.2).collect();
        let x = t.seconds_since(t0);
        Ok((lagrange(&xs, &rs, x), lagrange(&xs, &vs, x)))
    }
}
