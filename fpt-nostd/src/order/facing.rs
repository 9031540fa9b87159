//! The facing test of the walk: a run's or a switch's plane against the
//! view, in `f32` for stored planes and in fixed point for compact table
//! entries, with an optional per-frame memo (split out of `class.rs`, whose
//! culling loop is its main user).

use core::cell::Cell;

use super::LocalView;
use crate::cpu::{HAS_FPU, HAS_LONG_MUL};
use crate::format::{le_f32, le_u32, COMPACT_PLANE_LEN};

/// Whether facing memos are used: on cores without an FPU, where a facing
/// test is four software-float products and three sums; with one, a test
/// costs what its look-up does, so the walk does not look (this crate's
/// own tests use them on every target, so that the host checks the path).
/// The renderer gives a memo only when this holds
/// ([`crate::render`]'s banded draw).
pub(crate) const MEMO: bool = !HAS_FPU || cfg!(test);

/// The facing test in one form for both projections: a plane `(n, d)` is
/// backward when `n · a + d · w > 0`, with `a = −dir, w = 0` for a parallel
/// view and `a = eye, w = 1` for an eye. This is exactly
/// [`LocalView::is_backward`] for every finite plane, as validation makes
/// them (negation is exact in floating point, and the added `d · 0 = ±0` of a
/// parallel view changes no sign test), without a branch on the kind of view
/// in the loop.
///
/// With a **memo** (caller storage, two bits a plane: known, backward) a
/// plane is tested once a frame however many walks the frame takes: a band
/// renderer with less memory than a frame needs walks the tree several
/// times for the same view, and on a core without an FPU the four
/// software-float products of a test were the largest part of a walk.
#[derive(Clone, Copy, Debug)]
pub(super) struct Facing<'m> {
    a: [f32; 3],
    w: f32,
    /// `a` and `w` in fixed point for compact entries ([`fixed_view`]).
    #[cfg(feature = "compact-planes")]
    fixed: [i32; 4],
    memo: &'m [Cell<u32>],
}

