//! Convexity: when no part of the mesh can shadow or hide another, the two cosines
//! decide everything and no ray need be cast.

use super::faces::Faces;
use super::mesh::Mesh;
use super::union_find::{find, union};
use rayon::prelude::*;

/// Largest faces × vertices product checked exactly (all vertices behind every face).
const EXACT_LIMIT: usize = 400_000_000;
/// Below this faces × vertices product the exact test is cheaper than building edges.
const CHEAP_EXACT: usize = 20_000_000;

/// True when every vertex lies on or behind the plane of every face (within a tolerance
/// relative to the object's size). That is the exact condition for no self-shadowing of
/// one-sided faces. Large meshes first try the local test — closed, connected, every
/// edge convex — which implies global convexity (Tietze's theorem) in linear time; meshes
/// failing every test are treated as non-convex, which only costs rays.
pub fn is_convex(mesh: &Mesh, faces: &Faces) -> bool {
    let (_, scale) = mesh.bounding_sphere();
    let tol = 1e-9 * scale;
    let work = faces.len().saturating_mul(mesh.vertices.len());
    let exact = || {
        faces.faces.par_iter().all(|f| {
            let d = f.normal.dot(f.centroid);
            mesh.vertices.iter().all(|v| f.normal.dot(*v) - d <= tol)
        })
    };
    if work <= CHEAP_EXACT {
        exact()
    } else if locally_convex_and_closed(mesh, faces, tol) {
        true
    } else {
        work <= EXACT_LIMIT && exact()
    }
}

fn locally_convex_and_closed(mesh: &Mesh, faces: &Faces, tol: f64) -> bool {
    // the welded edges sorted: the triangles sharing an edge side by side, so no hash map
    let (welded, sorted) = faces.welded_edges(mesh);
    let mut parent: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
    // every edge shared by exactly two triangles (else open or non-manifold: leave it to
    // the rays), and the second's far corner not in front of the first's plane; the first
    // edge that fails ends the test (a rocket body's open skirt, a fragment's first dent)
    for shared in sorted.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let [(wa, wb, t0), (_, _, t1)] = shared[..] else {
            return false;
        };
        let far = mesh.triangles[t1 as usize]
            .iter()
            .find(|&&v| welded[v as usize] != wa && welded[v as usize] != wb);
        let Some(&far) = far else {
            return false; // a degenerate triangle along the edge
        };
        let n = mesh.area_vector(t0 as usize).normalize();
        let p = mesh.vertices[mesh.triangles[t0 as usize][0] as usize];
        if n.dot(mesh.vertices[far as usize] - p) > tol {
            return false;
        }
        union(&mut parent, t0, t1);
    }
    // one connected surface: two convex bodies side by side can shadow each other
    (0..parent.len() as u32).all(|t| find(&mut parent, t) == 0)
}

/// True when every vertex lies in one plane (a flat plate, even two-sided, cannot
/// shadow itself).
pub fn is_planar(mesh: &Mesh) -> bool {
    let (_, scale) = mesh.bounding_sphere();
    let tol = 1e-9 * scale;
    let n = (0..mesh.triangles.len())
        .map(|i| mesh.area_vector(i))
        .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
        .map(|a| a.normalize());
    let Some(n) = n else { return true };
    let p = mesh.vertices[mesh.triangles[0][0] as usize];
    mesh.triangles
        .iter()
        .flatten()
        .all(|&i| n.dot(mesh.vertices[i as usize] - p).abs() <= tol)
}

/// A connected piece of the mesh that lies on the boundary of its own convex hull, and
/// whose edges that no second face shares all lie in one plane: a closed convex body (a
/// box), or a convex cap open on one flat side (a dish). Along any direction it hides
/// exactly what its convex hull hides — a line that meets the hull enters and leaves it,
/// and at most once through the open side's plane — so its shadow on a plane wholly
/// behind it is the convex hull of its projected vertices: one polygon, however finely
/// the part is meshed.
#[derive(Debug, Clone)]
pub struct ConvexPart {
    /// Distinct vertices, m.
    pub vertices: Vec<glam::DVec3>,
    /// Indices of the faces (into [`Faces`]) that make up the part.
    pub faces: Vec<u32>,
    /// Per face (as in `faces`): does the part lie in front of its front side (a dish's
    /// concave side) rather than behind it (a box's outside)?
    pub hull_ahead: Vec<bool>,
    /// The open side, when it is one convex polygon.
    pub lid: Option<Lid>,
}

/// The open side of a convex cap: a convex polygon. A ray from a face of the cap into the
/// cap's hull leaves the hull once, and passes the cap unblocked exactly when it leaves
/// through the lid: a dish's faces see out only through its rim.
#[derive(Debug, Clone)]
pub struct Lid {
    /// Its corners in order, m.
    pub corners: Vec<glam::DVec3>,
    /// Unit normal pointing out of the hull.
    pub normal: glam::DVec3,
    /// In-plane axes (u × w = normal) and origin of `outline`, m.
    pub u: glam::DVec3,
    pub w: glam::DVec3,
    pub origin: glam::DVec3,
    /// The corners in (u, w) coordinates, counter-clockwise, m.
    pub outline: Vec<glam::DVec2>,
    /// A point inside the outline (the corners' mean), the radius of the circle about it
    /// that the outline contains, and of the one that contains the outline, m: most
    /// points are decided by these two without visiting the edges.
    centre: glam::DVec2,
    inner: f64,
    outer: f64,
    /// The corners' pseudo-angles about `centre` ([`pseudo_angle`]), increasing
    /// (unwrapped by 4 a turn): the edge a ray from the centre leaves through is found by
    /// bisection.
    angles: Vec<f64>,
}

impl Lid {
    /// Does the ray from `p` along unit `d` leave through the lid (within `tol`, m)? `p`
    /// must lie on the hull's side of the lid's plane.
    pub fn passes(&self, p: glam::DVec3, d: glam::DVec3, tol: f64) -> bool {
        self.along(d).is_some_and(|view| view.passes(p, tol))
    }

