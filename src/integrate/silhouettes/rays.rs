//! Rays along a direction from a point of a face, against a bounding-volume hierarchy of
//! the faces' polygons built once per request (f64 throughout, so a ray from a face is
//! decided at the mesh's own precision, not at f32's).
//!
//! Two questions are asked: how many sheets of the surface lie above a point along d
//! ([`Rays::count`]: the seed of each connected region's count, see [`super::counts`]),
//! and whether any does ([`Rays::blocked`]: the cells of a crossed face that is not convex).
//! A sheet counts where the ray leaves a closed piece (through a face facing along d) or
//! crosses an open one; each node keeps the cone of its closed faces' normals, so a
//! subtree whose closed faces all face away from d, and that holds no open face, is
//! skipped whole: rays near a surface that faces them skip the surface.

use super::polygons::Polygons;
use super::tally::{add, Tally};
use glam::DVec3;
use rayon::prelude::*;

/// Most polygons in a leaf.
const LEAF: usize = 4;

#[derive(Clone, Copy)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// The cone of the closed faces' normals below: axis, and the sine of its half angle
    /// (above 1: no narrow cone); whether any open face lies below.
    axis: DVec3,
    sin_half: f64,
    open: bool,
    /// A leaf: `prims[start..start + count]`; else (count 0) children at `start`,
    /// `start + 1`.
    start: u32,
    count: u32,
}

/// The hierarchy (see the module doc).
pub struct Rays {
    nodes: Vec<Node>,
    prims: Vec<u32>,
}

/// A ray's answer when a hit falls within rounding of a polygon's edge (the same sheet
/// might be counted twice, or not at all): the caller asks again from another point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ambiguous;

