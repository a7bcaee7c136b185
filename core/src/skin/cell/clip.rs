//! Clipping a cell's outline by the bisector with one neighbour (one pass of
//! Sutherland–Hodgman), which decides which lines bound the Voronoi region.

use super::super::sites::Site;
use super::{ClipVertex, MAX_OUTLINE, OutlineFull};

/// Keeps the part of the outline `vertices` nearer `a` than `b` (neighbour `j`), into `out`;
/// returns the new vertex count and the largest squared distance of a kept vertex from `a`,
/// or None (writing nothing) if the whole outline is already nearer `a`.
///
/// The outline is one pass of Sutherland–Hodgman: each vertex on `a`'s side in turn, and
/// where an edge crosses the bisector, the crossing. Which vertices lie beyond is marked a
/// bit each first; then the runs between changes of side are copied whole and the crossings
/// made where they change.
// (Never inlined: each form of it is then in the code once, not at each call.)
#[inline(never)]
pub(super) fn clip_by_bisector(
    vertices: &[ClipVertex],
    (a, b, j): (&Site, &Site, u32),
    out: &mut [ClipVertex],
) -> Result<Option<(usize, f64)>, OutlineFull> {
    // Nearly every outline fits one word of marks: a form of its own then clears and searches
    // only that word (a third fewer instructions in a build). Both forms compute alike; a
    // 32-bit target, whose smallest parts are short of flash (the Cortex-M3's 256 KiB), has
    // the general one alone.
    #[cfg(target_pointer_width = "64")]
    if vertices.len() <= 64 {
        return clip_marked::<1>(vertices, (a, b, j), out);
    }
    clip_marked::<{ MAX_OUTLINE / 64 }>(vertices, (a, b, j), out)
}

/// [`clip_by_bisector`] with `WORDS` words of marks (at least one bit per vertex).
#[inline(always)]
pub(super) fn clip_marked<const WORDS: usize>(
    vertices: &[ClipVertex],
    (a, b, j): (&Site, &Site, u32),
    out: &mut [ClipVertex],
) -> Result<Option<(usize, f64)>, OutlineFull> {
    let n = vertices.len();
    let d = [b.at[0] - a.at[0], b.at[1] - a.at[1]];
    let m = [0.5 * (a.at[0] + b.at[0]), 0.5 * (a.at[1] + b.at[1])];
    let side = |p: [f64; 2]| (p[0] - m[0]) * d[0] + (p[1] - m[1]) * d[1];
    let reach = |p: [f64; 2]| {
        let r = [p[0] - a.at[0], p[1] - a.at[1]];
        r[0] * r[0] + r[1] * r[1]
    };
    // Bit k of `beyond` for vertex k (an outline has at most MAX_OUTLINE: the clip buffers'
    // length).
    debug_assert!(n <= 64 * WORDS && WORDS <= MAX_OUTLINE / 64);
    let mut beyond = [0u64; WORDS];
    let mut any = 0u64;
    for (word, chunk) in beyond.iter_mut().zip(vertices.chunks(64)) {
        // (On x86-64 two vertices at a time: `sides_beyond`.)
        #[cfg(target_arch = "x86_64")]
        {
            *word = sides_beyond(chunk, (m, d));
        }
        #[cfg(not(target_arch = "x86_64"))]
        for (i, v) in chunk.iter().enumerate() {
            *word |= u64::from(side(v.at) > 0.0) << i;
        }
        any |= *word;
    }
    if any == 0 {
        return Ok(None);
    }
    // The farthest of the vertices kept, as they are copied (the largest, whatever the order:
    // a NaN never counts).
    let mut farthest = 0.0f64;
    let is_beyond = |k: usize| beyond[k / 64] >> (k % 64) & 1 == 1;
    let mut written = 0;
    let mut k = 0;
    while k < n {
        // The run of vertices k..end on one side.
        let inside = !is_beyond(k);
        let end = first_from(&beyond, k, n, inside);
        if inside {
            // (A plain loop: runs are short, and a call to copy them would cost more.)
            let run = out.get_mut(written..written + (end - k)).ok_or(OutlineFull)?;
            for (o, v) in run.iter_mut().zip(&vertices[k..end]) {
                *o = *v;
                let r2 = reach(v.at);
                farthest = if r2 > farthest { r2 } else { farthest };
            }
            written += end - k;
        }
        // Where the edge from its last vertex leaves it (to vertex 0 when it ends the outline).
        let (cur, following) = (vertices[end - 1], vertices[if end == n { 0 } else { end }]);
        if end < n || is_beyond(0) == inside {
            let (sc, sn) = (side(cur.at), side(following.at));
            let t = sc / (sc - sn);
            let at = [cur.at[0] + t * (following.at[0] - cur.at[0]), cur.at[1] + t * (following.at[1] - cur.at[1])];
            let label = if inside { j } else { cur.label };
            *out.get_mut(written).ok_or(OutlineFull)? = ClipVertex { at, label };
            written += 1;
            let r2 = reach(at);
            farthest = if r2 > farthest { r2 } else { farthest };
        }
        k = end;
    }
    Ok(Some((written, farthest)))
}

