//! Cutting convex polygons in a face's plane: their edges as inward half-planes, a
//! split along a line, and where a convex piece lies against a convex polygon. What
//! [`super::Region`] cuts its pieces with.

use glam::DVec2;

/// Where a convex piece lies against a convex polygon given by its `edges` (point, unit
/// inward normal), within `eps` (m).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Relation {
    /// Wholly outside one edge (not every separated piece is found so).
    Apart,
    /// Inside every edge.
    Inside,
    Crossing,
}

/// One pass over the edges decides both: apart when the piece lies wholly outside one
/// edge, inside when wholly inside all. The piece's bounds `(lo, hi)` decide most edges
/// of a many-sided polygon without visiting its vertices.
pub(super) fn relation_to(
    piece: &[DVec2],
    (lo, hi): (DVec2, DVec2),
    edges: &[(DVec2, DVec2)],
    eps: f64,
) -> Relation {
    let mut inside = true;
    for &(a, m) in edges {
        // the bounding box's corners lowest and highest along m
        let (low, high) = corners_along(m, lo, hi);
        if m.dot(low - a) >= -eps {
            continue; // inside this edge
        }
        if m.dot(high - a) <= eps {
            return Relation::Apart;
        }
        let (l, h) = piece
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                let v = m.dot(*p - a);
                (l.min(v), h.max(v))
            });
        if h <= eps {
            return Relation::Apart;
        }
        inside &= l >= -eps;
    }
    if inside {
        Relation::Inside
    } else {
        Relation::Crossing
    }
}

/// The corners of the box `lo`..`hi` lowest and highest along `m`.
#[inline]
pub(super) fn corners_along(m: DVec2, lo: DVec2, hi: DVec2) -> (DVec2, DVec2) {
    let (lx, hx) = if m.x > 0.0 {
        (lo.x, hi.x)
    } else {
        (hi.x, lo.x)
    };
    let (ly, hy) = if m.y > 0.0 {
        (lo.y, hi.y)
    } else {
        (hi.y, lo.y)
    };
    (DVec2::new(lx, ly), DVec2::new(hx, hy))
}

/// Do the boxes `a` and `b` (lo, hi) overlap by no more than `eps` (m) along x or y?
pub(super) fn boxes_apart(a: (DVec2, DVec2), b: (DVec2, DVec2), eps: f64) -> bool {
    a.0.x >= b.1.x - eps || a.0.y >= b.1.y - eps || a.1.x <= b.0.x + eps || a.1.y <= b.0.y + eps
}

/// The edges of convex `poly` (counter-clockwise when `ccw`, else clockwise) into `out`:
/// a point on each and its unit inward normal; edges no longer than `eps` (m) are left
/// out.
pub(super) fn inward_edges(poly: &[DVec2], ccw: bool, eps: f64, out: &mut Vec<(DVec2, DVec2)>) {
    let vertex = |i: usize| {
        if ccw {
            poly[i]
        } else {
            poly[poly.len() - 1 - i]
        }
    };
    out.clear();
    for i in 0..poly.len() {
        let (p, q) = (vertex(i), vertex((i + 1) % poly.len()));
        let e = q - p;
        let len = e.length();
        if len > eps {
            out.push((p, e.perp() / len));
        }
    }
}

/// The box round the points `p` (m): its low and high corners.
pub fn bounds(p: &[DVec2]) -> (DVec2, DVec2) {
    p.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), q| (lo.min(*q), hi.max(*q)),
    )
}

/// Is all of `s` on the outer side of some edge of the counter-clockwise `piece` (within
/// `eps` of its line, m)? The distance e⊥·(p − a)/|e| ≤ eps is tested as e⊥·(p − a) ≤
/// eps·|e|: one square root per edge, not per point.
pub(super) fn separated_by_own_edges(
    piece: &[DVec2],
    s: impl Iterator<Item = DVec2> + Clone,
    eps: f64,
) -> bool {
    let n = piece.len();
    (0..n).any(|i| {
        let (a, b) = (piece[i], piece[(i + 1) % n]);
        let e = b - a;
        let limit = eps * e.length();
        s.clone().all(|p| e.perp_dot(p - a) <= limit)
    })
}

/// Splits the convex polygon `poly` by the line through `a` with unit normal `m` into
/// the part on the normal's side (`inside`) and the rest (`outside`); vertices within
/// `eps` of the line go to both.
pub(super) fn split(
    poly: &[DVec2],
    a: DVec2,
    m: DVec2,
    eps: f64,
    inside: &mut Vec<DVec2>,
    outside: &mut Vec<DVec2>,
) {
    inside.clear();
    outside.clear();
    let n = poly.len();
    let d = |p: DVec2| {
        let s = m.dot(p - a);
        if s.abs() <= eps {
            0.0
        } else {
            s
        }
    };
    for i in 0..n {
        let (p, q) = (poly[i], poly[(i + 1) % n]);
        let (dp, dq) = (d(p), d(q));
        if dp >= 0.0 {
            inside.push(p);
        }
        if dp <= 0.0 {
            outside.push(p);
        }
        if (dp > 0.0 && dq < 0.0) || (dp < 0.0 && dq > 0.0) {
            let x = p + (q - p) * (dp / (dp - dq));
            inside.push(x);
            outside.push(x);
        }
    }
}
