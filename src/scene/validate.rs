//! Request → Scene: every input checked at the boundary, every error naming its field.

use super::request::{
    EpochSpec, ExposureSpec, MaterialObject, MaterialSpec, MeshSpec, Request, ShadowingSpec,
    ThumbnailSpec, TimeSpec,
};
use super::{
    presets, EarthshineModel, Epoch, Exposure, Illumination, Material, Method, Scene, Thumbnails,
};
use crate::brdf::{AshikhminShirley, Brdf, Lambert, RoughConductor, SeedMicrofacet, Shadowing};
use crate::geometry::{builtin, obj, Mesh};
use crate::orbit::time::parse_utc;
use crate::orbit::UtcTime;
use crate::radiometry::{planck, AU_M, EARTH_RADIUS_M, SUN_RADIUS_M};
use glam::{DQuat, DVec3};

pub use super::error::{Limits, ValidationError};

/// Parses request JSON, turning serde's errors into field-naming ones.
pub fn parse_request(text: &str) -> Result<Request, ValidationError> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let request = serde_path_to_error::deserialize(&mut *de).map_err(|e| {
        let mut field = e.path().to_string();
        if field == "." {
            field.clear();
        }
        let inner = e.into_inner();
        let message = inner.to_string();
        // Name the unknown or repeated field itself; serde_path_to_error's path may
        // already end with it.
        let named_in = message
            .strip_prefix("unknown field `")
            .or_else(|| message.strip_prefix("duplicate field `"));
        if let Some(rest) = named_in {
            if let Some(name) = rest.split('`').next() {
                let named = field == name || field.ends_with(&format!(".{name}"));
                field = if named {
                    field
                } else if field.is_empty() {
                    name.to_string()
                } else {
                    format!("{field}.{name}")
                };
            }
        }
        // Strip serde's "at line L column C" suffix from the field-level message but
        // keep it for syntax errors, where there is no field to name.
        // serde reads a fixed-length array ([f64; 3]) and then expects its end: a longer
        // one reports "trailing characters" at the field, which is a wrong value (422),
        // not broken JSON
        let message = if message.starts_with("trailing characters") && !field.is_empty() {
            "more elements than this fixed-length array takes".to_string()
        } else if inner.is_syntax() || inner.is_eof() {
            format!("invalid JSON: {message}")
        } else {
            match message.rfind(" at line ") {
                Some(i) => message[..i].to_string(),
                None => message,
            }
        };
        ValidationError { field, message }
    })?;
    // one request per body: anything after it but whitespace is refused, not ignored
    de.end().map_err(|e| {
        ValidationError::new("", format!("invalid JSON: data after the request ({e})"))
    })?;
    Ok(request)
}

/// Parses any JSON body type with the same field-naming errors as [`parse_request`]
/// (e.g. `samples[3].phi_deg: invalid type: string "x", expected f64`).
pub fn parse_json<T: serde::de::DeserializeOwned>(text: &str) -> Result<T, ValidationError> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let value: T = serde_path_to_error::deserialize(&mut *de).map_err(|e| {
        let mut field = e.path().to_string();
        if field == "." {
            field.clear();
        }
        let inner = e.into_inner();
        let message = inner.to_string();
        if let Some(rest) = message.strip_prefix("unknown field `") {
            if let Some(name) = rest.split('`').next() {
                if !(field == name || field.ends_with(&format!(".{name}"))) {
                    field = if field.is_empty() {
                        name.to_string()
                    } else {
                        format!("{field}.{name}")
                    };
                }
            }
        }
        let message = if inner.is_syntax() || inner.is_eof() {
            format!("invalid JSON: {message}")
        } else {
            match message.rfind(" at line ") {
                Some(i) => message[..i].to_string(),
                None => message,
            }
        };
        ValidationError { field, message }
    })?;
    de.end().map_err(|e| {
        ValidationError::new("", format!("invalid JSON: data after the body ({e})"))
    })?;
    Ok(value)
}

fn err<T>(field: impl Into<String>, message: impl Into<String>) -> Result<T, ValidationError> {
    Err(ValidationError::new(field, message))
}

fn finite(field: &str, v: f64) -> Result<f64, ValidationError> {
    if v.is_finite() {
        Ok(v)
    } else {
        err(field, "must be a finite number")
    }
}

