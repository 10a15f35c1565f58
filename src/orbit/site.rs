//! A ground site on the WGS-84 ellipsoid, its local horizon, azimuth and elevation.

use glam::{DMat3, DVec3};

/// WGS-84 semi-major axis, m.
pub const WGS84_A_M: f64 = 6_378_137.0;
/// WGS-84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;

/// A site: geodetic latitude and longitude (degrees, east positive) and height above
/// the WGS-84 ellipsoid (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    pub lat_deg: f64,
    pub lon_deg: f64,
    pub alt_m: f64,
}

impl Site {
    /// The site's ITRF position, m.
    pub fn itrf(&self) -> DVec3 {
        let (sp, cp) = self.lat_deg.to_radians().sin_cos();
        let (sl, cl) = self.lon_deg.to_radians().sin_cos();
        let e2 = WGS84_F * (2.0 - WGS84_F);
        // 1 − e² sin²φ ≥ 1 − e² > 0.99
        let n = WGS84_A_M / (1.0 - e2 * sp * sp).sqrt();
        DVec3::new(
            (n + self.alt_m) * cp * cl,
            (n + self.alt_m) * cp * sl,
            (n * (1.0 - e2) + self.alt_m) * sp,
        )
    }

    /// Rows east, north, up: the ITRF → local east-north-up rotation (up is the
    /// ellipsoid's normal).
    pub fn enu(&self) -> DMat3 {
        let (sp, cp) = self.lat_deg.to_radians().sin_cos();
        let (sl, cl) = self.lon_deg.to_radians().sin_cos();
        let east = DVec3::new(-sl, cl, 0.0);
        let north = DVec3::new(-sp * cl, -sp * sl, cp);
        let up = DVec3::new(cp * cl, cp * sl, sp);
        DMat3::from_cols(east, north, up).transpose()
    }

    /// Azimuth (degrees from north through east, [0, 360)), elevation (degrees) and
    /// range (m) of an ITRF point seen from the site. A point at the site itself has
    /// azimuth and elevation 0.
    pub fn look(&self, itrf: DVec3) -> (f64, f64, f64) {
        let d = itrf - self.itrf();
        let l = self.enu() * d;
        let horizontal = l.x.hypot(l.y);
        let az = l.x.atan2(l.y).to_degrees().rem_euclid(360.0);
        let el = l.z.atan2(horizontal).to_degrees();
        // rem_euclid can round up to 360 for a tiny negative angle
        let az = if az >= 360.0 { 0.0 } else { az };
        (az, el, d.length())
    }
}
