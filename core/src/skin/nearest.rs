//! A parent's children in buckets over their centre points' box, and the walk that hands a
//! child its siblings nearest first (ties by place in the list) as its clipping asks for them
//! (Ishii et al. §3.1: a cell is the Voronoi region of its centre point among its siblings,
//! inside its parent).
//!
//! A child's clipping stops at the first sibling farther than twice its outline's reach
//! ([`super::cell`]); most children are done after a dozen or two. A sort of all of a
//! parent's children for each child would cost m·log m (m up to [`MAX_CHILDREN`]) for a cell
//! of a few vertices, so that one [`super::Skin::step`] unit (an outline vertex) would cost
//! more the more children a parent holds. The walk looks only at the buckets around the
//! child, widening the box it has looked in by one row or column of buckets at a time (the
//! side nearest the child), and hands out a sibling once no sibling outside the box can come
//! before it: the very order a sort gives, for work that follows the siblings near the child
//! rather than all of them.

use super::MAX_CHILDREN;
use super::sites::Site;

/// `u32` words one level's buckets take in caller memory: its children's places in the list,
/// bucket by bucket ([`MAX_CHILDREN`]), and where each bucket starts (at most one bucket per
/// child, and one more start).
pub(super) const WORDS: usize = 2 * MAX_CHILDREN + 1;

/// How a parent's children are bucketed: a grid of `dims` buckets over the box of their
/// centre points (in the level's frame), about one child a bucket.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Buckets {
    origin: [f64; 2],
    /// Buckets per frame unit along each axis (0 on an axis of one bucket).
    scale: [f64; 2],
    /// A bucket's side along each axis.
    side: [f64; 2],
    dims: [usize; 2],
    /// How far rounding can move a bucket's border, at most (the frame's units): a
    /// billionth of the box's largest coordinate, many times the few ulps the border and a
    /// child's bucket are computed to.
    slack: f64,
}

/// Children (or buckets) one piece of a bucketing handles, at most ([`Filling::piece`]).
pub(super) const PIECE: usize = 256;

/// A bucketing under way ([`Buckets::fill`] in pieces): each piece handles at most [`PIECE`]
/// children or buckets of one of its passes, and the bucketing resumes between any two.
#[derive(Clone, Copy, Debug)]
pub(super) struct Filling {
    pass: Pass,
    /// The next child or bucket of the pass.
    at: usize,
    /// The children's box so far (the first pass).
    low: [f64; 2],
    high: [f64; 2],
}

/// The passes of a bucketing, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// The box of the children's centre points, then the buckets over it.
    Bound,
    /// Each bucket's count set to 0.
    Clear,
    /// Each bucket's children counted.
    Count,
    /// The counts summed into the buckets' ends.
    Sum,
    /// Each child's place written in its bucket, in list order.
    Place,
    /// The ends moved up by one bucket into starts (from the last bucket down).
    Shift,
    Done,
}

impl Filling {
    pub(super) const fn new() -> Filling {
        Filling { pass: Pass::Bound, at: 0, low: [f64::INFINITY; 2], high: [f64::NEG_INFINITY; 2] }
    }

    /// Does the next piece of bucketing `sites` into `words` and `buckets` (the same `sites`
    /// and `words` at every piece; `buckets` is set by the first pass and read by the rest);
    /// returns whether the bucketing is done. Each piece is O([`PIECE`]).
    pub(super) fn piece(&mut self, buckets: &mut Buckets, sites: &[Site], words: &mut [u32]) -> bool {
        let count = sites.len().min(MAX_CHILDREN);
        let sites = &sites[..count];
        let (order, starts) = words.split_at_mut(MAX_CHILDREN);
        let total = buckets.dims[0] * buckets.dims[1];
        let from = self.at;
        // The end of this piece in a pass over `n` items, and whether it ends the pass.
        let upto = |n: usize| ((from + PIECE).min(n), from + PIECE >= n);
        let (to, last) = match self.pass {
            Pass::Bound => {
                let (to, last) = upto(count);
                for s in &sites[from..to] {
                    self.low = [self.low[0].min(s.at[0]), self.low[1].min(s.at[1])];
                    self.high = [self.high[0].max(s.at[0]), self.high[1].max(s.at[1])];
                }
                if last {
                    *buckets = Buckets::over(count, self.low, self.high);
                }
                (to, last)
            }
            Pass::Clear => {
                let (to, last) = upto(total + 1);
                starts[from..to].fill(0);
                (to, last)
            }
            Pass::Count => {
                let (to, last) = upto(count);
                for s in &sites[from..to] {
                    starts[buckets.index(s.at) + 1] += 1;
                }
                (to, last)
            }
            Pass::Sum => {
                // (Buckets 1 to total: at starts from 0.)
                let (to, last) = upto(total);
                for b in from + 1..=to {
                    starts[b] += starts[b - 1];
                }
                (to, last)
            }
            Pass::Place => {
                // (Each bucket's start moves to the next one's as it is filled, then back by
                // one: the next pass.)
                let (to, last) = upto(count);
                for (k, s) in sites.iter().enumerate().take(to).skip(from) {
                    let b = buckets.index(s.at);
                    order[starts[b] as usize] = k as u32;
                    starts[b] += 1;
                }
                (to, last)
            }
            Pass::Shift => {
                // (Buckets total down to 1, `at` counting those moved: each reads the one
                // below before that one is moved.)
                let (to, last) = upto(total);
                for b in (total - to + 1..=total - from).rev() {
                    starts[b] = starts[b - 1];
                }
                if last {
                    starts[0] = 0;
                }
                (to, last)
            }
            Pass::Done => return true,
        };
        self.at = to;
        if last {
            self.at = 0;
            self.pass = match self.pass {
                Pass::Bound => Pass::Clear,
                Pass::Clear => Pass::Count,
                Pass::Count => Pass::Sum,
                Pass::Sum => Pass::Place,
                Pass::Place => Pass::Shift,
                Pass::Shift | Pass::Done => Pass::Done,
            };
        }
        self.pass == Pass::Done
    }
}

