//! Vertex transform (model → clip space) and the perspective divide (clip →
//! screen fixed point), in interchangeable arithmetics: the two below and
//! the 32-bit integer path of [`super::int_path`] (for cores without an
//! FPU).
//!
//! * [`FixedPath<F>`]: matrix and vertices as [`Fx<F>`] (default 16.16),
//!   clip coordinates as [`FxWide<F>`] (i64). Model coordinates outside the
//!   `Fx<F>` range (±32768 for F = 16) saturate: such a vertex is moved onto
//!   the range boundary, never wrapped. Matrix entries saturate likewise.
//! * [`FloatPath<M>`]: `f32` throughout, with `M`'s reciprocal and floor in
//!   the divide. Clip coordinates beyond ±[`FLOAT_CLIP_LIMIT`] are treated
//!   as non-finite (the polygon is skipped) so that the clipper's sums can
//!   never overflow to infinity.
//!
//! Screen coordinates ([`ScreenPt`]) are integers in units of
//! `2^-SUB` pixel, produced only from clipped vertices (so `w ≥ near_w > 0`
//! and `|x|, |y| ≤ GUARD·w`). The divide rounds to nearest (halves up), and
//! the result is additionally clamped to ±[`SCREEN_LIMIT`], so no later
//! stage can overflow even if a caller feeds unclipped vertices.
//! The same clip vertex always gives the same screen point: projection is a
//! pure function, which is what lets shared vertices meet exactly.

use core::fmt::Debug;
use core::marker::PhantomData;

use super::camera::Mat4;
use super::clip::{ClipNum, ClipVert, GUARD};
use super::precision::MathFns;
use super::proof::{prove_float, VertexBound};
use crate::fixed::{div_floor_i64, Fx, FxWide};

/// Largest supported viewport side, in pixels.
pub const MAX_DIM: u32 = 16384;

/// Bound on screen coordinates in sub-pixel units. With `MAX_DIM = 2^14`,
/// the guard band (|ndc| ≤ 4 → at most 2.5 viewports from the origin) and
/// 8 sub-pixel bits, real coordinates stay below 2^23.4; the clamp is a
/// safety net with margin.
pub const SCREEN_LIMIT: i32 = 1 << 24;

/// Float clip coordinates larger than this are rejected (see module docs).
pub const FLOAT_CLIP_LIMIT: f32 = 1e36;

/// A vertex in screen space, in `2^-SUB` pixel units (`SUB` = the
/// precision's sub-pixel bits); y grows downward.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ScreenPt {
    /// x in sub-pixel units.
    pub x: i32,
    /// y in sub-pixel units.
    pub y: i32,
}

/// Viewport size and sub-pixel resolution: the clip → screen mapping.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Viewport {
    width: u32,
    height: u32,
    sub: u32,
    /// The integer projection's shifts for x and y (derived from the
    /// above once, see [`AxisShifts`]).
    shifts: [AxisShifts; 2],
    /// The float projection's scales for x and y, half a side in sub-pixel
    /// units (`0.5 · (side << sub)`, exact), as `f32` bits: derived once
    /// here, not at every vertex (they were ten instructions of a vertex
    /// cache's miss). Bits, so that the type keeps `Eq`.
    half_bits: [u32; 2],
    /// [`Viewport::float_points_fit_i16`], decided once here.
    float_fits_i16: bool,
}

/// The shifts with which the integer path maps `u/w` (a fixed-point ratio
/// with 23 fraction bits, below `5.1 · 2^23`) to sub-pixel units along an
/// axis of `n` pixels: `round((q >> pre) · n / 2^post)`. `pre =
/// max(0, bits(n) − 5)` keeps the product below `2^25.4 · 2^5 < 2^31`;
/// `post = 24 − sub − pre ≥ 6` (`n ≤ 2^14` so `pre ≤ 10`, `sub ≤ 8`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct AxisShifts {
    /// Right shift of the ratio before the multiply.
    pub(crate) pre: u32,
    /// Right shift (with rounding) after it.
    pub(crate) post: u32,
}

