//! Scanline fill: active-edge list, exact crossings, spans to a sink.
//!
//! Contract of [`fill_polygon`]:
//! * Input: a closed polygon in screen space (`2^-sub` pixel units), convex
//!   or concave, simple or not; at most 65 535 vertices and no more than
//!   the scratch (`edges`, `active`) holds.
//! * Coverage: pixel `(i, j)` is covered when its centre `(i+½, j+½)` has a
//!   winding number that is "inside" under the [`FillRule`], with edge
//!   ownership per the rules in [`super::edge`] (on-edge centres belong to
//!   the polygon on the edge's right; on a horizontal boundary to the
//!   polygon below). For simple polygons both rules agree.
//! * Output: disjoint spans `[x0, x1)` per row, left to right, rows top to
//!   bottom, each non-empty and inside [`SpanSink::bounds`]; a pixel is
//!   reported at most once per polygon. Rows outside the bounds cost
//!   nothing (edges start directly at the first row in bounds), so a band
//!   renderer pays per band only for the polygons that reach it.

use super::chain::{fill_monotone, fill_triangle};
use super::edge::{build_edges_with, packs, Dda32, Edge, Stepper, SMALL};
use super::transform::ScreenPt;
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

/// Which winding numbers are inside.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FillRule {
    /// Inside when the winding number is non-zero.
    #[default]
    NonZero,
    /// Inside when the winding number is odd.
    EvenOdd,
}

impl FillRule {
    #[inline]
    fn inside(self, winding: i32) -> bool {
        match self {
            FillRule::NonZero => winding != 0,
            FillRule::EvenOdd => winding & 1 != 0,
        }
    }
}

/// A half-open pixel rectangle `[x0, x1) × [y0, y1)` in frame coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpanBounds {
    /// First column.
    pub x0: i32,
    /// First row.
    pub y0: i32,
    /// Column after the last.
    pub x1: i32,
    /// Row after the last.
    pub y1: i32,
}

impl SpanBounds {
    /// The rectangle `[0, width) × [0, height)`.
    pub fn of_size(width: u32, height: u32) -> SpanBounds {
        let c = |v: u32| v.min(i32::MAX as u32) as i32;
        SpanBounds {
            x0: 0,
            y0: 0,
            x1: c(width),
            y1: c(height),
        }
    }

    /// The intersection with `o` (possibly empty).
    pub fn intersect(&self, o: &SpanBounds) -> SpanBounds {
        SpanBounds {
            x0: self.x0.max(o.x0),
            y0: self.y0.max(o.y0),
            x1: self.x1.min(o.x1),
            y1: self.y1.min(o.y1),
        }
    }

    /// True when no pixel is inside.
    pub fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }
}

/// What a polygon paints: its shaded colour and its identity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Paint {
    /// The shaded colour.
    pub rgb: Rgb888,
    /// The polygon id (id buffers store `id + 1`, keeping 0 for "empty").
    pub id: u32,
}

/// `rgb` as a word of 24 bits (red lowest), the default colour word of a
/// polygon kept between bands ([`SpanSink::keep_color`]).
#[inline(always)]
pub(crate) fn rgb_word(rgb: Rgb888) -> u32 {
    u32::from(rgb.r()) | u32::from(rgb.g()) << 8 | u32::from(rgb.b()) << 16
}

/// The colour [`rgb_word`] made `w` from (bits 24 up ignored).
#[inline(always)]
pub(crate) fn word_rgb(w: u32) -> Rgb888 {
    Rgb888::new(w as u8, (w >> 8) as u8, (w >> 16) as u8)
}

