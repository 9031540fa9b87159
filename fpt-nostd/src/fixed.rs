//! Fixed-point numbers as real types (in the style of tiny-skia, but not bare
//! integer aliases).
//!
//! * [`Fx<FRAC>`] is a 32-bit signed number with `FRAC` fraction bits, stored
//!   as `i32`. Its range is `[-2^(31-FRAC), 2^(31-FRAC) - 2^-FRAC]` and its
//!   resolution `2^-FRAC`. `Fx<16>` ([`Fx16`], 16.16) spans about ±32768 with a
//!   step of 1/65536; `Fx<14>` ([`Fx14`]) spans ±131072 with a step of
//!   1/16384.
//! * [`FxWide<FRAC>`] is the same idea over `i64`, used where products of two
//!   `Fx` values are accumulated (a matrix row times a vector) so that no
//!   intermediate overflows: `|Fx * Fx| < 2^62`, and after the `>> FRAC`
//!   rescale four such terms still fit with room to spare.
//!
//! Contract: every arithmetic operation either saturates (the operator
//! traits, `saturating_*`) or reports overflow (`checked_*`); none wraps and
//! none panics. Conversions from `f32` saturate at the range ends and map NaN
//! to `None` (`try_from_f32`) or zero (`from_f32_saturating`). Products and
//! quotients round toward negative infinity (an arithmetic shift), which is
//! deterministic on every target; determinism matters more here than the
//! last half-ulp because the rasterizer relies on bit-identical results for
//! vertices shared between polygons.
//!
//! `FRAC` must be at most 30 (at least one integer bit besides the sign);
//! this is checked at compile time when a constructor is instantiated.

use core::ops::{Add, Mul, Neg, Sub};

/// A 32-bit fixed-point number with `FRAC` fraction bits (see module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Fx<const FRAC: u32>(i32);

/// 16.16 fixed point: range ±32768, step 1/65536.
pub type Fx16 = Fx<16>;
/// 18.14 fixed point: range ±131072, step 1/16384. Used for unit vectors and
/// light intensities, where the extra integer bits absorb dot-product sums.
pub type Fx14 = Fx<14>;
/// 24.8 fixed point: range ±8388608, step 1/256 (screen coordinates with
/// 8 sub-pixel bits).
pub type Fx8 = Fx<8>;

impl<const FRAC: u32> Fx<FRAC> {
    /// Compile-time guard on `FRAC`; referenced by the constructors so that
    /// an invalid format fails to build instead of misbehaving.
    const VALID: () = assert!(FRAC <= 30, "Fx<FRAC>: FRAC must be <= 30");

    /// Zero.
    pub const ZERO: Self = Self(0);
    /// One (`1 << FRAC`).
    pub const ONE: Self = Self(1 << FRAC);
    /// Largest value, `2^(31-FRAC) - 2^-FRAC`.
    pub const MAX: Self = Self(i32::MAX);
    /// Smallest value, `-2^(31-FRAC)`.
    pub const MIN: Self = Self(i32::MIN);
    /// The resolution, one unit in the last place (`2^-FRAC`).
    pub const EPSILON: Self = Self(1);

