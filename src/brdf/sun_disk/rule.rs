//! The rule chosen for one epoch: which points of which rule average the lobe over the
//! disk, given the lobe's width across it and the Earth (in penumbra, the finer pattern
//! with the points the Earth hides dropped).

use super::cubature::{disk_directions, hex_points, hex_spacing, penumbra_points, smooth_rules};
use super::penumbra::EarthDisk;
use super::{angle, PENUMBRA_RINGS, RINGS, SMOOTH_RULES};
use glam::DVec3;

/// How the disk is averaged for one epoch: by points, or, for a lobe much narrower than
/// the whole disk in view, as the disk's image through the lobe
/// ([`Image`](super::image::Image)), with the hexagonal pattern of [`RINGS`] rings for
/// faces so near grazing that their horizon cuts the lobe (`grazing`).
pub(super) enum DiskRule {
    Points(Rule),
    Image { grazing: Rule },
}

/// A rule of points for one epoch: its directions with weights (summing to 1 over the
/// visible part of the disk), the slope its lobes get in the Sun–observer plane, and
/// the blob's slope (rad, in the half vector) when it is a hexagonal pattern.
pub(super) struct Rule {
    pub(super) dirs: Vec<(f64, DVec3)>,
    pub(super) slope_in: f64,
    pub(super) blob: Option<f64>,
}

/// The rule for a lobe of RMS slope `slope` against a disk of angular radius
/// `sun_radius` (rad) about `l`, seen from `v`, perhaps partly hidden by `earth`; `blob`
/// is the penumbra pattern's least slope in solar radii. `None` when the Earth hides
/// every direction of the rule.
///
/// Across the disk the lobe is narrower than its slope says when the phase angle g is
/// large: moving the Sun by β in the plane of `l` and `v` turns the half vector by β/2,
/// but out of that plane by β/(2·cos(g/2)). What the rule must resolve is the narrow
/// width, slope·cos(g/2) (a quarter of the slope at g = 151°). A lobe narrower than
/// every smooth rule's width images the disk: [`DiskRule::Image`].
///
/// With part of the disk behind the Earth the finer hexagonal pattern of
/// [`PENUMBRA_RINGS`](super::PENUMBRA_RINGS) rings serves whatever the lobe, its hidden
/// points dropped and the others' weights renormalised to 1 ([`penumbra_rule`]).
pub(super) fn disk_rule(
    slope: f64,
    l: DVec3,
    v: DVec3,
    sun_radius: f64,
    earth: Option<EarthDisk>,
    blob: f64,
) -> Option<DiskRule> {
    if let Some(earth) = earth.filter(|e| angle(l, e.dir) < sun_radius + e.radius) {
        return penumbra_rule(slope, l, sun_radius, earth, blob).map(DiskRule::Points);
    }
    let width = slope * 0.5 * (l + v).length() / sun_radius;
    Some(match SMOOTH_RULES.iter().position(|r| width >= r.0) {
        Some(k) => DiskRule::Points(Rule {
            dirs: disk_directions(&smooth_rules()[k], l, sun_radius).collect(),
            slope_in: slope,
            blob: None,
        }),
        None => {
            let blob = blob * sun_radius;
            DiskRule::Image {
                grazing: Rule {
                    dirs: disk_directions(hex_points(), l, sun_radius).collect(),
                    slope_in: slope.max(blob),
                    blob: Some(blob),
                },
            }
        }
    })
}

/// The rule while the Earth hides part of the disk: the finer hexagonal pattern of
/// [`PENUMBRA_RINGS`] rings whatever the lobe, its hidden points dropped and the others'
/// weights renormalised to 1; `blob` as [`disk_rule`] takes it.
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
