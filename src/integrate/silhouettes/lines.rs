//! The faces that fold lines along one direction d cross ([`crossing`]): a fold's
//! shadow falls on the faces below it whose polygons its projection along d crosses.
//! Each crossing is kept as a line in the receiving face's own plane ([`Line`]), with
//! the jump in the number of sheets across it. Which folds a patch's faces are tested
//! against comes from the folds' tree ([`super::fold_tree`]).

use super::folds::Fold;
use super::polygons::{orient, segment_meets, Polygons};
use glam::{DVec2, DVec3};

/// A fold's shadow on a face, in the face's plane coordinates (m): crossing it from its
/// right (of p → q) to its left adds `jump` sheets above the point.
#[derive(Debug, Clone, Copy)]
pub struct Line {
    pub p: DVec2,
    pub q: DVec2,
    pub jump: i32,
    /// Whether the face may turn from lit to dark across it. A valley's shadow does not on
    /// a face outside the valley's notch ([`outside_notch`]): the solid lies above both
    /// sides of it, so the count is at least 1 on both. Hence
    /// on a part of a face that no bounding line crosses the count is zero everywhere or
    /// nowhere: a face is cut along its bounding lines only, and a cell's count (at its
    /// centroid, through every line) decides all of it.
    pub bounds: bool,
}

/// What [`crossing`] needs of a direction: d, its basis across (u, w) with u × w = d,
/// and the rounding scales.
#[derive(Clone, Copy)]
pub struct Across {
    pub d: DVec3,
    pub u: DVec3,
    pub w: DVec3,
    /// Height (m) above a face that counts as in front of it.
    pub eps: f64,
    /// Distance (m) within which a line counts as touching a face.
    pub tol: f64,
}

impl Default for Across {
    fn default() -> Self {
        Across {
            d: DVec3::Z,
            u: DVec3::X,
            w: DVec3::Y,
            eps: 0.0,
            tol: 0.0,
        }
    }
}

/// A receiving face as [`crossing`] tests folds against it, read once per face rather
/// than once per fold: its index, unit normal, a point of its plane (m), 1 / (n·d) (a
/// receiver faces along d or against it, never edge-on: n·d is not near zero), and its
/// corners across d when it is one polygon.
#[derive(Clone, Copy)]
pub struct Receiver<'c> {
    f: usize,
    n: DVec3,
    o: DVec3,
    inv_nd: f64,
    across: Option<&'c [DVec2]>,
}

impl<'c> Receiver<'c> {
    /// Face `f` receiving along unit `d`; `across`: its corners across d when it is one
    /// polygon (the test is then made there, where distances are never longer than in
    /// the face's plane, so a line within `tol` of the face there is kept, never one
    /// within it in the plane lost).
    #[inline]
    pub fn new(polys: &Polygons, f: usize, d: DVec3, across: Option<&'c [DVec2]>) -> Self {
        let n = polys.normal[f];
        Receiver {
            f,
            n,
            o: polys.point[f],
            inv_nd: 1.0 / n.dot(d),
            across,
        }
    }
}

/// The shadow of fold `fold` on face `r` when it crosses one of the face's polygons
/// (within `tol`) above the face's plane, as a line in the face's plane.
#[inline]
pub fn crossing(polys: &Polygons, r: &Receiver, fold: &Fold, dir: &Across) -> Option<Line> {
    let Across { d, eps, tol, .. } = *dir;
    let Receiver {
        f,
        n,
        o,
        inv_nd,
        across,
    } = *r;
    // heights of the fold's ends above the face's plane, along d
    let sa = n.dot(fold.a - o) * inv_nd;
    let sb = n.dot(fold.b - o) * inv_nd;
    if sa <= eps && sb <= eps {
        return None;
    }
    // the part of the fold above the plane, as a range of its parameter
    let (mut t0, mut t1) = (0.0, 1.0);
    if sa <= eps {
        t0 = (eps - sa) / (sb - sa);
    } else if sb <= eps {
        t1 = 1.0 - (eps - sb) / (sa - sb);
    }
    // n·d has the sign of 1 / (n·d)
    let along = inv_nd > 0.0;
    if let Some(corners) = across {
        let e = fold.pb - fold.pa;
        if !segment_meets(fold.pa + e * t0, fold.pa + e * t1, corners, tol, along) {
            return None;
        }
    }
    // along d onto the plane: linear in the fold's parameter, so its ends' images
    // give the clipped part's
    let (ea, eb) = (polys.to2(f, fold.a - d * sa), polys.to2(f, fold.b - d * sb));
    let (p, q) = (ea + (eb - ea) * t0, ea + (eb - ea) * t1);
    if across.is_none() && !polys.segment_meets_face(f, p, q, tol) {
        return None;
    }
    // The plane's coordinates turn the way (u, w) does seen along d when the face's
    // normal faces along d: u_f × w_f = n, so the map between them has the sign of n·d.
    let jump = if along { fold.jump } else { -fold.jump };
    Some(Line {
        p,
        q,
        jump,
        bounds: fold.bounds || !outside_notch(polys, f, fold, eps),
    })
}

/// Does face `f` lie wholly outside the notch of valley `fold` (the wedge in front of both
/// its faces' planes)? A ray from a point outside the notch that passes the valley's edge
/// goes through the solid on either side of it, so the valley's shadow cannot turn such a
/// point from lit to dark; a ray that starts inside the notch may leave it on one side of
/// the edge through no solid at all, so there the shadow bounds light like any fold's.
/// Sufficient: every corner of `f` on or behind (within `eps`, m) one of the two planes.
fn outside_notch(polys: &Polygons, f: usize, fold: &Fold, eps: f64) -> bool {
    let behind = |side: u32| {
        let n = polys.normal[side as usize];
        polys
            .of(f)
            .flat_map(|k| polys.corners3(k))
            .all(|&v| n.dot(v - fold.a) <= eps)
    };
    behind(fold.faces.0) || behind(fold.faces.1)
}

