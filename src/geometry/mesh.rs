//! The triangle mesh in the body frame, in f64 metres.

use super::csr::{csr_of, sort_within};
use glam::DVec3;
use rayon::prelude::*;

/// A validated triangle mesh: every index in range, every triangle non-degenerate,
/// one material index per triangle.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, m.
    pub vertices: Vec<DVec3>,
    /// Counter-clockwise (seen from outside) vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Index into the scene's materials, one per triangle.
    pub material_ids: Vec<u32>,
    /// How far the input's rounding may have moved a coordinate from its true value, m:
    /// half a step of the last digit a file wrote them with ([`written_rounding`]), 0 for
    /// coordinates made in f64. Rigid motions keep it.
    pub rounding: f64,
}

impl Mesh {
    /// The three corners of triangle `i`, m.
    #[inline]
    pub fn corners(&self, i: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[i];
        [
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        ]
    }

    /// For each vertex, the first vertex at exactly the same position: ids that let meshes
    /// with split vertices (as OBJ exporters often write them) still share their edges.
    pub fn welded_ids(&self) -> Vec<u32> {
        self.welded_ids_within(None)
    }

    /// [`Mesh::welded_ids`], welding only vertices of one group when `group` (per
    /// vertex) is given: parts that move apart (articulated links) never share an edge.
    pub fn welded_ids_within(&self, group: Option<&[u32]>) -> Vec<u32> {
        // A vertex's place: its position's bits, and its group.
        let place = |i: usize| {
            let v = self.vertices[i];
            let g = group.map_or(0, |g| g[i]);
            ([v.x.to_bits(), v.y.to_bits(), v.z.to_bits()], g)
        };
        first_at_place(self.vertices.len(), place, place_hash)
    }

    /// The welded ids ([`Mesh::welded_ids`]) and every triangle's edges by their welded
    /// ends, lower first, with the triangle, sorted: the triangles sharing an edge are then
    /// side by side, the first of them first (grouped by the lower end, then each vertex's
    /// few edges sorted by the other: no hash map, no comparison sort of them all).
    pub fn welded_edges(&self) -> (Vec<u32>, Vec<(u32, u32, u32)>) {
        self.welded_edges_within(None)
    }

    /// [`Mesh::welded_edges`] with vertices welded only within their `group`
    /// ([`Mesh::welded_ids_within`]).
    pub fn welded_edges_within(&self, group: Option<&[u32]>) -> (Vec<u32>, Vec<(u32, u32, u32)>) {
        let welded = self.welded_ids_within(group);
        // grouped by the lower end, in triangle order, then each vertex's few edges by
        // the other end, stably
        let ids = &welded;
        let edges = self.triangles.iter().enumerate().flat_map(|(t, tri)| {
            (0..3).map(move |k| {
                let (a, b) = (ids[tri[k] as usize], ids[tri[(k + 1) % 3] as usize]);
                (a.min(b), (a.min(b), a.max(b), t as u32))
            })
        });
        let (at, mut edges) = csr_of(welded.len(), edges);
        sort_within(&at, &mut edges, |e| e.1);
        (welded, edges)
    }

    /// Twice-area vector (b−a)×(c−a) of triangle `i`: its direction is the outward normal.
    #[inline]
    pub fn area_vector(&self, i: usize) -> DVec3 {
        let [a, b, c] = self.corners(i);
        (b - a).cross(c - a)
    }

    /// Centre of the axis-aligned bounding box and the radius of the sphere around it
    /// that holds every vertex, m.
    pub fn bounding_sphere(&self) -> (DVec3, f64) {
        bounding_sphere(&self.vertices)
    }

    /// Height (m) within which points count as one place in this mesh — rounding, not
    /// geometry: 1e-9 of its size, or 8× its [`Mesh::rounding`] where that is more. A
    /// corner rounded by r a coordinate lies within √3·r of its true plane, and a plane
    /// fitted to rounded corners may tilt by as much again at a face's rim: merged faces
    /// are kept flat within half of this ([`super::faces::Faces::build`]), so their own
    /// corners stay well within it of their planes.
    pub fn tolerance(&self) -> f64 {
        self.tolerance_at(self.bounding_sphere().1)
    }

