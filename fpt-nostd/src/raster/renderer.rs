//! The per-frame renderer: transform → clip → project → shade → fill, one
//! polygon at a time, so that integrating a tree walk is a loop.
//!
//! [`Renderer<P>`] holds the frame state (matrix in `P`'s format, near
//! threshold, viewport, light, shading mode, fill rule) and counters;
//! [`Scratch<P, N>`] holds the per-polygon buffers, sized for at most `N`
//! vertices at every stage (input, after clipping, edges).
//!
//! Polygon outcomes ([`Outcome`]) — nothing ever panics:
//! * more than `N` input vertices, or a clip result that would exceed `N`
//!   → skipped ([`SkipReason::TooManyVertices`], [`SkipReason::ClipCapacity`]);
//!   choose `N` with headroom: clipping can add up to 5 vertices to a convex
//!   polygon (one per plane) and more to a concave one;
//! * a non-finite vertex (input, after transform, or after clipping)
//!   → skipped ([`SkipReason::NonFinite`]);
//! * fewer than 3 vertices, or nothing left after clipping → invisible;
//! * otherwise drawn (possibly zero spans, e.g. edge-on or off-screen).
//!
//! The renderer does not cull back faces or sort: the priority tree decides
//! which faces to emit and in which order.
//!
//! Effects ([`crate::effects`]): the renderer's stages clipping, lighting,
//! depth cueing and outlines are each tested once per polygon against the
//! active [`Effects`] and the pipeline type `E` ([`Compiled`]): a stage `E`
//! leaves out is compiled out. The tree walks call the stages with a
//! second pipeline type `X`, the one the frame's code is compiled for
//! (`Renderer::effects_as`; [`crate::effects`], "Off is compiled out"):
//! a stage outside `X` is compiled out of that code too. Without clipping, a polygon that would need
//! it (crossing the near plane or the guard band) is dropped whole
//! (invisible), so no input can overflow either way. Culling and two-sided
//! lighting belong to the walk ([`crate::render::draw_frame`]); dithering
//! is a sink ([`super::dither`]).

use core::marker::PhantomData;

use embedded_graphics::pixelcolor::Rgb888;

use super::camera::{Camera, Orbit};
use super::chain::TriangleBand;
use super::clip::{clip_polygon, ClipNum, ClipVert};
use super::edge::{Dda32, Edge};
use super::gouraud::{fill_smooth, Smooth, SmoothSink};
use super::outline::draw_outline;
use super::precision::Precision;
use super::scan::{fill_polygon_in, Bbox, FillRule, Paint, SpanBounds, SpanSink};
use super::shade::{shade_color, DepthCue, IntensityMemo, Light, ShadeMode};
use super::transform::{ScreenPt, VertexPath, Viewport};
use crate::effects::{AllEffects, Compiled, Effects};
use crate::fixed::Fx14;

type Scalar<P> = <<P as Precision>::Path as VertexPath>::Scalar;
type PathMatrix<P> = <<P as Precision>::Path as VertexPath>::Matrix;

/// Per-polygon scratch buffers for at most `N` vertices (`N ≤ 65 535`).
/// Size per vertex: two clip vertices + a screen point (8 B) + an edge
/// (48 B) + an active-list slot (2 B): 106 B with the fixed path (24-byte
/// clip vertices), 82 B with f32; `N = 64` is 6.6 KiB fixed, 5.1 KiB f32.
#[derive(Debug)]
pub struct Scratch<P: Precision, const N: usize> {
    clip_a: [ClipVert<Scalar<P>>; N],
    clip_b: [ClipVert<Scalar<P>>; N],
    screen: [ScreenPt; N],
    edges: [Edge; N],
    active: [u16; N],
}

impl<P: Precision, const N: usize> Scratch<P, N> {
    /// Zeroed buffers.
    ///
    /// A `const fn` of constant zeroes: usable in a `static` initialiser,
    /// and at run time the optimiser writes the zeroes straight into the
    /// destination instead of building a multi-KiB temporary on the stack
    /// and copying it (which cost a small-RAM target its stack budget).
    pub const fn new() -> Self {
        let zero = ClipVert {
            x: <Scalar<P> as ClipNum>::ZERO,
            y: <Scalar<P> as ClipNum>::ZERO,
            w: <Scalar<P> as ClipNum>::ZERO,
        };
        Scratch {
            clip_a: [zero; N],
            clip_b: [zero; N],
            screen: [ScreenPt { x: 0, y: 0 }; N],
            edges: [Edge::ZERO; N],
            active: [0; N],
        }
    }
}

