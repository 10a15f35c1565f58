//! The mesh as a surface, built once per request: its edges (with the faces beside each
//! and a point of each of those faces), which faces meet across which edge, which
//! connected pieces are open, and where separate pieces touch or cross (the *contacts*).
//!
//! Along a direction d, how many sheets of the surface lie above a point of a face
//! changes only across the shadow of an edge where the surface folds over as seen along
//! d (or an open surface's border): its *jump* ([`Edge::jump`]) is not zero there. Or
//! across a line where another piece of the mesh meets the face's plane inside the face
//! (a contact: a boom's foot on a bus), fixed in the body frame and found here.

use super::contacts::{contact_segments, Contact, TriangleGrid};
use crate::geometry::articulation::Motion;
use crate::geometry::csr::{csr_of, sort_within};
use crate::geometry::faces::WeldedEdge;
use crate::geometry::permute::gather;
use crate::geometry::union_find::{find, union};
use crate::geometry::{Faces, Mesh};
use glam::DVec3;

/// No triangle (a border edge's missing second side).
pub const NONE: u32 = u32::MAX;

/// An edge of the welded mesh between two faces, or along one face's border (an edge
/// inside a face, between coplanar triangles of one face, is none). Where more than two
/// triangles meet, each is given an edge of its own with no second face: the sheets
/// beside such an edge count one by one.
#[derive(Debug, Clone, Copy)]
pub struct Edge {
    /// Its ends, m.
    pub a: DVec3,
    pub b: DVec3,
    /// The faces on either side; `f1` is [`NONE`] on a border.
    pub f0: u32,
    pub f1: u32,
    /// A point of each face off the edge's line (the third corner of a triangle along
    /// it), m: which side of the edge each face lies on, seen along a direction.
    pub in0: DVec3,
    pub in1: DVec3,
    /// A valley of a closed, outward-facing piece: the surface turns inward across it,
    /// so along any direction its shadow runs inside the solid on both sides of it:
    /// the count changes across it, but never to or from zero (see
    /// [`super::lines::Line::bounds`]).
    pub valley: bool,
    /// Its two triangles wind the same way along it (a mesh whose orientation flips
    /// here): two faces that both face along a direction may then lie on one side of
    /// it, folded over, so facing alone does not say that nothing folds here.
    pub flipped: bool,
}

impl Edge {
    /// How many more sheets lie above a point just left of the edge's shadow than just
    /// right of it, seen along `d` (left of a → b in the plane across d with basis
    /// `(u, w)`, u × w = d); `blocks(face)` says whether a face's sheet counts along d
    /// (it faces along d, or belongs to an open piece), `faces_on(face)` that its
    /// plane is not edge-on to d. Zero for an edge along which the surface does not
    /// fold over as seen along d.
    #[inline]
    pub fn jump(&self, u: DVec3, w: DVec3, blocks: impl Fn(u32) -> bool) -> i32 {
        let pa = glam::DVec2::new(self.a.dot(u), self.a.dot(w));
        let pb = glam::DVec2::new(self.b.dot(u), self.b.dot(w));
        let side = |p: DVec3| {
            let s = (pb - pa).perp_dot(glam::DVec2::new(p.dot(u), p.dot(w)) - pa);
            if s > 0.0 {
                1
            } else if s < 0.0 {
                -1
            } else {
                0
            }
        };
        let mut j = 0;
        if blocks(self.f0) {
            j += side(self.in0);
        }
        if self.f1 != NONE && blocks(self.f1) {
            j += side(self.in1);
        }
        j
    }
}

/// The surface's structure (see the module doc).
pub struct Topology {
    pub edges: Vec<Edge>,
    /// Per face: the faces it meets across an edge, with that edge (CSR: `adjacent_at[f]
    /// ..adjacent_at[f + 1]`).
    pub adjacent_at: Vec<u32>,
    pub adjacent: Vec<(u32, u32)>,
    /// Per face: its piece is open (a border, a non-manifold or inconsistently wound
    /// edge) or its material is two-sided, so it may block a ray whichever way it faces.
    pub open: Vec<bool>,
    /// Per face: where another piece of the mesh meets the face: segments (m, in the
    /// face's plane), each with the other piece's triangle that meets it there (CSR as
    /// `adjacent`).
    pub contacts_at: Vec<u32>,
    pub contacts: Vec<Contact>,
    /// Some edge is [`Edge::flipped`]: a well-wound mesh has none, and the flood then
    /// need not read an edge to know that it does not fold (at ~200k triangles the
    /// edges' table is larger than the cache).
    pub any_flipped: bool,
}

