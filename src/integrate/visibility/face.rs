//! Each face's geometry for the tests ([`FaceGeom`]): its plane, bounding sphere and
//! vertices, the convex polygons it is clipped and sampled as, and what the convex parts
//! and caps around it settle for it (filled in by [`super::Visibility::build`]).

use super::VisibilityMode;
use crate::geometry::Faces;
use crate::scene::Scene;
use glam::DVec3;
use rayon::prelude::*;

/// How one convex part shadows one face.
#[derive(Debug, Clone)]
pub(super) struct PartShadow {
    pub(super) part: u32,
    /// Sides of the face (front, back) whose shadows it casts whole.
    pub(super) sides: [bool; 2],
    /// Sides it lies wholly behind: none of its faces can block them.
    pub(super) behind: [bool; 2],
    /// The face's plane cuts the part: its shadow is that of the hull's part on the face's
    /// side, whose corners include `crossings`.
    pub(super) cut: bool,
    /// Where the part's edges cross the face's plane, m.
    pub(super) crossings: Vec<DVec3>,
}

/// Per-face geometry for the tests.
pub(super) struct FaceGeom {
    pub(super) normal: DVec3,
    /// Point on the plane (centroid), m.
    pub(super) centroid: DVec3,
    pub(super) radius: f64,
    /// Area, m².
    pub(super) area: f64,
    pub(super) two_sided: bool,
    /// Triangles to sample: the face's own, or — when the face is a convex polygon however
    /// finely it is meshed — a fan over its outline, so sampling cost follows the face's
    /// shape, not its tessellation.
    pub(super) pieces: Vec<[DVec3; 3]>,
    /// Their total area, m² (the face's area to rounding).
    pub(super) pieces_area: f64,
    /// The face's outline when it is a convex polygon (else empty): one polygon to project
    /// as a shadow or to clip, however finely the face is meshed.
    pub(super) outline: Vec<DVec3>,
    /// Distinct vertices of the face, for exact half-space tests.
    pub(super) vertices: Vec<DVec3>,
    /// Convex parts whose shadows on the face are cast whole (one hull each).
    pub(super) part_shadows: Vec<PartShadow>,
    /// Per side (front, back): parts that may hide that side whole along a direction
    /// ([`super::parts::cover_candidates`]).
    pub(super) covers: [Vec<u32>; 2],
    /// Per side (front, back): the face belongs to a cap with a lid and that side faces
    /// into the cap.
    pub(super) lid_side: [bool; 2],
    /// Per side: the lid alone decides what the face sees along any direction (it faces
    /// into a cap that nothing else can reach into, and no part is cast whole on it).
    pub(super) lid_only: [bool; 2],
    /// Per side: the face belongs to a convex part and that side faces away from it, so
    /// no face of the part can block it.
    pub(super) own_outside: [bool; 2],
    /// Index of its patch.
    pub(super) patch: u32,
}

/// Which side of a face is asked about: the one its normal points out of, or the other
/// (a two-sided material's back). Not [`super::proofs::Side`], a patch's relation to a
/// plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FaceSide {
    Front,
    Back,
}

impl FaceSide {
    /// Both sides, front first.
    pub const BOTH: [FaceSide; 2] = [FaceSide::Front, FaceSide::Back];

    /// +1 front, −1 back: the side's normal is the face's times this.
    #[inline]
    pub fn sign(self) -> f64 {
        match self {
            FaceSide::Front => 1.0,
            FaceSide::Back => -1.0,
        }
    }

    /// Where the side sits in a face's per-side arrays (`[_; 2]`): 0 front, 1 back.
    #[inline]
    pub fn index(self) -> usize {
        match self {
            FaceSide::Front => 0,
            FaceSide::Back => 1,
        }
    }
}

impl FaceGeom {
    /// The convex polygons the face is made of: its outline, or else its triangles.
    pub(super) fn polygons(&self) -> impl Iterator<Item = &[DVec3]> {
        let outline = (!self.outline.is_empty()).then_some(&self.outline[..]);
        let pieces = self.outline.is_empty().then_some(&self.pieces[..]);
        outline
            .into_iter()
            .chain(pieces.into_iter().flatten().map(|t| &t[..]))
    }

    /// The face as one convex polygon (its outline, or its one triangle); empty when it
    /// is none.
    pub(super) fn convex(&self) -> &[DVec3] {
        if self.outline.is_empty() && self.pieces.len() == 1 {
            &self.pieces[0][..]
        } else {
            &self.outline[..]
        }
    }
}

