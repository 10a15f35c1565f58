//! Where separate pieces of the mesh touch or cross (the *contacts*: a boom's foot on a
//! bus), found once per request: the segments where triangles of different faces meet as
//! separate pieces ([`contact_segments`]), and how the count of sheets above a face
//! changes across one along a direction ([`Contact::jump`]).

use super::level_grid::{LevelGrid, MIXED};
use super::sheets::{sheets, NONE};
use crate::geometry::faces::WeldedEdge;
use crate::geometry::Mesh;
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Where another piece meets a face: a segment in the face's plane (m), and the face of
/// the other piece that meets it along the segment with three points of that face (m):
/// its corners highest above and lowest below the receiving face's plane, or the corners
/// of its one triangle that meets it there. Above the face, the other face is a sheet on
/// one side of the segment: the count changes across it as across a fold
/// ([`Contact::jump`]).
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
    /// sheet counts along d. Zero when the other points lie below the plane along d.
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
        // the other points above the plane, along d
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

/// Where triangles `s` and `t` of `mesh` meet as separate pieces ([`meet`], within
/// `tol`, m): two that share no vertex wherever they meet; two that share one vertex
/// only where they meet beyond it (neighbours around a corner touch there and nowhere
/// else, but a plate whose edge is welded to the centre of a cap it stands on meets
/// the cap along a line from that corner); two that share an edge never (neighbours
/// along it: the topology's).
fn meeting(mesh: &Mesh, welded: &[u32], s: usize, t: usize, tol: f64) -> Option<(DVec3, DVec3)> {
    meeting_of(&Tri::of(mesh, welded, s), &Tri::of(mesh, welded, t), tol)
}

/// A triangle as [`meeting_of`] reads it: its corners (m) and their welded ids.
#[derive(Clone, Copy)]
struct Tri {
    c: [DVec3; 3],
    w: [u32; 3],
}

impl Tri {
    #[inline]
    fn of(mesh: &Mesh, welded: &[u32], t: usize) -> Tri {
        Tri {
            c: mesh.corners(t),
            w: mesh.triangles[t].map(|v| welded[v as usize]),
        }
    }
}

/// [`meeting`] of two triangles read already.
#[inline]
fn meeting_of(s: &Tri, t: &Tri, tol: f64) -> Option<(DVec3, DVec3)> {
    let mut shared = (0..3).filter(|&i| t.w.contains(&s.w[i]));
    let (first, second) = (shared.next(), shared.next());
    if second.is_some() {
        return None;
    }
    let (cs, ct) = (&s.c, &t.c);
    match first {
        None => meet(cs, ct, tol),
        Some(i) => {
            let at = cs[i];
            // one's other two corners on one side of the other's plane: they touch at the
            // corner only (most pairs around a corner of a smooth surface)
            let apart = |x: &[DVec3; 3], y: &[DVec3; 3]| {
                // heights times |n|, against tol times |n| (no square root)
                let n = (y[1] - y[0]).cross(y[2] - y[0]);
                let reach = tol * tol * n.length_squared();
                let mut sides = x.iter().filter(|&&v| v != at).map(|&v| n.dot(v - at));
                let (h0, h1) = (sides.next().unwrap_or(0.0), sides.next().unwrap_or(0.0));
                h0 * h1 > 0.0 && h0 * h0 > reach && h1 * h1 > reach
            };
            if apart(cs, ct) || apart(ct, cs) {
                return None;
            }
            let (p, q) = meet(cs, ct, tol)?;
            // beyond the corner by more than rounding: a thousandth of the pair's size,
            // and twice as far as two planes at θ through one corner stay within tol of
            // each other (tol / sin θ: the fans of a rounded mesh's nearly flat corners)
            let size = cs
                .iter()
                .chain(ct)
                .map(|&x| (x - at).length())
                .fold(0.0f64, f64::max);
            let far = (p - at).length().max((q - at).length());
            let sin = sin_between(cs, ct);
            let near = if sin > 0.0 { 2.0 * tol / sin } else { 0.0 };
            (far > 1e-3 * size && far > near).then_some((p, q))
        }
    }
}

/// Segments (m) where triangles of different faces meet as separate pieces
/// ([`meeting`]): each is recorded on both faces. Found through grids of the triangles'
/// boxes ([`LevelGrid`]).
/// With `group` (per triangle), only triangles of one group are paired: the contacts that
/// a rigid motion of each group carries along ([`Across`] finds the others).
/// `grid`: the mesh's [`TriangleGrid`] at `tol` when built already, else built here.
pub(super) fn contact_segments(
    mesh: &Mesh,
    (welded, edges): (&[u32], &[WeldedEdge]),
    tri_face: &[u32],
    group: Option<&[u32]>,
    tol: f64,
    grid: Option<TriangleGrid>,
) -> Vec<(u32, Contact)> {
    PairSearch::new(mesh, (welded, edges), tri_face, group, tol, grid)
        .finish()
        .on_faces(mesh, tri_face, tol)
}

/// Sheets are sought when at least one triangle in this many lies in a cell of several
/// faces (sheets cost about as much a triangle as the search does an item of such a cell).
const SHEETS_WORTH: usize = 8;

// a triangle in no sheet and a cell of several sheets are the same label to the grid
const _: () = assert!(NONE == MIXED);

/// A segment (m) where two triangles meet: (lower index, higher index, segment).
type Pair = (u32, u32, (DVec3, DVec3));

