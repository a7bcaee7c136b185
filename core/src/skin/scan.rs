//! Which pixels a cell owns, decided exactly. Cell outlines are in fixed point and
//! neighbouring cells share their edges vertex for vertex (or, along a parent's edge, with
//! vertices exactly on it), so the even–odd rule with a half-open crossing test, done in
//! integers, gives every pixel centre to exactly one cell.

/// The centre of pixel `i` in fixed point of `shift` fractional bits.
pub(super) const fn pixel_centre(i: i64, shift: u32) -> i64 {
    (2 * i + 1) << (shift - 1)
}

/// The farthest an outline vertex is taken to lie from the origin, per axis (fixed point). A
/// vertex beyond it (only a degenerate stretch puts one there: a Voronoi vertex of nearly
/// collinear centres or a periodic box that saturated at `i64`'s range, the skin fuzz
/// target's finding 15) is scanned as if there, so that the scan's sums and differences
/// (of two vertices, or of a vertex and a pixel centre: at most 6·2⁶⁰) stay within `i64`,
/// alike in every build. Real outlines lie within it: a surface of at most 2¹⁵ px in at most
/// 44 fractional bits is 2⁵⁹, and a periodic box reaches five periods (5·2⁵⁹ < 3·2⁶⁰).
const REACH: i64 = 3 << 60;

/// `v` within [`REACH`] on both axes.
#[inline]
fn within_reach(v: [i64; 2]) -> [i64; 2] {
    [v[0].clamp(-REACH, REACH), v[1].clamp(-REACH, REACH)]
}

/// Whether the edge a→b crosses the horizontal through `p` to the right of `p` (half-open in
/// y, strict in x), exactly.
fn crosses(a: [i64; 2], b: [i64; 2], p: [i64; 2]) -> bool {
    let (ax, ay, bx, by) = (a[0], a[1], b[0], b[1]);
    let straddles = (ay > p[1]) != (by > p[1]);
    // p.x < ax + (p.y − ay)(bx − ax)/(by − ay), multiplied through by (by − ay). (Worked out
    // whether or not the edge straddles, without branches: which edges do follows the
    // outline's shape, no pattern a processor could learn.)
    let lhs = i128::from(p[0] - ax) * i128::from(by - ay);
    let rhs = i128::from(p[1] - ay) * i128::from(bx - ax);
    straddles & (if by > ay { lhs < rhs } else { lhs > rhs })
}

/// [`crosses`], deciding first without products where it can: an edge that does not
/// straddle the horizontal through `p` is not crossed, and one that does is crossed when `p`
/// lies left of both its ends and not when it lies at or right of both (the crossing lies
/// between the ends' x, inclusive). Only an edge `p`'s row meets within its x range is
/// worked out exactly. (For point-in-outline tests, where most edges near the ray miss its
/// row; the scan, whose edges all straddle, keeps [`crosses`].)
/// The three cases are told apart without branches (which one an edge falls in follows the
/// outline's shape); only the rare exact case branches.
#[inline(always)]
fn crosses_quick(a: [i64; 2], b: [i64; 2], p: [i64; 2]) -> bool {
    let straddles = (a[1] > p[1]) != (b[1] > p[1]);
    let left = p[0] < a[0].min(b[0]);
    let between = !left & (p[0] < a[0].max(b[0]));
    if straddles & between {
        return crosses(a, b, p);
    }
    straddles & left
}

/// Whether `outline` contains `p` (even–odd rule, fixed point).
#[cfg(test)]
fn contains(outline: &[[i64; 2]], p: [i64; 2]) -> bool {
    let n = outline.len();
    (0..n).filter(|&i| crosses(outline[i], outline[(i + 1) % n], p)).count() % 2 == 1
}

/// [`contains`], passing over runs of `chunk` edges whose boxes (x0, y0, x1, y1) in `boxes`
/// the ray from `p` towards +x cannot meet.
pub(super) fn contains_chunked(outline: &[[i64; 2]], boxes: &[[i64; 4]], chunk: usize, p: [i64; 2]) -> bool {
    let n = outline.len();
    let mut inside = false;
    for (c, b) in boxes.iter().enumerate() {
        if b[1] > p[1] || b[3] < p[1] || b[2] < p[0] {
            continue;
        }
        for i in c * chunk..((c + 1) * chunk).min(n) {
            inside ^= crosses_quick(outline[i], outline[if i + 1 == n { 0 } else { i + 1 }], p);
        }
    }
    inside
}

