//! The four-sided pieces of split triangles carried across band edges
//! (see [`super`]): a polygon of four corners cut by a band's end keeps
//! its two chains' edge steppers and the vertices still ahead, and the
//! next band resumes it instead of the general fill's box, monotonicity
//! pass and chain seeks.
//!
//! # Contract
//!
//! [`TriangleBand::start_quad`] then [`TriangleBand::run_chains`] (or,
//! for a quad ending in the band, [`QuadStart::Whole`], the full frame's
//! `chain::quad_rows`) emit exactly the spans of `fill_polygon_in` for
//! the same polygon and band (or decline, [`QuadStart::Outside`], before
//! emitting anything, where that one takes its general path);
//! [`TriangleBand::run_chains`] of the state it left, resumed in the next
//! band (through the ring's words, [`Ring::pop_quad`]), emits exactly
//! what `fill_polygon_in` would there.

use embedded_graphics::pixelcolor::Rgb888;

use super::super::chain::{
    is_y_monotone, last_above, opposite_lowest, pair_of, quad_rows, TriangleBand,
};
use super::super::edge::{packs, Dda32, Packed, Stepper, SMALL};
use super::super::scan::{pair_rows, Bbox, Paint, Pair, SpanSink};
use super::super::transform::ScreenPt;
use super::{most_ahead, Ring};

/// A stepper a kept polygon's state holds between bands (the band carry,
/// [`super`], [`Chains`]): made from a [`Dda32`] when a chain starts an edge, and
/// written to and read from the ring's words as it is, so that a resumed
/// polygon steps on without converting (a [`Packed`] was packed from and
/// stored back into a `Dda32` on every resume: session 21).
pub(crate) trait Kept: Stepper + Copy + Default + core::fmt::Debug {
    /// Words it takes in a ring entry.
    const WORDS: usize;
    /// The stepper of the edge `d` starts.
    fn of(d: &Dda32) -> Self;
    /// Its words (the first [`Kept::WORDS`] of the array).
    fn to_words(&self) -> [u32; 5];
    /// The stepper [`Kept::to_words`] wrote (`w`: its first words).
    fn from_words(w: &[u32]) -> Self;
}

impl Kept for Dda32 {
    const WORDS: usize = 5;
    #[inline(always)]
    fn of(d: &Dda32) -> Self {
        *d
    }
    #[inline(always)]
    fn to_words(&self) -> [u32; 5] {
        Dda32::to_words(*self)
    }
    #[inline(always)]
    fn from_words(w: &[u32]) -> Self {
        match *w {
            [c, g, qs, rs, d, ..] => Dda32::from_words([c, g, qs, rs, d]),
            _ => Dda32::default(),
        }
    }
}

impl Kept for Packed {
    const WORDS: usize = 3;
    #[inline(always)]
    fn of(d: &Dda32) -> Self {
        Packed::of(d)
    }
    #[inline(always)]
    fn to_words(&self) -> [u32; 5] {
        let [a, b, c] = Packed::to_words(*self);
        [a, b, c, 0, 0]
    }
    #[inline(always)]
    fn from_words(w: &[u32]) -> Self {
        match *w {
            [a, b, c, ..] => Packed::from_words([a, b, c]),
            _ => Packed::default(),
        }
    }
}

/// A polygon's fill state on some row, for an arc of `N` points (the
/// four-sided pieces of split triangles here, `N` = 5; the longer
/// polygons of [`super::poly`] share it with a longer arc): each chain's
/// current edge, and the vertices still ahead of them (see
/// [`crate::raster::chain::fill_monotone`] for the two chains). The edges
/// step as `S`: [`Packed`] where [`packs`] holds (as the chains of
/// `fill_polygon_in` step them), else [`Dda32`]; a band picks one by its
/// sub-pixel bits ([`TriangleBand::quad`]) and the ring keeps it as it is.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Chains<S, const N: usize> {
    /// The chain walking the vertex list forward, and its edge's end row.
    pub(super) l: S,
    pub(super) ly1: i32,
    /// The chain walking it backward, and its edge's end row.
    pub(super) r: S,
    pub(super) ry1: i32,
    /// The vertices from the top, in list order, the top again at the
    /// end: the forward chain's edge ends at `arc[lo]`, the backward
    /// one's at `arc[hi]`; `arc[lo..=hi]` are the vertices still ahead.
    pub(super) arc: [ScreenPt; N],
    pub(super) lo: usize,
    pub(super) hi: usize,
    /// One past the polygon's last row.
    pub(crate) end: i32,
}

