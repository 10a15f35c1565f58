//! A patch bounded by a slab about its cone's axis ([`Slab`]): per direction, the folds
//! over a flat patch's box that pass beside or below all its faces are set aside before
//! any face is read ([`super::Silhouettes::receivers`]).

use super::polygons::Polygons;
use crate::geometry::polygon::line_meets_box;
use glam::{DVec2, DVec3};

/// Thickest slab, as a share of its rectangle's larger half extent, whose bound is
/// worth testing folds against: a crumpled surface's patches are thick, and the folds
/// over their boxes mostly do cross a face.
const FLAT_SLAB: f64 = 0.05;

/// A patch bounded by a slab about its cone's axis: a rectangle in the plane through
/// its middle, and how far its faces stand off that plane. A patch that faces one way is
/// nearly flat, and its axis-aligned box, seen along a slanting direction, covers far
/// more than its faces do: folds pass over that box without crossing a face of it (on
/// the box-wing, 60 % of the faces the patches that folds reach were tested against
/// them in vain). The slab bounds it tightly enough to tell most of those folds apart.
#[derive(Debug, Clone, Copy)]
pub struct Slab {
    /// The middle of the rectangle (m), the plane's unit normal (the cone's axis) and
    /// its in-plane axes.
    pub centre: DVec3,
    pub n: DVec3,
    pub e1: DVec3,
    pub e2: DVec3,
    /// The rectangle's half extents along `e1`, `e2` (m), and the faces' largest
    /// distance from its plane (m).
    pub half: DVec2,
    pub thick: f64,
}

impl Slab {
    /// The slab about unit `n` holding faces `m`' polygons.
    pub(super) fn of(polys: &Polygons, m: &[u32], n: DVec3) -> Slab {
        let (e1, e2) = super::polygons::basis(n);
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for &f in m {
            for k in polys.of(f as usize) {
                for &q in polys.corners3(k) {
                    let at = DVec3::new(q.dot(e1), q.dot(e2), q.dot(n));
                    lo = lo.min(at);
                    hi = hi.max(at);
                }
            }
        }
        let (mid, half) = ((lo + hi) * 0.5, (hi - lo) * 0.5);
        Slab {
            centre: e1 * mid.x + e2 * mid.y + n * mid.z,
            n,
            e1,
            e2,
            half: DVec2::new(half.x, half.y),
            thick: half.z,
        }
    }

    /// The slab seen along unit `d`, within `tol` (m), ready to test segments against;
    /// `None` when it is too thick for its bound to be worth the test, or d runs too
    /// close to its plane. What depends on d alone is found here, once a patch.
    #[inline]
    pub fn along(&self, d: DVec3, tol: f64) -> Option<SlabAlong<'_>> {
        let nd = self.n.dot(d);
        if nd.abs() < 0.05 || self.thick > FLAT_SLAB * self.half.max_element() {
            return None;
        }
        // a face point off the plane by at most `thick` lands within this of its own
        // place when moved along d onto it; `tol` across d is at most tol/|n·d| in it
        let reach = (self.thick * (1.0 - nd * nd).max(0.0).sqrt() + 2.0 * tol) / nd.abs();
        Some(SlabAlong {
            slab: self,
            d,
            nd,
            side: nd.signum(),
            tol,
            reach: self.half + DVec2::splat(reach),
        })
    }
}

/// A [`Slab`] seen along a direction ([`Slab::along`]): d, n·d and its sign (the side of
/// the plane d points to), the tolerance (m), and the rectangle's half extents widened by
/// what the thickness and the tolerance reach.
pub struct SlabAlong<'s> {
    slab: &'s Slab,
    d: DVec3,
    nd: f64,
    side: f64,
    tol: f64,
    reach: DVec2,
}