/// [`contains`], testing only the edges in `edges` (bit k for edge k), which must hold every
/// edge the ray from `p` towards +x can cross.
pub(super) fn contains_among(outline: &[[i64; 2]], edges: u64, p: [i64; 2]) -> bool {
    let mut inside = false;
    super::grid::each_edge(edges, |i| {
        // (The last edge ends at the first vertex.)
        inside ^= crosses_quick(outline[i], *outline.get(i + 1).unwrap_or(&outline[0]), p);
        false
    });
    inside
}

/// Rows a cell may span for [`for_each_span`]'s direct path.
const DIRECT_ROWS: usize = 64;

/// Crossings [`for_each_span`] holds at once (2 KiB, on the caller's stack).
const HELD: usize = 256;

/// [`for_each_span`]'s working memory: one per render, not one per cell.
pub(super) type Held = [u64; HELD];

/// Working memory for [`for_each_span`].
pub(super) const fn held() -> Held {
    [0; HELD]
}

/// Bits of a crossing's sort key below its column: the edge's index, which makes every key of
/// a band unique (an outline has at most [`super::MAX_OUTLINE`] edges).
const EDGE_BITS: u32 = 11;

/// Bits of a crossing's sort key for its column, counted from the outline's left.
const COLUMN_BITS: u32 = 40;

const _: () = assert!(super::MAX_OUTLINE <= 1 << EDGE_BITS);
// A band's row (below HELD) fits above the column and the edge.
const _: () = assert!((HELD as u64) < 1 << (64 - COLUMN_BITS - EDGE_BITS));

