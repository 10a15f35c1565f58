//! The Sun as a disk for narrow specular lobes (docs/physics.md §7).
//!
//! A point Sun makes the glint of a mirror-smooth face (slope_rms ~1e-4) a spike far
//! narrower than the Sun's disk (angular radius ρ ≈ 4.65e-3 rad at 1 AU): epochs either
//! miss it or hit it by luck. What an observer sees is the Sun's disk reflected by the
//! face, blurred by the lobe. So where a material's lobe is not wide (RMS slope below
//! [`WIDE_LOBE`]·ρ) and the observer is near the glint, the specular part is averaged
//! over directions spread over the disk; the diffuse part stays a point evaluation
//! (exact to O(ρ²)), and a wide lobe is left exactly as it is.
//!
//! The rule follows the lobe's width across the disk (see [`disk_rule`]):
//! - A lobe smooth over the disk (at least [`SMOOTH_RULES`]' widths) is averaged by a
//!   rule exact for polynomials: Radon's 7 points for a lobe as wide as the disk, products
//!   of Gauss points in r² and even angles (24 to 48 points) for narrower ones, each
//!   within ~2e-4 of the glint's peak down to its width (~5e-4 for the narrowest).
//! - A lobe narrower still images the disk itself, sharp edge and all: [`HEX_POINTS`]
//!   directions spread evenly over the disk (a hexagonal pattern of equal weights),
//!   each direction's lobe widened to [`BLOB`]·ρ when narrower, so the samples blend
//!   into the disk's image instead of separate spikes; widening keeps each lobe's
//!   normalisation, so the reflected energy is unchanged. Across the plane of Sun and
//!   observer the blob is widened further, by 1/cos(g/2) at phase g, so that it stays
//!   round in the reflected direction (see [`SunLight`]).
//! - While the Earth hides part of the disk (penumbra), a finer hexagonal pattern
//!   ([`PENUMBRA_RINGS`]) with its hidden points dropped averages over the visible part
//!   only ([`SunLight::eclipsed`]).

use super::{Brdf, Directions, Fixed, Frame};
use crate::geometry::orthonormal_basis;
use glam::DVec3;

/// Lobes with an RMS slope above this many solar radii see the Sun as a point. A point
/// Sun misses the disk's blur of the glint's peak by ρ²/(8δ²) of it (a Beckmann lobe
/// e^(−θ²/2σ²) in the Sun's direction, σ = √2·δ, averaged over a disk of radius ρ):
/// 7.8e−3 here, falling as 1/δ². At a phase angle g the lobe narrows out of the plane
/// of Sun and observer (see [`disk_rule`]) and the miss grows by (1 + 1/cos²(g/2))/2:
/// 1.5× at 90°, 7.5× at 150°. (At 12 the miss would be under 1e−3 at small phase, but
/// Ashikhmin–Shirley lobes that narrow, averaged over the disk, light a sphere's limb at
/// phase 180° to 0.6 % of its phase-0 brightness through that model's 1/(h·l) at
/// grazing: left for a decision on that model's grazing behaviour.)
pub const WIDE_LOBE: f64 = 4.0;
/// The rules for lobes smooth over the disk: (least width across the disk in solar radii,
/// rings of Gauss points in r², angles per ring), Radon's 7-point rule written as 0 rings.
/// The width is the RMS slope times cos(g/2) (see [`disk_rule`]). Measured against a
/// fine polar grid over the disk at phase 48°–150° (see the tests), each is within
/// 2.1e−4 of the glint's peak at its least width (5.2e−4 for the last), where the 37
/// hexagonal points miss by 2.1e−3, 4.7e−3, 5.1e−3 and 2.4e−2. Near phase 180° the
/// glint itself lies at grazing incidence and the Sun's disk straddles the face's
/// horizon, a kink no polynomial follows; by then the width has fallen below the last
/// and the hexagonal pattern serves.
pub const SMOOTH_RULES: [(f64, usize, usize); 4] =
    [(0.8, 0, 0), (0.4, 3, 8), (0.3, 3, 10), (0.2, 4, 12)];
