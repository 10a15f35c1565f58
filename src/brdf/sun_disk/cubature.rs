//! The rules that average over the Sun's disk: points on the unit disk with weights —
//! hexagonal patterns of equal weights, Radon's 7 points, products of Gauss points in r²
//! and even angles — and their directions on the sky.

use super::{PENUMBRA_RINGS, RINGS, SMOOTH_RULES};
use crate::geometry::orthonormal_basis;
use glam::DVec3;

/// A point of a rule on the unit disk: offsets in units of the disk radius, and weight
/// (a rule's weights sum to 1).
pub(super) type DiskPoint = (f64, f64, f64);

/// The spacing of a hexagonal pattern of `rings` rings on the unit disk, chosen so that
/// each point stands for an equal share of the disk's area (π = N·(√3/2)·d²).
pub(super) fn hex_spacing(rings: usize) -> f64 {
    let n = 1 + 3 * rings * (rings + 1);
    (2.0 * std::f64::consts::PI / (n as f64 * 3f64.sqrt())).sqrt()
}

/// Every point of a hexagonal lattice within `rings` rings of the centre, spaced by
/// [`hex_spacing`], with equal weights.
fn hex_pattern(rings: usize) -> Vec<DiskPoint> {
    let d = hex_spacing(rings);
    let k = rings as i32;
    let n = 1 + 3 * rings * (rings + 1);
    let w = 1.0 / n as f64;
    let mut p = Vec::with_capacity(n);
    for i in -k..=k {
        for j in -k..=k {
            // axial hex coordinates: inside ring k when the third coordinate is too
            if (i + j).abs() <= k {
                let x = d * (i as f64 + 0.5 * j as f64);
                let y = d * (0.75f64.sqrt() * j as f64);
                p.push((x, y, w));
            }
        }
    }
    debug_assert_eq!(p.len(), n);
    p
}

/// The hexagonal pattern of [`RINGS`] rings ([`HEX_POINTS`] points).
pub(super) fn hex_points() -> &'static [DiskPoint] {
    static POINTS: std::sync::OnceLock<Vec<DiskPoint>> = std::sync::OnceLock::new();
    POINTS.get_or_init(|| hex_pattern(RINGS))
}

/// The hexagonal pattern of [`PENUMBRA_RINGS`] rings.
pub(super) fn penumbra_points() -> &'static [DiskPoint] {
    static POINTS: std::sync::OnceLock<Vec<DiskPoint>> = std::sync::OnceLock::new();
    POINTS.get_or_init(|| hex_pattern(PENUMBRA_RINGS))
}

/// Radon's 7-point rule for the disk, exact for polynomials of degree 5 (Stroud's
/// S2:5-1): the centre with weight 1/4 and six points at radius √(2/3), 60° apart, with
/// 1/8 each.
fn radon_points() -> Vec<DiskPoint> {
    let r = (2.0f64 / 3.0).sqrt();
    let mut p = vec![(0.0, 0.0, 0.25)];
    p.extend((0..6).map(|k| {
        let (s, c) = (k as f64 * std::f64::consts::FRAC_PI_3).sin_cos();
        (r * c, r * s, 0.125)
    }));
    p
}

