//! The search for the pairs of triangles that meet as separate pieces ([`PairSearch`]):
//! the triangles' boxes binned in grids of cells at levels of doubling size
//! ([`TriangleGrid`]), each pair of overlapping boxes tested once, in the cell that owns
//! it, and only where a cell holds triangles of more than one face and sheet.

use super::join::join_pieces;
use super::meet::{meeting, meeting_of, Tri};
use super::Contact;
use crate::geometry::faces::WeldedEdge;
use crate::geometry::Mesh;
use crate::integrate::silhouettes::level_grid::{overlap, LevelGrid, MIXED};
use crate::integrate::silhouettes::sheets::{sheets, NONE};
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

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
pub(in crate::integrate::silhouettes) struct PairSearch<'a> {
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
pub(in crate::integrate::silhouettes) struct MeetingPairs(Vec<Pair>);

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

/// A triangle's box widened by `tol` (m).
#[inline]
pub(super) fn box_of(c: &[DVec3; 3], tol: f64) -> (DVec3, DVec3) {
    let lo = c[0].min(c[1]).min(c[2]) - DVec3::splat(tol);
    let hi = c[0].max(c[1]).max(c[2]) + DVec3::splat(tol);
    (lo, hi)
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
        crate::integrate::silhouettes::fixtures::push_ball(
            &mut mesh,
            12,
            0.3,
            DVec3::new(0.4, 0.1, 0.2),
        );
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
    fn pairs_within_a_surface_that_crosses_itself_are_all_found() {
        // the sheets the search leaves out must not hold a pair that meets: each such
        // surface faces one way and is one piece, yet crosses itself
        use crate::integrate::silhouettes::sheets::tests::{
            fan_wound_twice, sheets_of, strip_through_itself,
        };
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
}
