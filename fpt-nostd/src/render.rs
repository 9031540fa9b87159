//! Drawing a whole tree: the glue between the walk ([`crate::order`]) and
//! the rasterizer ([`crate::raster`]).
//!
//! Per frame, [`Frame::new`] turns the caller's camera (a model → clip
//! matrix, in the model's own coordinates) into what the two halves need:
//!
//! * **the walk's view**, derived from the matrix alone: the centre of
//!   projection is the homogeneous point `C` with `(M·C).x = (M·C).y =
//!   (M·C).w = 0` (the null vector of rows x, y, w). `C.w ≠ 0` is a
//!   perspective camera with the eye at `C.xyz / C.w`; `C.w = 0` a parallel
//!   one looking along `±C.xyz`, the sign chosen so that `ndc.z` grows along
//!   it (smaller `ndc.z` is nearer). The eye is computed in `f64` and made
//!   relative to the tree's origin before rounding to `f32`, so a model far
//!   from the coordinate origin keeps its precision. A matrix whose x, y
//!   and w rows are dependent has no centre of projection (it collapses the
//!   picture); it still gets some view and renders without error.
//! * **the renderer's matrix**, composed once in `f64`:
//!   `k · M · T(origin) · S(s)`. `T(origin)` lets the vertices, stored
//!   relative to the origin, go straight through the transform. `S(s)` and
//!   `k` are powers of two chosen for the fixed-point path (16.16 vertices
//!   and matrix, range ±2^15, step 2^-16): the vertices are multiplied by
//!   the exact `1/s`, which brings the bounding radius to `[2^13, 2^14]`,
//!   and `k` brings the largest matrix entry to `[2^13, 2^14)`. Both are
//!   as large as the range allows (half of it, for headroom), which makes
//!   both rounding errors — of a vertex, `2^-17` against a vertex of up to
//!   `2^14`, and of an entry, `2^-17` against the largest entry — about
//!   `2^-31` relative, for a model of any size and any distance from the
//!   coordinate origin. Products stay below `2^60` (the transform's `i64`
//!   sums have room for four), and the `f32` path is not affected at all
//!   (powers of two scale exactly). Neither changes a projected point: `k`
//!   scales `x, y, w` and the near threshold together, `S` is undone by
//!   `1/s`.
//!
//! Then [`render_tree`] walks the classes back to front and draws each
//! polygon with its plane normal for the Lambert term. An open (two-sided)
//! model shows both sides of a face, so a face seen from behind is lit
//! with its normal flipped toward the viewer. Ids written to an
//! [`crate::raster::IdBuffer`] are the polygon's source face or its id in
//! the file ([`FaceIds`]).
//!
//! Band rendering ([`TreeRenderer::render_banded_in`]) walks the tree once
//! a frame into a display list in the caller's working memory and replays
//! it into each band of one band buffer (`render::cached`; with less memory
//! it walks more often, without any once per band); the result is the
//! full-frame picture exactly (see [`crate::raster::band`]).
//!
//! Nothing here allocates or panics, whatever the camera: degenerate,
//! non-finite or extreme matrices render something or nothing, never fail,
//! except that a renderer whose walk stack `N` or vertex capacity `V` is
//! smaller than the tree's header says it needs is refused before anything
//! is drawn ([`CapacityError`], [`check_capacities`]). With the capacities
//! checked, no polygon is skipped for want of room: a polygon is skipped
//! ([`RenderStats::skipped`]) only when a camera makes a vertex non-finite.

use crate::effects::{AllEffects, Compiled, Effects};
use crate::format::{EDGE_HIDDEN, EDGE_SOFT};
use crate::order::{LocalView, OrderError, View};
use crate::raster::{
    Camera, Face, Framebuffer, FramebufferError, Light, Mat4, PixelFormat, Precision, RenderStats,
    Renderer, Scratch, SpanSink,
};
use crate::reader::{Plane, PolygonAt, Tree};

