//! Fast path of the scan conversion for y-monotone polygons (every convex
//! polygon among them): walk the left and right boundary chains from the
//! top vertex down with 32-bit DDAs, instead of building, sorting and
//! scanning a general active-edge list.
//!
//! Contract: [`fill_monotone`] emits exactly the spans the general fill
//! ([`super::scan`]) would, or declines (`None`, before emitting anything)
//! when the polygon is not y-monotone or not small enough for
//! `Edge::new_small`. Why it is exact:
//! * In a y-monotone polygon the vertex y sequence, read cyclically, goes
//!   down once and up once (exactly two changes of direction, horizontal
//!   edges ignored). Under the half-open row rule each of the two chains
//!   from the top vertex to the bottom one then has exactly one active edge
//!   on every row of `[first, end)` of the polygon, and no other edge is
//!   active: the general loop would see two active edges, one traversed
//!   downward, one upward.
//! * With two crossings of opposite directions the general walk paints
//!   `[min, max)` under both fill rules (see `two_edge_rows` in
//!   [`super::scan`]).
//! * Each crossing is computed by the same exact quotient/remainder DDA as
//!   the general path (`Edge::new_small` started at the current row
//!   equals stepping from an earlier row), so pixels are identical,
//!   shared edges included.

use super::edge::{all_small, packs, Dda32, Packed};
use super::scan::{pair_rows, Bbox, Pair, SpanBounds, SpanSink};
use super::transform::ScreenPt;
use crate::cpu::{HAS_DIV, HAS_FPU};

/// One boundary chain: the vertex its current edge ends at, the direction
/// it walks the vertex list, and the current edge's state.
struct Chain {
    /// Index of the current edge's end vertex.
    at: usize,
    /// +1 (forward through the vertex list) or −1 (backward), as
    /// `n − 1` for backward so that indices stay unsigned.
    step: usize,
    /// Row after the current edge's last active row.
    y1: i32,
    dda: Packed,
}

impl Chain {
    /// Advances to the edge active on row `y` (the first of this chain with
    /// a row after `y`), at most `n` edges; false if none is (which the
    /// monotonicity check rules out; kept as a no-panic guard).
    #[inline(always)]
    fn seek(&mut self, pts: &[ScreenPt], sub: u32, y: i32, row_hi: i32) -> bool {
        let n = pts.len();
        for _ in 0..n {
            let from = pts[self.at];
            let next = wrap(self.at + self.step, n);
            let to = pts[next];
            self.at = next;
            if to.y == from.y {
                continue; // horizontal: never active
            }
            if to.y < from.y {
                return false; // past the bottom vertex
            }
            // Both chains run downward: `from` is the edge's top endpoint,
            // as in the general edge setup's normalisation.
            let (first, end) = Dda32::rows(from, to, sub);
            if end <= y {
                continue; // ended above this row
            }
            if first > y {
                return false; // a gap: not what monotonicity allows
            }
            self.y1 = end.min(row_hi);
            self.dda = Packed::start(from, to, sub, y);
            return true;
        }
        false
    }
}

/// `i mod n` for `i < 2·n` (a chain's next vertex: `at < n`, `step < n`):
/// `%` where the core divides (two instructions), else one subtraction
/// (without a divider `%` is a call of about 70 instructions).
#[inline(always)]
fn wrap(i: usize, n: usize) -> usize {
    if HAS_DIV {
        i % n
    } else {
        wrap_once(i, n)
    }
}

/// [`wrap`] without a division.
#[inline(always)]
fn wrap_once(i: usize, n: usize) -> usize {
    if i >= n {
        i - n
    } else {
        i
    }
}

/// The largest sub-pixel y at which an edge ending there has no active
/// row from `y` on: `Dda32::rows(_, b, sub).1 <= y` exactly when `b.y` is
/// at most this (the row's sample line `(y + ½)·2^sub`, rounded down), so
/// a kept polygon's seek (`carry::quad`) passes the edges above a band
/// with one comparison each instead of their row ranges. (The same in
/// [`Chain::seek`], the general fill's, took bench_city's band frames
/// 3 to 26 k lower but its full frames 34 to 49 k higher: session 21.)
#[inline(always)]
pub(crate) fn last_above(y: i32, sub: u32) -> i32 {
    ((2 * y + 1) << sub) >> 1
}