impl AxisShifts {
    const fn of(n: u32, sub: u32) -> AxisShifts {
        let pre = (32 - n.leading_zeros()).saturating_sub(5);
        let post = 24u32.saturating_sub(sub + pre);
        AxisShifts {
            pre,
            // `max(1)`, spelt out (`Ord::max` is not `const`).
            post: if post < 1 { 1 } else { post },
        }
    }
}

impl Viewport {
    /// A viewport of `width × height` pixels with `sub` sub-pixel bits.
    /// `None` when a side is 0 or above [`MAX_DIM`], or `sub > 8`.
    pub const fn new(width: u32, height: u32, sub: u32) -> Option<Viewport> {
        if !(width >= 1 && width <= MAX_DIM && height >= 1 && height <= MAX_DIM && sub <= 8) {
            return None;
        }
        Some(Viewport {
            width,
            height,
            sub,
            shifts: [AxisShifts::of(width, sub), AxisShifts::of(height, sub)],
            half_bits: [
                (0.5 * (width << sub) as f32).to_bits(),
                (0.5 * (height << sub) as f32).to_bits(),
            ],
            // Float NDC is within ±4.5 (the clamp, or a miss's clip test),
            // so a coordinate lies in `[−3.5·half, 5.5·half + 0.5]`, `half =
            // (side << sub) / 2`: `i16` when `11·(side << sub) + 2 ≤ 4·32767`.
            float_fits_i16: 11 * ((if width > height { width } else { height }) << sub) + 2
                <= 4 * 32767,
        })
    }

    /// The integer projection's shifts for x (`0`) and y (`1`).
    #[inline]
    pub(crate) fn shifts(&self) -> [AxisShifts; 2] {
        self.shifts
    }

    /// Whether every screen point [`FloatPath`] gives for this viewport
    /// (projected, clipped or not) has both coordinates within `i16`: a
    /// tagged vertex cache then packs a miss's point without its test
    /// (`vcache::pack_tagged`), proven once per viewport, not per vertex.
    #[inline]
    pub(crate) fn float_points_fit_i16(&self) -> bool {
        self.float_fits_i16
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Sub-pixel bits.
    pub fn sub_bits(&self) -> u32 {
        self.sub
    }

    /// `width / height`.
    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }
}