/// Bit k for vertex k of `chunk` (at most 64) beyond the line through `m` across `d`: where
/// (p − m)·d > 0, computed as [`clip_marked`] computes it (the x term plus the y term), two
/// vertices a step in SSE2's lanes.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn sides_beyond(chunk: &[ClipVertex], (m, d): ([f64; 2], [f64; 2])) -> u64 {
    use safe_arch::*;
    let (mx, my) = (set_splat_m128d(m[0]), set_splat_m128d(m[1]));
    let (dx, dy) = (set_splat_m128d(d[0]), set_splat_m128d(d[1]));
    let side = |x: m128d, y: m128d| add_m128d(mul_m128d(sub_m128d(x, mx), dx), mul_m128d(sub_m128d(y, my), dy));
    let mut word = 0u64;
    let pairs = chunk.chunks_exact(2);
    let last = pairs.remainder();
    for (i, pair) in pairs.enumerate() {
        let (p, q) = (m128d::from(pair[0].at), m128d::from(pair[1].at));
        let s = side(unpack_low_m128d(p, q), unpack_high_m128d(p, q));
        word |= (move_mask_m128d(cmp_gt_mask_m128d(s, zeroed_m128d())) as u64) << (2 * i);
    }
    if let [v] = last {
        let s = side(set_splat_m128d(v.at[0]), set_splat_m128d(v.at[1]));
        word |= ((move_mask_m128d(cmp_gt_mask_m128d(s, zeroed_m128d())) & 1) as u64) << (chunk.len() - 1);
    }
    word
}

/// The first k in `from..n` whose bit in `bits` is `set`, or n.
pub(super) fn first_from(bits: &[u64], from: usize, n: usize, set: bool) -> usize {
    let flip = if set { 0 } else { u64::MAX };
    let mut w = from / 64;
    let mut word = (bits[w] ^ flip) >> (from % 64) << (from % 64);
    while word == 0 {
        w += 1;
        if w * 64 >= n {
            return n;
        }
        word = bits[w] ^ flip;
    }
    (w * 64 + word.trailing_zeros() as usize).min(n)
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn sides_beyond_marks_what_the_one_vertex_test_marks() {
        // Chunks of every length up to 64 around lines of every direction, with coordinates on
        // the line, signed zeros, huge, infinite and NaN ones among them.
        let mut rng = Rng::from_key(11, 0);
        let special = [0.0, -0.0, 1e300, -1e300, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 0.5];
        let mut coordinate = move || match rng.next_u32() % 16 {
            k @ 0..8 => special[k as usize],
            k => f64::from(k) - 12.0 + f64::from(rng.next_u32() % 4) * 0.25,
        };
        for round in 0..4_000 {
            let (m, d) = ([coordinate(), coordinate()], [coordinate(), coordinate()]);
            let mut vertices = [ClipVertex::default(); 64];
            for v in &mut vertices {
                v.at = [coordinate(), coordinate()];
            }
            let chunk = &vertices[..round % 64 + 1];
            let side = |p: [f64; 2]| (p[0] - m[0]) * d[0] + (p[1] - m[1]) * d[1];
            let one_by_one = chunk.iter().enumerate().fold(0u64, |w, (i, v)| w | (u64::from(side(v.at) > 0.0) << i));
            assert_eq!(sides_beyond(chunk, (m, d)), one_by_one, "{m:?} {d:?}");
        }
    }
}