/// Calls `visit(row, c1, c2)` for every run of pixels `c1..c2` (c1 < c2) of one row in
/// `rows` (inclusive) whose centres `outline` (fixed point of `shift` fractional bits)
/// contains, in row order (columns, and rows in the window, may lie outside the raster; the
/// caller wraps or clips them). The work is bounded by the window's rows times the outline's
/// edges, however far the outline reaches (a perturbed edge of a strongly stretched level can
/// reach 10⁷ rows past a 33-row surface: the skin fuzz target's finding 14). Its working
/// memory is `held`, [`HELD`] crossings whatever the outline's length (its contents on entry
/// do not matter).
///
/// A centre is inside when an odd number of crossings lie strictly to its right: in each row,
/// the columns in [c1, c2), [c3, c4), ... of the sorted crossings. Most cells are crossed
/// twice in every row: their crossings are kept per row directly. Otherwise the outline is
/// walked edge by edge over bands of rows whose crossings fit in [`HELD`], and sorted; a
/// row with more crossings than that (an outline of over [`HELD`] edges) is taken in
/// passes, each collecting the next crossings in order (by row, column and edge, which is
/// unique) and drawing the runs of an even number of them.
pub(super) fn for_each_span(
    outline: &[[i64; 2]],
    shift: u32,
    rows: [i64; 2],
    held: &mut Held,
    mut visit: impl FnMut(i64, i64, i64),
) {
    let n = outline.len();
    if n < 3 {
        return;
    }
    // Keys tell edges apart by their index (a longer outline is no cell's).
    debug_assert!(n <= super::MAX_OUTLINE);
    let half = 1i64 << (shift - 1);
    let (mut y0, mut y1, mut x0) = (i64::MAX, i64::MIN, i64::MAX);
    for &v in outline {
        y0 = y0.min(v[1]);
        y1 = y1.max(v[1]);
        x0 = x0.min(v[0]);
    }
    // (Within reach: the extremes of the vertices within reach, as clamping is monotone.)
    let ([x0, y0], y1) = (within_reach([x0, y0]), y1.clamp(-REACH, REACH));
    // Rows whose centre lies in [y0, y1]. (An arithmetic shift right by `shift` is the floor of
    // the division by the unit.)
    let first = ((y0 - half) >> shift).max(rows[0]);
    let last = (((y1 - half) >> shift) + 1).min(rows[1]);
    if first > last {
        return;
    }
    let rows = (last - first + 1) as usize;
    if rows <= DIRECT_ROWS {
        // Each row's first two crossings, in `held`, and how many it has.
        let mut count = [0u8; DIRECT_ROWS];
        let pair = &mut held[..2 * rows];
        each_crossing(outline, shift, first, last, |_, row, column| {
            let r = (row - first) as usize;
            let k = count[r];
            if k < 2 {
                pair[2 * r + usize::from(k)] = column as u64;
            }
            count[r] = k.saturating_add(1);
        });
        if count[..rows].iter().all(|&k| k == 0 || k == 2) {
            for (r, (&k, c)) in count[..rows].iter().zip(pair.chunks_exact(2)).enumerate() {
                let (c1, c2) = (c[0] as i64, c[1] as i64);
                let (c1, c2) = (c1.min(c2), c1.max(c2));
                if k == 2 && c1 < c2 {
                    visit(first + r as i64, c1, c2);
                }
            }
            return;
        }
    }
    // Columns counted from `base` in the sort keys, modulo 2^40 (an outline 2^40 px wide, which
    // only a degenerate stretch makes, has its columns wrap, drawing wrong pixels but no more).
    let base = (x0 >> shift) - 2;
    let column_mask = (1u64 << COLUMN_BITS) - 1;
    let band = (HELD / n).max(1) as i64;
    let mut top = first;
    while top <= last {
        let bottom = (top + band - 1).min(last);
        // The keys from `floor` on are still to draw.
        let mut floor = 0u64;
        loop {
            // The smallest keys from `floor` on: all those up to `limit`, which drops when
            // `held` fills and its larger half is let go.
            let (mut m, mut limit) = (0, u64::MAX);
            each_crossing(outline, shift, top, bottom, |edge, row, column| {
                let key = ((row - top) as u64) << (COLUMN_BITS + EDGE_BITS)
                    | ((column - base) as u64 & column_mask) << EDGE_BITS
                    | edge as u64;
                if key < floor || key > limit {
                    return;
                }
                if m == HELD {
                    held.sort_unstable();
                    m = HELD / 2;
                    limit = held[m - 1];
                    if key > limit {
                        return;
                    }
                }
                held[m] = key;
                m += 1;
            });
            let found = &mut held[..m];
            found.sort_unstable();
            // Every key left is here unless some were let go; then an even number are drawn
            // now and the rest found again.
            let whole = limit == u64::MAX;
            let drawn = if whole { m } else { m & !1 };
            for pair in found[..drawn].chunks_exact(2) {
                let row = top + (pair[0] >> (COLUMN_BITS + EDGE_BITS)) as i64;
                let column = |key: u64| ((key >> EDGE_BITS) & column_mask) as i64 + base;
                let (c1, c2) = (column(pair[0]), column(pair[1]));
                if c1 < c2 {
                    visit(row, c1, c2);
                }
            }
            if whole {
                break;
            }
            floor = found[drawn - 1] + 1;
        }
        top = bottom + 1;
    }
}

