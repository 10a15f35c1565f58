//! A mirror-smooth glint against truths the code does not produce (issue 17, items 1 and
//! 5): the closed form of the reflected Sun's plateau, and brute-force quadrature over
//! the Sun's disk (a fine grid written here, the BRDF evaluated directly for the point-Sun
//! direction of every grid cell).
//!
//! Geometry: the Sun's centre `l`, the observer `v` at phase g. A plate's normal n mirrors
//! `v` into m = 2(n·v)n − v; placing m at offset (x, y)·ρ from `l` — x in the Sun–observer
//! plane, y across it — scans the glint's image. What the observer receives per unit
//! irradiance and area is the disk average of f·cosθi·cosθr,
//! P̄(n) = (1/Ω) ∫_disk P(n; l′, v) dω(l′), Ω = 2π(1 − cos ρ).
//!
//! For a lobe much narrower than the disk, inside the image (m well within the disk) the
//! seed model's P̄ is k^M·F(β)·4π·cosβ/Ω, β = angle(n, v): its C integrates to π over the
//! half vector, dω(l′) = 4 cosβ dω(h), V = 1 at the lobe's peak; to O(δ²).

mod common;

use glam::DVec3;
use glint::brdf::sun_disk::{self, EarthDisk, SunLight};
use glint::brdf::{Brdf, Frame, RoughConductor, SeedMicrofacet};
use glint::geometry::orthonormal_basis;
use glint::radiometry::{eclipse, sun, AU_M};
use std::f64::consts::PI;

/// The Sun's angular radius at 1 AU, rad.
fn rho() -> f64 {
    sun::angular_radius(AU_M)
}

/// The Sun's solid angle.
fn omega(rho: f64) -> f64 {
    2.0 * PI * (1.0 - rho.cos())
}

/// Sun and observer at phase `g_deg`, and the unit vectors in the Sun–observer plane
/// (`e_in`, ⟂ l) and across it (`e_out`).
struct Sky {
    l: DVec3,
    v: DVec3,
    e_in: DVec3,
    e_out: DVec3,
}

fn sky(g_deg: f64) -> Sky {
    let g = g_deg.to_radians();
    // an oblique frame so nothing lines up with the axes
    let q = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
    let l = q * DVec3::Z;
    let v = q * DVec3::new(g.sin(), 0.0, g.cos());
    let e_out = l.cross(v).normalize();
    let e_in = e_out.cross(l);
    Sky { l, v, e_in, e_out }
}

impl Sky {
    /// The direction at gnomonic offset (x, y)·ρ from the Sun's centre.
    fn at(&self, x: f64, y: f64, rho: f64) -> DVec3 {
        (self.l + (self.e_in * x + self.e_out * y) * rho.tan()).normalize()
    }

    /// The plate whose mirror direction is the direction at offset (x, y)·ρ.
    fn plate(&self, x: f64, y: f64, rho: f64) -> Frame {
        let n = (self.at(x, y, rho) + self.v).normalize();
        Frame {
            n,
            t: orthonormal_basis(n).0,
        }
    }
}

/// The brute-force truth (tests/common's `disk_truth`) with the directions behind the
/// Earth dropped.
fn truth(
    brdf: &Brdf,
    slope: f64,
    sky: &Sky,
    frame: &Frame,
    earth: Option<EarthDisk>,
    cells: usize,
) -> f64 {
    common::disk_truth(brdf, slope, (sky.l, rho()), sky.v, frame, cells, |d| {
        earth.is_some_and(|e| d.cross(e.dir).length().atan2(d.dot(e.dir)) < e.radius)
    })
}

/// The seed model's plateau for a plate of normal n (kd = 0): k^M F(β) 4π cosβ / Ω.
fn plateau(km: f64, seed: &SeedMicrofacet, sky: &Sky, frame: &Frame) -> f64 {
    let cos_b = frame.n.dot(sky.v);
    km * seed.fresnel.reflectance(cos_b) * 4.0 * PI * cos_b / omega(rho())
}

fn seed(slope: f64) -> (SeedMicrofacet, Brdf) {
    let m = SeedMicrofacet::new(0.0, 0.5, slope, 0.18, 3.6);
    (m, Brdf::SeedMicrofacet(m))
}