#[cfg(test)]
impl FaceGeom {
    /// A face of unit area with this plane and bounding sphere and nothing else (no
    /// pieces, vertices or parts), for tests to fill in.
    pub(super) fn bare(normal: DVec3, centroid: DVec3, radius: f64) -> FaceGeom {
        FaceGeom {
            normal,
            centroid,
            radius,
            area: 1.0,
            two_sided: false,
            pieces: Vec::new(),
            pieces_area: 0.0,
            outline: Vec::new(),
            vertices: Vec::new(),
            part_shadows: Vec::new(),
            covers: Default::default(),
            lid_side: [false; 2],
            lid_only: [false; 2],
            own_outside: [false; 2],
            patch: 0,
        }
    }
}

/// Each face's geometry for the visibility tests (pieces, outline, vertices), in
/// parallel; `per_patch` faces (in their spatial order) make a patch.
pub(super) fn face_geoms(
    scene: &Scene,
    faces: &Faces,
    corners: &[[DVec3; 3]],
    mode: VisibilityMode,
    per_patch: usize,
) -> Vec<FaceGeom> {
    faces
        .faces
        .par_iter()
        .enumerate()
        .map(|(i, f)| {
            let mut vertices: Vec<DVec3> = f
                .triangles
                .iter()
                .flat_map(|&t| corners[t as usize])
                .collect();
            sort_dedup(&mut vertices);
            let (pieces, outline) =
                pieces_of(f.normal, f.area, &f.triangles, corners, &vertices, mode);
            FaceGeom {
                normal: f.normal,
                centroid: f.centroid,
                radius: f.radius,
                area: f.area,
                two_sided: scene.materials[f.material as usize].two_sided,
                // a convex face's linear tests (which side of a plane) are decided by
                // its corners: a subdivided side keeps 4 vertices, not 81
                vertices: if outline.is_empty() {
                    vertices
                } else {
                    outline.clone()
                },
                pieces_area: pieces.iter().map(triangle_area).sum(),
                pieces,
                outline,
                part_shadows: Vec::new(),
                covers: Default::default(),
                lid_side: [false; 2],
                lid_only: [false; 2],
                own_outside: [false; 2],
                patch: (i / per_patch) as u32,
            }
        })
        .collect()
}

/// The triangles a face is sampled on, and its outline when it is a convex polygon (its
/// area equals its hull's). The triangles are a fan over that outline for a convex face
/// of more than two triangles, else the face's own. The centroid method always samples
/// the mesh's own triangles and needs no outline.
fn pieces_of(
    normal: DVec3,
    area: f64,
    triangles: &[u32],
    corners: &[[DVec3; 3]],
    vertices: &[DVec3],
    mode: VisibilityMode,
) -> (Vec<[DVec3; 3]>, Vec<DVec3>) {
    let own = || triangles.iter().map(|&t| corners[t as usize]).collect();
    if mode == VisibilityMode::Centroid {
        return (own(), Vec::new());
    }
    let (u, w) = crate::geometry::orthonormal_basis(normal);
    let origin = vertices[0];
    let plane_point = |v: &DVec3| ((*v - origin).dot(u), (*v - origin).dot(w));
    let mut pts: Vec<(f64, f64, usize)> = vertices
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let (x, y) = plane_point(v);
            (x, y, i)
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    // Andrew's monotone chain, counter-clockwise about `normal` (u × w = normal)
    let cross = |o: &(f64, f64, usize), a: &(f64, f64, usize), b: &(f64, f64, usize)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64, usize)> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64, usize)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for p in iter {
            while hull.len() >= start + 2
                && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(*p);
        }
        hull.pop();
    }
    if hull.len() < 3 {
        return (own(), Vec::new());
    }
    let hull_area: f64 = (1..hull.len() - 1)
        .map(|i| 0.5 * cross(&hull[0], &hull[i], &hull[i + 1]))
        .sum();
    if (hull_area - area).abs() > 1e-9 * area {
        return (own(), Vec::new()); // not convex (or holes): the mesh's triangles
    }
    let v = |h: &(f64, f64, usize)| vertices[h.2];
    let outline = hull.iter().map(v).collect();
    if triangles.len() <= 2 {
        return (own(), outline);
    }
    let fan = (1..hull.len() - 1)
        .map(|i| [v(&hull[0]), v(&hull[i]), v(&hull[i + 1])])
        .collect();
    (fan, outline)
}

/// Area of a triangle, m².
pub(super) fn triangle_area(t: &[DVec3; 3]) -> f64 {
    0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length()
}

/// Sorts points and drops exact repeats (the corners that neighbouring triangles share).
pub(super) fn sort_dedup(points: &mut Vec<DVec3>) {
    // equal points are the same point: no order among them to keep
    if points.len() > 4096 {
        points.par_sort_unstable_by(position_order);
    } else {
        points.sort_unstable_by(position_order);
    }
    points.dedup();
}

/// Points ordered by x, then y, then z: the order [`sort_dedup`] leaves, for bisection.
fn position_order(a: &DVec3, b: &DVec3) -> std::cmp::Ordering {
    a.to_array()
        .partial_cmp(&b.to_array())
        .unwrap_or(std::cmp::Ordering::Equal)
}