/// Rings of the hexagonal pattern of directions on the disk.
pub const RINGS: usize = 3;
/// Directions of the hexagonal pattern: 1 + 3·RINGS·(RINGS + 1).
pub const HEX_POINTS: usize = 1 + 3 * RINGS * (RINGS + 1);
/// Rings of the finer hexagonal pattern used while the Earth hides part of the disk
/// (127 directions, spacing 0.17 ρ): the points behind the Earth are dropped, so the
/// pattern's spacing is how sharply the Earth's limb is drawn across the glint. Penumbra
/// lasts a few epochs of an eclipse, so the cost does not count.
pub const PENUMBRA_RINGS: usize = 6;
/// Smallest lobe RMS slope used for one disk direction, in solar radii. The lobe's
/// width in the observer's angle is √2 times its slope, 0.25 ρ, about 0.8 of the pattern's
/// spacing (0.31 ρ): neighbours blend and the disk's image is flat to 1e-3 (tuned on a
/// mirror's sweep; 0.12–0.21 all keep the energy within 1 %). This is the width in the
/// plane of Sun and observer; across it the blob is widened by 1/cos(g/2) (see
/// [`SunLight`]), so that the blob is round in the reflected direction at every phase.
pub const BLOB: f64 = 0.18;
/// Least cos(g/2) a blob's widening across the Sun–observer plane uses, in solar radii
/// (a disk direction within 0.02 ρ of the anti-observer direction): keeps the widening
/// finite where the plane is undefined. At phase 180° the blobs of the inner ring then
/// span about a radian along the terminator, as the disk's image there does.
const LEAST_COS_HALF_PHASE: f64 = 0.01;
/// The specular term is negligible (e^-36 of its peak) this many lobe slopes past the
/// disk's edge, measured in the half vector (so twice that in the Sun's direction).
const TAIL: f64 = 6.0;

/// A point of a rule on the unit disk: offsets in units of the disk radius, and weight
/// (a rule's weights sum to 1).
type DiskPoint = (f64, f64, f64);

/// The spacing of a hexagonal pattern of `rings` rings on the unit disk, chosen so that
/// each point stands for an equal share of the disk's area (π = N·(√3/2)·d²).
fn hex_spacing(rings: usize) -> f64 {
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
fn hex_points() -> &'static [DiskPoint] {
    static POINTS: std::sync::OnceLock<Vec<DiskPoint>> = std::sync::OnceLock::new();
    POINTS.get_or_init(|| hex_pattern(RINGS))
}

/// The hexagonal pattern of [`PENUMBRA_RINGS`] rings.
fn penumbra_points() -> &'static [DiskPoint] {
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
fn smooth_rules() -> &'static [Vec<DiskPoint>] {
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

/// f·cosθi·cosθr (sr⁻¹) for sunlight from a disk of angular radius `sun_radius` (rad)
/// centred on `l`, averaged over the disk, towards `v`. Equals `brdf.projected(frame, l, v)`
/// for a point Sun (`sun_radius` = 0), for materials without a narrow lobe, and away
/// from the glint.
pub fn projected(brdf: &Brdf, frame: &Frame, l: DVec3, v: DVec3, sun_radius: f64) -> f64 {
    projected_with(brdf, frame, l, v, sun_radius, None, BLOB)
}

/// [`projected`] with part of the disk hidden by the Earth: the average over the part
/// of the disk `earth` leaves visible (the caller multiplies by the visible fraction's
/// irradiance, E_s·(1 − hidden)). The diffuse part stays a point evaluation.
pub fn projected_eclipsed(
    brdf: &Brdf,
    frame: &Frame,
    l: DVec3,
    v: DVec3,
    sun_radius: f64,
    earth: Option<EarthDisk>,
) -> f64 {
    projected_with(brdf, frame, l, v, sun_radius, earth, BLOB)
}

/// The Earth's disk on the object's sky: the unit direction of its centre and its
/// angular radius (rad). What hides part of the Sun in penumbra (docs/physics.md §4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EarthDisk {
    pub dir: DVec3,
    pub radius: f64,
}

impl EarthDisk {
    /// Whether the direction `d` (unit) lies behind the Earth.
    #[inline]
    fn hides(&self, d: DVec3) -> bool {
        angle(d, self.dir) < self.radius
    }
}

