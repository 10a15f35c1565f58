//! The magnitude conventions (docs/physics.md §10) against their closed forms: a
//! Lambertian sphere of 1 m² cross-section, whose irradiance at range R and phase g is
//! E = E_sun · ρ · (2/(3π)) · F(g) / R², F(g) = ((π − g) cos g + sin g)/π (the Lambert
//! sphere's phase law, geometric albedo 2ρ/3), so that
//!
//!   m(g, R)       = m_sun − 2.5 log10(ρ · 2/(3π) · F(g) / R²)
//!   m_1000km      = m(g, 1000 km)
//!   m_standard    = m(90°, 1000 km) = m_sun − 2.5 log10(2ρ/(3π²) · 1e-12)   at every epoch
//!   m_intrinsic   = m(0°, 1000 km)  = m_standard − 2.5 log10 π
//!
//! (issue 21, item 2).

mod common;

use common::*;
use glam::DVec3;
use glint::geometry::builtin::icosphere;
use std::f64::consts::PI;

/// The Lambert sphere's phase law, written here from its definition.
fn phase_law(g: f64) -> f64 {
    ((PI - g) * g.cos() + g.sin()) / PI
}

/// Sun along +x, the observer at phase `g_deg` in the x–y plane at `range` m.
fn at(g_deg: f64, range: f64) -> glint::scene::Epoch {
    let g = g_deg.to_radians();
    epoch(DVec3::X, DVec3::new(g.cos(), g.sin(), 0.0) * range)
}

/// Level-6 icosphere (81 920 facets) of 1 m² cross-section (r = 1/√π), albedo `rho`, at
/// the given (phase °, range m) epochs, in `illumination`'s band.
fn sphere_curve(
    rho: f64,
    epochs: &[(f64, f64)],
    illumination: glint::scene::Illumination,
) -> glint::Response {
    let mut s = scene(
        icosphere(6, 1.0 / PI.sqrt()),
        vec![lambert("s", rho, false)],
        epochs.iter().map(|&(g, r)| at(g, r)).collect(),
    );
    s.illumination = illumination;
    let r = glint::simulate(&s);
    assert_sane(&r);
    r
}

/// Checks every convention of a Lambert sphere's curve against the closed forms.
///
/// Tolerance: the icosphere's facets lie inside the sphere, so its sum differs from the
/// sphere's integral by at most 8/N of E(0) (`tests/analytic.rs` measures that bound per
/// level), N = 81 920: at phases ≤ 120° (F ≥ 0.109) that is ≤ 9e-4 of E, 1.0e-3 mag.
/// The reductions themselves are exact closed forms (rounding only).
fn check_sphere(rho: f64, illumination: glint::scene::Illumination) {
    let m_sun = illumination.sun_magnitude;
    let epochs = [
        (0.0, 1.0e6),
        (20.0, 3.6e7),
        (45.0, 2.0e6),
        (90.0, 1.0e6),
        (90.0, 4.2e7),
        (120.0, 8.0e5),
    ];
    let r = sphere_curve(rho, &epochs, illumination);
    let standard = m_sun - 2.5 * (2.0 * rho / (3.0 * PI * PI) * 1e-12).log10();
    let intrinsic = standard - 2.5 * PI.log10();
    let tol = 1.0e-3;
    for (e, &(g, range)) in r.epochs.iter().zip(&epochs) {
        let exact = m_sun
            - 2.5 * (rho * 2.0 / (3.0 * PI) * phase_law(g.to_radians()) / (range * range)).log10();
        let m = e.magnitude.expect("lit");
        assert!(
            (m - exact).abs() < tol,
            "phase {g}°, range {range}: m {m} vs {exact}"
        );
        let m1 = e.magnitude_1000km.unwrap();
        let exact1 = exact - 5.0 * (range / 1e6).log10();
        assert!(
            (m1 - exact1).abs() < tol,
            "phase {g}°: m_1000km {m1} vs {exact1}"
        );
        let ms = e.magnitude_standard.unwrap();
        assert!(
            (ms - standard).abs() < tol,
            "phase {g}°, range {range}: m_standard {ms} vs {standard}"
        );
        let mi = e.magnitude_intrinsic.unwrap();
        assert!(
            (mi - intrinsic).abs() < tol,
            "phase {g}°: m_intrinsic {mi} vs {intrinsic}"
        );
        // the two reductions differ by 2.5 log10 π exactly (rounding: 1e-12)
        assert!((ms - mi - 2.5 * PI.log10()).abs() < 1e-12);
    }
    // the standard magnitude is one number over the whole curve (all epochs share the
    // facet error's sign and nearly its size: 2e-3 mag between any two)
    let (lo, hi) = r
        .epochs
        .iter()
        .filter_map(|e| e.magnitude_standard)
        .fold((f64::MAX, f64::MIN), |(lo, hi), m| (lo.min(m), hi.max(m)));
    assert!(hi - lo < 2.0 * tol, "standard magnitude spread {lo}..{hi}");
}

/// An interval band (`band_um`, the Sun at −26.74): albedo 1 gives m_standard =
/// −26.74 + 2.926 + 30 = 6.186.
#[test]
fn lambert_sphere_magnitudes_in_an_interval_band() {
    let ill = glint::scene::Illumination {
        earthshine: glint::scene::EarthshineModel::Off,
        ..Default::default()
    };
    assert_eq!(ill.sun_magnitude, -26.74);
    check_sphere(1.0, ill);
    check_sphere(0.2, ill);
}

/// Johnson V (`"band": "V"`, the Sun at −26.76, Willmer 2018): a Lambert sphere of 1 m²
/// cross-section and albedo 1 has m_standard = −26.76 + 2.926 + 30 = 6.166 in V at every
/// epoch, whatever the solar spectrum.
#[test]
fn lambert_sphere_magnitudes_in_v() {
    for spectrum in ["planck", "calspec"] {
        let mut ill = from_json(&serde_json::json!({
            "object": { "mesh": { "builtin": "plate" }, "materials": [ { "name": "surface", "model": "lambert", "albedo": 0.5 } ] },
            "epochs": [ { "t": 0, "sun": [0, 0, 1], "observer": [0, 0, 1e7] } ],
            "illumination": { "band": "V", "solar_spectrum": spectrum, "earthshine": "off" }
        }))
        .illumination;
        assert_eq!(ill.sun_magnitude, -26.76);
        ill.earthshine = glint::scene::EarthshineModel::Off;
        check_sphere(1.0, ill);
        let standard = -26.76 - 2.5 * (2.0 / (3.0 * PI * PI) * 1e-12f64).log10();
        assert!((standard - 6.166).abs() < 5e-4, "{standard}");
    }
}

/// At phase 180° nothing sunlit is seen: the reduced magnitudes are `null` whatever
/// the apparent one (earthshine may still light the object), never infinite.
#[test]
fn no_reduction_at_phase_180() {
    let r = sphere_curve(
        0.5,
        &[(180.0, 1.0e6)],
        glint::scene::Illumination {
            earthshine: glint::scene::EarthshineModel::Off,
            ..Default::default()
        },
    );
    let e = &r.epochs[0];
    assert_eq!(e.magnitude_standard, None);
    assert_eq!(e.magnitude_intrinsic, None);
}