pub use cached::{memory_words, memory_words_for};
pub use double::{BandBuffers, BandTransfer};
pub use probe::{NoProbe, Phase, Probe};

/// Which number a polygon writes into id buffers (as `number + 1`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FaceIds {
    /// The input face it came from ([`crate::reader::PolygonRef::source`]):
    /// pieces of a split face share it.
    #[default]
    Source,
    /// Its id in the tree file.
    Polygon,
}

/// A capacity of the renderer, a const generic parameter, that is smaller
/// than the tree needs ([`crate::reader::Tree::capacities`]): the drawing
/// functions check them before they draw, so that no polygon is ever
/// skipped for want of room and no walk is cut short. `fpt info TREE`
/// prints the values to write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CapacityError {
    /// The walk's stack `N` is smaller than the tree's depth.
    WalkDepth {
        /// What `N` must be at least.
        need: u32,
        /// The `N` given.
        have: usize,
    },
    /// The vertex capacity `V` (of [`TreeRenderer`] or [`Scratch`]) is
    /// smaller than the tree's polygons need after clipping.
    Vertices {
        /// What `V` must be at least.
        need: u32,
        /// The `V` given.
        have: usize,
    },
}

impl core::fmt::Display for CapacityError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            CapacityError::WalkDepth { need, have } => write!(
                f,
                "walk stack N = {have} is smaller than the tree's depth: N must be at least {need}"
            ),
            CapacityError::Vertices { need, have } => write!(
                f,
                "vertex capacity V = {have} is too small for the tree's polygons: \
                 V must be at least {need} (TreeRenderer<P, {need}>)"
            ),
        }
    }
}

/// Checks that a walk stack of `N` levels and a vertex capacity of `V`
/// hold what `tree` needs ([`crate::reader::Tree::capacities`]). Every
/// drawing function of this module calls it first.
///
/// ```
/// use fpt_nostd::reader::Tree;
/// use fpt_nostd::render::{check_capacities, CapacityError};
///
/// let tree = Tree::from_bytes(include_bytes!("../../firmware/trees/vise.fpt")).unwrap();
/// let need = tree.capacities();
/// assert!(matches!(
///     check_capacities::<64, 8>(&tree),
///     Err(CapacityError::Vertices { have: 8, .. })
/// ));
/// assert_eq!(check_capacities::<64, 64>(&tree), Ok(()));
/// assert!(need.walk_depth <= 64 && need.vertices <= 64);
/// ```
pub fn check_capacities<const N: usize, const V: usize>(
    tree: &Tree<'_>,
) -> Result<(), CapacityError> {
    let c = tree.capacities();
    if c.walk_depth as usize > N {
        return Err(CapacityError::WalkDepth {
            need: c.walk_depth,
            have: N,
        });
    }
    if c.vertices as usize > V {
        return Err(CapacityError::Vertices {
            need: c.vertices,
            have: V,
        });
    }
    Ok(())
}

/// Why a banded frame with a fallible display
/// ([`TreeRenderer::try_render_banded_in`]) stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BandError<D> {
    /// The renderer refused the frame (before any band was sent).
    Render(RenderError),
    /// The display driver's error for a band: no later band was drawn.
    Display(D),
}

impl<D: core::fmt::Debug> core::fmt::Display for BandError<D> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BandError::Render(e) => write!(f, "{e}"),
            BandError::Display(e) => write!(f, "display: {e:?}"),
        }
    }
}

/// Why a frame could not be drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RenderError {
    /// The walk refused the tree (deeper than its stack; after
    /// [`check_capacities`] it cannot).
    Order(OrderError),
    /// The band buffer is too small or the band has a bad size.
    Band(FramebufferError),
    /// A capacity of the renderer is smaller than the tree needs.
    Capacity(CapacityError),
}

impl From<CapacityError> for RenderError {
    fn from(e: CapacityError) -> Self {
        RenderError::Capacity(e)
    }
}

impl From<OrderError> for RenderError {
    fn from(e: OrderError) -> Self {
        RenderError::Order(e)
    }
}

