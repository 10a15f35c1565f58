//! The integrator: Eq. 12 summed over faces for every epoch, in parallel.
//!
//! ```text
//! Scene ──prepare once──▶ Prepared (faces, convexity, BVH + occluder candidates, band integral)
//! for each epoch (rayon): geometry → illumination (sun, eclipse, earthshine)
//!                         → per face: BRDF × cosines × area × visible fraction → EpochResult
//! ```

pub mod articulated;
pub mod eq12;
pub mod image;
pub mod methods;
pub mod per_direction;
pub mod silhouettes;
pub mod visibility;

use crate::geometry::{convex, Faces};
use crate::scene::{EpochResult, MaterialAlbedo, Method, Response, Scene, Summary};
use rayon::prelude::*;
use silhouettes::tally::{self, Tally};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::time::Instant;
use visibility::{Visibility, VisibilityMode};

/// Progress and cancellation shared between a running simulation and its caller
/// (the CLI's progress bar, the service's job status).
#[derive(Debug, Default)]
pub struct Progress {
    done: AtomicUsize,
    total: AtomicUsize,
    cancel: AtomicBool,
}

impl Progress {
    pub fn new() -> Self {
        Self::default()
    }
    /// Epochs finished so far.
    pub fn done(&self) -> usize {
        self.done.load(Ordering::Relaxed)
    }
    /// Epochs in the running request (0 before it starts).
    pub fn total(&self) -> usize {
        self.total.load(Ordering::Relaxed)
    }
    /// Asks the running simulation to stop: at its next epoch, or within the epoch where
    /// one can take long (the `image` method's rows, the thumbnails' rows).
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
    pub fn is_cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// The simulation was cancelled through [`Progress::cancel`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("cancelled")]
pub struct Cancelled;

/// How an epoch finds which part of each face is lit and seen: one per method, each
/// with what it builds once per request.
pub enum Occlusion<'a> {
    /// Nothing can shadow or hide anything: a convex mesh (or `convex` asked for), every
    /// face facing a light and the observer is lit and seen whole.
    None,
    /// The per-face path (`adaptive`, `centroid`): proofs, exact clipping and rays face
    /// by face.
    PerFace(Box<Visibility>),
    /// The silhouette method (what `auto` takes for a non-convex mesh).
    Silhouettes(Box<silhouettes::Silhouettes<'a>>),
    /// The `image` method's pixel sampler.
    Image(Box<self::image::ImageView>),
}

/// Everything computed once per request.
pub struct Prepared<'a> {
    pub scene: &'a Scene,
    pub faces: Faces,
    pub convex: bool,
    /// How the parts of faces that are lit and seen are found.
    pub occlusion: Occlusion<'a>,
    /// Band solar irradiance at 1 AU, W/m² (the magnitude zero point).
    pub sun_band_1au: f64,
    /// What was chosen and why, for `summary.method`.
    pub method: String,
}

impl<'a> Prepared<'a> {
    /// Merges faces, detects convexity, builds the BVH if rays are needed.
    pub fn new(scene: &'a Scene) -> Prepared<'a> {
        let per_triangle = scene.method == Method::Centroid;
        let silhouettes = matches!(scene.method, Method::Silhouette | Method::Auto);
        // the contact search's grid needs only the triangles: binned while the faces
        // merge, most of which runs on one thread (wasted when `auto` finds the object
        // convex)
        let (mut faces, grid) = rayon::join(
            || {
                tally::timed(Tally::FacesNs, || {
                    let mut faces = Faces::build(&scene.mesh, !per_triangle);
                    faces.set_tangents(|m| scene.materials[m as usize].tangent);
                    faces.sort_spatially();
                    faces
                })
            },
            || {
                tally::timed(Tally::TriangleGridNs, || {
                    silhouettes.then(|| silhouettes::Silhouettes::contact_grid(&scene.mesh))
                })
            },
        );
        let convex = is_convex(scene, &faces);
        let occlusion = match scene.method {
            Method::Adaptive => Occlusion::PerFace(Box::new(Visibility::build(
                scene,
                &faces,
                VisibilityMode::Adaptive,
            ))),
            Method::Centroid => Occlusion::PerFace(Box::new(Visibility::build(
                scene,
                &faces,
                VisibilityMode::Centroid,
            ))),
            Method::Image => {
                Occlusion::Image(Box::new(self::image::ImageView::build(scene, &faces)))
            }
            Method::Auto if convex => Occlusion::None,
            Method::Silhouette | Method::Auto => Occlusion::Silhouettes(Box::new(
                silhouettes::Silhouettes::build_ordered(scene, &mut faces, grid),
            )),
            Method::Convex => Occlusion::None,
        };
        Prepared::from_parts(scene, faces, convex, occlusion)
    }

    /// A preparation from its parts, its method described.
    pub fn from_parts(
        scene: &'a Scene,
        faces: Faces,
        convex: bool,
        occlusion: Occlusion<'a>,
    ) -> Prepared<'a> {
        let method = format!(
            "{}; {}",
            method_note(scene, &faces, convex),
            light_model_note(scene)
        );
        Prepared {
            scene,
            faces,
            convex,
            occlusion,
            sun_band_1au: scene.illumination.sun_1au_w_m2,
            method,
        }
    }
}

