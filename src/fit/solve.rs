//! Bounded, weighted, robust nonlinear least squares: the one solver both fits use.
//!
//! The minimisation itself is the `levenberg-marquardt` crate (a port of MINPACK's
//! `lmder`: trust region, pivoted QR, scaled diagonal — the algorithm behind SciPy's
//! `least_squares(method="lm")`). This file adds what a fit needs around it:
//! - **bounds**, by a smooth change of variables ([`super::params::Bound`]): the solver moves
//!   freely in u and every model sees a parameter inside its bounds;
//! - **a finite-difference Jacobian** (the models are evaluated, not differentiated);
//! - **a robust loss** (Huber or Cauchy) by iteratively reweighted least squares: each
//!   round is a weighted LM solve, the weights recomputed from the standardised residuals;
//! - **uncertainties** from the Jacobian at the optimum, in the physical parameters:
//!   covariance = s² (JᵀJ)⁻¹, s² = Σ ω r² / (m − p).

use super::params::Bound;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};
use std::cell::Cell;

/// A model to fit: residuals of `p` (physical parameters, inside their bounds), already
/// divided by each datum's standard error or multiplied by √weight. `false` when the
/// model cannot be evaluated there (a non-finite value).
pub trait Residuals {
    /// Number of residuals m.
    fn count(&self) -> usize;
    /// Writes the m residuals of parameters `p` into `out`.
    fn eval(&self, p: &[f64], out: &mut [f64]) -> bool;
}

/// The loss applied to standardised residuals z = r / scale.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Loss {
    /// Ordinary least squares, ρ(z) = z²/2.
    L2,
    /// Huber, c = 1.345 (95 % efficiency on Gaussian data): quadratic within c, linear beyond.
    Huber,
    /// Cauchy (Lorentzian), c = 2.385: ρ(z) = c²/2 · ln(1 + (z/c)²); outliers lose all weight.
    Cauchy,
}

impl Loss {
    /// `l2`, `huber` or `cauchy`.
    pub fn parse(name: &str) -> Option<Loss> {
        match name {
            "l2" => Some(Loss::L2),
            "huber" => Some(Loss::Huber),
            "cauchy" => Some(Loss::Cauchy),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Loss::L2 => "l2",
            Loss::Huber => "huber",
            Loss::Cauchy => "cauchy",
        }
    }

    /// IRLS weight ω(z) = ρ'(z)/z.
    fn weight(self, z: f64) -> f64 {
        let z = z.abs();
        match self {
            Loss::L2 => 1.0,
            Loss::Huber => {
                if z <= HUBER_C {
                    1.0
                } else {
                    HUBER_C / z
                }
            }
            Loss::Cauchy => 1.0 / (1.0 + (z / CAUCHY_C).powi(2)),
        }
    }

    /// ρ(z), to compare the minima reached from different starts.
    pub fn rho(self, z: f64) -> f64 {
        let a = z.abs();
        match self {
            Loss::L2 => 0.5 * z * z,
            Loss::Huber => {
                if a <= HUBER_C {
                    0.5 * z * z
                } else {
                    HUBER_C * (a - 0.5 * HUBER_C)
                }
            }
            Loss::Cauchy => 0.5 * CAUCHY_C * CAUCHY_C * (1.0 + (z / CAUCHY_C).powi(2)).ln(),
        }
    }
}

const HUBER_C: f64 = 1.345;
const CAUCHY_C: f64 = 2.385;

/// How the robust loss scales residuals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scale {
    /// Residuals are already in units of their standard error (z = r).
    Known,
    /// Estimated from the residuals: 1.4826 × their median absolute value (MAD about 0).
    Mad,
}

/// Solver settings.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    pub loss: Loss,
    pub scale: Scale,
    /// Relative tolerance on the objective and the step (the crate's ftol and xtol).
    pub tolerance: f64,
    /// At most this many residual evaluations per LM run, times (p + 1).
    pub patience: usize,
    /// Relative finite-difference step in u for the solver's Jacobian.
    pub fd_step: f64,
    /// Most IRLS rounds (robust losses only).
    pub max_rounds: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            loss: Loss::Huber,
            scale: Scale::Mad,
            tolerance: 1e-10,
            patience: 100,
            fd_step: 1e-7,
            max_rounds: 12,
        }
    }
}