/// A four-sided polygon's fill state: its four corners from the top, the
/// top again after them.
pub(crate) type Quad<S> = Chains<S, 5>;

/// What [`TriangleBand::start_quad`] found.
#[derive(Clone, Copy, Debug)]
pub(crate) enum QuadStart<S> {
    /// Not for the chains (a corner outside ±`SMALL`, or not y-monotone):
    /// the general fill's.
    Outside,
    /// Nothing to fill in this band.
    Empty,
    /// The state to run from row `.1` (its chains not yet sought).
    Rows(Quad<S>, i32),
    /// A quad whose rows end in this band and whose corner opposite the
    /// top one is a lowest one: its corners from the top (`t, l, o, r`),
    /// its rows `[y, stop)` here and whether its box lies within the
    /// band's columns, for the full frame's `chain::quad_rows` (no
    /// chain seeks, nothing to keep).
    Whole([ScreenPt; 4], [i32; 2], bool),
}

/// The chain of `arc` from vertex `*at` one vertex on (`fwd`: forward)
/// to the edge active on row `y`, as `Chain::seek` in
/// [`crate::raster::chain`] (without clamping the end row to a band: the state
/// goes on in the next band); false where that one gives up.
#[inline(always)]
pub(super) fn seek<S: Kept, const N: usize>(
    arc: &[ScreenPt; N],
    (at, fwd): (&mut usize, bool),
    (dda, y1): (&mut S, &mut i32),
    sub: u32,
    y: i32,
) -> bool {
    let above = last_above(y, sub);
    for _ in 0..N - 1 {
        let next = if fwd { *at + 1 } else { at.wrapping_sub(1) };
        let (Some(&from), Some(&to)) = (arc.get(*at), arc.get(next)) else {
            return false;
        };
        *at = next;
        if to.y <= above {
            continue;
        }
        if to.y <= from.y {
            return false;
        }
        let (first, end) = Dda32::rows(from, to, sub);
        if first > y {
            return false;
        }
        *y1 = end;
        *dda = S::of(&Dda32::start(from, to, sub, y));
        return true;
    }
    false
}

impl TriangleBand {
    /// Sets up the four-sided polygon `pts` as `fill_polygon_in` does
    /// (its box rejects, then [`crate::raster::chain::fill_monotone`]'s set-up),
    /// to run from the first row of this band it touches.
    #[inline(always)]
    pub(crate) fn start_quad<S: Kept>(&self, pts: [ScreenPt; 4]) -> QuadStart<S> {
        let bbox = Bbox::of(&pts);
        let Bbox {
            lo, hi, top, bot, ..
        } = bbox;
        if !(lo > -SMALL && hi < SMALL && top > -SMALL && bot < SMALL) {
            return QuadStart::Outside;
        }
        let (sub, b) = (self.sub, &self.b);
        let col = |x: i32| (2 * x - (1 << sub)) >> (sub + 1);
        if col(hi) < b.x0 || col(lo) >= b.x1 {
            return QuadStart::Empty;
        }
        let (first, end) = Dda32::rows(ScreenPt { x: 0, y: top }, ScreenPt { x: 0, y: bot }, sub);
        if end <= b.y0 || first >= b.y1 || top == bot {
            return QuadStart::Empty;
        }
        let t = bbox.top_at;
        // Most quads are monotone with their chains meeting opposite the
        // top corner: two comparisons instead of the monotonicity pass.
        let opposite = opposite_lowest(&pts, t);
        if !opposite && !is_y_monotone(&pts, t) {
            return QuadStart::Outside;
        }
        let y = first.max(b.y0);
        if y >= end.min(b.y1) {
            return QuadStart::Empty;
        }
        let at = |k: usize| pts[(t + k) % 4];
        // A quad ending in this band has nothing to keep: the full frame's
        // row function fills it, its chains known from the corners (no
        // state to build, no seeks; packed steppers only). Session 24:
        // the firmware band set 0.4 to 8.5 k lower a frame.
        if opposite && end <= b.y1 && packs(sub) {
            let within = pair_of(&bbox, sub, b) == Pair::Within;
            return QuadStart::Whole([at(0), at(1), at(2), at(3)], [y, end], within);
        }
        let quad = Quad {
            l: S::default(),
            ly1: y,
            r: S::default(),
            ry1: y,
            arc: [at(0), at(1), at(2), at(3), at(0)],
            lo: 0,
            hi: 4,
            end,
        };
        QuadStart::Rows(quad, y)
    }