/// Whether the closed polygon `pts` is y-monotone, given `top`, the index
/// of a vertex with the least y: read cyclically from `top`, the y
/// coordinates never decrease and then never increase (horizontal edges
/// fit either phase). From a lowest vertex this is exactly "two changes of
/// vertical direction, or none": one pass of one comparison a vertex.
pub(super) fn is_y_monotone(pts: &[ScreenPt], top: usize) -> bool {
    let (Some(before), Some(after)) = (pts.get(..top), pts.get(top..)) else {
        return false;
    };
    let Some((first, after)) = after.split_first() else {
        return false;
    };
    let mut prev = first.y;
    let mut rising = false; // false: still going down the screen
    let mut fits = |y: i32| {
        if y < prev {
            rising = true;
        } else if y > prev && rising {
            return false;
        }
        prev = y;
        true
    };
    // The cyclic order from `top` as two plain slices (no index wrap or
    // bounds check a vertex); the step back to `top` itself, a lowest
    // vertex, never fails and is left out.
    after.iter().all(|p| fits(p.y)) && before.iter().all(|p| fits(p.y))
}

/// Fills the y-monotone polygon `pts` within `b` (already intersected with
/// the sink's bounds) and returns the number of spans, or `None` (nothing
/// emitted) when the polygon is not y-monotone. The caller guarantees
/// `|x|, |y| < edge::SMALL` for every vertex, `packs(sub)` (the edges
/// step as [`Packed`]), `pts.len() ≥ 3` and that `bbox` is `Bbox::of(pts)`.
pub(crate) fn fill_monotone<K: SpanSink>(
    pts: &[ScreenPt],
    bbox: &Bbox,
    sub: u32,
    b: &SpanBounds,
    color: K::Color,
    sink: &mut K,
) -> Option<usize> {
    let n = pts.len();
    let (top, ty, by) = (bbox.top_at, bbox.top, bbox.bot);
    if ty == by {
        return Some(0); // all on one row line: no active row
    }
    let (first, end) = Dda32::rows(ScreenPt { x: 0, y: ty }, ScreenPt { x: 0, y: by }, sub);
    let mut y = first.max(b.y0);
    let stop = end.min(b.y1);
    if let (true, &[p0, p1, p2, p3]) = (QUADS, pts) {
        if let Some(spans) = fill_quad([p0, p1, p2, p3], bbox, sub, [y, stop], b, color, sink) {
            return Some(spans);
        }
    }
    if !is_y_monotone(pts, top) {
        return None;
    }
    if y >= stop {
        return Some(0);
    }
    let blank = Packed::default();
    let mut l = Chain {
        at: top,
        step: 1,
        y1: y,
        dda: blank,
    };
    let mut r = Chain {
        at: top,
        step: n - 1,
        y1: y,
        dda: blank,
    };
    let pair = pair_of(bbox, sub, b);
    let mut spans = 0usize;
    while y < stop {
        if l.y1 <= y && !l.seek(pts, sub, y, stop) {
            break;
        }
        if r.y1 <= y && !r.seek(pts, sub, y, stop) {
            break;
        }
        let run = l.y1.min(r.y1);
        spans += pair_rows(&mut l.dda, &mut r.dda, pair, b, y, run, color, sink);
        y = run;
    }
    Some(spans)
}

/// Whether quads take [`fill_quad`]: on cores with an FPU (the
/// Cortex-M4F). On a Cortex-M0 the frame of its row function
/// (`quad_rows`, beside the fill's) took the socket's 8-row band frames
/// 192 B more stack, over its 16 KiB (`fpt mcu-bench --cpu m0`). This
/// crate's tests use it on every target.
const QUADS: bool = HAS_FPU || cfg!(test);

/// The row loop of a polygon with box `bbox` ([`fill_monotone`]'s and
/// [`fill_quad`]'s): `Pair::Within` when the box lies within `b`'s
/// columns, else `Pair::Span`.
#[inline(always)]
pub(crate) fn pair_of(bbox: &Bbox, sub: u32, b: &SpanBounds) -> Pair {
    // Every crossing lies in `[col(lo), col(hi) + 1]` (as in
    // `fill_polygon_in`'s reject): within the columns, its rows need no
    // clamp, which also frees two registers of the row loop.
    let col = |x: i32| (2 * x - (1 << sub)) >> (sub + 1);
    if col(bbox.lo) >= b.x0 && col(bbox.hi) < b.x1 {
        Pair::Within
    } else {
        Pair::Span
    }
}

