//! The polygons of a face that has many, as a hierarchy of boxes in the face's plane,
//! built once per request.
//!
//! A flat face that is not convex is kept as its triangles ([`super::polygons`]): a
//! finely meshed ring (a rocket body's aft annulus at 200k triangles) holds ~1,500. A
//! shadow segment's test against such a face, and cutting the face into cells along its
//! lines, would visit every triangle each time, so the face's cost would grow with its
//! tessellation rather than with the lines that cross it. With the tree, a segment's test
//! visits only the boxes it comes near, and cutting takes a box no line crosses as one
//! cell of known area ([`super::cells::Cells::wholes`]).

use super::cells::area_centroid;
use crate::geometry::polygon::line_meets_box;
use glam::DVec2;

/// Faces with more polygons than this get a tree.
pub const MIN_POLYGONS: usize = 16;
/// Most polygons in a leaf.
const LEAF: usize = 4;
/// No tree.
const NONE: u32 = u32::MAX;

/// A box of a face's polygons (in its plane's coordinates, m), with their total area
/// (m²) and a point inside the largest of them.
#[derive(Clone, Copy, Debug)]
pub struct Node {
    pub lo: DVec2,
    pub hi: DVec2,
    pub area: f64,
    pub point: DVec2,
    /// A leaf (`count` > 0): its polygons are `order[start..start + count]`; else its
    /// children are nodes `start` and `start + 1`.
    start: u32,
    count: u32,
}

impl Node {
    /// The box's corners, counter-clockwise.
    pub fn corners(&self) -> [DVec2; 4] {
        let (lo, hi) = (self.lo, self.hi);
        [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)]
    }
}

/// What a walk does at a node.
pub enum Visit {
    /// Nothing below it matters.
    Skip,
    /// Go down to its polygons.
    Open,
}

/// The trees of the faces that have more than [`MIN_POLYGONS`] polygons.
#[derive(Clone, Default)]
pub struct FaceTrees {
    /// Per face: its root node, or [`NONE`].
    root: Vec<u32>,
    nodes: Vec<Node>,
    /// Polygon indices, leaf by leaf.
    order: Vec<u32>,
}

/// A polygon's box, area (m²) and centroid, for the build.
#[derive(Clone, Copy)]
struct Item {
    k: u32,
    lo: DVec2,
    hi: DVec2,
    area: f64,
    centre: DVec2,
}

impl FaceTrees {
    /// `of_face`: per face its range of polygons; `corners2(k)`: polygon k's corners in
    /// its face's plane.
    pub fn build<'c>(of_face: &[(u32, u32)], corners2: impl Fn(usize) -> &'c [DVec2]) -> Self {
        let mut t = FaceTrees {
            root: vec![NONE; of_face.len()],
            ..Default::default()
        };
        let mut items = Vec::new();
        for (f, &(a, b)) in of_face.iter().enumerate() {
            if ((b - a) as usize) <= MIN_POLYGONS {
                continue;
            }
            items.clear();
            items.extend((a..b).map(|k| {
                let c = corners2(k as usize);
                let lo = c.iter().fold(DVec2::splat(f64::INFINITY), |m, &q| m.min(q));
                let hi = c
                    .iter()
                    .fold(DVec2::splat(f64::NEG_INFINITY), |m, &q| m.max(q));
                let (area, centre) = area_centroid(c);
                Item {
                    k,
                    lo,
                    hi,
                    area,
                    centre,
                }
            }));
            let root = t.nodes.len();
            t.nodes.push(placeholder());
            t.grow(root, &mut items);
            t.root[f] = root as u32;
        }
        t
    }

    /// Fills node `at` with `items`; returns the largest item's area.
    fn grow(&mut self, at: usize, items: &mut [Item]) -> f64 {
        let lo = items
            .iter()
            .fold(DVec2::splat(f64::INFINITY), |m, i| m.min(i.lo));
        let hi = items
            .iter()
            .fold(DVec2::splat(f64::NEG_INFINITY), |m, i| m.max(i.hi));
        let area = items.iter().map(|i| i.area).sum();
        if items.len() <= LEAF {
            let best = items
                .iter()
                .max_by(|x, y| x.area.total_cmp(&y.area))
                .expect("a leaf holds a polygon");
            self.nodes[at] = Node {
                lo,
                hi,
                area,
                point: best.centre,
                start: self.order.len() as u32,
                count: items.len() as u32,
            };
            self.order.extend(items.iter().map(|i| i.k));
            return best.area;
        }
        // halves at the median of the centroids along the box's longer side
        let (cl, ch) = items.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(l, h), i| (l.min(i.centre), h.max(i.centre)),
        );
        let axis = usize::from(ch.y - cl.y > ch.x - cl.x);
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |x, y| x.centre[axis].total_cmp(&y.centre[axis]));
        let first = self.nodes.len();
        self.nodes.push(placeholder());
        self.nodes.push(placeholder());
        let (left, right) = items.split_at_mut(mid);
        let (a, b) = (self.grow(first, left), self.grow(first + 1, right));
        let point = if a >= b {
            self.nodes[first].point
        } else {
            self.nodes[first + 1].point
        };
        self.nodes[at] = Node {
            lo,
            hi,
            area,
            point,
            start: first as u32,
            count: 0,
        };
        a.max(b)
    }

    /// Face `f`'s root node, when it has a tree.
    #[inline]
    pub fn root(&self, f: usize) -> Option<usize> {
        let r = *self.root.get(f)?;
        (r != NONE).then_some(r as usize)
    }

    /// Walks down from node `root`: `visit(node)` says whether to go below a node, and
    /// `polygon(k)` is called with each polygon of a leaf opened; the walk stops when it
    /// returns true. Returns whether it stopped.
    pub fn walk(
        &self,
        root: usize,
        mut visit: impl FnMut(&Node) -> Visit,
        mut polygon: impl FnMut(usize) -> bool,
    ) -> bool {
        // the tree is balanced: its depth is log2(polygons / LEAF) + 1
        let mut stack = [0u32; 64];
        stack[0] = root as u32;
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if let Visit::Skip = visit(node) {
                continue;
            }
            if node.count == 0 {
                stack[top] = node.start;
                stack[top + 1] = node.start + 1;
                top += 2;
                continue;
            }
            let (s, n) = (node.start as usize, node.count as usize);
            for &k in &self.order[s..s + n] {
                if polygon(k as usize) {
                    return true;
                }
            }
        }
        false
    }

    /// Does segment a–b come within `tol` (m) of one of the polygons under `root`, as
    /// `meets(k)` says of polygon k? Only the boxes the segment comes near are opened.
    pub fn segment_meets(
        &self,
        root: usize,
        a: DVec2,
        b: DVec2,
        tol: f64,
        meets: impl FnMut(usize) -> bool,
    ) -> bool {
        let (slo, shi) = (a.min(b) - DVec2::splat(tol), a.max(b) + DVec2::splat(tol));
        self.walk(
            root,
            |n| {
                let (lo, hi) = (n.lo - DVec2::splat(tol), n.hi + DVec2::splat(tol));
                if slo.cmpgt(hi).any() || shi.cmplt(lo).any() || !line_meets_box(a, b, lo, hi) {
                    Visit::Skip
                } else {
                    Visit::Open
                }
            },
            meets,
        )
    }
}