    /// Fills `q`'s rows from `y` (its current row) to the band's end or
    /// the polygon's; returns the spans. As for a triangle, it goes on in
    /// the next band when `q.end` is past this band's end
    /// ([`TriangleBand::continues_quad`]), and only then is it left stepped
    /// to that row (else only `q.end` is meaningful).
    #[inline(always)]
    pub(crate) fn run_chains<K: SpanSink, S: Kept, const N: usize>(
        &self,
        q: &mut Chains<S, N>,
        mut y: i32,
        color: K::Color,
        sink: &mut K,
    ) -> usize {
        let stop = q.end.min(self.b.y1);
        let mut spans = 0;
        // The chains' state in locals (registers) for the row loop, the
        // vertices left in memory.
        let (mut l, mut ly1, mut r, mut ry1) = (q.l, q.ly1, q.r, q.ry1);
        let (mut lo, mut hi) = (q.lo, q.hi);
        while y < stop {
            let ok = (ly1 > y || seek(&q.arc, (&mut lo, true), (&mut l, &mut ly1), self.sub, y))
                && (ry1 > y || seek(&q.arc, (&mut hi, false), (&mut r, &mut ry1), self.sub, y));
            if !ok {
                // Where the chain fill gives up: nothing more, here or after.
                q.end = y;
                break;
            }
            let run = ly1.min(ry1).min(stop);
            spans += pair_rows(&mut l, &mut r, Pair::Span, &self.b, y, run, color, sink);
            y = run;
        }
        // Stepped to the band's end only for a polygon that goes on (the
        // one state a caller keeps, [`TriangleBand::continues_quad`]): most
        // end in the band, and the fourteen stores were 30 k of a
        // bench_city band frame.
        if self.continues_quad_at(q.end) {
            (q.l, q.ly1, q.r, q.ry1, q.lo, q.hi) = (l, ly1, r, ry1, lo, hi);
        }
        spans
    }

    /// Resumes the four-sided polygon at the ring's head (record `here`)
    /// in this band, keeping it again (with `keep`) when it goes on;
    /// returns the spans. In line in the replay's loop.
    #[inline(always)]
    pub(crate) fn resume_quad<K: SpanSink>(
        &self,
        ring: &mut Ring,
        words: &mut [u32],
        (here, keep): (usize, bool),
        sink: &mut K,
    ) -> u64 {
        if packs(self.sub) {
            self.resume_as::<K, Packed>(ring, words, (here, keep), sink)
        } else {
            self.resume_as::<K, Dda32>(ring, words, (here, keep), sink)
        }
    }

    /// [`TriangleBand::resume_quad`] with the ring's steppers `S` (the
    /// band's): a quad's state, or (out of line, with packed steppers) a
    /// longer polygon's with four or five corners ahead.
    #[inline(always)]
    pub(super) fn resume_as<K: SpanSink, S: Kept>(
        &self,
        ring: &mut Ring,
        words: &mut [u32],
        (here, keep): (usize, bool),
        sink: &mut K,
    ) -> u64 {
        if most_ahead::<S>() > 3 && ring.next_ahead(words) > 3 {
            return self.resume_long::<K, S>(ring, words, (here, keep), sink);
        }
        self.resume_n::<K, S, 5>(ring, words, (here, keep), sink)
    }