/// Whether no face of the scene's mesh can shadow or hide another: a planar mesh when
/// any face is two-sided, else a convex one.
pub fn is_convex(scene: &Scene, faces: &Faces) -> bool {
    let two_sided = faces
        .faces
        .iter()
        .any(|f| scene.materials[f.material as usize].two_sided);
    if two_sided {
        convex::is_planar(&scene.mesh)
    } else {
        convex::is_convex(&scene.mesh, faces)
    }
}

/// What was chosen and why, for `summary.method` (the light model apart).
fn method_note(scene: &Scene, faces: &Faces, convex: bool) -> String {
    let auto = if scene.method == Method::Auto {
        "auto → "
    } else {
        ""
    };
    match scene.method {
        Method::Convex => "convex: back-face culling only, no rays (as requested)".to_string(),
        Method::Auto if convex => {
            "auto → convex: the mesh is convex, so no face can shadow or hide another; no rays"
                .to_string()
        }
        Method::Auto | Method::Silhouette => format!(
            "{auto}silhouette: {} faces from {} triangles; per direction, faces no shadow edge crosses \
             decided by one ray per connected group, crossed faces cut exactly along the shadow lines",
            faces.len(),
            scene.mesh.triangles.len(),
        ),
        Method::Adaptive => format!(
            "{auto}adaptive: {} faces from {} triangles; faces an occluder may touch {}",
            faces.len(),
            scene.mesh.triangles.len(),
            if scene.clip_shadows {
                format!("are clipped exactly (ray-sampled to tolerance {:e} where shadows cut one too finely)", scene.tolerance)
            } else {
                format!("are ray-sampled to tolerance {:e}", scene.tolerance)
            }
        ),
        Method::Centroid => {
            "centroid: one ray per direction at each triangle's centroid (all lit or all dark)"
                .to_string()
        }
        Method::Image => format!(
            "image: orthographic view from the observer, {0}x{0} pixels, {1}x{1} samples each, shadow rays per hit",
            scene.image_size, scene.image_samples
        ),
    }
}

/// What the illumination was modelled with, for `summary.method`: the earthshine model
/// and the band integral.
fn light_model_note(scene: &Scene) -> String {
    use crate::scene::EarthshineModel;
    let earthshine = match scene.illumination.earthshine {
        EarthshineModel::Off => "earthshine off".to_string(),
        EarthshineModel::Seed => "earthshine: the paper's parallel beam from the Earth".to_string(),
        EarthshineModel::Sphere => {
            "earthshine: the Earth's sunlit crescent integrated as an extended \
                                     source (crescent beams; narrow lobes by a glint rule per face)"
                .to_string()
        }
    };
    // Every material model has wavelength-independent parameters, so the band integral
    // factors out of the face sum (eq12's module doc).
    let ill = &scene.illumination;
    let spectrum = match ill.solar_spectrum {
        crate::scene::SolarSpectrumChoice::Planck => {
            format!("a {} K blackbody Sun", ill.sun_temperature_k)
        }
        crate::scene::SolarSpectrumChoice::Calspec => "the CALSPEC solar spectrum".to_string(),
    };
    let band = match ill.passband {
        Some(p) => format!(
            "band {}: {}, the Sun {} mag",
            p.name, p.description, p.sun_magnitude
        ),
        None => format!(
            "band {}–{} µm, the Sun {} mag",
            ill.band_um[0], ill.band_um[1], ill.sun_magnitude
        ),
    };
    format!(
        "{earthshine}; {band}, {spectrum}; band integral computed once (no material depends on wavelength)"
    )
}

/// Computes the light curve of a scene.
pub fn simulate(scene: &Scene) -> Response {
    simulate_with(scene, &Progress::new()).expect("not cancelled")
}

/// Computes the light curve, reporting progress and honouring cancellation.
pub fn simulate_with(scene: &Scene, progress: &Progress) -> Result<Response, Cancelled> {
    let bins = scene.spectral.len().max(1);
    progress
        .total
        .store(scene.epochs.len() * bins, Ordering::Relaxed);
    if scene.spectral.is_empty() {
        simulate_counted(scene, &[eq12::Lighting::of(scene)], progress)
    } else {
        simulate_spectral(scene, progress)
    }
}