    /// [`Mesh::tolerance`] for a mesh of bounding radius `scale` (m), known already.
    pub fn tolerance_at(&self, scale: f64) -> f64 {
        (1e-9 * scale).max(8.0 * self.rounding)
    }

    /// Total surface area, m².
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|i| 0.5 * self.area_vector(i).length())
            .sum()
    }

    /// The same mesh with every vertex mapped by `f` (scaling, rotation in tests).
    pub fn transformed(&self, f: impl Fn(DVec3) -> DVec3 + Sync) -> Mesh {
        use rayon::prelude::*;
        Mesh {
            // in parallel: a built-in object's noise costs thousands of operations a vertex
            vertices: self.vertices.par_iter().map(|v| f(*v)).collect(),
            triangles: self.triangles.clone(),
            material_ids: self.material_ids.clone(),
            rounding: self.rounding,
        }
    }
}

/// How far the digits that `vertices` were written with may have rounded a coordinate
/// off its value, m, or 0 when they show no rounding. Two ways of writing are read,
/// whichever shows the larger rounding: a fixed number of decimals (`%.6f`, what most OBJ
/// exporters write: half a step of the most decimals any coordinate carries, 6 to 9) and
/// a fixed number of significant digits (`%g`, C++ streams: half a step of the largest
/// coordinate's last digit, for the most digits any coordinate carries, 6 to 9).
/// Coordinates stored in single precision ([`single_rounding`]: a float32 array from
/// VTK, a binary STL, a GPU pipeline, an assimp export) are read as rounded by one step
/// of an f32 at the largest coordinate, printed in full or short.
/// Coordinates of more digits (made in f64), of fewer (a box at ±0.5 m: nothing was
/// rounded off, or too little to tell), or beyond 1 km at fixed decimals (where f64
/// cannot tell 9 decimals apart) read as exact.
pub fn written_rounding(vertices: &[DVec3]) -> f64 {
    // `%g` writes its small coordinates with more decimals than its large ones, whose
    // last digit rounds by more; `%.9f` writes more digits than `%g` reads
    let (decimals, digits) = (decimal_rounding(vertices), significant_rounding(vertices));
    decimals
        .max(digits)
        .max(single_rounding(vertices, decimals, digits > 0.0))
}

/// Coordinates looked at to tell whether short decimals are f32s printed short.
const SHORT_SAMPLE: usize = 4096;

/// [`written_rounding`] for coordinates that went through f32: one step of its 24-bit
/// significand at the largest coordinate (an f32 rounds a coordinate by up to half a
/// step, and the shortest decimal that reads back to it lies up to half a step further
/// on), or 0 when they did not. Printed in full (`0.10000000149011612`, what
/// `json.dumps(numpy.float32(x).tolist())` writes), every coordinate is an f32 read back
/// exactly, and some are not short decimals (a box at ±0.5 m is an f32 too, but nothing
/// was rounded off). Printed short (`0.1`, `str(numpy.float32(x))`; `0.100000001`,
/// `%.9g` as C++ streams at `max_digits10` and assimp write), every coordinate looked at
/// (up to [`SHORT_SAMPLE`], spread over the mesh) has as many digits as the shortest
/// decimal of its f32, or is its f32 rounded to the digits written. `decimals` and
/// `digits`: the other readings ([`decimal_rounding`], and whether
/// [`significant_rounding`] found 6 to 9 digits): without digits there are too few to
/// tell, and fixed decimals at least half as coarse as an f32's step explain short
/// coordinates themselves (`%.6f` of a 9.5 m coordinate is as short as its f32 printed
/// shortest). Most coordinates written with 8 or 9 digits from f64 are neither, so a
/// sample of thousands does not mistake the one for the other.
fn single_rounding(vertices: &[DVec3], decimals: f64, digits: bool) -> f64 {
    let coords = || vertices.iter().flat_map(|v| v.to_array());
    // most meshes are made in f64: their first coordinate that is no f32 ends this, before
    // the largest coordinate is looked for
    let in_full = coords().all(|x| (x as f32) as f64 == x) && coords().any(|x| !whole(x, 9));
    if !in_full && !digits {
        return 0.0;
    }
    let largest = coords().map(f64::abs).fold(0.0, f64::max);
    if !largest.is_normal() {
        return 0.0;
    }
    // the largest coordinate's binary exponent, read from its bits (no rounded log)
    let step = 2f64.powi(((largest.to_bits() >> 52) & 0x7ff) as i32 - 1023 - 23);
    // as many digits as the f32's shortest decimal (writers break ties either way), or
    // the f32 rounded to as many digits as were written, up to the 9 that tell any two
    // f32s apart (`%.9g`, `max_digits10`: what C++ streams and assimp write)
    let printed_short = || {
        let every = (3 * vertices.len()).div_ceil(SHORT_SAMPLE).max(1);
        coords().step_by(every).all(|x| {
            let (single, written) = (x as f32, digits_of(&format!("{x}")));
            written == digits_of(&format!("{single}"))
                || (written.max(1)..=9)
                    .any(|k| format!("{:.*e}", k - 1, single as f64).parse::<f64>() == Ok(x))
        })
    };
    let short = digits && decimals < 0.5 * step;
    if in_full || short && printed_short() {
        step
    } else {
        0.0
    }
}