/// Vertex arithmetic: how a model point becomes a clip vertex and a clip
/// vertex becomes a screen point.
pub trait VertexPath {
    /// Clip-space scalar.
    type Scalar: ClipNum;
    /// The per-frame matrix in this path's format.
    type Matrix: Copy + Debug;
    /// `Some(frac)` when the path prefers a q16 tree's vertices as stored
    /// (raw `i16` through [`VertexPath::transform_q`] with `frac` fraction
    /// bits, the camera folding in the per-axis scale:
    /// [`super::int_path::q16_camera`]) to decoding them to `f32`: a path
    /// for cores without an FPU. The tree walks of [`crate::render`] then
    /// draw q16 trees that way.
    const RAW_Q16_FRAC: Option<u32> = None;
    /// Whether the path's transform is `f32` products and sums of the
    /// matrix entries and the vertex (the float path): then a
    /// power-of-two vertex scale `s ≥ 1` may be moved into the matrix's
    /// first three columns where every scaled entry and coordinate stays
    /// finite, since `(m·s)·x` and `m·(x·s)` are then the same exact
    /// product, rounded once (`render::cached`, a multiplication less a
    /// coordinate on every transform).
    const FOLDS_SCALE: bool = false;
    /// The matrix of a renderer whose camera is not set yet
    /// ([`super::Renderer::sized`]): the zero matrix, which puts every
    /// vertex at `w = 0`, behind [`VertexPath::NEAR_MIN`], so nothing is
    /// drawn.
    const UNSET: Self::Matrix;
    /// The smallest near threshold [`VertexPath::near`] returns (one unit
    /// in the last place).
    const NEAR_MIN: Self::Scalar;
    /// Converts a matrix (once per frame).
    fn prepare(m: &Mat4) -> Self::Matrix;
    /// `M · [v, 1]`; `None` if `v` or the result is not finite.
    fn transform(m: &Self::Matrix, v: [f32; 3]) -> Option<ClipVert<Self::Scalar>>;
    /// Like [`VertexPath::transform`] for integer vertices with `frac`
    /// fraction bits (q16 → 16, q32 → 32; at most 62).
    fn transform_q(m: &Self::Matrix, v: [i32; 3], frac: u32) -> Option<ClipVert<Self::Scalar>>;
    /// The near threshold in this path's format for the prepared matrix
    /// `m` (at least one unit in the last place, so that it is positive).
    /// It takes the matrix because a path may choose the units of its clip
    /// coordinates per frame ([`super::int_path::IntPath`] does).
    fn near(m: &Self::Matrix, near_w: f32) -> Self::Scalar;
    /// A clip `w` of matrix `m` as `f32` in the camera's units (for
    /// per-face decisions such as depth cueing, compared with ranges in
    /// the units of [`super::camera::Camera::matrix`]).
    #[inline]
    fn depth(m: &Self::Matrix, w: Self::Scalar) -> f32 {
        let _ = m;
        w.to_f32()
    }
    /// Perspective divide and viewport mapping; `None` if `w ≤ 0` or the
    /// vertex is not finite.
    fn project(v: &ClipVert<Self::Scalar>, vp: &Viewport) -> Option<ScreenPt>;
    /// [`VertexPath::project`] of a vertex of the renderer's pipeline: one
    /// from [`VertexPath::transform`] (or [`VertexPath::transform_q`]) that
    /// is inside every clip plane ([`ClipNum::inside`]), kept whole or made
    /// by clipping. The same result, with the checks such a vertex cannot
    /// fail left out where that is cheaper.
    #[inline]
    fn project_clipped(v: &ClipVert<Self::Scalar>, vp: &Viewport) -> Option<ScreenPt> {
        Self::project(v, vp)
    }
    /// [`VertexPath::project_clipped`] of a vertex straight from
    /// [`VertexPath::transform`] (or [`VertexPath::transform_q`]) that is
    /// inside every clip plane ([`ClipNum::inside`]), not made by
    /// clipping: the same result, with what such a vertex cannot need left
    /// out where that is cheaper (a vertex cache's misses). The default is
    /// `project_clipped`.
    #[inline]
    fn project_inside(v: &ClipVert<Self::Scalar>, vp: &Viewport) -> Option<ScreenPt> {
        Self::project_clipped(v, vp)
    }
    /// Whether every screen point this path gives for viewport `vp` is
    /// proven to fit `i16` on both axes (so that a tagged cache's miss
    /// packs it without a test). The default proves nothing.
    #[inline]
    fn points_fit_i16(vp: &Viewport) -> bool {
        let _ = vp;
        false
    }
    /// The screen point of model point `v` as a vertex cache's miss needs
    /// it: [`VertexPath::transform`], the clip test ([`ClipNum::inside`])
    /// and [`VertexPath::project_inside`] (`None` when a check fails), the
    /// same result with the tests a path can share between them shared.
    /// The default is that chain.
    #[inline]
    fn project_model(
        m: &Self::Matrix,
        near: Self::Scalar,
        v: [f32; 3],
        vp: &Viewport,
    ) -> Option<ScreenPt> {
        Self::transform(m, v)
            .filter(|c| <Self::Scalar as ClipNum>::inside(c, near))
            .and_then(|c| Self::project_inside(&c, vp))
    }
    /// Whether, for prepared matrix `m` and near threshold `near`, every
    /// model point within `bound` is proven to pass every check of
    /// [`VertexPath::transform`], the clip test and the projection, so that
    /// [`VertexPath::project_proven`] may stand for them this frame
    /// (checked once a frame: [`super::proof`]). The default proves
    /// nothing.
    fn prove(m: &Self::Matrix, near: Self::Scalar, bound: &VertexBound) -> bool {
        let _ = (m, near, bound);
        false
    }
    /// The screen point of model point `v`: the same as
    /// [`VertexPath::transform`], the clip test ([`ClipNum::inside`]) and
    /// [`VertexPath::project_clipped`] give (`None` when one fails), for a
    /// frame where [`VertexPath::prove`] holds and `v` within its bound,
    /// where a path may leave the checks out. The default is that chain,
    /// as [`VertexPath::project_model`] gives it (the same result: a vertex
    /// the clip test passes projects the same by either projection).
    #[inline]
    fn project_proven(
        m: &Self::Matrix,
        near: Self::Scalar,
        v: [f32; 3],
        vp: &Viewport,
    ) -> Option<ScreenPt> {
        Self::project_model(m, near, v, vp)
    }
}

