//! CCSDS Attitude Ephemeris Messages (AEM, CCSDS 504.0-B), KVN text, quaternions only.
//!
//! Versions 1 and 2. A v1 message says where the scalar is (`QUATERNION_TYPE = FIRST`:
//! `epoch QC Q1 Q2 Q3`; `LAST`: `epoch Q1 Q2 Q3 QC`); v2 has no such keyword and lists
//! the scalar last. One of `REF_FRAME_A`/`REF_FRAME_B` is the body (`SC_BODY_*`), the
//! other the inertial frame, which must be TEME (glint's inertial frame: EME2000, GCRF
//! and ICRF differ from it by precession and nutation, ~0.36° in 2026, and are refused
//! rather than silently taken for it). `ATTITUDE_DIR = A2B` means the quaternion turns
//! frame A's axes onto frame B's: with A inertial and B the body it maps body
//! components to inertial ones, v_A = q·v_B·q* (glint's body → TEME); `B2A` is the
//! inverse, and so is each case with the frames swapped. `TIME_SYSTEM` may be UTC, TAI,
//! GPS or TT (fixed offsets from UTC: 37 s, 18 s, 69.184 s, in force since 2017).

use super::time::{parse_utc, UtcTime};
use glam::DQuat;

/// A parsed message: body → TEME quaternions at increasing UTC instants.
#[derive(Debug, Clone)]
pub struct Aem {
    pub samples: Vec<(UtcTime, DQuat)>,
}

/// Metadata of one segment, as the data lines need it.
#[derive(Debug, Default)]
struct Meta {
    frame_a: Option<String>,
    frame_b: Option<String>,
    dir: Option<String>,
    time_system: Option<String>,
    attitude_type: Option<String>,
    quaternion_type: Option<String>,
}

/// How one segment's data lines turn into body → TEME quaternions.
struct Reading {
    scalar_first: bool,
    /// The listed quaternion is TEME → body (invert it).
    invert: bool,
    /// Seconds to subtract from the message's times to get UTC.
    utc_offset: f64,
}

fn line_err<T>(number: usize, message: impl Into<String>) -> Result<T, String> {
    Err(format!("line {number}: {}", message.into()))
}

fn is_body(frame: &str) -> bool {
    frame.starts_with("SC_BODY")
}

impl Meta {
    fn set(&mut self, key: &str, value: &str) {
        let v = Some(value.to_string());
        match key {
            "REF_FRAME_A" => self.frame_a = v,
            "REF_FRAME_B" => self.frame_b = v,
            "ATTITUDE_DIR" => self.dir = v,
            "TIME_SYSTEM" => self.time_system = v,
            "ATTITUDE_TYPE" => self.attitude_type = v,
            "QUATERNION_TYPE" => self.quaternion_type = v,
            _ => {}
        }
    }

    /// Checks the segment's metadata (ending at line `number`) for version `v2`.
    fn reading(&self, number: usize, v2: bool) -> Result<Reading, String> {
        let need = |name: &str, x: &Option<String>| {
            x.clone()
                .ok_or_else(|| format!("line {number}: the segment has no {name}"))
        };
        let (a, b) = (
            need("REF_FRAME_A", &self.frame_a)?,
            need("REF_FRAME_B", &self.frame_b)?,
        );
        let dir = need("ATTITUDE_DIR", &self.dir)?;
        let kind = need("ATTITUDE_TYPE", &self.attitude_type)?;
        if kind != "QUATERNION" {
            return line_err(
                number,
                format!("ATTITUDE_TYPE = {kind}: only QUATERNION is read"),
            );
        }
        let scalar_first = match (v2, self.quaternion_type.as_deref()) {
            (false, Some("FIRST")) => true,
            (false, Some("LAST")) => false,
            (false, None) => {
                return line_err(
                    number,
                    "a version 1 message needs QUATERNION_TYPE (FIRST or LAST)",
                )
            }
            (false, Some(other)) => {
                return line_err(
                    number,
                    format!("QUATERNION_TYPE = {other}: must be FIRST or LAST"),
                )
            }
            (true, Some(_)) => {
                return line_err(
                    number,
                    "QUATERNION_TYPE is not a version 2 keyword (v2 lists the scalar last)",
                )
            }
            (true, None) => false,
        };
        let (inertial, body_is_b) = match (is_body(&a), is_body(&b)) {
            (false, true) => (a, true),
            (true, false) => (b, false),
            _ => {
                return line_err(
                    number,
                    format!("REF_FRAME_A = {a}, REF_FRAME_B = {b}: one must be the body (SC_BODY_n), the other TEME"),
                )
            }
        };
        if inertial != "TEME" {
            return line_err(
                number,
                format!(
                    "reference frame {inertial} is not supported: give attitudes in TEME (EME2000, \
                     GCRF and ICRF differ from it by precession and nutation)"
                ),
            );
        }
        let a2b = match dir.as_str() {
            "A2B" => true,
            "B2A" => false,
            other => {
                return line_err(
                    number,
                    format!("ATTITUDE_DIR = {other}: must be A2B or B2A"),
                )
            }
        };
        let utc_offset = match self.time_system.as_deref().unwrap_or("UTC") {
            "UTC" => 0.0,
            "TAI" => 37.0,
            "GPS" => 18.0,
            "TT" => 69.184,
            other => {
                return line_err(
                    number,
                    format!("TIME_SYSTEM = {other}: UTC, TAI, GPS or TT"),
                )
            }
        };
        Ok(Reading {
            scalar_first,
            // A2B with the body as B maps body → inertial: glint's direction
            invert: a2b != body_is_b,
            utc_offset,
        })
    }
}