/// Receives the spans of filled polygons.
///
/// The fill calls [`SpanSink::color`] once per polygon and then
/// [`SpanSink::span`] for each span, with `bounds().y0 ≤ y < bounds().y1`
/// and `bounds().x0 ≤ x0 < x1 ≤ bounds().x1`. Implementations should still
/// clip defensively (cheap, and keeps a buggy caller from panicking them).
pub trait SpanSink {
    /// The sink's native colour, converted once per polygon (compared by
    /// smooth shading, [`super::gouraud`], to paint runs of equal colour).
    type Color: Copy + PartialEq;
    /// Whether [`SpanSink::color`] reads [`Paint::id`]. Band rendering's
    /// display list stores each polygon's id only for sinks that do
    /// (2 bytes a polygon less for a plain framebuffer).
    const NEEDS_ID: bool = true;
    /// Converts a polygon's paint to the native colour.
    fn color(&self, paint: &Paint) -> Self::Color;
    /// `color`, the native colour of `paint`, as a word of at most 24
    /// bits for a polygon the band replay keeps from one band to the next
    /// (`raster::carry`), which [`SpanSink::kept_color`] turns back into
    /// the colour: by default the paint's rgb packed in a word, converted
    /// again; a sink whose colours fit the word keeps them as they are,
    /// so that a resumed polygon paints without converting (a `Rgb565`
    /// from its rgb took 20 instructions a resume).
    #[inline(always)]
    fn keep_color(&self, color: Self::Color, paint: &Paint) -> u32 {
        let _ = color;
        rgb_word(paint.rgb)
    }
    /// The colour a word of [`SpanSink::keep_color`] keeps (for a paint
    /// without id: the band replay keeps polygons only for sinks that
    /// paint without ids).
    #[inline(always)]
    fn kept_color(&self, word: u32) -> Self::Color {
        self.color(&Paint {
            rgb: word_rgb(word),
            id: 0,
        })
    }
    /// The pixels this sink can receive, in frame coordinates.
    fn bounds(&self) -> SpanBounds;
    /// Paints pixels `x0..x1` of row `y`.
    fn span(&mut self, y: i32, x0: i32, x1: i32, color: Self::Color);
    /// Paints one span a row on rows `y`, `y + 1`, … as `spans` yields
    /// them (`x0 ≥ x1`: nothing on that row), consuming `spans` to its end
    /// (the fill steps its edges as it yields); returns how many were not
    /// empty. The fill's row loops call this, with every span within
    /// [`SpanSink::bounds`], rather than [`SpanSink::span`] once a row: a
    /// sink that knows its rows' layout keeps a row pointer instead of
    /// computing and checking each row's address again (the
    /// framebuffers do). The default calls [`SpanSink::span`].
    #[inline(always)]
    fn span_rows<I: Iterator<Item = (i32, i32)>>(
        &mut self,
        y: i32,
        spans: I,
        color: Self::Color,
    ) -> usize {
        let mut n = 0;
        let mut row = y;
        for (x0, x1) in spans {
            if x0 < x1 {
                self.span(row, x0, x1, color);
                n += 1;
            }
            row = row.wrapping_add(1);
        }
        n
    }
}

impl<K: SpanSink + ?Sized> SpanSink for &mut K {
    type Color = K::Color;
    const NEEDS_ID: bool = K::NEEDS_ID;
    fn color(&self, paint: &Paint) -> K::Color {
        (**self).color(paint)
    }
    #[inline(always)]
    fn keep_color(&self, color: K::Color, paint: &Paint) -> u32 {
        (**self).keep_color(color, paint)
    }
    #[inline(always)]
    fn kept_color(&self, word: u32) -> K::Color {
        (**self).kept_color(word)
    }
    fn bounds(&self) -> SpanBounds {
        (**self).bounds()
    }
    fn span(&mut self, y: i32, x0: i32, x1: i32, color: K::Color) {
        (**self).span(y, x0, x1, color)
    }
    #[inline(always)]
    fn span_rows<I: Iterator<Item = (i32, i32)>>(
        &mut self,
        y: i32,
        spans: I,
        color: K::Color,
    ) -> usize {
        (**self).span_rows(y, spans, color)
    }
}

/// Why [`fill_polygon`] could not run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FillError {
    /// More vertices than the scratch buffers (or 65 535) allow.
    Capacity,
}

/// Fills polygon `pts` (screen space, `sub` sub-pixel bits) into `sink`,
/// restricted to `clip ∩ sink.bounds()`. `edges` and `active` are scratch
/// with at least `pts.len()` entries. Returns the number of spans emitted.
#[allow(clippy::too_many_arguments)]
pub fn fill_polygon<K: SpanSink>(
    pts: &[ScreenPt],
    sub: u32,
    rule: FillRule,
    clip: &SpanBounds,
    edges: &mut [Edge],
    active: &mut [u16],
    color: K::Color,
    sink: &mut K,
) -> Result<usize, FillError> {
    fill_polygon_in(pts, None, sub, rule, clip, edges, active, color, sink)
}

