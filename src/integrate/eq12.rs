//! One epoch of Eq. 12: E = Σ_faces (dI_sun + dI_earth)/R², with
//! dI = f·E·cosθi·cosθr·A_visible (Eq. 10), A_visible the part of the face both lit and seen.
//!
//! With constant material parameters the band integral factors out of the sum: the Sun's
//! band irradiance multiplies a purely geometric sum. A wavelength-dependent n(λ), k(λ)
//! would evaluate the face sum per spectral bin and weight by the bin's irradiance.

use super::per_direction::Toward;
use super::silhouettes::tally::{self, Tally};
use super::silhouettes::{PatchLight, Silhouettes};
use super::visibility::{FaceSide, Uncertain};
use super::{Occlusion, Prepared};
use crate::brdf::earth_light::EarthLight;
use crate::brdf::sun_disk::SunLight;
use crate::brdf::Frame;
use crate::geometry::angle_between;
use crate::light::EpochLight;
use crate::radiometry::{magnitude, sun};
use crate::scene::{Epoch, EpochResult, Illumination, Material, Scene};
use glam::DVec3;

/// What lights the prepared mesh in an evaluation: the materials and the illumination.
/// A scene's own ([`Lighting::of`]), or one wavelength bin's (its materials at the bin's
/// wavelength, its share of the Sun), so that the bins share one preparation.
#[derive(Clone, Copy)]
pub struct Lighting<'s> {
    pub materials: &'s [Material],
    pub illumination: Illumination,
}

impl<'s> Lighting<'s> {
    /// The scene's own materials and illumination.
    pub fn of(scene: &'s Scene) -> Lighting<'s> {
        Lighting {
            materials: &scene.materials,
            illumination: scene.illumination,
        }
    }
}

/// Per-thread buffers reused across epochs.
#[derive(Default)]
pub struct Scratch {
    lit: Vec<LitFace>,
    lit_patches: Vec<LitPatch>,
    visibility: super::visibility::Cache,
    image: super::image::ImageScratch,
    silhouettes: super::silhouettes::Scratch,
}

/// What lights faces of one material at this epoch: the Sun and the earthshine, each
/// with the BRDF's per-epoch part.
struct MaterialLight<'a> {
    two_sided: bool,
    /// The model can be linear over a patch of normals (patch sums).
    linear: bool,
    sun: SunLight<'a>,
    earth: EarthLight<'a>,
}

/// A face that reflects light towards the observer at this epoch.
struct LitFace {
    face: u32,
    /// The side seen (the back only of two-sided materials).
    side: FaceSide,
    /// Sun term f·cosθi·cosθr·E_s, W/(m²·sr) per m² of face.
    sun: f64,
    /// Earthshine term Σ f·cosθi·cosθr·E_beam, W/(m²·sr) per m² of face.
    earth: f64,
    /// The face's area, m² (kept here: pass 2 then reads this list alone).
    area: f64,
}

/// A patch of faces whose light pass 1 found linear over its normals, to be summed
/// whole where no direction decides its faces one by one ([`super::silhouettes`]'s
/// patch sums).
struct LitPatch {
    patch: u32,
    /// The Sun's and the earthshine's vectors L (Σ_f A_f (n_f·L)(n_f·v) is the patch's
    /// term, W/sr); zero for a light that reaches none of its faces.
    sun: DVec3,
    earth: DVec3,
    /// The patch's area, m².
    area: f64,
    light: PatchLight,
}

impl LitPatch {
    /// Whether the Sun and the earthshine reach it (the directions asked about it).
    fn lit_by(&self) -> (bool, bool) {
        (self.sun != DVec3::ZERO, self.earth != DVec3::ZERO)
    }

    /// One of its faces' Sun and earthshine terms, W/(m²·sr) per m², given its unit
    /// normal `n` and the unit direction to the observer `v`: (n·L)(n·v), what
    /// [`face_terms`] finds for every normal of the patch's cone, up to rounding. Either
    /// side's normal gives the same product.
    #[inline]
    fn face_terms(&self, n: DVec3, v: DVec3) -> (f64, f64) {
        let cr = n.dot(v);
        (
            (n.dot(self.sun) * cr).max(0.0),
            (n.dot(self.earth) * cr).max(0.0),
        )
    }
}

