//! Requests and responses (the wire format, with OpenAPI schemas), their validation
//! into a checked [`Scene`], and the material presets.

pub mod error;
pub mod geometry;
pub mod presets;
pub mod request;
pub mod response;
#[cfg(test)]
pub(crate) mod test_fixtures;
pub mod validate;

pub use error::{Limits, ValidationError};
pub use request::Request;
pub use response::{EpochResult, MaterialAlbedo, ObservationResult, Response, Summary};

use crate::brdf::Brdf;
use crate::geometry::Mesh;
use glam::DVec3;

/// A material after validation.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub name: String,
    pub brdf: Brdf,
    /// Lit and seen from both sides (thin sheets).
    pub two_sided: bool,
    /// Unit body-frame direction along which an anisotropic model's first exponent
    /// (Ashikhmin–Shirley's n_u) runs: each face takes it projected onto its plane
    /// ([`crate::geometry::faces::tangent_of`]). Default the body's x axis.
    pub tangent: DVec3,
}

/// One epoch's geometry in the body frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Epoch {
    /// Seconds (Unix seconds for ISO input).
    pub t: f64,
    /// Unit vector object → Sun.
    pub sun: DVec3,
    /// Object–Sun distance, m.
    pub sun_distance_m: f64,
    /// Vector object → observer, m.
    pub observer: DVec3,
    /// Vector object → Earth centre, m.
    pub earth: Option<DVec3>,
}

/// What a ground site sees of the object at one epoch of a `geometry` request.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sky {
    /// Degrees from north through east.
    pub azimuth_deg: f64,
    /// Degrees above the site's horizon (geometric).
    pub elevation_deg: f64,
    /// The Sun's elevation at the site, degrees (geometric).
    pub sun_elevation_deg: f64,
}

/// Earthshine model (docs/physics.md §5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EarthshineModel {
    Off,
    /// The paper's Eq. 3: ρE_s as a parallel beam from the Earth's direction.
    Seed,
    /// The Earth as a sunlit Lambertian sphere, integrated over its visible cap.
    Sphere,
}

/// Which solar spectrum the band is integrated against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolarSpectrumChoice {
    /// A blackbody at `sun_temperature_k` (the default).
    Planck,
    /// The tabulated CALSPEC solar spectrum (`radiometry::bands::calspec`).
    Calspec,
}

/// Illumination settings after validation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Illumination {
    /// Band [λ1, λ2], µm: the interval band, or the span of a named band's table.
    pub band_um: [f64; 2],
    /// A named passband (`illumination.band`), integrated through its response; `None`
    /// for the interval `band_um`.
    pub passband: Option<&'static crate::radiometry::bands::Passband>,
    /// Sun blackbody temperature, K.
    pub sun_temperature_k: f64,
    pub solar_spectrum: SolarSpectrumChoice,
    /// The Sun's irradiance at 1 AU in the band, W/m² (photon-weighted for a named band:
    /// `radiometry::bands`): the magnitude zero point's flux.
    pub sun_1au_w_m2: f64,
    /// The Sun's apparent magnitude at 1 AU in the band: the magnitude zero point.
    pub sun_magnitude: f64,
    /// The share of the band's sunlight this scene computes: 1, or one wavelength bin's
    /// (`SpectralBin::share`). Scales the Sun, not the zero point.
    pub sun_share: f64,
    pub earthshine: EarthshineModel,
    /// Earth's albedo ρ.
    pub earth_albedo: f64,
}

impl Default for Illumination {
    fn default() -> Self {
        Illumination {
            band_um: [0.4, 0.7],
            passband: None,
            sun_temperature_k: 5900.0,
            solar_spectrum: SolarSpectrumChoice::Planck,
            sun_1au_w_m2: crate::radiometry::sun::band_irradiance_1au([0.4, 0.7], 5900.0),
            sun_magnitude: crate::radiometry::magnitude::SUN_MAGNITUDE,
            sun_share: 1.0,
            earthshine: EarthshineModel::Sphere,
            earth_albedo: 0.35,
        }
    }
}

