//! The integer vertex path, for cores without an FPU (Cortex-M0: no
//! hardware divide, only a 32×32→32 multiply): transform, clipping and
//! projection in 32-bit integers, with no division per vertex (the
//! perspective divide's reciprocal is a table seed and one Newton step)
//! and no 64-bit division anywhere.
//!
//! Formats (see [`IntMatrix`] for the proofs of the bounds):
//! * **Vertices** are integers of at most 16 bits, `|v| ≤ 2^15`, in units
//!   of `2^-VB` ([`IntPath<VB>`]). `f32` vertices are rounded to that grid
//!   ([`VertexPath::transform`]: one conversion a coordinate), integer
//!   vertices with `frac` fraction bits are shifted onto it
//!   ([`VertexPath::transform_q`]). Coordinates beyond `±2^(15 − VB)`
//!   saturate there (the vertex moves onto the boundary, never wraps).
//!   The default `VB = 1` covers `±2^14`: the vertices of the renderer's
//!   frames ([`crate::render::Frame`] scales every tree to a radius in
//!   `[2^13, 2^14]`) with a resolution of `2^-15` of the radius, as fine as
//!   a q16 tree stores them.
//! * **Matrix** ([`IntMatrix`], made once a frame by
//!   [`VertexPath::prepare`], in `f32`): rows x, y and w; each row's three
//!   linear entries are 15-bit integers (the largest in `[2^13, 2^14]`)
//!   with a right shift of the row's product sum, and the translation is
//!   an `i32` already in output units. The output units `2^-e` are chosen
//!   per frame so that every clip coordinate of a vertex in range stays
//!   below `2^28 + 2^16` in magnitude.
//! * **Clip** coordinates are `i32` in those units ([`ClipNum`] for `i32`
//!   below). The units change with the camera, which is why
//!   [`VertexPath::near`] and [`VertexPath::depth`] take the matrix.
//! * **Per vertex**: nine 32×32→32 multiplies, adds and three shifts
//!   (transform); one count of leading zeros, a reciprocal from a 128-entry
//!   table and one Newton step (no division at all), and eight multiplies
//!   (projection).
//!
//! Accuracy (tests below, against [`super::transform::FloatPath`]): entries
//! carry 14–15 significant bits, vertices 16, the projection's `w` 16 and
//! its reciprocal 16: on a 240-pixel display with 4 sub-pixel bits a
//! vertex on screen lands within 1 sub-pixel unit of the `f32` path's
//! position (typically 0–1; the `f32` path itself rounds). Larger displays
//! lose precision in proportion (the ratio `x/w` has about 15 significant
//! bits), never range: nothing overflows for any viewport up to
//! [`super::transform::MAX_DIM`].
//!
//! Clipping (rare: only polygons crossing the near plane or the guard
//! band) interpolates with an exact `floor(da·2^30 / (da − db))` from a
//! bit-serial loop (no division routine, no 64-bit division) and one
//! 64-bit product a coordinate; it is computed once per new vertex
//! ([`ClipNum::lerp_vert`]).

use super::camera::Mat4;
use super::clip::{ClipNum, ClipVert, GUARD};
use super::transform::{AxisShifts, ScreenPt, VertexPath, Viewport};

/// Integer vertex path with vertices in units of `2^-VB` (see the module
/// docs; `VB ≤ 15`, larger values act as 15).
#[derive(Clone, Copy, Debug, Default)]
pub struct IntPath<const VB: u32 = 1>;

/// The per-frame matrix of [`IntPath`]: `clip_r = ((Σ_j m[r][j]·v_j) >>
/// shift[r]) + t[r]` for the rows x, y and w, in units of `2^-e` of the
/// camera's clip space.
///
/// Bounds (with `|v_j| ≤ 2^15`):
/// * `|m[r][j]| ≤ 2^14`, so each product is at most `2^29` and the sum of
///   three below `2^30.6`: no i32 overflow.
/// * `e` is the largest exponent with `B·2^e ≤ 2^28`, where `B` bounds
///   every row over the vertex range: `B = max_r(Σ_j |M_rj|·V + |T_r|)`,
///   `V = 2^(15 − VB)`. The row's entries are `m = round(M·2^a_r)` with
///   the row's largest in `[2^13, 2^14]`, and `shift = a_r + VB − e`.
///   Since `B ≥ max_j|M_rj|·V ≥ 2^(13 − a_r + 15 − VB)`, `e ≤ a_r + VB −
///   1`: the shift is at least 1, i.e. every row's products are scaled
///   down (never up) into output units.
/// * Hence `|clip_r| ≤ B·2^e + 1.5·2^15 + 1 < 2^28 + 2^16`: the guard
///   band's `4·w` and every clipping sum stay far inside i32.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IntMatrix {
    m: [[i32; 3]; 3],
    shift: [u32; 3],
    t: [i32; 3],
    e: i32,
}

