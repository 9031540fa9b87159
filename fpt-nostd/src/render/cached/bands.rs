//! The band half of the cached pipeline: the frame's walk (in
//! `cached.rs`) has filled the display list and the vertex cache once;
//! [`draw_bands`] and [`bands_into`] replay the list band by band
//! (`replay`), carrying the triangles, quads and polygons a band cuts
//! into the next (`crate::raster::carry`), and hand each finished band to
//! the caller's [`BandStore`]. Split out of `cached.rs`, whose module
//! docs state the contract.

use core::cell::Cell;
use core::marker::PhantomData;

use super::super::probe::{Phase, Probe};
use super::super::{BandBuffer, FaceIds, Frame, RenderError};
use super::{
    begin_frame, cacheable, fill, frame_effects, prefill, take_cache, walk_decoder, Step, Walk,
};
use crate::effects::{for_frame, Compiled, Effects, ForPipeline};
use crate::order::{memo_words, Order, MEMO};
use crate::raster::carry::{Ring, CARRY, NEED_KEPT, WORDS as CARRY_WORDS};
use crate::raster::list::{DisplayList, Entry, Points};
use crate::raster::renderer::{vertex_indices, Face, Ready};
use crate::raster::transform::ScreenPt;
use crate::raster::{
    Band, Framebuffer, PixelFormat, Precision, RenderStats, Renderer, Scratch, SpanBounds, SpanSink,
};
use crate::reader::Tree;

mod replay;
use replay::replay;

/// The record of a polygon of rows `first..end` that does not take the
/// list's common one (clipped, with ids or outlines, or a polygon index
/// past 16 bits), pushed by the band walk: `ready` and `face` as prepared,
/// `poly` its index when every vertex is cached. Out of line: inlined in
/// the walk's callback, its set-up was computed beside the common record's
/// for every polygon.
#[inline(never)]
fn push_other<P: Precision, const V: usize>(
    list: &mut DisplayList<'_>,
    (first, end): (i32, i32),
    ready: &Ready,
    face: &Face,
    poly: Option<u32>,
    (tree, s): (&Tree<'_>, &mut Scratch<P, V>),
) -> bool {
    let e = Entry {
        first,
        end,
        rgb: ready.rgb,
        id: face.id,
        hidden: face.hidden_edges,
        clipped: ready.clipped,
    };
    let pts = match poly {
        Some(i) if i <= u32::from(u16::MAX) => Points::Polygon(i as u16),
        Some(i) => {
            // The band walk loads without the indices
            // (`Renderer::load_cached_bare`): from the tree.
            vertex_indices(tree, i, s.active_mut());
            Points::Indices(s.active().get(..ready.n).unwrap_or(&[]))
        }
        None => Points::Inline(s.screen().get(..ready.n).unwrap_or(&[])),
    };
    list.push(&e, pts)
}

/// Band `y0` (of `rows` rows in a `size` frame) as a framebuffer over
/// `buf`, cleared to `background`.
fn open_band<'b, F: PixelFormat>(
    buf: &'b mut [F::Word],
    (w, h): (i32, i32),
    rows: i32,
    y0: i32,
    background: F::Color,
) -> Result<Framebuffer<'b, F>, RenderError> {
    let n = rows.min(h - y0) as u32;
    let mut fb = Framebuffer::<F>::new(buf, w as u32, n).map_err(RenderError::Band)?;
    fb.fill_all(background);
    Ok(fb)
}

