//! Reflectance models. Each evaluates the *projected* BRDF f·cosθi·cosθr (sr⁻¹):
//! Eq. 10 multiplies f_r by both cosines, so evaluating the product directly keeps
//! every model finite at grazing angles (docs/physics.md §6) — no division by a cosine.

pub mod albedo;
pub mod ashikhmin_shirley;
pub mod earth_light;
pub mod fresnel;
pub mod lambert;
pub mod rough_conductor;
pub mod seed_microfacet;
pub mod sun_disk;

#[cfg(test)]
mod linear_tests;

pub use ashikhmin_shirley::AshikhminShirley;
pub use lambert::Lambert;
pub use rough_conductor::{RoughConductor, Shadowing};
pub use seed_microfacet::SeedMicrofacet;

use crate::geometry::Cone;
use glam::DVec3;

/// Local geometry of one evaluation. All vectors unit length, in one frame.
#[derive(Debug, Clone, Copy)]
pub struct Frame {
    /// Surface normal (the side being lit and seen).
    pub n: DVec3,
    /// Tangent, for anisotropic models; perpendicular to `n`.
    pub t: DVec3,
}

/// A reflectance model with its parameters. An enum rather than a trait object so the
/// per-face loop stays monomorphic and inlinable.
#[derive(Debug, Clone, PartialEq)]
pub enum Brdf {
    Lambert(Lambert),
    SeedMicrofacet(SeedMicrofacet),
    RoughConductor(RoughConductor),
    AshikhminShirley(AshikhminShirley),
}

impl Brdf {
    /// f·cosθi·cosθr for light arriving from `l` and leaving towards `v` (unit vectors).
    /// Zero when either direction is at or below the surface. Units: sr⁻¹.
    #[inline]
    pub fn projected(&self, frame: &Frame, l: DVec3, v: DVec3) -> f64 {
        let ci = frame.n.dot(l);
        let cr = frame.n.dot(v);
        // below either horizon: no light, and no half vector or Fresnel term to compute
        if ci <= 0.0 || cr <= 0.0 {
            return 0.0;
        }
        Directions::new(self, l, v).projected(self, frame)
    }

    /// The model's name as used in requests.
    pub fn model_name(&self) -> &'static str {
        match self {
            Brdf::Lambert(_) => "lambert",
            Brdf::SeedMicrofacet(_) => "seed-microfacet",
            Brdf::RoughConductor(_) => "rough-conductor",
            Brdf::AshikhminShirley(_) => "ashikhmin-shirley",
        }
    }

    /// A copy with only the diffuse (`diffuse = true`) or only the specular part.
    /// Used by linearity tests and by callers that want the two terms separately.
    pub fn split(&self, diffuse: bool) -> Brdf {
        match self {
            Brdf::Lambert(m) => Brdf::Lambert(Lambert {
                albedo: if diffuse { m.albedo } else { 0.0 },
            }),
            Brdf::SeedMicrofacet(m) => Brdf::SeedMicrofacet(SeedMicrofacet {
                kd: if diffuse { m.kd } else { 0.0 },
                km: if diffuse { 0.0 } else { m.km },
                ..*m
            }),
            Brdf::RoughConductor(m) => Brdf::RoughConductor(RoughConductor {
                kd: if diffuse { m.kd } else { 0.0 },
                ks: if diffuse { 0.0 } else { m.ks },
                ..*m
            }),
            Brdf::AshikhminShirley(m) => Brdf::AshikhminShirley(AshikhminShirley {
                rd: if diffuse { m.rd } else { 0.0 },
                specular: !diffuse && m.specular,
                ..*m
            }),
        }
    }
}

impl Brdf {
    /// Whether the model is a constant times cosθi·cosθr away from its specular lobe
    /// (Lambert everywhere, the seed model where its lobe's term is exactly zero): only
    /// such a model can be linear over a patch ([`Directions::linear_over`]).
    pub fn has_constant_away_from_lobe(&self) -> bool {
        matches!(self, Brdf::Lambert(_) | Brdf::SeedMicrofacet(_))
    }

    /// RMS slope of the narrowest specular lobe, in the Beckmann convention
    /// exp(−tan²α/δ²) of the half vector (dimensionless); `None` without a specular lobe.
    /// Ashikhmin–Shirley's cosⁿ ≈ exp(−nα²/2) gives δ = √(2/n).
    pub fn lobe_slope(&self) -> Option<f64> {
        self.lobe_slopes().map(|(narrowest, _)| narrowest)
    }