    /// Wraps a raw representation (`value * 2^FRAC`).
    pub const fn from_raw(raw: i32) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        Self(raw)
    }

    /// The raw representation (`value * 2^FRAC`).
    pub const fn raw(self) -> i32 {
        self.0
    }

    /// An integer, saturating at the range ends.
    pub const fn from_int(v: i32) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        let wide = (v as i64) << FRAC;
        Self(sat_i32(wide))
    }

    /// Converts a float, rounding to nearest and saturating at the range
    /// ends; `None` for NaN. Infinities saturate.
    pub fn try_from_f32(v: f32) -> Option<Self> {
        #[allow(clippy::let_unit_value)]
        let () = Self::VALID;
        if v.is_nan() {
            return None;
        }
        // From the bits, in integers: `|v| = m · 2^(e − 150)` with the
        // 24-bit significand `m`, so `|v| · 2^FRAC = m · 2^k`, and rounding
        // half away from zero is `(m + 2^(s−1)) >> s` for `k = −s < 0`. A
        // core without an FPU (and even a Cortex-M4F, for the `f64` this
        // once used) pays a few integer instructions instead of software
        // floating point: this runs three times per vertex. Bit-identical
        // to rounding `v · 2^FRAC` in `f64` (tested).
        let bits = v.to_bits();
        let exp = ((bits >> 23) & 0xff) as i32;
        let frac_bits = bits & 0x7f_ffff;
        let (m, e) = if exp == 0 {
            (frac_bits, 1) // subnormal: no implicit bit
        } else {
            (frac_bits | 1 << 23, exp)
        };
        let k = e - 150 + FRAC as i32;
        // The magnitude in 32 bits, `2^31` standing for anything from
        // `2^31` on (which saturates either way): the 64-bit shifts this
        // once took were most of its cost, three times a vertex.
        let mag: u32 = if k >= 0 {
            // Only a normal number gets here (a subnormal's `k` is below
            // `FRAC − 148 < 0`), so `m ≥ 2^23`: from `k = 8` on the value
            // is at least `2^31` (infinity, exp = 255, too).
            if k >= 8 {
                1 << 31
            } else {
                m << k
            }
        } else {
            // From `s = 25` on `m < 2^24 ≤ 2^(s−1)`: it rounds to 0.
            let s = (-k) as u32;
            if s >= 25 {
                0
            } else {
                (m + (1 << (s - 1))) >> s
            }
        };
        let neg = bits >> 31 != 0;
        Some(Self(match (mag >= 1 << 31, neg) {
            (true, false) => i32::MAX,
            (true, true) => i32::MIN,
            (false, false) => mag as i32,
            (false, true) => -(mag as i32),
        }))
    }

    /// Like [`Fx::try_from_f32`] but NaN becomes zero.
    pub fn from_f32_saturating(v: f32) -> Self {
        Self::try_from_f32(v).unwrap_or(Self::ZERO)
    }

    /// The value as `f32` (exact when it fits in 24 significant bits).
    pub fn to_f32(self) -> f32 {
        (self.0 as f64 / (1u64 << FRAC) as f64) as f32
    }

    /// Saturating addition.
    pub const fn saturating_add(self, o: Self) -> Self {
        Self(self.0.saturating_add(o.0))
    }

    /// Saturating subtraction.
    pub const fn saturating_sub(self, o: Self) -> Self {
        Self(self.0.saturating_sub(o.0))
    }

    /// Checked addition.
    pub const fn checked_add(self, o: Self) -> Option<Self> {
        match self.0.checked_add(o.0) {
            Some(v) => Some(Self(v)),
            None => None,
        }
    }

    /// Product rounded toward negative infinity, saturating.
    pub const fn saturating_mul(self, o: Self) -> Self {
        Self(sat_i32(((self.0 as i64) * (o.0 as i64)) >> FRAC))
    }

    /// Product, `None` on overflow.
    pub const fn checked_mul(self, o: Self) -> Option<Self> {
        let p = ((self.0 as i64) * (o.0 as i64)) >> FRAC;
        if p > i32::MAX as i64 || p < i32::MIN as i64 {
            None
        } else {
            Some(Self(p as i32))
        }
    }

    /// The full product `self * o` in the wide format (never overflows).
    pub const fn mul_wide(self, o: Self) -> FxWide<FRAC> {
        FxWide(((self.0 as i64) * (o.0 as i64)) >> FRAC)
    }

    /// Quotient rounded toward negative infinity; `None` when `o` is zero or
    /// the result does not fit.
    pub const fn checked_div(self, o: Self) -> Option<Self> {
        if o.0 == 0 {
            return None;
        }
        let q = ((self.0 as i64) << FRAC).div_euclid(o.0 as i64);
        // div_euclid rounds so that the remainder is non-negative; for a
        // negative divisor that is a ceiling, so fix up to a floor.
        let q = if o.0 < 0 && ((self.0 as i64) << FRAC).rem_euclid(o.0 as i64) != 0 {
            q - 1
        } else {
            q
        };
        if q > i32::MAX as i64 || q < i32::MIN as i64 {
            None
        } else {
            Some(Self(q as i32))
        }
    }

    /// Quotient, saturating; division by zero gives `MAX`, `MIN` or zero
    /// according to the sign of the dividend.
    pub const fn saturating_div(self, o: Self) -> Self {
        if o.0 == 0 {
            return if self.0 > 0 {
                Self::MAX
            } else if self.0 < 0 {
                Self::MIN
            } else {
                Self::ZERO
            };
        }
        let q = ((self.0 as i64) << FRAC).div_euclid(o.0 as i64);
        let q = if o.0 < 0 && ((self.0 as i64) << FRAC).rem_euclid(o.0 as i64) != 0 {
            q - 1
        } else {
            q
        };
        Self(sat_i32(q))
    }

    /// Absolute value, saturating (`|MIN|` becomes `MAX`).
    pub const fn abs(self) -> Self {
        Self(self.0.saturating_abs())
    }

    /// Largest integer `<= self`.
    pub const fn floor_int(self) -> i32 {
        self.0 >> FRAC
    }

    /// Smallest integer `>= self`.
    pub const fn ceil_int(self) -> i32 {
        (((self.0 as i64) + (1i64 << FRAC) - 1) >> FRAC) as i32
    }

    /// Nearest integer, halves rounded up (toward positive infinity).
    pub const fn round_int(self) -> i32 {
        if FRAC == 0 {
            return self.0;
        }
        (((self.0 as i64) + (1i64 << (FRAC - 1))) >> FRAC) as i32
    }

    /// Converts to another fraction width, rounding toward negative infinity
    /// when bits are dropped and saturating when they are added.
    pub const fn convert<const TO: u32>(self) -> Fx<TO> {
        #[allow(clippy::let_unit_value)]
        let () = Fx::<TO>::VALID;
        if TO >= FRAC {
            Fx(sat_i32((self.0 as i64) << (TO - FRAC)))
        } else {
            Fx(self.0 >> (FRAC - TO))
        }
    }
}

