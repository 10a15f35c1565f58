//! The vocabulary of the request boundary, shared by the checks of every part of a
//! request ([`super::validate`], [`super::geometry`]): what a bad request is, and the size
//! bounds a request is checked against.

use std::fmt;

/// A bad request: which field, and what is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ValidationError {
    /// Path of the field, e.g. `object.materials[1].albedo` (empty for the whole body).
    pub field: String,
    pub message: String,
}

impl ValidationError {
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> Self {
        ValidationError {
            field: field.into(),
            message: message.into(),
        }
    }
    /// Whether the error is a size limit (HTTP 413) rather than a bad value (422/400).
    pub fn is_limit(&self) -> bool {
        self.message.starts_with("too many") || self.message.starts_with("too large")
    }
}

impl fmt::Display for ValidationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.field.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "{}: {}", self.field, self.message)
        }
    }
}

impl std::error::Error for ValidationError {}

/// Size bounds on a request. The CLI uses [`Limits::unlimited`]; the service sets its own.
///
/// The last two bound the work before it starts, so that a short request cannot ask for
/// hours of computation: a request over either is refused (HTTP 413) before any slot is
/// taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    pub max_triangles: usize,
    pub max_epochs: usize,
    /// Most triangle-epochs (triangles × epochs): the analytic methods' work grows with it.
    pub max_triangle_epochs: u64,
    /// Most pixel samples rendered: the `image` method's epochs × `image_size`² ×
    /// `image_samples`² plus the thumbnails' frames × size² × samples² (each sample one
    /// camera ray and up to two shadow rays).
    pub max_pixel_samples: u64,
}

impl Limits {
    pub const fn unlimited() -> Limits {
        Limits {
            max_triangles: usize::MAX,
            max_epochs: usize::MAX,
            max_triangle_epochs: u64::MAX,
            max_pixel_samples: u64::MAX,
        }
    }
}

impl Default for Limits {
    fn default() -> Self {
        Limits::unlimited()
    }
}