impl Buckets {
    /// Buckets `sites` (a parent's children, as listed): writes into `words` ([`WORDS`] of
    /// them) their places in the list bucket by bucket, in list order within a bucket, and
    /// after those ([`MAX_CHILDREN`] on) where each bucket's places start. O(children), in
    /// one go ([`Filling`] does it in pieces).
    #[cfg(test)]
    pub(super) fn fill(sites: &[Site], words: &mut [u32]) -> Buckets {
        let (mut filling, mut buckets) = (Filling::new(), Buckets::default());
        while !filling.piece(&mut buckets, sites, words) {}
        buckets
    }

    /// The buckets for `count` children whose centre points span the box [low, high].
    fn over(count: usize, low: [f64; 2], high: [f64; 2]) -> Buckets {
        let extent = [0, 1].map(|k| (high[k] - low[k]).max(0.0));
        // Square buckets of about one child each; an axis of no extent (a row of centres
        // without jitter) gets one bucket and the other axis all of them.
        let target = count.max(1) as f64;
        let area = extent[0] * extent[1];
        let edge = if area > 0.0 { crate::scalar::sqrt(area / target) } else { extent[0].max(extent[1]) / target };
        let mut dims = [0, 1].map(|k| {
            let d = libm::ceil(extent[k] / edge);
            // (`as` takes NaN to 0 and saturates: a box of no extent is one bucket.)
            (d as usize).clamp(1, count.max(1))
        });
        // At most one bucket per child.
        dims[1] = dims[1].min((count / dims[0]).max(1));
        let scale = [0, 1].map(|k| if extent[k] > 0.0 { dims[k] as f64 / extent[k] } else { 0.0 });
        let side = [0, 1].map(|k| extent[k] / dims[k] as f64);
        let magnitude = [0, 1].map(|k| low[k].abs().max(high[k].abs())).into_iter().fold(0.0, f64::max);
        Buckets { origin: low, scale, side, dims, slack: 1e-9 * magnitude }
    }

    /// The bucket (column, row) of a frame point, the nearest one for a point outside the box.
    #[inline]
    fn of(&self, at: [f64; 2]) -> [usize; 2] {
        // (`as` takes a negative or NaN product to 0 and saturates a huge one.)
        [0, 1].map(|k| (((at[k] - self.origin[k]) * self.scale[k]) as usize).min(self.dims[k] - 1))
    }

    #[inline]
    fn index(&self, at: [f64; 2]) -> usize {
        let [x, y] = self.of(at);
        y * self.dims[0] + x
    }
}

/// A walk over one child's siblings, nearest first.
pub(super) struct Nearest<'w> {
    buckets: &'w Buckets,
    /// The level's places bucket by bucket, and the buckets' starts ([`Buckets::fill`]).
    order: &'w [u32],
    starts: &'w [u32],
    sites: &'w [Site],
    /// The child's centre point.
    centre: [f64; 2],
    /// The buckets looked in: columns `low[0]..=high[0]`, rows `low[1]..=high[1]`.
    low: [usize; 2],
    high: [usize; 2],
    /// The siblings found there and not yet handed out: a binary heap of their places,
    /// nearest first.
    heap: &'w mut [u32],
    len: usize,
}