impl Rays {
    /// Builds the hierarchy over every polygon; `open[face]`: the face's sheet counts
    /// whichever way it faces.
    pub fn build(polys: &Polygons, open: &[bool]) -> Rays {
        let n = polys.len();
        let mut prims: Vec<u32> = (0..n as u32).collect();
        let boxes: Vec<(DVec3, DVec3)> = (0..n)
            .into_par_iter()
            .map(|k| {
                polys
                    .corners3(k)
                    .iter()
                    .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &q| {
                        (lo.min(q), hi.max(q))
                    })
            })
            .collect();
        let centres: Vec<DVec3> = boxes.par_iter().map(|b| (b.0 + b.1) * 0.5).collect();
        let build = Build {
            polys,
            open,
            boxes: &boxes,
            centres: &centres,
        };
        let mut nodes = Vec::with_capacity(2 * n / LEAF + 1);
        nodes.push(leaf(0, n));
        // The top levels on one thread, down to subtrees of at most an eighth of the
        // polygons; those built side by side, each in its own table, then appended
        // (a subtree's nodes are its own, so the tree is the same whichever thread built
        // what).
        let apart = if n >= 2 * PARALLEL {
            (n / 8).max(PARALLEL)
        } else {
            0
        };
        let mut subtrees = Vec::new();
        let root = Pending {
            node: 0,
            start: 0,
            end: n,
            depth: 0,
        };
        build.grow(&mut nodes, &mut prims, 0, root, apart, &mut subtrees);
        // each subtree's polygons, a range of `prims` of its own
        subtrees.sort_unstable_by_key(|p| p.start);
        let mut rest = &mut prims[..];
        let mut at = 0;
        let mut jobs = Vec::with_capacity(subtrees.len());
        for p in &subtrees {
            let (_, tail) = std::mem::take(&mut rest).split_at_mut(p.start - at);
            let (mine, tail) = tail.split_at_mut(p.end - p.start);
            (rest, at) = (tail, p.end);
            jobs.push((*p, mine));
        }
        let built: Vec<(usize, Vec<Node>)> = jobs
            .into_par_iter()
            .map(|(p, mine)| {
                let mut local = vec![leaf(p.start, p.end)];
                let root = Pending { node: 0, ..p };
                build.grow(&mut local, mine, p.start, root, 0, &mut Vec::new());
                (p.node, local)
            })
            .collect();
        for (i, local) in built {
            // the subtree's root in the place left for it, its other nodes appended: a
            // child at local index c (never 0, the root's) lands at `base + c - 1`
            let base = nodes.len();
            let moved = |mut node: Node| {
                if node.count == 0 {
                    node.start = (base + node.start as usize - 1) as u32;
                }
                node
            };
            nodes[i] = moved(local[0]);
            nodes.extend(local[1..].iter().map(|&node| moved(node)));
        }
        Rays { nodes, prims }
    }

    /// How many sheets the ray from `x` along unit `d` crosses beyond `eps` (m), leaving
    /// out face `own`: polygons of open faces, and of closed ones facing along d.
    /// `amb` (m): a hit that close to a polygon's edge makes the answer [`Ambiguous`].
    #[allow(clippy::too_many_arguments)]
    pub fn count(
        &self,
        polys: &Polygons,
        open: &[bool],
        x: DVec3,
        d: DVec3,
        own: u32,
        eps: f64,
        amb: f64,
    ) -> Result<u32, Ambiguous> {
        let mut n = 0;
        let mut ambiguous = false;
        self.visit(polys, open, x, d, own, eps, |corners, q| {
            match classify(corners, q, amb) {
                Hit::Inside => n += 1,
                Hit::Outside => {}
                Hit::Edge => {
                    ambiguous = true;
                    return true;
                }
            }
            false
        });
        if ambiguous {
            Err(Ambiguous)
        } else {
            Ok(n)
        }
    }

    /// Does the ray from `x` along unit `d` cross any sheet beyond `eps` (m), leaving out
    /// face `own`?
    pub fn blocked(
        &self,
        polys: &Polygons,
        open: &[bool],
        x: DVec3,
        d: DVec3,
        own: u32,
        eps: f64,
    ) -> bool {
        let mut hit = false;
        self.visit(polys, open, x, d, own, eps, |corners, q| {
            hit |= classify(corners, q, 0.0) != Hit::Outside;
            hit
        });
        hit
    }

    /// Calls `hit(corners, q)` for every polygon that counts along d whose plane the ray
    /// meets beyond `eps`, with its corners and the point met in its face's plane
    /// coordinates; stops when `hit` returns true.
    #[allow(clippy::too_many_arguments)]
    fn visit(
        &self,
        polys: &Polygons,
        open: &[bool],
        x: DVec3,
        d: DVec3,
        own: u32,
        eps: f64,
        mut hit: impl FnMut(&[glam::DVec2], glam::DVec2) -> bool,
    ) {
        let tiny = |c: f64| if c == 0.0 { 1e-300 } else { c };
        let inv = DVec3::ONE / DVec3::new(tiny(d.x), tiny(d.y), tiny(d.z));
        // from depth SAH_DEPTH on the splits are medians: the depth stays below
        // SAH_DEPTH + log2(polygons / LEAF), far below the stack's size
        let mut stack: [u32; 96] = [0; 96];
        let mut top = 1usize;
        add(Tally::Rays, 1);
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            add(Tally::RayNodes, 1);
            if !node.open && node.axis.dot(d) < -node.sin_half - 1e-12 {
                continue;
            }
            if !meets_box(node.lo, node.hi, x, inv, eps) {
                continue;
            }
            if node.count == 0 {
                stack[top] = node.start;
                stack[top + 1] = node.start + 1;
                top += 2;
                continue;
            }
            let s = node.start as usize;
            add(Tally::RayLeafPolygons, u64::from(node.count));
            for &k in &self.prims[s..s + node.count as usize] {
                let k = k as usize;
                let f = polys.face[k];
                if f == own {
                    continue;
                }
                let fi = f as usize;
                let n = polys.normal[fi];
                let nd = n.dot(d);
                if nd.abs() < 1e-12 || !(open[fi] || nd > 0.0) {
                    continue;
                }
                let t = n.dot(polys.point[fi] - x) / nd;
                if t <= eps {
                    continue;
                }

                add(Tally::RayPlanes, 1);
                let q = polys.to2(fi, x + d * t);
                if hit(polys.corners2(k), q) {
                    return;
                }
            }
        }
    }
}

/// Where a point lies against a convex polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Hit {
    Inside,
    Outside,
    /// Within `amb` of an edge, and not clearly outside.
    Edge,
}

/// Where `q` lies against convex polygon `c` (counter-clockwise, as every polygon of
/// [`Polygons`] is: u × w is its face's normal), `amb` (m) of an edge counting as on it.
#[inline]
fn classify(c: &[glam::DVec2], q: glam::DVec2, amb: f64) -> Hit {
    let n = c.len();
    let mut near = false;
    for i in 0..n {
        let (a, b) = (c[i], c[if i + 1 == n { 0 } else { i + 1 }]);
        let e = b - a;
        // |e| times q's distance inside the edge's line
        let s = e.perp_dot(q - a);
        let room = amb * amb * e.length_squared();
        if s < 0.0 && s * s > room {
            return Hit::Outside;
        }
        near |= s * s <= room;
    }
    if near {
        Hit::Edge
    } else {
        Hit::Inside
    }
}