/// A frame band by band through `band`'s buffer, with one walk per group
/// of bands whose polygons fit the display list in `memory` (see the module
/// docs); each finished band goes to `emit` with its first row (`emit`
/// returning `false` ends the frame there, with the counters so far), outside
/// the probe's measurement.
#[allow(clippy::too_many_arguments)]
pub(crate) fn draw_bands<P, E, F, Pr, const N: usize, const V: usize>(
    tree: &Tree<'_>,
    frame: &Frame,
    r: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    ids: FaceIds,
    memory: &mut [u32],
    band: BandBuffer<'_, F>,
    probe: &Pr,
    emit: impl FnMut(i32, &Framebuffer<'_, F>) -> bool,
) -> Result<RenderStats, RenderError>
where
    P: Precision,
    E: Compiled,
    F: PixelFormat,
    Pr: Probe,
{
    let BandBuffer {
        buf,
        rows,
        background,
    } = band;
    let mut one = OneBuffer {
        buf: Some(buf),
        emit,
    };
    let out = bands::<P, E, F, _, Pr, N, V>(
        tree,
        frame,
        r,
        scratch,
        (ids, memory),
        (rows, background),
        &mut one,
        probe,
    );
    if out.is_err() {
        // Every error leaves the probe running.
        probe.stop();
    }
    out
}

/// Where the band loop takes the storage of each band and where it
/// hands the finished band: one buffer reused for every band
/// ([`OneBuffer`]), or two in turns while a display transfer sends the
/// other (`render::double`).
pub(crate) trait BandStore<'b, F: PixelFormat> {
    /// The storage for the next band; `None` ends the frame.
    fn take(&mut self) -> Option<&'b mut [F::Word]>;
    /// Band `y` is finished in `fb`; `false` ends the frame.
    fn emit(&mut self, y: i32, fb: Framebuffer<'b, F>) -> bool;
}

/// One band buffer, lent to `emit` for each finished band and reused.
struct OneBuffer<'b, F: PixelFormat, X> {
    buf: Option<&'b mut [F::Word]>,
    emit: X,
}

impl<'b, F: PixelFormat, X> BandStore<'b, F> for OneBuffer<'b, F, X>
where
    X: FnMut(i32, &Framebuffer<'_, F>) -> bool,
{
    fn take(&mut self) -> Option<&'b mut [F::Word]> {
        self.buf.take()
    }

    fn emit(&mut self, y: i32, fb: Framebuffer<'b, F>) -> bool {
        let go = (self.emit)(y, &fb);
        self.buf = Some(fb.into_storage());
        go
    }
}

/// [`draw_bands`] with the bands' storage from `store` and `rows` rows a
/// band cleared to `background`; the probe is left running on an error.
#[allow(clippy::too_many_arguments)]
pub(crate) fn bands_into<'b, P, E, F, S, const N: usize, const V: usize>(
    tree: &Tree<'_>,
    frame: &Frame,
    r: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    (ids, memory): (FaceIds, &mut [u32]),
    (rows, background): (u32, F::Color),
    store: &mut S,
) -> Result<RenderStats, RenderError>
where
    P: Precision,
    E: Compiled,
    F: PixelFormat,
    S: BandStore<'b, F>,
{
    bands::<P, E, F, S, super::super::NoProbe, N, V>(
        tree,
        frame,
        r,
        scratch,
        (ids, memory),
        (rows, background),
        store,
        &super::super::NoProbe,
    )
}

/// [`draw_bands`] but for stopping the probe on an error: the frame's
/// effects settled, the bands drawn by the code compiled without the
/// switched effects that are off ([`for_frame`]).
#[allow(clippy::too_many_arguments)]
fn bands<'b, P, E, F, S, Pr, const N: usize, const V: usize>(
    tree: &Tree<'_>,
    frame: &Frame,
    r: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    (ids, memory): (FaceIds, &mut [u32]),
    (rows, background): (u32, F::Color),
    store: &mut S,
    probe: &Pr,
) -> Result<RenderStats, RenderError>
where
    P: Precision,
    E: Compiled,
    F: PixelFormat,
    S: BandStore<'b, F>,
    Pr: Probe,
{
    // The caller has started the probe (before its own set-up).
    probe.enter(Phase::Xform);
    let active = frame_effects(r, tree);
    let code = Bands::<'_, '_, '_, 'b, P, E, F, S, Pr, N, V> {
        tree,
        frame,
        r,
        scratch,
        ids,
        memory,
        rows,
        background,
        store,
        probe,
        active,
        band: PhantomData,
    };
    for_frame::<E, _>(active, code)
}

