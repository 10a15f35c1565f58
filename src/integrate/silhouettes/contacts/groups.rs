//! The contacts of an articulated mesh between groups of triangles that move apart (the
//! body, each link), found anew for each pose ([`GroupContacts`]).

use super::join::join_pieces;
use super::meet::meet;
use super::search::box_of;
use super::Contact;
use crate::geometry::Mesh;
use crate::integrate::silhouettes::level_grid::{overlap, LevelGrid};
use glam::DVec3;

/// Per group of triangles that move as one (the body, each articulated link): where its
/// triangles meet another group's, found anew for each pose without the pairs inside a
/// group. The body's grid is built once: it does not move.
pub(in crate::integrate::silhouettes) struct GroupContacts {
    /// Per group: its triangles (mesh indices).
    members: Vec<Vec<u32>>,
    /// The body's (group 0's) boxes, widened by the tolerance they were built with,
    /// binned.
    body: Option<LevelGrid>,
}

impl GroupContacts {
    /// `group`: per triangle, its group (0 the body, which never moves, then the links);
    /// `groups`: how many.
    pub fn build(mesh: &Mesh, group: &[u32], groups: usize, tol: f64) -> GroupContacts {
        let mut members = vec![Vec::new(); groups];
        for (t, &g) in group.iter().enumerate() {
            members[g as usize].push(t as u32);
        }
        let body = (groups > 1 && !members[0].is_empty()).then(|| {
            let boxes: Vec<_> = members[0]
                .iter()
                .map(|&t| box_of(&mesh.corners(t as usize), tol))
                .collect();
            LevelGrid::build(&boxes, tol)
        });
        GroupContacts { members, body }
    }

    /// The contacts between triangles of two groups, `corners` (per triangle, m) posed
    /// (the body's as built), as [`contact_segments`] finds them on the posed mesh:
    /// the same pairs (their boxes widened by `tol` overlap, they meet) and segments.
    /// No two groups may share a vertex.
    pub fn contacts(
        &self,
        corners: &[[DVec3; 3]],
        tri_face: &[u32],
        tol: f64,
    ) -> Vec<(u32, Contact)> {
        let ng = self.members.len();
        let mut pairs = Vec::new();
        let mut stamp: Vec<u32> = Vec::new();
        for g in 0..ng {
            for h in g + 1..ng {
                // the smaller group's triangles asked against the larger's grid: the
                // body's as built, a link's binned for this pose
                let (small, large) = if g == 0 || self.members[h].len() <= self.members[g].len() {
                    (h, g)
                } else {
                    (g, h)
                };
                let (a, b) = (&self.members[small], &self.members[large]);
                if a.is_empty() || b.is_empty() {
                    continue;
                }
                let built;
                let grid = match (&self.body, large) {
                    (Some(grid), 0) => grid,
                    _ => {
                        let boxes: Vec<_> = b
                            .iter()
                            .map(|&t| box_of(&corners[t as usize], tol))
                            .collect();
                        built = LevelGrid::build(&boxes, tol);
                        &built
                    }
                };
                stamp.clear();
                stamp.resize(b.len(), u32::MAX);
                for &s in a {
                    let bs = box_of(&corners[s as usize], tol);
                    // what a box binned within `tol` of it can share a cell with
                    let ask = (bs.0 - DVec3::splat(tol), bs.1 + DVec3::splat(tol));
                    grid.overlapping(ask, |k| {
                        if std::mem::replace(&mut stamp[k as usize], s) == s {
                            return;
                        }
                        let t = b[k as usize];
                        if !overlap(bs, box_of(&corners[t as usize], tol)) {
                            return;
                        }
                        let (lo, hi) = (s.min(t), s.max(t));
                        let (cl, ch) = (&corners[lo as usize], &corners[hi as usize]);
                        if let Some(seg) = meet(cl, ch, tol) {
                            pairs.push((lo, hi, seg));
                        }
                    });
                }
            }
        }
        pairs.sort_unstable_by_key(|&(s, t, _)| (s, t));
        join_pieces(&pairs, |t| corners[t], tri_face, tol)
    }
}
