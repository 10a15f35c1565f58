//! A request's free parameters from an observed light curve: weighted least squares on
//! magnitudes, each evaluation a full light curve of the request's epochs that were
//! observed.
//!
//! **Free parameters** are named by path:
//! - `materials.<name>.<parameter>`: a numeric parameter of the material called `<name>`
//!   (a preset is expanded into its model and values first), within the bounds the
//!   request's validation takes: `albedo`; `kd`, `km`, `slope_rms`, `n`, `k`
//!   (seed-microfacet); `alpha`, `n`, `k`, `kd` (rough-conductor); `rd`, `rs`, `nu`, `nv`
//!   (ashikhmin-shirley);
//! - `attitude.yaw_deg`: a rotation ψ (degrees, positive counter-clockwise seen from +z) of
//!   the object about its own body z axis at every epoch, before the request's attitude:
//!   attitude′ = attitude · R_z(ψ) (body → inertial; the identity when an epoch has none).
//!   In the body frame every epoch's Sun, observer and Earth vectors turn by R_z(−ψ).
//!
//! **Residuals** r = (m_obs − m_model)/σ per observation. Where the model has no light at
//! all (its magnitude is `null`) it is taken as 5 mag fainter than the faintest
//! observation, so the fit is pushed back towards light without a NaN.

use super::params::{Bound, Named, SolverReport};
use super::solve::{self, Loss, Residuals, Scale, Settings};
use crate::integrate::simulate;
use crate::scene::request::{MaterialObject, MaterialSpec};
use crate::scene::{validate, Limits, Request, Scene, ValidationError};
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};
use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;
use utoipa::ToSchema;

/// One observation of the object's apparent magnitude.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Observation {
    /// Time, seconds: the `t` of one of the request's epochs (Unix seconds for ISO times).
    pub t: f64,
    /// Apparent magnitude (the band of the request's illumination).
    pub magnitude: f64,
    /// 1σ error of the magnitude (> 0).
    pub sigma: f64,
}

/// The path of the yaw offset among the free parameters.
pub const YAW: &str = "attitude.yaw_deg";

/// What to fit.
#[derive(Debug, Clone)]
pub struct Options {
    /// Free parameter paths (`materials.panel.albedo`, `attitude.yaw_deg`).
    pub free: Vec<String>,
    /// Starting values by path; a parameter not named starts at the request's value (0
    /// for the yaw).
    pub start: BTreeMap<String, f64>,
    /// `l2` (default, weighted least squares), `huber` or `cauchy` (on r = Δm/σ).
    pub loss: Loss,
}

/// The result of a light-curve fit.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct LightcurveFit {
    /// Fitted value of each free parameter, by path.
    #[schema(value_type = Object)]
    pub parameters: Named,
    /// 1σ of each (same units), from s²(JᵀJ)⁻¹ at the optimum; `null` where the light
    /// curve does not determine it.
    #[schema(value_type = Object)]
    pub uncertainty: BTreeMap<String, Option<f64>>,
    /// Where each started.
    #[schema(value_type = Object)]
    pub start: Named,
    /// Parameters that ended on a bound.
    pub at_bound: Vec<String>,
    /// χ² = Σ ((m_obs − m_fit)/σ)².
    pub chi2: f64,
    /// Observations − free parameters.
    pub dof: usize,
    /// χ²/dof (≈ 1 when the model explains the curve within its errors).
    pub chi2_dof: f64,
    /// RMS of m_obs − m_fit, mag.
    pub rms_mag: f64,
    /// Observations used.
    pub observations: usize,
    /// Correlations of the fitted parameters, in the order of `correlation_order`.
    pub correlation: Vec<Vec<Option<f64>>>,
    pub correlation_order: Vec<String>,
    /// Per observation: t (s), observed magnitude, σ, fitted magnitude (`null`: no light).
    pub curve: Vec<FittedEpoch>,
    /// The request with the fitted values in place (materials changed; the yaw folded into
    /// every epoch's `attitude`), ready to simulate.
    #[schema(value_type = Object)]
    pub request: serde_json::Value,
    pub warnings: Vec<String>,
    /// Evaluations are full light curves: `solver.evaluations` of them in
    /// `solver.wall_time_s`.
    pub solver: SolverReport,
}

