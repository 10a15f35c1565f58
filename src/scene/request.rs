//! The request JSON, exactly as clients send it (CLI file or HTTP body).
//!
//! These types only describe the wire format; [`super::validate`] turns a
//! [`Request`] into a checked [`super::Scene`]. Every struct rejects unknown
//! fields so a typo is an error that names the field, not a silent default.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

mod geometry;
pub use geometry::*;

/// A light-curve request: one object, its epochs, and how it is lit.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// The object: its mesh and materials.
    pub object: ObjectSpec,
    /// The epochs to compute, in any order; results come back in the same order. Give
    /// either `epochs` or `geometry`, not both.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub epochs: Option<Vec<EpochSpec>>,
    /// The epochs computed from an element set, a ground site, a time window and an
    /// attitude law, instead of explicit `epochs`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub geometry: Option<GeometrySpec>,
    /// Band, Sun temperature and earthshine. Optional; defaults as documented per field.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub illumination: Option<IlluminationSpec>,
    /// Relative tolerance of the lit-and-visible area integration for partly shadowed
    /// faces (fraction of the epoch's unshadowed signal), where they are ray-sampled:
    /// faces clipped exactly (the usual case) are exact whatever it says. Default 1e-3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 1e-3)]
    pub tolerance: Option<f64>,
    /// Integration method: `auto` (default), `silhouette`, `adaptive`, `centroid`, `convex` or `image`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub method: Option<String>,
    /// `image` method only: pixels on a side of the orthographic view from the observer
    /// (it spans the object's bounding sphere), 8 to 4096. Default 256.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 256)]
    pub image_size: Option<u32>,
    /// `image` method only: stratified samples per pixel side (samples² per pixel),
    /// 1 to 16. Default 4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 4)]
    pub image_samples: Option<u32>,
    /// `centroid` method only: split every triangle into four this many times before
    /// casting one ray per direction at each centroid, 0 to 8. Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 0)]
    pub centroid_subdivisions: Option<u32>,
    /// Rendered images of the object as the observer sees it, returned in
    /// `thumbnails` of the response. Absent: no images (and no cost).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thumbnails: Option<ThumbnailSpec>,
    /// A telescope observing the object: per epoch its signal, sky and noise electrons in
    /// a photometric aperture, SNR, ADU, saturation and a noisy sample (the CCD equation,
    /// docs/physics.md §10a). Needs a named `illumination.band`. Absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub observation: Option<ObservationSpec>,
    /// Articulated parts with explicit `epochs` (a `geometry` request gives them as
    /// `geometry.articulation`): the same list, an `angles` law's times on the epochs'
    /// own `t` scale.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub articulation: Option<Vec<ArticulationSpec>>,
}

/// A telescope, its detector and the sky.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ObservationSpec {
    /// Aperture diameter, m (0 < D ≤ 50).
    #[schema(example = 0.5)]
    pub aperture_m: f64,
    /// Exposure time, s (0 < t ≤ 1e5).
    #[schema(example = 1.0)]
    pub exposure_s: f64,
    /// Central obstruction as a fraction of the diameter, 0 to 0.99. Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub obstruction: Option<f64>,
    /// Detector quantum efficiency in the band, 0 to 1 (exclusive of 0). Default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quantum_efficiency: Option<f64>,
    /// Optics and filter throughput beyond the band's own response, 0 to 1 (exclusive of
    /// 0). Default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub throughput: Option<f64>,
    /// Pixel scale, arcsec per pixel (> 0). Default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pixel_scale_arcsec: Option<f64>,
    /// Seeing: FWHM of the Gaussian star image, arcsec (> 0). Default 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seeing_fwhm_arcsec: Option<f64>,
    /// Radius of the circular photometric aperture, arcsec (> 0). Default the seeing
    /// FWHM (which holds 93.75 % of a Gaussian image).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aperture_radius_arcsec: Option<f64>,
    /// Read noise, e⁻ rms per pixel (≥ 0). Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub read_noise_e: Option<f64>,
    /// Dark current, e⁻/s per pixel (≥ 0). Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dark_e_per_s: Option<f64>,
    /// Gain, e⁻ per ADU (> 0). Default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gain_e_per_adu: Option<f64>,
    /// Full well, e⁻ (> 0): the brightest pixel at or above it is saturated. Default:
    /// none (never saturated).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub full_well_e: Option<f64>,
    /// Sky brightness in the band, mag/arcsec², as measured at the site (−10 to 40).
    /// Default: no sky.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 21.0)]
    pub sky_mag_per_arcsec2: Option<f64>,
    /// Airmass (1 to 40). Default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub airmass: Option<f64>,
    /// Atmospheric extinction, mag per airmass (0 to 10). Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extinction_mag_per_airmass: Option<f64>,
    /// Seed of the noisy samples: the same seed gives the same samples. Default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
}