impl<'w> Nearest<'w> {
    /// Starts the walk of the child at `centre` among `sites` (the children as bucketed into
    /// `words`), its found siblings kept in `heap` (at least as long as `sites`).
    pub(super) fn new(
        buckets: &'w Buckets,
        words: &'w [u32],
        sites: &'w [Site],
        centre: [f64; 2],
        heap: &'w mut [u32],
    ) -> Nearest<'w> {
        let (order, starts) = words.split_at(MAX_CHILDREN);
        let at = buckets.of(centre);
        let mut walk = Nearest { buckets, order, starts, sites, centre, low: at, high: at, heap, len: 0 };
        walk.take(at[0], at[1]);
        walk
    }

    /// The squared distance of sibling `k` from the child, and its place: the order they are
    /// handed out in.
    #[inline]
    fn key(&self, k: u32) -> (f64, u32) {
        let p = self.sites[k as usize].at;
        let d = [p[0] - self.centre[0], p[1] - self.centre[1]];
        (d[0] * d[0] + d[1] * d[1], k)
    }

    #[inline]
    fn before(&self, a: u32, b: u32) -> bool {
        let (ka, kb) = (self.key(a), self.key(b));
        ka.0.total_cmp(&kb.0).then(ka.1.cmp(&kb.1)).is_lt()
    }

    /// Puts the siblings of bucket (x, y) on the heap.
    fn take(&mut self, x: usize, y: usize) {
        let b = y * self.buckets.dims[0] + x;
        let (from, to) = (self.starts[b] as usize, self.starts[b + 1] as usize);
        for i in from..to {
            let k = self.order[i];
            let mut at = self.len;
            self.len += 1;
            while at > 0 {
                let up = (at - 1) / 2;
                if !self.before(k, self.heap[up]) {
                    break;
                }
                self.heap[at] = self.heap[up];
                at = up;
            }
            self.heap[at] = k;
        }
    }

    /// Takes the nearest sibling off the heap.
    fn pop(&mut self) -> u32 {
        let top = self.heap[0];
        self.len -= 1;
        let last = self.heap[self.len];
        let mut at = 0;
        loop {
            let mut child = 2 * at + 1;
            if child >= self.len {
                break;
            }
            if child + 1 < self.len && self.before(self.heap[child + 1], self.heap[child]) {
                child += 1;
            }
            if !self.before(self.heap[child], last) {
                break;
            }
            self.heap[at] = self.heap[child];
            at = child;
        }
        self.heap[at] = last;
        top
    }

    /// The side of the box looked in that is nearest the child and has buckets beyond it
    /// (0 to 3: columns below, rows below, columns above, rows above), and how far the child
    /// is from it at the least: no sibling outside the box is nearer. None once every bucket
    /// has been looked in.
    fn nearest_side(&self) -> Option<(usize, f64)> {
        let b = self.buckets;
        let mut side: Option<(usize, f64)> = None;
        for k in 0..2 {
            let (below, above) = (self.low[k] > 0, self.high[k] + 1 < b.dims[k]);
            // A sibling in a bucket before `low` lies before its border, one after `high`
            // after the border past it (up to the slack).
            let gaps = [
                (below, self.centre[k] - (b.origin[k] + self.low[k] as f64 * b.side[k])),
                (above, b.origin[k] + (self.high[k] + 1) as f64 * b.side[k] - self.centre[k]),
            ];
            for (s, (open, gap)) in gaps.into_iter().enumerate() {
                let gap = (gap - b.slack).max(0.0);
                if open && side.is_none_or(|(_, g)| gap < g) {
                    side = Some((2 * s + k, gap));
                }
            }
        }
        side
    }

    /// Looks in the row or column of buckets beyond `side` of the box.
    fn widen(&mut self, side: usize) {
        let k = side % 2;
        let line = if side < 2 {
            self.low[k] -= 1;
            self.low[k]
        } else {
            self.high[k] += 1;
            self.high[k]
        };
        let other = 1 - k;
        for along in self.low[other]..=self.high[other] {
            let (x, y) = if k == 0 { (line, along) } else { (along, line) };
            self.take(x, y);
        }
    }

    /// The next sibling's place, nearest first and ties by place in the list (the child itself
    /// too, at distance 0); None when every sibling has been handed out, or when the next
    /// lies farther than `limit` (a squared distance) from the child.
    pub(super) fn next(&mut self, limit: f64) -> Option<usize> {
        loop {
            let side = self.nearest_side();
            // No sibling outside the box is nearer than `gap`: its squared distance, as
            // computed, is at least gap² less a few ulps.
            let beyond = side.map_or(f64::INFINITY, |(_, gap)| gap * gap * (1.0 - 1e-9));
            if self.len > 0 {
                let nearest = self.key(self.heap[0]).0;
                if nearest > limit && beyond > limit {
                    return None;
                }
                if nearest < beyond {
                    return Some(self.pop() as usize);
                }
            } else if beyond > limit {
                return None;
            }
            // (The box holds every bucket once no side is left: `beyond` is then infinite,
            // and a sibling on the heap is handed out or it is empty.)
            let (s, _) = side?;
            self.widen(s);
        }
    }

    /// Siblings looked at so far (the walk's work, for tests).
    #[cfg(test)]
    fn looked_at(&self) -> usize {
        let b = self.buckets;
        let mut n = 0;
        for y in self.low[1]..=self.high[1] {
            for x in self.low[0]..=self.high[0] {
                let i = y * b.dims[0] + x;
                n += (self.starts[i + 1] - self.starts[i]) as usize;
            }
        }
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// Most sites a test walks.
    const SITES: usize = 4000;

    /// The squared distance of `s` from `centre`, as the walk and the clipping compute it.
    fn d2(s: &Site, centre: [f64; 2]) -> f64 {
        let d = [s.at[0] - centre[0], s.at[1] - centre[1]];
        d[0] * d[0] + d[1] * d[1]
    }

    #[test]
    fn the_walk_hands_out_what_a_sort_gives() {
        // Jittered and exact lattices (exact ties), rows of no height, far-off boxes; every
        // child (or every few) walked to the end, and again up to a limit.
        let mut rng = Rng::from_key(41, 42);
        let mut sites = [Site::default(); SITES];
        let (mut words, mut heap) = ([0u32; WORDS], [0u32; MAX_CHILDREN]);
        let (mut expected, mut got) = ([0usize; SITES], [0usize; SITES]);
        let mut walked = 0;
        for case in 0..60 {
            let count = [1, 2, 3, 97, 200, 1000][case % 6];
            let offset = [0.0, 1e6, -3.5e9][case % 3];
            let jitter = if case % 4 == 0 { 0.0 } else { rng.uniform_f64() };
            let (step, columns) = (0.5 + 3.0 * rng.uniform_f64(), 1 + (case * 7) % 40);
            for (k, s) in sites[..count].iter_mut().enumerate() {
                let (i, j) = ((k % columns) as f64, (k / columns) as f64);
                let row = if case % 5 == 0 { 0.0 } else { j * step * 0.87 };
                let at = [
                    offset + i * step + jitter * (rng.uniform_f64() - 0.5),
                    offset + row + jitter * (rng.uniform_f64() - 0.5),
                ];
                *s = Site { at, base: at, id: k as u32, image: [0, 0] };
            }
            let sites = &sites[..count];
            let buckets = Buckets::fill(sites, &mut words);
            assert!(buckets.dims[0] * buckets.dims[1] <= count, "case {case}: at most a bucket a child");
            for (c, child) in sites.iter().enumerate().step_by(1 + count / 40) {
                // What a sort by (squared distance, place) gives.
                let expected = &mut expected[..count];
                for (k, e) in expected.iter_mut().enumerate() {
                    *e = k;
                }
                expected.sort_unstable_by(|&i, &j| {
                    d2(&sites[i], child.at).total_cmp(&d2(&sites[j], child.at)).then(i.cmp(&j))
                });
                // To the end, and up to the limit of a sibling halfway: every sibling within it
                // (ties at the limit included), and not one more.
                let limit = d2(&sites[expected[count / 2]], child.at);
                let within = expected.iter().take_while(|&&k| d2(&sites[k], child.at) <= limit).count();
                for (limit, length) in [(f64::INFINITY, count), (limit, within)] {
                    let mut walk = Nearest::new(&buckets, &words, sites, child.at, &mut heap);
                    let mut n = 0;
                    while let Some(k) = walk.next(limit) {
                        got[n] = k;
                        n += 1;
                    }
                    assert_eq!(got[..n], expected[..length], "case {case}, child {c}, limit {limit}");
                    walked += 1;
                }
            }
        }
        assert!(walked > 1000, "{walked} walks");
    }

    #[test]
    fn a_child_among_many_looks_at_the_siblings_near_it() {
        // 4 000 centres of a jittered lattice: the dozen nearest of a child in the middle are
        // handed out after looking at a few dozen siblings, not at all of them.
        let mut rng = Rng::from_key(43, 44);
        let mut sites = [Site::default(); SITES];
        for (k, s) in sites.iter_mut().enumerate() {
            let at = [(k % 64) as f64 + 0.5 * rng.uniform_f64(), (k / 64) as f64 + 0.5 * rng.uniform_f64()];
            *s = Site { at, base: at, id: k as u32, image: [0, 0] };
        }
        let (mut words, mut heap) = ([0u32; WORDS], [0u32; MAX_CHILDREN]);
        let buckets = Buckets::fill(&sites, &mut words);
        let child = sites[31 * 64 + 32].at;
        let mut walk = Nearest::new(&buckets, &words, &sites, child, &mut heap);
        for _ in 0..12 {
            walk.next(f64::INFINITY).expect("a sibling");
        }
        let looked = walk.looked_at();
        assert!(looked < 100, "{looked} siblings looked at for 12");
    }
}