/// Angle between unit vectors, rad (atan2: accurate near 0 and π).
fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The Sun (a disk) and the observer fixed for one epoch and material: [`projected`]
/// for many faces, with what does not depend on the face computed once (the Fresnel
/// terms of the point Sun and of every disk direction). Faces away from the glint
/// (almost all) cost one point-Sun evaluation.
///
/// For the hexagonal patterns each direction's lobe is widened to a blob. In the plane
/// of the Sun and the observer the blob has slope δ_in = max(δ, BLOB·ρ) in the half
/// vector; across that plane the half vector moves 1/cos(g/2) times as fast as in it
/// (g the phase angle), so there the blob gets δ_out = max(δ, BLOB·ρ/cos(g/2)): round,
/// of slope 2·BLOB·ρ, in the reflected direction, where the pattern's points are evenly
/// spaced. The lobe is evaluated with its offset across the plane scaled by
/// q = δ_in/δ_out and multiplied by q, which keeps its normalisation.
#[derive(Debug, Clone)]
pub struct SunLight<'a> {
    point: Fixed<'a>,
    v: DVec3,
    l: DVec3,
    /// Present when the disk can matter (a narrow lobe and a Sun of some size).
    disk: Option<Disk>,
}

#[derive(Debug, Clone)]
struct Disk {
    /// cos of the angle from the mirror direction beyond which the disk cannot matter.
    cos_reach: f64,
    diffuse: Brdf,
    diffuse_dirs: Directions,
    /// The specular part, widened to the blob's slope in the Sun–observer plane where
    /// narrower.
    spec: Brdf,
    /// Each direction of the rule, with its weight and stretch.
    spec_dirs: Vec<Sample>,
}

/// One direction on the disk.
#[derive(Debug, Clone)]
struct Sample {
    /// Weight (the weights of a rule sum to 1).
    w: f64,
    dirs: Directions,
    /// Unit half vector of this direction and the observer.
    h: DVec3,
    /// Unit vector across the plane of this direction and the observer (l_k × v).
    across: DVec3,
    /// δ_in/δ_out (≤ 1): how much the lobe's offset across the plane is scaled; 1 leaves
    /// the lobe as the (widened) model has it.
    squeeze: f64,
}

impl Sample {
    /// w·f·cosθi·cosθr of this direction on a face (`cr` = n·v).
    #[inline]
    fn projected_given(&self, spec: &Brdf, frame: &Frame, cr: f64) -> f64 {
        if self.squeeze >= 1.0 {
            return self.w * self.dirs.projected_given(spec, frame, cr);
        }
        if cr <= 0.0 {
            return 0.0;
        }
        // the half vector turned towards n across the plane by (1 − q) of n's angle a
        // from it that way, so the lobe sees that angle scaled by q (an angle, not a
        // tangent offset: near phase 180° the blobs span radians along the terminator);
        // and the light moved with it (the direction that h mirrors into v), so the blob
        // is lit as from where it lies
        let n = frame.n;
        let a = n.dot(self.across).atan2(n.dot(self.h));
        let (sa, ca) = ((1.0 - self.squeeze) * a).sin_cos();
        let h = self.h * ca + self.across * sa;
        let v = self.dirs.view();
        let l = 2.0 * h.dot(v) * h - v;
        let ci = n.dot(l);
        if ci <= 0.0 {
            return 0.0;
        }
        self.w * self.squeeze * self.dirs.model_moved(spec, frame, ci, cr, l, h)
    }
}

/// The rule chosen for one epoch: its directions with weights (summing to 1 over the
/// visible part of the disk), the slope its lobes get in the Sun–observer plane, and
/// the blob's slope (rad, in the half vector) when it is a hexagonal pattern.
struct Rule {
    dirs: Vec<(f64, DVec3)>,
    slope_in: f64,
    blob: Option<f64>,
}

impl<'a> SunLight<'a> {
    pub fn new(brdf: &'a Brdf, l: DVec3, v: DVec3, sun_radius: f64) -> SunLight<'a> {
        SunLight::build(brdf, l, v, sun_radius, None, BLOB)
    }

    /// [`SunLight::new`] with part of the disk perhaps hidden by the Earth: values are
    /// averages over the visible part (see [`projected_eclipsed`]).
    pub fn eclipsed(
        brdf: &'a Brdf,
        l: DVec3,
        v: DVec3,
        sun_radius: f64,
        earth: Option<EarthDisk>,
    ) -> SunLight<'a> {
        SunLight::build(brdf, l, v, sun_radius, earth, BLOB)
    }

