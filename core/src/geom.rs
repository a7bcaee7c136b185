//! The geometry the models share: points and segments with their exact intersection
//! (generic over the [`Scalar`] backend; glass's growth), and the `f32` helpers of the
//! outlines (shoelace area, ray crossing, pseudo-angle, rounding).
//!
//! The intersection test decides by the signs of cross products (no division), handles
//! parallel and collinear segments, and returns shared endpoints exactly (the very point, with
//! parameter 0 or 1), so that a crack that stops on another one ends exactly on it.
//!
//! With the Q16.16 backend the cross products are saturated beyond ±32768: keep coordinates
//! within about ±128 units there.

use core::ops::{Add, Mul, Neg, Sub};

use crate::scalar::Scalar;

/// A point (or vector) in the plane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Point<S> {
    /// x coordinate.
    pub x: S,
    /// y coordinate.
    pub y: S,
}

impl<S: Scalar> Point<S> {
    /// The point (x, y).
    pub const fn new(x: S, y: S) -> Self {
        Point { x, y }
    }

    /// The origin.
    pub const ORIGIN: Self = Point { x: S::ZERO, y: S::ZERO };

    /// Dot product.
    pub fn dot(self, other: Self) -> S {
        self.x * other.x + self.y * other.y
    }

    /// The z component of the cross product: positive when `other` is counter-clockwise
    /// from `self`.
    pub fn cross(self, other: Self) -> S {
        self.x * other.y - self.y * other.x
    }

    /// Squared length.
    pub fn length_squared(self) -> S {
        self.dot(self)
    }
}

impl<S: Scalar> Add for Point<S> {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Point::new(self.x + rhs.x, self.y + rhs.y)
    }
}

impl<S: Scalar> Sub for Point<S> {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        Point::new(self.x - rhs.x, self.y - rhs.y)
    }
}

impl<S: Scalar> Mul<S> for Point<S> {
    type Output = Self;
    fn mul(self, k: S) -> Self {
        Point::new(self.x * k, self.y * k)
    }
}

impl<S: Scalar> Neg for Point<S> {
    type Output = Self;
    fn neg(self) -> Self {
        Point::new(-self.x, -self.y)
    }
}

/// The straight segment from `start` to `end`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Segment<S> {
    /// Where the segment begins (parameter 0).
    pub start: Point<S>,
    /// Where the segment ends (parameter 1).
    pub end: Point<S>,
}

/// Where two segments meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Intersection<S> {
    /// They do not meet.
    None,
    /// They meet in one point, at parameter `along_first` of the first segment and
    /// `along_second` of the second (0 and 1 exactly at endpoints).
    Point {
        /// The meeting point (an endpoint, exactly, when one is shared or touched).
        point: Point<S>,
        /// Parameter along the first segment, in [0, 1].
        along_first: S,
        /// Parameter along the second segment, in [0, 1].
        along_second: S,
    },
    /// They are collinear and share the stretch from `start` to `end`, ordered along the
    /// first segment; both ends are endpoints of the inputs, exactly.
    Overlap {
        /// The end of the shared stretch nearer the first segment's start.
        start: Point<S>,
        /// The end of the shared stretch nearer the first segment's end.
        end: Point<S>,
    },
}

impl<S: Scalar> Segment<S> {
    /// The segment from `start` to `end`.
    pub const fn new(start: Point<S>, end: Point<S>) -> Self {
        Segment { start, end }
    }

    /// `end − start`.
    pub fn direction(self) -> Point<S> {
        self.end - self.start
    }

    /// The parameter in [0, 1] of the point of the segment closest to `p`.
    pub fn closest_parameter(self, p: Point<S>) -> S {
        let d = self.direction();
        let dd = d.length_squared();
        if dd == S::ZERO {
            return S::ZERO;
        }
        ((p - self.start).dot(d) / dd).clamp(S::ZERO, S::ONE)
    }

    /// Whether `p` lies on the segment, decided exactly from the inputs' values.
    pub fn contains(self, p: Point<S>) -> bool {
        let d = self.direction();
        let to_p = p - self.start;
        if d.cross(to_p) != S::ZERO {
            return false;
        }
        let along = to_p.dot(d);
        along >= S::ZERO && along <= d.length_squared() && (d != Point::ORIGIN || p == self.start)
    }