/// One observation and the fitted model there.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema)]
pub struct FittedEpoch {
    pub t: f64,
    pub observed: f64,
    pub sigma: f64,
    pub fitted: Option<f64>,
}

/// Reads observations from CSV: a header with `t` and `magnitude` (or `mag`) and an error
/// column `sigma` (or `mag_err`, `magnitude_err`, `sigma_mag`); other columns are ignored,
/// so `glint simulate`'s CSV with an error column added is accepted. Without an error
/// column every row takes `default_sigma`, if given. Rows with an empty magnitude (no
/// detection) are skipped. Errors name `observed[i].column` and the line.
pub fn parse_observed_csv(
    text: &str,
    default_sigma: Option<f64>,
) -> Result<Vec<Observation>, ValidationError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(ValidationError::new(
            "observed",
            "the file has no header and no rows",
        ));
    };
    let columns: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |names: &[&str]| columns.iter().position(|c| names.contains(c));
    let t_col = find(&["t", "t_s"]).ok_or_else(|| {
        ValidationError::new("observed.t", format!("no `t` column (header: {header})"))
    })?;
    let m_col = find(&["magnitude", "mag"]).ok_or_else(|| {
        ValidationError::new(
            "observed.magnitude",
            format!("no `magnitude` column (header: {header})"),
        )
    })?;
    let s_col = find(&["sigma", "mag_err", "magnitude_err", "sigma_mag"]);
    if s_col.is_none() && default_sigma.is_none() {
        return Err(ValidationError::new(
            "observed.sigma",
            "no error column (`sigma`, `mag_err`) and no default σ given",
        ));
    }
    let mut out = Vec::new();
    for (i, (line, row)) in lines.enumerate() {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        let cell = |c: usize, name: &str| -> Result<&str, ValidationError> {
            cells.get(c).copied().ok_or_else(|| {
                ValidationError::new(
                    format!("observed[{i}].{name}"),
                    format!("line {line} has no `{name}` cell"),
                )
            })
        };
        let num = |c: usize, name: &str| -> Result<f64, ValidationError> {
            let s = cell(c, name)?;
            let v: f64 = s.parse().map_err(|_| {
                ValidationError::new(
                    format!("observed[{i}].{name}"),
                    format!("line {line}: `{s}` is not a number"),
                )
            })?;
            if !v.is_finite() {
                return Err(ValidationError::new(
                    format!("observed[{i}].{name}"),
                    format!("line {line}: must be a finite number"),
                ));
            }
            Ok(v)
        };
        if cell(m_col, "magnitude")?.is_empty() {
            continue;
        }
        let sigma = match s_col {
            Some(c) => num(c, "sigma")?,
            None => default_sigma.unwrap_or(f64::NAN),
        };
        if !(sigma > 0.0 && sigma.is_finite()) {
            return Err(ValidationError::new(
                format!("observed[{i}].sigma"),
                format!("line {line}: must be a finite number > 0, got {sigma}"),
            ));
        }
        out.push(Observation {
            t: num(t_col, "t")?,
            magnitude: num(m_col, "magnitude")?,
            sigma,
        });
    }
    Ok(out)
}

/// A resolved free parameter.
#[derive(Debug, Clone)]
enum Target {
    /// `materials[index].field`
    Material {
        index: usize,
        field: String,
    },
    Yaw,
}

/// The parameters a model's material takes, with the bounds of the request's validation.
fn material_params(model: &str, normalised: bool) -> &'static [(&'static str, Bound)] {
    const LAMBERT: &[(&str, Bound)] = &[("albedo", Bound::new(0.0, 1.0))];
    const SEED: &[(&str, Bound)] = &[
        ("kd", Bound::new(0.0, 1.0)),
        ("km", Bound::new(0.0, 1e3)),
        ("slope_rms", Bound::new(1e-6, 10.0)),
        ("n", Bound::new(1e-6, 1e3)),
        ("k", Bound::new(0.0, 1e3)),
    ];
    const SEED_NORMALISED: &[(&str, Bound)] = &[
        ("kd", Bound::new(0.0, 1.0)),
        ("km", Bound::new(0.0, 1.0)),
        ("slope_rms", Bound::new(1e-6, 10.0)),
        ("n", Bound::new(1e-6, 1e3)),
        ("k", Bound::new(0.0, 1e3)),
    ];
    const ROUGH: &[(&str, Bound)] = &[
        ("alpha", Bound::new(1e-6, 10.0)),
        ("n", Bound::new(1e-6, 1e3)),
        ("k", Bound::new(0.0, 1e3)),
        ("kd", Bound::new(0.0, 1.0)),
    ];
    const ASHIKHMIN: &[(&str, Bound)] = &[
        ("rd", Bound::new(0.0, 1.0)),
        ("rs", Bound::new(0.0, 1.0)),
        ("nu", Bound::new(0.0, 1e7)),
        ("nv", Bound::new(0.0, 1e7)),
    ];
    match model {
        "lambert" => LAMBERT,
        "seed-microfacet" if normalised => SEED_NORMALISED,
        "seed-microfacet" => SEED,
        "rough-conductor" => ROUGH,
        "ashikhmin-shirley" => ASHIKHMIN,
        _ => &[],
    }
}