fn vector(field: &str, v: [f64; 3]) -> Result<DVec3, ValidationError> {
    let d = DVec3::from_array(v);
    if !d.is_finite() {
        return err(field, "must have three finite components");
    }
    if d == DVec3::ZERO {
        return err(field, "must not be the zero vector");
    }
    let l2 = d.length_squared();
    // |v|² must be a normal f64 for the direction and the range to be computed.
    if l2.is_infinite() {
        return err(field, "is too long: its length must be below 1e150");
    }
    if !l2.is_normal() {
        return err(
            field,
            "is too short to give a direction: its length must be above 1e-150",
        );
    }
    Ok(d)
}

fn in_range(field: &str, v: f64, lo: f64, hi: f64) -> Result<f64, ValidationError> {
    finite(field, v)?;
    if v < lo || v > hi {
        return err(field, format!("must be between {lo} and {hi}, got {v}"));
    }
    Ok(v)
}

fn positive(field: &str, v: f64) -> Result<f64, ValidationError> {
    finite(field, v)?;
    if v <= 0.0 {
        return err(field, format!("must be positive, got {v}"));
    }
    Ok(v)
}

/// Checks a whole request.
pub fn validate(req: &Request, limits: &Limits) -> Result<Scene, ValidationError> {
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
    let mesh = mesh(&req.object.mesh, &materials, limits)?;

    let illumination = illumination(req)?;
    let (epoch_specs, built) = match (&req.epochs, &req.geometry) {
        (Some(_), Some(_)) => {
            return err("geometry", "give either `epochs` or `geometry`, not both")
        }
        (None, None) => return err("epochs", "is required (or give `geometry`)"),
        (Some(e), None) => (e.as_slice(), None),
        (None, Some(g)) => (&[][..], Some(super::geometry::build(g, limits)?)),
    };
    if built.is_none() && epoch_specs.is_empty() {
        return err("epochs", "must list at least one epoch");
    }
    if epoch_specs.len() > limits.max_epochs {
        return err(
            "epochs",
            format!(
                "too many epochs: {} (limit {})",
                epoch_specs.len(),
                limits.max_epochs
            ),
        );
    }
    let earthshine_explicit = req
        .illumination
        .as_ref()
        .and_then(|i| i.earthshine.as_ref())
        .is_some();
    // Eq. 12 is a far-field sum (every face seen along one direction, at one range): an
    // observer inside the object's bounding sphere is no telescope
    let (centre, radius) = mesh.bounding_sphere();
    let (given, sky, warnings) = match built {
        Some(b) => (Some(b.epochs), b.sky, b.warnings),
        None => (None, Vec::new(), Vec::new()),
    };
    let from_specs = given.is_none();
    let checked: Vec<Epoch> = match given {
        Some(e) => e,
        None => epoch_specs
            .iter()
            .enumerate()
            .map(|(i, e)| epoch(&format!("epochs[{i}]"), e))
            .collect::<Result<_, _>>()?,
    };
    // a geometry's epochs are named by their index in the computed list
    let name = |i: usize| {
        if from_specs {
            format!("epochs[{i}]")
        } else {
            format!("geometry (epoch {i})")
        }
    };
    let epochs = checked
        .into_iter()
        .enumerate()
        .map(|(i, ep)| {
            let range = (ep.observer - centre).length();
            if range <= radius {
                return err(
                    format!("{}.observer", name(i)),
                    format!(
                        "the observer is {range:.3e} m from the object's centre, within its \
                         bounding radius {radius:.3e} m: give the observer's position \
                         relative to the object, in metres, from outside it"
                    ),
                );
            }
            if ep.earth.is_none()
                && earthshine_explicit
                && illumination.earthshine != EarthshineModel::Off
            {
                return err(
                    format!("{}.earth", name(i)),
                    "is required when illumination.earthshine is not \"off\"",
                );
            }
            Ok(ep)
        })
        .collect::<Result<Vec<_>, _>>()?;

    let tolerance = match req.tolerance {
        None => 1e-3,
        Some(t) => {
            finite("tolerance", t)?;
            if !(1e-9..=0.5).contains(&t) {
                return err(
                    "tolerance",
                    format!("must be between 1e-9 and 0.5, got {t}"),
                );
            }
            t
        }
    };
    let method = match req.method.as_deref() {
        None | Some("auto") => Method::Auto,
        Some("adaptive") => Method::Adaptive,
        Some("silhouette") => Method::Silhouette,
        Some("centroid") => Method::Centroid,
        Some("convex") => Method::Convex,
        Some("image") => Method::Image,
        Some(other) => {
            return err(
                "method",
                format!(
                    "unknown method `{other}`; expected auto, adaptive, centroid, convex or image"
                ),
            )
        }
    };
    let (image_size, image_samples, centroid_subdivisions) =
        fidelity(req, method, mesh.triangles.len(), limits)?;
    let thumbnails = req
        .thumbnails
        .as_ref()
        .map(|t| thumbnails(t, epochs.len()))
        .transpose()?;
    work(
        limits,
        mesh.triangles.len(),
        epochs.len(),
        (method == Method::Image).then_some((image_size, image_samples)),
        thumbnails.as_ref(),
    )?;
    Ok(Scene {
        mesh,
        materials,
        epochs,
        illumination,
        tolerance,
        method,
        image_size,
        image_samples,
        centroid_subdivisions,
        thumbnails,
        clip_shadows: true,
        sky,
        warnings,
    })
}

