//! The lid: a face of a convex cap, on its inner side, sees out only through the cap's
//! rim. Per direction the lid passes all of it, none of it, or clips it ([`LidState`],
//! from the cap's tree, [`super::caps`]); a face that nothing else can reach is decided by
//! its lid alone — for the whole epoch at once ([`LidTable`]), or one face at a time.

use super::blockers::Blocker;
use super::caps::{CapStates, LidState};
use super::clip::{above_horizon, ShadowBuffers};
use super::face::{FaceGeom, FaceSide};
use super::settle::Settled;
use super::{face_directions, Cache, Uncertain, Visibility, VisibilityMode, NO_PART};
use crate::geometry::polygon::twice_signed_area;
use crate::integrate::per_direction::{PerDirection, Toward};
use glam::DVec3;

impl Visibility {
    /// Every cap's face states along this epoch's view, Sun (when sunlit) and earthshine
    /// shadow direction (when earthlit), brought up to date in `cache`, for
    /// [`LidTable::decided`]; `None` when no lid decides any face.
    pub fn lid_table<'a>(
        &'a self,
        cache: &'a mut Cache,
        view: DVec3,
        sun: Option<DVec3>,
        earth: Option<DVec3>,
    ) -> Option<LidTable<'a>> {
        if !(self.mode == VisibilityMode::Adaptive && self.clip)
            || self.parts.iter().all(|p| p.cap_tree.is_none())
        {
            return None;
        }
        let dirs = Uncertain { view, sun, earth };
        let directions = PerDirection {
            view: Some(view),
            sun,
            earth,
        };
        for (k, d) in directions.pairs() {
            let Some(d) = *d else { continue };
            let states = &mut cache.cap_states[k];
            states.resize_with(self.parts.len(), Default::default);
            for (cap, p) in self.parts.iter().enumerate() {
                if let (Some(tree), Some(lid)) = (&p.cap_tree, &p.convex.lid) {
                    states[cap].along(tree, lid, d, self.tol);
                }
            }
        }
        Some(LidTable {
            vis: self,
            dirs,
            states: cache.cap_states.each_ref().map(Vec::as_slice),
        })
    }

    /// Is `f` (on side `side`) a cap's inner face that nothing but its own cap can shadow?
    #[inline]
    pub(super) fn lid_decides(&self, f: &FaceGeom, side: FaceSide) -> bool {
        self.mode == VisibilityMode::Adaptive && self.clip && f.lid_only[side.index()]
    }

    /// [`Visibility::visible_area`] for a face (side normal `n`) that its own cap's lid
    /// alone decides ([`Visibility::lid_decides`]): seen-and-sunlit and seen-and-earthlit
    /// areas, m², with no search. `None` when clipping to the lid cuts the face into too
    /// many pieces: the caller searches and samples as for any face.
    pub(super) fn through_own_lid(
        &self,
        cache: &mut Cache,
        face: usize,
        n: DVec3,
        directions: &PerDirection<Option<DVec3>>,
    ) -> Option<(f64, f64)> {
        let f = &self.faces[face];
        let lids = self.own_lid_states(cache, face, directions);
        if let Some(areas) = lid_decided(&lids, f.pieces_area) {
            return Some(areas);
        }
        // Clipped along one direction only: the lid's cut, measured on the lid's plane.
        // (The rim's shadow and its occlusion cross a dish along different curves, so
        // a face on one seldom lies on the other.)
        let mut clipped = Toward::ALL
            .into_iter()
            .filter(|&k| lids[k] == LidState::Clip);
        if let (Some(k), None) = (clipped.next(), clipped.next()) {
            let d = directions[k].expect("a clipped direction exists");
            if let Some(a) = self.area_through_lid(&mut cache.clip.shadows, face, n, d) {
                let full = f.pieces_area;
                let areas = match k {
                    Toward::View => (a, a), // seen part, and all of it lit (or none: `dark`)
                    Toward::Sun => (a, full),
                    Toward::Earth => (full, a),
                };
                return Some(dark(&lids, areas));
            }
        }
        // clipped to the lid alone: no blockers to search for
        cache.part_hits.iter_mut().for_each(Vec::clear);
        cache.settled.iter_mut().for_each(Settled::clear);
        let none: PerDirection<Vec<Blocker>> = Default::default();
        let open = open_directions(directions, &lids);
        self.exact_area(cache, face, n, &open, &none, &lids)
            .map(|areas| dark(&lids, areas))
    }

    /// For a face that its own cap's lid alone decides ([`Visibility::lid_decides`]): the
    /// lid's state along each direction ([`lid_states`]), walking the cap's tree where the
    /// epoch has not yet.
    #[inline]
    fn own_lid_states(
        &self,
        cache: &mut Cache,
        face: usize,
        directions: &PerDirection<Option<DVec3>>,
    ) -> PerDirection<LidState> {
        let cap = self.part_of[face];
        let lid = self.parts[cap as usize]
            .convex
            .lid
            .as_ref()
            .expect("caps have lids");
        lid_states(directions, |k, d| {
            self.lid_state(&mut cache.cap_states[k], lid, cap, face, d)
        })
    }

    /// The state of cap `cap`'s lid for its face `face` along `d`, from the cap's tree
    /// walked once per epoch and direction (`states`: the cache's, for this direction).
    #[inline(always)]
    pub(super) fn lid_state(
        &self,
        states: &mut Vec<CapStates>,
        lid: &crate::geometry::convex::Lid,
        cap: u32,
        face: usize,
        d: DVec3,
    ) -> LidState {
        if states.len() < self.parts.len() {
            states.resize_with(self.parts.len(), Default::default);
        }
        let tree = self.parts[cap as usize]
            .cap_tree
            .as_ref()
            .expect("caps have trees");
        states[cap as usize].along(tree, lid, d, self.tol)[self.cap_slot[face] as usize]
    }

    /// Area (m²) of `face` (side normal `n`) whose rays along `d` leave through `lid`, its
    /// own cap's: the face seen along d on the lid's plane, clipped to the lid there. A
    /// tube of rays along d crosses both planes, so an area A on the lid's plane is
    /// A·(d·n_lid)/(d·n) on the face's, and nothing needs projecting back. `None` when
    /// the face is no convex polygon.
    pub(super) fn area_through_lid(
        &self,
        x: &mut ShadowBuffers,
        face: usize,
        n: DVec3,
        d: DVec3,
    ) -> Option<f64> {
        let f = &self.faces[face];
        let lid = self.parts[self.part_of[face] as usize]
            .convex
            .lid
            .as_ref()?;
        let convex = f.convex();
        let d = above_horizon(d, n);
        let dl = d.dot(lid.normal);
        if convex.is_empty() || dl <= 0.0 {
            return None;
        }
        x.part_points.clear();
        x.part_points.extend(convex.iter().map(|p| lid.meet(*p, d)));
        lid.clip(&mut x.part_points, &mut x.lid_edges, &mut x.shadow);
        let on_lid = 0.5 * twice_signed_area(&x.part_points).abs();
        Some((on_lid * dl / d.dot(n)).min(f.pieces_area))
    }
}

