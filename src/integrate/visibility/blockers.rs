//! The blocker search: per face, side and direction, the faces that may shadow (or hide)
//! it — patch-level proofs first ([`Visibility::flag_patches`]), then face-level ones
//! ([`Visibility::blocker`]), from the epoch's grid of faces when there are many to test.
//! Faces of parts cast whole or wholly behind the face, and a cap's own faces (decided by
//! its lid), are left out.

use super::caps::LidState;
use super::face::{FaceSide, PartShadow};
use super::grid::{FaceGrid, Projection, Stamp, GRID_MIN_FACES};
use super::proofs::{outline_clear, reaches, reaches_front, LARGE_BLOCKER};
use super::{Cache, Visibility, NO_PART};
use crate::integrate::per_direction::{PerDirection, Toward};
use glam::{DVec2, DVec3};

impl Visibility {
    /// Patch- then face-level proofs; what survives are the possible blockers of `face`
    /// (on side `side`) along each direction, into `out`. With `whole` (for exact
    /// clipping), parts that shadow the face whole go to `cache.part_hits` instead of
    /// face by face, and a face on the inner side of a cap is decided against its lid
    /// (returned per direction) instead of the cap's faces.
    pub(super) fn collect_blockers(
        &self,
        cache: &mut Cache,
        face: usize,
        side: FaceSide,
        directions: &PerDirection<Option<DVec3>>,
        whole: bool,
        out: &mut PerDirection<Vec<Blocker>>,
    ) -> PerDirection<LidState> {
        let f = &self.faces[face];
        let n = f.normal * side.sign();
        let key = (f.patch, side);
        if cache.search.key != Some(key) {
            cache.search.reset();
            cache.search.key = Some(key);
        }
        cache.part_hits.iter_mut().for_each(Vec::clear);
        let left = self.left_out(face, side, whole);
        let mut lids = PerDirection::splat(LidState::Open);
        for (k, d) in directions.pairs() {
            let Some(d) = *d else { continue };
            lids[k] = self.blockers_along(cache, face, n, k, d, whole, &left, &mut out[k]);
        }
        lids
    }