/// Within a thousandth of a step, `x`·10ᵏ is a whole number: a decimal read into f64 is
/// off by ~1e-16 of itself, well within that up to 10¹² steps.
fn whole(x: f64, k: i32) -> bool {
    let y = x * 10f64.powi(k);
    (y - y.round()).abs() <= 1e-3
}

/// The significant digits of a number as Rust writes it (no exponent): `-0.0012500` → 3.
fn digits_of(written: &str) -> usize {
    let digits: String = written.chars().filter(char::is_ascii_digit).collect();
    digits.trim_start_matches('0').trim_end_matches('0').len()
}

/// [`written_rounding`] for a fixed number of decimals.
fn decimal_rounding(vertices: &[DVec3]) -> f64 {
    let coords = || vertices.iter().flat_map(|v| v.to_array());
    if vertices.is_empty() || coords().any(|x| x.abs() >= 1e3 || !whole(x, 9)) {
        return 0.0;
    }
    match (5..9).find(|&k| coords().all(|x| whole(x, k))) {
        Some(5) => 0.0,
        Some(k) => 0.5 * 10f64.powi(-k),
        None => 0.5e-9,
    }
}

/// [`written_rounding`] for a fixed number of significant digits.
fn significant_rounding(vertices: &[DVec3]) -> f64 {
    // x > 0 is 10^e times a number in [1, 10)
    let exponent = |x: f64| {
        let e = x.log10().floor() as i32;
        if 10f64.powi(e) > x {
            e - 1
        } else if 10f64.powi(e + 1) <= x {
            e + 1
        } else {
            e
        }
    };
    let (mut digits, mut largest) = (0, i32::MIN);
    // below 1e-12 m a coordinate is zero written as noise, whatever its digits
    for x in vertices
        .iter()
        .flat_map(|v| v.to_array())
        .map(f64::abs)
        .filter(|&x| x > 1e-12)
    {
        let e = exponent(x);
        largest = largest.max(e);
        // x to s digits is a whole number of 10^(e − s + 1)
        if digits > 0 && whole(x, digits - 1 - e) {
            continue;
        }
        match (digits + 1..=9).find(|&s| whole(x, s - 1 - e)) {
            Some(s) => digits = s,
            None => return 0.0,
        }
    }
    if digits < 6 {
        return 0.0;
    }
    0.5 * 10f64.powi(largest - digits + 1)
}

/// A sphere holding every point: centre (of their bounding box) and radius, m.
pub fn bounding_sphere(points: &[DVec3]) -> (DVec3, f64) {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), v| (lo.min(*v), hi.max(*v)),
    );
    let centre = 0.5 * (lo + hi);
    let radius = points
        .iter()
        .map(|v| v.distance(centre))
        .fold(0.0, f64::max);
    (centre, radius)
}

