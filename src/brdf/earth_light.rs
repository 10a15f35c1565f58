//! Earthshine on a face: the `sphere` model's beams, and a glint rule for narrow lobes
//! (docs/physics.md §5).
//!
//! Each beam of [`Earthshine`] stands for a patch of the lit Earth about
//! [`Earthshine::patch`] across. A specular lobe narrower than that, evaluated at the
//! beams' directions alone, turns the Earth into a lattice of bright points: its glint
//! spikes where the face's mirror direction meets a beam and vanishes between them. So
//! for a material whose lobe slope is below [`GLINT_BELOW`] patches, the beams carry the
//! diffuse part only and the specular part is integrated per face over the lobe itself:
//! nodes in the half vector h about the face's normal, Gauss–Laguerre in s = tan²α/δ²
//! (the Beckmann lobe is e^−s in it) and even azimuths (32; 8 on a face whose whole lobe
//! is proven to see the lit Earth, where the integrand is smooth in azimuth), each looking
//! up the Earth's radiance along its light direction l = 2(v·h)h − v. With
//! dΩ_l = 4(v·h) dΩ_h and dΩ_h = δ² cos³α / 2 ds dφ,
//!
//! ```text
//! ∫ P_spec(l) L(l) dΩ_l ≈ Σ_ij W_i e^(s_i) · (2π/M) · 2 (v·h) δ² cos³α · P_spec(l_ij) L(l_ij)
//! ```
//!
//! exact for the lobe's own shape, so the glint follows the Earth's radiance (its
//! terminator and limb) at the lobe's resolution. Faces whose mirror direction is beyond
//! the lobe's reach of the Earth's disk skip it (its nodes would all see space). A lobe
//! as wide as the patches or wider is evaluated at the beams like the rest.

use super::{Brdf, Directions, Frame};
use crate::geometry::{orthonormal_basis, Cone};
use crate::radiometry::earth::{gauss_legendre, Earthshine, SunlitEarth};
use crate::radiometry::EARTH_RADIUS_M;
use glam::DVec3;
use std::f64::consts::TAU;

/// A material whose lobe RMS slope is below this many beam patches takes the glint rule.
pub const GLINT_BELOW: f64 = 1.0;
/// Gauss–Laguerre nodes of the glint rule in s = tan²α/δ².
pub const LAGUERRE: usize = 6;
/// Azimuths of the glint rule about the face's normal.
pub const GLINT_AZIMUTHS: usize = 32;
/// Gauss–Legendre points on a lit piece of an azimuth that an edge of the lit Earth cuts.
pub const PIECE_POINTS: usize = 6;
/// Spacing in u = tanα/δ of the probes that look for an edge of the lit Earth along an
/// azimuth of the glint rule: a crescent narrower than this (in the lobe's units) can
/// slip between them.
pub const PROBE_STEP: f64 = 0.1;
/// Width in u = tanα/δ to which an edge of the lit Earth is found along an azimuth: a
/// probe step halved 40 times (a lobe's integral moves by about this share).
const EDGE_WIDTH: f64 = PROBE_STEP / (1u64 << 40) as f64;
/// Most steps of the Illinois method for one edge ([`Glint::edge`]).
const ILLINOIS_STEPS: usize = 60;
/// Most edge crossings kept along one azimuth.
const MAX_CUTS: usize = 16;
/// Runs of an azimuth's probes that a bound may answer whole ([`over_earth`]).
const SPANS: usize = 4;
/// Fewest beams for which a face's earthshine is bounded over them all at once
/// ([`AllBeams`]): the paper's single beam is cheaper evaluated.
const MIN_BEAMS: usize = 4;

/// Earthshine on the faces of one material at one epoch.
#[derive(Debug, Clone)]
pub struct EarthLight<'a> {
    brdf: &'a Brdf,
    /// What the beams evaluate when not the whole BRDF (its diffuse part).
    beam_brdf: Option<Brdf>,
    beams: Vec<(f64, Directions)>,
    /// Bounds over all the beams at once, when every beam's model is constant away from
    /// its lobe.
    all: Option<AllBeams>,
    glint: Option<Glint>,
}

/// Every beam at once: the cones holding their light directions and their lobes' half
/// vectors, and their sum. A face that every beam lights and no beam's lobe reaches
/// (most faces that see the lit Earth) takes Σ_b E_b k_b (n·l_b)(n·v) = (n·T)(n·v) from
/// the one vector T = Σ_b E_b k_b l_b, and a face that no beam lights takes nothing,
/// instead of a BRDF per beam: the `sphere` model's 48–240 beams were most of an
/// epoch on a finely meshed object. The same holds for a cone of normals (patch sums).
#[derive(Debug, Clone)]
struct AllBeams {
    /// Holds every beam's light direction (widened past rounding: a bound from it holds
    /// for each beam's n·l as computed).
    lights: Cone,
    /// Holds every lobe's half vector; `None` when no beam has a lobe.
    halves: Option<Cone>,
    /// The two cones' half-angles, rad (what a cone of normals is widened by).
    lights_half: f64,
    halves_half: f64,
    /// The smallest (n·h)² under which a beam's lobe is zero, over the beams with one.
    below: f64,
    /// T = Σ_b E_b k_b l_b (k_b the diffuse constant, sr⁻¹), W/(m²·sr), summed as
    /// [`EarthLight::linear_over`] sums it beam by beam.
    sum: DVec3,
}

