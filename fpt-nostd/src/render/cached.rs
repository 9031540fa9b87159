//! One walk and one transform a frame: the draw loops that use the
//! caller's working memory.
//!
//! Without memory, band rendering walks the tree and transforms, clips,
//! projects and shades every polygon once per band, and every polygon
//! transforms its own corners although its vertices are shared. With
//! memory (a `&mut [u32]` of any length the caller chooses):
//!
//! * a **vertex cache** ([`crate::raster::vcache`]) holds each vertex's
//!   screen point once it is computed, so a vertex is transformed at most
//!   once a frame, whatever the number of its polygons and bands;
//! * a **display list** ([`crate::raster::list`]) records each polygon,
//!   ready to fill, during one walk, and every band replays the records
//!   that touch its rows: the walk, transform and shading happen once a
//!   frame, a band costs only its fill. After a walk that covers several
//!   bands, the words the list leaves hold, when they can, a band index
//!   ([`DisplayList::index_bands`](crate::raster::list::DisplayList::index_bands)): each band then reads only its own
//!   records, in walk order; without room it scans the record groups
//!   that overlap it (the same picture either way).
//! * The words the list and its index leave then hold the **kept
//!   triangles** ([`crate::raster::carry`], on cores with an FPU): a
//!   triangle cut by a band's end keeps its edge steppers for the next
//!   band instead of being read back and set up again there (60 bytes a
//!   triangle, at most [`crate::raster::carry`]'s 64 at once; without
//!   room, set up again: the same picture). The four-sided pieces of
//!   split triangles are kept the same way.
//!
//! # Less memory than a frame needs
//!
//! The picture never depends on the memory, only the time does:
//!
//! * The cache takes one word per vertex of the tree, up to three
//!   quarters of the memory (and 2^16 vertices); vertices beyond it are
//!   transformed per polygon, as without a cache. A full frame, which
//!   records nothing for later, instead makes the words it has a tagged
//!   cache when they cannot hold every vertex ([`VertexCache::tagged`]):
//!   a vertex shared by polygons drawn close together in the walk is
//!   still transformed once.
//! * The list takes the rest. A walk records the polygons touching rows
//!   `[y, cut)`, `cut` starting at the frame's bottom; when a record does
//!   not fit, `cut` moves up by a sixth of the bands still covered (in
//!   whole bands), records starting at or below it are dropped, and the
//!   walk goes on. The bands above `cut` are then replayed and the next
//!   walk starts at `cut` (measured costs: docs/small-ram.md).
//! * When even one band's polygons do not fit, that band is drawn as the
//!   walk goes: the records so far are replayed into it, and the rest of
//!   the walk fills it directly (one walk per band, today's cost without
//!   memory, but still with the cache).
//!
//! The counters ([`RenderStats`]) count each polygon once a frame (from the
//! first walk) and every span filled.

use super::probe::{Phase, Probe};
use super::slivers::turns_toward;
use super::{face_of, FaceIds, Frame, WalkFx};
use crate::effects::{for_frame, Compiled, Effects, ForPipeline};
use crate::order::{memo_words, Class, Order, OrderError};
use crate::raster::clip::ClipVert;
use crate::raster::renderer::Ready;
use crate::raster::transform::{ScreenPt, VertexPath};
use crate::raster::vcache::VertexCache;
use crate::raster::{
    Face, Outcome, Precision, RenderStats, Renderer, Scratch, SpanBounds, SpanSink,
};
use crate::reader::{PolygonAt, Tree, VertexDecoder, VertexIndices};

/// The clip-space scalar of `P`'s vertex path.
type PathScalar<P> = <<P as Precision>::Path as VertexPath>::Scalar;

/// Most vertices the cache holds: the display list stores their indices
/// as `u16`.
const MAX_CACHED: usize = 1 << 16;

/// Words of memory with which a frame of `tree` needs one walk and
/// transforms each vertex once, whatever the view, with the effects the
/// tree declares: [`memory_words_for`].
pub fn memory_words(tree: &Tree<'_>) -> usize {
    memory_words_for(tree, Effects::from_bits(tree.effects()))
}

