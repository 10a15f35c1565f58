//! The fold edges along one direction d: the edges across whose shadow the number of
//! sheets above a point changes ([`super::topology::Edge::jump`] not zero): where the
//! surface folds over as seen along d (a ridge or a valley with one side facing along d
//! and the other away), an open surface's border, or where more than two sheets meet.
//!
//! Only a patch that faces both ways along d can hold a fold inside it, and only a rim
//! between patches that face differently can be one: the search visits those, not every
//! edge ([`super::patches`]).

use super::patches::{Facing, Patches, RimEdge, MAX_FLAT_FACES};
use super::tally::{add, Tally};
use super::topology::{Edge, Topology, NONE};
use glam::{DVec2, DVec3};

/// A fold edge along d.
#[derive(Debug, Clone, Copy)]
pub struct Fold {
    /// Its ends, m.
    pub a: DVec3,
    pub b: DVec3,
    /// Its ends across d (in the basis (u, w), u × w = d), m.
    pub pa: DVec2,
    pub pb: DVec2,
    /// Its highest point along d, m.
    pub top: f64,
    /// How many more sheets lie above a point just left of pa → pb than just right of it.
    pub jump: i32,
    /// Not a valley: a face may turn from lit to dark across its shadow.
    pub bounds: bool,
    /// The edge's faces (a valley's two sides, whose planes bound its notch).
    pub faces: (u32, u32),
    /// The edge's index in the topology.
    pub edge: u32,
}

impl Fold {
    /// Its box across d (lowest, highest corner; m).
    #[inline]
    pub fn box_across(&self) -> (DVec2, DVec2) {
        (self.pa.min(self.pb), self.pa.max(self.pb))
    }
}

/// Finds every fold along unit `d` (every edge that is one, except perhaps an edge
/// whose two triangles wind the same way along it: the search does not look inside a
/// patch that faces one way) (basis across it `(u, w)`, u × w = d); `facing`: each
/// patch's facing along d; `normal`: each face's unit normal; `blocks(face)`: the face's
/// sheet counts along d; `(maybe_folds, out)`: room for the edges that may be folds, and
/// the folds.
#[allow(clippy::too_many_arguments)]
pub fn find(
    patches: &Patches,
    topo: &Topology,
    facing: &[Facing],
    normal: &[DVec3],
    d: DVec3,
    u: DVec3,
    w: DVec3,
    blocks: impl Fn(u32) -> bool + Copy,
    (maybe_folds, out): (&mut Vec<u32>, &mut Vec<Fold>),
) {
    out.clear();
    maybe_folds.clear();
    // The edges that may be folds are listed first and read after: at ~200k triangles
    // the edges' table is larger than the caches, and reading each edge as it was found
    // waited on its misses one edge at a time.
    let mut list = |e: u32| maybe_folds.push(e);
    // edge e, when it is a fold (it is not `same_way`)
    let read = |e: u32, out: &mut Vec<Fold>| {
        let edge = &topo.edges[e as usize];
        let jump = edge.jump(u, w, blocks);
        if jump != 0 {
            out.push(Fold {
                a: edge.a,
                b: edge.b,
                pa: DVec2::new(edge.a.dot(u), edge.a.dot(w)),
                pb: DVec2::new(edge.b.dot(u), edge.b.dot(w)),
                top: edge.a.dot(d).max(edge.b.dot(d)),
                jump,
                bounds: !edge.valley,
                faces: (edge.f0, edge.f1),
                edge: e,
            });
        }
    };
    // as `same_way`, from the patch's copy of the edge's faces
    let passes = |pe: &RimEdge| {
        pe.f1 == NONE
            || pe.always
            || !one_way(normal[pe.f0 as usize].dot(d), normal[pe.f1 as usize].dot(d))
    };
    // a patch's faces' n·d, in the order of its list (a patch holds at most
    // MAX_FLAT_FACES)
    let mut side = [0.0f64; MAX_FLAT_FACES];
    for p in 0..patches.len() {
        let fp = facing[p];
        if fp == Facing::Mixed {
            add(Tally::MixedPatches, 1);
            add(Tally::MixedFaces, patches.faces_of(p).len() as u64);
            add(Tally::InnerEdges, patches.inner_of(p).len() as u64);
            for (s, &f) in side.iter_mut().zip(patches.faces_of(p)) {
                *s = normal[f as usize].dot(d);
            }
            for inner in patches.inner_of(p) {
                let (a, b) = (side[inner.at.0 as usize], side[inner.at.1 as usize]);
                if inner.always || !one_way(a, b) {
                    list(inner.edge);
                }
            }
        }
        // two patches facing one way meet without a fold, unless they face away and
        // only one of them blocks that way (an open piece's face beside a closed one's)
        let plain = |q: u32| {
            q != NONE
                && fp != Facing::Mixed
                && facing[q as usize] == fp
                && (fp == Facing::Along || patches.open[p] == patches.open[q as usize])
        };
        // so a patch whose every neighbour it meets plainly, and no border, has no fold
        // on its rim
        if !patches.border[p] && patches.links_of(p).iter().all(|l| plain(l.patch)) {
            continue;
        }
        add(Tally::RimEdges, patches.rim_of(p).len() as u64);
        for rim in patches.rim_of(p) {
            if !plain(rim.other) && passes(rim) {
                list(rim.edge);
            }
        }
    }
    // a word from the start, middle and end of each listed edge (an edge spans two or
    // three cache lines) loaded by loads that wait on nothing, so that their misses
    // overlap; then each edge read whole from the cache
    let touched = maybe_folds.iter().fold(0u64, |x, &e| {
        let edge = &topo.edges[e as usize];
        x ^ edge.a.x.to_bits() ^ edge.in0.x.to_bits() ^ edge.in1.z.to_bits() ^ u64::from(edge.f0)
    });
    std::hint::black_box(touched);
    for &e in maybe_folds.iter() {
        read(e, out);
    }
}