    /// The lid seen along unit `d`, for testing many points along one direction; `None`
    /// when d does not point out through the lid's plane (no ray leaves through it).
    pub fn along(&self, d: glam::DVec3) -> Option<LidView<'_>> {
        let dn = d.dot(self.normal);
        if dn <= 0.0 {
            return None;
        }
        // meet(p) = u·(p − o) + (u·d)·(n·(o − p))/dn = (u − n·(u·d)/dn)·(p − o), and as
        // much for w: an affine map of p
        let x = self.u - self.normal * (self.u.dot(d) / dn);
        let y = self.w - self.normal * (self.w.dot(d) / dn);
        Some(LidView {
            lid: self,
            x,
            y,
            offset: -glam::DVec2::new(x.dot(self.origin), y.dot(self.origin)),
            dn,
        })
    }

    /// The edge (index of its first corner) that the ray from the centre through `q`
    /// (outline coordinates) leaves the outline by.
    fn sector(&self, q: glam::DVec2) -> usize {
        let mut phi = pseudo_angle(q - self.centre);
        let start = self.angles[0];
        while phi < start {
            phi += TURN;
        }
        while phi >= start + TURN {
            phi -= TURN;
        }
        self.angles.partition_point(|&a| a <= phi).saturating_sub(1)
    }

    /// When the points `poly` (outline coordinates) lie within a wedge about the centre of
    /// less than half a turn: the sectors ([`Lid::sector`]) of its first and last corner
    /// counter-clockwise. `None` when they spread wider, or a point is at the centre.
    fn wedge(&self, poly: &[glam::DVec2]) -> Option<(usize, usize)> {
        let at = |q: glam::DVec2| {
            let r = q - self.centre;
            (r.length_squared() > 1e-24 * self.outer * self.outer).then(|| pseudo_angle(r))
        };
        let a0 = at(*poly.first()?)?;
        let (mut lo, mut hi) = ((0.0, 0), (0.0, 0));
        for (i, q) in poly.iter().enumerate().skip(1) {
            // angle from the first point, within half a turn either way
            let mut t = at(*q)? - a0;
            if t > 0.5 * TURN {
                t -= TURN;
            } else if t <= -0.5 * TURN {
                t += TURN;
            }
            if t < lo.0 {
                lo = (t, i);
            }
            if t > hi.0 {
                hi = (t, i);
            }
        }
        // a margin below half a turn: the wrap above must not be in doubt
        if hi.0 - lo.0 >= 0.45 * TURN {
            return None;
        }
        Some((self.sector(poly[lo.1]), self.sector(poly[hi.1])))
    }

    /// Edge `i` (< the number of corners): its first and second corner.
    fn edge(&self, i: usize) -> (glam::DVec2, glam::DVec2) {
        let next = if i + 1 == self.outline.len() {
            0
        } else {
            i + 1
        };
        (self.outline[i], self.outline[next])
    }

    /// Where the ray from `p` along unit `d` meets the lid's plane, in the outline's
    /// coordinates (m); `d` must not be parallel to the plane.
    pub fn meet(&self, p: glam::DVec3, d: glam::DVec3) -> glam::DVec2 {
        let hit = p + d * (self.normal.dot(self.origin - p) / d.dot(self.normal)) - self.origin;
        glam::DVec2::new(hit.dot(self.u), hit.dot(self.w))
    }

    /// The point of the lid's plane at outline coordinates `q`, m.
    pub fn at(&self, q: glam::DVec2) -> glam::DVec3 {
        self.origin + self.u * q.x + self.w * q.y
    }

    /// Clips the convex polygon `poly` (outline coordinates) to the outline; `scratch` is
    /// a buffer. Only edges that some corner lies outside of cut, so a small polygon near
    /// the rim costs one pass over the edges and a cut or two.
    pub fn clip(
        &self,
        poly: &mut Vec<glam::DVec2>,
        edges: &mut Vec<usize>,
        scratch: &mut Vec<glam::DVec2>,
    ) {
        // The edges that some corner lies outside of: for a corner outside the outline,
        // a run of edges about the one its ray from the centre leaves by. Cutting by
        // those alone is exact: the polygon lies inside every other edge already.
        let n = self.outline.len();
        let outside = |i: usize, q: glam::DVec2| {
            let (a, b) = self.edge(i);
            (b - a).perp_dot(q - a) < 0.0
        };
        edges.clear();
        if let Some((first, last)) = self.wedge(poly) {
            // The polygon lies in a wedge about the centre of less than half a turn, where
            // the outline is bounded by the edges from the sector of its first corner to
            // that of its last: only those can cut it (a small face near the rim meets one
            // or two, where a corner far outside lies outside of many edges).
            let mut i = first;
            loop {
                if poly.iter().any(|&q| outside(i, q)) {
                    edges.push(i);
                }
                if i == last {
                    break;
                }
                i = if i + 1 == n { 0 } else { i + 1 };
            }
        } else {
            for &q in poly.iter() {
                if q.distance(self.centre) <= self.inner {
                    continue;
                }
                let j = self.sector(q);
                if !outside(j, q) {
                    continue;
                }
                edges.push(j);
                for step in 1..n {
                    let i = if j + step >= n {
                        j + step - n
                    } else {
                        j + step
                    };
                    if !outside(i, q) {
                        break;
                    }
                    edges.push(i);
                }
                for step in 1..n {
                    let i = if j >= step { j - step } else { j + n - step };
                    if !outside(i, q) {
                        break;
                    }
                    edges.push(i);
                }
            }
        }
        edges.sort_unstable();
        edges.dedup();
        for &i in edges.iter() {
            let (a, b) = self.edge(i);
            let e = b - a;
            let side = |q: glam::DVec2| e.perp_dot(q - a);
            scratch.clear();
            for j in 0..poly.len() {
                let (p, q) = (poly[j], poly[(j + 1) % poly.len()]);
                let (sp, sq) = (side(p), side(q));
                if sp >= 0.0 {
                    scratch.push(p);
                }
                if (sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0) {
                    scratch.push(p + (q - p) * (sp / (sp - sq)));
                }
            }
            std::mem::swap(poly, scratch);
            if poly.len() < 3 {
                poly.clear();
                return;
            }
        }
    }

    /// [`LidView::classify`] along unit `d`.
    pub fn classify(&self, c: glam::DVec3, r: f64, d: glam::DVec3, tol: f64) -> Option<bool> {
        match self.along(d) {
            None => Some(false),
            Some(view) => view.classify(c, r, tol),
        }
    }
}

