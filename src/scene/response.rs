//! The response JSON: one result per epoch and a summary.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// The light curve and how it was computed. (Named `LightCurve` in the OpenAPI spec: a
/// schema called `Response` collides with the generated Python client's own `Response`.)
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
#[schema(as = LightCurve)]
pub struct Response {
    pub epochs: Vec<EpochResult>,
    pub summary: Summary,
    /// Rendered images, when the request asked for `thumbnails`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thumbnails: Option<Vec<Thumbnail>>,
    /// What the caller should know about the result (a material that reflects more light
    /// than it receives); absent when there is nothing to say.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// One rendered image of the object as the observer sees it.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema, PartialEq)]
pub struct Thumbnail {
    /// Index of the epoch in the request.
    pub epoch: usize,
    /// Epoch time, seconds.
    pub t: f64,
    /// Image width and height, pixels.
    pub size: u32,
    /// Scale of the image, metres per pixel (at the object).
    pub metres_per_pixel: f64,
    /// Radiance mapped to full white (8-bit 255), W/(m²·sr); one value for a whole sequence.
    pub exposure_w_m2_sr: f64,
    /// The 8-bit PNG, base64-encoded.
    pub png_base64: String,
}

/// Brightness of the object at one epoch.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema, PartialEq)]
pub struct EpochResult {
    /// Epoch time, seconds (Unix seconds when the request gave an ISO string).
    pub t: f64,
    /// Total irradiance at the observer, W/m² (band-integrated).
    pub irradiance_w_m2: f64,
    /// Part of the irradiance due to direct sunlight, W/m².
    pub sun_w_m2: f64,
    /// Part of the irradiance due to earthshine, W/m².
    pub earthshine_w_m2: f64,
    /// Radiant intensity of the object towards the observer, W/sr.
    pub intensity_w_sr: f64,
    /// Apparent magnitude in the request's band: m = m_sun − 2.5 log10(E / E_sun), E_sun
    /// the Sun's irradiance at 1 AU in the same band and m_sun its magnitude there (−26.74
    /// for a `band_um` interval; a named `band` carries its own). `null` when no light at
    /// all reaches the observer.
    pub magnitude: Option<f64>,
    /// Range-normalised magnitude: `magnitude` moved to a range of 1000 km,
    /// m − 5 log10(R / 1000 km), the phase left as it is. `null` with `magnitude`.
    /// (Formerly `magnitude_std`.)
    pub magnitude_1000km: Option<f64>,
    /// The observers' standard magnitude: at 1000 km and 90° phase, the phase reduced with
    /// the Lambert sphere's phase law F(g) = ((π − g) cos g + sin g)/π:
    /// `magnitude_1000km` + 2.5 log10(F(g) / F(90°)). Constant over a light curve of a
    /// Lambertian sphere. `null` with `magnitude`, or at phase 180° (F = 0).
    pub magnitude_standard: Option<f64>,
    /// McCants' intrinsic magnitude: at 1000 km and full phase (0°), the phase reduced with
    /// the same Lambert sphere law: `magnitude_1000km` + 2.5 log10 F(g)
    /// (= `magnitude_standard` − 2.5 log10 π, 1.243 mag brighter). `null` with
    /// `magnitude_standard`.
    pub magnitude_intrinsic: Option<f64>,
    /// Sun–object–observer angle, degrees.
    pub phase_angle_deg: f64,
    /// Object–observer distance, m.
    pub range_m: f64,
    /// Area both sunlit and seen by the observer, m².
    pub lit_visible_area_m2: f64,
    /// Fraction of the solar disk hidden by the Earth (0 sunlit, 1 umbra).
    pub eclipse: f64,
    /// The Earth lies across the line of sight (the segment from the object to the
    /// observer passes through it): nothing reaches the observer, so the irradiances are 0
    /// and the magnitudes `null` (`intensity_w_sr` is still the object's). `false` when the
    /// epoch gives no `earth`.
    pub earth_blocks_view: bool,
    /// `geometry` requests only: the object's azimuth seen from the site, degrees from
    /// north through east (geometric, no refraction).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub azimuth_deg: Option<f64>,
    /// `geometry` requests only: the object's elevation above the site's horizon,
    /// degrees (geometric, no refraction).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elevation_deg: Option<f64>,
    /// `geometry` requests only: the Sun's elevation at the site, degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sun_elevation_deg: Option<f64>,
    /// `geometry` requests only: the Earth hides some of the Sun from the object
    /// (penumbra or umbra; `eclipse` says how much).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub in_earth_shadow: Option<bool>,
    /// Requests with an `observation` only: the telescope's counts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub observation: Option<ObservationResult>,
}

/// A telescope's counts of the object at one epoch (the CCD equation, docs/physics.md
/// §10a). S = Φ·10^(−0.4kX)·A·t·q·τ·f_ap; N = √(S + sky + dark + n_pix·σ_R²).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, ToSchema, PartialEq)]
pub struct ObservationResult {
    /// The object's electrons in the photometric aperture, S.
    pub signal_e: f64,
    /// The sky's electrons in the aperture.
    pub sky_e: f64,
    /// Dark-current electrons in the aperture.
    pub dark_e: f64,
    /// Pixels in the aperture, π r² / s².
    pub pixels: f64,
    /// Noise in the aperture, e⁻: √(S + sky + dark + pixels·read_noise²).
    pub noise_e: f64,
    /// Signal-to-noise ratio S / N (0 when there is neither signal nor noise).
    pub snr: f64,
    /// The signal in ADU, S / gain.
    pub signal_adu: f64,
    /// Electrons on the brightest pixel (the image centred on it, plus sky and dark).
    pub peak_pixel_e: f64,
    /// The brightest pixel reaches the full well.
    pub saturated: bool,
    /// A noisy measurement of S: Poisson(S + sky + dark) plus normal read noise, less the
    /// expected sky and dark, drawn with the request's seed.
    pub sample_e: f64,
    /// The sample as a magnitude in the band, m − 2.5 log10(sample / S); `null` when the
    /// sample is not positive or there is no magnitude.
    pub sample_magnitude: Option<f64>,
}

/// How the light curve was computed.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct Summary {
    pub epochs: usize,
    pub triangles: usize,
    /// Planar faces after merging coplanar connected triangles of one material.
    pub faces: usize,
    /// Shadow and occlusion rays cast over all epochs.
    pub rays: u64,
    /// Wall-clock time of the computation, ms.
    pub elapsed_ms: f64,
    /// The method used and why it was chosen.
    pub method: String,
    /// Whether the mesh was detected as convex (no rays needed).
    pub convex: bool,
    /// Per material, in the request's order: how much of the light it receives it
    /// reflects.
    #[serde(default)]
    pub materials: Vec<MaterialAlbedo>,
}

/// A material's directional-hemispherical albedo ρ(θi) = ∫ f cosθr dω over the view
/// hemisphere (dimensionless): above 1 it reflects more light than it receives, as the
/// paper's Eqs. 7–8 do for its own fitted materials (docs/physics.md §6.5).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema, PartialEq)]
pub struct MaterialAlbedo {
    pub name: String,
    /// ρ for light at normal incidence.
    pub albedo_normal: f64,
    /// The largest ρ over incidences 0°, 30°, 50°, 65°, 75° and 85°.
    pub albedo_max: f64,
    /// The incidence of `albedo_max`, degrees.
    pub albedo_max_incidence_deg: f64,
}
