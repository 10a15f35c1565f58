//! How much of the light a material receives it reflects: the directional-hemispherical
//! albedo ρ(θi) = ∫ f(l, v) cosθr dω_v over the hemisphere (docs/physics.md §6.5).
//!
//! The paper's Eqs. 7–8 are not normalised: its specular term reflects ≈ 4π·k^M·F of a
//! mirror-smooth lobe at normal incidence, so a fitted k^M = 0.4 reflects 5× the light it
//! receives. glint keeps the paper's form (it is what the paper fitted) and reports each
//! material's albedo in the response's summary, with a warning above 1.
//!
//! The integral is split as the model is: the diffuse part over the view hemisphere
//! (Gauss–Legendre in cosθr, even in azimuth), the specular part over the half vector
//! (dω_v = 4 (v·h) dω_h), where a narrow lobe lives: Gauss–Legendre in the half vector's
//! polar angle out to eight lobe slopes (e^−64 of the peak), even in azimuth. No cosine
//! is divided by: f·cosθr is the projected value over cosθi, and θi stays below 90°.

use super::{Brdf, Frame, SeedMicrofacet};
use crate::radiometry::earth::gauss_legendre;
use glam::DVec3;

/// Nodes of the polar-angle rules (Gauss–Legendre).
const POLAR: usize = 48;
/// Azimuths (even spacing: exact for the trigonometric polynomials a lobe is in azimuth).
const AZIMUTHS: usize = 64;
/// Incidence angles scanned for the largest albedo, degrees (the albedo of every model
/// here is largest at normal incidence or towards grazing, where the Fresnel term rises
/// or a lobe's 1/cosθi grows).
const INCIDENCES: [f64; 6] = [0.0, 30.0, 50.0, 65.0, 75.0, 85.0];

/// A material's albedo at normal incidence and its largest over incidence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Albedo {
    /// ρ at normal incidence (dimensionless).
    pub normal: f64,
    /// The largest ρ over the incidences scanned (0°–85°), and where, degrees.
    pub max: f64,
    pub max_at_deg: f64,
}

/// Scans incidence 0°–85° ([`INCIDENCES`]) (and, for an anisotropic model, the light along the face's
/// tangent and across it).
pub fn albedo(brdf: &Brdf) -> Albedo {
    let azimuths: &[f64] = match brdf {
        Brdf::AshikhminShirley(m) if m.nu != m.nv => &[0.0, std::f64::consts::FRAC_PI_2],
        _ => &[0.0],
    };
    let normal = directional(brdf, 0.0, 0.0);
    let (mut max, mut max_at_deg) = (normal, 0.0);
    for &deg in &INCIDENCES[1..] {
        for &phi in azimuths {
            let a = directional(brdf, deg.to_radians(), phi);
            if a > max {
                (max, max_at_deg) = (a, deg);
            }
        }
    }
    Albedo {
        normal,
        max,
        max_at_deg,
    }
}

/// The seed model in its normalised form (`"normalised": true`): `km` is the lobe's
/// directional albedo at normal incidence, so Eq. 8 is evaluated with k^M = km / a, a the
/// albedo at normal incidence of the lobe with k^M = 1 (docs/physics.md §6.6), and the
/// material's albedo at normal incidence is kd + km. `Err(a)` when that lobe reflects
/// (almost) nothing (a ≤ 1e-9: n ≈ 1, k ≈ 0), so km cannot be scaled to an albedo.
/// Parameters as [`SeedMicrofacet::new`] takes them (km = 0 is left as it is).
pub fn normalised_seed(
    kd: f64,
    km: f64,
    slope_rms: f64,
    n: f64,
    k: f64,
) -> Result<SeedMicrofacet, f64> {
    if km <= 0.0 {
        return Ok(SeedMicrofacet::new(kd, km, slope_rms, n, k));
    }
    let unit = Brdf::SeedMicrofacet(SeedMicrofacet::new(0.0, 1.0, slope_rms, n, k));
    let a = directional(&unit, 0.0, 0.0);
    if a <= 1e-9 {
        return Err(a);
    }
    Ok(SeedMicrofacet::new(kd, km / a, slope_rms, n, k))
}

/// Models whose albedo [`remembered`] keeps (the latest asked about).
const REMEMBERED: usize = 64;

