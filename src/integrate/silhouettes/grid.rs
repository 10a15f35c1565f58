//! The mesh seen along one direction d: every triangle that can block a ray along d,
//! projected onto the plane across d and binned in a uniform grid. A ray along d is then
//! a point of that plane, and it is blocked where a triangle's projection holds the
//! point above the ray's start (a few point-in-triangle tests, in f64, no BVH); a
//! silhouette edge's shadow falls on the receiving triangles that its projection crosses
//! below it.

use glam::{DVec2, DVec3};

/// One direction's projected triangles.
#[derive(Default)]
pub struct Grid {
    /// The direction, and the plane across it (u, w).
    pub d: DVec3,
    u: DVec3,
    w: DVec3,
    /// Per mesh vertex: its position across d (m) and its height along d (m).
    pub at: Vec<DVec2>,
    pub h: Vec<f64>,
    lo: DVec2,
    inv_cell: f64,
    nx: usize,
    ny: usize,
    /// Triangles per cell (CSR).
    start: Vec<u32>,
    items: Vec<u32>,
    counts: Vec<u32>,
}

/// What the grid needs of the mesh.
pub struct Triangles<'a> {
    pub vertices: &'a [DVec3],
    pub triangles: &'a [[u32; 3]],
    pub tri_face: &'a [u32],
}