impl<const FRAC: u32> Add for Fx<FRAC> {
    type Output = Self;
    /// Saturating.
    fn add(self, o: Self) -> Self {
        self.saturating_add(o)
    }
}

impl<const FRAC: u32> Sub for Fx<FRAC> {
    type Output = Self;
    /// Saturating.
    fn sub(self, o: Self) -> Self {
        self.saturating_sub(o)
    }
}

impl<const FRAC: u32> Mul for Fx<FRAC> {
    type Output = Self;
    /// Saturating, rounded toward negative infinity.
    fn mul(self, o: Self) -> Self {
        self.saturating_mul(o)
    }
}

impl<const FRAC: u32> Neg for Fx<FRAC> {
    type Output = Self;
    /// Saturating (`-MIN` is `MAX`).
    fn neg(self) -> Self {
        Self(self.0.saturating_neg())
    }
}

/// A 64-bit fixed-point number with `FRAC` fraction bits: the accumulator
/// format for sums of [`Fx`] products (see module docs). Range
/// `±2^(63-FRAC)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FxWide<const FRAC: u32>(i64);

impl<const FRAC: u32> FxWide<FRAC> {
    /// Zero.
    pub const ZERO: Self = Self(0);
    /// One (`1 << FRAC`).
    pub const ONE: Self = Self(1 << FRAC);

    /// Wraps a raw representation (`value * 2^FRAC`).
    pub const fn from_raw(raw: i64) -> Self {
        Self(raw)
    }

    /// The raw representation.
    pub const fn raw(self) -> i64 {
        self.0
    }