/// Offsets (x, y) in solar radii well inside the image: its centre, and rings at 0.175 ρ
/// and 0.35 ρ in 8 directions. (The disk's image is blurred by the blobs, σ = 0.25 ρ in
/// the reflected direction: within 0.35 ρ of the centre the edge is 2.6 σ away.)
fn inside() -> Vec<(f64, f64)> {
    let mut p = vec![(0.0, 0.0)];
    for r in [0.175, 0.35] {
        for k in 0..8 {
            let a = k as f64 * PI / 4.0 + 0.1;
            p.push((r * a.cos(), r * a.sin()));
        }
    }
    p
}

#[test]
fn a_mirror_glints_plateau_is_the_closed_form_at_every_phase() {
    // Seed model, slope 1e-4 (0.02 ρ): inside the image (m within 0.35 ρ of the centre)
    // the glint is its plateau. The closed form is exact to O(δ²) ≈ 1e-8 of itself, and
    // so is the code's image (a Gaussian lobe's mass times its share in the disk): held
    // to 1e-6 from phase 20° to 175° (done-when: 1 % at 160°). Measured ≤ 9e-8. History:
    // a point Sun's rule gave 0.04× … 2.4× at 160°; 37 blended blobs, ≤ 1.3 %.
    let rho = rho();
    let (m, brdf) = seed(1e-4);
    for g in [20.0, 60.0, 120.0, 150.0, 160.0, 170.0, 175.0] {
        let s = sky(g);
        let light = SunLight::new(&brdf, s.l, s.v, rho);
        let bound = 1e-6;
        let (mut worst, mut centre) = (0.0f64, 0.0);
        for &(x, y) in &inside() {
            let frame = s.plate(x, y, rho);
            let want = plateau(0.5, &m, &s, &frame);
            let got = light.projected(&frame);
            let err = (got / want - 1.0).abs();
            worst = worst.max(err);
            if x == 0.0 && y == 0.0 {
                centre = err;
            }
            assert!(
                err < bound,
                "phase {g}° at ({x:.2}, {y:.2}) ρ: {got:.6e} vs plateau {want:.6e}"
            );
        }
        println!("plateau at phase {g}°: worst {worst:.2e}, centre {centre:.2e}");
    }
}

#[test]
fn the_brute_force_truth_is_the_closed_form_inside_the_image() {
    // The test's own two truths agree (so neither is a typo): at 160° inside the image,
    // to 1e-3 (the grid's cells are 1/33 of the lobe's width; the closed form is exact to
    // O(δ²)).
    let rho = rho();
    let (m, brdf) = seed(1e-4);
    let s = sky(160.0);
    for &(x, y) in &[(0.0, 0.0), (0.3, -0.4)] {
        let frame = s.plate(x, y, rho);
        let a = truth(&brdf, 1e-4, &s, &frame, None, 100);
        let b = plateau(0.5, &m, &s, &frame);
        assert!(
            (a / b - 1.0).abs() < 1e-3,
            "grid {a:.6e} vs closed form {b:.6e}"
        );
    }
}

#[test]
fn exact_specular_at_grazing_incidence() {
    // The plate at exact specular (m on the Sun's centre) at 80° incidence (phase 160°):
    // before the fix +145 % for the seed model at slope 1e-4 and +105 % for a rough
    // conductor at α = 1e-3. Held to 2e-3 of the brute-force truth, twice the truth's own
    // error (its grid against the closed form, above).
    let rho = rho();
    let s = sky(160.0);
    let frame = s.plate(0.0, 0.0, rho);
    for (brdf, slope) in [
        (seed(1e-4).1, 1e-4),
        (
            Brdf::RoughConductor(RoughConductor::new(1e-3, 1.1, 6.8, 0.0)),
            1e-3,
        ),
    ] {
        let want = truth(&brdf, slope, &s, &frame, None, 100);
        let got = SunLight::new(&brdf, s.l, s.v, rho).projected(&frame);
        println!("{}: {got:.5e} vs {want:.5e}", brdf.model_name());
        assert!(
            (got / want - 1.0).abs() < 2e-3,
            "{brdf:?}: {got:.6e} vs truth {want:.6e}"
        );
    }
}

