//! The Earth's disk hiding part of the Sun's (penumbra): which directions it hides, and
//! the finer hexagonal pattern that averages over the visible part only.

use super::cubature::{disk_directions, hex_spacing, penumbra_points};
use super::rule::Rule;
use super::{angle, PENUMBRA_RINGS, RINGS};
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
    fn hides(&self, d: DVec3) -> bool {
        angle(d, self.dir) < self.radius
    }
}

/// The rule while the Earth hides part of the disk: the finer hexagonal pattern of
/// [`PENUMBRA_RINGS`] rings whatever the lobe, its hidden points dropped and the others'
/// weights renormalised to 1; `blob` as [`disk_rule`](super::rule::disk_rule) takes it.
/// `None` when the Earth hides every direction.
pub(super) fn penumbra_rule(
    slope: f64,
    l: DVec3,
    sun_radius: f64,
    earth: EarthDisk,
    blob: f64,
) -> Option<Rule> {
    let blob = blob * sun_radius * hex_spacing(PENUMBRA_RINGS) / hex_spacing(RINGS);
    let dirs: Vec<(f64, DVec3)> = disk_directions(penumbra_points(), l, sun_radius)
        .filter(|&(_, d)| !earth.hides(d))
        .collect();
    let total: f64 = dirs.iter().map(|p| p.0).sum();
    if dirs.is_empty() {
        return None;
    }
    Some(Rule {
        dirs: dirs.into_iter().map(|(w, d)| (w / total, d)).collect(),
        slope_in: slope.max(blob),
        blob: Some(blob),
    })
}