    /// [`TriangleBand::resume_as`] of a polygon with more than three
    /// corners ahead: out of line, so that the quads' resume in the
    /// replay's loop stays as it was.
    #[inline(never)]
    fn resume_long<K: SpanSink, S: Kept>(
        &self,
        ring: &mut Ring,
        words: &mut [u32],
        (here, keep): (usize, bool),
        sink: &mut K,
    ) -> u64 {
        self.resume_n::<K, S, 7>(ring, words, (here, keep), sink)
    }

    /// Resumes the entry at the ring's head as a state of arc `N`.
    #[inline(always)]
    fn resume_n<K: SpanSink, S: Kept, const N: usize>(
        &self,
        ring: &mut Ring,
        words: &mut [u32],
        (here, keep): (usize, bool),
        sink: &mut K,
    ) -> u64 {
        let Some((mut q, word)) = ring.pop_quad::<S, N>(words, self) else {
            return 0;
        };
        let color = sink.kept_color(word);
        let spans = self.run_chains(&mut q, self.first_row(), color, sink) as u64;
        if keep && self.continues_quad_at(q.end) {
            ring.push_quad(words, &q, (here, self.end_row()), word);
        }
        spans
    }

    /// Sets up and fills the four-sided polygon `pts` (record `here`, id
    /// `id`) and, when this band's end cuts it, keeps it for the next band
    /// (the caller passes a polygon that goes on only when there is a next
    /// band of the same list); `None`, nothing emitted, when it is the
    /// general fill's ([`TriangleBand::start_quad`]).
    #[inline(never)]
    pub(crate) fn quad<K: SpanSink>(
        &self,
        pts: [ScreenPt; 4],
        (ring, words): (&mut Ring, &mut [u32]),
        (here, rgb, id): (usize, Rgb888, u32),
        sink: &mut K,
    ) -> Option<u64> {
        if packs(self.sub) {
            self.quad_as::<K, Packed>(pts, (ring, words), (here, rgb, id), sink)
        } else {
            self.quad_as::<K, Dda32>(pts, (ring, words), (here, rgb, id), sink)
        }
    }

    /// [`TriangleBand::quad`] with steppers `S` (the band's).
    #[inline(always)]
    fn quad_as<K: SpanSink, S: Kept>(
        &self,
        pts: [ScreenPt; 4],
        (ring, words): (&mut Ring, &mut [u32]),
        (here, rgb, id): (usize, Rgb888, u32),
        sink: &mut K,
    ) -> Option<u64> {
        match self.start_quad::<S>(pts) {
            QuadStart::Outside => None,
            QuadStart::Empty => Some(0),
            QuadStart::Whole(corners, rows, within) => {
                let color = sink.color(&Paint { rgb, id });
                let (sub, b) = (self.sub, &self.b);
                Some(quad_rows(corners, sub, rows, within, b, color, sink) as u64)
            }
            QuadStart::Rows(mut q, y) => {
                let paint = Paint { rgb, id };
                let color = sink.color(&paint);
                let spans = self.run_chains(&mut q, y, color, sink) as u64;
                if self.continues_quad(&q) {
                    let word = sink.keep_color(color, &paint);
                    ring.push_quad(words, &q, (here, self.end_row()), word);
                }
                Some(spans)
            }
        }
    }

    /// Whether `q`, run through this band, has rows after it.
    #[inline(always)]
    pub(crate) fn continues_quad<S>(&self, q: &Quad<S>) -> bool {
        self.continues_quad_at(q.end)
    }

