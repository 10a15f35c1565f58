//! How a light curve is computed and how closely: `method`, `tolerance`, and each
//! method's own settings (`image_size`, `image_samples`, `centroid_subdivisions`).

use super::values::{err, finite};
use super::{Limits, ValidationError};
use crate::scene::request::Request;
use crate::scene::Method;

/// `tolerance`, the relative accuracy asked of the adaptive methods; 1e-3 when not given.
pub(super) fn tolerance(req: &Request) -> Result<f64, ValidationError> {
    Ok(match req.tolerance {
        None => 1e-3,
        Some(t) => {
            finite("tolerance", t)?;
            if !(1e-9..=0.5).contains(&t) {
                return err(
                    "tolerance",
                    format!("must be between 1e-9 and 0.5, got {t}"),
                );
            }
            t
        }
    })
}

/// `method`, by name; `auto` when not given.
pub(super) fn method(req: &Request) -> Result<Method, ValidationError> {
    Ok(match req.method.as_deref() {
        None | Some("auto") => Method::Auto,
        Some("adaptive") => Method::Adaptive,
        Some("silhouette") => Method::Silhouette,
        Some("centroid") => Method::Centroid,
        Some("convex") => Method::Convex,
        Some("image") => Method::Image,
        Some(other) => {
            return err(
                "method",
                format!(
                    "unknown method `{other}`; expected auto, silhouette, adaptive, centroid, convex or image"
                ),
            )
        }
    })
}

/// The methods' fidelity settings: (image_size, image_samples, centroid_subdivisions).
/// A setting given for another method is an error, so a request never silently ignores it.
pub(super) fn fidelity(
    req: &Request,
    method: Method,
    triangles: usize,
    limits: &Limits,
) -> Result<(u32, u32, u32), ValidationError> {
    let only_for = |field: &str, m: Method| -> Result<(), ValidationError> {
        if method != m {
            return err(
                field,
                format!(
                    "applies only to \"method\": \"{}\" (the request uses `{}`)",
                    m.name(),
                    method.name()
                ),
            );
        }
        Ok(())
    };
    let mut out = (256, 4, 0);
    if let Some(size) = req.image_size {
        only_for("image_size", Method::Image)?;
        if !(8..=4096).contains(&size) {
            return err(
                "image_size",
                format!("must be between 8 and 4096 pixels, got {size}"),
            );
        }
        out.0 = size;
    }
    if let Some(samples) = req.image_samples {
        only_for("image_samples", Method::Image)?;
        if !(1..=16).contains(&samples) {
            return err(
                "image_samples",
                format!("must be between 1 and 16 per pixel side, got {samples}"),
            );
        }
        out.1 = samples;
    }
    if let Some(k) = req.centroid_subdivisions {
        only_for("centroid_subdivisions", Method::Centroid)?;
        if k > 8 {
            return err(
                "centroid_subdivisions",
                format!("must be between 0 and 8, got {k}"),
            );
        }
        let refined = (triangles as u128) << (2 * k);
        if refined > limits.max_triangles.min(1 << 26) as u128 {
            return err(
                "centroid_subdivisions",
                format!(
                    "too many triangles after {k} subdivisions: {refined} (limit {})",
                    limits.max_triangles.min(1 << 26)
                ),
            );
        }
        out.2 = k;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::{check, check_with, refused};
    use crate::scene::validate::{Limits, ValidationError};
    use crate::scene::Method;
    use serde_json::json;

    #[test]
    fn tolerance_and_method_are_checked() {
        let e = refused(|v| v["tolerance"] = json!(1.0));
        assert_eq!(
            e,
            ValidationError::new("tolerance", "must be between 1e-9 and 0.5, got 1")
        );
        let e = refused(|v| v["method"] = json!("guess"));
        assert_eq!(e.field, "method");
        assert!(e.message.starts_with("unknown method `guess`"), "{e}");
        let scene = check(|_| {}).expect("valid");
        assert_eq!((scene.method, scene.tolerance), (Method::Auto, 1e-3));
    }

    #[test]
    fn a_setting_of_another_method_is_refused() {
        let e = refused(|v| v["image_size"] = json!(64));
        assert_eq!(
            e,
            ValidationError::new(
                "image_size",
                "applies only to \"method\": \"image\" (the request uses `auto`)"
            )
        );
        let scene = check(|v| {
            v["method"] = json!("image");
            v["image_size"] = json!(64);
        })
        .expect("valid");
        assert_eq!((scene.image_size, scene.image_samples), (64, 4));
    }

    #[test]
    fn centroid_subdivisions_are_bounded_by_the_triangle_limit() {
        let limits = Limits {
            max_triangles: 16,
            ..Limits::default()
        };
        let subdivide = |k: u32| {
            move |v: &mut serde_json::Value| {
                v["method"] = json!("centroid");
                v["centroid_subdivisions"] = json!(k);
            }
        };
        // 2 triangles × 4² = 32 > 16; × 4 = 8 is within
        let e = check_with(subdivide(2), &limits).unwrap_err();
        assert_eq!(e.field, "centroid_subdivisions");
        assert_eq!(
            e.message,
            "too many triangles after 2 subdivisions: 32 (limit 16)"
        );
        assert!(check_with(subdivide(1), &limits).is_ok());
    }
}
