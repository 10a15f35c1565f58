//! A telescope's counts and noise (issue 21, item 3): the CCD equation evaluated by hand
//! here against `radiometry::ccd` and the light curve's `observation`, and the noisy
//! samples' mean and variance over 10⁴ draws.

mod common;

use common::*;
use glint::radiometry::ccd::{photon_rate, Observation, SplitMix};
use std::f64::consts::PI;

/// h·c, J·m (CODATA 2018, exact).
const HC: f64 = 6.626_070_15e-34 * 299_792_458.0;

fn telescope() -> Observation {
    Observation {
        aperture_m: 0.5,
        obstruction: 0.3,
        exposure_s: 2.0,
        quantum_efficiency: 0.8,
        throughput: 0.6,
        pixel_scale_arcsec: 1.5,
        seeing_fwhm_arcsec: 2.5,
        aperture_radius_arcsec: 3.0,
        read_noise_e: 10.0,
        dark_e_per_s: 0.5,
        gain_e_per_adu: 2.0,
        full_well_e: Some(1e5),
        sky_mag_per_arcsec2: Some(20.0),
        airmass: 1.5,
        extinction_mag_per_airmass: 0.2,
        seed: 7,
    }
}

/// The photon-weighted mean wavelength of V from its table, by Simpson on each interval
/// (written here; the code integrates the linear pieces in closed form).
fn v_mean_wavelength() -> f64 {
    let r = glint::radiometry::bands::find("V").unwrap().response();
    let (mut a, mut b) = (0.0, 0.0);
    for p in r.windows(2) {
        let ((l0, r0), (l1, r1)) = (p[0], p[1]);
        let m = 0.5 * (l0 + l1);
        let rm = 0.5 * (r0 + r1);
        let h = (l1 - l0) / 6.0;
        a += h * (r0 * l0 + 4.0 * rm * m + r1 * l1);
        b += h * (r0 + 4.0 * rm + r1);
    }
    a / b
}