/// One solve from one start.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Physical parameters at the optimum.
    pub p: Vec<f64>,
    /// Data residuals there (without the robust weights).
    pub residuals: Vec<f64>,
    /// Robust weights ω of the last round (1 for L2).
    pub weights: Vec<f64>,
    /// Scale the robust loss used in its last round (1 for a known scale).
    pub scale: f64,
    /// Residual evaluations, including the finite-difference Jacobians.
    pub evaluations: usize,
    /// Whether the last LM run ended by meeting its tolerances.
    pub converged: bool,
    /// The LM crate's termination reason of the last run, as text.
    pub termination: String,
}

struct Lm<'a, R: Residuals> {
    model: &'a R,
    bounds: &'a [Bound],
    u: DVector<f64>,
    /// √ω per residual.
    sqrt_w: &'a [f64],
    step: f64,
    evaluations: &'a Cell<usize>,
}

impl<R: Residuals> Lm<'_, R> {
    fn weighted(&self, u: &DVector<f64>) -> Option<DVector<f64>> {
        let p: Vec<f64> = u.iter().zip(self.bounds).map(|(&u, b)| b.to_p(u)).collect();
        let mut r = vec![0.0; self.model.count()];
        self.evaluations.set(self.evaluations.get() + 1);
        if !self.model.eval(&p, &mut r) {
            return None;
        }
        let mut out = DVector::from_vec(r);
        for (x, w) in out.iter_mut().zip(self.sqrt_w) {
            *x *= w;
            if !x.is_finite() {
                return None;
            }
        }
        Some(out)
    }
}

impl<R: Residuals> LeastSquaresProblem<f64, Dyn, Dyn> for Lm<'_, R> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, u: &DVector<f64>) {
        self.u.copy_from(u);
    }

    fn params(&self) -> DVector<f64> {
        self.u.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.weighted(&self.u)
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        // central differences in u: the models are smooth there, and the cost (2p model
        // evaluations) is small beside a light curve's own
        let (m, n) = (self.model.count(), self.u.len());
        let mut j = DMatrix::zeros(m, n);
        for c in 0..n {
            let h = self.step * self.u[c].abs().max(1.0);
            let mut up = self.u.clone();
            up[c] += h;
            let mut down = self.u.clone();
            down[c] -= h;
            let (rp, rm) = (self.weighted(&up)?, self.weighted(&down)?);
            for r in 0..m {
                j[(r, c)] = (rp[r] - rm[r]) / (2.0 * h);
            }
        }
        Some(j)
    }
}

/// Minimises Σ ρ(r/scale) over parameters within `bounds`, from `start` (physical values,
/// inside the bounds).
pub fn solve<R: Residuals>(
    model: &R,
    bounds: &[Bound],
    start: &[f64],
    settings: &Settings,
) -> Solution {
    let evaluations = Cell::new(0);
    let m = model.count();
    let mut u = DVector::from_iterator(
        start.len(),
        start.iter().zip(bounds).map(|(&p, b)| b.to_u(p)),
    );
    let mut weights: Vec<f64> = vec![1.0; m];
    let mut scale = 1.0;
    let mut converged = false;
    let mut termination = String::new();
    let rounds = if settings.loss == Loss::L2 {
        1
    } else {
        settings.max_rounds.max(1)
    };
    let solver = LevenbergMarquardt::new()
        .with_ftol(settings.tolerance)
        .with_xtol(settings.tolerance)
        .with_gtol(0.0)
        .with_patience(settings.patience);
    for round in 0..rounds {
        let sqrt_w: Vec<f64> = weights.iter().map(|w| w.sqrt()).collect();
        let problem = Lm {
            model,
            bounds,
            u: u.clone(),
            sqrt_w: &sqrt_w,
            step: settings.fd_step,
            evaluations: &evaluations,
        };
        let (problem, report) = solver.minimize(problem);
        // keep the solver's point only if the model can be evaluated there
        if problem.weighted(&problem.u).is_some() {
            u = problem.u;
        }
        converged = report.termination.was_successful();
        termination = format!("{:?}", report.termination);
        if settings.loss == Loss::L2 || round + 1 == rounds {
            break;
        }
        // new weights from the residuals at this round's optimum
        let r = raw_residuals(model, bounds, &u, &evaluations);
        let Some(r) = r else { break };
        let s = match settings.scale {
            Scale::Known => 1.0,
            Scale::Mad => mad(&r),
        };
        if !(s > 0.0 && s.is_finite()) {
            // a perfect fit: nothing to down-weight
            break;
        }
        scale = s;
        let new: Vec<f64> = r.iter().map(|x| settings.loss.weight(x / s)).collect();
        let change = new
            .iter()
            .zip(&weights)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        weights = new;
        if change < 1e-4 && round > 0 {
            break;
        }
    }
    let residuals = raw_residuals(model, bounds, &u, &evaluations).unwrap_or_else(|| vec![0.0; m]);
    Solution {
        p: u.iter().zip(bounds).map(|(&u, b)| b.to_p(u)).collect(),
        residuals,
        weights,
        scale,
        evaluations: evaluations.get(),
        converged,
        termination,
    }
}

