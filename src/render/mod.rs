//! Thumbnails: images of the object as the observer sees it, with the light curve's
//! physics per pixel (same BRDFs, Sun after eclipse, earthshine, cast shadows).
//!
//! ```text
//! Scene ──Renderer::new──▶ faces, BVH (once per request)
//! epoch ──camera (orthographic along −v, Sun "up")──▶ per-face radiance (shade.rs)
//!       ──per pixel: samples² stratified jittered rays, closest hit, shadow rays──▶
//!       RadiometricImage (f32 radiance, W/(m²·sr))
//!       ──exposure (one for a sequence, or log/auto)──▶ 8-bit PNG
//! ```
//!
//! The radiometric image is the light curve seen pixel by pixel:
//! Σ_pixels L·A_pixel / R² estimates the epoch's irradiance (see [`shade`]), with a
//! sampling error that [`RadiometricImage::std_error_w_m2`] estimates.

pub mod camera;
pub mod exposure;
pub mod png;
pub mod shade;

pub use camera::Camera;

use crate::geometry::bvh::Occluder;
use crate::geometry::Faces;
use crate::light::EpochLight;
use crate::radiometry::sun;
use crate::scene::response::Thumbnail;
use crate::scene::{Epoch, Exposure, Method, Scene, Thumbnails};
use base64::Engine as _;
use rayon::prelude::*;
use shade::{face_shades, Shader};

/// Seed of the sub-pixel jitter: fixed, so the same pixel is sampled at the same
/// places in every frame and a still edge does not flicker through a sequence.
const JITTER_SEED: u64 = 0x676c_696e_745f_7278;

/// A rendered image in physical units.
#[derive(Debug, Clone, PartialEq)]
pub struct RadiometricImage {
    /// The camera that took it (orientation, frame, scale).
    pub camera: Camera,
    /// Pixels on a side.
    pub size: u32,
    /// Samples per pixel side.
    pub samples: u32,
    /// Radiance towards the observer per pixel, W/(m²·sr), row-major, top row first.
    pub radiance: Vec<f32>,
    /// Object–observer range, m.
    pub range_m: f64,
    /// Σ radiance over pixels in f64, W/(m²·sr).
    pub sum_radiance: f64,
    /// Estimated variance of `sum_radiance` from the sub-pixel samples, (W/(m²·sr))².
    pub sum_variance: f64,
    /// Rays cast (primary and shadow).
    pub rays: u64,
}

impl RadiometricImage {
    /// Scale at the object, m per pixel.
    pub fn metres_per_pixel(&self) -> f64 {
        self.camera.metres_per_pixel()
    }

    /// Radiant intensity towards the observer, Σ L·A_pixel, W/sr.
    pub fn intensity_w_sr(&self) -> f64 {
        self.sum_radiance * self.camera.pixel_area_m2()
    }

    /// Irradiance at the observer, Σ L·A_pixel / R², W/m²: the light curve's value.
    pub fn irradiance_w_m2(&self) -> f64 {
        self.intensity_w_sr() / (self.range_m * self.range_m)
    }

    /// Estimated standard error of [`Self::irradiance_w_m2`], W/m². From the spread of
    /// each pixel's samples (treated as independent, which overstates the error of
    /// stratified sampling); with one sample per pixel, from the spread of horizontally
    /// adjacent pixel pairs.
    pub fn std_error_w_m2(&self) -> f64 {
        self.sum_variance.sqrt() * self.camera.pixel_area_m2() / (self.range_m * self.range_m)
    }

    /// Brightest pixel, W/(m²·sr).
    pub fn max_radiance(&self) -> f64 {
        exposure::peak(&self.radiance)
    }
}

/// Everything built once per request for rendering: faces and the BVH.
pub struct Renderer<'a> {
    scene: &'a Scene,
    faces: Faces,
    /// Face index of every triangle.
    face_of: Vec<u32>,
    occluder: Occluder,
}

