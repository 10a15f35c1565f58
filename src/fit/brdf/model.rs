//! The models that can be fitted: their parameters with the bounds a request's validation
//! takes, the BRDF each set of values builds, and the starting points of a fit.

use super::samples::{evaluate, Sample};
use crate::brdf::albedo::normalised_seed;
use crate::brdf::{AshikhminShirley, Brdf, Lambert, RoughConductor, SeedMicrofacet};
use crate::fit::params::{Bound, Named};

/// One parameter of a model.
#[derive(Debug, Clone, Copy)]
pub struct ParamSpec {
    /// Its name in a request's material.
    pub name: &'static str,
    pub bound: Bound,
}

/// The models that can be fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    Lambert,
    /// The paper's Eqs. 6–8 as it fitted them (`normalised: false`).
    SeedMicrofacet,
    /// `seed-microfacet` with `"normalised": true`: km is the lobe's albedo at normal
    /// incidence ([`crate::brdf::albedo::normalised_seed`]), so kd + km is the material's,
    /// and the fit keeps kd + km ≤ 1.
    SeedNormalised,
    RoughConductor,
    AshikhminShirley,
}

/// Upper bound of a refractive index's parts, as the request's validation takes them.
const INDEX_MAX: f64 = 1e3;

const LAMBERT: &[ParamSpec] = &[ParamSpec {
    name: "albedo",
    bound: Bound::new(0.0, 1.0),
}];
const SEED: &[ParamSpec] = &[
    ParamSpec {
        name: "kd",
        bound: Bound::new(0.0, 1.0),
    },
    ParamSpec {
        name: "km",
        bound: Bound::new(0.0, 1e3),
    },
    ParamSpec {
        name: "slope_rms",
        bound: Bound::new(1e-6, 10.0),
    },
    ParamSpec {
        name: "n",
        bound: Bound::new(1e-6, INDEX_MAX),
    },
    ParamSpec {
        name: "k",
        bound: Bound::new(0.0, INDEX_MAX),
    },
];
/// The normalised form: km is an albedo, within [0, 1] as the request's validation takes
/// it (and kd + km ≤ 1, which the fit keeps by solving for their sum).
const SEED_NORMALISED: &[ParamSpec] = &[
    ParamSpec {
        name: "kd",
        bound: Bound::new(0.0, 1.0),
    },
    ParamSpec {
        name: "km",
        bound: Bound::new(0.0, 1.0),
    },
    ParamSpec {
        name: "slope_rms",
        bound: Bound::new(1e-6, 10.0),
    },
    ParamSpec {
        name: "n",
        bound: Bound::new(1e-6, INDEX_MAX),
    },
    ParamSpec {
        name: "k",
        bound: Bound::new(0.0, INDEX_MAX),
    },
];
const ROUGH: &[ParamSpec] = &[
    ParamSpec {
        name: "alpha",
        bound: Bound::new(1e-6, 10.0),
    },
    ParamSpec {
        name: "n",
        bound: Bound::new(1e-6, INDEX_MAX),
    },
    ParamSpec {
        name: "k",
        bound: Bound::new(0.0, INDEX_MAX),
    },
    ParamSpec {
        name: "kd",
        bound: Bound::new(0.0, 1.0),
    },
];
/// Ashikhmin–Shirley with nu = nv: the samples' relative azimuth cannot tell a lobe's
/// orientation on the face, so the exponent is fitted once and reported as both.
const ASHIKHMIN: &[ParamSpec] = &[
    ParamSpec {
        name: "rd",
        bound: Bound::new(0.0, 1.0),
    },
    ParamSpec {
        name: "rs",
        bound: Bound::new(0.0, 1.0),
    },
    ParamSpec {
        name: "nu",
        bound: Bound::new(0.0, 1e7),
    },
];

impl Model {
    pub const NAMES: &'static str =
        "seed-microfacet, rough-conductor, ashikhmin-shirley or lambert";

    pub fn parse(name: &str) -> Option<Model> {
        match name {
            "lambert" => Some(Model::Lambert),
            "seed-microfacet" => Some(Model::SeedMicrofacet),
            "rough-conductor" => Some(Model::RoughConductor),
            "ashikhmin-shirley" => Some(Model::AshikhminShirley),
            _ => None,
        }
    }