impl AllBeams {
    /// The bounds, when every beam's model is constant away from its lobe and there are
    /// enough beams for them to pay (a bound costs about what a beam does).
    fn of(beams: &[(f64, Directions)]) -> Option<AllBeams> {
        if beams.len() < MIN_BEAMS {
            return None;
        }
        let lobe = |d: &Directions| {
            d.away
                .as_ref()
                .filter(|a| a.below.is_finite() && a.h != DVec3::ZERO)
                .map(|a| a.h)
        };
        let (mut sum, mut axis, mut h_axis) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        let mut below = f64::INFINITY;
        for (irradiance, d) in beams {
            let away = d.away.as_ref()?;
            sum += (irradiance * away.diffuse) * d.light();
            axis += d.light();
            if let Some(h) = lobe(d) {
                h_axis += h;
                below = below.min(away.below);
            }
        }
        let lights = Cone::about(axis.try_normalize()?, beams.iter().map(|(_, d)| d.light()));
        let halves = if below.is_finite() {
            let hs = beams.iter().filter_map(|(_, d)| lobe(d));
            Some(Cone::about(h_axis.try_normalize()?, hs))
        } else {
            None
        };
        Some(AllBeams {
            lights,
            lights_half: lights.half(),
            halves_half: halves.map_or(0.0, |h| h.half()),
            halves,
            below,
            sum,
        })
    }

    /// Is every beam above every normal of `cone` (`Some(true)`), below every one
    /// (`Some(false)`), with no lobe reaching any of them either way; `None` when the
    /// bounds cannot tell.
    fn over(&self, cone: &Cone) -> Option<bool> {
        // the normals against the lights (and the half vectors): the cone widened by the
        // lights' (the halves') half-angle, against their axis
        let half = cone.half();
        self.verdict(
            Cone::new(cone.axis, half + self.lights_half).dots(self.lights.axis),
            |h| Cone::new(cone.axis, half + self.halves_half).max_dot(h.axis),
        )
    }

    /// [`AllBeams::over`] for one normal `n`.
    #[inline]
    fn at(&self, n: DVec3) -> Option<bool> {
        self.verdict(self.lights.dots(n), |h| h.max_dot(n))
    }

    /// The answer of [`AllBeams::over`] and [`AllBeams::at`] from the least and largest
    /// n·l over the beams and the normals, and `lobe(halves)`: the largest n·h.
    #[inline]
    fn verdict(&self, (least, most): (f64, f64), lobe: impl FnOnce(&Cone) -> f64) -> Option<bool> {
        if least <= 0.0 {
            return (most < 0.0).then_some(false);
        }
        let clear = self.halves.as_ref().is_none_or(|h| {
            let most = lobe(h);
            most <= 0.0 || most * most < self.below
        });
        clear.then_some(true)
    }
}

#[derive(Debug, Clone)]
struct Glint {
    spec: Brdf,
    slope: f64,
    earth: SunlitEarth,
    /// What [`over_earth`] needs of `earth`, computed once.
    bounds: EarthBounds,
    v: DVec3,
    /// cos of the largest angle between the face's mirror direction and the Earth's
    /// centre at which a node can still see the Earth.
    cos_reach: f64,
    /// The largest tilt of h from the face's normal that a probe reaches, rad: the
    /// probes' light directions lie within twice it of the mirror direction.
    probe_tilt: f64,
    /// Twice it: the cone about the mirror direction that holds every probe's light.
    lobe: Spread,
    /// The probes' runs: run i from probe `ends[i]` to `ends[i + 1]` (`ends[SPANS]`: the
    /// last probe, [`probes`]).
    ends: [usize; SPANS + 1],
    /// The arcs an azimuth's probes are bounded on: each run of them ([`SPANS`]), then
    /// all of them. They depend on the lobe's slope alone, so they are found once per
    /// epoch and material, not per face and azimuth.
    arcs: [Arc; SPANS + 1],
}

/// The tilts of h from n, α = atan(δ u), of a run of probes from u_a to u_b, as
/// [`Glint::projected_given`] bounds their light directions: tan of the middle tilt, cos
/// and sin of the last, and the run's width α_b − α_a (as the half-angle of a cone that
/// [`over_earth`] reads).
#[derive(Debug, Clone, Copy)]
struct Arc {
    tan_mid: f64,
    cos_b: f64,
    sin_b: f64,
    width: Spread,
}

impl Arc {
    fn new(slope: f64, ua: f64, ub: f64) -> Arc {
        let (aa, ab) = ((slope * ua).atan(), (slope * ub).atan());
        Arc {
            tan_mid: (0.5 * (aa + ab)).tan(),
            cos_b: ab.cos(),
            sin_b: ab.sin(),
            width: Spread::new(ab - aa),
        }
    }
}

/// (sin, cos) of the glint rule's azimuths.
fn glint_azimuths() -> &'static [(f64, f64); GLINT_AZIMUTHS] {
    static AZ: std::sync::OnceLock<[(f64, f64); GLINT_AZIMUTHS]> = std::sync::OnceLock::new();
    AZ.get_or_init(|| {
        let step = TAU / GLINT_AZIMUTHS as f64;
        std::array::from_fn(|j| (step * (j as f64 + 0.5)).sin_cos())
    })
}

/// Azimuths of the glint rule on a face whose every probe is proven to find the lit
/// Earth ([`Glint::lit_throughout`]).
pub const LIT_AZIMUTHS: usize = 8;

/// (sin, cos) of [`LIT_AZIMUTHS`] even azimuths.
fn lit_azimuths() -> &'static [(f64, f64); LIT_AZIMUTHS] {
    static AZ: std::sync::OnceLock<[(f64, f64); LIT_AZIMUTHS]> = std::sync::OnceLock::new();
    AZ.get_or_init(|| {
        let step = TAU / LIT_AZIMUTHS as f64;
        std::array::from_fn(|j| (step * (j as f64 + 0.5)).sin_cos())
    })
}

/// What every probe of a face's lobe finds ([`over_earth`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Whole {
    /// The lit Earth along every probe: the plain rule on every azimuth.
    Lit,
    /// Space or the Earth's night side along every probe: nothing.
    Dark,
    /// Either, or not proven: probed azimuth by azimuth.
    Mixed,
}