impl Topology {
    /// The topology of `faces`: its edges, which faces meet across them, which pieces are
    /// open, and the contacts, found only between triangles of one `group` (per triangle)
    /// when given: what moves with each group of an articulated mesh.
    /// `faces` must then have been merged within the groups
    /// ([`Faces::build_within`]): no edge joins two groups. `grid`: the contact search's
    /// grid of the mesh at `tol` when built already ([`TriangleGrid`]).
    pub fn build_within(
        mesh: &Mesh,
        faces: &Faces,
        tri_face: &[u32],
        two_sided: &[bool],
        group: Option<&[u32]>,
        tol: f64,
        grid: Option<TriangleGrid>,
    ) -> Topology {
        // the edges and the contacts need only the welded mesh: found side by side (at
        // ~200k triangles each is tens of milliseconds, and the edges' steps run on one
        // thread)
        let (welded, edges) = faces.welded_edges(mesh);
        let (topo, contacts) = rayon::join(
            || Topology::without_contacts(mesh, faces, (&welded, &edges), tri_face, two_sided, tol),
            || contact_segments(mesh, (&welded, &edges), tri_face, group, tol, grid),
        );
        topo.with_contacts(contacts)
    }

    /// The topology with no contacts yet ([`Topology::with_contacts`] adds them): the
    /// edges, which faces meet across them, which pieces are open. `two_sided` is per
    /// face; `welded`, `sorted`: the mesh's welded ids and edges
    /// ([`Faces::welded_edges`]).
    pub fn without_contacts(
        mesh: &Mesh,
        faces: &Faces,
        (welded, sorted): (&[u32], &[WeldedEdge]),
        tri_face: &[u32],
        two_sided: &[bool],
        tol: f64,
    ) -> Topology {
        let mut found = edges_of(mesh, welded, sorted, tri_face, tol);
        let open = open_faces(&mut found, tri_face, two_sided);
        keep_solid_valleys(&mut found, mesh, faces, &open);
        let edges = merge_in_line(found.edges, &found.ends, &mesh.vertices);
        let (adjacent_at, adjacent) = adjacency(&edges, faces.len());
        let (contacts_at, contacts) = csr_of(faces.len(), std::iter::empty());
        Topology {
            any_flipped: edges.iter().any(|e| e.flipped),
            edges,
            adjacent_at,
            adjacent,
            open,
            contacts_at,
            contacts,
        }
    }

    /// This topology with `contacts` (per face: where another piece meets it), in place
    /// of any it had.
    pub fn with_contacts(mut self, contacts: Vec<(u32, Contact)>) -> Topology {
        (self.contacts_at, self.contacts) = csr_of(self.open.len(), contacts.iter().copied());
        self
    }

    /// The topology of the mesh with each face moved rigidly by `motion(face)` (no two
    /// faces that met across an edge moving apart): its edges and contacts carried
    /// along, and `more` contacts (found on the moved mesh) added.
    pub fn moved(&self, motion: impl Fn(u32) -> Motion, more: Vec<(u32, Contact)>) -> Topology {
        let edges = self
            .edges
            .iter()
            .map(|e| {
                let m = motion(e.f0);
                Edge {
                    a: m.apply(e.a),
                    b: m.apply(e.b),
                    in0: m.apply(e.in0),
                    in1: m.apply(e.in1),
                    ..*e
                }
            })
            .collect();
        let nf = self.open.len();
        let mut contacts = Vec::with_capacity(self.contacts.len() + more.len());
        for f in 0..nf {
            let m = motion(f as u32);
            for c in self.contacts_of(f) {
                let o = motion(c.face);
                let moved = Contact {
                    a: m.apply(c.a),
                    b: m.apply(c.b),
                    other: c.other.map(|v| o.apply(v)),
                    face: c.face,
                };
                contacts.push((f as u32, moved));
            }
        }
        contacts.extend(more);
        let (contacts_at, contacts) = csr_of(nf, contacts.iter().copied());
        Topology {
            edges,
            adjacent_at: self.adjacent_at.clone(),
            adjacent: self.adjacent.clone(),
            open: self.open.clone(),
            contacts_at,
            contacts,
            any_flipped: self.any_flipped,
        }
    }

