//! The Q16.16 fixed-point backend: [`Q16`], a saturating wrapper over `fixed`'s `I16F16`.
//!
//! Range ±32768 with a resolution of 2⁻¹⁶ ≈ 1.5·10⁻⁵. Every operation saturates at the range
//! instead of overflowing (so debug and release agree bit for bit) and division by zero gives
//! the saturated value of the dividend's sign (0 for 0/0). Models that run on this backend
//! work in lattice units so that their values stay well inside the range.
//!
//! `sqrt` is `fixed`'s (exact to the last bit); `sin`, `cos`, `atan2` and `exp` are written here
//! in integer arithmetic with 30 fractional bits and rounded once to Q16.16. Their errors, as
//! the tests measure them against `f64`: sin/cos ≤ 3·10⁻⁵, atan2 ≤ 3·10⁻⁵, exp ≤ 3·10⁻⁵ relative.

use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use fixed::types::I16F16;

use super::Scalar;

/// A Q16.16 fixed-point number with saturating arithmetic.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Q16(pub I16F16);

/// Fractional bits of the internal precision of the functions.
const WIDE_FRAC: u32 = 30;
/// π/2, π and 2π with 30 fractional bits.
const HALF_PI_WIDE: i128 = 1_686_629_713;
const PI_WIDE: i128 = 3_373_259_426;
const TAU_WIDE: i128 = 6_746_518_852;
/// ln 2 with 30 fractional bits.
const LN2_WIDE: i128 = 744_261_118;
/// 1 with 30 fractional bits.
const ONE_WIDE: i128 = 1 << WIDE_FRAC;

impl Q16 {
    /// The raw two's-complement bits (value × 2¹⁶).
    pub const fn to_bits(self) -> i32 {
        self.0.to_bits()
    }

    /// The number whose raw bits (value × 2¹⁶) are `bits`.
    pub const fn from_bits(bits: i32) -> Self {
        Q16(I16F16::from_bits(bits))
    }

    /// The value with 30 fractional bits.
    fn to_wide(self) -> i128 {
        i128::from(self.to_bits()) << (WIDE_FRAC - 16)
    }

    /// A value with 30 fractional bits, rounded to nearest (ties up) and saturated.
    fn from_wide(wide: i128) -> Self {
        let rounded = (wide + (1 << (WIDE_FRAC - 17))) >> (WIDE_FRAC - 16);
        Q16::from_bits(rounded.clamp(i128::from(i32::MIN), i128::from(i32::MAX)) as i32)
    }
}

/// Product of two values with 30 fractional bits.
fn mul_wide(a: i128, b: i128) -> i128 {
    (a * b) >> WIDE_FRAC
}

/// Evaluates Σ cᵢ·xⁱ by Horner's rule, coefficients with 30 fractional bits, highest first.
fn horner(x: i128, coefficients: &[i128]) -> i128 {
    coefficients.iter().fold(0, |acc, &c| mul_wide(acc, x) + c)
}

/// A real coefficient with 30 fractional bits (used only in constant tables).
const fn wide(c: f64) -> i128 {
    (c * (1u64 << WIDE_FRAC) as f64) as i128
}

/// sin r for r in [−π, π], 30 fractional bits: fold to [−π/2, π/2], then the Taylor series to
/// r¹¹ (truncation error < 6·10⁻⁸).
fn sin_wide(r: i128) -> i128 {
    let r = if r > HALF_PI_WIDE {
        PI_WIDE - r
    } else if r < -HALF_PI_WIDE {
        -PI_WIDE - r
    } else {
        r
    };
    const TAYLOR: [i128; 6] = [
        wide(-1.0 / 39_916_800.0),
        wide(1.0 / 362_880.0),
        wide(-1.0 / 5_040.0),
        wide(1.0 / 120.0),
        wide(-1.0 / 6.0),
        ONE_WIDE,
    ];
    mul_wide(r, horner(mul_wide(r, r), &TAYLOR))
}

/// x reduced to [−π, π] (x with 30 fractional bits).
fn reduce_angle(x: i128) -> i128 {
    let turns = (x + PI_WIDE).div_euclid(TAU_WIDE);
    x - turns * TAU_WIDE
}

/// atan t for t in [0, 1], 30 fractional bits: Abramowitz & Stegun 4.4.49 (error ≤ 10⁻⁵).
fn atan_unit(t: i128) -> i128 {
    const ODD: [i128; 5] =
        [wide(0.020_835_1), wide(-0.085_133_0), wide(0.180_141_0), wide(-0.330_299_5), wide(0.999_866_0)];
    mul_wide(t, horner(mul_wide(t, t), &ODD))
}

impl Scalar for Q16 {
    const ZERO: Self = Q16(I16F16::ZERO);
    const ONE: Self = Q16(I16F16::ONE);
    const HALF: Self = Q16::from_bits(1 << 15);
    const TWO: Self = Q16::from_bits(2 << 16);
    const PI: Self = Q16(I16F16::PI);
    const MAX: Self = Q16(I16F16::MAX);
    const RESOLUTION: Self = Q16(I16F16::DELTA);

