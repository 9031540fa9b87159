//! Polygons of five to [`MAX_SIDES`] corners carried across band edges
//! (see [`super`]; bench_city's polygons average 5.3 corners). Such a
//! polygon cut by a band's end is set up once by the chains (as the
//! general fill's monotone path does), and once no more of its corners
//! are left ahead than an entry holds (three with `Dda32` steppers, five
//! with packed ones: `super::most_ahead`) it is kept in the ring **as a
//! four-sided polygon's entry**: two edge steppers and the corners ahead
//! are all a resumed chain fill needs, whatever the polygon had above. So
//! the next band resumes it by the quads' own path ([`super::quad`],
//! `Ring::pop_quad`; with more than three corners ahead, its out-of-line
//! twin with a longer arc).
//!
//! Why a path of its own: generalising the quads' state to nine corners
//! (session 15, f55b955) took the general fill's set-ups off these
//! polygons but slowed every quad (the longer arc's slice and seek loops)
//! and the replay (its pre-check inline): a loss on bench_city. Here the
//! quads' code is untouched and this set-up is out of line, called only
//! for a polygon of five or more corners that goes on below the band.
//!
//! # Contract
//!
//! [`TriangleBand::start_poly`] then [`TriangleBand::run_chains`] emit
//! exactly the spans of `fill_polygon_in` for the same polygon and band
//! (or decline, [`PolyStart::Outside`], before emitting anything, where
//! that one takes its general path). The state [`TriangleBand::poly`]
//! keeps (only with at most `most_ahead` corners ahead, else nothing: the next
//! band sets the polygon up again, the same picture), resumed in the next
//! band by `Ring::pop_quad` and `TriangleBand::run_chains`, emits exactly
//! what `fill_polygon_in` would there.

use embedded_graphics::pixelcolor::Rgb888;

use super::super::chain::{is_y_monotone, TriangleBand};
use super::super::edge::{packs, Dda32, Packed, SMALL};
use super::super::scan::{Bbox, Paint, SpanSink};
use super::super::transform::ScreenPt;
use super::quad::{Chains, Kept};
use super::Ring;

/// Most corners of a polygon this path sets up; one with more takes the
/// general fill. 12 since session 21 (8 before): with packed ring entries
/// holding five corners ahead, a polygon of 9 to 12 corners is often kept
/// after its first band (bench_city's band frames 6 to 21 k lower than
/// with 8; 10 gave 6 to 19 k more than 12, 16 gave 3 to 7 k more).
pub(crate) const MAX_SIDES: usize = 12;

/// The arc's room: the corners from the top, the top again after them.
const ARC: usize = MAX_SIDES + 1;

/// A polygon's fill state on some row: [`Quad`]'s with a longer arc.
pub(crate) type Poly<S> = Chains<S, ARC>;

/// What [`TriangleBand::start_poly`] found.
#[derive(Clone, Copy, Debug)]
pub(crate) enum PolyStart<S> {
    /// Not for the chains (more than [`MAX_SIDES`] corners, a corner
    /// outside ±`SMALL`, or not y-monotone): the general fill's.
    Outside,
    /// Nothing to fill in this band.
    Empty,
    /// The state to run from row `.1` (its chains not yet sought).
    Rows(Poly<S>, i32),
}

impl TriangleBand {
    /// Sets up polygon `pts` (five to [`MAX_SIDES`] corners; any count
    /// from three works) as `fill_polygon_in` does (its box rejects, then
    /// [`crate::raster::chain::fill_monotone`]'s set-up), to run from the
    /// first row of this band it touches.
    #[inline(always)]
    pub(crate) fn start_poly<S: Kept>(&self, pts: &[ScreenPt]) -> PolyStart<S> {
        let n = pts.len();
        if !(3..=MAX_SIDES).contains(&n) {
            return PolyStart::Outside;
        }
        let bbox = Bbox::of(pts);
        let Bbox {
            lo, hi, top, bot, ..
        } = bbox;
        if !(lo > -SMALL && hi < SMALL && top > -SMALL && bot < SMALL) {
            return PolyStart::Outside;
        }
        let (sub, b) = (self.sub, &self.b);
        let col = |x: i32| (2 * x - (1 << sub)) >> (sub + 1);
        if col(hi) < b.x0 || col(lo) >= b.x1 {
            return PolyStart::Empty;
        }
        let (first, end) = Dda32::rows(ScreenPt { x: 0, y: top }, ScreenPt { x: 0, y: bot }, sub);
        if end <= b.y0 || first >= b.y1 || top == bot {
            return PolyStart::Empty;
        }
        let t = bbox.top_at;
        if !is_y_monotone(pts, t) {
            return PolyStart::Outside;
        }
        let y = first.max(b.y0);
        if y >= end.min(b.y1) {
            return PolyStart::Empty;
        }
        // The corners from the top, the top again after them (two
        // copies, not an index modulo `n`: a division per corner).
        let mut arc = [ScreenPt::default(); ARC];
        let (head, tail) = pts.split_at(t.min(n));
        for (dst, &p) in arc
            .iter_mut()
            .zip(tail.iter().chain(head).chain(tail.first()))
        {
            *dst = p;
        }
        let poly = Poly {
            l: S::default(),
            ly1: y,
            r: S::default(),
            ry1: y,
            arc,
            lo: 0,
            hi: n,
            end,
        };
        PolyStart::Rows(poly, y)
    }