/// Fixed-point vertex path with `F` fraction bits (see module docs).
#[derive(Clone, Copy, Debug, Default)]
pub struct FixedPath<const F: u32>;

/// `f32` vertex path using math library `M` for the divide.
#[derive(Clone, Copy, Debug, Default)]
pub struct FloatPath<M>(PhantomData<M>);

impl<const F: u32> FixedPath<F> {
    fn row(m: &[Fx<F>; 4], v: &[Fx<F>; 3]) -> FxWide<F> {
        // Products ≤ 2^(62-F) after the rescale: from F = 2 on the sum fits
        // i64, so plain adds, not `FxWide`'s saturating ones (their tests).
        if F >= 2 {
            let p = |i: usize| m[i].mul_wide(v[i]).raw();
            FxWide::from_raw(p(0) + p(1) + p(2) + i64::from(m[3].raw()))
        } else {
            m[0].mul_wide(v[0]) + m[1].mul_wide(v[1]) + m[2].mul_wide(v[2]) + FxWide::from_fx(m[3])
        }
    }

    fn apply(m: &[[Fx<F>; 4]; 4], v: [Fx<F>; 3]) -> ClipVert<FxWide<F>> {
        ClipVert {
            x: Self::row(&m[0], &v),
            y: Self::row(&m[1], &v),
            w: Self::row(&m[3], &v),
        }
    }
}

impl<const F: u32> VertexPath for FixedPath<F> {
    type Scalar = FxWide<F>;
    type Matrix = [[Fx<F>; 4]; 4];
    const UNSET: Self::Matrix = [[Fx::ZERO; 4]; 4];
    const NEAR_MIN: Self::Scalar = FxWide::from_raw(1);

    fn prepare(m: &Mat4) -> Self::Matrix {
        m.0.map(|row| row.map(Fx::from_f32_saturating))
    }

    fn transform(m: &Self::Matrix, v: [f32; 3]) -> Option<ClipVert<Self::Scalar>> {
        if !v.iter().all(|c| c.is_finite()) {
            return None;
        }
        Some(Self::apply(m, v.map(Fx::from_f32_saturating)))
    }

    fn transform_q(m: &Self::Matrix, v: [i32; 3], frac: u32) -> Option<ClipVert<Self::Scalar>> {
        if frac > 62 {
            return None;
        }
        let conv = |c: i32| -> Fx<F> {
            let c = c as i64;
            let raw = if frac >= F {
                c >> (frac - F)
            } else {
                c.checked_shl(F - frac)
                    .filter(|s| s >> (F - frac) == c)
                    .unwrap_or(if c < 0 { i64::MIN } else { i64::MAX })
            };
            Fx::from_raw(raw.clamp(i32::MIN as i64, i32::MAX as i64) as i32)
        };
        Some(Self::apply(m, v.map(conv)))
    }