impl core::fmt::Display for RenderError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RenderError::Order(e) => write!(f, "{e}"),
            RenderError::Band(e) => write!(f, "band buffer: {e}"),
            RenderError::Capacity(e) => write!(f, "{e}"),
        }
    }
}

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
fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn xyz(r: [f64; 4]) -> [f64; 3] {
    [r[0], r[1], r[2]]
}

/// `row · [p, 1]`.
#[inline(never)]
fn eval_row(r: [f64; 4], p: [f64; 3]) -> f64 {
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

/// Draws `tree` through `camera` into `sink`: derives the [`Frame`], sets
/// it as `renderer`'s camera, zeroes its counters, walks the classes back
/// to front (a stack of `N` frames) and draws every polygon; returns the
/// counters. The renderer's light, shading mode and fill rule are used as
/// set, its effects as [`Renderer::begin_tree`] decides (the tree's own
/// unless overridden). Fails only when `N` or `V` is smaller than the tree
/// needs ([`check_capacities`]); then nothing is drawn.
pub fn render_tree<P: Precision, const N: usize, const V: usize, E: Compiled, K: SpanSink>(
    tree: &Tree<'_>,
    camera: &Camera,
    renderer: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    ids: FaceIds,
    sink: &mut K,
) -> Result<RenderStats, RenderError> {
    let frame = Frame::new(tree, camera);
    draw_frame::<P, N, V, E, K>(tree, &frame, renderer, scratch, ids, sink)
}

/// [`render_tree`] for an already derived [`Frame`] (saves deriving it
/// again per band).
///
/// Effects ([`crate::effects`]) handled here: `culling` chooses the walk
/// ([`crate::order::Order::with_culling`]); `two-sided` lights a face seen from behind
/// with its normal flipped toward the viewer (without it, such a face is
/// lit by its own normal, usually only by the ambient term). The others
/// are the renderer's.
pub fn draw_frame<P: Precision, const N: usize, const V: usize, E: Compiled, K: SpanSink>(
    tree: &Tree<'_>,
    frame: &Frame,
    renderer: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    ids: FaceIds,
    sink: &mut K,
) -> Result<RenderStats, RenderError> {
    check_capacities::<N, V>(tree)?;
    Ok(cached::draw_direct::<P, E, K, NoProbe, N, V>(
        tree,
        frame,
        renderer,
        scratch,
        ids,
        &mut [],
        sink,
        &NoProbe,
    )?)
}

/// What the walk of a frame needs from the effects (see
/// [`walk_effects`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct WalkFx {
    /// Cull back faces (choose the culling walk).
    pub(crate) cull: bool,
    /// Light back sides as if they faced the viewer.
    pub(crate) two_sided: bool,
    /// Lighting is on: the face needs its normal.
    pub(crate) lit: bool,
    /// Outlines are on: the face needs its outline mask.
    pub(crate) outline: bool,
    /// Gouraud shading is on (with lighting, and the tree has corner
    /// normals): each polygon gets its colour plane
    /// ([`crate::raster::gouraud`]).
    pub(crate) smooth: bool,
}

/// Settles the renderer's effects for `tree` ([`Renderer::begin_tree`])
/// and returns what the walk needs of them. Shared by [`draw_frame`] and
/// the loops of `render::cached`. (The walk itself is built by each
/// caller: handing a walk back by value would copy its whole stack every
/// frame.)
#[inline]
pub(crate) fn walk_effects<P: Precision, E: Compiled>(
    tree: &Tree<'_>,
    renderer: &mut Renderer<P, E>,
) -> WalkFx {
    let fx = renderer.begin_tree(Effects::from_bits(tree.effects()));
    WalkFx {
        cull: fx.contains(Effects::CULLING),
        two_sided: fx.contains(Effects::TWO_SIDED),
        lit: fx.contains(Effects::LIGHTING),
        outline: fx.contains(Effects::OUTLINE),
        // Without corner normals every corner has the flat colour: nothing
        // to interpolate.
        smooth: fx.contains(Effects::SMOOTH)
            && fx.contains(Effects::LIGHTING)
            && tree.has_normals(),
    }
}

