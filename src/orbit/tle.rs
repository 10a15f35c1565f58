//! Element sets (TLE or CCSDS OMM) and their SGP4 propagation.
//!
//! Propagation is the `sgp4` crate in its AFSPC-compatible mode (WGS-72 constants, the
//! AFSPC sidereal time and epoch expressions: Vallado's `opsmode 'a'`), which is what
//! python-sgp4 computes with `sgp4init(WGS72, 'a', …)`; the output frame is TEME.

use super::time::UtcTime;
use glam::DVec3;

/// A problem with an element set: the index of the line at fault (TLE lines counted
/// from 0 as given), when one line is, and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ElementError {
    pub line: Option<usize>,
    pub message: String,
}

fn fail<T>(line: Option<usize>, message: impl Into<String>) -> Result<T, ElementError> {
    Err(ElementError {
        line,
        message: message.into(),
    })
}

/// An element set ready to propagate.
#[derive(Debug, Clone)]
pub struct ElementSet {
    pub elements: sgp4::Elements,
    constants: sgp4::Constants,
    /// The elements' epoch (UTC).
    pub epoch: UtcTime,
}

/// The TLE checksum of a line's first 68 characters: digits summed, each `-` counting
/// 1, modulo 10.
pub fn checksum(line: &str) -> u32 {
    line.bytes()
        .take(68)
        .map(|c| match c {
            b'0'..=b'9' => (c - b'0') as u32,
            b'-' => 1,
            _ => 0,
        })
        .sum::<u32>()
        % 10
}

impl ElementSet {
    /// Two lines, or three with the object's name first (an optional leading `0 ` on
    /// the name is dropped). Trailing whitespace is ignored; every data line must have
    /// 69 characters and a correct checksum.
    pub fn from_tle(lines: &[String]) -> Result<ElementSet, ElementError> {
        let (name, first) = match lines.len() {
            2 => (None, 0),
            3 => {
                let n = lines[0].trim();
                let n = n.strip_prefix("0 ").unwrap_or(n).trim();
                (Some(n.to_string()), 1)
            }
            n => return fail(None, format!("must have 2 or 3 lines, got {n}")),
        };
        let data: Vec<&str> = lines[first..].iter().map(|l| l.trim_end()).collect();
        for (k, line) in data.iter().enumerate() {
            let i = first + k;
            let want = if k == 0 { '1' } else { '2' };
            if !line.is_ascii() {
                return fail(Some(i), "must be ASCII");
            }
            if !line.starts_with(want) {
                return fail(Some(i), format!("line {} must start with `{want}`", k + 1));
            }
            if line.len() != 69 {
                return fail(
                    Some(i),
                    format!("must have 69 characters, has {}", line.len()),
                );
            }
            let given = line.as_bytes()[68];
            let sum = checksum(line);
            if given != b'0' + sum as u8 {
                return fail(
                    Some(i),
                    format!(
                        "bad checksum: the last character is `{}`, the line's checksum is {sum}",
                        given as char
                    ),
                );
            }
        }
        let elements = sgp4::Elements::from_tle(name, data[0].as_bytes(), data[1].as_bytes())
            .map_err(|e| ElementError {
                line: None,
                message: e.to_string(),
            })?;
        ElementSet::from_elements(elements)
    }

    /// A CCSDS OMM in its JSON form (the keys of CelesTrak's and Space-Track's `json`
    /// output: `EPOCH`, `MEAN_MOTION`, `ECCENTRICITY`, `INCLINATION`, `RA_OF_ASC_NODE`,
    /// `ARG_OF_PERICENTER`, `MEAN_ANOMALY`, `BSTAR`, …; numbers or numeric strings).
    pub fn from_omm_json(omm: &serde_json::Value) -> Result<ElementSet, ElementError> {
        let elements: sgp4::Elements =
            serde_json::from_value(omm.clone()).map_err(|e| ElementError {
                line: None,
                message: format!("not a CCSDS OMM: {e}"),
            })?;
        ElementSet::from_elements(elements)
    }

    fn from_elements(elements: sgp4::Elements) -> Result<ElementSet, ElementError> {
        let finite = [
            elements.inclination,
            elements.right_ascension,
            elements.eccentricity,
            elements.argument_of_perigee,
            elements.mean_anomaly,
            elements.mean_motion,
            elements.drag_term,
            elements.mean_motion_dot,
            elements.mean_motion_ddot,
        ];
        if finite.iter().any(|v| !v.is_finite()) {
            return fail(None, "an element is not a finite number");
        }
        if !(0.0..1.0).contains(&elements.eccentricity) {
            return fail(
                None,
                format!("eccentricity {} is outside [0, 1)", elements.eccentricity),
            );
        }
        if !(elements.mean_motion > 0.0 && elements.mean_motion < 20.0) {
            return fail(
                None,
                format!(
                    "mean motion {} rev/day is outside (0, 20)",
                    elements.mean_motion
                ),
            );
        }
        let constants = sgp4::Constants::from_elements_afspc_compatibility_mode(&elements)
            .map_err(|e| ElementError {
                line: None,
                message: e.to_string(),
            })?;
        Ok(ElementSet {
            epoch: UtcTime::from_naive(&elements.datetime),
            elements,
            constants,
        })
    }

    /// Orbital period from the mean motion, s.
    pub fn period_s(&self) -> f64 {
        86_400.0 / self.elements.mean_motion
    }

    /// TEME position (m) and velocity (m/s) at `t`; an error when SGP4 fails there (the
    /// orbit has decayed or diverged).
    pub fn teme_at(&self, t: UtcTime) -> Result<(DVec3, DVec3), String> {
        self.teme_at_minutes(t.seconds_since(self.epoch) / 60.0)
    }

    /// TEME position (m) and velocity (m/s) `minutes` after the epoch.
    pub fn teme_at_minutes(&self, minutes: f64) -> Result<(DVec3, DVec3), String> {
        let p = self
            .constants
            .propagate_afspc_compatibility_mode(sgp4::MinutesSinceEpoch(minutes))
            .map_err(|e| e.to_string())?;
        let r = DVec3::from_array(p.position) * 1e3;
        let v = DVec3::from_array(p.velocity) * 1e3;
        if !r.is_finite() || !v.is_finite() {
            return Err(format!(
                "SGP4 gave no finite state {minutes} min after the epoch"
            ));
        }
        Ok((r, v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const L1: &str = "1 25544U 98067A   08264.51782528 -.00002182  00000-0 -11606-4 0  2927";
    const L2: &str = "2 25544  51.6416 247.4627 0006703 130.5360 325.0288 15.72125391563537";

    fn lines(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    /// The checksum of a published element set (exact).
    #[test]
    fn checksums() {
        assert_eq!(checksum(L1), 7);
        assert_eq!(checksum(L2), 7);
        assert!(ElementSet::from_tle(&lines(&[L1, L2])).is_ok());
        assert!(ElementSet::from_tle(&lines(&["ISS (ZARYA)", L1, L2])).is_ok());
        let bad = L2.replace("563537", "563538");
        let e = ElementSet::from_tle(&lines(&[L1, &bad])).unwrap_err();
        assert_eq!(e.line, Some(1));
        assert!(e.message.contains("checksum"), "{}", e.message);
        let e = ElementSet::from_tle(&lines(&[L1])).unwrap_err();
        assert_eq!(e.line, None);
    }
}