    fn near(_: &Self::Matrix, near_w: f32) -> Self::Scalar {
        let raw = FxWide::<F>::try_from_f32(near_w).map_or(1, FxWide::raw);
        FxWide::from_raw(raw.max(1))
    }

    fn project(v: &ClipVert<Self::Scalar>, vp: &Viewport) -> Option<ScreenPt> {
        let (mut x, mut y, mut w) = (v.x.raw(), v.y.raw(), v.w.raw());
        if w <= 0 {
            return None;
        }
        // Scale x, y, w down together (the ratio is all that matters) until
        // they fit in 33 bits, so that (x + w)·W·2^SUB < 2^34·2^22 fits.
        let big = x.unsigned_abs().max(y.unsigned_abs()).max(w.unsigned_abs());
        let shift = (64 - big.leading_zeros()).saturating_sub(33);
        x >>= shift;
        y >>= shift;
        w >>= shift;
        if w <= 0 {
            return None;
        }
        let sx = ((vp.width as i64) << vp.sub) * (x + w);
        let sy = ((vp.height as i64) << vp.sub) * (w - y);
        let d = 2 * w;
        let round = |n: i64| div_floor_i64(2 * n + d, 2 * d);
        let lim = SCREEN_LIMIT as i64;
        Some(ScreenPt {
            x: round(sx).clamp(-lim, lim) as i32,
            y: round(sy).clamp(-lim, lim) as i32,
        })
    }
}

impl<M: MathFns> VertexPath for FloatPath<M> {
    type Scalar = f32;
    type Matrix = Mat4;
    const FOLDS_SCALE: bool = true;
    const UNSET: Mat4 = Mat4([[0.0; 4]; 4]);
    const NEAR_MIN: f32 = 1e-30;

    fn prepare(m: &Mat4) -> Mat4 {
        *m
    }

    fn transform(m: &Mat4, v: [f32; 3]) -> Option<ClipVert<f32>> {
        // Rows x, y and w only (clip z is never used). A non-finite input
        // needs no test of its own: it makes every row non-finite (∞ times
        // an entry is ±∞ or, for a zero entry, NaN), which the output test
        // rejects.
        let ClipVert { x, y, w } = clip_f32(m, v);
        // `|s| ≤ LIMIT` is false for NaN and ±∞: it is the finiteness test.
        let ok = |s: f32| s.abs() <= FLOAT_CLIP_LIMIT;
        (ok(x) && ok(y) && ok(w)).then_some(ClipVert { x, y, w })
    }

    fn transform_q(m: &Mat4, v: [i32; 3], frac: u32) -> Option<ClipVert<f32>> {
        if frac > 62 {
            return None;
        }
        let scale = 1.0 / (1u64 << frac) as f64;
        Self::transform(m, v.map(|c| (c as f64 * scale) as f32))
    }

    fn near(_: &Mat4, near_w: f32) -> f32 {
        if near_w.is_finite() && near_w > 1e-30 {
            near_w
        } else {
            1e-30
        }
    }

    fn project(v: &ClipVert<f32>, vp: &Viewport) -> Option<ScreenPt> {
        if !(v.w > 0.0 && v.x.is_finite() && v.y.is_finite() && v.w.is_finite()) {
            return None;
        }
        let (x, y) = screen_f32::<M>(v, vp);
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        let lim = SCREEN_LIMIT;
        Some(ScreenPt {
            x: floor_to_i32(x).clamp(-lim, lim),
            y: floor_to_i32(y).clamp(-lim, lim),
        })
    }

    /// The same arithmetic as [`VertexPath::project`], without the checks
    /// such a vertex passes anyway: the transform bounds every coordinate
    /// by [`FLOAT_CLIP_LIMIT`], so clipping's sums and interpolations stay
    /// finite (that is what the limit is for), and every kept or clipped
    /// vertex has `w ≥ near > 0`: `x`, `y`, `w` need no test. The NDC
    /// clamp stays (it bounds what follows even for an inexact reciprocal,
    /// and is what `project` computes); after it `|x|, |y| ≤ 5.5 · 2^21 <
    /// SCREEN_LIMIT` (largest viewport, 8 sub-pixel bits), so the results
    /// are finite and the screen clamp changes nothing.
    #[inline]
    fn project_clipped(v: &ClipVert<f32>, vp: &Viewport) -> Option<ScreenPt> {
        let (x, y) = screen_f32::<M>(v, vp);
        Some(ScreenPt {
            x: floor_to_i32(x),
            y: floor_to_i32(y),
        })
    }

