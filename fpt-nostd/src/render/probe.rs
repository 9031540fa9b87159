//! Measuring hooks in the draw loops: where a frame's time goes.
//!
//! The draw loops of [`crate::render`] take a [`Probe`]: hooks at the
//! boundaries between the phases of a frame ([`Phase`]: tree walk,
//! transform, fill). Every hook has an empty default body and the probe is
//! a generic parameter, so with [`NoProbe`] (what the product API passes)
//! they compile to nothing. The project's measuring harness (the
//! `fpt-frames` crate, shared by the firmware and `fpt frames`) passes
//! probes that read a cycle counter, through
//! [`TreeRenderer::render_probed`] and
//! [`TreeRenderer::render_banded_probed`].

use super::{cached, check_capacities, BandBuffer, Frame, RenderError, TreeRenderer};
use crate::effects::Compiled;
use crate::raster::{Framebuffer, PixelFormat, Precision, RenderStats, SpanSink};
use crate::reader::{PolygonRef, Tree};

/// The phases of a frame's cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Postprocessing: the back-to-front tree walk and fetching each
    /// polygon's plane and colour.
    Post = 0,
    /// Camera setup, vertex decode and transform, clipping, projection and
    /// shading.
    Xform = 1,
    /// Clearing the buffer, edge setup and scan conversion, pixel writes.
    Fill = 2,
}

impl Phase {
    /// Every phase, in index order.
    pub const ALL: [Phase; 3] = [Phase::Post, Phase::Xform, Phase::Fill];
}

/// Hooks at the phase boundaries of a frame (see the module docs). All do
/// nothing by default; `&self` so that a sink wrapper can call them too
/// (a measuring probe keeps its state in `Cell`s).
///
/// ```
/// use core::cell::Cell;
/// use fpt_nostd::render::{Phase, Probe};
/// /// Counts the polygons a frame hands to the renderer.
/// #[derive(Default)]
/// struct Count(Cell<u32>);
/// impl Probe for Count {
///     fn polygon(&self, _p: &fpt_nostd::reader::PolygonRef<'_>) {
///         self.0.set(self.0.get() + 1);
///     }
/// }
/// let c = Count::default();
/// c.enter(Phase::Fill); // the other hooks keep their empty defaults
/// assert_eq!(c.0.get(), 0);
/// ```
pub trait Probe {
    /// The frame's work starts or resumes, in `phase`.
    #[inline(always)]
    fn start(&self, _phase: Phase) {}
    /// From now on the time belongs to `phase`. Called a few times per
    /// drawn polygon: keep it cheap.
    #[inline(always)]
    fn enter(&self, _phase: Phase) {}
    /// The frame's work stops until the next [`Probe::start`] (what
    /// follows, e.g. sending or checksumming a band, is not the frame's
    /// cost).
    #[inline(always)]
    fn stop(&self) {}
    /// The walk hands polygon `p` to the renderer (for counting what a
    /// frame is made of; timing probes leave it empty).
    #[inline(always)]
    fn polygon(&self, _p: &PolygonRef<'_>) {}
}

/// The probe that measures nothing (and costs nothing).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProbe;

impl Probe for NoProbe {}

impl<P: Precision, const V: usize, E: Compiled> TreeRenderer<P, V, E> {
    /// [`TreeRenderer::render_cached`] with `probe`'s hooks at the
    /// boundaries of the phases of the frame ([`Probe`]: walk, transform,
    /// fill; the measuring harness's cycle counters). The caller starts
    /// the probe before and stops it after; with [`NoProbe`] this is
    /// `render_cached`.
    pub fn render_probed<const N: usize, K: SpanSink, Pr: Probe>(
        &mut self,
        tree: &Tree<'_>,
        frame: &Frame,
        memory: &mut [u32],
        sink: &mut K,
        probe: &Pr,
    ) -> Result<RenderStats, RenderError> {
        check_capacities::<N, V>(tree)?;
        Ok(cached::draw_direct::<P, E, K, Pr, N, V, true>(
            tree,
            frame,
            &mut self.renderer,
            &mut self.scratch,
            self.ids,
            memory,
            sink,
            probe,
        )?)
    }

    /// [`TreeRenderer::render_banded_in`] with `probe`'s hooks (see
    /// [`TreeRenderer::render_probed`]; the probe is stopped while `emit`
    /// runs and started again after it, and left stopped on an error).
    /// `emit` returns `false` to end the frame there.
    pub fn render_banded_probed<const N: usize, F: PixelFormat, Pr: Probe>(
        &mut self,
        tree: &Tree<'_>,
        frame: &Frame,
        band: BandBuffer<'_, F>,
        memory: &mut [u32],
        probe: &Pr,
        emit: impl FnMut(i32, &Framebuffer<'_, F>) -> bool,
    ) -> Result<RenderStats, RenderError> {
        check_capacities::<N, V>(tree)?;
        cached::draw_bands::<P, E, F, Pr, N, V>(
            tree,
            frame,
            &mut self.renderer,
            &mut self.scratch,
            self.ids,
            memory,
            band,
            probe,
            emit,
        )
    }
}
