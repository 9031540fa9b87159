//! Compact plane table entries ([`super::FLAG_COMPACT_PLANES`]): a plane in
//! [`COMPACT_PLANE_LEN`] = 8 bytes instead of four `f32`.
//!
//! An entry is `m: i16 × 3, e: i16`, little-endian, for the plane
//! `m · x + e · u = 0` (`x` relative to the origin, as every stored plane),
//! where `u` is the file's **plane unit** `radius · √3` ([`plane_unit`]).
//! The writer scales the unit normal so that its largest component is
//! ±32767 (so `|m|` is 32767 to 32767·√3) and rounds; the offset
//! `d · |m|` is then at most `radius · 32767 · √3` in magnitude, so `e`
//! fits an `i16` in steps of `u`: a plane moves by at most `u / (2 |m|) ≤
//! radius · √3 / 65534` across its normal, about what the normal's own
//! rounding (±½ in 32767 a component) tilts it by at the bounding
//! sphere. An `i32` offset (10 bytes) would remove only the first of the
//! two errors.
//!
//! The facing test `m · a + e · u · w > 0` needs no normalisation (its sign
//! is that of the unit plane's); [`compact_side`] gives it the four
//! factors as `f32`. Only planes themselves (lighting, outlines,
//! [`crate::reader::Plane`]) are normalised ([`compact_plane`]).
//!
//! Well-formed entries (checked at load, else
//! [`super::FormatError::BadPlane`]): every component in `−32767..=32767`
//! (−32768 is refused, so that each plane has one encoding with its
//! negation) and the largest `|m_i|` exactly 32767 (so `m` is never zero).

use super::{le_u32, Q16_MAX};

/// Length of one compact plane table entry.
pub const COMPACT_PLANE_LEN: usize = 8;

/// `√3` as the reader rounds it: the writer encodes with the same `f32`.
const SQRT_3: f32 = 1.732_050_8;

/// The plane unit `u` of a file whose header radius is `radius`: the step
/// of a compact entry's offset.
#[inline]
pub fn plane_unit(radius: f32) -> f32 {
    radius * SQRT_3
}

/// The four `i16` of an entry.
#[inline(always)]
fn fields<const L: usize>(r: &[u8; L]) -> [i16; 4] {
    let w0 = le_u32(r, 0);
    let w1 = le_u32(r, 4);
    [w0 as i16, (w0 >> 16) as i16, w1 as i16, (w1 >> 16) as i16]
}

/// `[m₀, m₁, m₂, e · unit]` of the entry at the start of `r`: the facing
/// test's factors (`m · a + e · unit · w`), exact conversions and one
/// product.
#[inline(always)]
pub fn compact_side<const L: usize>(r: &[u8; L], unit: f32) -> [f32; 4] {
    let [x, y, z, e] = fields(r);
    [
        f32::from(x),
        f32::from(y),
        f32::from(z),
        f32::from(e) * unit,
    ]
}

/// The unit normal and offset of the entry at the start of `r` (the
/// plane divided by `|m|`).
#[inline]
pub fn compact_plane<const L: usize>(r: &[u8; L], unit: f32) -> ([f32; 3], f32) {
    let [x, y, z, d] = compact_side(r, unit);
    // |m| ≥ 32767 on a well-formed entry; zeros (an index past the end,
    // never read on a validated file) give zeros, not NaN.
    let len2 = x * x + y * y + z * z;
    let k = if len2 > 0.0 {
        1.0 / libm::sqrtf(len2)
    } else {
        0.0
    };
    ([x * k, y * k, z * k], d * k)
}

/// Whether the entry at the start of `r` is well formed (see the module
/// docs).
pub fn compact_plane_ok<const L: usize>(r: &[u8; L]) -> bool {
    let f = fields(r);
    let max = Q16_MAX.unsigned_abs();
    f.iter().all(|&c| c != i16::MIN) && f[..3].iter().map(|c| c.unsigned_abs()).max() == Some(max)
}