/// Whether the quad `pts`' corner opposite its top one `top` (a corner
/// with the least y) is a lowest corner: then the y coordinates read from
/// `top` go down to it and back up, so the quad is y-monotone (what
/// [`is_y_monotone`] would answer in a pass) and its two chains meet there.
#[inline(always)]
pub(crate) fn opposite_lowest(pts: &[ScreenPt; 4], top: usize) -> bool {
    let y = |k: usize| pts[(top + k) & 3].y;
    y(2) >= y(1) && y(2) >= y(3)
}

/// [`fill_monotone`] for a quad whose corner opposite the top one (`bbox`'s
/// `top_at`) is a lowest corner: then its chains are the two pairs of
/// edges from the top corner `t` through a side corner to the opposite one
/// `o`, so no monotonicity pass or chain seek is needed (the same edges,
/// started at the same or later rows, are active on every row, so the
/// spans are the chain walk's). `None` for the other quads (the chain walk
/// then). Rows `[y, stop)`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn fill_quad<K: SpanSink>(
    pts: [ScreenPt; 4],
    bbox: &Bbox,
    sub: u32,
    [y, stop]: [i32; 2],
    b: &SpanBounds,
    color: K::Color,
    sink: &mut K,
) -> Option<usize> {
    let top = bbox.top_at;
    if !opposite_lowest(&pts, top) {
        return None;
    }
    let at = |k: usize| pts[(top + k) & 3];
    let (t, l, o, r) = (at(0), at(1), at(2), at(3));
    if y >= stop {
        return Some(0);
    }
    let within = pair_of(bbox, sub, b) == Pair::Within;
    Some(quad_rows(
        [t, l, o, r],
        sub,
        [y, stop],
        within,
        b,
        color,
        sink,
    ))
}

/// The rows `[y, stop)` of a quad `t, l, o, r` whose chains are
/// `t → l → o` and `t → r → o` (`t` a top corner, `o` a bottom one):
/// [`fill_quad`]'s second half, not inlined for the reason
/// [`triangle_rows`] is not (the steppers stay in registers). Each side
/// starts on the edge active on row `y` and changes to its second edge on
/// the first row of its middle corner; `y` is at least the first row of
/// `t` and `stop` at most the first row of `o`, so every start is on one
/// of its edge's active rows. `within`: [`pair_of`] is `Pair::Within`
/// (a flag rather than the pair, so that only those two row loops are
/// compiled here: measured 6 to 16 k cheaper a `bench_city` full frame).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(crate) fn quad_rows<K: SpanSink>(
    [t, l, o, r]: [ScreenPt; 4],
    sub: u32,
    [mut y, stop]: [i32; 2],
    within: bool,
    b: &SpanBounds,
    color: K::Color,
    sink: &mut K,
) -> usize {
    // The first row of a corner: where the edge above it ends and the one
    // below it starts.
    let row = |p: ScreenPt| Dda32::rows(p, p, sub).0;
    let (ly, ry) = (row(l), row(r));
    // Each side's edge on row `y`, and the row where it changes to its
    // second edge (`stop`: it does not change within the rows).
    let (mut le, mut l_at) = if y < ly {
        (Packed::start_inline(t, l, sub, y), ly.min(stop))
    } else {
        (Packed::start_inline(l, o, sub, y), stop)
    };
    let (mut re, mut r_at) = if y < ry {
        (Packed::start_inline(t, r, sub, y), ry.min(stop))
    } else {
        (Packed::start_inline(r, o, sub, y), stop)
    };
    let pair = if within { Pair::Within } else { Pair::Span };
    let mut spans = 0;
    while y < stop {
        let run = l_at.min(r_at);
        spans += pair_rows(&mut le, &mut re, pair, b, y, run, color, sink);
        y = run;
        if y == l_at && y < stop {
            le = Packed::start_inline(l, o, sub, y);
            l_at = stop;
        }
        if y == r_at && y < stop {
            re = Packed::start_inline(r, o, sub, y);
            r_at = stop;
        }
    }
    spans
}