    /// RMS slopes of the specular lobe's narrowest and widest directions (equal for an
    /// isotropic lobe), as [`Brdf::lobe_slope`]; `None` without a specular lobe.
    pub fn lobe_slopes(&self) -> Option<(f64, f64)> {
        match self {
            Brdf::Lambert(_) => None,
            Brdf::SeedMicrofacet(m) => (m.km > 0.0).then_some((m.slope_rms, m.slope_rms)),
            Brdf::RoughConductor(m) => (m.ks > 0.0).then_some((m.alpha, m.alpha)),
            Brdf::AshikhminShirley(m) => (m.specular && m.rs > 0.0).then(|| {
                let slope = |n: f64| (2.0 / n.max(1e-300)).sqrt();
                (slope(m.nu.max(m.nv)), slope(m.nu.min(m.nv)))
            }),
        }
    }

    /// Variances of the specular lobe's half vector about its peak, along the face's
    /// tangent t and along n × t, rad²: δ²/2 each for a Beckmann lobe of RMS slope δ,
    /// 1/n_u and 1/n_v for Ashikhmin–Shirley's cosⁿ lobe (the same δ²/2 of its
    /// [`Brdf::lobe_slopes`]); `None` without a specular lobe. The Sun's disk seen through
    /// a narrow lobe ([`sun_disk`]) takes the lobe as a Gaussian of these variances.
    pub fn lobe_variances(&self) -> Option<(f64, f64)> {
        match self {
            Brdf::AshikhminShirley(m) => self
                .lobe_slopes()
                .map(|_| (1.0 / m.nu.max(1e-300), 1.0 / m.nv.max(1e-300))),
            _ => self.lobe_slope().map(|d| (0.5 * d * d, 0.5 * d * d)),
        }
    }

    /// A copy whose specular lobe is at least `slope` wide: a narrower lobe convolved with
    /// a Gaussian of slope √(slope² − δ²) (slopes add in quadrature), which keeps its
    /// normalisation. Used to blur the lobe over the Sun's disk ([`sun_disk`]).
    pub fn widened(&self, slope: f64) -> Brdf {
        let widen = |d: f64| d.max(slope);
        match self {
            Brdf::Lambert(m) => Brdf::Lambert(*m),
            Brdf::SeedMicrofacet(m) => Brdf::SeedMicrofacet(SeedMicrofacet {
                slope_rms: widen(m.slope_rms),
                ..*m
            }),
            Brdf::RoughConductor(m) => Brdf::RoughConductor(RoughConductor {
                alpha: widen(m.alpha),
                ..*m
            }),
            Brdf::AshikhminShirley(m) => {
                let exponent = |n: f64| 2.0 / widen((2.0 / n.max(1e-300)).sqrt()).powi(2);
                Brdf::AshikhminShirley(AshikhminShirley {
                    nu: exponent(m.nu),
                    nv: exponent(m.nv),
                    ..*m
                })
            }
        }
    }
}

/// The part of a microfacet BRDF that depends on the light and view directions only:
/// one per epoch, material and light instead of one per face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Half {
    /// Unit half vector.
    pub h: DVec3,
    /// cos of the angle between the light and the half vector.
    pub cos_b: f64,
    /// Fresnel reflectance at that angle.
    pub fresnel: f64,
}

impl Half {
    /// For light from `l` seen from `v` on microfacets with this Fresnel term; `None`
    /// when `l` and `v` are opposite.
    #[inline]
    pub fn new(l: DVec3, v: DVec3, fresnel: &fresnel::Fresnel) -> Option<Half> {
        let h = half_vector(l, v)?;
        let cos_b = l.dot(h).max(0.0);
        Some(Half {
            h,
            cos_b,
            fresnel: fresnel.reflectance(cos_b),
        })
    }

    /// [`Half::new`] for a specular lobe of weight `weight` (k^M, k_s): `None` when the
    /// weight is 0, which lights nothing.
    #[inline]
    pub fn of_lobe(weight: f64, l: DVec3, v: DVec3, fresnel: &fresnel::Fresnel) -> Option<Half> {
        if weight == 0.0 {
            return None;
        }
        Half::new(l, v, fresnel)
    }
}

