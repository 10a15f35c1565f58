//! Counts of what the silhouette method does (folds, lines, dirty patches, rays and the
//! nodes they visit, faces summed one by one), and the time its steps take, for
//! measuring where an epoch's work goes: kept only with the `counters` feature, e.g.
//! `cargo run --release --example suite --features counters -- --threads 1`. Without it
//! every [`add`], [`now`] and [`took`] compiles to nothing and [`report`] says so.
//!
//! The counts are process-wide atomics: take them from one thread (`--threads 1`), or
//! they cost the contention they measure. Each timed step reads the clock twice (~50 ns:
//! a patch's steps are timed per patch, ~150 a direction at ~20k triangles, so the times
//! run a few percent above an untimed run's).

/// What is counted (see [`report`] for how each is shown).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tally {
    /// Directions decided (an epoch's view, Sun and Earth each once; a direction kept
    /// from the last epoch, a Sun fixed in the body frame, is not decided again).
    Directions,
    /// Patches facing both ways along a direction, their faces, and the edges inside
    /// them and on the patches' rims the fold search tested.
    MixedPatches,
    MixedFaces,
    InnerEdges,
    RimEdges,
    /// Folds found, and lines they cut across faces (folds and contacts).
    Folds,
    Lines,
    /// Patches decided whole, and patches decided face by face with their faces, of which
    /// lines cross some.
    CleanPatches,
    DirtyPatches,
    DirtyFaces,
    CrossedFaces,
    /// Rays cast (counts and blocked tests), the hierarchy's nodes they visited, the
    /// polygons in the leaves they reached, and those whose plane they met.
    Rays,
    RayNodes,
    RayLeafPolygons,
    RayPlanes,
    /// Epochs, and the faces of seen patches whose light was summed face by face, and
    /// those summed whole from their patch's form; of these, those of patches a line
    /// crossed, decided face by face with terms from their patch's lights.
    Epochs,
    FacesOneByOne,
    FacesInSums,
    FacesInCrossedSums,
    /// The patches' queries for the folds above them: the folds met in the tree's leaves,
    /// of which below the patch along d, off its box, off its slab; the rest are kept as near. Then, per receiving face of a
    /// dirty patch, the near folds scanned, and those whose box reaches the face's
    /// corners and are tested exactly.
    QueryFolds,
    QueryBelow,
    QueryOffBox,
    QueryOffSlab,
    NearScanned,
    NearTested,
    /// Time (ns) per direction: the fold search, the folds' tree, the patches' queries
    /// for folds, the dirty patches' footprints (and their near folds narrowed to them),
    /// their faces' lines, the flood of counts (its rays included); per epoch: the areas
    /// of lit and seen faces (the crossed ones cut into cells) and the whole epoch.
    FoldSearchNs,
    FoldTreeNs,
    QueriesNs,
    FootprintsNs,
    FaceLinesNs,
    FloodNs,
    AreasNs,
    EpochNs,
    /// Preparations, and the time (ns, on the thread that ran it) of each step: the
    /// faces merged, the triangles' grid for the contact search, the faces renumbered
    /// by patches, the contact search, the topology, the polygons, the patches, the
    /// rays' hierarchy.
    Preparations,
    FacesNs,
    TriangleGridNs,
    RenumberNs,
    ContactSearchNs,
    TopologyNs,
    PolygonsNs,
    PatchesNs,
    RaysTreeNs,
}

/// Whether the counts are kept (the `counters` feature).
pub const ON: bool = cfg!(feature = "counters");

/// How many kinds of count there are (the last variant's index and one).
#[cfg(feature = "counters")]
const KINDS: usize = Tally::RaysTreeNs as usize + 1;

#[cfg(feature = "counters")]
static COUNTS: [std::sync::atomic::AtomicU64; KINDS] =
    [const { std::sync::atomic::AtomicU64::new(0) }; KINDS];

/// Adds `n` to `what` (nothing without the `counters` feature).
#[inline(always)]
pub fn add(what: Tally, n: u64) {
    #[cfg(feature = "counters")]
    COUNTS[what as usize].fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    #[cfg(not(feature = "counters"))]
    let _ = (what, n);
}

/// A moment a step is timed from ([`now`], [`took`]): the clock is read only with the
/// `counters` feature.
#[derive(Clone, Copy)]
pub struct Since {
    #[cfg(feature = "counters")]
    at: std::time::Instant,
}

/// The moment to time a step from.
#[inline(always)]
pub fn now() -> Since {
    Since {
        #[cfg(feature = "counters")]
        at: std::time::Instant::now(),
    }
}

/// Adds the time since `since` (ns) to `what`.
#[inline(always)]
pub fn took(what: Tally, since: Since) {
    #[cfg(feature = "counters")]
    add(what, since.at.elapsed().as_nanos() as u64);
    #[cfg(not(feature = "counters"))]
    let _ = (what, since);
}

/// `step()`, its time added to `what`.
#[inline(always)]
pub fn timed<T>(what: Tally, step: impl FnOnce() -> T) -> T {
    let since = now();
    let out = step();
    took(what, since);
    out
}

