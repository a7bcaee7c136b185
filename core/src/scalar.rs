//! The number type the models compute in.
//!
//! A model is written once, generic over [`Scalar`], and runs on any backend:
//!
//! | backend | type | math | determinism |
//! |---|---|---|---|
//! | default | `f32` | IEEE `+ − × ÷`, `libm` for the rest | same bits everywhere |
//! | `micromath` feature | `micromath::F32` | fast approximations of sin, cos, atan2, exp (errors ≤ 1.5·10⁻³, atan2 ≤ 4·10⁻³); IEEE sqrt | same bits everywhere |
//! | `fixed` feature | `Q16` (Q16.16) | integer arithmetic, saturating; functions in `fixed_point` | same bits everywhere |
//!
//! All three are deterministic: the float backends use only IEEE basic operations (the
//! square root among them, correctly rounded in every implementation) and software functions
//! (`libm`, `micromath`), never `mul_add` or platform approximations; the
//! fixed backend is pure integer arithmetic that saturates instead of overflowing, so debug
//! and release builds agree.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// The square root of `x`, correctly rounded (IEEE 754), so the same bits on every target.
/// On x86-64 it is SSE's `sqrtss` by way of the compiler's intrinsic (`safe_arch`), which
/// LLVM vectorises in a loop: four roots in one `sqrtps`, where `libm::sqrtf`, inline
/// assembly there, keeps every loop that takes a root scalar. Elsewhere `libm::sqrtf` (the
/// hardware instruction where there is one, a correctly rounded software root otherwise).
#[inline(always)]
pub(crate) fn sqrtf(x: f32) -> f32 {
    #[cfg(target_arch = "x86_64")]
    {
        safe_arch::get_f32_from_m128_s(safe_arch::sqrt_m128_s(safe_arch::set_m128_s(x)))
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        libm::sqrtf(x)
    }
}

/// [`sqrtf`] in `f64`: SSE2's `sqrtsd` on x86-64, `libm::sqrt` elsewhere.
#[inline(always)]
pub(crate) fn sqrt(x: f64) -> f64 {
    #[cfg(target_arch = "x86_64")]
    {
        let x = safe_arch::set_m128d_s(x);
        safe_arch::get_f64_from_m128d_s(safe_arch::sqrt_m128d_s(x, x))
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        libm::sqrt(x)
    }
}

#[cfg(feature = "fixed")]
pub mod fixed_point;
#[cfg(feature = "fixed")]
pub use fixed_point::Q16;

/// A real number as the models compute it.
pub trait Scalar:
    Copy
    + Debug
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 1/2.
    const HALF: Self;
    /// 2.
    const TWO: Self;
    /// π.
    const PI: Self;
    /// The largest finite value.
    const MAX: Self;
    /// The smallest positive step the backend resolves (machine epsilon near 1 for floats,
    /// one unit in the last place for fixed point).
    const RESOLUTION: Self;

    /// The nearest value to `x`; fixed point saturates at its range and maps NaN to 0.
    fn from_f32(x: f32) -> Self;
    /// The value as `f32` (exact for `f32`, nearest for the others).
    fn to_f32(self) -> f32;
    /// The nearest value to the integer `n`.
    fn from_i32(n: i32) -> Self;

    /// √x; 0 for x ≤ 0.
    fn sqrt(self) -> Self;
    /// sin x (radians).
    fn sin(self) -> Self;
    /// cos x (radians).
    fn cos(self) -> Self;
    /// The angle of the vector (x, y) in (−π, π]: `y.atan2(x)`. 0 for (0, 0).
    fn atan2(self, x: Self) -> Self;
    /// eˣ (saturating for fixed point).
    fn exp(self) -> Self;
    /// The largest integer ≤ x.
    fn floor(self) -> Self;

    /// 1/√x for x > 0. The default is `ONE / sqrt(x)`; `f32` overrides it with a form made of
    /// basic IEEE operations only (see there), which hot loops can vectorise.
    fn inverse_sqrt(self) -> Self {
        Self::ONE / self.sqrt()
    }

    /// |x|.
    fn abs(self) -> Self {
        if self < Self::ZERO { -self } else { self }
    }
    /// The smaller of the two (the first if they compare equal or unordered).
    fn min(self, other: Self) -> Self {
        if other < self { other } else { self }
    }
    /// The larger of the two (the first if they compare equal or unordered).
    fn max(self, other: Self) -> Self {
        if other > self { other } else { self }
    }
    /// `self` limited to [`low`, `high`].
    fn clamp(self, low: Self, high: Self) -> Self {
        self.max(low).min(high)
    }
}