impl<P: Precision, const N: usize> Scratch<P, N> {
    /// The projected points of the polygon at hand.
    #[inline]
    pub(crate) fn screen(&self) -> &[ScreenPt] {
        &self.screen
    }

    /// The same, to fill in (the display list's replay).
    #[inline]
    pub(crate) fn screen_mut(&mut self) -> &mut [ScreenPt] {
        &mut self.screen
    }

    /// The vertex indices [`Renderer::load_cached`] left.
    #[inline]
    pub(crate) fn active(&self) -> &[u16] {
        &self.active
    }

    /// The same, to fill in (the band walk, which loads without them).
    #[inline]
    pub(crate) fn active_mut(&mut self) -> &mut [u16] {
        &mut self.active
    }
}

impl<P: Precision, const N: usize> Default for Scratch<P, N> {
    fn default() -> Self {
        Self::new()
    }
}

/// What [`Renderer::load`] leaves in the scratch: `n` clip vertices, and
/// whether every one is inside all clip planes (`ClipNum::inside`).
#[derive(Clone, Copy, Debug)]
struct Loaded {
    n: usize,
    inside: bool,
}

/// Frame state and the polygon pipeline (see module docs). `E` names the
/// stages compiled in (default: all).
#[derive(Debug)]
pub struct Renderer<P: Precision, E: Compiled = AllEffects> {
    matrix: PathMatrix<P>,
    near: Scalar<P>,
    viewport: Viewport,
    light: Light,
    /// Intensities of normals lit under `light` (emptied with it).
    memo: IntensityMemo,
    mode: ShadeMode,
    rule: FillRule,
    stats: RenderStats,
    forced: Option<Effects>,
    slivers: bool,
    active: Effects,
    cue: DepthCue,
    outline: Rgb888,
    /// The colour plane of the polygon the walk hands to the fill next
    /// (`smooth` effect, [`super::gouraud`]): kept here, not in [`Ready`],
    /// so that the flat path's per-polygon data stays as small as before.
    smooth: Option<Smooth>,
    pipeline: PhantomData<E>,
}

impl<P: Precision, E: Compiled> Renderer<P, E> {
    /// A renderer for a `width × height` frame; `None` if a side is 0 or
    /// above [`super::transform::MAX_DIM`].
    pub fn new(width: u32, height: u32, camera: &Camera) -> Option<Self> {
        let viewport = Viewport::new(width, height, P::SUB_BITS)?;
        let matrix = P::Path::prepare(&camera.matrix);
        Some(Renderer {
            matrix,
            near: P::Path::near(&matrix, camera.near_w),
            viewport,
            light: Light::default(),
            memo: IntensityMemo::EMPTY,
            mode: ShadeMode::default(),
            rule: FillRule::default(),
            stats: RenderStats::default(),
            forced: None,
            slivers: false,
            active: Effects::defaults(true),
            cue: DepthCue::default(),
            outline: Rgb888::new(0, 0, 0),
            smooth: None,
            pipeline: PhantomData,
        })
    }

    /// A renderer for a `width × height` frame with no camera yet (it
    /// draws nothing until [`Renderer::set_camera`]; the tree walks of
    /// [`crate::render`] set one every frame) and the default light,
    /// shading and fill rule; `None` as for [`Renderer::new`].
    ///
    /// A `const fn`: it can initialise a `static`, so that a renderer
    /// never lives on the stack (see [`crate::render::TreeRenderer::new`]).
    pub const fn sized(width: u32, height: u32) -> Option<Self> {
        let Some(viewport) = Viewport::new(width, height, P::SUB_BITS) else {
            return None;
        };
        Some(Renderer {
            matrix: P::Path::UNSET,
            near: P::Path::NEAR_MIN,
            viewport,
            light: Light::DEFAULT,
            memo: IntensityMemo::EMPTY,
            mode: ShadeMode::Lambert,
            rule: FillRule::NonZero,
            stats: RenderStats::ZERO,
            forced: None,
            slivers: false,
            active: Effects::defaults(true),
            cue: DepthCue::DEFAULT,
            outline: Rgb888::new(0, 0, 0),
            smooth: None,
            pipeline: PhantomData,
        })
    }