/// Fills the triangle `pts` within `b` (already intersected with the
/// sink's bounds) and returns the number of spans: the spans
/// [`fill_monotone`] (and the general fill) would emit, with less set-up.
/// A triangle is always y-monotone: sorted by y into top `t`, middle `m`
/// and bottom `u`, the long edge `t → u` is active on every row of the
/// triangle, `t → m` on the rows above the middle vertex's and `m → u` on
/// the rows from it on (the half-open rule of [`super::edge`]: the two
/// short edges' row ranges meet at `m`'s row and do not overlap), and the
/// two active edges run in opposite directions around it, so each row is
/// `[min, max)` of the two crossings. No box, monotonicity pass or chain
/// seek: three compare-and-swaps, three row bounds and two or three edge
/// starts. The caller guarantees `|x|, |y| < edge::SMALL` and
/// `packs(sub)`: the edges step as [`Packed`]. A triangle whose corners'
/// columns lie within `b`'s has every crossing within them too (as in
/// [`fill_monotone`]): its rows are not clamped.
#[inline(always)]
pub(crate) fn fill_triangle<K: SpanSink>(
    pts: [ScreenPt; 3],
    sub: u32,
    b: &SpanBounds,
    color: K::Color,
    sink: &mut K,
) -> usize {
    let [t, m, u] = sort_by_y(pts);
    let (first, mid) = Dda32::rows(t, m, sub);
    let end = Dda32::rows(m, u, sub).1;
    let y = first.max(b.y0);
    let stop = end.min(b.y1);
    if y >= stop {
        return 0;
    }
    // Which side the long edge is on: the sign of `m`'s offset from it
    // (`|coordinates| < 2^13`: the products fit i32). On every row the
    // left edge's exact x is at most the right one's, and so is its
    // crossing (a monotone function of x): the span is `[left, right)`
    // without comparing. Collinear vertices give equal crossings on every
    // row, so no span at all.
    let side = (m.x - t.x) * (u.y - t.y) - (m.y - t.y) * (u.x - t.x);
    let col = |x: i32| (2 * x - (1 << sub)) >> (sub + 1);
    let within = col(t.x.min(m.x).min(u.x)) >= b.x0 && col(t.x.max(m.x).max(u.x)) < b.x1;
    let pair = match (side, within) {
        (0, _) => return 0,
        (1.., true) => Pair::AbWithin,
        (1.., false) => Pair::Ab,
        (_, true) => Pair::BaWithin,
        (_, false) => Pair::Ba,
    };
    triangle_rows([t, m, u], sub, [y, mid, stop], pair, b, color, sink)
}

/// The edge starts and the rows of a triangle sorted by y (`t`, `m`, `u`),
/// from row `y` (an active row of the long edge) to `stop`, the short edge
/// changing at `mid`: [`fill_triangle`]'s second half. Not inlined: in a
/// function of their own the two steppers stay in registers through the
/// row loops (inlined into the fill they were stored every row); with the
/// whole of [`fill_triangle`] out of line instead, the fill's chain path
/// cost `bench_city` 69–84 k more a full frame (`docs/cortex-m4.md`,
/// session 21).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn triangle_rows<K: SpanSink>(
    [t, m, u]: [ScreenPt; 3],
    sub: u32,
    [mut y, mid, stop]: [i32; 3],
    pair: Pair,
    b: &SpanBounds,
    color: K::Color,
    sink: &mut K,
) -> usize {
    // `first ≤ y < end`: `t.y < u.y`, and `y` is one of the long edge's
    // active rows.
    let mut long = Packed::start_inline(t, u, sub, y);
    let mut spans = 0;
    if y < mid {
        // `t → m` is active on `[first, mid)`, which holds `y`.
        let mut e = Packed::start_inline(t, m, sub, y);
        let run = mid.min(stop);
        spans += pair_rows(&mut long, &mut e, pair, b, y, run, color, sink);
        y = run;
    }
    if y < stop {
        // `mid ≤ y < end`: `m → u` is active on row `y`.
        let mut e = Packed::start_inline(m, u, sub, y);
        spans += pair_rows(&mut long, &mut e, pair, b, y, stop, color, sink);
    }
    spans
}

