//! The cell edges' perturbation (Ishii et al. §4.2, parameter 2): where the parent's outline
//! crosses a bisector edge, and the midpoint displacement of each piece, drawn and judged so
//! that both cells sharing the edge get the same points.

use super::super::params::MAX_PERTURBATION_DEPTH;
use super::super::sites::Site;
#[cfg(target_pointer_width = "64")]
use super::SHALLOW_DEPTH;
use super::frame::{Corner, Frame, bisector_meets_edge, sorted2};
use super::{MAX_CROSSINGS, Nearby, next};
use crate::rng::{Rng, Stream};

/// Exact orientation of the fixed-point triangle (a, b, c).
pub(super) fn orient_fixed(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i128 {
    i128::from(b[0] - a[0]) * i128::from(c[1] - a[1]) - i128::from(b[1] - a[1]) * i128::from(c[0] - a[0])
}

/// The corners where the parent's outline properly crosses the bisector edge of `a` and `b`
/// from `start` to `end`, in order from `start`, written from `out[1]` on; returns how many.
/// Each is computed as the sibling computes the same corner (the bisector meeting that
/// parent edge), so both cells get the same pieces.
pub(super) fn crossings(
    f: &Frame,
    a: &Site,
    b: &Site,
    (start, end): (&Corner, &Corner),
    nearby: &Nearby,
    out: &mut [Corner],
) -> usize {
    let (x, y) = (start.fixed, end.fixed);
    let (low, high) = ([x[0].min(y[0]), x[1].min(y[1])], [x[0].max(y[0]), x[1].max(y[1])]);
    let parent = nearby.parent.outline;
    let m = parent.len();
    let mut found = 0;
    // Position along start → end, which the crossings are ordered by.
    let along = |c: &Corner| {
        i128::from(c.fixed[0] - x[0]) * i128::from(y[0] - x[0])
            + i128::from(c.fixed[1] - x[1]) * i128::from(y[1] - x[1])
    };
    nearby.edges_near((low, high), 0, |e| {
        let (p, q) = (parent[e], parent[next(e, m)]);
        // (Proper crossings only: an end on the parent edge, where the edge starts or ends on
        // the parent's outline, is none. All four sides worked out, without branches: which
        // edges straddle follows the outline's shape, no pattern a processor could learn.)
        let straddles = |s1: i128, s2: i128| ((s1 > 0) & (s2 < 0)) | ((s1 < 0) & (s2 > 0));
        let proper = straddles(orient_fixed(p, q, x), orient_fixed(p, q, y))
            & straddles(orient_fixed(x, y, p), orient_fixed(x, y, q));
        if !proper || found == MAX_CROSSINGS {
            return false;
        }
        let c = bisector_meets_edge(f, a, b, p, q);
        // (Inserted in order: crossings are rare, and their positions recomputed as compared.)
        let t = along(&c);
        let mut i = found + 1;
        while i > 1 && along(&out[i - 1]) > t {
            out[i] = out[i - 1];
            i -= 1;
        }
        out[i] = c;
        found += 1;
        false
    });
    found
}

/// Orientation of the triangle (a, b, c): positive counter-clockwise.
pub(super) fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether `p` lies in the triangle (a, b, c), boundary included.
#[cfg(test)]
pub(super) fn in_triangle(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let (x, y, z) = (orient(a, b, p), orient(b, c, p), orient(c, a, p));
    ((x >= 0.0) & (y >= 0.0) & (z >= 0.0)) | ((x <= 0.0) & (y <= 0.0) & (z <= 0.0))
}

/// Whether `p` lies in the triangle (x, b, c) or in (y, b, c), boundary included: what
/// the triangle test (the signs of the three orientations) tells of each, their shared side
/// b–c worked out once.
pub(super) fn in_either_triangle(p: [f64; 2], (x, y): ([f64; 2], [f64; 2]), b: [f64; 2], c: [f64; 2]) -> bool {
    let side = orient(b, c, p);
    let within = |a: [f64; 2]| {
        let (u, w) = (orient(a, b, p), orient(c, a, p));
        ((u >= 0.0) & (side >= 0.0) & (w >= 0.0)) | ((u <= 0.0) & (side <= 0.0) & (w <= 0.0))
    };
    // (Both, without branches, on 64-bit targets: which one holds follows the perturbation's
    // draws. A 32-bit target's soft float skips the second where the first holds.)
    #[cfg(target_pointer_width = "64")]
    return within(x) | within(y);
    #[cfg(not(target_pointer_width = "64"))]
    return within(x) || within(y);
}

/// Whether the open segments p–q and r–s cross.
pub(super) fn cross(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let (d1, d2) = (orient(p, q, r), orient(p, q, s));
    let (d3, d4) = (orient(r, s, p), orient(r, s, q));
    (d1 * d2 < 0.0) & (d3 * d4 < 0.0)
}

/// The inner points of the edge between `a`'s and `b`'s cells from corner `start` to `end`
/// (as `a` runs it), by midpoint displacement V = A·2^(−n·h)·Rnd·L (paper §4.2 (2)), written
/// from `points[1]` on; returns 2^depth, or 1 (no inner points) where the wiggle would leave
/// the edge's diamond (the triangles it forms with the two centre points, which no other
/// edge enters) or its parent cell. Drawn from
/// the edge's own stream in the direction the lower id runs it, and judged on data both
/// cells share, so both cells get the same points.
pub(super) fn perturb(
    f: &Frame,
    a: &Site,
    b: &Site,
    ends: (&Corner, &Corner),
    nearby: &Nearby,
    points: &mut [[i64; 2]],
) -> usize {
    // The finer levels' shallow subdivisions (depth 2 and less, where nearly all edges are)
    // get a line of their own length, which is cheaper to set up than the deepest one's.
    #[cfg(target_pointer_width = "64")]
    if f.depth <= SHALLOW_DEPTH {
        return perturb_in::<{ (1 << SHALLOW_DEPTH) + 1 }>(f, a, b, ends, nearby, points);
    }
    perturb_in::<{ (1 << MAX_PERTURBATION_DEPTH) + 1 }>(f, a, b, ends, nearby, points)
}

/// [`perturb`] with a line of `N` points (at least 2^depth + 1).
#[inline(always)]
fn perturb_in<const N: usize>(
    f: &Frame,
    a: &Site,
    b: &Site,
    (start, end): (&Corner, &Corner),
    nearby: &Nearby,
    points: &mut [[i64; 2]],
) -> usize {
    let (lo, hi) = sorted2(a, b);
    let forward = (a.id, a.image) == (lo.id, lo.image);
    let (from, to) = if forward { (start, end) } else { (end, start) };
    // Both ends in `lo`'s frame.
    let place = |c: &Corner| {
        // (Nearly always in `lo`'s image: its own position, which adding 0·period leaves as it
        // is, as at [`Frame::relative`].)
        if c.image == lo.image {
            return c.at;
        }
        let d = [c.image[0] - lo.image[0], c.image[1] - lo.image[1]];
        [c.at[0] + f64::from(d[0]) * f.period[0], c.at[1] + f64::from(d[1]) * f.period[1]]
    };
    let (p0, p1) = (place(from), place(to));
    let length = crate::scalar::sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) + (p1[1] - p0[1]) * (p1[1] - p0[1]));
    let pieces = 1usize << f.depth;
    let mut line = [[0.0f64; 2]; N];
    line[0] = p0;
    line[pieces] = p1;
    if length > 0.0 {
        let normal = [-(p1[1] - p0[1]) / length, (p1[0] - p0[0]) / length];
        let offset = [hi.image[0] - lo.image[0], hi.image[1] - lo.image[1]];
        let key = Stream::EdgePerturbation.key()
            ^ (u64::from(f.level) << 58)
            ^ (u64::from(lo.id) << 29)
            ^ u64::from(hi.id)
            ^ ((offset[0] as u64 & 0xF) << 50)
            ^ ((offset[1] as u64 & 0xF) << 54);
        // The piece's own ends (an edge split at its parent's outline has several pieces).
        // (relative to `lo`'s image, the same for every periodic copy).
        // (In two's complement, as `edge_key` takes the same offset off: finding 15.)
        let local =
            |p: [i64; 2]| [0, 1].map(|k| p[k].wrapping_sub(i64::from(lo.image[k]).wrapping_mul(f.world_period[k])));
        let ends = [local(from.fixed), local(to.fixed)]
            .as_flattened()
            .iter()
            .fold(0u64, |h, &v| (h ^ v as u64).wrapping_mul(0x0000_0100_0000_01B3).rotate_left(29));
        let mut rng = Rng::from_key(f.seed, key ^ ends);
        // Rnd: standard normal, both values of each polar step in turn, redrawn beyond ±3 so
        // that no wiggle runs away.
        let mut spare = None;
        let mut rnd = || loop {
            let v = spare.take().unwrap_or_else(|| {
                let [first, second] = rng.normal_pair();
                spare = Some(second);
                first
            });
            if v.abs() <= 3.0 {
                break v;
            }
        };
        let mut step = pieces;
        for level in 1..=f.depth {
            let amplitude = f.amplitude[level as usize - 1] * length;
            let half = step / 2;
            let mut i = 0;
            while i < pieces {
                let rnd = rnd();
                let v = amplitude * rnd;
                let (x, y) = (line[i], line[i + step]);
                line[i + half] = [0.5 * (x[0] + y[0]) + v * normal[0], 0.5 * (x[1] + y[1]) + v * normal[1]];
                i += step;
            }
            step = half;
        }
    }
    let line = &line[..=pieces];
    let (x, y) = (lo.base, f.relative(hi, lo));
    if !line[1..pieces].iter().all(|&q| in_either_triangle(q, (x, y), p0, p1)) {
        return 1;
    }
    // The diamond's outline: no piece between points inside it can cross it where it is
    // convex.
    let diamond = [x, p0, y, p1];
    let turns = [orient(x, p0, y), orient(p0, y, p1), orient(y, p1, x), orient(p1, x, p0)];
    let convex = turns.iter().all(|&t| t > 0.0) || turns.iter().all(|&t| t < 0.0);
    let mut blocked = false;
    if !convex {
        for w in line.windows(2) {
            for k in 0..4 {
                let (r, s) = (diamond[k], diamond[(k + 1) % 4]);
                blocked |= cross(w[0], w[1], r, s);
            }
        }
    }
    // A child's edge must stay inside its parent: not cross the parent's outline anywhere,
    // and (near it) keep every point inside. The parent is the same for both cells that
    // share the edge, so they judge alike. (Level 0's "parent" is the surface or a box of
    // the cell's own; its edges may leave it.)
    if f.level > 0 && !blocked && !nearby.is_empty() {
        let (mut low, mut high) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for q in line {
            low = [low[0].min(q[0]), low[1].min(q[1])];
            high = [high[0].max(q[0]), high[1].max(q[1])];
        }
        let (low, high) = (f.fixed(low, lo), f.fixed(high, lo));
        let slack = f.inside_slack();
        let parent = nearby.parent.outline;
        let m = parent.len();
        let mut near = false;
        nearby.edges_near((low, high), slack, |e| {
            near = true;
            let (r, s) = (f.unfixed(parent[e], lo), f.unfixed(parent[next(e, m)], lo));
            blocked = line.windows(2).any(|w| cross(w[0], w[1], r, s));
            blocked
        });
        // With no crossing, only a first or last piece leaving from an end on the outline
        // can lie outside: its inner end tells (in fixed point, as it is written).
        if near && !blocked {
            inner_fixed(f, lo, (line, forward), points);
            let at = |k: usize| points[if forward { k } else { pieces - k }];
            // (One point when the edge has two pieces.)
            let inside = nearby.parent.contains(at(1)) && (pieces == 2 || nearby.parent.contains(at(pieces - 1)));
            return if inside { pieces } else { 1 };
        }
    }
    if blocked {
        return 1;
    }
    inner_fixed(f, lo, (line, forward), points);
    pieces
}