    fn build(
        brdf: &'a Brdf,
        l: DVec3,
        v: DVec3,
        sun_radius: f64,
        earth: Option<EarthDisk>,
        blob: f64,
    ) -> SunLight<'a> {
        let disk = match brdf.lobe_slope() {
            Some(slope)
                if !sun_radius.is_nan() && sun_radius > 0.0 && slope <= WIDE_LOBE * sun_radius =>
            {
                disk_rule(slope, l, v, sun_radius, earth, blob).map(|rule| {
                    let reach = sun_radius + 2.0 * TAIL * rule.slope_in;
                    let diffuse = brdf.split(true);
                    let spec = widened(brdf.split(false), slope, rule.slope_in);
                    let spec_dirs = rule
                        .dirs
                        .iter()
                        .map(|&(w, d)| sample(&spec, w, d, v, slope, rule.blob, sun_radius))
                        .collect();
                    Disk {
                        cos_reach: if reach >= std::f64::consts::PI {
                            -1.0
                        } else {
                            reach.cos()
                        },
                        diffuse_dirs: Directions::new(&diffuse, l, v),
                        diffuse,
                        spec,
                        spec_dirs,
                    }
                })
            }
            _ => None,
        };
        SunLight {
            point: Fixed::new(brdf, l, v),
            v,
            l,
            disk,
        }
    }

    /// [`projected`] for a face with this frame, sr⁻¹ (the same value, computed faster).
    #[inline]
    pub fn projected(&self, frame: &Frame) -> f64 {
        self.projected_given(frame, frame.n.dot(self.v))
    }

    /// [`SunLight::projected`] given `cr` = n·v, which the caller already has.
    #[inline]
    pub fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        if let Some(disk) = &self.disk {
            let n = frame.n;
            // near the glint: the mirror direction within the disk's reach
            if cr > 0.0 && (2.0 * cr * n - self.v).dot(self.l) >= disk.cos_reach {
                return disk.projected_given(frame, cr);
            }
        }
        self.point.projected_given(frame, cr)
    }
}

/// One direction `d` of weight `w` for the specular part `spec` (widened to the blob in
/// the Sun–observer plane), with its stretch across that plane for a hexagonal pattern
/// of blob slope `blob` (rad).
fn sample(
    spec: &Brdf,
    w: f64,
    d: DVec3,
    v: DVec3,
    slope: f64,
    blob: Option<f64>,
    sun_radius: f64,
) -> Sample {
    let dirs = Directions::new(spec, d, v);
    let plain = Sample {
        w,
        dirs,
        h: DVec3::ZERO,
        across: DVec3::ZERO,
        squeeze: 1.0,
    };
    let Some(blob) = blob else {
        return plain;
    };
    let (Some(h), Some(across)) = (super::half_vector(d, v), d.cross(v).try_normalize()) else {
        return plain;
    };
    let cos_half = (0.5 * (d + v).length()).max(LEAST_COS_HALF_PHASE * sun_radius);
    let squeeze = slope.max(blob) / slope.max(blob / cos_half);
    Sample {
        h,
        across,
        squeeze,
        ..plain
    }
}

impl Disk {
    /// The disk's average near the glint, sr⁻¹.
    #[inline]
    fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        let sum: f64 = self
            .spec_dirs
            .iter()
            .map(|d| d.projected_given(&self.spec, frame, cr))
            .sum();
        self.diffuse_dirs.projected_given(&self.diffuse, frame, cr) + sum
    }
}

/// The rule for a lobe of RMS slope `slope` against a disk of angular radius
/// `sun_radius` (rad) about `l`, seen from `v`, perhaps partly hidden by `earth`; `blob`
/// is the hexagonal pattern's least slope in solar radii. `None` when the Earth hides
/// every direction of the rule.
///
/// Across the disk the lobe is narrower than its slope says when the phase angle g is
/// large: moving the Sun by β in the plane of `l` and `v` turns the half vector by β/2,
/// but out of that plane by β/(2·cos(g/2)). What the rule must resolve is the narrow
/// width, slope·cos(g/2) (a quarter of the slope at g = 151°).
///
/// With part of the disk behind the Earth the finer hexagonal pattern of
/// [`PENUMBRA_RINGS`] rings serves whatever the lobe, its hidden points dropped and the
/// others' weights renormalised to 1.
fn disk_rule(
    slope: f64,
    l: DVec3,
    v: DVec3,
    sun_radius: f64,
    earth: Option<EarthDisk>,
    blob: f64,
) -> Option<Rule> {
    if let Some(earth) = earth.filter(|e| angle(l, e.dir) < sun_radius + e.radius) {
        let blob = blob * sun_radius * hex_spacing(PENUMBRA_RINGS) / hex_spacing(RINGS);
        let dirs: Vec<(f64, DVec3)> = disk_directions(penumbra_points(), l, sun_radius)
            .filter(|&(_, d)| !earth.hides(d))
            .collect();
        let total: f64 = dirs.iter().map(|p| p.0).sum();
        if dirs.is_empty() {
            return None;
        }
        return Some(Rule {
            dirs: dirs.into_iter().map(|(w, d)| (w / total, d)).collect(),
            slope_in: slope.max(blob),
            blob: Some(blob),
        });
    }
    let width = slope * 0.5 * (l + v).length() / sun_radius;
    let (points, blob) = match SMOOTH_RULES.iter().position(|r| width >= r.0) {
        Some(k) => (&smooth_rules()[k][..], None),
        None => (hex_points(), Some(blob * sun_radius)),
    };
    Some(Rule {
        dirs: disk_directions(points, l, sun_radius).collect(),
        slope_in: blob.map_or(slope, |b| slope.max(b)),
        blob,
    })
}