/// The corners of a triangle sorted by y: top, middle, bottom (three
/// compare-and-swaps; [`fill_triangle`] and the band carry's set-up).
#[inline(always)]
pub(crate) fn sort_by_y([mut t, mut m, mut u]: [ScreenPt; 3]) -> [ScreenPt; 3] {
    if m.y < t.y {
        core::mem::swap(&mut t, &mut m);
    }
    if u.y < m.y {
        core::mem::swap(&mut m, &mut u);
        if m.y < t.y {
            core::mem::swap(&mut t, &mut m);
        }
    }
    [t, m, u]
}

/// A band's set-up for replaying triangles: the bounds and sub-pixel bits
/// with which [`super::scan::fill_polygon_in`] hands a triangle to
/// [`fill_triangle`], found once a band instead of once a triangle (the
/// display list's replay fills every record of a band with the same
/// renderer and sink).
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriangleBand {
    /// Sub-pixel bits.
    pub(super) sub: u32,
    /// The band's bounds (clip and sink intersected).
    pub(super) b: SpanBounds,
}

impl TriangleBand {
    /// The set-up for a fill clipped to `clip` into a sink with bounds
    /// `sink`, with `edges` edge slots and `active` active-edge slots in
    /// the scratch; `None` when `fill_polygon_in` would not take the
    /// triangle path (`packs(sub)` false, too few slots) or would fill nothing
    /// (the bounds are empty), so that the caller takes the general fill.
    #[inline]
    pub(crate) fn new(
        sub: u32,
        clip: &SpanBounds,
        sink: &SpanBounds,
        edges: usize,
        active: usize,
    ) -> Option<Self> {
        let b = clip.intersect(sink);
        (packs(sub) && edges >= 3 && active >= 3 && !b.is_empty()).then_some(Self { sub, b })
    }

    /// Fills triangle `pts` as `fill_polygon_in` would with this band's
    /// set-up (the same spans, in the same order), or `None`, with nothing
    /// emitted, when a point is outside ±`SMALL` (the general path).
    #[inline(always)]
    pub(crate) fn fill<K: SpanSink>(
        &self,
        pts: [ScreenPt; 3],
        color: K::Color,
        sink: &mut K,
    ) -> Option<usize> {
        if !all_small(&pts) {
            return None;
        }
        Some(fill_triangle(pts, self.sub, &self.b, color, sink))
    }
}

#[cfg(test)]
pub(super) mod tests {
    extern crate std;
    use super::super::edge::{build_edges, Edge, SMALL};
    use super::super::scan::{fill_polygon_in, scan, FillRule, Paint};
    use super::*;
    use std::vec::Vec;

    /// A chain's next vertex without a division is `%`'s.
    #[test]
    fn wrap_once_is_mod_below_twice_n() {
        for n in 1..40 {
            for i in 0..2 * n {
                assert_eq!(wrap_once(i, n), i % n, "{i} {n}");
            }
        }
    }

    /// Records spans (also the band-carry tests' sink, `carry.rs`).
    pub(in super::super) struct Rec(pub Vec<(i32, i32, i32)>, pub SpanBounds);

    impl SpanSink for Rec {
        type Color = ();
        fn color(&self, _: &Paint) {}
        fn bounds(&self) -> SpanBounds {
            self.1
        }
        fn span(&mut self, y: i32, x0: i32, x1: i32, _: ()) {
            self.0.push((y, x0, x1));
        }
    }

    /// `last_above(y, sub)` is the largest sub-pixel y at which an edge
    /// ending there has its row range end by row `y`, for every sub-pixel
    /// count the renderer uses and rows on both sides of 0.
    #[test]
    fn last_above_bounds_the_edges_ended_before_a_row() {
        for sub in 0..=8u32 {
            for y in -40..40 {
                let ends =
                    |b: i32| Dda32::rows(ScreenPt { x: 0, y: b }, ScreenPt { x: 0, y: b }, sub).1;
                let a = last_above(y, sub);
                assert!(ends(a) <= y && ends(a + 1) > y, "{sub} {y}");
            }
        }
    }

    /// A band of 1 to 20 rows within the polygons' reach (`m` sub-pixel
    /// units), between random columns.
    fn random_band(rnd: &mut impl FnMut(i32) -> i32, m: i32, sub: u32) -> SpanBounds {
        let (y0, h) = (rnd(m >> sub), 1 + rnd(20).abs());
        SpanBounds {
            x0: rnd(30),
            y0,
            x1: 30 + rnd(30).abs(),
            y1: y0 + h,
        }
    }