#[test]
fn images_are_flat_at_high_phase() {
    // Slopes 1e-4 … 1e-2 at phase 150°–175°, wherever the disk's image serves (the lobe's
    // width across the disk, slope·cos(g/2), below 0.2 ρ): inside the image (m within
    // 0.35 ρ of the centre). For slopes 1e-4 and 1e-3 the truth is the flat plateau:
    // every value within 2e-3 of the brute-force truth (twice the truth's own error;
    // measured ≤ 7.7e-4), the ratio's max/min within 1.002 (≤ 1.0013). At 1e-2 (2.2 ρ,
    // wider than the disk in the plane) the faces at 170°–175° lie so near grazing
    // (n·v = cos(g/2) ≤ 0.087) that their horizon cuts the lobe, and the 37-point pattern
    // of blobs (σ = 0.25 ρ) serves them, blurring the disk's chord profile: within 5 %
    // (measured 0.9 % at 170°, 4.5 % at 175°, as before the image), max/min within
    // 1.06. (A point Sun's rule ranged over 0.04× … 2.4× at 160°; 37 blended blobs
    // everywhere, ≤ 1.4 %.)
    let rho = rho();
    for slope in [1e-4, 1e-3, 1e-2] {
        let (_, brdf) = seed(slope);
        for g in [150.0, 155.0, 160.0, 165.0, 170.0, 175.0] {
            let s = sky(g);
            if slope * (0.5 * g.to_radians()).cos() >= 0.2 * rho {
                continue; // a smooth rule serves
            }
            let light = SunLight::new(&brdf, s.l, s.v, rho);
            let (mut lo, mut hi, mut worst) = (f64::INFINITY, 0.0f64, 0.0f64);
            for &(x, y) in &inside() {
                let frame = s.plate(x, y, rho);
                let want = truth(&brdf, slope, &s, &frame, None, 100);
                let got = light.projected(&frame);
                let err = (got / want - 1.0).abs();
                worst = worst.max(err);
                // flatness of the code's image, corrected for the truth's slow drift
                // (F and cosβ change across the image)
                lo = lo.min(got / want);
                hi = hi.max(got / want);
                assert!(
                    err < if slope > 5e-3 { 0.05 } else { 2e-3 },
                    "slope {slope:e} phase {g}° at ({x:.2}, {y:.2}) ρ: {got:.6e} vs {want:.6e}"
                );
            }
            println!(
                "slope {slope:e} phase {g}°: worst {worst:.2e}, ripple {:.2e}",
                hi / lo - 1.0
            );
            let ripple = if slope > 5e-3 { 1.06 } else { 1.002 };
            assert!(
                hi / lo < ripple,
                "slope {slope:e} phase {g}°: ripple {}",
                hi / lo
            );
        }
    }
}

#[test]
fn outside_the_disks_edge_the_glint_falls_away() {
    // Slope 1e-4 at 160°: the truth just outside the disk's edge is the lobe's tail
    // (~1e-5 of the peak 0.13 ρ out in the plane, nothing across it, where the lobe is
    // narrower). The code's image is as sharp as the lobe: held to 1e-6 of the peak from
    // the brute-force truth (600 cells a side, its error across the edge about a cell's
    // share of the lobe), at 1.13–2.5 ρ in five directions; and across the edge itself
    // (0.97–1.03 ρ, where the glint falls from the plateau to nothing) to 1e-3 of the
    // peak. (37 blended blobs gave 0.23–0.30 of the peak at 1.13 ρ.)
    let rho = rho();
    let (m, brdf) = seed(1e-4);
    let s = sky(160.0);
    let light = SunLight::new(&brdf, s.l, s.v, rho);
    let peak = plateau(0.5, &m, &s, &s.plate(0.0, 0.0, rho));
    let mut worst: f64 = 0.0;
    for (r, bound) in [
        (0.97, 1e-3),
        (1.0, 1e-3),
        (1.03, 1e-3),
        (1.13, 1e-6),
        (1.5, 1e-6),
        (2.0, 1e-6),
        (2.5, 1e-6),
    ] {
        for (ux, uy) in [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0), (0.6, 0.8)] {
            let frame = s.plate(r * ux, r * uy, rho);
            let got = light.projected(&frame) / peak;
            let want = truth(&brdf, 1e-4, &s, &frame, None, 600) / peak;
            println!("edge r {r} dir ({ux}, {uy}): code {got:.4e}, truth {want:.4e} of peak");
            worst = worst.max((got - want).abs());
            assert!(
                (got - want).abs() < bound,
                "r {r} ρ dir ({ux}, {uy}): {got:.4e} vs truth {want:.4e} of the peak"
            );
        }
    }
    println!("worst |code − truth| {worst:.2e} of the peak");
}