impl Scalar for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const HALF: Self = 0.5;
    const TWO: Self = 2.0;
    const PI: Self = core::f32::consts::PI;
    const MAX: Self = f32::MAX;
    const RESOLUTION: Self = f32::EPSILON;

    fn from_f32(x: f32) -> Self {
        x
    }
    fn to_f32(self) -> f32 {
        self
    }
    fn from_i32(n: i32) -> Self {
        n as f32
    }
    fn sqrt(self) -> Self {
        if self > 0.0 { crate::scalar::sqrtf(self) } else { 0.0 }
    }
    fn sin(self) -> Self {
        libm::sinf(self)
    }
    fn cos(self) -> Self {
        libm::cosf(self)
    }
    fn atan2(self, x: Self) -> Self {
        libm::atan2f(self, x)
    }
    fn exp(self) -> Self {
        libm::expf(self)
    }
    fn floor(self) -> Self {
        libm::floorf(self)
    }
    /// A bit-level first guess (relative error ≤ 3.5·10⁻²) refined by three Newton steps
    /// y ← y·(1.5 − ½x·y²): only integer and IEEE basic operations, so it is the same on every
    /// platform and vectorises (libm's sqrt is a scalar instruction behind inline assembly).
    /// Relative error ≤ 3·10⁻⁷ (tests).
    fn inverse_sqrt(self) -> Self {
        let half = 0.5 * self;
        let mut y = f32::from_bits(0x5f37_5a86u32.wrapping_sub(self.to_bits() >> 1));
        for _ in 0..3 {
            y *= 1.5 - half * y * y;
        }
        y
    }
}

#[cfg(feature = "micromath")]
impl Scalar for micromath::F32 {
    const ZERO: Self = micromath::F32(0.0);
    const ONE: Self = micromath::F32(1.0);
    const HALF: Self = micromath::F32(0.5);
    const TWO: Self = micromath::F32(2.0);
    const PI: Self = micromath::F32(core::f32::consts::PI);
    const MAX: Self = micromath::F32(f32::MAX);
    const RESOLUTION: Self = micromath::F32(f32::EPSILON);

