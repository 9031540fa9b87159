//! A frame's set-up: the caller's camera matrix turned into the walk's view
//! ([`MatrixView`], the centre of projection) and the renderer's matrix
//! ([`Frame`]), composed in `f64` as the parent module's docs describe.

use crate::order::View;
use crate::raster::{Camera, Light, Mat4};
use crate::reader::Tree;

/// Everything one frame needs, derived from a tree and a camera (see the
/// module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The renderer's camera: maps origin-relative vertices multiplied by
    /// [`Frame::vertex_scale`] to clip space.
    pub camera: Camera,
    /// The exact power of two every origin-relative vertex is multiplied by.
    pub vertex_scale: f32,
    /// The walk's view.
    pub view: View,
}

/// The rows of `m` in `f64` (the form [`MatrixView::of`], [`near_w_for`]
/// and [`Frame::from_f64`] take).
pub fn rows_f64(m: &Mat4) -> [[f64; 4]; 4] {
    m.0.map(|r| r.map(f64::from))
}

// The `f64` helpers below run a few dozen times per frame (camera set-up),
// in software floating point on a Cortex-M: they stay out of line, one copy
// each, because every inlined copy of a soft-float expression costs code
// (about a kilobyte of `.text` for these) and saves nothing measurable.
#[inline(never)]
fn det3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// The null vector of rows x, y and w: `C_i = (−1)^i · det(minor without
/// column i)`, which is orthogonal to each of the three rows (expanding a
/// determinant with a repeated row).
fn centre_of_projection(r: &[[f64; 4]; 4]) -> [f64; 4] {
    let pick = |row: [f64; 4], skip: usize| {
        let mut o = [0.0; 3];
        let mut k = 0;
        for (i, v) in row.iter().enumerate() {
            if i != skip {
                if let Some(slot) = o.get_mut(k) {
                    *slot = *v;
                }
                k += 1;
            }
        }
        o
    };
    let minor = |skip: usize| det3(pick(r[0], skip), pick(r[1], skip), pick(r[3], skip));
    [minor(0), -minor(1), minor(2), -minor(3)]
}

/// `2^e` as `f64`, `e` clamped to keep it normal.
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e.clamp(-1000, 1000) + 1023) as u64) << 52)
}

/// `floor(log2(x))` for finite `x > 0`.
fn log2_floor(x: f64) -> Option<i32> {
    if !(x.is_finite() && x > 0.0) {
        return None;
    }
    let e = ((x.to_bits() >> 52) & 0x7ff) as i32;
    // Subnormals are far below anything that matters here.
    Some(if e == 0 { -1023 } else { e - 1023 })
}

#[inline(never)]
pub(super) fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn xyz(r: [f64; 4]) -> [f64; 3] {
    [r[0], r[1], r[2]]
}

/// `row · [p, 1]`.
#[inline(never)]
pub(super) fn eval_row(r: [f64; 4], p: [f64; 3]) -> f64 {
    dot3(xyz(r), p) + r[3]
}

/// `v / |v|`, or `None` for a zero or non-finite vector.
#[inline(never)]
fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let l = libm::sqrt(dot3(v, v));
    (l.is_finite() && l > 0.0).then(|| v.map(|c| c / l))
}

/// A view derived from a model → clip matrix (see the module docs), in
/// `f64`, in the matrix's input coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MatrixView {
    /// Parallel projection looking along `dir` (largest component ±1).
    Parallel {
        /// Viewing direction, from the viewer into the scene.
        dir: [f64; 3],
    },
    /// Perspective projection from `eye`.
    Perspective {
        /// The eye point.
        eye: [f64; 3],
    },
    /// The x, y and w rows are dependent: there is no centre of projection.
    Degenerate,
}

impl MatrixView {
    /// The view of the row-major matrix `r`. `reference` is a point of the
    /// model (its centre): the matrix is read relative to it, and it
    /// decides the sign of a parallel direction when `w` is negative there.
    ///
    /// Any model scale and offset: the matrix is first rewritten for
    /// coordinates relative to `reference` in units of a power of two `u`
    /// that balances its x, y, z columns against its translation column
    /// (`u` about the model's size for a camera that frames it), the view
    /// is found there and mapped back exactly (`eye = reference + u·eye'`).
    /// Taken as it is, a matrix that frames a model of size 1e10 has x, y,
    /// z columns 1e-10 of its translation column, its centre of
    /// projection shrinks by 1e-20 against its rows, and a good camera was
    /// called degenerate. With `reference` at the origin the power-of-two
    /// scaling changes no bit of the result.
    ///
    /// ```
    /// use fpt_nostd::render::MatrixView;
    /// // Looking down −z from (0, 0, 3e20) at a model of size 1e20 at the
    /// // origin: x, y, z columns 1e-20 of the translation.
    /// let s = 1e-20;
    /// let r = [
    ///     [s, 0.0, 0.0, 0.0],
    ///     [0.0, s, 0.0, 0.0],
    ///     [0.0, 0.0, -s, 1.0],
    ///     [0.0, 0.0, -s, 3.0],
    /// ];
    /// let MatrixView::Perspective { eye } = MatrixView::of(&r, [0.0; 3]) else {
    ///     panic!("not a perspective view");
    /// };
    /// assert!((eye[2] / 3e20 - 1.0).abs() < 1e-12);
    /// ```
    pub fn of(r: &[[f64; 4]; 4], reference: [f64; 3]) -> MatrixView {
        match Self::relative(r, reference) {
            MatrixView::Perspective { eye } => MatrixView::Perspective {
                eye: [0, 1, 2].map(|i| reference[i] + eye[i]),
            },
            v => v,
        }
    }

