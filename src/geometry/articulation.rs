//! Articulated parts: groups of triangles that turn about hinges, each epoch.
//!
//! The mesh as given is the reference pose (every angle 0). A hinge (a [`Joint`]) turns
//! its link — the vertices of its triangles that no nested hinge moves — about the line
//! through `pivot` along `axis`, right-handed, by its angle; a nested hinge's axis and
//! pivot are given in the reference pose and are carried by its parent, so a vertex of
//! a nested link moves by T_parent ∘ R_joint (the joint's own rotation, in the reference
//! pose, then its parent's). Vertices shared between links were split at validation;
//! those lying on their own hinge line are placed exactly where the parent puts them, so
//! a hinge stays welded (same position, bit for bit) to what it hangs from.

use glam::{DMat3, DVec3};

/// How a hinge's angle is found at each epoch (radians).
#[derive(Debug, Clone, PartialEq)]
pub enum JointLaw {
    /// The angle that turns `normal` (unit, reference pose, body frame) onto the Sun's
    /// projection on the plane normal to the (current) axis; 0 when the Sun lies along
    /// the axis.
    SunTracking {
        normal: DVec3,
    },
    Fixed {
        angle: f64,
    },
    /// (t, angle) at increasing t (the epochs' own seconds), linear between; the epochs
    /// lie within (checked at validation; clamped here).
    Series {
        series: Vec<(f64, f64)>,
    },
}

/// One hinge.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Unit direction, reference pose, body frame.
    pub axis: DVec3,
    /// A point of the hinge line, m, reference pose.
    pub pivot: DVec3,
    /// The hinge this one is nested in (an earlier index).
    pub parent: Option<usize>,
    pub law: JointLaw,
}

impl Joint {
    /// The joint's link's motion (reference pose → body frame): its hinge turned by
    /// `angle` (radians), after its parent's motion `parent`.
    fn motion(&self, parent: Motion, angle: f64) -> Motion {
        parent.after(&Motion::hinge(self.axis, self.pivot, angle))
    }
}

/// The motion of joint `j`'s parent link among `motions` (the earlier joints'), or none.
fn parent_motion(j: &Joint, motions: &[Motion]) -> Motion {
    j.parent.map_or(Motion::IDENTITY, |p| motions[p])
}

/// Body: the vertices no hinge moves.
pub const BODY: u32 = u32::MAX;

/// The hinges of a mesh and which of its vertices each moves.
#[derive(Debug, Clone, PartialEq)]
pub struct Articulation {
    /// Parents before children.
    pub joints: Vec<Joint>,
    /// Per mesh vertex: the joint whose link it belongs to, or [`BODY`].
    pub link: Vec<u32>,
    /// Per mesh vertex: it lies on its own joint's hinge line (to 1e-12 of the mesh's
    /// size), so that joint's rotation leaves it where the parent puts it.
    pub on_hinge: Vec<bool>,
}

/// A rigid motion v ↦ rot·v + shift.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    pub rot: DMat3,
    pub shift: DVec3,
}

impl Motion {
    pub const IDENTITY: Motion = Motion {
        rot: DMat3::IDENTITY,
        shift: DVec3::ZERO,
    };

    #[inline]
    pub fn apply(&self, v: DVec3) -> DVec3 {
        self.rot * v + self.shift
    }

    /// The motion that undoes this one.
    pub fn inverse(&self) -> Motion {
        let rot = self.rot.transpose();
        Motion {
            rot,
            shift: -(rot * self.shift),
        }
    }

    /// `self` after `inner`: v ↦ self(inner(v)).
    fn after(&self, inner: &Motion) -> Motion {
        Motion {
            rot: self.rot * inner.rot,
            shift: self.rot * inner.shift + self.shift,
        }
    }

    /// The turn by `angle` about the line through `pivot` along unit `axis`.
    pub fn hinge(axis: DVec3, pivot: DVec3, angle: f64) -> Motion {
        let rot = DMat3::from_axis_angle(axis, angle);
        Motion {
            rot,
            shift: pivot - rot * pivot,
        }
    }
}

