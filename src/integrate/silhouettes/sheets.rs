//! Sheets: connected pieces of the mesh proven to cross nowhere, so that the search for
//! contacts ([`super::contacts`]) need not pair two triangles of one sheet.
//!
//! Most pairs of triangles close enough to share a cell of the contact grid are
//! neighbours on one smooth surface (on a rocket body of 200k triangles, 1.4 M pairs were
//! tested and none met): the search is the largest part of the preparation of a finely
//! meshed object, and almost all of it proves what the surface's shape already says. A
//! sheet says it once, for many triangles together (the normal cones of self-collision
//! culling). Its triangles are joined across edges that exactly two of them share with
//! opposite windings, and every one of them faces within 60° of the sheet's axis a. Seen
//! along a, each triangle then keeps its winding, so the view along a is one-to-one near
//! every point of the sheet that is not on its rim, once the angles about each inner
//! vertex add up to one turn (a fan could wind twice). A disc mapped so, whose rim maps
//! to a simple closed curve, is mapped one-to-one as a whole; so the sheet crosses
//! itself nowhere, and two of its triangles meet only where they share corners. Each
//! condition is checked, with margins above the search's tolerance (each triangle's
//! least angle and height, the rim's clearance from itself); a sheet that fails any is
//! given up, its triangles searched as before.

use crate::geometry::faces::WeldedEdge;
use crate::geometry::polygon::segment_distance;
use crate::geometry::Mesh;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::f64::consts::TAU;

/// No sheet, or no triangle across an edge.
pub(super) const NONE: u32 = u32::MAX;

/// Least cosine between a triangle's normal and its sheet's axis (60°): well short of
/// edge-on, so that each triangle seen along the axis keeps a sure winding.
const MIN_COS: f64 = 0.5;
/// Most triangles in a sheet: larger sheets leave fewer pairs across their rims, but
/// close round a hole more often (at 4,096 every sheet of the box-wing's tested first
/// did, and none was a disc).
const MAX_TRIANGLES: usize = 1024;
/// Least angle (rad) of a triangle seen along its sheet's axis (0.06°): a count of the
/// turn about a vertex is then sure, and slivers (a fine dish's near its apex) are left
/// to the search. Long flat panels' triangles are thinner than 1°.
const MIN_ANGLE: f64 = 1e-3;
/// Least height of a triangle seen along its sheet's axis, in tolerances: the pair test
/// finds two triangles meeting where they come within 4 tolerances of each other.
const MIN_HEIGHT: f64 = 8.0;
/// Margin (rad) on the turn about a vertex.
const TURN_TOL: f64 = 1e-6;

/// Per triangle of `mesh` (`welded`: each vertex's welded id; `edges`: the welded edges
/// as (lower id, higher id, triangle), sorted, as [`Mesh::welded_edges`] gives them), the
/// sheet it lies in, or [`NONE`]; only triangles `wanted` are put in sheets. `tol` (m):
/// distances within it count as touching; the rim of a sheet keeps well clear of itself.
pub(super) fn sheets(
    mesh: &Mesh,
    (welded, edges): (&[u32], &[WeldedEdge]),
    wanted: &[bool],
    tol: f64,
) -> Vec<u32> {
    let n = mesh.triangles.len();
    let ids = |t: usize| mesh.triangles[t].map(|v| welded[v as usize]);
    let normal: Vec<DVec3> = (0..n)
        .into_par_iter()
        .map(|t| mesh.area_vector(t).normalize_or_zero())
        .collect();
    let across = neighbours(n, &ids, edges);
    // grown one after another, in triangle order: the same sheets on every run
    let mut sheet = vec![NONE; n];
    let mut count = 0u32;
    let mut queue = Vec::new();
    for seed in 0..n {
        if sheet[seed] != NONE || !wanted[seed] || normal[seed] == DVec3::ZERO {
            continue;
        }
        let axis = normal[seed];
        sheet[seed] = count;
        queue.clear();
        queue.push(seed as u32);
        let mut next = 0;
        while next < queue.len() && queue.len() < MAX_TRIANGLES {
            let t = queue[next] as usize;
            next += 1;
            for &u in &across[t] {
                let u = u as usize;
                if u as u32 != NONE
                    && sheet[u] == NONE
                    && wanted[u]
                    && normal[u].dot(axis) >= MIN_COS
                    && queue.len() < MAX_TRIANGLES
                {
                    sheet[u] = count;
                    queue.push(u as u32);
                }
            }
        }
        count += 1;
    }
    let (start, members) = crate::geometry::csr::csr_of(
        count as usize,
        (0..n as u32)
            .filter(|&t| sheet[t as usize] != NONE)
            .map(|t| (sheet[t as usize], t)),
    );
    let places = welded.iter().map(|&w| w as usize + 1).max().unwrap_or(0);
    let prove = |k: usize| {
        let tris = &members[start[k] as usize..start[k + 1] as usize];
        // the seed, the sheet's first triangle: its normal is the axis
        let axis = normal[tris[0] as usize];
        tris.len() > 1
            && FANS.with_borrow_mut(|fans| {
                if fans.stamp.len() < places {
                    fans.stamp.resize(places, 0);
                    fans.wedges.resize(places, 0);
                    fans.on_rim.resize(places, false);
                    fans.turn.resize(places, 0.0);
                }
                embedded(k as u32, tris, axis, mesh, &ids, &across, &sheet, tol, fans)
            })
    };
    let proven: Vec<bool> = (0..count as usize).into_par_iter().map(prove).collect();
    for s in sheet.iter_mut() {
        if *s != NONE && !proven[*s as usize] {
            *s = NONE;
        }
    }
    sheet
}

