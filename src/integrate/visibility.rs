//! Which part of a face is both lit and seen: shadowing and occlusion by the mesh itself.
//!
//! Per face and epoch, a direction (to the Sun, the Earth or the observer) is *clear*
//! when no possible occluder can lie along it: the possible occluders of a face are
//! found once per request (triangles with a vertex in front of the face's plane), and per
//! epoch each is tested against the half-infinite cylinder swept by the face's bounding
//! sphere along the direction. A face with every needed direction clear is wholly lit and
//! seen — exact, no rays. Only the rest are sampled with rays, refining each triangle
//! adaptively (4-way splits) until either the samples agree or a leaf is small enough
//! that mis-classifying all of it stays within the tolerance.

use crate::geometry::bvh::Occluder;
use crate::geometry::Faces;
use crate::scene::Scene;
use glam::DVec3;
use rayon::prelude::*;

/// How faces are sampled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VisibilityMode {
    /// Clear-direction classification, then adaptive refinement of uncertain faces.
    Adaptive,
    /// One ray per direction at each face's centroid (faces are single triangles).
    Centroid,
}

/// The directions of one epoch that matter for a face.
#[derive(Debug, Clone, Copy)]
pub struct Uncertain {
    /// Towards the observer (always needed).
    pub view: DVec3,
    /// Towards the Sun, when the face is sunlit.
    pub sun: Option<DVec3>,
    /// Representative earthshine direction, when earthshine reaches the face.
    pub earth: Option<DVec3>,
}

/// Possible occluders stored as a compressed list per face and side.
#[derive(Default)]
struct Candidates {
    offsets: Vec<u32>,
    items: Vec<u32>,
    /// Faces whose list would be too long: always sampled.
    all: Vec<bool>,
}

impl Candidates {
    fn of(&self, face: usize) -> Option<&[u32]> {
        if self.all[face] {
            None
        } else {
            Some(&self.items[self.offsets[face] as usize..self.offsets[face + 1] as usize])
        }
    }
}

struct FaceGeom {
    normal: DVec3,
    centroid: DVec3,
    radius: f64,
    triangles: Vec<u32>,
}

/// Ray-casting state built once per request.
pub struct Visibility {
    mode: VisibilityMode,
    occluder: Occluder,
    corners: Vec<[DVec3; 3]>,
    faces: Vec<FaceGeom>,
    /// Bounding spheres (centre, radius) of occluder clusters.
    clusters: Vec<(DVec3, f64)>,
    front: Candidates,
    back: Candidates,
}

/// More triangles than this are grouped into clusters for the candidate lists.
const MAX_CLUSTERS: usize = 4096;
/// Above this many candidate entries in all, faces are sampled without classification.
const MAX_CANDIDATE_ENTRIES: usize = 32_000_000;
/// Deepest refinement: leaves down to 4⁻¹⁰ ≈ 1e-6 of a triangle.
const MAX_DEPTH: u32 = 10;

impl Visibility {
    pub fn build(scene: &Scene, faces: &Faces, mode: VisibilityMode) -> Visibility {
        let mesh = &scene.mesh;
        let occluder = Occluder::build(mesh);
        let corners: Vec<[DVec3; 3]> = (0..mesh.triangles.len()).map(|i| mesh.corners(i)).collect();
        let geoms: Vec<FaceGeom> = faces
            .faces
            .iter()
            .map(|f| FaceGeom {
                normal: f.normal,
                centroid: f.centroid,
                radius: f.radius,
                triangles: f.triangles.clone(),
            })
            .collect();
        let (_, scale) = mesh.bounding_sphere();
        let tol = 1e-9 * scale;

        // Clusters of triangles (one per triangle for small meshes) with the face each
        // triangle belongs to, so a face never counts itself as an occluder.
        let mut face_of = vec![0u32; mesh.triangles.len()];
        for (fi, f) in faces.faces.iter().enumerate() {
            for &t in &f.triangles {
                face_of[t as usize] = fi as u32;
            }
        }
        let clusters_of_tris: Vec<Vec<u32>> = cluster_triangles(&corners);
        let clusters: Vec<(DVec3, f64)> = clusters_of_tris
            .iter()
            .map(|tris| {
                let pts = tris.iter().flat_map(|&t| corners[t as usize]);
                bounding_sphere(pts)
            })
            .collect();

        let side_lists = |side: f64| -> Candidates {
            let per_face: Vec<Option<Vec<u32>>> = geoms
                .par_iter()
                .enumerate()
                .map(|(fi, f)| {
                    if mode == VisibilityMode::Centroid {
                        return None;
                    }
                    let two_sided = scene.materials[faces.faces[fi].material as usize].two_sided;
                    if side < 0.0 && !two_sided {
                        return Some(Vec::new());
                    }
                    let n = f.normal * side;
                    let d = n.dot(f.centroid);
                    let list = (0..clusters.len() as u32)
                        .filter(|&c| {
                            let (cc, rc) = clusters[c as usize];
                            if n.dot(cc) - d + rc <= tol {
                                return false; // wholly behind the plane
                            }
                            clusters_of_tris[c as usize].iter().any(|&t| {
                                face_of[t as usize] != fi as u32
                                    && corners[t as usize].iter().any(|v| n.dot(*v) - d > tol)
                            })
                        })
                        .collect();
                    Some(list)
                })
                .collect();
            let total: usize = per_face.iter().flatten().map(Vec::len).sum();
            let mut c = Candidates {
                offsets: vec![0],
                items: Vec::new(),
                all: vec![false; per_face.len()],
            };
            for (fi, list) in per_face.into_iter().enumerate() {
                match list {
                    Some(l) if total <= MAX_CANDIDATE_ENTRIES => c.items.extend(l),
                    _ => c.all[fi] = true,
                }
                c.offsets.push(c.items.len() as u32);
            }
            c
        };
        let front = side_lists(1.0);
        let back = side_lists(-1.0);
        Visibility {
            mode,
            occluder,
            corners,
            faces: geoms,
            clusters,
            front,
            back,
        }
    }

