//! One cell's outline (Ishii et al. §3.1, §4.1): the Voronoi region of its centre point among
//! its neighbours, clipped to its parent polygon, with its edges perturbed by midpoint
//! displacement (parameter 2) and stretched (parameter 3).
//!
//! The region is found by clipping the parent outline with the bisector of each neighbour,
//! nearest first, until no farther neighbour can reach the outline. Clipping only decides
//! which lines bound the region; each corner is then recomputed from those lines in a frame
//! and an order that depend on the sites' ids alone (the circumcentre of three sites, or a
//! bisector meeting a parent edge), and perturbation points are drawn from the edge's own
//! random stream in one direction. So both cells sharing an edge get it bit for bit, and
//! after rounding to fixed point they share its vertices.
//!
//! Fixed point: level l rounds its own points to 1/2^(8 + 12·l) px, and puts a corner on its
//! parent's edge at a parameter rounded to 1/2^12 of that edge, which is exactly
//! representable one level finer. So a child's corner lies exactly on the parent's edge,
//! children of neighbouring parents meet along the very same line, and no pixel falls in a
//! gap or an overlap between them. Everything is stored at the finest level's resolution.

mod clip;
mod frame;
mod perturb;

use clip::clip_by_bisector;
use frame::{Corner, bisector_meets_edge, circumcentre, sorted2};
pub(super) use frame::{Frame, fixed_point_bits};
use perturb::{crossings, perturb};

use super::MAX_CHILDREN;
use super::grid::{EdgeGrid, each_edge};
use super::nearest::{self, Buckets, Nearest};
use super::params::MAX_PERTURBATION_DEPTH;
use super::shared::{EdgeKey, KEPT_POINTS, SharedEdges};
use super::sites::Site;

/// Most vertices one cell outline can have.
pub const MAX_OUTLINE: usize = 2048;

/// A clip label: the outline edge runs along the parent's edge `k` (bit 31 set) or along the
/// bisector with neighbour `k`.
const PARENT_EDGE: u32 = 1 << 31;

/// A vertex of the outline being clipped: approximate position in the level's frame, and the
/// label of the edge that starts at it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClipVertex {
    at: [f64; 2],
    label: u32,
}

/// Why an outline could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct OutlineFull;

/// The index after `i` around a closed outline of `n` vertices (no division).
#[inline]
fn next(i: usize, n: usize) -> usize {
    if i + 1 == n { 0 } else { i + 1 }
}

/// Edges of a parent outline per chunk (for its bounding boxes).
pub(super) const CHUNK: usize = 4;

/// Scratch for splitting one bisector edge where its parent's outline crosses it: its pieces
/// and the parent's edges near it. Only levels from 1 have one: a level-0 cell's parent is a
/// rectangle its bisector edges end on, which no edge crosses (one piece, from corner to
/// corner, and no parent edge to list).
#[derive(Clone)]
pub(super) struct CrossingScratch {
    pieces: [Corner; MAX_CROSSINGS + 2],
    /// The parent's edges near the edge being built.
    listed: [u32; LISTED],
}

/// Most parent edges listed near one bisector edge (beyond, its tests look at all of them).
const LISTED: usize = 64;

// (The edges of a list that meet a box are marked a bit each.)
const _: () = assert!(LISTED <= 64);

impl CrossingScratch {
    pub(super) fn new() -> CrossingScratch {
        CrossingScratch { pieces: [Corner::default(); MAX_CROSSINGS + 2], listed: [0; LISTED] }
    }
}

/// Where a level's bisector edges are built: the shared edges it keeps for its cells'
/// neighbours (none where it keeps none: [`super::Layout`]) and the crossing scratch of a
/// level from 1.
pub(super) struct EdgeWork<'w> {
    pub(super) shared: Option<&'w mut SharedEdges>,
    pub(super) crossing: Option<&'w mut CrossingScratch>,
    /// The cell's own place among its neighbours when they are built in their order (a
    /// parent's children): those before it are built, those after it not yet, so an edge
    /// with one before it can only be taken, and one with a later one only kept. `None`
    /// (level 0's window): either may hold, and every edge is looked up and kept.
    pub(super) own: Option<usize>,
}

/// Scratch for building outlines.
pub(super) struct Builder<'s> {
    pub(super) clip: &'s mut [ClipVertex],
    pub(super) spare: &'s mut [ClipVertex],
    /// The skin's `words` (none for one level): the siblings a cell's walk has found and not
    /// yet handed out ([`Nearest`], the first [`MAX_CHILDREN`]), then each finer level's
    /// buckets of its parent's children ([`super::Layout::words_at`]).
    pub(super) words: &'s mut [u32],
}

