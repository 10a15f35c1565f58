//! glint: photometric light curves of space objects.
//!
//! The physics (PHYSICS.md) lives in [`radiometry`], [`brdf`], [`geometry`] and
//! [`integrate`]; [`scene`] holds the request/response types and their validation;
//! [`report`] writes CSV and plots. The command line ([`cli`]) and the HTTP service
//! ([`service`]) are thin doors onto the same [`simulate`].

pub mod brdf;
pub mod cli;
pub mod geometry;
pub mod integrate;
pub mod radiometry;
pub mod render;
pub mod report;
pub mod scene;
pub mod service;

pub use integrate::{simulate, simulate_with, Cancelled, Progress};
pub use scene::{Limits, Request, Response, Scene, ValidationError};