/// One epoch's lid states of every cap's faces ([`Visibility::lid_table`]).
pub struct LidTable<'a> {
    vis: &'a Visibility,
    /// View, Sun, earthshine shadow direction, as the states were made for.
    dirs: Uncertain,
    /// Per direction, per part: its face states (a cap's), in tree order.
    states: PerDirection<&'a [CapStates]>,
}

impl LidTable<'_> {
    /// Seen-and-sunlit and seen-and-earthlit areas (m²) of `face` (on side `side`, lit by
    /// the Sun and by earthshine as told) when its own cap's lid decides it whole along
    /// every direction — a dish's inner face away from the rim's shadow: no search, no
    /// clipping, exactly what [`Visibility::visible_area`] returns for it. `None` when
    /// the face needs that call.
    #[inline]
    pub fn decided(
        &self,
        face: usize,
        side: FaceSide,
        sunlit: bool,
        earthlit: bool,
    ) -> Option<(f64, f64)> {
        let vis = self.vis;
        let f = &vis.faces[face];
        if !vis.lid_decides(f, side) {
            return None;
        }
        let (cap, slot) = (vis.part_of[face] as usize, vis.cap_slot[face] as usize);
        let dirs = Uncertain {
            sun: self.dirs.sun.filter(|_| sunlit),
            earth: self.dirs.earth.filter(|_| earthlit),
            ..self.dirs
        };
        let directions = face_directions(&dirs, f.normal * side.sign());
        let lids = lid_states(&directions, |k, _| self.states[k][cap].states[slot]);
        lid_decided(&lids, f.pieces_area)
    }
}