/// A scene whose materials depend on wavelength: the light curve of each wavelength bin
/// (its materials, its share of the Sun), summed, the magnitudes taken from the sum
/// (docs/physics.md §8).
fn simulate_spectral(scene: &Scene, progress: &Progress) -> Result<Response, Cancelled> {
    let start = Instant::now();
    let base = Scene {
        spectral: Vec::new(),
        observation: None,
        thumbnails: None,
        ..scene.clone()
    };
    // each bin: its materials at its wavelength, its share of the Sun; one preparation
    let lightings: Vec<eq12::Lighting> = scene
        .spectral
        .iter()
        .map(|bin| eq12::Lighting {
            materials: &bin.materials,
            illumination: crate::scene::Illumination {
                sun_share: bin.share,
                ..scene.illumination
            },
        })
        .collect();
    let mut r = simulate_counted(&base, &lightings, progress)?;
    let ill = &scene.illumination;
    for e in &mut r.epochs {
        let phase = e.phase_angle_deg.to_radians();
        eq12::set_magnitudes(e, phase, ill.sun_1au_w_m2, ill.sun_magnitude);
    }
    observe(scene, &mut r.epochs);
    if let Some(spec) = &scene.thumbnails {
        // rendered with each material at the bins' mean wavelength
        let mut grey = base.clone();
        grey.materials = scene.materials.clone();
        r.thumbnails = Some(
            crate::render::Renderer::new(&grey)
                .thumbnails_until(spec, &|| progress.is_cancelled())
                .ok_or(Cancelled)?,
        );
    }
    let (materials, mut warnings) = material_albedos(scene);
    warnings.extend(scene.warnings.iter().cloned());
    r.summary.materials = materials;
    r.warnings = warnings;
    r.summary.elapsed_ms = start.elapsed().as_secs_f64() * 1e3;
    r.summary.method = format!(
        "{}; per wavelength: {} bins of the band, each material at each bin's mean wavelength",
        r.summary.method.replace(
            "; band integral computed once (no material depends on wavelength)",
            ""
        ),
        scene.spectral.len()
    );
    Ok(r)
}

/// A telescope's counts on each epoch, when the scene asks for them (validation saw to a
/// named band).
fn observe(scene: &Scene, epochs: &mut [EpochResult]) {
    let (Some(obs), Some(band)) = (&scene.observation, scene.illumination.passband) else {
        return;
    };
    use crate::radiometry::ccd::photon_rate;
    let ill = &scene.illumination;
    let mean = band.mean_wavelength_um();
    let zero_rate = photon_rate(ill.sun_1au_w_m2 * 10f64.powf(0.4 * ill.sun_magnitude), mean);
    for (i, e) in epochs.iter_mut().enumerate() {
        let c = obs.counts(photon_rate(e.irradiance_w_m2, mean), zero_rate, i as u64);
        let sample_magnitude = match e.magnitude {
            Some(m) if c.sample_e > 0.0 && c.signal_e > 0.0 => {
                Some(m - 2.5 * (c.sample_e / c.signal_e).log10())
            }
            _ => None,
        };
        e.observation = Some(crate::scene::ObservationResult {
            signal_e: c.signal_e,
            sky_e: c.sky_e,
            dark_e: c.dark_e,
            pixels: c.pixels,
            noise_e: c.noise_e,
            snr: c.snr,
            signal_adu: c.signal_adu,
            peak_pixel_e: c.peak_pixel_e,
            saturated: c.saturated,
            sample_e: c.sample_e,
            sample_magnitude,
        });
    }
}

/// What a request's preparation tells its summary.
pub struct PreparedInfo {
    pub faces: usize,
    pub method: String,
    pub convex: bool,
}

impl PreparedInfo {
    fn of(p: &Prepared) -> PreparedInfo {
        PreparedInfo {
            faces: p.faces.len(),
            method: p.method.clone(),
            convex: p.convex,
        }
    }
}

/// The epochs `which` (indices into `epochs`) of a prepared scene, in parallel, each
/// counted in `progress`; `None` where cancelled. With several `lightings` (a spectral
/// scene's wavelength bins) each epoch is evaluated under each, in order, and their
/// irradiances and intensities summed: one preparation serves every bin.
pub fn evaluate_epochs(
    prepared: &Prepared,
    lightings: &[eq12::Lighting],
    epochs: &[crate::scene::Epoch],
    which: &[usize],
    progress: &Progress,
    rays: &AtomicU64,
) -> Vec<Option<EpochResult>> {
    let under = |lighting: &eq12::Lighting| -> Vec<Option<EpochResult>> {
        which
            .par_iter()
            .map_init(eq12::Scratch::default, |scratch, &i| {
                if progress.is_cancelled() {
                    return None;
                }
                let (result, n) = eq12::evaluate(prepared, lighting, &epochs[i], scratch, &|| {
                    progress.is_cancelled()
                });
                rays.fetch_add(n, Ordering::Relaxed);
                progress.done.fetch_add(1, Ordering::Relaxed);
                Some(result)
            })
            .collect()
    };
    let (first, rest) = lightings.split_first().expect("at least one lighting");
    let mut total = under(first);
    for lighting in rest {
        for (t, r) in total.iter_mut().zip(under(lighting)) {
            match (t.as_mut(), r) {
                (Some(a), Some(b)) => {
                    a.irradiance_w_m2 += b.irradiance_w_m2;
                    a.sun_w_m2 += b.sun_w_m2;
                    a.earthshine_w_m2 += b.earthshine_w_m2;
                    a.intensity_w_sr += b.intensity_w_sr;
                }
                _ => *t = None,
            }
        }
    }
    total
}