impl SlabAlong<'_> {
    /// Might the segment `a`–`b` shade some point of the slab (lie above it, seen along
    /// d, within the tolerance)? False only when no part of it lies above the slab's far
    /// side, or the part that does passes beside the widened rectangle.
    #[inline]
    pub fn may_shade(&self, a: DVec3, b: DVec3) -> bool {
        let SlabAlong {
            slab,
            d,
            nd,
            side,
            tol,
            reach: h,
        } = *self;
        // height off the plane towards d's side, from the slab's far side: a point below
        // that shades nothing of the slab
        let (ha, hb) = (
            side * slab.n.dot(a - slab.centre) + slab.thick + tol,
            side * slab.n.dot(b - slab.centre) + slab.thick + tol,
        );
        if ha <= 0.0 && hb <= 0.0 {
            return false;
        }
        let (mut t0, mut t1) = (0.0, 1.0);
        if ha <= 0.0 {
            t0 = ha / (ha - hb);
        } else if hb <= 0.0 {
            t1 = ha / (ha - hb);
        }
        // the part above, along d onto the middle plane, in the rectangle's axes
        let onto = |x: DVec3| {
            let y = x - d * (slab.n.dot(x - slab.centre) / nd);
            DVec2::new(slab.e1.dot(y - slab.centre), slab.e2.dot(y - slab.centre))
        };
        let (pa, pb) = (onto(a + (b - a) * t0), onto(a + (b - a) * t1));
        if pa.min(pb).cmpgt(h).any() || pa.max(pb).cmplt(-h).any() {
            return false;
        }
        line_meets_box(pa, pb, -h, h)
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures;
    use super::super::patches::Facing;
    use crate::geometry::builtin::geodesic_sphere;
    use glam::DVec3;

    #[test]
    fn a_slab_turns_away_only_segments_that_shade_none_of_its_faces() {
        // Against brute force: points along each segment moved along -d onto each face's
        // plane, inside the face's polygon and below the point. A segment the slab turns
        // away must shade no face of the patch at any of 400 points along it (the bound
        // is conservative, so no tolerance: a point that shades is a failure).
        let b = fixtures::build(&geodesic_sphere(24, 1.5));
        let corners: Vec<DVec3> = (0..b.polys.len())
            .flat_map(|k| b.polys.corners3(k).to_vec())
            .collect();
        let mut next = crate::test_rng(0x9e37_79b9_7f4a_7c15);
        let shades = |p: usize, a: DVec3, c: DVec3, d: DVec3| {
            b.patches.faces_of(p).iter().any(|&f| {
                let f = f as usize;
                let (n, o) = (b.polys.normal[f], b.polys.point[f]);
                (0..=400).any(|i| {
                    let x = a + (c - a) * (i as f64 / 400.0);
                    let s = n.dot(x - o) / n.dot(d);
                    let q = b.polys.to2(f, x - d * s);
                    s > 0.0
                        && b.polys.of(f).any(|k| {
                            let c2 = b.polys.corners2(k);
                            (0..c2.len()).all(|j| {
                                crate::integrate::silhouettes::polygons::orient(
                                    c2[j],
                                    c2[(j + 1) % c2.len()],
                                    q,
                                ) >= 0.0
                            })
                        })
                })
            })
        };
        let (mut tested, mut turned_away) = (0, 0);
        for d in fixtures::directions() {
            for p in 0..b.patches.len() {
                if b.patches.facing(p, d) != Facing::Along {
                    continue;
                }
                let slab = &b.patches.slab[p];
                for _ in 0..4 {
                    // segments near the patch: from its corners and the sphere's, pushed out
                    let pick = |r: f64| corners[(r * corners.len() as f64) as usize];
                    let near = slab.centre + slab.n * (0.3 * next() - 0.1);
                    let a = if next() < 0.5 {
                        near
                    } else {
                        pick(next()) * 1.2
                    };
                    let c = pick(next()) + d * next();
                    let Some(may) = slab.along(d, 1e-9).map(|s| s.may_shade(a, c)) else {
                        continue;
                    };
                    tested += 1;
                    if !may {
                        turned_away += 1;
                        assert!(
                            !shades(p, a, c, d),
                            "patch {p}: a segment that shades was turned away"
                        );
                    }
                }
            }
        }
        // the test means something: the slabs were asked, and turned many away
        assert!(
            tested > 1000 && turned_away > tested / 4,
            "{turned_away} of {tested}"
        );
    }
}