/// Refuses a request whose work, estimated before any is done, is over the limits:
/// triangles × epochs, and the pixel samples of the `image` method (`image`: its size and
/// samples per side) and of the thumbnails.
fn work(
    limits: &Limits,
    triangles: usize,
    epochs: usize,
    image: Option<(u32, u32)>,
    thumbnails: Option<&Thumbnails>,
) -> Result<(), ValidationError> {
    let triangle_epochs = triangles as u64 * epochs as u64;
    if triangle_epochs > limits.max_triangle_epochs {
        return err(
            "epochs",
            format!(
                "too large a computation: {triangles} triangles × {epochs} epochs = \
                 {triangle_epochs} triangle-epochs (limit {}); send fewer epochs, a coarser \
                 mesh, or submit it as a job",
                limits.max_triangle_epochs
            ),
        );
    }
    let image_samples = image.map_or(0, |(size, samples)| {
        epochs as u64 * (size as u64).pow(2) * (samples as u64).pow(2)
    });
    let thumbnail_samples = thumbnails.map_or(0, |t| {
        t.epochs.len() as u64 * (t.size as u64).pow(2) * (t.samples as u64).pow(2)
    });
    let (field, what) = if image_samples > limits.max_pixel_samples {
        let (size, samples) = image.unwrap_or_default();
        (
            "image_size",
            format!("{epochs} epochs × {size}² pixels × {samples}² samples = {image_samples}"),
        )
    } else if image_samples + thumbnail_samples > limits.max_pixel_samples {
        (
            "thumbnails",
            format!(
                "{thumbnail_samples} thumbnail samples{}",
                if image_samples > 0 {
                    format!(" + {image_samples} of the `image` method")
                } else {
                    String::new()
                }
            ),
        )
    } else {
        return Ok(());
    };
    err(
        field,
        format!(
            "too large a computation: {what} pixel samples (limit {}); render fewer or \
             smaller images, or submit it as a job",
            limits.max_pixel_samples
        ),
    )
}

/// Most pixel samples (frames × size² × samples²) one request may ask to render.
pub const MAX_THUMBNAIL_SAMPLES: u64 = 1 << 30;
/// Most pixels (frames × size²) one request may ask to render: 256 MiB of f32 radiance.
pub const MAX_THUMBNAIL_PIXELS: u64 = 1 << 26;