/// Calls `put(edge, row, column)` for every crossing of edge `edge` of `outline` (the one
/// ending at vertex `edge`) with the centre line of a row in `top..=bottom`: `column` is
/// the first pixel column whose centre is not left of the crossing (the half-open [`crosses`]
/// test, decided exactly).
#[inline]
fn each_crossing(outline: &[[i64; 2]], shift: u32, top: i64, bottom: i64, mut put: impl FnMut(usize, i64, i64)) {
    let unit = 1i64 << shift;
    let half = unit / 2;
    // 2^−shift: scaling by it is exact, like dividing by `unit`.
    let to_pixels = 1.0 / unit as f64;
    // The first row whose centre is not below y (monotone in y, so that the rows of an edge's
    // lower and higher end are the lower and higher of its ends' rows), made once per vertex,
    // as each vertex is taken within reach.
    let first_row = |y: i64| (y - half + unit - 1) >> shift;
    let last = within_reach(outline[outline.len() - 1]);
    let (mut a, mut row_a) = (last, first_row(last[1]));
    for (edge, &b) in outline.iter().enumerate() {
        let b = within_reach(b);
        let row_b = first_row(b[1]);
        // The edge a→b (in any order: the caller sorts the crossings by row).
        let (a, row_a) = (core::mem::replace(&mut a, b), core::mem::replace(&mut row_a, row_b));
        // Rows whose centre yc has low <= yc < high (exactly one end above it).
        let from = row_a.min(row_b).max(top);
        let to = (row_a.max(row_b) - 1).min(bottom);
        if from > to {
            continue;
        }
        // The edge crosses the row through yc at X = ax + (yc − ay)·dx/dy, and `crosses`
        // holds for the pixel centres left of X: the first column not left of it is
        // ceil((X − half) / unit) = ax_pixels + ceil(f), with ax − half = ax_pixels·unit +
        // ax_rest (0 <= ax_rest < unit) and f = (ax_rest + (yc − ay)·dx/dy) / unit.
        //
        // In f64, with |dx|, |dy| < 2^52 and shift <= 52 every integer here converts exactly
        // (yc − ay too, |yc − ay| <= |dy|, and stepping it by the unit stays exact); slope =
        // dx/dy, the product and the sum each round once (relative error 2^−53), so
        // |f̃ − f| <= (3.01·|dx| + 1.01·ax_rest)·2^−53 / unit <= (3.01·2^20 + 1.01)·2^−53 <
        // 2^−31 when |dx| < 2^20 pixels; the fraction of f̃ rounds by at most 2^−53 more. So
        // when that fraction is more than 2^−30 from 0 and 1, f lies strictly between the
        // same integers and ceil(f) = floor(f̃) + 1. Otherwise (X within 2^−30 px of a pixel
        // centre, or a huge edge) the exact integer test settles it.
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let fast = shift <= 52 && dx.unsigned_abs() < 1 << 52.min(shift + 20) && dy.unsigned_abs() < 1 << 52;
        let ax_pixels = (a[0] - half) >> shift;
        let ax_rest = ((a[0] - half) & (unit - 1)) as f64;
        let slope = dx as f64 / dy as f64;
        // yc − ay.
        let mut rise = (pixel_centre(from, shift) - a[1]) as f64;
        for row in from..=to {
            let f = (ax_rest + rise * slope) * to_pixels;
            rise += unit as f64;
            // floor(f) and f − floor(f) without a conversion, for |f| < 2^51 (on the fast path
            // |f| <= 2^20 + 1): f + 1.5·2^52 is f rounded to an integer, exactly, in the low
            // bits of the sum.
            let sum = f + ROUND;
            let near = sum - ROUND;
            let up = near > f;
            let whole = (sum.to_bits() as i64).wrapping_sub(ROUND.to_bits() as i64).wrapping_sub(i64::from(up));
            let fraction = f - if up { near - 1.0 } else { near };
            let column = if fast && fraction > MARGIN && fraction < 1.0 - MARGIN {
                ax_pixels + whole + 1
            } else {
                // Found near the estimate, then settled with the exact test.
                let yc = pixel_centre(row, shift);
                let mut column = ax_pixels.saturating_add(floor(f));
                while crosses(a, b, [pixel_centre(column, shift), yc]) {
                    column += 1;
                }
                while !crosses(a, b, [pixel_centre(column - 1, shift), yc]) {
                    column -= 1;
                }
                column
            };
            put(edge, row, column);
        }
    }
}

/// How close (in pixels) a crossing's estimate may come to a pixel centre before the exact
/// test decides (see [`each_crossing`]).
const MARGIN: f64 = 1.0 / (1u64 << 30) as f64;

/// 1.5·2^52, which rounds an f64 below 2^51 in magnitude to an integer when added.
const ROUND: f64 = 6_755_399_441_055_744.0;

/// The largest integer <= `x`, for |x| < 2^63 (saturating beyond; NaN gives 0).
fn floor(x: f64) -> i64 {
    let t = x as i64;
    t - i64::from((t as f64) > x)
}