    /// The model's name in a request (`seed-microfacet` for both seed forms).
    pub fn name(self) -> &'static str {
        match self {
            Model::Lambert => "lambert",
            Model::SeedMicrofacet | Model::SeedNormalised => "seed-microfacet",
            Model::RoughConductor => "rough-conductor",
            Model::AshikhminShirley => "ashikhmin-shirley",
        }
    }

    /// The parameters, in the order [`Model::build`] takes them.
    pub fn params(self) -> &'static [ParamSpec] {
        match self {
            Model::Lambert => LAMBERT,
            Model::SeedMicrofacet => SEED,
            Model::SeedNormalised => SEED_NORMALISED,
            Model::RoughConductor => ROUGH,
            Model::AshikhminShirley => ASHIKHMIN,
        }
    }

    /// Whether the model is the normalised seed form (a request's `"normalised": true`).
    pub fn is_normalised(self) -> bool {
        self == Model::SeedNormalised
    }

    /// The model in its normalised form when `normalised`: `seed-microfacet` only; `None`
    /// for another model.
    pub fn with_normalised(self, normalised: bool) -> Option<Model> {
        match (self, normalised) {
            (m, false) => Some(m),
            (Model::SeedMicrofacet | Model::SeedNormalised, true) => Some(Model::SeedNormalised),
            _ => None,
        }
    }

    /// The BRDF of parameters `p` (in [`Model::params`] order): as a request's material
    /// of this model with these values builds it (seed-microfacet in the paper's form,
    /// `normalised: false`, or normalised; rough-conductor with separable shadowing).
    ///
    /// Panics for normalised seed parameters whose lobe reflects nothing (n ≈ 1, k ≈ 0),
    /// which [`Model::try_build`] answers with `None`.
    pub fn build(self, p: &[f64]) -> Brdf {
        self.try_build(p)
            .expect("a normalised seed lobe that reflects something")
    }

    /// [`Model::build`], `None` for normalised seed parameters whose lobe reflects
    /// (almost) nothing, so km cannot be scaled to an albedo.
    pub fn try_build(self, p: &[f64]) -> Option<Brdf> {
        Some(match self {
            Model::Lambert => Brdf::Lambert(Lambert { albedo: p[0] }),
            Model::SeedMicrofacet => {
                Brdf::SeedMicrofacet(SeedMicrofacet::new(p[0], p[1], p[2], p[3], p[4]))
            }
            Model::SeedNormalised => {
                Brdf::SeedMicrofacet(normalised_seed(p[0], p[1], p[2], p[3], p[4]).ok()?)
            }
            Model::RoughConductor => {
                Brdf::RoughConductor(RoughConductor::new(p[0], p[1], p[2], p[3]))
            }
            Model::AshikhminShirley => {
                Brdf::AshikhminShirley(AshikhminShirley::new(p[0], p[1], p[2], p[2]))
            }
        })
    }

    /// Parameters by request name (Ashikhmin–Shirley's exponent as both `nu` and `nv`).
    pub(super) fn named(self, p: &[f64]) -> Named {
        let mut out: Named = self
            .params()
            .iter()
            .zip(p)
            .map(|(s, &v)| (s.name.to_string(), v))
            .collect();
        if self == Model::AshikhminShirley {
            out.insert("nv".into(), p[2]);
        }
        out
    }

    /// Starting points: a grid over the lobe's width (and the index of refraction), with
    /// the scale of the lobe set from the data, so that a narrow specular lobe between
    /// samples is found. Values are inside the bounds; fixed ones are overwritten later.
    pub(super) fn starts(self, samples: &[Sample], fixed: &[Option<f64>]) -> Vec<Vec<f64>> {
        let mut values: Vec<f64> = samples.iter().map(|s| s.brdf_sr).collect();
        values.sort_by(f64::total_cmp);
        let q25 = values[values.len() / 4];
        let diffuse = (std::f64::consts::PI * q25).clamp(1e-3, 0.95);
        let fix = |i: usize, v: f64| fixed[i].unwrap_or(v);
        match self {
            Model::Lambert => vec![vec![fix(0, diffuse.min(0.95))]],
            Model::SeedMicrofacet | Model::SeedNormalised => {
                let kd = fix(0, diffuse);
                let mut out = Vec::new();
                for (n, k) in [(0.2, 3.0), (1.5, 0.0)] {
                    let (n, k) = (fix(3, n), fix(4, k));
                    for slope in [0.003, 0.01, 0.03, 0.1, 0.3, 1.0] {
                        let slope = fix(2, slope);
                        // k^M from the samples the unit lobe lights: the median of
                        // (f − kd/π) / f_lobe over those within a decade of its peak
                        let Some(unit) = self.try_build(&[0.0, 1.0, slope, n, k]) else {
                            continue;
                        };
                        let lobe: Vec<f64> = samples.iter().map(|s| evaluate(&unit, s)).collect();
                        let peak = lobe.iter().copied().fold(0.0, f64::max);
                        let mut ratios: Vec<f64> = samples
                            .iter()
                            .zip(&lobe)
                            .filter(|(_, &g)| g > 0.1 * peak && g > 0.0)
                            .map(|(s, g)| (s.brdf_sr - kd / std::f64::consts::PI).max(0.0) / g)
                            .collect();
                        ratios.sort_by(f64::total_cmp);
                        let km = ratios.get(ratios.len() / 2).copied().unwrap_or(0.1);
                        let km = if self.is_normalised() {
                            // an albedo: kd + km at most 0.98, a start inside the bound
                            fix(1, km.clamp(1e-4, (0.98 - kd).max(1e-4)))
                        } else {
                            fix(1, km.clamp(1e-4, 900.0))
                        };
                        out.push(vec![kd, km, slope, n, k]);
                        if fixed[2].is_some() {
                            break;
                        }
                    }
                    if fixed[3].is_some() && fixed[4].is_some() {
                        break;
                    }
                }
                out
            }
            Model::RoughConductor => {
                let mut out = Vec::new();
                for (n, k) in [(0.2, 3.0), (1.5, 0.5)] {
                    for alpha in [0.01, 0.03, 0.1, 0.3, 0.8] {
                        out.push(vec![fix(0, alpha), fix(1, n), fix(2, k), fix(3, diffuse)]);
                        if fixed[0].is_some() {
                            break;
                        }
                    }
                    if fixed[1].is_some() && fixed[2].is_some() {
                        break;
                    }
                }
                out
            }
            Model::AshikhminShirley => {
                let mut out = Vec::new();
                for rs in [0.05, 0.5] {
                    for exponent in [3.0, 30.0, 300.0, 3e3, 3e4, 3e5] {
                        out.push(vec![fix(0, diffuse), fix(1, rs), fix(2, exponent)]);
                        if fixed[2].is_some() {
                            break;
                        }
                    }
                    if fixed[1].is_some() {
                        break;
                    }
                }
                out
            }
        }
    }
}