/// The search for the pairs of triangles that meet as separate pieces, taken a piece of
/// work at a time (a cell of the grid, then a triangle against the coarser levels) so
/// that one thread may start it while the other does something else, and both finish it
/// ([`PairSearch::run_until`], [`PairSearch::finish`]). It reads only which triangles
/// share a face, never how the faces are numbered: it may run while they are renumbered
/// ([`super::Silhouettes::build_ordered`]).
pub(super) struct PairSearch<'a> {
    mesh: &'a Mesh,
    welded: &'a [u32],
    edges: &'a [WeldedEdge],
    tri_face: &'a [u32],
    /// Per triangle, its sheet ([`super::sheets`]; two triangles of one never meet as
    /// separate pieces), or [`NONE`]; empty until the work starts, with `group`, or where
    /// sheets would not pay.
    sheet: Vec<u32>,
    sheets_found: bool,
    group: Option<&'a [u32]>,
    tol: f64,
    boxes: Vec<(DVec3, DVec3)>,
    grid: LevelGrid,
    /// Where each level's cells start in the order of the work, then where the
    /// triangles asked against coarser levels start (the cells' count), and the end.
    starts: Vec<usize>,
    /// The work done (the first pieces, in order) and the pairs it found.
    next: usize,
    pairs: Vec<Pair>,
}