/// Which epochs to render, and how. `every` and `epochs` may be combined (their union
/// is rendered); with neither, about eight frames spread over the sequence.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ThumbnailSpec {
    /// Pixels on a side (square images), 8 to 2048. Default 128.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 128)]
    pub size: Option<u32>,
    /// Render every N-th epoch, starting with the first.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = 10)]
    pub every: Option<usize>,
    /// Indices of epochs to render (0-based, into `epochs`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub epochs: Option<Vec<usize>>,
    /// Stratified samples per pixel side (samples² per pixel), 1 to 16. Default 3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<u32>,
    /// `fixed` (default: one exposure for the whole sequence, from the typical bright
    /// pixel of its frames, glints saturate), `peak` (one exposure, the sequence's
    /// brightest pixel white), `auto` (each image on its own), `log` (six decades
    /// below the sequence's brightest pixel are black), or a radiance in W/(m²·sr)
    /// to map to white.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exposure: Option<ExposureSpec>,
}

/// An exposure mode by name, or the radiance (W/(m²·sr)) that maps to white.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(untagged)]
pub enum ExposureSpec {
    Radiance(f64),
    Mode(String),
}

/// The object: a triangle mesh and the materials its triangles use.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ObjectSpec {
    pub mesh: MeshSpec,
    /// Materials, indexed by `mesh.material_ids` (inline meshes) or matched by name
    /// (`usemtl` in OBJ text and built-in objects). A bare string names a preset.
    pub materials: Vec<MaterialSpec>,
}

/// A mesh: inline `vertices` + `triangles`, or `obj` text, or a `builtin` name.
/// Exactly one of the three forms must be given.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Vertex positions in metres, body frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vertices: Option<Vec<[f64; 3]>>,
    /// Vertex indices per triangle, counter-clockwise seen from outside.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub triangles: Option<Vec<[u32; 3]>>,
    /// Index into `object.materials` per triangle; when absent all use `materials[0]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material_ids: Option<Vec<u32>>,
    /// Wavefront OBJ text (metres); faces take the material named by `usemtl`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub obj: Option<String>,
    /// Name of an object shipped with glint (see `GET /v1/scenes`), e.g. `box-wing`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub builtin: Option<String>,
    /// Tessellation of a `builtin` object: `coarse` (about 2k triangles), `medium` (about
    /// 20k) or `fine` (about 200k). Default: `medium`, except `box-wing`, `sphere` and
    /// `plate`, which default to their original meshes (coarse: 268, 1280 and 2 triangles;
    /// the box-wing's medium is the 15.5k-triangle fine-dish box-wing).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = "medium")]
    pub detail: Option<String>,
    /// Inline meshes only: named groups of triangles, for `articulation` (OBJ text names
    /// its groups with `g` or `o`). A triangle belongs to one part at most.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parts: Option<Vec<PartSpec>>,
}

/// A named group of an inline mesh's triangles.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PartSpec {
    #[schema(example = "panel")]
    pub name: String,
    /// Indices into `triangles`.
    pub triangles: Vec<u32>,
}

/// A material: a preset name, or an object with `name` and either `model` + parameters
/// or `preset`.
#[derive(Debug, Clone, Serialize, ToSchema)]
#[serde(untagged)]
// One per material in a request: boxing the large variant would buy nothing.
#[allow(clippy::large_enum_variant)]
pub enum MaterialSpec {
    /// A preset by name: `seed-body-wrap` or `seed-white-paint` (the paper's §5.1).
    Preset(String),
    Full(MaterialObject),
}

