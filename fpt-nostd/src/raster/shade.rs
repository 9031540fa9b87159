//! Flat shading: one colour per face, from a directional light plus ambient,
//! in fixed point.
//!
//! `intensity = clamp(ambient + diffuse · max(0, n̂ · l̂), 0, 1)` with `n̂` the
//! face's unit normal and `l̂` the unit direction *toward* the light, both in
//! the same (model) space. Unit vectors are [`Fx14`] triples: an `f32`
//! vector that is unit length already (the tree's stored plane normals) is
//! rounded to Q14 directly; any other is normalised with an integer square
//! root after one division that brings it to a common scale. Both are
//! IEEE-exact operations, so the result is bit-identical on every target
//! and for every [`super::precision::Precision`].
//!
//! Lighting is one-sided: a face whose normal points away from the light
//! gets the ambient term only. For open (two-sided) models the caller
//! passes the normal of the side being drawn (the tree walk knows it).
//!
//! Modes: [`ShadeMode::Flat`] (the face colour as is), [`ShadeMode::Lambert`]
//! (face colour × intensity: the paper's Figure 16), [`ShadeMode::Grey`]
//! (a grey level × intensity, face colours ignored: Figure 15).

use crate::cpu::HAS_FPU;
use core::cell::Cell;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use crate::fixed::{isqrt_u64, Fx14};

/// How faces are coloured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ShadeMode {
    /// The face colour, unlit.
    Flat,
    /// The face colour scaled by the light intensity.
    #[default]
    Lambert,
    /// The given grey level scaled by the light intensity (face colours
    /// ignored).
    Grey(u8),
}

/// A directional light with an ambient term.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Light {
    /// Unit vector toward the light; `None` means "no direction" (only the
    /// ambient term applies).
    dir: Option<[Fx14; 3]>,
    ambient: Fx14,
    diffuse: Fx14,
}

impl Default for Light {
    /// [`Light::DEFAULT`].
    fn default() -> Light {
        Light::DEFAULT
    }
}

/// Normalises an integer vector to an [`Fx14`] unit vector; `None` for zero.
fn unit_from_ints(v: [i64; 3]) -> Option<[Fx14; 3]> {
    let big = v.iter().map(|c| c.unsigned_abs()).max().unwrap_or(0);
    if big == 0 {
        return None;
    }
    // Bring the largest component to 15..=16 bits so the squared length
    // fits easily in u64 and the quotient keeps 14 fraction bits.
    let lz = big.leading_zeros() as i32; // big has 64 - lz bits
    let shift = (64 - lz) - 16;
    let s = v.map(|c| if shift >= 0 { c >> shift } else { c << -shift });
    let len2: u64 = s.iter().map(|c| (c * c) as u64).sum();
    let len = isqrt_u64(len2) as i64;
    if len == 0 {
        return None;
    }
    Some(s.map(|c| {
        let n = c << 14;
        // Round to nearest (halves away from zero) for symmetry.
        let q = (n.abs() + len / 2) / len;
        Fx14::from_raw((if n < 0 { -q } else { q }) as i32)
    }))
}

/// `c` with `|c| < 2` scaled by `2^frac` (`frac` at most 29) and rounded,
/// halves away from zero, exactly (0 for anything smaller than half a
/// unit).
///
/// Two implementations with the same results (a test compares them),
/// chosen by the target: on a core without an FPU each `f32` operation is
/// a software routine of some 50–90 instructions, and shading a polygon
/// from its stored `f32` normal (a unit-length test and three roundings)
/// was about a tenth of a Cortex-M0 frame, so there it is integer work on
/// the bits; with an FPU a few float instructions are cheaper. (The older
/// `(|c| · 2^14 + 0.5) as i32` rounded twice; both of these round once.)
#[inline(always)]
fn round_scaled(c: f32, frac: u32) -> i32 {
    if HAS_FPU {
        round_scaled_fpu(c, frac)
    } else {
        round_scaled_bits(c, frac)
    }
}