/// Per triangle, the triangle across each of its edges (corner k to k + 1) when exactly
/// two triangles share that edge and wind opposite ways along it, else [`NONE`].
fn neighbours(n: usize, ids: &impl Fn(usize) -> [u32; 3], edges: &[WeldedEdge]) -> Vec<[u32; 3]> {
    let mut across = vec![[NONE; 3]; n];
    // the side of triangle t along edge (lo, hi): its index, and whether t runs lo → hi
    let side = |t: usize, lo: u32, hi: u32| {
        let w = ids(t);
        (0..3).find_map(|k| {
            let (a, b) = (w[k], w[(k + 1) % 3]);
            (a.min(b) == lo && a.max(b) == hi).then_some((k, a == lo))
        })
    };
    for run in edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let &[(lo, hi, s), (_, _, t)] = run else {
            continue;
        };
        if lo == hi || s == t {
            continue;
        }
        let (s, t) = (s as usize, t as usize);
        if let (Some((ks, fs)), Some((kt, ft))) = (side(s, lo, hi), side(t, lo, hi)) {
            if fs != ft {
                across[s][ks] = t as u32;
                across[t][kt] = s as u32;
            }
        }
    }
    across
}

/// Per-thread scratch of [`embedded`], by welded vertex id: the sheet that last touched
/// the vertex (its stamp), and there the wedges about it that hold the direction +e1 and
/// its turn (rad; rim vertices only).
#[derive(Default)]
struct Fans {
    stamp: Vec<u64>,
    wedges: Vec<u32>,
    on_rim: Vec<bool>,
    turn: Vec<f64>,
}

thread_local! {
    /// Each worker's [`Fans`], kept from sheet to sheet and call to call: stamped, never
    /// cleared.
    static FANS: std::cell::RefCell<Fans> = std::cell::RefCell::default();
}

/// A stamp no sheet has used before (per process).
fn new_stamp() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