/// What the ray from a point does at the lid ([`LidView::test`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LidPoint {
    /// It leaves through the lid (within the tolerance).
    Passes,
    /// It misses, beyond the line of the outline's edge with this index.
    Beyond(u32),
    /// It misses, beyond the circle about the outline.
    Far,
    /// It passes, but only within the tolerance of the outline's boundary.
    OnEdge,
}

/// A [`Lid`] seen along one direction d (pointing out through its plane): where a ray
/// along d from a point meets the plane is an affine map of the point, two dot products.
#[derive(Debug, Clone, Copy)]
pub struct LidView<'a> {
    lid: &'a Lid,
    /// Rows of the map to outline coordinates, and its offset.
    x: glam::DVec3,
    y: glam::DVec3,
    offset: glam::DVec2,
    /// d·normal, > 0.
    dn: f64,
}

impl LidView<'_> {
    /// Where the ray from `p` meets the lid's plane, in outline coordinates (m).
    #[inline]
    pub fn meet(&self, p: glam::DVec3) -> glam::DVec2 {
        glam::DVec2::new(self.x.dot(p), self.y.dot(p)) + self.offset
    }

    /// Does the ray from `p` leave through the lid (within `tol`, m)? `p` must lie on the
    /// hull's side of the lid's plane.
    pub fn passes(&self, p: glam::DVec3, tol: f64) -> bool {
        matches!(
            self.test(self.meet(p), tol),
            LidPoint::Passes | LidPoint::OnEdge
        )
    }

    /// The edge (index) that the ray from the outline's centre through `q` leaves by, how
    /// far inside its line `q` lies (twice the area it spans with the edge, m², negative
    /// outside), and the tolerance `tol` (m) as a margin in those units.
    #[inline]
    fn edge_side(&self, q: glam::DVec2, tol: f64) -> (usize, f64, f64) {
        let j = self.lid.sector(q);
        let (a, b) = self.lid.edge(j);
        let e = b - a;
        (j, e.perp_dot(q - a), tol * e.length())
    }

    /// [`LidView::passes`] for the point whose ray meets the lid's plane at `q` (outline
    /// coordinates, [`LidView::meet`]), told apart: for a point that does not pass, the
    /// outline's edge whose line it lies beyond by more than `tol` (m), when it does; for
    /// one that passes only by the tolerance, that it lies on the outline (a rim vertex of
    /// the cap itself). Points all on or beyond one line that the lid lies behind span no
    /// area that passes.
    pub fn test(&self, q: glam::DVec2, tol: f64) -> LidPoint {
        let lid = self.lid;
        let r = q.distance(lid.centre);
        if r <= lid.inner {
            return LidPoint::Passes;
        }
        if r > lid.outer + tol {
            // outside: which edge's line it lies beyond is found when asked
            return LidPoint::Far;
        }
        // inside exactly when inside the edge that the ray from the centre through q
        // leaves by (the outline is convex about the centre)
        let (j, side, margin) = self.edge_side(q, tol);
        if side < -margin {
            LidPoint::Beyond(j as u32)
        } else if side <= margin {
            LidPoint::OnEdge
        } else {
            LidPoint::Passes
        }
    }

    /// For a point [`LidView::test`] found [`LidPoint::Far`] (meeting the plane at `q`):
    /// the edge whose line it lies beyond by more than `tol` (m), `None` when not by that
    /// much.
    pub fn beyond(&self, q: glam::DVec2, tol: f64) -> Option<u32> {
        let (j, side, margin) = self.edge_side(q, tol);
        (side < -margin).then_some(j as u32)
    }

    /// A line the lid lies behind, as its unit outward normal and a point on it (outline
    /// coordinates, m): that of the outline's edge `j`, or with `corner`, the line through
    /// the corner after edge `j` square to the mean of its two edges' normals.
    pub fn support(&self, j: u32, corner: bool) -> (glam::DVec2, glam::DVec2) {
        let lid = self.lid;
        let outward = |i: usize| {
            let (a, b) = lid.edge(i);
            let e = (b - a).normalize();
            (glam::DVec2::new(e.y, -e.x), a, b)
        };
        let (n, a, b) = outward(j as usize);
        if corner {
            let (m, _, _) = outward((j as usize + 1) % lid.outline.len());
            ((n + m).normalize(), b)
        } else {
            (n, a)
        }
    }

    /// The outline's number of edges.
    pub fn edges(&self) -> u32 {
        self.lid.outline.len() as u32
    }

    /// [`LidView::passes`] for every point of the ball about `c` of radius `r` (m) at
    /// once: `Some(true)` when every ray from it leaves through the lid, `Some(false)`
    /// when none does, `None` when the ball is not decided as a whole. The rays from the
    /// ball meet the lid's plane within r/cos of the centre's ray, cos = d·normal.
    pub fn classify(&self, c: glam::DVec3, r: f64, tol: f64) -> Option<bool> {
        let reach = r / self.dn;
        if !reach.is_finite() {
            return None;
        }
        let rq = self.meet(c).distance(self.lid.centre);
        if rq + reach <= self.lid.inner {
            Some(true)
        } else if rq - reach > self.lid.outer + tol {
            Some(false)
        } else {
            None
        }
    }
}

/// Fewest faces for a part to be worth treating whole (below, the faces' own shadows are
/// as cheap).
const MIN_PART_FACES: usize = 3;
/// Largest faces × vertices work spent proving parts convex, per request.
const PART_WORK_LIMIT: usize = 100_000_000;

/// The convex parts of a mesh (see [`ConvexPart`]): faces connected through shared edges
/// (vertices welded by position), each part checked exactly — every vertex on one side
/// of every face's plane, within `tol` (m), and its open edges in one plane. A cap with a
/// lid (a dish) is proven so from its edges in linear time ([`Cap::sides`]); other parts
/// test their vertices against each face's plane.
pub fn convex_parts(mesh: &Mesh, faces: &Faces, tol: f64) -> Vec<ConvexPart> {
    parts_of(mesh, faces, tol, true)
        .into_iter()
        .map(|(part, _)| part)
        .collect()
}