    /// [`VertexPath::project_clipped`] without the NDC clamp, which
    /// cannot fire here: the clip test holds exactly (`|x|, |y| ≤ 4w`,
    /// `4w` exact, `w ≥ near > 0` and finite), so with a reciprocal of
    /// relative error below `2^-12` (libm's is exact to half an ulp,
    /// micromath's is tested below that, `super::proof`) `|x·r|, |y·r| ≤
    /// 4·(1 + 2^-12)·(1 + 2^-24) < 4.5`, inside the clamp's `±4.5`. A
    /// clipped vertex may sit a rounding outside the guard plane, which is
    /// why `project_clipped` keeps it. Four compares a vertex cache miss.
    #[inline(always)]
    fn project_inside(v: &ClipVert<f32>, vp: &Viewport) -> Option<ScreenPt> {
        let r = M::recip(v.w);
        let (x, y) = ndc_to_screen(v.x * r, v.y * r, vp);
        Some(ScreenPt {
            x: floor_bounded(x),
            y: floor_bounded(y),
        })
    }

    /// The transform's finiteness test and the clip test in one: with
    /// `near ≤ w ≤ LIMIT / GUARD` (false for NaN), `|x|, |y| ≤ GUARD·w`
    /// (the clip test, `GUARD·w` exact) implies `|x|, |y|, |w| ≤ LIMIT`
    /// (the finiteness test), and a vertex below `near` fails the clip
    /// test whatever its finiteness; `w` above `LIMIT / GUARD` (never
    /// seen in a real scene) takes the two tests as written, out of line.
    /// The same points as the chain, three tests fewer a vertex.
    #[inline(always)]
    fn project_model(m: &Mat4, near: f32, v: [f32; 3], vp: &Viewport) -> Option<ScreenPt> {
        let c = clip_f32(m, v);
        // Both false for NaN.
        let (in_front, moderate) = (c.w >= near, c.w <= FLOAT_CLIP_LIMIT / GUARD as f32);
        if !in_front {
            return None;
        }
        if !moderate {
            // Transformed again there (the same arithmetic, the same
            // values): `c` need not be kept for it on the common path.
            let [x, y, z] = v;
            return project_model_huge::<M>(m, near, x, y, z, vp);
        }
        let g = GUARD as f32 * c.w;
        if !(c.x.abs() <= g && c.y.abs() <= g) {
            return None;
        }
        Self::project_inside(&c, vp)
    }

    fn prove(m: &Mat4, near: f32, bound: &VertexBound) -> bool {
        prove_float(m, near, bound)
    }

    #[inline(always)]
    fn points_fit_i16(vp: &Viewport) -> bool {
        vp.float_points_fit_i16()
    }

    /// The transform and projection without a check: in a proven frame
    /// ([`super::proof`]) `X`, `Y`, `W` are finite with `W ≥ near` and
    /// `|X|, |Y| ≤ (1 − 2^-8)·W`, so the finiteness and clip tests pass,
    /// `x/w` and `y/w` lie in `[−1, 1]` (the NDC clamp changes nothing)
    /// and the screen coordinates are at least 0.5 and below `2^23`,
    /// where the truncating conversion is the exact floor: the same
    /// arithmetic as the checked chain, the same point.
    #[inline(always)]
    fn project_proven(m: &Mat4, _near: f32, v: [f32; 3], vp: &Viewport) -> Option<ScreenPt> {
        let c = clip_f32(m, v);
        let r = M::recip(c.w);
        let (x, y) = ndc_to_screen(c.x * r, c.y * r, vp);
        Some(ScreenPt {
            x: x as i32,
            y: y as i32,
        })
    }
}

