//! Where separate pieces of the mesh touch or cross (the *contacts*: a boom's foot on a
//! bus), found once per request: the segments where triangles of different faces that
//! share no vertex meet ([`contact_segments`]), and how the count of sheets above a face
//! changes across one along a direction ([`Contact::jump`]).

use crate::geometry::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// Where another piece meets a face: a segment in the face's plane (m) and the other
/// piece's triangle (its corners, m, and its face) that meets the face along it. Above
/// the face, that triangle is a sheet on one side of the segment: the count changes
/// across it as across a fold ([`Contact::jump`]).
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    pub a: DVec3,
    pub b: DVec3,
    pub other: [DVec3; 3],
    pub face: u32,
}

impl Contact {
    /// How many more sheets lie just left of the segment than just right of it (seen
    /// along `d` in the plane's coordinates of a face with unit normal `n` through `o`;
    /// `to2` maps a point of that plane to them); `blocks`: whether the other face's
    /// sheet counts along d. Zero when the other triangle lies below the plane along d.
    pub fn jump(
        &self,
        n: DVec3,
        o: DVec3,
        d: DVec3,
        eps: f64,
        blocks: bool,
        to2: impl Fn(DVec3) -> glam::DVec2,
    ) -> i32 {
        if !blocks {
            return 0;
        }
        let nd = n.dot(d);
        // the other triangle's corners above the plane, along d
        let (mut sum, mut k) = (DVec3::ZERO, 0);
        for v in self.other {
            if n.dot(v - o) / nd > eps {
                sum += v;
                k += 1;
            }
        }
        if k == 0 {
            return 0;
        }
        let c = sum / k as f64;
        let onto = |x: DVec3| to2(x - d * (n.dot(x - o) / nd));
        let (pa, pb, pc) = (onto(self.a), onto(self.b), onto(c));
        let s = (pb - pa).perp_dot(pc - pa);
        if s > 0.0 {
            1
        } else if s < 0.0 {
            -1
        } else {
            0
        }
    }
}

/// Segments (m) where triangles of different faces that share no vertex meet: each is
/// recorded on both faces. Found through a uniform grid of the triangles' boxes. With
/// `group` (per triangle), only triangles of one group are paired: the contacts that a
/// rigid motion of each group carries along ([`Across`] finds the others).
pub(super) fn contact_segments(
    mesh: &Mesh,
    welded: &[u32],
    tri_face: &[u32],
    group: Option<&[u32]>,
    tol: f64,
) -> Vec<(u32, Contact)> {
    let nt = mesh.triangles.len();
    if nt < 2 {
        return Vec::new();
    }
    let corners: Vec<[DVec3; 3]> = (0..nt).map(|i| mesh.corners(i)).collect();
    let boxes: Vec<(DVec3, DVec3)> = corners.iter().map(|c| box_of(c, tol)).collect();
    let grid = BoxGrid::build(&boxes, tol);
    let found = Found {
        mesh,
        welded,
        tri_face,
        group,
        corners: &corners,
        boxes: &boxes,
        tol,
    };
    let pairs = meeting_pairs(&found, &grid);
    join_pieces(&pairs, &corners, tri_face, tol)
}

/// A triangle's box widened by `tol` (m).
#[inline]
fn box_of(c: &[DVec3; 3], tol: f64) -> (DVec3, DVec3) {
    let lo = c[0].min(c[1]).min(c[2]) - DVec3::splat(tol);
    let hi = c[0].max(c[1]).max(c[2]) + DVec3::splat(tol);
    (lo, hi)
}

/// Per group of triangles that move as one (the body, each articulated link): where its
/// triangles meet another group's, found anew for each pose without the pairs inside a
/// group. The body's grid is built once: it does not move.
pub(super) struct Across {
    /// Per group: its triangles (mesh indices).
    members: Vec<Vec<u32>>,
    /// The body's (group 0's) boxes, widened by the tolerance they were built with,
    /// binned.
    body: Option<BoxGrid>,
}