    /// True when some possible occluder of `face` may lie along `dir`.
    fn may_block(&self, face: usize, cands: Option<&[u32]>, dir: DVec3) -> bool {
        let Some(cands) = cands else { return true };
        let f = &self.faces[face];
        cands.iter().any(|&c| {
            let (cc, rc) = self.clusters[c as usize];
            let w = cc - f.centroid;
            let t = w.dot(dir).max(0.0);
            let reach = f.radius + rc;
            (w - dir * t).length_squared() < reach * reach
        })
    }

    /// Area of `face` (m²) that is both seen and lit by the Sun, and both seen and lit by
    /// the earthshine direction, on side `side` (+1 front, −1 back); plus rays cast.
    /// `min_area` is the leaf size (m²) below which refinement stops.
    pub fn visible_area(&self, face: usize, side: f64, dirs: &Uncertain, min_area: f64) -> (f64, f64, u64) {
        let f = &self.faces[face];
        let n = f.normal * side;
        // Earthshine's representative direction may lie below the face while parts of
        // the Earth light it: no meaningful ray then, count it as unshadowed.
        let earth = dirs.earth.filter(|e| n.dot(*e) > 1e-3);
        let mut ctx = Sampler {
            vis: self,
            n,
            view: dirs.view,
            sun: dirs.sun,
            earth,
            check_view: true,
            check_sun: dirs.sun.is_some(),
            check_earth: earth.is_some(),
            min_area,
            rays: 0,
            a_sun: 0.0,
            a_earth: 0.0,
        };
        let area_of = |t: &[DVec3; 3]| 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
        let full_area: f64 = f.triangles.iter().map(|&t| area_of(&self.corners[t as usize])).sum();
        if self.mode == VisibilityMode::Centroid {
            for &t in &f.triangles {
                let c = &self.corners[t as usize];
                let bits = ctx.eval((c[0] + c[1] + c[2]) / 3.0);
                let a = area_of(c);
                ctx.a_sun += a * (bits & 1) as f64;
                ctx.a_earth += a * ((bits >> 1) & 1) as f64;
            }
            return (ctx.a_sun, ctx.a_earth, ctx.rays);
        }
        let cands = if side > 0.0 { self.front.of(face) } else { self.back.of(face) };
        ctx.check_view = self.may_block(face, cands, dirs.view);
        ctx.check_sun = ctx.sun.is_some_and(|d| self.may_block(face, cands, d));
        ctx.check_earth = ctx.earth.is_some_and(|d| self.may_block(face, cands, d));
        if !ctx.check_view && !ctx.check_sun && !ctx.check_earth {
            return (full_area, full_area, 0);
        }
        for &t in &f.triangles {
            let [a, b, c] = self.corners[t as usize];
            let (va, vb, vc) = (ctx.eval(a), ctx.eval(b), ctx.eval(c));
            ctx.refine([a, b, c], [va, vb, vc], area_of(&[a, b, c]), 0);
        }
        (ctx.a_sun, ctx.a_earth, ctx.rays)
    }
}

/// Adaptive sampler state for one face.
struct Sampler<'a> {
    vis: &'a Visibility,
    n: DVec3,
    view: DVec3,
    sun: Option<DVec3>,
    earth: Option<DVec3>,
    check_view: bool,
    check_sun: bool,
    check_earth: bool,
    min_area: f64,
    rays: u64,
    a_sun: f64,
    a_earth: f64,
}