/// Bins along the centres' longest extent for the split's cost.
const BINS: usize = 16;
/// What building the hierarchy reads: the polygons, which faces are open, and each
/// polygon's box (m) and its centre.
struct Build<'a> {
    polys: &'a Polygons,
    open: &'a [bool],
    boxes: &'a [(DVec3, DVec3)],
    centres: &'a [DVec3],
}

/// A node still to bound and split: its index in its table, its polygons' range of the
/// whole `prims` table, its depth.
#[derive(Clone, Copy)]
struct Pending {
    node: usize,
    start: usize,
    end: usize,
    depth: usize,
}

impl Build<'_> {
    /// Grows the subtree of node `root` (`prims` holding `prims[at..]` of the whole
    /// table): each node bounded and split until its leaves hold at most [`LEAF`]
    /// polygons, except that a node of at most `apart` polygons (and more than a leaf's)
    /// is left as it is and listed in `later`.
    fn grow(
        &self,
        nodes: &mut Vec<Node>,
        prims: &mut [u32],
        at: usize,
        root: Pending,
        apart: usize,
        later: &mut Vec<Pending>,
    ) {
        let mut todo = vec![root];
        while let Some(pending) = todo.pop() {
            let Pending {
                node: i,
                start: s,
                end: e,
                depth,
            } = pending;
            if e - s > LEAF && e - s <= apart {
                later.push(pending);
                continue;
            }
            let range = &mut prims[s - at..e - at];
            let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            let (mut clo, mut chi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            for &k in range.iter() {
                let (a, b) = self.boxes[k as usize];
                lo = lo.min(a);
                hi = hi.max(b);
                clo = clo.min(self.centres[k as usize]);
                chi = chi.max(self.centres[k as usize]);
            }
            let (axis, sin_half, any_open) = cone(self.polys, self.open, range);
            nodes[i].lo = lo;
            nodes[i].hi = hi;
            nodes[i].axis = axis;
            nodes[i].sin_half = sin_half;
            nodes[i].open = any_open;
            if e - s <= LEAF {
                continue;
            }
            let mid = split(
                range,
                self.boxes,
                self.centres,
                clo,
                chi,
                depth >= SAH_DEPTH,
            );
            let left = nodes.len();
            nodes.push(leaf(s, s + mid));
            nodes.push(leaf(s + mid, e));
            nodes[i].start = left as u32;
            nodes[i].count = 0;
            for (node, start, end) in [(left, s, s + mid), (left + 1, s + mid, e)] {
                todo.push(Pending {
                    node,
                    start,
                    end,
                    depth: depth + 1,
                });
            }
        }
    }
}

/// Fewest polygons in a subtree built apart from the rest (on another thread).
const PARALLEL: usize = 4096;

/// Depth from which nodes are split at the median (keeps the tree's depth bounded).
const SAH_DEPTH: usize = 40;