/// `2^k` as `f32`, for `k` in `[-126, 127]` (clamped).
#[inline]
fn pow2(k: i32) -> f32 {
    f32::from_bits(((k.clamp(-126, 127) + 127) as u32) << 23)
}

/// `x · 2^k` for any `k` (in steps that stay in range; `0` or `±∞` when
/// the result underflows or overflows).
fn scale2(x: f32, k: i32) -> f32 {
    let mut x = x;
    let mut k = k;
    while k > 126 {
        x *= pow2(126);
        k -= 126;
    }
    while k < -126 {
        x *= pow2(-126);
        k += 126;
    }
    x * pow2(k)
}

/// `floor(log2 |x|)` of a finite non-zero normal `x`; `None` for zero,
/// subnormals and non-finite values.
#[inline]
fn exponent(x: f32) -> Option<i32> {
    let b = (x.to_bits() >> 23) & 0xff;
    (b != 0 && b != 0xff).then_some(b as i32 - 127)
}

/// Round half away from zero, saturating outside i32 (NaN → 0).
#[inline]
fn round_i32(x: f32) -> i32 {
    (if x >= 0.0 { x + 0.5 } else { x - 0.5 }) as i32
}

/// Largest vertex coordinate in grid units.
const VLIM: i32 = 1 << 15;

impl<const VB: u32> IntPath<VB> {
    /// The vertex grid's fraction bits.
    const B: u32 = if VB > 15 { 15 } else { VB };

    /// `M · [v, 1]` for a vertex on the grid (`|v_j| ≤ 2^15`).
    #[inline(always)]
    fn apply(m: &IntMatrix, v: [i32; 3]) -> ClipVert<i32> {
        let row = |r: usize| {
            let [a, b, c] = m.m[r];
            // |a·v0 + b·v1 + c·v2| ≤ 3·2^29 (IntMatrix bounds); shift ≤ 31.
            ((a * v[0] + b * v[1] + c * v[2]) >> m.shift[r]) + m.t[r]
        };
        ClipVert {
            x: row(0),
            y: row(1),
            w: row(2),
        }
    }

    /// An integer coordinate with `frac` fraction bits on the grid:
    /// rounded (half up) when it has more fraction bits, saturating when
    /// shifted up; then clamped to `±2^15`.
    #[inline]
    fn to_grid(c: i32, frac: u32) -> i32 {
        let c = if frac > Self::B {
            // floor((c + 2^(s−1)) / 2^s) = ceil-half of floor(c / 2^(s−1)),
            // without the overflow of adding first.
            let t = c >> (frac - Self::B - 1).min(31);
            (t >> 1) + (t & 1)
        } else {
            let s = Self::B - frac;
            c.clamp(-(VLIM >> s), VLIM >> s) << s
        };
        c.clamp(-VLIM, VLIM)
    }
}

impl<const VB: u32> VertexPath for IntPath<VB> {
    type Scalar = i32;
    type Matrix = IntMatrix;
    const RAW_Q16_FRAC: Option<u32> = Some(VB);
    const UNSET: IntMatrix = IntMatrix {
        m: [[0; 3]; 3],
        shift: [0; 3],
        t: [0; 3],
        e: 0,
    };
    const NEAR_MIN: i32 = 1;