/// The face the rasterizer draws for polygon `p` of the walk: its colour,
/// `id`, its outline mask, and the normal that lighting uses: with
/// `two_sided`, a face seen from behind is lit as if it faced the viewer.
/// Without lighting the plane is not read at all (the normal is zero), so
/// that lighting switched off costs what lighting compiled out does.
/// Shared by [`draw_frame`] and the loops of `render::cached`, so all draw
/// alike.
#[inline(always)]
pub(crate) fn face_of(
    tree: &Tree<'_>,
    p: &PolygonAt<'_, '_>,
    view: &LocalView,
    fx: WalkFx,
    id: u32,
) -> Face {
    let normal = if fx.lit {
        let plane = p.plane();
        if fx.two_sided && !view.is_backward(&plane) {
            plane.normal.map(|c| -c)
        } else {
            plane.normal
        }
    } else {
        [0.0; 3]
    };
    Face {
        normal,
        color: p.color(),
        id,
        hidden_edges: if fx.outline {
            outline_mask(tree, p.id(), *view)
        } else {
            0
        },
    }
}

/// `sin²` of the angle within which a soft edge's neighbour counts as
/// edge-on (14.5°, see [`outline_mask`]).
const EDGE_ON_SIN2: f32 = 0.0625;

/// The edges of `p` that the `outline` effect leaves out in this view
/// (bit `i`: edge `i`; see [`crate::format`]). With the file's edge
/// section: the hidden edges, and the soft ones that are no silhouette:
/// the neighbour across the edge faces the viewer the same way as `p`,
/// and is not within 14.5° of edge-on. (An edge-on neighbour is the face
/// that draws the silhouette; it may be thinner than a pixel, and `p`,
/// painted after it, would cover that line, so `p` draws the edge too.)
/// Without the section, the polygon's 8-bit mask.
///
/// Out of line, and given the polygon by id and the view by value: the
/// walk's loop (where `face_of` is inlined) keeps its `PolygonRef` in
/// registers only while no call takes its address; passing it by
/// reference had it written to the stack for every polygon, outlines on or
/// off (3.6 % of a `bench_city` frame on the Cortex-M4).
#[inline(never)]
fn outline_mask(tree: &Tree<'_>, id: u32, view: LocalView) -> u64 {
    let Some(p) = tree.polygon(id) else {
        return 0;
    };
    let view = &view;
    if !p.has_edges() {
        return u64::from(p.hidden_edges());
    }
    let facing = view.is_backward(&p.plane());
    let mut mask = 0u64;
    for i in 0..p.vertex_count().min(64) {
        let hide = match p.edge(i) {
            Some((EDGE_HIDDEN, _)) => true,
            Some((EDGE_SOFT, n)) => {
                // The neighbour's plane through the edge's first vertex:
                // the same facing test as the walk's.
                let normal = n.map(f32::from);
                let v = p.vertex(i);
                let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                let plane = Plane {
                    normal,
                    d: -dot(normal, v),
                };
                // The neighbour's facing, and the ray it is seen along.
                let ray = match view {
                    LocalView::Parallel(dir) => dir.map(|c| -c),
                    LocalView::Eye(e) => [e[0] - v[0], e[1] - v[1], e[2] - v[2]],
                };
                let s = dot(normal, ray);
                let edge_on = s * s <= EDGE_ON_SIN2 * dot(normal, normal) * dot(ray, ray);
                view.is_backward(&plane) == facing && !edge_on
            }
            _ => false,
        };
        mask |= u64::from(hide) << i;
    }
    mask
}

