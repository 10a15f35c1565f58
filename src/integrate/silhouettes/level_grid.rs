//! The triangles' boxes binned in grids of cells at levels of doubling size
//! ([`LevelGrid`]): what the search for contacts ([`super::contacts`]) pairs triangles
//! through.

use crate::geometry::csr::csr_of;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// The triangles' boxes binned in grids of cells at levels of doubling size, each
/// triangle at the finest level where its box spans a few cells ([`level_of`]), and only
/// occupied cells stored. One uniform grid fits no mesh with both a finely meshed dish and
/// long panels: cells as small as the dish's triangles would be millions along a panel,
/// cells fit for the panels would each hold hundreds of the dish's triangles.
pub(super) struct LevelGrid {
    lo: DVec3,
    /// Per level, cells a metre (1 / the side, exactly halved from one level to the
    /// next): a point's cell is a product, not a quotient.
    per_m: Vec<f64>,
    /// Per triangle: its level, and the cell of its box's low corner at that level.
    pub(super) level: Vec<u8>,
    pub(super) first: Vec<[u32; 3]>,
    pub(super) levels: Vec<Level>,
}

/// One level's occupied cells.
#[derive(Default)]
pub(super) struct Level {
    /// Cell key → its index (CSR: cell `i` holds `binned[start[i]..start[i + 1]]`,
    /// ascending triangle indices); `keys[i]`: cell `i`'s key.
    index: HashMap<u64, u32, BuildHasherDefault<CellHash>>,
    pub(super) keys: Vec<u64>,
    pub(super) start: Vec<u32>,
    pub(super) binned: Vec<u32>,
    /// Per cell of a level above the finest, the box bounding its triangles' boxes (m);
    /// empty at level 0, which no finer triangle asks. A coarse cell of a boom's or a
    /// strut's long triangles holds tens of them, and the fine triangles around it ask
    /// the cell for its triangles one by one; most are asked in vain.
    bound: Vec<(DVec3, DVec3)>,
    /// Above level 0, the box bounding all its cells' (m): most of a fine mesh lies
    /// far from the few coarse triangles (a boom, a panel's edge) and need not ask
    /// their cells one by one.
    whole: Option<(DVec3, DVec3)>,
    /// Per cell, after [`LevelGrid::mark_faces`]: the one face all its triangles lie in,
    /// or [`MIXED`]; empty before.
    pub(super) face: Vec<u32>,
    /// Per cell, after [`LevelGrid::mark_sheets`]: the one sheet all its triangles lie
    /// in, or [`MIXED`]; empty before.
    pub(super) sheet: Vec<u32>,
}

/// The level of grid (level 0's cells `per_m` a metre) at which box `b` spans about
/// [`CELLS`] cells or fewer: the finest at which (1 + its extent / the side) multiplied
/// over the axes is at most that. By volume, not by its longest side: a long thin
/// triangle (a boom's, a strut's) then sits at a level whose cells are about as thick as
/// it is long over a few cells, not in cells as wide as it is long, which would each hold
/// every finer triangle around it.
fn level_of(b: &(DVec3, DVec3), per_m: f64) -> u8 {
    // in cells of the level (halved exactly at each step up): no quotient a level
    let mut cells = (b.1 - b.0) * per_m;
    let mut k = 0;
    while k < 63 && (cells + 1.0).element_product() > CELLS {
        cells *= 0.5;
        k += 1;
    }
    k
}

/// Cells a triangle's box spans at its level, about. Against 8 (a box as wide as a cell
/// binned in 2 × 2 × 2) the search for meeting pairs took 10–40 % fewer instructions on
/// the suite at ~200k triangles (a dish's fine triangles no longer asked a cell as wide
/// as an array panel), and 27 gained no more.
const CELLS: f64 = 16.0;

/// Cells remembered while binning ([`LevelGrid::bin`]).
const RECENT: usize = 64;

/// A cell key's slot among the [`RECENT`] (its bits mixed, the top six kept: the low bits
/// are x's alone, the same for every cell of a face across x).
#[inline]
fn recent_slot(key: u64) -> usize {
    (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 58) as usize
}

/// The hash of a cell key that keeps neighbours near: its low bits (where the map picks
/// a slot) are x + P y + Q z, so the cells of one row along x, which neighbouring
/// triangles find one after another, fall in neighbouring slots (a map of ~100k cells
/// does not fit in cache, and a mixing hash made each new cell a cache miss: the
/// cubesat's 200k triangles now bin 4 ms faster of 24, one thread); its top seven bits
/// (the map's tag within a group) are mixed.
#[derive(Default)]
struct CellHash(u64);

