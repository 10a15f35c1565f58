//! Named photometric passbands and the solar spectrum they are integrated against
//! (docs/physics.md §2a). Each band's response is the table of `spectra/`, written by
//! `spectra/generate.py` from the package named in its first line; the band's response
//! is that table, piecewise linear in λ, zero outside it.
//!
//! The band integral is photon-weighted, as a photon-counting detector (CCD) measures
//! and as the zero points are defined: E_band = ∫ E_λ R(λ) (λ/λ̄) dλ, λ̄ = ∫R λ dλ / ∫R dλ,
//! an irradiance in W/m² whose ratios are photon-count ratios (for light of the Sun's own
//! spectrum the λ/λ̄ factor changes nothing but the number; ratios of grey reflections are
//! the same either way). It is evaluated by Gauss–Legendre on each interval of the table
//! ([`Passband::weights`]).

use super::{AU_M, SUN_RADIUS_M};
use std::sync::OnceLock;

/// How a band's magnitudes are zero-pointed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ZeroPoint {
    /// Vega = 0.03 mag (spectra/generate.py).
    Vega,
    /// AB: 3631 Jy = 0 mag.
    Ab,
}

/// A named passband: its response table and the Sun's magnitude in it.
#[derive(Debug, PartialEq)]
pub struct Passband {
    /// The request's name for it (`illumination.band`).
    pub name: &'static str,
    /// What it is and where its table comes from.
    pub description: &'static str,
    pub zero_point: ZeroPoint,
    /// The Sun's apparent magnitude at 1 AU in this band: the magnitude zero point.
    pub sun_magnitude: f64,
    /// Where `sun_magnitude` comes from.
    pub sun_magnitude_source: &'static str,
    /// `spectra/<file>.csv`: `wavelength_um,response`.
    table: &'static str,
}

// The Sun's magnitudes. V and B are Willmer (2018, ApJS 236, 47), whose abstract gives
// M_V = 4.81 and M_B = 5.44 (Vega); at 1 AU, m = M − 5 log10(10 pc / 1 AU) = M − 31.572.
// The others have no published value this project could read: they are computed by
// spectra/generate.py from the CALSPEC solar spectrum and the band's zero point
// (spectra/solar_magnitudes.csv), rounded to 0.01. The computed V and B differ from
// Willmer's by 0.016 and 0.005 mag (tests/bands.rs holds them to 0.02).
const WILLMER: &str = "Willmer 2018, ApJS 236, 47 (M = 4.81 V, 5.44 B, Vega) − 31.572";
const COMPUTED: &str =
    "computed from the CALSPEC solar spectrum and the band's zero point (spectra/generate.py)";

/// The named passbands.
pub static PASSBANDS: [Passband; 8] = [
    Passband {
        name: "V",
        description: "Johnson V (Bessell 1990, PASP 102, 1181; speclite bessell-V)",
        zero_point: ZeroPoint::Vega,
        sun_magnitude: -26.76,
        sun_magnitude_source: WILLMER,
        table: include_str!("../../spectra/bessell-V.csv"),
    },
    Passband {
        name: "B",
        description: "Johnson B (Bessell 1990, PASP 102, 1181; speclite bessell-B)",
        zero_point: ZeroPoint::Vega,
        sun_magnitude: -26.13,
        sun_magnitude_source: WILLMER,
        table: include_str!("../../spectra/bessell-B.csv"),
    },
    Passband {
        name: "R",
        description: "Cousins R (Bessell 1990, PASP 102, 1181; speclite bessell-R)",
        zero_point: ZeroPoint::Vega,
        sun_magnitude: -27.13,
        sun_magnitude_source: COMPUTED,
        table: include_str!("../../spectra/bessell-R.csv"),
    },
    Passband {
        name: "G",
        description: "Gaia G, EDR3/DR3 passband (Riello et al. 2021, A&A 649, A3; speclite gaiadr3-G)",
        zero_point: ZeroPoint::Vega,
        sun_magnitude: -26.89,
        sun_magnitude_source: COMPUTED,
        table: include_str!("../../spectra/gaiadr3-G.csv"),
    },
    Passband {
        name: "g",
        description: "SDSS g, 2.5 m reference response at airmass 1.3 (Doi et al. 2010, AJ 139, 1628; speclite sdss2010-g)",
        zero_point: ZeroPoint::Ab,
        sun_magnitude: -26.46,
        sun_magnitude_source: COMPUTED,
        table: include_str!("../../spectra/sdss2010-g.csv"),
    },
    Passband {
        name: "r",
        description: "SDSS r, 2.5 m reference response at airmass 1.3 (Doi et al. 2010, AJ 139, 1628; speclite sdss2010-r)",
        zero_point: ZeroPoint::Ab,
        sun_magnitude: -26.93,
        sun_magnitude_source: COMPUTED,
        table: include_str!("../../spectra/sdss2010-r.csv"),
    },
    Passband {
        name: "i",
        description: "SDSS i, 2.5 m reference response at airmass 1.3 (Doi et al. 2010, AJ 139, 1628; speclite sdss2010-i)",
        zero_point: ZeroPoint::Ab,
        sun_magnitude: -27.04,
        sun_magnitude_source: COMPUTED,
        table: include_str!("../../spectra/sdss2010-i.csv"),
    },
    Passband {
        name: "clear",
        description: "unfiltered silicon CCD, as the Kepler photometer's response, 0.42–0.905 µm (Van Cleve & Caldwell 2016, KSCI-19033-002; pyphot KEPLER_Kp); a camera's own response differs: give band_um for a plain interval",
        zero_point: ZeroPoint::Vega,
        sun_magnitude: -26.88,
        sun_magnitude_source: COMPUTED,
        table: include_str!("../../spectra/kepler-Kp.csv"),
    },
];