// By hand rather than `untagged`: an untagged enum buffers the value and reports only
// "did not match any variant", losing the field (`albdo`, a string `albedo`) that is wrong.
// Dispatching on the JSON type keeps serde's own error and its path.
impl<'de> Deserialize<'de> for MaterialSpec {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = MaterialSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a preset name or a material object")
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<MaterialSpec, E> {
                Ok(MaterialSpec::Preset(s.to_owned()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<MaterialSpec, A::Error> {
                MaterialObject::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    .map(MaterialSpec::Full)
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

/// A material with its model parameters. Which parameters are allowed depends on `model`:
/// - `seed-microfacet`: `kd`, `km`, `slope_rms`, `n`, `k` (the paper's Eqs. 6–8), optional
///   `normalised`
/// - `lambert`: `albedo`
/// - `rough-conductor`: `alpha`, `n`, `k`, optional `kd` and `shadowing` (Beckmann + Smith,
///   as Mitsuba 3's `roughconductor`; pbrt's Smith form with `shadowing: correlated`)
/// - `ashikhmin-shirley`: `rd`, `rs`, `nu`, `nv`, optional `tangent`
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialObject {
    /// Name used by `usemtl` and built-in objects.
    pub name: String,
    /// `seed-microfacet`, `lambert`, `rough-conductor` or `ashikhmin-shirley`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<String>,
    /// Use a preset's model and parameters under this material's name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preset: Option<String>,
    /// Diffuse coefficient k^D (dimensionless, 0..1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kd: Option<f64>,
    /// Specular coefficient k^M (dimensionless, >= 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub km: Option<f64>,
    /// RMS microfacet slope δ (dimensionless, > 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slope_rms: Option<f64>,
    /// `seed-microfacet` only. `false` (default): k^M as the paper's Eq. 8 writes it, whose
    /// lobe reflects ≈ 4π·k^M·F(0) of the light at normal incidence (a smooth lobe; more
    /// than 1 for k^M above ~0.08). `true`: k^M (0..1) is the specular lobe's albedo at
    /// normal incidence — Eq. 8's k^M is k^M / a(δ, n, k), a the lobe's albedo with
    /// k^M = 1 — so kd + km ≤ 1 reflects no more than it receives there.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normalised: Option<bool>,
    /// Real part of the complex refractive index.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub n: Option<f64>,
    /// Imaginary part (extinction coefficient) of the refractive index.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k: Option<f64>,
    /// Lambertian albedo (0..1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<f64>,
    /// Beckmann roughness α of `rough-conductor` (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alpha: Option<f64>,
    /// Smith masking–shadowing of `rough-conductor`: `separable` (the default) is
    /// G = G1(l)·G1(v), as Mitsuba 3's `roughconductor`, glint's reference renderer;
    /// `correlated` is the height-correlated G = 1/(1 + Λ(l) + Λ(v)) of pbrt. They agree
    /// near the normal and part at grazing angles (at the 80° specular peak the correlated
    /// form is 1.015× the separable one at α 0.3, 1.40× at α 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shadowing: Option<ShadowingSpec>,
    /// Ashikhmin–Shirley diffuse reflectance R_d (0..1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rd: Option<f64>,
    /// Ashikhmin–Shirley specular reflectance at normal incidence R_s (0..1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rs: Option<f64>,
    /// Ashikhmin–Shirley Phong exponent along the face tangent (> 0): see `tangent`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nu: Option<f64>,
    /// Ashikhmin–Shirley Phong exponent along the face bitangent (> 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nv: Option<f64>,
    /// Ashikhmin–Shirley only: the body-frame direction [x, y, z] (any length) along which
    /// `nu` runs, e.g. a brushed or grooved direction. Each face takes it projected onto
    /// its plane; a face whose normal is within 8.1° of it takes instead a fixed direction
    /// perpendicular to it. Default [1, 0, 0], the body's x axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(min_items = 3, max_items = 3)]
    pub tangent: Option<[f64; 3]>,
    /// Thin sheet lit and seen from both sides (solar panels). Default false.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub two_sided: Option<bool>,
    /// Wavelength-dependent `n`, `k` or `albedo` as a short table (instead of the
    /// number): the band integral then runs per wavelength (docs/physics.md §8).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spectral: Option<SpectralSpec>,
}

/// A material's parameters against wavelength: linear between the points, constant
/// beyond the first and last.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct SpectralSpec {
    /// Wavelengths, µm, increasing, 2 to 64 of them.
    #[schema(example = json!([0.4, 0.55, 0.7]))]
    pub wavelength_um: Vec<f64>,
    /// Real part of the refractive index at each wavelength.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub n: Option<Vec<f64>>,
    /// Imaginary part of the refractive index at each wavelength.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub k: Option<Vec<f64>>,
    /// Lambertian albedo at each wavelength.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<Vec<f64>>,
}

/// How a rough conductor's Smith term combines the light's and the view's masking.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, ToSchema)]
#[serde(rename_all = "lowercase")]
pub enum ShadowingSpec {
    /// G = G1(l)·G1(v) (Mitsuba 3; the default).
    Separable,
    /// G = 1/(1 + Λ(l) + Λ(v)) (height-correlated; pbrt).
    Correlated,
}

// By hand: serde_json reads a derived enum from a non-string (`"shadowing": 1`) as a
// syntax error ("invalid JSON: expected value"); asking for a string gives "invalid type:
// integer `1`, expected ..." and keeps "unknown variant" for a wrong name.
impl<'de> Deserialize<'de> for ShadowingSpec {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = ShadowingSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("`separable` or `correlated`")
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<ShadowingSpec, E> {
                match s {
                    "separable" => Ok(ShadowingSpec::Separable),
                    "correlated" => Ok(ShadowingSpec::Correlated),
                    other => Err(E::unknown_variant(other, &["separable", "correlated"])),
                }
            }
        }
        deserializer.deserialize_str(Visitor)
    }
}

/// Time of an epoch: seconds (any origin), or an ISO 8601 / RFC 3339 UTC string.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(untagged)]
pub enum TimeSpec {
    Seconds(f64),
    Iso(String),
}

/// One epoch's geometry, in the body frame (or inertial when `attitude` is given).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct EpochSpec {
    /// Seconds, or an ISO 8601 UTC time string (reported as Unix seconds).
    #[schema(value_type = f64, example = 0.0)]
    pub t: TimeSpec,
    /// Direction from the object to the Sun (any length; normalised).
    #[schema(min_items = 3, max_items = 3)]
    pub sun: [f64; 3],
    /// Vector from the object to the observer, metres; its length is the range R. It must
    /// lie outside the mesh's bounding sphere (Eq. 12 is a far-field sum).
    #[schema(min_items = 3, max_items = 3)]
    pub observer: [f64; 3],
    /// Vector from the object to the Earth's centre, metres. Needed for earthshine and eclipses.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(min_items = 3, max_items = 3)]
    pub earth: Option<[f64; 3]>,
    /// Object–Sun distance in AU. Default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sun_distance_au: Option<f64>,
    /// Body-to-inertial attitude quaternion [w, x, y, z]; when given, `sun`, `observer`
    /// and `earth` are inertial and are rotated into the body frame.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(min_items = 4, max_items = 4)]
    pub attitude: Option<[f64; 4]>,
}

/// Illumination: spectral band, Sun temperature, earthshine.
#[derive(Debug, Clone, Default, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct IlluminationSpec {
    /// Spectral band [λ1, λ2] in µm, every wavelength in it counted alike. Default
    /// [0.4, 0.7]. Its magnitudes put the Sun at 1 AU at −26.74 (V-like). The Sun's
    /// irradiance in it at 1 AU must be at least 1e-200 W/m² (not so only far in the Wien
    /// tail of a cold Sun). Not with `band`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(min_items = 2, max_items = 2)]
    pub band_um: Option<[f64; 2]>,
    /// A standard passband instead of `band_um`, integrated through its tabulated response
    /// (photon-weighted, as a CCD counts): `V`, `B` (Johnson, Bessell 1990), `R` (Cousins,
    /// Bessell 1990), `G` (Gaia EDR3), `g`, `r`, `i` (SDSS, Doi et al. 2010; AB), `clear`
    /// (an unfiltered silicon CCD: the Kepler photometer's response, 0.42–0.905 µm). Its
    /// magnitudes take the Sun's magnitude in that band as zero point: V −26.76 and B
    /// −26.13 (Willmer 2018, ApJS 236, 47), R −27.13, G −26.89, clear −26.88 (Vega),
    /// g −26.46, r −26.93, i −27.04 (AB), computed from the CALSPEC solar spectrum
    /// (docs/physics.md §10).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = "V")]
    pub band: Option<String>,
    /// Sun blackbody temperature in K. Default 5900 (the paper's value). Used with
    /// `solar_spectrum: planck`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sun_temperature_k: Option<f64>,
    /// The solar spectrum integrated through the band: `planck` (default: a blackbody at
    /// `sun_temperature_k`) or `calspec` (the tabulated CALSPEC solar reference spectrum,
    /// Colina, Bohlin & Castelli 1996, 0.1195–2.70 µm; the band must lie within it).
    /// Magnitudes of wavelength-independent materials do not depend on it: E and the
    /// Sun's in-band irradiance change alike.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(example = "planck")]
    pub solar_spectrum: Option<String>,
    /// `off`, `sphere` (the default: the sunlit Lambertian Earth over its visible cap, with
    /// its distance and phase) or `seed` (the paper's Eq. 3: ρ·E_s as one parallel beam
    /// from the Earth's direction at any distance and Earth phase — to reproduce the
    /// paper; at GEO it is 59× the sphere at full Earth). Without `earth` in the epochs,
    /// no earthshine.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub earthshine: Option<String>,
    /// Earth's Bond albedo ρ. Default 0.35.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub earth_albedo: Option<f64>,
}
