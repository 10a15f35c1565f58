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
//! - A lobe narrower still images the disk itself, sharp edge and all: the glint is the
//!   lobe's whole mass (its value at the mirror direction times its Gaussian volume)
//!   times the share of the lobe inside the disk, computed exactly for a Gaussian
//!   (see `image`). Its edge is as sharp as the lobe, at every phase.
//! - Where that cannot hold, a hexagonal pattern of directions spread evenly over the
//!   disk averages the lobe: for a face so near grazing that its horizon cuts the lobe
//!   ([`HEX_POINTS`] directions), and while the Earth hides part of the disk (penumbra:
//!   a finer pattern, [`PENUMBRA_RINGS`], with its hidden points dropped, averaging over
//!   the visible part only, [`SunLight::eclipsed`]). Each direction's lobe is widened to
//!   a blob ([`BLOB`]) so that the samples blend into one image, keeping each lobe's
//!   normalisation, and across the plane of Sun and observer widened further, by
//!   1/cos(g/2) at phase g, so that it stays round in the reflected direction.
//!
//! Where things are: `cubature` (the points of every rule on the unit disk, and their
//! directions on the sky), `rule` (which rule an epoch gets, in penumbra too), `image`
//! (the disk's image through a narrow lobe), `penumbra` (the Earth's disk and the
//! directions it hides), `blob` (one direction of a rule, its lobe widened and squeezed);
//! here the constants, [`SunLight`] and the `projected` functions.

mod blob;
mod cubature;
mod image;
mod penumbra;
mod rule;

pub use penumbra::EarthDisk;

use super::{Brdf, Directions, Fixed, Frame};
use crate::geometry::Cone;
use blob::{sample, widened, Sample};
use glam::DVec3;
use image::Image;
use rule::{disk_rule, DiskRule};

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
/// and the disk's image (`image`) serves.
pub const SMOOTH_RULES: [(f64, usize, usize); 4] =
    [(0.8, 0, 0), (0.4, 3, 8), (0.3, 3, 10), (0.2, 4, 12)];
/// Rings of the hexagonal pattern of directions on the disk, for faces whose horizon cuts
/// a narrow lobe (the pattern [`BLOB`] was tuned on; the penumbra pattern's blobs are
/// scaled by its spacing against this one's).
pub const RINGS: usize = 3;
/// Directions of the hexagonal pattern: 1 + 3·RINGS·(RINGS + 1).
pub const HEX_POINTS: usize = 1 + 3 * RINGS * (RINGS + 1);
/// Rings of the finer hexagonal pattern used while the Earth hides part of the disk
/// (127 directions, spacing 0.17 ρ): the points behind the Earth are dropped, so the
/// pattern's spacing is how sharply the Earth's limb is drawn across the glint. Penumbra
/// lasts a few epochs of an eclipse, so the cost does not count.
pub const PENUMBRA_RINGS: usize = 6;
/// Smallest lobe RMS slope used for one direction of a hexagonal pattern, in solar radii
/// (for the 37-direction pattern of [`RINGS`]; scaled by the spacing for others). The lobe's
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
    specular: Specular,
}

/// The specular part near the glint.
#[derive(Debug, Clone)]
enum Specular {
    /// Averaged by a rule's points.
    Points(Points),
    /// The disk's image through a lobe much narrower than it; for faces whose horizon
    /// cuts the lobe, the hexagonal pattern's points (`grazing`).
    Image { image: Image, grazing: Points },
}

/// A rule's directions: the specular part `spec`, widened to the blob's slope in the
/// Sun–observer plane where narrower (hexagonal patterns), and each direction with its
/// weight and stretch.
#[derive(Debug, Clone)]
struct Points {
    spec: Brdf,
    dirs: Vec<Sample>,
}

impl Points {
    fn new(brdf: &Brdf, slope: f64, rule: &rule::Rule, v: DVec3, sun_radius: f64) -> Points {
        let spec = widened(brdf.split(false), slope, rule.slope_in);
        let dirs = rule
            .dirs
            .iter()
            .map(|&(w, d)| sample(&spec, w, d, v, slope, rule.blob, sun_radius))
            .collect();
        Points { spec, dirs }
    }

    /// Σ w·f·cosθi·cosθr over the directions, sr⁻¹.
    #[inline]
    fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        self.dirs
            .iter()
            .map(|d| d.projected_given(&self.spec, frame, cr))
            .sum()
    }
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
        let disk = match brdf.lobe_slopes() {
            Some((slope, widest))
                if !sun_radius.is_nan() && sun_radius > 0.0 && slope <= WIDE_LOBE * sun_radius =>
            {
                disk_rule(slope, l, v, sun_radius, earth, blob).and_then(|rule| {
                    let diffuse = brdf.split(true);
                    let points = |rule: &rule::Rule| Points::new(brdf, slope, rule, v, sun_radius);
                    let reach =
                        |rule: &rule::Rule| sun_radius + 2.0 * TAIL * rule.slope_in.max(widest);
                    let (specular, reach) = match rule {
                        DiskRule::Points(rule) => (Specular::Points(points(&rule)), reach(&rule)),
                        DiskRule::Image { grazing } => {
                            let least_cos = LEAST_COS_HALF_PHASE * sun_radius;
                            let image = Image::new(brdf.split(false), l, v, sun_radius, least_cos)?;
                            let specular = Specular::Image {
                                image,
                                grazing: points(&grazing),
                            };
                            (specular, reach(&grazing))
                        }
                    };
                    Some(Disk {
                        cos_reach: if reach >= std::f64::consts::PI {
                            -1.0
                        } else {
                            reach.cos()
                        },
                        diffuse_dirs: Directions::new(&diffuse, l, v),
                        diffuse,
                        specular,
                    })
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

    /// The Sun's f·cosθi·cosθr over a cone of normals that all face the view, where it
    /// is linear: `Some(L)` with [`SunLight::projected_given`] = (n·L)(n·v) for every
    /// normal n of `cone` (L = k·l, zero when the Sun is below every normal), `None` where
    /// the glint's reach or a lobe may touch a normal of it ([`Directions::linear_over`]).
    pub fn linear_over(&self, cone: &Cone) -> Option<DVec3> {
        if let Some(disk) = &self.disk {
            // the mirror direction's reach: (2(n·v)n − v)·l = 2(n·v)(n·l) − v·l, at most
            // this where n·v > 0 (n·l's bound taken at 0 when it is negative)
            let most =
                2.0 * cone.max_dot(self.v) * cone.max_dot(self.l).max(0.0) - self.v.dot(self.l);
            if most >= disk.cos_reach {
                return None;
            }
        }
        self.point.dirs.linear_over(cone).map(|k| k * self.l)
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

impl Disk {
    /// The disk's average near the glint, sr⁻¹.
    #[inline]
    fn projected_given(&self, frame: &Frame, cr: f64) -> f64 {
        let specular = match &self.specular {
            Specular::Points(points) => points.projected_given(frame, cr),
            Specular::Image { image, grazing } => image
                .projected_given(frame, cr)
                .unwrap_or_else(|| grazing.projected_given(frame, cr)),
        };
        self.diffuse_dirs.projected_given(&self.diffuse, frame, cr) + specular
    }
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

    use crate::geometry::orthonormal_basis;

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