impl Across {
    /// `group`: per triangle, its group (0 the body, which never moves, then the links);
    /// `groups`: how many.
    pub fn build(mesh: &Mesh, group: &[u32], groups: usize, tol: f64) -> Across {
        let mut members = vec![Vec::new(); groups];
        for (t, &g) in group.iter().enumerate() {
            members[g as usize].push(t as u32);
        }
        let body = (groups > 1 && !members[0].is_empty()).then(|| {
            let boxes: Vec<_> = members[0]
                .iter()
                .map(|&t| box_of(&mesh.corners(t as usize), tol))
                .collect();
            BoxGrid::build(&boxes, tol)
        });
        Across { members, body }
    }

    /// The contacts between triangles of two groups, `corners` (per triangle, m) posed
    /// (the body's as built), as [`contact_segments`] finds them on the posed mesh:
    /// the same pairs (their boxes widened by `tol` overlap, they meet) and segments.
    /// No two groups may share a vertex.
    pub fn contacts(
        &self,
        corners: &[[DVec3; 3]],
        tri_face: &[u32],
        tol: f64,
    ) -> Vec<(u32, Contact)> {
        let ng = self.members.len();
        let mut pairs = Vec::new();
        let mut stamp: Vec<u32> = Vec::new();
        for g in 0..ng {
            for h in g + 1..ng {
                // the smaller group's triangles asked against the larger's grid: the
                // body's as built, a link's binned for this pose
                let (small, large) = if g == 0 || self.members[h].len() <= self.members[g].len() {
                    (h, g)
                } else {
                    (g, h)
                };
                let (a, b) = (&self.members[small], &self.members[large]);
                if a.is_empty() || b.is_empty() {
                    continue;
                }
                let built;
                let grid = match (&self.body, large) {
                    (Some(grid), 0) => grid,
                    _ => {
                        let boxes: Vec<_> = b
                            .iter()
                            .map(|&t| box_of(&corners[t as usize], tol))
                            .collect();
                        built = BoxGrid::build(&boxes, tol);
                        &built
                    }
                };
                stamp.clear();
                stamp.resize(b.len(), u32::MAX);
                for &s in a {
                    let bs = box_of(&corners[s as usize], tol);
                    // what a box binned within `tol` of it can share a cell with
                    let ask = (bs.0 - DVec3::splat(tol), bs.1 + DVec3::splat(tol));
                    for c in grid.cells_of(ask) {
                        for &k in grid.in_cell(grid.linear(c)) {
                            if std::mem::replace(&mut stamp[k as usize], s) == s {
                                continue;
                            }
                            let t = b[k as usize];
                            let bt = box_of(&corners[t as usize], tol);
                            if bs.0.cmpgt(bt.1).any() || bt.0.cmpgt(bs.1).any() {
                                continue;
                            }
                            let (lo, hi) = (s.min(t), s.max(t));
                            let (cl, ch) = (&corners[lo as usize], &corners[hi as usize]);
                            if let Some(seg) = meet(cl, ch, tol) {
                                pairs.push((lo, hi, seg));
                            }
                        }
                    }
                }
            }
        }
        join_pieces(&pairs, corners, tri_face, tol)
    }
}

/// What [`meeting_pairs`] looks through: the mesh, its welded ids, each triangle's face
/// and group (pairs only within one, when given), corners and boxes (widened by `tol`).
struct Found<'a> {
    mesh: &'a Mesh,
    welded: &'a [u32],
    tri_face: &'a [u32],
    group: Option<&'a [u32]>,
    corners: &'a [[DVec3; 3]],
    boxes: &'a [(DVec3, DVec3)],
    tol: f64,
}