impl<'m> Facing<'m> {
    /// The test of `view`, remembering results in `memo` (empty: none),
    /// with `w` times `scale`: 1, or the plane unit of compact planes
    /// (whose offsets are in its steps, so that a test converts the
    /// entry and multiplies nothing more).
    pub(super) fn of(view: &LocalView, memo: &'m [Cell<u32>], scale: f32) -> Facing<'m> {
        let (a, w) = match *view {
            LocalView::Parallel(d) => ([-d[0], -d[1], -d[2]], 0.0),
            LocalView::Eye(e) => (e, scale),
        };
        Facing {
            a,
            w,
            #[cfg(feature = "compact-planes")]
            fixed: fixed_view([a[0], a[1], a[2], w]),
            memo,
        }
    }

    /// [`Facing::fixed`] (zeros without the `compact-planes` feature,
    /// where no tree has compact entries).
    #[inline(always)]
    fn fixed(&self) -> [i32; 4] {
        #[cfg(feature = "compact-planes")]
        return self.fixed;
        #[cfg(not(feature = "compact-planes"))]
        [0; 4]
    }

    /// [`Facing::backward`] of plane number `i` (runs first, then switch
    /// records), through the memo when it holds the plane.
    #[inline]
    pub(super) fn backward_at<P: FacingPlane>(&self, i: u32, r: P) -> bool {
        if !MEMO {
            return self.backward(r);
        }
        let Some(cell) = self.memo.get((i / 16) as usize) else {
            return self.backward(r);
        };
        let word = cell.get();
        let shift = 2 * (i % 16);
        if word >> shift & 2 != 0 {
            return word >> shift & 1 != 0;
        }
        let b = self.backward(r);
        cell.set(word | (2 | u32::from(b)) << shift);
        b
    }

    /// Whether the plane `r` is backward.
    #[inline(always)]
    pub(super) fn backward<P: FacingPlane>(&self, r: P) -> bool {
        r.backward(self)
    }
}

/// `[a₀, a₁, a₂, w]` in fixed point, for the facing test of compact
/// entries ([`CompactPlane`]): each times the power of two `2^s` that
/// brings the largest magnitude into `[2^28, 2^29)`, truncated (`as`:
/// saturating, NaN 0; never a panic). With the entry's `i16` factors the
/// test is then integer products and sums (`smmul`, `smmla` on a
/// Cortex-M4) instead of four `i16 → f32` conversions and four float
/// operations. The view is rounded to 2⁻²⁸ of its largest factor `M`
/// (of |a| and |u · w|) and each product floored to 2¹⁶ units: the test's
/// value is off by less than `M / 512` (with `m` up to 32767), a plane
/// moved by less than `M · 2⁻²⁴`, as an `f32` test's rounding moves it
/// for an eye as far as `u` (and far below the entry's own rounding,
/// `u / 65534`): the two agree but on near-ties (a plane edge-on within
/// that), which either calls forward or backward.
#[cfg(feature = "compact-planes")]
fn fixed_view(v: [f32; 4]) -> [i32; 4] {
    let max = v.iter().fold(0u32, |m, x| m.max(x.to_bits() & 0x7FFF_FFFF));
    // The exponent of the largest magnitude (NaN and infinity 128,
    // zero and subnormals −127), the scale 2^s kept a normal f32.
    let e = ((max >> 23) & 0xFF) as i32 - 127;
    let s = (28 - e).clamp(-126, 127);
    let scale = f32::from_bits(((s + 127) as u32) << 23);
    v.map(|x| (x * scale) as i32)
}

/// A plane as the facing test reads it.
pub(super) trait FacingPlane: Copy {
    /// Whether it is backward for `face`.
    fn backward(self, face: &Facing<'_>) -> bool;
}

/// A plane stored at the start of a record: `f32` normal `n` and offset
/// `d`, backward when `n · a + d · w > 0`.
impl<const L: usize> FacingPlane for &[u8; L] {
    #[inline(always)]
    fn backward(self, face: &Facing<'_>) -> bool {
        let [n0, n1, n2, d] = [
            le_f32(self, 0),
            le_f32(self, 4),
            le_f32(self, 8),
            le_f32(self, 12),
        ];
        let a = face.a;
        n0 * a[0] + n1 * a[1] + n2 * a[2] + d * face.w > 0.0
    }
}

/// A compact table entry as its two little-endian words (`m₀, m₁` and
/// `m₂, e` as `i16`): backward when `m · a + e · (u · w) > 0`, the same
/// sign as its unit plane's, tested in fixed point ([`fixed_view`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct CompactPlane([u32; 2]);

impl CompactPlane {
    /// The entry `r`.
    #[inline(always)]
    pub(super) fn of(r: &[u8; COMPACT_PLANE_LEN]) -> CompactPlane {
        CompactPlane([le_u32(r, 0), le_u32(r, 4)])
    }
}

impl FacingPlane for CompactPlane {
    #[inline(always)]
    fn backward(self, face: &Facing<'_>) -> bool {
        let [w0, w1] = self.0;
        let f = face.fixed();
        // Each `i16` of a word times its factor, the product's bits 16
        // to 47 (`smulwb`, `smlawt`: a word times the bottom or top half
        // of another, accumulated, one instruction a term with no halves
        // extracted): `⌊m · f / 2^16⌋`, below 2^28 in magnitude (|m| ≤
        // 2^15, |f| < 2^29), the sum below 2^30. Each floor is at most the
        // exact term, so a sum of exact value 0 or less stays 0 or less
        // (forward, as a tie must be); an error under 4 · 2^16 of terms up
        // to 2^44 decides the sign otherwise.
        let p = |f: i32, m: u32| {
            if HAS_LONG_MUL {
                ((i64::from(f) * i64::from(m as i16)) >> 16) as i32
            } else {
                mul_hi16(f, m as i16)
            }
        };
        p(f[0], w0)
            .wrapping_add(p(f[1], w0 >> 16))
            .wrapping_add(p(f[2], w1))
            .wrapping_add(p(f[3], w1 >> 16))
            > 0
    }
}

/// `⌊f · m / 2^16⌋` in 32-bit products, for `|f| < 2^29` (what
/// [`fixed_view`] makes): with `f = h · 2^16 + l` (`0 ≤ l < 2^16`) the
/// product is `h · m · 2^16 + l · m`, whose floor by `2^16` is
/// `h · m + ⌊l · m / 2^16⌋` exactly, and `|l · m| < 2^31`. The `i64`
/// form's value, for cores without a 64-bit multiply ([`HAS_LONG_MUL`]).
#[inline(always)]
fn mul_hi16(f: i32, m: i16) -> i32 {
    let m = i32::from(m);
    (f >> 16)
        .wrapping_mul(m)
        .wrapping_add(((f & 0xFFFF) * m) >> 16)
}

#[cfg(test)]
mod tests {
    use super::mul_hi16;

    /// The 32-bit form gives the `i64` form's value over the whole range
    /// the facing test feeds it (|f| < 2^29, every `i16`), ends included.
    #[test]
    fn mul_hi16_equals_the_i64_product() {
        let mut rng = crate::raster::tests::Rng(1616);
        let lim = (1 << 29) - 1;
        let ends = [0, 1, -1, 0xFFFF, -0x10000, 0x10000, lim, -lim];
        for k in 0..200_000 {
            let f = if k < 64 {
                ends[k % ends.len()]
            } else {
                rng.range(-lim, lim)
            };
            let m = match k % 4 {
                0 => i16::MIN,
                1 => i16::MAX,
                _ => rng.range(-32768, 32767) as i16,
            };
            let want = ((i64::from(f) * i64::from(m)) >> 16) as i32;
            assert_eq!(mul_hi16(f, m), want, "{f} {m}");
        }
    }
}