/// The Earth's disk whose limb crosses the Sun's disk through the point at offset
/// `through`·ρ from the centre along the unit vector `toward` (x, y), the Earth on that
/// side; angular radius `radius`.
fn earth_across(s: &Sky, toward: (f64, f64), through: f64, radius: f64) -> EarthDisk {
    let rho = rho();
    let dir = (s.e_in * toward.0 + s.e_out * toward.1).normalize();
    // the Earth's centre at angle through·ρ + radius from the Sun's centre
    let a = through * rho + radius;
    EarthDisk {
        dir: s.l * a.cos() + dir * a.sin(),
        radius,
    }
}

#[test]
fn a_glint_in_penumbra_reflects_only_the_visible_part_of_the_disk() {
    // The Earth's limb across the Sun's disk: half the disk hidden (limb through the
    // centre) and a third hidden (limb 0.27 ρ from the centre) by the Earth seen from LEO
    // (angular radius 1.1 rad: a straight edge) and from beyond GEO (0.15 rad: a curved
    // one), the Earth in the Sun–observer plane, across it and between, at phase 60° and
    // 160°. The light curve multiplies the visible-disk average by E_s·(1 − hidden).
    // Points 0.4–0.6 ρ from the limb's image and within 0.6 ρ of the image's centre
    // (the penumbra pattern's blobs have σ = 0.14 ρ): on the lit side within 2 % of the
    // plateau (measured ≤ 1.7 %), on the hidden side below 1e−2 of it (measured ≤ 5.0e−3;
    // the truth there is 0, and before this fix both sides were 0.5× the plateau). Every
    // value is also held to the brute-force truth over the visible part of the disk
    // within 2 % of the plateau.
    let rho = rho();
    let (m, brdf) = seed(1e-4);
    for g in [60.0, 160.0] {
        let s = sky(g);
        for toward in [(1.0, 0.0), (0.0, 1.0), (-0.6, 0.8)] {
            for radius in [1.1, 0.15] {
                for through in [0.0, 0.27] {
                    let earth = earth_across(&s, toward, through, radius);
                    let ang = s.l.cross(earth.dir).length().atan2(s.l.dot(earth.dir));
                    let hidden = eclipse::hidden_fraction(rho, radius, ang);
                    let light = SunLight::eclipsed(&brdf, s.l, s.v, rho, Some(earth));
                    let mut checked = (0, 0);
                    let (mut dark, mut lit) = (0.0f64, 0.0f64);
                    let (ux, uy) = (
                        toward.0 / toward.0.hypot(toward.1),
                        toward.1 / toward.0.hypot(toward.1),
                    );
                    for past in [-0.6, -0.5, -0.4, 0.4, 0.5, 0.6] {
                        for t in [-0.45, -0.3, -0.15, 0.0, 0.15, 0.3, 0.45] {
                            // `past` ρ beyond the limb towards the Earth, `t` ρ along it
                            let a = through + past;
                            let (x, y) = (a * ux - t * uy, a * uy + t * ux);
                            if x.hypot(y) > 0.6 {
                                continue;
                            }
                            let frame = s.plate(x, y, rho);
                            let top = plateau(0.5, &m, &s, &frame);
                            let got = light.projected(&frame) * (1.0 - hidden);
                            let want = truth(&brdf, 1e-4, &s, &frame, Some(earth), 100);
                            let ctx = format!(
                                "phase {g}° earth {radius} toward {toward:?} limb {through} \
                                 at ({x:.2}, {y:.2}): {got:.4e} truth {want:.4e} plateau {top:.4e}"
                            );
                            assert!((got - want).abs() < 0.02 * top, "{ctx}");
                            if past > 0.0 {
                                assert!(got < 1e-2 * top, "hidden side: {ctx}");
                                dark = dark.max(got / top);
                                checked.0 += 1;
                            } else {
                                assert!((got / top - 1.0).abs() < 0.02, "lit side: {ctx}");
                                lit = lit.max((got / top - 1.0).abs());
                                checked.1 += 1;
                            }
                        }
                    }
                    println!(
                        "phase {g} toward {toward:?} earth {radius} limb {through}: {checked:?} \
                         points, hidden side ≤ {dark:.1e}, lit side within {lit:.1e} of the plateau"
                    );
                    assert!(checked.1 >= 1, "{checked:?}");
                }
            }
        }
    }
}