/// [`albedo`], remembered for the last [`REMEMBERED`] models asked about in this process:
/// a service asked again and again about the same materials integrates each once. Its
/// six integrations are most of a small request's time (a 2k-triangle object, one
/// epoch).
pub fn remembered(brdf: &Brdf) -> Albedo {
    static SEEN: std::sync::Mutex<Vec<(Brdf, Albedo)>> = std::sync::Mutex::new(Vec::new());
    let known = |seen: &[(Brdf, Albedo)]| seen.iter().find(|(b, _)| b == brdf).map(|&(_, a)| a);
    // a poisoned lock still holds whole entries: each is pushed complete
    if let Some(a) = known(&SEEN.lock().unwrap_or_else(|e| e.into_inner())) {
        return a;
    }
    // integrated outside the lock: requests on other threads wait for nothing
    let a = albedo(brdf);
    let mut seen = SEEN.lock().unwrap_or_else(|e| e.into_inner());
    if known(&seen).is_none() {
        if seen.len() == REMEMBERED {
            seen.remove(0);
        }
        seen.push((brdf.clone(), a));
    }
    a
}

/// ρ(θi) for light at incidence `theta_i` (rad, below π/2) and azimuth `phi_i` from the
/// face's tangent (rad).
pub fn directional(brdf: &Brdf, theta_i: f64, phi_i: f64) -> f64 {
    directional_with(brdf, theta_i, phi_i, POLAR, AZIMUTHS)
}

/// The `polar`-node Gauss–Legendre rule on [0, 1] (node, weight): [`POLAR`]'s found
/// once per process. Its Newton iterations cost about a quarter of what an albedo's
/// integration does, and every request asks for six albedos per material.
fn polar_nodes(polar: usize) -> std::borrow::Cow<'static, [(f64, f64)]> {
    static NODES: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    if polar == POLAR {
        std::borrow::Cow::Borrowed(NODES.get_or_init(|| gauss_legendre(POLAR)))
    } else {
        std::borrow::Cow::Owned(gauss_legendre(polar))
    }
}

