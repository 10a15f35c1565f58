//! `thumbnails`: the rendered images a request asks for (size, samples, which epochs,
//! exposure), within the limits on pixels and pixel samples one request may render.

use super::values::{err, positive};
use super::ValidationError;
use crate::scene::request::{ExposureSpec, ThumbnailSpec};
use crate::scene::{Exposure, Thumbnails};

/// Most pixel samples (frames × size² × samples²) one request may ask to render.
pub const MAX_THUMBNAIL_SAMPLES: u64 = 1 << 30;
/// Most pixels (frames × size²) one request may ask to render: 256 MiB of f32 radiance.
pub const MAX_THUMBNAIL_PIXELS: u64 = 1 << 26;

/// The thumbnails of a request of `n_epochs` epochs, the defaults filled in.
pub(super) fn thumbnails(
    spec: &ThumbnailSpec,
    n_epochs: usize,
) -> Result<Thumbnails, ValidationError> {
    let mut out = Thumbnails::default_for(n_epochs);
    if let Some(size) = spec.size {
        if !(8..=2048).contains(&size) {
            return err(
                "thumbnails.size",
                format!("must be between 8 and 2048 pixels, got {size}"),
            );
        }
        out.size = size;
    }
    if let Some(samples) = spec.samples {
        if !(1..=16).contains(&samples) {
            return err(
                "thumbnails.samples",
                format!("must be between 1 and 16 per pixel side, got {samples}"),
            );
        }
        out.samples = samples;
    }
    if spec.every.is_some() || spec.epochs.is_some() {
        let mut chosen = Vec::new();
        if let Some(every) = spec.every {
            if every == 0 {
                return err("thumbnails.every", "must be at least 1");
            }
            chosen.extend((0..n_epochs).step_by(every));
        }
        for (i, &e) in spec.epochs.iter().flatten().enumerate() {
            if e >= n_epochs {
                return err(
                    format!("thumbnails.epochs[{i}]"),
                    format!("epoch index {e} out of range (there are {n_epochs} epochs)"),
                );
            }
            chosen.push(e);
        }
        chosen.sort_unstable();
        chosen.dedup();
        if chosen.is_empty() {
            return err("thumbnails.epochs", "selects no epoch");
        }
        out.epochs = chosen;
    }
    out.exposure = match &spec.exposure {
        None => Exposure::Fixed,
        Some(ExposureSpec::Mode(m)) => match m.as_str() {
            "fixed" => Exposure::Fixed,
            "peak" => Exposure::Peak,
            "auto" => Exposure::Auto,
            "log" => Exposure::Log,
            other => {
                return err(
                    "thumbnails.exposure",
                    format!("unknown exposure `{other}`; expected fixed, peak, auto, log or a radiance in W/(m²·sr)"),
                )
            }
        },
        Some(ExposureSpec::Radiance(r)) => Exposure::Radiance(positive("thumbnails.exposure", *r)?),
    };
    // The radiometric images of a sequence are held together (one exposure for all).
    let pixels = out.epochs.len() as u64 * (out.size as u64).pow(2);
    if pixels > MAX_THUMBNAIL_PIXELS {
        return err(
            "thumbnails",
            format!(
                "too many pixels: {} frames × {}² = {pixels} (limit {MAX_THUMBNAIL_PIXELS}); render fewer or smaller frames",
                out.epochs.len(),
                out.size
            ),
        );
    }
    let total = pixels * (out.samples as u64).pow(2);
    if total > MAX_THUMBNAIL_SAMPLES {
        return err(
            "thumbnails",
            format!(
                "too many pixel samples: {} frames × {}² pixels × {}² samples = {total} (limit {MAX_THUMBNAIL_SAMPLES})",
                out.epochs.len(),
                out.size,
                out.samples
            ),
        );
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::{check, refused};
    use crate::scene::validate::ValidationError;
    use serde_json::json;

    #[test]
    fn the_chosen_epochs_are_checked_and_named() {
        let e = refused(|v| v["thumbnails"] = json!({"every": 0}));
        assert_eq!(
            e,
            ValidationError::new("thumbnails.every", "must be at least 1")
        );
        let e = refused(|v| v["thumbnails"] = json!({"epochs": [0, 5]}));
        assert_eq!(
            e,
            ValidationError::new(
                "thumbnails.epochs[1]",
                "epoch index 5 out of range (there are 1 epochs)"
            )
        );
    }

    #[test]
    fn size_samples_and_exposure_are_checked() {
        let e = refused(|v| v["thumbnails"] = json!({"size": 4}));
        assert_eq!(e.field, "thumbnails.size");
        let e = refused(|v| v["thumbnails"] = json!({"samples": 17}));
        assert_eq!(e.field, "thumbnails.samples");
        let e = refused(|v| v["thumbnails"] = json!({"exposure": "bright"}));
        assert_eq!(e.field, "thumbnails.exposure");
        let e = refused(|v| v["thumbnails"] = json!({"exposure": -1.0}));
        assert_eq!(
            e,
            ValidationError::new("thumbnails.exposure", "must be positive, got -1")
        );
    }

    #[test]
    fn an_empty_spec_takes_the_defaults() {
        let scene = check(|v| v["thumbnails"] = json!({})).expect("valid");
        let t = scene.thumbnails.expect("thumbnails asked for");
        assert_eq!((t.size, t.epochs), (128, vec![0]));
    }
}
