//! The folds along one direction as a tree of their boxes across d and their tops along d
//! ([`FoldTree`]): a patch asks it for the folds that may lie above its box, and a
//! subtree whose box misses the patch's, or whose highest fold is below the patch, is
//! passed over whole.
//!
//! Folds crowd where the outlines are (a dish's rim, a bell's lip) and are sparse
//! elsewhere; a tree follows that crowding where a uniform grid cannot, and holds each
//! fold once, so no query meets a fold twice.

use super::folds::Fold;
use glam::DVec2;

/// Most folds a leaf holds.
const LEAF: usize = 4;

/// A node: the box across d (m) and the highest top along d (m) of its folds; a leaf
/// (`count > 0`) holds folds `first..first + count`; an inner node's first child follows
/// it, and `skip` is the node after its subtree.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: DVec2,
    hi: DVec2,
    top: f64,
    skip: u32,
    first: u32,
    count: u32,
}

/// The folds of one direction in a tree, built anew for each direction.
#[derive(Default)]
pub struct FoldTree {
    nodes: Vec<Node>,
    /// (Morton key of a fold's box centre, the fold's index), sorted.
    keys: Vec<u64>,
    /// Room for the folds in their new order.
    sorted: Vec<Fold>,
}

impl FoldTree {
    /// Puts `folds` in the order of their boxes' centres along a Morton curve across d
    /// (neighbours in the plane neighbours in the list) and builds the tree over them.
    pub fn build(&mut self, folds: &mut Vec<Fold>) {
        self.nodes.clear();
        if folds.is_empty() {
            return;
        }
        let (lo, hi, _) = bounds(folds);
        // centres on a 2^16 lattice over the folds' box
        let scale = DVec2::splat(65535.0) / (hi - lo).max(DVec2::splat(1e-300));
        self.keys.clear();
        self.keys.extend(folds.iter().enumerate().map(|(i, f)| {
            let c = ((f.pa + f.pb) * 0.5 - lo) * scale;
            let (x, y) = (
                c.x.clamp(0.0, 65535.0) as u32,
                c.y.clamp(0.0, 65535.0) as u32,
            );
            (morton(x, y) as u64) << 32 | i as u64
        }));
        self.keys.sort_unstable();
        self.sorted.clear();
        self.sorted
            .extend(self.keys.iter().map(|&k| folds[(k & 0xffff_ffff) as usize]));
        std::mem::swap(folds, &mut self.sorted);
        self.node(folds, 0, folds.len());
    }

    /// Appends the subtree over `folds[a..b]`; returns its box and top.
    fn node(&mut self, folds: &[Fold], a: usize, b: usize) -> (DVec2, DVec2, f64) {
        let at = self.nodes.len();
        self.nodes.push(Node {
            lo: DVec2::ZERO,
            hi: DVec2::ZERO,
            top: 0.0,
            skip: 0,
            first: a as u32,
            count: 0,
        });
        let (lo, hi, top) = if b - a <= LEAF {
            self.nodes[at].count = (b - a) as u32;
            bounds(&folds[a..b])
        } else {
            // halves in whole leaves, so that only the last leaf is short
            let m = a + (b - a).div_ceil(2 * LEAF) * LEAF;
            let (l0, h0, t0) = self.node(folds, a, m);
            let (l1, h1, t1) = self.node(folds, m, b);
            (l0.min(l1), h0.max(h1), t0.max(t1))
        };
        let skip = self.nodes.len() as u32;
        let n = &mut self.nodes[at];
        (n.lo, n.hi, n.top, n.skip) = (lo, hi, top, skip);
        (lo, hi, top)
    }

