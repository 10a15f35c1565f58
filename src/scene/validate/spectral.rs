//! Materials' `spectral` tables (n, k or albedo against wavelength) and the band's
//! wavelength bins they are evaluated in (docs/physics.md §8).

use super::materials::material;
use super::table::at;
use super::values::err;
use super::ValidationError;
use crate::radiometry::bands::SolarSpectrum;
use crate::radiometry::earth::gauss_legendre;
use crate::scene::request::{MaterialObject, MaterialSpec, Request};
use crate::scene::{Illumination, Material, SolarSpectrumChoice, SpectralBin};

/// Wavelength bins the band is cut into when a material depends on wavelength.
pub const BINS: usize = 16;
/// The longest interval band a spectral material may be integrated over, µm.
pub const MAX_BAND_UM: f64 = 30.0;

/// The band's wavelength bins with every material in each, and the materials to report
/// (a spectral material at the bins' mean wavelength); no bins when no material has a
/// table.
pub(super) fn bins(
    req: &Request,
    materials: Vec<Material>,
    ill: &Illumination,
) -> Result<(Vec<Material>, Vec<SpectralBin>), ValidationError> {
    let spectral: Vec<(usize, &MaterialObject)> = req
        .object
        .materials
        .iter()
        .enumerate()
        .filter_map(|(i, m)| match m {
            MaterialSpec::Full(o) if o.spectral.is_some() => Some((i, o)),
            _ => None,
        })
        .collect();
    if spectral.is_empty() {
        return Ok((materials, Vec::new()));
    }
    // the band's quadrature nodes, weighted by the Sun's spectrum: g_i = w_i E_λ(λ_i)
    let sun = match ill.solar_spectrum {
        SolarSpectrumChoice::Planck => SolarSpectrum::Planck(ill.sun_temperature_k),
        SolarSpectrumChoice::Calspec => SolarSpectrum::Calspec,
    };
    let nodes: Vec<(f64, f64)> = match ill.passband {
        Some(p) => p.weights(),
        None => {
            let [a, b] = ill.band_um;
            if b - a > MAX_BAND_UM {
                return err(
                    "illumination.band_um",
                    format!(
                        "a material with a `spectral` table needs a band at most \
                         {MAX_BAND_UM} µm wide, got [{a}, {b}]"
                    ),
                );
            }
            // 8-point Gauss–Legendre on 64 equal pieces: energy-weighted, as the
            // interval band is
            let gl = gauss_legendre(8);
            let h = (b - a) / 64.0;
            (0..64)
                .flat_map(|k| {
                    gl.iter()
                        .map(move |&(x, w)| (a + h * (k as f64 + x), h * w))
                })
                .collect()
        }
    };
    let g: Vec<(f64, f64)> = nodes
        .iter()
        .map(|&(l, w)| (l, w * sun.irradiance_1au(l)))
        .filter(|&(_, x)| x > 0.0 && x.is_finite())
        .collect();
    let total: f64 = g.iter().map(|&(_, x)| x).sum();
    if g.is_empty() || total.is_nan() || total <= 0.0 {
        return err(
            "illumination",
            "the band holds no sunlight to integrate the spectral materials over",
        );
    }
    let (lo, hi) = (g[0].0, g[g.len() - 1].0);
    let width = (hi - lo) / BINS as f64;
    let mut sums = [(0.0f64, 0.0f64); BINS];
    for &(l, x) in &g {
        let k = if width > 0.0 {
            (((l - lo) / width) as usize).min(BINS - 1)
        } else {
            0
        };
        sums[k].0 += x;
        sums[k].1 += x * l;
    }
    let with_materials = |lambda: f64| -> Result<Vec<Material>, ValidationError> {
        let mut out = materials.clone();
        for &(i, m) in &spectral {
            let field = format!("object.materials[{i}]");
            let at = at(&field, m, lambda)?;
            out[i] = material(&field, &MaterialSpec::Full(at))?;
        }
        Ok(out)
    };
    let mut bins = Vec::new();
    let mut mean = 0.0;
    for &(x, xl) in sums.iter().filter(|s| s.0 > 0.0) {
        let lambda = xl / x;
        mean += xl / total;
        bins.push(SpectralBin {
            wavelength_um: lambda,
            share: x / total,
            materials: with_materials(lambda)?,
        });
    }
    Ok((with_materials(mean)?, bins))
}