/// [`convex_parts`], each with whether its convexity was proven from its edges
/// ([`Cap::sides`]), which `by_edges = false` never tries.
fn parts_of(mesh: &Mesh, faces: &Faces, tol: f64, by_edges: bool) -> Vec<(ConvexPart, bool)> {
    let mut face_of = vec![0u32; mesh.triangles.len()];
    for (i, f) in faces.faces.iter().enumerate() {
        for &t in &f.triangles {
            face_of[t as usize] = i as u32;
        }
    }
    // the triangles' edges by their welded ends, sorted so that each edge's uses are side
    // by side (a sort, not a hash map of lists: no allocation per edge), as merging faces
    // left them; unmerged faces kept none
    let (welded, sorted) = faces.welded_edges(mesh);
    // each use with its face and whether its triangle runs from the lower end: a shared
    // edge joins two faces
    let edges: Vec<((u32, u32), u32, bool, u32)> = sorted
        .iter()
        .map(|&(a, b, t)| {
            let tri = mesh.triangles[t as usize].map(|v| welded[v as usize]);
            let forward = a < b && (0..3).any(|k| tri[k] == a && tri[(k + 1) % 3] == b);
            ((a, b), face_of[t as usize], forward, t)
        })
        .collect();
    let uses = || edges.chunk_by(|x, y| x.0 == y.0);
    let mut parent: Vec<u32> = (0..faces.len() as u32).collect();
    for adj in uses() {
        for w in adj.windows(2) {
            union(&mut parent, w[0].1, w[1].1);
        }
    }
    // each part under its least face, which is its root
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); faces.len()];
    for f in 0..faces.len() as u32 {
        members[find(&mut parent, f) as usize].push(f);
    }
    // open edges per part: an edge of a part that no other triangle of it uses the
    // other way round (edges inside a merged face cancel like any other), in the
    // direction its triangle runs; sorted, so the lid's corners start from the first
    let mut open: Vec<Vec<(u32, u32)>> = vec![Vec::new(); faces.len()];
    // and its inner edges: the two triangles that share each (for `Cap::sides`)
    let mut inner: Vec<Vec<(u32, u32)>> = vec![Vec::new(); faces.len()];
    let mut non_manifold = vec![false; faces.len()];
    for adj in uses() {
        let ((a, b), face, _, _) = adj[0];
        let part = find(&mut parent, face) as usize;
        match adj {
            [(_, _, forward, _)] => open[part].push(if *forward { (a, b) } else { (b, a) }),
            [(_, _, x, s), (_, _, y, t)] if x != y => inner[part].push((*s, *t)),
            _ => non_manifold[part] = true, // used twice one way, or by three faces
        }
    }
    for edges in &mut open {
        edges.sort_unstable();
    }
    let mut work = 0usize;
    let mut parts: Vec<(ConvexPart, bool)> = members
        .into_iter()
        .enumerate()
        .filter(|(root, fs)| fs.len() >= MIN_PART_FACES && !non_manifold[*root])
        .filter_map(|(root, fs)| {
            let mut ids: Vec<u32> = fs
                .iter()
                .flat_map(|&f| faces.faces[f as usize].triangles.iter())
                .flat_map(|&t| mesh.triangles[t as usize].map(|v| welded[v as usize]))
                .collect();
            ids.sort_unstable();
            ids.dedup();
            let vertices: Vec<glam::DVec3> =
                ids.iter().map(|&v| mesh.vertices[v as usize]).collect();
            work = work.saturating_add(fs.len().saturating_mul(vertices.len()));
            if work > PART_WORK_LIMIT {
                return None;
            }
            let mean = vertices.iter().sum::<glam::DVec3>() / vertices.len() as f64;
            let mut lid = None;
            if let Some(open) = Some(&open[root]).filter(|o| !o.is_empty()) {
                // the open side must be flat: Newell's normal of its edges, then distances
                let p = mesh.vertices[open[0].0 as usize];
                let n = open.iter().fold(glam::DVec3::ZERO, |acc, &(a, b)| {
                    let (a, b) = (mesh.vertices[a as usize] - p, mesh.vertices[b as usize] - p);
                    acc + a.cross(b)
                });
                let flat = n.length() > 0.0 && {
                    let n = n.normalize();
                    open.iter()
                        .flat_map(|&(a, b)| [a, b])
                        .all(|v| n.dot(mesh.vertices[v as usize] - p).abs() <= tol)
                };
                if !flat {
                    return None;
                }
                lid = lid_of(open, mesh, mean - p, n.normalize(), tol);
            }
            // Per face: which side the part lies on, and that no vertex lies beyond its
            // plane on the other: from a cap's edges when it has a lid, else vertex by
            // vertex.
            let cap = lid.as_ref().filter(|_| by_edges).and_then(|lid| {
                let cap = Cap {
                    mesh,
                    welded: &welded,
                    faces,
                    part: &fs,
                    ids: &ids,
                    vertices: &vertices,
                    open: &open[root],
                    inner: &inner[root],
                };
                cap.sides(lid, tol)
            });
            let proven = cap.is_some();
            let hull_ahead = match cap {
                Some(sides) => sides,
                None => tree_sides(faces, &fs, &vertices, mean, tol)?,
            };
            let part = ConvexPart {
                vertices,
                faces: fs,
                hull_ahead,
                lid,
            };
            Some((part, proven))
        })
        .collect();
    parts.sort_by_key(|(p, _)| p.faces[0]);
    parts
}

/// Per face of a part (`part`, with distinct `vertices` and their `mean`, m): whether the
/// part lies ahead of it, by testing the vertices against its plane (within `tol`, m), in
/// parallel; `None` when some face has vertices beyond it on both sides.
fn tree_sides(
    faces: &Faces,
    part: &[u32],
    vertices: &[glam::DVec3],
    mean: glam::DVec3,
    tol: f64,
) -> Option<Vec<bool>> {
    let points = super::mesh::Points::new(vertices);
    let tree = super::mesh::PointTree::new(vertices);
    // well over the rounding of a height (~1e-16 of the coordinates)
    let slack = 1e-4 * tol;
    part.par_iter()
        .map(|&f| {
            let face = &faces.faces[f as usize];
            let (n, c) = (face.normal, face.centroid);
            let h = n.dot(mean - c);
            // the mean's height is the vertices' mean height, to rounding far below the
            // tolerance: beyond twice it, some vertex is beyond it
            let (ahead, behind) = if h < -2.0 * tol {
                (tree.any_beyond(n, c, tol, slack), true)
            } else if h > 2.0 * tol {
                (true, tree.any_beyond(-n, c, tol, slack))
            } else {
                points.sides(n, c, tol)
            };
            // on its hull's boundary unless vertices lie on both sides
            (!(ahead && behind)).then_some(ahead)
        })
        .collect()
}

