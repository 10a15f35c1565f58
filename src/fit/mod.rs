//! Fitting: a material's parameters from measured BRDF samples ([`brdf`]), and a request's
//! free parameters (materials, attitude) from an observed light curve ([`lightcurve`]).
//! Both are weighted, bounded, robust least squares through one solver ([`solve`], on the
//! `levenberg-marquardt` crate). The CLI and the service only call these functions.

pub mod brdf;
pub mod csv;
pub mod lightcurve;
pub mod params;
pub mod solve;