    /// Where this segment meets `other` (see [`Intersection`]).
    pub fn intersect(self, other: Segment<S>) -> Intersection<S> {
        let r = self.direction();
        let s = other.direction();
        let denominator = r.cross(s);
        if denominator == S::ZERO {
            return self.intersect_parallel(other);
        }
        // Shared endpoints are answered exactly, before any arithmetic can blur them.
        for (t, p) in [(S::ZERO, self.start), (S::ONE, self.end)] {
            for (u, q) in [(S::ZERO, other.start), (S::ONE, other.end)] {
                if p == q {
                    return Intersection::Point { point: p, along_first: t, along_second: u };
                }
            }
        }
        let qp = other.start - self.start;
        let (mut t_num, mut u_num, mut den) = (qp.cross(s), qp.cross(r), denominator);
        if den < S::ZERO {
            (t_num, u_num, den) = (-t_num, -u_num, -den);
        }
        if t_num < S::ZERO || t_num > den || u_num < S::ZERO || u_num > den {
            return Intersection::None;
        }
        let (t, u) = (t_num / den, u_num / den);
        let point = if t_num == S::ZERO {
            self.start
        } else if t_num == den {
            self.end
        } else if u_num == S::ZERO {
            other.start
        } else if u_num == den {
            other.end
        } else {
            self.start + r * t
        };
        Intersection::Point {
            point,
            along_first: if t_num == den { S::ONE } else { t },
            along_second: if u_num == den { S::ONE } else { u },
        }
    }

    /// The parallel case of [`Segment::intersect`]: nothing, a touching point, or an overlap.
    fn intersect_parallel(self, other: Segment<S>) -> Intersection<S> {
        let r = self.direction();
        let rr = r.length_squared();
        if rr == S::ZERO {
            // The first segment is a point.
            return if other.contains(self.start) {
                Intersection::Point {
                    point: self.start,
                    along_first: S::ZERO,
                    along_second: other.closest_parameter(self.start),
                }
            } else {
                Intersection::None
            };
        }
        if r.cross(other.start - self.start) != S::ZERO || r.cross(other.end - self.start) != S::ZERO {
            return Intersection::None; // parallel on different lines
        }
        // Collinear: order the four endpoints by their projection onto the first segment.
        let along = |p: Point<S>| (p - self.start).dot(r);
        let (mut near, mut far) = (other.start, other.end);
        if along(far) < along(near) {
            (near, far) = (far, near);
        }
        let start = if along(near) > S::ZERO { near } else { self.start };
        let end = if along(far) < rr { far } else { self.end };
        let (a, b) = (along(start), along(end));
        if a > b {
            Intersection::None
        } else if a == b {
            Intersection::Point {
                point: start,
                along_first: self.closest_parameter(start),
                along_second: other.closest_parameter(start),
            }
        } else {
            Intersection::Overlap { start, end }
        }
    }
}

/// A monotone stand-in for the angle of direction `d` ≠ 0, in [0, 4): exact arithmetic and no
/// trigonometry, so that every platform orders directions alike.
///
/// Quadrant 0 (x, y ≥ 0) gives y / (x + y), 1 (x < 0 ≤ y) 1 + |x| / (|x| + |y|), 2 (x, y < 0)
/// 2 + |y| / (|x| + |y|), 3 (y < 0 ≤ x) 3 + x / (x − y): one division, chosen without
/// branches, so that loops over many directions vectorise.
#[inline]
pub fn pseudo_angle(d: [f32; 2]) -> f32 {
    let [x, y] = d;
    let (upper, right) = (y >= 0.0, x >= 0.0);
    let (ax, ay) = (x.abs(), y.abs());
    let num = if upper == right { ay } else { ax };
    let base = (u32::from(!upper) << 1 | u32::from(upper != right)) as f32;
    let length = ax + ay;
    // The zero vector (an edge between coincident points) has no direction; it takes 0, so
    // that the order of a vertex's edges stays total (0/0 would be NaN, and a NaN key breaks
    // the rotation that face walks follow: fuzz finding 11).
    if length == 0.0 { 0.0 } else { base + num / length }
}

/// `libm::round(x) as i64` (nearest integer, halves away from zero; saturating, NaN → 0),
/// without libm's bit-level software rounding: x plus ½ − 2⁻⁵⁴ towards its sign, truncated.
/// The sum, rounded to the nearest `f64`, reaches the next integer away from zero exactly
/// when x's fraction is ½ or more: below 1 in magnitude ½ − 2⁻⁵⁴ keeps a fraction under ½
/// short of it and a fraction of ½ or more (a multiple of 2⁻⁵³) rounds to at least it; from
/// 1 on the spacing is at least 2⁻⁵², so the 2⁻⁵⁴ taken off never moves the sum across an
/// integer; from 2^52 on every `f64` is already an integer and the sum rounds back to it.
/// NaN stays NaN, which `as` maps to 0, and `as` saturates the rest.
#[inline]
pub fn round_to_i64(x: f64) -> i64 {
    (x + 0.499_999_999_999_999_94f64.copysign(x)) as i64
}

/// Twice the signed area of the triangle (0, a, b): one shoelace term.
pub fn shoelace(a: [f32; 2], b: [f32; 2]) -> f64 {
    f64::from(a[0]) * f64::from(b[1]) - f64::from(b[0]) * f64::from(a[1])
}

