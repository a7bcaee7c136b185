//! Triangles of one polygon with holes: ear clipping (Meisters' two-ears theorem: a simple
//! polygon of more than three points has two ears, corners whose triangle holds no other
//! point) after bridging each hole to the outer ring (Eberly, "Triangulation by Ear
//! Clipping", §3: a ray from the hole's rightmost point finds a point of the outer ring it
//! sees; the hole is spliced in there by a two-way bridge edge).
//!
//! The polygon lives in caller scratch as a doubly linked cycle of `m` nodes (the outer
//! ring's `n` points, each hole's points plus its two bridge ends: `m = n + Σ (hᵢ + 2)`),
//! four words a node. Work, in point tests: `m²` to mark the ears, then per clipped corner a
//! scan of at most the remaining nodes for a marked ear and two ear tests of the corner's
//! neighbours (only their status can change when an ear is clipped, Eberly §2), so at most
//! `3·m²` in all, whatever the points hold; a bridge costs `m` edge tests more per hole.
//!
//! Exact in its bookkeeping: clipping a corner splits the cycle's signed area into the
//! triangle's and the rest's, so the triangles' signed areas add up to the polygon's
//! (outer ring's minus the holes') up to the rounding of their f64 cross products. A corner
//! of zero area (collinear points, a repeated point, the fold of a slit, or one whose f64
//! cross product at any of its corners rounds to zero) is removed without a triangle. The ear tests' orientations are exact (Shewchuk's adaptive predicate), so a
//! simple ring always has an ear, however close its points. When no corner is marked an ear
//! (a ring that crosses itself), the corner of largest area is clipped anyway, so the work
//! stays bounded; a corner of negative area is then dropped rather than written clockwise.

use super::Ring;

/// Twice the signed area of triangle (a, b, c), positive counter-clockwise with y up.
pub(crate) fn cross(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> f64 {
    let (ax, ay) = (f64::from(a[0]), f64::from(a[1]));
    (f64::from(b[0]) - ax) * (f64::from(c[1]) - ay) - (f64::from(b[1]) - ay) * (f64::from(c[0]) - ax)
}

/// The orientation of (a, b, c) with an exact sign: positive counter-clockwise with y up,
/// negative clockwise, zero only for collinear points. [`cross`] rounds: two f32 points
/// `FLT_MIN` apart, seen from a point 10 px away, have the same f64 cross product, which
/// put a point outside an ear on its edge and left a simple ring with no ear. Shewchuk's
/// adaptive test ("Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
/// Predicates", 1997) is exact for f32 points, whose differences' products neither overflow
/// nor underflow in f64.
fn orient(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> f64 {
    let at = |p: [f32; 2]| robust::Coord { x: p[0], y: p[1] };
    robust::orient2d(at(a), at(b), at(c))
}

/// Whether `p` lies in or on counter-clockwise triangle (a, b, c) (exact).
fn in_triangle(a: [f32; 2], b: [f32; 2], c: [f32; 2], p: [f32; 2]) -> bool {
    orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0
}

/// Scratch words per node of the cycle.
pub(crate) const WORDS_PER_NODE: usize = 4;

/// Twice the signed area of `ring` (shoelace over its points), positive counter-clockwise.
pub(crate) fn ring_area2(ring: &Ring, points: &[[f32; 2]]) -> f64 {
    let pts = &points[ring.first_point as usize..][..ring.point_count as usize];
    let mut sum = 0.0;
    for (i, a) in pts.iter().enumerate() {
        let b = pts[(i + 1) % pts.len()];
        sum += f64::from(a[0]) * f64::from(b[1]) - f64::from(b[0]) * f64::from(a[1]);
    }
    sum
}

/// Offset in `ring` of its rightmost point (the first of the largest x).
pub(crate) fn rightmost(ring: &Ring, points: &[[f32; 2]]) -> u32 {
    let pts = &points[ring.first_point as usize..][..ring.point_count as usize];
    let (mut best, mut x) = (0, f32::NEG_INFINITY);
    for (i, q) in pts.iter().enumerate() {
        if q[0] > x {
            (best, x) = (i, q[0]);
        }
    }
    best as u32
}

/// The cycle being clipped: per node its point index, neighbours and ear mark.
struct Cycle<'a> {
    point: &'a mut [u32],
    next: &'a mut [u32],
    prev: &'a mut [u32],
    ear: &'a mut [u32],
    len: usize,
}

impl Cycle<'_> {
    fn push(&mut self, p: u32) -> u32 {
        let n = self.len as u32;
        self.point[self.len] = p;
        self.len += 1;
        n
    }
    fn link(&mut self, a: u32, b: u32) {
        self.next[a as usize] = b;
        self.prev[b as usize] = a;
    }
    /// Pushes `count` points of `ring` from offset `start`, backwards when `reverse`, linked
    /// in a chain; returns the first node.
    fn push_chain(&mut self, ring: &Ring, start: u32, count: u32, reverse: bool) -> u32 {
        let n = ring.point_count;
        let first = self.len as u32;
        for k in 0..count {
            let offset = if reverse { (start + n - k % n) % n } else { (start + k) % n };
            let i = self.push(ring.first_point + offset);
            if k > 0 {
                self.link(i - 1, i);
            }
        }
        first
    }
}