    /// Widens a 32-bit value (exact).
    pub const fn from_fx(v: Fx<FRAC>) -> Self {
        Self(v.0 as i64)
    }

    /// Narrows to 32 bits, saturating.
    pub const fn saturating_narrow(self) -> Fx<FRAC> {
        Fx(sat_i32(self.0))
    }

    /// Saturating addition.
    pub const fn saturating_add(self, o: Self) -> Self {
        Self(self.0.saturating_add(o.0))
    }

    /// Saturating subtraction.
    pub const fn saturating_sub(self, o: Self) -> Self {
        Self(self.0.saturating_sub(o.0))
    }

    /// Converts a float, rounding toward zero and saturating; `None` for NaN.
    pub fn try_from_f32(v: f32) -> Option<Self> {
        if v.is_nan() {
            return None;
        }
        Some(Self((v as f64 * (1u64 << FRAC) as f64) as i64))
    }

    /// The value as `f32`.
    pub fn to_f32(self) -> f32 {
        (self.0 as f64 / (1u64 << FRAC) as f64) as f32
    }
}

impl<const FRAC: u32> Add for FxWide<FRAC> {
    type Output = Self;
    /// Saturating.
    fn add(self, o: Self) -> Self {
        self.saturating_add(o)
    }
}

impl<const FRAC: u32> Sub for FxWide<FRAC> {
    type Output = Self;
    /// Saturating.
    fn sub(self, o: Self) -> Self {
        self.saturating_sub(o)
    }
}

/// Clamps an `i64` into `i32` range.
const fn sat_i32(v: i64) -> i32 {
    if v > i32::MAX as i64 {
        i32::MAX
    } else if v < i32::MIN as i64 {
        i32::MIN
    } else {
        v as i32
    }
}

/// `floor(n / d)` for `d > 0`, exact for every such pair, with one 32-bit
/// division and a few corrections when the quotient is small (below about
/// `2^17`, as a projection's screen coordinates are) and a 64-bit division
/// otherwise.
///
/// Why: on a 32-bit core `i64::div_euclid` is a call to a 64-bit division
/// routine (about 100 instructions), twice per vertex on the fixed path's
/// projection. Here `d` cut to its top 16 bits, rounded up, divides `n`
/// cut by as many bits: that estimate is never above the quotient and below
/// it by at most `(q + 1)/2^15 + 2`, and the exact remainder (one
/// 32×32→64 multiply) corrects it.
#[inline]
pub fn div_floor_i64(n: i64, d: i64) -> i64 {
    // For `n < 0`, `floor(n/d) = !floor(!n / d)` with `!n = −n − 1 ≥ 0`:
    // the sign mask `s` flips both sides without a branch.
    let s = n >> 63;
    let m = (n ^ s) as u64;
    (div_u64_small(m, d as u64) as i64) ^ s
}

/// `floor(n / d)` for `d > 0` ([`div_floor_i64`]'s unsigned part).
#[inline]
fn div_u64_small(n: u64, d: u64) -> u64 {
    let k = (64 - d.leading_zeros()).saturating_sub(16);
    // `d`'s top bits, plus one when bits were dropped (so `top > d / 2^k`
    // and the estimate is at most the quotient); exact when none were.
    let top = (d >> k) as u32 + u32::from(k != 0);
    match u32::try_from(n >> k) {
        Ok(nk) if top != 0 => {
            let mut q = u64::from(nk / top);
            // `q ≤ n / d`: no underflow; a few steps at most (see above).
            let mut r = n - q * d;
            while r >= d {
                q += 1;
                r -= d;
            }
            q
        }
        _ => n / d,
    }
}