impl Grid {
    /// Projects the mesh along `d` and bins the triangles `keep` says may block.
    pub fn build(&mut self, mesh: &Triangles, d: DVec3, keep: impl Fn(usize) -> bool) {
        let (u, w) = crate::radiometry::earth::orthonormal_basis(d);
        self.d = d;
        self.u = u;
        self.w = w;
        self.at.clear();
        self.h.clear();
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for v in mesh.vertices {
            let p = DVec2::new(v.dot(u), v.dot(w));
            lo = lo.min(p);
            hi = hi.max(p);
            self.at.push(p);
            self.h.push(v.dot(d));
        }
        let ext = (hi - lo).max(DVec2::splat(1e-300));
        let kept: Vec<u32> = (0..mesh.triangles.len() as u32)
            .filter(|&t| keep(t as usize))
            .collect();
        // about two triangles a cell
        let cells = (kept.len() as f64 / 2.0).max(1.0);
        let cell = (ext.x * ext.y / cells)
            .sqrt()
            .max(ext.max_element() / 4096.0);
        self.inv_cell = 1.0 / cell;
        self.nx = ((ext.x / cell).ceil() as usize).clamp(1, 4096);
        self.ny = ((ext.y / cell).ceil() as usize).clamp(1, 4096);
        self.lo = lo;
        let n = self.nx * self.ny;
        self.counts.clear();
        self.counts.resize(n + 1, 0);
        for &t in &kept {
            let (a, b) = self.cell_box(mesh.triangles[t as usize]);
            for y in a.1..=b.1 {
                for x in a.0..=b.0 {
                    self.counts[y * self.nx + x + 1] += 1;
                }
            }
        }
        for i in 0..n {
            self.counts[i + 1] += self.counts[i];
        }
        self.start.clear();
        self.start.extend_from_slice(&self.counts);
        self.items.clear();
        self.items.resize(self.counts[n] as usize, 0);
        for &t in &kept {
            let (a, b) = self.cell_box(mesh.triangles[t as usize]);
            for y in a.1..=b.1 {
                for x in a.0..=b.0 {
                    let c = y * self.nx + x;
                    self.items[self.counts[c] as usize] = t;
                    self.counts[c] += 1;
                }
            }
        }
    }

    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let q = (p - self.lo) * self.inv_cell;
        (
            (q.x.max(0.0) as usize).min(self.nx - 1),
            (q.y.max(0.0) as usize).min(self.ny - 1),
        )
    }

    fn cell_box(&self, tri: [u32; 3]) -> ((usize, usize), (usize, usize)) {
        let [a, b, c] = tri.map(|i| self.at[i as usize]);
        (self.cell_of(a.min(b).min(c)), self.cell_of(a.max(b).max(c)))
    }

    fn cell(&self, x: usize, y: usize) -> &[u32] {
        let c = y * self.nx + x;
        &self.items[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// Position across d and height along d of a point.
    pub fn project(&self, p: DVec3) -> (DVec2, f64) {
        (DVec2::new(p.dot(self.u), p.dot(self.w)), p.dot(self.d))
    }

    /// Does the ray from `p` along d meet a triangle (of another face than `own`) more than
    /// `eps` (m) above `p`?
    pub fn blocked(&self, mesh: &Triangles, p: DVec3, own: u32, eps: f64) -> bool {
        let (q, hp) = self.project(p);
        let (x, y) = self.cell_of(q);
        self.cell(x, y).iter().any(|&t| {
            if mesh.tri_face[t as usize] == own {
                return false;
            }
            let tri = mesh.triangles[t as usize];
            match barycentric(tri.map(|i| self.at[i as usize]), q) {
                Some(l) if l.iter().all(|&x| x >= 0.0) => {
                    let h = l[0] * self.h[tri[0] as usize]
                        + l[1] * self.h[tri[1] as usize]
                        + l[2] * self.h[tri[2] as usize];
                    h > hp + eps
                }
                _ => false,
            }
        })
    }

    /// Calls `hit(t)` for every binned triangle `t` that `receives` says may take a
    /// shadow and over which the segment a–b (m) passes above its plane by more than
    /// `eps`, within `tol` across d.
    pub fn shadowed_by(
        &self,
        mesh: &Triangles,
        a: DVec3,
        b: DVec3,
        eps: f64,
        tol: f64,
        receives: impl Fn(usize) -> bool,
        mut hit: impl FnMut(u32),
    ) {
        let (pa, ha) = self.project(a);
        let (pb, hb) = self.project(b);
        let lo = pa.min(pb) - DVec2::splat(tol);
        let hi = pa.max(pb) + DVec2::splat(tol);
        let (x0, y0) = self.cell_of(lo);
        let (x1, y1) = self.cell_of(hi);
        let single = x0 == x1 && y0 == y1;
        for y in y0..=y1 {
            for x in x0..=x1 {
                for &t in self.cell(x, y) {
                    if !receives(t as usize) {
                        continue;
                    }
                    // a triangle in several cells: test it in the first cell of the
                    // query's box that holds it
                    if !single && !self.first_cell(mesh.triangles[t as usize], (x, y), (x0, y0)) {
                        continue;
                    }
                    let tri = mesh.triangles[t as usize];
                    let p = tri.map(|i| self.at[i as usize]);
                    let hs = tri.map(|i| self.h[i as usize]);
                    // heights of the segment's ends above the triangle's plane, along d
                    let Some(la) = barycentric(p, pa) else {
                        continue;
                    };
                    let Some(lb) = barycentric(p, pb) else {
                        continue;
                    };
                    let sa = ha - (la[0] * hs[0] + la[1] * hs[1] + la[2] * hs[2]);
                    let sb = hb - (lb[0] * hs[0] + lb[1] * hs[1] + lb[2] * hs[2]);
                    if sa <= eps && sb <= eps {
                        continue;
                    }
                    // the part of the segment above the plane
                    let (mut qa, mut qb) = (pa, pb);
                    if sa <= eps {
                        qa = pa + (pb - pa) * ((eps - sa) / (sb - sa));
                    } else if sb <= eps {
                        qb = pb + (pa - pb) * ((eps - sb) / (sa - sb));
                    }
                    if segment_meets_triangle(qa, qb, p, tol) {
                        hit(t);
                    }
                }
            }
        }
    }

    /// Is `(x, y)` the first cell, within the query box from `from`, of triangle `tri`?
    fn first_cell(&self, tri: [u32; 3], (x, y): (usize, usize), from: (usize, usize)) -> bool {
        let (a, _) = self.cell_box(tri);
        (x, y) == (a.0.max(from.0), a.1.max(from.1))
    }
}

/// Barycentric coordinates of `q` in the triangle `p` (None when it is degenerate).
#[inline]
fn barycentric(p: [DVec2; 3], q: DVec2) -> Option<[f64; 3]> {
    let e1 = p[1] - p[0];
    let e2 = p[2] - p[0];
    let det = e1.perp_dot(e2);
    let scale = e1.length_squared().max(e2.length_squared());
    if det.abs() <= 1e-14 * scale {
        return None;
    }
    let r = q - p[0];
    let l1 = r.perp_dot(e2) / det;
    let l2 = e1.perp_dot(r) / det;
    Some([1.0 - l1 - l2, l1, l2])
}

/// Does segment a–b come within `tol` of triangle `p` (2D; separating axes)?
fn segment_meets_triangle(a: DVec2, b: DVec2, p: [DVec2; 3], tol: f64) -> bool {
    let separated = |axis: DVec2| {
        let len = axis.length();
        if len == 0.0 {
            return false;
        }
        let axis = axis / len;
        let (s0, s1) = (a.dot(axis), b.dot(axis));
        let (smin, smax) = (s0.min(s1), s0.max(s1));
        let t = p.map(|v| v.dot(axis));
        let (tmin, tmax) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
        smin > tmax + tol || tmin > smax + tol
    };
    let seg = b - a;
    !(separated(seg.perp())
        || separated((p[1] - p[0]).perp())
        || separated((p[2] - p[1]).perp())
        || separated((p[0] - p[2]).perp())
        || separated(DVec2::X)
        || separated(DVec2::Y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_meet_triangles_as_drawn() {
        let t = [DVec2::ZERO, DVec2::X, DVec2::Y];
        assert!(segment_meets_triangle(
            DVec2::new(-1.0, 0.2),
            DVec2::new(2.0, 0.2),
            t,
            0.0
        ));
        assert!(!segment_meets_triangle(
            DVec2::new(0.6, 0.6),
            DVec2::new(2.0, 2.0),
            t,
            0.0
        ));
        assert!(segment_meets_triangle(
            DVec2::new(0.5, 0.5),
            DVec2::new(2.0, 2.0),
            t,
            1e-12
        ));
        assert!(segment_meets_triangle(
            DVec2::new(0.1, 0.1),
            DVec2::new(0.2, 0.1),
            t,
            0.0
        ));
    }
}