/// The directions of one epoch in the body frame (unit vectors) and the Sun's band
/// irradiance at the object after any eclipse (W/m²).
#[derive(Clone, Copy)]
struct Directions {
    view: DVec3,
    sun: DVec3,
    sun_w_m2: f64,
    /// Along which earthshine casts shadows, when there is earthshine.
    earth: Option<DVec3>,
}

impl Directions {
    /// The Sun's direction when it lights the object (not in umbra).
    fn sunlit(&self) -> Option<DVec3> {
        (self.sun_w_m2 > 0.0).then_some(self.sun)
    }
}

/// Evaluates one epoch; returns the result and the number of rays cast.
///
/// `cancelled` is polled inside the epoch where one epoch can take long (the `image`
/// method's rows); once it returns true the result is meaningless and the caller drops it.
pub fn evaluate(
    p: &Prepared,
    lighting: &Lighting,
    epoch: &Epoch,
    scratch: &mut Scratch,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> (EpochResult, u64) {
    let since = tally::now();
    let ill = &lighting.illumination;
    let range = epoch.observer.length();
    let light = EpochLight::at(ill, epoch);
    let dirs = Directions {
        view: epoch.observer / range,
        sun: epoch.sun,
        sun_w_m2: light.sun_w_m2,
        earth: light.earthshine.shadow_dir,
    };
    let lights = material_lights(lighting.materials, epoch, dirs.view, &light);
    let (decided, unshadowed) = lit_faces(p, &lights, &dirs, scratch);
    let (sums, rays) = visible_sums(p, &dirs, decided, unshadowed, scratch, cancelled);
    let result = epoch_result(p, epoch, range, dirs.view, &light, sums);
    tally::took(Tally::EpochNs, since);
    (result, rays)
}

/// Per material, what lights its faces at this epoch with what does not depend on the
/// face computed once: the Sun's and each earthshine beam's half vector and Fresnel term.
fn material_lights<'a>(
    materials: &'a [Material],
    epoch: &Epoch,
    v: DVec3,
    light: &'a EpochLight,
) -> Vec<MaterialLight<'a>> {
    let sun_radius = sun::angular_radius(epoch.sun_distance_m);
    materials
        .iter()
        .map(|m| MaterialLight {
            two_sided: m.two_sided,
            linear: m.brdf.has_constant_away_from_lobe(),
            sun: SunLight::eclipsed(&m.brdf, epoch.sun, v, sun_radius, light.penumbra),
            earth: EarthLight::new(&m.brdf, &light.earthshine, v),
        })
        .collect()
}

/// Pass 1: which faces send light to the observer, and how much each would if wholly lit
/// and seen. Faces whose visible areas need no search are summed here, where their terms
/// are at hand: every face when nothing can shadow or hide another, and a dish's inner
/// faces that their own lid decides along every direction; the rest are listed in
/// `scratch.lit` for pass 2. Returns those sums and the whole unshadowed signal (W/sr).
fn lit_faces(
    p: &Prepared,
    lights: &[MaterialLight],
    dirs: &Directions,
    scratch: &mut Scratch,
) -> (Sums, f64) {
    let (v, es) = (dirs.view, dirs.sun_w_m2);
    scratch.lit.clear();
    scratch.visibility.reset();
    if let Occlusion::Silhouettes(sil) = &p.occlusion {
        return (Sums::default(), lit_patches(p, sil, lights, dirs, scratch));
    }
    let mut unshadowed = 0.0;
    let lids = match &p.occlusion {
        Occlusion::PerFace(vis) => {
            vis.lid_table(&mut scratch.visibility, v, dirs.sunlit(), dirs.earth)
        }
        _ => None,
    };
    // Without rays or pixels every face is seen and lit whole: summed here too, in the
    // order pass 2 would, with no list between the passes.
    let whole = matches!(p.occlusion, Occlusion::None);
    let mut decided = Sums::default();
    for (i, face) in p.faces.faces.iter().enumerate() {
        let Some((side, sun_term, earth_term)) = face_terms(face, lights, v, es) else {
            continue;
        };
        unshadowed += (sun_term + earth_term) * face.area;
        if whole {
            decided.add(sun_term, earth_term, (face.area, face.area));
            continue;
        }
        if let Some(lids) = &lids {
            if let Some(areas) = lids.decided(i, side, sun_term > 0.0, earth_term > 0.0) {
                decided.add(sun_term, earth_term, areas);
                continue;
            }
        }
        scratch.lit.push(LitFace {
            face: i as u32,
            side,
            sun: sun_term,
            earth: earth_term,
            area: face.area,
        });
    }
    (decided, unshadowed)
}