impl Illumination {
    /// The Sun's irradiance in the band at `distance_m` from it, W/m². An interval band
    /// under a blackbody Sun is Planck's band integral at that distance, as always; every
    /// other band scales its 1 AU value by (AU/D)².
    pub fn sun_irradiance(&self, distance_m: f64) -> f64 {
        use crate::radiometry::{sun, AU_M};
        let full = if self.passband.is_none() && self.solar_spectrum == SolarSpectrumChoice::Planck
        {
            sun::band_irradiance(self.band_um, self.sun_temperature_k, distance_m)
        } else {
            let ratio = AU_M / distance_m;
            self.sun_1au_w_m2 * ratio * ratio
        };
        if self.sun_share == 1.0 {
            full
        } else {
            full * self.sun_share
        }
    }
}

/// How visibility (shadowing and occlusion by the mesh itself) is integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Convex meshes: no rays; otherwise `Silhouette`.
    Auto,
    /// Faces decided from the shadows of the mesh's silhouette edges: groups of faces no
    /// shadow crosses by one ray each, crossed faces cut into cells along the shadow lines
    /// (exact, for any mesh).
    Silhouette,
    /// Per-face classification; partly shadowed faces clipped exactly (ray-sampled to the
    /// tolerance where shadows cut a face too finely).
    Adaptive,
    /// One ray per direction at each triangle's centroid: all lit or all dark.
    Centroid,
    /// Back-face culling only (exact for convex meshes, wrong otherwise).
    Convex,
    /// Orthographic pixel sampling from the observer, as rendering and summing an image
    /// would: `image_size`² pixels, `image_samples`² rays each, plus shadow rays.
    Image,
}

impl Method {
    pub fn name(self) -> &'static str {
        match self {
            Method::Auto => "auto",
            Method::Adaptive => "adaptive",
            Method::Silhouette => "silhouette",
            Method::Centroid => "centroid",
            Method::Convex => "convex",
            Method::Image => "image",
        }
    }
}

/// A checked request: everything the engine needs, in SI units and the body frame.
#[derive(Debug, Clone)]
pub struct Scene {
    pub mesh: Mesh,
    pub materials: Vec<Material>,
    pub epochs: Vec<Epoch>,
    pub illumination: Illumination,
    /// Relative tolerance of the visibility integration.
    pub tolerance: f64,
    pub method: Method,
    /// `image` method: pixels on a side of the view, which spans the mesh's bounding sphere.
    pub image_size: u32,
    /// `image` method: stratified samples per pixel side (samples² per pixel).
    pub image_samples: u32,
    /// `centroid` method: times each triangle is split into four before sampling.
    pub centroid_subdivisions: u32,
    /// Images to render after the light curve (`None`: none, and no cost).
    pub thumbnails: Option<Thumbnails>,
    /// `adaptive`: clip partly shadowed faces exactly (true, the default) or sample them
    /// with rays to the tolerance (false; kept to chart and test the sampler, which is
    /// also the fallback for faces too finely cut by shadows to clip). Not in the request.
    pub clip_shadows: bool,
    /// Per epoch, what the site sees, when the epochs came from `geometry` (empty
    /// otherwise; ignored unless it has one entry per epoch).
    pub sky: Vec<Sky>,
    /// Notes for the response's `warnings` (e.g. Earth orientation taken as zero).
    pub warnings: Vec<String>,
    /// A telescope's counts per epoch, when the request asked for them.
    pub observation: Option<crate::radiometry::ccd::Observation>,
    /// The band in wavelength bins, each with its materials, when a material depends on
    /// wavelength (empty otherwise: the band integral factors out of the face sum).
    pub spectral: Vec<SpectralBin>,
    /// Hinged parts and their laws (`None`: the mesh is rigid). `mesh` is then the
    /// reference pose (every angle 0), its vertices split between links.
    pub articulation: Option<crate::geometry::articulation::Articulation>,
}