/// The arguments of [`bands`], handed to the code [`for_frame`] picks.
struct Bands<'x, 't, 'p, 'b, P, E, F, S, Pr, const N: usize, const V: usize>
where
    P: Precision,
    E: Compiled,
    F: PixelFormat,
{
    tree: &'x Tree<'t>,
    frame: &'x Frame,
    r: &'x mut Renderer<P, E>,
    scratch: &'x mut Scratch<P, V>,
    ids: FaceIds,
    memory: &'x mut [u32],
    rows: u32,
    background: F::Color,
    store: &'x mut S,
    probe: &'p Pr,
    active: Effects,
    /// The lifetime of the bands' storage (`S: BandStore<'b, F>`).
    band: PhantomData<&'b ()>,
}

impl<'b, P, E, F, S, Pr, const N: usize, const V: usize> ForPipeline
    for Bands<'_, '_, '_, 'b, P, E, F, S, Pr, N, V>
where
    P: Precision,
    E: Compiled,
    F: PixelFormat,
    S: BandStore<'b, F>,
    Pr: Probe,
{
    type Output = Result<RenderStats, RenderError>;

    #[inline(always)]
    fn run<X: Compiled>(self) -> Self::Output {
        let Bands {
            tree,
            frame,
            r,
            scratch,
            ids,
            memory,
            rows,
            background,
            store,
            probe,
            active,
            band: _,
        } = self;
        bands_as::<P, E, X, F, S, Pr, N, V>(
            tree,
            frame,
            r,
            scratch,
            (ids, memory),
            (rows, background),
            store,
            (probe, active),
        )
    }
}

