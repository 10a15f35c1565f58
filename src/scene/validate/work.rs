//! What a request would cost, estimated before any work is done, against the limits:
//! triangles × epochs for the analytic methods (an articulated scene's epochs weighed by
//! their poses' preparation), pixel samples for the rendered images.

use super::values::err;
use super::{Limits, ValidationError};
use crate::scene::Thumbnails;

/// Refuses a request whose work, estimated before any is done, is over the limits:
/// triangles × epochs (× `epoch_work`, an epoch's cost in a rigid mesh's epochs:
/// [`crate::scene::epoch_work`]), and the pixel samples of the `image` method (`image`: its size and
/// samples per side) and of the thumbnails.
pub(super) fn work(
    limits: &Limits,
    triangles: usize,
    epochs: usize,
    epoch_work: f64,
    image: Option<(u32, u32)>,
    thumbnails: Option<&Thumbnails>,
) -> Result<(), ValidationError> {
    let rigid = triangles as u64 * epochs as u64;
    let triangle_epochs = (rigid as f64 * epoch_work).ceil() as u64;
    if triangle_epochs > limits.max_triangle_epochs {
        let poses = if epoch_work > 1.0 {
            format!(" × {epoch_work} (each epoch a pose of the articulated parts, prepared anew)")
        } else {
            String::new()
        };
        return err(
            "epochs",
            format!(
                "too large a computation: {triangles} triangles × {epochs} epochs{poses} = \
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

    /// An articulated scene whose angle changes prepares a pose an epoch: its epochs
    /// weigh more (1.5 rigid epochs' work each with the silhouette method); a `fixed`
    /// hinge is one pose, and weighs nothing more.
    #[test]
    fn an_epoch_of_moving_parts_counts_its_pose() {
        let limits = Limits {
            max_triangle_epochs: 2,
            ..Limits::default()
        };
        let hinge = |law: serde_json::Value| {
            move |v: &mut serde_json::Value| {
                v["object"]["mesh"]["parts"] = json!([{ "name": "flap", "triangles": [1] }]);
                let mut h = json!({ "parts": ["flap"], "axis": [1, 0, 0] });
                for (k, x) in law.as_object().unwrap() {
                    h[k] = x.clone();
                }
                v["articulation"] = json!([h]);
            }
        };
        let fixed = json!({ "law": "fixed", "angle_deg": 10 });
        assert!(check_with(hinge(fixed), &limits).is_ok());
        let series = json!({ "law": "angles", "series": [
            { "t": -1e9, "angle_deg": 0 }, { "t": 1e9, "angle_deg": 10 }
        ] });
        let e = check_with(hinge(series), &limits).unwrap_err();
        assert!(
            e.message
                .contains("2 triangles × 1 epochs × 1.5 (each epoch a pose")
                && e.message.contains("= 3 triangle-epochs (limit 2)"),
            "{e}"
        );
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
