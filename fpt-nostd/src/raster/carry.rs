//! Triangles carried across band edges: a triangle cut by the bottom of
//! a band keeps its two edge steppers, stepped to the band's last row, for
//! the next band, instead of being read back from the display list and
//! set up again there (sorting its corners, its row bounds and two or
//! three exact edge starts, each with two divisions). The four-sided
//! pieces of split triangles ([`quad`]) are carried the same way: their
//! two chains' steppers and the vertices still ahead, instead of the
//! general fill's box, monotonicity pass and chain seeks in every band.
//!
//! # Contract
//!
//! * [`TriangleBand::start`] then [`TriangleBand::run`] emit exactly the
//!   spans of [`TriangleBand::fill`] (so of `fill_polygon_in`) for the same
//!   triangle and band; [`TriangleBand::run`] of the state it left, in the
//!   next band (whose first row is this band's end), emits exactly what
//!   [`TriangleBand::fill`] would there: an exact stepper started on a row
//!   equals one stepped to it from an earlier row (see [`super::edge`]).
//! * The kept states live in a [`Ring`] over caller words (the words the
//!   display list and its band index leave, `DisplayList::replay_parts`),
//!   [`WORDS`] words a triangle. Bands replay their records in walk order,
//!   and the triangles a band keeps are among the next band's records in
//!   the same order, so the next band finds each one by comparing record
//!   offsets with the ring's head: a merge, no search.
//! * With too few words a triangle is not kept ([`Ring::push`] says so)
//!   and the next band sets it up from its record as before: the same
//!   picture, only slower. A kept state that the next band does not meet
//!   where expected (another band, another record) is dropped, never
//!   drawn.
//! * Four-sided polygons, in the same ring (a flag in the entry): see
//!   [`quad`]. Polygons of five or more corners are set up by their own
//!   path and, once at most five corners are left ahead, kept as
//!   four-sided polygons' entries: see [`poly`].

use super::chain::{sort_by_y, TriangleBand};
use super::edge::{all_small, Dda32, Packed};
use super::scan::{pair_rows, Pair, SpanSink};
use super::transform::ScreenPt;
use crate::cpu::HAS_FPU;

mod poly;
mod quad;
use quad::{Chains, Kept};

/// Words (`u32`) a kept triangle takes in the ring.
pub(crate) const WORDS: usize = 15;

/// A triangle's fill state on some row (see [`super::chain::fill_triangle`]
/// for the edges): the long edge `t → u`, the short edge active on that
/// row, and what the lower short edge needs to start. The edges step as
/// [`Packed`] (a [`TriangleBand`] exists only where `packs(sub)`), as in
/// the full frame's triangles: three words each in registers and in the
/// ring instead of [`Dda32`]'s five (session 21).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tri {
    long: Packed,
    short: Packed,
    /// The middle and bottom corners (`m → u` starts from them).
    m: ScreenPt,
    u: ScreenPt,
    /// First row of `m → u`.
    mid: i32,
    /// One past the triangle's last row.
    pub(crate) end: i32,
    /// Whether `short` is still `t → m`.
    upper: bool,
    /// Whether the long edge is the left one (else the right one).
    ab: bool,
}

/// Whether bands keep cut triangles: on cores with an FPU (the
/// Cortex-M4F). On a Cortex-M0 its 16 KiB rarely leave room for the band
/// index, let alone kept triangles, and the larger replay cost it 1.4 %
/// (measured, `fpt mcu-bench --cpu m0`): there the replay is the one
/// before (`TriangleBand::fill`). This crate's tests use it on every
/// target.
pub(crate) const CARRY: bool = HAS_FPU || cfg!(test);

/// What [`TriangleBand::start`] found.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Start {
    /// A corner outside ±`SMALL`: the general fill's.
    Outside,
    /// Nothing to fill in this band (no row of it, or collinear corners).
    Empty,
    /// The state on row `.1`, the band's first row the triangle touches.
    Rows(Tri, i32),
}

