//! The replay of one band: the records of the frame's display list that
//! touch the band's rows, in push order, drawn from the vertex cache the
//! walk filled ([`replay`]), with the triangles, quads and polygons a band
//! cuts kept for the next band (`crate::raster::carry`). Split out of
//! `bands.rs`, which drives it band by band.

use crate::effects::Compiled;
use crate::raster::carry::{Ring, Start, CARRY};
use crate::raster::list::{DisplayList, Kind};
use crate::raster::renderer::Ready;
use crate::raster::vcache::{unpack, Slot, VertexCache};
use crate::raster::{Outcome, Paint, Precision, Renderer, Scratch, SpanSink};
use crate::reader::Tree;

/// Replays the records of `list` that touch rows `[y0, y1)` into `sink`;
/// returns the spans. `carry`: the triangles kept by the band before
/// (resumed where they stopped instead of set up again) and the words
/// they live in; with `keep`, the band after this one comes from the same
/// list, and the triangles this band cuts are kept for it
/// ([`crate::raster::carry`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn replay<P: Precision, E: Compiled, X: Compiled, K: SpanSink, const V: usize>(
    r: &Renderer<P, E>,
    scratch: &mut Scratch<P, V>,
    tree: &Tree<'_>,
    list: &DisplayList<'_>,
    cache: &VertexCache<'_>,
    (y0, y1): (i32, i32),
    sink: &mut K,
    (ring, words, keep): (&mut Ring, &mut [u32], bool),
) -> u64 {
    // Counted in a word: a band's spans are far below 2^32 (at most its
    // rows a record), and a `u64` sum took two more instructions and a
    // stack round trip for every record.
    let mut spans: usize = 0;
    // The band's own records when the list has a band index; else every
    // record of the groups that overlap the band (whole groups that miss
    // it are skipped unread). One loop over either, so that the fill is
    // inlined once.
    let indexed = list.band(y0);
    let records = Records {
        indexed: indexed.unwrap_or(&[]).iter(),
        scan: indexed.is_none().then_some(Scan {
            group: 0,
            at: 0,
            stop: 0,
        }),
        list,
        rows: (y0, y1),
    };
    // Triangles by polygon (most records) go straight to the triangle
    // fill with the band's bounds found once here: what `fill_ready`
    // does for each, without its per-record checks.
    let tri = r.triangle_band::<X, K, V>(scratch, sink);
    // Kept triangles carry their colour, not their id: only for sinks
    // that paint without ids.
    let carry = tri.filter(|_| CARRY && !K::NEEDS_ID && !words.is_empty());
    if CARRY {
        ring.begin(words);
    }
    let keep = keep && carry.is_some();
    let mut want = if CARRY { ring.peek(words) } else { None };
    let slots = cache.indexed_slots();
    for here in records {
        if let Some(band) = &carry {
            // The incoming triangles are among this band's records, in the
            // same order: one comparison a record. One that is not where
            // expected (it cannot be) is dropped, never drawn.
            while let Some((at, row)) = want {
                if at >= here && row == band.first_row() {
                    break;
                }
                ring.skip();
                want = ring.peek(words);
            }
            if want.is_some_and(|(at, _)| at == here) {
                if CARRY_QUADS && ring.next_is_quad(words) {
                    spans += band.resume_quad(ring, words, (here, keep), sink) as usize;
                    want = ring.peek(words);
                    continue;
                }
                if let Some((mut t, word)) = ring.pop(words) {
                    want = ring.peek(words);
                    let color = sink.kept_color(word);
                    spans += band.run(&mut t, band.first_row(), color, sink);
                    if keep && band.continues(&t) {
                        ring.push(words, &t, (here, band.end_row()), word);
                    }
                    continue;
                }
            }
        }
        let Some(rec) = list.record(here) else {
            break;
        };
        let e = rec.entry;
        // (A record by polygon has `n = 0`: its count is the tree's, and
        // the scratch bounds it below.)
        if rec.n > V {
            continue;
        }
        let mut ok = true;
        let n = match rec.kind {
            Kind::Polygon => {
                // Recorded by polygon only when every vertex was cached.
                let Some(i) = list.polygon(&rec) else {
                    continue;
                };
                let vs = tree.polygon_vertex_indices(i);
                if let Some(bytes) = vs.narrow() {
                    // 2-byte indices (every tree below 65,536 vertices):
                    // one loop over the bytes and the scratch together.
                    let n = bytes.len() / 2;
                    let Some(screen) = scratch.screen_mut().get_mut(..n) else {
                        continue;
                    };
                    // Recorded by polygon only when every vertex is cached
                    // as a point in the (indexed) cache: read without the
                    // layout and sentinel tests.
                    for (dst, b) in screen.iter_mut().zip(bytes.chunks_exact(2)) {
                        let v = usize::from(b[0]) | usize::from(b[1]) << 8;
                        match slots.get(v) {
                            Some(&w) => *dst = unpack(w),
                            None => ok = false,
                        }
                    }
                    n
                } else {
                    let mut n = 0;
                    for v in vs {
                        match (scratch.screen_mut().get_mut(n), cache.get(v)) {
                            (Some(dst), Slot::Point(p)) => *dst = p,
                            _ => ok = false,
                        }
                        n += 1;
                    }
                    n
                }
            }
            Kind::Indices => {
                for (dst, &v) in scratch.screen_mut().iter_mut().zip(list.indices(&rec)) {
                    match cache.get(u32::from(v)) {
                        Slot::Point(p) => *dst = p,
                        // Recorded by index only when cached: not reached.
                        _ => ok = false,
                    }
                }
                rec.n
            }
            Kind::Inline => {
                for (i, dst) in scratch.screen_mut()[..rec.n].iter_mut().enumerate() {
                    *dst = list.inline_point(&rec, i);
                }
                rec.n
            }
        };
        if !ok {
            continue;
        }
        if let (Some(band), 3) = (&tri, n) {
            if let [a, b, c, ..] = *scratch.screen() {
                let paint = Paint {
                    rgb: e.rgb,
                    id: e.id,
                };
                let color = sink.color(&paint);
                if !(keep && e.end > y1 && ring.has_room()) {
                    // Nothing can be kept (the last band of the walk, a
                    // triangle whose rows end in this band, a full ring, or
                    // a core without the carry): the plain
                    // triangle fill, cheaper than the set-up that keeps
                    // (measured: with it here, socket's bands in 3,675
                    // words cost 1 % more than before the carry).
                    if let Some(s) = band.fill([a, b, c], color, sink) {
                        spans += s;
                        continue;
                    }
                } else {
                    match band.start([a, b, c]) {
                        Start::Outside => {}
                        Start::Empty => continue,
                        Start::Rows(mut t, y) => {
                            spans += band.run(&mut t, y, color, sink);
                            if keep && band.continues(&t) {
                                let word = sink.keep_color(color, &paint);
                                ring.push(words, &t, (here, band.end_row()), word);
                            }
                            continue;
                        }
                    }
                }
            }
        }
        // The four-sided pieces of split triangles the band cuts: set up
        // once and carried like the triangles (else the general fill's
        // box, monotonicity pass and chain seeks in every band); those
        // ending here too, as its set-up is cheaper than the general
        // fill's (bench_city −14 to −38 k a band frame; not so for 5–8
        // corners, +72 to +89 k).
        if let (true, Some(band), 4, true) = (CARRY_QUADS, &carry, n, keep || e.end <= y1) {
            if let [a, b, c, d, ..] = *scratch.screen() {
                if let Some(s) = band.quad([a, b, c, d], (ring, words), (here, e.rgb, e.id), sink) {
                    spans += s as usize;
                    continue;
                }
            }
        }
        // Polygons of five or more corners the band cuts: set up by the
        // chains out of line, and kept (as quads) once at most five
        // corners (three with `Dda32` steppers) are left ahead
        // (`raster::carry::poly`).
        if let (true, Some(band), true) = (CARRY_POLYS, &carry, n > 4 && keep && e.end > y1) {
            if let Some(pts) = scratch.screen().get(..n) {
                if let Some(s) = band.poly(pts, (ring, words), (here, e.rgb, e.id), sink) {
                    spans += s as usize;
                    continue;
                }
            }
        }
        let ready = Ready {
            n,
            // The fill computes the box if it needs it (not for a
            // triangle).
            bbox: None,
            first: e.first,
            end: e.end,
            rgb: e.rgb,
            clipped: e.clipped,
            depth: 0.0,
        };
        if let Outcome::Drawn { spans: s } =
            r.fill_ready::<X, K, V>(scratch, &ready, e.id, e.hidden, sink)
        {
            spans += s;
        }
    }
    spans as u64
}