/// The count of `what` since the last [`reset`] (0 without the `counters` feature).
pub fn get(what: Tally) -> u64 {
    #[cfg(feature = "counters")]
    return COUNTS[what as usize].load(std::sync::atomic::Ordering::Relaxed);
    #[cfg(not(feature = "counters"))]
    {
        let _ = what;
        0
    }
}

/// Sets every count to zero.
pub fn reset() {
    #[cfg(feature = "counters")]
    for c in &COUNTS {
        c.store(0, std::sync::atomic::Ordering::Relaxed);
    }
}

/// The counts since the last [`reset`], per direction (and per ray for the rays'
/// visits), on a few lines; `None` without the `counters` feature.
pub fn report() -> Option<String> {
    if !ON {
        return None;
    }
    let per_dir = |t: Tally| get(t) as f64 / get(Tally::Directions).max(1) as f64;
    let per_ray = |t: Tally| get(t) as f64 / get(Tally::Rays).max(1) as f64;
    let per_epoch = |t: Tally| get(t) as f64 / get(Tally::Epochs).max(1) as f64;
    let per_prep = |t: Tally| get(t) as f64 / get(Tally::Preparations).max(1) as f64;
    let us = |t: f64| t / 1e3;
    Some(format!(
        "per direction ({} directions):\n  \
         fold search: {:.0} mixed patches with {:.0} faces, {:.0} inner and {:.0} rim edges tested, {:.0} folds\n  \
         patches: {:.0} clean, {:.0} dirty with {:.0} faces, {:.0} of them crossed by {:.0} lines\n  \
         fold queries: {:.0} folds met in leaves, {:.0} below, {:.0} off the box, {:.0} off the slab; \
         faces' scans: {:.0} near folds, {:.0} tested exactly\n  \
         rays: {:.1} a direction, each visiting {:.1} nodes, {:.1} leaf polygons, {:.1} planes met\n  \
         µs: fold search {:.1}, folds' tree {:.1}, fold queries {:.1}, footprints {:.1}, faces' lines {:.1}, flood {:.1}\n\
         per epoch ({} epochs): light summed over {:.0} faces one by one, {:.0} in whole patches \
         ({:.0} of them in patches a line crosses); \
         µs: areas {:.1}, whole epoch {:.1}\n\
         per preparation ({}), ms on the thread that ran each step: faces {:.2}, triangles' grid {:.2}, \
         renumbering {:.2}, contact search {:.2}, topology {:.2}, polygons {:.2}, patches {:.2}, rays' tree {:.2}",
        get(Tally::Directions),
        per_dir(Tally::MixedPatches),
        per_dir(Tally::MixedFaces),
        per_dir(Tally::InnerEdges),
        per_dir(Tally::RimEdges),
        per_dir(Tally::Folds),
        per_dir(Tally::CleanPatches),
        per_dir(Tally::DirtyPatches),
        per_dir(Tally::DirtyFaces),
        per_dir(Tally::CrossedFaces),
        per_dir(Tally::Lines),
        per_dir(Tally::QueryFolds),
        per_dir(Tally::QueryBelow),
        per_dir(Tally::QueryOffBox),
        per_dir(Tally::QueryOffSlab),
        per_dir(Tally::NearScanned),
        per_dir(Tally::NearTested),
        per_dir(Tally::Rays),
        per_ray(Tally::RayNodes),
        per_ray(Tally::RayLeafPolygons),
        per_ray(Tally::RayPlanes),
        us(per_dir(Tally::FoldSearchNs)),
        us(per_dir(Tally::FoldTreeNs)),
        us(per_dir(Tally::QueriesNs)),
        us(per_dir(Tally::FootprintsNs)),
        us(per_dir(Tally::FaceLinesNs)),
        us(per_dir(Tally::FloodNs)),
        get(Tally::Epochs),
        per_epoch(Tally::FacesOneByOne),
        per_epoch(Tally::FacesInSums),
        per_epoch(Tally::FacesInCrossedSums),
        us(per_epoch(Tally::AreasNs)),
        us(per_epoch(Tally::EpochNs)),
        get(Tally::Preparations),
        per_prep(Tally::FacesNs) / 1e6,
        per_prep(Tally::TriangleGridNs) / 1e6,
        per_prep(Tally::RenumberNs) / 1e6,
        per_prep(Tally::ContactSearchNs) / 1e6,
        per_prep(Tally::TopologyNs) / 1e6,
        per_prep(Tally::PolygonsNs) / 1e6,
        per_prep(Tally::PatchesNs) / 1e6,
        per_prep(Tally::RaysTreeNs) / 1e6,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_kept_only_with_the_feature() {
        reset();
        add(Tally::Folds, 3);
        let kept = get(Tally::Folds);
        // other tests may add concurrently with the feature on: at least ours
        assert!(if ON { kept >= 3 } else { kept == 0 });
        assert_eq!(report().is_some(), ON);
        // a timed step's result passes through; its time is kept only with the feature
        let before = get(Tally::AreasNs);
        let out = timed(Tally::AreasNs, || {
            std::thread::sleep(std::time::Duration::from_millis(2));
            7
        });
        assert_eq!(out, 7);
        let spent = get(Tally::AreasNs) - before;
        assert!(if ON { spent >= 2_000_000 } else { spent == 0 });
    }
}