#[test]
fn per_face_and_per_epoch_agree_in_penumbra() {
    // `projected_eclipsed` (the renderer's) and `SunLight::eclipsed` (the light curve's)
    // are one function.
    let rho = rho();
    let (_, brdf) = seed(1e-4);
    let s = sky(120.0);
    let earth = earth_across(&s, (0.0, 1.0), 0.2, 1.1);
    let light = SunLight::eclipsed(&brdf, s.l, s.v, rho, Some(earth));
    for k in 0..40 {
        let (x, y) = (0.07 * k as f64 - 1.4, 0.3);
        let frame = s.plate(x, y, rho);
        let a = light.projected(&frame);
        let b = sun_disk::projected_eclipsed(&brdf, &frame, s.l, s.v, rho, Some(earth));
        assert!((a - b).abs() <= 1e-12 * a.abs().max(1e-300), "{a} vs {b}");
    }
}

#[test]
fn a_glossy_sphere_at_phase_180_reflects_the_sun_on_its_limb() {
    // Phase 180° exactly: the Sun's disk, centred behind the sphere, lights the facets
    // within ρ of the terminator at grazing, and its reflection there is of the order of
    // the sphere's brightness at phase 0 (a mirror ball scatters alike at every phase).
    // Summed over the level-4 icosphere's facets (Σ area·P̄), the code against the
    // brute-force disk average per facet (a polar grid, 50 × 4000: the same to 1e−4 as
    // 100 × 8000, the lobe resolved along the terminator): within 15 % for the
    // paper's presets (δ 0.01, 0.007), measured −9.0 % for both. (Before this fix the
    // 37 lobes, narrow along the terminator, left gaps there, and tests/stability.rs
    // held the sphere at 180° below 1e−4 of its phase-0 brightness.)
    let rho = rho();
    let l = DVec3::new(0.3, -0.5, 0.81).normalize();
    let v = -l;
    let mesh = glint::geometry::builtin::icosphere(4, 1.0);
    let (a, b) = orthonormal_basis(l);
    for slope in [0.01, 0.007] {
        let (_, brdf) = seed(slope);
        let light = SunLight::new(&brdf, l, v, rho);
        let (mut code, mut truth) = (0.0, 0.0);
        for t in &mesh.triangles {
            let p = t.map(|i| mesh.vertices[i as usize]);
            let c = (p[1] - p[0]).cross(p[2] - p[0]);
            let area = 0.5 * c.length();
            let n = c.normalize();
            let frame = Frame {
                n,
                t: orthonormal_basis(n).0,
            };
            code += area * light.projected(&frame);
            // only faces within ρ of the terminator are lit by the disk and seen
            if n.dot(v) <= 0.0 || n.dot(v) > rho.sin() {
                continue;
            }
            let (nr, nt) = (50, 4000);
            let mut sum = 0.0;
            for i in 0..nr {
                let r = (i as f64 + 0.5) / nr as f64;
                for j in 0..nt {
                    let th = (j as f64 + 0.5) / nt as f64 * 2.0 * PI;
                    let (sr, cr) = (r * rho).sin_cos();
                    let d = l * cr + (a * th.cos() + b * th.sin()) * sr;
                    // the cell's share r·dr·dθ of the disk's π (flat: O(ρ²))
                    sum += brdf.projected(&frame, d, v) * r * 2.0 / (nr * nt) as f64;
                }
            }
            truth += area * sum;
        }
        println!("sphere at 180°, slope {slope}: code {code:.4e}, truth {truth:.4e}");
        assert!(
            truth > 0.0 && (code / truth - 1.0).abs() < 0.15,
            "{code} vs {truth}"
        );
    }
}