/// [`round_scaled`] in integers, from the bits of `c`.
#[inline]
fn round_scaled_bits(c: f32, frac: u32) -> i32 {
    let bits = c.to_bits();
    let exp = bits >> 23 & 0xff;
    // value = m · 2^(e − 150) (subnormals: e = 1 without the hidden bit).
    let (m, e) = if exp == 0 {
        (bits & 0x7f_ffff, 1)
    } else {
        (bits & 0x7f_ffff | 0x80_0000, exp)
    };
    // × 2^frac: m · 2^(e + frac − 150), a right shift by k = 150 − e − frac;
    // |c| < 2 means e ≤ 127, so k ≥ 23 − frac ≥ −6.
    let k = 150i32 - e as i32 - frac as i32;
    let mag = if k <= 0 {
        m << (-k).min(6) as u32
    } else if k > 25 {
        // m < 2^24 is below half a unit (2^(k−1) ≥ 2^25).
        0
    } else {
        (m + (1 << (k - 1))) >> k
    } as i32;
    if bits >> 31 != 0 {
        -mag
    } else {
        mag
    }
}

/// [`round_scaled`] in `f32`: the scaling by a power of two, the
/// truncation and the fraction `x − ⌊x⌋` are all exact.
#[inline]
fn round_scaled_fpu(c: f32, frac: u32) -> i32 {
    let x = c.abs() * (1u32 << frac) as f32;
    let t = x as i32;
    let mag = t + i32::from(x - t as f32 >= 0.5);
    if c.is_sign_negative() {
        -mag
    } else {
        mag
    }
}

/// `c` in `[-1, 1]` rounded to Q14 (halves away from zero, as
/// [`unit_from_ints`]).
fn q14_round(c: f32) -> Fx14 {
    Fx14::from_raw(round_scaled(c, 14))
}

/// Whether `bits` is a finite `f32` with magnitude below 2.
#[inline]
fn below_two(c: f32) -> bool {
    c.to_bits() & 0x7fff_ffff < 0x4000_0000
}

/// Normalises an `f32` vector; `None` for zero or non-finite input.
/// Inlined into the per-face shading: the fast path is a few dozen
/// instructions, and the general one ([`unit_from_f32_slow`]) out of line
/// keeps its registers (and their saving) out of every face's call.
#[inline]
fn unit_from_f32(v: [f32; 3]) -> Option<[Fx14; 3]> {
    // Fast path: stored normals are unit already, and a 64-bit integer
    // square root plus three 64-bit divisions per face was the whole cost
    // of shading on a 32-bit core. The length test is on the rounded Q14
    // components, in integers (the same decision on every target, and
    // cheap without an FPU): |q|² within 2^16 of 2^28, i.e. |v|² within
    // about 2^-12 of 1 (the rounding takes up to 2^-13.2 of it), where
    // rounding each component directly is within two Q14 units of the
    // normalised vector. Components below 2 in magnitude cannot overflow.
    if v.iter().all(|&c| below_two(c)) {
        let q = v.map(q14_round);
        let len2: u32 = q.iter().map(|c| c.raw().unsigned_abs().pow(2)).sum();
        if len2.abs_diff(1 << 28) <= 1 << 16 {
            return Some(q);
        }
    }
    unit_from_f32_slow(v)
}

/// [`unit_from_f32`] past its fast path: a vector that is not unit length
/// or has a component of magnitude 2 or more (or not finite).
#[cold]
#[inline(never)]
fn unit_from_f32_slow(v: [f32; 3]) -> Option<[Fx14; 3]> {
    // After the fast path, which needs no finiteness test of its own (a
    // component below 2 in magnitude is finite): three tests fewer a face.
    if !v.iter().all(|c| c.is_finite()) {
        return None;
    }
    let big = v.iter().fold(0.0f32, |m, c| m.max(c.abs()));
    if big == 0.0 {
        return None;
    }
    // One division brings every magnitude to [-1, 1]; from here on it is
    // integer arithmetic (2^30 keeps plenty of bits for tiny components).
    let scale = (1u32 << 30) as f32 / big;
    unit_from_ints(v.map(|c| (c * scale) as i64))
}

