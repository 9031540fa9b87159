//! Homogeneous clipping in clip space, before anything becomes a screen
//! integer.
//!
//! Sutherland–Hodgman against five planes (order: near, then the guard
//! band; see `PLANES` for why):
//! * near: `w − near_w ≥ 0` (drops everything at or behind the eye; the
//!   caller guarantees `near_w > 0`, so every kept point has `w > 0`);
//! * the guard band: `G·w ∓ x ≥ 0`, `G·w ∓ y ≥ 0` with [`GUARD`] = 4, i.e.
//!   `|ndc.x|, |ndc.y| ≤ 4` — a band of about four screens around the
//!   viewport. Polygons crossing the screen edge but not the band (the
//!   usual case) are not clipped at all, and the band bounds every
//!   projected coordinate, which is what keeps the fixed-point screen
//!   coordinates and the scan converter's i64 edge arithmetic from
//!   overflowing whatever the camera.
//!
//! Contract:
//! * Works for convex and concave polygons; a concave polygon may come out
//!   with zero-width "bridges" along a clip plane, which both fill rules
//!   render as nothing.
//! * Capacity: output is written to caller buffers of fixed length. Each
//!   plane can grow a concave polygon by up to half its vertex count; if the
//!   result would not fit, [`ClipError::Capacity`] is returned and the
//!   caller skips the polygon (never a partial polygon, never a panic).
//! * Determinism across polygons: an edge crossing a plane is always
//!   interpolated from its inside endpoint toward its outside endpoint, and
//!   the new vertex is snapped exactly onto the plane. Two polygons that
//!   share an edge (in either direction) therefore produce bit-identical
//!   intersection vertices, so clipping opens no crack between them.
//! * Accuracy limit (not a safety issue): clipping is only as good as its
//!   input. On the f32 path the transform of a vertex with coordinates
//!   around 1e9 already rounds by ~64 units, more than the distance from
//!   the eye to a plane seen from 10 units away, so such a scene cannot be
//!   drawn faithfully in f32 (the fixed path transforms exactly and can);
//!   and near-plane vertices carry the absolute rounding error of the
//!   polygon's coordinates divided by `near_w` after projection. Nothing
//!   overflows or panics either way; non-finite results skip the polygon.
//! * Arithmetic is generic over [`ClipNum`]: `f32` for the float path,
//!   [`FxWide`] (i64 with i128 products in the interpolation) for the fixed
//!   path, `i32` for the integer path (`super::int_path`: saturating
//!   plane tests, an exact bit-serial interpolation parameter, no division
//!   routine). None overflows on values the transform stage admits.

use core::fmt::Debug;

use crate::fixed::FxWide;

/// Guard-band half-width in NDC units: kept points satisfy `|x|, |y| ≤ G·w`.
pub const GUARD: i32 = 4;

/// A clip-space vertex. `z` is not kept: nothing is depth-tested or
/// far-clipped (visibility comes from the priority tree).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClipVert<S> {
    /// Clip x.
    pub x: S,
    /// Clip y.
    pub y: S,
    /// Clip w (eye depth for perspective, 1 for parallel cameras).
    pub w: S,
}

