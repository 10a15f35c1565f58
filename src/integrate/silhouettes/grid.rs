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
    /// Per polygon corner: its position across d (m).
    pub at: Vec<DVec2>,
    lo: DVec2,
    inv_cell: f64,
    nx: usize,
    ny: usize,
    /// Per polygon binned: its box across d (m).
    boxes: Vec<(DVec2, DVec2)>,
    /// Polygons per cell (CSR).
    start: Vec<u32>,
    items: Vec<u32>,
    counts: Vec<u32>,
    /// The polygons binned (a buffer kept from direction to direction).
    kept: Vec<u32>,
    /// Per polygon: the last segment query that met it, and the current query's number.
    seen: Vec<u32>,
    query: u32,
    /// Per binned polygon: its first and last cells (a buffer kept between directions).
    spans: Vec<[u32; 4]>,
}

/// What the grid needs of the mesh: its faces as convex polygons (a face's outline when
/// it is convex, else its triangles), by vertex index.
pub struct Polygons<'a> {
    /// The polygons' corners, m.
    pub vertices: &'a [DVec3],
    /// Per polygon: its range of `index`.
    pub spans: &'a [(u32, u32)],
    pub index: &'a [u32],
    /// Per polygon: its face; per face: its unit normal and a point of its plane.
    pub face: &'a [u32],
    pub normal: &'a [DVec3],
    pub point: &'a [DVec3],
}

impl Polygons<'_> {
    pub fn len(&self) -> usize {
        self.spans.len()
    }

    /// Polygon `i`'s plane: its face's unit normal and a point of it.
    fn plane(&self, i: usize) -> (DVec3, DVec3) {
        let f = self.face[i] as usize;
        (self.normal[f], self.point[f])
    }

    fn corners(&self, i: usize) -> &[u32] {
        let (a, b) = self.spans[i];
        &self.index[a as usize..b as usize]
    }
}