/// The specular part `spec` (RMS slope `slope`) with its lobe widened to `to` where
/// narrower.
fn widened(spec: Brdf, slope: f64, to: f64) -> Brdf {
    if to > slope {
        spec.widened(to)
    } else {
        spec
    }
}

/// The rule's weights and directions on the disk of angular radius `sun_radius` (rad)
/// about `l`.
fn disk_directions(
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

/// [`projected_eclipsed`] with the smallest lobe slope per direction of the hexagonal
/// pattern given as `blob` solar radii (for tuning and tests).
#[doc(hidden)]
pub fn projected_with(
    brdf: &Brdf,
    frame: &Frame,
    l: DVec3,
    v: DVec3,
    sun_radius: f64,
    earth: Option<EarthDisk>,
    blob: f64,
) -> f64 {
    let point = || brdf.projected(frame, l, v);
    let Some(slope) = brdf.lobe_slope() else {
        return point();
    };
    if sun_radius.is_nan() || sun_radius <= 0.0 || slope > WIDE_LOBE * sun_radius {
        return point();
    }
    // The Sun direction that would mirror into `v`; the glint lives within the disk
    // radius plus the lobe's reach of it (the widest blob's, for any rule).
    let n = frame.n;
    let mirror = 2.0 * n.dot(v) * n - v;
    if n.dot(v) <= 0.0 || angle(mirror, l) > sun_radius + 2.0 * TAIL * slope.max(blob * sun_radius)
    {
        return point();
    }
    SunLight::build(brdf, l, v, sun_radius, earth, blob).projected(frame)
}

#[cfg(test)]
mod tests {
    use super::*;

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

    /// The average of `brdf.projected` over the disk by a fine polar midpoint grid: the
    /// reference the rules are held to.
    fn disk_average(brdf: &Brdf, frame: &Frame, l: DVec3, v: DVec3, rho: f64) -> f64 {
        let (a, b) = orthonormal_basis(l);
        let (nr, nt) = (80, 160);
        let mut sum = 0.0;
        for i in 0..nr {
            let r = (i as f64 + 0.5) / nr as f64;
            for j in 0..nt {
                let t = (j as f64 + 0.5) / nt as f64 * std::f64::consts::TAU;
                let (sr, cr) = (r * rho).sin_cos();
                let d = l * cr + (a * t.cos() + b * t.sin()) * sr;
                // cell area r·dr·dθ over the disk's π
                sum += brdf.projected(frame, d, v) * r * 2.0 / (nr * nt) as f64;
            }
        }
        sum
    }

    #[test]
    fn smooth_lobes_average_the_disk_and_wide_ones_need_not() {
        // Faces from the glint out to the disk's reach, pure lobes (kd = 0, so the
        // specular part is all there is), at phase 48° and 150°, where the lobe's width
        // across the disk is slope·cos(g/2) (0.91 and 0.26 of it). Each smooth rule, at
        // its least width and at 1.5 times that, is held to 3e−4 of the glint's peak
        // (measured ≤ 2.1e−4), the last to 7e−4 (5.2e−4); the 37 hexagonal points would
        // miss by 2e−3 to 2.4e−2 there. At 48° past WIDE_LOBE a point Sun is held to
        // its predicted miss ρ²(1 + 1/cos²(g/2))/(16δ²) (7.9e−3 at 4.16 ρ), a fifth to
        // spare.
        use crate::brdf::{RoughConductor, SeedMicrofacet};
        let rho = 4.65e-3;
        let l = DVec3::new(0.3, -0.2, 0.9).normalize();
        for (v, point_sun_too) in [
            (DVec3::new(-0.4, 0.1, 0.8), true),
            (DVec3::new(-0.94, 0.1, -0.85), false),
        ] {
            let v = v.normalize();
            let across = 0.5 * (l + v).length();
            let glint = (l + v).normalize();
            let axis = glint.cross(DVec3::X).normalize();
            let mut cases = vec![];
            for (k, &(width, _, _)) in SMOOTH_RULES.iter().enumerate() {
                let bound = if k + 1 == SMOOTH_RULES.len() {
                    7e-4
                } else {
                    3e-4
                };
                for w in [width, 1.5 * width] {
                    if w / across <= WIDE_LOBE {
                        cases.push((w / across, bound));
                    }
                }
            }
            if point_sun_too {
                let miss = |radii: f64| (1.0 + 1.0 / (across * across)) / (16.0 * radii * radii);
                cases.push((1.04 * WIDE_LOBE, 1.2 * miss(1.04 * WIDE_LOBE)));
            }
            for (radii, bound) in cases {
                let slope = radii * rho;
                for brdf in [
                    Brdf::SeedMicrofacet(SeedMicrofacet::new(0.0, 0.5, slope, 0.18, 3.6)),
                    Brdf::RoughConductor(RoughConductor::new(slope, 1.1, 6.8, 0.0)),
                ] {
                    let frame_at = |tilt: f64| {
                        let n = glam::DQuat::from_axis_angle(axis, tilt) * glint;
                        Frame {
                            n,
                            t: orthonormal_basis(n).0,
                        }
                    };
                    let peak = disk_average(&brdf, &frame_at(0.0), l, v, rho);
                    let light = SunLight::new(&brdf, l, v, rho);
                    for k in 0..=24 {
                        // the face's tilt from the glint: out to 0.6 of the reach
                        // (mirror angle 2·tilt), where the lobe is down to e^−13
                        let tilt = k as f64 / 24.0 * 0.6 * (rho + 2.0 * TAIL * slope) / 2.0;
                        let frame = frame_at(tilt);
                        let exact = disk_average(&brdf, &frame, l, v, rho);
                        let got = light.projected(&frame);
                        assert!(
                            (got - exact).abs() <= bound * peak,
                            "{brdf:?} phase {:.0}° tilt {tilt:.2e}: {got} vs disk {exact} \
                             (peak {peak})",
                            l.dot(v).acos().to_degrees()
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn sun_light_is_projected_for_every_face() {
        // The per-epoch form must give the per-face function's values (bit for bit up to
        // the order of a sum): narrow and wide lobes, faces from the glint out to 0.2 rad
        // (past the disk test's reach of 0.125 rad in the mirror angle for slope 0.01).
        use crate::brdf::{Lambert, RoughConductor, SeedMicrofacet};
        let l = DVec3::new(0.3, -0.2, 0.9).normalize();
        let v = DVec3::new(-0.4, 0.1, 0.8).normalize();
        let rho = 4.65e-3;
        let glint_normal = (l + v).normalize();
        let brdfs = [
            Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.5, 0.01, 0.18, 3.6)),
            Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.5, 0.3, 0.18, 3.6)),
            Brdf::RoughConductor(RoughConductor::new(1e-4, 1.1, 6.8, 0.05)),
            Brdf::Lambert(Lambert { albedo: 0.3 }),
        ];
        for brdf in &brdfs {
            let light = SunLight::new(brdf, l, v, rho);
            for k in 0..200 {
                let t = k as f64 * 0.0137;
                let n = (glint_normal
                    + DVec3::new(t.sin(), (1.7 * t).cos() - 1.0, 0.0) * (0.001 * k as f64))
                    .normalize();
                let (tx, _) = orthonormal_basis(n);
                let frame = Frame { n, t: tx };
                let a = light.projected(&frame);
                let b = projected(brdf, &frame, l, v, rho);
                assert!(
                    (a - b).abs() <= 1e-12 * b.abs().max(1e-300),
                    "{brdf:?} face {k}: {a} vs {b}"
                );
            }
        }
    }
}