/// A face's side seen from unit `v` and its Sun and earthshine terms, W/(m²·sr) per m²
/// (the Sun's band irradiance `es` included); `None` when it sends no light to the
/// observer (not seen, or neither light reaches the side seen).
#[inline]
fn face_terms(
    face: &crate::geometry::Face,
    lights: &[MaterialLight],
    v: DVec3,
    es: f64,
) -> Option<(FaceSide, f64, f64)> {
    let light = &lights[face.material as usize];
    let cr = face.normal.dot(v);
    let side = if cr > 0.0 {
        FaceSide::Front
    } else if light.two_sided && cr < 0.0 {
        FaceSide::Back
    } else {
        return None;
    };
    let frame = Frame {
        n: face.normal * side.sign(),
        t: face.tangent,
    };
    // n·v on the side seen, for every light: (side·n)·v is side·(n·v) exactly
    let cr = cr.abs();
    let sun_term = if es > 0.0 {
        // the Sun as a disk: a narrow lobe's glint is the disk's reflection, not a spike
        es * light.sun.projected_given(&frame, cr)
    } else {
        0.0
    };
    let earth_term = light.earth.projected_given(&frame, cr);
    (sun_term > 0.0 || earth_term > 0.0).then_some((side, sun_term, earth_term))
}

/// Pass 1 for the silhouette method, a patch at a time: a patch of one material seen
/// from one side, whose lights are linear over its normals, is listed whole in
/// `scratch.lit_patches`; the faces of any other are listed one by one in `scratch.lit`.
/// Returns the unshadowed signal (W/sr).
fn lit_patches(
    p: &Prepared,
    sil: &Silhouettes,
    lights: &[MaterialLight],
    dirs: &Directions,
    scratch: &mut Scratch,
) -> f64 {
    let (v, es) = (dirs.view, dirs.sun_w_m2);
    tally::add(Tally::Epochs, 1);
    scratch.lit_patches.clear();
    let mut unshadowed = 0.0;
    for k in 0..sil.patches() {
        // about half the patches face away from the observer: skipped without reading
        // their faces
        if sil.unseen(k, v) {
            continue;
        }
        let faces = sil.patch_faces(k);
        // the patch's one material, from the patch's table: reading it off a face is a
        // cache miss per patch, the largest cost of this pass at ~200k triangles
        let linear = sil
            .material(k)
            .map(|m| &lights[m as usize])
            .filter(|m| m.linear);
        if let Some((first, (cone, area, light))) =
            linear.and_then(|m| Some((m, sil.summable(k, v, m.two_sided)?)))
        {
            let sun = if es > 0.0 {
                first.sun.linear_over(&cone).map(|l| es * l)
            } else {
                Some(DVec3::ZERO)
            };
            if let (Some(sun), Some(earth)) = (sun, first.earth.linear_over(&cone)) {
                let lp = LitPatch {
                    patch: k as u32,
                    sun,
                    earth,
                    area,
                    light,
                };
                tally::add(Tally::FacesInSums, faces.len() as u64);
                if lp.lit_by() != (false, false) {
                    unshadowed += lp.light.of(sun) + lp.light.of(earth);
                    scratch.lit_patches.push(lp);
                }
                continue;
            }
        }
        tally::add(Tally::FacesOneByOne, faces.len() as u64);
        for &f in faces {
            let face = &p.faces.faces[f as usize];
            if let Some((side, sun, earth)) = face_terms(face, lights, v, es) {
                unshadowed += (sun + earth) * face.area;
                scratch.lit.push(LitFace {
                    face: f,
                    side,
                    sun,
                    earth,
                    area: face.area,
                });
            }
        }
    }
    unshadowed
}