/// A cap's triangles and edges, for proving it convex from its edges alone.
struct Cap<'a> {
    mesh: &'a Mesh,
    /// Per mesh vertex: its welded id.
    welded: &'a [u32],
    faces: &'a Faces,
    /// The cap's faces.
    part: &'a [u32],
    /// The cap's welded vertex ids, sorted, and their positions (m).
    ids: &'a [u32],
    vertices: &'a [glam::DVec3],
    /// Its open edges (welded ids) and inner edges (the two triangles sharing each).
    open: &'a [(u32, u32)],
    inner: &'a [(u32, u32)],
}

/// Least cosine between a cap's triangles and its lid's axis for the local proof: a
/// triangle closer to edge-on projects too thin for the error bound to be useful.
const MIN_CAP_COS: f64 = 1e-6;

impl Cap<'_> {
    /// Per face, whether the cap lies ahead of it (its vertices all on that side of the
    /// face's plane, within `tol`, m), proven from the cap's edges; `None` when the proof
    /// does not apply (the caller then tests every face against the vertices).
    ///
    /// Linear time, where a tree query per face costs a pass near its plane: the cap is a
    /// disk (V − E + F = 1, one boundary loop: the lid's, convex and simple); every
    /// triangle projects onto the lid's plane with one orientation, and the projected
    /// angles about each inner vertex add up to one turn, so the projection is a local
    /// homeomorphism that takes the boundary once round the lid: by the degree argument it
    /// is one-to-one, and the cap is the graph of a piecewise-linear function over a
    /// convex polygon. Every inner edge bends one way, so that function is convex (or
    /// concave) and every triangle's plane supports it. Kinks the wrong way (rounding, or
    /// faces merged within the merge tolerance) are allowed while the bound they put on
    /// any vertex's distance beyond a face's plane stays within `tol`.
    fn sides(&self, lid: &Lid, tol: f64) -> Option<Vec<bool>> {
        let (vertices, n) = (self.vertices, self.vertices.len());
        let triangles: Vec<u32> = self
            .part
            .iter()
            .flat_map(|&f| self.faces.faces[f as usize].triangles.iter().copied())
            .collect();
        if n + triangles.len() != self.inner.len() + self.open.len() + 1 {
            return None; // not a disk (V − E + F = 1)
        }
        let mut local = vec![u32::MAX; self.mesh.vertices.len()];
        for (i, &v) in self.ids.iter().enumerate() {
            local[v as usize] = i as u32;
        }
        let corners = |t: u32| {
            self.mesh.triangles[t as usize]
                .map(|v| local[self.welded[v as usize] as usize] as usize)
        };
        let flat = |p: glam::DVec3| glam::DVec2::new(p.dot(lid.u), p.dot(lid.w));
        // one orientation in projection, and the projected angles about each vertex
        let mut sign = 0.0;
        let mut turn = vec![0.0; n];
        for &t in &triangles {
            let c = corners(t);
            let p = c.map(|i| vertices[i]);
            let area = (p[1] - p[0]).cross(p[2] - p[0]);
            let cos = area.dot(lid.normal) / area.length();
            // (a NaN cosine, of a degenerate triangle, fails too)
            if cos.abs().is_nan()
                || cos.abs() < MIN_CAP_COS
                || (sign != 0.0 && cos.signum() != sign)
            {
                return None;
            }
            sign = cos.signum();
            let q = p.map(flat);
            for k in 0..3 {
                let (e1, e2) = (q[(k + 1) % 3] - q[k], q[(k + 2) % 3] - q[k]);
                turn[c[k]] += (sign * e1.perp_dot(e2)).atan2(e1.dot(e2));
            }
        }
        let mut rim = vec![false; n];
        for &(a, b) in self.open {
            rim[local[a as usize] as usize] = true;
            rim[local[b as usize] as usize] = true;
        }
        // the angle sums are whole turns: once round, not twice
        let once_round = |t: f64| (t - std::f64::consts::TAU).abs() <= 0.5;
        if (0..n).any(|i| !rim[i] && !once_round(turn[i])) {
            return None;
        }
        // Every inner edge bends one way. A kink the wrong way (by rounding, on a face
        // merged from triangles) of normal height h, over a far corner at projected
        // distance d from the edge, turns the function's slope by h/(cos·d); a straight
        // path over the projection crosses each edge at most once, so over the cap's width
        // 2r the kinks misplace a vertex by at most 2r·Σ h/(cos·d) against any triangle's
        // plane.
        let (mut ahead_sum, mut behind_sum) = (0.0, 0.0);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &(s, t) in self.inner {
            let (a, b) = (corners(s), corners(t));
            let far = |x: &[usize; 3], y: &[usize; 3]| {
                let mut far = x.iter().filter(|v| !y.contains(v));
                match (far.next(), far.next()) {
                    (Some(&v), None) => Some(v),
                    _ => None,
                }
            };
            let (fa, fb) = (far(&a, &b)?, far(&b, &a)?);
            // b's far corner against a's plane
            let p = a.map(|i| vertices[i]);
            let area = (p[1] - p[0]).cross(p[2] - p[0]);
            let normal = area / area.length();
            let h = normal.dot(vertices[fb] - p[0]);
            let cos = normal.dot(lid.normal).abs();
            let edge: Vec<glam::DVec2> = a
                .iter()
                .filter(|&&v| v != fa)
                .map(|&v| flat(vertices[v]))
                .collect();
            let along = edge[1] - edge[0];
            let d = along.perp_dot(flat(vertices[fb]) - edge[0]).abs() / along.length();
            lo = lo.min(h);
            hi = hi.max(h);
            let turn = h.abs() / (cos * d);
            if h > 0.0 {
                behind_sum += turn; // a wrong-way kink if the hull lies behind
            } else {
                ahead_sum += turn;
            }
        }
        let slack = 1e-4 * tol;
        let (ahead, turns) = if hi <= slack {
            (false, behind_sum)
        } else if lo >= -slack {
            (true, ahead_sum)
        } else {
            return None;
        };
        let (_, radius) = super::mesh::bounding_sphere(vertices);
        let bound = 2.0 * radius * turns;
        // A face's plane against its first triangle's: every vertex within `bound` of the
        // triangle's plane on the hull's side is within this much more of the face's.
        let mut sides = Vec::with_capacity(self.part.len());
        for &f in self.part {
            let face = &self.faces.faces[f as usize];
            let p = corners(face.triangles[0]).map(|i| vertices[i]);
            let area = (p[1] - p[0]).cross(p[2] - p[0]);
            let tilt = (face.normal - area / area.length()).length();
            let off = p
                .iter()
                .map(|q| face.normal.dot(*q - face.centroid).abs())
                .fold(0.0, f64::max);
            let beyond = bound + 2.0 * radius * tilt + off;
            if beyond.is_nan() || beyond > tol {
                return None; // a kinked merged face: leave it to the tree
            }
            sides.push(ahead);
        }
        Some(sides)
    }
}