    /// The parts whose faces the search for `face`'s blockers (on side `side`) leaves out
    /// along every direction: parts cast whole or wholly behind the face (with `whole`),
    /// and the face's own part where it faces away from it or into its lid.
    fn left_out(&self, face: usize, side: FaceSide, whole: bool) -> LeftOut<'_> {
        let f = &self.faces[face];
        let side_index = side.index();
        let own_cap = (whole && self.clip && f.lid_side[side_index]).then(|| self.part_of[face]);
        let shadowing: &[PartShadow] = if whole { &f.part_shadows } else { &[] };
        let own_outside = f.own_outside[side_index].then(|| self.part_of[face]);
        // the first 64 parts as bits: asked once per face of every patch searched
        let bit = |p: u32| if p < 64 { 1u64 << p } else { 0 };
        let mask = shadowing
            .iter()
            .filter(|p| p.sides[side_index] || p.behind[side_index])
            .map(|p| bit(p.part))
            .chain(own_cap.map(bit))
            .chain(own_outside.map(bit))
            .fold(0, |m, b| m | b);
        LeftOut {
            own_cap,
            own_outside,
            shadowing,
            side_index,
            mask,
        }
    }

    /// The possible blockers of `face` (side normal `n`) along `d` (direction `k`), into
    /// `out`, but the faces of the parts `left` leaves out; returns the state of the
    /// face's own lid along `d` (`Open` unless it faces into its cap and `whole`).
    #[allow(clippy::too_many_arguments)]
    fn blockers_along(
        &self,
        cache: &mut Cache,
        face: usize,
        n: DVec3,
        k: Toward,
        d: DVec3,
        whole: bool,
        left: &LeftOut,
        out: &mut Vec<Blocker>,
    ) -> LidState {
        let f = &self.faces[face];
        // and the parts this direction's cover test settled: missing the face, or (when
        // clipping) cast whole
        let settled = &cache.settled[k];
        let mask = left.mask | settled.miss | if whole { settled.ahead_bits } else { 0 };
        let left_out = |part: u32| left.by(mask, part);
        let mut lid_state = LidState::Open;
        let mut lid_blockers = None;
        if let Some(cap) = left.own_cap {
            let entry = &self.parts[cap as usize];
            let lid = entry.convex.lid.as_ref().expect("caps have lids");
            lid_state = self.lid_state(&mut cache.cap_states[k], lid, cap, face, d);
            if lid_state == LidState::Closed {
                return lid_state; // dark along d whatever else lies there
            }
            lid_blockers = entry
                .lid_blockers
                .as_deref()
                .filter(|b| b.len() <= GRID_MIN_FACES);
        }
        for (i, p) in left.shadowing.iter().enumerate() {
            let (c, r) = self.parts[p.part as usize].sphere;
            if p.sides[left.side_index] && reaches(f.centroid, f.radius, c, r, d) {
                cache.part_hits[k].push(i as u32);
            }
        }
        if let Some(list) = lid_blockers {
            // a cap's inner face: only what lies in front of its lid or in its hull
            for &g in list {
                if !left_out(self.part_of[g as usize]) {
                    let along = Along::Direction(d);
                    self.consider_blocker(face, n, g as usize, along, out);
                }
            }
            return lid_state;
        }
        let kept = self.kept_patches(&mut cache.search, f.patch, k, d, mask, left_out);
        if kept.count == 0 {
            return lid_state;
        }
        if kept.count <= GRID_MIN_FACES {
            for &p in &kept.patches {
                // the patch test was for the receiver's whole patch: this face may be
                // out of reach
                let pp = &self.patches[p as usize];
                if reaches(f.centroid, f.radius, pp.centre, pp.radius, d) {
                    // few faces: their spheres tested as they are, with no
                    // projection of every face built for them
                    for g in self.patch_parts.faces(p, left_out) {
                        self.consider_blocker(face, n, g as usize, Along::Direction(d), out);
                    }
                }
            }
            return lid_state;
        }
        let search = &mut cache.search;
        self.search_grid(search, face, n, k, d, left.own_cap, left_out, out);
        lid_state
    }

    /// The occluder patches flagged for the receiver patch `patch` along `d` (direction
    /// `k`) that have faces to test when the parts in `mask` are left out, with their
    /// count: from `search` when it holds them for that mask.
    fn kept_patches<'s>(
        &self,
        search: &'s mut SearchScratch,
        patch: u32,
        k: Toward,
        d: DVec3,
        mask: u64,
        left_out: impl Fn(u32) -> bool + Copy,
    ) -> &'s Kept {
        let flagged = search.flagged[k].get_or_insert_with(|| self.flag_patches(patch, d));
        // faces to test: those of the flagged patches but the parts left out (a mask
        // says which when there are few parts)
        let cached = self.parts.len() <= 64;
        let stale = |kept: &Kept| !(cached && kept.mask == mask);
        let slot = &mut search.kept[k];
        if slot.as_ref().is_some_and(stale) {
            *slot = None;
        }
        slot.get_or_insert_with(|| {
            let mut kept = Kept {
                mask,
                patches: Vec::new(),
                count: 0,
            };
            for &p in flagged.iter() {
                let n = self.patch_parts.count(p, left_out);
                if n > 0 {
                    kept.patches.push(p);
                    kept.count += n;
                }
            }
            kept
        })
    }

    /// Many faces to test (a finely meshed curved part): asks the epoch's grid of faces
    /// seen along `d` (direction `k`) for those whose shadow can fall on `face` (side
    /// normal `n`), and tests those not `left_out` (a cap's own faces, `own_cap`, are left
    /// out of the grid: there are many).
    #[allow(clippy::too_many_arguments)]
    fn search_grid(
        &self,
        search: &mut SearchScratch,
        face: usize,
        n: DVec3,
        k: Toward,
        d: DVec3,
        own_cap: Option<u32>,
        left_out: impl Fn(u32) -> bool,
        out: &mut Vec<Blocker>,
    ) {
        let proj = &mut search.projections[k];
        if proj.dir != Some(d) {
            proj.build(&self.faces, d);
        }
        let proj = &search.projections[k];
        let grid = &mut search.grids[k][usize::from(own_cap.is_some())];
        if grid.dir != Some(d) || grid.excluded != own_cap {
            grid.build(proj, self.grid_cell, own_cap, &self.part_of);
        }
        let at = &proj.at[face];
        let centre = DVec2::new(at[0], at[1]);
        grid.query(centre, at[3], &mut search.stamp, |g| {
            if !left_out(self.part_of[g as usize]) {
                self.consider_blocker(face, n, g as usize, Along::Projected(proj), out)
            }
        });
    }

    /// Face-level tests of face `g` as a blocker of `face` (side normal `n`) along `d`;
    /// pushes it to `out` when none proves it harmless.
    #[inline]
    fn consider_blocker(
        &self,
        face: usize,
        n: DVec3,
        g: usize,
        along: Along,
        out: &mut Vec<Blocker>,
    ) {
        let f = &self.faces[face];
        let o = &self.faces[g];
        let (reached, d) = match along {
            Along::Projected(proj) => (
                proj.reaches(face, g),
                proj.dir.expect("projection built for this direction"),
            ),
            Along::Direction(d) => (reaches(f.centroid, f.radius, o.centroid, o.radius, d), d),
        };
        if g == face || !reached {
            return;
        }
        if let Some(blocker) = self.blocker(face, n, g, d) {
            out.push(blocker);
        }
    }

    /// Can face `g` shadow `face` (side normal `n`) along unit `d`? Its reach first, then
    /// [`Visibility::blocker`]'s proofs.
    pub(super) fn may_block(&self, face: usize, n: DVec3, g: usize, d: DVec3) -> bool {
        let (f, o) = (&self.faces[face], &self.faces[g]);
        g != face
            && reaches(f.centroid, f.radius, o.centroid, o.radius, d)
            && self.blocker(face, n, g, d).is_some()
    }

    /// Face `g` as a blocker of `face` (side normal `n`) along unit `d`, given that it
    /// reaches it; `None` when a proof rules it out.
    #[inline]
    fn blocker(&self, face: usize, n: DVec3, g: usize, d: DVec3) -> Option<Blocker> {
        let (f, o) = (&self.faces[face], &self.faces[g]);
        // the occluder must reach in front of the face's lit/seen side
        if !reaches_front(o, n, f.centroid, self.tol) {
            return None;
        }
        let blocker = Blocker {
            face: g as u32,
            centre: o.centroid,
            radius: o.radius,
            normal: o.normal,
            // Width of shadow to hunt for: the blocker's radius. Its true width
            // (a thin strip's) would find narrower shadows, but the small faces of
            // a curved part then force fine sampling under their joint shadow,
            // which is wide: ~6x the rays on the box-wing. Known limit: a shadow
            // narrower than its caster's radius can fall between samples.
            feature: o.radius,
            // largest shadow it can cast on this face's plane
            shadow_area: o.area * d.dot(o.normal).abs() / n.dot(d).max(1e-3),
        };
        // half-space proof with the face's own vertices
        if blocker.half_space_clear(d, &f.vertices, self.tol) {
            return None;
        }
        // a plate much larger than the face (a solar panel over a dish's facet): no line
        // from the face meets it when all their meets with its plane lie beyond one edge
        if o.radius > LARGE_BLOCKER * f.radius && outline_clear(o, d, &f.vertices, self.tol) {
            return None;
        }
        Some(blocker)
    }
}

