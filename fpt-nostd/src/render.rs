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
//! One file per part: `frame` (the camera matrix into the walk's view and
//! the renderer's matrix), `draw` (one pass over the tree into a sink),
//! `tree_renderer` ([`TreeRenderer`], the one-call API), `error`, `cached`
//! (the walk loop every draw goes through, the display list's replay per
//! band), `slivers`, `double` (double-buffered bands) and `probe` (the
//! measuring hooks).
//!
//! Nothing here allocates or panics, whatever the camera: degenerate,
//! non-finite or extreme matrices render something or nothing, never fail,
//! except that a renderer whose walk stack `N` or vertex capacity `V` is
//! smaller than the tree's header says it needs is refused before anything
//! is drawn ([`CapacityError`], [`check_capacities`]). With the capacities
//! checked, no polygon is skipped for want of room: a polygon is skipped
//! ([`RenderStats::skipped`](crate::raster::RenderStats::skipped)) only when a camera makes a vertex non-finite.

mod draw;
mod error;
mod frame;
mod tree_renderer;
pub use draw::{draw_frame, render_tree};
pub(crate) use draw::{face_of, walk_effects, WalkFx};
pub use error::{check_capacities, BandError, CapacityError, RenderError};
pub use frame::{near_w_for, rows_f64, Frame, MatrixView};
pub use tree_renderer::{BandBuffer, TreeRenderer};

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

pub(crate) mod cached;
pub mod double;
pub mod probe;
mod slivers;
#[cfg(test)]
mod tests;