/// A parent outline (fixed point, counter-clockwise) and the bounding boxes (x0, y0, x1, y1)
/// of its edges, `CHUNK` at a time (from [`chunk_boxes`]).
#[derive(Clone, Copy)]
pub(super) struct Parent<'p> {
    pub(super) outline: &'p [[i64; 2]],
    pub(super) chunks: &'p [[i64; 4]],
    /// Its edges binned, for an outline short enough ([`EdgeGrid::of`]; searched through the
    /// chunks otherwise).
    pub(super) grid: Option<&'p EdgeGrid>,
    /// The outline as its children's clipping starts from it ([`parent_vertex`], made once
    /// for all of them).
    pub(super) frame: &'p [ClipVertex],
}

impl Parent<'_> {
    /// Calls `visit` with each edge whose box meets [low, high] (widened by `slack`), in the
    /// outline's order, until it returns true.
    fn edges_near(&self, (low, high): ([i64; 2], [i64; 2]), slack: i64, visit: impl FnMut(usize) -> bool) {
        let Some(grid) = self.grid else {
            return edges_near(self.outline, self.chunks, (low, high), slack, visit);
        };
        let outline = self.outline;
        let m = outline.len();
        let wide = ([low[0] - slack, low[1] - slack], [high[0] + slack, high[1] + slack]);
        // The edges whose boxes meet, marked without branches (which do follows the outline's
        // shape, no pattern a processor could learn), then visited.
        let mut meet = 0;
        each_edge(grid.near(wide), |e| {
            meet |= u64::from(!apart(outline[e], outline[next(e, m)], wide)) << e;
            false
        });
        each_edge(meet, visit);
    }

    /// Whether the outline contains `p` (even–odd rule, fixed point).
    pub(super) fn contains(&self, p: [i64; 2]) -> bool {
        match self.grid {
            Some(grid) => super::scan::contains_among(self.outline, grid.across(p), p),
            None => super::scan::contains_chunked(self.outline, self.chunks, CHUNK, p),
        }
    }
}

/// Vertex `k` of a parent's outline as a child in frame `f` starts clipping it: labelled as
/// the parent's edge `k`.
pub(super) fn parent_vertex(f: &Frame, outline: &[[i64; 2]], k: usize) -> ClipVertex {
    ClipVertex { at: f.in_frame(outline[k]), label: PARENT_EDGE | k as u32 }
}

/// How many chunk boxes an outline of `m` vertices has ([`chunk_boxes`]).
pub(super) fn chunk_count(m: usize) -> usize {
    m.div_ceil(CHUNK)
}

/// Fills `chunks` with the boxes of `outline`'s edges taken `CHUNK` at a time; returns how
/// many ([`chunk_count`]).
pub(super) fn chunk_boxes(outline: &[[i64; 2]], chunks: &mut [[i64; 4]]) -> usize {
    let m = outline.len();
    let count = chunk_count(m);
    for (c, b) in chunks[..count].iter_mut().enumerate() {
        let mut bounds = [i64::MAX, i64::MAX, i64::MIN, i64::MIN];
        for i in c * CHUNK..=((c + 1) * CHUNK).min(m) {
            let p = outline[if i == m { 0 } else { i }];
            bounds = [bounds[0].min(p[0]), bounds[1].min(p[1]), bounds[2].max(p[0]), bounds[3].max(p[1])];
        }
        *b = bounds;
    }
    count
}

/// Whether the box of the edge p–q misses the box [low, high] (tested without branches).
#[inline]
fn apart(p: [i64; 2], q: [i64; 2], (low, high): ([i64; 2], [i64; 2])) -> bool {
    (p[0].max(q[0]) < low[0]) | (p[0].min(q[0]) > high[0]) | (p[1].max(q[1]) < low[1]) | (p[1].min(q[1]) > high[1])
}

/// Calls `visit` with each edge of `outline` whose box meets [low, high] (widened by
/// `slack`), chunk by chunk, until it returns true.
fn edges_near(
    outline: &[[i64; 2]],
    chunks: &[[i64; 4]],
    (low, high): ([i64; 2], [i64; 2]),
    slack: i64,
    mut visit: impl FnMut(usize) -> bool,
) {
    let m = outline.len();
    let (low, high) = ([low[0] - slack, low[1] - slack], [high[0] + slack, high[1] + slack]);
    for (c, b) in chunks.iter().enumerate() {
        if b[2] < low[0] || b[0] > high[0] || b[3] < low[1] || b[1] > high[1] {
            continue;
        }
        // The chunk's edges that meet the box, listed without branches (which ones do follows
        // the outline's shape, no pattern a processor could learn), then visited.
        let (mut hits, mut count) = ([0usize; CHUNK], 0);
        for e in c * CHUNK..((c + 1) * CHUNK).min(m) {
            hits[count] = e;
            count += usize::from(!apart(outline[e], outline[next(e, m)], (low, high)));
        }
        for &e in &hits[..count] {
            if visit(e) {
                return;
            }
        }
    }
}