impl Reading {
    fn sample(&self, number: usize, line: &str) -> Result<(UtcTime, DQuat), String> {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.len() != 5 {
            return line_err(
                number,
                format!(
                    "a quaternion line has an epoch and 4 numbers, this has {} words",
                    words.len()
                ),
            );
        }
        let t = parse_utc(words[0]).map_err(|m| format!("line {number}: {m}"))?;
        let mut x = [0.0; 4];
        for (k, w) in words[1..].iter().enumerate() {
            x[k] = w
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("line {number}: `{w}` is not a finite number"))?;
        }
        let q = if self.scalar_first {
            DQuat::from_xyzw(x[1], x[2], x[3], x[0])
        } else {
            DQuat::from_xyzw(x[0], x[1], x[2], x[3])
        };
        if (q.length() - 1.0).abs() > 1e-6 {
            return line_err(
                number,
                format!(
                    "the quaternion has norm {:.9}, not 1 (within 1e-6)",
                    q.length()
                ),
            );
        }
        let q = q.normalize();
        Ok((
            t.plus(-self.utc_offset),
            if self.invert { q.inverse() } else { q },
        ))
    }
}

/// Parses AEM KVN text; errors name the line.
pub fn parse(text: &str) -> Result<Aem, String> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.trim()));
    let v2 = match lines.find(|(_, l)| !l.is_empty() && !l.starts_with("COMMENT")) {
        Some((n, l)) => match l.split_once('=').map(|(k, v)| (k.trim(), v.trim())) {
            Some(("CCSDS_AEM_VERS", v)) if v.starts_with('1') => false,
            Some(("CCSDS_AEM_VERS", v)) if v.starts_with('2') => true,
            _ => return line_err(n, "an AEM starts with CCSDS_AEM_VERS = 1.0 or 2.0"),
        },
        None => return Err("the message is empty".into()),
    };
    let mut samples: Vec<(UtcTime, DQuat)> = Vec::new();
    let (mut meta, mut reading) = (None::<Meta>, None::<Reading>);
    for (n, line) in lines {
        if line.is_empty() || line.starts_with("COMMENT") {
            continue;
        }
        match line {
            "META_START" => meta = Some(Meta::default()),
            "META_STOP" => {
                let m = meta
                    .take()
                    .ok_or_else(|| format!("line {n}: META_STOP without META_START"))?;
                reading = Some(m.reading(n, v2)?);
            }
            "DATA_START" if reading.is_none() => {
                return line_err(n, "DATA_START before a metadata block")
            }
            "DATA_START" => {}
            "DATA_STOP" => reading = None,
            _ => {
                if let Some(m) = meta.as_mut() {
                    if let Some((k, v)) = line.split_once('=') {
                        m.set(k.trim(), v.trim());
                    }
                } else if let Some(r) = &reading {
                    let s = r.sample(n, line)?;
                    if let Some(&(prev, _)) = samples.last() {
                        if s.0.seconds_since(prev) <= 0.0 {
                            return line_err(n, "epochs must increase from line to line");
                        }
                    }
                    samples.push(s);
                }
                // header keywords (CREATION_DATE, ORIGINATOR, ...) are not needed
            }
        }
    }
    if samples.is_empty() {
        return Err("the message has no quaternion data lines".into());
    }
    Ok(Aem { samples })
}