    /// Whether a polygon whose rows end before row `end` has rows after
    /// this band.
    #[inline(always)]
    pub(super) fn continues_quad_at(&self, end: i32) -> bool {
        end > self.b.y1
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::super::chain::tests::Rec;
    use super::super::super::scan::rgb_word;
    use super::super::tests::{bands, corners, general_fill};
    use super::super::{Start, WORDS};
    use super::*;
    use crate::raster::tests::Rng;
    use std::vec::Vec;

    /// Random four-sided polygons (convex ones, as the pieces of split
    /// triangles are, and any others) drawn in bands of random heights:
    /// set up in a band, or resumed from the state the band before kept
    /// (after a trip through the ring's words, beside a kept triangle),
    /// they emit in every band exactly the spans of `fill_polygon_in`
    /// there, the general fill's path the replay takes without the carry.
    #[test]
    fn kept_quads_equal_the_polygon_fill_in_every_band() {
        let (kept, fresh_runs, general) = quad_sweep::<Dda32>(4545, false);
        assert!(
            kept > 1000 && fresh_runs > 1000 && general > 100,
            "{kept} {fresh_runs} {general}"
        );
        // Packed steppers where the band's sub-pixel bits allow them
        // (a quarter of the cases), as the replay keeps them there.
        let (kept, fresh_runs, general) = quad_sweep::<Packed>(45451, true);
        assert!(
            kept > 250 && fresh_runs > 250 && general > 10,
            "{kept} {fresh_runs} {general}"
        );
    }

    /// The sweep of [`kept_quads_equal_the_polygon_fill_in_every_band`] with steppers `S`, over the cases
    /// whose sub-pixel bits [`packs`] with `packed_only`: how many
    /// band pieces were resumed, set up fresh, and left to the general fill.
    fn quad_sweep<S: Kept>(seed: u64, packed_only: bool) -> (usize, usize, usize) {
        let mut rng = Rng(seed);
        let mut words = [0u32; 4 * WORDS];
        let (mut kept, mut fresh_runs, mut general) = (0, 0, 0);
        for k in 0..4000 {
            let (sub, m, quad) = corners(&mut rng, k, 4, k % 3 != 0);
            if packed_only && !packs(sub) {
                continue;
            }
            let quad = [quad[0], quad[1], quad[2], quad[3]];
            let tri = [quad[0], quad[1], quad[2]];
            let mut ring = Ring::new();
            let rgb = rgb_word(Rgb888::new(k as u8, 2, 3));
            for band in bands(&mut rng, m, sub) {
                let (b, y0) = (band.b, band.b.y0);
                let mut want = Rec(Vec::new(), b);
                let n = general_fill(&quad, &band, &mut want);
                ring.begin(&words);
                // A triangle kept before the quad (record 3), so that the
                // two kinds share the ring.
                let mut t_state = None;
                if ring.peek(&words).is_some_and(|(at, _)| at == 3) {
                    assert!(!ring.next_is_quad(&words));
                    let Some((t, _)) = ring.pop(&words) else {
                        panic!("a triangle")
                    };
                    t_state = Some((t, band.first_row()));
                } else if let Start::Rows(t, y) = band.start(tri) {
                    t_state = Some((t, y));
                }
                if let Some((mut t, y)) = t_state {
                    band.run(&mut t, y, (), &mut Rec(Vec::new(), b));
                    if band.continues(&t) {
                        assert!(ring.push(&mut words, &t, (3, band.end_row()), rgb));
                    }
                }
                let mut got = Rec(Vec::new(), b);
                let mut state = None;
                if let Some((at, row)) = ring.peek(&words) {
                    assert_eq!((at, row), (7, y0));
                    assert!(ring.next_is_quad(&words));
                    let Some((mut q, c)) = ring.pop_quad::<S, 5>(&words, &band) else {
                        panic!("a quad")
                    };
                    assert_eq!(c, rgb);
                    assert_eq!(band.run_chains(&mut q, band.first_row(), (), &mut got), n);
                    kept += 1;
                    state = Some(q);
                } else {
                    match band.start_quad::<S>(quad) {
                        QuadStart::Outside => {
                            general += 1;
                            general_fill(&quad, &band, &mut got);
                        }
                        QuadStart::Empty => assert_eq!(n, 0),
                        QuadStart::Whole(c, rows, within) => {
                            fresh_runs += 1;
                            let (sub, b) = (band.sub, &band.b);
                            assert_eq!(quad_rows(c, sub, rows, within, b, (), &mut got), n);
                        }
                        QuadStart::Rows(mut q, y) => {
                            fresh_runs += 1;
                            assert_eq!(band.run_chains(&mut q, y, (), &mut got), n);
                            state = Some(q);
                        }
                    }
                }
                assert_eq!(got.0, want.0, "{quad:?} {sub} {b:?}");
                if let Some(q) = state.filter(|q| band.continues_quad(q)) {
                    assert!(ring.push_quad(&mut words, &q, (7, band.end_row()), rgb));
                }
            }
        }
        (kept, fresh_runs, general)
    }
}