/// The normal a face is lit by, as the tree stores it: an `f32` vector
/// ([`Normal::from_f32`], a 16-byte plane's) or an integer one
/// ([`Normal::from_compact`], a compact plane entry's). Lighting rounds
/// either to a Q14 unit vector in integers, on every target alike.
///
/// Held as three words and no tag, not as an enum: the renderer's
/// intensity memo keys on exactly these words, so a face's shading takes
/// no branch on the form until a memo miss. An `f32` vector is its three
/// bit patterns; an integer one is its first two components packed in
/// one word, the third in the next (low half) and `0xFFFF_FFFF`, a NaN
/// pattern, in the last, where a finite `f32` never has it. (A fourth
/// word for the form, kept and tested by the memo, cost a narrow tree's
/// Cortex-M4F `bench_city` frame 1.4 % with the `compact-planes` feature
/// compiled in; session 27.) So an `f32` vector whose third component
/// has the bits `0xFFFF_FFFF` (a NaN, which no file's plane has:
/// validation refuses them) is taken for an integer one. Without the
/// `compact-planes` feature there is no integer form. Equality is of the
/// words.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Normal {
    /// `f32` patterns, or `m₀ | m₁ << 16`, `m₂` (low half) and
    /// [`COMPACT_MARK`].
    bits: [u32; 3],
}

/// The last word of an integer [`Normal`]: a NaN pattern (all ones), which
/// no finite `f32` has.
const COMPACT_MARK: u32 = u32::MAX;

impl Normal {
    /// An `f32` vector of any length (a 16-byte plane's unit normal).
    #[inline(always)]
    pub fn from_f32(n: [f32; 3]) -> Normal {
        Normal {
            bits: n.map(f32::to_bits),
        }
    }

    /// An integer vector of any length. A compact plane table entry's unit
    /// normal times 32767 ([`crate::format::FLAG_COMPACT_PLANES`]) takes
    /// a short path: each component `c` halved and rounded, halves away
    /// from zero, which is `c · 2^14 / 32767` rounded exactly, with no
    /// float operation (the entry decoded to `f32` and rounded cost four
    /// software-float routines a face on a core without an FPU).
    /// (Only with the `compact-planes` feature, whose trees have such
    /// normals.)
    #[cfg(feature = "compact-planes")]
    #[inline(always)]
    pub fn from_compact(m: [i16; 3]) -> Normal {
        let h = m.map(|c| u32::from(c as u16));
        Normal::from_entry_words(h[0] | h[1] << 16, h[2])
    }

    /// The normal of a compact plane entry whose first two little-endian
    /// words are `w0` (`m₀, m₁`) and `w1` (`m₂, e`): no unpacking.
    #[cfg(feature = "compact-planes")]
    #[inline(always)]
    pub(crate) fn from_entry_words(w0: u32, w1: u32) -> Normal {
        Normal {
            bits: [w0, w1 & 0xFFFF, COMPACT_MARK],
        }
    }

    /// Whether it is an integer vector (never without the
    /// `compact-planes` feature).
    #[inline(always)]
    fn is_compact(self) -> bool {
        cfg!(feature = "compact-planes") && self.bits[2] == COMPACT_MARK
    }

    /// The `f32` vector, if it is one.
    #[inline(always)]
    pub fn as_f32(self) -> Option<[f32; 3]> {
        (!self.is_compact()).then(|| self.bits.map(f32::from_bits))
    }

    /// The integer vector, if it is one (never without the
    /// `compact-planes` feature).
    #[inline(always)]
    pub fn as_compact(self) -> Option<[i16; 3]> {
        let [w0, w1, _] = self.bits;
        self.is_compact()
            .then_some([w0 as i16, (w0 >> 16) as i16, w1 as i16])
    }

    /// The normal pointing the other way: exact in both forms (the sign
    /// bit of an `f32`; an `i16` other than −32768, which no well-formed
    /// compact entry has, negated; −32768 stays).
    #[inline(always)]
    pub fn flipped(self) -> Normal {
        #[cfg(feature = "compact-planes")]
        if let Some(m) = self.as_compact() {
            return Normal::from_compact(m.map(i16::wrapping_neg));
        }
        Normal {
            bits: self.bits.map(|b| b ^ 0x8000_0000),
        }
    }