/// [`memory_words`] for a renderer drawing with `effects` (its forced
/// effects, or the tree's): the facing memo, a cache slot for every vertex
/// and a list with room for every polygon (by polygon index, with ids and
/// outline masks); with depth cueing, which keeps the cache off, every
/// record holds its points inline (about four times the words).
/// Clipped polygons are stored inline and may need more; a frame that
/// needs more still draws the same picture, with one more walk (see the
/// module docs).
pub fn memory_words_for(tree: &Tree<'_>, effects: Effects) -> usize {
    let v = (tree.vertex_count() as usize).min(MAX_CACHED);
    // A record by polygon: at most 7 header words (a long row span, one
    // word of the outline mask, the id), the polygon index and its share
    // of the group table (4 words a group of 16); with outlines, 3 more
    // words of the mask (it takes 4); polygons from the 65,537th on are
    // stored by vertex index, a word a vertex more.
    let polygons = tree.polygon_count() as usize;
    let per = if effects.contains(Effects::OUTLINE) {
        12
    } else {
        9
    };
    let mut halves = per * polygons;
    if polygons > MAX_CACHED {
        halves += tree.index_count() as usize;
    }
    let list = halves.div_ceil(2);
    // The cache may take at most three quarters of the memory; the facing
    // memo (without an FPU) comes first.
    let cached = (v + list).max((4 * v).div_ceil(3));
    // Depth cueing keeps no cache: every record holds its points inline
    // (4 words a point, a count word).
    let need = if effects.contains(Effects::DEPTH_CUE) {
        (per * polygons + 4 * tree.index_count() as usize).div_ceil(2)
    } else {
        cached
    };
    memo_words(tree) + need
}

/// What a walk's callback asks for next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Step {
    /// The next polygon.
    Next,
    /// The same polygon, prepared again.
    Again,
}

/// Everything a walk needs besides the renderer.
struct Walk<'t, 'a, 'c> {
    tree: &'a Tree<'t>,
    /// The tree's vertex decoder, made once a frame: the loads' closures
    /// capture a reference to it (with the scale, two words handed over
    /// in registers), not a copy of it made for every polygon.
    dec: &'a VertexDecoder<'t>,
    source: Source,
    fx: WalkFx,
    /// Which id a face carries; `None` when the sink paints without ids
    /// (the band walk's framebuffers): every face then carries 0, and no
    /// polygon's id is read from the tree.
    ids: Option<FaceIds>,
    cache: &'a mut VertexCache<'c>,
    /// How a face toward the viewer winds on screen, when slivers are
    /// drawn ([`slivers::front_turn`]); 0: no sliver pass.
    turn: i32,
}

/// Which pass of [`Walk::run`] a polygon is drawn by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// The walk's.
    Walk,
    /// The sliver pass's ([`slivers`]), its screen points found wound
    /// toward the viewer.
    Sliver,
    /// The sliver pass's, not yet tested (it needs clipping): drawn only
    /// when its clipped points turn toward the viewer, wound as this
    /// [`slivers::front_turn`] says.
    Unsure(i32),
}