fn raw_residuals<R: Residuals>(
    model: &R,
    bounds: &[Bound],
    u: &DVector<f64>,
    evaluations: &Cell<usize>,
) -> Option<Vec<f64>> {
    let p: Vec<f64> = u.iter().zip(bounds).map(|(&u, b)| b.to_p(u)).collect();
    let mut r = vec![0.0; model.count()];
    evaluations.set(evaluations.get() + 1);
    (model.eval(&p, &mut r) && r.iter().all(|x| x.is_finite())).then_some(r)
}

/// 1.4826 × the median of |r|: the standard deviation for Gaussian residuals, unmoved by
/// a minority of outliers.
pub fn mad(r: &[f64]) -> f64 {
    let mut a: Vec<f64> = r.iter().map(|x| x.abs()).collect();
    if a.is_empty() {
        return 0.0;
    }
    a.sort_by(f64::total_cmp);
    let n = a.len();
    let med = if n % 2 == 1 {
        a[n / 2]
    } else {
        0.5 * (a[n / 2 - 1] + a[n / 2])
    };
    1.4826 * med
}

/// The robust objective Σ ρ(r/scale)·scale² of a solution, at a common `scale`: how the
/// minima from several starts are compared.
pub fn objective(loss: Loss, residuals: &[f64], scale: f64) -> f64 {
    let s = if scale > 0.0 && scale.is_finite() {
        scale
    } else {
        1.0
    };
    residuals.iter().map(|r| loss.rho(r / s)).sum::<f64>() * s * s
}

/// Parameter uncertainties at an optimum.
#[derive(Debug, Clone)]
pub struct Covariance {
    /// s² = Σ ω r² / (m − p), the residual variance per degree of freedom.
    pub s2: f64,
    /// 1σ per parameter; `None` where the Jacobian does not determine it (a direction
    /// the data do not constrain).
    pub sigma: Vec<Option<f64>>,
    /// Correlation matrix (row-major, p × p); `None` entries as `sigma`.
    pub correlation: Vec<Vec<Option<f64>>>,
    /// Residual evaluations spent on the Jacobian.
    pub evaluations: usize,
}

/// Covariance s² (JᵀJ)⁻¹ at `sol`, with J the Jacobian of the √ω-weighted residuals with
/// respect to the *physical* parameters (central differences, one-sided at a bound).
pub fn covariance<R: Residuals>(model: &R, bounds: &[Bound], sol: &Solution) -> Covariance {
    let (m, n) = (model.count(), sol.p.len());
    let mut evaluations = 0;
    let j = physical_jacobian(model, bounds, sol, &mut evaluations);
    let dof = m.saturating_sub(n).max(1) as f64;
    let s2 = sol
        .residuals
        .iter()
        .zip(&sol.weights)
        .map(|(r, w)| w * r * r)
        .sum::<f64>()
        / dof;
    let Some((mut cov, undetermined)) = j.and_then(|j| inverse_normal(j, n)) else {
        return Covariance {
            s2,
            sigma: vec![None; n],
            correlation: vec![vec![None; n]; n],
            evaluations,
        };
    };
    cov *= s2;
    let sigma: Vec<Option<f64>> = (0..n)
        .map(|c| {
            let v = cov[(c, c)];
            (!undetermined[c] && v.is_finite() && v >= 0.0).then(|| v.sqrt())
        })
        .collect();
    let correlation = correlations(&cov, &sigma);
    Covariance {
        s2,
        sigma,
        correlation,
        evaluations,
    }
}