/// The scalar operations clipping needs.
pub trait ClipNum: Copy + PartialOrd + Debug + Default {
    /// Zero.
    const ZERO: Self;
    /// `a − b` (saturating where that applies).
    fn sub(a: Self, b: Self) -> Self;
    /// `g·w − c` when `neg` is false, `g·w + c` when true.
    fn guard(w: Self, c: Self, g: i32, neg: bool) -> Self;
    /// The point on segment `a → b` where a linear function that is `da`
    /// at `a` and `db` at `b` vanishes; callers guarantee `da ≥ 0 > db`.
    /// The result lies between `a` and `b` (inclusive).
    fn lerp(a: Self, b: Self, da: Self, db: Self) -> Self;
    /// The vertex on segment `i → o` where the plane's distance (`di` at
    /// `i`, `d_o` at `o`, `di ≥ 0 > d_o`) vanishes: [`ClipNum::lerp`] of
    /// each coordinate. A type whose interpolation parameter is costly
    /// (the integer path divides) computes it once here instead.
    #[inline]
    fn lerp_vert(i: &ClipVert<Self>, o: &ClipVert<Self>, di: Self, d_o: Self) -> ClipVert<Self> {
        ClipVert {
            x: Self::lerp(i.x, o.x, di, d_o),
            y: Self::lerp(i.y, o.y, di, d_o),
            w: Self::lerp(i.w, o.w, di, d_o),
        }
    }
    /// `g·w` (used to snap a guard-band intersection onto the plane).
    fn scale(w: Self, g: i32) -> Self;
    /// Negation.
    fn neg(a: Self) -> Self;
    /// The value as `f32`, rounded (for per-face decisions such as depth
    /// cueing, not for geometry).
    fn to_f32(self) -> f32;
    /// Whether `v` is inside every plane (`dist ≥ 0` for all of them): the
    /// test of every vertex of every polygon, so a type may answer it more
    /// directly, with the same result.
    #[inline]
    fn inside(v: &ClipVert<Self>, near: Self) -> bool {
        PLANES.iter().all(|p| p.dist(v, near) >= Self::ZERO)
    }
}

impl ClipNum for f32 {
    const ZERO: f32 = 0.0;
    fn sub(a: f32, b: f32) -> f32 {
        a - b
    }
    fn guard(w: f32, c: f32, g: i32, neg: bool) -> f32 {
        if neg {
            g as f32 * w + c
        } else {
            g as f32 * w - c
        }
    }
    fn lerp(a: f32, b: f32, da: f32, db: f32) -> f32 {
        // t in [0, 1] by the caller's sign guarantee; the clamp also
        // absorbs the inf/inf that a pathological (but finite) input could
        // produce, so the result stays between a and b.
        let t = da / (da - db);
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        a + (b - a) * t
    }
    fn scale(w: f32, g: i32) -> f32 {
        g as f32 * w
    }
    fn neg(a: f32) -> f32 {
        -a
    }
    fn to_f32(self) -> f32 {
        self
    }
    /// `w − near ≥ 0` is `w ≥ near`, and the two guard planes of an axis,
    /// `4w − x ≥ 0` and `4w + x ≥ 0`, are `4w − |x| ≥ 0` (an IEEE
    /// difference of finite values is zero only for equal operands and has
    /// the right sign, and `4w` is exact); infinities and NaN give the same
    /// NaN or sign in both forms.
    #[inline]
    fn inside(v: &ClipVert<f32>, near: f32) -> bool {
        let g = GUARD as f32 * v.w;
        v.w - near >= 0.0 && g - v.x.abs() >= 0.0 && g - v.y.abs() >= 0.0
    }
}

impl<const F: u32> ClipNum for FxWide<F> {
    const ZERO: Self = FxWide::ZERO;
    fn sub(a: Self, b: Self) -> Self {
        a.saturating_sub(b)
    }
    fn guard(w: Self, c: Self, g: i32, neg: bool) -> Self {
        let gw = w.raw().saturating_mul(g as i64);
        FxWide::from_raw(if neg {
            gw.saturating_add(c.raw())
        } else {
            gw.saturating_sub(c.raw())
        })
    }
    fn lerp(a: Self, b: Self, da: Self, db: Self) -> Self {
        // i128: |b − a| < 2^64 and da < 2^63, so the product fits; the
        // quotient is at most |b − a| and is truncated toward zero, which
        // keeps the result between a and b.
        let (a, b) = (a.raw() as i128, b.raw() as i128);
        let (da, db) = (da.raw() as i128, db.raw() as i128);
        let den = da - db;
        if den <= 0 {
            return FxWide::from_raw(a as i64);
        }
        let v = a + (b - a) * da / den;
        FxWide::from_raw(v.clamp(i64::MIN as i128, i64::MAX as i128) as i64)
    }
    fn scale(w: Self, g: i32) -> Self {
        FxWide::from_raw(w.raw().saturating_mul(g as i64))
    }
    /// The five planes' saturating tests as comparisons, the same answer
    /// for every input (as the integer path's): `sat(w − near) ≥ 0` iff
    /// `w ≥ near`, and `sat(g − x) ≥ 0`, `sat(g + x) ≥ 0` hold together iff
    /// `g ≥ |x|` with `g = sat(4w)`, which needs `g ≥ 0`. Every vertex of
    /// the fixed path takes this test (a vertex cache's misses too); the
    /// planes' saturating 64-bit arithmetic cost a few dozen instructions.
    #[inline]
    fn inside(v: &ClipVert<Self>, near: Self) -> bool {
        let (x, y, w) = (v.x.raw(), v.y.raw(), v.w.raw());
        let g = w.saturating_mul(GUARD as i64);
        v.w >= near && g >= 0 && x.unsigned_abs() <= g as u64 && y.unsigned_abs() <= g as u64
    }
    fn neg(a: Self) -> Self {
        FxWide::from_raw(a.raw().saturating_neg())
    }
    fn to_f32(self) -> f32 {
        // 2^-F exactly (F < 127), built from its bits.
        self.raw() as f32 * f32::from_bits((127 - F.min(126)) << 23)
    }
}