/// The parent's edges a bisector edge is tested against ([`crossings`], [`perturb`]): every
/// one (found through the chunk boxes), or, for a test that stays inside `region`, the ones
/// listed as meeting it (in order, so that both give the same edges in the same order).
#[derive(Clone, Copy)]
struct Nearby<'p> {
    parent: Parent<'p>,
    region: [i64; 4],
    listed: Option<&'p [u32]>,
}

impl<'p> Nearby<'p> {
    /// Lists (into `space`) the edges of `parent` that meet the box any test of the bisector
    /// edge from `start` to `end` can make: the edge's box widened by the farthest its
    /// perturbation can reach ([`Frame::reach`] times its length) and the tests' slack.
    fn list(f: &Frame, parent: Parent<'p>, (start, end): (&Corner, &Corner), space: &'p mut [u32; LISTED]) -> Self {
        let (x, y) = (start.fixed, end.fixed);
        let d = f.in_frame([y[0] - x[0], y[1] - x[1]]);
        let length = crate::scalar::sqrt(d[0] * d[0] + d[1] * d[1]);
        let reach = f.reach * length;
        // (Plus the stay-inside test's slack, and a few units for rounding to fixed point.)
        // Saturating: a huge perturbation ratio (1e30) reaches past i64 (`as` saturates), and
        // the box then takes in every edge instead of overflowing.
        let widen = |k: usize| ((reach * f.from_frame[k]) as i64).saturating_add(f.inside_slack() + 16);
        let (wx, wy) = (widen(0), widen(1));
        let low = [x[0].min(y[0]).saturating_sub(wx), x[1].min(y[1]).saturating_sub(wy)];
        let high = [x[0].max(y[0]).saturating_add(wx), x[1].max(y[1]).saturating_add(wy)];
        let (mut count, mut fits) = (0, true);
        parent.edges_near((low, high), 0, |e| {
            if count == LISTED {
                fits = false;
                return true;
            }
            space[count] = e as u32;
            count += 1;
            false
        });
        let space: &'p [u32; LISTED] = space;
        Nearby { parent, region: [low[0], low[1], high[0], high[1]], listed: fits.then(|| &space[..count]) }
    }

    /// Whether no parent edge comes near the bisector edge: then every test within the
    /// region finds none, the edge crosses no parent edge and stays inside the parent.
    fn is_empty(&self) -> bool {
        self.listed.is_some_and(|listed| listed.is_empty())
    }

    /// [`edges_near`] over the parent.
    fn edges_near(&self, (low, high): ([i64; 2], [i64; 2]), slack: i64, mut visit: impl FnMut(usize) -> bool) {
        let outline = self.parent.outline;
        let r = self.region;
        let wide = ([low[0] - slack, low[1] - slack], [high[0] + slack, high[1] + slack]);
        let ([x0, y0], [x1, y1]) = wide;
        match self.listed {
            Some(listed) if r[0] <= x0 && r[1] <= y0 && x1 <= r[2] && y1 <= r[3] => {
                let m = outline.len();
                // Those whose boxes meet, marked without branches (a bit per place in the
                // list, which holds at most 64), then visited.
                let mut meet = 0u64;
                for (i, &e) in listed.iter().enumerate() {
                    meet |= u64::from(!apart(outline[e as usize], outline[next(e as usize, m)], wide)) << i;
                }
                each_edge(meet, |i| visit(listed[i] as usize));
            }
            _ => self.parent.edges_near((low, high), slack, visit),
        }
    }
}