/// A polygon's bounding box (screen units) and the index of its first
/// lowest vertex: the fill's first pass, which a caller that needs the
/// box itself computes once and hands to [`fill_polygon_in`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bbox {
    pub(crate) lo: i32,
    pub(crate) hi: i32,
    pub(crate) top: i32,
    pub(crate) bot: i32,
    pub(crate) top_at: usize,
}

impl Bbox {
    /// The box of `pts` (empty: `lo > hi`, `top > bot`).
    #[inline]
    pub(crate) fn of(pts: &[ScreenPt]) -> Bbox {
        let mut b = Bbox {
            lo: i32::MAX,
            hi: i32::MIN,
            top: i32::MAX,
            bot: i32::MIN,
            top_at: 0,
        };
        for (i, p) in pts.iter().enumerate() {
            b.lo = b.lo.min(p.x);
            b.hi = b.hi.max(p.x);
            if p.y < b.top {
                b.top = p.y;
                b.top_at = i;
            }
            b.bot = b.bot.max(p.y);
        }
        b
    }

    /// [`Bbox::of`] with its loop seeded by the first point (one point
    /// fewer through it): the same box. The walk's preparation of every
    /// polygon takes it (`Renderer::shade_ready`); measured (session 17,
    /// firmware frame sets, every checksum equal): band frames 7–31 k
    /// instructions cheaper a view (bench_city 26–31 k), full frames
    /// 0.6–3.2 k dearer. The other callers keep [`Bbox::of`]: seeded in the
    /// fill's own box (`fill_polygon_in`, the band replay's path) the full
    /// frames cost 17–25 k more; in the carry's set-ups it compiled to the
    /// same counts; as `enumerate().skip(1)` or in pairs every frame cost
    /// 21–109 k more (the loop's shape, not its work).
    #[inline]
    pub(crate) fn seeded(pts: &[ScreenPt]) -> Bbox {
        let Some((p0, rest)) = pts.split_first() else {
            return Bbox::of(pts);
        };
        let mut b = Bbox {
            lo: p0.x,
            hi: p0.x,
            top: p0.y,
            bot: p0.y,
            top_at: 0,
        };
        for (i, p) in rest.iter().enumerate() {
            b.lo = b.lo.min(p.x);
            b.hi = b.hi.max(p.x);
            if p.y < b.top {
                b.top = p.y;
                b.top_at = i + 1;
            }
            b.bot = b.bot.max(p.y);
        }
        b
    }

    /// The `top` and `bot` of [`Bbox::of`] alone: one pass over the
    /// points' `y`, seeded by the first point. The band walk's preparation
    /// takes it (`Renderer::shade_ready` without the box): its display
    /// list records a polygon's rows, never its box, so the walk's box was
    /// thrown away. Measured (session 19, firmware band set, every
    /// checksum equal): bench_city −55.6 to −62.0 k instructions a view,
    /// house −39.0 to −42.5 k, vise −15.5 to −19.7 k.
    #[inline]
    pub(crate) fn rows(pts: &[ScreenPt]) -> (i32, i32) {
        let Some((p0, rest)) = pts.split_first() else {
            return (i32::MAX, i32::MIN);
        };
        let (mut top, mut bot) = (p0.y, p0.y);
        for p in rest {
            top = top.min(p.y);
            bot = bot.max(p.y);
        }
        (top, bot)
    }
}