fn get_field(m: &MaterialObject, field: &str) -> Option<f64> {
    match field {
        "albedo" => m.albedo,
        "kd" => m.kd.or(Some(0.0)),
        "km" => m.km,
        "slope_rms" => m.slope_rms,
        "n" => m.n,
        "k" => m.k.or(Some(0.0)),
        "alpha" => m.alpha,
        "rd" => m.rd,
        "rs" => m.rs,
        "nu" => m.nu,
        "nv" => m.nv,
        _ => None,
    }
}

fn set_field(m: &mut MaterialObject, field: &str, v: f64) {
    let slot = match field {
        "albedo" => &mut m.albedo,
        "kd" => &mut m.kd,
        "km" => &mut m.km,
        "slope_rms" => &mut m.slope_rms,
        "n" => &mut m.n,
        "k" => &mut m.k,
        "alpha" => &mut m.alpha,
        "rd" => &mut m.rd,
        "rs" => &mut m.rs,
        "nu" => &mut m.nu,
        "nv" => &mut m.nv,
        _ => return,
    };
    *slot = Some(v);
}

/// A material spec as a full object with a model and its values (a preset expanded).
fn expanded(spec: &MaterialSpec, field: &str) -> Result<MaterialObject, ValidationError> {
    let (name, preset, two_sided) = match spec {
        MaterialSpec::Preset(p) => (p.clone(), p.clone(), None),
        MaterialSpec::Full(m) => match &m.preset {
            None => return Ok(m.clone()),
            Some(p) => (m.name.clone(), p.clone(), m.two_sided),
        },
    };
    let p = crate::scene::presets::find(&preset).ok_or_else(|| {
        ValidationError::new(
            format!("{field}.preset"),
            format!("unknown preset `{preset}`"),
        )
    })?;
    let mut m = MaterialObject {
        name,
        two_sided,
        ..Default::default()
    };
    match (p.brdf)() {
        crate::brdf::Brdf::SeedMicrofacet(s) => {
            let (n, k) = s.fresnel.index();
            m.model = Some("seed-microfacet".into());
            m.kd = Some(s.kd);
            m.km = Some(s.km);
            m.slope_rms = Some(s.slope_rms);
            m.n = Some(n);
            m.k = Some(k);
        }
        other => {
            return Err(ValidationError::new(
                format!("{field}.preset"),
                format!(
                    "preset of model `{}` cannot be expanded",
                    other.model_name()
                ),
            ))
        }
    }
    Ok(m)
}

fn material_name(spec: &MaterialSpec) -> &str {
    match spec {
        MaterialSpec::Preset(p) => p,
        MaterialSpec::Full(m) => &m.name,
    }
}

/// The request as validated once, and what each evaluation changes.
struct Problem {
    scene: RefCell<Scene>,
    /// The observed epochs' body-frame vectors before any yaw: (sun, observer, earth).
    base: Vec<(DVec3, DVec3, Option<DVec3>)>,
    /// Full material objects (presets expanded) of the materials a parameter touches.
    materials: BTreeMap<usize, MaterialObject>,
    targets: Vec<Target>,
    observed: Vec<Observation>,
    /// Magnitude taken where the model has no light.
    dark: f64,
    /// The last evaluation's model magnitudes.
    last: RefCell<Vec<Option<f64>>>,
    evaluations: Cell<usize>,
    /// A material error at some parameters (should not happen within the bounds).
    error: RefCell<Option<ValidationError>>,
}