/// [`simulate_with`] for one scene, progress counted but its total left as it is.
fn simulate_counted(
    scene: &Scene,
    lightings: &[eq12::Lighting],
    progress: &Progress,
) -> Result<Response, Cancelled> {
    let start = Instant::now();
    let rays = AtomicU64::new(0);
    let all: Vec<usize> = (0..scene.epochs.len()).collect();
    let (epochs, info, thumbnails) = match &scene.articulation {
        Some(a) => articulated::simulate(scene, a, lightings, progress, &rays)?,
        None => {
            // `centroid` with subdivisions samples a refined copy of the mesh
            let refined = methods::refined_for_centroid(scene);
            let scene = refined.as_ref().unwrap_or(scene);
            let prepared = Prepared::new(scene);
            let epochs =
                evaluate_epochs(&prepared, lightings, &scene.epochs, &all, progress, &rays);
            // Images only when asked for: a light curve without them pays nothing.
            let thumbnails = match &scene.thumbnails {
                Some(spec) if !progress.is_cancelled() => Some(
                    crate::render::Renderer::with_faces(scene, prepared.faces.clone())
                        .thumbnails_until(spec, &|| progress.is_cancelled())
                        .ok_or(Cancelled)?,
                ),
                _ => None,
            };
            (epochs, PreparedInfo::of(&prepared), thumbnails)
        }
    };
    if progress.is_cancelled() {
        return Err(Cancelled);
    }
    let mut epochs: Vec<EpochResult> = epochs
        .into_iter()
        .map(|e| e.ok_or(Cancelled))
        .collect::<Result<_, _>>()?;
    // what the site sees, for epochs computed from a `geometry`
    if scene.sky.len() == epochs.len() {
        for (e, s) in epochs.iter_mut().zip(&scene.sky) {
            e.azimuth_deg = Some(s.azimuth_deg);
            e.elevation_deg = Some(s.elevation_deg);
            e.sun_elevation_deg = Some(s.sun_elevation_deg);
            e.in_earth_shadow = Some(e.eclipse > 0.0);
        }
    }
    observe(scene, &mut epochs);
    let (materials, mut warnings) = material_albedos(scene);
    warnings.extend(scene.warnings.iter().cloned());
    Ok(Response {
        summary: Summary {
            epochs: epochs.len(),
            triangles: scene.mesh.triangles.len(),
            faces: info.faces,
            rays: rays.load(Ordering::Relaxed),
            elapsed_ms: start.elapsed().as_secs_f64() * 1e3,
            method: info.method,
            convex: info.convex,
            materials,
        },
        epochs,
        thumbnails,
        warnings,
    })
}

/// Each material's albedo, and a warning for each that reflects more than it receives.
fn material_albedos(scene: &Scene) -> (Vec<MaterialAlbedo>, Vec<String>) {
    let mut warnings = Vec::new();
    let found: Vec<_> = scene
        .materials
        .par_iter()
        .map(|m| crate::brdf::albedo::remembered(&m.brdf))
        .collect();
    let albedos = scene
        .materials
        .iter()
        .zip(found)
        .map(|(m, a)| {
            if a.max > 1.0 {
                let hint = match m.brdf {
                    crate::brdf::Brdf::SeedMicrofacet(_) => {
                        " (the paper's Eqs. 7-8 are not normalised: with \"normalised\": true, \
                         km is the specular albedo)"
                    }
                    _ => "",
                };
                warnings.push(format!(
                    "material `{}` reflects more light than it receives: its directional \
                     albedo is {:.3} at normal incidence, up to {:.3} at {}° incidence{hint}",
                    m.name, a.normal, a.max, a.max_at_deg
                ));
            }
            MaterialAlbedo {
                name: m.name.clone(),
                albedo_normal: a.normal,
                albedo_max: a.max,
                albedo_max_incidence_deg: a.max_at_deg,
            }
        })
        .collect();
    (albedos, warnings)
}
