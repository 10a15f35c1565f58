//! A material's parameters from measured BRDF samples (the paper's §5.1 step, its Fig. 2).
//!
//! **Angles.** A sample gives the incidence zenith θi, the reflection zenith θr and the
//! relative azimuth φ between the two directions' planes, in degrees, with φ = 180° the
//! forward side of the plane of incidence, where the mirror direction lies. In the face
//! frame (normal z, tangent x), the direction towards the light is
//! l = (sin θi, 0, cos θi) and towards the detector v = (sin θr cos φ, sin θr sin φ, cos θr):
//! θr = θi at φ = 180° is the mirror direction (−l_x, −l_y, l_z) — the specular peak.
//!
//! **Residuals.** In `log` space (the default) r = ln(f_model + f₀) − ln(f_meas + f₀), f₀ a
//! thousandth of the smallest positive measurement (so a zero measurement is usable): a
//! BRDF spans five decades between its diffuse floor and a glossy peak, and a relative error
//! is what a goniometer's is. In `linear` space r = f_model − f_meas (sr⁻¹). Either is
//! multiplied by √weight.
//!
//! Where things are: `samples` (a measurement, its checks and CSV, a BRDF evaluated at
//! it, synthetic samples), `geometry` (angles as directions, a BRDF evaluated there, the
//! paper's layout of angles), `model` (the models' parameters, bounds and starts), `request` (the
//! options of a fit), `fitting` (the fit), `report` (its result and plot data).

mod fitting;
mod geometry;
mod model;
mod report;
mod request;
mod samples;

pub use fitting::fit;
pub use geometry::{directions, evaluate_at, paper_geometry};
pub use model::{Model, ParamSpec};
pub use report::{plot_data, BrdfFit};
pub use request::{BrdfFitRequest, Options, Space};
pub use samples::{evaluate, parse_csv, synthetic, to_csv, validate_samples, Sample};