impl<'a> EarthLight<'a> {
    /// The beams of `shine` on `brdf`, seen from `v`.
    pub fn new(brdf: &'a Brdf, shine: &Earthshine, v: DVec3) -> EarthLight<'a> {
        let glint = match (brdf.lobe_slope(), &shine.sunlit) {
            (Some(slope), Some(earth))
                if slope > 0.0 && slope < GLINT_BELOW * shine.patch && !shine.beams.is_empty() =>
            {
                let tan_max = slope * laguerre().last().map_or(0.0, |n| n.0).sqrt();
                let probe_tilt = (slope * probes() as f64 * PROBE_STEP).atan();
                let reach = earth.cos_cap.clamp(-1.0, 1.0).acos() + 2.0 * tan_max.atan();
                let span_ends: [usize; SPANS + 1] = std::array::from_fn(|i| i * probes() / SPANS);
                Some(Glint {
                    spec: brdf.split(false),
                    slope,
                    earth: *earth,
                    bounds: EarthBounds::of(earth),
                    v,
                    cos_reach: if reach >= std::f64::consts::PI {
                        -1.0
                    } else {
                        reach.cos()
                    },
                    probe_tilt,
                    lobe: Spread::new(2.0 * probe_tilt),
                    ends: span_ends,
                    arcs: std::array::from_fn(|i| {
                        // the runs, then all the probes (from ends[0] = 0 to ends[SPANS])
                        let (a, b) = if i < SPANS {
                            (span_ends[i], span_ends[i + 1])
                        } else {
                            (span_ends[0], span_ends[SPANS])
                        };
                        Arc::new(slope, a as f64 * PROBE_STEP, b as f64 * PROBE_STEP)
                    }),
                })
            }
            _ => None,
        };
        let beam_brdf = glint.as_ref().map(|_| brdf.split(true));
        let beams: Vec<(f64, Directions)> = shine
            .beams
            .iter()
            .map(|b| {
                (
                    b.irradiance,
                    Directions::new(beam_brdf.as_ref().unwrap_or(brdf), b.dir, v),
                )
            })
            .collect();
        let all = AllBeams::of(&beams);
        EarthLight {
            brdf,
            beam_brdf,
            beams,
            all,
            glint,
        }
    }

    /// Σ f·cosθi·cosθr·E over the earthshine, W/(m²·sr) per m² of face, given `cr` = n·v.
    #[inline]
    pub fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        let beams = self.beams_given(frame, cr);
        match &self.glint {
            Some(g) if cr > 0.0 => beams + g.projected_given(frame, cr),
            _ => beams,
        }
    }

    /// The beams' part of [`EarthLight::projected_given`]: at once where [`AllBeams`]
    /// decides the face, else beam by beam.
    #[inline]
    fn beams_given(&self, frame: &Frame, cr: f64) -> f64 {
        if let Some(all) = self.all.as_ref().filter(|_| cr > 0.0) {
            match all.at(frame.n) {
                Some(true) => return cr * frame.n.dot(all.sum),
                Some(false) => return 0.0,
                None => {}
            }
        }
        self.beams_one_by_one(frame, cr)
    }

    /// Σ_b E_b f_b·cosθi·cosθr, each beam's BRDF evaluated.
    fn beams_one_by_one(&self, frame: &Frame, cr: f64) -> f64 {
        let brdf = self.beam_brdf.as_ref().unwrap_or(self.brdf);
        self.beams
            .iter()
            .map(|(irradiance, d)| irradiance * d.projected_given(brdf, frame, cr))
            .sum()
    }

    /// The earthshine's f·cosθi·cosθr over a cone of normals that all face the view,
    /// where it is linear: `Some(L)` with [`EarthLight::projected_given`] = (n·L)(n·v)
    /// for every normal n of `cone` (L = Σ E_b k_b l_b over the beams above the cone;
    /// zero when none is), `None` where a beam grazes the cone, a lobe may touch it, or
    /// the glint rule may reach one of its normals.
    pub fn linear_over(&self, cone: &Cone) -> Option<DVec3> {
        if let Some(g) = &self.glint {
            let v = g.v;
            // the rule answers 0 while the mirror direction (2(n·v)n − v) stays out of
            // its reach of the Earth's centre c: (2(n·v)n − v)·c ≤ this where n·v > 0
            let c = g.earth.centre_dir;
            let most = 2.0 * cone.max_dot(v) * cone.max_dot(c).max(0.0) - v.dot(c);
            if most >= g.cos_reach {
                return None;
            }
        }
        if let Some(all) = &self.all {
            // what every beam's own test would find, at once
            if let (Some(lit), Some((_, d))) = (all.over(cone), self.beams.first()) {
                if cone.min_dot(d.v) <= 0.0 {
                    return None;
                }
                return Some(if lit { all.sum } else { DVec3::ZERO });
            }
        }
        self.beams_linear_one_by_one(cone)
    }

    /// The beams' L of [`EarthLight::linear_over`], each beam's own test made.
    fn beams_linear_one_by_one(&self, cone: &Cone) -> Option<DVec3> {
        let mut sum = DVec3::ZERO;
        for (irradiance, d) in &self.beams {
            sum += (irradiance * d.linear_over(cone)?) * d.light();
        }
        Some(sum)
    }

    /// [`EarthLight::projected_given`] computing n·v.
    pub fn projected(&self, frame: &Frame, v: DVec3) -> f64 {
        self.projected_given(frame, frame.n.dot(v))
    }
}