/// A face that may cast a shadow on (or hide) the face being sampled.
#[derive(Debug, Clone, Copy)]
pub(super) struct Blocker {
    /// Index of the blocking face.
    pub(super) face: u32,
    pub(super) centre: DVec3,
    pub(super) radius: f64,
    pub(super) normal: DVec3,
    /// Width of shadow to look for between samples, m (its bounding radius).
    pub(super) feature: f64,
    /// Upper bound of its shadow's area on the face, m².
    pub(super) shadow_area: f64,
}

impl Blocker {
    /// Half-space proof: all `points` lie on the side of the blocker's plane that `d`
    /// points away from, so rays from them along `d` never cross the plane.
    #[inline]
    pub(super) fn half_space_clear(&self, d: DVec3, points: &[DVec3], tol: f64) -> bool {
        let dn = d.dot(self.normal);
        if dn == 0.0 {
            return false;
        }
        let s = dn.signum();
        points
            .iter()
            .all(|v| s * self.normal.dot(*v - self.centre) >= -tol)
    }
}

/// How [`Visibility::consider_blocker`] tests a blocker's reach along the direction: from
/// the epoch's projection of every face, or from the two spheres as they are.
#[derive(Clone, Copy)]
enum Along<'a> {
    Projected(&'a Projection),
    Direction(DVec3),
}

