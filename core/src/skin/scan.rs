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
pub(super) fn contains(outline: &[[i64; 2]], p: [i64; 2]) -> bool {
    let n = outline.len();
    (0..n).filter(|&i| crosses(outline[i], outline[(i + 1) % n], p)).count() % 2 == 1
}

/// Calls `visit(column, row)` for every pixel whose centre `outline` (fixed point of `shift`
/// fractional bits) contains, in row order (columns and rows may lie outside the raster; the
/// caller wraps or clips them). `crossings` is scratch for one row's edge crossings (at least
/// the outline's length).
pub(super) fn for_each_pixel(outline: &[[i64; 2]], shift: u32, crossings: &mut [i64], mut visit: impl FnMut(i64, i64)) {
    let n = outline.len();
    if n < 3 {
        return;
    }
    let unit = 1i64 << shift;
    let (mut y0, mut y1) = (i64::MAX, i64::MIN);
    for v in outline {
        y0 = y0.min(v[1]);
        y1 = y1.max(v[1]);
    }
    // Rows whose centre lies in [y0, y1].
    let first = (y0 - unit / 2).div_euclid(unit);
    let last = (y1 - unit / 2).div_euclid(unit) + 1;
    for row in first..=last {
        let yc = pixel_centre(row, shift);
        let mut m = 0;
        for i in 0..n {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let (ay, by) = (a[1], b[1]);
            if (ay > yc) == (by > yc) {
                continue;
            }
            // The first pixel column whose centre is not left of the crossing: find it near
            // the rounded crossing, then settle it with the exact test.
            let (ax, bx) = (a[0], b[0]);
            let x = ax as f64 + (yc - ay) as f64 * (bx - ax) as f64 / (by - ay) as f64;
            let mut column = libm::floor((x - (unit / 2) as f64) / unit as f64) as i64;
            while crosses(a, b, [pixel_centre(column, shift), yc]) {
                column += 1;
            }
            while !crosses(a, b, [pixel_centre(column - 1, shift), yc]) {
                column -= 1;
            }
            // Now: centres at `column` and beyond are not left of the crossing.
            crossings[m] = column;
            m += 1;
        }
        let row_crossings = &mut crossings[..m];
        row_crossings.sort_unstable();
        // A centre is inside when an odd number of crossings lie strictly to its right: the
        // columns in [c1, c2), [c3, c4), ...
        for pair in row_crossings.chunks_exact(2) {
            for column in pair[0]..pair[1] {
                visit(column, row);
            }
        }
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
        let (mut count, mut scratch) = ([[0u8; 24]; 24], [0i64; 8]);
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