/// The lid of a cap whose open edges (directed, welded ids) lie in the plane of unit
/// normal `n`: `None` unless they chain into one convex loop. `inside` points from the
/// plane into the hull.
fn lid_of(
    open: &[(u32, u32)],
    mesh: &Mesh,
    inside: glam::DVec3,
    n: glam::DVec3,
    tol: f64,
) -> Option<Lid> {
    let mut next: Vec<(u32, u32)> = open.to_vec();
    next.sort_unstable();
    if next.windows(2).any(|w| w[0].0 == w[1].0) {
        return None; // the boundary passes a vertex twice
    }
    let mut ring = vec![next[0].0];
    loop {
        let last = *ring.last().expect("not empty");
        let k = next.binary_search_by_key(&last, |e| e.0).ok()?;
        if next[k].1 == ring[0] {
            break;
        }
        ring.push(next[k].1);
        if ring.len() > next.len() {
            return None;
        }
    }
    if ring.len() != next.len() {
        return None; // more than one loop
    }
    let normal = if n.dot(inside) > 0.0 { -n } else { n };
    let (u, w) = crate::geometry::orthonormal_basis(normal);
    let corners: Vec<glam::DVec3> = ring.iter().map(|&v| mesh.vertices[v as usize]).collect();
    let origin = corners[0];
    let mut outline: Vec<glam::DVec2> = corners
        .iter()
        .map(|c| glam::DVec2::new((*c - origin).dot(u), (*c - origin).dot(w)))
        .collect();
    if super::polygon::twice_signed_area(&outline) < 0.0 {
        outline.reverse();
    }
    // convex: no corner turns clockwise by more than `tol`, and the turns add up to one
    // full turn (a star polygon turns one way everywhere but winds more than once)
    let m = outline.len();
    let mut turning = 0.0;
    let convex = (0..m).all(|i| {
        let (a, b, c) = (outline[i], outline[(i + 1) % m], outline[(i + 2) % m]);
        let (e1, e2) = (b - a, c - b);
        turning += e1.perp_dot(e2).atan2(e1.dot(e2));
        e1.perp_dot(e2) >= -tol * e1.length().max(e2.length())
    });
    if !(convex && (turning - std::f64::consts::TAU).abs() < 1e-6) {
        return None;
    }
    Some(Lid::new(corners, normal, (u, w, origin), outline))
}

impl Lid {
    /// A lid from its corners (m), outward unit normal, in-plane axes and origin, and its
    /// outline (counter-clockwise, convex, in those axes): the circles and angles about
    /// the corners' mean that [`Lid::passes`] and [`Lid::clip`] decide by.
    fn new(
        corners: Vec<glam::DVec3>,
        normal: glam::DVec3,
        (u, w, origin): (glam::DVec3, glam::DVec3, glam::DVec3),
        outline: Vec<glam::DVec2>,
    ) -> Lid {
        let m = outline.len();
        let centre = outline.iter().sum::<glam::DVec2>() / m as f64;
        let inner = (0..m)
            .map(|i| {
                let (a, b) = (outline[i], outline[(i + 1) % m]);
                (b - a).perp_dot(centre - a) / (b - a).length().max(f64::MIN_POSITIVE)
            })
            .fold(f64::INFINITY, f64::min);
        let outer = outline
            .iter()
            .map(|p| p.distance(centre))
            .fold(0.0, f64::max);
        let mut angles: Vec<f64> = outline.iter().map(|p| pseudo_angle(*p - centre)).collect();
        for i in 1..angles.len() {
            while angles[i] < angles[i - 1] {
                angles[i] += TURN;
            }
        }
        Lid {
            corners,
            normal,
            u,
            w,
            origin,
            outline,
            centre,
            angles,
            // shrunk by a hair for rounding: a point this close is decided edge by edge
            inner: inner * (1.0 - 1e-9),
            outer,
        }
    }
}

/// A full turn in [`pseudo_angle`]'s units.
const TURN: f64 = 4.0;