    /// The effects in use: the ones set with [`Renderer::set_effects`], or
    /// else the tree's (from the last [`Renderer::begin_tree`]), or else
    /// the defaults of a closed volume. Always within `E`'s compiled set.
    pub fn effects(&self) -> Effects {
        self.active.and(E::SET)
    }

    /// [`Renderer::effects`] as the code compiled for pipeline `X` sees
    /// them: an effect outside `X`'s set is compiled out of that code (the
    /// walk-and-fill copies of [`crate::effects`]'s dispatch; `X = E` for
    /// the renderer's own).
    #[inline(always)]
    pub(crate) fn effects_as<X: Compiled>(&self) -> Effects {
        self.active.and(E::SET.and(X::SET))
    }

    /// Draws, before the culling walk of a closed tree, the culled
    /// polygons that the sub-pixel snap winds toward the viewer (see
    /// [`crate::render`], "Slivers"): no background pixel inside the
    /// snapped silhouette, at a cost (socket.off, Cortex-M4F: +18 % a
    /// frame), so it is off unless asked for.
    ///
    /// ```
    /// # use fpt_nostd::raster::{DefaultPrecision, Renderer};
    /// let mut r = Renderer::<DefaultPrecision>::sized(32, 24).unwrap();
    /// assert!(!r.slivers());
    /// r.set_slivers(true);
    /// assert!(r.slivers());
    /// ```
    pub fn set_slivers(&mut self, on: bool) {
        self.slivers = on;
    }

    /// Whether slivers are drawn ([`Renderer::set_slivers`]).
    pub fn slivers(&self) -> bool {
        self.slivers
    }

    /// Uses `effects` from now on, whatever the trees declare; `None` goes
    /// back to each tree's own.
    pub fn set_effects(&mut self, effects: Option<Effects>) {
        self.forced = effects;
        if let Some(e) = effects {
            self.active = e;
        }
    }

    /// Called by the tree walk at the start of each frame with the tree's
    /// declared effects; returns the effects in use for the frame.
    pub fn begin_tree(&mut self, declared: Effects) -> Effects {
        self.active = self.forced.unwrap_or(declared);
        self.smooth = None;
        self.effects()
    }

    /// Sets the depth cueing parameters (used when `depth-cue` is on).
    pub fn set_depth_cue(&mut self, cue: DepthCue) {
        self.cue = cue;
    }

    /// Sets the outline colour (used when `outline` is on; default black).
    pub fn set_outline_color(&mut self, c: Rgb888) {
        self.outline = c;
    }

    /// The viewport.
    pub fn viewport(&self) -> Viewport {
        self.viewport
    }

    /// Sets the camera (model → clip matrix and near threshold).
    pub fn set_camera(&mut self, camera: &Camera) {
        self.matrix = P::Path::prepare(&camera.matrix);
        self.near = P::Path::near(&self.matrix, camera.near_w);
    }

    /// Sets an orbit camera, using `P`'s math library and the viewport's
    /// aspect ratio.
    pub fn set_orbit(&mut self, orbit: &Orbit) {
        let cam = orbit.camera::<P::Math>(self.viewport.aspect());
        self.set_camera(&cam);
    }

    /// Sets the light.
    pub fn set_light(&mut self, light: Light) {
        self.light = light;
        self.memo = IntensityMemo::EMPTY;
    }

    /// Sets the colour plane the next [`Renderer::fill_ready`] paints with
    /// (`None`: flat); only a walk with smooth shading sets it.
    #[inline]
    pub(crate) fn set_smooth(&mut self, plane: Option<Smooth>) {
        self.smooth = plane;
    }

    /// The light, shading mode and depth cueing parameters (for the
    /// `smooth` effect's corner colours, [`super::gouraud`]).
    #[inline]
    pub(crate) fn lighting(&self) -> (&Light, ShadeMode, &DepthCue) {
        (&self.light, self.mode, &self.cue)
    }