/// The band buffer of [`TreeRenderer::render_banded`]: storage for `rows`
/// full-width rows, and the colour every band starts from.
#[derive(Debug)]
pub struct BandBuffer<'b, F: PixelFormat> {
    /// At least `rows × words_per_row(width)` words.
    pub buf: &'b mut [F::Word],
    /// Rows per band (at least 1).
    pub rows: u32,
    /// Background colour.
    pub background: F::Color,
}

/// A renderer with its scratch buffers and id choice: everything needed to
/// draw trees, in one value (about `V × 106` bytes plus a few dozen with
/// the fixed path; place it in a `static` on a small stack).
#[derive(Debug)]
pub struct TreeRenderer<P: Precision, const V: usize, E: Compiled = AllEffects> {
    /// The polygon renderer (set its light, shading mode and effects here).
    pub renderer: Renderer<P, E>,
    /// Per-polygon buffers for up to `V` vertices.
    pub scratch: Scratch<P, V>,
    /// What id buffers receive.
    pub ids: FaceIds,
}

impl<P: Precision, const V: usize, E: Compiled> TreeRenderer<P, V, E> {
    /// A renderer for `width × height` frames; `None` when a side is 0 or
    /// too large (see [`Renderer::new`]).
    ///
    /// A `const fn`, so that the renderer (a few KiB of scratch buffers)
    /// can live in a `static` and is never built on the stack nor copied
    /// through it: with `static_cell`'s `ConstStaticCell` it is taken once
    /// as a `&'static mut`, without `unsafe` (a size that does not fit
    /// fails the build):
    ///
    /// ```
    /// use fpt_nostd::raster::FloatLibm;
    /// use fpt_nostd::render::TreeRenderer;
    /// use static_cell::ConstStaticCell;
    ///
    /// type Renderer = TreeRenderer<FloatLibm<4>, 48>;
    /// static RENDERER: ConstStaticCell<Renderer> =
    ///     ConstStaticCell::new(Renderer::new(240, 240).expect("a 240×240 frame"));
    ///
    /// let r: &'static mut Renderer = RENDERER.take(); // once, at start-up
    /// assert_eq!(r.renderer.viewport().width(), 240);
    /// ```
    pub const fn new(width: u32, height: u32) -> Option<Self> {
        let Some(renderer) = Renderer::sized(width, height) else {
            return None;
        };
        Some(TreeRenderer {
            renderer,
            scratch: Scratch::new(),
            ids: FaceIds::Source,
        })
    }

    /// [`draw_frame`] into `sink`, walking with a stack of `N` frames.
    pub fn render<const N: usize, K: SpanSink>(
        &mut self,
        tree: &Tree<'_>,
        frame: &Frame,
        sink: &mut K,
    ) -> Result<RenderStats, RenderError> {
        draw_frame::<P, N, V, E, K>(
            tree,
            frame,
            &mut self.renderer,
            &mut self.scratch,
            self.ids,
            sink,
        )
    }

