//! Fitted parameters: their bounds, the change of variables that keeps the solver inside
//! them, and how results are reported.

use crate::scene::ValidationError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use utoipa::ToSchema;

/// The closed range a parameter may take, in its own units. The solver works in an
/// unbounded variable u:
/// - both ends finite: p = lo + (hi − lo)·σ(u), σ the logistic function. Near a bound of 0
///   (the usual case: kd, km, δ) this is p ≈ hi·eᵘ, so small values such as δ = 0.007 are
///   reached with steps of ordinary size;
/// - only `lo` finite: p = lo + eᵘ;
/// - neither: p = u.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bound {
    pub lo: f64,
    pub hi: f64,
}

impl Bound {
    pub const fn new(lo: f64, hi: f64) -> Bound {
        Bound { lo, hi }
    }

    pub const FREE: Bound = Bound {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };

    /// The physical value of solver variable `u` (always within the bounds).
    pub fn to_p(self, u: f64) -> f64 {
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (true, true) => {
                let s = if u >= 0.0 {
                    1.0 / (1.0 + (-u).exp())
                } else {
                    let e = u.exp();
                    e / (1.0 + e)
                };
                (self.lo + (self.hi - self.lo) * s).clamp(self.lo, self.hi)
            }
            (true, false) => self.lo + u.exp(),
            _ => u,
        }
    }

    /// The solver variable of physical value `p`; a value on (or past) a bound is moved
    /// just inside it, where the change of variables is finite.
    pub fn to_u(self, p: f64) -> f64 {
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (true, true) => {
                let w = self.hi - self.lo;
                let s = ((p - self.lo) / w).clamp(1e-12, 1.0 - 1e-12);
                (s / (1.0 - s)).ln()
            }
            (true, false) => (p - self.lo).max(1e-300).ln(),
            _ => p,
        }
    }

    pub fn contains(self, p: f64) -> bool {
        p >= self.lo && p <= self.hi
    }

    /// Whether `p` is within a millionth of the range of a finite bound: the
    /// fit ran into it, and its uncertainty is a one-sided matter.
    pub fn at_bound(self, p: f64) -> bool {
        let tol = if self.lo.is_finite() && self.hi.is_finite() {
            1e-6 * (self.hi - self.lo)
        } else {
            1e-9 * p.abs().max(1.0)
        };
        (self.lo.is_finite() && p - self.lo <= tol) || (self.hi.is_finite() && self.hi - p <= tol)
    }

    /// "[lo, hi]" for messages.
    pub fn describe(self) -> String {
        match (self.lo.is_finite(), self.hi.is_finite()) {
            (true, true) => format!("[{}, {}]", self.lo, self.hi),
            (true, false) => format!("≥ {}", self.lo),
            _ => "any value".into(),
        }
    }
}

/// Checks a value given for a parameter (a BRDF fit's fixed value, a light-curve fit's
/// start, a `sample-brdf` parameter): a finite number within `bound`, else an error on
/// `field` naming the range, "`v` is out of range [lo, hi]".
pub fn check_in_bound(field: String, v: f64, bound: Bound) -> Result<(), ValidationError> {
    if !v.is_finite() || !bound.contains(v) {
        return Err(ValidationError::new(
            field,
            format!("{v} is out of range {}", bound.describe()),
        ));
    }
    Ok(())
}

/// A value with a name, ordered as the model lists its parameters.
pub type Named = BTreeMap<String, f64>;

/// What a fit reports about how its solver went.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct SolverReport {
    /// `levenberg-marquardt` (the crate; MINPACK's lmder).
    pub algorithm: String,
    /// Loss: `l2`, `huber` or `cauchy` (IRLS).
    pub loss: String,
    /// Starts tried; the reported fit is the best of them.
    pub starts: usize,
    /// RMS of the fit-space residuals each start ended with (in start order): more than
    /// one distinct value means several minima.
    pub start_rms: Vec<f64>,
    /// Model evaluations over all starts, Jacobians included.
    pub evaluations: usize,
    /// Whether the best start's last solve met its tolerances.
    pub converged: bool,
    /// The solver's own termination reason for the best start.
    pub termination: String,
    /// Wall time of the whole fit, s.
    pub wall_time_s: f64,
}
