//! Polygons of five to [`MAX_SIDES`] corners kept across a band edge with
//! **four or more corners still ahead** (see [`super::poly`], which keeps
//! the ones with at most three as quads' entries). Their state does not
//! fit a ring entry, and a third kind of ring entry slowed the replay's
//! loop more than it saved (session 16), so they go to a second, smaller
//! FIFO that the replay's loop never reads: only [`TriangleBand::poly`],
//! out of line, which the replay calls for a polygon of five or more
//! corners cut by the band's top or end, looks in it.
//!
//! An entry holds the two chains' steppers, the arc positions and the
//! polygon's top corner, not its corners: the replay has just read the
//! record's points for the call, so the arc is rebuilt from them, and the
//! box, the monotonicity pass and the chain seeks from the top (two exact
//! starts, each with two divisions) are what a resume saves.
//!
//! # Contract
//!
//! * The store lives in the spare words **beyond** the ring's most
//!   ([`super::MAX_KEPT`] entries): with fewer words there is no store,
//!   and everything else (the ring, the memory a frame needs) is as
//!   before. It is a cache: an entry that does not fit is not kept, and
//!   the next band sets the polygon up again (the same picture).
//! * Entries are in record order, as the ring's, and the next band meets
//!   them in that order: [`Side::take`] drops the entries it passes, and
//!   [`Side::begin`] what the band before left unmet; an entry is only
//!   taken for its record offset and row.
//! * A resumed polygon emits exactly what `fill_polygon_in` would in that
//!   band (the chains' contract, [`super::quad`]): tested below against
//!   it in bands of random heights.

use embedded_graphics::pixelcolor::Rgb888;

use super::super::chain::TriangleBand;
use super::super::edge::Dda32;
use super::super::scan::{Paint, SpanSink};
use super::super::transform::ScreenPt;
use super::poly::{Poly, PolyStart, ARC, MAX_SIDES};
use super::{Ring, MAX_KEPT, WORDS};

/// Words (`u32`) a kept polygon takes in the store.
pub(crate) const SIDE_WORDS: usize = 12;

/// Most entries the store holds at once: bench_city's bands cut about
/// 20–80 such polygons a frame, a band at most about 20.
const MAX_SIDE: usize = 64;

/// The store's words: those past the ring's most.
#[inline(always)]
fn store(words: &mut [u32]) -> &mut [u32] {
    words.get_mut(MAX_KEPT * WORDS..).unwrap_or_default()
}

/// How many words [`store`] gives.
#[inline(always)]
fn store_len(words: &[u32]) -> usize {
    words.len().saturating_sub(MAX_KEPT * WORDS)
}

/// Entries a store over `words` (the store's own) holds.
#[inline(always)]
fn capacity(len: usize) -> usize {
    (len / SIDE_WORDS).min(MAX_SIDE)
}

/// The second FIFO's place: as [`Ring`]'s fields for the ring.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Side {
    /// Slot of the oldest entry.
    head: usize,
    /// Entries held.
    len: usize,
    /// Entries at the head kept by the previous band and not yet met.
    incoming: usize,
}

impl Side {
    /// An empty store.
    pub(crate) const fn new() -> Self {
        Side {
            head: 0,
            len: 0,
            incoming: 0,
        }
    }

    /// Starts a band, as [`Ring::begin`]: the unmet entries of the band
    /// before are dropped, what it kept becomes this band's incoming.
    pub(crate) fn begin(&mut self, words: &[u32]) {
        let cap = capacity(store_len(words));
        if cap == 0 {
            *self = Side::new();
            return;
        }
        self.head = (self.head + self.incoming) % cap;
        self.len -= self.incoming.min(self.len);
        self.incoming = self.len;
    }

    /// Drops the next incoming entry.
    fn skip(&mut self, cap: usize) {
        if self.incoming == 0 || cap == 0 {
            return;
        }
        self.head = (self.head + 1) % cap;
        self.len -= 1;
        self.incoming -= 1;
    }

    /// Resumes into `q` the state kept for record `here` on row `row`,
    /// its arc rebuilt from the record's corners `pts` (in place: the
    /// state is large, and a returned copy of it is a block move); the
    /// entries before it (not met where expected: they cannot be) are
    /// dropped. Gives the polygon's top corner, `None` when there is no
    /// entry for it.
    fn take(
        &mut self,
        words: &mut [u32],
        (here, row): (usize, i32),
        pts: &[ScreenPt],
        q: &mut Poly,
    ) -> Option<usize> {
        let words = store(words);
        let cap = capacity(words.len());
        while self.incoming > 0 {
            let at = self.head * SIDE_WORDS;
            let w: &[u32; SIDE_WORDS] = words.get(at..at + SIDE_WORDS)?.try_into().ok()?;
            let (offset, from) = ((w[10] & 0xffff) as usize, (w[10] as i32) >> 16);
            if offset > here {
                return None;
            }
            if offset < here || from != row {
                self.skip(cap);
                continue;
            }
            let dda = |k: usize| Dda32::from_words([w[k], w[k + 1], w[k + 2], w[k + 3], w[k + 4]]);
            let s = w[11];
            let (lo, hi, top) = (
                (s & 15) as usize,
                (s >> 4 & 15) as usize,
                (s >> 8 & 15) as usize,
            );
            let n = pts.len();
            if top >= n || !(1..=n).contains(&lo) || !(lo..=n).contains(&hi) {
                self.skip(cap);
                return None;
            }
            (q.l, q.r, q.lo, q.hi, q.end) = (dda(0), dda(5), lo, hi, (s as i32) >> 16);
            self.skip(cap);
            fill_arc(&mut q.arc, pts, top);
            return Some(top);
        }
        None
    }