/// [`fill_polygon`] with `pts`' box if already computed (`Bbox::of(pts)`;
/// else computed here when needed: a triangle does not need it).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(crate) fn fill_polygon_in<K: SpanSink>(
    pts: &[ScreenPt],
    bbox: Option<&Bbox>,
    sub: u32,
    rule: FillRule,
    clip: &SpanBounds,
    edges: &mut [Edge],
    active: &mut [u16],
    color: K::Color,
    sink: &mut K,
) -> Result<usize, FillError> {
    if pts.len() > u16::MAX as usize || active.len() < pts.len() {
        return Err(FillError::Capacity);
    }
    let b = clip.intersect(&sink.bounds());
    if b.is_empty() || pts.len() < 3 {
        return Ok(0);
    }
    // Triangles (most polygons of a tessellated mesh) within ±SMALL take
    // the shortest set-up of the same spans, before the box rejects below:
    // a triangle that misses `b` emits nothing there either, and costs
    // about what the rejects would. (With the general path's capacity
    // check, so that the outcome is the same.)
    if let [p0, p1, p2] = *pts {
        // The walk's box, when it handed one, answers in four comparisons
        // what six magnitudes would (session 21: socket −20 k a frame).
        let near = |p: ScreenPt| p.x.abs() < SMALL && p.y.abs() < SMALL;
        let small = match bbox {
            Some(b) => b.lo > -SMALL && b.hi < SMALL && b.top > -SMALL && b.bot < SMALL,
            None => near(p0) && near(p1) && near(p2),
        };
        if packs(sub) && edges.len() >= 3 && small {
            return Ok(fill_triangle([p0, p1, p2], sub, &b, color, sink));
        }
    }
    let bbox = &match bbox {
        Some(b) => *b,
        None => Bbox::of(pts),
    };
    // Cheap reject on the horizontal extent (rows are handled by the edge
    // setup): crossing columns are ceil(x − ½), monotone in x.
    let Bbox {
        lo, hi, top, bot, ..
    } = *bbox;
    // The bounding box decides the 32-bit edge setup (see Edge::new_small),
    // and the arithmetic of the two rejects below: with every coordinate
    // within ±SMALL (and `sub ≤ 8`) they fit in 32 bits, which a 32-bit
    // core shifts in one instruction instead of a 64-bit sequence. The
    // chains step their edges as `Packed`, exact where `packs(sub)` holds:
    // only there (3 or 4 sub-pixel bits, the default) is a polygon `small`.
    let small = lo > -SMALL && hi < SMALL && top > -SMALL && bot < SMALL && packs(sub);
    // col(x) = floor((x − ½ pixel) in pixels) (an arithmetic shift is a
    // floor division by 2^(sub+1)); every crossing lies in
    // [col(lo), col(hi) + 1].
    let (col_lo, col_hi) = if small {
        let col = |x: i32| i64::from((2 * x - (1 << sub)) >> (sub + 1));
        (col(lo), col(hi))
    } else {
        let col = |x: i32| (2 * x as i64 - (1i64 << sub)) >> (sub + 1);
        (col(lo), col(hi))
    };
    if col_hi < b.x0 as i64 || col_lo >= b.x1 as i64 {
        return Ok(0);
    }
    // Same on rows, before any edge setup: the polygon's active rows are
    // within Edge::rows(top, bottom), so a band it misses costs one pass
    // over the vertices.
    let (top_pt, bot_pt) = (ScreenPt { x: 0, y: top }, ScreenPt { x: 0, y: bot });
    let (first, end) = if small {
        Dda32::rows(top_pt, bot_pt, sub)
    } else {
        Edge::rows(top_pt, bot_pt, sub)
    };
    if end <= b.y0 || first >= b.y1 {
        return Ok(0);
    }
    if edges.len() < pts.len() {
        return Err(FillError::Capacity);
    }
    if small {
        // Convex and other y-monotone polygons: two chains, no edge list.
        if let Some(spans) = fill_monotone(pts, bbox, sub, &b, color, sink) {
            return Ok(spans);
        }
    }
    let n = build_edges_with(pts, sub, b.y0, b.y1, edges, small).ok_or(FillError::Capacity)?;
    Ok(scan(&mut edges[..n], active, rule, &b, color, sink))
}

