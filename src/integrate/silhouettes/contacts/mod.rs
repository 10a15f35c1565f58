//! Where separate pieces of the mesh touch or cross (the *contacts*: a boom's foot on a
//! bus), found once per request: the segments where triangles of different faces meet as
//! separate pieces ([`contact_segments`]), and how the count of sheets above a face
//! changes across one along a direction ([`Contact::jump`]).
//!
//! In the order the work runs:
//! - [`search`]: the pairs of triangles that may meet, through grids of their boxes
//!   ([`PairSearch`], begun while the faces are renumbered and finished on every thread);
//! - [`meet`]: where two triangles meet as separate pieces (not as neighbours along an
//!   edge or around a corner), and the segment they share;
//! - [`join`]: the pairs' segments as contacts on both faces, a face's pieces along one
//!   other face joined into one segment;
//! - [`groups`]: for an articulated mesh, the contacts between groups that move apart,
//!   found anew for each pose ([`GroupContacts`]).

mod groups;
mod join;
mod meet;
mod search;

pub(super) use groups::GroupContacts;
pub(super) use search::PairSearch;
pub use search::TriangleGrid;

use crate::geometry::faces::WeldedEdge;
use crate::geometry::Mesh;
use glam::DVec3;

/// Where another piece meets a face: a segment in the face's plane (m), and the face of
/// the other piece that meets it along the segment with three points of that face (m):
/// its corners highest above and lowest below the receiving face's plane, or the corners
/// of its one triangle that meets it there. Above the face, the other face is a sheet on
/// one side of the segment: the count changes across it as across a fold
/// ([`Contact::jump`]).
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    pub a: DVec3,
    pub b: DVec3,
    pub other: [DVec3; 3],
    pub face: u32,
}

impl Contact {
    /// How many more sheets lie just left of the segment than just right of it (seen
    /// along `d` in the plane's coordinates of a face with unit normal `n` through `o`;
    /// `to2` maps a point of that plane to them); `blocks`: whether the other face's
    /// sheet counts along d. Zero when the other points lie below the plane along d.
    pub fn jump(
        &self,
        n: DVec3,
        o: DVec3,
        d: DVec3,
        eps: f64,
        blocks: bool,
        to2: impl Fn(DVec3) -> glam::DVec2,
    ) -> i32 {
        if !blocks {
            return 0;
        }
        let nd = n.dot(d);
        // the other points above the plane, along d
        let (mut sum, mut k) = (DVec3::ZERO, 0);
        for v in self.other {
            if n.dot(v - o) / nd > eps {
                sum += v;
                k += 1;
            }
        }
        if k == 0 {
            return 0;
        }
        let c = sum / k as f64;
        let onto = |x: DVec3| to2(x - d * (n.dot(x - o) / nd));
        let (pa, pb, pc) = (onto(self.a), onto(self.b), onto(c));
        let s = (pb - pa).perp_dot(pc - pa);
        if s > 0.0 {
            1
        } else if s < 0.0 {
            -1
        } else {
            0
        }
    }
}

/// Segments (m) where triangles of different faces meet as separate pieces
/// ([`meeting`]): each is recorded on both faces. Found through grids of the triangles'
/// boxes ([`LevelGrid`]).
/// With `group` (per triangle), only triangles of one group are paired: the contacts that
/// a rigid motion of each group carries along ([`GroupContacts`] finds the others).
/// `grid`: the mesh's [`TriangleGrid`] at `tol` when built already, else built here.
pub(super) fn contact_segments(
    mesh: &Mesh,
    (welded, edges): (&[u32], &[WeldedEdge]),
    tri_face: &[u32],
    group: Option<&[u32]>,
    tol: f64,
    grid: Option<TriangleGrid>,
) -> Vec<(u32, Contact)> {
    PairSearch::new(mesh, (welded, edges), tri_face, group, tol, grid)
        .finish()
        .on_faces(mesh, tri_face, tol)
}
