//! The `image` method: visibility by orthographic pixel sampling from the observer, as
//! rendering the object and summing the image would (the usual renderer-based way).
//!
//! Per epoch, a square view perpendicular to the line of sight spans the mesh's bounding
//! sphere with `size`² pixels and `samples`² stratified rays per pixel. Each ray's closest
//! hit is the surface the observer sees there; a shadow ray from it towards the Sun (and
//! the earthshine direction) decides whether that spot is lit. A ray that hits face `f`
//! stands for a patch of f of area (pixel area / samples²) / |cos θr|, so summing the
//! patches gives each face's seen-and-lit area, which replaces the adaptive method's
//! exact classification in Eq. 12. The BRDF stays per face (a flat face has one θi and
//! one θr), so what this method measures is the cost and error of pixel sampling alone.
//!
//! Sharing with `src/render`: the view basis, the ray origin per pixel sample and the
//! closest-hit + shadow-ray step are the same as a thumbnail renderer's; a later
//! refactor could give both one `View { origin(px, py, sample) }` and one
//! `shade_hit(hit) -> (face, lit_sun, lit_earth)` and keep only the accumulation
//! (per-face area here, per-pixel radiance there) separate.

use crate::geometry::bvh::Occluder;
use crate::geometry::orthonormal_basis;
use crate::geometry::Faces;
use crate::scene::Scene;
use glam::DVec3;

/// Ray-casting state of the `image` method, built once per request.
pub struct ImageView {
    occluder: Occluder,
    /// Face of each mesh triangle.
    face_of: Vec<u32>,
    centre: DVec3,
    radius: f64,
    size: u32,
    samples: u32,
}

/// What one epoch needs sampled for one face.
#[derive(Debug, Clone, Copy, Default)]
struct Wanted {
    /// The face reflects sunlight towards the observer (needs Sun shadow rays).
    sun: bool,
    /// The face reflects earthshine towards the observer.
    earth: bool,
    /// Side seen: +1 front, −1 back (two-sided materials), 0 not sending light.
    side: f64,
}

/// Per-thread buffers of the `image` method, reused across epochs.
#[derive(Default)]
pub struct ImageScratch {
    wanted: Vec<Wanted>,
    /// Seen-and-sunlit area per face, m².
    a_sun: Vec<f64>,
    /// Seen-and-earthlit area per face, m².
    a_earth: Vec<f64>,
}

impl ImageScratch {
    /// Fractions of face `face` (of area `area`, m²) seen and sunlit, seen and earthlit,
    /// as sampled by the last [`ImageView::sample`].
    pub fn fractions(&self, face: usize, area: f64) -> (f64, f64) {
        (self.a_sun[face] / area, self.a_earth[face] / area)
    }
}

impl ImageView {
    /// Builds the BVH and the triangle → face map.
    pub fn build(scene: &Scene, faces: &Faces) -> ImageView {
        let mut face_of = vec![u32::MAX; scene.mesh.triangles.len()];
        for (fi, f) in faces.faces.iter().enumerate() {
            for &t in &f.triangles {
                face_of[t as usize] = fi as u32;
            }
        }
        let (centre, radius) = scene.mesh.bounding_sphere();
        ImageView {
            occluder: Occluder::build(&scene.mesh),
            face_of,
            centre,
            radius,
            size: scene.image_size,
            samples: scene.image_samples,
        }
    }

    /// Pixels on a side and samples per pixel side.
    pub fn resolution(&self) -> (u32, u32) {
        (self.size, self.samples)
    }

