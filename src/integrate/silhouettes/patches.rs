//! Patches: connected clusters of faces whose normals lie in a narrow cone, built once
//! per request, so that per direction most of the mesh is handled a patch at a time.
//!
//! Along a direction d a patch's cone says at once whether all its faces face along d,
//! all face away, or it is *mixed*. Only a mixed patch can hold an edge where the surface
//! folds over as seen along d, so the search for shadow edges looks inside mixed patches
//! and along the rims between patches that face differently, not at every edge; and a
//! patch that faces along d as a whole and that no shadow line reaches is one unit of the
//! flood of counts ([`super::counts`]). A finely meshed smooth surface thus costs per
//! direction what its patches and its shadow lines cost, not what its faces cost.

use super::polygons::Polygons;
use super::slab::Slab;
use super::topology::{Topology, NONE};
use crate::geometry::csr::{csr_of, sort_within};
use crate::geometry::faces::WeldedEdge;
use crate::geometry::permute::permute;
use glam::{DMat3, DVec3};
use rayon::prelude::*;

/// Most faces a patch holds wherever the surface turns (up to [`MAX_TURN_COS`]).
const MAX_FACES: usize = 16;
/// Largest angle between a face's normal and its patch's first face's normal (cos).
const MAX_TURN_COS: f64 = 0.94;
/// Most faces a patch holds where the surface stays nearly flat: past [`MAX_FACES`] a
/// patch takes only faces within [`FLAT_TURN_COS`] of its first face's normal. A finely
/// meshed smooth surface (a dish, a cylinder, at ~200k triangles) then has a quarter as
/// many patches to ask about per direction, while a crumpled one keeps small patches:
/// 64 faces everywhere cost the crumpled fragment and the rocket body at 20k triangles
/// 2–3 %, 16 everywhere the fine dishes 6–8 % (docs/performance.md, eleventh sitting).
pub(super) const MAX_FLAT_FACES: usize = 64;
/// Largest turn (cos, about 5.7°) of a face joining a patch past [`MAX_FACES`].
const FLAT_TURN_COS: f64 = 0.995;

/// How a patch faces along a direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Facing {
    /// Every face's normal has n·d > 0.
    Along,
    /// Every face's normal has n·d < 0.
    Away,
    /// Some of each, or too close to tell.
    Mixed,
}

/// An edge on a patch's rim with what the search for folds asks of it before reading
/// the edge itself: its faces, so that which way they face along a direction is read
/// from their normals (at ~200k triangles the edges' table is larger than the cache, and
/// most edges looked at are not folds).
#[derive(Debug, Clone, Copy)]
pub struct RimEdge {
    pub edge: u32,
    /// Its faces; `f1` is [`NONE`] on a border.
    pub f0: u32,
    pub f1: u32,
    /// The patch across it, [`NONE`] on a border.
    pub other: u32,
    /// Facing alone does not say that the surface does not fold here: its triangles
    /// wind the same way ([`super::topology::Edge::flipped`]), or one face's sheet is
    /// open and the other's closed.
    pub always: bool,
}

/// An edge between two faces of one patch: its index, its faces' places in the patch's
/// list of faces (a patch holds at most [`MAX_FLAT_FACES`]), and whether facing alone
/// does not say that the surface does not fold here ([`RimEdge::always`]). Along a
/// direction the search for folds finds which way each face of a patch that faces both
/// ways faces once, then reads its inner edges' faces from that.
#[derive(Debug, Clone, Copy)]
pub struct InnerEdge {
    pub edge: u32,
    pub at: (u8, u8),
    pub always: bool,
}

/// A neighbouring patch and the edges into it (a range of [`Patches::exits`]).
#[derive(Debug, Clone, Copy)]
pub struct Link {
    pub patch: u32,
    pub exits: (u32, u32),
}