/// The five clip planes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Plane {
    Near,
    Right,
    Left,
    Top,
    Bottom,
}

/// Clipping order: near plane first. Afterwards every vertex has
/// `w ≥ near_w > 0`, so the guard passes only interpolate between points
/// in front of the eye and never create vertices on the line where two
/// guard planes meet at the eye (`x = w = 0`), where classification would
/// be at the mercy of rounding.
const PLANES: [Plane; 5] = [
    Plane::Near,
    Plane::Right,
    Plane::Left,
    Plane::Top,
    Plane::Bottom,
];

impl Plane {
    /// Signed distance-like value, `≥ 0` inside.
    fn dist<S: ClipNum>(self, v: &ClipVert<S>, near: S) -> S {
        match self {
            Plane::Near => S::sub(v.w, near),
            Plane::Right => S::guard(v.w, v.x, GUARD, false),
            Plane::Left => S::guard(v.w, v.x, GUARD, true),
            Plane::Top => S::guard(v.w, v.y, GUARD, false),
            Plane::Bottom => S::guard(v.w, v.y, GUARD, true),
        }
    }

    /// Puts an interpolated vertex exactly on the plane, so that rounding
    /// can never leave it (slightly) outside — for the near plane that
    /// would mean a `w` below `near_w`, possibly zero.
    fn snap<S: ClipNum>(self, v: &mut ClipVert<S>, near: S) {
        match self {
            Plane::Near => v.w = near,
            Plane::Right => v.x = S::scale(v.w, GUARD),
            Plane::Left => v.x = S::neg(S::scale(v.w, GUARD)),
            Plane::Top => v.y = S::scale(v.w, GUARD),
            Plane::Bottom => v.y = S::neg(S::scale(v.w, GUARD)),
        }
    }
}

/// Clipping failed because the result needs more vertices than the buffers
/// hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClipError {
    /// The clipped polygon would exceed the buffer capacity.
    Capacity,
}

/// The result of [`clip_polygon`].
#[derive(Debug)]
pub struct Clipped<'a, S> {
    /// The clipped polygon (fewer than 3 vertices: nothing visible).
    pub verts: &'a [ClipVert<S>],
    /// False when the polygon was inside every plane and passed unchanged.
    pub clipped: bool,
}

/// Whether every one of the first `n` vertices of `a` is in front of the
/// near plane and inside the guard band, so that clipping would leave the
/// polygon as it is (the test [`clip_polygon`] starts with). A renderer
/// without the clipping stage drops the polygons that fail it.
#[inline]
pub fn all_inside<S: ClipNum>(a: &[ClipVert<S>], n: usize, near: S) -> bool {
    a[..n.min(a.len())].iter().all(|v| S::inside(v, near))
}

/// Clips the polygon `a[..n]` (clip space) against the near plane
/// `w ≥ near` and the guard band. `a` and `b` are scratch of equal length
/// (the capacity); the result is a slice of one of them. An empty slice (or
/// fewer than 3 vertices) means nothing is visible.
///
/// `near` must be positive (see module docs).
pub fn clip_polygon<'a, S: ClipNum>(
    a: &'a mut [ClipVert<S>],
    n: usize,
    b: &'a mut [ClipVert<S>],
    near: S,
) -> Result<Clipped<'a, S>, ClipError> {
    let (verts, clipped) = clip_inner(a, n, b, near)?;
    Ok(Clipped { verts, clipped })
}