impl Problem {
    /// Puts parameters `p` into the scene.
    fn apply(&self, p: &[f64]) -> Result<(), ValidationError> {
        let mut scene = self.scene.borrow_mut();
        let mut materials = self.materials.clone();
        let mut yaw = 0.0;
        for (t, &v) in self.targets.iter().zip(p) {
            match t {
                Target::Material { index, field } => {
                    set_field(materials.get_mut(index).expect("resolved"), field, v)
                }
                Target::Yaw => yaw = v,
            }
        }
        for (index, m) in materials {
            scene.materials[index] = validate::material(
                &format!("object.materials[{index}]"),
                &MaterialSpec::Full(m),
            )?;
        }
        let turn = DQuat::from_rotation_z(-yaw.to_radians());
        for (e, (sun, obs, earth)) in scene.epochs.iter_mut().zip(&self.base) {
            e.sun = turn * *sun;
            e.observer = turn * *obs;
            e.earth = earth.map(|v| turn * v);
        }
        Ok(())
    }

    fn magnitudes(&self, p: &[f64]) -> Option<Vec<Option<f64>>> {
        if let Err(e) = self.apply(p) {
            *self.error.borrow_mut() = Some(e);
            return None;
        }
        self.evaluations.set(self.evaluations.get() + 1);
        let response = simulate(&self.scene.borrow());
        Some(response.epochs.iter().map(|e| e.magnitude).collect())
    }
}

impl Residuals for Problem {
    fn count(&self) -> usize {
        self.observed.len()
    }

    fn eval(&self, p: &[f64], out: &mut [f64]) -> bool {
        let Some(mags) = self.magnitudes(p) else {
            return false;
        };
        for ((o, obs), m) in out.iter_mut().zip(&self.observed).zip(&mags) {
            *o = (obs.magnitude - m.unwrap_or(self.dark)) / obs.sigma;
        }
        *self.last.borrow_mut() = mags;
        true
    }
}

