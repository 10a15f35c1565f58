//! `glint fit-brdf`, `glint sample-brdf` and `glint fit-lightcurve`: files in,
//! [`crate::fit`] does the work, a summary out (and the JSON result and a plot when asked).
//!
//! Each command is its arguments and a `run_*` function; what they share (reading a file,
//! `NAME=VALUE` lists, writing the result and the plot, printing warnings) is at the end.

use crate::fit::{brdf, lightcurve, params};
use crate::report::fit_plot;
use crate::scene::validate;
use anyhow::Context;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Debug, clap::Args)]
pub struct FitBrdfArgs {
    /// Samples CSV: header `theta_i_deg,theta_r_deg,phi_deg,brdf_sr` (degrees, sr⁻¹; φ = 180
    /// the forward side of the plane of incidence), optional `weight`, `wavelength_um`.
    pub samples: PathBuf,
    /// seed-microfacet, rough-conductor, ashikhmin-shirley or lambert.
    #[arg(long)]
    pub model: String,
    /// Write the result as JSON.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write the plot (measured points, model curves per incidence): `*.png` as PNG,
    /// anything else SVG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Hold parameters fixed: `n=0.18,k=3.6`.
    #[arg(long, value_name = "NAME=VALUE,...")]
    pub fix: Option<String>,
    /// huber (default), cauchy or l2.
    #[arg(long, default_value = "huber")]
    pub loss: String,
    /// Residual space: log (default) or linear.
    #[arg(long, default_value = "log")]
    pub space: String,
    /// seed-microfacet only: fit the normalised form (km the lobe's albedo at normal
    /// incidence; kd + km ≤ 1), as a material with `"normalised": true`.
    #[arg(long)]
    pub normalised: bool,
}

/// `glint fit-brdf`: a material model fitted to the samples of a CSV file.
pub fn run_brdf(args: &FitBrdfArgs) -> anyhow::Result<()> {
    let text = read_text(&args.samples)?;
    let samples = brdf::parse_csv(&text)
        .map_err(|e| anyhow::anyhow!("invalid samples {}: {e}", args.samples.display()))?;
    let request = brdf::BrdfFitRequest {
        model: args.model.clone(),
        samples: Vec::new(),
        fixed: args
            .fix
            .as_deref()
            .map(|f| assignments("--fix", f))
            .transpose()?,
        loss: Some(args.loss.clone()),
        space: Some(args.space.clone()),
        plot: None,
        normalised: Some(args.normalised),
    };
    let opts = brdf::Options::from_request(&request).map_err(|e| {
        anyhow::anyhow!(
            "--{}: {}",
            e.field
                .split('.')
                .next()
                .unwrap_or("")
                .replace("fixed", "fix"),
            e.message
        )
    })?;
    let result = brdf::fit(&samples, &opts).map_err(|e| match e.field.strip_prefix("fixed.") {
        Some(name) => anyhow::anyhow!("--fix {name}: {}", e.message),
        None => anyhow::anyhow!("{e}"),
    })?;
    print_brdf_summary(&result);
    write_result(args.out.as_deref(), &result)?;
    if let Some(plot) = &args.plot {
        let brdf = result.brdf().context("fitted parameters")?;
        let groups = brdf::plot_data(&samples, &brdf);
        let title = format!("{} fitted to {}", result.model, file_name(&args.samples));
        write_plot(
            plot,
            || fit_plot::brdf_svg(&title, &groups),
            || fit_plot::brdf_png(&title, &groups),
        )?;
    }
    Ok(())
}

/// The fit's summary on standard output: the solver's work, each parameter with its 1σ,
/// the misfit and albedo, the warnings.
fn print_brdf_summary(result: &brdf::BrdfFit) {
    println!(
        "{}{} fitted to {} samples ({} starts, {} evaluations, {:.2} s, loss {}, {} space)",
        result.model,
        if result.normalised {
            " (normalised)"
        } else {
            ""
        },
        result.samples,
        result.solver.starts,
        result.solver.evaluations,
        result.solver.wall_time_s,
        result.solver.loss,
        result.space
    );
    for (name, value) in &result.parameters {
        match (
            result.uncertainty.get(name),
            result.fixed.contains_key(name),
        ) {
            (_, true) => println!("  {name:<10} {value:.6} (fixed)"),
            (Some(Some(s)), _) => println!("  {name:<10} {value:.6} ± {s:.2e}"),
            _ => println!("  {name:<10} {value:.6} ± (undetermined)"),
        }
    }
    println!(
        "  rms {:.4e} sr⁻¹, rms_log {}, albedo (normal incidence) {:.3}",
        result.rms,
        result.rms_log.map_or("-".into(), |r| format!("{r:.4}")),
        result.albedo
    );
    print_warnings(&result.warnings);
}