/// The passband of that name (case-sensitive: `g` is SDSS, `G` Gaia).
pub fn find(name: &str) -> Option<&'static Passband> {
    PASSBANDS.iter().find(|b| b.name == name)
}

/// The names, for error messages and docs.
pub fn names() -> Vec<&'static str> {
    PASSBANDS.iter().map(|b| b.name).collect()
}

/// Rows `a,b` of a CSV table after its header and `#` comments.
fn parse_table(text: &str) -> Vec<(f64, f64)> {
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .skip(1)
        .map(|l| {
            let (a, b) = l.split_once(',').expect("two columns");
            (
                a.trim().parse().expect("a number"),
                b.trim().parse().expect("a number"),
            )
        })
        .collect()
}

impl Passband {
    /// The response table: (λ µm, R), λ increasing.
    pub fn response(&self) -> Vec<(f64, f64)> {
        parse_table(self.table)
    }

    /// The wavelengths the response spans, µm.
    pub fn range_um(&self) -> [f64; 2] {
        let r = self.response();
        [r[0].0, r[r.len() - 1].0]
    }

    /// The photon-weighted mean wavelength λ̄ = ∫R λ dλ / ∫R dλ, µm (exact for the
    /// piecewise-linear R).
    pub fn mean_wavelength_um(&self) -> f64 {
        let r = self.response();
        let (mut int_r, mut int_rl) = (0.0, 0.0);
        for p in r.windows(2) {
            let ((l0, r0), (l1, r1)) = (p[0], p[1]);
            let h = l1 - l0;
            int_r += 0.5 * h * (r0 + r1);
            // ∫ of a linear R times λ over [l0, l1], exactly
            int_rl += h * (r0 * (2.0 * l0 + l1) + r1 * (l0 + 2.0 * l1)) / 6.0;
        }
        int_rl / int_r
    }

    /// Quadrature of the photon-weighted band integral: (λ_i, w_i) with
    /// Σ w_i f(λ_i) = ∫ f R (λ/λ̄) dλ, by 4-point Gauss–Legendre on each interval of the
    /// table (R is linear there: exact for f a polynomial of degree ≤ 5 on it, and far
    /// below the tables' own precision for the smooth solar spectra).
    pub fn weights(&self) -> Vec<(f64, f64)> {
        // nodes on [−1, 1] (±) and weights of the 4-point rule
        const GL4: [(f64, f64); 2] = [
            (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
            (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
        ];
        let r = self.response();
        let mut w = Vec::with_capacity(4 * r.len());
        let (mut int_r, mut int_rl) = (0.0, 0.0);
        for p in r.windows(2) {
            let ((l0, r0), (l1, r1)) = (p[0], p[1]);
            let (mid, half) = (0.5 * (l0 + l1), 0.5 * (l1 - l0));
            for &(x, gw) in &GL4 {
                for l in [mid - half * x, mid + half * x] {
                    let resp = r0 + (r1 - r0) * (l - l0) / (l1 - l0);
                    let rw = half * gw * resp;
                    int_r += rw;
                    int_rl += rw * l;
                    if rw > 0.0 {
                        w.push((l, rw * l));
                    }
                }
            }
        }
        let mean = int_rl / int_r;
        w.iter().map(|&(l, x)| (l, x / mean)).collect()
    }
}

/// The Sun's spectrum a band is integrated against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SolarSpectrum {
    /// A blackbody at this temperature (K), of the Sun's radius (the default; the paper's).
    Planck(f64),
    /// The CALSPEC solar reference spectrum (`spectra/sun_calspec.csv`), 0.1195–2.70 µm.
    Calspec,
}

/// The CALSPEC solar spectrum at 1 AU: (λ µm, W/(m²·µm)).
pub fn calspec() -> &'static [(f64, f64)] {
    static TABLE: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    TABLE.get_or_init(|| parse_table(include_str!("../../spectra/sun_calspec.csv")))
}

