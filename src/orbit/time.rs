//! UTC instants precise enough for SGP4 at the millimetre.
//!
//! A Unix time of 1.8e9 s in one f64 resolves only 0.24 µs (1.8 mm of a LEO orbit), so an
//! instant is kept as whole seconds plus a fraction in [0, 1).

use chrono::{DateTime, Utc};

/// Unix seconds of J2000.0 as a UT instant, 2000-01-01T12:00:00.
pub const J2000_UNIX_S: i64 = 946_728_000;
/// Seconds in a day.
pub const DAY_S: f64 = 86_400.0;
/// TT − UTC, s: 32.184 s + 37 leap seconds (in force since 2017-01-01). Used only by
/// the Sun's series, whose 0.01° does not feel a leap second (0.00001°).
pub const TT_MINUS_UTC_S: f64 = 69.184;

/// A UTC instant: `secs` whole Unix seconds plus `frac` (0 ≤ frac < 1) seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UtcTime {
    pub secs: i64,
    pub frac: f64,
}

impl UtcTime {
    /// From whole seconds and any finite fraction (normalised into [0, 1)).
    pub fn new(secs: i64, frac: f64) -> UtcTime {
        let whole = frac.floor();
        UtcTime {
            secs: secs + whole as i64,
            frac: frac - whole,
        }
    }

    /// From a chrono UTC time (nanoseconds kept).
    pub fn from_datetime(dt: &DateTime<Utc>) -> UtcTime {
        UtcTime::new(dt.timestamp(), dt.timestamp_subsec_nanos() as f64 * 1e-9)
    }

    /// From a naive date-time read as UTC (nanoseconds kept).
    pub fn from_naive(dt: &chrono::NaiveDateTime) -> UtcTime {
        UtcTime::from_datetime(&dt.and_utc())
    }

    /// This instant plus `seconds` (finite).
    pub fn plus(self, seconds: f64) -> UtcTime {
        let whole = seconds.trunc();
        UtcTime::new(self.secs + whole as i64, self.frac + (seconds - whole))
    }

    /// Seconds from `earlier` to this instant (negative if `earlier` is later).
    pub fn seconds_since(self, earlier: UtcTime) -> f64 {
        (self.secs - earlier.secs) as f64 + (self.frac - earlier.frac)
    }

    /// Unix seconds as one f64 (for reporting; 0.24 µs resolution today).
    pub fn unix(self) -> f64 {
        self.secs as f64 + self.frac
    }

    /// Days since J2000.0 (2000-01-01T12:00) of this instant shifted by `offset_s`
    /// seconds, split as (whole days, fraction of a day in [0, 1)): the fraction keeps
    /// full precision, the day count is exact.
    pub fn j2000_days_split(self, offset_s: f64) -> (f64, f64) {
        let shifted = self.plus(offset_s);
        let s = shifted.secs - J2000_UNIX_S;
        let days = s.div_euclid(86_400);
        let rem = s.rem_euclid(86_400) as f64 + shifted.frac;
        (days as f64, rem / DAY_S)
    }
}

/// ISO 8601 / RFC 3339 UTC time → an exact UTC instant. A missing zone is taken as UTC.
pub fn parse_utc(s: &str) -> Result<UtcTime, String> {
    use chrono::{DateTime, NaiveDateTime};
    if let Ok(dt) = DateTime::parse_from_rfc3339(s) {
        return Ok(UtcTime::from_datetime(&dt.with_timezone(&chrono::Utc)));
    }
    for fmt in [
        "%Y-%m-%dT%H:%M:%S%.f",
        "%Y-%m-%d %H:%M:%S%.f",
        "%Y-%m-%dT%H:%M",
    ] {
        if let Ok(n) = NaiveDateTime::parse_from_str(s, fmt) {
            return Ok(UtcTime::from_naive(&n));
        }
    }
    Err(format!(
        "`{s}` is not an ISO 8601 UTC time (e.g. 2026-11-22T04:50:00Z)"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact arithmetic on the split: a microsecond survives 1.8e9 s of Unix time
    /// (tolerance 1e-12 s: the fraction's own f64 rounding).
    #[test]
    fn keeps_microseconds() {
        let t = UtcTime::new(1_796_000_000, 0.25);
        let u = t.plus(1e-6);
        assert!((u.seconds_since(t) - 1e-6).abs() < 1e-12);
        let v = t.plus(-2.75);
        assert_eq!(v.secs, 1_795_999_997);
        assert!((v.frac - 0.5).abs() < 1e-15);
        let (d, f) = UtcTime::new(J2000_UNIX_S + 86_400 + 43_200, 0.0).j2000_days_split(0.0);
        assert_eq!((d, f), (1.0, 0.5));
    }
}
