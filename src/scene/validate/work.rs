//! What a request would cost, estimated before any work is done, against the limits:
//! triangles × epochs for the analytic methods, pixel samples for the rendered images.

use super::values::err;
use super::{Limits, ValidationError};
use crate::scene::Thumbnails;

/// Refuses a request whose work, estimated before any is done, is over the limits:
/// triangles × epochs, and the pixel samples of the `image` method (`image`: its size and
/// samples per side) and of the thumbnails.
pub(super) fn work(
    limits: &Limits,
    triangles: usize,
    epochs: usize,
    image: Option<(u32, u32)>,
    thumbnails: Option<&Thumbnails>,
) -> Result<(), ValidationError> {
    let triangle_epochs = triangles as u64 * epochs as u64;
    if triangle_epochs > limits.max_triangle_epochs {
        return err(
            "epochs",
            format!(
                "too large a computation: {triangles} triangles × {epochs} epochs = \
                 {triangle_epochs} triangle-epochs (limit {}); send fewer epochs, a coarser \
                 mesh, or submit it as a job",
                limits.max_triangle_epochs
            ),
        );
    }
    let image_samples = image.map_or(0, |(size, samples)| {
        epochs as u64 * (size as u64).pow(2) * (samples as u64).pow(2)
    });
    let thumbnail_samples = thumbnails.map_or(0, |t| {
        t.epochs.len() as u64 * (t.size as u64).pow(2) * (t.samples as u64).pow(2)
    });
    let (field, what) = if image_samples > limits.max_pixel_samples {
        let (size, samples) = image.unwrap_or_default();
        (
            "image_size",
            format!("{epochs} epochs × {size}² pixels × {samples}² samples = {image_samples}"),
        )
    } else if image_samples + thumbnail_samples > limits.max_pixel_samples {
        (
            "thumbnails",
            format!(
                "{thumbnail_samples} thumbnail samples{}",
                if image_samples > 0 {
                    format!(" + {image_samples} of the `image` method")
                } else {
                    String::new()
                }
            ),
        )
    } else {
        return Ok(());
    };
    err(
        field,
        format!(
            "too large a computation: {what} pixel samples (limit {}); render fewer or \
             smaller images, or submit it as a job",
            limits.max_pixel_samples
        ),
    )
}
