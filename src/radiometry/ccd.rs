//! A telescope's counts and noise (docs/physics.md §10a): the CCD equation for the
//! object's light in a circular photometric aperture, and a noisy sample drawn with a
//! seeded generator.
//!
//! With Φ the object's photon rate per m² in the band above the atmosphere (from its
//! irradiance: `photon_rate`), A = π/4 D² (1 − ε²) the collecting area, t the exposure,
//! q the quantum efficiency, τ the throughput, X the airmass and k the extinction
//! (mag per airmass), f_ap the share of a Gaussian image of FWHM θ inside a radius r,
//! 1 − 2^(−4 r²/θ²), and n_pix = π r² / s² pixels of scale s:
//!
//!   S      = Φ · 10^(−0.4 k X) · A · t · q · τ · f_ap                 signal, e⁻
//!   B_sky  = Φ₀ · 10^(−0.4 μ) · A · t · q · τ · π r²                  sky, e⁻ (μ mag/arcsec²)
//!   B_dark = d · t · n_pix                                           dark, e⁻
//!   N      = √(S + B_sky + B_dark + n_pix σ_R²)                      noise, e⁻
//!   SNR    = S / N
//!
//! (the CCD equation of Howell, *Handbook of CCD Astronomy*, §4.4, without the term for
//! the uncertainty of the background estimate). Φ₀ is the photon rate of a 0 mag source in
//! the band, the Sun's at 1 AU times 10^(0.4 m_sun). The sky is as measured at the site
//! (no extinction applied to it). The noisy sample is Poisson(S + B_sky + B_dark) plus a
//! normal read noise of variance n_pix σ_R², less the expected background B_sky + B_dark.

/// Planck's constant times the speed of light, J·m.
pub const HC_J_M: f64 = 6.626_070_15e-34 * 299_792_458.0;

/// A telescope, its detector and the sky, validated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    pub aperture_m: f64,
    /// Central obstruction, as a fraction of the aperture's diameter.
    pub obstruction: f64,
    pub exposure_s: f64,
    pub quantum_efficiency: f64,
    pub throughput: f64,
    pub pixel_scale_arcsec: f64,
    pub seeing_fwhm_arcsec: f64,
    /// Radius of the photometric aperture.
    pub aperture_radius_arcsec: f64,
    pub read_noise_e: f64,
    pub dark_e_per_s: f64,
    pub gain_e_per_adu: f64,
    /// The brightest pixel's electrons at which it saturates; `None`: never.
    pub full_well_e: Option<f64>,
    /// `None`: no sky.
    pub sky_mag_per_arcsec2: Option<f64>,
    pub airmass: f64,
    pub extinction_mag_per_airmass: f64,
    pub seed: u64,
}

/// One epoch's counts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Counts {
    pub signal_e: f64,
    pub sky_e: f64,
    pub dark_e: f64,
    pub pixels: f64,
    pub noise_e: f64,
    pub snr: f64,
    pub signal_adu: f64,
    /// Signal, sky and dark on the brightest pixel (the star's image centred on it).
    pub peak_pixel_e: f64,
    pub saturated: bool,
    /// A noisy measurement of `signal_e`: the drawn counts less the expected background.
    pub sample_e: f64,
}

/// Photon rate per m² of an irradiance in a named band, photons/(s·m²): E·λ̄/(hc), λ̄ the
/// band's photon-weighted mean wavelength (µm), E photon-weighted (`radiometry::bands`).
pub fn photon_rate(irradiance_w_m2: f64, mean_wavelength_um: f64) -> f64 {
    irradiance_w_m2 * mean_wavelength_um * 1e-6 / HC_J_M
}

impl Observation {
    /// Collecting area, m².
    pub fn area_m2(&self) -> f64 {
        std::f64::consts::FRAC_PI_4
            * self.aperture_m
            * self.aperture_m
            * (1.0 - self.obstruction * self.obstruction)
    }

    /// Share of a Gaussian image of FWHM θ inside the aperture radius r: 1 − 2^(−4r²/θ²).
    pub fn aperture_fraction(&self) -> f64 {
        let q = self.aperture_radius_arcsec / self.seeing_fwhm_arcsec;
        -(-4.0 * q * q * std::f64::consts::LN_2).exp_m1()
    }

    /// Share of a Gaussian image on the pixel it is centred on: erf(s / (2√2 σ))²,
    /// σ = θ / (2√(2 ln 2)).
    pub fn peak_pixel_fraction(&self) -> f64 {
        let sigma = self.seeing_fwhm_arcsec / (2.0 * (2.0 * std::f64::consts::LN_2).sqrt());
        let e = libm::erf(self.pixel_scale_arcsec / (2.0 * std::f64::consts::SQRT_2 * sigma));
        e * e
    }