/// Fits `opts.free` of `request` to `observed`. Errors name the field: `free[i]` for a
/// path that does not exist, `observed[i].t` for a time that is no epoch of the request,
/// `start.<path>` for a start outside the bounds.
pub fn fit(
    request: &Request,
    observed: &[Observation],
    opts: &Options,
) -> Result<LightcurveFit, ValidationError> {
    let started = std::time::Instant::now();
    if opts.free.is_empty() {
        return Err(ValidationError::new(
            "free",
            "name at least one free parameter",
        ));
    }
    let mut scene = Scene::from_request(request, &Limits::unlimited())?;
    scene.thumbnails = None;
    // resolve the paths
    let mut targets = Vec::new();
    let mut bounds = Vec::new();
    let mut start = Vec::new();
    let mut materials: BTreeMap<usize, MaterialObject> = BTreeMap::new();
    for (i, path) in opts.free.iter().enumerate() {
        let field = format!("free[{i}]");
        if opts.free[..i].contains(path) {
            return Err(ValidationError::new(
                field,
                format!("`{path}` is named twice"),
            ));
        }
        if path == YAW {
            targets.push(Target::Yaw);
            bounds.push(Bound::FREE);
            start.push(0.0);
            continue;
        }
        let parts: Vec<&str> = path.split('.').collect();
        let [root, name, param] = parts[..] else {
            return Err(ValidationError::new(
                field,
                format!("`{path}` is not a free parameter: expected `materials.<name>.<parameter>` or `{YAW}`"),
            ));
        };
        if root != "materials" {
            return Err(ValidationError::new(
                field,
                format!("`{path}` is not a free parameter: expected `materials.<name>.<parameter>` or `{YAW}`"),
            ));
        }
        let specs = &request.object.materials;
        let Some(index) = specs.iter().position(|m| material_name(m) == name) else {
            let names: Vec<&str> = specs.iter().map(material_name).collect();
            return Err(ValidationError::new(
                field,
                format!(
                    "`{path}`: no material named `{name}` (materials: {})",
                    names.join(", ")
                ),
            ));
        };
        let mfield = format!("object.materials[{index}]");
        if let std::collections::btree_map::Entry::Vacant(slot) = materials.entry(index) {
            slot.insert(expanded(&specs[index], &mfield)?);
        }
        let m = &materials[&index];
        let model = m.model.clone().unwrap_or_default();
        let params = material_params(&model, m.normalised.unwrap_or(false));
        let Some(&(_, bound)) = params.iter().find(|(n, _)| *n == param) else {
            let names: Vec<&str> = params.iter().map(|p| p.0).collect();
            return Err(ValidationError::new(
                field,
                format!(
                    "`{path}`: `{param}` is not a parameter of material `{name}` (model `{model}`: {})",
                    names.join(", ")
                ),
            ));
        };
        let current = get_field(m, param).ok_or_else(|| {
            ValidationError::new(
                field.clone(),
                format!("`{path}` has no value in the request"),
            )
        })?;
        targets.push(Target::Material {
            index,
            field: param.to_string(),
        });
        bounds.push(bound);
        start.push(current);
    }
    for (name, &v) in &opts.start {
        let field = format!("start.{name}");
        let Some(i) = opts.free.iter().position(|p| p == name) else {
            return Err(ValidationError::new(
                field,
                format!("`{name}` is not among the free parameters"),
            ));
        };
        if !v.is_finite() || !bounds[i].contains(v) {
            return Err(ValidationError::new(
                field,
                format!("{v} is out of range {}", bounds[i].describe()),
            ));
        }
        start[i] = v;
    }
    // a start on a bound is moved a little inside it, where the change of variables moves
    for (s, b) in start.iter_mut().zip(&bounds) {
        if b.lo.is_finite() && b.hi.is_finite() {
            let w = b.hi - b.lo;
            *s = s.clamp(b.lo + 1e-4 * w.min(1.0), b.hi - 1e-4 * w.min(1.0));
        }
    }
    // the observed epochs, in the order observed
    let times: Vec<f64> = scene.epochs.iter().map(|e| e.t).collect();
    let mut epochs = Vec::with_capacity(observed.len());
    for (i, o) in observed.iter().enumerate() {
        let f = |name: &str| format!("observed[{i}].{name}");
        if !o.t.is_finite() {
            return Err(ValidationError::new(f("t"), "must be a finite number"));
        }
        if !o.magnitude.is_finite() {
            return Err(ValidationError::new(
                f("magnitude"),
                "must be a finite number",
            ));
        }
        if !(o.sigma.is_finite() && o.sigma > 0.0) {
            return Err(ValidationError::new(
                f("sigma"),
                "must be a finite number > 0",
            ));
        }
        let tol = 1e-6 * o.t.abs().max(1.0);
        let Some(j) = times.iter().position(|&t| (t - o.t).abs() <= tol) else {
            return Err(ValidationError::new(
                f("t"),
                format!("t = {} s is not the time of any epoch of the request", o.t),
            ));
        };
        epochs.push(scene.epochs[j]);
    }
    if observed.len() <= targets.len() {
        return Err(ValidationError::new(
            "observed",
            format!(
                "too few observations: {} for {} free parameters (need at least {})",
                observed.len(),
                targets.len(),
                targets.len() + 1
            ),
        ));
    }
    scene.epochs = epochs;
    let base = scene
        .epochs
        .iter()
        .map(|e| (e.sun, e.observer, e.earth))
        .collect();
    let dark = observed
        .iter()
        .map(|o| o.magnitude)
        .fold(f64::NEG_INFINITY, f64::max)
        + 5.0;
    let problem = Problem {
        scene: RefCell::new(scene),
        base,
        materials,
        targets,
        observed: observed.to_vec(),
        dark,
        last: RefCell::new(Vec::new()),
        evaluations: Cell::new(0),
        error: RefCell::new(None),
    };
    let settings = Settings {
        loss: opts.loss,
        scale: Scale::Known,
        tolerance: 1e-8,
        patience: 50,
        fd_step: 1e-5,
        max_rounds: 8,
    };
    let sol = solve::solve(&problem, &bounds, &start, &settings);
    if let Some(e) = problem.error.borrow_mut().take() {
        return Err(e);
    }
    let cov = solve::covariance(&problem, &bounds, &sol);
    // the curve at the optimum (the covariance's evaluations moved the scene)
    let mut r = vec![0.0; problem.count()];
    if !problem.eval(&sol.p, &mut r) {
        return Err(ValidationError::new(
            "free",
            "the model cannot be evaluated at the optimum",
        ));
    }
    let fitted = problem.last.borrow().clone();
    let chi2: f64 = r.iter().map(|x| x * x).sum();
    let n = observed.len();
    let p = problem.targets.len();
    let dof = n - p;
    let rms_mag = (observed
        .iter()
        .zip(&fitted)
        .map(|(o, m)| (o.magnitude - m.unwrap_or(dark)).powi(2))
        .sum::<f64>()
        / n as f64)
        .sqrt();
    let names = opts.free.clone();
    let parameters: Named = names.iter().cloned().zip(sol.p.iter().copied()).collect();
    let uncertainty = names
        .iter()
        .cloned()
        .zip(cov.sigma.iter().copied())
        .collect();
    let at_bound: Vec<String> = names
        .iter()
        .zip(&sol.p)
        .zip(&bounds)
        .filter(|((_, &v), b)| b.at_bound(v))
        .map(|((n, _), _)| n.clone())
        .collect();
    let mut warnings = Vec::new();
    if !sol.converged {
        warnings.push(format!(
            "the solver stopped before converging: {}",
            sol.termination
        ));
    }
    if !at_bound.is_empty() {
        warnings.push(format!(
            "{} ended on a bound: its uncertainty is one-sided",
            at_bound.join(", ")
        ));
    }
    let dark_epochs = fitted.iter().filter(|m| m.is_none()).count();
    if dark_epochs > 0 {
        warnings.push(format!(
            "the fitted model has no light at {dark_epochs} observed epochs (taken as {dark:.2} mag)"
        ));
    }
    let request_out = fitted_request(request, &problem, &sol.p);
    Ok(LightcurveFit {
        parameters,
        uncertainty,
        start: names.iter().cloned().zip(start.iter().copied()).collect(),
        at_bound,
        chi2,
        dof,
        chi2_dof: chi2 / dof.max(1) as f64,
        rms_mag,
        observations: n,
        correlation: cov.correlation,
        correlation_order: names,
        curve: observed
            .iter()
            .zip(&fitted)
            .map(|(o, m)| FittedEpoch {
                t: o.t,
                observed: o.magnitude,
                sigma: o.sigma,
                fitted: *m,
            })
            .collect(),
        request: request_out,
        warnings,
        solver: SolverReport {
            algorithm: "levenberg-marquardt".into(),
            loss: opts.loss.name().into(),
            starts: 1,
            start_rms: vec![(chi2 / n as f64).sqrt()],
            evaluations: problem.evaluations.get(),
            converged: sol.converged,
            termination: sol.termination,
            wall_time_s: started.elapsed().as_secs_f64(),
        },
    })
}

