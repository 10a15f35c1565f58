//! What the convex parts settle for a face along a direction before any blocker is
//! searched: one part may hide it whole (dark: nothing else matters), parts may miss it or
//! lie wholly ahead of it (their shadows cast whole, from their silhouettes), and with
//! every part missed and no loose face in reach it is clear. Parts are tested against the
//! face's whole part first ([`Visibility::part_cover`]), then against the face.

use super::clip::above_horizon;
use super::face::{FaceGeom, FaceSide};
use super::parts::{self, Cover, PartCover, Silhouette};
use super::proofs::reaches;
use super::{Cache, Visibility, NO_PART};
use crate::integrate::per_direction::{PerDirection, Toward};
use glam::{DVec2, DVec3};

/// What the parts that may hide a face whole settle along one direction.
#[derive(Default)]
pub(super) struct Settled {
    /// Parts (bit p for part p < 64) none of whose faces need testing: they miss the face.
    pub(super) miss: u64,
    /// Parts wholly ahead of the face ([`parts::Cover::Ahead`]): cast whole by their
    /// silhouettes when clipping, instead of face by face; and their bits.
    pub(super) ahead: Vec<u32>,
    pub(super) ahead_bits: u64,
}

impl Settled {
    pub(super) fn clear(&mut self) {
        self.miss = 0;
        self.ahead.clear();
        self.ahead_bits = 0;
    }
}

/// Fewest faces of a part for the cover test to be tried against it whole first
/// ([`Visibility::part_cover`]): a box's six faces gain nothing from it.
const PART_COVER_MIN_FACES: usize = 32;

/// Most loose faces (of no part) a face is tested against for being clear of shadows
/// along a direction ([`Visibility::settle_by_parts`]).
const MAX_LOOSE: usize = 8;

/// Buffers for [`Visibility::settle_by_parts`] ([`Cache::settle`]).
#[derive(Default)]
pub(super) struct SettleScratch {
    /// Per direction, per part: the other parts' cover test against it whole.
    part_covers: PerDirection<Vec<PartCover>>,
    /// The face's vertices projected across the direction being settled.
    across: Vec<DVec2>,
}

impl Visibility {
    /// Per direction: is `face` (on side `side`) hidden whole along it by one convex part
    /// (first), or can nothing shadow it along it (second)? What else its cover
    /// candidates settle goes to `cache.settled` ([`parts::Silhouette::cover`]).
    /// Parts are tested first against the face's whole part ([`Visibility::part_cover`]),
    /// then against the face.
    pub(super) fn settle_by_parts(
        &self,
        cache: &mut Cache,
        face: usize,
        side: FaceSide,
        directions: &PerDirection<Option<DVec3>>,
    ) -> (PerDirection<bool>, PerDirection<bool>) {
        let f = &self.faces[face];
        let side_index = side.index();
        let n = f.normal * side.sign();
        let covers = &f.covers[side_index];
        let (mut hidden, mut clear) = (PerDirection::splat(false), PerDirection::splat(false));
        if covers.is_empty() || f.vertices.is_empty() {
            return (hidden, clear);
        }
        let own = self.part_of[face];
        // the face's part as a whole is tested only for parts of many faces, where it
        // saves many faces' tests; and nothing but other parts (and loose faces) can shadow
        // a face that faces out of its own convex part
        let whole_part = own != NO_PART
            && self.parts[own as usize].convex.faces.len() >= PART_COVER_MIN_FACES
            && self.parts.len() <= 64;
        let others = if whole_part && f.own_outside[side_index] {
            (u64::MAX >> (64 - self.parts.len())) & !(1u64 << own)
        } else {
            u64::MAX // never all settled: no direction is called clear
        };
        let x = &mut cache.settle;
        for (k, d) in directions.pairs() {
            let Some(d) = *d else { continue };
            // the direction the shadows are cast along (`exact_area`'s)
            let cast = above_horizon(d, n);
            // the face's corners across d, projected once a part needs its silhouette
            x.across.clear();
            let (silhouettes, settled) = (&mut cache.silhouettes[k], &mut cache.settled[k]);
            // (a face whose horizon bends the direction has its own: no part's result)
            if whole_part && cast == d {
                let whole = self.own_part_cover(&mut x.part_covers[k], silhouettes, own, d);
                if whole.hidden {
                    hidden[k] = true;
                    if k == Toward::View {
                        break; // unseen: nothing else matters
                    }
                    continue;
                }
                settled.miss |= whole.miss;
            }
            let d = cast;
            hidden[k] = self.settle_by_covers(f, covers, d, silhouettes, settled, &mut x.across);
            if k == Toward::View && hidden.view {
                break; // unseen: nothing else matters
            }
            clear[k] = !hidden[k]
                && others & !settled.miss == 0
                && self.loose.len() <= MAX_LOOSE
                && self
                    .loose
                    .iter()
                    .all(|&g| !self.may_block(face, n, g as usize, d));
        }
        (hidden, clear)
    }