    /// The faces `face` meets across an edge, with the edge.
    pub fn neighbours(&self, face: usize) -> &[(u32, u32)] {
        &self.adjacent[self.adjacent_at[face] as usize..self.adjacent_at[face + 1] as usize]
    }

    /// Where other pieces of the mesh meet `face`.
    pub fn contacts_of(&self, face: usize) -> &[Contact] {
        &self.contacts[self.contacts_at[face] as usize..self.contacts_at[face + 1] as usize]
    }
}

/// The welded mesh's edges before those in line are merged, with the pieces the
/// triangles form.
struct Found {
    edges: Vec<Edge>,
    /// Each edge's welded ends.
    ends: Vec<(u32, u32)>,
    /// Union-find over the triangles: a piece is the triangles joined by shared edges.
    parent: Vec<u32>,
    /// Triangles beside an edge not shared by exactly two triangles wound opposite ways.
    bad_triangles: Vec<u32>,
}

/// Every edge between two faces or along a border (`sorted`: the welded edges as
/// (welded a, welded b, triangle), grouped by their ends), and the pieces.
fn edges_of(
    mesh: &Mesh,
    welded: &[u32],
    sorted: &[(u32, u32, u32)],
    tri_face: &[u32],
    tol: f64,
) -> Found {
    let nt = mesh.triangles.len();
    // pieces by union-find over shared edges; a piece is open when any edge of it is
    // not shared by exactly two triangles wound the opposite ways
    let mut parent: Vec<u32> = (0..nt as u32).collect();
    let mut edges = Vec::new();
    let mut ends: Vec<(u32, u32)> = Vec::new();
    let mut bad_triangles = Vec::new();
    let face = |t: u32| tri_face[t as usize];
    for shared in sorted.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let (wa, wb, t0) = shared[0];
        let a = mesh.vertices[wa as usize];
        let b = mesh.vertices[wb as usize];
        let forward = |t: u32| {
            let tri = mesh.triangles[t as usize];
            (0..3).any(|k| welded[tri[k] as usize] == wa && welded[tri[(k + 1) % 3] as usize] == wb)
        };
        // triangle t's corner off the edge
        let third = |t: u32| {
            let tri = mesh.triangles[t as usize];
            let v = tri
                .iter()
                .copied()
                .find(|&v| welded[v as usize] != wa && welded[v as usize] != wb)
                .unwrap_or(tri[0]);
            mesh.vertices[v as usize]
        };
        let single = |t: u32| Edge {
            a,
            b,
            f0: face(t),
            f1: NONE,
            in0: third(t),
            in1: third(t),
            valley: false,
            flipped: false,
        };
        match shared.len() {
            1 => {
                bad_triangles.push(t0);
                edges.push(single(t0));
                ends.push((wa, wb));
            }
            2 => {
                let t1 = shared[1].2;
                union(&mut parent, t0, t1);
                let flipped = forward(t0) == forward(t1);
                if flipped {
                    bad_triangles.extend([t0, t1]);
                }
                if flipped || face(t0) != face(t1) {
                    // t1's corner off the edge, above t0's plane: the surface turns
                    // inward here (checked against the piece below)
                    let [p0, p1, p2] = mesh.corners(t0 as usize);
                    let n0 = (p1 - p0).cross(p2 - p0);
                    let off = n0.dot(third(t1) - a);
                    edges.push(Edge {
                        a,
                        b,
                        f0: face(t0),
                        f1: face(t1),
                        in0: third(t0),
                        in1: third(t1),
                        valley: !flipped && off > tol * n0.length(),
                        flipped,
                    });
                    ends.push((wa, wb));
                }
            }
            _ => {
                for w in shared.windows(2) {
                    union(&mut parent, w[0].2, w[1].2);
                }
                bad_triangles.extend(shared.iter().map(|s| s.2));
                // more than two sheets meet here: each counts on its own side
                for s in shared {
                    edges.push(single(s.2));
                    ends.push((wa, wb));
                }
            }
        }
    }
    Found {
        edges,
        ends,
        parent,
        bad_triangles,
    }
}