/// The triangles' boxes binned in a uniform grid of cells.
struct BoxGrid {
    lo: DVec3,
    /// Cell side, m.
    cell: f64,
    dims: glam::UVec3,
    /// Per cell: its range of `binned` (CSR).
    start: Vec<u32>,
    binned: Vec<u32>,
}

impl BoxGrid {
    fn build(boxes: &[(DVec3, DVec3)], tol: f64) -> BoxGrid {
        let nt = boxes.len();
        let (lo, hi) = boxes
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), b| {
                (lo.min(b.0), hi.max(b.1))
            });
        // cells of about the median triangle's box size
        let mut sizes: Vec<f64> = boxes.iter().map(|b| (b.1 - b.0).max_element()).collect();
        let mid = sizes.len() / 2;
        sizes.select_nth_unstable_by(mid, f64::total_cmp);
        let extent = (hi - lo).max(DVec3::splat(tol));
        // at most ~8 cells a triangle (a finely meshed dish beside long panels would
        // otherwise ask for millions of empty cells), and at most 1024 along an axis
        let volume = extent.x * extent.y * extent.z;
        let cell = sizes[mid]
            .max((volume / (8.0 * nt as f64).min(4.0e6)).cbrt())
            .max(extent.max_element() / 1024.0)
            .max(tol);
        let dims =
            ((extent / cell).ceil().as_uvec3()).clamp(glam::UVec3::ONE, glam::UVec3::splat(1025));
        let mut grid = BoxGrid {
            lo,
            cell,
            dims,
            start: Vec::new(),
            binned: Vec::new(),
        };
        // the triangles binned by cell (a counting sort: no comparison sort of the entries)
        let n_cells = (dims.x * dims.y * dims.z) as usize;
        let mut start = vec![0u32; n_cells + 1];
        for b in boxes {
            for c in grid.cells_of(*b) {
                start[grid.linear(c) + 1] += 1;
            }
        }
        for i in 0..n_cells {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut binned = vec![0u32; start[n_cells] as usize];
        for (t, b) in boxes.iter().enumerate() {
            for c in grid.cells_of(*b) {
                let k = grid.linear(c);
                binned[fill[k] as usize] = t as u32;
                fill[k] += 1;
            }
        }
        grid.start = start;
        grid.binned = binned;
        grid
    }

    /// The cell holding point `p` (clamped to the grid).
    fn index(&self, p: DVec3) -> glam::UVec3 {
        let q = ((p - self.lo) / self.cell).floor();
        glam::UVec3::new(
            (q.x.max(0.0) as u32).min(self.dims.x - 1),
            (q.y.max(0.0) as u32).min(self.dims.y - 1),
            (q.z.max(0.0) as u32).min(self.dims.z - 1),
        )
    }

    fn linear(&self, c: glam::UVec3) -> usize {
        (c.x + self.dims.x * (c.y + self.dims.y * c.z)) as usize
    }

    /// The cells box `b` touches.
    fn cells_of(&self, b: (DVec3, DVec3)) -> impl Iterator<Item = glam::UVec3> {
        let (a, z) = (self.index(b.0), self.index(b.1));
        (a.z..=z.z).flat_map(move |w| {
            (a.y..=z.y).flat_map(move |y| (a.x..=z.x).map(move |x| glam::UVec3::new(x, y, w)))
        })
    }

    /// The triangles binned in cell `k` (linear index).
    fn in_cell(&self, k: usize) -> &[u32] {
        &self.binned[self.start[k] as usize..self.start[k + 1] as usize]
    }

    /// How many cells box `b` touches.
    fn span(&self, b: (DVec3, DVec3)) -> u32 {
        let (a, z) = (self.index(b.0), self.index(b.1));
        (z - a + glam::UVec3::ONE).element_product()
    }
}