/// The patches (see the module doc).
#[derive(Clone)]
pub struct Patches {
    /// Per face: its patch.
    pub of_face: Vec<u32>,
    /// Per patch: its faces (CSR).
    pub faces_at: Vec<u32>,
    pub faces: Vec<u32>,
    /// Per patch: the axis of the cone holding its normals and the sine of its half
    /// angle (above 1 when no cone narrower than a hemisphere holds them).
    pub axis: Vec<DVec3>,
    pub sin_half: Vec<f64>,
    /// Per patch: its box, as centre and half extents (m).
    pub centre: Vec<DVec3>,
    pub half: Vec<DVec3>,
    /// Per patch: the slab about its cone's axis that holds its faces ([`Slab`]).
    pub slab: Vec<Slab>,
    /// Per patch: some face of it meets another piece inside it (a contact).
    pub contacts: Vec<bool>,
    /// Per patch: its faces' sheets count along every direction (an open piece, or
    /// two-sided faces); a patch is all open or all closed (its faces are connected,
    /// and one two-sidedness).
    pub open: Vec<bool>,
    /// Per patch: the edges between two of its own faces (CSR).
    pub inner_at: Vec<u32>,
    pub inner: Vec<InnerEdge>,
    /// Per patch: the edges on its rim, each listed once over the whole mesh (in the
    /// patch of the edge's first face), with the other side's patch ([`NONE`] on a
    /// border) (CSR).
    pub rim_at: Vec<u32>,
    pub rim: Vec<RimEdge>,
    /// Per patch: an edge of its rim is a border of the mesh.
    pub border: Vec<bool>,
    /// Per patch: its neighbouring patches, each with the ways into it across an edge:
    /// (edge, face inside, face outside), a range of `exits` (CSR).
    pub links_at: Vec<u32>,
    pub links: Vec<Link>,
    pub exits: Vec<(u32, u32, u32)>,
    /// Per patch: the first face of its faces' run when their numbers are one run
    /// (faces renumbered in patch order, `order_by_patches`, mostly are), else [`NONE`]:
    /// what is noted for every face of such a patch is then noted over one range.
    pub run: Vec<u32>,
}

impl Patches {
    pub fn build(polys: &Polygons, topo: &Topology) -> Patches {
        let (of_face, faces_at, faces) = grow(polys, topo);
        let np = faces_at.len() - 1;
        let shapes = Shapes::of(polys, topo, &faces_at, &faces);
        let ((inner_at, inner), (rim_at, rim), (links_at, links, exits)) =
            edges_by_patch(topo, &of_face, (&faces_at, &faces));
        let run = (0..np)
            .map(|p| {
                let m = &faces[faces_at[p] as usize..faces_at[p + 1] as usize];
                let (lo, hi) = m
                    .iter()
                    .fold((u32::MAX, 0), |(lo, hi), &f| (lo.min(f), hi.max(f)));
                // distinct numbers: one run exactly when they span as many as there are
                if !m.is_empty() && (hi - lo) as usize + 1 == m.len() {
                    lo
                } else {
                    NONE
                }
            })
            .collect();
        Patches {
            of_face,
            faces_at,
            faces,
            axis: shapes.axis,
            sin_half: shapes.sin_half,
            centre: shapes.centre,
            half: shapes.half,
            slab: shapes.slab,
            contacts: shapes.contacts,
            open: shapes.open,
            inner_at,
            inner,
            border: (0..np)
                .map(|p| {
                    rim[rim_at[p] as usize..rim_at[p + 1] as usize]
                        .iter()
                        .any(|e| e.other == NONE)
                })
                .collect(),
            rim_at,
            rim,
            links_at,
            links,
            exits,
            run,
        }
    }

    pub fn len(&self) -> usize {
        self.axis.len()
    }

    /// The patches of the same faces moved rigidly (`polys` and `topo` moved already),
    /// each patch's faces turned by `turn(patch)`: the cones turned, the boxes and which
    /// patches contacts run through found again.
    pub fn moved(
        &self,
        polys: &Polygons,
        topo: &Topology,
        turn: impl Fn(usize) -> DMat3,
    ) -> Patches {
        let mut p = self.clone();
        for k in 0..self.len() {
            let m = self.faces_of(k);
            p.axis[k] = turn(k) * self.axis[k];
            (p.centre[k], p.half[k]) = box_of(polys, m);
            p.slab[k] = Slab::of(polys, m, p.axis[k]);
            p.contacts[k] = m.iter().any(|&f| !topo.contacts_of(f as usize).is_empty());
        }
        p
    }

    #[inline]
    pub fn faces_of(&self, p: usize) -> &[u32] {
        &self.faces[self.faces_at[p] as usize..self.faces_at[p + 1] as usize]
    }

    #[inline]
    pub fn inner_of(&self, p: usize) -> &[InnerEdge] {
        &self.inner[self.inner_at[p] as usize..self.inner_at[p + 1] as usize]
    }

    #[inline]
    pub fn rim_of(&self, p: usize) -> &[RimEdge] {
        &self.rim[self.rim_at[p] as usize..self.rim_at[p + 1] as usize]
    }

