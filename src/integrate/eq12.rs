//! One epoch of Eq. 12: E = Σ_faces (dI_sun + dI_earth)/R², with
//! dI = f·E·cosθi·cosθr·A_visible (Eq. 10), A_visible the part of the face both lit and seen.
//!
//! With constant material parameters the band integral factors out of the sum: the Sun's
//! band irradiance multiplies a purely geometric sum. A wavelength-dependent n(λ), k(λ)
//! would evaluate the face sum per spectral bin and weight by the bin's irradiance.

use super::visibility::Uncertain;
use super::Prepared;
use crate::brdf::earth_light::EarthLight;
use crate::brdf::sun_disk::{EarthDisk, SunLight};
use crate::brdf::Frame;
use crate::radiometry::{earth, eclipse, magnitude, sun, EARTH_RADIUS_M};
use crate::scene::{EarthshineModel, Epoch, EpochResult, Illumination};
use glam::DVec3;

/// Per-thread buffers reused across epochs.
#[derive(Default)]
pub struct Scratch {
    lit: Vec<LitFace>,
    visibility: super::visibility::Cache,
    image: super::image::ImageScratch,
    silhouettes: super::silhouettes::Scratch,
}

/// What lights faces of one material at this epoch: the Sun and the earthshine, each
/// with the BRDF's per-epoch part.
struct MaterialLight<'a> {
    two_sided: bool,
    sun: SunLight<'a>,
    earth: EarthLight<'a>,
}

/// A face that reflects light towards the observer at this epoch.
struct LitFace {
    face: u32,
    /// +1 front side seen, −1 back side (two-sided materials).
    side: f64,
    /// Sun term f·cosθi·cosθr·E_s, W/(m²·sr) per m² of face.
    sun: f64,
    /// Earthshine term Σ f·cosθi·cosθr·E_beam, W/(m²·sr) per m² of face.
    earth: f64,
    /// The face's area, m² (kept here: pass 2 then reads this list alone).
    area: f64,
}

/// The light arriving at the object at one epoch: the Sun (after any eclipse) and the
/// earthshine beams. Shared by the light curve and the renderer, so both see one Sun.
#[derive(Debug, Clone, Default)]
pub struct EpochLight {
    /// Direct solar band irradiance at the object after the eclipse, W/m².
    pub sun_w_m2: f64,
    /// Fraction of the solar disk hidden by the Earth (0..1).
    pub eclipse: f64,
    /// The Earth's disk while it hides part of the Sun's (penumbra, 0 < `eclipse` < 1):
    /// a glint then reflects only the visible part of the disk.
    pub penumbra: Option<EarthDisk>,
    pub earthshine: earth::Earthshine,
}

impl EpochLight {
    pub fn at(ill: &Illumination, epoch: &Epoch) -> EpochLight {
        let l = epoch.sun;
        let es_full =
            sun::band_irradiance(ill.band_um, ill.sun_temperature_k, epoch.sun_distance_m);
        let (hidden, penumbra, earthshine) = match epoch.earth {
            None => (0.0, None, earth::Earthshine::default()),
            Some(e) => {
                let d = e.length();
                let e_dir = e / d;
                let earth_radius = (EARTH_RADIUS_M / d).min(1.0).asin();
                let hidden = eclipse::hidden_fraction(
                    sun::angular_radius(epoch.sun_distance_m),
                    earth_radius,
                    angle_between(l, e_dir),
                );
                let penumbra = (hidden > 0.0 && hidden < 1.0).then_some(EarthDisk {
                    dir: e_dir,
                    radius: earth_radius,
                });
                // The Earth reflects the sunlight that reaches it, which no eclipse of the
                // object changes.
                let shine = match ill.earthshine {
                    EarthshineModel::Off => earth::Earthshine::default(),
                    EarthshineModel::Seed => earth::seed(e_dir, ill.earth_albedo, es_full),
                    EarthshineModel::Sphere => earth::sphere(e, l, ill.earth_albedo, es_full),
                };
                (hidden, penumbra, shine)
            }
        };
        EpochLight {
            sun_w_m2: es_full * (1.0 - hidden),
            eclipse: hidden,
            penumbra,
            earthshine,
        }
    }
}