/// A number in [0, 4) that increases with the angle of `r` from the x axis
/// (counter-clockwise) as atan2 does, one unit per quadrant: ordering by it is ordering by
/// angle, for a division instead of an arctangent. 0 for the zero vector.
fn pseudo_angle(r: glam::DVec2) -> f64 {
    let (x, y) = (r.x, r.y);
    let quarter = |a: f64, b: f64| if a + b > 0.0 { b / (a + b) } else { 0.0 };
    if y >= 0.0 {
        if x >= 0.0 {
            quarter(x, y)
        } else {
            1.0 + quarter(y, -x)
        }
    } else if x < 0.0 {
        2.0 + quarter(-x, -y)
    } else {
        3.0 + quarter(-y, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::builtin;

    #[test]
    fn a_finely_meshed_sphere_is_convex_by_its_edges_and_a_dent_or_a_second_one_is_not() {
        // 20·4^5 = 20,480 triangles: faces × vertices is past the exact test's cheap limit,
        // so the edge test decides
        let sphere = builtin::icosphere(5, 1.0);
        let faces = |m: &Mesh| Faces::build(m, true);
        assert!(sphere.triangles.len() * sphere.vertices.len() > CHEAP_EXACT);
        assert!(is_convex(&sphere, &faces(&sphere)));
        // one vertex pushed in by 1 % of the radius: a dent
        let mut dented = sphere.clone();
        dented.vertices[100] *= 0.99;
        assert!(!is_convex(&dented, &faces(&dented)));
        // two spheres side by side: each locally convex, together not
        let mut two = sphere.clone();
        let n = two.vertices.len() as u32;
        two.vertices
            .extend(sphere.vertices.iter().map(|v| *v + glam::DVec3::X * 3.0));
        two.triangles
            .extend(sphere.triangles.iter().map(|t| t.map(|i| i + n)));
        two.material_ids.extend(sphere.material_ids.iter().copied());
        assert!(!is_convex(&two, &faces(&two)));
    }

    /// The box-wing dish's lid, with a 7-gon squeezed off-centre for a lid whose inner
    /// and outer circles are far apart.
    fn lids() -> Vec<Lid> {
        let mesh = builtin::box_wing();
        let faces = Faces::build(&mesh, true);
        let parts = convex_parts(&mesh, &faces, 1e-9);
        let dish = parts
            .into_iter()
            .find(|p| p.lid.is_some())
            .expect("the dish");
        let mut lids = vec![dish.lid.expect("lid")];
        let base = &lids[0];
        let outline: Vec<glam::DVec2> = (0..7)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 7.0;
                glam::DVec2::new(0.9 * a.cos() + 0.2, 0.4 * a.sin() - 0.1)
            })
            .collect();
        let corners = outline.iter().map(|q| base.at(*q)).collect();
        let odd = Lid::new(corners, base.normal, (base.u, base.w, base.origin), outline);
        lids.push(odd);
        lids
    }

    /// Inside the outline, by every edge (the definition the lid's shortcuts must match).
    fn inside(lid: &Lid, q: glam::DVec2) -> bool {
        (0..lid.outline.len()).all(|i| {
            let (a, b) = lid.edge(i);
            (b - a).perp_dot(q - a) >= 0.0
        })
    }

    #[test]
    fn pseudo_angle_orders_as_the_angle_does() {
        // against atan2 over random vectors and the axes (where quadrants meet): exact
        // comparisons, since sectors are found by bisection on these keys
        let mut rnd = crate::test_rng(5);
        let angle = |r: glam::DVec2| r.y.atan2(r.x).rem_euclid(std::f64::consts::TAU);
        let mut v: Vec<glam::DVec2> = (0..2000)
            .map(|_| glam::DVec2::new(2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0))
            .collect();
        v.extend(
            [
                (1.0, 0.0),
                (0.0, 1.0),
                (-1.0, 0.0),
                (0.0, -1.0),
                (1.0, -1e-12),
            ]
            .map(|(x, y)| glam::DVec2::new(x, y)),
        );
        v.sort_by(|a, b| angle(*a).total_cmp(&angle(*b)));
        for w in v.windows(2) {
            assert!(
                pseudo_angle(w[0]) <= pseudo_angle(w[1]),
                "{} {}",
                w[0],
                w[1]
            );
            assert!((0.0..TURN).contains(&pseudo_angle(w[0])));
        }
        assert_eq!(pseudo_angle(glam::DVec2::new(0.0, 1.0)), 1.0);
        assert_eq!(pseudo_angle(glam::DVec2::new(-1.0, 0.0)), 2.0);
    }

    #[test]
    fn lid_shortcuts_agree_with_testing_every_edge() {
        // `passes` (one edge found by angle), `classify` (a ball at once) and `clip` (only
        // the edges some corner is outside of) against plain tests over all edges, for
        // random points, balls and triangles about the rim.
        let mut rnd = crate::test_rng(21);
        for lid in lids() {
            let below = lid.origin - lid.normal * 0.1;
            let (mut inside_n, mut outside_n, mut decided) = (0, 0, 0);
            let (mut wedged, mut wide) = (0, 0);
            for _ in 0..4000 {
                let d = (lid.normal * (0.2 + rnd())
                    + lid.u * (2.0 * rnd() - 1.0)
                    + lid.w * (2.0 * rnd() - 1.0))
                    .normalize();
                let p = below + lid.u * (2.0 * rnd() - 1.0) + lid.w * (2.0 * rnd() - 1.0);
                let q = lid.meet(p, d);
                let want = inside(&lid, q);
                assert_eq!(lid.passes(p, d, 0.0), want, "point {p} along {d}");
                if want {
                    inside_n += 1
                } else {
                    outside_n += 1
                }
                // a ball: its verdict must hold at its centre and at points on its surface
                let r = 0.2 * rnd();
                if let Some(all) = lid.classify(p, r, d, 0.0) {
                    decided += 1;
                    for _ in 0..20 {
                        let e = glam::DVec3::new(
                            2.0 * rnd() - 1.0,
                            2.0 * rnd() - 1.0,
                            2.0 * rnd() - 1.0,
                        );
                        let x = p + e.normalize_or_zero() * r;
                        assert_eq!(
                            inside(&lid, lid.meet(x, d)),
                            all,
                            "ball {p} r {r} along {d}"
                        );
                    }
                }
                // a triangle about q, clipped: its area against the plain clip by all edges
                // (now and then a large one, wider than a wedge of half a turn)
                let size = if rnd() < 0.25 { 3.0 } else { 0.6 };
                let tri: Vec<glam::DVec2> = (0..3)
                    .map(|_| q + glam::DVec2::new(rnd() - 0.5, rnd() - 0.5) * size)
                    .collect();
                if lid.wedge(&tri).is_some() {
                    wedged += 1;
                } else {
                    wide += 1;
                }
                let (mut poly, mut edges, mut scratch) = (tri.clone(), Vec::new(), Vec::new());
                lid.clip(&mut poly, &mut edges, &mut scratch);
                let mut region = crate::geometry::polygon::Region::default();
                region.reset(2.0);
                region.add_convex(&tri);
                region.intersect_convex(&lid.outline);
                let got = crate::geometry::polygon::twice_signed_area(&poly).abs() / 2.0;
                assert!(
                    (got - region.area()).abs() < 1e-12,
                    "{got} vs {}",
                    region.area()
                );
            }
            assert!(
                inside_n > 500 && outside_n > 500 && decided > 1000,
                "{inside_n} {outside_n} {decided}"
            );
            assert!(wedged > 1000 && wide > 200, "{wedged} {wide}");
        }
    }

    #[test]
    fn the_box_wings_parts_are_its_boxes_and_its_dish() {
        let mesh = builtin::box_wing();
        let faces = Faces::build(&mesh, true);
        let mut sizes: Vec<usize> = convex_parts(&mesh, &faces, 1e-9)
            .iter()
            .map(|p| p.faces.len())
            .collect();
        sizes.sort_unstable();
        // bus, two booms, mast (6 faces each); dish: 24 fan triangles + 4 × 24 quads
        assert_eq!(sizes, vec![6, 6, 6, 6, 120]);
        let parts = convex_parts(&mesh, &faces, 1e-9);
        let dish = parts.iter().find(|p| p.faces.len() == 120).unwrap();
        let lid = dish.lid.as_ref().expect("the dish's rim is its lid");
        assert_eq!(lid.corners.len(), 24);
        assert!(
            (lid.normal - glam::DVec3::Z).length() < 1e-12,
            "{}",
            lid.normal
        );
        assert!(
            dish.hull_ahead.iter().all(|&a| a),
            "the dish opens towards its normals"
        );
        // a ray from the dish's centre straight up leaves through the rim; one at 80°
        // from the axis hits the dish's side
        let centre = glam::DVec3::new(0.0, 0.0, 1.2);
        assert!(lid.passes(centre, glam::DVec3::Z, 1e-9));
        let low = glam::DVec3::new(80f64.to_radians().sin(), 0.0, 80f64.to_radians().cos());
        assert!(!lid.passes(centre, low, 1e-9));
        for p in parts.iter().filter(|p| p.faces.len() == 6) {
            assert!(
                p.lid.is_none() && p.hull_ahead.iter().all(|&a| !a),
                "boxes are closed"
            );
        }
    }

    /// A part as its faces, their sides and its lid's corner count.
    type PartSummary = (Vec<u32>, Vec<bool>, usize);

    /// The parts, and which were proven from their edges.
    fn summary(mesh: &Mesh, by_edges: bool) -> (Vec<PartSummary>, Vec<bool>) {
        let faces = Faces::build(mesh, true);
        let (_, scale) = mesh.bounding_sphere();
        parts_of(mesh, &faces, 1e-9 * scale, by_edges)
            .into_iter()
            .map(|(p, proven)| {
                let corners = p.lid.as_ref().map_or(0, |l| l.corners.len());
                ((p.faces, p.hull_ahead, corners), proven)
            })
            .unzip()
    }

    #[test]
    fn a_caps_edges_prove_what_testing_its_vertices_says() {
        // the box-wing's dishes, coarse and fine (the fine one's quads are faces of two
        // triangles, flat to rounding: kinks the wrong way within rounding)
        for mesh in [builtin::box_wing(), builtin::box_wing_with(48, 128, 3)] {
            let (by_edges, proven) = summary(&mesh, true);
            let (by_vertices, _) = summary(&mesh, false);
            assert_eq!(by_edges, by_vertices);
            // the dish is proven from its edges; the closed boxes are not caps
            let caps: Vec<bool> = by_edges.iter().map(|(_, _, c)| *c > 0).collect();
            assert_eq!(proven, caps);
            assert_eq!(caps.iter().filter(|&&c| c).count(), 1);
        }
    }

    #[test]
    fn a_dent_in_a_cap_is_found_from_its_edges_as_from_its_vertices() {
        // Push one inner dish vertex out of the dish's hull (against its concave side)
        // by multiples of the tolerance: beyond it the dish is no convex part; well
        // within it, still one (vertex by vertex), though no longer proven from edges
        // that now bend the wrong way by more than rounding.
        let plain = builtin::box_wing_with(16, 48, 0);
        let (_, scale) = plain.bounding_sphere();
        let tol = 1e-9 * scale;
        // the dish's vertices follow everything else: centre, then 48 per ring
        let dish_start = plain.vertices.len() - (1 + 16 * 48);
        for (ring, dents) in [(3, 1e3), (8, 10.0), (5, 0.1)] {
            let mut mesh = plain.clone();
            let v = dish_start + 1 + (ring - 1) * 48 + 7;
            mesh.vertices[v].z -= dents * tol;
            let (by_edges, proven) = summary(&mesh, true);
            let (by_vertices, _) = summary(&mesh, false);
            assert_eq!(by_edges, by_vertices, "dent of {dents} tol");
            let dish_kept = by_edges.iter().any(|(_, _, c)| *c > 0);
            assert_eq!(dish_kept, dents < 1.0, "dent of {dents} tol");
            assert!(proven.iter().all(|p| !p), "dent of {dents} tol");
        }
    }

    #[test]
    fn non_convex_or_open_on_two_sides_is_no_part() {
        // a zigzag of three plates: the middle one's plane has the others' far edges on
        // both of its sides
        let mut zigzag = Mesh::default();
        let y = glam::DVec3::Y;
        let p: Vec<glam::DVec3> = [(0.0, 0.0), (1.0, 1.0), (2.0, 0.0), (3.0, 1.0)]
            .iter()
            .map(|&(x, z)| glam::DVec3::new(x, 0.0, z))
            .collect();
        for w in p.windows(2) {
            builtin::push_quad(&mut zigzag, [w[0], w[1], w[1] + y, w[0] + y], 0);
        }
        let faces = Faces::build(&zigzag, true);
        assert_eq!(faces.len(), 3);
        assert!(convex_parts(&zigzag, &faces, 1e-9).is_empty());
        // a square tube (a box without its two ends): convex, but a line along its axis
        // passes through both open ends without touching it
        let mut tube = Mesh::default();
        builtin::push_box(
            &mut tube,
            glam::DVec3::splat(-1.0),
            glam::DVec3::splat(1.0),
            0,
        );
        let keep: Vec<bool> = (0..tube.triangles.len())
            .map(|t| tube.area_vector(t).normalize().z.abs() < 0.5)
            .collect();
        let mut k = keep.iter();
        tube.triangles.retain(|_| *k.next().unwrap());
        tube.material_ids.truncate(tube.triangles.len());
        let faces = Faces::build(&tube, true);
        assert_eq!(faces.len(), 4);
        assert!(convex_parts(&tube, &faces, 1e-9).is_empty());
    }
}