    #[inline]
    pub fn links_of(&self, p: usize) -> &[Link] {
        &self.links[self.links_at[p] as usize..self.links_at[p + 1] as usize]
    }

    #[inline]
    pub fn exits_of(&self, link: &Link) -> &[(u32, u32, u32)] {
        &self.exits[link.exits.0 as usize..link.exits.1 as usize]
    }

    /// How patch `p` faces along unit `d`.
    #[inline]
    pub fn facing(&self, p: usize, d: DVec3) -> Facing {
        let c = self.axis[p].dot(d);
        let s = self.sin_half[p] + 1e-12;
        if c > s {
            Facing::Along
        } else if c < -s {
            Facing::Away
        } else {
            Facing::Mixed
        }
    }
}

/// The patches grown breadth first over shared edges: per face its patch, and per patch
/// its faces (CSR).
fn grow(polys: &Polygons, topo: &Topology) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    grow_over(
        polys.faces(),
        |f| polys.normal[f],
        |f| polys.two_sided[f],
        |f| topo.neighbours(f).iter().map(|&(g, _)| g),
    )
}

/// [`grow`] over any adjacency: `n` faces, each with its unit normal, its
/// two-sidedness and the faces it meets across an edge.
fn grow_over<I: Iterator<Item = u32>>(
    n: usize,
    normal: impl Fn(usize) -> DVec3,
    two_sided: impl Fn(usize) -> bool,
    neighbours: impl Fn(usize) -> I,
) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let mut of_face = vec![NONE; n];
    let mut faces_at = vec![0u32];
    let mut faces = Vec::with_capacity(n);
    let mut queue = std::collections::VecDeque::new();
    // grown breadth first from each face not yet taken, in the faces' (spatial) order
    for seed in 0..n {
        if of_face[seed] != NONE {
            continue;
        }
        let p = (faces_at.len() - 1) as u32;
        let n0 = normal(seed);
        let sided = two_sided(seed);
        of_face[seed] = p;
        faces.push(seed as u32);
        let start = faces.len() - 1;
        queue.clear();
        queue.push_back(seed as u32);
        'grow: while let Some(f) = queue.pop_front() {
            for g in neighbours(f as usize) {
                let gi = g as usize;
                let size = faces.len() - start;
                let turn = if size < MAX_FACES {
                    MAX_TURN_COS
                } else {
                    FLAT_TURN_COS
                };
                if of_face[gi] != NONE || two_sided(gi) != sided || normal(gi).dot(n0) < turn {
                    continue;
                }
                if size >= MAX_FLAT_FACES {
                    break 'grow;
                }
                of_face[gi] = p;
                faces.push(g);
                queue.push_back(g);
            }
        }
        faces_at.push(faces.len() as u32);
    }
    (of_face, faces_at, faces)
}

/// Renumbers `faces` (of `mesh`; `two_sided(material)`) so that the faces of each patch
/// come one after another, as `Patches::build` will grow them: every step of a
/// direction reads a patch's faces together (their polygons, normals, counts), and a
/// patch whose faces lie scattered over the mesh's arrays costs a cache miss per face
/// at ~200k faces. The patches are grown here over the faces' shared welded edges (what
/// `Topology` is built from, without its contacts and polygons), so the build that
/// follows grows the same patches, or nearly, from faces already in their order.
/// `sorted`: the mesh's welded edges ([`crate::geometry::Faces::welded_edges`]).
pub fn order_by_patches(
    mesh: &crate::geometry::Mesh,
    faces: &mut crate::geometry::Faces,
    sorted: &[WeldedEdge],
    two_sided: impl Fn(u32) -> bool,
) {
    let nf = faces.len();
    if nf < 2 {
        return;
    }
    let tri_face = faces.triangle_faces(mesh.triangles.len());
    let mut pairs = Vec::new();
    for run in sorted.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        for (i, x) in run.iter().enumerate() {
            for y in &run[i + 1..] {
                let (f, g) = (tri_face[x.2 as usize], tri_face[y.2 as usize]);
                if f != g {
                    pairs.push((f, g));
                    pairs.push((g, f));
                }
            }
        }
    }
    let (at, mut next) = csr_of(nf, pairs.iter().copied());
    // each face's neighbours by index, not in the welded edges' order: the order must
    // follow from the geometry alone, not from how the mesh numbers its vertices
    sort_within(&at, &mut next, |&g| g);
    let list = &faces.faces;
    let (_, _, order) = grow_over(
        nf,
        |f| list[f].normal,
        |f| two_sided(list[f].material),
        |f| next[at[f] as usize..at[f + 1] as usize].iter().copied(),
    );
    permute(&mut faces.faces, &order);
}