impl TriangleBand {
    /// Sets up triangle `pts` on the first row of this band it touches,
    /// as [`super::chain::fill_triangle`] does.
    #[inline(always)]
    pub(crate) fn start(&self, pts: [ScreenPt; 3]) -> Start {
        if !all_small(&pts) {
            return Start::Outside;
        }
        let [t, m, u] = sort_by_y(pts);
        let sub = self.sub;
        let (first, mid) = Dda32::rows(t, m, sub);
        let end = Dda32::rows(m, u, sub).1;
        let y = first.max(self.b.y0);
        if y >= end.min(self.b.y1) {
            return Start::Empty;
        }
        // The long edge's side: the sign of `m`'s offset from it (see
        // `fill_triangle`); collinear corners fill nothing.
        let side = (m.x - t.x) * (u.y - t.y) - (m.y - t.y) * (u.x - t.x);
        if side == 0 {
            return Start::Empty;
        }
        let upper = y < mid;
        let short = if upper {
            Packed::start(t, m, sub, y)
        } else {
            Packed::start(m, u, sub, y)
        };
        let tri = Tri {
            long: Packed::start(t, u, sub, y),
            short,
            m,
            u,
            mid,
            end,
            upper,
            ab: side > 0,
        };
        Start::Rows(tri, y)
    }

    /// Fills `tri`'s rows from `y` (its current row) to the band's end or
    /// the triangle's, leaving it stepped to that row; returns the spans.
    /// The triangle goes on in the next band when `tri.end` is past this
    /// band's end ([`TriangleBand::continues`]).
    #[inline(always)]
    pub(crate) fn run<K: SpanSink>(
        &self,
        tri: &mut Tri,
        mut y: i32,
        color: K::Color,
        sink: &mut K,
    ) -> usize {
        let stop = tri.end.min(self.b.y1);
        let pair = if tri.ab { Pair::Ab } else { Pair::Ba };
        let mut spans = 0;
        // One row loop for both short edges (code size: it is inlined
        // into the replay).
        while y < stop {
            let run = if !tri.upper {
                stop
            } else if y < tri.mid {
                tri.mid.min(stop)
            } else {
                tri.short = Packed::start(tri.m, tri.u, self.sub, y);
                tri.upper = false;
                stop
            };
            spans += pair_rows(
                &mut tri.long,
                &mut tri.short,
                pair,
                &self.b,
                y,
                run,
                color,
                sink,
            );
            y = run;
        }
        spans
    }

    /// Whether `tri`, run through this band, has rows after it.
    #[inline(always)]
    pub(crate) fn continues(&self, tri: &Tri) -> bool {
        tri.end > self.b.y1
    }

    /// This band's first row (where a kept triangle must resume).
    #[inline(always)]
    pub(crate) fn first_row(&self) -> i32 {
        self.b.y0
    }

    /// This band's end row (where the triangles it keeps stop).
    #[inline(always)]
    pub(crate) fn end_row(&self) -> i32 {
        self.b.y1
    }
}

/// Most triangles a ring keeps at once. A band of socket's orbit keeps
/// up to about 40 and its replay holds two bands' worth (78 entries at
/// most); bench_city's bands keep more (the four-sided pieces of its
/// split polygons too). The ring only uses the words the list and its
/// index leave, so the cap bounds the spare words a frame notes as used
/// (`DisplayList::note_spare_used`), not what it needs: 128 × 60 B =
/// 7.5 KiB at most. Measured against 64 (session 14): bench_city's band
/// frames 0.03–1.35 % faster, socket's 16-row bands 2.0 k a frame faster
/// with the same memory (4,567 words) and RAM; 96 gave less, 256 no more.
/// Session 16, with the longer polygons carried too (as quads, [`poly`]):
/// 192 against 128 took bench_city's band frames 0.0–41.7 k instructions
/// lower (no view slower); 256 gave one view 48.5 k but another +1.0 k.
/// A triangle beyond it is set up again in the next band.
pub(crate) const MAX_KEPT: usize = 192;

/// Most kept states a frame counts in the memory it used
/// (`RenderStats::memory_used`, so the default memory of `fpt mcu-bench`
/// and `fpt bench-memory`'s "words a frame uses"): the ring is a cache in
/// spare words, and states past this many are speed where the memory
/// allows, not a need. Measured (session 15): counting every state of
/// socket's 16-row bands (M4F) made the default memory 4,843 words, 32,824 B of RAM (56 B over 32 KiB), for the same
/// instructions as 4,567 words (2,119,824.5 against 2,119,821.5), which is
/// what 64 counts. 64 was [`MAX_KEPT`] before session 14, so the need is
/// the one docs/small-ram.md's tables were measured with.
pub(crate) const NEED_KEPT: usize = 64;