    /// The counts of an object whose photon rate above the atmosphere is `rate`
    /// (photons/(s·m²)), with `zero_rate` that of a 0 mag source, for epoch `index` (which
    /// picks its own stream of the seeded generator).
    pub fn counts(&self, rate: f64, zero_rate: f64, index: u64) -> Counts {
        let collect = self.area_m2() * self.exposure_s * self.quantum_efficiency * self.throughput;
        let extinction = 10f64.powf(-0.4 * self.extinction_mag_per_airmass * self.airmass);
        let signal_e = rate * extinction * collect * self.aperture_fraction();
        let area_arcsec2 = std::f64::consts::PI * self.aperture_radius_arcsec.powi(2);
        let pixels = area_arcsec2 / (self.pixel_scale_arcsec * self.pixel_scale_arcsec);
        let sky_rate_arcsec2 = self
            .sky_mag_per_arcsec2
            .map_or(0.0, |mu| zero_rate * 10f64.powf(-0.4 * mu));
        let sky_e = sky_rate_arcsec2 * collect * area_arcsec2;
        let dark_e = self.dark_e_per_s * self.exposure_s * pixels;
        let read_var = pixels * self.read_noise_e * self.read_noise_e;
        let noise_e = (signal_e + sky_e + dark_e + read_var).sqrt();
        let snr = if noise_e > 0.0 {
            signal_e / noise_e
        } else {
            0.0
        };
        let pixel_arcsec2 = self.pixel_scale_arcsec * self.pixel_scale_arcsec;
        let peak_pixel_e = rate * extinction * collect * self.peak_pixel_fraction()
            + sky_rate_arcsec2 * collect * pixel_arcsec2
            + self.dark_e_per_s * self.exposure_s;
        let mut rng = SplitMix::new(self.seed, index);
        let drawn = rng.poisson(signal_e + sky_e + dark_e) + read_var.sqrt() * rng.normal();
        Counts {
            signal_e,
            sky_e,
            dark_e,
            pixels,
            noise_e,
            snr,
            signal_adu: signal_e / self.gain_e_per_adu,
            peak_pixel_e,
            saturated: self.full_well_e.is_some_and(|w| peak_pixel_e >= w),
            sample_e: drawn - sky_e - dark_e,
        }
    }
}

/// splitmix64 (Steele, Lea & Flood 2014): a generator whose stream for (seed, index) is
/// the same on every machine and in any thread order.
pub struct SplitMix(u64);

impl SplitMix {
    pub fn new(seed: u64, index: u64) -> SplitMix {
        let mut s = SplitMix(seed ^ index.wrapping_mul(0xD1B5_4A32_D192_ED03));
        s.next_u64();
        s
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let u1 = (1.0 - self.uniform()).max(f64::MIN_POSITIVE);
        let u2 = self.uniform();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }

    /// Poisson with mean `mean` ≥ 0: by multiplying uniforms below 30, by Hörmann's
    /// transformed rejection (PTRS, Insurance: Mathematics and Economics 12, 39, 1993)
    /// above. Exact in distribution, as a float.
    pub fn poisson(&mut self, mean: f64) -> f64 {
        if mean.is_nan() || mean <= 0.0 || mean.is_infinite() {
            return 0.0;
        }
        if mean < 30.0 {
            let limit = (-mean).exp();
            let mut k = 0.0;
            let mut p = self.uniform();
            while p > limit {
                k += 1.0;
                p *= self.uniform();
            }
            return k;
        }
        let slam = mean.sqrt();
        let loglam = mean.ln();
        let b = 0.931 + 2.53 * slam;
        let a = -0.059 + 0.02483 * b;
        let inv_alpha = 1.1239 + 1.1328 / (b - 3.4);
        let vr = 0.9277 - 3.6224 / (b - 2.0);
        loop {
            let u = self.uniform() - 0.5;
            let v = self.uniform();
            let us = 0.5 - u.abs();
            let k = ((2.0 * a / us + b) * u + mean + 0.43).floor();
            if us >= 0.07 && v <= vr {
                return k;
            }
            if k < 0.0 || (us < 0.013 && v > us) {
                continue;
            }
            if v.ln() + inv_alpha.ln() - (a / (us * us) + b).ln()
                <= -mean + k * loglam - ln_factorial(k)
            {
                return k;
            }
        }
    }
}

/// ln k! for a whole k ≥ 0: summed below 20, by Stirling's series for ln Γ(k + 1) above
/// (five terms: error below 1e-13 there).
fn ln_factorial(k: f64) -> f64 {
    if k < 20.0 {
        (2..=k as u64).map(|i| (i as f64).ln()).sum()
    } else {
        let x = k + 1.0;
        let x2 = x * x;
        (x - 0.5) * x.ln() - x
            + 0.5 * std::f64::consts::TAU.ln()
            + (1.0 / 12.0 - (1.0 / 360.0 - 1.0 / (1260.0 * x2)) / x2) / x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Stirling against the sum at the switch and beyond (1e-12 relative: rounding of
    /// the sum of logs).
    #[test]
    fn ln_factorial_is_continuous_at_its_switch() {
        for k in [20u64, 21, 50, 170] {
            let sum: f64 = (2..=k).map(|i| (i as f64).ln()).sum();
            assert!((ln_factorial(k as f64) / sum - 1.0).abs() < 1e-12, "{k}");
        }
    }
}