/// Per patch: its normals' cone, its box, whether a contact runs through it, and whether
/// it is open.
struct Shapes {
    axis: Vec<DVec3>,
    sin_half: Vec<f64>,
    centre: Vec<DVec3>,
    half: Vec<DVec3>,
    slab: Vec<Slab>,
    contacts: Vec<bool>,
    open: Vec<bool>,
}

impl Shapes {
    fn of(polys: &Polygons, topo: &Topology, faces_at: &[u32], faces: &[u32]) -> Shapes {
        let np = faces_at.len() - 1;
        let members = |p: usize| &faces[faces_at[p] as usize..faces_at[p + 1] as usize];
        let mut axis = Vec::with_capacity(np);
        let mut sin_half = Vec::with_capacity(np);
        let mut centre = Vec::with_capacity(np);
        let mut half = Vec::with_capacity(np);
        let mut slab = Vec::with_capacity(np);
        let mut contacts = Vec::with_capacity(np);
        let mut open = Vec::with_capacity(np);
        for p in 0..np {
            let m = members(p);
            let sum: DVec3 = m.iter().map(|&f| polys.normal[f as usize]).sum();
            let a = sum.try_normalize().unwrap_or(polys.normal[m[0] as usize]);
            let cos_min = m
                .iter()
                .map(|&f| polys.normal[f as usize].dot(a))
                .fold(1.0f64, f64::min)
                .clamp(-1.0, 1.0);
            // the cone's half angle, widened a little for rounding
            let half_angle = cos_min.acos() + 1e-9;
            axis.push(a);
            sin_half.push(if half_angle < std::f64::consts::FRAC_PI_2 {
                half_angle.sin()
            } else {
                2.0
            });
            let (c, h) = box_of(polys, m);
            centre.push(c);
            half.push(h);
            slab.push(Slab::of(polys, m, a));
            contacts.push(m.iter().any(|&f| !topo.contacts_of(f as usize).is_empty()));
            open.push(topo.open[m[0] as usize]);
        }
        Shapes {
            axis,
            sin_half,
            centre,
            half,
            slab,
            contacts,
            open,
        }
    }
}

/// The box of faces `m`' polygons: centre and half extents (m).
fn box_of(polys: &Polygons, m: &[u32]) -> (DVec3, DVec3) {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for &f in m {
        for k in polys.of(f as usize) {
            for &q in polys.corners3(k) {
                lo = lo.min(q);
                hi = hi.max(q);
            }
        }
    }
    ((lo + hi) * 0.5, (hi - lo) * 0.5)
}

/// CSR tables.
type Csr<T> = (Vec<u32>, Vec<T>);