    /// Keeps `q` (top corner `top`, record `offset`) for the band starting
    /// on row `row`; `false`, nothing kept, when the store is full or
    /// absent. Rows are within ±2^14, so they fit 16 bits.
    fn push(
        &mut self,
        words: &mut [u32],
        q: &Poly,
        top: usize,
        (offset, row): (usize, i32),
    ) -> bool {
        let words = store(words);
        let cap = capacity(words.len());
        if self.len >= cap || offset > usize::from(u16::MAX) || q.lo > 15 || q.hi > 15 || top > 15 {
            return false;
        }
        let at = (self.head + self.len) % cap * SIDE_WORDS;
        let Some(out) = words.get_mut(at..at + SIDE_WORDS) else {
            return false;
        };
        let Ok(out) = <&mut [u32; SIDE_WORDS]>::try_from(out) else {
            return false;
        };
        let [l0, l1, l2, l3, l4] = q.l.to_words();
        let [r0, r1, r2, r3, r4] = q.r.to_words();
        // Word by word: a copy of an array is a `memcpy` call.
        out[0] = l0;
        out[1] = l1;
        out[2] = l2;
        out[3] = l3;
        out[4] = l4;
        out[5] = r0;
        out[6] = r1;
        out[7] = r2;
        out[8] = r3;
        out[9] = r4;
        out[10] = (offset as u32) | (row as u32) << 16;
        out[11] = q.lo as u32 | (q.hi as u32) << 4 | (top as u32) << 8 | (q.end as u32) << 16;
        self.len += 1;
        true
    }
}

/// The corners of `pts` from corner `top` on, the top again after them
/// (two copies, not an index modulo the count: a division per corner).
#[inline(always)]
pub(super) fn arc_of(pts: &[ScreenPt], top: usize) -> [ScreenPt; ARC] {
    let mut arc = [ScreenPt::default(); ARC];
    fill_arc(&mut arc, pts, top);
    arc
}

/// [`arc_of`] into `arc`.
#[inline(always)]
fn fill_arc(arc: &mut [ScreenPt; ARC], pts: &[ScreenPt], top: usize) {
    let n = pts.len();
    let mut at = top;
    for dst in arc.iter_mut().take(n + 1) {
        if at >= n {
            at = 0;
        }
        if let Some(&p) = pts.get(at) {
            *dst = p;
        }
        at += 1;
    }
}

impl TriangleBand {
    /// Fills polygon `pts` (five to [`MAX_SIDES`] corners; record `here`,
    /// id `id`) in this band, which cuts it: its top (`cut.0`: it may have
    /// been kept by the band before) or its end (`cut.1`: it goes on in
    /// the next band of this list, so is kept). A kept state is resumed;
    /// else a polygon that goes on is set up by the chains
    /// ([`TriangleBand::start_poly`]). It is kept again when it goes on,
    /// as a quad's entry in the ring with at most three corners ahead,
    /// else in the store. `None`, nothing emitted, when it is the general
    /// fill's (not kept and not going on, or not for the chains). Out of
    /// line: the replay's loop keeps its registers for the triangles and
    /// quads.
    #[inline(never)]
    pub(crate) fn poly<K: SpanSink>(
        &self,
        pts: &[ScreenPt],
        (ring, words): (&mut Ring, &mut [u32]),
        (here, rgb, id): (usize, Rgb888, u32),
        (first, end, keep): (i32, i32, bool),
        sink: &mut K,
    ) -> Option<u64> {
        let (top_cut, goes_on) = (first < self.b.y0, keep && end > self.b.y1);
        if !(top_cut || goes_on) || !(3..=MAX_SIDES).contains(&pts.len()) {
            return None;
        }
        let mut q = Poly::EMPTY;
        let kept = if top_cut {
            ring.side.take(words, (here, self.first_row()), pts, &mut q)
        } else {
            None
        };
        let (y, top) = match kept {
            Some(top) => {
                // Each chain's edge ends on its vertex's row.
                let row = |p: ScreenPt| Dda32::rows(p, p, self.sub).1;
                q.ly1 = q.arc.get(q.lo).map_or(0, |&p| row(p));
                q.ry1 = q.arc.get(q.hi).map_or(0, |&p| row(p));
                (self.first_row(), top)
            }
            None if goes_on => match self.start_poly(pts) {
                PolyStart::Outside => return None,
                PolyStart::Empty => return Some(0),
                PolyStart::Rows(p, y, top) => {
                    q = p;
                    (y, top)
                }
            },
            None => return None,
        };
        let color = sink.color(&Paint { rgb, id });
        let spans = self.run_chains(&mut q, y, color, sink) as u64;
        if goes_on && q.end > self.b.y1 {
            if let Some(quad) = q.as_quad() {
                ring.push_quad(words, &quad, (here, self.end_row()), rgb);
            } else {
                ring.side.push(words, &q, top, (here, self.end_row()));
            }
        }
        Some(spans)
    }
}
