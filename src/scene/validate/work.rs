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

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::check_with;
    use crate::scene::validate::Limits;
    use serde_json::json;

    #[test]
    fn triangle_epochs_over_the_limit_are_refused_before_any_work() {
        let limits = Limits {
            max_triangle_epochs: 1,
            ..Limits::default()
        };
        let e = check_with(|_| {}, &limits).unwrap_err();
        assert_eq!(e.field, "epochs");
        assert!(
            e.message.starts_with(
                "too large a computation: 2 triangles × 1 epochs = 2 triangle-epochs (limit 1)"
            ),
            "{e}"
        );
        assert!(e.is_limit());
    }

    #[test]
    fn pixel_samples_are_counted_for_the_image_method_then_the_thumbnails() {
        let limits = Limits {
            max_pixel_samples: 1000,
            ..Limits::default()
        };
        let image = |v: &mut serde_json::Value| {
            v["method"] = json!("image");
            v["image_size"] = json!(16);
            v["image_samples"] = json!(2);
        };
        // 1 epoch × 16² pixels × 2² samples = 1024
        let e = check_with(image, &limits).unwrap_err();
        assert_eq!(e.field, "image_size");
        assert!(
            e.message.contains("= 1024 pixel samples (limit 1000)"),
            "{e}"
        );
        // 1 frame × 16² × 3² = 2304 thumbnail samples
        let thumbs = |v: &mut serde_json::Value| v["thumbnails"] = json!({"size": 16});
        let e = check_with(thumbs, &limits).unwrap_err();
        assert_eq!(e.field, "thumbnails");
        assert!(
            e.message.contains("2304 thumbnail samples pixel samples"),
            "{e}"
        );
    }
}