/// A face's own lid's state along each of `directions` (view, Sun, Earth), by `state`:
/// `Open` along one not asked for; once the view is closed, the rest is not looked up.
#[inline]
fn lid_states(
    directions: &PerDirection<Option<DVec3>>,
    mut state: impl FnMut(Toward, DVec3) -> LidState,
) -> PerDirection<LidState> {
    let mut lids = PerDirection::splat(LidState::Open);
    for (k, d) in directions.pairs() {
        if let Some(d) = *d {
            lids[k] = state(k, d);
            if k == Toward::View && lids.view == LidState::Closed {
                break;
            }
        }
    }
    lids
}

/// The areas (m²) of a face of area `area` whose own lid has `lids` along view, Sun and
/// Earth, when no state is `Clip`: all of it or nothing along each.
#[inline]
fn lid_decided(lids: &PerDirection<LidState>, area: f64) -> Option<(f64, f64)> {
    if lids.view == LidState::Closed {
        return Some((0.0, 0.0));
    }
    if lids.iter().any(|l| *l == LidState::Clip) {
        return None;
    }
    Some(dark(lids, (area, area)))
}

/// The directions along which a face's own cap does not close it: along the others it is
/// dark, with no shadows to cast.
pub(super) fn open_directions(
    directions: &PerDirection<Option<DVec3>>,
    lids: &PerDirection<LidState>,
) -> PerDirection<Option<DVec3>> {
    PerDirection::from_fn(|k| directions[k].filter(|_| lids[k] != LidState::Closed))
}

/// Sunlit and earthlit areas (m²) zeroed where the face's own cap closes the Sun's or the
/// Earth's direction.
pub(super) fn dark(lids: &PerDirection<LidState>, (a_sun, a_earth): (f64, f64)) -> (f64, f64) {
    let lit = |l: LidState, a: f64| if l == LidState::Closed { 0.0 } else { a };
    (lit(lids.sun, a_sun), lit(lids.earth, a_earth))
}

