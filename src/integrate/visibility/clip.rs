//! Exact clipping of a face: each blocker (a face cut to the part in front of the face's
//! plane, a convex part's silhouette, or a cap's lid projected back) is projected along
//! the direction onto the face's plane, a convex polygon, and subtracted from the face
//! ([`Region`]). No rays, no tolerance: a few polygon splits per blocker.

use super::blockers::Blocker;
use super::caps::LidState;
use super::parts::Silhouette;
use super::{Cache, Visibility};
use crate::geometry::polygon::{convex_hull, Region};
use crate::integrate::per_direction::{PerDirection, Toward};
use glam::{DVec2, DVec3};

/// Buffers for [`Visibility::exact_area`] ([`Cache::clip`]).
#[derive(Default)]
pub(super) struct ClipScratch {
    /// Seen (and then sunlit) part of the face.
    lit: Region,
    /// Seen and earthlit part.
    earthlit: Region,
    pub(super) shadows: ShadowBuffers,
}

/// Buffers for casting one direction's shadows.
#[derive(Default)]
pub(super) struct ShadowBuffers {
    /// One blocker polygon: projected vertex and height above the face's plane.
    pub(super) clip_in: Vec<(DVec2, f64)>,
    pub(super) shadow: Vec<DVec2>,
    /// A cut convex part's projected corners, and the hull's sort order.
    pub(super) part_points: Vec<DVec2>,
    /// The lid's edges that cut a face (see [`crate::geometry::convex::Lid::clip`]).
    pub(super) lid_edges: Vec<usize>,
    pub(super) hull_order: Vec<u32>,
}

/// Above this many convex pieces per face, shadows are sampled instead of clipped (the
/// 16×48 dish of `examples/scale` needs up to a few hundred).
const MAX_PIECES: usize = 4096;

/// Shadows along directions closer than this cosine to a face's plane are cast as if
/// from this cosine: the projection stretches by 1/cos, and 1e6 keeps f64 coordinates
/// of a few object radii exact to ~1e-10 of the face.
pub(super) const MIN_COS_EXACT: f64 = 1e-6;

/// A direction at or below a face's horizon (side normal `n`) still lights it through the
/// upper part of the Sun's disk: its shadows are those of a direction just above the
/// horizon (the light it brings is already weighted by the BRDF's disk average).
pub(super) fn above_horizon(d: DVec3, n: DVec3) -> DVec3 {
    let c = n.dot(d);
    if c >= MIN_COS_EXACT {
        return d;
    }
    let t = d - n * c;
    let len = t.length();
    if len == 0.0 {
        return n;
    }
    let s = MIN_COS_EXACT;
    t / len * (1.0 - s * s).sqrt() + n * s
}

