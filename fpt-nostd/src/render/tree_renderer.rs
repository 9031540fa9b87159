//! [`TreeRenderer`]: a renderer with its scratch buffers, the one-call way
//! to draw a tree into a framebuffer, id buffer or bands.

use super::{draw_frame, BandError, FaceIds, Frame, NoProbe, RenderError};
use crate::effects::{AllEffects, Compiled};
use crate::raster::{
    Framebuffer, PixelFormat, Precision, RenderStats, Renderer, Scratch, SpanSink,
};
use crate::reader::Tree;

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
    /// bands, when `memory` holds [`memory_words`](super::memory_words) words; less memory
    /// gives the same picture with more walks (see the module docs of
    /// `render::cached` in the source, summarised in docs/small-ram.md). The
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
    /// let tree = Tree::from_bytes(include_bytes!("../../../firmware/trees/vise.fpt")).unwrap();
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