/// The request with fitted values `p` in place: changed materials as full objects, and a
/// yaw folded into every epoch's attitude (attitude · R_z(ψ)).
fn fitted_request(request: &Request, problem: &Problem, p: &[f64]) -> serde_json::Value {
    let mut out = request.clone();
    let mut materials = problem.materials.clone();
    let mut yaw = None;
    for (t, &v) in problem.targets.iter().zip(p) {
        match t {
            Target::Material { index, field } => {
                set_field(materials.get_mut(index).expect("resolved"), field, v)
            }
            Target::Yaw => yaw = Some(v),
        }
    }
    for (index, m) in materials {
        out.object.materials[index] = MaterialSpec::Full(m);
    }
    if let Some(yaw) = yaw {
        let turn = DQuat::from_rotation_z(yaw.to_radians());
        // A request given by `geometry` has no epochs to fold the yaw into: its fitted
        // yaw is in the report's parameters only.
        for e in out.epochs.iter_mut().flatten() {
            let q = e
                .attitude
                .map(|q| DQuat::from_xyzw(q[1], q[2], q[3], q[0]))
                .unwrap_or(DQuat::IDENTITY);
            let q = (q * turn).normalize();
            e.attitude = Some([q.w, q.x, q.y, q.z]);
        }
    }
    serde_json::to_value(&out).unwrap_or(serde_json::Value::Null)
}

impl LightcurveFit {
    /// The data of the observed-against-fitted plot.
    pub fn plot_data(&self) -> crate::report::fit_plot::LightcurvePlot {
        let mut curve = self.curve.clone();
        curve.sort_by(|a, b| a.t.total_cmp(&b.t));
        crate::report::fit_plot::LightcurvePlot {
            observed: curve.iter().map(|c| (c.t, c.observed, c.sigma)).collect(),
            fitted: curve.iter().map(|c| (c.t, c.fitted)).collect(),
        }
    }
}