impl<'a> PairSearch<'a> {
    /// The search over `mesh`'s triangles (welded ids `welded` and edges `edges`, as
    /// [`Mesh::welded_edges`] gives them; faces `tri_face` in any numbering; with `group`,
    /// pairs only within one group; `grid`: the mesh's [`TriangleGrid`] at `tol` when
    /// built already).
    pub fn new(
        mesh: &'a Mesh,
        (welded, edges): (&'a [u32], &'a [WeldedEdge]),
        tri_face: &'a [u32],
        group: Option<&'a [u32]>,
        tol: f64,
        grid: Option<TriangleGrid>,
    ) -> PairSearch<'a> {
        let TriangleGrid {
            boxes,
            mut grid,
            tol: binned_at,
        } = match grid {
            _ if mesh.triangles.len() < 2 => TriangleGrid {
                boxes: Vec::new(),
                grid: LevelGrid::build(&[], tol),
                tol,
            },
            Some(grid) => grid,
            None => TriangleGrid::build(mesh, tol),
        };
        debug_assert_eq!(binned_at, tol, "the grid was binned at another tolerance");
        grid.mark_faces(tri_face);
        let mut starts = vec![0];
        for level in &grid.levels {
            starts.push(starts.last().unwrap() + level.keys.len());
        }
        starts.push(starts.last().unwrap() + boxes.len());
        PairSearch {
            mesh,
            welded,
            edges,
            tri_face,
            sheet: Vec::new(),
            sheets_found: false,
            group,
            tol,
            boxes,
            grid,
            starts,
            next: 0,
            pairs: Vec::new(),
        }
    }

    /// Does the work in order on this thread until `stop` is set or none is left.
    pub fn run_until(&mut self, stop: &AtomicBool) {
        self.run_while(|| !stop.load(Ordering::Relaxed));
    }

    /// Finds the sheets and marks the cells that lie in one, once, before any pair is
    /// tested (without `group`: an articulated mesh's pieces move apart).
    fn find_sheets(&mut self) {
        if self.group.is_some() || self.sheets_found || self.mesh.triangles.len() < 2 {
            return;
        }
        self.sheets_found = true;
        // only triangles in a cell of several faces are ever paired in one: where few are
        // (large flat faces), the search is short and sheets would cost more than it
        let paired = self.grid.in_mixed_cells();
        if paired.iter().filter(|&&p| p).count() * SHEETS_WORTH < paired.len() {
            return;
        }
        self.sheet = sheets(self.mesh, (self.welded, self.edges), &paired, self.tol);
        self.grid.mark_sheets(&self.sheet);
    }

    /// Per triangle, its sheet, or [`NONE`].
    #[inline]
    fn sheet_of(&self, t: usize) -> u32 {
        self.sheet.get(t).copied().unwrap_or(NONE)
    }

    /// Does the work in order while `go()`, asked before each piece, says so.
    fn run_while(&mut self, mut go: impl FnMut() -> bool) {
        // needed before any pair, whoever does the work
        self.find_sheets();
        let end = *self.starts.last().unwrap();
        let (mut local, mut pairs) = (Vec::new(), Vec::new());
        let mut next = self.next;
        while next < end && go() {
            let l = self.starts.partition_point(|&s| s <= next) - 1;
            if l < self.grid.levels.len() {
                self.cell_pairs(l, next - self.starts[l], &mut local, &mut pairs);
            } else {
                self.triangle_pairs(next - self.starts[l], &mut pairs);
            }
            next += 1;
        }
        self.next = next;
        self.pairs.append(&mut pairs);
    }

    /// The rest of the work on every thread: every pair, sorted.
    pub fn finish(mut self) -> MeetingPairs {
        self.find_sheets();
        let mut pairs = std::mem::take(&mut self.pairs);
        let search = &self;
        let (starts, next) = (&self.starts, self.next);
        let levels = self.grid.levels.len();
        // what is left of each level's cells, then of the triangles
        let left =
            |l: usize| next.clamp(starts[l], starts[l + 1]) - starts[l]..starts[l + 1] - starts[l];
        let cells = (0..levels).into_par_iter().flat_map(|l| {
            left(l).into_par_iter().map_init(Vec::new, move |local, i| {
                let mut out = Vec::new();
                search.cell_pairs(l, i, local, &mut out);
                out
            })
        });
        let triangles = left(levels).into_par_iter().flat_map_iter(|s| {
            let mut out = Vec::new();
            search.triangle_pairs(s, &mut out);
            out
        });
        pairs.par_extend(cells.flatten_iter().chain(triangles));
        // in one order whatever found them: a face's pieces are joined from the first one on
        pairs.sort_unstable_by_key(|&(s, t, _)| (s, t));
        MeetingPairs(pairs)
    }

    /// The pairs of triangles (lower index first) of different faces, sharing no welded
    /// vertex, that meet, both binned at level `l`, that cell `i` of that level owns, with
    /// the segment where they do, appended to `out` (`local`: scratch for the cell's
    /// triangles).
    fn cell_pairs(&self, l: usize, i: usize, local: &mut Vec<Binned>, out: &mut Vec<Pair>) {
        let (grid, group) = (&self.grid, self.group);
        let level = &grid.levels[l];
        // a cell of one face's triangles holds no pair: pairs in one face are not contacts;
        // nor does a cell of one sheet's
        if level.face.get(i).is_some_and(|&f| f != MIXED)
            || level.sheet.get(i).is_some_and(|&s| s != MIXED)
        {
            return;
        }
        // each pair of the cell's triangles, read from a copy of them gathered once (a cell
        // of k holds k²/2 pairs, and reading each pair's boxes and faces from the mesh's
        // tables cost more than testing them)
        let items = &level.binned[level.start[i] as usize..level.start[i + 1] as usize];
        let cell = LevelGrid::coords(level.keys[i]);
        local.clear();
        local.extend(items.iter().map(|&t| {
            let first = grid.first[t as usize];
            let (lo, hi) = self.boxes[t as usize];
            Binned {
                t,
                face: self.tri_face[t as usize],
                sheet: self.sheet_of(t as usize),
                corner: starts_in(first, cell),
                lo,
                hi,
                tri: Tri::of(self.mesh, self.welded, t as usize),
            }
        }));
        for (j, a) in local.iter().enumerate() {
            for b in &local[j + 1..] {
                if !owns(a.corner, b.corner)
                    || a.face == b.face
                    || (a.sheet == b.sheet && a.sheet != NONE)
                    || !overlap((a.lo, a.hi), (b.lo, b.hi))
                    || group.is_some_and(|g| g[a.t as usize] != g[b.t as usize])
                {
                    continue;
                }
                // the lower index first, as `meeting` is asked
                let (lo, hi) = if a.t < b.t { (a, b) } else { (b, a) };
                out.extend(meeting_of(&lo.tri, &hi.tri, self.tol).map(|seg| (lo.t, hi.t, seg)));
            }
        }
    }

    /// The pairs, as [`PairSearch::cell_pairs`] finds them, of triangle `s` with the
    /// triangles binned at coarser levels than its own: `s` asks those levels' cells that
    /// its box touches (a few each).
    fn triangle_pairs(&self, s: usize, out: &mut Vec<Pair>) {
        let (grid, boxes, tri_face, group) = (&self.grid, &self.boxes, self.tri_face, self.group);
        let levels = grid.levels.len() as u8;
        if grid.level[s] + 1 >= levels {
            return;
        }
        let sheet_s = self.sheet_of(s);
        // a finer triangle s against a coarser one t (`first_s`: the cell of s's box's low
        // corner at t's level)
        let pair = |s: usize, t: usize, first_s: [u32; 3], cell: [u32; 3]| {
            let (bs, bt, first_t) = (boxes[s], boxes[t], grid.first[t]);
            if tri_face[s] == tri_face[t]
                || (sheet_s != NONE && self.sheet_of(t) == sheet_s)
                || group.is_some_and(|g| g[s] != g[t])
                || !overlap(bs, bt)
                || !owns(starts_in(first_s, cell), starts_in(first_t, cell))
            {
                return None;
            }
            let (lo, hi) = (s.min(t), s.max(t));
            meeting(self.mesh, self.welded, lo, hi, self.tol).map(|seg| (lo as u32, hi as u32, seg))
        };
        for k in grid.level[s] + 1..levels {
            let first_s = grid.cell_at(boxes[s].0, k);
            grid.cells_near(boxes[s], k, Some(tri_face[s]), |key, items| {
                let cell = LevelGrid::coords(key);
                for &t in items {
                    out.extend(pair(s, t as usize, first_s, cell));
                }
            });
        }
    }
}

/// The pairs of triangles that meet as separate pieces, with the segment (m) where each
/// pair does, before they are told which face they belong to.
pub(super) struct MeetingPairs(Vec<Pair>);

impl MeetingPairs {
    /// The contacts on the faces of `tri_face` (the numbering they keep; the same
    /// triangles share a face as when the pairs were found).
    pub fn on_faces(&self, mesh: &Mesh, tri_face: &[u32], tol: f64) -> Vec<(u32, Contact)> {
        join_pieces(&self.0, |t| mesh.corners(t), tri_face, tol)
    }
}

/// What the contact search needs of the mesh alone, before its faces are known: the
/// triangles' boxes (widened by `tol`, m) binned in a [`LevelGrid`]. Built apart so
/// that it can be built while the faces merge: at ~200k triangles it is 20–30 ms on one
/// thread.
pub struct TriangleGrid {
    boxes: Vec<(DVec3, DVec3)>,
    grid: LevelGrid,
    tol: f64,
}