/// The CCD equation by hand for three cases: the default telescope, a bright object with
/// no sky, dark or read noise (SNR = √S), and a faint one under a bright sky
/// (background-limited, SNR ≈ S/√sky). Tolerance 1e-12 relative: the same closed forms in
/// another order, rounding only.
#[test]
fn the_ccd_equation_by_hand() {
    let mean = v_mean_wavelength();
    let band = glint::radiometry::bands::find("V").unwrap();
    assert!(rel(band.mean_wavelength_um(), mean) < 1e-13, "λ̄ {mean}");
    // a 0 mag source in V: the Sun at 1 AU (CALSPEC, photon-weighted) scaled by its −26.76
    let sun = glint::radiometry::bands::SolarSpectrum::Calspec.band_1au(band);
    let zero_e = sun * 10f64.powf(0.4 * -26.76);
    let zero_rate = zero_e * mean * 1e-6 / HC;
    assert!(rel(photon_rate(zero_e, mean), zero_rate) < 1e-14);
    for (case, (e_obj, edit)) in [
        (
            1e-14,
            Box::new(|_: &mut Observation| {}) as Box<dyn Fn(&mut Observation)>,
        ),
        (
            1e-12,
            Box::new(|o: &mut Observation| {
                o.sky_mag_per_arcsec2 = None;
                o.read_noise_e = 0.0;
                o.dark_e_per_s = 0.0;
            }),
        ),
        (
            1e-17,
            Box::new(|o: &mut Observation| {
                o.sky_mag_per_arcsec2 = Some(17.0);
                o.read_noise_e = 0.0;
                o.dark_e_per_s = 0.0;
            }),
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let mut o = telescope();
        edit(&mut o);
        let c = o.counts(photon_rate(e_obj, mean), zero_rate, 0);
        // by hand
        let area = PI / 4.0 * o.aperture_m.powi(2) * (1.0 - o.obstruction.powi(2));
        let collect = area * o.exposure_s * o.quantum_efficiency * o.throughput;
        let sigma = o.seeing_fwhm_arcsec / 2.354_820_045_030_949;
        let f_ap = 1.0 - (-(o.aperture_radius_arcsec.powi(2)) / (2.0 * sigma * sigma)).exp();
        let ext = 10f64.powf(-0.4 * o.extinction_mag_per_airmass * o.airmass);
        let s = e_obj * mean * 1e-6 / HC * ext * collect * f_ap;
        let omega = PI * o.aperture_radius_arcsec.powi(2);
        let npix = omega / o.pixel_scale_arcsec.powi(2);
        let sky = o.sky_mag_per_arcsec2.map_or(0.0, |mu| {
            zero_rate * 10f64.powf(-0.4 * mu) * collect * omega
        });
        let dark = o.dark_e_per_s * o.exposure_s * npix;
        let noise = (s + sky + dark + npix * o.read_noise_e.powi(2)).sqrt();
        for (what, got, want) in [
            ("signal", c.signal_e, s),
            ("sky", c.sky_e, sky),
            ("dark", c.dark_e, dark),
            ("pixels", c.pixels, npix),
            ("noise", c.noise_e, noise),
            ("snr", c.snr, s / noise),
            ("adu", c.signal_adu, s / o.gain_e_per_adu),
        ] {
            assert!(
                got == want || rel(got, want) < 1e-12,
                "case {case} {what}: {got} vs {want}"
            );
        }
        match case {
            1 => assert!(rel(c.snr, s.sqrt()) < 1e-12),
            2 => assert!(c.sky_e > 100.0 * c.signal_e && rel(c.snr, s / sky.sqrt()) < 0.01),
            _ => {}
        }
    }
}

/// The brightest pixel against the full well: a star image centred on a pixel puts
/// erf(s/(2√2σ))² of its light there; here checked against a 2-D midpoint sum over the
/// pixel written here (1e-6: 400² points).
#[test]
fn saturation_at_the_full_well() {
    let o = telescope();
    let sigma = o.seeing_fwhm_arcsec / 2.354_820_045_030_949;
    let n = 400;
    let h = o.pixel_scale_arcsec / n as f64;
    let mut frac = 0.0;
    for i in 0..n {
        for j in 0..n {
            let x = -0.5 * o.pixel_scale_arcsec + (i as f64 + 0.5) * h;
            let y = -0.5 * o.pixel_scale_arcsec + (j as f64 + 0.5) * h;
            frac += (-(x * x + y * y) / (2.0 * sigma * sigma)).exp() * h * h;
        }
    }
    frac /= 2.0 * PI * sigma * sigma;
    assert!(
        rel(o.peak_pixel_fraction(), frac) < 1e-6,
        "{} vs {frac}",
        o.peak_pixel_fraction()
    );
    let zero_rate = 1e10;
    let faint = o.counts(1.0, zero_rate, 0);
    assert!(!faint.saturated && faint.peak_pixel_e < 1e5);
    let bright = o.counts(1e9, zero_rate, 0);
    assert!(bright.saturated && bright.peak_pixel_e >= 1e5);
    let mut never = o;
    never.full_well_e = None;
    assert!(!never.counts(1e12, zero_rate, 0).saturated);
}

/// Mean and variance of n draws.
fn moments(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    (
        m,
        x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (n - 1.0),
    )
}

/// 10⁴ Poisson draws at means in both of the generator's regimes (multiplying uniforms
/// below 30, PTRS above): mean within 4 standard errors (√(λ/n)), variance within 4 of
/// its standard errors (≈ λ√(2/n) for large λ, √((λ + 2λ²)/n) in general).
#[test]
fn poisson_draws_have_their_mean_and_variance() {
    let n = 10_000;
    for (k, lambda) in [0.7, 5.0, 29.0, 31.0, 250.0, 1e6].into_iter().enumerate() {
        let mut rng = SplitMix::new(42, k as u64);
        let x: Vec<f64> = (0..n).map(|_| rng.poisson(lambda)).collect();
        assert!(x.iter().all(|v| v.fract() == 0.0 && *v >= 0.0));
        let (m, v) = moments(&x);
        let nf = n as f64;
        assert!(
            (m - lambda).abs() < 4.0 * (lambda / nf).sqrt(),
            "λ {lambda}: mean {m}"
        );
        let se_var = ((lambda + 2.0 * lambda * lambda) / nf).sqrt();
        assert!(
            (v - lambda).abs() < 4.0 * se_var,
            "λ {lambda}: variance {v}"
        );
    }
}

/// 10⁴ noisy samples of one epoch's signal (the same telescope, epoch indices 0..10⁴ each
/// its own stream): their mean is S and their variance N² = S + sky + dark + n_pix σ_R²,
/// within 4 standard errors (N/√n for the mean, N²√(2/(n−1)) for the variance: the
/// samples are nearly normal at these counts). Two cases: sky- and read-noise-dominated,
/// and signal-dominated.
#[test]
fn noisy_samples_have_the_stated_mean_and_variance() {
    let n = 10_000;
    for (rate, zero_rate) in [(2e3, 1e10), (1e6, 1e10)] {
        let o = telescope();
        let stated = o.counts(rate, zero_rate, 0);
        let samples: Vec<f64> = (0..n)
            .map(|i| o.counts(rate, zero_rate, i as u64).sample_e)
            .collect();
        let (m, v) = moments(&samples);
        let nf = n as f64;
        let (s, nn) = (stated.signal_e, stated.noise_e);
        assert!(
            (m - s).abs() < 4.0 * nn / nf.sqrt(),
            "mean {m} vs S {s} (N {nn})"
        );
        let var = nn * nn;
        assert!(
            (v - var).abs() < 4.0 * var * (2.0 / (nf - 1.0)).sqrt(),
            "variance {v} vs N² {var}"
        );
    }
}

/// One request asks for V magnitudes, standard magnitudes and a telescope's SNR; the
/// same seed gives the same samples, another seed others.
#[test]
fn a_light_curve_with_a_telescope() {
    let request = |seed: u64| {
        from_json(&serde_json::json!({
            "object": { "mesh": { "builtin": "sphere" }, "materials": [ { "name": "surface", "model": "lambert", "albedo": 0.3 } ] },
            "epochs": [
                { "t": 0, "sun": [1, 0, 0], "observer": [2e6, 3e6, 0.0], "earth": [0, 0, -4.2e7] },
                { "t": 1, "sun": [1, 0, 0], "observer": [4e6, 0, 0] }
            ],
            "illumination": { "band": "V", "earthshine": "off" },
            "observation": { "aperture_m": 0.4, "exposure_s": 1.0, "quantum_efficiency": 0.9,
                             "sky_mag_per_arcsec2": 21.0, "read_noise_e": 8.0, "seed": seed,
                             "full_well_e": 60000 }
        }))
    };
    let a = glint::simulate(&request(1));
    assert_sane(&a);
    let b = glint::simulate(&request(1));
    let c = glint::simulate(&request(2));
    for ((ea, eb), ec) in a.epochs.iter().zip(&b.epochs).zip(&c.epochs) {
        let (oa, ob, oc) = (
            ea.observation.unwrap(),
            eb.observation.unwrap(),
            ec.observation.unwrap(),
        );
        assert_eq!(oa, ob);
        assert_ne!(oa.sample_e, oc.sample_e);
        assert!(oa.snr > 0.0 && oa.snr.is_finite() && oa.noise_e > 0.0);
        assert!(ea.magnitude_standard.is_some());
        let m = ea.magnitude.unwrap();
        let ms = oa.sample_magnitude.unwrap();
        // the sample's magnitude lies within 5 σ of the magnitude (σ_m ≈ 1.0857/SNR)
        assert!(
            (ms - m).abs() < 5.0 * 1.0857 / oa.snr,
            "{m} {ms} snr {}",
            oa.snr
        );
    }
    let csv = glint::report::csv::to_csv(&a);
    let header = csv.lines().next().unwrap();
    assert!(
        header.ends_with(glint::report::csv::OBSERVATION_HEADER),
        "{header}"
    );
    let row: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(row.len(), header.split(',').count());
}