impl Hasher for CellHash {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, _: &[u8]) {
        unreachable!("cell keys are hashed as u64")
    }

    #[inline]
    fn write_u64(&mut self, key: u64) {
        let [x, y, z] = LevelGrid::coords(key).map(u64::from);
        let near = x
            .wrapping_add(y.wrapping_mul(0x9E37_79B9))
            .wrapping_add(z.wrapping_mul(0x85EB_CA77_C2B2_AE63));
        let tag = key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 57 << 57;
        self.0 = near & ((1 << 57) - 1) | tag;
    }
}

/// Do boxes `a` and `b` (m) overlap (touching counts)?
#[inline]
pub(super) fn overlap(a: (DVec3, DVec3), b: (DVec3, DVec3)) -> bool {
    !(a.0.cmpgt(b.1).any() || b.0.cmpgt(a.1).any())
}

/// A cell whose triangles lie in more than one face.
pub(super) const MIXED: u32 = u32::MAX;

/// Bits of a cell coordinate in a key (cells along an axis at level 0 are capped below
/// 2^BITS).
const BITS: u32 = 21;

impl LevelGrid {
    pub(super) fn build(boxes: &[(DVec3, DVec3)], tol: f64) -> LevelGrid {
        let (lo, hi) = boxes
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), b| {
                (lo.min(b.0), hi.max(b.1))
            });
        let size = |b: &(DVec3, DVec3)| (b.1 - b.0).max_element();
        // level 0: cells of about the median triangle's box
        let mut sizes: Vec<f64> = boxes.iter().map(size).collect();
        let mid = sizes.len() / 2;
        let median = match sizes.is_empty() {
            true => tol,
            false => *sizes.select_nth_unstable_by(mid, f64::total_cmp).1,
        };
        let extent = (hi - lo).max_element().max(tol);
        let cell = median.max(extent / (1u64 << (BITS - 1)) as f64).max(tol);
        let per_m: Vec<f64> = (0..64).map(|k| 1.0 / cell * 0.5f64.powi(k)).collect();
        let mut grid = LevelGrid {
            lo,
            per_m,
            level: Vec::new(),
            first: Vec::new(),
            levels: Vec::new(),
        };
        (grid.level, grid.first) = boxes
            .par_iter()
            .map(|b| {
                let k = level_of(b, grid.per_m[0]);
                (k, grid.cell_at(b.0, k))
            })
            .unzip();
        let top = grid.level.iter().copied().max().unwrap_or(0) as usize;
        grid.levels = (0..=top).map(|k| grid.bin(boxes, k as u8)).collect();
        grid
    }

    /// Level `k`'s cells, with the triangles at that level binned (a counting sort).
    fn bin(&self, boxes: &[(DVec3, DVec3)], k: u8) -> Level {
        // about as many cells as triangles, a few cells each: room made once, not by
        // doubling (the map's rehashing was a tenth of the binning)
        let n = self.level.iter().filter(|&&l| l == k).count();
        let mut level = Level::default();
        level.index.reserve(n);
        level.keys.reserve(n);
        let mut entries: Vec<(u32, u32)> = Vec::with_capacity(4 * n);
        // Neighbouring triangles (mostly neighbours in the mesh's order too) touch
        // mostly the same cells: the last cells found, by their keys' hash, before
        // the map.
        let mut recent = [(u64::MAX, 0u32); RECENT];
        for (t, b) in boxes.iter().enumerate() {
            if self.level[t] != k {
                continue;
            }
            self.cells_of(*b, k, |key| {
                let slot = &mut recent[recent_slot(key)];
                let i = if slot.0 == key {
                    slot.1
                } else {
                    let next = level.index.len() as u32;
                    let i = *level.index.entry(key).or_insert(next);
                    if i == next {
                        level.keys.push(key);
                    }
                    *slot = (key, i);
                    i
                };
                entries.push((i, t as u32));
            });
        }
        (level.start, level.binned) = csr_of(level.keys.len(), entries.iter().copied());
        if k > 0 {
            level.bound = level
                .start
                .windows(2)
                .map(|w| {
                    let items = &level.binned[w[0] as usize..w[1] as usize];
                    let empty = (DVec3::INFINITY, DVec3::NEG_INFINITY);
                    items.iter().fold(empty, |(lo, hi), &t| {
                        let b = boxes[t as usize];
                        (lo.min(b.0), hi.max(b.1))
                    })
                })
                .collect();
            level.whole = level
                .bound
                .iter()
                .copied()
                .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)));
        }
        level
    }

    /// The integer coordinates at level `k` of the cell holding point `p` (clamped to
    /// the grid).
    #[inline]
    pub(super) fn cell_at(&self, p: DVec3, k: u8) -> [u32; 3] {
        let max = ((1u64 << BITS) - 1) as f64;
        // clamped first, the cast truncates towards zero: the floor, without a call to it
        ((p - self.lo) * self.per_m[k as usize])
            .clamp(DVec3::ZERO, DVec3::splat(max))
            .as_uvec3()
            .to_array()
    }

    /// A cell's key from its integer coordinates, and back.
    #[inline]
    fn key(c: [u32; 3]) -> u64 {
        c[0] as u64 | (c[1] as u64) << BITS | (c[2] as u64) << (2 * BITS)
    }

    #[inline]
    pub(super) fn coords(key: u64) -> [u32; 3] {
        let mask = (1u64 << BITS) - 1;
        [
            (key & mask) as u32,
            (key >> BITS & mask) as u32,
            (key >> (2 * BITS)) as u32,
        ]
    }

    /// Calls `each` with the key of every cell at level `k` that box `b` touches.
    #[inline]
    fn cells_of(&self, b: (DVec3, DVec3), k: u8, mut each: impl FnMut(u64)) {
        let (a, z) = (self.cell_at(b.0, k), self.cell_at(b.1, k));
        for w in a[2]..=z[2] {
            for y in a[1]..=z[1] {
                for x in a[0]..=z[0] {
                    each(LevelGrid::key([x, y, w]));
                }
            }
        }
    }

    /// Calls `each` with the key and the triangles of every occupied cell at level `k`
    /// that box `b` touches, passing over the cells whose
    /// triangles all lie in face `except` (after [`LevelGrid::mark_faces`]) and, above
    /// level 0, those whose triangles' boxes all miss b.
    #[inline]
    pub(super) fn cells_near(
        &self,
        b: (DVec3, DVec3),
        k: u8,
        except: Option<u32>,
        mut each: impl FnMut(u64, &[u32]),
    ) {
        let level = &self.levels[k as usize];
        if level.binned.is_empty() || level.whole.is_some_and(|w| !overlap(w, b)) {
            return;
        }
        self.cells_of(b, k, |key| {
            if let Some(&i) = level.index.get(&key) {
                if except.is_some() && level.face.get(i as usize) == except.as_ref() {
                    return;
                }
                if level.bound.get(i as usize).is_some_and(|&c| !overlap(c, b)) {
                    return;
                }
                let (s, e) = (level.start[i as usize], level.start[i as usize + 1]);
                each(key, &level.binned[s as usize..e as usize]);
            }
        });
    }

    /// How many occupied cells at level `k` box `b` touches, read or not.
    #[cfg(test)]
    fn cells_near_all(&self, b: (DVec3, DVec3), k: u8) -> usize {
        let mut n = 0;
        let index = &self.levels[k as usize].index;
        self.cells_of(b, k, |key| n += usize::from(index.contains_key(&key)));
        n
    }

    /// Notes per cell the one face (`tri_face`: per triangle) all its triangles lie in:
    /// a cell inside a large flat face, which the search for meetings with other faces
    /// can pass over ([`LevelGrid::cells_near`]).
    pub(super) fn mark_faces(&mut self, tri_face: &[u32]) {
        for level in &mut self.levels {
            level.face = level.one_of(tri_face);
        }
    }

    /// Per triangle: does it lie in a cell whose triangles lie in several faces (after
    /// [`LevelGrid::mark_faces`])?
    pub(super) fn in_mixed_cells(&self) -> Vec<bool> {
        let mut mixed = vec![false; self.level.len()];
        for level in &self.levels {
            for (i, w) in level.start.windows(2).enumerate() {
                if level.face[i] == MIXED {
                    for &t in &level.binned[w[0] as usize..w[1] as usize] {
                        mixed[t as usize] = true;
                    }
                }
            }
        }
        mixed
    }

    /// Notes per cell the one sheet (`sheet`: per triangle, [`MIXED`] for none) all its
    /// triangles lie in: no two of them meet as separate pieces.
    pub(super) fn mark_sheets(&mut self, sheet: &[u32]) {
        for level in &mut self.levels {
            level.sheet = level.one_of(sheet);
        }
    }

    /// Calls `each` with binned triangles near box `b`: at least every one whose box
    /// overlaps b, some more than once (those of the cells at its level that b touches).
    /// A level where `b` spans more cells than are occupied is read whole instead of
    /// cell by cell.
    pub(super) fn overlapping(&self, b: (DVec3, DVec3), mut each: impl FnMut(u32)) {
        for (k, level) in self.levels.iter().enumerate() {
            let span = ((b.1 - b.0) * self.per_m[k] + DVec3::splat(2.0)).element_product();
            if span > level.keys.len() as f64 {
                level.binned.iter().for_each(|&t| each(t));
            } else {
                self.cells_near(b, k as u8, None, |_, items| {
                    items.iter().for_each(|&t| each(t))
                });
            }
        }
    }
}