/// Points stored by coordinate (all x, then all y, then all z), for tests run against
/// many points at once: plane-side tests over them compile to vector instructions.
#[derive(Debug, Clone, Default)]
pub struct Points {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
}

impl Points {
    pub fn new(points: &[DVec3]) -> Points {
        Points {
            x: points.iter().map(|p| p.x).collect(),
            y: points.iter().map(|p| p.y).collect(),
            z: points.iter().map(|p| p.z).collect(),
        }
    }

    /// Whether some point lies more than `tol` (m) in front of the plane through `c` with
    /// unit normal `n`, and whether some point lies more than `tol` behind it. Heights are
    /// `n·(p − c)` rounded as [`DVec3::dot`] rounds them.
    pub fn sides(&self, n: DVec3, c: DVec3, tol: f64) -> (bool, bool) {
        let (mut ahead, mut behind) = (false, false);
        for ((&x, &y), &z) in self.x.iter().zip(&self.y).zip(&self.z) {
            let h = height(n, c, x, y, z);
            ahead |= h > tol;
            behind |= h < -tol;
        }
        (ahead, behind)
    }
}

/// Height (m) of the point (x, y, z) above the plane through `c` with unit normal `n`,
/// rounded as [`DVec3::dot`] rounds it: one expression for every test that must agree
/// to the last bit.
#[inline(always)]
fn height(n: DVec3, c: DVec3, x: f64, y: f64, z: f64) -> f64 {
    (n.x * (x - c.x) + n.y * (y - c.y)) + n.z * (z - c.z)
}

/// Points in a tree of boxes, to show that none lies beyond a plane without testing each:
/// a box wholly on the near side is passed over. Proving a convex part's faces (every
/// vertex on one side of every face's plane) visits, per face, the boxes near its plane.
/// Boxes, not balls: a shallow dish lies within a ball's radius of every tangent plane,
/// but its boxes are flat.
#[derive(Debug, Clone, Default)]
pub struct PointTree {
    /// The points in tree order: each node covers a range.
    points: Points,
    nodes: Vec<PointNode>,
}

#[derive(Debug, Clone)]
struct PointNode {
    /// Centre and half extents of the node's bounding box, m.
    centre: DVec3,
    half: DVec3,
    start: u32,
    end: u32,
    /// Index of the second child (the first is the next node); 0 for a leaf.
    second: u32,
}

/// Points per leaf: below this a box test saves less than it costs.
const TREE_LEAF: usize = 16;

impl PointTree {
    pub fn new(points: &[DVec3]) -> PointTree {
        let mut order: Vec<DVec3> = points.to_vec();
        let mut nodes = Vec::with_capacity(2 * points.len() / TREE_LEAF + 1);
        if !order.is_empty() {
            let n = order.len();
            split_points(&mut order, 0, n, &mut nodes);
        }
        PointTree {
            points: Points::new(&order),
            nodes,
        }
    }

    /// Does some point lie more than `limit` (m) in front of the plane through `c` with
    /// unit normal `n` — its height `n·(p − c)` rounded as [`Points::sides`] rounds it?
    /// `slack` (m) must exceed the rounding of a height (a box is passed over when its
    /// bound is below `limit − slack`), so the answer is exactly that of testing every
    /// point.
    pub fn any_beyond(&self, n: DVec3, c: DVec3, limit: f64, slack: f64) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = vec![0usize];
        while let Some(at) = stack.pop() {
            let node = &self.nodes[at];
            if n.dot(node.centre - c) + n.abs().dot(node.half) <= limit - slack {
                continue;
            }
            if node.second == 0 {
                let (start, end) = (node.start as usize, node.end as usize);
                let (x, y, z) = (&self.points.x, &self.points.y, &self.points.z);
                if (start..end).any(|i| height(n, c, x[i], y[i], z[i]) > limit) {
                    return true;
                }
                continue;
            }
            stack.push(node.second as usize);
            stack.push(at + 1);
        }
        false
    }
}

