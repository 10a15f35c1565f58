//! `object.materials`: each material, a preset or a model with its parameters, each
//! parameter in its range and none that the model does not use; names unique.

use super::table::{at, column, PARAMETERS};
use super::values::{err, in_range, positive, vector};
use super::ValidationError;
use crate::brdf::{AshikhminShirley, Brdf, Lambert, RoughConductor, SeedMicrofacet, Shadowing};
use crate::scene::request::{MaterialObject, MaterialSpec, Request, ShadowingSpec};
use crate::scene::{presets, Material};
use glam::DVec3;

/// The request's materials, in order: at least one, each checked, no name twice.
pub(super) fn materials(req: &Request) -> Result<Vec<Material>, ValidationError> {
    if req.object.materials.is_empty() {
        return err("object.materials", "must list at least one material");
    }
    let materials = req
        .object
        .materials
        .iter()
        .enumerate()
        .map(|(i, m)| material(&format!("object.materials[{i}]"), m))
        .collect::<Result<Vec<_>, _>>()?;
    for (i, m) in materials.iter().enumerate() {
        if materials[..i].iter().any(|o| o.name == m.name) {
            return err(
                format!("object.materials[{i}].name"),
                format!("duplicate material name `{}`", m.name),
            );
        }
    }
    Ok(materials)
}

/// One material of a request, checked (`field` is its path, e.g. `object.materials[1]`);
/// the light-curve fit re-validates a material whose parameter it changed.
pub(crate) fn material(field: &str, spec: &MaterialSpec) -> Result<Material, ValidationError> {
    let preset = |name: &str, f: &str| {
        presets::find(name).ok_or_else(|| {
            ValidationError::new(
                f,
                format!("unknown preset `{name}`; presets: {}", presets::names()),
            )
        })
    };
    match spec {
        MaterialSpec::Preset(name) => Ok(Material {
            name: name.clone(),
            brdf: (preset(name, field)?.brdf)(),
            two_sided: false,
            tangent: DVec3::X,
        }),
        MaterialSpec::Full(m) if m.spectral.is_some() => {
            // each point of the table a material of its own; the first stands for it here
            // (validate::spectral puts it at the band's wavelengths)
            let first = check_points(field, m)?;
            material(field, &MaterialSpec::Full(first))
        }
        MaterialSpec::Full(m) => {
            if m.name.is_empty() {
                return err(format!("{field}.name"), "must not be empty");
            }
            let two_sided = m.two_sided.unwrap_or(false);
            match (&m.preset, &m.model) {
                (Some(_), Some(_)) => err(
                    format!("{field}.model"),
                    "give either `model` or `preset`, not both",
                ),
                (Some(p), None) => {
                    let brdf = (preset(p, &format!("{field}.preset"))?.brdf)();
                    only(field, m, &[])?;
                    Ok(Material {
                        name: m.name.clone(),
                        brdf,
                        two_sided,
                        tangent: DVec3::X,
                    })
                }
                (None, None) => err(format!("{field}.model"), "is required (or give `preset`)"),
                (None, Some(model)) => Ok(Material {
                    name: m.name.clone(),
                    brdf: model_brdf(field, model, m)?,
                    two_sided,
                    tangent: match m.tangent {
                        None => DVec3::X,
                        Some(t) => {
                            let t = vector(&format!("{field}.tangent"), t)?;
                            if t.length() == 0.0 {
                                return err(format!("{field}.tangent"), "must not be zero");
                            }
                            t.normalize()
                        }
                    },
                }),
            }
        }
    }
}

/// Rejects parameters that the model does not use, naming the first one.
fn only(field: &str, m: &MaterialObject, allowed: &[&str]) -> Result<(), ValidationError> {
    let given = [
        ("kd", m.kd.is_some()),
        ("km", m.km.is_some()),
        ("slope_rms", m.slope_rms.is_some()),
        ("normalised", m.normalised.is_some()),
        ("n", m.n.is_some()),
        ("k", m.k.is_some()),
        ("albedo", m.albedo.is_some()),
        ("alpha", m.alpha.is_some()),
        ("shadowing", m.shadowing.is_some()),
        ("rd", m.rd.is_some()),
        ("rs", m.rs.is_some()),
        ("nu", m.nu.is_some()),
        ("nv", m.nv.is_some()),
        ("tangent", m.tangent.is_some()),
    ];
    for (name, present) in given {
        if present && !allowed.contains(&name) {
            let what = m
                .model
                .as_deref()
                .map_or("a preset".to_string(), |s| format!("model `{s}`"));
            return err(
                format!("{field}.{name}"),
                format!("is not a parameter of {what}"),
            );
        }
    }
    Ok(())
}