/// Triangulates the polygon of outer ring `outer` and the holes `holes` (ring indices, each
/// of at least 3 points; reordered here by their rightmost x), calling `emit` with each
/// triangle's point indices, counter-clockwise. `scratch` holds [`WORDS_PER_NODE`] words per
/// node; the outer ring has at least 3 points.
pub(crate) fn polygon(
    rings: &[Ring],
    outer: usize,
    holes: &mut [u32],
    right: &[u32],
    points: &[[f32; 2]],
    scratch: &mut [u32],
    emit: &mut impl FnMut([u32; 3]),
) {
    let ring = &rings[outer];
    let m =
        ring.point_count as usize + holes.iter().map(|&h| rings[h as usize].point_count as usize + 2).sum::<usize>();
    let (point, rest) = scratch.split_at_mut(m);
    let (next, rest) = rest.split_at_mut(m);
    let (prev, rest) = rest.split_at_mut(m);
    let mut c = Cycle { point, next, prev, ear: &mut rest[..m], len: 0 };
    // The outer ring counter-clockwise, each hole clockwise, whatever order they came in.
    let n = ring.point_count;
    c.push_chain(ring, 0, n, ring_area2(ring, points) < 0.0);
    c.link(n - 1, 0);
    // Holes by rightmost x, largest first (ties by ring index): each bridges to what is in.
    let x = |h: u32| points[(rings[h as usize].first_point + right[h as usize]) as usize][0];
    holes.sort_unstable_by(|&a, &b| x(b).total_cmp(&x(a)).then(a.cmp(&b)));
    for &h in holes.iter() {
        let hole = &rings[h as usize];
        let start = right[h as usize];
        let bridge = find_bridge(&c, points, points[(hole.first_point + start) as usize]);
        // bridge → M → the hole … → M again → a copy of bridge → bridge's old next.
        let after = c.next[bridge as usize];
        let first = c.push_chain(hole, start, hole.point_count + 1, ring_area2(hole, points) > 0.0);
        let last = c.len as u32 - 1;
        let bridge_copy = c.push(c.point[bridge as usize]);
        c.link(bridge, first);
        c.link(last, bridge_copy);
        c.link(bridge_copy, after);
    }
    clip(&mut c, points, emit);
}