impl Walk<'_, '_, '_> {
    /// Walks the tree back to front and hands each polygon, prepared for
    /// rows `reach()`, to `f`, with the cache (which `f` may read). `f`
    /// returns [`Step::Again`] to have the same polygon prepared and
    /// handed over once more (after it has used the scratch for something
    /// else). `count`: add each polygon's outcome to the counters.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn run<
        P: Precision,
        E: Compiled,
        X: Compiled,
        Pr: Probe,
        const N: usize,
        const V: usize,
        const BOX: bool,
    >(
        &mut self,
        order: &mut Order<'_, N>,
        r: &mut Renderer<P, E>,
        scratch: &mut Scratch<P, V>,
        probe: &Pr,
        count: bool,
        reach: impl Fn() -> SpanBounds,
        mut f: impl FnMut(
            &mut Renderer<P, E>,
            &mut Scratch<P, V>,
            &Ready,
            Option<u32>,
            &Face,
            &VertexCache<'_>,
        ) -> Step,
    ) {
        probe.enter(Phase::Post);
        order.restart();
        let view = order.view();
        // Slivers first (see `render::slivers`): culled polygons that the
        // snap winds toward the viewer, under everything the walk draws.
        // One loop over both passes' ranges, so that the walk-and-fill
        // function holds one copy of `draw` (the prepare and the fill
        // inlined into it), not one per pass.
        let mut slivers = (self.turn != 0).then(|| order.culled(self.tree));
        loop {
            let (range, sliver) = match slivers.as_mut().map(Class::next_range) {
                Some(Some(range)) => (range, true),
                Some(None) => {
                    slivers = None;
                    continue;
                }
                None => match order.next_range() {
                    Some(range) => (range, false),
                    None => break,
                },
            };
            for id in range {
                // The polygon borrowing the tree: a `PolygonRef` (a copy
                // of the tree's geometry) only for the probe, which
                // `NoProbe` leaves unused.
                let Some(p) = self.tree.polygon_at(id) else {
                    continue;
                };
                let (fx, pass) = if sliver {
                    let sure = match self.screen_points::<P, E, V, BOX>(r, scratch, &p) {
                        Some(n) => {
                            let pts = scratch.screen().get(..n).unwrap_or(&[]);
                            if !turns_toward(pts, self.turn) {
                                continue;
                            }
                            true
                        }
                        // Needs clipping: tested on its clipped points.
                        None => false,
                    };
                    let fx = WalkFx {
                        two_sided: true,
                        outline: false,
                        ..self.fx
                    };
                    let pass = if sure {
                        Pass::Sliver
                    } else {
                        Pass::Unsure(self.turn)
                    };
                    (fx, pass)
                } else {
                    (self.fx, Pass::Walk)
                };
                if let Some(p) = self.tree.polygon(id) {
                    probe.polygon(&p);
                }
                let mut face = face_of(self.tree, &p, &view, fx, self.id_of(&p));
                if sliver {
                    face.hidden_edges = u64::MAX;
                }
                let polygon = (&p, &face, pass);
                self.draw::<P, E, X, Pr, V, BOX>(r, scratch, polygon, probe, count, &reach, &mut f);
                probe.enter(Phase::Post);
            }
        }
    }

    /// The id `p` writes into id buffers.
    #[inline(always)]
    fn id_of(&self, p: &PolygonAt<'_, '_>) -> u32 {
        match self.ids {
            Some(FaceIds::Source) => p.source(),
            Some(FaceIds::Polygon) => p.id(),
            None => 0,
        }
    }

    /// Prepares polygon `p` (drawn as `face`) and hands it to `f` (again
    /// while `f` asks for it), counting it once (slivers apart).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn draw<P: Precision, E: Compiled, X: Compiled, Pr: Probe, const V: usize, const BOX: bool>(
        &mut self,
        r: &mut Renderer<P, E>,
        scratch: &mut Scratch<P, V>,
        (p, face, pass): (&PolygonAt<'_, '_>, &Face, Pass),
        probe: &Pr,
        count: bool,
        reach: &impl Fn() -> SpanBounds,
        f: &mut impl FnMut(
            &mut Renderer<P, E>,
            &mut Scratch<P, V>,
            &Ready,
            Option<u32>,
            &Face,
            &VertexCache<'_>,
        ) -> Step,
    ) {
        let mut first = true;
        let clipped = r.stats_mut().clipped;
        loop {
            probe.enter(Phase::Xform);
            let (ready, by_index) = self.prepare::<P, E, X, V, BOX>(r, scratch, p, face, &reach());
            if let Pass::Unsure(t) = pass {
                let sliver = ready.as_ref().is_ok_and(|ready| {
                    turns_toward(scratch.screen().get(..ready.n).unwrap_or(&[]), t)
                });
                if !sliver {
                    // Not a sliver after all: as if never prepared.
                    let now = r.stats_mut();
                    now.clipped = now.clipped.min(clipped);
                    return;
                }
            }
            if !first {
                // Prepared again: count its clipping once.
                let now = r.stats_mut();
                now.clipped = now.clipped.min(clipped + 1);
            }
            if count && first {
                if pass != Pass::Walk {
                    r.stats_mut().slivers += 1;
                } else {
                    match ready {
                        // `count` of `Drawn { spans: 0 }` without the
                        // 64-bit addition of nothing (a polygon's spans
                        // are added as the fill returns them).
                        Ok(_) => r.stats_mut().drawn += 1,
                        Err(o) => r.count(o),
                    }
                }
            }
            first = false;
            let step = match ready {
                // Every vertex cached: the polygon's index stands for its
                // points.
                Ok(ready) => {
                    let smooth = X::SET.contains(Effects::SMOOTH) && self.fx.smooth;
                    if smooth {
                        let plane = r.smooth_plane::<X, V>(scratch, &ready, self.tree, p, face);
                        r.set_smooth(plane);
                    }
                    let poly = by_index.then(|| p.id());
                    let step = f(r, scratch, &ready, poly, face, self.cache);
                    if smooth {
                        // No plane outlives its polygon.
                        r.set_smooth(None);
                    }
                    step
                }
                Err(_) => Step::Next,
            };
            if step == Step::Next {
                break;
            }
        }
    }

    /// The screen points of `p` through the cache into `scratch.screen`
    /// (their number), without shading or clipping; `None` when `p` needs
    /// the per-polygon path (a vertex outside a clip plane, not finite or
    /// far off screen).
    /// The band walk (`!BOX`) loads without the vertex indices, as in
    /// [`Walk::prepare_from`].
    #[inline(always)]
    fn screen_points<P: Precision, E: Compiled, const V: usize, const BOX: bool>(
        &mut self,
        r: &Renderer<P, E>,
        scratch: &mut Scratch<P, V>,
        p: &PolygonAt<'_, '_>,
    ) -> Option<usize> {
        let dec = self.dec;
        let (cache, indices) = (&mut *self.cache, p.vertex_indices());
        let loaded = match self.source.arm::<P>() {
            Arm::Decoded(Some(s)) => {
                let scale = move |x: [f32; 3]| x.map(|c| c * s);
                Self::load_decoded::<P, E, V, BOX>(r, scratch, (cache, indices), dec, scale)
            }
            Arm::Decoded(None) => {
                let scale = |x: [f32; 3]| x;
                Self::load_decoded::<P, E, V, BOX>(r, scratch, (cache, indices), dec, scale)
            }
            Arm::Raw(frac) => {
                let decode = |v: u32| dec.raw_q16(v as usize);
                if BOX {
                    let xform =
                        |v: u32| <P::Path as VertexPath>::transform_q(r.matrix(), decode(v), frac);
                    r.load_cached(scratch, cache, indices, xform)
                } else {
                    let point = |r: &Renderer<P, E>, x| r.raw_point(x, frac);
                    r.load_cached_bare(scratch, cache, indices, (decode, point))
                }
            }
        };
        loaded.map(|(n, _)| n)
    }

    /// [`Walk::screen_points`]' load of vertices decoded to `f32` and
    /// multiplied by the frame's scale with `scale` (the identity when
    /// the scale is folded into the matrix).
    #[inline(always)]
    fn load_decoded<P: Precision, E: Compiled, const V: usize, const BOX: bool>(
        r: &Renderer<P, E>,
        scratch: &mut Scratch<P, V>,
        (cache, indices): (&mut VertexCache<'_>, VertexIndices<'_>),
        dec: &VertexDecoder<'_>,
        scale: impl Fn([f32; 3]) -> [f32; 3] + Copy,
    ) -> Option<(usize, bool)> {
        let decode = move |v: u32| scale(dec.get(v as usize));
        if BOX {
            let xform = |v: u32| <P::Path as VertexPath>::transform(r.matrix(), decode(v));
            r.load_cached(scratch, cache, indices, xform)
        } else {
            let point = |r: &Renderer<P, E>, x| r.model_point(x);
            r.load_cached_bare(scratch, cache, indices, (decode, point))
        }
    }

    /// Prepares `p` through the cache when every vertex is inside the clip
    /// planes (`true`: every vertex is cached, and its indices are in
    /// `scratch.active`), else per polygon.
    #[inline(always)]
    fn prepare<P: Precision, E: Compiled, X: Compiled, const V: usize, const BOX: bool>(
        &mut self,
        r: &mut Renderer<P, E>,
        scratch: &mut Scratch<P, V>,
        p: &PolygonAt<'_, '_>,
        face: &Face,
        reach: &SpanBounds,
    ) -> (Result<Ready, Outcome>, bool) {
        let dec = self.dec;
        let xf = |m: &_, x| <P::Path as VertexPath>::transform(m, x);
        let pt = |r: &Renderer<P, E>, x| r.model_point(x);
        match self.source.arm::<P>() {
            Arm::Decoded(Some(s)) => {
                let decode = move |v: u32| dec.get(v as usize).map(|c| c * s);
                let how = (decode, xf, pt);
                self.prepare_from::<P, E, X, _, V, BOX>(r, scratch, p, how, face, reach)
            }
            Arm::Decoded(None) => {
                let decode = move |v: u32| dec.get(v as usize);
                let how = (decode, xf, pt);
                self.prepare_from::<P, E, X, _, V, BOX>(r, scratch, p, how, face, reach)
            }
            Arm::Raw(frac) => {
                let decode = move |v: u32| dec.raw_q16(v as usize);
                let xf = move |m: &_, x| <P::Path as VertexPath>::transform_q(m, x, frac);
                let pt = move |r: &Renderer<P, E>, x| r.raw_point(x, frac);
                let how = (decode, xf, pt);
                self.prepare_from::<P, E, X, _, V, BOX>(r, scratch, p, how, face, reach)
            }
        }
    }

    /// [`Walk::prepare`] for vertices that `decode` reads by index, `xf`
    /// transforms with the frame's matrix and `pt` takes to the screen
    /// (a tagged cache's misses: [`Renderer::model_point`]).
    #[inline(always)]
    fn prepare_from<P: Precision, E: Compiled, X: Compiled, T, const V: usize, const BOX: bool>(
        &mut self,
        r: &mut Renderer<P, E>,
        scratch: &mut Scratch<P, V>,
        p: &PolygonAt<'_, '_>,
        (decode, xf, pt): (
            impl Fn(u32) -> T + Copy,
            impl Fn(&<P::Path as VertexPath>::Matrix, T) -> Option<ClipVert<PathScalar<P>>>,
            impl Fn(&Renderer<P, E>, T) -> Option<ScreenPt> + Copy,
        ),
        face: &Face,
        reach: &SpanBounds,
    ) -> (Result<Ready, Outcome>, bool) {
        if self.cache.indexed_len() > 0 {
            let xform = |v: u32| xf(r.matrix(), decode(v));
            // The band walk (`!BOX`) leaves the vertex indices out of
            // `scratch.active` (its callback reads them from the tree in
            // the rare case it records them).
            let indices = p.vertex_indices();
            let loaded = if BOX {
                r.load_cached(scratch, self.cache, indices, xform)
            } else {
                r.load_cached_bare(scratch, self.cache, indices, (&decode, &pt))
            };
            if let Some((n, by_index)) = loaded {
                return (
                    r.prepare_screen::<X, V, BOX>(scratch, n, face, reach),
                    by_index,
                );
            }
        } else if self.cache.is_tagged() {
            // By value: the closures' few words reach the miss in registers.
            let how = (decode, pt);
            if let Some(n) = r.load_tagged(scratch, self.cache, p.vertex_indices(), how) {
                return (
                    r.prepare_screen::<X, V, BOX>(scratch, n, face, reach),
                    false,
                );
            }
        }
        let verts = p.vertex_indices().map(decode);
        (
            r.prepare_verts::<X, T, _, V>(scratch, verts, xf, face, reach),
            false,
        )
    }
}