fn clip_inner<'a, S: ClipNum>(
    a: &'a mut [ClipVert<S>],
    n: usize,
    b: &'a mut [ClipVert<S>],
    near: S,
) -> Result<(&'a [ClipVert<S>], bool), ClipError> {
    let n = n.min(a.len());
    // Fast accept (the common case: in front of the near plane and inside
    // the guard band): one short-circuiting pass, no outcode bookkeeping.
    if all_inside(a, n, near) {
        return Ok((&a[..n], false));
    }
    // Outcodes: trivially reject (all vertices outside one plane) or find
    // the planes that need a pass, without any interpolation yet.
    let mut any_out = 0u8;
    for v in &a[..n] {
        for (k, p) in PLANES.iter().enumerate() {
            if p.dist(v, near) < S::ZERO {
                any_out |= 1 << k;
            }
        }
    }
    if any_out == 0 {
        return Ok((&a[..n], false));
    }
    let mut src: &'a mut [ClipVert<S>] = a;
    let mut dst: &'a mut [ClipVert<S>] = b;
    let mut len = n;
    for (k, p) in PLANES.iter().enumerate() {
        // Points inside a half-space stay inside after interpolation with
        // other inside points (convexity; snapping covers rounding), so a
        // plane no input vertex crossed needs no pass.
        if any_out & (1 << k) == 0 {
            continue;
        }
        len = clip_one(&src[..len], dst, *p, near)?;
        core::mem::swap(&mut src, &mut dst);
        if len < 3 {
            return Ok((&src[..0], true));
        }
    }
    Ok((&src[..len], true))
}