impl TriangleGrid {
    pub fn build(mesh: &Mesh, tol: f64) -> TriangleGrid {
        let boxes: Vec<(DVec3, DVec3)> = (0..mesh.triangles.len())
            .into_par_iter()
            .map(|i| box_of(&mesh.corners(i), tol))
            .collect();
        let grid = LevelGrid::build(&boxes, tol);
        TriangleGrid { boxes, grid, tol }
    }
}

/// Do boxes `a` and `b` overlap (touching counts)?
#[inline]
fn overlap(a: (DVec3, DVec3), b: (DVec3, DVec3)) -> bool {
    !(a.0.cmpgt(b.1).any() || b.0.cmpgt(a.1).any())
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
    body: Option<LevelGrid>,
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
            LevelGrid::build(&boxes, tol)
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
                        built = LevelGrid::build(&boxes, tol);
                        &built
                    }
                };
                stamp.clear();
                stamp.resize(b.len(), u32::MAX);
                for &s in a {
                    let bs = box_of(&corners[s as usize], tol);
                    // what a box binned within `tol` of it can share a cell with
                    let ask = (bs.0 - DVec3::splat(tol), bs.1 + DVec3::splat(tol));
                    grid.overlapping(ask, |k| {
                        if std::mem::replace(&mut stamp[k as usize], s) == s {
                            return;
                        }
                        let t = b[k as usize];
                        if !overlap(bs, box_of(&corners[t as usize], tol)) {
                            return;
                        }
                        let (lo, hi) = (s.min(t), s.max(t));
                        let (cl, ch) = (&corners[lo as usize], &corners[hi as usize]);
                        if let Some(seg) = meet(cl, ch, tol) {
                            pairs.push((lo, hi, seg));
                        }
                    });
                }
            }
        }
        pairs.sort_unstable_by_key(|&(s, t, _)| (s, t));
        join_pieces(&pairs, |t| corners[t], tri_face, tol)
    }
}

/// A triangle of a cell as [`PairSearch::cell_pairs`] tests it against the cell's others: its
/// index, face, box (widened, m), on which axes its box starts in the cell's row (bit i:
/// axis i), and its corners.
#[derive(Clone, Copy)]
struct Binned {
    t: u32,
    face: u32,
    sheet: u32,
    corner: u8,
    lo: DVec3,
    hi: DVec3,
    tri: Tri,
}

/// On which axes a box whose low corner lies in cell `first` starts in the row of
/// `cell` (bit i: axis i; `cell` is one the box touches, so never before `first`).
#[inline]
fn starts_in(first: [u32; 3], cell: [u32; 3]) -> u8 {
    (0..3).fold(0, |m, i| m | u8::from(first[i] == cell[i]) << i)
}

/// Is a pair of overlapping boxes, starting in `cell`'s rows on the axes `a` and `b`
/// ([`starts_in`]), tested in that cell? Two overlapping boxes share the cell (at the
/// coarser one's level) that holds the low corner of their overlap, whose coordinates
/// are the larger of their own low corners': on each axis one of them starts in its
/// row. The pair is tested there only, so none is tested twice and no list of
/// candidates needs sorting.
#[inline]
fn owns(a: u8, b: u8) -> bool {
    a | b == 0b111
}

/// Where a triangle of one face meets another face's: the receiving face, the other face,
/// the other triangle and the receiving one, and the segment (m).
#[derive(Clone, Copy)]
struct Piece {
    face: u32,
    other_face: u32,
    other: u32,
    own: u32,
    seg: (DVec3, DVec3),
}