/// Per face: its piece is open (a bad triangle in it) or it is two-sided.
fn open_faces(found: &mut Found, tri_face: &[u32], two_sided: &[bool]) -> Vec<bool> {
    let nt = tri_face.len();
    let parent = &mut found.parent;
    let face = |t: u32| tri_face[t as usize];
    let mut open_root = vec![false; nt];
    for &t in &found.bad_triangles {
        let r = find(parent, t);
        open_root[r as usize] = true;
    }
    let mut open = two_sided.to_vec();
    for t in 0..nt as u32 {
        open[face(t) as usize] |= open_root[find(parent, t) as usize];
    }
    open
}

/// Keeps an edge a valley only between faces of closed pieces whose normals point out
/// of them (positive volume) and whose faces are one-sided: only there does a valley
/// keep its shadow inside a solid.
fn keep_solid_valleys(found: &mut Found, mesh: &Mesh, faces: &Faces, open: &[bool]) {
    let nt = mesh.triangles.len();
    let parent = &mut found.parent;
    let mut volume = vec![0.0f64; nt];
    for t in 0..nt as u32 {
        let [p0, p1, p2] = mesh.corners(t as usize);
        volume[find(parent, t) as usize] += p0.dot(p1.cross(p2));
    }
    let solid_face = |f: u32, parent: &mut Vec<u32>| {
        let t = faces.faces[f as usize].triangles[0];
        !open[f as usize] && volume[find(parent, t) as usize] > 0.0
    };
    for e in found.edges.iter_mut().filter(|e| e.valley) {
        e.valley = solid_face(e.f0, parent) && solid_face(e.f1, parent);
    }
}