/// Marks each face whose lid alone decides what one side of it sees (`lid_only`).
pub(super) fn mark_lid_only(
    geoms: &mut [FaceGeom],
    part_of: &[u32],
    lid_blockers: &[Option<Vec<u32>>],
) {
    // the lid alone decides a cap's inner face when no other face can reach into the
    // cap and no part is cast whole on the face
    for (g, &k) in geoms.iter_mut().zip(part_of) {
        let sealed = k != NO_PART && matches!(&lid_blockers[k as usize], Some(b) if b.is_empty());
        for s in 0..2 {
            g.lid_only[s] = sealed && g.lid_side[s] && !g.part_shadows.iter().any(|p| p.sides[s]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::oracle::*;
    use super::*;
    use crate::geometry::builtin;

    #[test]
    fn a_sealed_caps_faces_clipped_by_the_lid_alone_match_face_by_face_clipping() {
        // A dish that nothing reaches into: its inner faces are decided by the lid alone,
        // and a face clipped along one direction only is measured on the lid's plane
        // (`area_through_lid`). Against clipping by every other face of the dish, one by
        // one, in the face's own plane: both exact up to the clipper's plane tolerance
        // (1e-9 of the object's radius), so, as in the test below, they must agree to
        // 1e-7 of the largest face.
        let vis = visibility_of(builtin::box_wing_with(8, 24, 0));
        let largest = vis.faces.iter().map(|g| g.area).fold(0.0, f64::max);
        let mut rnd = crate::test_rng(9);
        let mut unit = || random_unit(&mut rnd);
        let mut cache = Cache::default();
        let (mut compared, mut one_clipped, mut partial, mut overruled) = (0, 0, 0, 0);
        for _ in 0..60 {
            // from above the dish mostly, where its inside is seen and lit
            let lift = |d: DVec3| (d + DVec3::Z).normalize_or(DVec3::Z);
            let (view, sun, earth) = (lift(unit()), lift(unit()), lift(unit()));
            cache.reset();
            for (i, g) in vis.faces.iter().enumerate() {
                for side in FaceSide::BOTH {
                    let n = g.normal * side.sign();
                    if !g.lid_only[side.index()] || n.dot(view) <= 0.0 {
                        continue;
                    }
                    let dirs = Uncertain {
                        view,
                        sun: (n.dot(sun) > 0.0).then_some(sun),
                        earth: Some(earth),
                    };
                    let (a_sun, a_earth, rays) = vis.visible_area(&mut cache, i, side, &dirs, 1e-6);
                    let Some((b_sun, b_earth)) = vis.face_by_face(&mut cache, i, side, &dirs)
                    else {
                        continue;
                    };
                    assert_eq!(rays, 0);
                    let b_sun = if dirs.sun.is_some() { b_sun } else { a_sun };
                    let tol = 1e-7 * largest;
                    if (a_sun - b_sun).abs() > tol || (a_earth - b_earth).abs() > tol {
                        // where the two disagree (the plain clipper's slivers at grazing
                        // directions), rays decide, as in the test below
                        rays_decide(&vis, i, side, &dirs, (a_sun, a_earth), (b_sun, b_earth));
                        overruled += 1;
                    }
                    compared += 1;
                    let cap = vis.part_of[i];
                    let lid = vis.parts[cap as usize].convex.lid.as_ref().expect("lid");
                    let earth = dirs.earth.filter(|e| n.dot(*e) > 1e-3);
                    let clipped = PerDirection {
                        view: Some(view),
                        sun: dirs.sun,
                        earth,
                    }
                    .pairs()
                    .filter(|(k, d)| {
                        d.is_some_and(|d| {
                            let states = &mut cache.cap_states[*k];
                            vis.lid_state(states, lid, cap, i, d) == LidState::Clip
                        })
                    })
                    .count();
                    one_clipped += usize::from(clipped == 1);
                    partial += usize::from(clipped == 1 && b_sun > tol && b_sun < g.area - tol);
                }
            }
        }
        assert!(
            compared > 5000 && one_clipped > 300 && partial > 100,
            "{compared} {one_clipped} {partial}"
        );
        assert!(
            overruled * 100 < compared,
            "{overruled} of {compared} overruled"
        );
    }

    #[test]
    fn the_epochs_lid_table_decides_a_face_as_visible_area_does() {
        // `LidTable::decided` is a shortcut the per-face loop takes before calling
        // `visible_area`: wherever it answers, the answer must be `visible_area`'s to the
        // last bit (the light curve must not depend on which path a face took), and it
        // must answer for most of a dish's inner faces. Directions from all round, the
        // earthshine direction often near the faces' horizons (its filter at n·e = 1e-3).
        let vis = visibility_of(builtin::box_wing_with(8, 24, 0));
        let mut rnd = crate::test_rng(23);
        let mut unit = || random_unit(&mut rnd);
        let (mut table_cache, mut cache) = (Cache::default(), Cache::default());
        let (mut decided, mut lid_faces, mut closed_earth) = (0, 0, 0);
        for trial in 0..80 {
            let view = (unit() + DVec3::Z).normalize_or(DVec3::Z);
            let sun = (trial % 4 != 0).then(&mut unit);
            let earth = (trial % 3 != 0).then(|| {
                if trial % 2 == 0 {
                    unit()
                } else {
                    // near the dish's rim plane, where faces' horizons are
                    (unit() * DVec3::new(1.0, 1.0, 0.05)).normalize_or(DVec3::X)
                }
            });
            table_cache.reset();
            let table = vis
                .lid_table(&mut table_cache, view, sun, earth)
                .expect("the dish is a cap");
            cache.reset();
            for (i, g) in vis.faces.iter().enumerate() {
                for side in FaceSide::BOTH {
                    let n = g.normal * side.sign();
                    if n.dot(view) <= 0.0 {
                        continue;
                    }
                    let sunlit = sun.is_some_and(|d| n.dot(d) > 0.0);
                    let earthlit = earth.is_some() && trial % 5 != 0;
                    lid_faces += usize::from(vis.lid_decides(g, side));
                    let Some((a_sun, a_earth)) = table.decided(i, side, sunlit, earthlit) else {
                        continue;
                    };
                    let dirs = Uncertain {
                        view,
                        sun: sun.filter(|_| sunlit),
                        earth: earth.filter(|_| earthlit),
                    };
                    let (b_sun, b_earth, rays) = vis.visible_area(&mut cache, i, side, &dirs, 1e-6);
                    assert_eq!(rays, 0);
                    assert_eq!(
                        (a_sun.to_bits(), a_earth.to_bits()),
                        (b_sun.to_bits(), b_earth.to_bits()),
                        "face {i} side {side:?}: {a_sun} {a_earth} against {b_sun} {b_earth}"
                    );
                    decided += 1;
                    closed_earth += usize::from(a_earth == 0.0 && a_sun > 0.0);
                }
            }
        }
        assert!(
            decided * 10 > lid_faces * 8 && closed_earth > 100,
            "{decided} decided of {lid_faces}, {closed_earth} dark to the Earth only"
        );
    }
}
