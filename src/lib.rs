//! glint: photometric light curves of space objects.
//!
//! The physics (docs/physics.md) lives in [`radiometry`], [`brdf`], [`geometry`],
//! [`light`] (what lights the object at an epoch) and [`integrate`]; [`scene`] holds the
//! request/response types and their validation; [`report`] writes CSV and plots. The
//! command line ([`cli`]) and the HTTP service ([`service`]) are thin doors onto the same
//! [`simulate`].

pub mod brdf;
pub mod cli;
pub mod fit;
pub mod geometry;
pub mod integrate;
pub mod light;
pub mod orbit;
pub mod radiometry;
pub mod render;
pub mod report;
pub mod scene;
pub mod service;

pub use integrate::{simulate, simulate_with, Cancelled, Progress};

/// A small deterministic generator for unit tests: uniform numbers in [0, 1) from a
/// 64-bit linear congruential sequence started at `seed`.
#[cfg(test)]
pub(crate) fn test_rng(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A unit vector from three of `rnd`'s numbers (a point of the cube [−1, 1]³ normalised;
/// +z in the unlikely case of the origin), for unit tests.
#[cfg(test)]
pub(crate) fn test_unit(rnd: &mut dyn FnMut() -> f64) -> glam::DVec3 {
    glam::DVec3::new(2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0)
        .normalize_or(glam::DVec3::Z)
}
pub use scene::{Limits, Request, Response, Scene, ValidationError};
