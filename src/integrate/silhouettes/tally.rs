//! Counts of what the silhouette method does (folds, lines, dirty patches, rays and the
//! nodes they visit, faces summed one by one), for measuring where an epoch's work goes:
//! kept only with the `counters` feature, e.g.
//! `cargo run --release --example suite --features counters -- --threads 1`. Without it
//! every [`add`] compiles to nothing and [`report`] says so.
//!
//! The counts are process-wide atomics: take them from one thread (`--threads 1`), or
//! they cost the contention they measure.

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
    /// those summed whole from their patch's form.
    Epochs,
    FacesOneByOne,
    FacesInSums,
}

/// Whether the counts are kept (the `counters` feature).
pub const ON: bool = cfg!(feature = "counters");

/// How many kinds of count there are (the last variant's index and one).
#[cfg(feature = "counters")]
const KINDS: usize = Tally::FacesInSums as usize + 1;

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
    Some(format!(
        "per direction ({} directions):\n  \
         fold search: {:.0} mixed patches with {:.0} faces, {:.0} inner and {:.0} rim edges tested, {:.0} folds\n  \
         patches: {:.0} clean, {:.0} dirty with {:.0} faces, {:.0} of them crossed by {:.0} lines\n  \
         rays: {:.1} a direction, each visiting {:.1} nodes, {:.1} leaf polygons, {:.1} planes met\n\
         per epoch ({} epochs): light summed over {:.0} faces one by one, {:.0} in whole patches",
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
        per_dir(Tally::Rays),
        per_ray(Tally::RayNodes),
        per_ray(Tally::RayLeafPolygons),
        per_ray(Tally::RayPlanes),
        get(Tally::Epochs),
        per_epoch(Tally::FacesOneByOne),
        per_epoch(Tally::FacesInSums),
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
    }
}