/// The pairs' segments as contacts, on both faces of each pair, with a face's pieces along
/// one other face joined where they overlap or touch.
fn join_pieces(
    pairs: &[(u32, u32, (DVec3, DVec3))],
    corner: impl Fn(usize) -> [DVec3; 3],
    tri_face: &[u32],
    tol: f64,
) -> Vec<(u32, Contact)> {
    // each contact seen from both sides
    let mut seen: Vec<Piece> = Vec::with_capacity(2 * pairs.len());
    for &(s, t, seg) in pairs {
        let (fs, ft) = (tri_face[s as usize], tri_face[t as usize]);
        seen.push(Piece {
            face: fs,
            other_face: ft,
            other: t,
            own: s,
            seg,
        });
        seen.push(Piece {
            face: ft,
            other_face: fs,
            other: s,
            own: t,
            seg,
        });
    }
    // Two faces are flat: they meet along one line, found once per pair of their
    // triangles that touch. Where that line runs along an edge inside a face, both
    // triangles beside the edge find the same piece (counting it twice would double its
    // jump); and where another piece pierces a finely meshed flat face, its line comes in
    // as many pieces as triangles it crosses on either side, each a segment that the
    // face's cells are cut along and that each ray's region is keyed by (a cluster of
    // boxes through one another took ~50 a face). So the pieces of one face along one
    // other face are joined where they overlap or touch.
    seen.sort_unstable_by_key(|c| (c.face, c.other_face, c.other, c.own));
    let mut out = Vec::with_capacity(seen.len());
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for group in seen.chunk_by(|x, y| (x.face, x.other_face) == (y.face, y.other_face)) {
        let face = group[0].face;
        // the line along the longest piece
        let longest = group
            .iter()
            .map(|c| c.seg)
            .max_by(|x, y| {
                (x.1 - x.0)
                    .length_squared()
                    .total_cmp(&(y.1 - y.0).length_squared())
            })
            .unwrap_or(group[0].seg);
        let (o, e) = (longest.0, (longest.1 - longest.0).normalize_or_zero());
        // The two planes are each known to within `tol` (the faces merged triangles
        // within it), so the line where they meet is known to within about tol / sin θ
        // across it (θ between the planes); pieces found from pairs of triangles wander
        // that much about it (up to 5.3 tol / sin θ on a cluster of boxes written with
        // nine decimals).
        let own = corner(group[0].own as usize);
        let n = (own[1] - own[0]).cross(own[2] - own[0]);
        let sin = sin_between(&own, &corner(group[0].other as usize));
        let reach = 8.0 * tol / sin;
        let off_line = |x: DVec3| (x - o - e * (x - o).dot(e)).length() > reach;
        if e == DVec3::ZERO
            || sin < 1e-3
            || group.iter().any(|c| off_line(c.seg.0) || off_line(c.seg.1))
        {
            // not one line after all (faces nearly parallel, or flat only to within
            // their merging angle): the pieces along each other triangle joined
            for along in group.chunk_by(|x, y| x.other == y.other) {
                let (a, b) = along[0].seg;
                let (o, e) = (a, (b - a).normalize_or_zero());
                let other = corner(along[0].other as usize);
                let other_face = along[0].other_face;
                let made = join_spans(along, o, e, tol, &mut spans);
                out.extend(
                    made.into_iter()
                        .map(|seg| (face, contact(seg, other, other_face))),
                );
            }
            continue;
        }
        // Of the other face, its corners highest above and lowest below the receiving
        // face's plane: the other face is flat, so its part on either side of that plane
        // lies on one side of the line, as any of its points there does
        // ([`Contact::jump`] needs one on each side that has one; on a side with none,
        // a point of the plane stands in, which counts on neither).
        let height = |v: DVec3| n.dot(v - own[0]);
        let (mut top, mut bottom) = (own[0], own[0]);
        for c in group {
            for v in corner(c.other as usize) {
                if height(v) > height(top) {
                    top = v;
                }
                if height(v) < height(bottom) {
                    bottom = v;
                }
            }
        }
        let other = [top, bottom, top];
        let other_face = group[0].other_face;
        let made = join_spans(group, o, e, tol, &mut spans);
        out.extend(
            made.into_iter()
                .map(|seg| (face, contact(seg, other, other_face))),
        );
    }
    out
}

/// The segments (m) of `pieces`, all on the line through `o` along unit `e`, joined where
/// they overlap or come within `tol` (m) of each other (`spans`: scratch); a lone piece
/// as it is.
fn join_spans(
    pieces: &[Piece],
    o: DVec3,
    e: DVec3,
    tol: f64,
    spans: &mut Vec<(f64, f64)>,
) -> Vec<(DVec3, DVec3)> {
    if let [piece] = pieces {
        return vec![piece.seg];
    }
    spans.clear();
    spans.extend(pieces.iter().map(|&Piece { seg: (a, b), .. }| {
        let (s, t) = ((a - o).dot(e), (b - o).dot(e));
        (s.min(t), s.max(t))
    }));
    spans.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    let mut joined: Vec<(f64, f64)> = Vec::with_capacity(spans.len());
    for &(lo, hi) in spans.iter() {
        match joined.last_mut() {
            Some(cur) if lo <= cur.1 + tol => cur.1 = cur.1.max(hi),
            _ => joined.push((lo, hi)),
        }
    }
    joined
        .into_iter()
        .map(|(lo, hi)| (o + e * lo, o + e * hi))
        .collect()
}

/// The sine of the angle between the planes of triangles `s` and `t` (corners, m); 0
/// for a degenerate one.
fn sin_between(s: &[DVec3; 3], t: &[DVec3; 3]) -> f64 {
    let (ns, nt) = (
        (s[1] - s[0]).cross(s[2] - s[0]),
        (t[1] - t[0]).cross(t[2] - t[0]),
    );
    let lengths = ns.length() * nt.length();
    if lengths > 0.0 {
        ns.cross(nt).length() / lengths
    } else {
        0.0
    }
}

/// A contact along segment `seg` with a sheet of face `face` (`other`: points of it).
fn contact(seg: (DVec3, DVec3), other: [DVec3; 3], face: u32) -> Contact {
    Contact {
        a: seg.0,
        b: seg.1,
        other,
        face,
    }
}

/// The segment where triangles `a` and `b` meet (touching within `tol` counts), when it
/// is longer than `tol`; coplanar triangles are left out (nothing in a face's plane
/// shades it).
pub fn meet(a: &[DVec3; 3], b: &[DVec3; 3], tol: f64) -> Option<(DVec3, DVec3)> {
    let na = (a[1] - a[0]).cross(a[2] - a[0]).normalize_or_zero();
    let nb = (b[1] - b[0]).cross(b[2] - b[0]).normalize_or_zero();
    // most pairs that get here are neighbours on one smooth surface, one wholly on one
    // side of the other's plane: that answer first, before the line they would share
    if beyond_plane(a, nb, b[0], tol) || beyond_plane(b, na, a[0], tol) {
        return None;
    }
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
    let (p, q) = (p0 + line * (lo - t0), p0 + line * (hi - t0));
    // Where the planes are nearly parallel, corners within tol of the other's plane are
    // taken as on the line though they may lie far from it, and the overlap along the
    // line says nothing of how far apart across it the two cuts are (two slivers of a
    // finely meshed dish near its apex, sharing a corner, "met" along 5 mm): keep only
    // the part of the segment within a few tol of both triangles.
    let reach = 4.0 * tol;
    let (u0, u1) = [(a, na), (b, nb)]
        .iter()
        .try_fold((0.0, 1.0), |(u0, u1), &(t, n)| {
            within(t, n, p, q, reach, u0, u1)
        })?;
    ((u1 - u0) * (q - p).length() > tol).then(|| (p + (q - p) * u0, p + (q - p) * u1))
}