    /// Random polygons (many y-monotone, many not), small and at the
    /// limit, cut by random bands: the chain walk, whenever it accepts,
    /// emits exactly the general active-edge fill's spans.
    #[test]
    fn chains_equal_the_general_fill() {
        let mut rng = crate::raster::tests::Rng(99);
        let mut rnd = |m: i32| rng.range(-m, m);
        let mut accepted = 0;
        for k in 0..4000 {
            let sub = 3 + (k % 2) as u32;
            let m = if k % 5 == 0 { SMALL - 1 } else { 40 << sub };
            let nv = 3 + (rnd(3).unsigned_abs() as usize);
            let pts: Vec<ScreenPt> = (0..nv).map(|_| pt(rnd(m), rnd(m))).collect();
            let b = random_band(&mut rnd, m, sub);
            let mut fast = Rec(Vec::new(), b);
            let Some(n) = fill_monotone(&pts, &Bbox::of(&pts), sub, &b, (), &mut fast) else {
                continue;
            };
            accepted += 1;
            assert_eq!(n, fast.0.len());
            let mut edges = [Edge::ZERO; 8];
            let mut active = [0u16; 8];
            let Some(ne) = build_edges(&pts, sub, b.y0, b.y1, &mut edges) else {
                panic!("capacity")
            };
            let mut slow = Rec(Vec::new(), b);
            for rule in [FillRule::NonZero, FillRule::EvenOdd] {
                slow.0.clear();
                let mut e2 = edges;
                scan(&mut e2[..ne], &mut active, rule, &b, (), &mut slow);
                assert_eq!(fast.0, slow.0, "{pts:?} {sub} {b:?}");
            }
        }
        assert!(accepted > 1000, "{accepted}");
    }

    /// Random triangles (small, at the limit, degenerate, with shared
    /// rows), cut by random bands, at the sub-pixel bits where the chain
    /// walk applies (`packs`): the triangle path emits exactly the chain
    /// walk's spans, so the general fill's.
    #[test]
    fn triangles_equal_the_chain_walk() {
        let mut rng = crate::raster::tests::Rng(4242);
        let mut rnd = |m: i32| rng.range(-m, m);
        for k in 0..20_000 {
            let sub = 3 + (k % 2) as u32;
            let m = match k % 5 {
                0 => SMALL - 1,
                1 => 3 << sub,
                _ => 40 << sub,
            };
            let mut tri = [pt(rnd(m), rnd(m)), pt(rnd(m), rnd(m)), pt(rnd(m), rnd(m))];
            if k % 7 == 0 {
                tri[1].y = tri[0].y; // a horizontal edge
            }
            if k % 11 == 0 {
                tri[2] = tri[(k / 11) % 2]; // a repeated vertex
            }
            let b = random_band(&mut rnd, m, sub);
            let mut fast = Rec(Vec::new(), b);
            let n = fill_triangle(tri, sub, &b, (), &mut fast);
            assert_eq!(n, fast.0.len());
            let mut chain = Rec(Vec::new(), b);
            let Some(c) = fill_monotone(&tri, &Bbox::of(&tri), sub, &b, (), &mut chain) else {
                panic!("a triangle is y-monotone: {tri:?}")
            };
            assert_eq!(c, n);
            assert_eq!(fast.0, chain.0, "{tri:?} {sub} {b:?}");
        }
    }