fn thumbnails(spec: &ThumbnailSpec, n_epochs: usize) -> Result<Thumbnails, ValidationError> {
    let mut out = Thumbnails::default_for(n_epochs);
    if let Some(size) = spec.size {
        if !(8..=2048).contains(&size) {
            return err(
                "thumbnails.size",
                format!("must be between 8 and 2048 pixels, got {size}"),
            );
        }
        out.size = size;
    }
    if let Some(samples) = spec.samples {
        if !(1..=16).contains(&samples) {
            return err(
                "thumbnails.samples",
                format!("must be between 1 and 16 per pixel side, got {samples}"),
            );
        }
        out.samples = samples;
    }
    if spec.every.is_some() || spec.epochs.is_some() {
        let mut chosen = Vec::new();
        if let Some(every) = spec.every {
            if every == 0 {
                return err("thumbnails.every", "must be at least 1");
            }
            chosen.extend((0..n_epochs).step_by(every));
        }
        for (i, &e) in spec.epochs.iter().flatten().enumerate() {
            if e >= n_epochs {
                return err(
                    format!("thumbnails.epochs[{i}]"),
                    format!("epoch index {e} out of range (there are {n_epochs} epochs)"),
                );
            }
            chosen.push(e);
        }
        chosen.sort_unstable();
        chosen.dedup();
        if chosen.is_empty() {
            return err("thumbnails.epochs", "selects no epoch");
        }
        out.epochs = chosen;
    }
    out.exposure = match &spec.exposure {
        None => Exposure::Fixed,
        Some(ExposureSpec::Mode(m)) => match m.as_str() {
            "fixed" => Exposure::Fixed,
            "peak" => Exposure::Peak,
            "auto" => Exposure::Auto,
            "log" => Exposure::Log,
            other => {
                return err(
                    "thumbnails.exposure",
                    format!("unknown exposure `{other}`; expected fixed, peak, auto, log or a radiance in W/(m²·sr)"),
                )
            }
        },
        Some(ExposureSpec::Radiance(r)) => Exposure::Radiance(positive("thumbnails.exposure", *r)?),
    };
    // The radiometric images of a sequence are held together (one exposure for all).
    let pixels = out.epochs.len() as u64 * (out.size as u64).pow(2);
    if pixels > MAX_THUMBNAIL_PIXELS {
        return err(
            "thumbnails",
            format!(
                "too many pixels: {} frames × {}² = {pixels} (limit {MAX_THUMBNAIL_PIXELS}); render fewer or smaller frames",
                out.epochs.len(),
                out.size
            ),
        );
    }
    let total = pixels * (out.samples as u64).pow(2);
    if total > MAX_THUMBNAIL_SAMPLES {
        return err(
            "thumbnails",
            format!(
                "too many pixel samples: {} frames × {}² pixels × {}² samples = {total} (limit {MAX_THUMBNAIL_SAMPLES})",
                out.epochs.len(),
                out.size,
                out.samples
            ),
        );
    }
    Ok(out)
}

/// The methods' fidelity settings: (image_size, image_samples, centroid_subdivisions).
/// A setting given for another method is an error, so a request never silently ignores it.
fn fidelity(
    req: &Request,
    method: Method,
    triangles: usize,
    limits: &Limits,
) -> Result<(u32, u32, u32), ValidationError> {
    let only_for = |field: &str, m: Method| -> Result<(), ValidationError> {
        if method != m {
            return err(
                field,
                format!(
                    "applies only to \"method\": \"{}\" (the request uses `{}`)",
                    m.name(),
                    method.name()
                ),
            );
        }
        Ok(())
    };
    let mut out = (256, 4, 0);
    if let Some(size) = req.image_size {
        only_for("image_size", Method::Image)?;
        if !(8..=4096).contains(&size) {
            return err(
                "image_size",
                format!("must be between 8 and 4096 pixels, got {size}"),
            );
        }
        out.0 = size;
    }
    if let Some(samples) = req.image_samples {
        only_for("image_samples", Method::Image)?;
        if !(1..=16).contains(&samples) {
            return err(
                "image_samples",
                format!("must be between 1 and 16 per pixel side, got {samples}"),
            );
        }
        out.1 = samples;
    }
    if let Some(k) = req.centroid_subdivisions {
        only_for("centroid_subdivisions", Method::Centroid)?;
        if k > 8 {
            return err(
                "centroid_subdivisions",
                format!("must be between 0 and 8, got {k}"),
            );
        }
        let refined = (triangles as u128) << (2 * k);
        if refined > limits.max_triangles.min(1 << 26) as u128 {
            return err(
                "centroid_subdivisions",
                format!(
                    "too many triangles after {k} subdivisions: {refined} (limit {})",
                    limits.max_triangles.min(1 << 26)
                ),
            );
        }
        out.2 = k;
    }
    Ok(out)
}