    fn from_f32(x: f32) -> Self {
        micromath::F32(x)
    }
    fn to_f32(self) -> f32 {
        self.0
    }
    fn from_i32(n: i32) -> Self {
        micromath::F32(n as f32)
    }
    fn sqrt(self) -> Self {
        // micromath's bit-trick sqrt is off by up to 6 %, too coarse for spring lengths;
        // IEEE sqrt is correctly rounded, deterministic and cheap.
        if self.0 > 0.0 { micromath::F32(crate::scalar::sqrtf(self.0)) } else { Self::ZERO }
    }
    fn sin(self) -> Self {
        micromath::F32::sin(self)
    }
    fn cos(self) -> Self {
        micromath::F32::cos(self)
    }
    fn atan2(self, x: Self) -> Self {
        if self.0 == 0.0 && x.0 == 0.0 {
            return Self::ZERO;
        }
        micromath::F32::atan2(self, x)
    }
    fn exp(self) -> Self {
        micromath::F32::exp(self)
    }
    fn floor(self) -> Self {
        micromath::F32::floor(self)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Sample points over [low, high], endpoints included.
    pub(crate) fn grid(low: f64, high: f64, n: u32) -> impl Iterator<Item = f64> {
        (0..=n).map(move |i| low + (high - low) * f64::from(i) / f64::from(n))
    }

    /// Checks one backend's functions against `f64` references (libm), with absolute error
    /// bounds stated per function and per range.
    pub(crate) fn check_backend<S: Scalar>(bounds: &Bounds) {
        let close = |name: &str, x: f64, got: S, want: f64, bound: f64| {
            let err = (f64::from(got.to_f32()) - want).abs();
            assert!(err <= bound, "{name}({x}) = {:?}, want {want}, error {err} > {bound}", got);
        };
        let s = |x: f64| S::from_f32(x as f32);
        for x in grid(0.0, 100.0, 2000) {
            close("sqrt", x, s(x).sqrt(), libm::sqrt(x), bounds.sqrt * (1.0 + libm::sqrt(x)));
        }
        assert_eq!(s(-4.0).sqrt(), S::ZERO);
        for x in grid(-20.0, 20.0, 4000) {
            close("sin", x, s(x).sin(), libm::sin(x), bounds.trig);
            close("cos", x, s(x).cos(), libm::cos(x), bounds.trig);
        }
        for y in grid(-50.0, 50.0, 60) {
            for x in grid(-50.0, 50.0, 60) {
                if x == 0.0 && y == 0.0 {
                    continue;
                }
                close("atan2", y, s(y).atan2(s(x)), libm::atan2(y, x), bounds.atan2);
            }
        }
        assert_eq!(S::ZERO.atan2(S::ZERO), S::ZERO);
        for x in grid(-10.0, 10.0, 2000) {
            let want = libm::exp(x);
            close("exp", x, s(x).exp(), want, bounds.exp * want.max(1.0));
        }
        for x in grid(-7.5, 7.5, 60) {
            close("floor", x, s(x).floor(), libm::floor(x), 0.0);
        }
        for (a, b) in [(1.5, -2.25), (-3.0, 0.125), (7.0, 7.0)] {
            close("add", a, s(a) + s(b), a + b, bounds.arith);
            close("mul", a, s(a) * s(b), a * b, bounds.arith * (1.0 + (a * b).abs()));
            close("div", a, s(a) / s(b), a / b, bounds.arith * (1.0 + (a / b).abs()));
            close("min", a, s(a).min(s(b)), a.min(b), 0.0);
            close("max", a, s(a).max(s(b)), a.max(b), 0.0);
            close("abs", a, s(a).abs(), a.abs(), 0.0);
        }
        for x in grid(0.01, 100.0, 2000) {
            // Against the input as the backend holds it (Q16.16 rounds 0.01 by 0.06 %).
            let want = 1.0 / libm::sqrt(f64::from(s(x).to_f32()));
            let bound = bounds.sqrt * 4.0 * want * (1.0 + want) + f64::from(S::RESOLUTION.to_f32());
            close("inverse_sqrt", x, s(x).inverse_sqrt(), want, bound);
        }
        close("pi", 0.0, S::PI, core::f64::consts::PI, bounds.arith);
        close("clamp", 5.0, s(5.0).clamp(S::ZERO, S::ONE), 1.0, 0.0);
        assert_eq!(S::from_i32(-3), s(-3.0));
        assert_eq!(S::HALF + S::HALF, S::ONE);
        assert_eq!(S::ONE + S::ONE, S::TWO);
        assert!(S::RESOLUTION > S::ZERO && S::RESOLUTION < s(1e-3));
    }

    /// Absolute error bounds of one backend (relative where the check says so).
    pub(crate) struct Bounds {
        pub(crate) arith: f64,
        /// Relative to 1 + √x.
        pub(crate) sqrt: f64,
        pub(crate) trig: f64,
        pub(crate) atan2: f64,
        /// Relative to max(eˣ, 1).
        pub(crate) exp: f64,
    }

    #[test]
    fn f32_libm_backend_is_within_a_few_ulps() {
        check_backend::<f32>(&Bounds { arith: 1e-6, sqrt: 1e-7, trig: 2e-6, atan2: 1e-6, exp: 1e-6 });
    }

    #[test]
    fn f32_inverse_sqrt_is_within_three_tenths_of_a_millionth() {
        let mut worst = 0.0f64;
        for i in 0..200_000 {
            let x = libm::exp(-20.0 + 40.0 * f64::from(i) / 200_000.0) as f32;
            let want = 1.0 / libm::sqrt(f64::from(x));
            worst = worst.max((f64::from(x.inverse_sqrt()) - want).abs() / want);
        }
        assert!(worst < 3e-7, "relative error {worst}");
    }

    /// Fuzz finding 5: a NaN or negative length² (a diverging run) made the first guess's
    /// subtraction from the magic constant overflow, a panic with overflow checks (which these
    /// tests have). It wraps, as release builds always did; a NaN stays NaN.
    #[test]
    fn f32_inverse_sqrt_of_nan_or_a_negative_is_no_panic() {
        for x in [f32::NAN, -f32::NAN, -1.0, -0.0, f32::NEG_INFINITY, -f32::MIN_POSITIVE] {
            let y = x.inverse_sqrt();
            assert!(!x.is_nan() || y.is_nan(), "{x}: {y}");
        }
    }

    #[cfg(feature = "micromath")]
    #[test]
    fn micromath_backend_is_within_its_documented_approximation() {
        check_backend::<micromath::F32>(&Bounds { arith: 1e-6, sqrt: 1e-7, trig: 1.5e-3, atan2: 4e-3, exp: 1.5e-3 });
    }
}