/// Calls `visit(column, row)` for every pixel whose centre `outline` (fixed point of `shift`
/// fractional bits) contains, in row order; see [`for_each_span`].
#[cfg(test)]
fn for_each_pixel(outline: &[[i64; 2]], shift: u32, mut visit: impl FnMut(i64, i64)) {
    for_each_span(outline, shift, [i64::MIN, i64::MAX], &mut held(), |row, c1, c2| {
        (c1..c2).for_each(|column| visit(column, row))
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_triangles_sharing_an_edge_own_every_pixel_once() {
        let u = 256;
        // A square split along a slanted diagonal, with vertices off the pixel grid.
        let (a, b, c, d) = ([3 * u / 2 + 7, 5], [20 * u + 3, 11], [20 * u + 9, 17 * u + 1], [13, 17 * u - 5]);
        let mut count = [[0u8; 24]; 24];
        for tri in [[a, b, c], [a, c, d]] {
            for_each_pixel(&tri, 8, |x, y| count[y as usize][x as usize] += 1);
        }
        let mut inside = 0;
        for (y, row) in count.iter().enumerate() {
            for (x, &k) in row.iter().enumerate() {
                let p = [pixel_centre(x as i64, 8), pixel_centre(y as i64, 8)];
                let expected = u8::from(contains(&[a, b, c, d], p));
                assert_eq!(k, expected, "pixel ({x}, {y})");
                inside += usize::from(k);
            }
        }
        assert!(inside > 300, "{inside}");
    }

    #[test]
    fn the_quick_crossing_test_answers_as_the_exact_one() {
        // Edges and points on a small grid (ends level with the point, the point on an end's
        // x, on the edge itself) and spread wide (products past i64).
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let (mut crossed, mut worked) = (0, 0);
        for case in 0..200_000 {
            let span = if case % 2 == 0 { 9 } else { 1 << 58 };
            let mut coordinate = || (next(&mut state) % (2 * span + 1)) as i64 - span as i64;
            let (a, b, p) = ([coordinate(), coordinate()], [coordinate(), coordinate()], [coordinate(), coordinate()]);
            let exact = crosses(a, b, p);
            assert_eq!(crosses_quick(a, b, p), exact, "{a:?} → {b:?}, {p:?}");
            crossed += usize::from(exact);
            let straddles = (a[1] > p[1]) != (b[1] > p[1]);
            worked += usize::from(straddles && a[0].min(b[0]) <= p[0] && p[0] < a[0].max(b[0]));
        }
        assert!(crossed > 20_000 && worked > 10_000, "{crossed} crossed, {worked} worked out exactly");
    }

    /// A xorshift step.
    fn next(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    #[test]
    fn every_crossing_is_the_first_column_not_left_of_the_edge() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        for shift in [8, 20, 32, 44] {
            let unit = 1i64 << shift;
            for case in 0..20_000 {
                let mut r = |bits: u32| {
                    let bits = bits.min(62);
                    (next(&mut state) >> (64 - bits)) as i64 - (1i64 << (bits - 1))
                };
                let a = [r(shift + 16), r(shift + 16)];
                // Mostly short edges; some wider than the fast path takes (2^20 px), some
                // through pixel centres or a unit beside them.
                let (dx, dy) = match case % 4 {
                    0 => (r(shift + 6), r(shift + 6)),
                    1 => (r(shift + 23), r(shift + 3)),
                    2 => (0, r(shift + 4)),
                    _ => (2 * unit * r(5), unit * r(4)),
                };
                let mut a = a;
                if case % 8 >= 4 {
                    // A corner on, or a unit beside, a pixel centre.
                    a = [pixel_centre(a[0] >> shift, shift) + r(2), pixel_centre(a[1] >> shift, shift)];
                }
                let b = [a[0] + dx, a[1] + dy];
                let (low, high) = (a[1].min(b[1]), a[1].max(b[1]));
                // Row centres (2k + 1)·unit/2 in [low, high).
                let (half, unit) = (i128::from(unit / 2), i128::from(unit));
                let first = -(half - i128::from(low)).div_euclid(unit);
                let last = (i128::from(high) - 1 - half).div_euclid(unit);
                let rows = (last - first + 1).max(0) as usize;
                let mut found = 0;
                // Both directions of the edge (an outline of two vertices).
                each_crossing(&[a, b], shift, i64::MIN / 4, i64::MAX / 4, |_, row, column| {
                    let yc = pixel_centre(row, shift);
                    assert!((low..high).contains(&yc), "{a:?} {b:?}: row {row}");
                    let left = crosses(a, b, [pixel_centre(column - 1, shift), yc]);
                    let here = crosses(a, b, [pixel_centre(column, shift), yc]);
                    assert!(left && !here, "{a:?} {b:?} shift {shift}: row {row}, column {column}");
                    found += 1;
                });
                assert_eq!(found, 2 * rows, "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn spans_are_the_pixels_inside_on_both_paths() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        for shift in [8u32, 32] {
            let unit = 1i64 << shift;
            for case in 0..400 {
                // A star around (20, 20) px (two crossings per row, mostly), or a random
                // polygon (often self-crossing: more).
                let n = 3 + (next(&mut state) % 14) as usize;
                let mut outline = [[0i64; 2]; 16];
                for (i, v) in outline[..n].iter_mut().enumerate() {
                    let random = (next(&mut state) >> 40) as i64 % (40 * unit);
                    *v = if case % 2 == 0 {
                        let t = core::f64::consts::TAU * i as f64 / n as f64;
                        let radius = (4 + (next(&mut state) % 12) as i64) * unit;
                        let (s, c) = libm::sincos(t);
                        [20 * unit + (radius as f64 * c) as i64, 20 * unit + (radius as f64 * s) as i64]
                    } else {
                        [random, (next(&mut state) >> 40) as i64 % (40 * unit)]
                    };
                    if i % 3 == 0 {
                        // Corners on pixel centres.
                        *v = [pixel_centre(v[0] >> shift, shift), pixel_centre(v[1] >> shift, shift)];
                    }
                }
                let outline = &outline[..n];
                let mut grid = [[0u8; 44]; 44];
                for_each_pixel(outline, shift, |x, y| grid[y as usize][x as usize] += 1);
                for (y, row) in grid.iter().enumerate() {
                    for (x, &k) in row.iter().enumerate() {
                        let p = [pixel_centre(x as i64, shift), pixel_centre(y as i64, shift)];
                        assert_eq!(k, u8::from(contains(outline, p)), "case {case}: ({x}, {y})");
                    }
                }
            }
        }
    }

    #[test]
    fn rows_crossed_more_often_than_the_stack_holds_are_drawn_in_passes() {
        // Combs: a top edge of `teeth` spikes over a bar, each row through the spikes crossed
        // twice per spike (more than HELD for the larger ones), tall enough (over DIRECT_ROWS
        // rows) or short, with corners on and off pixel centres.
        let u = 256i64;
        for (teeth, height, offset) in
            [(40usize, 80i64, 0i64), (150, 40, 7), (300, 40, 128), (700, 20, 3), (690, 20, 5)]
        {
            let mut outline = [[0i64; 2]; 2 * 700 + 2];
            let width = 3 * teeth as i64;
            outline[0] = [width * u + offset, height * u];
            outline[1] = [offset, height * u];
            for t in 0..teeth {
                let x = 3 * t as i64 * u + offset;
                outline[2 + 2 * t] = [x + u, 2 * u + offset];
                outline[3 + 2 * t] = [x + 2 * u + 100, (height - 3) * u];
            }
            let n = 2 * teeth + 2;
            // Starting mid-comb too, so that smaller crossings come after the stack fills.
            outline[..n].rotate_left(offset as usize % 7 * n / 13);
            let outline = &outline[..n];
            assert!(outline.len() > HELD || teeth < 100);
            let (columns, rows) = (width as usize + 2, height as usize + 2);
            let mut grid = [0u8; 2102 * 42];
            assert!(columns * rows <= grid.len());
            for_each_pixel(outline, 8, |x, y| grid[y as usize * columns + x as usize] += 1);
            let mut inside = 0;
            for y in 0..rows {
                for x in 0..columns {
                    let p = [pixel_centre(x as i64, 8), pixel_centre(y as i64, 8)];
                    let k = grid[y * columns + x];
                    assert_eq!(k, u8::from(contains(outline, p)), "{teeth} teeth: ({x}, {y})");
                    inside += usize::from(k);
                }
            }
            assert!(inside > teeth * height as usize / 2, "{teeth} teeth: {inside} pixels");
        }
    }
}