/// [`directional`] with `polar` Gauss–Legendre nodes and `azimuths` azimuths.
fn directional_with(brdf: &Brdf, theta_i: f64, phi_i: f64, polar: usize, azimuths: usize) -> f64 {
    let frame = Frame {
        n: DVec3::Z,
        t: DVec3::X,
    };
    let ci = theta_i.cos();
    let l = DVec3::new(theta_i.sin() * phi_i.cos(), theta_i.sin() * phi_i.sin(), ci);
    // (node, weight) on [0, 1]
    let nodes = polar_nodes(polar);
    let d_phi = std::f64::consts::TAU / azimuths as f64;
    // the half vector's azimuth from the plane of incidence: the lobe is mirror-symmetric
    // about that plane for an isotropic model, and for an anisotropic one lit along an
    // axis of its ellipse, so half the circle, counted twice, is the whole
    let symmetric = match brdf {
        Brdf::AshikhminShirley(m) if m.nu != m.nv => (phi_i.sin() * phi_i.cos()).abs() < 1e-12,
        _ => true,
    };
    let (turns, twice) = if symmetric {
        (azimuths / 2, 2.0)
    } else {
        (azimuths, 1.0)
    };
    // the half vector's azimuths' (cos, sin), the same for every polar node
    let azimuth: Vec<(f64, f64)> = (0..turns)
        .map(|k| {
            let (s, c) = (phi_i + (k as f64 + 0.5) * d_phi).sin_cos();
            (c, s)
        })
        .collect();
    // f·cosθr at view v: the projected value over cosθi
    let f_cos = |b: &Brdf, v: DVec3| b.projected(&frame, l, v) / ci;

    // diffuse part over the view hemisphere, in μ = cosθr ∈ (0, 1): dω = dμ dφ; every
    // model's diffuse term depends on cosθi and cosθr only, so one azimuth stands for 2π
    let diffuse = brdf.split(true);
    let mut sum = 0.0;
    for &(mu, wi) in nodes.iter() {
        let v = DVec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
        sum += wi * std::f64::consts::TAU * f_cos(&diffuse, v);
    }

    // specular part over the half vector's polar angle α ∈ (0, α_max)
    let specular = brdf.split(false);
    if let Some((_, slope)) = brdf.lobe_slopes() {
        let a_max = (8.0 * slope).atan().min(std::f64::consts::FRAC_PI_2);
        for &(t, wi) in nodes.iter() {
            let a = a_max * t;
            let (sa, ca) = a.sin_cos();
            for &(cp, sp) in &azimuth {
                let h = DVec3::new(sa * cp, sa * sp, ca);
                let lh = l.dot(h);
                if lh <= 0.0 {
                    continue;
                }
                let v = 2.0 * lh * h - l;
                if v.z <= 0.0 {
                    continue;
                }
                // dω_v = 4 (v·h) dω_h, dω_h = sinα dα dφ; v·h = l·h
                sum += twice * a_max * wi * d_phi * sa * 4.0 * lh * f_cos(&specular, v);
            }
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brdf::{AshikhminShirley, Lambert, RoughConductor, SeedMicrofacet};

    #[test]
    fn a_remembered_albedo_is_the_albedo() {
        // asked twice (the second from the memory) and after more models than it keeps
        let b = Brdf::SeedMicrofacet(SeedMicrofacet::new(0.3, 0.2, 0.15, 1.4, 0.1));
        let a = albedo(&b);
        assert_eq!(remembered(&b), a);
        assert_eq!(remembered(&b), a);
        for i in 0..REMEMBERED + 1 {
            remembered(&Brdf::Lambert(Lambert {
                albedo: 0.01 * (i + 1) as f64,
            }));
        }
        assert_eq!(remembered(&b), a);
        assert_eq!(
            remembered(&Brdf::Lambert(Lambert { albedo: 0.5 })).normal,
            albedo(&Brdf::Lambert(Lambert { albedo: 0.5 })).normal
        );
    }

    #[test]
    fn lambert_reflects_its_albedo_at_every_incidence() {
        // ∫ (a/π) cosθr dω = a exactly: the rule's own error is rounding
        let b = Brdf::Lambert(Lambert { albedo: 0.7 });
        for deg in [0.0, 30.0, 60.0, 85.0] {
            let a = directional(&b, f64::to_radians(deg), 0.0);
            assert!((a - 0.7).abs() < 1e-12, "{deg}: {a}");
        }
    }

    #[test]
    fn a_smooth_seed_lobe_reflects_4_pi_km_fresnel_at_normal_incidence() {
        // Eq. 8 at l = n: ρ = ∫ k^M C V F · 4cosα dω_h = 4π k^M ∫ (C/π) V F cosα dω_h, and
        // C/π is a normalised Beckmann distribution. With δ = 0.01, V = 1 (2cos2α ≥ 1 for
        // α < 30°) and F(β = α) moves by O(δ²) ~ 1e-4 over the lobe: ρ = 4π k^M F(0) to 1e-3.
        let m = SeedMicrofacet::new(0.0, 0.3, 0.01, 1.5, 0.0);
        let f0 = m.fresnel.reflectance(1.0);
        let a = directional(&Brdf::SeedMicrofacet(m), 0.0, 0.0);
        let truth = 4.0 * std::f64::consts::PI * 0.3 * f0;
        assert!((a / truth - 1.0).abs() < 1e-3, "{a} vs {truth}");
    }

    #[test]
    fn a_smooth_rough_conductor_reflects_its_fresnel_term() {
        // Beckmann D with Smith G → 1 for a smooth lobe: ρ(0) = F(0) to O(α²)
        let m = RoughConductor::new(0.01, 1.5, 0.0, 0.0);
        let f0 = m.fresnel.reflectance(1.0);
        let a = directional(&Brdf::RoughConductor(m), 0.0, 0.0);
        assert!((a / f0 - 1.0).abs() < 1e-3, "{a} vs {f0}");
    }

    #[test]
    fn the_rules_have_converged() {
        // doubling both rules moves no model's albedo by more than 1e-3 (relative) at any
        // incidence scanned: the reported albedo is the rules' limit to that. (Not
        // tighter: the V-cavity's min() and the view's horizon are kinks in the integrand,
        // which Gauss–Legendre follows only algebraically; a wide lobe's moves 2e-4.)
        let models = [
            Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.5, 0.01, 0.18, 3.6)),
            Brdf::SeedMicrofacet(SeedMicrofacet::new(0.2, 0.3, 0.5, 1.5, 0.0)),
            Brdf::SeedMicrofacet(SeedMicrofacet::new(0.0, 1.0, 1e-4, 1.5, 0.0)),
            Brdf::RoughConductor(RoughConductor::new(0.3, 0.2, 3.0, 0.1)),
            Brdf::AshikhminShirley(AshikhminShirley::new(0.3, 0.4, 100.0, 10.0)),
        ];
        for b in &models {
            for deg in [0.0, 45.0, 85.0] {
                let t = f64::to_radians(deg);
                let a = directional_with(b, t, 0.3, POLAR, AZIMUTHS);
                let fine = directional_with(b, t, 0.3, 2 * POLAR, 2 * AZIMUTHS);
                assert!(
                    (a / fine - 1.0).abs() < 1e-3,
                    "{b:?} at {deg}°: {a} vs {fine}"
                );
            }
        }
    }

    #[test]
    fn albedo_finds_the_anisotropic_lobe_either_way() {
        // a diffuse-free A–S lobe reflects at most about its R_s (its Fresnel–Schlick
        // rises towards grazing): finite, positive, and the same scan both ways
        let b = Brdf::AshikhminShirley(AshikhminShirley::new(0.0, 0.5, 10.0, 1000.0));
        let a = albedo(&b);
        assert!(a.normal > 0.3 && a.normal < 0.7, "{a:?}");
        assert!(a.max >= a.normal && a.max.is_finite(), "{a:?}");
    }
}