/// Builds the nodes over `points[start..end]` (reordered): median splits along the widest
/// axis.
fn split_points(points: &mut [DVec3], start: usize, end: usize, nodes: &mut Vec<PointNode>) {
    let part = &mut points[start..end];
    let (lo, hi) = part
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let at = nodes.len();
    nodes.push(PointNode {
        centre: 0.5 * (lo + hi),
        // a little over, by the rounding of the centre: a bound must not fall short
        half: 0.5 * (hi - lo) + lo.abs().max(hi.abs()) * (4.0 * f64::EPSILON),
        start: start as u32,
        end: end as u32,
        second: 0,
    });
    if part.len() <= TREE_LEAF {
        return;
    }
    let axis = (hi - lo).max_position();
    let mid = part.len() / 2;
    part.select_nth_unstable_by(mid, |a, b| a[axis].total_cmp(&b[axis]));
    split_points(points, start, start + mid, nodes);
    nodes[at].second = nodes.len() as u32;
    split_points(points, start + mid, end, nodes);
}

/// For each of `n` items, the least index with the same place (`place(i)`), found
/// through `hash` of the places. Every place's items fall in one bucket of the hash's
/// top bits (about a hundred items a bucket); sorted by hash and index within its
/// bucket, a run of one hash starts with its least index, which each item of the run
/// takes. Each item is then checked against the one it took, and a run in which two
/// places share a hash is done again by place. No comparison sort of all the places:
/// a triangle soup of 600k vertices (every triangle its own corners, as STL files and
/// many OBJ exporters write them) sorted by place took 40–60 ms, most of a
/// 200k-triangle cubesat's preparation (docs/performance.md, twenty-fourth sitting).
fn first_at_place<P: Ord + Copy + Send>(
    n: usize,
    place: impl Fn(usize) -> P + Sync,
    hash: impl Fn(P) -> u64 + Sync,
) -> Vec<u32> {
    let hashes: Vec<u64> = (0..n).into_par_iter().map(|i| hash(place(i))).collect();
    let bits = (n / 128)
        .max(1)
        .next_power_of_two()
        .trailing_zeros()
        .clamp(1, 16);
    let bucket = |h: u64| (h >> (64 - bits)) as u32;
    let (start, mut keyed) = csr_of(
        1 << bits,
        hashes
            .iter()
            .enumerate()
            .map(|(i, &h)| (bucket(h), (h, i as u32))),
    );
    // each bucket by (hash, index); each entry's hash then replaced by its run's first
    keyed
        .par_chunk_by_mut(|a, b| bucket(a.0) == bucket(b.0))
        .for_each(|items| {
            items.sort_unstable();
            for run in items.chunk_by_mut(|a, b| a.0 == b.0) {
                let first = u64::from(run[0].1);
                run.iter_mut().for_each(|e| e.0 = first);
            }
        });
    let mut ids = vec![0u32; n];
    for &(first, i) in &keyed {
        ids[i as usize] = first as u32;
    }
    // an item whose first differs in place shares its hash with another place
    let mut clashes: Vec<u64> = (0..n)
        .into_par_iter()
        .filter(|&i| place(ids[i] as usize) != place(i))
        .map(|i| hashes[i])
        .collect();
    clashes.sort_unstable();
    clashes.dedup();
    for h in clashes {
        let b = bucket(h) as usize;
        let mut by_place: Vec<(P, u32)> = keyed[start[b] as usize..start[b + 1] as usize]
            .iter()
            .filter(|e| hashes[e.1 as usize] == h)
            .map(|&(_, i)| (place(i as usize), i))
            .collect();
        by_place.sort_unstable();
        for same in by_place.chunk_by(|a, b| a.0 == b.0) {
            for &(_, i) in same {
                ids[i as usize] = same[0].1;
            }
        }
    }
    ids
}