impl Grid {
    /// Projects the mesh along `d` and bins the polygons `keep` says may block.
    pub fn build(&mut self, mesh: &Polygons, d: DVec3, keep: impl Fn(usize) -> bool) {
        let (u, w) = crate::geometry::orthonormal_basis(d);
        self.d = d;
        self.u = u;
        self.w = w;
        self.at.clear();
        self.at
            .extend(mesh.vertices.iter().map(|v| DVec2::new(v.dot(u), v.dot(w))));
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for &p in &self.at {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        let ext = (hi - lo).max(DVec2::splat(1e-300));
        let mut kept = std::mem::take(&mut self.kept);
        kept.clear();
        kept.extend((0..mesh.len() as u32).filter(|&t| keep(t as usize)));
        // only the binned polygons' boxes are ever read (through the cells)
        self.boxes.resize(
            mesh.len(),
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::INFINITY)),
        );
        for &t in &kept {
            let (mut a, mut b) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            for &i in mesh.corners(t as usize) {
                a = a.min(self.at[i as usize]);
                b = b.max(self.at[i as usize]);
            }
            self.boxes[t as usize] = (a, b);
        }
        // about one polygon a cell (measured on the suite: two a cell is 5-10 % slower,
        // half a cell slower again where long strips span many cells)
        let cells = (kept.len() as f64).max(1.0);
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
        // each polygon's cells, found once for both passes of the counting sort
        let mut spans = std::mem::take(&mut self.spans);
        spans.clear();
        // (whole rows of cells as slices: no per-cell bounds checks or inclusive ranges)
        for &t in &kept {
            let (a, b) = self.cell_box(t as usize);
            spans.push([a.0 as u32, a.1 as u32, b.0 as u32, b.1 as u32]);
            for y in a.1..b.1 + 1 {
                let row = y * self.nx + 1;
                for c in &mut self.counts[row + a.0..row + b.0 + 1] {
                    *c += 1;
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
        for (&t, &[x0, y0, x1, y1]) in kept.iter().zip(&spans) {
            for y in y0 as usize..y1 as usize + 1 {
                let row = y * self.nx;
                for c in &mut self.counts[row + x0 as usize..row + x1 as usize + 1] {
                    self.items[*c as usize] = t;
                    *c += 1;
                }
            }
        }
        self.spans = spans;
        self.kept = kept;
    }

    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let q = (p - self.lo) * self.inv_cell;
        (
            (q.x.max(0.0) as usize).min(self.nx - 1),
            (q.y.max(0.0) as usize).min(self.ny - 1),
        )
    }

    /// The cells binned polygon `t`'s box spans (first, last).
    fn cell_box(&self, t: usize) -> ((usize, usize), (usize, usize)) {
        let (lo, hi) = self.boxes[t];
        (self.cell_of(lo), self.cell_of(hi))
    }

    fn cell(&self, x: usize, y: usize) -> &[u32] {
        let c = y * self.nx + x;
        &self.items[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// Position across d and height along d of a point.
    pub fn project(&self, p: DVec3) -> (DVec2, f64) {
        (DVec2::new(p.dot(self.u), p.dot(self.w)), p.dot(self.d))
    }

    /// Does the ray from `p` along d meet a polygon (of another face than `own`) more
    /// than `eps` (m) above `p`?
    pub fn blocked(&self, mesh: &Polygons, p: DVec3, own: u32, eps: f64) -> bool {
        let (q, _) = self.project(p);
        let (x, y) = self.cell_of(q);
        self.cell(x, y).iter().any(|&t| {
            let t = t as usize;
            let (lo, hi) = self.boxes[t];
            if q.cmplt(lo).any() || q.cmpgt(hi).any() || mesh.face[t] == own {
                return false;
            }
            let (n, o) = mesh.plane(t);
            let nd = n.dot(self.d);
            if nd == 0.0 {
                return false;
            }
            // how far along d the ray meets the polygon's plane
            let along = n.dot(o - p) / nd;
            along > eps && self.inside(mesh.corners(t), q)
        })
    }

    /// Is `q` inside (or on) the projected convex polygon?
    fn inside(&self, corners: &[u32], q: DVec2) -> bool {
        let n = corners.len();
        let (mut pos, mut neg) = (false, false);
        for k in 0..n {
            let a = self.at[corners[k] as usize];
            let b = self.at[corners[(k + 1) % n] as usize];
            let s = (b - a).perp_dot(q - a);
            pos |= s > 0.0;
            neg |= s < 0.0;
            if pos && neg {
                return false;
            }
        }
        true
    }

    /// Calls `hit(t)` for every binned polygon `t` that `receives` says may take a
    /// shadow and over which the segment a–b (m) passes above its plane by more than
    /// `eps`, within `tol` across d.
    #[allow(clippy::too_many_arguments)]
    pub fn shadowed_by(
        &mut self,
        mesh: &Polygons,
        a: DVec3,
        b: DVec3,
        eps: f64,
        tol: f64,
        receives: impl Fn(usize) -> bool,
        mut hit: impl FnMut(u32),
    ) {
        let (pa, _) = self.project(a);
        let (pb, _) = self.project(b);
        let lo = pa.min(pb) - DVec2::splat(tol);
        let hi = pa.max(pb) + DVec2::splat(tol);
        let (_, y0) = self.cell_of(lo);
        let (_, y1) = self.cell_of(hi);
        // each polygon once per segment, however many of its cells the segment passes
        self.query = self.query.wrapping_add(1);
        if self.query == 0 {
            self.seen.iter_mut().for_each(|s| *s = 0);
            self.query = 1;
        }
        self.seen.resize(self.boxes.len(), 0);
        let cell = 1.0 / self.inv_cell;
        for y in y0..=y1 {
            // the cells of this row that the segment passes within tol of: a long
            // diagonal edge visits the cells along it, not its whole box
            let (ylo, yhi) = (
                self.lo.y + y as f64 * cell - tol,
                self.lo.y + (y + 1) as f64 * cell + tol,
            );
            let dy = pb.y - pa.y;
            let (t0, t1) = if dy == 0.0 {
                (0.0, 1.0)
            } else {
                let (ta, tb) = ((ylo - pa.y) / dy, (yhi - pa.y) / dy);
                (ta.min(tb).max(0.0), ta.max(tb).min(1.0))
            };
            if t0 > t1 {
                continue;
            }
            let (xa, xb) = (pa.x + (pb.x - pa.x) * t0, pa.x + (pb.x - pa.x) * t1);
            let (x0, _) = self.cell_of(DVec2::new(xa.min(xb) - tol, ylo));
            let (x1, _) = self.cell_of(DVec2::new(xa.max(xb) + tol, ylo));
            for x in x0..=x1 {
                let c = y * self.nx + x;
                for &t in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                    let ti = t as usize;
                    if self.seen[ti] == self.query {
                        continue;
                    }
                    self.seen[ti] = self.query;
                    if !receives(ti) {
                        continue;
                    }
                    let (plo, phi) = self.boxes[ti];
                    if plo.cmpgt(hi).any() || phi.cmplt(lo).any() {
                        continue;
                    }
                    let corners = mesh.corners(ti);
                    let (n, o) = mesh.plane(ti);
                    let nd = n.dot(self.d);
                    if nd == 0.0 {
                        continue;
                    }
                    // heights of the segment's ends above the polygon's plane, along d
                    let sa = n.dot(a - o) / nd;
                    let sb = n.dot(b - o) / nd;
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
                    if self.segment_meets(qa, qb, corners, tol) {
                        hit(t);
                    }
                }
            }
        }
    }

    /// Does segment a–b come within `tol` of the projected convex polygon (separating
    /// axes)?
    fn segment_meets(&self, a: DVec2, b: DVec2, corners: &[u32], tol: f64) -> bool {
        // apart along `axis` by more than tol (axis not normalised: the gap is compared
        // squared with tol²·|axis|², no square root)
        let separated = |axis: DVec2| {
            let len2 = axis.length_squared();
            if len2 == 0.0 {
                return false;
            }
            let (s0, s1) = (a.dot(axis), b.dot(axis));
            let (smin, smax) = (s0.min(s1), s0.max(s1));
            let (mut tmin, mut tmax) = (f64::INFINITY, f64::NEG_INFINITY);
            for &c in corners {
                let t = self.at[c as usize].dot(axis);
                tmin = tmin.min(t);
                tmax = tmax.max(t);
            }
            let gap = (smin - tmax).max(tmin - smax);
            gap > 0.0 && gap * gap > tol * tol * len2
        };
        let n = corners.len();
        if separated((b - a).perp()) || separated(DVec2::X) || separated(DVec2::Y) {
            return false;
        }
        !(0..n).any(|k| {
            let e = self.at[corners[(k + 1) % n] as usize] - self.at[corners[k] as usize];
            separated(e.perp())
        })
    }
}