/// f·cosθi·cosθr (sr⁻¹) of a microfacet model with a Lambert term: (kd/π)·cosθi·cosθr,
/// plus `lobe(half, n·h)` where its specular lobe can light the face of normal `n`
/// (a half vector, and n·h > 0). `ci`, `cr` > 0 are given by the caller.
#[inline]
fn diffuse_and_lobe(
    kd: f64,
    n: DVec3,
    half: &Option<Half>,
    ci: f64,
    cr: f64,
    lobe: impl FnOnce(&Half, f64) -> f64,
) -> f64 {
    let diffuse = kd * std::f64::consts::FRAC_1_PI * ci * cr;
    let Some(half) = half else {
        return diffuse;
    };
    let cos_h = n.dot(half.h);
    if cos_h <= 0.0 {
        return diffuse;
    }
    diffuse + lobe(half, cos_h)
}

/// The Beckmann distribution of microfacet slopes, exp(−tan²θ/a²)/(norm·a²·cos⁴θ) (a the
/// RMS slope, θ the half vector's angle from the normal): `norm` π for the normalised
/// NDF (the rough conductor's D), 1 for the paper's C. tan²θ is formed as
/// (1 − cos²θ)/cos²θ, and the exponent is tested against −`tail` before the division, so
/// a tiny a at a large θ gives 0, never 0·∞. Both models' one formula.
#[inline]
fn beckmann(cos: f64, a: f64, norm: f64, tail: f64) -> f64 {
    let c2 = cos * cos;
    let a2 = a * a;
    let exponent = -(1.0 - c2) / (c2 * a2);
    if exponent < -tail {
        return 0.0;
    }
    exponent.exp() / (norm * a2 * c2 * c2)
}

/// A BRDF with its light direction `l` and view direction `v` fixed (one epoch): the
/// half vector and the (complex) Fresnel term are computed once, so each face costs
/// only its own cosines and slope distribution.
#[derive(Debug, Clone, Copy)]
pub struct Fixed<'a> {
    brdf: &'a Brdf,
    dirs: Directions,
}

/// A light and a view direction with the face-independent part of a given BRDF.
#[derive(Debug, Clone, Copy)]
pub struct Directions {
    l: DVec3,
    v: DVec3,
    half: Option<Half>,
    /// For models that are a constant times cosθi·cosθr away from their specular lobe.
    away: Option<AwayFromLobe>,
}

/// A model's value where its specular lobe is negligible: there f·cosθi·cosθr is a
/// constant times cosθi·cosθr, which the per-face loops evaluate with one more dot
/// product (n·h) instead of the model (most faces of a glossy object lie far from the
/// glint).
#[derive(Debug, Clone, Copy)]
struct AwayFromLobe {
    /// The diffuse constant, sr⁻¹ (kd/π, albedo/π).
    diffuse: f64,
    /// Unit half vector (zero without a lobe).
    h: DVec3,
    /// (n·h)² below which the lobe's term is exactly zero as the model computes it (it is
    /// zero too where n·h ≤ 0).
    below: f64,
}

impl<'a> Fixed<'a> {
    pub fn new(brdf: &'a Brdf, l: DVec3, v: DVec3) -> Fixed<'a> {
        Fixed {
            brdf,
            dirs: Directions::new(brdf, l, v),
        }
    }

    /// f·cosθi·cosθr (sr⁻¹) of a face with this frame: [`Brdf::projected`] exactly.
    #[inline]
    pub fn projected(&self, frame: &Frame) -> f64 {
        self.dirs.projected(self.brdf, frame)
    }

    /// [`Fixed::projected`] given `cr` = n·v, which the caller already has.
    #[inline]
    pub fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        self.dirs.projected_given(self.brdf, frame, cr)
    }
}