    /// [`MatrixView::of`] with the eye relative to `reference` (no
    /// precision lost to a large `reference`).
    fn relative(r: &[[f64; 4]; 4], reference: [f64; 3]) -> MatrixView {
        // Relative to `reference`, x, y, z columns times `u`.
        let t = r.map(|row| eval_row(row, reference));
        let big_xyz = r
            .iter()
            .flat_map(|row| xyz(*row))
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let big_t = t.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let u = match (log2_floor(big_t), log2_floor(big_xyz)) {
            (Some(et), Some(ex)) => pow2(et - ex),
            _ => 1.0,
        };
        let a = [0, 1, 2, 3].map(|i| {
            let row = r[i];
            [row[0] * u, row[1] * u, row[2] * u, t[i]]
        });
        match Self::balanced(&a) {
            MatrixView::Perspective { eye } => MatrixView::Perspective {
                eye: eye.map(|v| u * v),
            },
            v => v,
        }
    }

    /// [`MatrixView::of`] for a matrix already relative to the reference
    /// point and balanced.
    fn balanced(r: &[[f64; 4]; 4]) -> MatrixView {
        let c = centre_of_projection(r);
        let big = c[0].abs().max(c[1].abs()).max(c[2].abs());
        // |C| is at most the product of the three rows' lengths; far below
        // it, the rows are dependent up to rounding.
        let len = |row: [f64; 4]| libm::sqrt(row.iter().map(|v| v * v).sum::<f64>());
        let scale = len(r[0]) * len(r[1]) * len(r[3]);
        let size = big.max(c[3].abs());
        if !(size.is_finite() && scale.is_finite()) || size <= 1e-12 * scale {
            return MatrixView::Degenerate;
        }
        // Same threshold as the host reference renderer, so that both call
        // the same matrices parallel.
        if c[3].abs() > 1e-12 * (c[0].abs() + c[1].abs() + c[2].abs()) {
            let eye = [c[0] / c[3], c[1] / c[3], c[2] / c[3]];
            if eye.iter().all(|v| v.is_finite()) {
                return MatrixView::Perspective { eye };
            }
        }
        if big == 0.0 {
            return MatrixView::Degenerate;
        }
        let mut dir = [c[0] / big, c[1] / big, c[2] / big];
        // Along `dir` only clip z changes; ndc.z = z / w must grow.
        let dz = dot3(xyz(r[2]), dir);
        // `w` at the reference point.
        let w = r[3][3];
        if dz * w < 0.0 {
            dir = dir.map(|v| -v);
        }
        MatrixView::Parallel { dir }
    }
}

/// The near threshold on `w` that matches the near plane `z = −w` of a
/// conventional projection matrix (row-major rows `r`, model coordinates),
/// so that the renderer drops exactly what a z-clipping renderer would drop
/// at the near plane:
/// * the plane `z + w = 0` is a plane `w = near` when row z + row w is
///   `α·(row w) + β·[0, 0, 0, 1]` (every perspective and parallel matrix
///   built the usual way); then `near = −β/α` when that is positive;
/// * a parallel matrix (`w` constant) gets half that constant (nothing is
///   near-clipped: the renderer does not clip at a parallel near plane);
/// * otherwise a small fraction of the largest `w` over the tree's
///   bounding sphere.
///
/// Always positive and finite.
pub fn near_w_for(r: &[[f64; 4]; 4], tree: &Tree<'_>) -> f32 {
    const TINY: f32 = 1e-30;
    let rw = r[3];
    let s = [
        r[2][0] + rw[0],
        r[2][1] + rw[1],
        r[2][2] + rw[2],
        r[2][3] + rw[3],
    ];
    let ww = dot3(xyz(rw), xyz(rw));
    let ok = |v: f64| v.is_finite() && (v as f32) > TINY && (v as f32).is_finite();
    if ww == 0.0 {
        let half = 0.5 * rw[3];
        return if ok(half) { half as f32 } else { TINY };
    }
    let alpha = dot3(xyz(s), xyz(rw)) / ww;
    let resid = [
        s[0] - alpha * rw[0],
        s[1] - alpha * rw[1],
        s[2] - alpha * rw[2],
    ];
    if alpha > 0.0 && dot3(resid, resid) <= 1e-12 * dot3(xyz(s), xyz(s)) {
        let near = -(s[3] - alpha * rw[3]) / alpha;
        if ok(near) {
            return near as f32;
        }
    }
    let wmax = eval_row(rw, tree.origin()) + f64::from(tree.bounding_radius()) * libm::sqrt(ww);
    let near = 1e-5 * wmax;
    if ok(near) {
        near as f32
    } else {
        TINY
    }
}

