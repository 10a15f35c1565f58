//! The bound behind the patch sums ([`Directions::linear_over`], `SunLight::linear_over`,
//! `EarthLight::linear_over`): where a light says it is linear over a cone of normals,
//! the face-by-face evaluation gives every normal of the cone — its rim included —
//! (n·L)(n·v). The truth is the per-face code itself, which the bound did not produce.

use super::earth_light::EarthLight;
use super::sun_disk::SunLight;
use super::*;
use crate::geometry::Cone;
use crate::radiometry::earth;

/// A light's per-face value f·cosθi·cosθr given the frame and n·v.
type PerFace<'a> = dyn Fn(&Frame, f64) -> f64 + 'a;

/// Normals of `cone`: on its rim (the bound's extreme) and inside it.
fn normals_in(cone: &Cone, rnd: &mut impl FnMut() -> f64) -> Vec<DVec3> {
    let (t1, t2) = crate::geometry::orthonormal_basis(cone.axis);
    // just inside the rim: the cone's half-angle carries a 1e-9 margin
    let half = (cone.half() - 2e-9).max(0.0);
    (0..40)
        .map(|i| {
            let phi = std::f64::consts::TAU * rnd();
            let theta = if i < 20 { half } else { half * rnd().sqrt() };
            let side = t1 * phi.cos() + t2 * phi.sin();
            (cone.axis * theta.cos() + side * theta.sin()).normalize()
        })
        .collect()
}

#[test]
fn a_light_linear_over_a_cone_is_linear_on_every_normal_of_it() {
    // Tolerance 1e-12 relative (of the larger value): the linear form differs from the
    // per-face sum only in the order of its products (~1e-16 each); a light wrongly
    // called linear (a lobe or a glint reaching the cone) misses by far more.
    let mut rnd = crate::test_rng(41);
    let unit = crate::test_unit;
    let brdfs = [
        Brdf::Lambert(Lambert { albedo: 0.3 }),
        Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.5, 0.01, 0.18, 3.6)),
        Brdf::SeedMicrofacet(SeedMicrofacet::new(0.2, 0.3, 0.1, 0.2, 2.5)),
        Brdf::RoughConductor(RoughConductor::new(0.25, 1.4, 7.5, 0.15)),
    ];
    let (mut linear, mut not, mut at_lobe) = (0, 0, 0);
    for trial in 0..3000 {
        let brdf = &brdfs[trial % brdfs.len()];
        let v = unit(&mut rnd);
        let l = unit(&mut rnd);
        let h = half_vector(l, v).unwrap_or(v);
        // a third of the cones about the half vector, where a lobe must rule them out
        let axis = if trial % 3 == 0 {
            (h + 0.05 * unit(&mut rnd)).normalize()
        } else {
            unit(&mut rnd)
        };
        let cone = Cone::new(axis, 0.35 * rnd());
        if cone.min_dot(v) <= 0.0 {
            // the callers' precondition: every normal faces the view
            continue;
        }
        let normals = normals_in(&cone, &mut rnd);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs());
        // the Sun as seen from 1 AU (a disk of 0.27°) or far closer (its reach beyond the
        // lobe's cut), and a sunlit Earth below, 1,000 km up
        let sun_radius = if trial % 2 == 0 { 4.65e-3 } else { 0.08 };
        let sun = SunLight::eclipsed(brdf, l, v, sun_radius, None);
        let earth_at = -unit(&mut rnd) * 7.371e6;
        let shine = earth::sphere(earth_at, l, 0.3, 1361.0);
        let earthlight = EarthLight::new(brdf, &shine, v);
        let dirs = Directions::new(brdf, l, v);
        let lights: [(&str, Option<DVec3>, &PerFace); 3] = [
            (
                "directions",
                dirs.linear_over(&cone).map(|k| k * l),
                &|f, cr| dirs.projected_given(brdf, f, cr),
            ),
            ("sun", sun.linear_over(&cone), &|f, cr| {
                sun.projected_given(f, cr)
            }),
            ("earth", earthlight.linear_over(&cone), &|f, cr| {
                earthlight.projected_given(f, cr)
            }),
        ];
        for (name, lin, value) in lights {
            let Some(big_l) = lin else {
                not += 1;
                at_lobe += usize::from(trial % 3 == 0 && !matches!(brdf, Brdf::Lambert(_)));
                continue;
            };
            linear += 1;
            for &n in &normals {
                let frame = Frame {
                    n,
                    t: n.any_orthonormal_vector(),
                };
                let cr = n.dot(v);
                assert!(cr > 0.0);
                let want = n.dot(big_l) * cr;
                let got = value(&frame, cr);
                assert!(
                    close(got, want),
                    "{name} {brdf:?} cone {cone:?} n {n} l {l} v {v}: {got} against {want}"
                );
            }
        }
    }
    // neither answer vacuous
    assert!(
        linear > 1000 && not > 1000 && at_lobe > 300,
        "{linear} {not} {at_lobe}"
    );
}