impl Directions {
    /// `l`, `v` and what `brdf` needs of them alone.
    pub fn new(brdf: &Brdf, l: DVec3, v: DVec3) -> Directions {
        let half = match brdf {
            Brdf::SeedMicrofacet(m) => m.half(l, v),
            Brdf::RoughConductor(m) => m.half(l, v),
            Brdf::Lambert(_) | Brdf::AshikhminShirley(_) => None,
        };
        let no_lobe = |diffuse: f64| AwayFromLobe {
            diffuse,
            h: DVec3::ZERO,
            below: f64::INFINITY,
        };
        let away = match brdf {
            Brdf::Lambert(m) => Some(no_lobe(m.albedo * std::f64::consts::FRAC_1_PI)),
            Brdf::SeedMicrofacet(m) => {
                let diffuse = m.kd * std::f64::consts::FRAC_1_PI;
                Some(match half {
                    None => no_lobe(diffuse),
                    Some(half) => AwayFromLobe {
                        diffuse,
                        h: half.h,
                        below: seed_microfacet::lobe_vanishes_below(m.slope_rms),
                    },
                })
            }
            Brdf::RoughConductor(_) | Brdf::AshikhminShirley(_) => None,
        };
        Directions { l, v, half, away }
    }

    /// f·cosθi·cosθr (sr⁻¹) of `brdf` — the one these directions were made for — on a
    /// face with this frame.
    // always inlined: the per-face loops depend on it, and `Brdf::projected` calling it
    // too would otherwise tip the compiler into an out-of-line call
    #[inline(always)]
    pub fn projected(&self, brdf: &Brdf, frame: &Frame) -> f64 {
        self.projected_given(brdf, frame, frame.n.dot(self.v))
    }

    /// [`Directions::projected`] given `cr` = n·v (the per-face loops compute it once for
    /// every light).
    #[inline(always)]
    pub fn projected_given(&self, brdf: &Brdf, frame: &Frame, cr: f64) -> f64 {
        let ci = frame.n.dot(self.l);
        if ci <= 0.0 || cr <= 0.0 {
            return 0.0;
        }
        if let Some(away) = &self.away {
            let ch = frame.n.dot(away.h);
            if ch <= 0.0 || ch * ch < away.below {
                // the model's own value there, bit for bit: its diffuse term plus zero
                let value = away.diffuse * ci * cr;
                return if value > 0.0 { value } else { 0.0 };
            }
        }
        self.model(brdf, frame, ci, cr)
    }

    /// Where this light is linear over a cone of normals that all face the view
    /// direction: `Some(k)` when, for every normal n of `cone`,
    /// [`Directions::projected_given`] is exactly k·(n·l)·(n·v) as it computes it (k ≥ 0,
    /// and 0 when l lies below every normal); `None` when it is not (`l` grazes the cone,
    /// a specular lobe may reach some normal, or a model with no constant away from its
    /// lobe). A patch of faces can then be summed as lᵀ(Σ A n nᵀ)v.
    pub fn linear_over(&self, cone: &Cone) -> Option<f64> {
        if cone.min_dot(self.v) <= 0.0 {
            return None;
        }
        if cone.max_dot(self.l) < 0.0 {
            return Some(0.0);
        }
        if cone.min_dot(self.l) <= 0.0 {
            return None;
        }
        let away = self.away.as_ref()?;
        if away.below.is_finite() {
            // the lobe's term is zero on every face: n·h ≤ 0, or (n·h)² below its cut
            let most = cone.max_dot(away.h);
            if most > 0.0 && most * most >= away.below {
                return None;
            }
        }
        Some(away.diffuse)
    }

    /// The light direction.
    #[inline]
    pub(crate) fn light(&self) -> DVec3 {
        self.l
    }

    /// The model for light from `l` (unit, `ci` = n·l > 0 and `cr` > 0 given), whose half
    /// vector with the view direction is `h`, keeping the Fresnel term of these
    /// directions' own half vector (it varies slowly): how [`sun_disk`] moves one disk
    /// direction's lobe across the Sun–observer plane, light and half vector together.
    #[inline]
    pub(crate) fn model_moved(
        &self,
        brdf: &Brdf,
        frame: &Frame,
        ci: f64,
        cr: f64,
        l: DVec3,
        h: DVec3,
    ) -> f64 {
        let moved = |x: Half| Half {
            h,
            cos_b: l.dot(h).max(0.0),
            ..x
        };
        let value = match brdf {
            Brdf::Lambert(m) => m.projected(ci, cr),
            Brdf::SeedMicrofacet(m) => m.projected_fixed(frame.n, &self.half.map(moved), ci, cr),
            Brdf::RoughConductor(m) => m.projected_fixed(frame.n, &self.half.map(moved), ci, cr),
            Brdf::AshikhminShirley(m) => m.projected(frame, l, self.v, ci, cr),
        };
        if value.is_finite() && value > 0.0 {
            value
        } else {
            0.0
        }
    }