impl Builder<'_> {
    /// Builds the outline of `site`'s cell among `neighbours` (which may include `site`
    /// itself, skipped by id and image) inside `parent` (fixed point, counter-clockwise), into
    /// `out`; returns its length (0 if the cell misses the parent).
    ///
    /// More than [`FEW`] neighbours must come with their `buckets` (a parent's children:
    /// [`nearest::Filling`] into `words` from the place given); fewer are picked without.
    pub(super) fn outline(
        &mut self,
        f: &Frame,
        site: &Site,
        (neighbours, buckets): (&[Site], Option<(&Buckets, usize)>),
        parent: Parent,
        (out, work): (&mut [[i64; 2]], EdgeWork),
    ) -> Result<usize, OutlineFull> {
        let n0 = parent.outline.len();
        debug_assert_eq!(parent.frame.len(), n0, "the parent's clip vertices are made");
        if n0 > self.clip.len() {
            return Err(OutlineFull);
        }
        // The outline starts as the parent's, read from it until the first clip writes one.
        let mut n = n0;
        let mut fresh = true;
        // Neighbours nearest first, ties by place in the list (which is the order of ids:
        // sites are listed in lattice order), handed out as the clipping asks for them (most
        // cells are done after a handful). A few are picked one at a time among all of them;
        // more (a parent's children) are walked bucket by bucket from the cell's own
        // ([`Nearest`]), which looks at the siblings near it only.
        let distance_to = |p: [f64; 2]| {
            let d = [p[0] - site.at[0], p[1] - site.at[1]];
            d[0] * d[0] + d[1] * d[1]
        };
        let distance = |s: &Site| distance_to(s.at);
        let m = neighbours.len();
        let mut walk = match buckets {
            Some((buckets, at)) if m > FEW => {
                let (heap, levels) = self.words.split_at_mut(MAX_CHILDREN);
                let words = &levels[at - MAX_CHILDREN..][..nearest::WORDS];
                Some(Nearest::new(buckets, words, neighbours, site.at, heap))
            }
            // (Only a parent's children outnumber the few, and they come bucketed.)
            None if m > FEW => return Err(OutlineFull),
            _ => None,
        };
        // A handful (nearly always a parent's children): the nearest of those left picked at
        // each turn, without branches (ties by place: the first of equal keys). Their keys are
        // the distances' bits, which order as the distances do (none is negative; NaN and
        // infinity are never handed out: they are left out as the largest key).
        let mut handful = [FAR; SHORT];
        let few = walk.is_none() && m <= SHORT;
        if few {
            for (key, s) in handful.iter_mut().zip(neighbours) {
                let d = distance(s);
                *key = if d.is_nan() || d == f64::INFINITY { FAR } else { d.to_bits() };
            }
        }
        // More: sorted once (by distance, ties by place), handed out in that order.
        let (mut order, mut sorted) = ([0u8; FEW], 0);
        if walk.is_none() && !few {
            sorted = sort_few(neighbours, distance, &mut order);
        }
        let mut handed = 0;
        // (Unbounded until the first clip: the nearest neighbours clip the parent.)
        let mut farthest = f64::INFINITY;
        loop {
            let j = match walk.as_mut() {
                // (None once the next lies farther than the check below lets through, or
                // none is left.)
                Some(walk) => match walk.next(4.0 * farthest) {
                    Some(j) => j,
                    None => break,
                },
                None if few => {
                    let (mut nearest, mut at) = (FAR, SHORT);
                    for (i, &key) in handful[..m].iter().enumerate() {
                        let nearer = key < nearest;
                        nearest = core::hint::select_unpredictable(nearer, key, nearest);
                        at = core::hint::select_unpredictable(nearer, i, at);
                    }
                    // (Every one handed out.)
                    let Some(key) = handful.get_mut(at) else { break };
                    *key = FAR;
                    at
                }
                None => {
                    // (Every one handed out.)
                    if handed == sorted {
                        break;
                    }
                    handed += 1;
                    usize::from(order[handed - 1])
                }
            };
            let b = &neighbours[j];
            if b.id == site.id && b.image == site.image {
                continue;
            }
            // No part of the outline is farther than half this neighbour's distance: it and
            // every farther one leave the outline alone.
            if distance(b) > 4.0 * farthest {
                break;
            }
            let clipped = if fresh {
                clip_by_bisector(&parent.frame[..n], (site, b, j as u32), self.clip)?
            } else {
                let clipped = clip_by_bisector(&self.clip[..n], (site, b, j as u32), self.spare)?;
                if clipped.is_some() {
                    core::mem::swap(&mut self.clip, &mut self.spare);
                }
                clipped
            };
            if let Some((count, reach)) = clipped {
                (n, fresh, farthest) = (count, false, reach);
                if n == 0 {
                    return Ok(0);
                }
            }
        }
        if fresh {
            self.clip[..n].copy_from_slice(parent.frame);
        }
        self.finish(f, site, neighbours, parent, n, (out, work))
    }

    /// The corner between an edge labelled `into` and one labelled `from` (starting at clip
    /// vertex `k`).
    fn corner(
        &self,
        f: &Frame,
        a: &Site,
        neighbours: &[Site],
        parent: &[[i64; 2]],
        (into, from): (u32, u32),
        k: usize,
    ) -> Corner {
        let edge = |label: u32| {
            let i = (label & !PARENT_EDGE) as usize;
            (parent[i], parent[next(i, parent.len())])
        };
        match (into & PARENT_EDGE != 0, from & PARENT_EDGE != 0) {
            // (Between two of the parent's edges, where nothing is perturbed: only its
            // fixed-point position is read.)
            (true, true) => Corner { fixed: edge(from).0, ..Corner::default() },
            (false, false) if into != from => {
                circumcentre(f, a, &neighbours[into as usize], &neighbours[from as usize])
            }
            (false, true) => {
                let (p, q) = edge(from);
                bisector_meets_edge(f, a, &neighbours[into as usize], p, q)
            }
            (true, false) => {
                let (p, q) = edge(into);
                bisector_meets_edge(f, a, &neighbours[from as usize], p, q)
            }
            // A degenerate corner (the same bisector on both sides): where clipping put it.
            (false, false) => {
                let at = [self.clip[k].at[0] - a.at[0] + a.base[0], self.clip[k].at[1] - a.at[1] + a.base[1]];
                Corner { at, image: a.image, fixed: f.fixed(at, a) }
            }
        }
    }

    /// Recomputes the corners, perturbs the bisector edges and writes the fixed-point outline.
    // (Never inlined: its frame, with one piece's points, is then on the stack only while an
    // outline is finished, not in each level's frame of a build's recursion.)
    #[inline(never)]
    fn finish(
        &mut self,
        f: &Frame,
        a: &Site,
        neighbours: &[Site],
        near: Parent,
        n: usize,
        (out, work): (&mut [[i64; 2]], EdgeWork),
    ) -> Result<usize, OutlineFull> {
        let EdgeWork { mut shared, mut crossing, own } = work;
        // The points of one perturbed piece of a bisector edge (its start, inner points and
        // end: 2^depth + 1), on the stack: one outline's edges are built one after another, at
        // any level, and the points are written out before the next piece is perturbed.
        // (A shallow subdivision's few points in an array of their own, cheaper to set up.)
        let (mut shallow, mut deep);
        let points: &mut [[i64; 2]] = if f.depth <= SHALLOW_DEPTH {
            shallow = [[0i64; 2]; (1 << SHALLOW_DEPTH) + 1];
            &mut shallow
        } else {
            deep = [[0i64; 2]; (1 << MAX_PERTURBATION_DEPTH) + 1];
            &mut deep
        };
        let mut written = 0;
        // (The last point written, which a repeat of it is not written after.)
        let mut last = None;
        let mut push = |p: [i64; 2], written: &mut usize| -> Result<(), OutlineFull> {
            if last == Some(p) {
                return Ok(());
            }
            *out.get_mut(*written).ok_or(OutlineFull)? = p;
            *written += 1;
            last = Some(p);
            Ok(())
        };
        let corner_at = |k: usize| {
            let into = self.clip[if k == 0 { n - 1 } else { k - 1 }].label;
            self.corner(f, a, neighbours, near.outline, (into, self.clip[k].label), k)
        };
        let mut start = corner_at(0);
        let first = start;
        for k in 0..n {
            let end = if k + 1 == n { first } else { corner_at(k + 1) };
            let label = self.clip[k].label;
            if label & PARENT_EDGE != 0 {
                push(start.fixed, &mut written)?;
                start = end;
                continue;
            }
            // A bisector edge, split where the parent's outline crosses it (clipping a
            // non-convex parent bridges such crossings; the sibling has the pieces), each piece
            // perturbed: built by whichever of the two cells comes first.
            let b = &neighbours[label as usize];
            push(start.fixed, &mut written)?;
            let (key, forward, image) = edge_key(f, a, b, &start, &end);
            let to_surface = |p: [i64; 2]| [p[0].wrapping_add(image[0]), p[1].wrapping_add(image[1])];
            // (A neighbour built before this cell may have kept the edge; one built after it
            // will look for it.)
            let (built, unbuilt) = own.map_or((true, true), |k| ((label as usize) < k, (label as usize) > k));
            if let Some((points, m)) = shared.as_deref_mut().filter(|_| built).and_then(|s| s.take(&key)) {
                for i in 0..m {
                    push(to_surface(points[if forward { i } else { m - 1 - i }]), &mut written)?;
                }
                start = end;
                continue;
            }
            let mut kept = [[0i64; 2]; KEPT_POINTS];
            let (mut m, mut fits) = (0, true);
            let ends;
            let (pieces, nearby) = match crossing.as_deref_mut() {
                Some(CrossingScratch { pieces, listed }) => {
                    pieces[0] = start;
                    let nearby = Nearby::list(f, near, (&start, &end), listed);
                    // (No parent edge near: nothing to cross.)
                    let count = if nearby.is_empty() { 0 } else { crossings(f, a, b, (&start, &end), &nearby, pieces) };
                    pieces[count + 1] = end;
                    (&pieces[..count + 2], nearby)
                }
                // (Level 0: the edge is one piece, from corner to corner.)
                None => {
                    ends = [start, end];
                    (&ends[..], Nearby { parent: near, region: [0; 4], listed: None })
                }
            };
            for (i, w) in pieces.windows(2).enumerate() {
                points[0] = w[0].fixed;
                let inner = if f.perturbation > 0.0 && f.depth > 0 {
                    perturb(f, a, b, (&w[0], &w[1]), &nearby, points)
                } else {
                    1
                };
                for p in &points[usize::from(i == 0)..inner] {
                    push(*p, &mut written)?;
                    if m < KEPT_POINTS {
                        kept[m] = [p[0] - image[0], p[1] - image[1]];
                        m += 1;
                    } else {
                        fits = false;
                    }
                }
            }
            if let Some(shared) = shared.as_deref_mut().filter(|_| fits && unbuilt) {
                if !forward {
                    kept[..m].reverse();
                }
                shared.keep(key, &kept[..m]);
            }
            start = end;
        }
        if written > 1 && out[written - 1] == out[0] {
            written -= 1;
        }
        Ok(written)
    }
}

