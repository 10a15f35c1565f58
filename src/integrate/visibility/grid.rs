//! Per-epoch acceleration of the blocker search: every face's bounding sphere seen
//! along a direction ([`Projection`]), and faces binned on the plane across it ([`FaceGrid`]).

use super::face::FaceGeom;
use crate::geometry::Faces;
use glam::{DVec2, DVec3};

/// Last-query marks per face, so a face in several cells is returned once.
#[derive(Default)]
pub(super) struct Stamp {
    marks: Vec<u32>,
    current: u32,
}

/// Every face's bounding sphere seen along one direction: its centre across the direction
/// and its depth along it, in one flat array. The reach test between two faces then reads
/// 32 bytes per face instead of the faces' geometry (measured: the candidate search was
/// half of an epoch's time on the box-wing's dish).
#[derive(Default)]
pub(super) struct Projection {
    pub(super) dir: Option<DVec3>,
    pub(super) u: DVec3,
    pub(super) w: DVec3,
    /// Per face: x, y across the direction, depth along it, radius (m).
    pub(super) at: Vec<[f64; 4]>,
}

impl Projection {
    pub(super) fn build(&mut self, faces: &[FaceGeom], d: DVec3) {
        let (u, w) = crate::geometry::orthonormal_basis(d);
        self.dir = Some(d);
        self.u = u;
        self.w = w;
        self.at.clear();
        self.at.extend(faces.iter().map(|f| {
            [
                f.centroid.dot(u),
                f.centroid.dot(w),
                f.centroid.dot(d),
                f.radius,
            ]
        }));
    }

    /// [`super::proofs::reaches`] from the projected spheres: `o`'s sphere meets the cylinder that `f`'s
    /// sweeps along the direction. In the basis (u, w, d), w_vec − d·max(w_vec·d, 0) has
    /// the across components and the depth difference only when it is negative.
    #[inline]
    pub(super) fn reaches(&self, f: usize, o: usize) -> bool {
        let (a, b) = (&self.at[f], &self.at[o]);
        let (dx, dy, dt) = (b[0] - a[0], b[1] - a[1], (b[2] - a[2]).min(0.0));
        let reach = a[3] + b[3];
        dx * dx + dy * dy + dt * dt < reach * reach
    }
}

/// All faces binned by their bounding discs projected on the plane across a direction:
/// a face's shadow along the direction can only fall on faces whose discs overlap its.
#[derive(Default)]
pub(super) struct FaceGrid {
    pub(super) dir: Option<DVec3>,
    /// The part whose faces were left out.
    pub(super) excluded: Option<u32>,
    lo: DVec2,
    cell: f64,
    nx: usize,
    ny: usize,
    /// Cell c holds items[start[c]..start[c + 1]].
    start: Vec<u32>,
    items: Vec<u32>,
    /// Faces wider than two cells: returned by every query (few: a body's sides).
    big: Vec<u32>,
    /// Number of faces binned.
    faces: usize,
}

/// Most cells per side of a face grid.
const GRID_MAX_CELLS: usize = 512;
/// Above this many faces in the flagged patches, blockers come from the face grid (below,
/// testing them all is cheaper than binning every face: measured on the box-wings of
/// `examples/scale`).
pub(super) const GRID_MIN_FACES: usize = 400;

impl FaceGrid {
    /// Bins the faces seen along the projection's direction, but those of part
    /// `exclude` (by `part_of`).
    pub(super) fn build(
        &mut self,
        proj: &Projection,
        cell: f64,
        exclude: Option<u32>,
        part_of: &[u32],
    ) {
        let faces = &proj.at;
        let at = |f: &[f64; 4]| DVec2::new(f[0], f[1]);
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for f in faces {
            let p = at(f);
            lo = lo.min(p - f[3]);
            hi = hi.max(p + f[3]);
        }
        let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        // about four cells per binned face at most: a grid of mostly empty cells costs
        // its prefix sums at every build (twice per direction and epoch)
        let binned = match exclude {
            None => faces.len(),
            Some(p) => part_of.iter().filter(|&&q| q != p).count(),
        };
        let side = ((2.0 * (binned as f64).sqrt()).ceil() as usize).clamp(1, GRID_MAX_CELLS);
        let cell = cell.max(extent / side as f64);
        let nx = (((hi.x - lo.x) / cell) as usize + 1).min(GRID_MAX_CELLS);
        let ny = (((hi.y - lo.y) / cell) as usize + 1).min(GRID_MAX_CELLS);
        *self = FaceGrid {
            dir: proj.dir,
            excluded: exclude,
            lo,
            cell,
            nx,
            ny,
            start: std::mem::take(&mut self.start),
            items: std::mem::take(&mut self.items),
            big: std::mem::take(&mut self.big),
            faces: faces.len(),
        };
        self.start.clear();
        self.start.resize(nx * ny + 1, 0);
        self.big.clear();
        // counting sort of (cell, face) pairs
        for pass in 0..2 {
            for (i, f) in faces.iter().enumerate() {
                if exclude.is_some_and(|p| part_of[i] == p) {
                    continue;
                }
                if f[3] > 2.0 * cell {
                    if pass == 0 {
                        self.big.push(i as u32);
                    }
                    continue;
                }
                let (x0, y0, x1, y1) = self.span(at(f), f[3]);
                for y in y0..=y1 {
                    for x in x0..=x1 {
                        let c = y * nx + x;
                        if pass == 0 {
                            self.start[c + 1] += 1;
                        } else {
                            let slot = self.start[c] as usize;
                            self.items[slot] = i as u32;
                            self.start[c] += 1;
                        }
                    }
                }
            }
            if pass == 0 {
                for c in 0..nx * ny {
                    self.start[c + 1] += self.start[c];
                }
                self.items.clear();
                self.items.resize(self.start[nx * ny] as usize, 0);
            } else {
                // start[c] now holds the end of cell c: shift back
                for c in (1..=nx * ny).rev() {
                    self.start[c] = self.start[c - 1];
                }
                self.start[0] = 0;
            }
        }
    }