/// The part `u0..u1` (parameters along p → q) of segment p–q that lies within `reach`
/// (m) of triangle `t`'s plane (unit normal `n`, as [`meet`] found it) and of its edges'
/// lines inside it (the triangle widened by `reach`), or None when none does.
fn within(
    t: &[DVec3; 3],
    n: DVec3,
    p: DVec3,
    q: DVec3,
    reach: f64,
    u0: f64,
    u1: f64,
) -> Option<(f64, f64)> {
    // each bound as g(x) = k·(x − o) + c ≥ 0, linear along the segment
    let mut range = (u0, u1);
    let mut keep = |k: DVec3, o: DVec3, c: f64| {
        let (gp, gq) = (k.dot(p - o) + c, k.dot(q - o) + c);
        if gp < 0.0 && gq < 0.0 {
            return false;
        }
        if gp < 0.0 {
            range.0 = f64::max(range.0, gp / (gp - gq));
        } else if gq < 0.0 {
            range.1 = f64::min(range.1, gp / (gp - gq));
        }
        range.0 <= range.1
    };
    let plane = keep(n, t[0], reach) && keep(-n, t[0], reach);
    let edges = (0..3).all(|i| {
        let e = t[(i + 1) % 3] - t[i];
        // inward across the edge, in the plane (the corners turn counter-clockwise about n)
        let inward = n.cross(e).normalize_or_zero();
        keep(inward, t[i], reach)
    });
    (plane && edges).then_some(range)
}

/// Do triangle `t`'s corners all lie farther than `tol` (m) on one side of the plane
/// (unit `n`, through `p`)?
#[inline]
fn beyond_plane(t: &[DVec3; 3], n: DVec3, p: DVec3, tol: f64) -> bool {
    let s = t.map(|v| n.dot(v - p));
    s.iter().all(|&x| x > tol) || s.iter().all(|&x| x < -tol)
}