    /// Samples one epoch's view towards `view` (unit, object → observer) with the Sun
    /// towards `sun` and earthshine's shadow direction `earth` (`None`: unshadowed).
    /// `lit` lists the faces that send light: (face, side seen ±1, sunlit, earthlit).
    /// Afterwards [`ImageScratch::fractions`] gives each face's sampled fractions.
    /// Returns the rays cast. Stops early (fractions meaningless) once `cancelled` returns
    /// true: it is polled once a row, as a 4096-px view takes minutes.
    #[allow(clippy::too_many_arguments)]
    pub fn sample(
        &self,
        scratch: &mut ImageScratch,
        faces: &Faces,
        lit: impl Iterator<Item = (u32, f64, bool, bool)>,
        view: DVec3,
        sun: DVec3,
        earth: Option<DVec3>,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> u64 {
        let ImageScratch {
            wanted,
            a_sun,
            a_earth,
        } = scratch;
        wanted.clear();
        wanted.resize(faces.faces.len(), Wanted::default());
        for (face, side, sun, earth) in lit {
            wanted[face as usize] = Wanted { sun, earth, side };
        }
        self.visible_areas(faces, wanted, view, sun, earth, a_sun, a_earth, cancelled)
    }

    #[allow(clippy::too_many_arguments)]
    fn visible_areas(
        &self,
        faces: &Faces,
        wanted: &[Wanted],
        view: DVec3,
        sun: DVec3,
        earth: Option<DVec3>,
        a_sun: &mut Vec<f64>,
        a_earth: &mut Vec<f64>,
        cancelled: &(dyn Fn() -> bool + Sync),
    ) -> u64 {
        let nf = faces.faces.len();
        a_sun.clear();
        a_sun.resize(nf, 0.0);
        a_earth.clear();
        a_earth.resize(nf, 0.0);
        // obvhs 0.4 misses every hit along a direction with a −0.0 component (its octant
        // test and 1/−0 = −∞ disagree): hand it +0.0, also for what would round to −0 in f32
        let clean = |d: DVec3| {
            DVec3::from_array(d.to_array().map(|x| if x.abs() < 1e-37 { 0.0 } else { x }))
        };
        let (view, sun, earth) = (clean(view), clean(sun), earth.map(clean));
        let back = clean(-view);
        let (u, w) = orthonormal_basis(view);
        // Start the rays outside the bounding sphere, looking back along the line of sight.
        let r = self.radius.max(f64::MIN_POSITIVE) * 1.001;
        let plane = self.centre + view * (2.0 * r);
        let n = self.size as usize;
        let s = self.samples as usize;
        let pixel = 2.0 * r / n as f64;
        let sample_area = pixel * pixel / (s * s) as f64;
        let mut rays = 0u64;
        for py in 0..n {
            if cancelled() {
                break;
            }
            for px in 0..n {
                for sy in 0..s {
                    for sx in 0..s {
                        // stratified: the centre of each of the s × s sub-squares
                        let x = -r + pixel * (px as f64 + (sx as f64 + 0.5) / s as f64);
                        let y = -r + pixel * (py as f64 + (sy as f64 + 0.5) / s as f64);
                        if x * x + y * y > r * r {
                            continue; // outside the bounding sphere's disk: nothing to hit
                        }
                        let origin = plane + u * x + w * y;
                        rays += 1;
                        let Some((t, tri)) = self.occluder.first_hit(origin, back) else {
                            continue;
                        };
                        let fi = self.face_of[tri] as usize;
                        let want = wanted[fi];
                        if want.side == 0.0 || !(want.sun || want.earth) {
                            continue; // back of a one-sided face, or a face sending no light
                        }
                        let normal = faces.faces[fi].normal * want.side;
                        let cos_r = normal.dot(view);
                        if cos_r <= 0.0 {
                            continue;
                        }
                        let hit = origin - view * t;
                        let patch = sample_area / cos_r;
                        if want.sun {
                            rays += 1;
                            if self.occluder.is_clear(hit, normal, sun) {
                                a_sun[fi] += patch;
                            }
                        }
                        if want.earth {
                            let lit = match earth {
                                Some(e) if normal.dot(e) > 1e-3 => {
                                    rays += 1;
                                    self.occluder.is_clear(hit, normal, e)
                                }
                                _ => true,
                            };
                            if lit {
                                a_earth[fi] += patch;
                            }
                        }
                    }
                }
            }
        }
        rays
    }
}
