//! One direction of a rule on the disk: its weight, its lobe (widened to a blob for the
//! hexagonal patterns) and the blob's squeeze across the plane of Sun and observer.

use super::LEAST_COS_HALF_PHASE;
use crate::brdf::{Brdf, Directions, Frame};
use glam::DVec3;

/// One direction on the disk.
#[derive(Debug, Clone)]
pub(super) struct Sample {
    /// Weight (the weights of a rule sum to 1).
    w: f64,
    dirs: Directions,
    /// Unit half vector of this direction and the observer.
    h: DVec3,
    /// Unit vector across the plane of this direction and the observer (l_k × v).
    across: DVec3,
    /// δ_in/δ_out (≤ 1): how much the lobe's offset across the plane is scaled; 1 leaves
    /// the lobe as the (widened) model has it.
    squeeze: f64,
}

impl Sample {
    /// w·f·cosθi·cosθr of this direction on a face (`cr` = n·v).
    #[inline]
    pub(super) fn projected_given(&self, spec: &Brdf, frame: &Frame, cr: f64) -> f64 {
        if self.squeeze >= 1.0 {
            return self.w * self.dirs.projected_given(spec, frame, cr);
        }
        if cr <= 0.0 {
            return 0.0;
        }
        // the half vector turned towards n across the plane by (1 − q) of n's angle a
        // from it that way, so the lobe sees that angle scaled by q (an angle, not a
        // tangent offset: near phase 180° the blobs span radians along the terminator);
        // and the light moved with it (the direction that h mirrors into v), so the blob
        // is lit as from where it lies
        let n = frame.n;
        let a = n.dot(self.across).atan2(n.dot(self.h));
        let (sa, ca) = ((1.0 - self.squeeze) * a).sin_cos();
        let h = self.h * ca + self.across * sa;
        let v = self.dirs.view();
        let l = 2.0 * h.dot(v) * h - v;
        let ci = n.dot(l);
        if ci <= 0.0 {
            return 0.0;
        }
        self.w * self.squeeze * self.dirs.model_moved(spec, frame, ci, cr, l, h)
    }
}

/// One direction `d` of weight `w` for the specular part `spec` (widened to the blob in
/// the Sun–observer plane), with its stretch across that plane for a hexagonal pattern
/// of blob slope `blob` (rad).
pub(super) fn sample(
    spec: &Brdf,
    w: f64,
    d: DVec3,
    v: DVec3,
    slope: f64,
    blob: Option<f64>,
    sun_radius: f64,
) -> Sample {
    let dirs = Directions::new(spec, d, v);
    let plain = Sample {
        w,
        dirs,
        h: DVec3::ZERO,
        across: DVec3::ZERO,
        squeeze: 1.0,
    };
    let Some(blob) = blob else {
        return plain;
    };
    let (Some(h), Some(across)) = (crate::brdf::half_vector(d, v), d.cross(v).try_normalize())
    else {
        return plain;
    };
    let cos_half = (0.5 * (d + v).length()).max(LEAST_COS_HALF_PHASE * sun_radius);
    let squeeze = slope.max(blob) / slope.max(blob / cos_half);
    Sample {
        h,
        across,
        squeeze,
        ..plain
    }
}

/// The specular part `spec` (RMS slope `slope`) with its lobe widened to `to` where
/// narrower.
pub(super) fn widened(spec: Brdf, slope: f64, to: f64) -> Brdf {
    if to > slope {
        spec.widened(to)
    } else {
        spec
    }
}