/// Per patch (of `np`): the edges inside it, those on its rim with the patch across,
/// and its links to its neighbours with the exits into each.
#[allow(clippy::type_complexity)]
fn edges_by_patch(
    topo: &Topology,
    of_face: &[u32],
    (faces_at, faces): (&[u32], &[u32]),
) -> (
    Csr<InnerEdge>,
    Csr<RimEdge>,
    (Vec<u32>, Vec<Link>, Vec<(u32, u32, u32)>),
) {
    let np = faces_at.len() - 1;
    // each face's place in its patch's list
    let mut place = vec![0u8; of_face.len()];
    for p in 0..np {
        let faces = &faces[faces_at[p] as usize..faces_at[p + 1] as usize];
        debug_assert!(faces.len() <= MAX_FLAT_FACES && MAX_FLAT_FACES <= 256);
        for (i, &f) in faces.iter().enumerate() {
            place[f as usize] = i as u8;
        }
    }
    let mut inner_items = Vec::new();
    let mut rim_items = Vec::new();
    let mut exit_items = Vec::new();
    for (i, e) in topo.edges.iter().enumerate() {
        let p0 = of_face[e.f0 as usize];
        let p1 = if e.f1 == NONE {
            NONE
        } else {
            of_face[e.f1 as usize]
        };
        let always =
            e.flipped || (e.f1 != NONE && topo.open[e.f0 as usize] != topo.open[e.f1 as usize]);
        if p0 == p1 {
            let at = (place[e.f0 as usize], place[e.f1 as usize]);
            let edge = i as u32;
            inner_items.push((p0, InnerEdge { edge, at, always }));
        } else {
            let (edge, f0, f1, other) = (i as u32, e.f0, e.f1, p1);
            rim_items.push((
                p0,
                RimEdge {
                    edge,
                    f0,
                    f1,
                    other,
                    always,
                },
            ));
        }
        if e.f1 != NONE && p0 != p1 {
            exit_items.push((p0, (i as u32, e.f0, e.f1)));
            exit_items.push((p1, (i as u32, e.f1, e.f0)));
        }
    }
    let (inner_at, inner) = csr_of(np, inner_items.iter().copied());
    let (rim_at, rim) = csr_of(np, rim_items.iter().copied());
    // the exits grouped by the patch they lead into
    exit_items.par_sort_by_key(|&(p, (_, _, out))| (p, of_face[out as usize]));
    let mut links_at = vec![0u32; np + 1];
    let mut links = Vec::new();
    let exits: Vec<(u32, u32, u32)> = exit_items.iter().map(|x| x.1).collect();
    let mut i = 0;
    while i < exit_items.len() {
        let (p, (_, _, out)) = exit_items[i];
        let q = of_face[out as usize];
        let mut j = i;
        while j < exit_items.len()
            && exit_items[j].0 == p
            && of_face[exit_items[j].1 .2 as usize] == q
        {
            j += 1;
        }
        links.push(Link {
            patch: q,
            exits: (i as u32, j as u32),
        });
        links_at[p as usize + 1] += 1;
        i = j;
    }
    for k in 0..np {
        links_at[k + 1] += links_at[k];
    }
    ((inner_at, inner), (rim_at, rim), (links_at, links, exits))
}

#[cfg(test)]
mod tests {
    use super::super::fixtures;
    use super::*;
    use crate::geometry::builtin::geodesic_sphere;

    #[test]
    fn a_permutation_puts_each_item_where_the_order_says() {
        let mut rnd = crate::test_rng(3);
        for n in [0usize, 1, 2, 7, 1000] {
            // a random permutation (Fisher–Yates), and its cycles followed
            let mut order: Vec<u32> = (0..n as u32).collect();
            for i in (1..n).rev() {
                order.swap(i, ((rnd() * (i + 1) as f64) as usize).min(i));
            }
            let mut items: Vec<u32> = (0..n as u32).map(|i| 10 * i).collect();
            permute(&mut items, &order);
            let want: Vec<u32> = order.iter().map(|&k| 10 * k).collect();
            assert_eq!(items, want);
        }
    }

    #[test]
    fn ordered_by_patches_each_patch_is_a_run_of_faces_and_no_face_is_lost() {
        use crate::geometry::builtin::{fragment, rocket_body, Detail};
        use crate::geometry::Faces;
        for (what, mesh) in [
            ("fragment", fragment::build(Detail::Coarse)),
            ("rocket body", rocket_body::build(Detail::Coarse)),
        ] {
            let mut faces = Faces::build(&mesh, true);
            faces.sort_spatially();
            let before: Vec<Vec<u32>> = faces.faces.iter().map(|f| f.triangles.clone()).collect();
            let (_, sorted) = faces.welded_edges(&mesh);
            let sorted = sorted.into_owned();
            order_by_patches(&mesh, &mut faces, &sorted, |_| false);
            // a permutation: every face once, unchanged
            let mut after: Vec<Vec<u32>> =
                faces.faces.iter().map(|f| f.triangles.clone()).collect();
            let mut sorted_before = before.clone();
            sorted_before.sort();
            after.sort();
            assert_eq!(after, sorted_before, "{what}");
            // the build grows its patches from faces already in their order: a patch's
            // faces are one run of indices (the build's adjacency may differ from the
            // welded edges' where edges were merged in line: nearly every patch, not all)
            let b = fixtures::of_faces(&mesh, &faces).patches;
            let runs = (0..b.len())
                .filter(|&p| {
                    let mut m = b.faces_of(p).to_vec();
                    m.sort_unstable();
                    let run = m.windows(2).all(|w| w[1] == w[0] + 1);
                    // and the patch's `run` says so, from its first face
                    let want = if run { m[0] } else { NONE };
                    assert_eq!(b.run[p], want, "{what}: patch {p}'s run");
                    run
                })
                .count();
            assert!(
                runs as f64 >= 0.95 * b.len() as f64,
                "{what}: {runs} of {} patches are runs",
                b.len()
            );
        }
    }

