//! What the renderer reports: the face a polygon is shaded as
//! ([`Face`]), what became of each polygon ([`Outcome`], [`SkipReason`]:
//! nothing panics, a polygon the scratch cannot hold is skipped and
//! counted) and the frame's counters ([`RenderStats`]).

use crate::raster::Normal;

/// What a polygon looks like to the shader and the id buffer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Face {
    /// Plane normal (any length; model space, pointing to the visible
    /// side): `f32`, or a compact plane entry's integers as stored.
    pub normal: Normal,
    /// Base colour.
    pub color: [u8; 3],
    /// Polygon id (id buffers store `id + 1`).
    pub id: u32,
    /// Bit `i` set: edge `i` (vertex `i` to `i + 1`) is not drawn by the
    /// `outline` effect (inside the source face, or a smooth edge that is
    /// not a silhouette in this view; see [`crate::format`]); edges from 64
    /// on are always outlines. Only the `outline` effect reads it.
    pub hidden_edges: u64,
}

/// Why a polygon was not drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkipReason {
    /// More input vertices than the scratch capacity.
    TooManyVertices,
    /// Clipping produced more vertices than the scratch capacity.
    ClipCapacity,
    /// A vertex was not finite (or out of range for the float path).
    NonFinite,
}

/// The result of drawing one polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Scan-converted; `spans` spans were sent to the sink.
    Drawn {
        /// Spans emitted.
        spans: usize,
    },
    /// Degenerate or entirely clipped away (behind the eye, off-band).
    Invisible,
    /// Not drawn, for the given reason.
    Skipped(SkipReason),
}

/// Counters since the last [`Renderer::reset_stats`](super::Renderer::reset_stats).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RenderStats {
    /// Polygons scan-converted.
    pub drawn: u32,
    /// Polygons degenerate or clipped away.
    pub invisible: u32,
    /// Polygons skipped (any [`SkipReason`]).
    pub skipped: u32,
    /// Polygons that needed clipping (crossed the near plane or the guard
    /// band).
    pub clipped: u32,
    /// Polygons the culling walk of a closed tree leaves out that were
    /// drawn all the same, first, because the sub-pixel snap turned them
    /// toward the viewer (see [`crate::render`]'s slivers); not counted in
    /// `drawn`, which counts what the walk emits.
    pub slivers: u32,
    /// Spans emitted.
    pub spans: u64,
    /// Tree walks the frame took: 1 for a full frame and for bands whose
    /// polygons all fit the working memory, more with less memory (see
    /// [`crate::render::memory_words`]); 0 when no tree was drawn.
    pub walks: u32,
    /// Words of the caller's working memory the frame used (vertex cache
    /// slots plus the display list's peak, with its band index and at most
    /// 64 kept band states: more are kept when the memory allows, as speed,
    /// not need).
    pub memory_used: u32,
}

impl RenderStats {
    /// Every counter 0 (the [`Default`], as a constant).
    pub const ZERO: RenderStats = RenderStats {
        drawn: 0,
        invisible: 0,
        skipped: 0,
        clipped: 0,
        slivers: 0,
        spans: 0,
        walks: 0,
        memory_used: 0,
    };
}

impl core::ops::AddAssign for RenderStats {
    /// Adds every counter (e.g. the bands of one frame).
    fn add_assign(&mut self, o: RenderStats) {
        self.drawn += o.drawn;
        self.invisible += o.invisible;
        self.skipped += o.skipped;
        self.clipped += o.clipped;
        self.slivers += o.slivers;
        self.spans += o.spans;
        self.walks += o.walks;
        self.memory_used = self.memory_used.max(o.memory_used);
    }
}