/// J of the √ω-weighted residuals in the physical parameters at `sol` (central
/// differences, one-sided at a bound), its evaluations counted in `evaluations`; `None`
/// when a parameter has no room to move or the model cannot be evaluated beside the
/// optimum.
fn physical_jacobian<R: Residuals>(
    model: &R,
    bounds: &[Bound],
    sol: &Solution,
    evaluations: &mut usize,
) -> Option<DMatrix<f64>> {
    let (m, n) = (model.count(), sol.p.len());
    let sqrt_w: Vec<f64> = sol.weights.iter().map(|w| w.sqrt()).collect();
    let mut eval = |p: &[f64]| -> Option<Vec<f64>> {
        let mut r = vec![0.0; m];
        *evaluations += 1;
        if !model.eval(p, &mut r) {
            return None;
        }
        r.iter_mut().zip(&sqrt_w).for_each(|(x, w)| *x *= w);
        r.iter().all(|x| x.is_finite()).then_some(r)
    };
    let mut j = DMatrix::zeros(m, n);
    for c in 0..n {
        let b = bounds[c];
        let p0 = sol.p[c];
        let h = 1e-5 * p0.abs().max(1e-3 * (b.hi - b.lo).min(1.0)).max(1e-12);
        let (lo, hi) = ((p0 - h).max(b.lo), (p0 + h).min(b.hi));
        if hi <= lo {
            return None;
        }
        let mut pp = sol.p.clone();
        pp[c] = hi;
        let mut pm = sol.p.clone();
        pm[c] = lo;
        // both sides evaluated before either is judged, as the evaluation count says
        let (rp, rm) = (eval(&pp), eval(&pm));
        let (rp, rm) = (rp?, rm?);
        for r in 0..m {
            j[(r, c)] = (rp[r] - rm[r]) / (hi - lo);
        }
    }
    Some(j)
}

/// (JᵀJ)⁻¹ by SVD of J (J = U Σ Vᵀ ⇒ (JᵀJ)⁻¹ = V Σ⁻² Vᵀ) over the `n` parameters, and which
/// parameters it leaves undetermined: those with a share in a direction whose singular
/// value is below 1e-10 of the largest. `None` when the SVD fails or J is zero.
fn inverse_normal(j: DMatrix<f64>, n: usize) -> Option<(DMatrix<f64>, Vec<bool>)> {
    let svd = j.svd(false, true);
    let vt = svd.v_t?;
    let smax = svd.singular_values.iter().copied().fold(0.0, f64::max);
    if smax <= 0.0 || smax.is_nan() {
        return None;
    }
    let mut cov = DMatrix::zeros(n, n);
    let mut undetermined = vec![false; n];
    for (k, &s) in svd.singular_values.iter().enumerate() {
        if s <= 1e-10 * smax {
            // every parameter with a share in this direction is undetermined
            for (c, flag) in undetermined.iter_mut().enumerate() {
                if vt[(k, c)].abs() > 1e-6 {
                    *flag = true;
                }
            }
            continue;
        }
        let row = vt.row(k);
        cov += row.transpose() * row / (s * s);
    }
    Some((cov, undetermined))
}

/// The correlation matrix of `cov` (p × p) given each parameter's 1σ; `None` where either
/// σ is missing or zero.
fn correlations(cov: &DMatrix<f64>, sigma: &[Option<f64>]) -> Vec<Vec<Option<f64>>> {
    let n = sigma.len();
    (0..n)
        .map(|a| {
            (0..n)
                .map(|b| match (sigma[a], sigma[b]) {
                    (Some(sa), Some(sb)) if sa > 0.0 && sb > 0.0 => {
                        Some((cov[(a, b)] / (sa * sb)).clamp(-1.0, 1.0))
                    }
                    _ => None,
                })
                .collect()
        })
        .collect()
}