    /// Random triangles at 0 to 8 sub-pixel bits (the triangle path's
    /// steppers, the general fill beyond ±SMALL): `fill_polygon_in` emits
    /// exactly the general active-edge fill's spans.
    #[test]
    fn triangles_at_every_sub_equal_the_general_fill() {
        let mut rng = crate::raster::tests::Rng(3131);
        let mut rnd = |m: i32| rng.range(-m, m);
        for k in 0..20_000 {
            let sub = [0u32, 1, 2, 3, 4, 8][k % 6];
            let m = if k % 3 == 0 { SMALL - 1 } else { 40 << sub };
            let tri = [pt(rnd(m), rnd(m)), pt(rnd(m), rnd(m)), pt(rnd(m), rnd(m))];
            let b = random_band(&mut rnd, m, sub);
            let (mut edges, mut active) = ([Edge::ZERO; 3], [0u16; 3]);
            let mut fast = Rec(Vec::new(), b);
            let rule = FillRule::NonZero;
            let filled = fill_polygon_in(
                &tri,
                None,
                sub,
                rule,
                &b,
                &mut edges,
                &mut active,
                (),
                &mut fast,
            );
            let Ok(n) = filled else { panic!("capacity") };
            assert_eq!(n, fast.0.len());
            let Some(ne) = build_edges(&tri, sub, b.y0, b.y1, &mut edges) else {
                panic!("capacity")
            };
            let mut slow = Rec(Vec::new(), b);
            scan(&mut edges[..ne], &mut active, rule, &b, (), &mut slow);
            assert_eq!(fast.0, slow.0, "{tri:?} {sub} {b:?}");
        }
    }

    /// Random triangles (small, at and beyond the ±SMALL limit), clips and
    /// sink bounds: whenever the band set-up accepts a triangle, it emits
    /// exactly the spans of `fill_polygon_in` (what `fill_ready` calls);
    /// it declines only for a point beyond ±SMALL (nothing emitted) or for
    /// bounds that leave nothing to fill.
    #[test]
    fn triangle_band_equals_the_polygon_fill() {
        let mut rng = crate::raster::tests::Rng(515);
        let mut rnd = |m: i32| rng.range(-m, m);
        let (mut accepted, mut declined) = (0, 0);
        for k in 0..20_000 {
            let sub = [0u32, 3, 4, 8][k % 4];
            let m = match k % 5 {
                0 => SMALL + SMALL / 4,
                1 => SMALL - 1,
                _ => 40 << sub,
            };
            let tri = [pt(rnd(m), rnd(m)), pt(rnd(m), rnd(m)), pt(rnd(m), rnd(m))];
            let clip = random_band(&mut rnd, 40 << sub, sub);
            let bounds = random_band(&mut rnd, 40 << sub, sub);
            let mut slow = Rec(Vec::new(), bounds);
            let (mut edges, mut active) = ([Edge::ZERO; 3], [0u16; 3]);
            let rule = FillRule::NonZero;
            let Ok(n) = fill_polygon_in(
                &tri,
                None,
                sub,
                rule,
                &clip,
                &mut edges,
                &mut active,
                (),
                &mut slow,
            ) else {
                panic!("capacity")
            };
            let Some(band) = TriangleBand::new(sub, &clip, &bounds, 3, 3) else {
                assert!(!packs(sub) || clip.intersect(&bounds).is_empty() && n == 0);
                continue;
            };
            let mut fast = Rec(Vec::new(), bounds);
            match band.fill(tri, (), &mut fast) {
                Some(f) => {
                    accepted += 1;
                    assert_eq!(f, n);
                    assert_eq!(fast.0, slow.0, "{tri:?} {sub} {clip:?} {bounds:?}");
                }
                None => {
                    declined += 1;
                    assert!(fast.0.is_empty());
                    assert!(tri.iter().any(|p| p.x.abs() >= SMALL || p.y.abs() >= SMALL));
                }
            }
        }
        assert!(accepted > 2000 && declined > 100, "{accepted} {declined}");
        // No set-up where the polygon fill would not take the triangle path.
        let b = SpanBounds {
            x0: 0,
            y0: 0,
            x1: 8,
            y1: 8,
        };
        assert!(TriangleBand::new(9, &b, &b, 3, 3).is_none());
        assert!(TriangleBand::new(2, &b, &b, 3, 3).is_none());
        assert!(TriangleBand::new(4, &b, &b, 2, 3).is_none());
        assert!(TriangleBand::new(4, &b, &b, 3, 2).is_none());
        assert!(TriangleBand::new(4, &b, &b, 3, 3).is_some());
    }