/// Fills one prepared polygon into `sink` (the probe sees the fill).
#[inline(always)]
fn fill<P: Precision, E: Compiled, X: Compiled, K: SpanSink, Pr: Probe, const V: usize>(
    r: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    ready: &Ready,
    face: &Face,
    sink: &mut K,
    probe: &Pr,
) -> u64 {
    probe.enter(Phase::Fill);
    match r.fill_ready::<X, K, V>(scratch, ready, face.id, face.hidden_edges, sink) {
        Outcome::Drawn { spans } => spans as u64,
        _ => 0,
    }
}

/// Whether this frame may use the vertex cache: depth cueing needs each
/// polygon's clip `w`, which the cache does not keep.
fn cacheable<P: Precision, E: Compiled, X: Compiled>(r: &Renderer<P, E>) -> bool {
    !r.effects_as::<X>().contains(Effects::DEPTH_CUE)
}

/// The frame's effects, settled for `tree` by [`Renderer::begin_tree`]:
/// what [`for_frame`] picks the frame's code by.
#[inline(always)]
fn frame_effects<P: Precision, E: Compiled>(r: &mut Renderer<P, E>, tree: &Tree<'_>) -> Effects {
    r.begin_tree(Effects::from_bits(tree.effects()))
}

/// A full frame into `sink`, each vertex transformed once through a cache
/// in `memory` (see the module docs), drawn by the walk-and-fill compiled
/// without the switched effects that are off for the frame
/// ([`for_frame`]). `MEMORY`: whether the caller may give memory at all
/// (`false`: `memory` is ignored, and the code without a cache is compiled
/// without its tests, as when it was inlined into a caller passing none).
#[allow(clippy::too_many_arguments)]
pub(crate) fn draw_direct<P, E, K, Pr, const N: usize, const V: usize, const MEMORY: bool>(
    tree: &Tree<'_>,
    frame: &Frame,
    r: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    ids: FaceIds,
    memory: &mut [u32],
    sink: &mut K,
    probe: &Pr,
) -> Result<RenderStats, OrderError>
where
    P: Precision,
    E: Compiled,
    K: SpanSink,
    Pr: Probe,
{
    let active = frame_effects(r, tree);
    let code = Direct::<'_, '_, '_, P, E, K, Pr, N, V, MEMORY> {
        tree,
        frame,
        r,
        scratch,
        ids,
        memory,
        sink,
        probe,
        active,
    };
    for_frame::<E, _>(active, code)
}