/// Entries a ring over `words` holds.
#[inline(always)]
fn capacity(words: &[u32]) -> usize {
    (words.len() / WORDS).min(MAX_KEPT)
}

/// A ring of kept triangles over caller words: the ones the previous band
/// kept (its **incoming**, read in order by the band being replayed) and
/// the ones this band keeps for the next, appended behind them.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Ring {
    /// Slot of the oldest entry.
    head: usize,
    /// Entries held.
    len: usize,
    /// Entries at the head kept by the previous band and not yet met.
    incoming: usize,
    /// The most entries held at once since [`Ring::clear`]'s caller made it.
    most: usize,
    /// Entries the band's words hold ([`capacity`]), found once a band by
    /// [`Ring::begin`] rather than in every push, skip and room test.
    cap: usize,
}

impl Ring {
    /// An empty ring.
    pub(crate) const fn new() -> Self {
        Ring {
            head: 0,
            len: 0,
            incoming: 0,
            most: 0,
            cap: 0,
        }
    }

    /// Forgets every entry (a new list: its offsets mean other records).
    pub(crate) fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
        self.incoming = 0;
    }

    /// The most entries held at once (the words used: `WORDS` each).
    pub(crate) fn most(&self) -> usize {
        self.most
    }

    /// Starts a band: what the band before left unmet is dropped, and
    /// what it kept becomes this band's incoming.
    pub(crate) fn begin(&mut self, words: &[u32]) {
        let cap = capacity(words);
        self.cap = cap;
        if cap == 0 {
            self.clear();
            return;
        }
        self.head = (self.head + self.incoming) % cap;
        self.len -= self.incoming.min(self.len);
        self.incoming = self.len;
    }

    /// The record offset and row of the next incoming entry.
    #[inline(always)]
    pub(crate) fn peek(&self, words: &[u32]) -> Option<(usize, i32)> {
        if self.incoming == 0 {
            return None;
        }
        let w = *words.get(self.head * WORDS + 13)?;
        Some(((w & 0xffff) as usize, (w as i32) >> 16))
    }

    /// Whether [`Ring::push`] has room for one more entry.
    #[inline(always)]
    pub(crate) fn has_room(&self) -> bool {
        self.len < self.cap
    }

    /// Drops the next incoming entry.
    #[inline(always)]
    pub(crate) fn skip(&mut self) {
        let cap = self.cap;
        if self.incoming == 0 || cap == 0 {
            return;
        }
        self.head = (self.head + 1) % cap;
        self.len -= 1;
        self.incoming -= 1;
    }

    /// Takes the next incoming entry: the triangle and its colour word
    /// (24 bits, `SpanSink::keep_color`'s).
    #[inline(always)]
    pub(crate) fn pop(&mut self, words: &[u32]) -> Option<(Tri, u32)> {
        let at = self.head * WORDS;
        // By reference and word by word: a copy of the array is a `memcpy`
        // call.
        let w: &[u32; WORDS] = words.get(at..at + WORDS)?.try_into().ok()?;
        let lo = |x: u32| i32::from(x as u16 as i16);
        let hi = |x: u32| (x as i32) >> 16;
        let dda = |k: usize| Packed::from_words([w[k], w[k + 1], w[k + 2]]);
        let c = w[14];
        let tri = Tri {
            long: dda(0),
            short: dda(5),
            m: ScreenPt {
                x: lo(w[10]),
                y: hi(w[10]),
            },
            u: ScreenPt {
                x: lo(w[11]),
                y: hi(w[11]),
            },
            mid: lo(w[12]),
            end: hi(w[12]),
            upper: c & 1 << 24 != 0,
            ab: c & 1 << 25 != 0,
        };
        self.skip();
        Some((tri, c & COLOR))
    }

    /// Keeps `tri` (record at `offset`, drawn in colour word `color`, 24
    /// bits: `SpanSink::keep_color`'s) for the band
    /// starting at row `row`; `false`, nothing kept, when the ring is full
    /// (or `offset` is not below 2^16). Corners and rows are within
    /// ±2^14 (the corners within ±`SMALL`), so they fit 16 bits.
    #[inline(always)]
    pub(crate) fn push(
        &mut self,
        words: &mut [u32],
        tri: &Tri,
        (offset, row): (usize, i32),
        color: u32,
    ) -> bool {
        let cap = self.cap;
        if self.len >= cap || offset > usize::from(u16::MAX) {
            return false;
        }
        let at = (self.head + self.len) % cap * WORDS;
        let Some(out) = words.get_mut(at..at + WORDS) else {
            return false;
        };
        let Ok(out) = <&mut [u32; WORDS]>::try_from(out) else {
            return false;
        };
        let pack = |a: i32, b: i32| (a as u16 as u32) | (b as u32) << 16;
        let [l0, l1, l2] = tri.long.to_words();
        let [s0, s1, s2] = tri.short.to_words();
        let c = color & COLOR | u32::from(tri.upper) << 24 | u32::from(tri.ab) << 25;
        // Word by word: a copy of an array is a `memcpy` call.
        out[0] = l0;
        out[1] = l1;
        out[2] = l2;
        // Words 3, 4, 8 and 9 unused: the quads' entries (`QUAD`) need
        // the 15.
        out[5] = s0;
        out[6] = s1;
        out[7] = s2;
        out[10] = pack(tri.m.x, tri.m.y);
        out[11] = pack(tri.u.x, tri.u.y);
        out[12] = pack(tri.mid, tri.end);
        out[13] = pack(offset as i32, row);
        out[14] = c;
        self.len += 1;
        self.most = self.most.max(self.len);
        true
    }

    /// Whether the next incoming entry is a four-sided polygon's
    /// ([`Ring::pop_quad`]; else a triangle's, [`Ring::pop`]).
    #[inline(always)]
    pub(crate) fn next_is_quad(&self, words: &[u32]) -> bool {
        words
            .get(self.head * WORDS + 14)
            .is_some_and(|&c| c & QUAD != 0)
    }

    /// The number of corners ahead in the next incoming entry, a
    /// four-sided polygon's ([`Ring::next_is_quad`]).
    #[inline(always)]
    pub(crate) fn next_ahead(&self, words: &[u32]) -> usize {
        words
            .get(self.head * WORDS + 14)
            .map_or(0, |&c| (c >> 24 & 7) as usize)
    }

    /// Takes the next incoming entry, a four-sided polygon's, for `band`:
    /// the state (its corners ahead at `arc[1..=count]`, so at most `N − 2`
    /// of them: [`Ring::next_ahead`]) and its colour. `S`: the steppers the
    /// entry was kept with (the band's, as for [`Ring::push_quad`]).
    #[inline(always)]
    pub(crate) fn pop_quad<S: Kept, const N: usize>(
        &mut self,
        words: &[u32],
        band: &TriangleBand,
    ) -> Option<(Chains<S, N>, u32)> {
        let at = self.head * WORDS;
        let w: &[u32; WORDS] = words.get(at..at + WORDS)?.try_into().ok()?;
        let lo = |x: u32| i32::from(x as u16 as i16);
        let hi = |x: u32| (x as i32) >> 16;
        let pt = |x: u32| ScreenPt { x: lo(x), y: hi(x) };
        let c = w[14];
        // The vertices ahead at `arc[1..=count]`; each chain's edge ends
        // on its vertex's row, and the polygon on the lowest's.
        let count = (c >> 24 & 7) as usize;
        let k = arc_at::<S>();
        // Unrolled: an iterator's `take(..).skip(..)` here was an
        // out-of-line `Take::nth` call a resume.
        let mut arc = [ScreenPt::default(); N];
        let mut put = |i: usize| {
            if let (Some(a), Some(&x)) = (arc.get_mut(i + 1), w.get(k + i)) {
                *a = pt(x);
            }
        };
        put(0);
        put(1);
        put(2);
        if N > 5 {
            put(3);
            put(4);
        }
        let (ly1, ry1, end) = if rows_kept::<S>() {
            let r = 2 * S::WORDS;
            (lo(w[r]), hi(w[r]), lo(w[r + 1]))
        } else {
            let row = |p: ScreenPt| Dda32::rows(p, p, band.sub).1;
            let at = |i: usize| arc.get(i).copied().unwrap_or_default();
            // The lowest of `arc[1..=count]` (`count` is 1 to 3 here),
            // unrolled: a `take(..).skip(..)` loop made an out-of-line
            // `Take::nth` call for every resumed quad.
            let mut bottom = at(1);
            if count >= 2 && at(2).y > bottom.y {
                bottom = at(2);
            }
            if count >= 3 && at(3).y > bottom.y {
                bottom = at(3);
            }
            (row(at(1)), row(at(count)), row(bottom))
        };
        let quad = Chains {
            l: S::from_words(&w[..]),
            ly1,
            r: S::from_words(&w[S::WORDS..]),
            ry1,
            arc,
            lo: 1,
            hi: count,
            end,
        };
        self.skip();
        Some((quad, c & COLOR))
    }

    /// Keeps polygon state `q` (record at `offset`, drawn in colour word
    /// `color`, as [`Ring::push`]) for the
    /// band starting at row `row` as a four-sided polygon's entry: its
    /// steppers and the corners still ahead, at most [`most_ahead`] of
    /// them; `false`, nothing kept, with more, when the ring is full (or
    /// `offset` is not below 2^16). Corners and rows are within ±2^14 (the
    /// corners within ±`SMALL`), so they fit 16 bits.
    #[inline(always)]
    pub(crate) fn push_quad<S: Kept, const N: usize>(
        &mut self,
        words: &mut [u32],
        q: &Chains<S, N>,
        (offset, row): (usize, i32),
        color: u32,
    ) -> bool {
        let cap = self.cap;
        if self.len >= cap || offset > usize::from(u16::MAX) {
            return false;
        }
        // The vertices ahead: none before the chains' first seek, at most
        // three for a quad once both chains have left the top (always,
        // after a run).
        let count = q.hi.wrapping_sub(q.lo).wrapping_add(1);
        if q.lo == 0 || count > most_ahead::<S>() {
            return false;
        }
        let at = (self.head + self.len) % cap * WORDS;
        let Some(out) = words.get_mut(at..at + WORDS) else {
            return false;
        };
        let Ok(out) = <&mut [u32; WORDS]>::try_from(out) else {
            return false;
        };
        let pack = |a: i32, b: i32| (a as u16 as u32) | (b as u32) << 16;
        let pt = |p: ScreenPt| pack(p.x, p.y);
        let c = color & COLOR | (count as u32) << 24 | QUAD;
        let (l, r) = (q.l.to_words(), q.r.to_words());
        // Word by word: a copy of an array is a `memcpy` call (a
        // slice's `copy_from_slice` too, for a length the type gives).
        #[allow(clippy::manual_memcpy)]
        for i in 0..S::WORDS {
            out[i] = l[i];
            out[S::WORDS + i] = r[i];
        }
        if rows_kept::<S>() {
            out[2 * S::WORDS] = pack(q.ly1, q.ry1);
            out[2 * S::WORDS + 1] = pack(q.end, 0);
        }
        // The corners an arc of `N` can hold ahead (three for a quad).
        let k = arc_at::<S>();
        for i in 0..most_ahead::<S>().min(N - 2) {
            out[k + i] = q.arc.get(q.lo + i).map_or(0, |&p| pt(p));
        }
        out[13] = pack(offset as i32, row);
        out[14] = c;
        self.len += 1;
        self.most = self.most.max(self.len);
        true
    }
}