#[derive(Debug, clap::Args)]
pub struct SampleBrdfArgs {
    /// seed-microfacet, rough-conductor, ashikhmin-shirley or lambert.
    #[arg(long)]
    pub model: String,
    /// Every parameter of the model: `kd=0.1,km=0.2,slope_rms=0.007,n=0.2,k=2.5`.
    #[arg(long, value_name = "NAME=VALUE,...")]
    pub params: String,
    /// Relative (log-normal) noise σ: each value times e^{σ·N(0,1)}.
    #[arg(long, default_value_t = 0.0)]
    pub noise: f64,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// The CSV to write (`fit-brdf` reads it).
    #[arg(long)]
    pub out: PathBuf,
    /// seed-microfacet only: the normalised form (km the lobe's albedo at normal
    /// incidence).
    #[arg(long)]
    pub normalised: bool,
}

/// `glint sample-brdf`: synthetic samples of a model at the paper's Fig. 2 geometry.
pub fn run_sample(args: &SampleBrdfArgs) -> anyhow::Result<()> {
    let model = brdf::Model::parse(&args.model).ok_or_else(|| {
        anyhow::anyhow!(
            "--model: unknown model `{}`; expected {}",
            args.model,
            brdf::Model::NAMES
        )
    })?;
    let model = model
        .with_normalised(args.normalised)
        .ok_or_else(|| anyhow::anyhow!("--normalised: applies only to model `seed-microfacet`"))?;
    let p = model_values(model, &args.params)?;
    if !(args.noise.is_finite() && args.noise >= 0.0) {
        anyhow::bail!("--noise: must be a finite number >= 0");
    }
    if model.is_normalised() && p[0] + p[1] > 1.0 {
        anyhow::bail!(
            "--params: kd + km = {} is above 1 (the normalised form's albedo at normal incidence)",
            p[0] + p[1]
        );
    }
    let brdf = model.try_build(&p).ok_or_else(|| {
        anyhow::anyhow!(
            "--params: with this n and k the lobe reflects nothing; km cannot be an albedo"
        )
    })?;
    let samples = brdf::synthetic(&brdf, &brdf::paper_geometry(), args.noise, args.seed);
    let comment = format!(
        "SYNTHETIC samples, not a measurement: `glint sample-brdf --model {}{} --params {} --noise {} --seed {}`\n\
         (the paper's Fig. 2 geometry: incidence 10, 30, 45, 60 degrees; phi = 180 is the forward side)",
        model.name(),
        if model.is_normalised() { " --normalised" } else { "" },
        args.params,
        args.noise,
        args.seed
    );
    std::fs::write(&args.out, brdf::to_csv(&samples, &comment))
        .with_context(|| format!("cannot write {}", args.out.display()))?;
    println!("{} samples: {}", samples.len(), args.out.display());
    Ok(())
}

/// `--params`: every parameter of `model`, in its order, each within its bounds, and no
/// other.
fn model_values(model: brdf::Model, text: &str) -> anyhow::Result<Vec<f64>> {
    let given = assignments("--params", text)?;
    let mut p = Vec::new();
    for spec in model.params() {
        let v = *given.get(spec.name).ok_or_else(|| {
            anyhow::anyhow!(
                "--params: `{}` is required by model `{}`",
                spec.name,
                model.name()
            )
        })?;
        params::check_in_bound(spec.name.to_string(), v, spec.bound)
            .map_err(|e| anyhow::anyhow!("--params {}: {}", e.field, e.message))?;
        p.push(v);
    }
    for name in given.keys() {
        if !model.params().iter().any(|s| s.name == name) {
            anyhow::bail!(
                "--params {name}: not a parameter of model `{}`",
                model.name()
            );
        }
    }
    Ok(p)
}