/// Evaluates one epoch; returns the result and the number of rays cast.
///
/// `cancelled` is polled inside the epoch where one epoch can take long (the `image`
/// method's rows); once it returns true the result is meaningless and the caller drops it.
pub fn evaluate(
    p: &Prepared,
    epoch: &Epoch,
    scratch: &mut Scratch,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> (EpochResult, u64) {
    let scene = p.scene;
    let ill = &scene.illumination;
    let range = epoch.observer.length();
    let v = epoch.observer / range;
    let l = epoch.sun;

    let EpochLight {
        sun_w_m2: es,
        eclipse: hidden,
        penumbra,
        earthshine,
    } = EpochLight::at(ill, epoch);
    let sun_radius = sun::angular_radius(epoch.sun_distance_m);

    // Pass 1: which faces send light to the observer, and how much if fully visible.
    // Per material, what does not depend on the face is computed once: the Sun's and each
    // earthshine beam's half vector and Fresnel term.
    let lights: Vec<MaterialLight> = scene
        .materials
        .iter()
        .map(|m| MaterialLight {
            two_sided: m.two_sided,
            sun: SunLight::eclipsed(&m.brdf, l, v, sun_radius, penumbra),
            earth: EarthLight::new(&m.brdf, &earthshine, v),
        })
        .collect();
    scratch.lit.clear();
    scratch.visibility.reset();
    let mut unshadowed = 0.0;
    // faces whose visible areas need no search (a dish's inner faces that their own lid
    // decides along every direction): summed here, where their terms are at hand
    let lids = match &p.visibility {
        Some(vis) if p.image.is_none() => vis.lid_table(
            &mut scratch.visibility,
            v,
            (es > 0.0).then_some(l),
            earthshine.shadow_dir,
        ),
        _ => None,
    };
    // Without rays or pixels every face is seen and lit whole: summed here too, in the
    // order pass 2 would, with no list between the passes.
    let whole = p.visibility.is_none() && p.image.is_none() && p.silhouettes.is_none();
    let mut decided = Sums::default();
    for (i, face) in p.faces.faces.iter().enumerate() {
        let light = &lights[face.material as usize];
        let cr = face.normal.dot(v);
        let side = if cr > 0.0 {
            1.0
        } else if light.two_sided && cr < 0.0 {
            -1.0
        } else {
            continue;
        };
        let frame = Frame {
            n: face.normal * side,
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
        if sun_term > 0.0 || earth_term > 0.0 {
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
    }

    // Pass 2: visible fractions (all 1 without rays).
    let mut sums = decided;
    let mut rays = 0u64;
    if let Some(img) = &p.image {
        let lit = scratch
            .lit
            .iter()
            .map(|lf| (lf.face, lf.side, lf.sun > 0.0, lf.earth > 0.0));
        rays += img.sample(
            &mut scratch.image,
            &p.faces,
            lit,
            v,
            l,
            earthshine.shadow_dir,
            cancelled,
        );
    }
    // Faces whose shadows are clipped exactly need no budget. For sampled ones the
    // tolerance is a share of the epoch's signal. The first sweep budgets against the
    // unshadowed signal; where shadows leave much less than that (a glint's tail on a
    // mostly shadowed face), the sweep is repeated against the signal it found, so the
    // tolerance stays relative to what the observer actually receives.
    let mut exact_rays = 0u64;
    if let Some(sil) = &p.silhouettes {
        let s = &mut scratch.silhouettes;
        let wanted = scratch
            .lit
            .iter()
            .map(|lf| (lf.face, lf.sun > 0.0, lf.earth > 0.0));
        sil.want(s, wanted);
        sil.prepare(s, 0, Some(v));
        sil.prepare(s, 1, (es > 0.0).then_some(l));
        sil.prepare(s, 2, earthshine.shadow_dir);
        exact_rays += sil.group_rays(s);
    }
    let mut reference = unshadowed;
    for sweep in 0..2 {
        let rays_before = rays;
        sums = decided;
        for lf in &scratch.lit {
            // lit-and-seen areas, m²
            let (a_sun, a_earth) = match (&p.visibility, &p.silhouettes) {
                _ if p.image.is_some() => {
                    let (f_sun, f_earth) = scratch.image.fractions(lf.face as usize, lf.area);
                    (f_sun * lf.area, f_earth * lf.area)
                }
                (_, Some(sil)) => {
                    let (a_sun, a_earth, n) = sil.areas(
                        &mut scratch.silhouettes,
                        lf.face as usize,
                        lf.area,
                        &p.faces.faces[lf.face as usize].triangles,
                        lf.sun > 0.0,
                        lf.earth > 0.0,
                    );
                    exact_rays += n;
                    (a_sun, a_earth)
                }
                // without rays or pixels pass 1 summed every face (`whole`)
                (None, None) => unreachable!("no face is listed for pass 2 without visibility"),
                (Some(vis), None) => {
                    let dirs = Uncertain {
                        view: v,
                        sun: (lf.sun > 0.0).then_some(l),
                        earth: if lf.earth > 0.0 {
                            earthshine.shadow_dir
                        } else {
                            None
                        },
                    };
                    // Area of this face whose misclassification costs the tolerance's
                    // share of the signal.
                    let weight = lf.sun + lf.earth;
                    let budget = scene.tolerance * reference / weight;
                    let (a_sun, a_earth, n) = vis.visible_area(
                        &mut scratch.visibility,
                        lf.face as usize,
                        lf.side,
                        &dirs,
                        budget,
                    );
                    rays += n;
                    (a_sun, a_earth)
                }
            };
            sums.add(lf.sun, lf.earth, (a_sun, a_earth));
        }
        let found = sums.sun + sums.earth;
        // exact (clipped) areas do not depend on the budget: only sampled faces re-run
        let rays_used = p.image.is_none() && rays > rays_before;
        if sweep > 0 || !rays_used || found >= 0.5 * reference || found <= 0.0 {
            break;
        }
        reference = found;
    }

    rays += exact_rays;
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
    let mag = magnitude::apparent(irradiance, p.sun_band_1au);
    (
        EpochResult {
            t: epoch.t,
            irradiance_w_m2: irradiance,
            sun_w_m2: seen * sun_sum / r2,
            earthshine_w_m2: seen * earth_sum / r2,
            intensity_w_sr: intensity,
            magnitude: mag,
            magnitude_std: magnitude::standardised(mag, range),
            phase_angle_deg: angle_between(l, v).to_degrees(),
            range_m: range,
            lit_visible_area_m2: lit_visible_area,
            eclipse: hidden,
            earth_blocks_view: blocked,
            azimuth_deg: None,
            elevation_deg: None,
            sun_elevation_deg: None,
            in_earth_shadow: None,
        },
        rays,
    )
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

/// Angle between unit vectors, rad; atan2 keeps it accurate near 0 and π.
pub fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}