    /// The cover test of every other part against `face`'s own part `own` as a whole
    /// along unit `d` ([`Visibility::part_cover`]), kept in `covers` (the direction's,
    /// per part) until the direction changes.
    fn own_part_cover<'c>(
        &self,
        covers: &'c mut Vec<PartCover>,
        silhouettes: &mut Vec<Silhouette>,
        own: u32,
        d: DVec3,
    ) -> &'c PartCover {
        if covers.len() < self.parts.len() {
            covers.resize_with(self.parts.len(), Default::default);
        }
        let whole = &mut covers[own as usize];
        if whole.dir != Some(d) {
            *whole = self.part_cover(silhouettes, own as usize, d);
        }
        whole
    }

    /// The cover test of face `f`'s candidate parts `covers` along `d` (the direction the
    /// shadows are cast along): whether one hides it whole; the parts it misses, and
    /// those wholly ahead of it, go to `settled`. `across`: the face's corners projected
    /// across `d`, filled on first use (empty on entry).
    fn settle_by_covers(
        &self,
        f: &FaceGeom,
        covers: &[u32],
        d: DVec3,
        silhouettes: &mut Vec<Silhouette>,
        settled: &mut Settled,
        across: &mut Vec<DVec2>,
    ) -> bool {
        // beyond the convexity proof's tolerance, which the hull may stand out by
        let margin = 2.0 * self.tol;
        for &part in covers {
            let bit = if part < 64 { 1u64 << part } else { 0 };
            if settled.miss & bit != 0 {
                continue; // settled for the whole part
            }
            let p = part as usize;
            let sphere = self.parts[p].sphere;
            if !reaches(f.centroid, f.radius, sphere.0, sphere.1, d) {
                settled.miss |= bit;
                continue;
            }
            let Some(planes) = &self.parts[p].planes else {
                continue;
            };
            let Some(ahead) = (parts::Planes { planes, sphere }).settle(&f.vertices, d, margin)
            else {
                settled.miss |= bit;
                continue;
            };
            if across.is_empty() {
                let (u, w) = Silhouette::axes(d);
                across.extend(f.vertices.iter().map(|p| DVec2::new(p.dot(u), p.dot(w))));
            }
            let hull = self.silhouette(silhouettes, part, d);
            match hull.cover(ahead, across, margin) {
                Cover::Hidden => return true,
                Cover::Miss => settled.miss |= bit,
                Cover::Ahead if bit != 0 => {
                    settled.ahead.push(part);
                    settled.ahead_bits |= bit;
                }
                Cover::Ahead | Cover::Unknown => {}
            }
        }
        false
    }

    /// The cover test of every other part against part `p` as a whole along unit `d`
    /// ([`parts::PartCover`]): against the convex hull of the corners of `p`'s bounding
    /// box, which holds every face of `p`, so what holds for it holds for each of them.
    fn part_cover(&self, silhouettes: &mut Vec<Silhouette>, p: usize, d: DVec3) -> PartCover {
        let corners = &self.parts[p].corners;
        let (u, w) = Silhouette::axes(d);
        let across = corners.map(|c| DVec2::new(c.dot(u), c.dot(w)));
        let margin = 2.0 * self.tol;
        let (centre, radius) = self.parts[p].sphere;
        let mut out = PartCover {
            dir: Some(d),
            ..PartCover::default()
        };
        for (q, other) in self.parts.iter().enumerate().take(64) {
            let sphere = other.sphere;
            let bit = 1u64 << q;
            if q == p {
                continue;
            }
            if !reaches(centre, radius, sphere.0, sphere.1, d) {
                out.miss |= bit;
                continue;
            }
            let Some(planes) = &other.planes else {
                continue;
            };
            let Some(ahead) = (parts::Planes { planes, sphere }).settle(corners, d, margin) else {
                out.miss |= bit;
                continue;
            };
            match self
                .silhouette(silhouettes, q as u32, d)
                .cover(ahead, &across, margin)
            {
                Cover::Hidden => {
                    out.hidden = true;
                    break;
                }
                Cover::Miss => out.miss |= bit,
                Cover::Ahead | Cover::Unknown => {}
            }
        }
        out
    }

    /// Part `part`'s silhouette along unit `d`, from the direction's cache (computed unless
    /// already held).
    pub(super) fn silhouette<'a>(
        &self,
        silhouettes: &'a mut Vec<Silhouette>,
        part: u32,
        d: DVec3,
    ) -> &'a mut Silhouette {
        if silhouettes.len() < self.parts.len() {
            silhouettes.resize_with(self.parts.len(), Default::default);
        }
        let p = part as usize;
        let hull = &mut silhouettes[p];
        let entry = &self.parts[p];
        hull.along(&entry.convex, &entry.cones, d, self.tol);
        hull
    }
}