/// The node the hole point `m` is bridged to: a node at the same place (a hole that touches
/// the ring), else the nearer end of the first edge a ray from `m` towards +x meets, unless a
/// node inside the triangle that end spans with the ray hides it: then the one of those at
/// the smallest angle to the ray (Eberly §3).
fn find_bridge(c: &Cycle, points: &[[f32; 2]], m: [f32; 2]) -> u32 {
    let at = |i: u32| points[c.point[i as usize] as usize];
    let (mut best, mut best_x) = (0u32, f64::INFINITY);
    let mut p = 0u32;
    for _ in 0..c.len {
        if at(p) == m {
            return p;
        }
        let q = c.next[p as usize];
        let (a, b) = (at(p), at(q));
        if (a[1] <= m[1] && m[1] <= b[1] || b[1] <= m[1] && m[1] <= a[1]) && a[1] != b[1] {
            let (ax, ay, by) = (f64::from(a[0]), f64::from(a[1]), f64::from(b[1]));
            let x = ax + (f64::from(m[1]) - ay) * (f64::from(b[0]) - ax) / (by - ay);
            if x >= f64::from(m[0]) && x < best_x {
                best_x = x;
                best = if a[1] == m[1] {
                    p
                } else if b[1] == m[1] {
                    q
                } else if a[0] > b[0] {
                    p
                } else {
                    q
                };
            }
        }
        p = q;
    }
    let bp = at(best);
    if best_x.is_infinite() || bp[1] == m[1] {
        return best;
    }
    let hit = [best_x as f32, m[1]];
    let (a, b, d) = if bp[1] < m[1] { (hit, m, bp) } else { (m, hit, bp) };
    let (mut chosen, mut tan) = (best, f64::INFINITY);
    let mut p = 0u32;
    for _ in 0..c.len {
        let q = at(p);
        if p != best && q[0] > m[0] && in_triangle(a, b, d, q) {
            let t = (f64::from(m[1]) - f64::from(q[1])).abs() / (f64::from(q[0]) - f64::from(m[0]));
            if t < tan || (t == tan && q[0] < at(chosen)[0]) {
                (chosen, tan) = (p, t);
            }
        }
        p = c.next[p as usize];
    }
    chosen
}

/// Whether node `v` is an ear: its corner has zero area, or is convex with no other point of
/// the cycle in or on its triangle (points at the triangle's corners, such as a bridge's
/// copies, do not count).
fn is_ear(c: &Cycle, points: &[[f32; 2]], v: u32) -> bool {
    let at = |i: u32| points[c.point[i as usize] as usize];
    let (p, n) = (c.prev[v as usize], c.next[v as usize]);
    let (a, b, d) = (at(p), at(v), at(n));
    let corner = orient(a, b, d);
    if corner == 0.0 {
        return true;
    }
    if corner < 0.0 || corner.is_nan() {
        return false;
    }
    // A point outside the triangle's box is outside the triangle: most points are, and the
    // box's comparisons are exact and cheaper than the orientations.
    let (low, high) =
        ([a[0].min(b[0]).min(d[0]), a[1].min(b[1]).min(d[1])], [a[0].max(b[0]).max(d[0]), a[1].max(b[1]).max(d[1])]);
    let mut q = c.next[n as usize];
    while q != p {
        let x = at(q);
        let boxed = x[0] >= low[0] && x[0] <= high[0] && x[1] >= low[1] && x[1] <= high[1];
        if boxed && x != a && x != b && x != d && in_triangle(a, b, d, x) {
            return false;
        }
        q = c.next[q as usize];
    }
    true
}