/// One wavelength bin of the band: its share of the Sun's in-band irradiance and every
/// material at its mean wavelength.
#[derive(Debug, Clone)]
pub struct SpectralBin {
    /// The bin's mean wavelength (weighted by the Sun's spectrum and the band), µm.
    pub wavelength_um: f64,
    /// Its share of the Sun's in-band irradiance (the bins' shares sum to 1).
    pub share: f64,
    pub materials: Vec<Material>,
}

/// How rendered radiance maps to 8-bit grey levels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Exposure {
    /// One exposure for the whole sequence, so brightness changes between frames stay
    /// visible: white is the median over the frames of each frame's 99th-percentile
    /// lit pixel, so that glints saturate instead of darkening every other frame.
    Fixed,
    /// One exposure for the whole sequence: its brightest pixel is white.
    Peak,
    /// Each image exposed on its own 99th-percentile lit pixel.
    Auto,
    /// Logarithmic: the sequence's brightest pixel is white, six decades below is black.
    Log,
    /// This radiance is white, W/(m²·sr).
    Radiance(f64),
}

/// Which epochs to render and how (validated `thumbnails` of the request).
#[derive(Debug, Clone, PartialEq)]
pub struct Thumbnails {
    /// Pixels on a side.
    pub size: u32,
    /// Samples per pixel side (samples² stratified samples per pixel).
    pub samples: u32,
    /// Indices into `Scene::epochs`, ascending, no repeats.
    pub epochs: Vec<usize>,
    pub exposure: Exposure,
}

impl Thumbnails {
    /// The default for `n_epochs` epochs: 128 px, about eight frames spread over the
    /// sequence, one exposure for all.
    pub fn default_for(n_epochs: usize) -> Thumbnails {
        let every = n_epochs.div_ceil(8).max(1);
        Thumbnails {
            size: 128,
            samples: DEFAULT_THUMBNAIL_SAMPLES,
            epochs: (0..n_epochs).step_by(every).collect(),
            exposure: Exposure::Fixed,
        }
    }
}

/// Default samples per pixel side of a thumbnail (3×3 stratified).
pub const DEFAULT_THUMBNAIL_SAMPLES: u32 = 3;

/// What an epoch of an articulated scene costs, in epochs of the same mesh held rigid:
/// with a hinge whose angle changes (Sun-tracking, a series) each epoch may be a pose of
/// its own, prepared anew. That preparation is ~0.4 of a rigid epoch where the parts'
/// structure is shared (`auto`, `silhouette`, `convex`) and ~2.5 where each pose is
/// prepared whole (the box-wing, docs/performance.md, 2026-12-04); counted here as 0.5
/// and 2.5 more.
pub fn epoch_work(
    articulation: Option<&crate::geometry::articulation::Articulation>,
    method: Method,
) -> f64 {
    use crate::geometry::articulation::JointLaw;
    let Some(a) = articulation else {
        return 1.0;
    };
    if a.joints
        .iter()
        .all(|j| matches!(j.law, JointLaw::Fixed { .. }))
    {
        return 1.0;
    }
    match method {
        Method::Auto | Method::Silhouette | Method::Convex => 1.5,
        Method::Adaptive | Method::Centroid | Method::Image => 3.5,
    }
}

impl Scene {
    /// What one epoch costs, in epochs of the mesh held rigid ([`epoch_work`]).
    pub fn epoch_work(&self) -> f64 {
        epoch_work(self.articulation.as_ref(), self.method)
    }

    /// Parses and validates request JSON text. The error names the offending field.
    pub fn from_json(text: &str, limits: &Limits) -> Result<Scene, ValidationError> {
        let request = validate::parse_request(text)?;
        Scene::from_request(&request, limits)
    }

    /// Validates a parsed request.
    pub fn from_request(request: &Request, limits: &Limits) -> Result<Scene, ValidationError> {
        validate::validate(request, limits)
    }
}
