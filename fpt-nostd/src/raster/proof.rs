//! Once a frame, a proof that the float transform's per-vertex checks
//! cannot fire: the model's vertex bound, seen through the frame's matrix,
//! lies inside the near plane and inside the viewport, with margins that
//! cover the `f32` rounding of the transform actually performed.
//!
//! The contract: when [`prove_float`] returns `true` for a matrix `m`, a
//! near threshold `near` and a [`VertexBound`] that holds for every vertex
//! `p` handed to the transform (`|p_i| ≤ abs[i]`, `|p|² ≤ norm2`), then for
//! every such `p` the values `X`, `Y`, `W` that
//! [`super::transform::FloatPath`] computes (rows 0, 1 and 3 of `m`, in
//! `f32`, in any association or with fused multiply-adds) satisfy
//!
//! * `W ≥ near` and `|X|, |Y|, |W| ≤ 10^30`: the transform's finiteness
//!   test and the near plane pass;
//! * `|X|, |Y| ≤ (1 − 2^-8)·W`: the guard planes (`|X| ≤ 4W`) pass, and
//!   with a reciprocal of relative error below `2^-8` (libm's is exact to
//!   half an ulp; micromath's is tested below `2^-12`, `tests` here) the
//!   projected `x/w`, `y/w` lie in `[−1, 1]`, so the NDC clamp of
//!   `screen_f32` does not change them and the screen coordinates it
//!   produces are at least 0.5, where truncation is the floor.
//!
//! So the unchecked projection ([`super::transform::VertexPath::project_proven`])
//! gives the very same screen point as the checked pipeline (transform,
//! clip test, projection); the proof only removes tests, never changes a
//! result.
//!
//! # The arithmetic
//!
//! For a plane `q·p + q₃ ≥ 0` (a combination of the matrix rows) its
//! smallest value over the ball `|p|² ≤ norm2` is `q₃ − |q|·√norm2`. The
//! true value must exceed the transform's rounding error: a four-term
//! `f32` dot product errs by at most `3u/(1 − 3u)·S` (`u = 2^-24`,
//! `S = Σ|m_i|·abs[i] + |m₃|`), and the vertex's own rounding (the frame's
//! scale) by `u` of each term: below `2^-21·S`. The test below demands a
//! margin of `2^-16·T`, `T` the sum of every magnitude involved (both rows'
//! `S` and `(|a|₁ + |w|₁)·√norm2`), which is at least 8 times that error
//! plus the rounding of the test's own few dozen `f32` operations (each at
//! most `u` relative to `T`, fewer than 64 of them: `< 2^-18·T`). The
//! square root is avoided: `A ≥ |q|·R` is tested as `A ≥ 0` and
//! `A² ≥ |q|²·R²·(1 + 2^-14)`, the factor covering the squares' rounding.
//! Every comparison is written so that a NaN anywhere fails it.

use super::camera::Mat4;

/// Bounds on a model's vertices as the transform receives them: the
/// largest magnitude of each coordinate and the largest squared length
/// (an upper bound, rounding included). Computed once when a tree is
/// read ([`crate::reader::Tree::vertex_bound`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexBound {
    /// Largest `|p_i|` per axis.
    pub abs: [f32; 3],
    /// Largest `p₀² + p₁² + p₂²`, rounded up.
    pub norm2: f32,
}

/// Relative slack of one `f32` rounding step, generously: the bounds
/// below are inflated by it wherever a value was rounded.
const SLACK: f32 = 1.0 / 65536.0;

impl VertexBound {
    /// The empty bound (no vertex): every proof holds for it.
    pub const EMPTY: VertexBound = VertexBound {
        abs: [0.0; 3],
        norm2: 0.0,
    };

    /// The bound grown to hold `p` as well (the squared length is computed
    /// in `f32`, so it is rounded up by `SLACK`, far above its error of
    /// three roundings).
    pub fn with(self, p: [f32; 3]) -> VertexBound {
        let a = p.map(f32::abs);
        let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (1.0 + SLACK);
        VertexBound {
            abs: [0, 1, 2].map(|i| max_nan(self.abs[i], a[i])),
            norm2: max_nan(self.norm2, n),
        }
    }