/// Neighbour lists up to this long are handed out nearest first by picking the nearest left
/// at each turn; longer ones (up to [`FEW`]) are sorted ([`sort_few`]).
const SHORT: usize = 16;

/// The key of a neighbour never handed out (at an infinite or NaN distance, or handed out
/// already): infinity's bits, above every finite distance's.
const FAR: u64 = 0x7FF0_0000_0000_0000;

/// Writes into `order` the places of `neighbours` (at most [`FEW`]) at a finite distance, by
/// distance, ties by place (a stable insertion sort); returns how many.
fn sort_few(neighbours: &[Site], distance: impl Fn(&Site) -> f64, order: &mut [u8; FEW]) -> usize {
    let mut keys = [0.0f64; FEW];
    let mut sorted = 0;
    for (i, s) in neighbours.iter().enumerate() {
        let key = distance(s);
        // (NaN and infinity are never handed out.)
        if key.is_nan() || key == f64::INFINITY {
            continue;
        }
        // (The sorted ones and the place after them, whose bounds hold every step.)
        let (keys, order) = (&mut keys[..=sorted], &mut order[..=sorted]);
        let mut at = sorted;
        while at > 0 && keys[at - 1] > key {
            (keys[at], order[at]) = (keys[at - 1], order[at - 1]);
            at -= 1;
        }
        // (At most FEW: fewer than 256.)
        (keys[at], order[at]) = (key, i as u8);
        sorted += 1;
    }
    sorted
}