impl Glint {
    fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        let n = frame.n;
        let mirror = 2.0 * cr * n - self.v;
        if mirror.dot(self.earth.centre_dir) < self.cos_reach {
            return 0.0;
        }
        // the probes' light directions lie within twice the largest tilt of the mirror
        // direction (reflecting v about h rather than n turns it by twice their angle);
        // every h of the lobe faces the viewer when n·v > sin(tilt)
        let tilt = self.probe_tilt;
        let whole = over_earth(&self.bounds, mirror, self.lobe, cr > tilt.sin());
        if whole == Whole::Dark {
            return 0.0;
        }
        let (t1, t2) = orthonormal_basis(n);
        let nodes = laguerre();
        if whole == Whole::Lit {
            return self.lit_throughout(frame, n, (t1, t2));
        }
        let step = TAU / GLINT_AZIMUTHS as f64;
        let ends = &self.ends;
        let probes = ends[SPANS];
        let mut sum = 0.0;
        for &(sp, cp) in glint_azimuths() {
            let across = t1 * cp + t2 * sp;
            // the integrand at u = √s
            let at = |u: f64| self.density(frame, n, across, u);
            // the rule where the Earth is lit all along the azimuth
            let plain = || self.along(frame, n, across);
            // Along one azimuth h turns about n × across, and l with it by twice the
            // angle: the light directions of the probes from u_a to u_b lie on an arc
            // within α_b − α_a of its middle one (tan α = δ u).
            let arc = |a: &Arc| {
                let h = (n + across * a.tan_mid).normalize();
                let middle = 2.0 * self.v.dot(h) * h - self.v;
                let facing = cr * a.cos_b > self.v.dot(across).abs() * a.sin_b;
                over_earth(&self.bounds, middle, a.width, facing)
            };
            let along = match whole {
                Whole::Mixed => arc(&self.arcs[SPANS]),
                known => known,
            };
            match along {
                Whole::Dark => continue,
                Whole::Lit => {
                    // what the probes would find: lit throughout
                    sum += plain();
                    continue;
                }
                Whole::Mixed => {}
            }
            let lit_at = |u: f64| self.lit(n, across, u);
            // the probes in runs, each answered whole where the bound can (an edge lies
            // in one run or two; the others need no probing)
            let spans: [Whole; SPANS] = std::array::from_fn(|i| arc(&self.arcs[i]));
            // probe k, at the end of the step from k − 1 in run `span`
            let probe = |k: usize, span: usize| match spans[span] {
                Whole::Lit => true,
                Whole::Dark => false,
                Whole::Mixed => lit_at(k as f64 * PROBE_STEP),
            };
            // is the Earth lit along this azimuth, probed every PROBE_STEP in u = √s
            // out to the last node's reach: if so throughout, the plain rule
            let mut cuts = [0.0f64; MAX_CUTS];
            let mut ncut = 1;
            let first = probe(0, 0);
            let mut prev = first;
            let mut span = 0;
            for k in 1..=probes {
                let u = k as f64 * PROBE_STEP;
                if k > ends[span + 1] {
                    span += 1;
                }
                let now = probe(k, span);
                if now != prev && ncut < MAX_CUTS {
                    // an edge (limb or terminator): find it in u
                    cuts[ncut] = self.edge(n, across, u - PROBE_STEP, u, prev);
                    ncut += 1;
                }
                prev = now;
            }
            if ncut == 1 {
                if first {
                    sum += plain();
                }
                continue;
            }
            // integrate the lit pieces on their own
            let mut now = first;
            for (c, &ua) in cuts[..ncut].iter().enumerate() {
                if now {
                    if let Some(&ub) = cuts[..ncut].get(c + 1) {
                        // a lit piece [ua, ub] in u: Gauss–Legendre on ∫ f(u²) 2u du
                        sum += legendre()
                            .iter()
                            .map(|&(x, w)| {
                                let u = ua + (ub - ua) * x;
                                w * (ub - ua) * 2.0 * u * at(u).unwrap_or(0.0)
                            })
                            .sum::<f64>();
                    } else {
                        // lit from ua on: Gauss–Laguerre shifted to s = ua² + s'
                        sum += nodes
                            .iter()
                            .map(|&(s, w)| w * at((ua * ua + s).sqrt()).unwrap_or(0.0))
                            .sum::<f64>();
                    }
                }
                now = !now;
            }
        }
        sum * step
    }

    /// The rule on a face whose whole lobe sees the lit Earth. With no edge in it the
    /// integrand is smooth and periodic in azimuth, and the even rule is exact for its
    /// Fourier terms below the count; those fall off as powers of the lobe's tilt (a few
    /// degrees), so [`LIT_AZIMUTHS`] do what 32 do where edges cut the lobe (within
    /// 1e-6 of the glint: `a_lobe_that_sees_the_lit_earth_throughout_takes_eight_azimuths`).
    fn lit_throughout(&self, frame: &Frame, n: DVec3, (t1, t2): (DVec3, DVec3)) -> f64 {
        let az = lit_azimuths();
        let step = TAU / az.len() as f64;
        let mut sum = 0.0;
        for &(sp, cp) in az {
            sum += self.along(frame, n, t1 * cp + t2 * sp);
        }
        sum * step
    }

    /// The plain rule along the azimuth `across` (every node lit or not by itself):
    /// Gauss–Laguerre in s over the integrand [`Glint::density`].
    #[inline]
    fn along(&self, frame: &Frame, n: DVec3, across: DVec3) -> f64 {
        laguerre()
            .iter()
            .zip(laguerre_roots())
            .map(|(&(_, w), &u)| w * self.density(frame, n, across, u).unwrap_or(0.0))
            .sum()
    }

    /// Where the lit test of this azimuth ([`Glint::lit`]) changes between u = `lo`
    /// (where it is `was`) and `hi`, to within [`EDGE_WIDTH`].
    ///
    /// It changes where one of its three conditions does: h faces the viewer, the light
    /// direction meets the Earth (the limb), the point met is on the day side (the
    /// terminator). Each is the sign of a quantity smooth in u ([`Glint::margins`]), so
    /// the one that differs between the ends is followed to its root by the Illinois
    /// method (false position that halves an end kept twice): ~10 tests where halving
    /// the step took 40, and these edges were a sixth of a rocket body's epoch in the
    /// default earthshine. The bracket found must still be an edge of the lit test
    /// itself; halving finishes it where it is not (two edges in one step).
    fn edge(&self, n: DVec3, across: DVec3, mut lo: f64, mut hi: f64, was: bool) -> f64 {
        let (ma, mb) = (self.margins(n, across, lo), self.margins(n, across, hi));
        if let Some(k) = (0..3).find(|&k| ma[k].1 != mb[k].1) {
            let (mut a, mut b) = (lo, hi);
            let (mut fa, mut fb) = (ma[k].0, mb[k].0);
            let a_sign = ma[k].1;
            let mut kept = 0i8;
            for _ in 0..ILLINOIS_STEPS {
                if b - a <= EDGE_WIDTH {
                    break;
                }
                let mut x = (a * fb - b * fa) / (fb - fa);
                if !(x > a && x < b) {
                    x = 0.5 * (a + b);
                }
                let (fx, sx) = self.margins(n, across, x)[k];
                if sx == a_sign {
                    (a, fa) = (x, fx);
                    if kept == -1 {
                        fb *= 0.5;
                    }
                    kept = -1;
                } else {
                    (b, fb) = (x, fx);
                    if kept == 1 {
                        fa *= 0.5;
                    }
                    kept = 1;
                }
            }
            if self.lit(n, across, a) == was && self.lit(n, across, b) != was {
                (lo, hi) = (a, b);
            }
        }
        for _ in 0..40 {
            if hi - lo <= EDGE_WIDTH {
                break;
            }
            let mid = 0.5 * (lo + hi);
            if self.lit(n, across, mid) == was {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The three conditions of [`Glint::lit`] at u on this azimuth, each as a value
    /// smooth in u and whether it holds: v·h > 0; the light direction meets the Earth
    /// in front (b² − c ≥ 0 with b = o·l < 0; −c − b² where b ≥ 0, continuous at b = 0);
    /// the point met has the Sun above its horizon (cos z > 0; −1 where nothing is met).
    #[inline]
    fn margins(&self, n: DVec3, across: DVec3, u: f64) -> [(f64, bool); 3] {
        let (vh, l) = self.probe(n, across, u);
        let (meets, cos_z) = self.earth.sight(l);
        let cos_z = cos_z.unwrap_or(-1.0);
        [(vh, vh > 0.0), (meets, meets >= 0.0), (cos_z, cos_z > 0.0)]
    }

    /// The probe at u = √s on this azimuth: v·h, and the light direction l = 2(v·h)h − v.
    #[inline]
    fn probe(&self, n: DVec3, across: DVec3, u: f64) -> (f64, DVec3) {
        let h = (n + across * (self.slope * u)).normalize();
        let vh = self.v.dot(h);
        (vh, 2.0 * vh * h - self.v)
    }

    /// Is the Earth lit along the light direction of the probe at u = √s on this
    /// azimuth? (Given u, not s: √(u²) is u, so the root would only be paid for.)
    #[inline]
    fn lit(&self, n: DVec3, across: DVec3, u: f64) -> bool {
        let (vh, l) = self.probe(n, across, u);
        vh > 0.0 && self.earth.radiance(l) > 0.0
    }

    /// The integrand in s = tan²α/δ² along the azimuth `across` (a unit vector ⟂ n),
    /// given u = √s (its callers have u, or a node's root found once): 2(v·h)δ²cos³α ·
    /// P_spec(l) · L(l); `None` where the Earth is dark or absent there.
    #[inline]
    fn density(&self, frame: &Frame, n: DVec3, across: DVec3, u: f64) -> Option<f64> {
        let t = self.slope * u;
        let cos_a = 1.0 / (1.0 + t * t).sqrt();
        let h = (n + across * t) * cos_a;
        let vh = self.v.dot(h);
        if vh <= 0.0 {
            return None;
        }
        let l = 2.0 * vh * h - self.v;
        let radiance = self.earth.radiance(l);
        if radiance <= 0.0 {
            return None;
        }
        let d2 = self.slope * self.slope;
        Some(2.0 * vh * d2 * cos_a.powi(3) * radiance * self.spec.projected(frame, l, self.v))
    }
}

/// Whether every light direction within `rho` (rad) of unit `axis` finds the lit
/// Earth (`b`), or every one finds none, when a bound proves it; `facing`: every h that
/// probes them has v·h > 0 (else a probe finds nothing, and `Lit` is not claimed).
/// Most faces' lobes, a few degrees wide, lie wholly on the day side, the night
/// side or off the Earth, and the 32 × 57 probes of [`Glint::lit`] along their
/// azimuths were two thirds of an epoch of a rocket body in the default earthshine.
///
/// A direction at angle γ from the Earth's centre (within its angular radius θ_E)
/// meets it at distance t(γ) = D cos γ − √(R² − D² sin² γ), which grows with γ, at a
/// point that is sunlit when o·s + t (l·s) > 0 (o the object from the Earth's centre,
/// D its length, s the Sun). Over the cone γ and l·s keep to ranges set by the
/// axis's angles from the centre and from the Sun, and the bilinear t (l·s) to those
/// ranges' corners. Margins of 1e-9 rad and 1e-9 D keep rounding on the side of
/// `Mixed`.
fn over_earth(b: &EarthBounds, axis: DVec3, rho: Spread, facing: bool) -> Whole {
    let EarthBounds {
        d,
        theta_e,
        os,
        centre_dir,
        sun_dir,
        ..
    } = *b;
    let Spread {
        rho,
        cos: cr,
        sin: sr,
    } = rho;
    // cos and sin of γ and β (in [0, π]: sin ≥ 0), and of the ends of their ranges by the
    // angle-sum rules: the angles themselves are never needed
    let (cg, cb) = (
        axis.dot(centre_dir).clamp(-1.0, 1.0),
        axis.dot(sun_dir).clamp(-1.0, 1.0),
    );
    let sine = |c: f64| ((1.0 - c) * (1.0 + c)).sqrt();
    let (sg, sb) = (sine(cg), sine(cb));
    // γ − ρ > θ_E + margin: every direction of the cone misses the Earth
    if theta_e + ANGLE + rho < std::f64::consts::PI && cg < b.cos_beyond(cr, sr) {
        return Whole::Dark;
    }
    let r = EARTH_RADIUS_M;
    let t = |(c, s): (f64, f64)| d * c - (r * r - (d * s).powi(2)).max(0.0).sqrt();
    // max(γ − ρ, 0)
    let lo = if cg >= cr {
        (1.0, 0.0)
    } else {
        (cg * cr + sg * sr, sg * cr - cg * sr)
    };
    // γ + ρ (when within π) and min(γ + ρ, θ_E)
    let sum = (cg >= -cr).then_some((cg * cr - sg * sr, sg * cr + cg * sr));
    let hi = match sum {
        Some((c, s)) if c > b.cos_e => (c, s),
        _ => (b.cos_e, b.sin_e),
    };
    let (t_lo, t_hi) = (t(lo), t(hi));
    // cos of min(β + ρ, π) and of max(β − ρ, 0)
    let ls_lo = if cb < -cr { -1.0 } else { cb * cr - sb * sr };
    let ls_hi = if cb >= cr { 1.0 } else { cb * cr + sb * sr };
    let margin = 1e-9 * d;
    let most = os + if ls_hi >= 0.0 { t_hi } else { t_lo } * ls_hi;
    if most < -margin {
        return Whole::Dark;
    }
    let least = os + if ls_lo >= 0.0 { t_lo } else { t_hi } * ls_lo;
    // γ + ρ < θ_E − margin
    let inside = sum.is_some_and(|(c, _)| c > b.cos_inner);
    if inside && least > margin && facing {
        return Whole::Lit;
    }
    Whole::Mixed
}

/// Margin (rad) that keeps the rounding of [`over_earth`]'s angles on the side of `Mixed`.
const ANGLE: f64 = 1e-9;

/// The half-angle ρ of a cone as [`over_earth`] reads it: ρ widened by its margin
/// ([`ANGLE`], rad), with its cos and sin found once (per epoch and material) rather
/// than once a face.
#[derive(Debug, Clone, Copy)]
struct Spread {
    rho: f64,
    cos: f64,
    sin: f64,
}

impl Spread {
    fn new(rho: f64) -> Spread {
        let rho = rho + ANGLE;
        Spread {
            rho,
            cos: rho.cos(),
            sin: rho.sin(),
        }
    }
}

/// The sunlit Earth as [`over_earth`] reads it, fixed for an epoch: the object's
/// distance from the Earth's centre D (m), the Earth's angular radius θ_E (rad), o·s (m),
/// and the unit directions to the Earth's centre and to the Sun.
#[derive(Debug, Clone, Copy)]
struct EarthBounds {
    d: f64,
    theta_e: f64,
    os: f64,
    centre_dir: DVec3,
    sun_dir: DVec3,
    /// cos and sin of θ_E; of θ_E + margin; cos of θ_E − margin.
    cos_e: f64,
    sin_e: f64,
    cos_outer: f64,
    sin_outer: f64,
    cos_inner: f64,
}

impl EarthBounds {
    fn of(e: &SunlitEarth) -> EarthBounds {
        let theta_e = e.cos_cap.clamp(-1.0, 1.0).acos();
        EarthBounds {
            d: e.object.length(),
            theta_e,
            os: e.object.dot(e.sun_dir),
            centre_dir: e.centre_dir,
            sun_dir: e.sun_dir,
            cos_e: theta_e.cos(),
            sin_e: theta_e.sin(),
            cos_outer: (theta_e + ANGLE).cos(),
            sin_outer: (theta_e + ANGLE).sin(),
            cos_inner: (theta_e - ANGLE).cos(),
        }
    }

    /// cos(θ_E + margin + ρ) from ρ's cos `cr` and sin `sr`.
    #[inline]
    fn cos_beyond(&self, cr: f64, sr: f64) -> f64 {
        self.cos_outer * cr - self.sin_outer * sr
    }
}

/// Probes along each azimuth of the glint rule: every [`PROBE_STEP`] in u out to
/// √(2 s) of the last Laguerre node.
fn probes() -> usize {
    ((2.0 * laguerre()[LAGUERRE - 1].0).sqrt() / PROBE_STEP).ceil() as usize
}

/// Gauss–Legendre nodes on [0, 1] for the lit pieces of an azimuth.
fn legendre() -> &'static [(f64, f64)] {
    static NODES: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    NODES.get_or_init(|| gauss_legendre(PIECE_POINTS))
}

/// The square roots of [`laguerre`]'s nodes: u = √s, at which the glint rule's integrand
/// is evaluated.
fn laguerre_roots() -> &'static [f64] {
    static ROOTS: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    ROOTS.get_or_init(|| laguerre().iter().map(|&(s, _)| s.sqrt()).collect())
}