/// Integer square root: the largest `r` with `r * r <= v` (`v >= 0`;
/// negative inputs give 0). Bit-by-bit, no floating point, so the result is
/// identical on every target.
pub const fn isqrt_u64(v: u64) -> u64 {
    let mut rem = v;
    let mut root = 0u64;
    let mut bit = 1u64 << 62;
    while bit > rem {
        bit >>= 2;
    }
    while bit != 0 {
        if rem >= root + bit {
            rem -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root
}

#[cfg(test)]
mod tests {
    extern crate std;

    /// The rounding the integer conversion replaces, in `f64`.
    fn via_f64<const F: u32>(v: f32) -> Option<i32> {
        if v.is_nan() {
            return None;
        }
        let scaled = v as f64 * (1u64 << F) as f64;
        let rounded = if scaled >= 0.0 {
            (scaled + 0.5) as i64
        } else {
            -((-scaled + 0.5) as i64)
        };
        Some(rounded.clamp(i32::MIN as i64, i32::MAX as i64) as i32)
    }

    #[test]
    fn float_conversion_matches_the_f64_rounding_bit_for_bit() {
        let mut x: u32 = 0x1234_5678;
        let mut samples = std::vec::Vec::new();
        for _ in 0..200_000 {
            // xorshift32 over all bit patterns.
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            samples.push(f32::from_bits(x));
        }
        for e in 0..=255u32 {
            for m in [0u32, 1, 0x40_0000, 0x7f_ffff, 0x3f_ffff, 0x40_0001] {
                for sign in [0u32, 1] {
                    samples.push(f32::from_bits(sign << 31 | e << 23 | m));
                }
            }
        }
        // Exact halves and their neighbours at several scales.
        for k in -30i32..30 {
            let h = 2f32.powi(k);
            for v in [h, 1.5 * h, 2.5 * h, h * 0.75] {
                for w in [
                    v,
                    -v,
                    f32::from_bits(v.to_bits() + 1),
                    f32::from_bits(v.to_bits() - 1),
                ] {
                    samples.push(w);
                }
            }
        }
        for v in samples {
            assert_eq!(
                Fx::<16>::try_from_f32(v).map(Fx::raw),
                via_f64::<16>(v),
                "{v:e}"
            );
            assert_eq!(
                Fx::<14>::try_from_f32(v).map(Fx::raw),
                via_f64::<14>(v),
                "{v:e}"
            );
            assert_eq!(
                Fx::<0>::try_from_f32(v).map(Fx::raw),
                via_f64::<0>(v),
                "{v:e}"
            );
            assert_eq!(
                Fx::<30>::try_from_f32(v).map(Fx::raw),
                via_f64::<30>(v),
                "{v:e}"
            );
        }
    }
    use super::*;

    #[test]
    fn conversions_round_and_saturate() {
        assert_eq!(Fx16::try_from_f32(1.5).map(Fx::raw), Some(0x18000));
        assert_eq!(Fx16::try_from_f32(-1.5).map(Fx::raw), Some(-0x18000));
        assert_eq!(Fx16::try_from_f32(1e9), Some(Fx16::MAX));
        assert_eq!(Fx16::try_from_f32(-1e9), Some(Fx16::MIN));
        assert_eq!(Fx16::try_from_f32(f32::INFINITY), Some(Fx16::MAX));
        assert_eq!(Fx16::try_from_f32(f32::NAN), None);
        assert_eq!(Fx16::from_f32_saturating(f32::NAN), Fx16::ZERO);
        assert_eq!(Fx16::from_int(40000), Fx16::MAX);
        assert_eq!(Fx16::from_int(-3).to_f32(), -3.0);
        // Half an ulp rounds away from zero symmetrically.
        assert_eq!(Fx::<0>::try_from_f32(2.5).map(Fx::raw), Some(3));
        assert_eq!(Fx::<0>::try_from_f32(-2.5).map(Fx::raw), Some(-3));
    }

    #[test]
    fn arithmetic_saturates_instead_of_wrapping() {
        let big = Fx16::from_int(30000);
        assert_eq!(big + big, Fx16::MAX);
        assert_eq!(-big - big, Fx16::MIN);
        assert_eq!(big * big, Fx16::MAX);
        assert_eq!(big.checked_mul(big), None);
        assert_eq!(big.checked_add(big), None);
        assert_eq!(-Fx16::MIN, Fx16::MAX);
        assert_eq!(Fx16::MIN.abs(), Fx16::MAX);
        let a = Fx16::from_f32_saturating(2.25);
        let b = Fx16::from_f32_saturating(-4.0);
        assert_eq!((a * b).to_f32(), -9.0);
        assert_eq!(a.mul_wide(b).to_f32(), -9.0);
        assert_eq!(big.mul_wide(big).to_f32(), 9.0e8);
    }

    #[test]
    fn division_floors_and_reports_zero_divisor() {
        let one = Fx::<0>::from_int(1);
        let three = Fx::<0>::from_int(3);
        assert_eq!(one.checked_div(three).map(Fx::raw), Some(0));
        assert_eq!((-one).checked_div(three).map(Fx::raw), Some(-1));
        assert_eq!(one.checked_div(-three).map(Fx::raw), Some(-1));
        assert_eq!((-one).checked_div(-three).map(Fx::raw), Some(0));
        assert_eq!(one.checked_div(Fx::ZERO), None);
        assert_eq!(one.saturating_div(Fx::ZERO), Fx::MAX);
        assert_eq!((-one).saturating_div(Fx::ZERO), Fx::MIN);
        let x = Fx16::from_f32_saturating(7.5);
        let y = Fx16::from_f32_saturating(2.5);
        assert_eq!(x.checked_div(y).map(Fx::to_f32), Some(3.0));
        assert_eq!(Fx16::MAX.checked_div(Fx16::EPSILON), None);
    }

    #[test]
    fn rounding_to_int() {
        let v = Fx16::from_f32_saturating(-1.25);
        assert_eq!((v.floor_int(), v.ceil_int(), v.round_int()), (-2, -1, -1));
        let v = Fx16::from_f32_saturating(2.5);
        assert_eq!((v.floor_int(), v.ceil_int(), v.round_int()), (2, 3, 3));
        assert_eq!(Fx16::MAX.ceil_int(), 32768);
        let c: Fx8 = Fx16::from_f32_saturating(1.0 + 1.0 / 256.0).convert();
        assert_eq!(c.raw(), 257);
        let c: Fx16 = Fx8::from_int(-40000).convert();
        assert_eq!(c, Fx16::MIN);
    }

    #[test]
    fn isqrt_is_exact_floor() {
        for v in [
            0u64,
            1,
            2,
            3,
            4,
            15,
            16,
            17,
            1 << 40,
            (1 << 62) + 12345,
            u64::MAX,
        ] {
            let r = isqrt_u64(v);
            assert!(r.checked_mul(r).is_some_and(|s| s <= v), "{v}");
            assert!((r + 1).checked_mul(r + 1).is_none_or(|s| s > v), "{v}");
        }
    }

    #[test]
    fn wide_floor_division_equals_div_euclid() {
        // Edges of each regime (exact 16-bit divisor, estimate, 64-bit
        // fallback) and a pseudo-random sweep over all magnitudes.
        let mut cases = std::vec![
            (0i64, 1i64),
            (-1, 1),
            (i64::MIN, 1),
            (i64::MAX, 1),
            (i64::MIN, i64::MAX),
            (i64::MAX, i64::MAX),
            (-5, 3),
            (5, 3),
            ((1 << 32) - 1, 65535),
            (1 << 32, 65535),
            ((1 << 47) + 12345, (1 << 31) + 1),
            (-(1 << 47) - 1, (1 << 31) + 1),
            (((1 << 32) - 1) << 20, (1 << 35) - 1),
        ];
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let (a, b) = (x, x.rotate_left(29));
            let n = (a as i64) >> (a % 60);
            let d = ((b >> 1) >> (b % 62)).max(1) as i64;
            cases.push((n, d));
        }
        for (n, d) in cases {
            assert_eq!(div_floor_i64(n, d), n.div_euclid(d), "{n} / {d}");
        }
    }
}