    /// Sets the shading mode.
    pub fn set_shade_mode(&mut self, mode: ShadeMode) {
        self.mode = mode;
    }

    /// Sets the fill rule (only matters for self-intersecting polygons).
    pub fn set_fill_rule(&mut self, rule: FillRule) {
        self.rule = rule;
    }

    /// Counters so far.
    pub fn stats(&self) -> RenderStats {
        self.stats
    }

    /// The counters, to correct (a polygon prepared twice counts once).
    pub(crate) fn stats_mut(&mut self) -> &mut RenderStats {
        &mut self.stats
    }

    /// Zeroes the counters.
    pub fn reset_stats(&mut self) {
        self.stats = RenderStats::default();
    }

    /// Draws a polygon given by model-space `f32` vertices.
    pub fn draw_polygon<K, I, const N: usize>(
        &mut self,
        scratch: &mut Scratch<P, N>,
        verts: I,
        face: &Face,
        sink: &mut K,
    ) -> Outcome
    where
        K: SpanSink,
        I: IntoIterator<Item = [f32; 3]>,
    {
        let m = self.matrix;
        let out = self.load(scratch, verts, |v| P::Path::transform(&m, v));
        self.finish(scratch, out, face, sink)
    }

    /// Draws a polygon given by integer vertices with `frac` fraction bits
    /// (q16.16 → 16, q32.32 low words → 32; see
    /// [`VertexPath::transform_q`]).
    pub fn draw_polygon_q<K, I, const N: usize>(
        &mut self,
        scratch: &mut Scratch<P, N>,
        verts: I,
        frac: u32,
        face: &Face,
        sink: &mut K,
    ) -> Outcome
    where
        K: SpanSink,
        I: IntoIterator<Item = [i32; 3]>,
    {
        let m = self.matrix;
        let out = self.load(scratch, verts, |v| P::Path::transform_q(&m, v, frac));
        self.finish(scratch, out, face, sink)
    }

    /// Transforms the input into `scratch.clip_a`.
    fn load<V, I, const N: usize>(
        &self,
        scratch: &mut Scratch<P, N>,
        verts: I,
        f: impl Fn(V) -> Option<ClipVert<Scalar<P>>>,
    ) -> Result<Loaded, SkipReason>
    where
        I: IntoIterator<Item = V>,
    {
        let mut n = 0usize;
        // The clipper's fast accept, taken while each vertex is at hand
        // (it is the common case, and saves a second pass over them).
        let mut inside = true;
        for v in verts {
            let slot = scratch
                .clip_a
                .get_mut(n)
                .ok_or(SkipReason::TooManyVertices)?;
            *slot = f(v).ok_or(SkipReason::NonFinite)?;
            inside &= <Scalar<P> as ClipNum>::inside(slot, self.near);
            n += 1;
        }
        Ok(Loaded { n, inside })
    }

    fn finish<K: SpanSink, const N: usize>(
        &mut self,
        scratch: &mut Scratch<P, N>,
        loaded: Result<Loaded, SkipReason>,
        face: &Face,
        sink: &mut K,
    ) -> Outcome {
        let outcome = self.pipeline(scratch, loaded, face, sink);
        self.count(outcome);
        outcome
    }

    /// Adds a polygon's outcome to the counters.
    #[inline]
    pub(crate) fn count(&mut self, outcome: Outcome) {
        match outcome {
            Outcome::Drawn { spans } => {
                self.stats.drawn += 1;
                self.stats.spans += spans as u64;
            }
            Outcome::Invisible => self.stats.invisible += 1,
            Outcome::Skipped(_) => self.stats.skipped += 1,
        }
    }

    /// The set-up with which [`Renderer::fill_ready`] fills a triangle
    /// into `sink` without a colour plane or outlines, found once for
    /// many triangles (a band's replay, `render::cached`); `None` when
    /// `fill_ready` would take another path (Gouraud, outlines, or see
    /// [`TriangleBand::new`]).
    #[inline]
    pub(crate) fn triangle_band<X: Compiled, K: SpanSink, const N: usize>(
        &self,
        _scratch: &Scratch<P, N>,
        sink: &K,
    ) -> Option<TriangleBand> {
        let smooth = E::SET.and(X::SET).contains(Effects::SMOOTH) && self.smooth.is_some();
        if smooth || self.effects_as::<X>().contains(Effects::OUTLINE) {
            return None;
        }
        let sub = self.viewport.sub_bits();
        TriangleBand::new(sub, &self.viewport_bounds(), &sink.bounds(), N, N)
    }