/// The least band irradiance of the Sun at 1 AU a request may ask for, W/m²: a scene's
/// geometry (albedo × area / range²) can take another hundred decades off it before f64
/// underflows, where a magnitude would turn `null` although light arrives.
pub const MIN_SUN_BAND_1AU_W_M2: f64 = 1e-200;

fn illumination(req: &Request) -> Result<Illumination, ValidationError> {
    let mut out = Illumination::default();
    let Some(spec) = &req.illumination else {
        return Ok(out);
    };
    if let Some([a, b]) = spec.band_um {
        finite("illumination.band_um[0]", a)?;
        finite("illumination.band_um[1]", b)?;
        if a < 0.0 || b <= a {
            return err(
                "illumination.band_um",
                format!("must be [λ1, λ2] in µm with 0 <= λ1 < λ2, got [{a}, {b}]"),
            );
        }
        out.band_um = [a, b];
    }
    if let Some(t) = spec.sun_temperature_k {
        out.sun_temperature_k = in_range("illumination.sun_temperature_k", t, 100.0, 100_000.0)?;
    }
    // A band far in the Wien tail of a cold Sun (0.01–0.05 µm at 300 K: ~1e-410 W/m²)
    // holds light that no f64 can carry through a scene: say so rather than answer 0.
    let [a, b] = out.band_um;
    let t = out.sun_temperature_k;
    let ln_es = planck::ln_band_exitance(a, b, t) + 2.0 * (SUN_RADIUS_M / AU_M).ln();
    if ln_es < MIN_SUN_BAND_1AU_W_M2.ln() {
        return err(
            "illumination.band_um",
            format!(
                "[{a}, {b}] µm holds almost none of a {t} K Sun's light: its irradiance at \
                 1 AU would be 1e{:.0} W/m², below the {MIN_SUN_BAND_1AU_W_M2:e} W/m² that \
                 f64 radiometry carries through a scene; choose a longer band or a hotter Sun",
                ln_es / std::f64::consts::LN_10
            ),
        );
    }
    if let Some(e) = &spec.earthshine {
        out.earthshine = match e.as_str() {
            "off" => EarthshineModel::Off,
            "seed" => EarthshineModel::Seed,
            "sphere" => EarthshineModel::Sphere,
            other => {
                return err(
                    "illumination.earthshine",
                    format!("unknown model `{other}`; expected off, seed or sphere"),
                )
            }
        };
    }
    if let Some(a) = spec.earth_albedo {
        out.earth_albedo = in_range("illumination.earth_albedo", a, 0.0, 1.0)?;
    }
    Ok(out)
}

fn epoch(field: &str, e: &EpochSpec) -> Result<Epoch, ValidationError> {
    let t = match &e.t {
        TimeSpec::Seconds(s) => finite(&format!("{field}.t"), *s)?,
        TimeSpec::Iso(s) => {
            parse_time(s).map_err(|m| ValidationError::new(format!("{field}.t"), m))?
        }
    };
    let mut sun = vector(&format!("{field}.sun"), e.sun)?.normalize();
    let mut observer = vector(&format!("{field}.observer"), e.observer)?;
    let mut earth = e
        .earth
        .map(|v| vector(&format!("{field}.earth"), v))
        .transpose()?;
    if let Some(q) = e.attitude {
        let qf = format!("{field}.attitude");
        let q = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
        if !q.is_finite() || (q.length() - 1.0).abs() > 1e-6 {
            return err(qf, "must be a unit quaternion [w, x, y, z]");
        }
        // attitude rotates body → inertial; the vectors are inertial
        let inv = q.inverse();
        sun = inv * sun;
        observer = inv * observer;
        earth = earth.map(|v| inv * v);
    }
    if let Some(d) = earth {
        if d.length() <= EARTH_RADIUS_M {
            return err(
                format!("{field}.earth"),
                format!(
                    "object is inside the Earth: |earth| = {:.0} m <= 6371 km",
                    d.length()
                ),
            );
        }
    }
    let au = match e.sun_distance_au {
        None => 1.0,
        Some(d) => in_range(&format!("{field}.sun_distance_au"), d, 0.01, 1000.0)?,
    };
    Ok(Epoch {
        t,
        sun,
        sun_distance_m: au * AU_M,
        observer,
        earth,
    })
}