/// Whether a four-sided polygon's entry with steppers `S` has room for its
/// chains' end rows and its own (words 2·`S::WORDS` and + 1), with three
/// corners ahead after them: packed steppers leave it, so a resume reads
/// them instead of finding them again from the corners ahead (three
/// `Dda32::rows` and the lowest corner's search a resumed quad).
#[inline(always)]
const fn rows_kept<S: Kept>() -> bool {
    2 * S::WORDS + 2 + 3 <= 13
}

/// Where an entry with steppers `S` keeps its corners ahead: after the
/// steppers and (when kept) the rows, up to word 12 (word 13 is the
/// record's offset, 14 the colour).
#[inline(always)]
const fn arc_at<S: Kept>() -> usize {
    2 * S::WORDS + if rows_kept::<S>() { 2 } else { 0 }
}

/// Most corners ahead an entry with steppers `S` holds: three with
/// `Dda32`s (a quad's, and a longer polygon's near its bottom), five with
/// packed steppers (session 21: a polygon of five or six corners is kept
/// from its first band on, one of seven or eight once it has passed two
/// or three of its corners).
#[inline(always)]
pub(crate) const fn most_ahead<S: Kept>() -> usize {
    13 - arc_at::<S>()
}
/// The flag of a four-sided polygon's entry (in its colour word).
const QUAD: u32 = 1 << 27;
/// The bits of an entry's colour word that hold the colour (the flags and
/// counts above them).
const COLOR: u32 = (1 << 24) - 1;