/// Is the sheet of triangles `tris` (number `here`, all facing within [`MIN_COS`] of unit
/// `axis`) a disc that the view along the axis maps one-to-one, with margins (module
/// docs)?
#[allow(clippy::too_many_arguments)]
fn embedded(
    here: u32,
    tris: &[u32],
    axis: DVec3,
    mesh: &Mesh,
    ids: &impl Fn(usize) -> [u32; 3],
    across: &[[u32; 3]],
    sheet: &[u32],
    tol: f64,
    fans: &mut Fans,
) -> bool {
    let (e1, e2) = super::polygons::basis(axis);
    let flat = |x: DVec3| DVec2::new(x.dot(e1), x.dot(e2));
    let (sin_min, cos_min) = MIN_ANGLE.sin_cos();
    let stamp = new_stamp();
    // the rim's edges, in the triangles' winding, and the triangles seen along the axis
    let mut rim: Vec<(u32, u32, DVec2, DVec2)> = Vec::new();
    let mut seen: Vec<([u32; 3], [DVec2; 3])> = Vec::with_capacity(tris.len());
    let mut vertices = 0i64;
    for &t in tris {
        let t = t as usize;
        let c = mesh.corners(t).map(flat);
        let w = ids(t);
        for k in 0..3 {
            let u = across[t][k];
            let v = w[k] as usize;
            if fans.stamp[v] != stamp {
                fans.stamp[v] = stamp;
                fans.wedges[v] = 0;
                fans.on_rim[v] = false;
                fans.turn[v] = 0.0;
                vertices += 1;
            }
            if u == NONE || sheet[u as usize] != here {
                rim.push((w[k], w[(k + 1) % 3], c[k], c[(k + 1) % 3]));
                fans.on_rim[v] = true;
            }
        }
        seen.push((w, c));
    }
    if rim.len() < 3 {
        return false;
    }
    // a disc: V − E + F = 1 (E = (3F + rim) / 2); one rim loop (below)
    let edges2 = 3 * tris.len() + rim.len();
    if edges2 % 2 != 0 || vertices - (edges2 / 2) as i64 + tris.len() as i64 != 1 {
        return false;
    }
    // each rim vertex starts one rim edge, and the loop through them is one
    rim.sort_unstable_by_key(|e| e.0);
    if rim.windows(2).any(|w| w[0].0 == w[1].0) {
        return false;
    }
    let next = |v: u32| rim.binary_search_by_key(&v, |e| e.0).ok();
    let (mut on_rim, mut at) = (0, 0);
    loop {
        on_rim += 1;
        match next(rim[at].1) {
            Some(0) => break,
            Some(i) if on_rim < rim.len() => at = i,
            _ => return false,
        }
    }
    if on_rim != rim.len() {
        return false;
    }
    // each corner keeps its winding and no angle is too thin; about an inner vertex the
    // wedges turn once (exactly one holds the direction +e1: no atan2), about a rim
    // vertex less than once
    let height = MIN_HEIGHT * tol;
    for (w, c) in &seen {
        // no height of the triangle under MIN_HEIGHT tolerances: two triangles that
        // share no corner then stay farther apart than the search's reach
        let twice_area = (c[1] - c[0]).perp_dot(c[2] - c[0]);
        let longest = (0..3)
            .map(|k| (c[(k + 1) % 3] - c[k]).length_squared())
            .fold(0.0, f64::max);
        // (a NaN fails the angles' test below)
        if twice_area * twice_area < height * height * longest {
            return false;
        }
        for k in 0..3 {
            let (p, q, r) = (c[k], c[(k + 1) % 3], c[(k + 2) % 3]);
            let (u, v) = (q - p, r - p);
            let (sin, cos) = (u.perp_dot(v), u.dot(v));
            // angle ≥ MIN_ANGLE (and < π, so the winding is kept): sin(angle − MIN) ≥ 0
            if !(sin * cos_min - cos * sin_min >= 0.0 && sin > 0.0) {
                return false;
            }
            let id = w[k] as usize;
            if fans.on_rim[id] {
                fans.turn[id] += sin.atan2(cos);
            } else if u.y <= 0.0 && v.y > 0.0 {
                fans.wedges[id] += 1;
            }
        }
    }
    for (w, _) in &seen {
        for &id in w {
            let id = id as usize;
            let ok = if fans.on_rim[id] {
                fans.turn[id] <= TAU - TURN_TOL
            } else {
                fans.wedges[id] == 1
            };
            if !ok {
                return false;
            }
        }
    }
    simple_rim(&rim, 64.0 * tol)
}