/// A product rule for the disk: Gauss–Legendre in u = r² (the disk's area is uniform in
/// u), exact for polynomials of degree 2·`rings` − 1 in it, times `angles` even angles
/// (exact for harmonics below that order), alternate rings turned by half a step.
fn polar_points(rings: usize, angles: usize) -> Vec<DiskPoint> {
    // nodes on [−1, 1] and weights (summing to 2)
    let gauss: &[(f64, f64)] = match rings {
        3 => &[
            (-0.774_596_669_241_483_4, 5.0 / 9.0),
            (0.0, 8.0 / 9.0),
            (0.774_596_669_241_483_4, 5.0 / 9.0),
        ],
        4 => &[
            (-0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
            (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
            (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
            (0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
        ],
        _ => unreachable!("SMOOTH_RULES uses 3 or 4 rings"),
    };
    let mut p = Vec::with_capacity(rings * angles);
    for (i, &(x, w)) in gauss.iter().enumerate() {
        let r = (0.5 * (x + 1.0)).sqrt();
        for j in 0..angles {
            let t = (j as f64 + 0.5 * (i % 2) as f64) / angles as f64 * std::f64::consts::TAU;
            p.push((r * t.cos(), r * t.sin(), 0.5 * w / angles as f64));
        }
    }
    p
}

/// The points of each of [`SMOOTH_RULES`], in its order.
pub(super) fn smooth_rules() -> &'static [Vec<DiskPoint>] {
    static RULES: std::sync::OnceLock<Vec<Vec<DiskPoint>>> = std::sync::OnceLock::new();
    RULES.get_or_init(|| {
        SMOOTH_RULES
            .iter()
            .map(|&(_, rings, angles)| {
                if rings == 0 {
                    radon_points()
                } else {
                    polar_points(rings, angles)
                }
            })
            .collect()
    })
}

/// The rule's weights and directions on the disk of angular radius `sun_radius` (rad)
/// about `l`.
pub(super) fn disk_directions(
    rule: &'static [DiskPoint],
    l: DVec3,
    sun_radius: f64,
) -> impl Iterator<Item = (f64, DVec3)> {
    let (a, b) = orthonormal_basis(l);
    rule.iter().map(move |&(x, y, w)| {
        // the point at angle r·ρ from the centre towards (x, y): exact on the sphere
        let r = (x * x + y * y).sqrt();
        let d = if r == 0.0 {
            l
        } else {
            let (sr, cr) = (r * sun_radius).sin_cos();
            l * cr + (a * x + b * y) * (sr / r)
        };
        (w, d)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brdf::sun_disk::HEX_POINTS;

    #[test]
    fn hex_points_fill_the_disk_evenly() {
        let p = hex_points();
        assert_eq!(p.len(), HEX_POINTS);
        // mean at the centre, mean square r² = 1/2 of a uniform unit disk within 10 %
        let (mx, my) = p.iter().fold((0.0, 0.0), |a, q| (a.0 + q.0, a.1 + q.1));
        assert!(mx.abs() < 1e-12 && my.abs() < 1e-12);
        let r2 = p.iter().map(|q| q.0 * q.0 + q.1 * q.1).sum::<f64>() / HEX_POINTS as f64;
        assert!((r2 - 0.5).abs() < 0.05, "mean r² {r2}");
        assert!(p.iter().all(|q| q.0.hypot(q.1) < 1.0));
        assert!((p.iter().map(|q| q.2).sum::<f64>() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn smooth_rules_integrate_the_disk_to_their_degree() {
        // Every monomial xⁱyʲ up to the rule's degree averages over the unit disk to
        // 2(i−1)!!(j−1)!!/((i+j+2)(i+j)!!) for i, j even, else 0. Radon's rule has
        // degree 5; a product rule min(2·rings·2 − 1, angles − 1) (Gauss in r² exact to
        // u^(2·rings−1), even angles to harmonics below their number).
        let double_factorial = |n: i32| (1..=n).rev().step_by(2).product::<i32>().max(1) as f64;
        let exact = |i: i32, j: i32| {
            if i % 2 == 1 || j % 2 == 1 {
                0.0
            } else {
                2.0 * double_factorial(i - 1) * double_factorial(j - 1)
                    / ((i + j + 2) as f64 * double_factorial(i + j))
            }
        };
        for (rule, &(_, rings, angles)) in smooth_rules().iter().zip(&SMOOTH_RULES) {
            let degree = if rings == 0 {
                5
            } else {
                (4 * rings - 1).min(angles - 1) as i32
            };
            assert!((rule.iter().map(|q| q.2).sum::<f64>() - 1.0).abs() < 1e-14);
            assert!(rule.iter().all(|q| q.0.hypot(q.1) < 1.0));
            for i in 0..=degree {
                for j in 0..=degree - i {
                    let m: f64 = rule
                        .iter()
                        .map(|&(x, y, w)| w * x.powi(i) * y.powi(j))
                        .sum();
                    let e = exact(i, j);
                    assert!(
                        (m - e).abs() < 1e-14,
                        "rule {rings}×{angles}: x^{i} y^{j}: {m} vs {e}"
                    );
                }
            }
        }
    }
}