/// Pass 2: the lit-and-seen areas of the faces pass 1 listed, by the prepared method,
/// added to pass 1's sums. Returns the epoch's sums and the rays cast.
fn visible_sums(
    p: &Prepared,
    dirs: &Directions,
    decided: Sums,
    unshadowed: f64,
    scratch: &mut Scratch,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> (Sums, u64) {
    let Scratch {
        lit,
        lit_patches,
        visibility,
        image,
        silhouettes,
    } = scratch;
    let mut sums = decided;
    match &p.occlusion {
        // pass 1 summed every face
        Occlusion::None => (sums, 0),
        Occlusion::Image(img) => {
            let faces = lit
                .iter()
                .map(|lf| (lf.face, lf.side.sign(), lf.sun > 0.0, lf.earth > 0.0));
            let rays = img.sample(
                image, &p.faces, faces, dirs.view, dirs.sun, dirs.earth, cancelled,
            );
            for lf in lit.iter() {
                let (f_sun, f_earth) = image.fractions(lf.face as usize, lf.area);
                sums.add(lf.sun, lf.earth, (f_sun * lf.area, f_earth * lf.area));
            }
            (sums, rays)
        }
        Occlusion::Silhouettes(sil) => {
            let whole = lit_patches.iter().map(|lp| {
                let (sun, earth) = lp.lit_by();
                (lp.patch, sun, earth)
            });
            let wanted = lit.iter().map(|lf| (lf.face, lf.sun > 0.0, lf.earth > 0.0));
            sil.want(silhouettes, wanted, whole);
            sil.prepare(silhouettes, Toward::View, Some(dirs.view));
            sil.drop_hidden(silhouettes);
            sil.prepare(silhouettes, Toward::Sun, dirs.sunlit());
            sil.prepare(silhouettes, Toward::Earth, dirs.earth);
            let mut rays = sil.group_rays(silhouettes);
            let since = tally::now();
            let face_areas = |scratch: &mut _, sums: &mut Sums, face: u32, sun, earth, area| {
                let (a_sun, a_earth, n) =
                    sil.areas(scratch, face as usize, area, sun > 0.0, earth > 0.0);
                sums.add(sun, earth, (a_sun, a_earth));
                n
            };
            for lf in lit.iter() {
                rays += face_areas(silhouettes, &mut sums, lf.face, lf.sun, lf.earth, lf.area);
            }
            for lp in lit_patches.iter() {
                let (sun, earth) = lp.lit_by();
                match sil.patch_visible(silhouettes, lp.patch as usize, sun, earth) {
                    Some((sun_clear, earth_clear)) => {
                        if sun_clear {
                            sums.sun += lp.light.of(lp.sun);
                            sums.lit_visible_area += lp.area;
                        }
                        if earth_clear {
                            sums.earth += lp.light.of(lp.earth);
                        }
                    }
                    // a line crosses it along some direction: face by face, each face's
                    // terms (n·L)(n·v) as the patch's sum takes them (its lights are
                    // linear over its normals), not a BRDF a face
                    None => {
                        let faces = sil.patch_faces(lp.patch as usize);
                        tally::add(Tally::FacesInCrossedSums, faces.len() as u64);
                        for &f in faces {
                            let face = &p.faces.faces[f as usize];
                            let (sun, earth) = lp.face_terms(face.normal, dirs.view);
                            if sun > 0.0 || earth > 0.0 {
                                rays +=
                                    face_areas(silhouettes, &mut sums, f, sun, earth, face.area);
                            }
                        }
                    }
                }
            }
            tally::took(Tally::AreasNs, since);
            (sums, rays)
        }
        Occlusion::PerFace(vis) => {
            // Faces whose shadows are clipped exactly need no budget. For sampled ones
            // the tolerance is a share of the epoch's signal. The first sweep budgets
            // against the unshadowed signal; where shadows leave much less than that (a
            // glint's tail on a mostly shadowed face), the sweep is repeated against the
            // signal it found, so the tolerance stays relative to what the observer
            // actually receives.
            let mut rays = 0u64;
            let mut reference = unshadowed;
            for sweep in 0..2 {
                let rays_before = rays;
                sums = decided;
                for lf in lit.iter() {
                    let uncertain = Uncertain {
                        view: dirs.view,
                        sun: (lf.sun > 0.0).then_some(dirs.sun),
                        earth: if lf.earth > 0.0 { dirs.earth } else { None },
                    };
                    // Area of this face whose misclassification costs the tolerance's
                    // share of the signal.
                    let weight = lf.sun + lf.earth;
                    let budget = p.scene.tolerance * reference / weight;
                    let (a_sun, a_earth, n) =
                        vis.visible_area(visibility, lf.face as usize, lf.side, &uncertain, budget);
                    rays += n;
                    sums.add(lf.sun, lf.earth, (a_sun, a_earth));
                }
                let found = sums.sun + sums.earth;
                // exact (clipped) areas do not depend on the budget: only sampled faces
                // re-run
                let rays_used = rays > rays_before;
                if sweep > 0 || !rays_used || found >= 0.5 * reference || found <= 0.0 {
                    break;
                }
                reference = found;
            }
            (sums, rays)
        }
    }
}

/// The epoch's result from its sums: irradiance at the observer (zero where the Earth
/// is across the line of sight), magnitudes, geometry.
fn epoch_result(
    p: &Prepared,
    epoch: &Epoch,
    range: f64,
    v: DVec3,
    light: &EpochLight,
    sums: Sums,
) -> EpochResult {
    let r2 = range * range;
    let Sums {
        sun: sun_sum,
        earth: earth_sum,
        lit_visible_area,
    } = sums;
    let intensity = sun_sum + earth_sum;
    // the Earth across the line of sight: the object shines, but not on this observer
    let blocked = epoch
        .earth
        .is_some_and(|e| crate::radiometry::earth::hides_observer(e, epoch.observer));
    let seen = if blocked { 0.0 } else { 1.0 };
    let irradiance = seen * intensity / r2;
    let phase = angle_between(epoch.sun, v);
    let mut e = EpochResult {
        t: epoch.t,
        irradiance_w_m2: irradiance,
        sun_w_m2: seen * sun_sum / r2,
        earthshine_w_m2: seen * earth_sum / r2,
        intensity_w_sr: intensity,
        magnitude: None,
        magnitude_1000km: None,
        magnitude_standard: None,
        magnitude_intrinsic: None,
        phase_angle_deg: phase.to_degrees(),
        range_m: range,
        lit_visible_area_m2: lit_visible_area,
        eclipse: light.eclipse,
        earth_blocks_view: blocked,
        azimuth_deg: None,
        elevation_deg: None,
        sun_elevation_deg: None,
        in_earth_shadow: None,
        observation: None,
    };
    set_magnitudes(
        &mut e,
        phase,
        p.sun_band_1au,
        p.scene.illumination.sun_magnitude,
    );
    e
}

/// An epoch's magnitudes from its irradiance, range and phase (rad) (docs/physics.md §10).
pub fn set_magnitudes(e: &mut EpochResult, phase: f64, sun_band_1au: f64, sun_magnitude: f64) {
    e.magnitude = magnitude::apparent(e.irradiance_w_m2, sun_band_1au, sun_magnitude);
    e.magnitude_1000km = magnitude::at_1000km(e.magnitude, e.range_m);
    e.magnitude_standard = magnitude::standard(e.magnitude_1000km, phase);
    e.magnitude_intrinsic = magnitude::intrinsic(e.magnitude_1000km, phase);
}

/// Running sums of one epoch: W/sr from the Sun and from earthshine, and the seen and
/// sunlit area, m².
#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    sun: f64,
    earth: f64,
    lit_visible_area: f64,
}

impl Sums {
    /// Adds a face's terms (W/(m²·sr)) times its seen-and-sunlit and seen-and-earthlit
    /// areas (m²).
    #[inline]
    fn add(&mut self, sun: f64, earth: f64, (a_sun, a_earth): (f64, f64)) {
        self.sun += sun * a_sun;
        self.earth += earth * a_earth;
        if sun > 0.0 {
            self.lit_visible_area += a_sun;
        }
    }
}
