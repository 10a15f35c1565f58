//! From an element set, a site and a time window to the directions the engine needs.
//!
//! Everything here is geometric (no refraction, no light-time correction) and in f64:
//! - [`time`]: UTC instants held as whole Unix seconds plus a fraction, exact to well
//!   below a nanosecond over any window (a bare f64 of Unix seconds is not: 0.24 µs);
//! - [`tle`]: two- and three-line element sets and CCSDS OMM (JSON), propagated by
//!   SGP4 (the `sgp4` crate in its AFSPC-compatible mode, WGS-72) in TEME;
//! - [`oem`]: CCSDS OEM ephemerides (TEME), interpolated by Lagrange polynomials;
//! - [`frames`]: TEME → PEF by the IAU-82 Greenwich mean sidereal time, PEF → ITRF by
//!   polar motion, with optional Earth orientation (UT1 − UTC, x_p, y_p);
//! - [`site`]: WGS-84 geodetic sites, their east-north-up frame, azimuth and elevation;
//! - [`sun`]: Meeus' low-accuracy solar coordinates (0.01°);
//! - [`attitude`]: attitude laws (nadir, Sun-pointing, inertial, spin, quaternion
//!   series, torque-free tumble), each giving the body → TEME rotation at an instant;
//! - [`pass`]: the per-epoch assembly of all of the above.
//!
//! The quasi-inertial frame throughout is TEME (SGP4's true equator, mean equinox of
//! date); attitude quaternions are body → TEME.

pub mod aem;
pub mod attitude;
pub mod frames;
pub mod oem;
pub mod pass;
pub mod site;
pub mod sun;
pub mod time;
pub mod tle;

pub use time::UtcTime;
