//! One instant of a pass: the object, the site and the Sun in TEME, and what the site
//! sees (azimuth, elevation, range, the Sun's elevation, the Earth's shadow).

use super::frames::{teme_to_itrf, EarthOrientation};
use super::site::Site;
use super::sun;
use super::time::UtcTime;
use super::tle::ElementSet;
use crate::radiometry::{eclipse, EARTH_RADIUS_M, SUN_RADIUS_M};
use glam::DVec3;

/// The geometry of one instant. Vectors are TEME, metres (velocity m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Instant {
    pub t: UtcTime,
    /// The object's geocentric position and velocity.
    pub r: DVec3,
    pub v: DVec3,
    /// The Sun's geocentric position.
    pub sun: DVec3,
    /// The site's geocentric position.
    pub site: DVec3,
    /// The object's ITRF position.
    pub r_itrf: DVec3,
    /// Seen from the site: degrees from north through east, degrees above the
    /// ellipsoid's horizon plane, metres.
    pub azimuth_deg: f64,
    pub elevation_deg: f64,
    pub range_m: f64,
    /// The Sun's elevation at the site, degrees (geometric, centre of the disk).
    pub sun_elevation_deg: f64,
}

impl Instant {
    /// Unit direction from the object to the Sun, and that distance (m).
    pub fn to_sun(&self) -> (DVec3, f64) {
        let d = self.sun - self.r;
        let n = d.length();
        (d / n, n)
    }

    /// Fraction of the Sun's disk the Earth (a sphere of `EARTH_RADIUS_M`) hides from
    /// the object: the engine's own eclipse model on these vectors.
    pub fn eclipse(&self) -> f64 {
        hidden_fraction(self.r, self.sun)
    }
}

/// Fraction of the solar disk hidden by the Earth seen from geocentric `r` with the
/// Sun at geocentric `sun` (both m, any one frame).
pub fn hidden_fraction(r: DVec3, sun: DVec3) -> f64 {
    let to_sun = sun - r;
    let (ds, de) = (to_sun.length(), r.length());
    if de <= EARTH_RADIUS_M || ds <= SUN_RADIUS_M {
        return 1.0;
    }
    let a_s = (SUN_RADIUS_M / ds).asin();
    let a_e = (EARTH_RADIUS_M / de).asin();
    let cos = (to_sun.dot(-r) / (ds * de)).clamp(-1.0, 1.0);
    eclipse::hidden_fraction(a_s, a_e, cos.acos())
}

/// Where an orbit's TEME state comes from: SGP4 on an element set, or an ephemeris.
pub trait Propagate {
    /// TEME position (m) and velocity (m/s) at `t`, or why there is none.
    fn teme_at(&self, t: UtcTime) -> Result<(DVec3, DVec3), String>;
}

impl Propagate for ElementSet {
    fn teme_at(&self, t: UtcTime) -> Result<(DVec3, DVec3), String> {
        ElementSet::teme_at(self, t)
    }
}

impl Propagate for super::oem::Ephemeris {
    fn teme_at(&self, t: UtcTime) -> Result<(DVec3, DVec3), String> {
        super::oem::Ephemeris::teme_at(self, t)
    }
}

/// An orbit: an element set (SGP4) or a CCSDS OEM's states.
#[derive(Debug, Clone)]
pub enum Orbit {
    Sgp4(Box<ElementSet>),
    Oem(super::oem::Ephemeris),
}

impl Propagate for Orbit {
    fn teme_at(&self, t: UtcTime) -> Result<(DVec3, DVec3), String> {
        match self {
            Orbit::Sgp4(s) => s.teme_at(t),
            Orbit::Oem(e) => e.teme_at(t),
        }
    }
}

/// The geometry at `t`; an error when the orbit has no state there.
pub fn at(
    set: &impl Propagate,
    site: &Site,
    eop: &EarthOrientation,
    t: UtcTime,
) -> Result<Instant, String> {
    let (r, v) = set.teme_at(t)?;
    let (sun_dir, sun_dist) = sun::position(t);
    let sun = sun_dir * sun_dist;
    let m = teme_to_itrf(t, eop);
    let site_itrf = site.itrf();
    let r_itrf = m * r;
    let (azimuth_deg, elevation_deg, range_m) = site.look(r_itrf);
    let (_, sun_elevation_deg, _) = site.look(m * sun);
    Ok(Instant {
        t,
        r,
        v,
        sun,
        site: m.transpose() * site_itrf,
        r_itrf,
        azimuth_deg,
        elevation_deg,
        range_m,
        sun_elevation_deg,
    })
}