/// Per face (of `nf`): the faces it meets across an edge, with the edge (CSR).
fn adjacency(edges: &[Edge], nf: usize) -> (Vec<u32>, Vec<(u32, u32)>) {
    let mut with_edge: Vec<(u32, (u32, u32))> = Vec::new();
    for (i, e) in edges.iter().enumerate() {
        let (f, g) = (e.f0, e.f1);
        if g != NONE && f != g {
            with_edge.push((f, (g, i as u32)));
            with_edge.push((g, (f, i as u32)));
        }
    }
    csr_of(nf, with_edge.iter().copied())
}
/// The edges with runs of edges between the same two faces (or along one face's border)
/// that continue one another in a straight line joined into one: a finely meshed box side
/// meets the next along one edge, not hundreds. Its shadow is the same line, so nothing
/// changes but the count of shadows to search and cut along.
fn merge_in_line(mut edges: Vec<Edge>, ends: &[(u32, u32)], vertices: &[DVec3]) -> Vec<Edge> {
    // each edge's key (its faces, lower first, whether a valley, whether flipped), taken
    // once in one pass: sorting and grouping by keys read through the edges (112 bytes
    // each, in another order) cost a cache miss a comparison at ~200k triangles
    let keys: Vec<(u32, u32, u8)> = edges
        .iter()
        .map(|e| {
            let kind = u8::from(e.valley) << 1 | u8::from(e.flipped);
            (e.f0.min(e.f1), e.f0.max(e.f1), kind)
        })
        .collect();
    let key = |i: u32| keys[i as usize];
    // sorted by key, the index breaking ties: grouped by the lower face (a real face:
    // NONE is the largest u32), then each face's few edges by the rest, stably
    let nf = keys.iter().map(|k| k.0).max().map_or(0, |f| f as usize + 1);
    let (at, mut order) = csr_of(nf, keys.iter().enumerate().map(|(i, k)| (k.0, i as u32)));
    sort_within(&at, &mut order, |&i| key(i));
    // The joined edges, in order, as the edge each is taken from (`from`) and, for a
    // run joined, its new ends (`runs`: its place, its first and last vertex); then
    // moved into place within `edges` itself. A new table of them (~14 MB at 200k
    // triangles) cost more in page faults than the joining did.
    let mut from: Vec<u32> = Vec::with_capacity(edges.len());
    let mut runs: Vec<(u32, u32, u32)> = Vec::new();
    let mut used = vec![false; edges.len()];
    // (vertex, edge) of one group, sorted by vertex
    let mut at: Vec<(u32, u32)> = Vec::new();
    let far = |i: u32, v: u32| {
        let (a, b) = ends[i as usize];
        if a == v {
            b
        } else {
            a
        }
    };
    for group in order.chunk_by(|&i, &j| key(i) == key(j)) {
        if group.len() == 1 {
            from.push(group[0]);
            continue;
        }
        at.clear();
        for &i in group {
            let (a, b) = ends[i as usize];
            at.extend([(a, i), (b, i)]);
        }
        at.sort_unstable();
        // the group's other edge at `v` when exactly two meet there, in line
        let next = |v: u32, from: u32| -> Option<u32> {
            let lo = at.partition_point(|x| x.0 < v);
            let hi = at.partition_point(|x| x.0 <= v);
            if hi - lo != 2 {
                return None;
            }
            let g = if at[lo].1 == from {
                at[lo + 1].1
            } else {
                at[lo].1
            };
            let c = vertices[v as usize];
            let u = c - vertices[far(from, v) as usize];
            let w = vertices[far(g, v) as usize] - c;
            (u.cross(w).length() <= 1e-12 * u.length() * w.length() && u.dot(w) > 0.0).then_some(g)
        };
        for &i in group {
            if used[i as usize] {
                continue;
            }
            // back to one end of the run, then along it to the other
            let (mut v, mut cur) = (ends[i as usize].0, i);
            while let Some(g) = next(v, cur).filter(|&g| g != i && !used[g as usize]) {
                v = far(g, v);
                cur = g;
            }
            let start = v;
            used[cur as usize] = true;
            let mut end = far(cur, start);
            while let Some(g) = next(end, cur).filter(|&g| !used[g as usize]) {
                used[g as usize] = true;
                end = far(g, end);
                cur = g;
            }
            // the joined edge is `i`'s, with the run's ends (`i` lies on the run)
            used[i as usize] = true;
            runs.push((from.len() as u32, start, end));
            from.push(i);
        }
    }
    gather(&mut edges, from);
    for (k, start, end) in runs {
        let e = &mut edges[k as usize];
        if e.f0 > e.f1 {
            (e.f0, e.f1) = (e.f1, e.f0);
            (e.in0, e.in1) = (e.in1, e.in0);
        }
        (e.a, e.b) = (vertices[start as usize], vertices[end as usize]);
    }
    edges
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_post_standing_on_the_diagonal_inside_a_face_meets_it_once() {
        // a square plate of two triangles (one face) whose shared diagonal runs under
        // the foot of a vertical triangle: both plate triangles find the same segment
        let vertices = vec![
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
            DVec3::new(-0.5, -0.5, 0.0),
            DVec3::new(0.5, 0.5, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        ];
        let mesh = Mesh {
            vertices,
            triangles: vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]],
            material_ids: vec![0; 3],
            rounding: 0.0,
        };
        let t = topology_of(&mesh, false);
        let faces = Faces::build(&mesh, true);
        let plate = (0..faces.len())
            .find(|&f| faces.faces[f].triangles.len() == 2)
            .expect("the plate is one face");
        let c = t.contacts_of(plate);
        assert_eq!(c.len(), 1, "{c:?}");
        assert!(((c[0].a - c[0].b).length() - 2f64.sqrt()).abs() < 1e-12);
        // and the post meets the plate once on its side too: the plate's two triangles
        // each find the same piece, joined as pieces along one face are
        let post = 1 - plate;
        let c = t.contacts_of(post);
        assert_eq!(c.len(), 1, "{c:?}");
        assert!(((c[0].a - c[0].b).length() - 2f64.sqrt()).abs() < 1e-12);
    }

    /// The topology of `mesh` (faces merged), with every face one-sided or two-sided.
    fn topology_of(mesh: &Mesh, two_sided: bool) -> Topology {
        topology_of_faces(mesh, &Faces::build(mesh, true), two_sided)
    }

    /// The topology of `mesh` as `faces`, with every face one-sided or two-sided.
    fn topology_of_faces(mesh: &Mesh, faces: &Faces, two_sided: bool) -> Topology {
        let tri_face = faces.triangle_faces(mesh.triangles.len());
        let two_sided = vec![two_sided; faces.len()];
        Topology::build_within(mesh, faces, &tri_face, &two_sided, None, 1e-9, None)
    }

    /// An L-shaped prism, 1 m high: its footprint (0,0) (2,0) (2,1) (1,1) (1,2) (0,2) turns
    /// inward at (1,1), so its vertical edge there is its one valley.
    fn l_prism() -> Mesh {
        let foot = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ];
        let mut vertices: Vec<DVec3> = foot.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect();
        vertices.extend(foot.iter().map(|&(x, y)| DVec3::new(x, y, 1.0)));
        // the footprint fanned from its reflex corner (3), counter-clockwise from above
        let fan = [[3, 4, 5], [3, 5, 0], [3, 0, 1], [3, 1, 2]];
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        for [a, b, c] in fan {
            triangles.push([a + 6, b + 6, c + 6]); // top, facing +z
            triangles.push([a, c, b]); // bottom, facing -z
        }
        for i in 0..6u32 {
            let j = (i + 1) % 6;
            triangles.push([i, j, j + 6]);
            triangles.push([i, j + 6, i + 6]);
        }
        let n = triangles.len();
        Mesh {
            vertices,
            triangles,
            material_ids: vec![0; n],
            rounding: 0.0,
        }
    }

    fn valleys(t: &Topology) -> Vec<(DVec3, DVec3)> {
        t.edges
            .iter()
            .filter(|e| e.valley)
            .map(|e| (e.a, e.b))
            .collect()
    }

    #[test]
    fn a_closed_solid_turns_inward_only_along_its_valleys() {
        let mesh = l_prism();
        let v = valleys(&topology_of(&mesh, false));
        assert_eq!(v.len(), 1, "{v:?}");
        let (a, b) = v[0];
        // the vertical edge at the reflex corner
        for p in [a, b] {
            assert!(
                (p.x - 1.0).abs() < 1e-15 && (p.y - 1.0).abs() < 1e-15,
                "{p}"
            );
        }
        assert!(((a - b).length() - 1.0).abs() < 1e-15);
        // inside out (its solid is everything else), or two-sided (no solid): no valleys,
        // since a valley's shadow is known to run inside the solid only when there is one
        let inverted = Mesh {
            triangles: mesh.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
            ..mesh.clone()
        };
        assert!(valleys(&topology_of(&inverted, false)).is_empty());
        assert!(valleys(&topology_of(&mesh, true)).is_empty());
    }

    #[test]
    fn a_finely_meshed_box_meets_each_side_along_one_edge() {
        let mut mesh = Mesh::default();
        crate::geometry::builtin::push_grid_box(
            &mut mesh,
            DVec3::ZERO,
            DVec3::new(3.0, 2.0, 1.0),
            [7, 5, 3],
            0,
        );
        let t = topology_of(&mesh, false);
        // 12 box edges, each whole (the runs of short edges along it joined), none a valley
        assert_eq!(t.edges.len(), 12);
        let mut lengths: Vec<f64> = t.edges.iter().map(|e| (e.a - e.b).length()).collect();
        lengths.sort_by(f64::total_cmp);
        let want = [1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0, 3.0, 3.0, 3.0, 3.0];
        for (l, w) in lengths.iter().zip(want) {
            assert!((l - w).abs() < 1e-12, "{lengths:?}");
        }
        assert!(t.edges.iter().all(|e| !e.valley));
        // each side meets its four neighbours
        for f in 0..6 {
            assert_eq!(t.neighbours(f).len(), 4);
        }
        // the joined edges are moved into place among the others (`merge_in_line`): in
        // the order of their lower face, each naming that face first, beside a point of
        // it off the edge (and the other face's point of the other face); with the
        // faces numbered backwards too, so that every edge found names its higher face
        // first
        for backwards in [false, true] {
            let mut faces = Faces::build(&mesh, true);
            if backwards {
                faces.faces.reverse();
            }
            let t = topology_of_faces(&mesh, &faces, false);
            assert_eq!(t.edges.len(), 12);
            let on_face = |f: u32, x: DVec3| {
                let face = &faces.faces[f as usize];
                let o = mesh.vertices[mesh.triangles[face.triangles[0] as usize][0] as usize];
                face.normal.dot(x - o).abs() < 1e-12
            };
            assert!(
                t.edges.windows(2).all(|w| w[0].f0 <= w[1].f0),
                "not in face order"
            );
            for e in &t.edges {
                assert!(e.f0 < e.f1, "{e:?}");
                assert!(on_face(e.f0, e.in0) && on_face(e.f1, e.in1), "{e:?}");
                assert!(!on_face(e.f0, e.in1) && !on_face(e.f1, e.in0), "{e:?}");
            }
        }
    }
}