/// The arguments of [`draw_direct`], handed to the code [`for_frame`]
/// picks.
struct Direct<
    'x,
    't,
    'p,
    P: Precision,
    E: Compiled,
    K,
    Pr,
    const N: usize,
    const V: usize,
    const MEMORY: bool,
> {
    tree: &'x Tree<'t>,
    frame: &'x Frame,
    r: &'x mut Renderer<P, E>,
    scratch: &'x mut Scratch<P, V>,
    ids: FaceIds,
    memory: &'x mut [u32],
    sink: &'x mut K,
    probe: &'p Pr,
    active: Effects,
}

impl<P, E, K, Pr, const N: usize, const V: usize, const MEMORY: bool> ForPipeline
    for Direct<'_, '_, '_, P, E, K, Pr, N, V, MEMORY>
where
    P: Precision,
    E: Compiled,
    K: SpanSink,
    Pr: Probe,
{
    type Output = Result<RenderStats, OrderError>;

    #[inline(always)]
    fn run<X: Compiled>(self) -> Self::Output {
        let Direct {
            tree,
            frame,
            r,
            scratch,
            ids,
            memory,
            sink,
            probe,
            active,
        } = self;
        let memory = if MEMORY { memory } else { &mut [] };
        direct_as::<P, E, X, K, Pr, N, V>(
            tree,
            frame,
            r,
            scratch,
            (ids, memory),
            sink,
            probe,
            active,
        )
    }
}