    /// Cells covered by the disc at `p` (grid plane coordinates) of radius `r`.
    #[inline]
    fn span(&self, p: DVec2, r: f64) -> (usize, usize, usize, usize) {
        let cell_of =
            |v: f64, lo: f64, n: usize| (((v - lo) / self.cell).max(0.0) as usize).min(n - 1);
        (
            cell_of(p.x - r, self.lo.x, self.nx),
            cell_of(p.y - r, self.lo.y, self.ny),
            cell_of(p.x + r, self.lo.x, self.nx),
            cell_of(p.y + r, self.lo.y, self.ny),
        )
    }

    /// Calls `found` once for every face whose disc may overlap the disc of radius `r`
    /// about `centre` (m) seen along the grid's direction.
    pub(super) fn query(
        &self,
        centre: DVec2,
        r: f64,
        stamp: &mut Stamp,
        mut found: impl FnMut(u32),
    ) {
        if stamp.current == u32::MAX {
            stamp.marks.clear();
            stamp.current = 0;
        }
        if stamp.marks.len() < self.faces {
            stamp.marks.resize(self.faces, 0);
        }
        stamp.current += 1;
        for &g in &self.big {
            found(g);
        }
        let (x0, y0, x1, y1) = self.span(centre, r);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let c = y * self.nx + x;
                for &g in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                    let m = &mut stamp.marks[g as usize];
                    if *m != stamp.current {
                        *m = stamp.current;
                        found(g);
                    }
                }
            }
        }
    }
}

/// Cell size of the per-epoch face grids, m: the median face diameter (at least 1e-9 of
/// the object's radius `scale`).
pub(super) fn cell_size(faces: &Faces, scale: f64) -> f64 {
    let mut d: Vec<f64> = faces.faces.iter().map(|f| 2.0 * f.radius).collect();
    d.sort_by(f64::total_cmp);
    d.get(d.len() / 2).copied().unwrap_or(1.0).max(1e-9 * scale)
}

#[cfg(test)]
mod tests {
    use super::super::proofs::reaches;
    use super::*;

    fn face_at(centroid: DVec3, radius: f64) -> FaceGeom {
        FaceGeom::bare(DVec3::Z, centroid, radius)
    }

    #[test]
    fn projected_reach_test_is_the_3d_one() {
        // Projection::reaches must decide exactly as reaches(); pairs are drawn so that
        // many sit near the boundary (distances comparable to the radii).
        let mut rnd = crate::test_rng(11);
        let faces: Vec<FaceGeom> = (0..400)
            .map(|_| {
                let c = DVec3::new(rnd() * 4.0 - 2.0, rnd() * 4.0 - 2.0, rnd() * 4.0 - 2.0);
                face_at(c, 0.05 + 0.5 * rnd())
            })
            .collect();
        let mut proj = Projection::default();
        let (mut hits, mut misses) = (0, 0);
        for d in [
            DVec3::new(0.3, -0.5, 0.8).normalize(),
            DVec3::new(-0.9, 0.1, 0.05).normalize(),
            DVec3::Z,
        ] {
            proj.build(&faces, d);
            for (i, f) in faces.iter().enumerate() {
                for (j, g) in faces.iter().enumerate() {
                    let want = reaches(f.centroid, f.radius, g.centroid, g.radius, d);
                    assert_eq!(proj.reaches(i, j), want, "faces {i}, {j} along {d}");
                    if want {
                        hits += 1
                    } else {
                        misses += 1
                    }
                }
            }
        }
        assert!(
            hits > 10_000 && misses > 10_000,
            "{hits} hits, {misses} misses"
        );
    }

    #[test]
    fn face_grid_returns_every_face_whose_shadow_can_reach() {
        // Against brute force: every face g with reaches(f, g, d) must come back from the
        // query for f, once. Small and large faces (the big list), directions off the axes.
        let mut rnd = crate::test_rng(7);
        let faces: Vec<FaceGeom> = (0..600)
            .map(|i| {
                let c = DVec3::new(rnd() * 10.0 - 5.0, rnd() * 4.0 - 2.0, rnd() * 3.0);
                let r = if i % 50 == 0 { 2.0 } else { 0.02 + 0.1 * rnd() };
                face_at(c, r)
            })
            .collect();
        let mut grid = FaceGrid::default();
        let mut stamp = Stamp::default();
        for d in [
            DVec3::new(0.3, -0.5, 0.8).normalize(),
            DVec3::new(-0.9, 0.1, 0.05).normalize(),
            DVec3::Z,
        ] {
            let mut proj = Projection::default();
            proj.build(&faces, d);
            grid.build(&proj, 0.1, None, &[]);
            for (i, f) in faces.iter().enumerate() {
                let mut got = vec![0u32; faces.len()];
                let at = DVec2::new(f.centroid.dot(proj.u), f.centroid.dot(proj.w));
                grid.query(at, f.radius, &mut stamp, |g| got[g as usize] += 1);
                for (j, g) in faces.iter().enumerate() {
                    assert!(got[j] <= 1, "face {j} returned {} times", got[j]);
                    if j != i && reaches(f.centroid, f.radius, g.centroid, g.radius, d) {
                        assert_eq!(
                            got[j], 1,
                            "direction {d}: face {j} can shadow {i} but was not returned"
                        );
                    }
                }
            }
        }
    }
}