const _: () = assert!(SHORT <= FEW);

/// The key both cells give the bisector edge of `a` and `b` from `start` to `end` (as `a`
/// runs it); whether `a` runs it in the key's direction; and the fixed-point offset of the
/// lower site's image, which kept points are relative to. (In two's complement: a period
/// past `i64`'s range, which only a degenerate stretch makes, wraps the same way in every
/// build, as the offset is taken off and put back; the skin fuzz target's finding 15.)
fn edge_key(f: &Frame, a: &Site, b: &Site, start: &Corner, end: &Corner) -> (EdgeKey, bool, [i64; 2]) {
    let (lo, hi) = sorted2(a, b);
    let forward = (a.id, a.image) == (lo.id, lo.image);
    let image = [0, 1].map(|k| i64::from(lo.image[k]).wrapping_mul(f.world_period[k]));
    let local = |c: &Corner| [c.fixed[0].wrapping_sub(image[0]), c.fixed[1].wrapping_sub(image[1])];
    let ends = if forward { [local(start), local(end)] } else { [local(end), local(start)] };
    let offset = [hi.image[0] - lo.image[0], hi.image[1] - lo.image[1]];
    (EdgeKey { ids: [lo.id, hi.id], offset, ends }, forward, image)
}

/// Neighbour lists up to this long are picked nearest first as the clipping asks for them,
/// longer ones sorted.
pub(super) const FEW: usize = 96;

// (A few are sorted by their places in bytes.)
const _: () = assert!(FEW <= 256);

/// Subdivision depths up to this one (the finer levels', where nearly all edges are) have
/// their points in arrays of their own length, which are cheaper to set up than the
/// deepest's.
const SHALLOW_DEPTH: u32 = 2;

