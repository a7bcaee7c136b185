//! Which pixels a cell owns, decided exactly. Cell outlines are in fixed point and
//! neighbouring cells share their edges vertex for vertex (or, along a parent's edge, with
//! vertices exactly on it), so the even–odd rule with a half-open crossing test, done in
//! integers, gives every pixel centre to exactly one cell.

/// The centre of pixel `i` in fixed point of `shift` fractional bits.
pub(super) const fn pixel_centre(i: i64, shift: u32) -> i64 {
    (2 * i + 1) << (shift - 1)
}

/// Whether the edge a→b crosses the horizontal through `p` to the right of `p` (half-open in
/// y, strict in x), exactly.
fn crosses(a: [i64; 2], b: [i64; 2], p: [i64; 2]) -> bool {
    let (ax, ay, bx, by) = (a[0], a[1], b[0], b[1]);
    if (ay > p[1]) == (by > p[1]) {
        return false;
    }
    // p.x < ax + (p.y − ay)(bx − ax)/(by − ay), multiplied through by (by − ay).
    let lhs = i128::from(p[0] - ax) * i128::from(by - ay);
    let rhs = i128::from(p[1] - ay) * i128::from(bx - ax);
    if by > ay { lhs < rhs } else { lhs > rhs }
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
            inside ^= crosses(outline[i], outline[(i + 1) % n], p);
        }
    }
    inside
}

/// Calls `visit(column, row)` for every pixel whose centre `outline` (fixed point of `shift`
/// fractional bits) contains, in row order (columns and rows may lie outside the raster; the
/// caller wraps or clips them). `crossings` is scratch for edge crossings (at least the
/// outline's length): the outline is walked edge by edge over bands of rows that fit in it.
pub(super) fn for_each_pixel(outline: &[[i64; 2]], shift: u32, crossings: &mut [u64], mut visit: impl FnMut(i64, i64)) {
    let n = outline.len();
    if n < 3 || crossings.len() < n {
        return;
    }
    let unit = 1i64 << shift;
    let half = unit / 2;
    let (mut y0, mut y1, mut x0) = (i64::MAX, i64::MIN, i64::MAX);
    for v in outline {
        y0 = y0.min(v[1]);
        y1 = y1.max(v[1]);
        x0 = x0.min(v[0]);
    }
    // Rows whose centre lies in [y0, y1]; columns counted from `base`.
    let first = (y0 - half).div_euclid(unit);
    let last = (y1 - half).div_euclid(unit) + 1;
    let base = x0.div_euclid(unit) - 2;
    let band = (crossings.len() / n).max(1) as i64;
    let mut top = first;
    while top <= last {
        let bottom = (top + band - 1).min(last);
        let mut m = 0;
        for i in 0..n {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let (low, high) = (a[1].min(b[1]), a[1].max(b[1]));
            if low == high {
                continue;
            }
            // Rows whose centre yc has low <= yc < high (exactly one end above it).
            let from = (low - half + unit - 1).div_euclid(unit).max(top);
            let to = ((high - half + unit - 1).div_euclid(unit) - 1).min(bottom);
            let (ax, ay, bx, by) = (a[0] as f64, a[1] as f64, b[0] as f64, b[1] as f64);
            for row in from..=to {
                let yc = pixel_centre(row, shift);
                // The first pixel column whose centre is not left of the crossing: found near
                // the rounded crossing, then settled with the exact test.
                let x = ax + (yc as f64 - ay) * (bx - ax) / (by - ay);
                let mut column = libm::floor((x - half as f64) / unit as f64) as i64;
                while crosses(a, b, [pixel_centre(column, shift), yc]) {
                    column += 1;
                }
                while !crosses(a, b, [pixel_centre(column - 1, shift), yc]) {
                    column -= 1;
                }
                crossings[m] = (((row - top) as u64) << 40) | (column - base) as u64;
                m += 1;
            }
        }
        let found = &mut crossings[..m];
        found.sort_unstable();
        // A centre is inside when an odd number of crossings lie strictly to its right: in each
        // row, the columns in [c1, c2), [c3, c4), ...
        for pair in found.chunks_exact(2) {
            let row = top + (pair[0] >> 40) as i64;
            let (c1, c2) = ((pair[0] & ((1 << 40) - 1)) as i64 + base, (pair[1] & ((1 << 40) - 1)) as i64 + base);
            for column in c1..c2 {
                visit(column, row);
            }
        }
        top = bottom + 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_triangles_sharing_an_edge_own_every_pixel_once() {
        let u = 256;
        // A square split along a slanted diagonal, with vertices off the pixel grid.
        let (a, b, c, d) = ([3 * u / 2 + 7, 5], [20 * u + 3, 11], [20 * u + 9, 17 * u + 1], [13, 17 * u - 5]);
        let (mut count, mut scratch) = ([[0u8; 24]; 24], [0u64; 8]);
        for tri in [[a, b, c], [a, c, d]] {
            for_each_pixel(&tri, 8, &mut scratch, |x, y| count[y as usize][x as usize] += 1);
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
}