#[cfg(test)]
mod tests {
    //! The carry's tests, and the set-up the tests of its triangles, quads
    //! and polygons share: a random shape and the sweep of random bands it
    //! is drawn in (below), so that each test states only what it checks
    //! of the ring.

    extern crate std;
    use super::super::edge::{packs, Edge, SMALL};
    use super::super::scan::{fill_polygon_in, rgb_word, FillRule, SpanBounds};
    use super::*;
    use crate::raster::tests::Rng;
    use embedded_graphics::pixelcolor::Rgb888;
    use std::vec::Vec;

    use super::super::chain::tests::Rec;

    pub(super) fn pt(x: i32, y: i32) -> ScreenPt {
        ScreenPt { x, y }
    }

    /// Case `k` of a random carry test: its sub-pixel bits, the bound `m`
    /// of its corners (±`m`; every fifth case the largest small
    /// coordinate), and `n` random corners, put in order around their
    /// centre when `around` (convex, as most of bench_city's polygons are;
    /// some with two corners on one row, or one column).
    pub(super) fn corners(
        rng: &mut Rng,
        k: usize,
        n: usize,
        around: bool,
    ) -> (u32, i32, Vec<ScreenPt>) {
        let sub = [0u32, 3, 4, 8][k % 4];
        let small = k.is_multiple_of(5);
        let m = if small { SMALL - 1 } else { 40 << sub };
        let mut poly: Vec<ScreenPt> = (0..n)
            .map(|_| pt(rng.range(-m, m), rng.range(-m, m)))
            .collect();
        if around {
            if k % 7 == 1 {
                poly[1].y = poly[0].y;
                poly[3].x = poly[2].x;
            }
            let cx = poly.iter().map(|p| p.x).sum::<i32>() / n as i32;
            let cy = poly.iter().map(|p| p.y).sum::<i32>() / n as i32;
            poly.sort_by(|a, b| {
                let aa = f64::from(a.y - cy).atan2(f64::from(a.x - cx));
                let ab = f64::from(b.y - cy).atan2(f64::from(b.x - cx));
                aa.total_cmp(&ab)
            });
        }
        (sub, m, poly)
    }