    /// As `f32`: an integer one as the reader decodes a compact plane
    /// ([`crate::format::compact_plane`]: each component times
    /// `1 / 32767`).
    pub fn to_f32(self) -> [f32; 3] {
        match self.as_compact() {
            None => self.bits.map(f32::from_bits),
            Some(m) => m.map(|c| f32::from(c) * crate::format::COMPACT_INV_SCALE),
        }
    }
}

impl From<[f32; 3]> for Normal {
    fn from(n: [f32; 3]) -> Normal {
        Normal::from_f32(n)
    }
}

/// `c / 2` rounded, halves away from zero: for `|c| ≤ 32767` the same as
/// `c · 2^14 / 32767` rounded (`c / 65534`, the difference, has `c`'s sign
/// and is below ½ in magnitude, so it moves an exact half away from zero
/// and nothing else across a rounding boundary).
#[inline(always)]
fn q14_of_compact(c: i16) -> i32 {
    let c = i32::from(c);
    // `c >> 31` is −1 for a negative `c`: `(c − 1) / 2` truncated is
    // `c / 2` rounded away from zero, as `(c + 1) / 2` for a positive one.
    (c + (c >> 31 | 1)) / 2
}

/// A compact normal as a Q14 unit vector; `None` for zero. A compact
/// entry's unit normal (length 32766 to 32768) always takes the short
/// path: its rounded components are within `√3 / 2` of half the entry's,
/// so `|q|²` is within about 61,300 of `2^28`, inside the fast path's
/// `2^16` (the test that also keeps out any other length).
#[inline(always)]
fn unit_from_compact(m: [i16; 3]) -> Option<[Fx14; 3]> {
    let q = m.map(q14_of_compact);
    let len2: u32 = q.iter().map(|c| c.unsigned_abs().pow(2)).sum();
    if len2.abs_diff(1 << 28) <= 1 << 16 {
        return Some(q.map(Fx14::from_raw));
    }
    unit_from_ints(m.map(i64::from))
}

/// `n` as a Q14 unit vector; `None` for zero or non-finite.
#[inline(always)]
fn unit_of(n: Normal) -> Option<[Fx14; 3]> {
    match n.as_compact() {
        None => unit_from_f32(n.bits.map(f32::from_bits)),
        Some(m) => unit_from_compact(m),
    }
}

impl Light {
    /// The ambient weight the project's pictures use: a quarter of a
    /// face's colour whatever its facing, so that faces turned away from
    /// the light stay visible.
    pub const AMBIENT: f32 = 0.25;
    /// The diffuse weight the project's pictures use: with
    /// [`Light::AMBIENT`] it adds up to 1, so a face turned straight to
    /// the light shows its full colour.
    pub const DIFFUSE: f32 = 0.75;

    /// A light from `+z` with the weights [`Light::AMBIENT`] and
    /// [`Light::DIFFUSE`]: what [`Light::new`]`([0.0, 0.0, 1.0],
    /// Light::AMBIENT, Light::DIFFUSE)` gives, as a constant (a
    /// renderer's light before any is set).
    ///
    /// ```
    /// use fpt_nostd::raster::Light;
    /// assert_eq!(Light::DEFAULT, Light::new([0.0, 0.0, 1.0], Light::AMBIENT, Light::DIFFUSE));
    /// ```
    pub const DEFAULT: Light = Light {
        dir: Some([Fx14::ZERO, Fx14::ZERO, Fx14::ONE]),
        ambient: Fx14::from_raw(1 << 12),
        diffuse: Fx14::from_raw(3 << 12),
    };

    /// A light shining from direction `toward_light` (need not be unit;
    /// zero or non-finite means ambient only), with `ambient` and `diffuse`
    /// weights in `[0, 1]` (clamped).
    pub fn new(toward_light: [f32; 3], ambient: f32, diffuse: f32) -> Light {
        let w = |v: f32| Fx14::from_f32_saturating(v.clamp(0.0, 1.0));
        Light {
            dir: unit_from_f32(toward_light),
            ambient: w(ambient),
            diffuse: w(diffuse),
        }
    }