/// The part of a convex polygon (vertices with heights `h`) at height above `tol`, as
/// its projected vertices in `out` (the projection is affine, so clipping before or after
/// it is the same).
fn clip_above(poly: &[(DVec2, f64)], tol: f64, out: &mut Vec<DVec2>) {
    out.clear();
    let n = poly.len();
    for i in 0..n {
        let (p, hp) = poly[i];
        let (q, hq) = poly[(i + 1) % n];
        let (dp, dq) = (hp - tol, hq - tol);
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp > 0.0 && dq < 0.0) || (dp < 0.0 && dq > 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
}

impl Visibility {
    /// Exact areas (m²) of `face` (side normal `n`) that are seen and sunlit, and seen
    /// and earthlit: the face minus the parallel projections onto its plane of the parts of
    /// the blockers in front of it. A point of the face is hidden along d exactly when the
    /// ray from it along d meets a blocker in front of the plane, i.e. when it lies in
    /// that projection. `None` when the shadows cut it into too many pieces (the caller
    /// samples instead).
    pub(super) fn exact_area(
        &self,
        cache: &mut Cache,
        face: usize,
        n: DVec3,
        dirs: &PerDirection<Option<DVec3>>,
        blockers: &PerDirection<Vec<Blocker>>,
        lids: &PerDirection<LidState>,
    ) -> Option<(f64, f64)> {
        let dirs = dirs.map(|d| d.map(|d| above_horizon(d, n)));
        let x = &mut cache.clip;
        let f = &self.faces[face];
        let plane = FacePlane::new(f.centroid, n);
        x.lit.reset(f.radius);
        let poly = &mut x.shadows.shadow;
        for p in f.polygons() {
            poly.clear();
            poly.extend(p.iter().map(|p| plane.at(*p)));
            x.lit.add_convex(poly);
        }
        let silhouettes = cache.silhouettes.each_mut();
        // one direction's shadows cast on `region`
        let cast = |region: &mut Region,
                    k: Toward,
                    x: &mut ShadowBuffers,
                    silhouettes: &mut Vec<Silhouette>| {
            let Some(d) = dirs[k] else { return Some(()) };
            let mut shadows = Shadows {
                vis: self,
                face,
                d,
                to_plane: ToPlane {
                    plane,
                    along: plane.along(d),
                },
                x,
                silhouettes,
            };
            shadows.cast(
                region,
                lids[k] == LidState::Clip,
                &cache.part_hits[k],
                &cache.settled[k].ahead,
                &blockers[k],
            )
        };
        // view first: both the sunlit and the earthlit parts must be seen
        cast(&mut x.lit, Toward::View, &mut x.shadows, silhouettes.view)?;
        let seen = x.lit.area();
        if x.lit.is_empty() {
            return Some((0.0, 0.0)); // hidden: nothing to light
        }
        let a_earth = if dirs.earth.is_some() {
            x.earthlit.clone_from(&x.lit);
            cast(
                &mut x.earthlit,
                Toward::Earth,
                &mut x.shadows,
                silhouettes.earth,
            )?;
            x.earthlit.area()
        } else {
            seen
        };
        let a_sun = if dirs.sun.is_some() {
            cast(&mut x.lit, Toward::Sun, &mut x.shadows, silhouettes.sun)?;
            x.lit.area()
        } else {
            seen
        };
        Some((a_sun, a_earth))
    }
}

/// A face's plane: 2-D coordinates in it about the face's centroid, and the projection
/// onto it along a direction.
#[derive(Clone, Copy)]
struct FacePlane {
    /// Side normal.
    n: DVec3,
    /// The face's centroid, the origin of the coordinates.
    c: DVec3,
    /// The plane's axes.
    u: DVec3,
    w: DVec3,
}

impl FacePlane {
    fn new(c: DVec3, n: DVec3) -> FacePlane {
        let (u, w) = crate::geometry::orthonormal_basis(n);
        FacePlane { n, c, u, w }
    }

    /// `p`'s coordinates in the plane (its foot along the normal).
    #[inline]
    fn at(&self, p: DVec3) -> DVec2 {
        let r = p - self.c;
        DVec2::new(r.dot(self.u), r.dot(self.w))
    }

    /// How far a point's projection along `d` moves in the plane per metre of height.
    fn along(&self, d: DVec3) -> DVec2 {
        DVec2::new(d.dot(self.u), d.dot(self.w)) / self.n.dot(d)
    }
}

/// The projection along a direction onto a face's plane.
#[derive(Clone, Copy)]
struct ToPlane {
    plane: FacePlane,
    /// [`FacePlane::along`] the direction.
    along: DVec2,
}

impl ToPlane {
    /// `y` projected along the direction onto the plane, and its height above the plane.
    #[inline]
    fn project(&self, y: DVec3) -> (DVec2, f64) {
        let h = self.plane.n.dot(y - self.plane.c);
        (self.plane.at(y) - self.along * h, h)
    }

    /// Appends to `out` the hull `corners` (indices into `vertices`) projected onto the
    /// plane: the projection is affine, so they stay the projected hull's corners, in order.
    fn project_hull(&self, corners: &[u32], vertices: &[DVec3], out: &mut Vec<DVec2>) {
        out.extend(
            corners
                .iter()
                .map(|&j| self.project(vertices[j as usize]).0),
        );
    }
}

/// One direction's shadows cast on a face: the direction, the projection onto the face's
/// plane, and the buffers the shadow polygons are built in.
struct Shadows<'a> {
    vis: &'a Visibility,
    face: usize,
    d: DVec3,
    to_plane: ToPlane,
    x: &'a mut ShadowBuffers,
    /// The direction's silhouettes of the parts.
    silhouettes: &'a mut Vec<Silhouette>,
}