/// ISO 8601 / RFC 3339 UTC time → Unix seconds. A missing zone is taken as UTC.
fn parse_time(s: &str) -> Result<f64, String> {
    parse_utc(s).map(UtcTime::unix).map_err(|_| {
        format!("`{s}` is neither seconds nor an ISO 8601 UTC time (e.g. 2026-11-22T04:50:00Z)")
    })
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
            let km = if normalised && km > 0.0 {
                // the lobe's albedo at normal incidence with k^M = 1
                let unit = Brdf::SeedMicrofacet(SeedMicrofacet::new(0.0, 1.0, d, n, k));
                let a = crate::brdf::albedo::directional(&unit, 0.0, 0.0);
                if a <= 1e-9 {
                    return err(
                        f("n"),
                        format!(
                            "with n = {n}, k = {k} the surface reflects (almost) nothing \
                             (lobe albedo {a:.1e}): km cannot be scaled to an albedo"
                        ),
                    );
                }
                km / a
            } else {
                km
            };
            Ok(Brdf::SeedMicrofacet(SeedMicrofacet::new(kd, km, d, n, k)))
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

/// Largest mesh coordinate accepted, m.
const MAX_COORDINATE_M: f64 = 1e12;

fn mesh(spec: &MeshSpec, materials: &[Material], limits: &Limits) -> Result<Mesh, ValidationError> {
    let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
    let forms = [
        spec.vertices.is_some() || spec.triangles.is_some(),
        spec.obj.is_some(),
        spec.builtin.is_some(),
    ];
    if forms.iter().filter(|&&b| b).count() != 1 {
        return err(
            "object.mesh",
            "give exactly one of `vertices` + `triangles`, `obj` or `builtin`",
        );
    }
    if spec.material_ids.is_some() && spec.triangles.is_none() {
        return err(
            "object.mesh.material_ids",
            "goes only with inline `triangles` (OBJ and built-in meshes use material names)",
        );
    }
    if spec.detail.is_some() && spec.builtin.is_none() {
        return err(
            "object.mesh.detail",
            "goes only with `builtin` (OBJ and inline meshes come as they are)",
        );
    }
    let mut mesh = if let Some(name) = &spec.builtin {
        let b = builtin::find(name).ok_or_else(|| {
            let known: Vec<_> = builtin::BUILTINS.iter().map(|b| b.name).collect();
            ValidationError::new(
                "object.mesh.builtin",
                format!("unknown object `{name}`; built-in: {}", known.join(", ")),
            )
        })?;
        let detail = match &spec.detail {
            None => b.default_detail,
            Some(d) => builtin::Detail::parse(d).ok_or_else(|| {
                ValidationError::new(
                    "object.mesh.detail",
                    format!("unknown detail `{d}`; expected coarse, medium or fine"),
                )
            })?,
        };
        let mut mesh = (b.build)(detail);
        // map the object's material names onto the request's materials
        let mut map = Vec::new();
        for n in b.material_names {
            match names.iter().position(|m| m == n) {
                Some(i) => map.push(i as u32),
                None if mesh
                    .material_ids
                    .iter()
                    .all(|&id| b.material_names[id as usize] != *n) =>
                {
                    map.push(0)
                }
                None => {
                    return err(
                        "object.materials",
                        format!(
                            "built-in object `{name}` needs a material named `{n}` (it uses: {})",
                            b.material_names.join(", ")
                        ),
                    )
                }
            }
        }
        for id in &mut mesh.material_ids {
            *id = map[*id as usize];
        }
        mesh
    } else if let Some(text) = &spec.obj {
        obj::parse(text, &names).map_err(|m| ValidationError::new("object.mesh.obj", m))?
    } else {
        let vertices = spec.vertices.as_ref().ok_or_else(|| {
            ValidationError::new("object.mesh.vertices", "is required with `triangles`")
        })?;
        let triangles = spec.triangles.as_ref().ok_or_else(|| {
            ValidationError::new("object.mesh.triangles", "is required with `vertices`")
        })?;
        let mut mesh = Mesh {
            vertices: Vec::with_capacity(vertices.len()),
            triangles: triangles.clone(),
            material_ids: Vec::new(),
        };
        for (i, v) in vertices.iter().enumerate() {
            let p = DVec3::from_array(*v);
            if !p.is_finite() {
                return err(
                    format!("object.mesh.vertices[{i}]"),
                    "must have three finite components",
                );
            }
            mesh.vertices.push(p);
        }
        mesh.material_ids = match &spec.material_ids {
            None => vec![0; triangles.len()],
            Some(ids) => {
                if ids.len() != triangles.len() {
                    return err(
                        "object.mesh.material_ids",
                        format!(
                            "has {} entries but there are {} triangles",
                            ids.len(),
                            triangles.len()
                        ),
                    );
                }
                for (i, &id) in ids.iter().enumerate() {
                    if id as usize >= materials.len() {
                        return err(
                            format!("object.mesh.material_ids[{i}]"),
                            format!(
                                "material index {id} out of range (there are {} materials)",
                                materials.len()
                            ),
                        );
                    }
                }
                ids.clone()
            }
        };
        mesh
    };
    if mesh.triangles.is_empty() {
        return err("object.mesh.triangles", "the mesh has no triangles");
    }
    if mesh.triangles.len() > limits.max_triangles {
        return err(
            "object.mesh",
            format!(
                "too many triangles: {} (limit {})",
                mesh.triangles.len(),
                limits.max_triangles
            ),
        );
    }
    let nv = mesh.vertices.len();
    for (i, t) in mesh.triangles.iter().enumerate() {
        if let Some(&bad) = t.iter().find(|&&k| k as usize >= nv) {
            return err(
                format!("object.mesh.triangles[{i}]"),
                format!("vertex index {bad} out of range (there are {nv} vertices)"),
            );
        }
    }
    // Metres: beyond 1e12 m (7 AU) the squares of the triangles' areas overflow f64 and
    // every triangle would look degenerate; no object in orbit comes near it.
    if let Some(i) = mesh
        .vertices
        .iter()
        .position(|v| !v.is_finite() || v.abs().max_element() > MAX_COORDINATE_M)
    {
        return err(
            format!("object.mesh.vertices[{i}]"),
            format!(
                "a coordinate that is not a finite number or lies beyond \
                 {MAX_COORDINATE_M:e} m: give the mesh in metres"
            ),
        );
    }
    // The same triangle twice (same corners, same winding) would count its light twice;
    // two triangles back to back (opposite windings) are a thin plate, and are kept.
    {
        let welded = mesh.welded_ids();
        let mut keyed: Vec<([u32; 3], usize)> = mesh
            .triangles
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let w = t.map(|k| welded[k as usize]);
                // rotated to start at its least corner: the winding kept
                let r = (0..3).min_by_key(|&k| w[k]).unwrap_or(0);
                ([w[r], w[(r + 1) % 3], w[(r + 2) % 3]], i)
            })
            .collect();
        keyed.sort_unstable();
        if let Some(pair) = keyed.windows(2).find(|p| p[0].0 == p[1].0) {
            let (a, b) = (pair[0].1.min(pair[1].1), pair[0].1.max(pair[1].1));
            return err(
                format!("object.mesh.triangles[{b}]"),
                format!(
                    "has the same corners, wound the same way, as triangles[{a}]: its light \
                     would be counted twice"
                ),
            );
        }
    }
    // Degenerate triangles carry no area and no normal: drop them rather than fail, as
    // exporters often leave a few; a mesh of nothing else is an error.
    let (_, scale) = mesh.bounding_sphere();
    let min_area2 = (1e-12 * scale * scale).powi(2);
    let keep: Vec<bool> = (0..mesh.triangles.len())
        .map(|i| mesh.area_vector(i).length_squared() > min_area2)
        .collect();
    if !keep.iter().any(|&k| k) {
        return err("object.mesh.triangles", "every triangle has zero area");
    }
    if keep.iter().any(|&k| !k) {
        let mut i = 0;
        mesh.triangles.retain(|_| {
            i += 1;
            keep[i - 1]
        });
        let mut j = 0;
        mesh.material_ids.retain(|_| {
            j += 1;
            keep[j - 1]
        });
    }
    Ok(mesh)
}