    /// The bound of the vertices multiplied by `s` (the frame's vertex
    /// scale; rounded up, so that it also holds for the rounded products).
    pub fn scaled(&self, s: f32) -> VertexBound {
        let s = s.abs() * (1.0 + SLACK);
        VertexBound {
            abs: self.abs.map(|a| a * s),
            norm2: self.norm2 * s * s,
        }
    }
}

/// `max(a, b)`, NaN if either is NaN (so that a non-finite vertex makes
/// every proof fail rather than being ignored).
fn max_nan(a: f32, b: f32) -> f32 {
    if a.is_nan() || b.is_nan() {
        f32::NAN
    } else if a >= b {
        a
    } else {
        b
    }
}

/// `1 − 2^-8`: how far inside the viewport's planes every vertex must be
/// (above any reciprocal's relative error the float path uses).
pub const INSET: f32 = 1.0 - 1.0 / 256.0;

/// Largest rounding bound `S` of a row accepted: keeps `|X|, |Y|, |W|`
/// far below the transform's limit of `10^36`.
const MAGNITUDE: f32 = 1e30;

/// `S = Σ|m_i|·abs[i] + |m₃|` for row `m`.
fn magnitude(m: &[f32; 4], b: &VertexBound) -> f32 {
    m[0].abs() * b.abs[0] + m[1].abs() * b.abs[1] + m[2].abs() * b.abs[2] + m[3].abs()
}

/// `|m₀| + |m₁| + |m₂|`.
fn norm1(m: &[f32; 4]) -> f32 {
    m[0].abs() + m[1].abs() + m[2].abs()
}

/// Whether `q·p + q₃ ≥ 0` holds with the margin `2^-16·t` for every `p`
/// of the ball `|p|² ≤ norm2` (see the module docs).
fn plane_holds(q: [f32; 4], norm2: f32, t: f32) -> bool {
    let a = q[3] - t * SLACK;
    let qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
    a >= 0.0 && a * a >= qq * norm2 * (1.0 + 4.0 * SLACK)
}