/// [`draw_direct`] compiled for pipeline `X`. Out of line: a frame of
/// `E` with an effect off and a frame of the pipeline built without it
/// run one and the same function body (compiled twice, identically), not
/// copies inlined into different callers. The references are parameters,
/// not fields of one struct, so that the compiler knows they do not alias
/// (it reloaded the renderer's fields after every span otherwise: +3.8 %
/// on `bench_city`).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn direct_as<P, E, X, K, Pr, const N: usize, const V: usize>(
    tree: &Tree<'_>,
    frame: &Frame,
    r: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    (ids, memory): (FaceIds, &mut [u32]),
    sink: &mut K,
    probe: &Pr,
    active: Effects,
) -> Result<RenderStats, OrderError>
where
    P: Precision,
    E: Compiled,
    X: Compiled,
    K: SpanSink,
    Pr: Probe,
{
    let (source, fx, turn) = begin_frame::<P, E, X>(r, tree, frame, active);
    let limit = memory.len();
    let (mut cache, _) = take_cache(memory, tree, (cacheable::<P, E, X>(r), true), limit);
    prefill(r, tree, source, &mut cache);
    let reach = r.viewport_bounds().intersect(&sink.bounds());
    let mut spans = 0;
    Order::<N>::check_depth(tree)?;
    let mut order = Order::<N>::unchecked(tree, frame.view, fx.cull, &[]);
    let dec = walk_decoder::<P>(tree, source);
    let mut walk = Walk {
        tree,
        dec: &dec,
        source,
        fx,
        ids: Some(ids),
        cache: &mut cache,
        turn,
    };
    walk.run::<P, E, X, Pr, N, V, true>(
        &mut order,
        r,
        scratch,
        probe,
        true,
        || reach,
        |r, s, ready, _, face, _| {
            spans += fill::<P, E, X, K, Pr, V>(r, s, ready, face, sink, probe);
            Step::Next
        },
    );
    let mut stats = r.stats();
    stats.spans = spans;
    stats.walks = 1;
    stats.memory_used = cache.words() as u32;
    Ok(stats)
}

mod bands;
mod setup;
pub(crate) use bands::{bands_into, draw_bands, BandStore};
use setup::{begin_frame, prefill, take_cache, walk_decoder, Arm, Source};