/// [`bands`] compiled for pipeline `X`; out of line and with its
/// references as parameters, as [`direct_as`](super::direct_as).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn bands_as<'b, P, E, X, F, S, Pr, const N: usize, const V: usize>(
    tree: &Tree<'_>,
    frame: &Frame,
    r: &mut Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    (ids, memory): (FaceIds, &mut [u32]),
    (rows, background): (u32, F::Color),
    store: &mut S,
    (probe, active): (&Pr, Effects),
) -> Result<RenderStats, RenderError>
where
    P: Precision,
    E: Compiled,
    X: Compiled,
    F: PixelFormat,
    S: BandStore<'b, F>,
    Pr: Probe,
{
    let (source, fx, turn) = begin_frame::<P, E, X>(r, tree, frame, active);
    let outlines = r.effects_as::<X>().contains(Effects::OUTLINE);
    // A frame that walks the tree more than once tests each plane once:
    // the facing memo comes first (a few dozen words), when the memory
    // has room for it beside a cache and the walk uses memos (`MEMO`:
    // cores without an FPU).
    let memo_n = memo_words(tree);
    let memo_n = if MEMO && memory.len() >= 8 * memo_n {
        memo_n
    } else {
        0
    };
    let (memo, memory) = memory.split_at_mut(memo_n);
    memo.fill(0);
    let memo = Cell::from_mut(&mut *memo).as_slice_of_cells();
    // Made once a frame and restarted for every walk (it is large).
    Order::<N>::check_depth(tree).map_err(RenderError::Order)?;
    let mut order = Order::<N>::unchecked(tree, frame.view, fx.cull, memo);
    // The cache takes at most three quarters of the memory (the list the
    // rest): a vertex missing from the cache is transformed again by each
    // of its polygons in every walk, which costs more than the walk a
    // smaller list adds (measured on a Cortex-M0, docs/small-ram.md).
    let most = memory.len() - memory.len() / 4;
    // Indexed only: the display list records polygons by vertex index
    // for the replay, which a tagged cache may have evicted by then.
    let (mut cache, rest) = take_cache(memory, tree, (cacheable::<P, E, X>(r), false), most);
    prefill(r, tree, source, &mut cache);
    let list_words = bytemuck::cast_slice_mut(rest);
    let needs_id = <Band<'_, Framebuffer<'_, F>> as SpanSink>::NEEDS_ID;
    let mut list = DisplayList::new(list_words, needs_id, outlines);
    let screen = r.viewport_bounds();
    let (w, h) = (screen.x1, screen.y1);
    let rows = rows.clamp(1, h.max(1) as u32) as i32;
    let mut spans = 0u64;
    let mut stats: Option<RenderStats> = None;
    let mut y = 0;
    let mut walks = 0;
    // Triangles cut by a band's end, kept for the next band of the same
    // walk in the words the list leaves ([`crate::raster::carry`]).
    let mut ring = Ring::new();
    let dec = walk_decoder::<P>(tree, source);
    while y < h {
        walks += 1;
        list.clear();
        ring.clear();
        // The list does not keep colour planes: with smooth shading every
        // band is filled as its walk goes (one walk per band).
        let smooth = X::SET.contains(Effects::SMOOTH) && fx.smooth;
        let cut = Cell::new(if smooth { y + rows } else { h });
        // The records a band, counted as the walk pushes them, for the
        // band index (a pass over the records less).
        list.tally_bands(y, rows, cut.get());
        // The list overflowed for band `y` alone: the rest of this walk
        // fills it directly.
        let mut direct = smooth;
        probe.enter(Phase::Fill);
        let Some(buf) = store.take() else {
            probe.stop();
            return Ok(stats.unwrap_or_default());
        };
        let mut fb = open_band::<F>(buf, (w, h), rows, y, background)?;
        let mut walk = Walk {
            tree,
            dec: &dec,
            source,
            fx,
            // A sink without ids reads none: the id of each walked
            // polygon (its source field, for `FaceIds::Source`) cost the
            // band walk 16 instructions a polygon, kept for nothing.
            ids: needs_id.then_some(ids),
            cache: &mut cache,
            turn,
        };
        let reach = || SpanBounds {
            y0: y,
            y1: cut.get(),
            ..screen
        };
        walk.run::<P, E, X, Pr, N, V, false>(
            &mut order,
            r,
            scratch,
            probe,
            stats.is_none(),
            reach,
            |r, s, ready, poly, face, cache| {
                if direct {
                    let band = &mut Band::new(&mut fb, y);
                    spans += fill::<P, E, X, _, Pr, V>(r, s, ready, face, band, probe);
                    return Step::Next;
                }
                let (first, end) = (ready.first.clamp(0, h), ready.end.clamp(0, h));
                loop {
                    // The common record straight from the parts, the
                    // entry made only for the others.
                    let short = match poly {
                        Some(i) if i <= u32::from(u16::MAX) && !ready.clipped => {
                            list.push_polygon((first, end), ready.rgb, i as u16)
                        }
                        _ => None,
                    };
                    let pushed = short.unwrap_or_else(|| {
                        push_other(&mut list, (first, end), ready, face, poly, (tree, s))
                    });
                    if pushed {
                        return Step::Next;
                    }
                    let left = (cut.get() - y + rows - 1) / rows;
                    if left <= 1 {
                        break;
                    }
                    // Keep the top five sixths of the bands still
                    // covered: a larger step wastes a walk whenever a bit
                    // more would have fitted, a smaller one costs more
                    // overflows, each a pass over the list (measured on a
                    // Cortex-M0, socket, 8-row bands in 1,635 words, median
                    // frame: 3/4 11.79 M, 5/6 10.64 M, 7/8 10.77 M, 9/10
                    // 10.89 M, 15/16 11.06 M; docs/small-ram.md).
                    cut.set(y + rows * (left * 5 / 6).clamp(1, left - 1));
                    list.retain_rows_below(cut.get());
                    if first >= cut.get() {
                        return Step::Next;
                    }
                }
                // Not even band `y` fits: draw what is recorded into it, then
                // this polygon (prepared again: the replay used the scratch)
                // and the rest of the walk straight into it.
                probe.enter(Phase::Fill);
                // The replay uses the scratch, where this polygon's points
                // are: on cores with an FPU they are kept aside and put
                // back for its fill, so that the walk's callback never asks
                // for a polygon again (the walk's loop without that path
                // measured 3 % cheaper on socket's 16-row bands); the
                // Cortex-M0 prepares it again (no stack for the copy).
                let mut kept = [ScreenPt::default(); V];
                let n = ready.n.min(V);
                if CARRY {
                    if let (Some(k), Some(p)) = (kept.get_mut(..n), s.screen().get(..n)) {
                        k.copy_from_slice(p);
                    }
                }
                // The replay scans the groups (no band index).
                list.seal();
                spans += replay::<P, E, X, _, V>(
                    r,
                    s,
                    tree,
                    &list,
                    cache,
                    (y, y + rows),
                    &mut Band::new(&mut fb, y),
                    (&mut Ring::new(), &mut [], false),
                );
                list.clear();
                direct = true;
                if !CARRY {
                    return Step::Again;
                }
                if let (Some(p), Some(k)) = (s.screen_mut().get_mut(..n), kept.get(..n)) {
                    p.copy_from_slice(k);
                }
                let band = &mut Band::new(&mut fb, y);
                spans += fill::<P, E, X, _, Pr, V>(r, s, ready, face, band, probe);
                Step::Next
            },
        );
        if stats.is_none() {
            stats = Some(r.stats());
        }
        // Band `y`, opened and cleared before the walk: filled during it
        // (`direct`, and then `cut` is its end) or from the list now.
        if !direct {
            probe.enter(Phase::Fill);
            // Each band then reads only its own records (when the words
            // the list leaves hold the index; else it scans, as before).
            if cut.get() > y + rows {
                list.index_bands(y, rows, cut.get());
            }
            let mut sink = Band::new(&mut fb, y);
            let keep = y + rows < cut.get();
            let (view, words) = list.replay_parts();
            let carry = (&mut ring, words, keep);
            let band = (y, y + rows);
            spans +=
                replay::<P, E, X, _, V>(r, scratch, tree, &view, &cache, band, &mut sink, carry);
        }
        probe.stop();
        if !store.emit(y, fb) {
            return Ok(stats.unwrap_or_default());
        }
        probe.start(Phase::Fill);
        let mut y0 = y + rows;
        while y0 < cut.get() {
            probe.enter(Phase::Fill);
            let Some(buf) = store.take() else {
                probe.stop();
                return Ok(stats.unwrap_or_default());
            };
            let mut fb = open_band::<F>(buf, (w, h), rows, y0, background)?;
            let mut sink = Band::new(&mut fb, y0);
            let keep = y0 + rows < cut.get();
            let (view, words) = list.replay_parts();
            let carry = (&mut ring, words, keep);
            let band = (y0, y0 + rows);
            spans +=
                replay::<P, E, X, _, V>(r, scratch, tree, &view, &cache, band, &mut sink, carry);
            probe.stop();
            if !store.emit(y0, fb) {
                return Ok(stats.unwrap_or_default());
            }
            probe.start(Phase::Fill);
            y0 += rows;
        }
        y = cut.get();
    }
    probe.stop();
    let mut stats = stats.unwrap_or_default();
    stats.spans = spans;
    stats.walks = walks;
    // The ring's states beyond `NEED_KEPT` are counted as unused: the
    // ring takes only the words left, so fewer cost speed, not a picture.
    list.note_spare_used(ring.most().min(NEED_KEPT) * CARRY_WORDS);
    stats.memory_used = (memo_n + cache.words() + list.peak().div_ceil(2)) as u32;
    Ok(stats)
}