impl Shadows<'_> {
    /// Takes from `region` what the direction's blockers hide: the lid's outside (when
    /// `through_lid`), then the parts that shadow the face whole (`part_hits`), the parts
    /// wholly ahead of it (`ahead`), and the blocker faces. `None` when that cuts it into
    /// too many pieces.
    fn cast(
        &mut self,
        region: &mut Region,
        through_lid: bool,
        part_hits: &[u32],
        ahead: &[u32],
        blockers: &[Blocker],
    ) -> Option<()> {
        if through_lid {
            self.clip_to_lid(region);
            if region.is_empty() {
                return Some(());
            }
        }
        if self.subtract_part_hulls(region, part_hits)? {
            return Some(());
        }
        if self.subtract_parts_ahead(region, ahead)? {
            return Some(());
        }
        self.subtract_blocker_faces(region, blockers)?;
        Some(())
    }

    /// Cuts `region` to what of the face sees out of its own cap: the lid, projected back.
    fn clip_to_lid(&mut self, region: &mut Region) {
        let vis = self.vis;
        let f = &vis.faces[self.face];
        let lid = vis.parts[vis.part_of[self.face] as usize]
            .convex
            .lid
            .as_ref()
            .expect("caps have lids");
        let (to_plane, x) = (self.to_plane, &mut *self.x);
        x.shadow.clear();
        let convex = f.convex();
        if convex.is_empty() {
            x.shadow
                .extend(lid.corners.iter().map(|y| to_plane.project(*y).0));
        } else {
            // Clipped in the lid's plane: the face (convex) seen along d on the lid's
            // plane, cut to the lid, and brought back. Only the few rim edges near it
            // cut, where projecting the whole rim onto the face costs a pass over every
            // corner and edge (measured: a tenth of the fine dish's epoch).
            let d = self.d;
            let mut poly = std::mem::take(&mut x.part_points);
            poly.clear();
            poly.extend(convex.iter().map(|p| lid.meet(*p, d)));
            lid.clip(&mut poly, &mut x.lid_edges, &mut x.shadow);
            x.shadow.clear();
            x.shadow
                .extend(poly.iter().map(|q| to_plane.project(lid.at(*q)).0));
            x.part_points = poly;
        }
        region.intersect_convex(&x.shadow);
    }

    /// Subtracts the convex parts that shadow the face whole (indices into its
    /// `part_shadows`): one hull each, from the part's silhouette — of the corners in
    /// front of the plane and the edges' crossings with it when the plane cuts the part.
    /// `Some(true)` once nothing is left of `region`; `None` at too many pieces.
    fn subtract_part_hulls(&mut self, region: &mut Region, part_hits: &[u32]) -> Option<bool> {
        let vis = self.vis;
        let tol = vis.tol;
        let f = &vis.faces[self.face];
        let (to_plane, x) = (self.to_plane, &mut *self.x);
        for &i in part_hits {
            let ps = &f.part_shadows[i as usize];
            let part = &vis.parts[ps.part as usize].convex;
            let hull = vis.silhouette(self.silhouettes, ps.part, self.d);
            x.shadow.clear();
            if ps.cut {
                x.part_points.clear();
                for &j in hull.near(tol) {
                    let (p, h) = to_plane.project(part.vertices[j as usize]);
                    if h >= -tol {
                        x.part_points.push(p);
                    }
                }
                x.part_points
                    .extend(ps.crossings.iter().map(|y| to_plane.project(*y).0));
                convex_hull(&x.part_points, &mut x.hull_order, &mut x.shadow);
            } else {
                to_plane.project_hull(&hull.corners, &part.vertices, &mut x.shadow);
            }
            if subtract(region, &x.shadow)? {
                return Some(true);
            }
        }
        Some(false)
    }

    /// Subtracts the parts wholly ahead of the face: their silhouettes, projected onto its
    /// plane. `Some(true)` once nothing is left of `region`; `None` at too many pieces.
    fn subtract_parts_ahead(&mut self, region: &mut Region, ahead: &[u32]) -> Option<bool> {
        let vis = self.vis;
        let (to_plane, x) = (self.to_plane, &mut *self.x);
        for &p in ahead {
            let part = &vis.parts[p as usize].convex;
            let hull = vis.silhouette(self.silhouettes, p, self.d);
            x.shadow.clear();
            to_plane.project_hull(&hull.corners, &part.vertices, &mut x.shadow);
            if subtract(region, &x.shadow)? {
                return Some(true);
            }
        }
        Some(false)
    }

    /// Subtracts each blocker face's convex polygons, cut to their part in front of the
    /// face's plane. `Some(true)` once nothing is left of `region`; `None` at too many
    /// pieces.
    fn subtract_blocker_faces(
        &mut self,
        region: &mut Region,
        blockers: &[Blocker],
    ) -> Option<bool> {
        let vis = self.vis;
        let (to_plane, x) = (self.to_plane, &mut *self.x);
        for b in blockers {
            let o = &vis.faces[b.face as usize];
            for p in o.polygons() {
                // project each vertex along d onto the plane; h is its height above it
                x.clip_in.clear();
                x.clip_in.extend(p.iter().map(|y| to_plane.project(*y)));
                clip_above(&x.clip_in, vis.tol, &mut x.shadow);
                if x.shadow.len() >= 3 && subtract(region, &x.shadow)? {
                    return Some(true);
                }
            }
        }
        Some(false)
    }
}