impl Frame {
    /// The frame of `tree` seen through `camera`, whose matrix takes model
    /// coordinates.
    pub fn new(tree: &Tree<'_>, camera: &Camera) -> Frame {
        Frame::build(
            tree,
            &rows_f64(&camera.matrix),
            f64::from(camera.near_w),
            false,
        )
    }

    /// The frame of `tree` seen through `camera`, whose matrix takes
    /// coordinates relative to the tree's origin (e.g. an [`crate::raster::Orbit`]
    /// around `[0, 0, 0]`, which is the bounding-sphere centre): no large
    /// translation ever rounds in `f32`.
    pub fn relative(tree: &Tree<'_>, camera: &Camera) -> Frame {
        Frame::build(
            tree,
            &rows_f64(&camera.matrix),
            f64::from(camera.near_w),
            true,
        )
    }

    /// Like [`Frame::new`] for a row-major `f64` matrix (model
    /// coordinates), so that a far-off model loses nothing to an `f32`
    /// matrix.
    pub fn from_f64(tree: &Tree<'_>, rows: &[[f64; 4]; 4], near_w: f64) -> Frame {
        Frame::build(tree, rows, near_w, false)
    }

    fn build(tree: &Tree<'_>, r: &[[f64; 4]; 4], near_w: f64, relative: bool) -> Frame {
        let o = if relative { [0.0; 3] } else { tree.origin() };
        let view = match MatrixView::relative(r, o) {
            MatrixView::Perspective { eye } => View::PerspectiveRelative {
                eye: eye.map(|v| v as f32),
            },
            MatrixView::Parallel { dir } => View::Parallel {
                dir: dir.map(|v| v as f32),
            },
            // Any view will do: the picture collapses to a line or a point.
            MatrixView::Degenerate => View::Parallel {
                dir: [0.0, 0.0, -1.0],
            },
        };
        // S(s): s = 2^e with radius / s in [2^13, 2^14] (module docs),
        // for every finite `f32` radius: `e` only needs clamping where
        // `2^−e` would stop being a normal `f32` (a radius below 2^−112).
        let e = log2_floor(f64::from(tree.bounding_radius()))
            .map_or(0, |e| (e + 1 - 14).clamp(-126, 126));
        let s = pow2(e);
        let a = r.map(|row| [row[0] * s, row[1] * s, row[2] * s, eval_row(row, o)]);
        let big = a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        // k: the largest entry in [2^13, 2^14).
        let k = log2_floor(big).map_or(1.0, |eb| pow2(13 - eb));
        let matrix = Mat4(a.map(|row| row.map(|v| (v * k) as f32)));
        let near = near_w * k;
        let near_w = if near.is_finite() && near > 0.0 {
            near as f32
        } else {
            near_w as f32
        };
        Frame {
            camera: Camera { matrix, near_w },
            vertex_scale: pow2(-e) as f32,
            view,
        }
    }

    /// The depth range of `tree`'s bounding sphere in the renderer's clip
    /// `w` (nearest, farthest): the range to give a
    /// [`crate::raster::DepthCue`]. Equal ends for a parallel camera.
    pub fn depth_range(&self, tree: &Tree<'_>) -> (f32, f32) {
        let m = &self.camera.matrix.0;
        let row = m[3];
        let len = libm::sqrtf(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]);
        let r = tree.bounding_radius() * self.vertex_scale * len;
        (row[3] - r, row[3] + r)
    }

    /// The project's light for this frame: from [`Frame::key_light`],
    /// with the weights [`Light::AMBIENT`] and [`Light::DIFFUSE`]. Set it
    /// every frame (`renderer.set_light(frame.light())`): the key light
    /// follows the camera.
    pub fn light(&self) -> Light {
        Light::new(self.key_light(), Light::AMBIENT, Light::DIFFUSE)
    }

    /// A light direction for [`crate::raster::Light::new`]: toward the
    /// viewer, raised a little toward the top of the screen and moved to
    /// its left, so that faces turned to the viewer differ in brightness
    /// (a pure headlight shades every face of a box seen straight on
    /// alike). `[0, 0, 1]` for a degenerate camera.
    pub fn key_light(&self) -> [f32; 3] {
        let r = rows_f64(&self.camera.matrix);
        let toward = match self.view {
            View::Parallel { dir } => dir.map(|v| -f64::from(v)),
            View::Perspective { eye } | View::PerspectiveRelative { eye } => eye.map(f64::from),
        };
        let (Some(t), Some(up), Some(right)) = (unit(toward), unit(xyz(r[1])), unit(xyz(r[0])))
        else {
            return [0.0, 0.0, 1.0];
        };
        let mix = |a: f64, b: f64, c: f64| (a + 0.6 * b - 0.4 * c) as f32;
        [
            mix(t[0], up[0], right[0]),
            mix(t[1], up[1], right[1]),
            mix(t[2], up[2], right[2]),
        ]
    }
}