/// Do the faces either side of `edge` both face along `d` or both away, with sheets of
/// one kind (both open or both closed), and wind opposite ways along it? The surface does
/// not fold over between them then: they lie on either side of the edge seen along d,
/// and count alike.
#[inline]
pub fn same_way(topo: &Topology, normal: &[DVec3], edge: &Edge, d: DVec3) -> bool {
    let (f, g) = (edge.f0 as usize, edge.f1 as usize);
    let (a, b) = (normal[f].dot(d), normal[g].dot(d));
    !edge.flipped && topo.open[f] == topo.open[g] && one_way(a, b)
}

/// Do two faces with n·d = `a` and `b` both face along d, or both away (neither edge-on)?
#[inline]
fn one_way(a: f64, b: f64) -> bool {
    (a > 1e-12 && b > 1e-12) || (a < -1e-12 && b < -1e-12)
}

#[cfg(test)]
mod tests {
    use super::super::{fixtures, polygons};
    use super::*;
    use crate::geometry::builtin::geodesic_sphere;

    #[test]
    fn on_every_builtin_class_the_search_finds_every_fold_that_testing_each_edge_finds() {
        // Brute force over every edge: not `same_way`, and a jump. The search may leave
        // out only an edge whose triangles wind the same way inside a patch that faces
        // one way (its doc says why); on these meshes (borders, open panels, crumpled
        // and curved surfaces, patches that face both ways) it must find all the rest.
        let mut with_mixed = 0;
        for b in crate::geometry::builtin::BUILTINS {
            let mesh = (b.build)(crate::geometry::builtin::Detail::Coarse);
            let built = fixtures::build(&mesh);
            let (normal, topo) = (&built.polys.normal, &built.topo);
            let mut out = Vec::new();
            let mut mixed_seen = false;
            for d in fixtures::directions() {
                let (u, w) = polygons::basis(d);
                let facing: Vec<Facing> = (0..built.patches.len())
                    .map(|p| built.patches.facing(p, d))
                    .collect();
                mixed_seen |= facing.contains(&Facing::Mixed);
                let blocks = |f: u32| {
                    let nd = normal[f as usize].dot(d);
                    nd.abs() > 1e-12 && (topo.open[f as usize] || nd > 0.0)
                };
                find(
                    &built.patches,
                    topo,
                    &facing,
                    normal,
                    d,
                    u,
                    w,
                    blocks,
                    (&mut Vec::new(), &mut out),
                );
                let mut found: Vec<u32> = out.iter().map(|f| f.edge).collect();
                found.sort_unstable();
                let want: Vec<u32> = (0..topo.edges.len() as u32)
                    .filter(|&e| {
                        let edge = &topo.edges[e as usize];
                        !(edge.f1 != NONE && same_way(topo, normal, edge, d))
                            && edge.jump(u, w, blocks) != 0
                    })
                    .filter(|&e| {
                        let edge = &topo.edges[e as usize];
                        let p = built.patches.of_face[edge.f0 as usize] as usize;
                        let inside_one_way = edge.f1 != NONE
                            && built.patches.of_face[edge.f1 as usize] as usize == p
                            && facing[p] != Facing::Mixed;
                        !(edge.flipped && inside_one_way)
                    })
                    .collect();
                assert_eq!(found, want, "{}: the folds along {d}", b.name);
            }
            with_mixed += usize::from(mixed_seen);
        }
        // the curved ones had patches that face both ways (the plate and the cubesat's
        // flat boxes and panels have none)
        assert!(
            with_mixed >= 5,
            "{with_mixed} meshes with patches facing both ways"
        );
    }

    #[test]
    fn on_a_closed_convex_mesh_the_folds_are_its_outline_edges() {
        let mesh = geodesic_sphere(10, 1.5);
        let b = fixtures::build(&mesh);
        let normal = &b.polys.normal;
        let mut out = Vec::new();
        for d in fixtures::directions() {
            let (u, w) = polygons::basis(d);
            let facing: Vec<Facing> = (0..b.patches.len())
                .map(|p| b.patches.facing(p, d))
                .collect();
            let blocks = |f: u32| normal[f as usize].dot(d) > 1e-12;
            find(
                &b.patches,
                &b.topo,
                &facing,
                normal,
                d,
                u,
                w,
                blocks,
                (&mut Vec::new(), &mut out),
            );
            // by brute force over every edge: one face along d, the other away
            let mut want: Vec<(u32, u32)> = b
                .topo
                .edges
                .iter()
                .filter(|e| blocks(e.f0) != blocks(e.f1))
                .map(|e| (e.f0.min(e.f1), e.f0.max(e.f1)))
                .collect();
            want.sort_unstable();
            assert!(!want.is_empty());
            assert_eq!(out.len(), want.len());
            for f in &out {
                // one sheet more on one side than the other, never a valley on a convex
                // solid, and its ends where the edge's are
                assert_eq!(f.jump.abs(), 1);
                assert!(f.bounds);
                assert!((f.pa - DVec2::new(f.a.dot(u), f.a.dot(w))).length() < 1e-12);
                let e = b
                    .topo
                    .edges
                    .iter()
                    .find(|e| e.a == f.a && e.b == f.b)
                    .unwrap();
                assert!(want
                    .binary_search(&(e.f0.min(e.f1), e.f0.max(e.f1)))
                    .is_ok());
            }
        }
    }
}
