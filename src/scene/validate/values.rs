//! The checks of one value that every part of a request shares: a finite number, a
//! positive one, one in a range, a usable vector. Each names the field it was given.

use super::ValidationError;
use glam::DVec3;

/// `Err` naming `field`: the one way every check here says no.
pub(super) fn err<T>(
    field: impl Into<String>,
    message: impl Into<String>,
) -> Result<T, ValidationError> {
    Err(ValidationError::new(field, message))
}

/// A finite number (not NaN nor ±∞).
pub(super) fn finite(field: &str, v: f64) -> Result<f64, ValidationError> {
    if v.is_finite() {
        Ok(v)
    } else {
        err(field, "must be a finite number")
    }
}

/// A vector that has a direction and a length: finite, not zero, and with |v|² a normal
/// f64 (its length between 1e-150 and 1e150, in the field's own unit).
pub(super) fn vector(field: &str, v: [f64; 3]) -> Result<DVec3, ValidationError> {
    let d = DVec3::from_array(v);
    if !d.is_finite() {
        return err(field, "must have three finite components");
    }
    if d == DVec3::ZERO {
        return err(field, "must not be the zero vector");
    }
    let l2 = d.length_squared();
    // |v|² must be a normal f64 for the direction and the range to be computed.
    if l2.is_infinite() {
        return err(field, "is too long: its length must be below 1e150");
    }
    if !l2.is_normal() {
        return err(
            field,
            "is too short to give a direction: its length must be above 1e-150",
        );
    }
    Ok(d)
}

/// A finite number in `[lo, hi]`.
pub(super) fn in_range(field: &str, v: f64, lo: f64, hi: f64) -> Result<f64, ValidationError> {
    finite(field, v)?;
    if v < lo || v > hi {
        return err(field, format!("must be between {lo} and {hi}, got {v}"));
    }
    Ok(v)
}

/// A finite number above zero.
pub(super) fn positive(field: &str, v: f64) -> Result<f64, ValidationError> {
    finite(field, v)?;
    if v <= 0.0 {
        return err(field, format!("must be positive, got {v}"));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vector_needs_a_direction_and_a_usable_length() {
        let msg = |v| vector("v", v).unwrap_err().message;
        assert_eq!(msg([0.0; 3]), "must not be the zero vector");
        assert_eq!(
            msg([f64::NAN, 0.0, 1.0]),
            "must have three finite components"
        );
        assert!(msg([1e200, 0.0, 0.0]).starts_with("is too long"));
        assert!(msg([1e-200, 0.0, 0.0]).starts_with("is too short"));
        assert_eq!(vector("v", [3.0, 4.0, 0.0]), Ok(DVec3::new(3.0, 4.0, 0.0)));
    }

    #[test]
    fn a_range_includes_its_ends_and_an_error_names_the_field() {
        assert_eq!(in_range("x", 1.0, 0.0, 1.0), Ok(1.0));
        assert_eq!(
            in_range("x", 1.5, 0.0, 1.0),
            Err(ValidationError::new(
                "x",
                "must be between 0 and 1, got 1.5"
            ))
        );
        assert_eq!(
            in_range("x", f64::NAN, 0.0, 1.0).unwrap_err().message,
            "must be a finite number"
        );
        assert_eq!(
            positive("y", 0.0),
            Err(ValidationError::new("y", "must be positive, got 0"))
        );
    }
}