    /// Once a frame, in `f32` (see [`IntMatrix`]). A matrix with a
    /// non-finite entry becomes the zero matrix: every vertex gets `w = 0`,
    /// behind the near plane, so nothing is drawn (the float path skips
    /// such vertices too). Entries below `2^-126` in magnitude count as 0.
    fn prepare(m: &Mat4) -> IntMatrix {
        let rows = [m.0[0], m.0[1], m.0[3]];
        if !rows.iter().flatten().all(|v| v.is_finite()) {
            return IntMatrix::default();
        }
        // Work with the entries scaled by 2^-g (g: the largest exponent),
        // so that the bound B cannot overflow f32.
        let g = rows
            .iter()
            .flatten()
            .filter_map(|&v| exponent(v))
            .max()
            .unwrap_or(0);
        let vmax = pow2(15 - Self::B as i32);
        let bound = rows
            .iter()
            .map(|r| {
                let s = |k: usize| scale2(r[k].abs(), -g);
                (s(0) + s(1) + s(2)) * vmax + s(3)
            })
            .fold(0.0f32, f32::max);
        let Some(eb) = exponent(bound) else {
            return IntMatrix::default();
        };
        // B·2^e < 2^(eb + g + 1)·2^e ≤ 2^28.
        let e = 27 - (eb + g);
        let mut out = IntMatrix {
            e,
            ..IntMatrix::default()
        };
        for (k, r) in rows.iter().enumerate() {
            out.t[k] = round_i32(scale2(r[3], e));
            let big = r[..3].iter().fold(0.0f32, |a, v| a.max(v.abs()));
            let Some(eb) = exponent(big) else {
                continue; // no linear part: m = 0, shift 0
            };
            let a = 13 - eb;
            // ≥ 1 by the bound argument; at most 31 (a row whose entries
            // are below 2^-17 of the bound loses them, as it should).
            let shift = (a + Self::B as i32 - e).clamp(1, 31);
            let a = shift + e - Self::B as i32;
            out.shift[k] = shift as u32;
            for (d, &v) in out.m[k].iter_mut().zip(r) {
                *d = round_i32(scale2(v, a)).clamp(-(1 << 14), 1 << 14);
            }
        }
        out
    }

    /// Rounds each coordinate to the grid (`None` if one is not finite).
    #[inline]
    fn transform(m: &IntMatrix, v: [f32; 3]) -> Option<ClipVert<i32>> {
        let s = pow2(Self::B as i32);
        let lim = VLIM as f32;
        let mut g = [0i32; 3];
        for (d, c) in g.iter_mut().zip(v) {
            if !c.is_finite() {
                return None;
            }
            *d = round_i32((c * s).clamp(-lim, lim));
        }
        Some(Self::apply(m, g))
    }

    #[inline]
    fn transform_q(m: &IntMatrix, v: [i32; 3], frac: u32) -> Option<ClipVert<i32>> {
        if frac > 62 {
            return None;
        }
        Some(Self::apply(m, v.map(|c| Self::to_grid(c, frac))))
    }

    /// `round(near_w · 2^e)`, at least 1 and at most `2^30`.
    fn near(m: &IntMatrix, near_w: f32) -> i32 {
        let n = scale2(near_w, m.e);
        if n >= 1.0 {
            round_i32(n.min(pow2(30)))
        } else {
            1
        }
    }

    fn depth(m: &IntMatrix, w: i32) -> f32 {
        scale2(w as f32, -m.e)
    }

    fn project(v: &ClipVert<i32>, vp: &Viewport) -> Option<ScreenPt> {
        if v.w <= 0 {
            return None;
        }
        // The guard band bounds what follows for any caller. It stays in
        // the pipeline's form too (the default `project_clipped`): a vertex
        // made by clipping can lie a few units outside a guard plane cut
        // by an earlier pass (each coordinate's interpolation rounds on
        // its own), and this clamp moves it back.
        let g = v.w.saturating_mul(GUARD);
        Some(project_inside(v.x.clamp(-g, g), v.y.clamp(-g, g), v.w, vp))
    }
}

