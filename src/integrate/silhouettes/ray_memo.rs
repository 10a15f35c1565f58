//! One direction's ray answers on one face, shared between the cells of a region
//! ([`RayMemo`]): where a face is decided by rays (lines cross it and it is not convex,
//! [`super::areas`]), one ray answers for every cell whose centroid lies on the same side
//! of each of the direction's bounding lines and the face's contacts.

use super::lines;
use super::polygons::orient;
use glam::DVec2;

/// Most lines (with contacts) a direction may cut a face by for its ray answers to be
/// shared between cells: finding a cell's region takes a test against each line, and
/// past a few hundred those cost more than the ray they might save.
const MEMO_LINES: usize = 256;

/// One direction's ray answers on one face, shared between the cells of a region.
///
/// On a convex face, the points on one side of each of the direction's bounding lines
/// (their whole lines, not only their segments) make a convex region that none of its
/// lines crosses, so they are all lit or all dark along it: one ray answers for every
/// cell whose centroid lies there. The cells are cut by the other directions' lines
/// too, so a face cut by the view and the Sun has more cells than either direction has
/// regions. (Where a boom stands on a face, the ring of its foot's contacts is as many
/// lines as the boom has sides, 96 on the dish-sat's at 200k triangles, and the cells
/// inside the ring are one region.)
#[derive(Default)]
pub(super) struct RayMemo {
    /// Whether the answers are shared on this face (convex, few enough lines).
    on: bool,
    lines: Vec<(DVec2, DVec2)>,
    /// 64-bit words a region's key takes: one bit per line, its side.
    words: usize,
    /// The key of the point asked about last.
    key: Vec<u64>,
    /// The regions answered: each key folded into one word (the key itself when it is
    /// one word), the keys in full when they are longer (`words` each), and whether the
    /// regions are open along the direction.
    folded: Vec<u64>,
    keys: Vec<u64>,
    answers: Vec<bool>,
}

/// A key of several words folded into one (FxHash's step): regions are looked up by it
/// and then compared in full.
fn fold_key(key: &[u64]) -> u64 {
    key.iter().fold(0u64, |h, &w| {
        (h.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
    })
}

impl RayMemo {
    /// Readies the memo for a face whose lines along the direction are `lines` and whose
    /// contacts are `contacts` (in its plane's coordinates, m): a region is bounded by
    /// every contact too, whether or not the count jumps across it along this direction
    /// (a ray does not know why it is blocked: bounded by every contact, a region lies on
    /// one side of each place another piece meets the face, whatever the count does there).
    pub(super) fn reset<'l>(
        &mut self,
        convex: bool,
        lines: impl Iterator<Item = &'l lines::Line>,
        contacts: impl Iterator<Item = (DVec2, DVec2)>,
    ) {
        self.lines.clear();
        self.keys.clear();
        self.folded.clear();
        self.answers.clear();
        self.lines
            .extend(lines.filter(|l| l.bounds).map(|l| (l.p, l.q)));
        push_new(&mut self.lines, contacts);
        self.on = convex && self.lines.len() <= MEMO_LINES;
        self.words = self.lines.len().div_ceil(64).max(1);
    }

    /// Sets `key` to which side of each line `q` lies on.
    fn sides(&mut self, q: DVec2) {
        self.key.clear();
        for chunk in self.lines.chunks(64) {
            let word = chunk.iter().enumerate().fold(0, |m, (i, &(a, b))| {
                m | u64::from(orient(a, b, q) > 0.0) << i
            });
            self.key.push(word);
        }
        if self.key.is_empty() {
            self.key.push(0);
        }
    }

    /// The answer at `q`: remembered for its region, or `ray()`'s, then remembered if
    /// `q` may `share` it. A point within the margin of a line (a sliver cell's centroid:
    /// the lines of two directions, or a line and a contact, nearly one) lies on either
    /// side of it as rounding has it, and its ray grazes whatever casts the line: its
    /// answer may be the other side's, and remembered it would stand for every cell of
    /// its key's region (an epoch of the held-out cluster lost 0.6 of its light that way
    /// under a looser rule of sharing).
    pub(super) fn open(&mut self, q: DVec2, share: bool, ray: impl FnOnce() -> bool) -> bool {
        if !self.on {
            return ray();
        }
        self.sides(q);
        // most faces have at most 64 lines: a key of one word, compared as one; longer
        // keys are sought by their folded word and then compared in full (comparing each
        // remembered key as a slice was 3 % of a box-wing run at 20k triangles, on its
        // bus faces that more than 64 lines cross)
        let words = self.words;
        let folded = if words == 1 {
            self.key[0]
        } else {
            fold_key(&self.key)
        };
        let mut from = 0;
        while let Some(i) = self.folded[from..].iter().position(|&h| h == folded) {
            let i = from + i;
            if words == 1 || self.keys[i * words..(i + 1) * words] == self.key[..] {
                return self.answers[i];
            }
            from = i + 1;
        }
        let open = ray();
        if !share {
            return open;
        }
        self.folded.push(folded);
        if words > 1 {
            self.keys.extend_from_slice(&self.key);
        }
        self.answers.push(open);
        open
    }
}