/// Orders `range` (polygons with `boxes` and `centres`, the centres within `clo`–`chi`)
/// into two halves and returns the first's length: where the binned surface-area
/// heuristic puts the cut (a ray meets a box about in proportion to its surface, and
/// the faces' polygons range from a bus's whole side to a dish's sliver), or at the
/// median when every centre falls in one bin or `median_only` is asked for.
fn split(
    range: &mut [u32],
    boxes: &[(DVec3, DVec3)],
    centres: &[DVec3],
    clo: DVec3,
    chi: DVec3,
    median_only: bool,
) -> usize {
    let ext = chi - clo;
    let k = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    let median = |range: &mut [u32]| {
        let mid = range.len() / 2;
        range.select_nth_unstable_by(mid, |&a, &b| {
            centres[a as usize][k].total_cmp(&centres[b as usize][k])
        });
        mid
    };
    if median_only || ext[k] <= 0.0 {
        return median(range);
    }
    // a product, not a quotient, for every polygon at every level
    let per_bin = BINS as f64 / ext[k];
    let bin_of = |c: DVec3| (((c[k] - clo[k]) * per_bin) as usize).min(BINS - 1);
    let empty = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    let mut bins = [(empty, 0usize); BINS];
    for &p in range.iter() {
        let (b, n) = &mut bins[bin_of(centres[p as usize])];
        let (lo, hi) = boxes[p as usize];
        *b = (b.0.min(lo), b.1.max(hi));
        *n += 1;
    }
    let area = |(lo, hi): (DVec3, DVec3)| {
        let d = (hi - lo).max(DVec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    };
    // the cost of each cut after bin i: left's area × count + right's
    let mut left = [0.0; BINS];
    let (mut b, mut n) = (empty, 0);
    for i in 0..BINS - 1 {
        b = (b.0.min(bins[i].0 .0), b.1.max(bins[i].0 .1));
        n += bins[i].1;
        left[i] = if n > 0 {
            area(b) * n as f64
        } else {
            f64::INFINITY
        };
    }
    let (mut best, mut cut) = (f64::INFINITY, usize::MAX);
    let (mut b, mut n) = (empty, 0);
    for i in (0..BINS - 1).rev() {
        b = (b.0.min(bins[i + 1].0 .0), b.1.max(bins[i + 1].0 .1));
        n += bins[i + 1].1;
        let cost = if n > 0 {
            left[i] + area(b) * n as f64
        } else {
            f64::INFINITY
        };
        if cost < best {
            (best, cut) = (cost, i);
        }
    }
    if cut == usize::MAX {
        return median(range);
    }
    // the polygons of bins up to `cut` first
    let mut i = 0;
    for j in 0..range.len() {
        if bin_of(centres[range[j] as usize]) <= cut {
            range.swap(i, j);
            i += 1;
        }
    }
    if i == 0 || i == range.len() {
        median(range)
    } else {
        i
    }
}

fn leaf(s: usize, e: usize) -> Node {
    Node {
        lo: DVec3::ZERO,
        hi: DVec3::ZERO,
        axis: DVec3::Z,
        sin_half: 2.0,
        open: true,
        start: s as u32,
        count: (e - s) as u32,
    }
}

/// The cone of the closed polygons' normals among `range` and whether any is open.
fn cone(polys: &Polygons, open: &[bool], range: &[u32]) -> (DVec3, f64, bool) {
    let mut sum = DVec3::ZERO;
    let mut any_open = false;
    let mut closed = 0;
    for &k in range {
        let f = polys.face[k as usize] as usize;
        if open[f] {
            any_open = true;
        } else {
            sum += polys.normal[f];
            closed += 1;
        }
    }
    let Some(axis) = sum.try_normalize() else {
        return (DVec3::Z, 2.0, any_open || closed > 0);
    };
    let cos_min = range
        .iter()
        .map(|&k| polys.face[k as usize] as usize)
        .filter(|&f| !open[f])
        .map(|f| polys.normal[f].dot(axis))
        .fold(1.0f64, f64::min)
        .clamp(-1.0, 1.0);
    let half = cos_min.acos() + 1e-9;
    let sin_half = if half < std::f64::consts::FRAC_PI_2 {
        half.sin()
    } else {
        2.0
    };
    (axis, sin_half, any_open)
}

/// Does the ray x + t·inv⁻¹, t > eps, pass through the box (widened by eps)? `inv`: the
/// reciprocal of the direction, whose zero components were replaced by a tiny number
/// (so no 0·∞ makes a NaN).
#[inline]
fn meets_box(lo: DVec3, hi: DVec3, x: DVec3, inv: DVec3, eps: f64) -> bool {
    let a = (lo - DVec3::splat(eps) - x) * inv;
    let b = (hi + DVec3::splat(eps) - x) * inv;
    let near = a.min(b).max_element().max(eps);
    let far = a.max(b).min_element();
    near <= far
}

#[cfg(test)]
mod tests {
    use super::super::fixtures;
    use super::*;
    use crate::geometry::builtin::push_box;
    use crate::geometry::Mesh;

    #[test]
    fn a_ray_counts_each_closed_box_it_leaves() {
        // two unit boxes stacked along z with a gap, and one off to the side
        let mut mesh = Mesh::default();
        push_box(
            &mut mesh,
            DVec3::new(0.0, 0.0, 2.0),
            DVec3::new(1.0, 1.0, 3.0),
            0,
        );
        push_box(
            &mut mesh,
            DVec3::new(0.0, 0.0, 4.0),
            DVec3::new(1.0, 1.0, 5.0),
            0,
        );
        push_box(
            &mut mesh,
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(4.0, 1.0, 1.0),
            0,
        );
        let b = fixtures::build(&mesh);
        let rays = Rays::build(&b.polys, &b.topo.open);
        let count =
            |x: DVec3, d: DVec3| rays.count(&b.polys, &b.topo.open, x, d, u32::MAX, 1e-9, 1e-9);
        let up = DVec3::Z;
        // below both stacked boxes, between them, above them, beside them
        assert_eq!(count(DVec3::new(0.3, 0.6, 0.0), up), Ok(2));
        assert_eq!(count(DVec3::new(0.3, 0.6, 3.5), up), Ok(1));
        assert_eq!(count(DVec3::new(0.3, 0.6, 6.0), up), Ok(0));
        assert_eq!(count(DVec3::new(2.0, 0.5, 0.0), up), Ok(0));
        // inside a box: it leaves that one and the one above
        assert_eq!(count(DVec3::new(0.3, 0.6, 2.5), up), Ok(2));
        // slanted, from below the stack through both
        let d = DVec3::new(0.05, 0.02, 1.0).normalize();
        assert_eq!(count(DVec3::new(0.3, 0.4, 0.0), d), Ok(2));
        // through an edge of the top box: within rounding of two polygons' edges
        assert_eq!(count(DVec3::new(1.0, 0.5, 0.0), up), Err(Ambiguous));
        // blocked agrees with the count away from edges
        let blocked = |x: DVec3| rays.blocked(&b.polys, &b.topo.open, x, up, u32::MAX, 1e-9);
        assert!(blocked(DVec3::new(0.3, 0.6, 3.5)));
        assert!(!blocked(DVec3::new(0.3, 0.6, 6.0)));
    }

    #[test]
    fn the_hierarchy_finds_what_testing_every_polygon_finds_on_a_mesh_of_mixed_scales() {
        // a 40 m slab, a finely meshed ball resting on it and a small box: polygons from
        // a 40 m square to ~3 cm triangles, which the split's cost sorts unevenly
        let mut mesh = Mesh::default();
        push_box(
            &mut mesh,
            DVec3::new(-20.0, -20.0, -0.5),
            DVec3::new(20.0, 20.0, 0.0),
            0,
        );
        push_box(
            &mut mesh,
            DVec3::new(2.0, -0.2, 0.1),
            DVec3::new(2.3, 0.2, 0.9),
            0,
        );
        fixtures::push_ball(&mut mesh, 12, 0.5, DVec3::new(0.4, 0.1, 0.6));
        let b = fixtures::build(&mesh);
        let rays = Rays::build(&b.polys, &b.topo.open);
        let (polys, open) = (&b.polys, &b.topo.open);
        let eps = 1e-9;
        // every polygon the ray meets beyond eps, as `visit` asks of a leaf
        let brute = |x: DVec3, d: DVec3| -> Result<u32, Ambiguous> {
            let mut n = 0;
            for k in 0..polys.len() {
                let f = polys.face[k] as usize;
                let nd = polys.normal[f].dot(d);
                if nd.abs() < 1e-12 || !(open[f] || nd > 0.0) {
                    continue;
                }
                let t = polys.normal[f].dot(polys.point[f] - x) / nd;
                if t <= eps {
                    continue;
                }
                match classify(polys.corners2(k), polys.to2(f, x + d * t), eps) {
                    Hit::Inside => n += 1,
                    Hit::Outside => {}
                    Hit::Edge => return Err(Ambiguous),
                }
            }
            Ok(n)
        };
        let mut rng = crate::test_rng(7);
        let mut hits = 0;
        for _ in 0..2000 {
            let x = DVec3::new(4.0 * rng() - 1.6, 2.0 * rng() - 0.9, 1.6 * rng() - 0.2);
            let d = DVec3::new(rng() - 0.5, rng() - 0.5, rng() - 0.2).normalize();
            let want = brute(x, d);
            assert_eq!(rays.count(polys, open, x, d, u32::MAX, eps, eps), want);
            if let Ok(n) = want {
                hits += n;
                let blocked = rays.blocked(polys, open, x, d, u32::MAX, eps);
                assert_eq!(blocked, n > 0, "from {x} along {d}");
            }
        }
        // the rays meet sheets often enough for the comparison to mean something
        assert!(hits > 500, "{hits} sheets met");
    }
}