/// One Sutherland–Hodgman pass; returns the output length.
fn clip_one<S: ClipNum>(
    input: &[ClipVert<S>],
    out: &mut [ClipVert<S>],
    plane: Plane,
    near: S,
) -> Result<usize, ClipError> {
    let mut len = 0usize;
    let mut push = |v: ClipVert<S>| -> Result<(), ClipError> {
        let slot = out.get_mut(len).ok_or(ClipError::Capacity)?;
        *slot = v;
        len += 1;
        Ok(())
    };
    let Some(&last) = input.last() else {
        return Ok(0);
    };
    let mut prev = last;
    let mut dprev = plane.dist(&prev, near);
    for &cur in input {
        let dcur = plane.dist(&cur, near);
        let prev_in = dprev >= S::ZERO;
        let cur_in = dcur >= S::ZERO;
        if prev_in != cur_in {
            // Always from the inside endpoint: see "Determinism" above.
            let (i, o, di, d_o) = if prev_in {
                (&prev, &cur, dprev, dcur)
            } else {
                (&cur, &prev, dcur, dprev)
            };
            let mut v = S::lerp_vert(i, o, di, d_o);
            plane.snap(&mut v, near);
            push(v)?;
        }
        if cur_in {
            push(cur)?;
        }
        prev = cur;
        dprev = dcur;
    }
    Ok(len)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cv(x: f32, y: f32, w: f32) -> ClipVert<f32> {
        ClipVert { x, y, w }
    }

    fn run(poly: &[ClipVert<f32>], near: f32) -> std::vec::Vec<ClipVert<f32>> {
        let mut a = [ClipVert::default(); 16];
        let mut b = [ClipVert::default(); 16];
        a[..poly.len()].copy_from_slice(poly);
        clip_polygon(&mut a, poly.len(), &mut b, near)
            .map(|s| s.verts.to_vec())
            .unwrap_or_default()
    }

    extern crate std;

    #[test]
    fn fixed_inside_equals_the_planes_saturating_tests() {
        let edges = [
            i64::MIN,
            i64::MIN + 1,
            i64::MIN / 4 - 1,
            i64::MIN / 4,
            -(1 << 48),
            -5,
            -4,
            -1,
            0,
            1,
            3,
            4,
            5,
            1 << 48,
            i64::MAX / 4,
            i64::MAX / 4 + 1,
            i64::MAX - 1,
            i64::MAX,
        ];
        let f = FxWide::<16>::from_raw;
        for &x in &edges {
            for &y in &edges {
                for &w in &edges {
                    for near in [-4, 0, 1, 5, i64::MAX] {
                        let v = ClipVert {
                            x: f(x),
                            y: f(y),
                            w: f(w),
                        };
                        let planes = PLANES.iter().all(|p| p.dist(&v, f(near)) >= FxWide::ZERO);
                        assert_eq!(ClipNum::inside(&v, f(near)), planes, "{x} {y} {w} {near}");
                    }
                }
            }
        }
    }

    #[test]
    fn inside_polygon_is_untouched() {
        let p = [cv(-1.0, -1.0, 2.0), cv(1.0, -1.0, 2.0), cv(0.0, 1.0, 2.0)];
        assert_eq!(run(&p, 0.1), p.to_vec());
    }

    #[test]
    fn polygon_behind_eye_gives_nothing() {
        let p = [
            cv(-1.0, -1.0, -2.0),
            cv(1.0, -1.0, -2.0),
            cv(0.0, 1.0, -0.5),
        ];
        assert!(run(&p, 0.1).is_empty());
        // Touching the near plane from behind with one vertex leaves only a
        // degenerate polygon on the plane (zero area: no pixel).
        let p = [cv(-1.0, -1.0, -2.0), cv(1.0, -1.0, -2.0), cv(0.0, 0.0, 0.1)];
        assert!(run(&p, 0.1).iter().all(|v| *v == cv(0.0, 0.0, 0.1)));
    }

    #[test]
    fn near_crossing_keeps_the_front_part_on_the_plane() {
        // Square in the x/w plane from w = -1 to w = 3; near at 1.
        let p = [
            cv(-1.0, 0.0, -1.0),
            cv(1.0, 0.0, -1.0),
            cv(1.0, 0.5, 3.0),
            cv(-1.0, 0.5, 3.0),
        ];
        let out = run(&p, 1.0);
        assert_eq!(out.len(), 4);
        assert!(out.iter().all(|v| v.w >= 1.0));
        let on_plane: std::vec::Vec<_> = out.iter().filter(|v| v.w == 1.0).collect();
        assert_eq!(on_plane.len(), 2);
        // y is linear in w along the sides: y = (w + 1)/8 → 0.25 at w = 1.
        assert!(on_plane.iter().all(|v| (v.y - 0.25).abs() < 1e-6));
    }

    #[test]
    fn guard_band_bounds_huge_coordinates() {
        let p = [
            cv(-1e30, -1e30, 1.0),
            cv(1e30, -1e30, 1.0),
            cv(0.0, 1e30, 1.0),
        ];
        let out = run(&p, 0.1);
        assert!(out.len() >= 3);
        for v in &out {
            assert!(v.x.abs() <= 4.0 * v.w && v.y.abs() <= 4.0 * v.w, "{v:?}");
        }
    }

    #[test]
    fn shared_edge_intersections_are_bit_identical() {
        // Two triangles sharing edge p-q, traversed in opposite directions:
        // once with p-q crossing the near plane, once the right guard plane.
        let r1 = cv(-1.0, 3.0, 2.0);
        let r2 = cv(2.0, -3.0, 1.3);
        for (p, q) in [
            (cv(0.3, 0.7, -0.77), cv(1.1, -0.2, 2.9)),
            (cv(0.3, 0.7, 0.5), cv(13.1, -0.2, 2.9)),
        ] {
            let t1 = run(&[p, q, r1], 0.37);
            let t2 = run(&[q, p, r2], 0.37);
            let new: std::vec::Vec<_> = t1.iter().filter(|v| ![p, q, r1].contains(v)).collect();
            assert!(!new.is_empty());
            // Every new vertex on the shared edge appears bit-identical in
            // the other triangle.
            let on_shared = new.iter().filter(|v| t2.contains(v)).count();
            assert_eq!(on_shared, 1, "{t1:?} {t2:?}");
        }
    }

    #[test]
    fn fixed_point_clip_matches_float() {
        type W = FxWide<16>;
        let f = |v: f32| W::try_from_f32(v).unwrap_or_default();
        let pf = [cv(-3.0, 0.0, -1.0), cv(9.0, 1.0, 2.0), cv(0.0, -2.0, 4.0)];
        let mut a = [ClipVert::<W>::default(); 16];
        let mut b = a;
        for (d, s) in a.iter_mut().zip(pf.iter()) {
            *d = ClipVert {
                x: f(s.x),
                y: f(s.y),
                w: f(s.w),
            };
        }
        let fixed = clip_polygon(&mut a, 3, &mut b, f(0.5)).map(|s| s.verts.to_vec());
        let float = run(&pf, 0.5);
        let fixed = fixed.unwrap_or_default();
        assert_eq!(fixed.len(), float.len());
        for (x, y) in fixed.iter().zip(float.iter()) {
            assert!((x.x.to_f32() - y.x).abs() < 1e-3, "{x:?} {y:?}");
            assert!((x.w.to_f32() - y.w).abs() < 1e-3);
            assert!(x.w >= f(0.5));
        }
    }

    #[test]
    fn capacity_overflow_is_an_error_not_a_panic() {
        // A comb: many teeth crossing the near plane needs more room.
        let mut poly = std::vec::Vec::new();
        for i in 0..8 {
            let x = i as f32;
            poly.push(cv(x, 0.0, 2.0));
            poly.push(cv(x + 0.5, 0.0, -1.0));
        }
        poly.push(cv(8.0, 0.0, 5.0));
        poly.push(cv(0.0, 0.0, 5.0));
        let mut a = [ClipVert::default(); 18];
        let mut b = [ClipVert::default(); 18];
        a[..poly.len()].copy_from_slice(&poly);
        assert_eq!(
            clip_polygon(&mut a, poly.len(), &mut b, 1.0).map(|s| s.verts.len()),
            Err(ClipError::Capacity)
        );
        let mut a = [ClipVert::default(); 40];
        let mut b = [ClipVert::default(); 40];
        a[..poly.len()].copy_from_slice(&poly);
        assert!(clip_polygon(&mut a, poly.len(), &mut b, 1.0).is_ok_and(|s| s.verts.len() > 18));
    }

    #[test]
    fn the_f32_inside_test_agrees_with_the_planes() {
        let near = 0.25f32;
        let vals = [
            0.0,
            -0.0,
            0.25,
            0.2499999,
            1.0,
            -1.0,
            4.0,
            -4.0,
            4.000001,
            -4.000001,
            1e-30,
            3.9999998,
            1e30,
            -1e30,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        for &x in &vals {
            for &y in &vals {
                for &w in &[
                    0.25f32,
                    0.2499999,
                    1.0,
                    0.0,
                    -1.0,
                    1e30,
                    f32::NAN,
                    f32::INFINITY,
                ] {
                    let v = ClipVert { x, y, w };
                    let planes = PLANES.iter().all(|p| p.dist(&v, near) >= 0.0);
                    assert_eq!(<f32 as ClipNum>::inside(&v, near), planes, "{v:?}");
                }
            }
        }
    }

    /// The integer path's direct test equals the five planes' on extreme
    /// values (saturation included).
    #[test]
    fn the_i32_inside_test_agrees_with_the_planes() {
        let vals = [
            i32::MIN,
            i32::MIN + 1,
            -(1 << 29) - 1,
            -(1 << 29),
            -5,
            -4,
            -1,
            0,
            1,
            3,
            4,
            5,
            1 << 29,
            (1 << 29) + 1,
            i32::MAX - 1,
            i32::MAX,
        ];
        for &x in &vals {
            for &y in &vals {
                for &w in &vals {
                    for near in [1, 4, i32::MAX] {
                        let v = ClipVert { x, y, w };
                        let planes = PLANES.iter().all(|p| p.dist(&v, near) >= 0);
                        assert_eq!(<i32 as ClipNum>::inside(&v, near), planes, "{v:?} {near}");
                    }
                }
            }
        }
    }
}