#[test]
fn a_penumbra_glint_through_simulate_reflects_the_visible_disk() {
    // End to end: a 1 m² mirror plate (rough conductor, α 1e-4) in penumbra at 400 km, the
    // Earth's limb across the Sun's disk through its centre (half the disk hidden),
    // observers on either side of the limb's image, 0.4–0.5 ρ from it. Each epoch's
    // intensity per E_s is the brute-force average
    // over the part of the disk the Earth leaves (tests/common's `disk_truth` with the
    // Earth's directions dropped) to 2 % of the plateau: the penumbra pattern's spacing
    // (0.17 ρ) is how sharply it draws the limb (its unit test above: lit side within
    // 1.7 %, hidden side ≤ 5e-3). In penumbra the image's own edge stays blurred by the
    // pattern's blobs (σ ≈ 0.14 ρ in the reflected direction): 1.2 ρ from the centre,
    // where the truth is ~0, held to 12 % of the plateau (measured 9 %). The reported eclipse is the
    // hidden fraction of a uniform disk: 1/2, less the limb's curvature's share (the limb
    // a circle of 70° through the Sun's centre: 4e-4), so within 1e-3 of 1/2.
    let rho = rho();
    let alpha = 1e-4;
    let brdf = Brdf::RoughConductor(RoughConductor::new(alpha, 1.1, 6.8, 0.0));
    let l = DVec3::new(0.3, -0.2, 0.9).normalize();
    let v = DVec3::new(-0.6, 0.25, 0.75).normalize();
    let n = (l + v).normalize();
    let (t, _) = orthonormal_basis(n);
    // the Earth below the object at 400 km, its limb through the Sun's centre
    let d: f64 = 6.371e6 + 400e3;
    let a_e = (6.371e6 / d).asin();
    let axis = l.cross(v).normalize();
    let e_dir = glam::DQuat::from_axis_angle(axis, a_e) * l;
    let earth = EarthDisk {
        dir: e_dir,
        radius: a_e,
    };
    // observers: the mirror direction at (x, y)·ρ from the Sun's centre, x towards the
    // Earth (x < 0 the lit half), y along the limb's image
    let toward = (e_dir - l * e_dir.dot(l)).normalize();
    let along = l.cross(toward);
    let mut observers = vec![];
    let mut bounds = vec![];
    for (x, bound) in [
        (-1.2, 0.12),
        (-0.5, 0.02),
        (-0.4, 0.02),
        (0.4, 0.02),
        (0.5, 0.02),
    ] {
        for y in [-0.3, 0.0, 0.3] {
            let m = (l + (toward * x + along * y) * rho).normalize();
            observers.push(2.0 * n.dot(m) * n - m);
            bounds.push(bound);
        }
    }
    let rotate = glam::DQuat::from_rotation_arc(n, DVec3::Z);
    let request = serde_json::json!({
        "object": { "mesh": { "builtin": "plate" },
                    "materials": [ { "name": "surface", "model": "rough-conductor", "alpha": alpha, "n": 1.1, "k": 6.8 } ] },
        "epochs": observers.iter().enumerate().map(|(i, o)| serde_json::json!({
            "t": i as f64,
            "sun": (rotate * l).to_array(),
            "observer": (rotate * *o * 4.0e7).to_array(),
            "earth": (rotate * e_dir * d).to_array(),
        })).collect::<Vec<_>>(),
        "illumination": { "earthshine": "off" }
    });
    let scene = common::from_json(&request);
    let r = glint::simulate(&scene);
    let es = sun::band_irradiance(scene.illumination.band_um, 5900.0, AU_M);
    let frame = Frame { n, t };
    let full = sun_disk::projected(&brdf, &frame, l, 2.0 * n.dot(l) * n - l, rho);
    let mut worst: f64 = 0.0;
    for (i, o) in observers.iter().enumerate() {
        let e = &r.epochs[i];
        assert!(
            (e.eclipse - 0.5).abs() < 1e-3,
            "epoch {i}: eclipse {}",
            e.eclipse
        );
        let got = e.intensity_w_sr / es;
        let want = common::disk_truth(&brdf, alpha, (l, rho), *o, &frame, 400, |dir| {
            dir.cross(earth.dir).length().atan2(dir.dot(earth.dir)) < earth.radius
        });
        if bounds[i] < 0.1 {
            worst = worst.max((got - want).abs() / full);
        }
        assert!(
            (got - want).abs() < bounds[i] * full,
            "epoch {i}: {got:e} vs truth {want:e} (plateau {full:e})"
        );
    }
    println!("penumbra through simulate: worst {worst:.2e} of the plateau inside the image");
}