fn placeholder() -> Node {
    Node {
        lo: DVec2::ZERO,
        hi: DVec2::ZERO,
        area: 0.0,
        point: DVec2::ZERO,
        start: 0,
        count: 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat ring (inner radius 0.5 m, outer 1 m) of `n` segments as 2n triangles.
    fn ring(n: usize) -> Vec<[DVec2; 3]> {
        let at = |r: f64, i: usize| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            DVec2::new(r * t.cos(), r * t.sin())
        };
        (0..n)
            .flat_map(|i| {
                let (a, b, c, d) = (at(0.5, i), at(1.0, i), at(1.0, i + 1), at(0.5, i + 1));
                [[a, b, c], [a, c, d]]
            })
            .collect()
    }

    fn tree_of(tris: &[[DVec2; 3]]) -> FaceTrees {
        FaceTrees::build(&[(0, tris.len() as u32)], |k| &tris[k][..])
    }

    #[test]
    fn the_tree_holds_every_polygon_once_and_the_areas_add_up() {
        let tris = ring(200);
        let t = tree_of(&tris);
        let root = t.root(0).expect("a face of 400 triangles has a tree");
        let mut seen = vec![0; tris.len()];
        t.walk(
            root,
            |_| Visit::Open,
            |k| {
                seen[k] += 1;
                false
            },
        );
        assert!(seen.iter().all(|&s| s == 1));
        let total: f64 = tris.iter().map(|c| area_centroid(c).0).sum();
        // the same areas, summed in another order: rounding only
        assert!((t.nodes[root].area - total).abs() <= 1e-12 * total);
        // every node's point lies in its box
        for n in &t.nodes {
            assert!(n.point.cmpge(n.lo).all() && n.point.cmple(n.hi).all());
        }
        // a face of few polygons has none
        assert!(tree_of(&tris[..MIN_POLYGONS]).root(0).is_none());
    }

    #[test]
    fn a_segment_meets_the_tree_where_it_meets_one_of_the_polygons() {
        // against testing every triangle, on segments of every length, many of them
        // across the hole, where they meet no triangle
        let tris = ring(300);
        let t = tree_of(&tris);
        let root = t.root(0).unwrap();
        let mut rnd = crate::test_rng(7);
        let mut range = |lo: f64, hi: f64| lo + (hi - lo) * rnd();
        let tol = 1e-9;
        let (mut met, mut missed) = (0, 0);
        for _ in 0..4000 {
            let a = DVec2::new(range(-1.2, 1.2), range(-1.2, 1.2));
            let len = 10f64.powf(range(-4.0, 0.5));
            let t_ = range(0.0, std::f64::consts::TAU);
            let b = a + len * DVec2::new(t_.cos(), t_.sin());
            let meets = |k: usize| super::super::polygons::segment_meets(a, b, &tris[k], tol, true);
            let brute = (0..tris.len()).any(meets);
            assert_eq!(t.segment_meets(root, a, b, tol, meets), brute, "{a} {b}");
            if brute {
                met += 1;
            } else {
                missed += 1;
            }
        }
        assert!(met > 500 && missed > 500, "{met} {missed}");
    }
}