/// The frame proof (module docs): `true` when no vertex within `bound`
/// can fail a check of the float transform and projection under matrix
/// `m` and near threshold `near`.
pub fn prove_float(m: &Mat4, near: f32, bound: &VertexBound) -> bool {
    let b = bound;
    let (x, y, w) = (&m.0[0], &m.0[1], &m.0[3]);
    let (sx, sy, sw) = (magnitude(x, b), magnitude(y, b), magnitude(w, b));
    // Also false for NaN: the comparisons are written to fail on it.
    if !(sx <= MAGNITUDE && sy <= MAGNITUDE && sw <= MAGNITUDE && near > 0.0 && near <= 1e30) {
        return false;
    }
    // An upper bound of the ball's radius √norm2 for the margins only,
    // where a factor of √3 does not matter: |p|₂ ≤ |p|₁ ≤ Σ abs[i]
    // (avoids a square root).
    let r = b.abs[0] + b.abs[1] + b.abs[2];
    // The near plane: w − near ≥ 0.
    let t = sw + near + norm1(w) * r;
    if !plane_holds([w[0], w[1], w[2], w[3] - near], b.norm2, t) {
        return false;
    }
    // The four side planes: INSET·w ∓ a ≥ 0 for a = x, y.
    for (a, sa) in [(x, sx), (y, sy)] {
        let t = sa + sw + (norm1(a) + norm1(w)) * r;
        for sign in [1.0f32, -1.0] {
            let q = [0, 1, 2, 3].map(|i| INSET * w[i] - sign * a[i]);
            if !plane_holds(q, b.norm2, t) {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::vec;
    use std::vec::Vec;

    use super::*;
    use crate::raster::camera::{Camera, Orbit};
    use crate::raster::clip::{ClipNum, ClipVert};
    use crate::raster::precision::{Config, Libm, MathFns, Micromath};
    use crate::raster::tests::Rng;
    use crate::raster::transform::{FloatPath, ScreenPt, VertexPath, Viewport, MAX_DIM};

    /// The unit ball's bound (box and squared length).
    const BALL: VertexBound = VertexBound {
        abs: [1.0; 3],
        norm2: 1.0,
    };

    fn orbit<M: MathFns>(yaw: f32, pitch: f32, distance: f32, fov: f32) -> Camera {
        Orbit::new([0.0; 3], yaw, pitch, distance, fov).camera::<M>(1.0)
    }

    fn near<M: MathFns>(c: &Camera) -> f32 {
        FloatPath::<M>::near(&c.matrix, c.near_w)
    }

    /// The checked chain: transform, clip test, projection.
    fn checked<M: MathFns>(c: &Camera, v: [f32; 3], vp: &Viewport) -> Option<ScreenPt> {
        let n = near::<M>(c);
        FloatPath::<M>::transform(&c.matrix, v)
            .filter(|p| <f32 as ClipNum>::inside(p, n))
            .and_then(|p| FloatPath::<M>::project_clipped(&p, vp))
    }

    /// A point of the unit ball: inside, on its surface or on an axis.
    fn ball_point(rng: &mut Rng, k: usize) -> [f32; 3] {
        let mut p = [0.0f32; 3].map(|_| rng.float(-1.0, 1.0));
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        match k % 3 {
            // On the sphere (rounded inward so that |p|² ≤ 1 holds).
            0 if n > 0.0 => p = p.map(|c| c / n * (1.0 - 1e-6)),
            1 => p = [0, 1, 2].map(|i| if i == k % 9 / 3 { p[0].signum() } else { 0.0 }),
            _ if n > 1.0 => p = p.map(|c| c / n * 0.999),
            _ => {}
        }
        p
    }

    /// The standard orbit (issue 13: 2.1 radii, 60°, pitch 25°, a yaw
    /// sweep) is proven, and every point of the ball projects the same
    /// without the checks, for both reciprocals and extreme viewports.
    #[test]
    fn standard_orbit_is_proven_and_projects_the_same() {
        fn run<M: MathFns>(rng: &mut Rng) {
            let vps = [(240, 240, 4), (1, 1, 0), (MAX_DIM, MAX_DIM, 8), (320, 7, 2)];
            for i in 0..100 {
                let yaw = core::f32::consts::TAU * i as f32 / 100.0;
                let cam = orbit::<M>(yaw, 25f32.to_radians(), 2.1, 60f32.to_radians());
                let n = near::<M>(&cam);
                assert!(prove_float(&cam.matrix, n, &BALL), "frame {i}");
                for k in 0..300 {
                    let v = ball_point(rng, k);
                    let &(w, h, sub) = &vps[k % vps.len()];
                    let vp = Viewport::new(w, h, sub).unwrap();
                    let want = checked::<M>(&cam, v, &vp);
                    assert!(want.is_some(), "{v:?}");
                    let got = FloatPath::<M>::project_proven(&cam.matrix, n, v, &vp);
                    assert_eq!(got, want, "{v:?} frame {i}");
                }
            }
        }
        let mut rng = Rng(7);
        run::<Libm>(&mut rng);
        run::<Micromath>(&mut rng);
    }

    /// Views where a check could fire are not proven: the eye near or
    /// inside the model, the model past the frustum's side, a vertex
    /// bound far beyond the model, a non-finite bound.
    #[test]
    fn risky_views_are_not_proven() {
        let fov = 60f32.to_radians();
        let cam = |d: f32, f: f32| orbit::<Libm>(0.3, 0.4, d, f);
        let fails = [
            (cam(1.5, fov), BALL),
            (cam(0.5, fov), BALL),
            (cam(2.1, 50f32.to_radians()), BALL),
            (cam(2.1, fov), BALL.scaled(1.2)),
            (cam(2.1, fov), BALL.scaled(1e20)),
            (cam(2.1, fov), BALL.with([f32::NAN, 0.0, 0.0])),
            (cam(2.1, fov), BALL.with([f32::INFINITY, 0.0, 0.0])),
        ];
        for (c, b) in fails {
            assert!(!prove_float(&c.matrix, near::<Libm>(&c), &b), "{b:?}");
        }
        // The ball's silhouette at 2.1 radii leaves the 60° frustum 5 % of
        // a radius to spare (sin 30° · 2.1 = 1.05); at 2.05 radii 2.5 %
        // still do, at 1.95 the ball crosses the frustum's sides.
        let c = cam(2.05, fov);
        assert!(prove_float(&c.matrix, near::<Libm>(&c), &BALL));
        let c = cam(1.95, fov);
        assert!(!prove_float(&c.matrix, near::<Libm>(&c), &BALL));
        assert!(prove_float(&c.matrix, 1.0, &VertexBound::EMPTY));
    }

    /// Random cameras, bounds and offsets: wherever the proof holds, every
    /// point within the bound passes every check and projects the same
    /// both ways; both outcomes occur.
    #[test]
    fn wherever_proven_the_points_are_the_same() {
        let mut rng = Rng(23);
        let vp = Viewport::new(240, 180, 4).unwrap();
        let (mut proven, mut not) = (0, 0);
        for _ in 0..3000 {
            let d = rng.float(1.6, 4.0);
            let fov = rng.float(0.5, 1.6);
            let cam = orbit::<Libm>(rng.float(-3.0, 3.0), rng.float(-1.5, 1.5), d, fov);
            let scale = [1e-3f32, 1.0, 1e3][rng.range(0, 2) as usize];
            let m = Mat4(cam.matrix.0.map(|r| [r[0], r[1], r[2], r[3] * scale]));
            let b = BALL.scaled(scale);
            let cam = Camera {
                matrix: m,
                near_w: cam.near_w * scale,
            };
            let n = near::<Libm>(&cam);
            if !prove_float(&cam.matrix, n, &b) {
                not += 1;
                continue;
            }
            proven += 1;
            for k in 0..40 {
                let v = ball_point(&mut rng, k).map(|c| c * scale);
                let want = checked::<Libm>(&cam, v, &vp);
                assert!(want.is_some(), "{v:?}");
                let got = FloatPath::<Libm>::project_proven(&cam.matrix, n, v, &vp);
                assert_eq!(got, want, "{v:?}");
            }
        }
        assert!(proven > 300 && not > 300, "{proven} {not}");
    }

    /// The reciprocals the float path uses err by far less than the
    /// inset (`2^-8`) the proof leaves for them, over every magnitude a
    /// clip `w` can take (the near threshold's `10^-30` to the bound's
    /// `10^30`).
    #[test]
    fn reciprocals_err_below_the_inset() {
        let mut worst = 0.0f64;
        let mut x = 1e-30f32;
        while x < 1e30 {
            for k in 0..64 {
                let w = x * (1.0 + k as f32 / 64.0);
                for r in [Libm::recip(w), Micromath::recip(w)] {
                    let e = (f64::from(r) * f64::from(w) - 1.0).abs();
                    worst = worst.max(e);
                }
            }
            x *= 1.7;
        }
        assert!(worst < 1.0 / 4096.0, "{worst}");
    }

    #[test]
    fn bounds_hold_their_points_and_scale_up() {
        let pts = [[1.0f32, -2.0, 0.5], [-3.0, 0.25, 0.0], [0.0, 0.0, -1.5]];
        let b = pts.iter().fold(VertexBound::EMPTY, |b, &p| b.with(p));
        assert_eq!(b.abs, [3.0, 2.0, 1.5]);
        for p in pts {
            assert!(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= b.norm2);
        }
        let s = b.scaled(-0.5);
        assert!(s.abs[0] >= 1.5 && s.abs[0] < 1.5001 && s.norm2 >= b.norm2 * 0.25);
        assert!(b.with([0.0, f32::NAN, 0.0]).norm2.is_nan());
    }

    /// A vertex path that proves nothing: the float path with every
    /// per-vertex check, for comparing whole frames.
    #[derive(Clone, Copy, Debug, Default)]
    struct Checked;

    impl VertexPath for Checked {
        type Scalar = f32;
        type Matrix = Mat4;
        const UNSET: Mat4 = FloatPath::<Libm>::UNSET;
        const NEAR_MIN: f32 = FloatPath::<Libm>::NEAR_MIN;
        fn prepare(m: &Mat4) -> Mat4 {
            FloatPath::<Libm>::prepare(m)
        }
        fn transform(m: &Mat4, v: [f32; 3]) -> Option<ClipVert<f32>> {
            FloatPath::<Libm>::transform(m, v)
        }
        fn transform_q(m: &Mat4, v: [i32; 3], frac: u32) -> Option<ClipVert<f32>> {
            FloatPath::<Libm>::transform_q(m, v, frac)
        }
        fn near(m: &Mat4, near_w: f32) -> f32 {
            FloatPath::<Libm>::near(m, near_w)
        }
        fn project(v: &ClipVert<f32>, vp: &Viewport) -> Option<ScreenPt> {
            FloatPath::<Libm>::project(v, vp)
        }
        fn project_clipped(v: &ClipVert<f32>, vp: &Viewport) -> Option<ScreenPt> {
            FloatPath::<Libm>::project_clipped(v, vp)
        }
    }

    /// Whole frames of a tree, with and without the frame proof, with and
    /// without a vertex cache: the same ids, on views that are proven and
    /// views that are not (near, inside, edge of the frustum).
    #[test]
    fn proven_frames_equal_checked_frames() {
        use crate::raster::{FloatLibm, IdBuffer};
        use crate::render::{Frame, TreeRenderer};
        use crate::test_util::two_floors;

        let bytes = two_floors().bytes();
        let Ok(t) = crate::reader::Tree::from_bytes(&bytes) else {
            panic!("tree")
        };
        fn ids<P: crate::raster::Precision>(
            t: &crate::reader::Tree<'_>,
            frame: &Frame,
            memory: &mut [u32],
        ) -> Vec<u32> {
            let mut buf = vec![0u32; 48 * 40];
            let Ok(mut sink) = IdBuffer::new(&mut buf, 48, 40) else {
                panic!("sink")
            };
            let Some(mut r) = TreeRenderer::<P, 16>::new(48, 40) else {
                panic!("renderer")
            };
            if let Err(e) = r.render_cached::<8, _>(t, frame, memory, &mut sink) {
                panic!("{e:?}");
            }
            buf
        }
        /// The frame in 7-row bands with `memory` (one walk, the cache
        /// filled before it in a proven frame), as RGB888 bytes.
        fn banded<P: crate::raster::Precision>(
            t: &crate::reader::Tree<'_>,
            frame: &Frame,
            memory: &mut [u32],
        ) -> Vec<u8> {
            use crate::raster::framebuffer::Rgb888Format;
            use crate::render::BandBuffer;
            use embedded_graphics::pixelcolor::Rgb888;
            let (w, h, rows) = (48usize, 40usize, 7u32);
            let mut out = vec![0xFFu8; 3 * w * h];
            let mut buf = vec![0u8; 3 * w * rows as usize];
            let band = BandBuffer::<Rgb888Format> {
                buf: &mut buf,
                rows,
                background: Rgb888::new(1, 2, 3),
            };
            let Some(mut r) = TreeRenderer::<P, 16>::new(w as u32, h as u32) else {
                panic!("renderer")
            };
            let res = r.render_banded_in::<8, _>(t, frame, band, memory, |y0, fb| {
                let start = 3 * y0 as usize * w;
                let d = fb.data();
                out[start..start + d.len()].copy_from_slice(d);
            });
            assert!(res.is_ok(), "{res:?}");
            out
        }
        let (mut proven, mut not, mut drawn) = (0, 0, 0);
        let r = t.bounding_radius();
        for i in 0..60 {
            let d = r * [0.3f32, 0.9, 1.6, 2.1, 3.0, 8.0][i % 6];
            let fov = [0.6f32, 1.047, 1.4][i % 3];
            let o = Orbit::new(
                [0.0; 3],
                i as f32 * 0.41,
                (i % 7) as f32 * 0.3 - 0.9,
                d,
                fov,
            );
            let frame = Frame::new(&t, &o.camera::<Libm>(1.2));
            let n = FloatPath::<Libm>::near(&frame.camera.matrix, frame.camera.near_w);
            let b = t.vertex_bound().scaled(frame.vertex_scale);
            if prove_float(&frame.camera.matrix, n, &b) {
                proven += 1;
            } else {
                not += 1;
            }
            // 2 and 5 words: a tagged cache of 1 and 2 entries for the 8
            // vertices (evictions in every frame; no fill ahead).
            for words in [0usize, 2, 5, 64] {
                let mut m1 = vec![0u32; words];
                let mut m2 = vec![0u32; words];
                let a = ids::<FloatLibm<4>>(&t, &frame, &mut m1);
                let c = ids::<Config<Checked, Libm, 4>>(&t, &frame, &mut m2);
                assert_eq!(a, c, "view {i}, {words} words");
                drawn += usize::from(a.iter().any(|&x| x != 0));
            }
            let mut m1 = vec![0u32; 4096];
            let mut m2 = vec![0u32; 4096];
            let a = banded::<FloatLibm<4>>(&t, &frame, &mut m1);
            let c = banded::<Config<Checked, Libm, 4>>(&t, &frame, &mut m2);
            assert!(a == c, "view {i}, bands");
        }
        assert!(proven >= 10 && not >= 10, "{proven} {not}");
        assert!(drawn >= 120, "{drawn} of 240 frames draw something");
    }
}