#[cfg(test)]
mod tests {
    use super::super::oracle::*;
    use super::*;

    #[test]
    fn parts_said_to_hide_miss_or_lie_ahead_of_a_face_do_so_for_rays_from_it() {
        // What `settle_by_parts` claims of a part along a direction, checked by f64 rays
        // from 64 random points of the face against the part's own triangles (no
        // tolerance: the claims hold by a margin far above rounding): Hidden, every ray
        // meets the part; Miss, none does; Ahead, no ray the other way meets it; Clear, no
        // ray meets any other face at all. The cluttered box-wing has boxes behind which
        // a dish's back and plates hide, beside which others pass, and a dish a plate
        // cuts; its dish is a part of many faces, tested whole first (`part_cover`).
        let vis = visibility_of(cluttered_box_wing());
        let mut rnd = crate::test_rng(5);
        let mut cache = Cache::default();
        let (mut hidden, mut missed, mut ahead, mut clear) = (0, 0, 0, 0);
        let meets_another = |face: usize, p: DVec3, d: DVec3| {
            vis.faces
                .iter()
                .enumerate()
                .any(|(j, o)| j != face && o.pieces.iter().any(|t| ray_meets_triangle(p, d, t)))
        };
        let hits = |part: u32, p: DVec3, d: DVec3| {
            vis.parts[part as usize].convex.faces.iter().any(|&f| {
                vis.faces[f as usize]
                    .pieces
                    .iter()
                    .any(|t| ray_meets_triangle(p, d, t))
            })
        };
        // near ±z too, where the bus lies behind the dish or the dish behind the bus
        let axial = [
            (DVec3::new(0.05, 0.03, 1.0), DVec3::new(-0.04, 0.06, -1.0)),
            (DVec3::new(-0.02, -0.07, -1.0), DVec3::new(0.03, 0.01, 1.0)),
        ];
        for trial in 0..32 {
            let (view, sun) = match axial.get(trial) {
                Some(&(v, s)) => (v.normalize(), s.normalize()),
                None => (random_unit(&mut rnd), random_unit(&mut rnd)),
            };
            cache.reset();
            for (i, g) in vis.faces.iter().enumerate() {
                for side in FaceSide::BOTH {
                    let n = g.normal * side.sign();
                    if (side == FaceSide::Back && !g.two_sided) || n.dot(view) <= 0.0 {
                        continue;
                    }
                    let dirs = PerDirection {
                        view: Some(view),
                        sun: (n.dot(sun) > 0.0).then_some(sun),
                        earth: None,
                    };
                    cache.settled.iter_mut().for_each(Settled::clear);
                    let (dark, unshadowed) = vis.settle_by_parts(&mut cache, i, side, &dirs);
                    let points: Vec<DVec3> = (0..64)
                        .map(|_| {
                            let t = g.pieces[(rnd() * g.pieces.len() as f64) as usize];
                            let (mut a, mut b) = (rnd(), rnd());
                            if a + b > 1.0 {
                                (a, b) = (1.0 - a, 1.0 - b);
                            }
                            t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b
                        })
                        .collect();
                    for k in [Toward::View, Toward::Sun] {
                        let Some(d) = dirs[k] else { continue };
                        let d = above_horizon(d, n);
                        if dark[k] {
                            hidden += 1;
                            let by = (0..vis.parts.len() as u32)
                                .any(|part| points.iter().all(|&p| hits(part, p, d)));
                            assert!(by, "face {i}: said hidden along {d}, but rays pass");
                            continue;
                        }
                        if unshadowed[k] {
                            clear += 1;
                            assert!(
                                points.iter().all(|&p| !meets_another(i, p, d)),
                                "face {i}: said clear along {d}, but a ray meets a face"
                            );
                        }
                        let settled = &cache.settled[k];
                        for part in 0..vis.parts.len().min(64) as u32 {
                            if settled.miss & (1 << part) != 0 {
                                missed += 1;
                                assert!(
                                    points.iter().all(|&p| !hits(part, p, d)),
                                    "face {i}: part {part} said to miss along {d}"
                                );
                            }
                        }
                        for &part in &settled.ahead {
                            ahead += 1;
                            assert!(
                                points.iter().all(|&p| !hits(part, p, -d)),
                                "face {i}: part {part} said to lie ahead along {d}"
                            );
                        }
                    }
                }
            }
        }
        assert!(
            hidden > 100 && missed > 1000 && ahead > 100 && clear > 300,
            "{hidden} hidden, {missed} missed, {ahead} ahead, {clear} clear"
        );
    }
}