impl Sampler<'_> {
    /// Bit 0: seen and sunlit; bit 1: seen and earthlit (or earthshine unshadowed).
    #[inline]
    fn eval(&mut self, p: DVec3) -> u8 {
        let occ = &self.vis.occluder;
        if self.check_view {
            self.rays += 1;
            if !occ.is_clear(p, self.n, self.view) {
                return 0;
            }
        }
        let mut bits = 0;
        if let Some(s) = self.sun {
            let lit = if self.check_sun {
                self.rays += 1;
                occ.is_clear(p, self.n, s)
            } else {
                true
            };
            bits |= lit as u8;
        }
        match self.earth {
            Some(e) => {
                let lit = if self.check_earth {
                    self.rays += 1;
                    occ.is_clear(p, self.n, e)
                } else {
                    true
                };
                bits |= (lit as u8) << 1;
            }
            None => bits |= 2,
        }
        bits
    }

    fn refine(&mut self, p: [DVec3; 3], v: [u8; 3], area: f64, depth: u32) {
        let m = (p[0] + p[1] + p[2]) / 3.0;
        let vm = self.eval(m);
        let uniform = v[0] == vm && v[1] == vm && v[2] == vm;
        // Big triangles of an uncertain face are split at least twice, so an occluder
        // whose shadow falls between the first samples is still likely to be seen.
        let forced = depth < 2 && area > 16.0 * self.min_area;
        if depth >= MAX_DEPTH || area <= self.min_area || (uniform && !forced) {
            // Leaf: corners weigh 1/6 each, the centroid 1/2 (exact for linear fields).
            for bit in 0..2 {
                let c = v.iter().map(|x| ((x >> bit) & 1) as f64).sum::<f64>() / 6.0 + ((vm >> bit) & 1) as f64 * 0.5;
                if bit == 0 {
                    self.a_sun += c * area;
                } else {
                    self.a_earth += c * area;
                }
            }
            return;
        }
        let ab = 0.5 * (p[0] + p[1]);
        let bc = 0.5 * (p[1] + p[2]);
        let ca = 0.5 * (p[2] + p[0]);
        let (vab, vbc, vca) = (self.eval(ab), self.eval(bc), self.eval(ca));
        let q = 0.25 * area;
        self.refine([p[0], ab, ca], [v[0], vab, vca], q, depth + 1);
        self.refine([ab, p[1], bc], [vab, v[1], vbc], q, depth + 1);
        self.refine([ca, bc, p[2]], [vca, vbc, v[2]], q, depth + 1);
        self.refine([ab, bc, ca], [vab, vbc, vca], q, depth + 1);
    }
}

/// Groups triangles into at most [`MAX_CLUSTERS`] spatially coherent clusters
/// (one per triangle when there are few).
fn cluster_triangles(corners: &[[DVec3; 3]]) -> Vec<Vec<u32>> {
    let n = corners.len();
    if n <= MAX_CLUSTERS {
        return (0..n as u32).map(|t| vec![t]).collect();
    }
    // Morton order of centroids, then equal chunks.
    let cents: Vec<DVec3> = corners.iter().map(|c| (c[0] + c[1] + c[2]) / 3.0).collect();
    let lo = cents.iter().fold(DVec3::splat(f64::INFINITY), |a, b| a.min(*b));
    let hi = cents.iter().fold(DVec3::splat(f64::NEG_INFINITY), |a, b| a.max(*b));
    let ext = (hi - lo).max(DVec3::splat(1e-300));
    let mut order: Vec<(u64, u32)> = cents
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let q = ((*c - lo) / ext * 1023.0).as_uvec3();
            (morton3(q.x, q.y, q.z), i as u32)
        })
        .collect();
    order.sort_unstable();
    let chunk = n.div_ceil(MAX_CLUSTERS);
    order.chunks(chunk).map(|c| c.iter().map(|&(_, i)| i).collect()).collect()
}

fn morton3(x: u32, y: u32, z: u32) -> u64 {
    fn spread(v: u32) -> u64 {
        let mut x = v as u64 & 0x3ff;
        x = (x | (x << 16)) & 0x30000ff;
        x = (x | (x << 8)) & 0x300f00f;
        x = (x | (x << 4)) & 0x30c30c3;
        x = (x | (x << 2)) & 0x9249249;
        x
    }
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

fn bounding_sphere(points: impl Iterator<Item = DVec3> + Clone) -> (DVec3, f64) {
    let (lo, hi) = points.clone().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    let c = 0.5 * (lo + hi);
    let r = points.map(|p| p.distance(c)).fold(0.0, f64::max);
    (c, r)
}