    /// The bands a shape of [`corners`] is drawn in, top to bottom: of one
    /// random width and height (1 to 13 rows), from above the shape to
    /// below it.
    pub(super) fn bands(rng: &mut Rng, m: i32, sub: u32) -> impl Iterator<Item = TriangleBand> {
        let (x0, x1) = (rng.range(-30, 30), 30 + rng.range(-30, 30).abs());
        let rows = 1 + rng.range(-12, 12).abs();
        let y = (m >> sub) + 1;
        (-y..=y).step_by(rows as usize).map(move |y0| TriangleBand {
            sub,
            b: SpanBounds {
                x0,
                y0,
                x1,
                y1: y0 + rows,
            },
        })
    }

    /// `poly`'s spans in `band` by the general fill (`fill_polygon_in`,
    /// the replay's path without the carry) into `rec`; their count.
    pub(super) fn general_fill(poly: &[ScreenPt], band: &TriangleBand, rec: &mut Rec) -> usize {
        let (mut edges, mut active) = ([Edge::ZERO; 16], [0u16; 16]);
        let filled = fill_polygon_in(
            poly,
            None,
            band.sub,
            FillRule::NonZero,
            &band.b,
            &mut edges,
            &mut active,
            (),
            rec,
        );
        let Ok(spans) = filled else { panic!("fill") };
        spans
    }

