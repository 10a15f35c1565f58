//! A face's lines sorted by the angle under which they are seen from its reference
//! ([`Fan`]): a count at a point of the face is its reference's plus the jumps of the
//! lines on the straight path between them ([`crossed`]), and such a path can cross only
//! the lines whose angle about the reference holds the point's. A face that a fine
//! outline's shadow crosses carries hundreds of lines and is cut into about as many
//! cells; counted through every line, each cell's count made the face's cost grow with
//! the square of its lines.

use super::lines::{crossed, Line};
use crate::geometry::csr::csr_of;
use glam::DVec2;

/// Buckets of angle about the reference (each 5.6°).
const BUCKETS: usize = 64;

/// A face's lines in buckets of angle about a point `r` (m, in the face's plane): each
/// line in every bucket its angle span about r meets, and in one more on either side
/// (the span's rounding). A line that passes within rounding of r is in every bucket.
#[derive(Default)]
pub struct Fan {
    r: DVec2,
    /// CSR: bucket `b` holds `members[start[b]..start[b + 1]]` (line indices).
    start: Vec<u32>,
    members: Vec<u32>,
    /// Per line, its first and last bucket (the last may wrap below the first).
    spans: Vec<(u32, u32)>,
}

/// A monotone stand-in for the angle of `v` (0 ≤ a < 4 for a turn), that maps −v to
/// a + 2 (mod 4): the diamond angle, a quotient rather than an arctangent.
#[inline]
fn pseudo_angle(v: DVec2) -> f64 {
    let p = v.y / (v.x.abs() + v.y.abs());
    if v.x >= 0.0 {
        if v.y >= 0.0 {
            p
        } else {
            4.0 + p
        }
    } else {
        2.0 - p
    }
}

/// The bucket of pseudo angle `a`.
#[inline]
fn bucket(a: f64) -> usize {
    ((a * (BUCKETS as f64 / 4.0)) as usize).min(BUCKETS - 1)
}

impl Fan {
    /// Puts `lines` in buckets of angle about `r`.
    pub fn build(&mut self, lines: &[Line], r: DVec2) {
        self.r = r;
        self.spans.clear();
        for l in lines {
            let (a, b) = (l.p - r, l.q - r);
            // a line whose own line passes this close to r (for its length), or a point,
            // is put in every bucket: its span's ends could not be trusted (an end at r
            // or a line of no length falls here too)
            let e = l.q - l.p;
            if e.perp_dot(a).abs() <= 1e-6 * e.length_squared() {
                self.spans.push((0, BUCKETS as u32 - 1));
                continue;
            }
            let (aa, ab) = (pseudo_angle(a), pseudo_angle(b));
            let forward = (ab - aa).rem_euclid(4.0);
            // the shorter way round: a segment clear of r is seen under less than half a
            // turn
            let (from, to) = if forward <= 2.0 { (aa, ab) } else { (ab, aa) };
            let first = (bucket(from) + BUCKETS - 1) % BUCKETS;
            let last = (bucket(to) + 1) % BUCKETS;
            self.spans.push((first as u32, last as u32));
        }
        let buckets_of = |&(first, last): &(u32, u32)| {
            let n = (last + BUCKETS as u32 - first) % BUCKETS as u32 + 1;
            (0..n).map(move |k| (first + k) % BUCKETS as u32)
        };
        let members = self
            .spans
            .iter()
            .enumerate()
            .flat_map(move |(i, s)| buckets_of(s).map(move |b| (b, i as u32)));
        (self.start, self.members) = csr_of(BUCKETS, members);
    }

    /// [`crossed`]`(lines, r, q)` for the `lines` the fan was built from: the same sum,
    /// read from the lines of `q`'s bucket alone.
    #[inline]
    pub fn crossed(&self, lines: &[Line], q: DVec2) -> i32 {
        let v = q - self.r;
        if v == DVec2::ZERO {
            return 0;
        }
        let b = bucket(pseudo_angle(v));
        let mut n = 0;
        for &i in &self.members[self.start[b] as usize..self.start[b + 1] as usize] {
            n += crossed(std::slice::from_ref(&lines[i as usize]), self.r, q);
        }
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fan_counts_as_every_line_counts_at_every_point() {
        // Lines as a face's shadows make them: a fine polyline round a circle (joints
        // shared exactly), long lines across the face, short ones scattered, one through
        // the reference's neighbourhood; points anywhere, on lines and at joints.
        let mut rng = crate::test_rng(7);
        let r = DVec2::new(0.1, -0.05);
        let mut lines = Vec::new();
        let n = 300;
        let at = |k: usize| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            DVec2::new(0.3 + 0.5 * t.cos(), 0.2 + 0.4 * t.sin())
        };
        for k in 0..n {
            lines.push(Line {
                p: at(k),
                q: at(k + 1),
                jump: 1,
                bounds: true,
            });
        }
        for _ in 0..200 {
            let p = DVec2::new(rng() * 2.0 - 1.0, rng() * 2.0 - 1.0);
            let q = p + DVec2::new(rng() - 0.5, rng() - 0.5) * if rng() < 0.2 { 4.0 } else { 0.3 };
            lines.push(Line {
                p,
                q,
                jump: if rng() < 0.5 { -1 } else { 2 },
                bounds: true,
            });
        }
        lines.push(Line {
            p: r - DVec2::new(1.0, 1e-12),
            q: r + DVec2::new(1.0, 3e-12),
            jump: 1,
            bounds: true,
        });
        let mut fan = Fan::default();
        fan.build(&lines, r);
        let mut points: Vec<DVec2> = (0..20_000)
            .map(|_| DVec2::new(rng() * 3.0 - 1.5, rng() * 3.0 - 1.5))
            .collect();
        points.extend((0..n).map(at));
        points.extend(lines.iter().map(|l| (l.p + l.q) * 0.5));
        points.extend([r, r + DVec2::X, r - DVec2::Y * 1e-300]);
        let mut nonzero = 0;
        for q in points {
            let all = crossed(&lines, r, q);
            nonzero += usize::from(all != 0);
            assert_eq!(fan.crossed(&lines, q), all, "at {q:?}");
        }
        // the test means something: most points lie across some line
        assert!(nonzero > 10_000, "{nonzero}");
    }
}
