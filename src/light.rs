//! The light that reaches the object at one epoch ([`EpochLight`]): the Sun's band
//! irradiance after any eclipse by the Earth, the Earth's disk while it hides part of the
//! Sun's, and the earthshine beams. The light curve (`integrate::eq12`) and the thumbnails
//! (`render`) both shade with it, so both see one Sun.

use crate::brdf::sun_disk::EarthDisk;
use crate::geometry::angle_between;
use crate::radiometry::{earth, eclipse, sun, EARTH_RADIUS_M};
use crate::scene::{EarthshineModel, Epoch, Illumination};

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
    /// The light at `epoch` under the request's illumination `ill` (the Sun's band
    /// irradiance at the epoch's Sun distance, its eclipse by the Earth, and the
    /// earthshine model asked for).
    pub fn at(ill: &Illumination, epoch: &Epoch) -> EpochLight {
        let l = epoch.sun;
        let es_full = ill.sun_irradiance(epoch.sun_distance_m);
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