/// The sheets added to the count along the path from `x` to `y` (in a face's plane) by
/// the lines it crosses. Ends shared by two lines (a polyline's joints) are put on one
/// side of the path by one test, so a path through a joint crosses exactly one of them.
#[inline]
pub fn crossed(lines: &[Line], x: DVec2, y: DVec2) -> i32 {
    // all four sides found, with no branch: which test ends a line is hard to predict
    let mut n = 0;
    for l in lines {
        let (sx, sy) = (orient(l.p, l.q, x) > 0.0, orient(l.p, l.q, y) > 0.0);
        let (sp, sq) = (orient(x, y, l.p) > 0.0, orient(x, y, l.q) > 0.0);
        let across = i32::from(sx != sy) & i32::from(sp != sq);
        let sign = 2 * i32::from(sy) - 1;
        n += across * sign * l.jump;
    }
    n
}

/// Joins the ends of `lines` that lie within `snap` (m) of an end of a contact's line
/// (`lines[contacts..]` are the contacts'), each moved onto it: where another piece's
/// fold edge pierces a face, its line and two of the piece's contacts end at one point,
/// but computed apart their ends differ by rounding, and a path through the gap between
/// them would cross neither ([`crossed`] counts a joint's lines right only where they
/// share the end exactly). The face's contacts are few: each is compared with every line.
pub fn join_at_contacts(lines: &mut [Line], contacts: usize, snap: f64) {
    let snap2 = snap * snap;
    for i in contacts..lines.len() {
        for end in [lines[i].p, lines[i].q] {
            for (j, l) in lines.iter_mut().enumerate() {
                if j == i {
                    continue;
                }
                if (l.p - end).length_squared() <= snap2 {
                    l.p = end;
                }
                if (l.q - end).length_squared() <= snap2 {
                    l.q = end;
                }
            }
        }
    }
}

/// The least distance (m) from `x` to any of `lines`.
pub fn clearance(lines: &[Line], x: DVec2) -> f64 {
    lines
        .iter()
        .map(|l| {
            let e = l.q - l.p;
            let t = if e.length_squared() > 0.0 {
                ((x - l.p).dot(e) / e.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (l.p + e * t - x).length()
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_crosses_one_of_two_lines_that_share_an_end() {
        // a polyline bent at (1, 0), jump 1 on its left
        let j = DVec2::new(1.0, 0.0);
        let lines = [
            Line {
                p: DVec2::new(0.0, -1.0),
                q: j,
                jump: 1,
                bounds: true,
            },
            Line {
                p: j,
                q: DVec2::new(0.0, 1.0),
                jump: 1,
                bounds: true,
            },
        ];
        // from outside the bend (right of both) to inside it, straight through the joint
        let n = crossed(&lines, DVec2::new(2.0, 0.0), DVec2::new(0.0, 0.0));
        assert_eq!(n, 1);
        // and back
        assert_eq!(
            crossed(&lines, DVec2::new(0.0, 0.0), DVec2::new(2.0, 0.0)),
            -1
        );
        // past the bend without crossing
        assert_eq!(
            crossed(&lines, DVec2::new(2.0, 2.0), DVec2::new(2.0, -2.0)),
            0
        );
        assert!((clearance(&lines, DVec2::new(2.0, 0.0)) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn a_folds_line_that_ends_a_rounding_short_of_a_contact_is_joined_to_it() {
        // A contact from (0, 0) to the pierce point (1, 0), and the piercing fold's line
        // from there on, both with the covered side on their left: one boundary. The
        // fold's end computed apart lies 2e-9 m off the contact's (as on the held-out
        // truss, whose tolerance is ~4e-9 m).
        let line = |p: DVec2, q: DVec2| Line {
            p,
            q,
            jump: 1,
            bounds: true,
        };
        let mut lines = [
            line(DVec2::new(1.0 + 2e-9, 1e-9), DVec2::new(2.0, 1.0)),
            line(DVec2::ZERO, DVec2::new(1.0, 0.0)),
        ];
        // a path across the boundary through the gap crosses neither line, one beside
        // it crosses the contact
        let (below, above) = (DVec2::new(1.0 + 1e-9, -1.0), DVec2::new(1.0 + 1e-9, 0.5));
        let (below_far, above_far) = (DVec2::new(0.5, -1.0), DVec2::new(0.5, 1.0));
        assert_eq!(crossed(&lines, below, above), 0);
        assert_eq!(crossed(&lines, below_far, above_far), 1);
        join_at_contacts(&mut lines, 1, 1e-8);
        assert_eq!(lines[0].p, DVec2::new(1.0, 0.0));
        assert_eq!(
            lines[1].q,
            DVec2::new(1.0, 0.0),
            "the contact does not move"
        );
        assert_eq!(crossed(&lines, below, above), 1);
        assert_eq!(crossed(&lines, below_far, above_far), 1);
        // an end farther than the snap stays where it is
        let mut apart = [
            line(DVec2::new(1.0, 1e-6), DVec2::new(2.0, 1.0)),
            line(DVec2::ZERO, DVec2::new(1.0, 0.0)),
        ];
        join_at_contacts(&mut apart, 1, 1e-8);
        assert_eq!(apart[0].p, DVec2::new(1.0, 1e-6));
    }
}