    /// Calls `found(i)` once for every fold (an index into the folds as [`build`]
    /// reordered them) in a leaf whose box meets box `lo`–`hi` (m, across d) and whose
    /// highest fold is above `bottom` (m along d): every fold whose box meets the box and
    /// whose top is above `bottom` among them.
    ///
    /// [`build`]: FoldTree::build
    #[inline]
    pub fn query(&self, lo: DVec2, hi: DVec2, bottom: f64, mut found: impl FnMut(u32)) {
        let mut i = 0;
        while i < self.nodes.len() {
            let n = &self.nodes[i];
            let off = (n.top <= bottom)
                | (n.lo.x > hi.x)
                | (n.lo.y > hi.y)
                | (n.hi.x < lo.x)
                | (n.hi.y < lo.y);
            if off {
                i = n.skip as usize;
                continue;
            }
            for k in n.first..n.first + n.count {
                found(k);
            }
            i += 1;
        }
    }
}

/// The box across d (m) and the highest top along d (m) of `folds`.
fn bounds(folds: &[Fold]) -> (DVec2, DVec2, f64) {
    let empty = (
        DVec2::splat(f64::INFINITY),
        DVec2::splat(f64::NEG_INFINITY),
        f64::NEG_INFINITY,
    );
    folds.iter().fold(empty, |(lo, hi, top), f| {
        let (flo, fhi) = f.box_across();
        (lo.min(flo), hi.max(fhi), top.max(f.top))
    })
}

/// The bits of `x` and `y` (16 each) interleaved, `x` in the even bits.
fn morton(x: u32, y: u32) -> u32 {
    fn spread(mut v: u32) -> u32 {
        v &= 0xffff;
        v = (v | v << 8) & 0x00ff_00ff;
        v = (v | v << 4) & 0x0f0f_0f0f;
        v = (v | v << 2) & 0x3333_3333;
        (v | v << 1) & 0x5555_5555
    }
    spread(x) | spread(y) << 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fold across d from `pa` to `pb` with top `top`, tagged by `edge`.
    fn fold(pa: DVec2, pb: DVec2, top: f64, edge: u32) -> Fold {
        Fold {
            a: pa.extend(top),
            b: pb.extend(top),
            pa,
            pb,
            top,
            jump: 1,
            bounds: true,
            faces: (0, 1),
            edge,
        }
    }

    #[test]
    fn a_query_finds_each_fold_above_and_over_the_box_once_as_all_pairs_compared_do() {
        let mut uniform = crate::test_rng(7);
        for n in [0usize, 1, 3, 4, 5, 17, 64, 333] {
            // crowded in one corner, sparse elsewhere, short and long, some degenerate
            let mut folds: Vec<Fold> = (0..n)
                .map(|e| {
                    let crowd = uniform() < 0.7;
                    let s = if crowd { 0.1 } else { 10.0 };
                    let pa = DVec2::new(uniform(), uniform()) * s;
                    let len = if e % 5 == 0 { 0.0 } else { uniform() * s * 0.3 };
                    let pb = pa + DVec2::new(uniform() - 0.5, uniform() - 0.5) * len;
                    fold(pa, pb, uniform() * 4.0 - 2.0, e as u32)
                })
                .collect();
            let mut tree = FoldTree::default();
            tree.build(&mut folds);
            // the folds are reordered, not changed
            let mut edges: Vec<u32> = folds.iter().map(|f| f.edge).collect();
            edges.sort_unstable();
            assert_eq!(edges, (0..n as u32).collect::<Vec<_>>());
            for _ in 0..200 {
                let c = DVec2::new(uniform(), uniform()) * 10.0 * uniform();
                let h = DVec2::new(uniform(), uniform()) * uniform();
                let (lo, hi, bottom) = (c - h, c + h, uniform() * 4.0 - 2.0);
                let mut got = Vec::new();
                tree.query(lo, hi, bottom, |i| got.push(i));
                let mut seen = got.clone();
                seen.sort_unstable();
                seen.dedup();
                assert_eq!(seen.len(), got.len(), "a fold met twice");
                for (i, f) in folds.iter().enumerate() {
                    let (flo, fhi) = f.box_across();
                    let meets = f.top > bottom && flo.cmple(hi).all() && fhi.cmpge(lo).all();
                    if meets {
                        assert!(got.contains(&(i as u32)), "fold {i} of {n} missed");
                    }
                }
            }
        }
    }
}