/// A hash of a vertex's place (its position's bits and its group) for
/// [`Mesh::welded_ids_within`]: its parts mixed so that positions a bit apart land far
/// apart (splitmix64's finaliser on a multiply-xor fold).
#[inline]
fn place_hash((bits, group): ([u64; 3], u32)) -> u64 {
    let mix = |h: u64| {
        let h = (h ^ (h >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        let h = (h ^ (h >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        h ^ (h >> 31)
    };
    let h = mix(bits[0] ^ u64::from(group).rotate_left(32));
    let h = mix(h ^ bits[1]);
    mix(h ^ bits[2])
}

/// An f32 printed by some writer, read back as f64.
#[cfg(test)]
pub(crate) type F32Print = fn(f32) -> f64;

/// An f32 as three writers hand it over, read back: in full (`json.dumps` of a float32
/// array's `tolist()`), shortest (`str(numpy.float32(x))`) and to 9 significant digits
/// (`%.9g`, C++ streams at `max_digits10`, assimp). For the tests of meshes stored in
/// single precision.
#[cfg(test)]
pub(crate) const F32_PRINTS: [(&str, F32Print); 3] = [
    ("in full", |x| x as f64),
    ("shortest", |x| format!("{x}").parse().expect("a number")),
    ("%.9g", |x| {
        format!("{:.8e}", x as f64).parse().expect("a number")
    }),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_tree_answers_as_testing_every_point_does() {
        // Exactly, also where a point lies at the limit: planes through points of the set
        // (limit 0 and ±1e-12), among them supporting planes (every point on or behind),
        // on a shallow dish, a flat grid and a cloud far from the origin (where the boxes'
        // centres round).
        let mut rnd = crate::test_rng(5);
        let dish: Vec<DVec3> = (0..3000)
            .map(|_| {
                let (x, y) = (2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0);
                DVec3::new(x, y, 0.3 * (x * x + y * y))
            })
            .collect();
        let flat: Vec<DVec3> = (0..40 * 40)
            .map(|i| DVec3::new((i % 40) as f64 * 0.025, (i / 40) as f64 * 0.025, 1.0))
            .collect();
        let far: Vec<DVec3> = (0..500)
            .map(|_| DVec3::new(1e6 + rnd(), -3e5 + rnd(), 7e5 + rnd()))
            .collect();
        let mut checked = [0usize; 2];
        for points in [dish, flat, far] {
            let (tree, all) = (PointTree::new(&points), Points::new(&points));
            for _ in 0..300 {
                let n =
                    DVec3::new(2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0).normalize();
                // through a random point, or the one farthest along n (none beyond)
                let c = if rnd() < 0.5 {
                    points[(rnd() * points.len() as f64) as usize]
                } else {
                    *points
                        .iter()
                        .max_by(|a, b| n.dot(**a).total_cmp(&n.dot(**b)))
                        .expect("points")
                };
                for limit in [0.0, 1e-12, -1e-12] {
                    let (ahead, _) = all.sides(n, c, limit);
                    assert_eq!(
                        tree.any_beyond(n, c, limit, 1e-13),
                        ahead,
                        "{n} {c} {limit}"
                    );
                    checked[usize::from(ahead)] += 1;
                }
            }
        }
        assert!(checked.iter().all(|&k| k > 100), "{checked:?}");
    }

    #[test]
    fn each_vertex_is_welded_to_the_first_at_its_place() {
        // the brute-force answer: the least index with the same bits and group
        fn first_at(vs: &[DVec3], group: Option<&[u32]>) -> Vec<u32> {
            let place = |i: usize| {
                let v = vs[i];
                let g = group.map_or(0, |g| g[i]);
                ([v.x.to_bits(), v.y.to_bits(), v.z.to_bits()], g)
            };
            (0..vs.len())
                .map(|i| (0..=i).find(|&k| place(k) == place(i)).unwrap() as u32)
                .collect()
        }
        // a ball whose triangles each have their own corners (five or six vertices a
        // place), 200 vertices at one place (past the short runs), +0 and −0 (places
        // apart: their bits differ), in a shuffled order
        let ball = crate::geometry::builtin::geodesic_sphere(3, 1.0);
        let mut vs: Vec<DVec3> = ball
            .triangles
            .iter()
            .flat_map(|t| t.map(|k| ball.vertices[k as usize]))
            .collect();
        vs.extend(std::iter::repeat_n(DVec3::new(2.0, 0.5, -1.0), 200));
        vs.extend([DVec3::new(0.0, 1.0, 5.0), DVec3::new(-0.0, 1.0, 5.0)]);
        vs.extend([DVec3::new(0.0, 1.0, 5.0), DVec3::new(-0.0, 1.0, 5.0)]);
        let n = vs.len();
        let order: Vec<usize> = (0..n).map(|i| (i * 7919) % n).collect();
        assert!(
            n % 7919 != 0,
            "i·7919 mod n is a permutation when 7919 (prime) does not divide n"
        );
        let vs: Vec<DVec3> = order.iter().map(|&i| vs[i]).collect();
        let mesh = Mesh {
            vertices: vs.clone(),
            ..Mesh::default()
        };
        assert_eq!(mesh.welded_ids(), first_at(&vs, None));
        // groups split places: every third vertex in group 1
        let group: Vec<u32> = (0..n as u32).map(|i| u32::from(i % 3 == 0)).collect();
        assert_eq!(
            mesh.welded_ids_within(Some(&group)),
            first_at(&vs, Some(&group))
        );
        // hashes that clash: every place one hash, and two hashes for many places
        let places = |i: usize| (vs[i].x.to_bits(), vs[i].y.to_bits(), vs[i].z.to_bits());
        let want = first_at(&vs, None);
        assert_eq!(first_at_place(n, places, |_| 0), want);
        assert_eq!(first_at_place(n, places, |p| p.0 & 1), want);
        // and the welding is not idle: the ball's corners share places
        assert!(
            mesh.welded_ids()
                .iter()
                .enumerate()
                .filter(|&(i, &w)| w as usize != i)
                .count()
                > n / 2
        );
    }

    #[test]
    fn welded_edges_are_every_edge_sorted_with_split_vertices_welded() {
        // a geodesic ball (valences 5 and 6) with every triangle given its own three
        // vertices, and a fan of 40 triangles around one vertex (one long run)
        let ball = crate::geometry::builtin::geodesic_sphere(4, 1.0);
        let mut mesh = Mesh::default();
        for t in &ball.triangles {
            let base = mesh.vertices.len() as u32;
            mesh.vertices.extend(t.map(|k| ball.vertices[k as usize]));
            mesh.triangles.push([base, base + 1, base + 2]);
        }
        let centre = mesh.vertices.len() as u32;
        mesh.vertices.push(DVec3::new(3.0, 0.0, 0.0));
        for i in 0..40u32 {
            let at = |k: u32| {
                let a = k as f64 / 40.0 * std::f64::consts::TAU;
                DVec3::new(3.0, a.cos(), a.sin())
            };
            let base = mesh.vertices.len() as u32;
            mesh.vertices.extend([at(i), at(i + 1)]);
            mesh.triangles.push([centre, base, base + 1]);
        }
        mesh.material_ids = vec![0; mesh.triangles.len()];
        let (welded, edges) = mesh.welded_edges();
        assert_eq!(welded, mesh.welded_ids());
        let mut want: Vec<(u32, u32, u32)> = Vec::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (welded[tri[k] as usize], welded[tri[(k + 1) % 3] as usize]);
                want.push((a.min(b), a.max(b), t as u32));
            }
        }
        want.sort_unstable();
        assert_eq!(edges, want);
        // welded: each inner edge of the ball is shared by two triangles
        let shared = edges
            .windows(2)
            .filter(|w| (w[0].0, w[0].1) == (w[1].0, w[1].1))
            .count();
        assert_eq!(shared, 3 * ball.triangles.len() / 2 + 39);
    }

    #[test]
    fn the_rounding_is_read_from_the_digits_written() {
        // points of a ball: every coordinate carries all its digits
        let ball = crate::geometry::builtin::geodesic_sphere(3, 1.3);
        let written = |k: i32| -> Vec<DVec3> {
            let s = 10f64.powi(k);
            ball.vertices.iter().map(|v| (*v * s).round() / s).collect()
        };
        assert_eq!(written_rounding(&ball.vertices), 0.0, "made in f64");
        for k in 6..=9 {
            assert_eq!(written_rounding(&written(k)), 0.5 * 10f64.powi(-k), "{k}");
        }
        // 5 decimals of coordinates up to 1.3 m are 6 significant digits
        assert_eq!(written_rounding(&written(5)), 0.5e-5);
        // significant digits (`%g`): half a step of the largest coordinate's last digit,
        // on a ball of 1.3 m and one of 130 m
        let digits = |r: f64, s: usize| -> Vec<DVec3> {
            let d = |x: f64| {
                format!("{:.*e}", s - 1, x)
                    .parse::<f64>()
                    .expect("a number")
            };
            ball.vertices
                .iter()
                .map(|v| (*v * r / 1.3).map(d))
                .collect()
        };
        for s in 6..=9 {
            let step = |e: i32| 0.5 * 10f64.powi(e - s as i32 + 1);
            let (small, large) = (
                written_rounding(&digits(1.3, s)),
                written_rounding(&digits(130.0, s)),
            );
            assert!((small / step(0) - 1.0).abs() < 1e-12, "{s}: {small:e}");
            assert!((large / step(2) - 1.0).abs() < 1e-12, "{s}: {large:e}");
        }
        assert_eq!(
            written_rounding(&digits(1.3, 5)),
            0.0,
            "too few digits to tell"
        );
        assert_eq!(
            written_rounding(&digits(1.3, 12)),
            0.0,
            "more digits than exporters write: made in f64"
        );
        // a box at ±0.5 m: nothing was rounded off
        let cube: Vec<DVec3> = (0..8)
            .map(|i| DVec3::new((i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2) as f64) - 0.5)
            .collect();
        assert_eq!(written_rounding(&cube), 0.0);
        // one written corner is enough to show the decimals
        let mut mixed = cube.clone();
        mixed.push(DVec3::new(0.123457, 0.5, 0.5));
        assert_eq!(written_rounding(&mixed), 0.5e-6);
        // where f64 holds too few decimals to tell
        let far: Vec<DVec3> = written(6).iter().map(|v| *v + 1e3).collect();
        assert_eq!(written_rounding(&far), 0.0);
        // stored in single precision: one step of an f32 at the largest coordinate
        // (the largest coordinate between 1 and 2 m, then between 128 and 256 m), printed
        // in full or shortest
        let single = |r: f64, print: fn(f32) -> f64| -> Vec<DVec3> {
            ball.vertices
                .iter()
                .map(|v| (*v * r / 1.3).map(|x| print(x as f32)))
                .collect()
        };
        let [(_, in_full), (_, shortest), _] = F32_PRINTS;
        for (r, e) in [(1.3, 0), (200.0, 7)] {
            for (how, print) in F32_PRINTS {
                let r_read = written_rounding(&single(r, print));
                assert_eq!(r_read, 2f64.powi(e - 23), "{r} {how}");
            }
        }
        // -1.39453125 lies halfway between two 8-digit decimals: Rust writes the one
        // above, Python's `%.8g` the one below (every coordinate of so few is looked at)
        let mut tie = single(1.3, shortest);
        tie.push(DVec3::new(-1.3945312, 0.5, 0.5));
        assert!(3 * tie.len() <= SHORT_SAMPLE);
        assert_eq!(written_rounding(&tie), 2f64.powi(-23));
        // 6 decimals of coordinates up to 9.5 m are as short as their f32s printed
        // shortest (an f32's step there is 9.5e-7 m): the decimals are what was written
        let big: Vec<DVec3> = ball.vertices.iter().map(|v| *v * 9.5 / 1.3).collect();
        let big6: Vec<DVec3> = big
            .iter()
            .map(|v| v.map(|x| (x * 1e6).round() / 1e6))
            .collect();
        assert_eq!(written_rounding(&big6), 0.5e-6);
        // (the cube above is an f32 box too, and was not rounded) one coordinate of a
        // ball made in f64 among f32s says that they are not all f32s
        let mut one_f64 = single(1.3, in_full);
        one_f64.push(ball.vertices[5]);
        assert_eq!(written_rounding(&one_f64), 0.0);
        // the tolerance: 8× the rounding where that is more than 1e-9 of the size
        let mut m = Mesh {
            vertices: written(6),
            ..Mesh::default()
        };
        assert_eq!(m.tolerance(), 1e-9 * m.bounding_sphere().1);
        m.rounding = written_rounding(&m.vertices);
        assert_eq!(m.tolerance(), 4e-6);
    }
}