/// Rows `[y, stop)` with exactly the two active edges `ia`, `ib`, stepping
/// both to row `stop`. The general walk on two crossings `x_a ≤ x_b` with
/// directions `d_a`, `d_b` starts a span at `x_a` (winding ±1 is inside
/// under both rules) and ends it at `x_b` exactly when the winding
/// `d_a + d_b` is outside: always for opposite directions, only under
/// even-odd for equal ones (winding ±2). So the span is `[min, max)` or
/// nothing for the whole run, whichever crossing comes first.
#[allow(clippy::too_many_arguments)]
// Not inlined: a rare path since the chain walk (`super::chain`) takes
// the common case; kept out of the caller's per-polygon code.
#[inline(never)]
fn two_edge_rows<K: SpanSink>(
    edges: &mut [Edge],
    ia: usize,
    ib: usize,
    rule: FillRule,
    b: &SpanBounds,
    y: i32,
    stop: i32,
    color: K::Color,
    sink: &mut K,
) -> usize {
    let (mut ea, mut eb) = (edges[ia], edges[ib]);
    let pair = if ea.dir != eb.dir || rule == FillRule::EvenOdd {
        Pair::Span
    } else {
        Pair::Step
    };
    if let (Some(mut da), Some(mut db)) = (ea.dda32(), eb.dda32()) {
        // Same loop in 32-bit registers (the usual case on screen).
        let spans = pair_rows(&mut da, &mut db, pair, b, y, stop, color, sink);
        edges[ia].set_dda32(&da);
        edges[ib].set_dda32(&db);
        return spans;
    }
    let spans = pair_rows(&mut ea, &mut eb, pair, b, y, stop, color, sink);
    edges[ia] = ea;
    edges[ib] = eb;
    spans
}

/// What [`pair_rows`] does on each row with the two crossings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Pair {
    /// Nothing: the rows are only stepped.
    Step,
    /// Paints `[min, max)` of the two crossings.
    Span,
    /// Paints `[a, b)`: the caller knows `a`'s crossing is never right of
    /// `b`'s (an empty span when they are equal), so no comparison orders
    /// them.
    Ab,
    /// Paints `[b, a)`, likewise.
    Ba,
    /// [`Pair::Span`] for crossings the caller knows are within `b`'s
    /// columns: not clamped to them.
    Within,
    /// [`Pair::Ab`] for crossings known within `b`'s columns.
    AbWithin,
    /// [`Pair::Ba`] for crossings known within `b`'s columns.
    BaWithin,
}

/// Rows `[y, stop)` between the two steppers `a` and `b`, stepping both to
/// row `stop`: each row's span (per `pair`) clipped to `b`'s columns.
/// Returns the spans emitted. The one row loop of the pairs of edges
/// (`two_edge_rows`, the monotone chains and the triangles,
/// `super::chain`).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn pair_rows<S: Stepper, K: SpanSink>(
    a: &mut S,
    c: &mut S,
    pair: Pair,
    b: &SpanBounds,
    y: i32,
    stop: i32,
    color: K::Color,
    sink: &mut K,
) -> usize {
    // One loop per order, so that no row tests `pair`.
    match pair {
        Pair::Step => {
            for _ in y..stop {
                a.step();
                c.step();
            }
            0
        }
        Pair::Ab => span_run(a, c, true, true, b, y, stop, color, sink),
        Pair::Ba => span_run(c, a, true, true, b, y, stop, color, sink),
        Pair::Span => span_run(a, c, false, true, b, y, stop, color, sink),
        Pair::Within => span_run(a, c, false, false, b, y, stop, color, sink),
        Pair::AbWithin => span_run(a, c, true, false, b, y, stop, color, sink),
        Pair::BaWithin => span_run(c, a, true, false, b, y, stop, color, sink),
    }
}

/// [`pair_rows`] painting `[l, r)` with `l`'s crossing on the left
/// (`ordered`) or the smaller crossing on the left, clamped to `b`'s
/// columns (`clamp`) or known to be within them, through
/// [`SpanSink::span_rows`].
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn span_run<S: Stepper, K: SpanSink>(
    l: &mut S,
    r: &mut S,
    ordered: bool,
    clamp: bool,
    b: &SpanBounds,
    y: i32,
    stop: i32,
    color: K::Color,
    sink: &mut K,
) -> usize {
    let (lo, hi) = (b.x0, b.x1);
    let spans = (y..stop).map(|_| {
        let (xl, xr) = (l.crossing(), r.crossing());
        l.step();
        r.step();
        let (x0, x1) = if ordered || xl <= xr {
            (xl, xr)
        } else {
            (xr, xl)
        };
        if clamp {
            (x0.max(lo), x1.min(hi))
        } else {
            (x0, x1)
        }
    });
    sink.span_rows(y, spans, color)
}