/// Does the closed loop of segments `rim` (in any order; consecutive ones share an end)
/// keep every two segments that share no end farther apart than `clear` (m)?
fn simple_rim(rim: &[(u32, u32, DVec2, DVec2)], clear: f64) -> bool {
    let mut order: Vec<usize> = (0..rim.len()).collect();
    let lo_x = |i: usize| rim[i].2.x.min(rim[i].3.x);
    let hi_x = |i: usize| rim[i].2.x.max(rim[i].3.x);
    order.sort_unstable_by(|&a, &b| lo_x(a).total_cmp(&lo_x(b)));
    for (k, &i) in order.iter().enumerate() {
        let reach = hi_x(i) + clear;
        for &j in &order[k + 1..] {
            if lo_x(j) > reach {
                break;
            }
            let (a, b) = (&rim[i], &rim[j]);
            if a.0 == b.0 || a.0 == b.1 || a.1 == b.0 || a.1 == b.1 {
                continue;
            }
            if segment_distance(a.2, a.3, b.2, b.3) <= clear {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The sheets of every triangle of `mesh`.
    pub fn sheets_of(mesh: &Mesh, tol: f64) -> Vec<u32> {
        let (welded, edges) = mesh.welded_edges();
        let all = vec![true; mesh.triangles.len()];
        sheets(mesh, (&welded, &edges), &all, tol)
    }

    fn mesh(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Mesh {
        Mesh {
            material_ids: vec![0; triangles.len()],
            vertices,
            triangles,
            ..Mesh::default()
        }
    }

    /// A 12 m square of 12 × 12 quads in the plane z = 0, facing +z (cell i + 12 j holds
    /// triangles 2(i + 12 j) and the next).
    fn square() -> Mesh {
        crate::geometry::builtin::plate(12.0, 12.0, 12)
    }

    /// Twelve triangles about the origin whose far corners wind twice round it, the
    /// second turn's heights the first's negated: the two turns cross each other, though
    /// every triangle faces within 45° of +z.
    pub fn fan_wound_twice() -> Mesh {
        let mut vertices = vec![DVec3::ZERO];
        for i in 0..12 {
            let a = i as f64 * TAU / 6.0;
            let h = 0.25 * (std::f64::consts::PI * i as f64 / 6.0 + 0.5).sin();
            vertices.push(DVec3::new(a.cos(), a.sin(), h));
        }
        let triangles = (0..12).map(|i| [0, 1 + i, 1 + (i + 1) % 12]).collect();
        mesh(vertices, triangles)
    }

    /// A flat-lying strip (radii 1 to 2 m) wound one and a half turns, rising and falling
    /// so that the third half-turn passes through the first.
    pub fn strip_through_itself() -> Mesh {
        let steps = 90;
        let mut vertices = Vec::new();
        for k in 0..=steps {
            let a = 3.0 * std::f64::consts::PI * k as f64 / steps as f64;
            let z = 0.3 * (a / 2.0 - 1.0).sin();
            vertices.push(DVec3::new(a.cos(), a.sin(), z));
            vertices.push(DVec3::new(2.0 * a.cos(), 2.0 * a.sin(), z));
        }
        let triangles = (0..steps as u32)
            .flat_map(|k| {
                let (i0, o0, i1, o1) = (2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3);
                [[i0, o0, o1], [i0, o1, i1]]
            })
            .collect();
        mesh(vertices, triangles)
    }

    #[test]
    fn a_flat_square_is_one_sheet_and_a_ball_is_all_in_sheets() {
        let flat = sheets_of(&square(), 1e-9);
        assert!(
            flat[0] != NONE && flat.iter().all(|&s| s == flat[0]),
            "{flat:?}"
        );
        let mut ball = Mesh::default();
        super::super::fixtures::push_ball(&mut ball, 12, 0.3, DVec3::ZERO);
        let sheet = sheets_of(&ball, 1e-9);
        assert!(sheet.iter().all(|&s| s != NONE));
        // a closed ball is never one disc: several sheets, each facing one way
        let mut ids = sheet.clone();
        ids.sort_unstable();
        ids.dedup();
        assert!(ids.len() >= 3, "{} sheets", ids.len());
    }

    #[test]
    fn surfaces_that_cross_themselves_are_not_proven_sheets() {
        // the fan's two turns each face within 45° of +z, so they grow into one sheet,
        // whose vertex turns twice; the strip's rim overlaps itself seen from above
        for (name, m) in [
            ("fan", fan_wound_twice()),
            ("strip", strip_through_itself()),
        ] {
            let sheet = sheets_of(&m, 1e-9);
            assert!(sheet.iter().all(|&s| s == NONE), "{name}: {sheet:?}");
        }
        // half of the strip, a single half-turn, is a disc seen one-to-one from above
        let mut half = strip_through_itself();
        half.triangles.truncate(60);
        half.material_ids.truncate(60);
        let sheet = sheets_of(&half, 1e-9);
        assert!(sheet[0] != NONE && sheet.iter().all(|&s| s == sheet[0]));
    }

    #[test]
    fn a_plate_with_a_hole_is_not_a_disc() {
        // the 12 × 12 square without its four middle quads
        let mut m = square();
        let keep: Vec<usize> = (0..m.triangles.len())
            .filter(|&t| {
                let (i, j) = ((t / 2) / 12, (t / 2) % 12);
                !((5..7).contains(&i) && (5..7).contains(&j))
            })
            .collect();
        m.triangles = keep.iter().map(|&t| m.triangles[t]).collect();
        m.material_ids.truncate(m.triangles.len());
        let sheet = sheets_of(&m, 1e-9);
        assert!(sheet.iter().all(|&s| s == NONE));
    }
}
