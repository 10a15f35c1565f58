//! Planck's law integrated over a band (Eq. 1), by its exact series — no quadrature.
//!
//! With x = c2/(λT), the exitance beyond λ is
//! M(λ→∞) = c1 (T/c2)⁴ ∫₀ˣ t³/(eᵗ−1) dt.
//! For x ≥ 1 we use ∫₀ˣ = π⁴/15 − Σₙ e^{−nx}(x³/n + 3x²/n² + 6x/n³ + 6/n⁴);
//! for x < 1 the Bernoulli series x³/3 − x⁴/8 + Σ B₂ₖ x^{2k+3}/((2k)!(2k+3)).

use std::f64::consts::PI;

/// First radiation constant c1 = 2πhc², W·µm⁴/m².
pub const C1: f64 = 3.741844e8;
/// Second radiation constant c2 = hc/k, µm·K.
pub const C2: f64 = 14388.0;

/// ∫₀ˣ t³/(eᵗ−1) dt, accurate to ~1e-15 relative for all x ≥ 0.
fn planck_cumulative(x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let total = PI.powi(4) / 15.0;
    if x >= 1.0 {
        let mut tail = 0.0;
        for n in 1..=200 {
            let nf = n as f64;
            let e = (-nf * x).exp();
            let term = e
                * (x.powi(3) / nf
                    + 3.0 * x * x / nf.powi(2)
                    + 6.0 * x / nf.powi(3)
                    + 6.0 / nf.powi(4));
            tail += term;
            if term < 1e-17 * tail {
                break;
            }
        }
        total - tail
    } else {
        // B2k / (2k)! for k = 1..8
        const B_OVER_FACT: [f64; 8] = [
            1.0 / 6.0 / 2.0,
            -1.0 / 30.0 / 24.0,
            1.0 / 42.0 / 720.0,
            -1.0 / 30.0 / 40320.0,
            5.0 / 66.0 / 3628800.0,
            -691.0 / 2730.0 / 479001600.0,
            7.0 / 6.0 / 87178291200.0,
            -3617.0 / 510.0 / 20922789888000.0,
        ];
        let mut sum = x.powi(3) / 3.0 - x.powi(4) / 8.0;
        for (i, c) in B_OVER_FACT.iter().enumerate() {
            let p = 2 * (i as i32 + 1) + 3;
            sum += c * x.powi(p) / p as f64;
        }
        sum
    }
}

/// Blackbody exitance between `lambda1_um` and `lambda2_um` at `temperature_k`, W/m².
/// Over the whole spectrum it equals σT⁴.
pub fn band_exitance(lambda1_um: f64, lambda2_um: f64, temperature_k: f64) -> f64 {
    let scale = C1 * (temperature_k / C2).powi(4);
    // exitance beyond λ; λ → 0 gives x → ∞ and the whole integral
    let beyond = |lambda: f64| {
        if lambda <= 0.0 {
            PI.powi(4) / 15.0
        } else if lambda.is_infinite() {
            0.0
        } else {
            planck_cumulative(C2 / (lambda * temperature_k))
        }
    };
    scale * (beyond(lambda1_um) - beyond(lambda2_um))
}