    #[test]
    fn every_face_is_in_one_patch_and_its_cone_holds_its_faces_normals() {
        let mesh = geodesic_sphere(12, 2.0);
        let b = fixtures::build(&mesh);
        let p = &b.patches;
        let nf = b.polys.faces();
        // each face once, in the patch of_face names
        let mut seen = vec![0u32; nf];
        for k in 0..p.len() {
            let m = p.faces_of(k);
            assert!(!m.is_empty() && m.len() <= MAX_FLAT_FACES);
            // past MAX_FACES, only faces within the flat turn of the first
            let n0 = b.polys.normal[m[0] as usize];
            for &f in m.iter().skip(MAX_FACES) {
                assert!(b.polys.normal[f as usize].dot(n0) >= FLAT_TURN_COS);
            }
            for &f in m {
                seen[f as usize] += 1;
                assert_eq!(p.of_face[f as usize] as usize, k);
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
        // fewer patches than faces: the sphere is smooth enough to group
        assert!(p.len() * 4 < nf, "{} patches for {nf} faces", p.len());
        // a cone of half-angle asin(sin_half) about the axis holds every normal (to
        // rounding), and the box holds every corner
        for k in 0..p.len() {
            let cos_half = (1.0 - p.sin_half[k].min(1.0).powi(2)).sqrt();
            for &f in p.faces_of(k) {
                let n = b.polys.normal[f as usize];
                assert!(n.dot(p.axis[k]) >= cos_half - 1e-12, "patch {k} face {f}");
                for q in b.polys.of(f as usize).flat_map(|i| b.polys.corners3(i)) {
                    let off = (*q - p.centre[k]).abs() - p.half[k];
                    assert!(off.max_element() <= 1e-12, "{off}");
                }
            }
        }
    }

    #[test]
    fn a_patch_facing_one_way_has_every_face_facing_that_way() {
        let mesh = geodesic_sphere(12, 2.0);
        let b = fixtures::build(&mesh);
        let p = &b.patches;
        let (mut along, mut away, mut mixed) = (0, 0, 0);
        for d in fixtures::directions() {
            for k in 0..p.len() {
                let dots = p
                    .faces_of(k)
                    .iter()
                    .map(|&f| b.polys.normal[f as usize].dot(d));
                match p.facing(k, d) {
                    Facing::Along => {
                        along += 1;
                        assert!(dots.clone().all(|x| x > 0.0));
                    }
                    Facing::Away => {
                        away += 1;
                        assert!(dots.clone().all(|x| x < 0.0));
                    }
                    Facing::Mixed => mixed += 1,
                }
            }
        }
        // the mixed ones are the few along the terminator
        assert!(mixed * 5 < along + away, "{along} {away} {mixed}");
    }

    #[test]
    fn patches_grow_past_sixteen_faces_only_where_the_surface_stays_flat() {
        // a sphere meshed finely enough that 64 faces turn less than the flat limit
        // about their first: its patches hold more than 32 faces on average; a coarse
        // one, where the faces beside a patch's first already turn about as much as the
        // limit, about 16 or fewer
        let mean = |freq: u32| {
            let b = fixtures::build(&geodesic_sphere(freq, 1.0));
            b.polys.faces() as f64 / b.patches.len() as f64
        };
        let (fine, coarse) = (mean(64), mean(12));
        assert!(fine > 32.0, "{fine} faces a patch on the fine sphere");
        assert!(
            coarse <= MAX_FACES as f64,
            "{coarse} faces a patch on the coarse sphere"
        );
    }

    #[test]
    fn links_lead_across_shared_edges_to_the_neighbouring_patch() {
        let mesh = geodesic_sphere(8, 1.0);
        let b = fixtures::build(&mesh);
        let p = &b.patches;
        for k in 0..p.len() {
            for link in p.links_of(k) {
                assert_ne!(link.patch as usize, k);
                let exits = p.exits_of(link);
                assert!(!exits.is_empty());
                for &(e, inside, outside) in exits {
                    let edge = &b.topo.edges[e as usize];
                    assert!([edge.f0, edge.f1].contains(&inside));
                    assert!([edge.f0, edge.f1].contains(&outside));
                    assert_eq!(p.of_face[inside as usize] as usize, k);
                    assert_eq!(p.of_face[outside as usize], link.patch);
                }
            }
        }
    }
}