/// The projection of `(x, y, w)` with `w > 0`, `|x|, |y| ≤ min(4w,
/// i32::MAX)`: `round((x/w + 1)·W·2^S/2)`, `round((1 − y/w)·H·2^S/2)`.
///
/// 1. `x, y, w` are shifted together (the ratios are all that matters) so
///    that `w' ∈ [2^15, 2^16)`: exact when shifted up, with a relative
///    error below `2^-15` when shifted down. Then `|x'|, |y'| ≤ 4w' + 3`.
/// 2. The reciprocal `r ≈ 2^31 / w'` ([`recip`]: a table and one Newton
///    step, no division), `2^15 < r ≤ 2^16`.
/// 3. `u = x' + w'` (`|u| < 5·2^16 + 3 < 2^18.4`); `q = floor(u·r / 2^8)
///    ≈ (u/w)·2^23`, `|q| < 5.1·2^23`, from two products that each fit
///    (`|u >> 8|·r < 2^26.4`, `(u & 255)·r < 2^24`).
/// 4. The screen coordinate `q·n·2^S / 2^24` via [`AxisShifts`].
///
/// Wrapping arithmetic keeps the function total for any input; for inputs
/// in its domain nothing wraps (the bounds above).
#[inline]
fn project_inside(x: i32, y: i32, w: i32, vp: &Viewport) -> ScreenPt {
    let bits = 32 - w.leading_zeros();
    let (x, y, w) = if bits > 16 {
        let s = bits - 16;
        (x >> s, y >> s, w >> s)
    } else {
        let s = 16 - bits;
        (x.wrapping_shl(s), y.wrapping_shl(s), w.wrapping_shl(s))
    };
    let r = recip(w as u32);
    let ratio = |u: i32| {
        (u >> 8)
            .wrapping_mul(r)
            .wrapping_add(((u & 255).wrapping_mul(r)) >> 8)
    };
    let [sx, sy] = vp.shifts();
    let screen = |q: i32, n: u32, s: AxisShifts| {
        (q >> s.pre)
            .wrapping_mul(n as i32)
            .wrapping_add(1 << (s.post - 1))
            >> s.post
    };
    ScreenPt {
        x: screen(ratio(x.wrapping_add(w)), vp.width(), sx),
        y: screen(ratio(w.wrapping_sub(y)), vp.height(), sy),
    }
}

/// Seeds of [`recip`]: `round(2^31 / m)` at the midpoint `m` of each of
/// the 128 intervals `[256·k, 256·(k + 1))`, `k ∈ [128, 256)`, i.e.
/// `round(2^24 / (2k + 1))`. Relative error below `2^-8` over the interval.
const RECIP_SEED: [u16; 128] = {
    let mut t = [0u16; 128];
    let mut i = 0;
    while i < 128 {
        let d = 2 * (i as u32 + 128) + 1;
        t[i] = ((1u32 << 25) / d).div_ceil(2) as u16;
        i += 1;
    }
    t
};

/// `2^31 / w` for `w ∈ [2^15, 2^16)`, from below: `2^31/w − 2 ≤ r ≤
/// 2^31/w` (checked for every `w` by a test), so `2^15 − 2 < r ≤ 2^16`.
///
/// No division: a core without a divide instruction (Cortex-M0) would call
/// a software division of about a hundred instructions; this is a table
/// load and three multiplies. A seed `r0` with relative error `ε ≤ 2^-8`,
/// then one Newton step `r1 = r0·(2 − w·r0/2^31)`, whose error is `−ε²·(1/w)`
/// (never above the true value) plus the truncations: `e = 2^31 − w·r0`
/// (`w·r0 < 2^32` as u32; `|e| ≤ 2^23.1`), `r1 = r0 + (r0·(e >> 9)) >> 22`
/// (`|r0·(e >> 9)| < 2^16·2^14.1 < 2^31`). Inputs outside the range give
/// some value without overflow (wrapping).
#[inline]
fn recip(w: u32) -> i32 {
    let k = ((w >> 8) as usize).wrapping_sub(128) & 127;
    let r0 = RECIP_SEED[k] as i32;
    let e = (1u32 << 31).wrapping_sub(w.wrapping_mul(r0 as u32)) as i32;
    r0.wrapping_add(r0.wrapping_mul(e >> 9) >> 22)
}