/// Most parent-outline crossings one bisector edge is split at.
const MAX_CROSSINGS: usize = 16;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::skin::grid::EdgeGrid;
    use crate::skin::params::LevelParams;

    /// The edges visited for a query box, through the chunk boxes or through `nearby`.
    fn visited(search: impl FnOnce(&mut dyn FnMut(usize) -> bool)) -> ([usize; 64], usize) {
        let (mut seen, mut count) = ([0usize; 64], 0);
        search(&mut |e| {
            seen[count] = e;
            count += 1;
            false
        });
        (seen, count)
    }

    #[test]
    fn the_grid_finds_what_the_chunks_find() {
        // Star-shaped outlines with deep notches (edges of every length and slope), boxes and
        // points inside, around and far outside them.
        let mut rng = Rng::from_key(5, 6);
        let unit = 1i64 << 20;
        for vertices in [3usize, 17, 40, 64] {
            let mut outline = [[0i64; 2]; 64];
            for (k, v) in outline[..vertices].iter_mut().enumerate() {
                let angle = k as f64 / vertices as f64 * core::f64::consts::TAU;
                let r = (2.0 + 10.0 * rng.uniform_f64()) * unit as f64;
                *v = [(r * libm::cos(angle)) as i64, (r * libm::sin(angle)) as i64];
            }
            let outline = &outline[..vertices];
            let mut boxes = [[0i64; 4]; 64 / CHUNK + 1];
            let chunks = chunk_boxes(outline, &mut boxes);
            let mut grid = EdgeGrid::new();
            let corner = |pick: fn(i64, i64) -> i64| {
                outline.iter().fold(outline[0], |c, v| [pick(c[0], v[0]), pick(c[1], v[1])])
            };
            grid.fill(outline, (corner(i64::min), corner(i64::max)));
            let chunked = Parent { outline, chunks: &boxes[..chunks], grid: None, frame: &[] };
            let binned = Parent { grid: grid.of(vertices), ..chunked };
            assert!(binned.grid.is_some());
            let (mut met, mut inside) = (0, 0);
            for _ in 0..4000 {
                let at = |rng: &mut Rng| ((rng.uniform_f64() * 30.0 - 15.0) * unit as f64) as i64;
                let p = [at(&mut rng), at(&mut rng)];
                let half = [0, 1].map(|_| (rng.uniform_f64() * rng.uniform_f64() * 8.0 * unit as f64) as i64);
                let (low, high) = ([p[0] - half[0], p[1] - half[1]], [p[0] + half[0], p[1] + half[1]]);
                let slack = (rng.uniform_f64() * 1000.0) as i64;
                let expected = visited(|visit| chunked.edges_near((low, high), slack, visit));
                assert_eq!(visited(|visit| binned.edges_near((low, high), slack, visit)), expected);
                met += usize::from(expected.1 > 0);
                let contained = chunked.contains(p);
                assert_eq!(binned.contains(p), contained, "{p:?} in an outline of {vertices}");
                inside += usize::from(contained);
            }
            assert!(met > 300 && inside > 50, "{met} boxes met edges, {inside} points inside");
        }
    }

    #[test]
    fn clipping_is_one_sutherland_hodgman_pass() {
        // Star-shaped outlines of every length around the 64-vertex words of the marks
        // (their runs wrap around and cross words), cut by bisectors in every direction.
        let mut rng = Rng::from_key(7, 8);
        let site = |at: [f64; 2], id: u32| Site { at, base: at, id, image: [0, 0] };
        let (mut out, mut expected) = ([ClipVertex::default(); MAX_OUTLINE], [ClipVertex::default(); 400]);
        let mut cut = 0;
        for case in 0..600 {
            let n = [3, 5, 63, 64, 65, 127, 129, 200][case % 8];
            let vertices: [ClipVertex; 200] = core::array::from_fn(|k| {
                let angle = k as f64 / n as f64 * core::f64::consts::TAU;
                let r = 2.0 + 8.0 * rng.uniform_f64();
                ClipVertex { at: [r * libm::cos(angle), r * libm::sin(angle)], label: PARENT_EDGE | k as u32 }
            });
            let vertices = &vertices[..n];
            let a = site([rng.uniform_f64() - 0.5, rng.uniform_f64() - 0.5], 1);
            let b = site([16.0 * rng.uniform_f64() - 8.0, 16.0 * rng.uniform_f64() - 8.0], 2);
            // The pass vertex by vertex.
            let side = |p: [f64; 2]| {
                (p[0] - 0.5 * (a.at[0] + b.at[0])) * (b.at[0] - a.at[0])
                    + (p[1] - 0.5 * (a.at[1] + b.at[1])) * (b.at[1] - a.at[1])
            };
            let (mut m, mut farthest) = (0, 0.0f64);
            for k in 0..n {
                let (cur, following) = (vertices[k], vertices[(k + 1) % n]);
                let (sc, sn) = (side(cur.at), side(following.at));
                let mut keep = |v: ClipVertex| {
                    let r = [v.at[0] - a.at[0], v.at[1] - a.at[1]];
                    farthest = farthest.max(r[0] * r[0] + r[1] * r[1]);
                    expected[m] = v;
                    m += 1;
                };
                if sc <= 0.0 {
                    keep(cur);
                }
                if (sc <= 0.0) != (sn <= 0.0) {
                    let t = sc / (sc - sn);
                    let at = [0, 1].map(|i| cur.at[i] + t * (following.at[i] - cur.at[i]));
                    keep(ClipVertex { at, label: if sc <= 0.0 { 3 } else { cur.label } });
                }
            }
            match clip_by_bisector(vertices, (&a, &b, 3), &mut out) {
                Ok(None) => assert_eq!(&expected[..m], vertices, "case {case}: nothing beyond"),
                Ok(Some((count, reach))) => {
                    assert_eq!((&out[..count], reach), (&expected[..m], farthest), "case {case}");
                    cut += 1;
                }
                Err(OutlineFull) => panic!("case {case}: full"),
            }
            // The general form (a 32-bit target's only one) gives what the one-word form gives.
            let (mut general, mut one) = ([ClipVertex::default(); 400], [ClipVertex::default(); 400]);
            let by_general = clip::clip_marked::<{ MAX_OUTLINE / 64 }>(vertices, (&a, &b, 3), &mut general);
            assert_eq!(by_general, clip_by_bisector(vertices, (&a, &b, 3), &mut one), "case {case}");
            assert_eq!(general, one, "case {case}");
            // Too little room for the outline kept: full.
            if m > 1 && m < n {
                assert_eq!(clip_by_bisector(vertices, (&a, &b, 3), &mut out[..m - 1]), Err(OutlineFull));
                let short = &mut general[..m - 1];
                let full = clip::clip_marked::<{ MAX_OUTLINE / 64 }>(vertices, (&a, &b, 3), short);
                assert_eq!(full, Err(OutlineFull));
            }
        }
        assert!(cut > 300, "{cut} of 600 cut");
    }

    #[test]
    fn listed_edges_give_what_the_chunks_give() {
        // A star-shaped outline of 40 wiggly vertices, queries of every size around it.
        let level = LevelParams { perturbation: 0.1, perturbation_depth: 2, ..LevelParams::default() };
        let f = Frame::new(1, &level, 1, [64, 64], 2);
        let mut rng = Rng::from_key(3, 4);
        let unit = 1i64 << f.shift;
        let outline: [[i64; 2]; 40] = core::array::from_fn(|k| {
            let angle = k as f64 / 40.0 * core::f64::consts::TAU;
            let r = (8.0 + 4.0 * rng.uniform_f64()) * unit as f64;
            [(32.0 * unit as f64 + r * libm::cos(angle)) as i64, (32.0 * unit as f64 + r * libm::sin(angle)) as i64]
        });
        let mut boxes = [[0i64; 4]; 40 / CHUNK + 1];
        let chunks = chunk_boxes(&outline, &mut boxes);
        let parent = Parent { outline: &outline, chunks: &boxes[..chunks], grid: None, frame: &[] };
        let mut space = [0u32; LISTED];
        let corner = |p: [i64; 2]| Corner { fixed: p, ..Corner::default() };
        let (start, end) = (corner([34 * unit, 32 * unit]), corner([42 * unit, 36 * unit]));
        let nearby = Nearby::list(&f, parent, (&start, &end), &mut space);
        assert!(nearby.listed.is_some_and(|l| !l.is_empty() && l.len() < 40));
        let (mut inside, mut outside) = (0, 0);
        for _ in 0..2000 {
            // Around the listed edge's box, some inside the region, some reaching past it.
            let centre =
                [(33.0 + 10.0 * rng.uniform_f64()) * unit as f64, (31.0 + 6.0 * rng.uniform_f64()) * unit as f64];
            let half = [0, 1].map(|_| rng.uniform_f64() * 3.0 * unit as f64);
            let low = [(centre[0] - half[0]) as i64, (centre[1] - half[1]) as i64];
            let high = [(centre[0] + half[0]) as i64, (centre[1] + half[1]) as i64];
            let slack = f.inside_slack();
            let r = nearby.region;
            let held = r[0] <= low[0] - slack && r[1] <= low[1] - slack && high[0] + slack <= r[2];
            if held && high[1] + slack <= r[3] {
                inside += 1;
            } else {
                outside += 1;
            }
            let expected = visited(|visit| edges_near(&outline, parent.chunks, (low, high), slack, visit));
            assert_eq!(visited(|visit| nearby.edges_near((low, high), slack, visit)), expected);
        }
        assert!(inside > 50 && outside > 50, "{inside} {outside}");
    }
}