/// The wavelengths the CALSPEC table spans, µm.
pub fn calspec_range_um() -> [f64; 2] {
    let t = calspec();
    [t[0].0, t[t.len() - 1].0]
}

/// Linear interpolation in a table sorted by x; `None` outside it.
fn interpolate(table: &[(f64, f64)], x: f64) -> Option<f64> {
    let i = table.partition_point(|&(a, _)| a < x);
    if i == 0 {
        return (table[0].0 == x).then_some(table[0].1);
    }
    if i == table.len() {
        return None;
    }
    let ((x0, y0), (x1, y1)) = (table[i - 1], table[i]);
    Some(y0 + (y1 - y0) * (x - x0) / (x1 - x0))
}

impl SolarSpectrum {
    /// The Sun's spectral irradiance at 1 AU, W/(m²·µm); 0 outside a table's range.
    pub fn irradiance_1au(&self, lambda_um: f64) -> f64 {
        match *self {
            SolarSpectrum::Planck(t) => {
                let x = super::planck::C2 / (lambda_um * t);
                let ratio = SUN_RADIUS_M / AU_M;
                ratio * ratio * super::planck::C1 * lambda_um.powi(-5) / x.exp_m1()
            }
            SolarSpectrum::Calspec => interpolate(calspec(), lambda_um).unwrap_or(0.0),
        }
    }

    /// The Sun's photon-weighted irradiance at 1 AU in a named band, W/m².
    pub fn band_1au(&self, band: &Passband) -> f64 {
        band.weights()
            .iter()
            .map(|&(l, w)| w * self.irradiance_1au(l))
            .sum()
    }

    /// The Sun's irradiance at 1 AU in the interval [λ1, λ2] µm of the CALSPEC table
    /// (trapezoid on the table's points inside and the interval's interpolated ends:
    /// exact for the table read as piecewise linear). `None` if the interval leaves the
    /// table.
    pub fn calspec_interval_1au(band_um: [f64; 2]) -> Option<f64> {
        let t = calspec();
        let [a, b] = band_um;
        let mut pts = vec![(a, interpolate(t, a)?)];
        let end = (b, interpolate(t, b)?);
        pts.extend(t.iter().copied().filter(|&(l, _)| l > a && l < b));
        pts.push(end);
        Some(
            pts.windows(2)
                .map(|p| 0.5 * (p[1].0 - p[0].0) * (p[0].1 + p[1].1))
                .sum(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_table_parses_and_spans_its_band() {
        for b in &PASSBANDS {
            let r = b.response();
            assert!(r.len() > 10, "{}", b.name);
            assert!(
                r.windows(2).all(|p| p[1].0 > p[0].0),
                "{}: λ increasing",
                b.name
            );
            assert!(
                r.iter().all(|&(_, x)| (0.0..=1.0).contains(&x)),
                "{}",
                b.name
            );
            let [lo, hi] = b.range_um();
            assert!(lo > 0.3 && hi < 1.2, "{}: {lo}..{hi}", b.name);
            let [clo, chi] = calspec_range_um();
            assert!(lo >= clo && hi <= chi, "{}: CALSPEC covers it", b.name);
        }
        assert!(find("g").is_some_and(|b| b.zero_point == ZeroPoint::Ab));
        assert!(find("G").is_some_and(|b| b.zero_point == ZeroPoint::Vega));
        assert_eq!(find("U"), None);
    }

    /// The weights integrate R·λ/λ̄ to ∫R, the trapezoid's exact value for a piecewise
    /// linear R (rounding only, 1e-12).
    #[test]
    fn the_weights_keep_the_response_integral() {
        for b in &PASSBANDS {
            let r = b.response();
            let int_r: f64 = r
                .windows(2)
                .map(|p| 0.5 * (p[1].0 - p[0].0) * (p[0].1 + p[1].1))
                .sum();
            let sum: f64 = b.weights().iter().map(|&(_, w)| w).sum();
            assert!((sum / int_r - 1.0).abs() < 1e-12, "{}", b.name);
        }
    }
}