/// The interval (along `line`) of triangle `t` where it meets the plane (`n`, through
/// `p`), with a point on it and that point's parameter; `t` is not wholly on one side
/// ([`beyond_plane`]).
fn cut_by_plane(
    t: &[DVec3; 3],
    n: DVec3,
    p: DVec3,
    tol: f64,
    line: DVec3,
) -> Option<(f64, f64, (DVec3, f64))> {
    let s = t.map(|v| n.dot(v - p));
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

    /// Every pair that meets, by testing all pairs (the truth the grids must find).
    fn all_pairs(mesh: &Mesh, welded: &[u32], tol: f64) -> Vec<(u32, u32, (DVec3, DVec3))> {
        let nt = mesh.triangles.len();
        let mut out = Vec::new();
        for s in 0..nt {
            for t in s + 1..nt {
                if let Some(seg) = meeting(mesh, welded, s, t, tol) {
                    out.push((s as u32, t as u32, seg));
                }
            }
        }
        out
    }

    #[test]
    fn the_level_grids_find_every_meeting_pair_of_a_mesh_of_mixed_scales() {
        // a 40 m plate (two triangles), a finely meshed ball sunk into it, and a long thin
        // rod through the ball: triangles from 40 m to ~3 cm, at several levels
        let mut mesh = Mesh {
            vertices: vec![
                DVec3::new(-20.0, -20.0, 0.0),
                DVec3::new(20.0, -20.0, 0.0),
                DVec3::new(20.0, 20.0, 0.0),
                DVec3::new(-20.0, 20.0, 0.0),
                DVec3::new(-3.0, 0.01, 0.2),
                DVec3::new(3.0, 0.01, 0.2),
                DVec3::new(0.0, 0.03, 0.21),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3], [4, 5, 6]],
            material_ids: vec![0; 3],
            rounding: 0.0,
        };
        super::super::fixtures::push_ball(&mut mesh, 12, 0.3, DVec3::new(0.4, 0.1, 0.2));
        let nt = mesh.triangles.len();
        let (welded, edges) = mesh.welded_edges();
        let tri_face: Vec<u32> = (0..nt as u32).collect();
        let tol = 1e-9;
        let corners: Vec<[DVec3; 3]> = (0..nt).map(|i| mesh.corners(i)).collect();
        let boxes: Vec<(DVec3, DVec3)> = corners
            .iter()
            .map(|c| {
                let lo = c[0].min(c[1]).min(c[2]) - DVec3::splat(tol);
                (lo, c[0].max(c[1]).max(c[2]) + DVec3::splat(tol))
            })
            .collect();
        let grid = LevelGrid::build(&boxes, tol);
        assert!(grid.levels.len() > 5, "{} levels", grid.levels.len());
        let triangles = |grid| TriangleGrid {
            boxes: boxes.clone(),
            grid,
            tol,
        };
        let search =
            |tri_face, grid| PairSearch::new(&mesh, (&welded, &edges), tri_face, None, tol, grid);
        let found = search(&tri_face, Some(triangles(grid))).finish().0;
        let truth = all_pairs(&mesh, &welded, tol);
        // the ball crosses the plate and the rod: dozens of pairs, each found once
        assert!(truth.len() > 40, "{} pairs", truth.len());
        let key =
            |v: &[(u32, u32, (DVec3, DVec3))]| v.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>();
        assert_eq!(key(&found), key(&truth));
        // with faces of several triangles (the plate one face, the ball's triangles in
        // fours) and the cells of one face passed over: the pairs across faces, still
        // each once
        let tri_face: Vec<u32> = (0..nt as u32)
            .map(|t| if t < 2 { 0 } else { 1 + t / 4 })
            .collect();
        let whole = search(&tri_face, None);
        assert!(
            whole
                .grid
                .levels
                .iter()
                .flat_map(|l| &l.face)
                .any(|&f| f != MIXED),
            "some cell holds one face's triangles only"
        );
        let across: Vec<_> = truth
            .iter()
            .filter(|p| tri_face[p.0 as usize] != tri_face[p.1 as usize])
            .copied()
            .collect();
        assert!(across.len() > 40, "{} pairs across faces", across.len());
        let end = *whole.starts.last().unwrap();
        assert_eq!(key(&whole.finish().0), key(&across));
        // begun on one thread and stopped after any number of pieces (none, a cell, half
        // the first level's cells, into the next level, into the triangles asked against
        // coarser levels, all), then finished on all: the same pairs
        let starts = search(&tri_face, None).starts;
        let (first, cells) = (starts[1], starts[starts.len() - 2]);
        for stop_after in [0, 1, first / 2, first + 3, cells + 3, end] {
            let mut part = search(&tri_face, None);
            let mut n = 0;
            part.run_while(|| {
                n += 1;
                n <= stop_after
            });
            assert_eq!(part.next, stop_after);
            assert_eq!(
                key(&part.finish().0),
                key(&across),
                "stopped after {stop_after}"
            );
        }
    }

    #[test]
    fn a_finely_meshed_wall_through_a_finely_meshed_plate_meets_it_along_one_segment() {
        // a 2 m plate and a 1.2 m × 1 m wall standing through it, 12 × 12 squares each
        // (the wall's line crosses a dozen of the plate's triangles and the plate's a
        // dozen of the wall's), turned off the axes and written to nine decimals, as an
        // OBJ file would hold them
        use crate::geometry::builtin::push_grid_quad;
        let mut mesh = Mesh::default();
        let (plate, wall) = (DVec3::new(-1.0, -1.0, 0.0), DVec3::new(-0.6, 0.1, -0.5));
        push_grid_quad(&mut mesh, plate, 2.0 * DVec3::X, 2.0 * DVec3::Y, 12, 12, 0);
        push_grid_quad(&mut mesh, wall, 1.2 * DVec3::X, DVec3::Z, 12, 12, 0);
        let turn = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
        let round = |x: f64| (x * 1e9).round() / 1e9;
        for v in &mut mesh.vertices {
            *v = (turn * *v).map(round);
        }
        let faces = crate::geometry::Faces::build(&mesh, true);
        assert_eq!(faces.len(), 2, "the plate and the wall, each one face");
        let tri_face = faces.triangle_faces(mesh.triangles.len());
        let (welded, edges) = mesh.welded_edges();
        let tol = 2e-9;
        let contacts = contact_segments(&mesh, (&welded, &edges), &tri_face, None, tol, None);
        // each face meets the other once, along the wall's whole width
        for f in 0..2 {
            let on: Vec<&Contact> = contacts.iter().filter(|c| c.0 == f).map(|c| &c.1).collect();
            assert_eq!(on.len(), 1, "face {f}: {on:?}");
            assert!(
                ((on[0].a - on[0].b).length() - 1.2).abs() < 1e-8,
                "{:?}",
                on[0]
            );
            assert_eq!(on[0].face, 1 - f);
        }
        // the joined contact's jump along any direction is each piece's (a piece: where
        // one triangle of the wall that reaches above the plate meets it, with that
        // triangle as the sheet)
        let plate = contacts.iter().find(|c| c.0 == 0).unwrap().1;
        let n = turn * DVec3::Z;
        let o = mesh.vertices[0];
        let (u, w) = (turn * DVec3::X, turn * DVec3::Y);
        let to2 = |x: DVec3| glam::DVec2::new((x - o).dot(u), (x - o).dot(w));
        let mesh = &mesh;
        let pieces: Vec<(DVec3, DVec3, [DVec3; 3])> = (0..mesh.triangles.len())
            .filter(|&t| tri_face[t] == 1)
            .flat_map(|t| {
                let wall = mesh.corners(t);
                (0..mesh.triangles.len())
                    .filter(|&s| tri_face[s] == 0)
                    .filter_map(move |s| {
                        meet(&mesh.corners(s), &wall, tol).map(|(a, b)| (a, b, wall))
                    })
            })
            .collect();
        assert!(pieces.len() > 12, "{} pieces", pieces.len());
        let mut checked = 0;
        for i in 0..40 {
            // directions over the sphere, those above the plate (the receiving side)
            let z = 1.0 - (2.0 * i as f64 + 1.0) / 40.0;
            let phi = i as f64 * 2.399_963_229_728_653 + 0.1;
            let r = (1.0 - z * z).sqrt();
            let d = turn * DVec3::new(r * phi.cos(), r * phi.sin(), z);
            if n.dot(d) < 0.05 {
                continue;
            }
            let joined = plate.jump(n, o, d, tol, true, to2);
            assert_ne!(
                joined, 0,
                "the wall's upper half lies on one side along {d}"
            );
            for &(a, b, other) in &pieces {
                let piece = Contact {
                    a,
                    b,
                    other,
                    face: 1,
                };
                let same_way = (b - a).dot(plate.b - plate.a).signum() as i32;
                let j = piece.jump(n, o, d, tol, true, to2);
                // (a wall triangle below the plate with an edge on it, its corners there
                // a rounding above or below, has no sheet above: not a piece to ask)
                let reaches_up = other.iter().any(|&v| n.dot(v - o) > 1e-3);
                if j != 0 && reaches_up {
                    assert_eq!(j * same_way, joined, "along {d}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 100, "{checked} pieces' jumps checked");
    }

    #[test]
    fn a_nearly_flat_fan_written_to_six_decimals_does_not_meet_itself() {
        // its triangles around the apex share it and lie within the tolerance (4e-6 m) of
        // one another out to ~0.5 mm from it: the corner's, not a contact
        let mut mesh = crate::geometry::faces::tests::apex();
        for v in &mut mesh.vertices {
            *v = v.map(|x| (x * 1e6).round() / 1e6);
        }
        mesh.rounding = crate::geometry::mesh::written_rounding(&mesh.vertices);
        let tri_face: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
        let (welded, edges) = mesh.welded_edges();
        let pairs = contact_segments(
            &mesh,
            (&welded, &edges),
            &tri_face,
            None,
            mesh.tolerance(),
            None,
        );
        assert!(pairs.is_empty(), "{} contacts", pairs.len());
    }

    #[test]
    fn pairs_within_a_surface_that_crosses_itself_are_all_found() {
        // the sheets the search leaves out must not hold a pair that meets: each such
        // surface faces one way and is one piece, yet crosses itself
        use super::super::sheets::tests::{fan_wound_twice, sheets_of, strip_through_itself};
        for (name, mesh) in [
            ("fan", fan_wound_twice()),
            ("strip", strip_through_itself()),
        ] {
            let (welded, edges) = mesh.welded_edges();
            let tol = 1e-9;
            let truth = all_pairs(&mesh, &welded, tol);
            assert!(!truth.is_empty(), "{name} crosses itself");
            let sheet = sheets_of(&mesh, tol);
            assert!(
                truth
                    .iter()
                    .all(|p| sheet[p.0 as usize] == NONE
                        || sheet[p.0 as usize] != sheet[p.1 as usize]),
                "{name}: a pair that meets within one sheet"
            );
            // each triangle its own face: every cell is searched
            let tri_face: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
            let found = PairSearch::new(&mesh, (&welded, &edges), &tri_face, None, tol, None)
                .finish()
                .0;
            let key = |v: &[Pair]| v.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>();
            assert_eq!(key(&found), key(&truth), "{name}");
        }
    }

    #[test]
    fn a_mesh_of_one_triangle_or_none_has_no_pairs_and_no_work() {
        for n in [0, 1] {
            let mesh = Mesh {
                vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
                triangles: vec![[0, 1, 2]; n],
                material_ids: vec![0; n],
                rounding: 0.0,
            };
            let (welded, edges) = mesh.welded_edges();
            let tri_face = vec![0; n];
            let mut search = PairSearch::new(&mesh, (&welded, &edges), &tri_face, None, 1e-9, None);
            search.run_while(|| true);
            assert_eq!(search.next, 0, "{n} triangles");
            assert!(search.finish().0.is_empty());
        }
    }

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

    #[test]
    fn two_slivers_of_a_fine_dish_near_its_apex_meet_only_at_their_shared_corner() {
        // the box-wing's dish at 200k triangles: 400 sectors, rings 5 mm apart, so the
        // triangles of the first rings are slivers 64 times longer than wide, their planes
        // within 1e-4 rad of each other. Two of neighbouring quads that share one corner
        // were found to meet along 5 mm (wrong: they touch at the corner only), which made
        // 400 of the dish's faces decided by rays.
        let (z0, f, sectors) = (1.2, 0.8, 400);
        let at = |r: f64, j: usize| {
            let phi = std::f64::consts::TAU * j as f64 / sectors as f64;
            DVec3::new(r * phi.cos(), r * phi.sin(), z0 + r * r / (4.0 * f))
        };
        let tol = 6.6e-9;
        for (r1, r2) in [(0.005, 0.01), (0.01, 0.015), (0.1, 0.105)] {
            for j in [0, 7, 100, 333] {
                let (a, b, c) = (at(r1, j), at(r2, j), at(r2, j + 1));
                let (d, e) = (at(r1, j + 1), at(r2, j + 2));
                let s = Tri {
                    c: [a, b, c],
                    w: [0, 1, 2],
                };
                let t = Tri {
                    c: [d, c, e],
                    w: [3, 2, 4],
                };
                assert!(meeting_of(&s, &t, tol).is_none(), "r {r1} sector {j}");
                // whatever meet finds lies within a few tol of both
                if let Some((p, q)) = meet(&s.c, &t.c, tol) {
                    assert!((q - p).length() < 1e-6, "r {r1} sector {j}: {p} {q}");
                }
            }
        }
        // a sliver standing across another along 3 mm still meets it there
        let flat = [at(0.005, 0), at(0.01, 0), at(0.01, 1)];
        let mid = (flat[0] + flat[1] + flat[2]) / 3.0;
        let up = [
            mid - DVec3::X * 0.0015 - DVec3::Z * 1e-3,
            mid + DVec3::X * 0.0015 - DVec3::Z * 1e-3,
            mid + DVec3::Z * 1e-3,
        ];
        let (p, q) = meet(&flat, &up, tol).expect("a sliver standing across meets");
        assert!((q - p).length() > 1e-5, "{p} {q}");
    }
}