impl Level {
    /// Per cell, the one `label` (per triangle) all its triangles have, or [`MIXED`].
    fn one_of(&self, label: &[u32]) -> Vec<u32> {
        self.start
            .par_windows(2)
            .map(|w| {
                let items = &self.binned[w[0] as usize..w[1] as usize];
                let first = items.first().map_or(MIXED, |&t| label[t as usize]);
                if items.iter().all(|&t| label[t as usize] == first) {
                    first
                } else {
                    MIXED
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Boxes (m): a 20 × 20 sheet of small triangles' boxes in z = 0 and a bundle of 32
    /// long thin ones along x above it (a boom's triangles over a finely meshed plate).
    fn plate_and_boom() -> Vec<(DVec3, DVec3)> {
        let mut boxes = Vec::new();
        for i in 0..20 {
            for j in 0..20 {
                let lo = DVec3::new(i as f64, j as f64, 0.0) * 0.05;
                boxes.push((lo, lo + DVec3::new(0.01, 0.01, 0.0)));
            }
        }
        for i in 0..32 {
            let lo = DVec3::new(0.0, 0.5, 0.5) + DVec3::splat(i as f64 * 1e-4);
            boxes.push((lo, lo + DVec3::new(1.0, 0.02, 0.02)));
        }
        boxes
    }

    fn near(grid: &LevelGrid, b: (DVec3, DVec3), k: u8) -> Vec<u32> {
        let mut found = Vec::new();
        grid.cells_near(b, k, None, |_, items| found.extend_from_slice(items));
        found
    }

    #[test]
    fn a_cell_is_passed_over_only_where_all_its_triangles_miss_the_box() {
        let mut rnd = crate::test_rng(7);
        let mut boxes = plate_and_boom();
        // random boxes of all sizes, so that every level holds some
        for _ in 0..300 {
            let lo = DVec3::new(rnd(), rnd(), rnd());
            let size = 0.3 * rnd().powi(3);
            let shape = DVec3::new(rnd(), rnd(), rnd());
            boxes.push((lo, lo + shape * size));
        }
        let grid = LevelGrid::build(&boxes, 1e-9);
        let boom = grid.level[boxes.len() - 300 - 1];
        assert!(boom > 0, "the boom's triangles sit above level 0");
        // Every triangle whose box overlaps the one asked about is found (the truth: all
        // pairs of boxes compared), at every level.
        for _ in 0..500 {
            let lo = DVec3::new(rnd(), rnd(), rnd()) * 1.2 - DVec3::splat(0.1);
            let b = (lo, lo + DVec3::new(rnd(), rnd(), rnd()) * 0.1);
            for k in 0..grid.levels.len() as u8 {
                let found = near(&grid, b, k);
                for (t, bt) in boxes.iter().enumerate() {
                    if overlap(*bt, b) && grid.level[t] == k {
                        assert!(
                            found.contains(&(t as u32)),
                            "triangle {t} missed at level {k}"
                        );
                    }
                }
            }
        }
        // A small box beside the boom, in its cell but clear of it: the cell's triangles
        // are not read.
        let b = (DVec3::new(0.5, 0.56, 0.56), DVec3::new(0.51, 0.57, 0.57));
        let boom_cells = grid.cells_near_all(b, boom);
        assert!(boom_cells > 0, "the box lies in a cell of the boom's");
        let found = near(&grid, b, boom);
        assert!(
            found
                .iter()
                .all(|&t| (t as usize) < 400 || (t as usize) >= 432),
            "a boom triangle clear of the box was read: {found:?}"
        );
    }
}