    /// The viewport's pixels.
    #[inline]
    pub(crate) fn viewport_bounds(&self) -> SpanBounds {
        SpanBounds::of_size(self.viewport.width(), self.viewport.height())
    }

    fn pipeline<K: SpanSink, const N: usize>(
        &mut self,
        scratch: &mut Scratch<P, N>,
        loaded: Result<Loaded, SkipReason>,
        face: &Face,
        sink: &mut K,
    ) -> Outcome {
        let reach = self.viewport_bounds().intersect(&sink.bounds());
        match self.prepare::<E, N>(scratch, loaded, face, &reach) {
            Ok(ready) => {
                self.fill_ready::<E, K, N>(scratch, &ready, face.id, face.hidden_edges, sink)
            }
            Err(outcome) => outcome,
        }
    }

    /// The frame's matrix in the path's format (for the walk's own
    /// transforms: the vertex cache's misses, [`Renderer::prepare_verts`]).
    #[inline]
    pub(crate) fn matrix(&self) -> &PathMatrix<P> {
        &self.matrix
    }

    /// Transforms (with `xf` and the frame's matrix: `VertexPath::transform`
    /// for model-space `f32` vertices as [`Renderer::draw_polygon`] takes
    /// them, `VertexPath::transform_q` for integer ones), clips and
    /// projects the polygon `verts` and shades it: everything but the
    /// fill, for rows `reach`.
    #[inline(always)]
    pub(crate) fn prepare_verts<X: Compiled, T, I, const N: usize>(
        &mut self,
        scratch: &mut Scratch<P, N>,
        verts: I,
        xf: impl Fn(&PathMatrix<P>, T) -> Option<ClipVert<Scalar<P>>>,
        face: &Face,
        reach: &SpanBounds,
    ) -> Result<Ready, Outcome>
    where
        I: IntoIterator<Item = T>,
    {
        let m = self.matrix;
        let loaded = self.load(scratch, verts, |v| xf(&m, v));
        self.prepare::<X, N>(scratch, loaded, face, reach)
    }

    /// [`Renderer::prepare_verts`] for points already in
    /// `scratch.screen[..n]` (from [`Renderer::load_cached`]: every one
    /// inside the clip planes). Not for depth cueing, which needs clip `w`.
    /// Without `BOX` the polygon's box is not kept for the fill, only its
    /// rows are found (see [`Renderer::shade_ready`]).
    #[inline]
    pub(crate) fn prepare_screen<X: Compiled, const N: usize, const BOX: bool>(
        &mut self,
        scratch: &Scratch<P, N>,
        n: usize,
        face: &Face,
        reach: &SpanBounds,
    ) -> Result<Ready, Outcome> {
        if n < 3 {
            return Err(Outcome::Invisible);
        }
        self.shade_ready::<X, BOX>(&scratch.screen[..n.min(N)], face, 0.0, false, reach)
    }