/// The blocker search's scratch ([`Cache::search`]): patch-level results for the receiver
/// patch and side last searched, and the faces seen along each direction.
#[derive(Default)]
pub(super) struct SearchScratch {
    /// The receiver patch, and its side, that the results below are for.
    key: Option<(u32, FaceSide)>,
    /// Flagged occluder patches for view, sun, earth (None: not computed yet).
    flagged: PerDirection<Option<Vec<u32>>>,
    /// Per direction: of the flagged patches, those with faces to test when the parts in
    /// a mask are left out, with their count — for the last mask asked (faces of a patch
    /// mostly share theirs).
    kept: PerDirection<Option<Kept>>,
    /// Faces' bounding spheres seen along each direction (built on first use in an epoch).
    projections: PerDirection<Projection>,
    /// Faces binned across each direction (built on first use in an epoch): all, and all
    /// but a cap's (for the cap's own faces, [`Visibility::collect_blockers`]).
    grids: PerDirection<[FaceGrid; 2]>,
    /// Per face: the query that last returned it (deduplicates multi-cell faces).
    stamp: Stamp,
}

impl SearchScratch {
    /// Forgets the patch-level results, which hold within one epoch. The projections and
    /// grids are keyed by their direction and kept.
    pub(super) fn reset(&mut self) {
        self.key = None;
        self.flagged = PerDirection::default();
        self.kept = PerDirection::default();
    }
}

/// The parts whose faces a face's blocker search leaves out
/// ([`Visibility::left_out`]).
struct LeftOut<'a> {
    /// The face's own cap, when it faces into it (decided by the lid).
    own_cap: Option<u32>,
    /// The face's own part, when it faces out of it.
    own_outside: Option<u32>,
    /// The parts that may shadow the face whole (none unless clipping).
    shadowing: &'a [PartShadow],
    /// The face's side, as an index into its per-side arrays.
    side_index: usize,
    /// Of the first 64 parts, those left out (bit p for part p).
    mask: u64,
}

impl LeftOut<'_> {
    /// Is `part` left out, given `mask` (this one's and what a direction adds)? Asked by
    /// bit for the first 64 parts; the rest one by one.
    fn by(&self, mask: u64, part: u32) -> bool {
        if part < 64 {
            mask & (1 << part) != 0
        } else {
            part != NO_PART && self.skipped(part)
        }
    }

    /// Parts cast whole or wholly behind the face, and the face's own part where it
    /// faces away from it or into its lid: their faces are not collected.
    fn skipped(&self, part: u32) -> bool {
        let s = self.side_index;
        self.own_cap == Some(part)
            || self.own_outside == Some(part)
            || self
                .shadowing
                .iter()
                .any(|p| p.part == part && (p.sides[s] || p.behind[s]))
    }
}

/// Flagged patches that have faces to test, given the parts left out ([`SearchScratch::kept`]).
struct Kept {
    /// Parts left out (bit p for part p).
    mask: u64,
    patches: Vec<u32>,
    /// Faces to test in them.
    count: usize,
}