impl<'a> Renderer<'a> {
    /// Builds faces (as the light curve does for this scene's method) and the BVH.
    pub fn new(scene: &'a Scene) -> Renderer<'a> {
        let mut faces = Faces::build(&scene.mesh, scene.method != Method::Centroid);
        faces.set_tangents(|m| scene.materials[m as usize].tangent);
        Renderer::with_faces(scene, faces)
    }

    /// Uses faces already built (the light curve's, so both share normals and
    /// tangents exactly).
    pub fn with_faces(scene: &'a Scene, faces: Faces) -> Renderer<'a> {
        let mut face_of = vec![0u32; scene.mesh.triangles.len()];
        for (fi, f) in faces.faces.iter().enumerate() {
            for &t in &f.triangles {
                face_of[t as usize] = fi as u32;
            }
        }
        Renderer {
            scene,
            faces,
            face_of,
            occluder: Occluder::build(&scene.mesh),
        }
    }

    /// Renders `epoch` on a `size`×`size` image with `samples`×`samples` stratified,
    /// jittered samples per pixel.
    pub fn render(&self, epoch: &Epoch, size: u32, samples: u32) -> RadiometricImage {
        self.render_until(epoch, size, samples, &|| false)
            .expect("never cancelled")
    }

    /// [`Self::render`], giving up (`None`) once `cancelled` returns true (checked per
    /// row, so a large image stops promptly).
    pub fn render_until(
        &self,
        epoch: &Epoch,
        size: u32,
        samples: u32,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> Option<RadiometricImage> {
        let size = size.max(1);
        let n = samples.max(1);
        let range = epoch.observer.length();
        let view = epoch.observer / range;
        let camera = Camera::frame(&self.scene.mesh, view, epoch.sun, size);
        let light = EpochLight::at(&self.scene.illumination, epoch);
        let sun_radius = sun::angular_radius(epoch.sun_distance_m);
        let shades = face_shades(
            &self.faces,
            &self.scene.materials,
            &light,
            epoch.sun,
            sun_radius,
            view,
        );
        let shader = Shader {
            occluder: &self.occluder,
            face_of: &self.face_of,
            shades: &shades,
            sun: shade::ray_dir(epoch.sun),
            earth: light.earthshine.shadow_dir.map(shade::ray_dir),
            dir: shade::ray_dir(-view),
        };
        let w = size as usize;
        let mut radiance = vec![0f32; w * w];
        let spp = (n * n) as f64;
        let rows: Vec<(f64, f64, u64)> = radiance
            .par_chunks_mut(w)
            .enumerate()
            .map(|(row, out)| {
                if cancelled() {
                    return (0.0, 0.0, 0);
                }
                let (mut sum, mut var, mut rays) = (0.0, 0.0, 0u64);
                let mut prev = 0.0;
                for (col, px) in out.iter_mut().enumerate() {
                    let pixel = (row * w + col) as u64;
                    let (mut s1, mut s2) = (0.0, 0.0);
                    for k in 0..n * n {
                        let (jx, jy) = jitter(pixel, k);
                        let u = col as f64 + ((k % n) as f64 + jx) / n as f64;
                        let v = row as f64 + ((k / n) as f64 + jy) / n as f64;
                        let (l, r) = shader.radiance(camera.ray_origin(u, v));
                        s1 += l;
                        s2 += l * l;
                        rays += r as u64;
                    }
                    let mean = s1 / spp;
                    *px = mean as f32;
                    sum += mean;
                    if n > 1 {
                        // variance of the pixel mean: sample variance / samples
                        var += ((s2 - s1 * mean) / (spp - 1.0)).max(0.0) / spp;
                    } else if col % 2 == 1 {
                        var += (mean - prev) * (mean - prev);
                    }
                    prev = mean;
                }
                (sum, var, rays)
            })
            .collect();
        let (sum_radiance, sum_variance, rays) = rows
            .iter()
            .fold((0.0, 0.0, 0), |a, r| (a.0 + r.0, a.1 + r.1, a.2 + r.2));
        if cancelled() {
            return None;
        }
        Some(RadiometricImage {
            camera,
            size,
            samples: n,
            radiance,
            range_m: range,
            sum_radiance,
            sum_variance,
            rays,
        })
    }

    /// Renders the scene's requested thumbnails (`scene.thumbnails`, or `spec`) as PNGs.
    pub fn thumbnails(&self, spec: &Thumbnails) -> Vec<Thumbnail> {
        self.thumbnails_until(spec, &|| false)
            .expect("never cancelled")
    }

    /// [`Self::thumbnails`], giving up (`None`) once `cancelled` returns true.
    pub fn thumbnails_until(
        &self,
        spec: &Thumbnails,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> Option<Vec<Thumbnail>> {
        let images: Vec<RadiometricImage> = spec
            .epochs
            .par_iter()
            .map(|&i| self.render_until(&self.scene.epochs[i], spec.size, spec.samples, cancelled))
            .collect::<Option<_>>()?;
        let times: Vec<f64> = spec
            .epochs
            .iter()
            .map(|&i| self.scene.epochs[i].t)
            .collect();
        Some(encode(spec, &images, &times))
    }
}

/// The PNG thumbnails of rendered `images` (one per `spec.epochs`, at `times`), exposed
/// together as `spec.exposure` says.
pub fn encode(spec: &Thumbnails, images: &[RadiometricImage], times: &[f64]) -> Vec<Thumbnail> {
    let radiances: Vec<&[f32]> = images.iter().map(|im| im.radiance.as_slice()).collect();
    let whites = exposure::white_levels(spec.exposure, &radiances);
    let b64 = base64::engine::general_purpose::STANDARD;
    spec.epochs
        .par_iter()
        .zip(times.par_iter())
        .zip(images.par_iter())
        .zip(whites.par_iter())
        .map(|(((&i, &t), img), &white)| {
            let grey = exposure::to_grey(&img.radiance, white, spec.exposure == Exposure::Log);
            Thumbnail {
                epoch: i,
                t,
                size: img.size,
                metres_per_pixel: img.metres_per_pixel(),
                exposure_w_m2_sr: white,
                png_base64: b64.encode(png::encode_grey(&grey, img.size)),
            }
        })
        .collect()
}

/// Renders epoch `epoch` (index into `scene.epochs`) of a scene: the radiometric image,
/// for tests, the consistency check and the image method.
pub fn radiometric_image(scene: &Scene, epoch: usize, size: u32, samples: u32) -> RadiometricImage {
    Renderer::new(scene).render(&scene.epochs[epoch], size, samples)
}

/// Renders the scene's requested thumbnails; empty when it asks for none.
pub fn thumbnails(scene: &Scene) -> Vec<Thumbnail> {
    match &scene.thumbnails {
        Some(spec) => Renderer::new(scene).thumbnails(spec),
        None => Vec::new(),
    }
}

/// Two uniforms in [0, 1) for sample `k` of `pixel`: a hash (SplitMix64), so the
/// pattern is fixed per pixel and independent between pixels.
#[inline]
fn jitter(pixel: u64, k: u32) -> (f64, f64) {
    let mut z = JITTER_SEED ^ pixel.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ ((k as u64) << 40);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    let to_unit = |x: u64| (x as f64) * (1.0 / 4_294_967_296.0);
    (to_unit(z >> 32), to_unit(z & 0xffff_ffff))
}