/// Every pair of triangles (lower index first) of different faces, sharing no welded
/// vertex, that meet, with the segment where they do.
fn meeting_pairs(found: &Found, grid: &BoxGrid) -> Vec<(u32, u32, (DVec3, DVec3))> {
    let Found {
        mesh,
        welded,
        tri_face,
        group,
        corners,
        boxes,
        tol,
    } = *found;
    let nt = boxes.len();
    // each pair sharing a cell is tested once, by the triangle of the two that spans fewer
    // cells (a large panel's triangle is found by the small ones in its cells, instead of
    // scanning them all), and the pairs are then put in order
    let spans: Vec<u32> = boxes.iter().map(|&b| grid.span(b)).collect();
    (0..nt)
        .into_par_iter()
        .map_init(
            || (vec![u32::MAX; nt], Vec::new()),
            |(stamp, near), s| {
                near.clear();
                let mine = (spans[s], s);
                for c in grid.cells_of(boxes[s]) {
                    for &t in grid.in_cell(grid.linear(c)) {
                        let ti = t as usize;
                        if ti != s && mine < (spans[ti], ti) && stamp[ti] != s as u32 {
                            stamp[ti] = s as u32;
                            near.push(t);
                        }
                    }
                }
                let mut found = Vec::new();
                for &t in near.iter() {
                    let t = t as usize;
                    if tri_face[s] == tri_face[t] || group.is_some_and(|g| g[s] != g[t]) {
                        continue;
                    }
                    let (bs, bt) = (boxes[s], boxes[t]);
                    if bs.0.cmpgt(bt.1).any() || bt.0.cmpgt(bs.1).any() {
                        continue;
                    }
                    let (ts, tt) = (mesh.triangles[s], mesh.triangles[t]);
                    let shares = ts
                        .iter()
                        .any(|&a| tt.iter().any(|&b| welded[a as usize] == welded[b as usize]));
                    if shares {
                        continue;
                    }
                    let (lo, hi) = (s.min(t), s.max(t));
                    if let Some(seg) = meet(&corners[lo], &corners[hi], tol) {
                        found.push((lo as u32, hi as u32, seg));
                    }
                }
                found
            },
        )
        .flatten()
        .collect()
}

/// The pairs' segments as contacts, on both faces of each pair, with a face's pieces along
/// one other triangle joined where they overlap.
fn join_pieces(
    pairs: &[(u32, u32, (DVec3, DVec3))],
    corners: &[[DVec3; 3]],
    tri_face: &[u32],
    tol: f64,
) -> Vec<(u32, Contact)> {
    // Each contact seen from both sides: (receiving face, other triangle, segment).
    let mut seen: Vec<(u32, u32, (DVec3, DVec3))> = Vec::with_capacity(2 * pairs.len());
    for &(s, t, seg) in pairs {
        seen.push((tri_face[s as usize], t, seg));
        seen.push((tri_face[t as usize], s, seg));
    }
    // A face of several triangles meets another triangle along one line (the triangle
    // across the face's plane), found once per triangle of the face that it touches: where
    // that line runs along an edge inside the face, both triangles beside the edge find
    // the same piece, and counting it twice would double its jump. So the pieces of one
    // face and one other triangle are joined where they overlap.
    seen.sort_unstable_by_key(|c| (c.0, c.1));
    let mut out = Vec::with_capacity(seen.len());
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for group in seen.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let (face, other) = (group[0].0, group[0].1 as usize);
        let contact = |a: DVec3, b: DVec3| {
            (
                face,
                Contact {
                    a,
                    b,
                    other: corners[other],
                    face: tri_face[other],
                },
            )
        };
        if group.len() == 1 {
            let (a, b) = group[0].2;
            out.push(contact(a, b));
            continue;
        }
        let (o, e) = (
            group[0].2 .0,
            (group[0].2 .1 - group[0].2 .0).normalize_or_zero(),
        );
        spans.clear();
        spans.extend(group.iter().map(|&(_, _, (a, b))| {
            let (s, t) = ((a - o).dot(e), (b - o).dot(e));
            (s.min(t), s.max(t))
        }));
        spans.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
        let mut cur = spans[0];
        for &(lo, hi) in &spans[1..] {
            if lo <= cur.1 + tol {
                cur.1 = cur.1.max(hi);
            } else {
                out.push(contact(o + e * cur.0, o + e * cur.1));
                cur = (lo, hi);
            }
        }
        out.push(contact(o + e * cur.0, o + e * cur.1));
    }
    out
}