    /// Everything of the pipeline before the fill: clipping, projection
    /// into `scratch.screen`, the row range, shading. `Err` is the
    /// polygon's outcome when there is nothing to fill (for rows `reach`).
    #[inline(always)]
    fn prepare<X: Compiled, const N: usize>(
        &mut self,
        scratch: &mut Scratch<P, N>,
        loaded: Result<Loaded, SkipReason>,
        face: &Face,
        reach: &SpanBounds,
    ) -> Result<Ready, Outcome> {
        let Loaded { n, inside } = match loaded {
            Ok(l) => l,
            Err(r) => return Err(Outcome::Skipped(r)),
        };
        if n < 3 {
            return Err(Outcome::Invisible);
        }
        let fx = self.effects_as::<X>();
        // Mean eye depth, before clipping changes the vertices.
        let depth = if fx.contains(Effects::DEPTH_CUE) {
            let sum: f32 = scratch.clip_a[..n.min(N)]
                .iter()
                .map(|v| P::Path::depth(&self.matrix, v.w))
                .sum();
            sum / n as f32
        } else {
            0.0
        };
        let (clipped, was_clipped) = if inside {
            // What clipping's fast accept returns (and what both arms
            // below would give).
            (&scratch.clip_a[..n.min(N)], false)
        } else if fx.contains(Effects::CLIPPING) {
            let Ok(c) = clip_polygon(&mut scratch.clip_a, n, &mut scratch.clip_b, self.near) else {
                return Err(Outcome::Skipped(SkipReason::ClipCapacity));
            };
            (c.verts, c.clipped)
        } else {
            // Without clipping, a polygon that needs it is dropped whole.
            return Err(Outcome::Invisible);
        };
        if was_clipped {
            self.stats.clipped += 1;
        }
        if clipped.len() < 3 {
            return Err(Outcome::Invisible);
        }
        // Every vertex here came from the transform and is inside every
        // clip plane (kept whole or made by clipping): the projection's
        // short form applies.
        for (dst, v) in scratch.screen.iter_mut().zip(clipped.iter()) {
            match P::Path::project_clipped(v, &self.viewport) {
                Some(p) => *dst = p,
                None => return Err(Outcome::Skipped(SkipReason::NonFinite)),
            }
        }
        let m = clipped.len();
        self.shade_ready::<X, true>(&scratch.screen[..m], face, depth, was_clipped, reach)
    }

    /// The row range and the shaded colour of projected points `pts`;
    /// `Err(Drawn { spans: 0 })` when the polygon misses rows `reach`.
    /// With `BOX` (or Gouraud shading compiled in) the polygon's box comes
    /// along for the fill; without, only its rows are found, by a pass over
    /// the points' `y` (the band walk: its display list keeps the rows, not
    /// the box, and the replay's fill finds the box itself; the fill as
    /// the walk goes, when the list is full, does too).
    #[inline(always)]
    fn shade_ready<X: Compiled, const BOX: bool>(
        &self,
        pts: &[ScreenPt],
        face: &Face,
        depth: f32,
        clipped: bool,
        reach: &SpanBounds,
    ) -> Result<Ready, Outcome> {
        // Shade only polygons that reach the sink at all (cheap test first).
        if reach.is_empty() {
            return Err(Outcome::Drawn { spans: 0 });
        }
        // A band renderer sees every polygon once per band: one that misses
        // the band's rows (the fill would find no active row, the same
        // outcome) skips shading and edge setup for one pass over its
        // vertices.
        // The fill's first pass, done once here for both.
        let (bbox, (top, bot)) = if BOX || X::SET.contains(Effects::SMOOTH) {
            let bbox = Bbox::seeded(pts);
            (Some(bbox), (bbox.top, bbox.bot))
        } else {
            (None, Bbox::rows(pts))
        };
        // Projected points are within ±SCREEN_LIMIT: the 32-bit row bounds
        // apply (and a 64-bit variable shift is not cheap on a 32-bit core).
        let sub = self.viewport.sub_bits();
        let fx = self.effects_as::<X>();
        let (first, end) = if fx.contains(Effects::OUTLINE) {
            // Outline pixels are the rows holding the vertices (`y >> sub`),
            // which may be one above the first row the fill samples.
            (top >> sub.min(16), (bot >> sub.min(16)).saturating_add(1))
        } else {
            Dda32::rows(ScreenPt { x: 0, y: top }, ScreenPt { x: 0, y: bot }, sub)
        };
        if end <= reach.y0 || first >= reach.y1 {
            return Err(Outcome::Drawn { spans: 0 });
        }
        let mut rgb = if fx.contains(Effects::LIGHTING) {
            self.memo
                .shade(self.mode, &self.light, face.normal, face.color)
        } else {
            shade_color(self.mode, face.color, Fx14::ONE)
        };
        if fx.contains(Effects::DEPTH_CUE) {
            rgb = self.cue.apply(rgb, depth);
        }
        Ok(Ready {
            n: pts.len(),
            bbox,
            first,
            end,
            rgb,
            clipped,
            depth,
        })
    }