/// Subtracts a convex polygon from `region`: whether nothing is left of it, or `None` at
/// too many pieces.
#[inline]
fn subtract(region: &mut Region, shadow: &[DVec2]) -> Option<bool> {
    region.subtract_convex(shadow, MAX_PIECES).ok()?;
    Some(region.is_empty())
}

#[cfg(test)]
mod tests {
    use super::super::oracle::*;
    use super::super::{Cache, FaceSide, Uncertain};
    use super::*;
    use crate::geometry::builtin;

    #[test]
    fn whole_parts_and_lids_agree_with_face_by_face_clipping() {
        // Two exact computations of every face's seen-and-lit areas: with convex parts cast
        // whole (hulls from silhouettes, cut parts with their crossings), caps decided by
        // their lids and their blockers from `lid_blockers`; and with every possible
        // blocker face clipped on its own. Both are exact up to the clipper's plane
        // tolerance (1e-9 of the object's radius), so they must agree to ~1e-9 of a face's
        // area; 1e-7 of the largest face leaves room for slivers along shadow edges.
        let vis = visibility_of(cluttered_box_wing());
        let cut = vis
            .faces
            .iter()
            .filter(|g| g.part_shadows.iter().any(|p| p.cut))
            .count();
        let whole = vis
            .faces
            .iter()
            .filter(|g| {
                g.part_shadows
                    .iter()
                    .any(|p| !p.cut && (p.sides[0] || p.sides[1]))
            })
            .count();
        let cap_blockers: usize = vis
            .parts
            .iter()
            .flat_map(|p| &p.lid_blockers)
            .map(Vec::len)
            .sum();
        assert!(
            cut > 0 && whole > 0 && cap_blockers > 0,
            "{cut} {whole} {cap_blockers}"
        );
        let largest = vis.faces.iter().map(|g| g.area).fold(0.0, f64::max);
        let mut rnd = crate::test_rng(3);
        let mut unit = || random_unit(&mut rnd);
        let (mut compared, mut shadowed, mut dark, mut overruled) = (0, 0, 0, 0);
        let mut cache = Cache::default();
        for _ in 0..40 {
            let (view, sun, earth) = (unit(), unit(), unit());
            cache.reset();
            for (i, g) in vis.faces.iter().enumerate() {
                for side in FaceSide::BOTH {
                    let n = g.normal * side.sign();
                    if (side == FaceSide::Back && !g.two_sided) || n.dot(view) <= 0.0 {
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
                        continue; // too many pieces for the plain clipper
                    };
                    assert_eq!(rays, 0, "face {i} fell back to rays");
                    let tol = 1e-7 * largest;
                    let b_sun = if dirs.sun.is_some() { b_sun } else { a_sun };
                    if (a_sun - b_sun).abs() > tol || (a_earth - b_earth).abs() > tol {
                        // where the two disagree, rays decide
                        rays_decide(&vis, i, side, &dirs, (a_sun, a_earth), (b_sun, b_earth));
                        overruled += 1;
                    }
                    compared += 1;
                    shadowed += usize::from(b_sun < g.area * (1.0 - 1e-6));
                    dark += usize::from(b_sun <= 1e-12 && dirs.sun.is_some());
                }
            }
        }
        // the comparison must have seen shadows, and faces in full shadow; the plain
        // clipper leaves slivers at grazing views through seams between its blockers,
        // which rays overrule, but seldom
        assert!(
            compared > 5000 && shadowed > 500 && dark > 100,
            "{compared} {shadowed} {dark}"
        );
        assert!(
            overruled * 100 < compared,
            "{overruled} of {compared} overruled"
        );
    }

