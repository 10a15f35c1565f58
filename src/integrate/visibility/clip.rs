//! Exact clipping of a face: each blocker (a face cut to the part in front of the face's
//! plane, a convex part's silhouette, or a cap's lid projected back) is projected along
//! the direction onto the face's plane, a convex polygon, and subtracted from the face
//! ([`Region`]). No rays, no tolerance: a few polygon splits per blocker.

use super::blockers::Blocker;
use super::caps::LidState;
use super::direction::{PerDirection, Toward};
use super::parts::Silhouette;
use super::{Cache, Visibility};
use crate::geometry::polygon::{convex_hull, Region};
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
        let (u, w) = crate::geometry::orthonormal_basis(n);
        let c = f.centroid;
        let plane = |p: DVec3| {
            let r = p - c;
            DVec2::new(r.dot(u), r.dot(w))
        };
        x.lit.reset(f.radius);
        let poly = &mut x.shadows.shadow;
        for p in f.polygons() {
            poly.clear();
            poly.extend(p.iter().map(|p| plane(*p)));
            x.lit.add_convex(poly);
        }
        // view first: both the sunlit and the earthlit parts must be seen
        let tol = self.tol;
        let shadows = |region: &mut Region,
                       k: Toward,
                       x: &mut ShadowBuffers,
                       silhouettes: &mut Vec<Silhouette>,
                       part_hits: &[u32],
                       ahead: &[u32]|
         -> Option<()> {
            let Some(d) = dirs[k] else { return Some(()) };
            let along = DVec2::new(d.dot(u), d.dot(w)) / n.dot(d);
            let project = |y: DVec3| {
                let h = n.dot(y - c);
                (plane(y) - along * h, h)
            };
            if lids[k] == LidState::Clip {
                // what of the face sees out of its own cap: the lid, projected back
                let lid = self.parts[self.part_of[face] as usize]
                    .convex
                    .lid
                    .as_ref()
                    .expect("caps have lids");
                x.shadow.clear();
                let convex = f.convex();
                if convex.is_empty() {
                    x.shadow.extend(lid.corners.iter().map(|y| project(*y).0));
                } else {
                    // Clipped in the lid's plane: the face (convex) seen along d on the
                    // lid's plane, cut to the lid, and brought back. Only the few rim edges
                    // near it cut, where projecting the whole rim onto the face costs a
                    // pass over every corner and edge (measured: a tenth of the fine dish's
                    // epoch).
                    let mut poly = std::mem::take(&mut x.part_points);
                    poly.clear();
                    poly.extend(convex.iter().map(|p| lid.meet(*p, d)));
                    lid.clip(&mut poly, &mut x.lid_edges, &mut x.shadow);
                    x.shadow.clear();
                    x.shadow.extend(poly.iter().map(|q| project(lid.at(*q)).0));
                    x.part_points = poly;
                }
                region.intersect_convex(&x.shadow);
                if region.is_empty() {
                    return Some(());
                }
            }
            // Convex parts: one hull each (see `parts`), from the part's silhouette.
            for &i in part_hits {
                let ps = &f.part_shadows[i as usize];
                let part = &self.parts[ps.part as usize].convex;
                let hull = self.silhouette(silhouettes, ps.part, d);
                x.shadow.clear();
                if ps.cut {
                    x.part_points.clear();
                    for &j in hull.near(tol) {
                        let (p, h) = project(part.vertices[j as usize]);
                        if h >= -tol {
                            x.part_points.push(p);
                        }
                    }
                    x.part_points
                        .extend(ps.crossings.iter().map(|y| project(*y).0));
                    convex_hull(&x.part_points, &mut x.hull_order, &mut x.shadow);
                } else {
                    // the projection onto this plane is affine: the same corners, in order
                    x.shadow.extend(
                        hull.corners
                            .iter()
                            .map(|&j| project(part.vertices[j as usize]).0),
                    );
                }
                region.subtract_convex(&x.shadow, MAX_PIECES).ok()?;
                if region.is_empty() {
                    return Some(());
                }
            }
            // Parts wholly ahead of the face: their silhouettes, projected onto its plane.
            for &p in ahead {
                let part = &self.parts[p as usize].convex;
                let hull = self.silhouette(silhouettes, p, d);
                x.shadow.clear();
                x.shadow.extend(
                    hull.corners
                        .iter()
                        .map(|&j| project(part.vertices[j as usize]).0),
                );
                region.subtract_convex(&x.shadow, MAX_PIECES).ok()?;
                if region.is_empty() {
                    return Some(());
                }
            }
            for b in &blockers[k] {
                let o = &self.faces[b.face as usize];
                for p in o.polygons() {
                    // project each vertex along d onto the plane; h is its height above it
                    x.clip_in.clear();
                    x.clip_in.extend(p.iter().map(|y| project(*y)));
                    clip_above(&x.clip_in, self.tol, &mut x.shadow);
                    if x.shadow.len() >= 3 {
                        region.subtract_convex(&x.shadow, MAX_PIECES).ok()?;
                        if region.is_empty() {
                            return Some(());
                        }
                    }
                }
            }
            Some(())
        };
        let PerDirection {
            view: sv,
            sun: ss,
            earth: se,
        } = &mut cache.silhouettes;
        let settled = &cache.settled;
        shadows(
            &mut x.lit,
            Toward::View,
            &mut x.shadows,
            sv,
            &cache.part_hits.view,
            &settled.view.ahead,
        )?;
        let seen = x.lit.area();
        if x.lit.is_empty() {
            return Some((0.0, 0.0)); // hidden: nothing to light
        }
        let a_earth = if dirs.earth.is_some() {
            x.earthlit.clone_from(&x.lit);
            shadows(
                &mut x.earthlit,
                Toward::Earth,
                &mut x.shadows,
                se,
                &cache.part_hits.earth,
                &settled.earth.ahead,
            )?;
            x.earthlit.area()
        } else {
            seen
        };
        let a_sun = if dirs.sun.is_some() {
            shadows(
                &mut x.lit,
                Toward::Sun,
                &mut x.shadows,
                ss,
                &cache.part_hits.sun,
                &settled.sun.ahead,
            )?;
            x.lit.area()
        } else {
            seen
        };
        Some((a_sun, a_earth))
    }
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