    /// Random quads (convex and not, many with corners on one row line:
    /// horizontal edges, several top or bottom corners), small and at the
    /// limit, cut by random bands: a quad whose corner opposite its top
    /// one is a lowest corner is y-monotone, and the quad path
    /// (`fill_quad`, which `fill_monotone` takes for it) emits exactly the
    /// general active-edge fill's spans.
    #[test]
    fn quads_equal_the_general_fill() {
        let mut rng = crate::raster::tests::Rng(23);
        let mut rnd = |m: i32| rng.range(-m, m);
        let mut quads = 0;
        for k in 0..6000 {
            let sub = 3 + (k % 2) as u32;
            let m = match k % 3 {
                0 => SMALL - 1,
                1 => 40 << sub,
                _ => 3 << sub, // few distinct rows: ties
            };
            let pts = [0; 4].map(|_| {
                let y = rnd(m);
                pt(rnd(m), if k % 3 == 2 { y & !((1 << sub) - 1) } else { y })
            });
            let bbox = Bbox::of(&pts);
            if !opposite_lowest(&pts, bbox.top_at) {
                continue;
            }
            assert!(is_y_monotone(&pts, bbox.top_at), "{pts:?}");
            quads += 1;
            let b = random_band(&mut rnd, m, sub);
            let mut fast = Rec(Vec::new(), b);
            let Some(n) = fill_monotone(&pts, &bbox, sub, &b, (), &mut fast) else {
                panic!("declined {pts:?}")
            };
            assert_eq!(n, fast.0.len());
            let mut edges = [Edge::ZERO; 4];
            let mut active = [0u16; 4];
            let Some(ne) = build_edges(&pts, sub, b.y0, b.y1, &mut edges) else {
                panic!("capacity")
            };
            for rule in [FillRule::NonZero, FillRule::EvenOdd] {
                let mut slow = Rec(Vec::new(), b);
                let mut e2 = edges;
                scan(&mut e2[..ne], &mut active, rule, &b, (), &mut slow);
                assert_eq!(fast.0, slow.0, "{pts:?} {sub} {b:?}");
            }
        }
        assert!(quads > 2000, "{quads}");
    }

    fn pt(x: i32, y: i32) -> ScreenPt {
        ScreenPt { x, y }
    }

    /// Reference: changes of vertical direction around the closed
    /// polygon, horizontal edges skipped (2 for a y-monotone polygon, 0
    /// when all vertices share one y).
    fn direction_changes(pts: &[ScreenPt]) -> u32 {
        let (mut first, mut last, mut changes) = (0i32, 0i32, 0u32);
        let mut prev = pts[pts.len() - 1];
        for &p in pts {
            let s = (p.y - prev.y).signum();
            if s != 0 {
                if first == 0 {
                    first = s;
                } else if s != last {
                    changes += 1;
                }
                last = s;
            }
            prev = p;
        }
        if first != 0 && first != last {
            changes += 1;
        }
        changes
    }

    #[test]
    fn monotone_shapes() {
        let mono = |p: &[ScreenPt]| is_y_monotone(p, Bbox::of(p).top_at);
        assert!(mono(&[pt(0, 0), pt(10, 5), pt(3, 9)]));
        // Horizontal top and bottom edges.
        assert!(mono(&[pt(0, 0), pt(10, 0), pt(10, 10), pt(0, 10)]));
        // A zigzag (concave in y), and an arrow head with a notch below.
        let w = [pt(0, 0), pt(2, 8), pt(4, 2), pt(6, 8), pt(8, 0), pt(4, 20)];
        assert!(!mono(&w));
        assert!(!mono(&[pt(0, 0), pt(10, 20), pt(0, 10), pt(-10, 20)]));
        assert!(mono(&[pt(0, 3), pt(5, 3), pt(9, 3)]));
    }

    /// The phase walk from any lowest vertex agrees with counting the
    /// changes of direction, on random polygons with many repeated ys
    /// (plateaus at the top, the bottom and in between).
    #[test]
    fn phase_walk_equals_direction_count() {
        let mut rng = crate::raster::tests::Rng(7);
        for _ in 0..20_000 {
            let n = 3 + rng.range(0, 5) as usize;
            let pts: Vec<ScreenPt> = (0..n).map(|_| pt(0, rng.range(0, 4))).collect();
            let want = matches!(direction_changes(&pts), 0 | 2);
            let ty = Bbox::of(&pts).top;
            for (top, _) in pts.iter().enumerate().filter(|(_, p)| p.y == ty) {
                assert_eq!(is_y_monotone(&pts, top), want, "{pts:?} from {top}");
            }
        }
    }
}