/// The interpolation parameter `floor(da·2^30 / (da − db))` in `[0, 2^30]`
/// for `da ≥ 0 > db` (other inputs are clamped into that domain), exact,
/// from a restoring division: 30 shift-and-subtract steps on a 64-bit
/// remainder below `2^33`, no division instruction or routine.
fn clip_param(da: i32, db: i32) -> u32 {
    let num = da.max(0) as u64;
    let den = num + (db.min(-1) as i64).unsigned_abs();
    if num >= den {
        return 1 << 30;
    }
    let mut rem = num;
    let mut t = 0u32;
    for _ in 0..30 {
        rem <<= 1;
        t <<= 1;
        if rem >= den {
            rem -= den;
            t |= 1;
        }
    }
    t
}

/// `a + floor((b − a)·t / 2^30)`: between `a` and `b` for `t ≤ 2^30`
/// (`|b − a| < 2^32`, so the product is below `2^62`).
#[inline]
fn mix(a: i32, b: i32, t: u32) -> i32 {
    let d = (b as i64 - a as i64) * t as i64;
    (a as i64 + (d >> 30)) as i32
}

/// Clip coordinates of the integer path. Every operation saturates (the
/// transform keeps values below `2^28 + 2^16`, where nothing does), so the
/// plane tests keep their sign for any input.
impl ClipNum for i32 {
    const ZERO: i32 = 0;
    fn sub(a: i32, b: i32) -> i32 {
        a.saturating_sub(b)
    }
    fn guard(w: i32, c: i32, g: i32, neg: bool) -> i32 {
        let gw = w.saturating_mul(g);
        if neg {
            gw.saturating_add(c)
        } else {
            gw.saturating_sub(c)
        }
    }
    fn lerp(a: i32, b: i32, da: i32, db: i32) -> i32 {
        mix(a, b, clip_param(da, db))
    }
    fn lerp_vert(i: &ClipVert<i32>, o: &ClipVert<i32>, di: i32, d_o: i32) -> ClipVert<i32> {
        let t = clip_param(di, d_o);
        ClipVert {
            x: mix(i.x, o.x, t),
            y: mix(i.y, o.y, t),
            w: mix(i.w, o.w, t),
        }
    }
    fn scale(w: i32, g: i32) -> i32 {
        w.saturating_mul(g)
    }
    fn neg(a: i32) -> i32 {
        a.saturating_neg()
    }
    /// In the path's units (see [`VertexPath::depth`] for camera units).
    fn to_f32(self) -> f32 {
        self as f32
    }
    /// The planes' tests, exactly: `sat(4w) − x ≥ 0` and `sat(4w) + x ≥
    /// 0` (saturation keeps the sign) hold together iff `4w ≥ |x|` with
    /// `4w` saturated, which needs `4w ≥ 0`.
    #[inline]
    fn inside(v: &ClipVert<i32>, near: i32) -> bool {
        let g = v.w.saturating_mul(GUARD);
        v.w.saturating_sub(near) >= 0
            && g >= 0
            && v.x.unsigned_abs() <= g as u32
            && v.y.unsigned_abs() <= g as u32
    }
}

/// The camera for drawing q16 vertices as stored (`i16` per axis, offset
/// `half_extent[axis] · q / 32767` from the tree's origin) through
/// [`super::Renderer::draw_polygon_q`] with `frac` fraction bits, when
/// `camera` is a [`crate::render::Frame`]'s camera, which takes
/// origin-relative vertices times `vertex_scale`: the per-axis scale is
/// folded into the matrix columns (once a frame), so the per-vertex work
/// has no multiply by it. With [`IntPath<VB>`] pass `frac = VB`: the raw
/// values are then on the vertex grid as they are (`|q| ≤ 32767`).
pub fn q16_camera(
    camera: &super::Camera,
    vertex_scale: f32,
    half_extent: [f32; 3],
    frac: u32,
) -> super::Camera {
    let k = pow2(frac.min(100) as i32);
    let col = half_extent.map(|h| h / 32767.0 * vertex_scale * k);
    let mut m = camera.matrix;
    for row in m.0.iter_mut() {
        for (e, s) in row.iter_mut().zip(col) {
            *e *= s;
        }
    }
    super::Camera {
        matrix: m,
        near_w: camera.near_w,
    }
}

#[cfg(test)]
mod tests;