    /// The normalised direction toward the light.
    pub fn direction(&self) -> Option<[Fx14; 3]> {
        self.dir
    }

    fn intensity_unit(&self, n: Option<[Fx14; 3]>) -> Fx14 {
        let cos = match (n, self.dir) {
            (Some(n), Some(l)) => {
                // Q14 · Q14 unit components: each product at most 2^28
                // (and a rounding unit), the sum of three within i32 (a
                // 64-bit multiply is a library call on a Cortex-M0).
                let dot: i32 = (0..3).map(|i| n[i].raw() * l[i].raw()).sum();
                Fx14::from_raw(dot >> 14)
            }
            _ => Fx14::ZERO,
        };
        // `diffuse` is in [0, 2^14] (`Light::new` clamps it, `DEFAULT`'s is
        // 3·2^12) and `cos` at most (2^31 − 1) >> 14, so their product fits
        // an `i32`: the saturating 64-bit `Fx14` product (a long multiply
        // and two saturation tests a face) is this one, exactly.
        let diffuse = (self.diffuse.raw() * cos.max(Fx14::ZERO).raw()) >> 14;
        let lit = self.ambient + Fx14::from_raw(diffuse);
        lit.clamp(Fx14::ZERO, Fx14::ONE)
    }

    /// Light intensity in `[0, 1]` for a face with (unnormalised) normal
    /// `normal`; a zero or non-finite normal gets the ambient term.
    pub fn intensity(&self, normal: [f32; 3]) -> Fx14 {
        self.intensity_unit(unit_from_f32(normal))
    }

    /// [`Light::intensity`] of a [`Normal`] in either form.
    ///
    /// ```
    /// # #[cfg(feature = "compact-planes")] {
    /// use fpt_nostd::raster::{Light, Normal};
    /// let l = Light::new([1.0, 2.0, 2.0], 0.25, 0.75);
    /// let m = [10_000i16, -20_000, 24_000]; // length 32,802: not a unit
    /// let unit = [10_922i16, -21_845, 21_845]; // length 32,767.3
    /// assert_eq!(
    ///     l.intensity_of(Normal::from_compact(unit)),
    ///     l.intensity(unit.map(|c| f32::from(c) * (1.0 / 32767.0)))
    /// );
    /// assert_eq!(l.intensity_of(Normal::from_compact(m)), l.intensity_q(m.map(i32::from)));
    /// # }
    /// ```
    pub fn intensity_of(&self, normal: Normal) -> Fx14 {
        self.intensity_unit(unit_of(normal))
    }

    /// Like [`Light::intensity`] for a unit normal stored as `i8` times
    /// 127 (the corner normals of [`crate::format`]): converted to Q14 and
    /// used as unit length, without the square root and divisions of
    /// normalising again (a few integer operations per corner).
    ///
    /// ```
    /// use fpt_nostd::raster::Light;
    /// let l = Light::new([0.0, 0.0, 1.0], 0.25, 0.75);
    /// assert_eq!(l.intensity_i8([0, 0, 127]), l.intensity([0.0, 0.0, 1.0]));
    /// assert_eq!(l.intensity_i8([0, 0, -127]), l.intensity([0.0, 0.0, -1.0]));
    /// ```
    pub fn intensity_i8(&self, normal: [i8; 3]) -> Fx14 {
        // 127ths to Q14, rounded half away from zero: |c| ≤ 127 gives at
        // most 2^14, so the dot product stays in i32.
        let q = normal.map(|c| {
            let n = i32::from(c) * (1 << 14);
            Fx14::from_raw((n + n.signum() * 63) / 127)
        });
        self.intensity_unit(Some(q))
    }

    /// Like [`Light::intensity`] for an integer normal (any scale).
    pub fn intensity_q(&self, normal: [i32; 3]) -> Fx14 {
        self.intensity_unit(unit_from_ints(normal.map(|c| c as i64)))
    }
}

/// Scales an 8-bit channel by an intensity in `[0, 1]`, rounding.
fn scale(c: u8, i: Fx14) -> u8 {
    let v = (c as i32 * i.raw() + (1 << 13)) >> 14;
    v.clamp(0, 255) as u8
}

