//! Exposure: radiance (W/(m²·sr)) → 8-bit grey levels.
//!
//! Linear exposures map radiance `L` to `255 · srgb(min(1, L / white))` — the sRGB
//! transfer curve, so that a PNG viewer shows brightness in proportion to radiance
//! and faint diffuse parts stay visible. The log exposure maps `L = white · 10^(−k)`
//! to `255 · (1 − k / 6)` over six decades.
//!
//! Why the default white level is not the brightest pixel: a specular face seen near
//! its mirror direction is 10⁴ times brighter than the diffuse rest (the box-wing's
//! light curve peaks near magnitude 1 against 12 elsewhere). Exposing every frame on
//! that glint would leave all other frames black. The default instead takes each
//! frame's 99th-percentile lit pixel and the median of that over the frames — one
//! white level for the whole sequence, so brightness changes stay visible, while
//! glints saturate as they would on a real detector.

use crate::scene::Exposure;

/// Decades of radiance shown by the log exposure.
pub const LOG_DECADES: f64 = 6.0;

/// Percentile of a frame's lit pixels taken as its typical bright level.
const BRIGHT_PERCENTILE: f64 = 0.99;

/// White level used when every image of a sequence is black (any positive value
/// gives the same all-black images; 1 keeps the reported exposure finite and plain).
const WHITE_WHEN_DARK: f64 = 1.0;

/// The radiance mapped to white for each image of a sequence, W/(m²·sr).
pub fn white_levels(exposure: Exposure, images: &[&[f32]]) -> Vec<f64> {
    let usable = |w: f64| {
        if w.is_finite() && w > 0.0 {
            w
        } else {
            WHITE_WHEN_DARK
        }
    };
    let n = images.len();
    match exposure {
        Exposure::Fixed => {
            let mut levels: Vec<f64> = images.iter().filter_map(|im| bright_level(im)).collect();
            levels.sort_by(f64::total_cmp);
            // lower median: with two frames, one glinting, the other sets the level
            let w = levels
                .get(levels.len().saturating_sub(1) / 2)
                .copied()
                .unwrap_or(0.0);
            vec![usable(w); n]
        }
        Exposure::Peak | Exposure::Log => {
            let w = images.iter().map(|im| peak(im)).fold(0.0, f64::max);
            vec![usable(w); n]
        }
        Exposure::Auto => images
            .iter()
            .map(|im| usable(bright_level(im).unwrap_or(0.0)))
            .collect(),
        Exposure::Radiance(w) => vec![usable(w); n],
    }
}

/// Brightest pixel, W/(m²·sr) (0 for a black image).
pub fn peak(radiance: &[f32]) -> f64 {
    radiance
        .iter()
        .copied()
        .filter(|x| x.is_finite())
        .fold(0.0f32, f32::max) as f64
}

/// The 99th percentile of the lit (non-zero) pixels, or `None` when none is lit.
pub fn bright_level(radiance: &[f32]) -> Option<f64> {
    let mut lit: Vec<f32> = radiance
        .iter()
        .copied()
        .filter(|x| x.is_finite() && *x > 0.0)
        .collect();
    if lit.is_empty() {
        return None;
    }
    let k = ((lit.len() - 1) as f64 * BRIGHT_PERCENTILE).round() as usize;
    let (_, v, _) = lit.select_nth_unstable_by(k, f32::total_cmp);
    Some(*v as f64)
}

/// Maps radiance to 8-bit grey levels with white level `white` (W/(m²·sr)).
pub fn to_grey(radiance: &[f32], white: f64, log: bool) -> Vec<u8> {
    radiance
        .iter()
        .map(|&l| {
            let x = l as f64 / white;
            let v = if log {
                if x > 0.0 {
                    1.0 + x.log10() / LOG_DECADES
                } else {
                    0.0
                }
            } else {
                srgb(x)
            };
            // NaN cannot reach here (radiance is finite), but clamp keeps it total
            (v.clamp(0.0, 1.0) * 255.0).round() as u8
        })
        .collect()
}

/// The sRGB transfer function (IEC 61966-2-1) of a linear value, clamped to [0, 1].
pub fn srgb(x: f64) -> f64 {
    let x = if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    };
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_is_one_robust_level_for_the_sequence() {
        // 200 diffuse pixels at 1..=200 and 1 glint pixel: the glint does not set it
        let mut a: Vec<f32> = (1..=200).map(|i| i as f32).collect();
        a.push(1e6);
        let b: Vec<f32> = vec![0.0, 50.0, 50.0];
        let glint: Vec<f32> = vec![1e5; 10];
        let w = white_levels(Exposure::Fixed, &[&a, &b, &glint]);
        // per-frame 99th percentiles: 199 (index round(200·0.99) = 198 → 199), 50, 1e5
        assert_eq!(w, vec![199.0; 3]);
        assert_eq!(white_levels(Exposure::Peak, &[&a, &b]), vec![1e6; 2]);
        assert_eq!(white_levels(Exposure::Auto, &[&b, &[0.0]]), vec![50.0, 1.0]);
        assert_eq!(white_levels(Exposure::Fixed, &[&[0.0f32][..]]), vec![1.0]);
        assert_eq!(white_levels(Exposure::Radiance(5.0), &[&b]), vec![5.0]);
    }

    #[test]
    fn grey_levels_are_monotonic_and_saturate() {
        let l: Vec<f32> = vec![0.0, 1e-7, 1e-5, 1e-3, 0.1, 0.5, 1.0, 2.0];
        for log in [false, true] {
            let g = to_grey(&l, 1.0, log);
            assert!(g.windows(2).all(|w| w[0] <= w[1]), "{g:?}");
            assert_eq!((g[0], g[6], g[7]), (0, 255, 255));
        }
        // sRGB: 18% grey is about 118/255; log: three decades below white is half
        assert_eq!(to_grey(&[0.18], 1.0, false)[0], 118);
        assert_eq!(to_grey(&[1e-3], 1.0, true)[0], 128);
    }
}