    fn from_f32(x: f32) -> Self {
        if x.is_nan() { Self::ZERO } else { Q16(I16F16::saturating_from_num(x)) }
    }
    fn to_f32(self) -> f32 {
        self.0.to_num::<f32>()
    }
    fn from_i32(n: i32) -> Self {
        Q16(I16F16::saturating_from_num(n))
    }
    fn sqrt(self) -> Self {
        Q16(self.0.checked_sqrt().unwrap_or(I16F16::ZERO))
    }
    fn sin(self) -> Self {
        Q16::from_wide(sin_wide(reduce_angle(self.to_wide())))
    }
    fn cos(self) -> Self {
        Q16::from_wide(sin_wide(reduce_angle(self.to_wide() + HALF_PI_WIDE)))
    }
    fn atan2(self, x: Self) -> Self {
        let (y, x) = (i128::from(self.to_bits()), i128::from(x.to_bits()));
        if y == 0 && x == 0 {
            return Self::ZERO;
        }
        let (ay, ax) = (y.abs(), x.abs());
        let first_octant =
            if ay <= ax { atan_unit((ay << WIDE_FRAC) / ax) } else { HALF_PI_WIDE - atan_unit((ax << WIDE_FRAC) / ay) };
        let half_plane = if x < 0 { PI_WIDE - first_octant } else { first_octant };
        Q16::from_wide(if y < 0 { -half_plane } else { half_plane })
    }
    fn exp(self) -> Self {
        // x = k·ln 2 + r with r in [0, ln 2): eˣ = 2ᵏ·eʳ, eʳ by its Taylor series to r⁹
        // (truncation error < 10⁻⁸).
        let x = self.to_wide();
        let k = x.div_euclid(LN2_WIDE);
        if k >= 16 {
            return Self::MAX;
        }
        if k < -18 {
            return Self::ZERO;
        }
        let r = x - k * LN2_WIDE;
        const TAYLOR: [i128; 10] = [
            wide(1.0 / 362_880.0),
            wide(1.0 / 40_320.0),
            wide(1.0 / 5_040.0),
            wide(1.0 / 720.0),
            wide(1.0 / 120.0),
            wide(1.0 / 24.0),
            wide(1.0 / 6.0),
            wide(0.5),
            ONE_WIDE,
            ONE_WIDE,
        ];
        let e_r = horner(r, &TAYLOR);
        let scaled = if k >= 0 { e_r << k } else { e_r >> -k };
        Q16::from_wide(scaled)
    }
    fn floor(self) -> Self {
        Q16::from_bits(self.to_bits() & !0xFFFF)
    }
}

/// `+`, `−` and `×` saturate at the format's range instead of wrapping.
macro_rules! saturating {
    ($($op:ident $method:ident $saturating:ident),*) => {$(
        impl $op for Q16 {
            type Output = Q16;
            fn $method(self, rhs: Q16) -> Q16 {
                Q16(self.0.$saturating(rhs.0))
            }
        }
    )*};
}

saturating!(Add add saturating_add, Sub sub saturating_sub, Mul mul saturating_mul);

impl Div for Q16 {
    type Output = Q16;
    fn div(self, rhs: Q16) -> Q16 {
        match self.0.checked_div(rhs.0) {
            Some(q) => Q16(q),
            None if self.0 == I16F16::ZERO => Q16::ZERO,
            None if (self.0 < I16F16::ZERO) == (rhs.0 < I16F16::ZERO) => Q16::MAX,
            None => Q16(I16F16::MIN),
        }
    }
}

impl Neg for Q16 {
    type Output = Q16;
    fn neg(self) -> Q16 {
        Q16(self.0.saturating_neg())
    }
}

impl AddAssign for Q16 {
    fn add_assign(&mut self, rhs: Q16) {
        *self = *self + rhs;
    }
}

impl SubAssign for Q16 {
    fn sub_assign(&mut self, rhs: Q16) {
        *self = *self - rhs;
    }
}

impl MulAssign for Q16 {
    fn mul_assign(&mut self, rhs: Q16) {
        *self = *self * rhs;
    }
}

impl DivAssign for Q16 {
    fn div_assign(&mut self, rhs: Q16) {
        *self = *self / rhs;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::tests::{Bounds, check_backend, grid};

    #[test]
    fn q16_backend_is_within_its_stated_bounds() {
        check_backend::<Q16>(&Bounds { arith: 2e-5, sqrt: 2e-5, trig: 3e-5, atan2: 3e-5, exp: 3e-5 });
    }

    #[test]
    fn q16_saturates_instead_of_overflowing() {
        let big = Q16::from_i32(30_000);
        assert_eq!(big + big, Q16::MAX);
        assert_eq!(-big - big, Q16(I16F16::MIN));
        assert_eq!(big * big, Q16::MAX);
        assert_eq!(Q16::ONE / Q16::ZERO, Q16::MAX);
        assert_eq!(-Q16::ONE / Q16::ZERO, Q16(I16F16::MIN));
        assert_eq!(Q16::ZERO / Q16::ZERO, Q16::ZERO);
        assert_eq!(Q16::from_f32(1e9), Q16::MAX);
        assert_eq!(Q16::from_f32(f32::NAN), Q16::ZERO);
        assert_eq!(Q16::from_i32(20).exp(), Q16::MAX);
        assert_eq!(Q16::from_i32(-20).exp(), Q16::ZERO);
    }

    #[test]
    fn q16_trig_holds_across_its_whole_range() {
        for x in grid(-32_000.0, 32_000.0, 997) {
            let q = Q16::from_f32(x as f32);
            let exact = f64::from(q.to_f32());
            assert!((f64::from(q.sin().to_f32()) - libm::sin(exact)).abs() < 3e-5, "sin {x}");
            assert!((f64::from(q.cos().to_f32()) - libm::cos(exact)).abs() < 3e-5, "cos {x}");
        }
    }
}