/// The BRDF of `model` (a name from the request), each of its parameters checked.
fn model_brdf(field: &str, model: &str, m: &MaterialObject) -> Result<Brdf, ValidationError> {
    let f = |p: &str| format!("{field}.{p}");
    let req = |p: &str, v: Option<f64>| {
        v.ok_or_else(|| ValidationError::new(f(p), format!("is required by model `{model}`")))
    };
    match model {
        "lambert" => {
            only(field, m, &["albedo"])?;
            Ok(Brdf::Lambert(Lambert {
                albedo: in_range(&f("albedo"), req("albedo", m.albedo)?, 0.0, 1.0)?,
            }))
        }
        "seed-microfacet" => {
            only(
                field,
                m,
                &["kd", "km", "slope_rms", "n", "k", "normalised"],
            )?;
            let normalised = m.normalised.unwrap_or(false);
            let kd = in_range(&f("kd"), req("kd", m.kd)?, 0.0, 1.0)?;
            let km_max = if normalised { 1.0 } else { 1e3 };
            let km = in_range(&f("km"), req("km", m.km)?, 0.0, km_max)?;
            let d = in_range(&f("slope_rms"), req("slope_rms", m.slope_rms)?, 1e-6, 10.0)?;
            let n = positive(&f("n"), req("n", m.n)?)?;
            let k = in_range(&f("k"), m.k.unwrap_or(0.0), 0.0, 1e3)?;
            if !normalised {
                return Ok(Brdf::SeedMicrofacet(SeedMicrofacet::new(kd, km, d, n, k)));
            }
            match crate::brdf::albedo::normalised_seed(kd, km, d, n, k) {
                Ok(seed) => Ok(Brdf::SeedMicrofacet(seed)),
                Err(a) => err(
                    f("n"),
                    format!(
                        "with n = {n}, k = {k} the surface reflects (almost) nothing \
                         (lobe albedo {a:.1e}): km cannot be scaled to an albedo"
                    ),
                ),
            }
        }
        "rough-conductor" => {
            only(field, m, &["alpha", "n", "k", "kd", "shadowing"])?;
            let alpha = in_range(&f("alpha"), req("alpha", m.alpha)?, 1e-6, 10.0)?;
            let n = positive(&f("n"), req("n", m.n)?)?;
            let k = in_range(&f("k"), req("k", m.k)?, 0.0, 1e3)?;
            let kd = in_range(&f("kd"), m.kd.unwrap_or(0.0), 0.0, 1.0)?;
            let shadowing = match m.shadowing {
                None => Shadowing::default(),
                Some(ShadowingSpec::Separable) => Shadowing::Separable,
                Some(ShadowingSpec::Correlated) => Shadowing::Correlated,
            };
            Ok(Brdf::RoughConductor(
                RoughConductor::new(alpha, n, k, kd).with_shadowing(shadowing),
            ))
        }
        "ashikhmin-shirley" => {
            only(field, m, &["rd", "rs", "nu", "nv", "tangent"])?;
            let rd = in_range(&f("rd"), req("rd", m.rd)?, 0.0, 1.0)?;
            let rs = in_range(&f("rs"), req("rs", m.rs)?, 0.0, 1.0)?;
            let nu = in_range(&f("nu"), req("nu", m.nu)?, 0.0, 1e7)?;
            let nv = in_range(&f("nv"), req("nv", m.nv)?, 0.0, 1e7)?;
            Ok(Brdf::AshikhminShirley(AshikhminShirley::new(rd, rs, nu, nv)))
        }
        other => err(
            f("model"),
            format!("unknown model `{other}`; expected seed-microfacet, lambert, rough-conductor or ashikhmin-shirley"),
        ),
    }
}

/// Every point of a material's table validated as a material of its own; an error names
/// the table's entry (`….spectral.n[2]`).
fn check_points(field: &str, m: &MaterialObject) -> Result<MaterialObject, ValidationError> {
    let s = m.spectral.as_ref().expect("a spectral material");
    let first = at(field, m, s.wavelength_um[0])?;
    for (j, &l) in s.wavelength_um.iter().enumerate() {
        let point = at(field, m, l)?;
        if let Err(e) = material(field, &MaterialSpec::Full(point)) {
            // a tabulated parameter out of its range: name the table's entry
            let named = PARAMETERS
                .iter()
                .find(|p| column(s, p).is_some() && e.field == format!("{field}.{p}"));
            return Err(match named {
                Some(p) => ValidationError::new(format!("{field}.spectral.{p}[{j}]"), e.message),
                None => e,
            });
        }
    }
    Ok(first)
}

#[cfg(test)]
mod tests {
    use crate::scene::test_fixtures::{check, refused};
    use crate::scene::validate::ValidationError;
    use serde_json::json;

    #[test]
    fn a_material_list_needs_one_and_no_name_twice() {
        let e = refused(|v| v["object"]["materials"] = json!([]));
        assert_eq!(
            e,
            ValidationError::new("object.materials", "must list at least one material")
        );
        let e = refused(|v| {
            let m = v["object"]["materials"][0].clone();
            v["object"]["materials"] = json!([m.clone(), m]);
        });
        assert_eq!(
            e,
            ValidationError::new(
                "object.materials[1].name",
                "duplicate material name `surface`"
            )
        );
    }

    #[test]
    fn a_parameter_is_checked_and_named_in_its_material() {
        let e = refused(|v| v["object"]["materials"][0]["albedo"] = json!(1.5));
        assert_eq!(e.field, "object.materials[0].albedo");
        assert_eq!(e.message, "must be between 0 and 1, got 1.5");
        let e = refused(|v| v["object"]["materials"][0]["kd"] = json!(0.1));
        assert_eq!(
            e,
            ValidationError::new(
                "object.materials[0].kd",
                "is not a parameter of model `lambert`"
            )
        );
    }

    #[test]
    fn a_preset_is_found_by_name() {
        let e = refused(|v| v["object"]["materials"][0] = json!({"name": "s", "preset": "nope"}));
        assert_eq!(e.field, "object.materials[0].preset");
        assert!(e.message.starts_with("unknown preset `nope`"), "{e}");
    }

    #[test]
    fn a_tangent_is_made_a_unit_vector() {
        let scene = check(|v| {
            v["object"]["materials"][0] = json!({
                "name": "surface", "model": "ashikhmin-shirley",
                "rd": 0.2, "rs": 0.1, "nu": 10.0, "nv": 100.0, "tangent": [0.0, 2.0, 0.0]
            })
        })
        .expect("valid");
        assert_eq!(scene.materials[0].tangent, glam::DVec3::Y);
    }
}