/// The colour of a face under `mode` given its light intensity.
pub fn shade_color(mode: ShadeMode, color: [u8; 3], intensity: Fx14) -> Rgb888 {
    match mode {
        ShadeMode::Flat => Rgb888::new(color[0], color[1], color[2]),
        ShadeMode::Lambert => Rgb888::new(
            scale(color[0], intensity),
            scale(color[1], intensity),
            scale(color[2], intensity),
        ),
        ShadeMode::Grey(g) => {
            let v = scale(g, intensity);
            Rgb888::new(v, v, v)
        }
    }
}

/// Shades a face: [`Light::intensity`] then [`shade_color`]. `Flat` skips
/// the lighting computation.
pub fn shade(mode: ShadeMode, light: &Light, normal: [f32; 3], color: [u8; 3]) -> Rgb888 {
    let i = match mode {
        ShadeMode::Flat => Fx14::ONE,
        _ => light.intensity(normal),
    };
    shade_color(mode, color, i)
}

/// Entries of an [`IntensityMemo`]: eight on cores with an FPU (a
/// scene's faces have few distinct normals: a city's walls and roofs face
/// five ways), none without (its 128 bytes would come out of the
/// Cortex-M0's 16 KiB).
const MEMO: usize = if HAS_FPU { 8 } else { 0 };

/// An empty memo entry's intensity: no intensity is above `2^14`.
const NO_INTENSITY: u32 = u32::MAX;

/// The light intensities of the last normals shaded, by their bits: a
/// renderer's memo for [`IntensityMemo::shade`], so that a face whose
/// normal was lit before takes the intensity back (a hash and four
/// comparisons) instead of rounding, testing and lighting it again (about
/// 70 instructions a face on a Cortex-M4F). Direct mapped (entry by a
/// hash of the bits); [`IntensityMemo::EMPTY`] when the light changes.
/// The same intensities as [`Light::intensity_of`]: a pure function of the
/// normal's bits and the light, which a renderer's memo never outlives.
#[derive(Clone, Debug)]
pub(crate) struct IntensityMemo {
    /// The normal's three words, then its intensity (raw `Fx14`;
    /// [`NO_INTENSITY`] when empty).
    entries: [Cell<[u32; 4]>; MEMO],
}

impl IntensityMemo {
    /// No normal remembered. A constant, each use a fresh memo (what the
    /// lint warns of is what is meant); as a `const fn` the renderers the
    /// firmware builds on its stack took a copy more (its effect runs'
    /// stack then reached the statics).
    #[allow(clippy::declare_interior_mutable_const)]
    pub(crate) const EMPTY: IntensityMemo = IntensityMemo {
        entries: [const { Cell::new([0, 0, 0, NO_INTENSITY]) }; MEMO],
    };

    /// [`shade`], with the intensity of `normal` under `light` taken from
    /// or kept in the memo (which must be [`IntensityMemo::EMPTY`] or hold
    /// only intensities under `light`). A hit is found in line (the hash,
    /// one entry's key compared, the colour scaled: most faces of a scene
    /// hit); a miss calls out of line, as the whole shading did (the walk
    /// paid the call, its prologue and the normal passed through memory
    /// for every face).
    #[inline(always)]
    pub(crate) fn shade(
        &self,
        mode: ShadeMode,
        light: &Light,
        normal: Normal,
        color: [u8; 3],
    ) -> Rgb888 {
        let i = match mode {
            ShadeMode::Flat => Some(Fx14::ONE),
            _ => self.hit(normal),
        };
        match i {
            Some(i) => shade_color(mode, color, i),
            None => self.shade_miss(mode, light, normal, color),
        }
    }

    /// [`IntensityMemo::shade`] of a normal the memo does not hold: the
    /// intensity computed and kept. Out of line and cold.
    #[cold]
    #[inline(never)]
    fn shade_miss(&self, mode: ShadeMode, light: &Light, normal: Normal, color: [u8; 3]) -> Rgb888 {
        shade_color(mode, color, self.intensity(light, normal))
    }