    #[test]
    fn a_convex_part_cut_by_a_plate_shadows_it_as_a_sphere_does() {
        // A 1,280-face icosphere of radius 1 about the origin, cut by the plane of a plate
        // (z = 0, x from 1.5 to 6, |y| < 3) that it does not touch, under a Sun sweeping
        // down towards the horizon beyond it. The sphere is cast whole from its silhouette
        // and the crossings of its edges with the plane. Checked against clipping face by
        // face (the same polyhedron: to 1e-9 of the plate) and against a true sphere's
        // shadow integrated on a grid (the polyhedron's radius falls short by up to 0.4 %
        // between its vertices, so within 2 %).
        let mut mesh = builtin::icosphere(3, 1.0);
        mesh.material_ids = vec![0; mesh.triangles.len()];
        let (vis, plate) = beside_plate(mesh);
        for deg in [60.0f64, 66.0, 72.0, 78.0, 85.0] {
            let t = deg.to_radians();
            let sun = DVec3::new(-t.sin(), 0.0, t.cos());
            let (a, b) = plate_lit(&vis, plate, sun);
            assert!((a - b).abs() <= 1e-9 * 27.0, "sun at {deg}°: {a} vs {b}");
            // a true sphere's shadow: points whose ray towards the Sun passes within 1 of
            // the centre ahead of them
            let (nx, ny) = (900, 1200);
            let (dx, dy) = (4.5 / nx as f64, 6.0 / ny as f64);
            let mut shadow = 0.0;
            for i in 0..nx {
                for j in 0..ny {
                    let p = DVec3::new(
                        1.5 + (i as f64 + 0.5) * dx,
                        -3.0 + (j as f64 + 0.5) * dy,
                        0.0,
                    );
                    let along = -p.dot(sun);
                    if along > 0.0 && (p + sun * along).length() < 1.0 {
                        shadow += dx * dy;
                    }
                }
            }
            assert!(
                shadow > 0.2,
                "sun at {deg}°: the shadow must fall on the plate"
            );
            let lit = 27.0 - shadow;
            assert!(
                (a - lit).abs() <= 0.02 * shadow,
                "sun at {deg}°: {a} vs sphere {lit}"
            );
        }
    }

    #[test]
    fn a_prism_cut_through_its_middle_shadows_through_its_crossings() {
        // A 20-sided prism (|z| ≤ 1, radius 1) cut halfway by the plate's plane: its
        // vertices lie far from the plane, so the cut shadow's corners near the plate are
        // where its side edges cross the plane. Against clipping face by face, to 1e-9 of
        // the plate, for a Sun sweeping down towards the horizon beyond it.
        let mut mesh = crate::geometry::Mesh::default();
        let k = 20;
        let ring = |j: usize, z: f64| {
            let a = std::f64::consts::TAU * (j % k) as f64 / k as f64;
            DVec3::new(a.cos(), a.sin(), z)
        };
        for j in 0..k {
            let (b0, b1, t0, t1) = (
                ring(j, -1.0),
                ring(j + 1, -1.0),
                ring(j, 1.0),
                ring(j + 1, 1.0),
            );
            builtin::push_quad(&mut mesh, [b0, b1, t1, t0], 0);
            for (a, b, c) in [(DVec3::Z, t0, t1), (-DVec3::Z, b1, b0)] {
                let base = mesh.vertices.len() as u32;
                mesh.vertices.extend([a, b, c]);
                mesh.triangles.push([base, base + 1, base + 2]);
                mesh.material_ids.push(0);
            }
        }
        let (vis, plate) = beside_plate(mesh);
        for deg in [60.0f64, 66.0, 72.0, 78.0, 85.0] {
            let t = deg.to_radians();
            let sun = DVec3::new(-t.sin(), 0.1, t.cos()).normalize();
            let (a, b) = plate_lit(&vis, plate, sun);
            assert!(
                b < 27.0 - 0.2,
                "sun at {deg}°: the shadow must fall on the plate"
            );
            assert!((a - b).abs() <= 1e-9 * 27.0, "sun at {deg}°: {a} vs {b}");
        }
    }
}