    /// Random triangles drawn in bands of random heights: resuming the
    /// state a band kept (after a trip through the ring's words) emits in
    /// every band exactly what a fresh set-up there emits (the replay's
    /// path without the carry, itself tested against the polygon fill in
    /// `chain`), and a triangle is kept exactly while rows are left.
    #[test]
    fn kept_triangles_equal_a_fresh_set_up_in_every_band() {
        let mut rng = Rng(2121);
        let mut words = [0u32; 3 * WORDS];
        let mut kept = 0;
        for k in 0..4000 {
            let (sub, m, tri) = corners(&mut rng, k, 3, false);
            if !packs(sub) {
                continue; // `TriangleBand::new` declines: the general fill
            }
            let tri = [tri[0], tri[1], tri[2]];
            let mut ring = Ring::new();
            let rgb = rgb_word(Rgb888::new(k as u8, 2, 3));
            for band in bands(&mut rng, m, sub) {
                let (b, y0) = (band.b, band.b.y0);
                let mut fresh = Rec(Vec::new(), b);
                let want = band.fill(tri, (), &mut fresh);
                ring.begin(&words);
                let mut got = Rec(Vec::new(), b);
                let mut state = None;
                if let Some((at, row)) = ring.peek(&words) {
                    assert_eq!((at, row), (7, y0));
                    let (mut t, c) = ring.pop(&words).unwrap();
                    assert_eq!(c, rgb);
                    let n = band.run(&mut t, band.first_row(), (), &mut got);
                    assert_eq!(Some(n), want);
                    kept += 1;
                    state = Some(t);
                } else if let Start::Rows(mut t, y) = band.start(tri) {
                    let n = band.run(&mut t, y, (), &mut got);
                    assert_eq!(Some(n), want);
                    state = Some(t);
                }
                assert_eq!(got.0, fresh.0, "{tri:?} {sub} {b:?}");
                if let Some(t) = state.filter(|t| band.continues(t)) {
                    assert!(ring.push(&mut words, &t, (7, band.end_row()), rgb));
                }
            }
        }
        assert!(kept > 1000, "{kept}");
    }

    /// The ring keeps entries in order, refuses one when full (nothing
    /// written), drops at a band's start what the band before did not
    /// meet, and never holds more than its words allow.
    #[test]
    fn ring_order_capacity_and_stale_entries() {
        let band = TriangleBand {
            sub: 0,
            b: SpanBounds {
                x0: 0,
                y0: 0,
                x1: 8,
                y1: 4,
            },
        };
        let Start::Rows(t, _) = band.start([pt(0, 0), pt(5, 9), pt(1, 9)]) else {
            panic!("rows")
        };
        let rgb = rgb_word(Rgb888::new(1, 2, 3));
        let mut words = [0u32; 2 * WORDS + 3];
        let mut ring = Ring::new();
        ring.begin(&words);
        assert_eq!(ring.peek(&words), None);
        assert!(ring.push(&mut words, &t, (3, 4), rgb));
        assert!(ring.push(&mut words, &t, (9, 4), rgb));
        assert!(!ring.push(&mut words, &t, (11, 4), rgb));
        assert!(!Ring::new().push(&mut words, &t, (70_000, 4), rgb));
        assert_eq!(ring.most(), 2);
        // This band's own entries are not its incoming.
        assert_eq!(ring.peek(&words), None);
        ring.begin(&words);
        assert_eq!(ring.peek(&words), Some((3, 4)));
        assert!(ring.pop(&words).is_some());
        assert_eq!(ring.peek(&words), Some((9, 4)));
        // Room again: one slot freed, wrapping around.
        assert!(ring.push(&mut words, &t, (12, 8), rgb));
        assert!(!ring.push(&mut words, &t, (13, 8), rgb));
        // (9, 4) was not met: dropped at the next band's start.
        ring.begin(&words);
        assert_eq!(ring.peek(&words), Some((12, 8)));
        ring.skip();
        assert_eq!(ring.peek(&words), None);
        // Never more than `MAX_KEPT`, however many words.
        let mut many = std::vec![0u32; (MAX_KEPT + 5) * WORDS];
        let mut big = Ring::new();
        big.begin(&many);
        for k in 0..MAX_KEPT {
            assert!(big.has_room());
            assert!(big.push(&mut many, &t, (k, 4), rgb));
        }
        assert!(!big.has_room());
        assert!(!big.push(&mut many, &t, (MAX_KEPT, 4), rgb));
        assert_eq!(big.most(), MAX_KEPT);
        // No words: nothing kept, nothing read.
        let mut none: [u32; 0] = [];
        ring.begin(&none);
        assert!(!ring.push(&mut none, &t, (1, 4), rgb));
        assert_eq!(ring.peek(&none), None);
    }
}