/// Gauss–Laguerre nodes s_i and weights W_i·e^(s_i) for ∫₀^∞ e^−s g(s) ds
/// ([`LAGUERRE`] of them), by Newton's method on the Laguerre polynomial (Numerical
/// Recipes' `gaulag`, α = 0).
fn laguerre() -> &'static [(f64, f64)] {
    static NODES: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    NODES.get_or_init(|| {
        let n = LAGUERRE;
        let mut out: Vec<(f64, f64)> = Vec::with_capacity(n);
        let mut z = 0.0f64;
        for i in 0..n {
            z = match i {
                0 => 3.0 / (1.0 + 2.4 * n as f64),
                1 => z + 15.0 / (1.0 + 2.5 * n as f64),
                _ => {
                    let ai = (i - 1) as f64;
                    z + (1.0 + 2.55 * ai) / (1.9 * ai) * (z - out[i - 2].0)
                }
            };
            let mut pp = 1.0;
            let mut p2 = 0.0;
            for _ in 0..100 {
                let mut p1 = 1.0;
                p2 = 0.0;
                for j in 0..n {
                    let p3 = p2;
                    p2 = p1;
                    p1 = ((2 * j + 1) as f64 - z) * p2 / (j + 1) as f64
                        - j as f64 * p3 / (j + 1) as f64;
                }
                pp = n as f64 * (p1 - p2) / z;
                let z1 = z;
                z = z1 - p1 / pp;
                if (z - z1).abs() <= 1e-15 * z.abs() {
                    break;
                }
            }
            // W_i = −1/(pp · n · L_{n−1}); times e^{s_i}
            let w = -1.0 / (pp * n as f64 * p2);
            out.push((z, w * z.exp()));
        }
        out
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every claim of [`over_earth`] holds at every one of ~1,600 directions spread over
    /// its cone (rings out to the rim, the rim included), looked up one by one with
    /// [`SunlitEarth::radiance`], over Earths seen from LEO to GEO at any phase and
    /// cones from 0.1° to 20°; and the claims are not idle: each of the three answers
    /// comes up at least a hundred times.
    #[test]
    fn a_lobe_claimed_wholly_lit_or_dark_is_so_at_every_direction_of_its_cone() {
        let mut next = crate::test_rng(0x9E37_79B9_7F4A_7C15);
        let unit = crate::test_unit;
        let mut counts = [0usize; 3];
        for _ in 0..3000 {
            let distance = EARTH_RADIUS_M + 4e5 + next() * 3.6e7;
            let object = unit(&mut next) * distance;
            let sun_dir = unit(&mut next);
            let centre_dir = -object / distance;
            let earth = SunlitEarth {
                object,
                sun_dir,
                radiance_scale: 1.0,
                cos_cap: (1.0 - (EARTH_RADIUS_M / distance).powi(2)).sqrt(),
                centre_dir,
            };
            // axes near the Earth's disk, most of them
            let axis = (centre_dir + unit(&mut next) * (2.0 * next())).normalize();
            let rho = (0.1 + 19.9 * next()).to_radians();
            let claim = over_earth(&EarthBounds::of(&earth), axis, Spread::new(rho), true);
            counts[claim as usize] += 1;
            if claim == Whole::Mixed {
                continue;
            }
            let (t1, t2) = orthonormal_basis(axis);
            for ring in 0..=40 {
                let a = rho * ring as f64 / 40.0;
                for k in 0..40 {
                    let phi = TAU * k as f64 / 40.0;
                    let l = axis * a.cos() + (t1 * phi.cos() + t2 * phi.sin()) * a.sin();
                    let lit = earth.radiance(l) > 0.0;
                    assert_eq!(
                        lit,
                        claim == Whole::Lit,
                        "{claim:?} at {a} rad from the axis, cone {rho} rad, {distance} m"
                    );
                }
            }
        }
        assert!(counts.iter().all(|&c| c > 100), "{counts:?}");
    }

    /// Where [`AllBeams`] answers for every beam at once, each beam evaluated one by one
    /// agrees: on single faces within 1e-12 of the larger value (the sum as one vector
    /// differs from the beams' own products in rounding only; a beam wrongly taken as
    /// lit, or a lobe wrongly taken as away, misses by far more), exactly where no beam
    /// lights the face, and bit for bit on cones of normals (the same sum, in the same
    /// order). Over Earths from LEO to GEO at any phase and views, materials with no lobe,
    /// a narrow and a wide one; each answer (lit, dark, undecided) comes up often.
    #[test]
    fn the_beams_taken_at_once_agree_with_the_beams_one_by_one() {
        let mut rnd = crate::test_rng(7);
        let unit = crate::test_unit;
        let brdfs = [
            Brdf::Lambert(crate::brdf::Lambert { albedo: 0.3 }),
            Brdf::SeedMicrofacet(crate::brdf::SeedMicrofacet::new(0.1, 0.5, 0.3, 0.18, 3.6)),
            Brdf::SeedMicrofacet(crate::brdf::SeedMicrofacet::new(0.2, 0.3, 0.05, 0.2, 2.5)),
        ];
        let (mut faces, mut cones) = ([0usize; 3], [0usize; 3]);
        for trial in 0..600 {
            let brdf = &brdfs[trial % brdfs.len()];
            let distance = EARTH_RADIUS_M + 4e5 + rnd() * 3.6e7;
            let shine = crate::radiometry::earth::sphere(
                -unit(&mut rnd) * distance,
                unit(&mut rnd),
                0.3,
                1361.0,
            );
            let v = unit(&mut rnd);
            let light = EarthLight::new(brdf, &shine, v);
            let Some(all) = &light.all else {
                continue;
            };
            for _ in 0..50 {
                let n = unit(&mut rnd);
                let cr = n.dot(v);
                if cr <= 0.0 {
                    continue;
                }
                let frame = Frame {
                    n,
                    t: n.any_orthonormal_vector(),
                };
                let (got, want) = (
                    light.beams_given(&frame, cr),
                    light.beams_one_by_one(&frame, cr),
                );
                let answer = all.at(n);
                faces[answer.map_or(2, usize::from)] += 1;
                match answer {
                    Some(false) => assert_eq!(got, 0.0),
                    _ => assert!(
                        (got - want).abs() <= 1e-12 * got.abs().max(want.abs()),
                        "{brdf:?} n {n} v {v}: {got} against {want}"
                    ),
                }
                let cone = Cone::new(n, 0.3 * rnd());
                if cone.min_dot(v) <= 0.0 {
                    continue;
                }
                let answer = all.over(&cone);
                cones[answer.map_or(2, usize::from)] += 1;
                if let Some(lit) = answer {
                    let got = if lit { all.sum } else { DVec3::ZERO };
                    let want = light.beams_linear_one_by_one(&cone);
                    assert_eq!(Some(got), want, "{brdf:?} {cone:?} v {v}");
                }
            }
        }
        assert!(
            faces.iter().chain(&cones).all(|&c| c > 300),
            "faces {faces:?}, cones {cones:?}"
        );
    }

    /// A glint rule's Earth seen from LEO to GEO at any phase, a viewer anywhere, and a
    /// face that faces it turned so that its mirror direction looks at or near the
    /// Earth's disk:
    /// `(rule, face frame)` for `tries` draws, where the body wrap's lobe (δ 0.01) takes
    /// the rule.
    fn glint_cases(seed: u64, tries: usize) -> Vec<(Glint, Frame)> {
        let mut next = crate::test_rng(seed);
        let unit = crate::test_unit;
        let brdf =
            Brdf::SeedMicrofacet(crate::brdf::SeedMicrofacet::new(0.1, 0.5, 0.01, 0.18, 3.60));
        let mut cases = Vec::new();
        for _ in 0..tries {
            let distance = EARTH_RADIUS_M + 4e5 + next() * 3.6e7;
            let earth = unit(&mut next) * distance;
            let shine = crate::radiometry::earth::sphere(earth, unit(&mut next), 0.3, 1361.0);
            let v = unit(&mut next);
            let Some(g) = EarthLight::new(&brdf, &shine, v).glint else {
                continue;
            };
            let target = (g.earth.centre_dir + unit(&mut next) * (1.2 * next())).normalize();
            let Some(n) = (v + target).try_normalize() else {
                continue;
            };
            if n.dot(v) <= 0.0 {
                continue;
            }
            let frame = Frame {
                n,
                t: orthonormal_basis(n).0,
            };
            cases.push((g, frame));
        }
        cases
    }

    /// The plain rule (every node lit or not by itself) over `azimuths` even azimuths.
    fn plain_over(g: &Glint, frame: &Frame, azimuths: usize) -> f64 {
        let n = frame.n;
        let (t1, t2) = orthonormal_basis(n);
        let step = TAU / azimuths as f64;
        let sum: f64 = (0..azimuths)
            .map(|j| {
                let (sp, cp) = (step * (j as f64 + 0.5)).sin_cos();
                g.along(frame, n, t1 * cp + t2 * sp)
            })
            .sum();
        sum * step
    }

    /// On a lobe that sees the lit Earth throughout, the even rule in azimuth is exact
    /// for the integrand's azimuthal terms below the count, and they fall off as powers
    /// of the lobe's tilt (a few degrees) times how fast the light, the Fresnel term and
    /// the shadowing turn: 8 azimuths agree with 32 (the rule elsewhere) and 128 within
    /// 1e-6 of the face's glint, three orders below a request's default tolerance. Over
    /// these ~440 lobes the worst was 3.7e-7, on a face seen at grazing (n·v 0.09), and
    /// all others below 3e-9; on the rocket body's default earthshine the curves moved
    /// by 3e-10 at most (4 azimuths: 2e-6).
    #[test]
    fn a_lobe_that_sees_the_lit_earth_throughout_takes_eight_azimuths() {
        let mut tested = 0;
        for (g, frame) in glint_cases(0x5EED_0008, 6000) {
            let n = frame.n;
            let cr = n.dot(g.v);
            let mirror = 2.0 * cr * n - g.v;
            let facing = cr > g.probe_tilt.sin();
            if over_earth(&g.bounds, mirror, g.lobe, facing) != Whole::Lit {
                continue;
            }
            let eight = g.lit_throughout(&frame, n, orthonormal_basis(n));
            assert!(eight > 0.0);

            for fine in [32, 128] {
                let want = plain_over(&g, &frame, fine);
                assert!(
                    (eight - want).abs() <= 1e-6 * want,
                    "{eight} against {want} ({fine} azimuths), n {n}, v {}",
                    g.v
                );
            }
            tested += 1;
        }
        assert!(tested >= 300, "{tested} lobes wholly lit");
    }

    /// Every edge of the lit Earth that the probes meet along an azimuth (limb,
    /// terminator, h turning from the viewer) is placed by false position where 40
    /// halvings of the step place it, within the width both aim at ([`EDGE_WIDTH`],
    /// 1e-13 in u); and every kind of edge comes up.
    #[test]
    fn an_edge_found_by_false_position_lies_where_halving_finds_it() {
        let mut edges = [0usize; 3];
        for (g, frame) in glint_cases(0x5EED_0E06, 3000) {
            let n = frame.n;
            let (t1, t2) = orthonormal_basis(n);
            for j in 0..GLINT_AZIMUTHS {
                let phi = TAU * (j as f64 + 0.5) / GLINT_AZIMUTHS as f64;
                let across = t1 * phi.cos() + t2 * phi.sin();
                let mut prev = g.lit(n, across, 0.0);
                for k in 1..=probes() {
                    let u = k as f64 * PROBE_STEP;
                    let now = g.lit(n, across, u);
                    if now != prev {
                        let (mut lo, mut hi) = (u - PROBE_STEP, u);
                        for _ in 0..40 {
                            let mid = 0.5 * (lo + hi);
                            if g.lit(n, across, mid) == prev {
                                lo = mid;
                            } else {
                                hi = mid;
                            }
                        }
                        let halved = 0.5 * (lo + hi);
                        let found = g.edge(n, across, u - PROBE_STEP, u, prev);
                        assert!(
                            (found - halved).abs() <= 1e-11,
                            "edge at u {found} against {halved}"
                        );
                        let (a, b) = (g.margins(n, across, lo), g.margins(n, across, hi));
                        if let Some(kind) = (0..3).find(|&k| a[k].1 != b[k].1) {
                            edges[kind] += 1;
                        }
                    }
                    prev = now;
                }
            }
        }
        assert!(edges.iter().all(|&e| e >= 20), "edges by kind {edges:?}");
    }

    #[test]
    fn laguerre_rule_integrates_polynomials_against_e_minus_s() {
        // ∫₀^∞ e^−s s^k ds = k!, exact up to degree 2n − 1
        let mut fact = 1.0;
        for k in 0..(2 * LAGUERRE) {
            if k > 0 {
                fact *= k as f64;
            }
            let sum: f64 = laguerre()
                .iter()
                .map(|&(s, w)| w * (-s).exp() * s.powi(k as i32))
                .sum();
            assert!((sum / fact - 1.0).abs() < 1e-10, "k {k}: {sum} vs {fact}");
        }
    }
}