#[derive(Debug, clap::Args)]
pub struct FitLightcurveArgs {
    /// The request (JSON): shape, materials and the epochs' geometry.
    pub request: PathBuf,
    /// Observed magnitudes, CSV: `t` (an epoch's t), `magnitude` and `sigma` columns.
    #[arg(long)]
    pub observed: PathBuf,
    /// Free parameters: `materials.panel.albedo,materials.body.slope_rms,attitude.yaw_deg`.
    #[arg(long)]
    pub free: String,
    /// Starting values: `materials.panel.albedo=0.3,attitude.yaw_deg=10` (default: the
    /// request's values, yaw 0).
    #[arg(long)]
    pub start: Option<String>,
    /// σ (mag) for every row when the CSV has no error column.
    #[arg(long)]
    pub sigma: Option<f64>,
    /// l2 (default: weighted least squares), huber or cauchy.
    #[arg(long, default_value = "l2")]
    pub loss: String,
    /// With the yaw free: yaws screened, evenly round the circle from its start (the three
    /// of lowest χ² are solved); 1 solves from the start alone.
    #[arg(long, default_value_t = lightcurve::DEFAULT_YAW_STARTS)]
    pub yaw_starts: usize,
    /// Most light curves the fit may evaluate, uncertainties included.
    #[arg(long, default_value_t = lightcurve::DEFAULT_MAX_EVALUATIONS)]
    pub max_evaluations: usize,
    /// Write the result as JSON.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write the plot (observed, fitted, residuals): `*.png` as PNG, anything else SVG.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// `glint fit-lightcurve`: a request's free parameters fitted to observed magnitudes.
pub fn run_lightcurve(args: &FitLightcurveArgs) -> anyhow::Result<()> {
    let text = read_text(&args.request)?;
    let request = validate::parse_request(&text)
        .map_err(|e| anyhow::anyhow!("invalid request {}: {e}", args.request.display()))?;
    let observed_text = read_text(&args.observed)?;
    let observed = lightcurve::parse_observed_csv(&observed_text, args.sigma)
        .map_err(|e| anyhow::anyhow!("invalid observations {}: {e}", args.observed.display()))?;
    let free: Vec<String> = args
        .free
        .split(',')
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .collect();
    let body = lightcurve::LightcurveFitRequest {
        request: request.clone(),
        observed: Vec::new(),
        free: free.clone(),
        start: args
            .start
            .as_deref()
            .map(|s| assignments("--start", s))
            .transpose()?,
        loss: Some(args.loss.clone()),
        yaw_starts: Some(args.yaw_starts),
        max_evaluations: Some(args.max_evaluations),
    };
    let opts = lightcurve::Options::from_request(&body)
        .map_err(|e| anyhow::anyhow!("--{}: {}", e.field.replace('_', "-"), e.message))?;
    let result = lightcurve::fit(&request, &observed, &opts).map_err(|e| {
        if let Some(i) = e
            .field
            .strip_prefix("free[")
            .and_then(|r| r.strip_suffix(']'))
        {
            anyhow::anyhow!(
                "--free (item {}): {}",
                i.parse::<usize>().map_or(0, |i| i + 1),
                e.message
            )
        } else if let Some(name) = e.field.strip_prefix("start.") {
            anyhow::anyhow!("--start {name}: {}", e.message)
        } else if e.field == "max_evaluations" {
            anyhow::anyhow!("--max-evaluations: {}", e.message)
        } else {
            anyhow::anyhow!("{e}")
        }
    })?;
    print_lightcurve_summary(&result, &free);
    write_result(args.out.as_deref(), &result)?;
    if let Some(plot) = &args.plot {
        let data = result.plot_data();
        let title = format!(
            "{} fitted to {}",
            file_name(&args.request),
            file_name(&args.observed)
        );
        write_plot(
            plot,
            || fit_plot::lightcurve_svg(&title, &data),
            || fit_plot::lightcurve_png(&title, &data),
        )?;
    }
    Ok(())
}

/// The fit's summary on standard output: the work, each free parameter (in the order
/// given) with its 1σ and start, χ² and the RMS, the warnings.
fn print_lightcurve_summary(result: &lightcurve::LightcurveFit, free: &[String]) {
    println!(
        "{} parameters fitted to {} observations: {} light curves in {:.2} s ({} solved from \
         the starts)",
        free.len(),
        result.observations,
        result.solver.evaluations,
        result.solver.wall_time_s,
        result.solver.starts
    );
    for name in free {
        let v = result.parameters[name];
        match result.uncertainty.get(name).copied().flatten() {
            Some(s) => println!(
                "  {name:<32} {v:.6} ± {s:.2e} (start {:.6})",
                result.start[name]
            ),
            None => println!("  {name:<32} {v:.6} ± (undetermined)"),
        }
    }
    println!(
        "  chi2 {:.2} for {} dof (chi2/dof {:.3}), rms {:.4} mag",
        result.chi2, result.dof, result.chi2_dof, result.rms_mag
    );
    print_warnings(&result.warnings);
}

/// A file's text; the error names the file.
fn read_text(path: &Path) -> anyhow::Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))
}

/// `name=value,name=value` → map; errors name the option and the item.
fn assignments(option: &str, text: &str) -> anyhow::Result<BTreeMap<String, f64>> {
    let mut out = BTreeMap::new();
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (name, value) = item
            .split_once('=')
            .ok_or_else(|| anyhow::anyhow!("{option}: `{item}` is not NAME=VALUE"))?;
        let v: f64 = value
            .trim()
            .parse()
            .map_err(|_| anyhow::anyhow!("{option}: `{value}` is not a number (in `{item}`)"))?;
        out.insert(name.trim().to_string(), v);
    }
    Ok(out)
}

fn print_warnings(warnings: &[String]) {
    for w in warnings {
        println!("warning: {w}");
    }
}

/// `--out`: the result as pretty JSON, when asked.
fn write_result(out: Option<&Path>, result: &impl Serialize) -> anyhow::Result<()> {
    if let Some(out) = out {
        std::fs::write(out, serde_json::to_string_pretty(result)? + "\n")
            .with_context(|| format!("cannot write {}", out.display()))?;
        println!("result: {}", out.display());
    }
    Ok(())
}

fn is_png(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn write_plot(
    path: &Path,
    svg: impl FnOnce() -> Result<String, String>,
    png: impl FnOnce() -> Result<Vec<u8>, String>,
) -> anyhow::Result<()> {
    let bytes = if is_png(path) {
        png().map_err(|e| anyhow::anyhow!("plot: {e}"))?
    } else {
        svg()
            .map_err(|e| anyhow::anyhow!("plot: {e}"))?
            .into_bytes()
    };
    std::fs::write(path, bytes).with_context(|| format!("cannot write {}", path.display()))?;
    println!("plot: {}", path.display());
    Ok(())
}