    /// The view direction.
    #[inline]
    pub(crate) fn view(&self) -> DVec3 {
        self.v
    }

    /// The model itself, given both cosines (> 0).
    #[inline]
    fn model(&self, brdf: &Brdf, frame: &Frame, ci: f64, cr: f64) -> f64 {
        let value = match brdf {
            Brdf::Lambert(m) => m.projected(ci, cr),
            Brdf::SeedMicrofacet(m) => m.projected_fixed(frame.n, &self.half, ci, cr),
            Brdf::RoughConductor(m) => m.projected_fixed(frame.n, &self.half, ci, cr),
            Brdf::AshikhminShirley(m) => m.projected(frame, self.l, self.v, ci, cr),
        };
        // A model must never let a NaN out; treat any as no light and keep the sum clean.
        if value.is_finite() && value > 0.0 {
            value
        } else {
            0.0
        }
    }
}

/// Half vector of `l` and `v`, or `None` when they are opposite (phase 180°), where
/// no specular reflection towards the observer is possible.
#[inline]
pub(crate) fn half_vector(l: DVec3, v: DVec3) -> Option<DVec3> {
    let h = l + v;
    let len2 = h.length_squared();
    if len2 < 1e-24 {
        None
    } else {
        Some(h / len2.sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn away_from_the_lobe_the_shortcut_gives_the_models_value_bit_for_bit() {
        // `Directions::projected_given` answers from `AwayFromLobe` for most faces; there
        // it must equal the model's own value exactly (a light curve must not depend on
        // the path). Normals are drawn about the half vector so that many land at the
        // edge where the lobe's exponent crosses −LOBE_TAIL_EXPONENT, and kd = 0 makes the
        // lobe's tiny tail (e^−54 ≈ 4e−24 of its peak) visible instead of lost in the
        // diffuse term.
        let mut rnd = crate::test_rng(31);
        let mut unit = || {
            let d = DVec3::new(2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0, 2.0 * rnd() - 1.0);
            d.normalize_or(DVec3::Z)
        };
        let (mut compared, mut near_edge) = (0, 0);
        for slope in [1e-4, 7e-3, 0.1, 0.5, 1.0] {
            for (kd, km) in [(0.0, 0.5), (0.1, 0.2), (0.3, 0.0)] {
                let seed = Brdf::SeedMicrofacet(SeedMicrofacet::new(kd, km, slope, 0.18, 3.6));
                let lambert = Brdf::Lambert(Lambert { albedo: kd + 0.05 });
                for brdf in [&seed, &lambert] {
                    for _ in 0..400 {
                        let (l, v) = (unit(), unit());
                        let dirs = Directions::new(brdf, l, v);
                        let Some(h) = half_vector(l, v) else { continue };
                        // a normal at the lobe's edge angle α₀ (tan²α₀ = Xδ²) from h,
                        // give or take a little
                        let edge = seed_microfacet::LOBE_TAIL_EXPONENT.sqrt() * slope;
                        let tilt = edge.atan() * (1.0 + 0.02 * (unit().x));
                        let axis = h.cross(unit()).normalize_or(h.any_orthonormal_vector());
                        let n = glam::DQuat::from_axis_angle(axis, tilt) * h;
                        let frame = Frame {
                            n,
                            t: n.any_orthonormal_vector(),
                        };
                        let (ci, cr) = (n.dot(l), n.dot(v));
                        if ci <= 0.0 || cr <= 0.0 {
                            continue;
                        }
                        let fast = dirs.projected_given(brdf, &frame, cr);
                        let model = dirs.model(brdf, &frame, ci, cr);
                        assert_eq!(
                            fast.to_bits(),
                            model.to_bits(),
                            "{brdf:?} n {n} l {l} v {v}: {fast} against {model}"
                        );
                        compared += 1;
                        // a pure lobe within a unit of its cut, on either side
                        let ca2 = n.dot(h).powi(2);
                        let u = (1.0 - ca2) / (ca2 * slope * slope);
                        let edge = (u - seed_microfacet::LOBE_TAIL_EXPONENT).abs() < 1.0;
                        near_edge += usize::from(edge && kd == 0.0 && brdf == &seed);
                    }
                }
            }
        }
        assert!(compared > 5000 && near_edge > 50, "{compared} {near_edge}");
    }
}
