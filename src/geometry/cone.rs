//! A cone of unit normals: the bound that lets a patch of faces be summed as one.

use super::angle_between;
use glam::DVec3;

/// Unit vectors within a half-angle of unit `axis`, the half-angle already widened past
/// rounding, so that a bound from it holds for every normal it was built from as those
/// normals are stored. The half-angle is kept as its cosine and sine: each bound is then
/// a dot and a cross product (cos(α ∓ h) expanded), no trigonometric call.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    pub axis: DVec3,
    cos: f64,
    sin: f64,
}

/// Widening of a cone's half-angle past the rounding of the normals and of the bounds'
/// own arithmetic (~1e-16): small beside any angle the bounds are compared at.
const MARGIN: f64 = 1e-9;

impl Cone {
    /// The narrowest cone about unit `axis` that holds every one of `normals` (unit).
    pub fn about(axis: DVec3, normals: impl Iterator<Item = DVec3>) -> Cone {
        let half = normals
            .map(|n| angle_between(axis, n))
            .fold(0.0_f64, f64::max);
        Cone::new(axis, half + MARGIN)
    }

    /// The cone of half-angle `half` (rad, 0–π) about unit `axis`.
    pub fn new(axis: DVec3, half: f64) -> Cone {
        let (sin, cos) = half.min(std::f64::consts::PI).sin_cos();
        Cone { axis, cos, sin }
    }

    /// The half-angle, rad.
    pub fn half(&self) -> f64 {
        self.sin.atan2(self.cos)
    }

    /// The cone of the opposite normals.
    pub fn flipped(&self) -> Cone {
        Cone {
            axis: -self.axis,
            ..*self
        }
    }

    /// cos and sin of the angle α between the axis and unit `d`.
    #[inline]
    fn angle(&self, d: DVec3) -> (f64, f64) {
        (self.axis.dot(d), self.axis.cross(d).length())
    }

    /// Largest n·d over the cone's normals (unit `d`): cos(max(0, α − h)).
    #[inline]
    pub fn max_dot(&self, d: DVec3) -> f64 {
        let (c, s) = self.angle(d);
        if c >= self.cos {
            1.0
        } else {
            c * self.cos + s * self.sin
        }
    }

    /// Smallest n·d over the cone's normals (unit `d`): cos(min(π, α + h)).
    #[inline]
    pub fn min_dot(&self, d: DVec3) -> f64 {
        let (c, s) = self.angle(d);
        if c <= -self.cos {
            -1.0
        } else {
            c * self.cos - s * self.sin
        }
    }

    /// ([`Cone::min_dot`], [`Cone::max_dot`]) of unit `d`, its angle from the axis
    /// found once.
    #[inline]
    pub fn dots(&self, d: DVec3) -> (f64, f64) {
        let (c, s) = self.angle(d);
        let least = if c <= -self.cos {
            -1.0
        } else {
            c * self.cos - s * self.sin
        };
        let most = if c >= self.cos {
            1.0
        } else {
            c * self.cos + s * self.sin
        };
        (least, most)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bounds_hold_for_every_normal_and_are_reached_to_the_margin() {
        // Truth independent of the bounds' formulas: n·d for every normal, compared
        // with the bounds. Tolerance: the bounds may exceed the extremes by the margin's
        // effect on a cosine (≤ 1e-9) and must never fall short of them at all.
        let mut rnd = crate::test_rng(7);
        let mut unit = || crate::test_unit(&mut rnd);
        for _ in 0..200 {
            let axis = unit();
            let spread = 0.4 * unit().x.abs();
            let normals: Vec<DVec3> = (0..12)
                .map(|_| (axis + spread * unit()).normalize())
                .collect();
            let cone = Cone::about(axis, normals.iter().copied());
            for _ in 0..20 {
                let d = unit();
                let dots: Vec<f64> = normals.iter().map(|n| n.dot(d)).collect();
                let hi = dots.iter().copied().fold(f64::MIN, f64::max);
                let lo = dots.iter().copied().fold(f64::MAX, f64::min);
                assert!(cone.max_dot(d) >= hi, "{} < {hi}", cone.max_dot(d));
                assert!(cone.min_dot(d) <= lo, "{} > {lo}", cone.min_dot(d));
                let flipped = cone.flipped();
                assert!(flipped.max_dot(d) >= -lo && flipped.min_dot(d) <= -hi);
            }
            // the axis and the widest normal reach the bounds (to the margin)
            let widest = normals
                .iter()
                .copied()
                .max_by(|a, b| angle_between(axis, *a).total_cmp(&angle_between(axis, *b)))
                .unwrap();
            assert!((cone.max_dot(axis) - 1.0).abs() < 1e-15);
            assert!((cone.min_dot(axis) - widest.dot(axis)).abs() < 2e-9);
            assert!((cone.half() - angle_between(axis, widest)).abs() < 2e-9);
        }
    }
}