    /// Draws the frame band by band through `band`'s buffer: for each band
    /// (top to bottom) fills it with the background, draws the tree into
    /// it, and hands it to `emit` with its first frame row. The bands put
    /// together are exactly the full-frame picture. Without working memory
    /// the tree is walked and every polygon transformed once per band;
    /// [`TreeRenderer::render_banded_in`] does it once a frame. The
    /// counters count each polygon once.
    pub fn render_banded<const N: usize, F: PixelFormat>(
        &mut self,
        tree: &Tree<'_>,
        frame: &Frame,
        band: BandBuffer<'_, F>,
        emit: impl FnMut(i32, &Framebuffer<'_, F>),
    ) -> Result<RenderStats, RenderError> {
        self.render_banded_in::<N, F>(tree, frame, band, &mut [], emit)
    }

    /// [`TreeRenderer::render`] with a vertex cache in `memory` (one word
    /// per vertex of the tree, [`Tree::vertex_count`]; less caches the
    /// vertices with the lowest indices): each vertex shared by several
    /// polygons is transformed once. The same pixels as without memory.
    pub fn render_cached<const N: usize, K: SpanSink>(
        &mut self,
        tree: &Tree<'_>,
        frame: &Frame,
        memory: &mut [u32],
        sink: &mut K,
    ) -> Result<RenderStats, RenderError> {
        self.render_probed::<N, K, NoProbe>(tree, frame, memory, sink, &NoProbe)
    }

    /// [`TreeRenderer::render_banded`] with working memory: one walk and
    /// at most one transform of each vertex a frame, shared by all the
    /// bands, when `memory` holds [`memory_words`] words; less memory
    /// gives the same picture with more walks (see the module docs of
    /// `render::cached` in the source, summarised in the README). The
    /// counters count each polygon once.
    pub fn render_banded_in<const N: usize, F: PixelFormat>(
        &mut self,
        tree: &Tree<'_>,
        frame: &Frame,
        band: BandBuffer<'_, F>,
        memory: &mut [u32],
        emit: impl FnMut(i32, &Framebuffer<'_, F>),
    ) -> Result<RenderStats, RenderError> {
        let mut emit = emit;
        self.try_render_banded_in::<N, F, core::convert::Infallible>(
            tree,
            frame,
            band,
            memory,
            |y, fb| {
                emit(y, fb);
                Ok(())
            },
        )
        .map_err(|e| match e {
            BandError::Render(e) => e,
            BandError::Display(never) => match never {},
        })
    }

    /// [`TreeRenderer::render_banded_in`] for a display that can fail:
    /// `emit` returns the display driver's `Result`, and the first error
    /// ends the frame (no further band is drawn) and comes back to the
    /// caller as [`BandError::Display`].
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb565;
    /// use fpt_nostd::raster::{FloatLibm, Libm, Orbit, Rgb565BeFormat};
    /// use fpt_nostd::reader::Tree;
    /// use fpt_nostd::render::{BandBuffer, BandError, Frame, TreeRenderer};
    ///
    /// let tree = Tree::from_bytes(include_bytes!("../../firmware/trees/vise.fpt")).unwrap();
    /// let mut r = TreeRenderer::<FloatLibm<4>, 64>::new(64, 64).unwrap();
    /// let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), 0.5, 0.4, 1.0, 1.0);
    /// let frame = Frame::relative(&tree, &orbit.camera::<Libm>(1.0));
    /// let mut buf = [0u16; 64 * 8];
    /// let band = BandBuffer::<Rgb565BeFormat> { buf: &mut buf, rows: 8, background: Rgb565::new(0, 0, 0) };
    /// let mut sent = 0;
    /// // A display whose SPI bus fails at the third band.
    /// let out = r.try_render_banded_in::<64, _, &str>(&tree, &frame, band, &mut [], |_y, fb| {
    ///     sent += fb.panel_bytes().len();
    ///     if sent > 2 * 64 * 8 * 2 { Err("spi") } else { Ok(()) }
    /// });
    /// assert_eq!(out, Err(BandError::Display("spi")));
    /// assert_eq!(sent, 3 * 64 * 8 * 2); // nothing after the failed band
    /// ```
    pub fn try_render_banded_in<const N: usize, F: PixelFormat, D>(
        &mut self,
        tree: &Tree<'_>,
        frame: &Frame,
        band: BandBuffer<'_, F>,
        memory: &mut [u32],
        mut emit: impl FnMut(i32, &Framebuffer<'_, F>) -> Result<(), D>,
    ) -> Result<RenderStats, BandError<D>> {
        let mut failed = None;
        let stats = self
            .render_banded_probed::<N, F, NoProbe>(tree, frame, band, memory, &NoProbe, |y, fb| {
                match emit(y, fb) {
                    Ok(()) => true,
                    Err(e) => {
                        failed = Some(e);
                        false
                    }
                }
            })
            .map_err(BandError::Render)?;
        match failed {
            Some(e) => Err(BandError::Display(e)),
            None => Ok(stats),
        }
    }
}

pub(crate) mod cached;
pub mod double;
pub mod probe;
mod slivers;
#[cfg(test)]
mod tests;