    /// Fills a prepared polygon (its points in `scratch.screen[..n]`) and
    /// draws its outline when that effect is on: the pipeline's last stage,
    /// which band rendering replays per band from the display list.
    #[inline(always)]
    pub(crate) fn fill_ready<X: Compiled, K: SpanSink, const N: usize>(
        &self,
        scratch: &mut Scratch<P, N>,
        ready: &Ready,
        id: u32,
        hidden_edges: u64,
        sink: &mut K,
    ) -> Outcome {
        let Some(pts) = scratch.screen.get(..ready.n) else {
            return Outcome::Skipped(SkipReason::ClipCapacity);
        };
        let sub = self.viewport.sub_bits();
        let vp = self.viewport_bounds();
        let (edges, active) = (&mut scratch.edges, &mut scratch.active);
        let plane = if E::SET.and(X::SET).contains(Effects::SMOOTH) {
            self.smooth.as_ref()
        } else {
            None
        };
        let filled = match plane {
            // Gouraud: the same fill, its spans painted by the colour plane.
            Some(s) => {
                let mut smooth = SmoothSink::new(s, id, sink);
                let (bbox, rule) = (ready.bbox.as_ref(), self.rule);
                fill_smooth(pts, bbox, sub, rule, &vp, edges, active, &mut smooth)
            }
            _ => {
                let color = sink.color(&Paint { rgb: ready.rgb, id });
                let (bbox, rule) = (ready.bbox.as_ref(), self.rule);
                fill_polygon_in(pts, bbox, sub, rule, &vp, edges, active, color, sink)
            }
        };
        let spans = match filled {
            Ok(spans) => spans,
            Err(_) => return Outcome::Skipped(SkipReason::ClipCapacity),
        };
        if self.effects_as::<X>().contains(Effects::OUTLINE) {
            let ink = sink.color(&Paint {
                rgb: self.outline,
                id,
            });
            // A clipped polygon's edges no longer match the stored ones.
            let hidden = if ready.clipped { 0 } else { hidden_edges };
            let lines = draw_outline(pts, hidden, sub, &vp, ink, sink);
            return Outcome::Drawn {
                spans: spans + lines,
            };
        }
        Outcome::Drawn { spans }
    }
}

/// A polygon transformed, clipped, projected and shaded, its screen points
/// in `scratch.screen[..n]`: what the fill needs (and what the display
/// list stores).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Ready {
    /// Points in `scratch.screen`.
    pub(crate) n: usize,
    /// Their box, when computed (the fill computes it when it needs it).
    pub(crate) bbox: Option<Bbox>,
    /// First row the fill (or the outline) may touch.
    pub(crate) first: i32,
    /// One past the last.
    pub(crate) end: i32,
    /// Shaded colour.
    pub(crate) rgb: Rgb888,
    /// Whether clipping changed the polygon.
    pub(crate) clipped: bool,
    /// Mean eye depth (with depth cueing; else 0).
    pub(crate) depth: f32,
}

mod load;
mod outcome;
pub(crate) use load::vertex_indices;
pub use outcome::{Face, Outcome, RenderStats, SkipReason};

#[cfg(test)]
mod tests {
    use super::super::precision::{FixedPrecision, FloatLibm};
    use super::*;

    #[test]
    fn stats_add_every_counter() {
        let a = RenderStats {
            drawn: 1,
            invisible: 2,
            skipped: 3,
            clipped: 4,
            slivers: 9,
            spans: 5,
            walks: 1,
            memory_used: 7,
        };
        let mut t = a;
        t += a;
        assert_eq!(
            t,
            RenderStats {
                drawn: 2,
                invisible: 4,
                skipped: 6,
                clipped: 8,
                slivers: 18,
                spans: 10,
                walks: 2,
                memory_used: 7,
            }
        );
    }

    #[test]
    fn scratch_sizes_match_the_documentation() {
        assert_eq!(core::mem::size_of::<Edge>(), 48);
        assert_eq!(
            core::mem::size_of::<Scratch<FixedPrecision<4>, 64>>(),
            64 * 106
        );
        assert_eq!(core::mem::size_of::<Scratch<FloatLibm<4>, 64>>(), 64 * 82);
    }
}
