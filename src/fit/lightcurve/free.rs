//! The free parameters: paths resolved against the request (a material's parameter with
//! its bounds and current value, or the yaw), their starts, and the fitted values put back
//! into the request.

use super::{Options, YAW};
use crate::fit::params::{check_in_bound, Bound};
use crate::scene::request::{MaterialObject, MaterialSpec};
use crate::scene::{Request, ValidationError};
use glam::DQuat;
use std::collections::BTreeMap;

/// A resolved free parameter.
#[derive(Debug, Clone)]
pub(super) enum Target {
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

/// The free parameters resolved against `request`, in the order of `opts.free`.
pub(super) struct Resolved {
    pub targets: Vec<Target>,
    pub bounds: Vec<Bound>,
    /// Where each starts: `opts.start`'s value or the request's (0 for the yaw), a little
    /// inside a bound it is on.
    pub start: Vec<f64>,
    /// Full material objects (presets expanded) of the materials a parameter touches.
    pub materials: BTreeMap<usize, MaterialObject>,
}

/// Resolves every path of `opts.free` and its start. Errors name `free[i]` or
/// `start.<path>`.
pub(super) fn resolve(request: &Request, opts: &Options) -> Result<Resolved, ValidationError> {
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
        let (target, bound, current) = resolve_path(request, path, field, &mut materials)?;
        targets.push(target);
        bounds.push(bound);
        start.push(current);
    }
    apply_starts(opts, &bounds, &mut start)?;
    Ok(Resolved {
        targets,
        bounds,
        start,
        materials,
    })
}

/// One free path (error field `field`): what it changes, its bounds and its value in the
/// request; the material it names is expanded into `materials` once.
fn resolve_path(
    request: &Request,
    path: &str,
    field: String,
    materials: &mut BTreeMap<usize, MaterialObject>,
) -> Result<(Target, Bound, f64), ValidationError> {
    if path == YAW {
        return Ok((Target::Yaw, Bound::FREE, 0.0));
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
    Ok((
        Target::Material {
            index,
            field: param.to_string(),
        },
        bound,
        current,
    ))
}

/// `opts.start`'s values in place of the request's, checked against the bounds; then a
/// start on a bound moved a little inside it.
fn apply_starts(
    opts: &Options,
    bounds: &[Bound],
    start: &mut [f64],
) -> Result<(), ValidationError> {
    for (name, &v) in &opts.start {
        let field = format!("start.{name}");
        let Some(i) = opts.free.iter().position(|p| p == name) else {
            return Err(ValidationError::new(
                field,
                format!("`{name}` is not among the free parameters"),
            ));
        };
        check_in_bound(field, v, bounds[i])?;
        start[i] = v;
    }
    // a start on a bound is moved a little inside it, where the change of variables moves
    for (s, b) in start.iter_mut().zip(bounds) {
        if b.lo.is_finite() && b.hi.is_finite() {
            let w = b.hi - b.lo;
            *s = s.clamp(b.lo + 1e-4 * w.min(1.0), b.hi - 1e-4 * w.min(1.0));
        }
    }
    Ok(())
}

/// Values `p` of the free parameters `targets` put in place: the materials they change,
/// as full objects (`materials` with the values set), and the yaw (degrees) when it is
/// free.
pub(super) fn assign(
    targets: &[Target],
    materials: &BTreeMap<usize, MaterialObject>,
    p: &[f64],
) -> (BTreeMap<usize, MaterialObject>, Option<f64>) {
    let mut materials = materials.clone();
    let mut yaw = None;
    for (t, &v) in targets.iter().zip(p) {
        match t {
            Target::Material { index, field } => {
                set_field(materials.get_mut(index).expect("resolved"), field, v)
            }
            Target::Yaw => yaw = Some(v),
        }
    }
    (materials, yaw)
}

/// The request with fitted values `p` of `targets` in place (`materials` as
/// [`Resolved::materials`]): changed materials as full objects, and a yaw folded into
/// every epoch's attitude (attitude · R_z(ψ)).
pub(super) fn fitted_request(
    request: &Request,
    materials: &BTreeMap<usize, MaterialObject>,
    targets: &[Target],
    p: &[f64],
) -> serde_json::Value {
    let mut out = request.clone();
    let (materials, yaw) = assign(targets, materials, p);
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
