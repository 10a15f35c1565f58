//! Law `tumble` of `geometry.attitude`: an inertia tensor that a rigid body can have,
//! and a window its integration can cover.

use super::{att, err, only, quaternion_or_identity, required, MAX_TUMBLE_STEPS};
use crate::orbit::attitude::{Law, Tumble};
use crate::orbit::UtcTime;
use crate::scene::request::{AttitudeSpec, InertiaSpec};
use crate::scene::ValidationError;
use glam::{DMat3, DVec3};

/// Law `tumble`: torque-free rotation from an inertia tensor and an initial rate, its
/// principal moments those of a rigid body and its integration over the window bounded.
pub(super) fn tumble(
    a: &AttitudeSpec,
    start: UtcTime,
    stop: UtcTime,
) -> Result<Law, ValidationError> {
    only(a, &["inertia_kg_m2", "omega_deg_s", "quaternion"])?;
    let Some(inertia) = &a.inertia_kg_m2 else {
        return err(att("inertia_kg_m2"), "is required by law `tumble`");
    };
    let tensor = inertia_tensor(inertia)?;
    let omega = DVec3::from_array(required("omega_deg_s", a.omega_deg_s, &a.law)?);
    if !omega.is_finite() || omega.length() > 36_000.0 {
        return err(
            att("omega_deg_s"),
            "must be finite and below 36000 °/s in magnitude",
        );
    }
    let tumble = Tumble::new(
        tensor,
        quaternion_or_identity(a)?,
        omega * (1f64.to_radians()),
    );
    rigid_body_moments(tumble.moments)?;
    let steps = tumble.steps_for(stop.seconds_since(start));
    if steps > MAX_TUMBLE_STEPS {
        return err(
            att("omega_deg_s"),
            format!(
                "too large: this triaxial tumble over the window needs {steps:.2e} \
                 integration steps (limit {MAX_TUMBLE_STEPS:e}); shorten the window \
                 or slow the spin"
            ),
        );
    }
    Ok(Law::Tumble(tumble))
}

/// The inertia tensor (kg·m²) of `inertia_kg_m2`: principal moments, or a full tensor
/// that must be symmetric; finite either way.
fn inertia_tensor(inertia: &InertiaSpec) -> Result<DMat3, ValidationError> {
    let tensor = match inertia {
        InertiaSpec::Principal(m) => DMat3::from_diagonal(DVec3::from_array(*m)),
        InertiaSpec::Tensor(t) => {
            let m = DMat3::from_cols_array_2d(t).transpose();
            let tol = 1e-9 * m.to_cols_array().iter().fold(0.0f64, |a, b| a.max(b.abs()));
            if (m - m.transpose())
                .to_cols_array()
                .iter()
                .any(|d| d.abs() > tol)
            {
                return err(att("inertia_kg_m2"), "the tensor must be symmetric");
            }
            m
        }
    };
    if !tensor.is_finite() {
        return err(att("inertia_kg_m2"), "must hold finite numbers");
    }
    Ok(tensor)
}

/// Principal moments `m` (kg·m²) a rigid body can have: positive, below 1e15, and obeying
/// the triangle inequality (a thin plate: equality).
fn rigid_body_moments(m: DVec3) -> Result<(), ValidationError> {
    let big = m.max_element();
    if !(m.min_element() > 1e-12 * big && big < 1e15) {
        return err(
            att("inertia_kg_m2"),
            format!(
                "principal moments {:?} kg·m² must be positive (and below 1e15)",
                m.to_array()
            ),
        );
    }
    let slack = 1e-9 * big;
    if m.x + m.y < m.z - slack || m.y + m.z < m.x - slack || m.x + m.z < m.y - slack {
        return err(
            att("inertia_kg_m2"),
            format!(
                "principal moments {:?} kg·m² break the triangle inequality \
                 (I_a + I_b ≥ I_c): no rigid body has them",
                m.to_array()
            ),
        );
    }
    Ok(())
}