/// Ear clipping of the cycle from node 0.
fn clip(c: &mut Cycle, points: &[[f32; 2]], emit: &mut impl FnMut([u32; 3])) {
    let mut remaining = c.len;
    for v in 0..c.len as u32 {
        c.ear[v as usize] = u32::from(is_ear(c, points, v));
    }
    let at = |c: &Cycle, i: u32| points[c.point[i as usize] as usize];
    let mut cursor = 0u32;
    while remaining > 2 {
        let mut v = cursor;
        let mut found = false;
        for _ in 0..remaining {
            if c.ear[v as usize] != 0 {
                found = true;
                break;
            }
            v = c.next[v as usize];
        }
        if !found {
            v = largest_corner(c, points, cursor, remaining);
        }
        let (p, n) = (c.prev[v as usize], c.next[v as usize]);
        // Written only when it is counter-clockwise as a caller sees it, in the f64 cross
        // product at each of its corners: a corner exactly convex but thinner than that
        // rounding (points FLT_MIN apart) is clipped without a triangle, as a collinear one is.
        let (a, b, d) = (at(c, p), at(c, v), at(c, n));
        if cross(a, b, d) > 0.0 && cross(b, d, a) > 0.0 && cross(d, a, b) > 0.0 {
            emit([c.point[p as usize], c.point[v as usize], c.point[n as usize]]);
        }
        c.link(p, n);
        remaining -= 1;
        if remaining > 2 {
            c.ear[p as usize] = u32::from(is_ear(c, points, p));
            c.ear[n as usize] = u32::from(is_ear(c, points, n));
        }
        cursor = n;
    }
}

/// The corner of largest area among the `remaining` nodes from `start`.
fn largest_corner(c: &Cycle, points: &[[f32; 2]], start: u32, remaining: usize) -> u32 {
    let at = |i: u32| points[c.point[i as usize] as usize];
    let (mut best, mut area, mut v) = (start, f64::NEG_INFINITY, start);
    for _ in 0..remaining {
        let a = cross(at(c.prev[v as usize]), at(v), at(c.next[v as usize]));
        if a > area {
            (best, area) = (v, a);
        }
        v = c.next[v as usize];
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point `FLT_MIN` below an ear's corner, seen from corners 10 px away: the rounded
    /// cross product puts it on the ear's edge, the exact orientation outside.
    #[test]
    fn a_point_flt_min_from_a_corner_is_outside_its_triangle() {
        let (a, b, d) = ([55.813_747, 2.041_761_2], [65.5, f32::MIN_POSITIVE], [58.814_26, 2.510_050_5]);
        let below = [65.5, 0.0];
        assert_eq!(cross(a, b, below), 0.0, "the rounded test cannot tell");
        assert!(orient(a, b, below) < 0.0 && orient(a, b, d) > 0.0);
        assert!(!in_triangle(a, b, d, below));
        assert!(in_triangle(a, b, d, [60.0, 1.5]) && in_triangle(a, b, d, a));
    }

    /// What was left of a glass fragment's ring after clipping, a spike whose tip is
    /// `FLT_MIN` above a corner of its base: the rounded tests saw no ear (the base's corner
    /// on the spike's edge), and clipping the largest corner made overlapping triangles.
    #[test]
    fn a_ring_with_corners_flt_min_apart_is_cut_into_its_area() {
        let t = f32::MIN_POSITIVE;
        let points = [
            [0.0, 129.0],
            [55.813_747, 2.041_761_2],
            [65.5, t],
            [58.814_26, 2.510_050_5],
            [57.082_626, 3.777_431],
            [72.773_33, 0.617_575_5],
            [73.381_73, 0.451_368_7],
            [65.5, 0.0],
            [131.0, 0.0],
        ];
        let ring = Ring { area: 0.0, first_point: 0, point_count: 9, hole_of: super::super::NOT_A_HOLE, reserved: 0 };
        let mut scratch = [0u32; 4 * 9];
        let (mut sum, mut count) = (0.0, 0);
        polygon(&[ring], 0, &mut [], &[0], &points, &mut scratch, &mut |t| {
            let [a, b, c] = t.map(|i| points[i as usize]);
            assert!(cross(a, b, c) > 0.0 && cross(b, c, a) > 0.0 && cross(c, a, b) > 0.0);
            sum += cross(a, b, c);
            count += 1;
        });
        let area = ring_area2(&ring, &points);
        assert!((sum - area).abs() <= 1e-9 * area, "triangles {sum}, ring {area}");
        assert_eq!(count, 7);
    }
}