/// Whether a ray from `p` towards +x crosses the edge a–b (half-open in y, so a ray through a
/// vertex counts once). An odd number of crossings puts `p` inside.
pub fn crosses_ray(a: [f32; 2], b: [f32; 2], p: [f32; 2]) -> bool {
    if (a[1] > p[1]) == (b[1] > p[1]) {
        return false;
    }
    let (ax, ay, bx, by) = (f64::from(a[0]), f64::from(a[1]), f64::from(b[0]), f64::from(b[1]));
    let x = ax + (f64::from(p[1]) - ay) * (bx - ax) / (by - ay);
    f64::from(p[0]) < x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pseudo_angle_is_the_quadrant_formula() {
        // The same values written with a branch per quadrant (IEEE arithmetic is symmetric in
        // sign, so x / (y − x) for x < 0 ≤ y is −|x| / (|x| + |y|) exactly, and so on).
        let by_quadrant = |x: f32, y: f32| {
            if y >= 0.0 {
                if x >= 0.0 { y / (x + y) } else { 1.0 - x / (y - x) }
            } else if x < 0.0 {
                2.0 - y / (-x - y)
            } else {
                3.0 + x / (x - y)
            }
        };
        let special = [0.0, -0.0, 1.0, -1.0, 1e-30, -1e-30, 3e7, -3e7, 0.5, -0.5];
        for a in special {
            for b in special {
                // Equal values: on an axis the branches may give −0 where this gives +0.
                if a != 0.0 || b != 0.0 {
                    assert_eq!(pseudo_angle([a, b]), by_quadrant(a, b), "({a}, {b})");
                }
            }
        }
        let mut r = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..200_000 {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            let scale = [1e-3, 1.0, 40.0, 1e4][(r >> 62) as usize];
            let (a, b) = (((r as u32) as f32 / 2e9 - 1.07) * scale, (((r >> 32) as u32) as f32 / 2e9 - 1.07) * scale);
            assert_eq!(pseudo_angle([a, b]).to_bits(), by_quadrant(a, b).to_bits(), "({a}, {b})");
        }
    }

    #[test]
    fn round_to_i64_is_libm_round() {
        let check = |c: f64| assert_eq!(round_to_i64(c), libm::round(c) as i64, "{c:e}");
        let edges = [0.0, -0.0, 0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 0.49999999999999994, -0.49999999999999994];
        let huge = [4_503_599_627_370_495.5, -4_503_599_627_370_495.5, 4_503_599_627_370_496.0, 1e19, -1e19];
        let special = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::MAX, f64::MIN_POSITIVE];
        edges.into_iter().chain(huge).chain(special).for_each(check);
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            // Magnitudes from 2^-4 to 2^60, with halves and their neighbours.
            let v = (x >> 11) as f64 / (1u64 << 53) as f64 + (x >> 44) as f64;
            let scale = (1u64 << (x % 61)) as f64 / 16.0;
            let half = (x >> 20) as f64 + 0.5;
            for c in [
                v * scale,
                -v * scale,
                half,
                -half,
                f64::from_bits(half.to_bits() - 1),
                f64::from_bits(half.to_bits() + 1),
            ] {
                check(c);
            }
        }
    }

    fn p(x: f32, y: f32) -> Point<f32> {
        Point::new(x, y)
    }
    fn seg(a: (f32, f32), b: (f32, f32)) -> Segment<f32> {
        Segment::new(p(a.0, a.1), p(b.0, b.1))
    }
    fn hit(point: Point<f32>, t: f32, u: f32) -> Intersection<f32> {
        Intersection::Point { point, along_first: t, along_second: u }
    }

    #[test]
    fn crossing_segments_meet_inside() {
        let i = seg((0.0, 0.0), (2.0, 2.0)).intersect(seg((0.0, 2.0), (2.0, 0.0)));
        assert_eq!(i, hit(p(1.0, 1.0), 0.5, 0.5));
        assert_eq!(seg((0.0, 0.0), (1.0, 0.0)).intersect(seg((2.0, -1.0), (2.0, 1.0))), Intersection::None);
    }

    #[test]
    fn shared_endpoints_are_exact_in_every_order() {
        // Endpoints that no float arithmetic reproduces exactly.
        let (a, b, c) = (p(0.1, 0.7), p(3.3, -1.9), p(-2.7, 5.1));
        for (first, second, point, t, u) in [
            (Segment::new(a, b), Segment::new(b, c), b, 1.0, 0.0),
            (Segment::new(a, b), Segment::new(c, b), b, 1.0, 1.0),
            (Segment::new(b, a), Segment::new(b, c), b, 0.0, 0.0),
            (Segment::new(b, a), Segment::new(c, b), b, 0.0, 1.0),
        ] {
            assert_eq!(first.intersect(second), hit(point, t, u));
        }
    }

    #[test]
    fn t_junction_returns_the_touching_endpoint_exactly() {
        let stem = Segment::new(p(0.3, 0.0), p(0.3, 0.9));
        let bar = Segment::new(p(-1.0, 0.9), p(1.0, 0.9));
        match stem.intersect(bar) {
            Intersection::Point { point, along_first, .. } => {
                assert_eq!(point, stem.end);
                assert_eq!(along_first, 1.0);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn parallel_and_collinear_cases() {
        let base = seg((0.0, 0.0), (4.0, 0.0));
        // Parallel on another line.
        assert_eq!(base.intersect(seg((0.0, 1.0), (4.0, 1.0))), Intersection::None);
        // Collinear, disjoint.
        assert_eq!(base.intersect(seg((5.0, 0.0), (6.0, 0.0))), Intersection::None);
        // Collinear, touching at one endpoint.
        assert_eq!(base.intersect(seg((4.0, 0.0), (6.0, 0.0))), hit(p(4.0, 0.0), 1.0, 0.0));
        // Collinear overlap, either direction of the second segment.
        let overlap = Intersection::Overlap { start: p(1.0, 0.0), end: p(4.0, 0.0) };
        assert_eq!(base.intersect(seg((1.0, 0.0), (6.0, 0.0))), overlap);
        assert_eq!(base.intersect(seg((6.0, 0.0), (1.0, 0.0))), overlap);
        // One inside the other.
        assert_eq!(
            base.intersect(seg((3.0, 0.0), (2.0, 0.0))),
            Intersection::Overlap { start: p(2.0, 0.0), end: p(3.0, 0.0) }
        );
        // Identical.
        assert_eq!(base.intersect(base), Intersection::Overlap { start: base.start, end: base.end });
    }

    #[test]
    fn degenerate_segments_are_points() {
        let point = seg((1.0, 1.0), (1.0, 1.0));
        assert_eq!(point.intersect(seg((0.0, 0.0), (2.0, 2.0))), hit(p(1.0, 1.0), 0.0, 0.5));
        assert_eq!(point.intersect(seg((0.0, 1.5), (2.0, 1.5))), Intersection::None);
        assert_eq!(seg((0.0, 0.0), (2.0, 2.0)).intersect(point), hit(p(1.0, 1.0), 0.5, 0.0));
        assert_eq!(point.intersect(point), hit(p(1.0, 1.0), 0.0, 0.0));
    }

    #[test]
    fn point_segment_projection() {
        let s = seg((0.0, 0.0), (4.0, 0.0));
        assert_eq!(s.closest_parameter(p(2.0, 3.0)), 0.5);
        assert_eq!(s.closest_parameter(p(-3.0, 4.0)), 0.0);
        assert_eq!(s.closest_parameter(p(7.0, -4.0)), 1.0);
        assert!(s.contains(p(4.0, 0.0)) && !s.contains(p(4.5, 0.0)) && !s.contains(p(2.0, 0.1)));
    }

    #[cfg(feature = "fixed")]
    #[test]
    fn geometry_runs_on_the_fixed_backend() {
        use crate::scalar::Q16;
        let q = |x: f32, y: f32| Point::new(Q16::from_f32(x), Q16::from_f32(y));
        let a = Segment::new(q(0.0, 0.0), q(2.0, 2.0));
        let b = Segment::new(q(0.0, 2.0), q(2.0, 0.0));
        assert_eq!(
            a.intersect(b),
            Intersection::Point { point: q(1.0, 1.0), along_first: Q16::HALF, along_second: Q16::HALF }
        );
        assert_eq!(Segment::new(q(0.0, 0.0), q(4.0, 0.0)).closest_parameter(q(2.0, 3.0)), Q16::HALF);
    }

    #[test]
    fn pseudo_angle_orders_directions_like_the_angle() {
        let mut previous = -1.0;
        for k in 0..360 {
            let a = (k as f32).to_radians();
            let d = [libm::cosf(a), libm::sinf(a)];
            let p = pseudo_angle(d);
            assert!((0.0..4.0).contains(&p) && p > previous, "{k}°: {p} after {previous}");
            previous = p;
        }
        assert_eq!(pseudo_angle([2.0, 0.0]), 0.0);
        assert_eq!(pseudo_angle([0.0, 3.0]), 1.0);
        assert_eq!(pseudo_angle([-1.0, 0.0]), 2.0);
        assert_eq!(pseudo_angle([0.0, -5.0]), 3.0);
        // The zero vector: 0, not NaN (a NaN key breaks the face walks' order, finding 11).
        assert_eq!([[0.0, 0.0], [-0.0, 0.0], [0.0, -0.0], [-0.0, -0.0]].map(pseudo_angle), [0.0; 4]);
    }
}