/// The records a band replays, in push order: those the band index lists
/// for it, else (no index) those of the groups that overlap it, tested by
/// their first words. The index's are read in line, one slice step each;
/// the scan, the rare case, out of line (a `chain` of the two tested
/// which of them it was in every step).
struct Records<'s, 'm> {
    indexed: core::slice::Iter<'s, u16>,
    scan: Option<Scan>,
    list: &'s DisplayList<'m>,
    rows: (i32, i32),
}

/// Where the scan of [`Records`] is: the next group, and the words
/// `at..stop` of the group being read.
struct Scan {
    group: usize,
    at: usize,
    stop: usize,
}

impl Iterator for Records<'_, '_> {
    type Item = usize;

    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        if let Some(&at) = self.indexed.next() {
            return Some(usize::from(at));
        }
        self.scan_next()
    }
}

impl Records<'_, '_> {
    /// The next record of the scan (none with a band index).
    #[inline(never)]
    fn scan_next(&mut self) -> Option<usize> {
        let s = self.scan.as_mut()?;
        let (y0, y1) = self.rows;
        loop {
            while s.at < s.stop {
                let Some((first, end, next)) = self.list.rows_at(s.at) else {
                    break;
                };
                let here = s.at;
                s.at = next;
                if end > y0 && first < y1 {
                    return Some(here);
                }
            }
            if s.group >= self.list.groups() {
                return None;
            }
            let g = s.group;
            s.group += 1;
            if let Some((first, end, start, stop)) = self.list.group(g) {
                if end > y0 && first < y1 {
                    (s.at, s.stop) = (start, stop);
                }
            }
        }
    }
}

/// Whether the replay carries the four-sided pieces of split triangles
/// across band edges as it does triangles (with [`CARRY`]).
const CARRY_QUADS: bool = CARRY;

/// Whether the replay sets up the polygons of five or more corners a band
/// cuts by their own path and carries them (with [`CARRY`]).
const CARRY_POLYS: bool = CARRY;