/// The segment where triangles `a` and `b` meet (touching within `tol` counts), when it
/// is longer than `tol`; coplanar triangles are left out (nothing in a face's plane
/// shades it).
pub fn meet(a: &[DVec3; 3], b: &[DVec3; 3], tol: f64) -> Option<(DVec3, DVec3)> {
    let na = (a[1] - a[0]).cross(a[2] - a[0]).normalize_or_zero();
    let nb = (b[1] - b[0]).cross(b[2] - b[0]).normalize_or_zero();
    let line = na.cross(nb);
    if line.length() < 1e-9 {
        return None;
    }
    let line = line.normalize();
    let sa = cut_by_plane(a, nb, b[0], tol, line)?;
    let sb = cut_by_plane(b, na, a[0], tol, line)?;
    let lo = sa.0.max(sb.0);
    let hi = sa.1.min(sb.1);
    if hi - lo <= tol {
        return None;
    }
    // a point on the line: from a's segment
    let (p0, t0) = sa.2;
    Some((p0 + line * (lo - t0), p0 + line * (hi - t0)))
}

/// The interval (along `line`) of triangle `t` where it meets the plane (`n`, through
/// `p`), with a point on it and that point's parameter.
fn cut_by_plane(
    t: &[DVec3; 3],
    n: DVec3,
    p: DVec3,
    tol: f64,
    line: DVec3,
) -> Option<(f64, f64, (DVec3, f64))> {
    let s = t.map(|v| n.dot(v - p));
    if s.iter().all(|&x| x > tol) || s.iter().all(|&x| x < -tol) {
        return None;
    }
    let mut pts: [DVec3; 4] = [DVec3::ZERO; 4];
    let mut k = 0;
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i].abs() <= tol {
            pts[k] = t[i];
            k += 1;
            if k == 4 {
                break;
            }
        }
        if (s[i] > tol && s[j] < -tol) || (s[i] < -tol && s[j] > tol) {
            let u = s[i] / (s[i] - s[j]);
            pts[k] = t[i] + (t[j] - t[i]) * u;
            k += 1;
            if k == 4 {
                break;
            }
        }
    }
    if k < 2 {
        return None;
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for q in &pts[..k] {
        let x = q.dot(line);
        lo = lo.min(x);
        hi = hi.max(x);
    }
    Some((lo, hi, (pts[0], pts[0].dot(line))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_post_standing_on_a_plate_meets_it_along_its_foot() {
        // a vertical triangle whose bottom edge lies on the plate z = 0
        let plate = [
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let post = [
            DVec3::new(-0.2, 0.0, 0.0),
            DVec3::new(0.2, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        ];
        let (p, q) = meet(&plate, &post, 1e-9).expect("they meet");
        let (lo, hi) = (p.x.min(q.x), p.x.max(q.x));
        assert!(
            (lo + 0.2).abs() < 1e-12 && (hi - 0.2).abs() < 1e-12,
            "{p} {q}"
        );
        assert!(p.y.abs() < 1e-12 && p.z.abs() < 1e-12);
        // lifted off the plate: no contact
        let lifted = post.map(|v| v + DVec3::Z * 0.01);
        assert!(meet(&plate, &lifted, 1e-9).is_none());
        // piercing it: the segment inside the plate
        let pierce = post.map(|v| v - DVec3::Z * 0.5);
        let (p, q) = meet(&plate, &pierce, 1e-9).expect("pierces");
        assert!(((p - q).length() - 0.2).abs() < 1e-12);
    }
}