/// Writes the inner points of `line` (a perturbed edge from its start to its end, in the
/// frame of `lo`) in fixed point into `points` from `points[1]` on, in the direction `a`
/// runs the edge (`forward`: as `line` runs).
fn inner_fixed(f: &Frame, lo: &Site, (line, forward): (&[[f64; 2]], bool), points: &mut [[i64; 2]]) {
    let pieces = line.len() - 1;
    let mut write = |image: [i32; 2]| {
        for k in 1..pieces {
            points[if forward { k } else { pieces - k }] = f.fixed_in(line[k], image);
        }
    };
    // (Nearly every site is image 0, whose points need no offset.)
    match lo.image {
        [0, 0] => write([0, 0]),
        image => write(image),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn either_triangle_is_each_triangle_tested_apart() {
        // Points on a small grid (on sides and corners too) against diamonds of every shape,
        // convex or not, and degenerate ones.
        let mut rng = Rng::from_key(7, 0);
        let mut coordinate = || f64::from(rng.next_u32() % 9) - 4.0;
        for _ in 0..20_000 {
            let [p, x, y, b, c] = [(); 5].map(|()| [coordinate(), coordinate()]);
            let apart = in_triangle(p, x, b, c) || in_triangle(p, y, b, c);
            assert_eq!(in_either_triangle(p, (x, y), b, c), apart, "{p:?} {x:?} {y:?} {b:?} {c:?}");
        }
    }
}