/// Appends to `lines` each of `more` it does not hold yet (a contact across which the
/// count jumps is one of a direction's lines already, with the same ends).
pub(super) fn push_new(
    lines: &mut Vec<(DVec2, DVec2)>,
    more: impl Iterator<Item = (DVec2, DVec2)>,
) {
    for c in more {
        if !lines.contains(&c) {
            lines.push(c);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lines::Line;

    fn line(p: (f64, f64), q: (f64, f64), bounds: bool) -> Line {
        Line {
            p: DVec2::new(p.0, p.1),
            q: DVec2::new(q.0, q.1),
            jump: 1,
            bounds,
        }
    }

    #[test]
    fn a_ray_answers_for_every_cell_of_its_region_and_only_there() {
        // two bounding lines crossing at the origin make four regions; a third line that
        // does not bound cuts no region
        let ls = [
            line((-1.0, 0.0), (1.0, 0.0), true),
            line((0.0, -1.0), (0.0, 1.0), true),
            line((-1.0, 0.5), (1.0, 0.5), false),
        ];
        let mut memo = RayMemo::default();
        memo.reset(true, ls.iter(), std::iter::empty());
        let mut rays = 0;
        let mut ask = |memo: &mut RayMemo, x: f64, y: f64| {
            memo.open(DVec2::new(x, y), true, || {
                rays += 1;
                x > 0.0
            })
        };
        // two cells in each quadrant, on both sides of the line that does not bound
        for (x, y) in [(0.3, 0.2), (0.3, 0.7), (-0.3, 0.2), (-0.3, 0.7)] {
            assert_eq!(ask(&mut memo, x, y), x > 0.0);
            assert_eq!(ask(&mut memo, x, -y), x > 0.0);
        }
        assert_eq!(rays, 4, "one ray a region");
        // a face that is not convex: a region may be two pieces of it, each its own ray
        memo.reset(false, ls.iter(), std::iter::empty());
        let mut rays = 0;
        for _ in 0..3 {
            memo.open(DVec2::new(0.3, 0.2), true, || {
                rays += 1;
                true
            });
        }
        assert_eq!(rays, 3, "no sharing on a face that is not convex");
    }

    #[test]
    fn the_cells_inside_a_ring_of_a_hundred_contacts_share_one_ray() {
        // a boom's foot: 100 contacts round a circle on a convex face, more than one
        // 64-bit word of sides; every point inside the ring lies on the inner side of
        // each contact's whole line, one region
        let n = 100;
        let at = |i: usize| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            DVec2::new(t.cos(), t.sin())
        };
        let ring: Vec<(DVec2, DVec2)> = (0..n).map(|i| (at(i), at(i + 1))).collect();
        let mut memo = RayMemo::default();
        memo.reset(true, std::iter::empty(), ring.iter().copied());
        assert_eq!(memo.words, 2);
        let mut rays = 0;
        for k in 0..50 {
            let t = k as f64 * 0.7;
            let r = 0.9 * (k as f64 / 50.0);
            assert!(!memo.open(DVec2::new(r * t.cos(), r * t.sin()), true, || {
                rays += 1;
                false
            }));
        }
        assert_eq!(rays, 1, "one ray inside the ring");
        // outside it, beyond one contact (the 70th: in the second word) and beyond its
        // opposite: two more regions, each its own ray and answer
        let beyond = |i: usize| (at(i) + at(i + 1)) * 0.6;
        for (q, open) in [(beyond(70), true), (beyond(20), true), (beyond(70), true)] {
            assert_eq!(
                memo.open(q, true, || {
                    rays += 1;
                    true
                }),
                open
            );
        }
        assert_eq!(rays, 3);
        // past MEMO_LINES, no sharing
        let many: Vec<(DVec2, DVec2)> = (0..=MEMO_LINES)
            .map(|i| (DVec2::new(i as f64, 5.0), DVec2::new(i as f64, 6.0)))
            .collect();
        memo.reset(true, std::iter::empty(), many.into_iter());
        assert!(!memo.on);
    }

    #[test]
    fn a_contact_bounds_the_regions_a_ray_answers_for_whatever_its_jump() {
        // one bounding line along x; a contact along y with no jump along this direction
        // (another piece's wall that faces away): a piece may cover one side of it and
        // not the other, so it splits the regions as a line would
        let ls = [line((-1.0, 0.0), (1.0, 0.0), true)];
        let contact = (DVec2::new(0.0, -1.0), DVec2::new(0.0, 1.0));
        let mut memo = RayMemo::default();
        memo.reset(true, ls.iter(), std::iter::once(contact));
        let mut rays = 0;
        for (x, y) in [
            (0.3, 0.2),
            (0.6, 0.4),
            (-0.3, 0.2),
            (-0.6, 0.4),
            (0.3, -0.2),
        ] {
            let open = memo.open(DVec2::new(x, y), true, || {
                rays += 1;
                x > 0.0
            });
            assert_eq!(open, x > 0.0, "({x}, {y})");
        }
        assert_eq!(rays, 3, "one ray for each of the three regions asked about");
        // a contact that is also a line of the direction is one bound, not two
        memo.reset(true, ls.iter(), std::iter::once((ls[0].p, ls[0].q)));
        assert_eq!(memo.lines.len(), 1);
    }

    #[test]
    fn a_point_on_a_line_answers_for_itself_and_for_no_other_point() {
        // a sliver cell's centroid on the bounding line y = 0, taken as above it by
        // rounding, whose ray grazes what casts the line and finds it dark: were it
        // remembered, every point above the line would be dark without a ray
        let ls = [line((-1.0, 0.0), (1.0, 0.0), true)];
        let mut memo = RayMemo::default();
        memo.reset(true, ls.iter(), std::iter::empty());
        let mut rays = 0;
        let mut ask = |memo: &mut RayMemo, y: f64, share: bool, truth: bool| {
            memo.open(DVec2::new(0.2, y), share, || {
                rays += 1;
                truth
            })
        };
        assert!(!ask(&mut memo, 1e-12, false, false));
        assert!(
            ask(&mut memo, 0.3, true, true),
            "its own ray, not the sliver's"
        );
        assert!(ask(&mut memo, 0.5, true, false), "the region's answer");
        assert_eq!(rays, 2);
    }
}