    /// Sets up and fills polygon `pts` (record `here`, id `id`, cut by
    /// this band's end) and keeps it for the next band when its corners
    /// left ahead fit an entry (as a quad's); `None`, nothing
    /// emitted, when it is the general fill's
    /// ([`TriangleBand::start_poly`]). Out of line: the replay's loop
    /// keeps its registers for the triangles and quads.
    #[inline(never)]
    pub(crate) fn poly<K: SpanSink>(
        &self,
        pts: &[ScreenPt],
        (ring, words): (&mut Ring, &mut [u32]),
        (here, rgb, id): (usize, Rgb888, u32),
        sink: &mut K,
    ) -> Option<u64> {
        if packs(self.sub) {
            self.poly_as::<K, Packed>(pts, (ring, words), (here, rgb, id), sink)
        } else {
            self.poly_as::<K, Dda32>(pts, (ring, words), (here, rgb, id), sink)
        }
    }

    /// [`TriangleBand::poly`] with steppers `S` (the band's).
    #[inline(always)]
    fn poly_as<K: SpanSink, S: Kept>(
        &self,
        pts: &[ScreenPt],
        (ring, words): (&mut Ring, &mut [u32]),
        (here, rgb, id): (usize, Rgb888, u32),
        sink: &mut K,
    ) -> Option<u64> {
        match self.start_poly::<S>(pts) {
            PolyStart::Outside => None,
            PolyStart::Empty => Some(0),
            PolyStart::Rows(mut q, y) => {
                let paint = Paint { rgb, id };
                let color = sink.color(&paint);
                let spans = self.run_chains(&mut q, y, color, sink) as u64;
                if q.end > self.b.y1 {
                    let word = sink.keep_color(color, &paint);
                    ring.push_quad(words, &q, (here, self.end_row()), word);
                }
                Some(spans)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::super::chain::tests::Rec;
    use super::super::super::scan::rgb_word;
    use super::super::tests::{bands, corners, general_fill};
    use super::super::{most_ahead, WORDS};
    use super::*;
    use crate::raster::tests::Rng;
    use std::vec::Vec;

    /// Random polygons of five to twelve corners (convex ones, as most of
    /// bench_city's are, and any others) drawn in bands of random
    /// heights: set up in a band ([`TriangleBand::poly`]'s path), or
    /// resumed by the quads' path from the entry a band before kept
    /// (after a trip through the ring's words), they emit in every band
    /// exactly the spans of `fill_polygon_in` there, the general fill the
    /// replay takes without the carry; and a polygon goes on in the ring
    /// exactly while it has rows left and its corners ahead fit an entry.
    #[test]
    fn kept_polygons_equal_the_polygon_fill_in_every_band() {
        let (kept, fresh_runs, general) = poly_sweep::<Dda32>(7373, false);
        assert!(
            kept > 1000 && fresh_runs > 1000 && general > 100,
            "{kept} {fresh_runs} {general}"
        );
        // Packed steppers where the band's sub-pixel bits allow them
        // (a quarter of the cases), as the replay keeps them there.
        let (kept, fresh_runs, general) = poly_sweep::<Packed>(73731, true);
        assert!(
            kept > 250 && fresh_runs > 250 && general > 10,
            "{kept} {fresh_runs} {general}"
        );
    }

    /// The sweep of [`kept_polygons_equal_the_polygon_fill_in_every_band`] with steppers `S`, over the cases
    /// whose sub-pixel bits [`packs`] with `packed_only`: how many
    /// band pieces were resumed, set up fresh, and left to the general fill.
    fn poly_sweep<S: Kept>(seed: u64, packed_only: bool) -> (usize, usize, usize) {
        let mut rng = Rng(seed);
        let mut words = [0u32; 2 * WORDS];
        let (mut kept, mut fresh_runs, mut general) = (0, 0, 0);
        for k in 0..4000 {
            let (sub, m, poly) = corners(&mut rng, k, 5 + k % 8, k % 3 != 0);
            if packed_only && !packs(sub) {
                continue;
            }
            let mut ring = Ring::new();
            let rgb = rgb_word(Rgb888::new(k as u8, 2, 3));
            for band in bands(&mut rng, m, sub) {
                let (b, y0) = (band.b, band.b.y0);
                let mut want = Rec(Vec::new(), b);
                let spans = general_fill(&poly, &band, &mut want);
                ring.begin(&words);
                let mut got = Rec(Vec::new(), b);
                if let Some((at, row)) = ring.peek(&words) {
                    assert_eq!((at, row), (7, y0));
                    assert!(ring.next_is_quad(&words));
                    assert!(ring.next_ahead(&words) <= most_ahead::<S>());
                    // The replay's resume: popped, run, kept again while
                    // it goes on.
                    let n = band.resume_as::<_, S>(&mut ring, &mut words, (7, true), &mut got);
                    assert_eq!(n as usize, spans);
                    kept += 1;
                } else {
                    let mut state = None;
                    match band.start_poly::<S>(&poly) {
                        PolyStart::Outside => {
                            general += 1;
                            general_fill(&poly, &band, &mut got);
                        }
                        PolyStart::Empty => assert_eq!(spans, 0),
                        PolyStart::Rows(mut q, y) => {
                            fresh_runs += 1;
                            assert_eq!(band.run_chains(&mut q, y, (), &mut got), spans);
                            state = Some(q);
                        }
                    }
                    if let Some(q) = state.filter(|q| q.end > band.end_row()) {
                        let pushed = ring.push_quad(&mut words, &q, (7, band.end_row()), rgb);
                        let ahead = q.hi + 1 - q.lo;
                        assert_eq!(pushed, ahead <= most_ahead::<S>(), "{poly:?} {q:?}");
                    }
                }
                assert_eq!(got.0, want.0, "{poly:?} {sub} {b:?}");
            }
        }
        (kept, fresh_runs, general)
    }
}
