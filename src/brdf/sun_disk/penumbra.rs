//! The Earth's disk hiding part of the Sun's (penumbra): which directions it hides. The
//! rule that averages over the visible part only is [`super::rule`]'s.

use super::angle;
use glam::DVec3;

/// The Earth's disk on the object's sky: the unit direction of its centre and its
/// angular radius (rad). What hides part of the Sun in penumbra (docs/physics.md §4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EarthDisk {
    pub dir: DVec3,
    pub radius: f64,
}

impl EarthDisk {
    /// Whether the direction `d` (unit) lies behind the Earth.
    #[inline]
    pub(super) fn hides(&self, d: DVec3) -> bool {
        angle(d, self.dir) < self.radius
    }
}
