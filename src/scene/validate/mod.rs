//! Request → Scene: every input checked at the boundary, every error naming its field.
//!
//! [`validate`] checks a parsed request part by part, in this order (a request with
//! several faults is told the first):
//!
//! | part | file |
//! |---|---|
//! | JSON text → [`Request`] ([`parse_request`], [`parse_json`]) | `json.rs` |
//! | `object.materials` | `materials.rs` |
//! | `object.mesh` | `mesh.rs` |
//! | `illumination` | `illumination.rs` |
//! | materials' `spectral` tables, the band's wavelength bins | `spectral.rs` |
//! | `epochs` or `geometry` (built in [`super::geometry`]) | `epochs.rs` |
//! | `geometry.articulation` (or `articulation`): hinges, nested hinges, split vertices | `articulation.rs` |
//! | `observation` | `observation.rs` |
//! | `tolerance`, `method`, `image_*`, `centroid_subdivisions` | `fidelity.rs` |
//! | `thumbnails` | `thumbnails.rs` |
//! | the work it asks for, against the [`Limits`] | `work.rs` |
//!
//! `values.rs` holds the checks of one number or vector that all of them share.

mod articulation;
mod epochs;
mod fidelity;
mod illumination;
mod json;
mod materials;
mod mesh;
mod observation;
mod spectral;
mod table;
mod thumbnails;
mod values;
mod work;

use super::request::Request;
use super::{Method, Scene};

pub use super::error::{Limits, ValidationError};
pub use illumination::MIN_SUN_BAND_1AU_W_M2;
pub use json::{parse_json, parse_request};
pub(crate) use materials::material;
pub use thumbnails::{MAX_THUMBNAIL_PIXELS, MAX_THUMBNAIL_SAMPLES};

/// Checks a whole request.
pub fn validate(req: &Request, limits: &Limits) -> Result<Scene, ValidationError> {
    let materials = materials::materials(req)?;
    let mut grouped = mesh::mesh(&req.object.mesh, &materials, limits)?;
    let mesh = &grouped.mesh;
    let illumination = illumination::illumination(req)?;
    let (materials, spectral) = spectral::bins(req, materials, &illumination)?;
    let epochs::Epochs {
        epochs,
        sky,
        warnings,
        origin,
    } = epochs::epochs(req, limits, mesh, &illumination)?;
    let articulation = articulation::articulation(req, &mut grouped, &materials, &epochs, origin)?;
    let mesh = grouped.mesh;
    if let Some(a) = &articulation {
        articulation::observers_outside(&mesh, a, &epochs, req.geometry.is_some())?;
    }
    let observation = req
        .observation
        .as_ref()
        .map(|o| observation::observation(o, &illumination))
        .transpose()?;
    let tolerance = fidelity::tolerance(req)?;
    let method = fidelity::method(req)?;
    let (image_size, image_samples, centroid_subdivisions) =
        fidelity::fidelity(req, method, mesh.triangles.len(), limits)?;
    let thumbnails = req
        .thumbnails
        .as_ref()
        .map(|t| thumbnails::thumbnails(t, epochs.len()))
        .transpose()?;
    work::work(
        limits,
        mesh.triangles.len(),
        epochs.len(),
        super::epoch_work(articulation.as_ref(), method),
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
        observation,
        spectral,
        articulation,
    })
}
