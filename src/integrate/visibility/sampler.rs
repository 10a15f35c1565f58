//! Adaptive ray sampling of a face's visible area, where exact clipping cannot decide.

use super::blockers::Blocker;
use super::face::triangle_area;
use super::proofs::reaches;
use crate::geometry::bvh::LazyOccluder;
use crate::integrate::per_direction::{PerDirection, Toward};
use glam::DVec3;

/// Deepest refinement: leaves down to 2⁻¹⁶ of a triangle's size.
const MAX_DEPTH: u32 = 16;

/// Adaptive sampler state for one face.
pub(super) struct Sampler<'a> {
    occluder: &'a LazyOccluder,
    n: DVec3,
    /// Face centroid: samples are nudged towards it (see [`Sampler::eval`]).
    centre: DVec3,
    /// View, sun and earthshine directions (sun/earth absent when they do not light the face).
    dirs: PerDirection<Option<DVec3>>,
    /// Possible blockers per direction; an empty list means the direction is clear.
    pub(super) blockers: PerDirection<Vec<Blocker>>,
    /// Leaf diameter (m) below which refinement stops.
    min_size: f64,
    /// Area of the face (m²) whose misclassification the tolerance allows.
    budget: f64,
    pub(super) rays: u64,
    pub(super) a_sun: f64,
    pub(super) a_earth: f64,
}

impl<'a> Sampler<'a> {
    pub(super) fn new(
        occluder: &'a LazyOccluder,
        n: DVec3,
        centre: DVec3,
        dirs: PerDirection<Option<DVec3>>,
        min_size: f64,
        budget: f64,
        blockers: PerDirection<Vec<Blocker>>,
    ) -> Self {
        Sampler {
            occluder,
            n,
            centre,
            dirs,
            blockers,
            min_size,
            budget,
            rays: 0,
            a_sun: 0.0,
            a_earth: 0.0,
        }
    }

    /// Bit 0: seen and sunlit; bit 1: seen and earthlit (or earthshine unshadowed).
    /// Rays are cast only for the directions in `check`.
    #[inline]
    fn eval(&mut self, p: DVec3, check: PerDirection<bool>) -> u8 {
        // A sample on the face's edge may lie in the plane of a neighbour that shares the
        // edge; a ray from there would hit that neighbour at t ≈ 0. Nudge it into the face
        // by the ray offset (scaled to the object) so edges see what the face's interior sees.
        let towards = self.centre - p;
        let len = towards.length();
        let p = if len > 0.0 {
            p + towards * (self.occluder.get().offset().min(0.5 * len) / len)
        } else {
            p
        };
        let mut clear = PerDirection::splat(true);
        for (k, &(c, d)) in check.zip(self.dirs).pairs() {
            if let (true, Some(d)) = (c, d) {
                self.rays += 1;
                clear[k] = self.occluder.get().is_clear(p, self.n, d);
                if k == Toward::View && !clear.view {
                    return 0; // hidden from the observer: nothing else matters
                }
            }
        }
        let sun = self.dirs.sun.is_some() && clear.sun;
        (sun as u8) | ((clear.earth as u8) << 1)
    }

    /// The centroid method: one ray per direction at each of `pieces`' centroids, which
    /// decides the whole triangle. Seen-and-sunlit and seen-and-earthlit areas (m²), and
    /// the rays cast.
    pub(super) fn centroids(&mut self, pieces: &[[DVec3; 3]]) -> (f64, f64, u64) {
        for c in pieces {
            let bits = self.eval((c[0] + c[1] + c[2]) / 3.0, PerDirection::splat(true));
            let a = triangle_area(c);
            self.a_sun += a * (bits & 1) as f64;
            self.a_earth += a * ((bits >> 1) & 1) as f64;
        }
        (self.a_sun, self.a_earth, self.rays)
    }

    /// Refines triangle `p`. `values` are corner samples taken by the parent (with its
    /// checks, a superset of this piece's); `None` means take them here.
    pub(super) fn refine(
        &mut self,
        p: [DVec3; 3],
        values: Option<[u8; 3]>,
        area: f64,
        depth: u32,
        tol: f64,
    ) {
        let m = (p[0] + p[1] + p[2]) / 3.0;
        let radius = p.iter().map(|q| q.distance(m)).fold(0.0, f64::max);
        // Which directions still have a blocker that can reach this piece, and the
        // narrowest shadow such a blocker can cast.
        let mut check = PerDirection::splat(false);
        let mut feature = f64::INFINITY;
        for ((needed, dir), blockers) in check
            .iter_mut()
            .zip(self.dirs.iter())
            .zip(self.blockers.iter())
        {
            let dir = *dir;
            let Some(d) = dir else { continue };
            for b in blockers {
                if reaches(m, radius, b.centre, b.radius, d) && !b.half_space_clear(d, &p, tol) {
                    *needed = true;
                    // a shadow too small to matter need not be hunted for
                    if b.shadow_area > 0.5 * self.budget {
                        feature = feature.min(b.feature);
                    }
                }
            }
        }
        if check == PerDirection::splat(false) {
            // proven clear: seen, and lit by whatever lights the face
            self.a_sun += if self.dirs.sun.is_some() { area } else { 0.0 };
            self.a_earth += area;
            return;
        }
        let v = match values {
            Some(v) => v,
            None => [
                self.eval(p[0], check),
                self.eval(p[1], check),
                self.eval(p[2], check),
            ],
        };
        let vm = self.eval(m, check);
        let uniform = v[0] == vm && v[1] == vm && v[2] == vm;
        // Pieces wider than the narrowest possible shadow are split even when their
        // samples agree (it could fall between them), down to the tolerance's leaf size,
        // below which a missed sliver is within the error budget.
        let size = 2.0 * radius;
        let forced = size > self.min_size && size > feature;
        if depth >= MAX_DEPTH || size <= self.min_size || (uniform && !forced) {
            // Leaf: corners weigh 1/6 each, the centroid 1/2 (exact for linear fields).
            let frac = |bit: u8| {
                v.iter().map(|x| ((x >> bit) & 1) as f64).sum::<f64>() / 6.0
                    + ((vm >> bit) & 1) as f64 * 0.5
            };
            self.a_sun += frac(0) * area;
            self.a_earth += frac(1) * area;
            return;
        }
        let ab = 0.5 * (p[0] + p[1]);
        let bc = 0.5 * (p[1] + p[2]);
        let ca = 0.5 * (p[2] + p[0]);
        let (vab, vbc, vca) = (
            self.eval(ab, check),
            self.eval(bc, check),
            self.eval(ca, check),
        );
        let q = 0.25 * area;
        self.refine([p[0], ab, ca], Some([v[0], vab, vca]), q, depth + 1, tol);
        self.refine([ab, p[1], bc], Some([vab, v[1], vbc]), q, depth + 1, tol);
        self.refine([ca, bc, p[2]], Some([vca, vbc, v[2]]), q, depth + 1, tol);
        self.refine([ab, bc, ca], Some([vab, vbc, vca]), q, depth + 1, tol);
    }
}