/// The active-edge loop over edges sorted by first row.
pub(super) fn scan<K: SpanSink>(
    edges: &mut [Edge],
    active: &mut [u16],
    rule: FillRule,
    b: &SpanBounds,
    color: K::Color,
    sink: &mut K,
) -> usize {
    let mut spans = 0usize;
    let mut next = 0usize;
    let mut nact = 0usize;
    let Some(first) = edges.first() else {
        return 0;
    };
    let mut y = first.y0;
    while y < b.y1 {
        while next < edges.len() && edges[next].y0 <= y {
            active[nact] = next as u16;
            nact += 1;
            next += 1;
        }
        // Drop edges that ended (half-open: active on y0..y1).
        let mut k = 0;
        while k < nact {
            if edges[active[k] as usize].y1 <= y {
                nact -= 1;
                active[k] = active[nact];
            } else {
                k += 1;
            }
        }
        if nact == 0 {
            match edges.get(next) {
                Some(e) => {
                    y = e.y0;
                    continue;
                }
                None => break,
            }
        }
        if nact == 2 {
            // The common case (every row of a convex polygon, most rows of
            // others): two edges stay active until one ends or another
            // starts, and the rows between are a tight two-DDA loop that
            // gives exactly what the general walk below would.
            let mut stop = b.y1;
            if let Some(e) = edges.get(next) {
                stop = stop.min(e.y0);
            }
            let (ia, ib) = (active[0] as usize, active[1] as usize);
            stop = stop.min(edges[ia].y1).min(edges[ib].y1);
            spans += two_edge_rows(edges, ia, ib, rule, b, y, stop, color, sink);
            y = stop;
            continue;
        }
        // Crossings, then insertion sort by crossing: the order changes
        // little from row to row, so this is close to linear.
        for &i in &active[..nact] {
            let e = &mut edges[i as usize];
            e.x = e.crossing();
        }
        for k in 1..nact {
            let cur = active[k];
            let cx = edges[cur as usize].x;
            let mut m = k;
            while m > 0 && edges[active[m - 1] as usize].x > cx {
                active[m] = active[m - 1];
                m -= 1;
            }
            active[m] = cur;
        }
        // Walk left to right; a span runs from where the winding becomes
        // inside to where it stops being inside. The order among equal
        // crossings does not matter: coverage of pixel i depends only on
        // the multiset of crossings ≤ i.
        let mut winding = 0i32;
        let mut start = 0i32;
        for &i in &active[..nact] {
            let e = &edges[i as usize];
            let was = rule.inside(winding);
            winding += e.dir as i32;
            let now = rule.inside(winding);
            if !was && now {
                start = e.x;
            } else if was && !now {
                let (x0, x1) = (start.max(b.x0), e.x.min(b.x1));
                if x0 < x1 {
                    sink.span(y, x0, x1, color);
                    spans += 1;
                }
            }
        }
        for &i in &active[..nact] {
            edges[i as usize].step();
        }
        y += 1;
    }
    spans
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// `Bbox::seeded` is `Bbox::of` (the walk takes one, the fills the
    /// other, and a polygon's rows and top corner must agree), and
    /// `Bbox::rows` its `top` and `bot` (the band walk's rows): random
    /// point sets of 0 to 11 points, with repeated coordinates (ties for
    /// the lowest point keep the first), every field equal.
    #[test]
    fn seeded_box_equals_the_plain_one() {
        let mut rng = super::super::tests::Rng(1717);
        for k in 0..5000 {
            let n = k % 12;
            let m = [3, 40, 1 << 13][k % 3];
            let pts: std::vec::Vec<ScreenPt> = (0..n)
                .map(|_| ScreenPt {
                    x: rng.range(-m, m),
                    y: rng.range(-m, m),
                })
                .collect();
            let (a, b) = (Bbox::of(&pts), Bbox::seeded(&pts));
            assert_eq!(
                (a.lo, a.hi, a.top, a.bot, a.top_at),
                (b.lo, b.hi, b.top, b.bot, b.top_at),
                "{pts:?}"
            );
            assert_eq!(Bbox::rows(&pts), (a.top, a.bot), "{pts:?}");
        }
    }
}