/// Right-handed angle about unit `axis` from `from` to `to`, both projected on the plane
/// normal to it; `None` when either projection vanishes (relative 1e-12).
pub fn angle_about(axis: DVec3, from: DVec3, to: DVec3) -> Option<f64> {
    let f = from - axis * axis.dot(from);
    let t = to - axis * axis.dot(to);
    if f.length() <= 1e-12 * from.length() || t.length() <= 1e-12 * to.length() {
        return None;
    }
    Some(axis.dot(f.cross(t)).atan2(f.dot(t)))
}

/// Linear interpolation in a series of (t, value), t increasing; clamped at the ends.
pub fn interpolate(series: &[(f64, f64)], t: f64) -> f64 {
    let Some(&(t0, v0)) = series.first() else {
        return 0.0;
    };
    if t <= t0 || series.len() == 1 {
        return v0;
    }
    let k = series.partition_point(|(ti, _)| *ti <= t);
    if k >= series.len() {
        return series[series.len() - 1].1;
    }
    let ((ta, va), (tb, vb)) = (series[k - 1], series[k]);
    // times strictly increase (validated)
    va + (vb - va) * ((t - ta) / (tb - ta))
}

impl Articulation {
    /// Each joint's angle (radians) and motion (reference pose → body frame) at time `t`
    /// (s, the epochs' scale) with the Sun along unit `sun` (body frame).
    pub fn motions(&self, t: f64, sun: DVec3) -> (Vec<f64>, Vec<Motion>) {
        let mut angles = Vec::with_capacity(self.joints.len());
        let mut motions: Vec<Motion> = Vec::with_capacity(self.joints.len());
        for j in &self.joints {
            let parent = parent_motion(j, &motions);
            let angle = match &j.law {
                JointLaw::Fixed { angle } => *angle,
                JointLaw::Series { series } => interpolate(series, t),
                JointLaw::SunTracking { normal } => {
                    let axis = parent.rot * j.axis;
                    angle_about(axis, parent.rot * *normal, sun).unwrap_or(0.0)
                }
            };
            angles.push(angle);
            motions.push(j.motion(parent, angle));
        }
        (angles, motions)
    }

    /// Each joint's angle, radians, at time `t` (s) with the Sun along unit `sun`.
    pub fn angles(&self, t: f64, sun: DVec3) -> Vec<f64> {
        self.motions(t, sun).0
    }

    /// Each joint's link's motion (reference pose → body frame) at these angles.
    pub fn motions_at(&self, angles: &[f64]) -> Vec<Motion> {
        let mut motions: Vec<Motion> = Vec::with_capacity(self.joints.len());
        for (j, &a) in self.joints.iter().zip(angles) {
            motions.push(j.motion(parent_motion(j, &motions), a));
        }
        motions
    }

    /// The mesh's vertices (`reference`, the mesh as validated) posed at these angles.
    pub fn pose(&self, reference: &[DVec3], angles: &[f64]) -> Vec<DVec3> {
        let motions = self.motions_at(angles);
        reference
            .iter()
            .zip(self.link.iter().zip(&self.on_hinge))
            .map(|(&v, (&link, &on_hinge))| {
                if link == BODY {
                    return v;
                }
                let j = link as usize;
                if on_hinge {
                    // where the parent puts it, computed as the parent's own vertices are
                    match self.joints[j].parent {
                        None => v,
                        Some(p) => motions[p].apply(v),
                    }
                } else {
                    motions[j].apply(v)
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The angle between two vectors about an axis, against hand-computed cases (exact
    /// to rounding: 1e-15).
    #[test]
    fn angles_about_an_axis() {
        let a = angle_about(DVec3::Z, DVec3::X, DVec3::new(0.0, 1.0, 5.0)).unwrap();
        assert!((a - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let a = angle_about(DVec3::Z, DVec3::X, DVec3::new(-1.0, -1.0, 0.0)).unwrap();
        assert!((a + 0.75 * std::f64::consts::PI).abs() < 1e-15);
        assert!(angle_about(DVec3::Z, DVec3::X, DVec3::Z).is_none());
        assert_eq!(interpolate(&[(0.0, 1.0), (2.0, 3.0)], 1.5), 2.5);
        assert_eq!(interpolate(&[(0.0, 1.0), (2.0, 3.0)], 9.0), 3.0);
    }
}