    /// The entry of `normal`'s words `b` (`None`: no memo).
    #[inline(always)]
    fn entry(&self, b: [u32; 3]) -> Option<&Cell<[u32; 4]>> {
        // A multiplicative hash of the three words; its top bits pick
        // the entry. The rotations and multiplier put the six axis
        // normals in six distinct entries in either form (a scene's walls
        // and floors face these ways; the hash before session 27 put the
        // compact +x, +y and +z in one entry, and `bench_city`'s frame
        // missed three times as often, 3.4 % dearer on the Cortex-M4F):
        // `memo_entries_of_axis_normals_differ`.
        let h = (b[0] ^ b[1].rotate_left(22) ^ b[2].rotate_left(24)).wrapping_mul(0x27D4_EB2F);
        self.entries.get((h >> 29) as usize % MEMO.max(1))
    }

    /// The intensity the memo holds for `normal`, if any.
    #[inline(always)]
    fn hit(&self, normal: Normal) -> Option<Fx14> {
        let b = normal.bits;
        let [k0, k1, k2, i] = self.entry(b)?.get();
        // Word by word (an array comparison is a `memcmp` call). The two
        // forms' keys differ in their words (see `Normal`).
        (k0 == b[0] && k1 == b[1] && k2 == b[2] && i != NO_INTENSITY)
            .then(|| Fx14::from_raw(i as i32))
    }

    /// [`Light::intensity_of`] of a normal the memo does not hold, kept in
    /// its entry (evicting the entry's normal).
    #[inline(always)]
    fn intensity(&self, light: &Light, normal: Normal) -> Fx14 {
        let i = light.intensity_of(normal);
        let b = normal.bits;
        if let Some(e) = self.entry(b) {
            e.set([b[0], b[1], b[2], i.raw() as u32]);
        }
        i
    }
}

/// Depth cueing (the `depth-cue` effect): a face fades toward the fog
/// colour with its eye depth.
///
/// The renderer passes the mean clip `w` of the face's vertices (eye depth
/// for a perspective camera; a parallel camera has one `w` everywhere and
/// so no fade). Between `near` and `far` (usually the depth range of the
/// tree's bounding sphere, [`crate::render::Frame::depth_range`]) the
/// weight of the fog grows linearly from 0 to `strength / 256`:
/// `c' = (c · (256 − a) + fog · a + 128) / 256` with
/// `a = ⌊strength · clamp((w − near) / (far − near), 0, 1)⌋`. One
/// division and a few integer operations per face; IEEE `f32`, so
/// identical on every target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthCue {
    /// Depth at which fading starts.
    pub near: f32,
    /// Depth of the strongest fade.
    pub far: f32,
    /// The colour faces fade toward (usually the background).
    pub fog: Rgb888,
    /// Fog weight at `far`, in 256ths (0..=256).
    pub strength: u16,
}

impl Default for DepthCue {
    /// [`DepthCue::DEFAULT`].
    fn default() -> DepthCue {
        DepthCue::DEFAULT
    }
}

impl DepthCue {
    /// No range yet (nothing fades until one is set), toward black, 3/4 at
    /// the far end.
    pub const DEFAULT: DepthCue = DepthCue {
        near: 0.0,
        far: 0.0,
        fog: Rgb888::new(0, 0, 0),
        strength: 192,
    };

    /// The fog weight (0..=256) at depth `w`.
    pub fn weight(&self, w: f32) -> u32 {
        let span = self.far - self.near;
        if !(span > 0.0 && w.is_finite() && span.is_finite()) {
            return 0;
        }
        let t = ((w - self.near) / span).clamp(0.0, 1.0);
        (t * f32::from(self.strength.min(256))) as u32
    }

    /// `c` faded for depth `w`.
    pub fn apply(&self, c: Rgb888, w: f32) -> Rgb888 {
        let a = self.weight(w);
        if a == 0 {
            return c;
        }
        let mix = |c: u8, f: u8| ((u32::from(c) * (256 - a) + u32::from(f) * a + 128) >> 8) as u8;
        Rgb888::new(
            mix(c.r(), self.fog.r()),
            mix(c.g(), self.fog.g()),
            mix(c.b(), self.fog.b()),
        )
    }
}

#[cfg(test)]
mod tests;