/// [`VertexPath::project_model`] of [`FloatPath`] for a model point
/// (`x`, `y`, `z`) whose clip `w` is above `LIMIT / GUARD`: the chain as
/// written (transform with its finiteness test, clip test, projection).
/// The point comes as three scalars, in registers: as an array, its
/// caller stored it to memory for every vertex, the common path's too.
#[cold]
#[inline(never)]
fn project_model_huge<M: MathFns>(
    m: &Mat4,
    near: f32,
    x: f32,
    y: f32,
    z: f32,
    vp: &Viewport,
) -> Option<ScreenPt> {
    FloatPath::<M>::transform(m, [x, y, z])
        .filter(|c| <f32 as ClipNum>::inside(c, near))
        .and_then(|c| FloatPath::<M>::project_inside(&c, vp))
}

/// Clip `x`, `y`, `w` of model point `v` (rows 0, 1 and 3 of `m`; clip
/// `z` is never used), unchecked.
#[inline(always)]
fn clip_f32(m: &Mat4, v: [f32; 3]) -> ClipVert<f32> {
    let row = |r: &[f32; 4]| r[0] * v[0] + r[1] * v[1] + r[2] * v[2] + r[3];
    ClipVert {
        x: row(&m.0[0]),
        y: row(&m.0[1]),
        w: row(&m.0[3]),
    }
}

/// The float projection's arithmetic, shared by both of its forms: clip
/// `x`, `y` divided by `w` (with `M`'s reciprocal), clamped to the guard
/// band plus half a unit, mapped to sub-pixel screen units with the half
/// unit that makes the later floor round to nearest.
#[inline(always)]
fn screen_f32<M: MathFns>(v: &ClipVert<f32>, vp: &Viewport) -> (f32, f32) {
    let r = M::recip(v.w);
    // Clipped vertices are within ±GUARD already; the clamp only protects
    // against rounding and against unclipped callers, and keeps the
    // float → int conversion in range.
    let lim = GUARD as f32 + 0.5;
    let nx = (v.x * r).clamp(-lim, lim);
    let ny = (v.y * r).clamp(-lim, lim);
    ndc_to_screen(nx, ny, vp)
}

/// NDC `nx`, `ny` mapped to sub-pixel screen units, with the half unit
/// that makes the later floor round to nearest.
#[inline(always)]
fn ndc_to_screen(nx: f32, ny: f32, vp: &Viewport) -> (f32, f32) {
    // `0.5 · (side << sub)`, computed when the viewport was made.
    let [sw, sh] = vp.half_bits.map(f32::from_bits);
    ((nx + 1.0) * sw + 0.5, (1.0 - ny) * sh + 0.5)
}

/// `floor(x)` as an integer for finite `x`, saturating outside the i32
/// range (the caller clamps to far less). Exact: the float → int
/// conversion truncates toward zero, which is the floor except for
/// negative non-integers, where the truncated value converts back to
/// something above `x`. A software `floorf` call per coordinate was a
/// visible part of the transform cost on a Cortex-M4.
#[inline]
fn floor_to_i32(x: f32) -> i32 {
    let t = x as i32;
    t.saturating_sub(((t as f32) > x) as i32)
}

/// [`floor_to_i32`] of an `x` known to lie well inside the `i32` range
/// (`|x| < 2^30`: [`VertexPath::project_inside`]'s points, within
/// `5.5 · 2^21` for the largest viewport), where the truncated value less
/// one cannot overflow: the same floor without the saturation, a
/// conditional subtraction (two instructions fewer a coordinate of a
/// cache miss).
#[inline(always)]
fn floor_bounded(x: f32) -> i32 {
    let t = x as i32;
    t - i32::from((t as f32) > x)
}

#[cfg(test)]
mod tests;
