//! Compact plane table entries ([`super::FLAG_COMPACT_PLANES`]): a plane in
//! [`COMPACT_PLANE_LEN`] = 8 bytes instead of four `f32`.
//!
//! An entry is `m: i16 × 3, e: i16`, little-endian: the unit normal times
//! 32767, rounded, and the offset in steps of `u / 32767`, where `u` is
//! the file's **plane unit** `√3 · max(half_extent)` ([`plane_unit`], at
//! least the bounding radius, so every plane through the model fits):
//! the plane is `m · x + e · u = 0` (`x` relative to the origin, as every
//! stored plane). Its normal is within `√3 / 65534` of the exact one and
//! of length 1 within 3·10⁻⁵ (lighting reads it as it is: halved and
//! rounded, the Q14 of the normal times 1/32767, see
//! [`crate::raster::Normal`]),
//! its offset within `u / 65534` (`radius · √3 / 65534` at most): the
//! plane moves by about `radius / 20,000` at the bounding sphere. An `i32`
//! offset (10 bytes) would remove only the offset's half of that error.
//!
//! The facing test is `m · a + e · (u · w) > 0`: the walk scales the view's
//! `w` by `u` and puts `a` and `u · w` in fixed point once a walk, then
//! tests each entry's four `i16` with integer products and sums, without
//! converting them (`order::class`, `CompactPlane` and `fixed_view`: off
//! by less than `M / 512`, a near-tie; session 26).
//! [`compact_side`] gives the four factors converted to `f32`.
//!
//! Well-formed entries (checked at load, else
//! [`super::FormatError::BadPlane`]): no component −32768 and `|m|`
//! within 32766 to 32768 (what rounding a unit normal gives; never zero).

use super::le_u32;
use crate::cpu::HAS_FPU;

/// Length of one compact plane table entry.
pub const COMPACT_PLANE_LEN: usize = 8;

/// `√3` as the reader rounds it: the writer encodes with the same `f32`.
const SQRT_3: f32 = 1.732_050_8;

/// `1 / 32767`: a compact normal's scale.
pub(crate) const INV_SCALE: f32 = 1.0 / 32767.0;

/// The plane unit `u` of a file whose header half extent is
/// `half_extent`: `√3` times its largest component (at least the
/// distance of any stored vertex from the origin).
#[inline]
pub fn plane_unit(half_extent: [f32; 3]) -> f32 {
    SQRT_3 * half_extent[0].max(half_extent[1]).max(half_extent[2])
}

/// The four `i16` of the entry at the start of `r`: `[m₀, m₁, m₂, e]`
/// (lighting reads the normal as these integers).
#[inline(always)]
pub fn compact_fields<const L: usize>(r: &[u8; L]) -> [i16; 4] {
    let w0 = le_u32(r, 0);
    let w1 = le_u32(r, 4);
    [w0 as i16, (w0 >> 16) as i16, w1 as i16, (w1 >> 16) as i16]
}

/// `[m₀, m₁, m₂, e]` of the entry at the start of `r`, converted exactly:
/// the facing test's factors, with `w` scaled by the plane unit.
#[inline(always)]
pub fn compact_side<const L: usize>(r: &[u8; L]) -> [f32; 4] {
    compact_fields(r).map(f32_of_i16)
}

/// `c` as `f32` (exact: every `i16` is one), the bits the conversion
/// gives. Without an FPU built from the integer's bits in line: the
/// library's general `i32 → f32` routine (a call, a software count of
/// leading zeros and a rounding step no `i16` needs) was four fifths of
/// the conversion's cost, and the facing test converts four a plane.
#[inline(always)]
pub(crate) fn f32_of_i16(c: i16) -> f32 {
    if HAS_FPU {
        f32::from(c)
    } else {
        f32_of_i16_bits(c)
    }
}

/// [`f32_of_i16`] in integers (a test compares it with `f32::from` for
/// every `i16`). Out of line: in line at every conversion of every walk
/// it made violin_case's compact tree 768 bytes too big for the
/// Cortex-M0's flash.
#[inline(never)]
pub(super) fn f32_of_i16_bits(c: i16) -> f32 {
    if c == 0 {
        return 0.0;
    }
    let sign = u32::from(c as u16) << 16 & 0x8000_0000;
    // |c| in 1..=32768 shifted until its top bit is bit 15; the exponent
    // (biased) is 15 + 127 less the shift.
    let mut m = u32::from(c.unsigned_abs());
    let mut e = 15 + 127;
    if m < 1 << 8 {
        m <<= 8;
        e -= 8;
    }
    if m < 1 << 12 {
        m <<= 4;
        e -= 4;
    }
    if m < 1 << 14 {
        m <<= 2;
        e -= 2;
    }
    if m < 1 << 15 {
        m <<= 1;
        e -= 1;
    }
    // The 15 bits below the top one are the fraction's first 15 of 23.
    f32::from_bits(sign | e << 23 | (m << 8 & 0x7f_ffff))
}

/// The normal (unit within 3·10⁻⁵) and offset of the entry at the start
/// of `r` in a file of plane unit `unit`.
#[inline]
pub fn compact_plane<const L: usize>(r: &[u8; L], unit: f32) -> ([f32; 3], f32) {
    let [x, y, z, e] = compact_side(r);
    (
        [x * INV_SCALE, y * INV_SCALE, z * INV_SCALE],
        e * (unit * INV_SCALE),
    )
}

/// Whether the entry at the start of `r` is well formed (see the module
/// docs).
pub fn compact_plane_ok<const L: usize>(r: &[u8; L]) -> bool {
    let f = compact_fields(r);
    let len2: i64 = f[..3].iter().map(|&c| i64::from(c) * i64::from(c)).sum();
    f.iter().all(|&c| c != i16::MIN) && (32766 * 32766..=32768 * 32768).contains(&len2)
}
