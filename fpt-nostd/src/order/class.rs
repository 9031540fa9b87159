//! One class of the walk: the culling loop over a bunch's runs.
//!
//! A class is at most two bunches (a level's `B_j` and `F_j`, or a switch's
//! `O_k`), each a contiguous range of runs with a pick (backward faces,
//! forward faces, or all). The facing of a run is tested once, from the
//! run's plane, and a passing run is handed out whole as a range of polygon
//! ids: a flat face triangulated into many polygons costs one test.

use core::ops::Range;

use super::facing::{CompactPlane, Facing, FacingPlane};
use crate::format::{le_u32, plane_at, run as rn, table_run as tr};
use crate::format::{RUN_LEN, TABLE_RUN_LEN};
use crate::reader::{table_plane, PolygonRef, Runs, Tree, WalkData};

/// Which faces of a bunch a class takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Pick {
    Backward,
    Forward,
    All,
}

/// The runs `run..run_end` of one bunch still to test, the first of them
/// starting at polygon `start`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Seg {
    run: u32,
    run_end: u32,
    start: u32,
    pick: Pick,
}

impl Seg {
    /// Nothing.
    pub(super) const EMPTY: Seg = Seg {
        run: 0,
        run_end: 0,
        start: 0,
        pick: Pick::All,
    };

    /// The runs `runs` of a bunch.
    #[inline(always)]
    pub(super) fn new(w: &WalkData<'_>, runs: (u32, u32), pick: Pick) -> Seg {
        by_layout!(w.runs, R => Self::new_as::<R>(w, runs, pick))
    }

    /// [`Seg::new`] over the run records of layout `R`.
    #[inline(always)]
    pub(super) fn new_as<R: RunRecord>(w: &WalkData<'_>, runs: (u32, u32), pick: Pick) -> Seg {
        let (run, run_end) = runs;
        Seg {
            run,
            run_end,
            // Only read when there is a run to start.
            start: if run < run_end {
                match run.checked_sub(1) {
                    Some(prev) => R::end(&w.runs, prev),
                    None => 0,
                }
            } else {
                0
            },
            pick,
        }
    }

    /// Whether no run is left.
    #[inline(always)]
    pub(super) fn is_empty(&self) -> bool {
        self.run >= self.run_end
    }

    /// The polygon ids of the next run that passes, and moves past it.
    #[inline(always)]
    fn take(&mut self, runs: &Runs<'_>, face: &Facing<'_>) -> Option<(u32, u32)> {
        by_layout!(runs, R => self.take_as::<R>(runs, face))
    }

    /// [`Seg::take`] over the run records of layout `R`.
    #[inline(always)]
    fn take_as<R: RunRecord>(&mut self, runs: &Runs<'_>, face: &Facing<'_>) -> Option<(u32, u32)> {
        // Emptiness first: the second bunch of a closed volume's class is
        // always empty, and this keeps that case to one predictable branch.
        if self.is_empty() {
            return None;
        }
        let want = match self.pick {
            Pick::Backward => true,
            Pick::Forward => false,
            Pick::All => {
                // Everything at once: the runs are contiguous.
                let end = R::end(runs, self.run_end.wrapping_sub(1));
                let start = self.start;
                self.run = self.run_end;
                self.start = end;
                return Some((start, end));
            }
        };
        self.scan::<R>(runs, face, want)
    }

    /// [`Seg::take`]'s scan for a run whose facing is `want`, over the
    /// records of layout `R`.
    #[inline(always)]
    fn scan<R: RunRecord>(
        &mut self,
        runs: &Runs<'_>,
        face: &Facing<'_>,
        want: bool,
    ) -> Option<(u32, u32)> {
        // One range check for the whole scan; the records are then read
        // from fixed-size arrays (see `crate::reader`).
        let mut recs = R::records(runs, self.run, self.run_end);
        let mut start = self.start;
        let mut run = self.run;
        while let Some((end, backward, rest)) = R::test(recs, runs, run, face) {
            recs = rest;
            let passes = backward == want;
            run = run.wrapping_add(1);
            if passes {
                self.run = run;
                self.start = end;
                return Some((start, end));
            }
            start = end;
        }
        self.run = self.run_end;
        None
    }

    /// [`Seg::take`] for the walk's own hand-out ([`Cursor::next_range_walk`]):
    /// the passing runs that follow the first one are contiguous ids and
    /// join its range, so that one range handed out (a call into the walk
    /// and back for the renderer) covers every run that passes in a row.
    /// The first run that then fails is used up with them (tested once,
    /// never emitted). The ids and their order are [`Seg::take`]'s.
    #[inline(always)]
    fn take_walk<R: RunRecord>(
        &mut self,
        runs: &Runs<'_>,
        face: &Facing<'_>,
    ) -> Option<(u32, u32)> {
        if self.is_empty() {
            return None;
        }
        // One scan per pick, each with its facing a constant: a `want`
        // read and compared in the loop was a register more than the table
        // layout's loop had.
        match self.pick {
            Pick::Backward => self.scan_walk::<R>(runs, face, true),
            Pick::Forward => self.scan_walk::<R>(runs, face, false),
            Pick::All => self.take_as::<R>(runs, face),
        }
    }

    /// [`Seg::take_walk`]'s scan for runs whose facing is `want`, over the
    /// records of layout `R`.
    #[inline(always)]
    fn scan_walk<R: RunRecord>(
        &mut self,
        runs: &Runs<'_>,
        face: &Facing<'_>,
        want: bool,
    ) -> Option<(u32, u32)> {
        let mut recs = R::records(runs, self.run, self.run_end);
        let mut start = self.start;
        let mut run = self.run;
        // The first passing run's start, once one passed, else `NONE`:
        // one register (an `Option` was two, and with a table's base and
        // length one more than the loop had, spilled to the stack). No run
        // starts at `NONE` (a start is at most the polygon count).
        const NONE: u32 = u32::MAX;
        let mut first = NONE;
        // Record by record off the front (a length test each), rather than
        // `chunks_exact`, whose set-up divides the length: a class has one
        // or two runs, mostly.
        while let Some((end, backward, rest)) = R::test(recs, runs, run, face) {
            recs = rest;
            run = run.wrapping_add(1);
            if backward == want {
                if first == NONE {
                    first = start;
                }
            } else if first != NONE {
                // Used up with the runs before it: tested, never emitted.
                self.run = R::run_after(self.run_end, rest, run);
                self.start = end;
                return Some((first, start));
            }
            start = end;
        }
        self.run = self.run_end;
        self.start = start;
        (first != NONE).then_some((first, start))
    }

    /// Polygons left (an upper bound on what passes).
    fn left(&self, runs: &Runs<'_>) -> u32 {
        match self.run_end.checked_sub(1).filter(|_| !self.is_empty()) {
            Some(last) => runs.end(last).saturating_sub(self.start),
            None => 0,
        }
    }
}

/// How the walk reads one layout of run records ([`Runs`]) and their
/// planes: chosen once per call into the walk ([`super::Order::next_range`]
/// and the out-of-line class start are compiled once per layout), so that
/// neither the loops over the records nor the registers they keep pay for
/// the other layout. Everything the walk reads of a run or a switch's
/// plane goes through here: another encoding of the planes is another
/// implementation.
pub(super) trait RunRecord {
    /// The records of the runs `run..run_end` (one range check for the
    /// whole scan; empty if out of range).
    fn records<'a>(runs: &Runs<'a>, run: u32, run_end: u32) -> &'a [u8];

    /// One past the last polygon of run `r < run_count`.
    fn end(runs: &Runs<'_>, r: u32) -> u32;

    /// The plane as the facing test reads it.
    type Plane<'a>: FacingPlane;

    /// The first record of `recs` (that of run `run`): its end, the memo's
    /// number of its plane, the plane (in `recs` or in the table of
    /// `runs`), and the records after it.
    fn split<'a>(
        recs: &'a [u8],
        runs: &Runs<'a>,
        run: u32,
    ) -> Option<(u32, u32, Self::Plane<'a>, &'a [u8])>;

    /// [`RunRecord::split`] and the facing test of the plane: the end,
    /// whether the plane is backward for `face`, the records after it.
    #[inline(always)]
    fn test<'a>(
        recs: &'a [u8],
        runs: &Runs<'a>,
        run: u32,
        face: &Facing<'_>,
    ) -> Option<(u32, bool, &'a [u8])> {
        let (end, no, plane, rest) = Self::split(recs, runs, run)?;
        Some((end, face.backward_at(no, plane), rest))
    }

    /// The memo's number and the record of the plane of switch `k`
    /// (`base`: the number of switch record 0 without a table).
    fn switch_at<'a>(w: &WalkData<'a>, k: u32, base: u32) -> (u32, Self::Plane<'a>);

    /// The run after a scan's last test, whose records after it are
    /// `rest` (of the runs up to `run_end`), `counted` by the scan.
    /// Counted by default; a layout whose test needs no run number
    /// derives it from `rest` instead, so that its scan keeps no counter
    /// (a register in a loop that spilled).
    #[inline(always)]
    fn run_after(run_end: u32, rest: &[u8], counted: u32) -> u32 {
        let _ = (run_end, rest);
        counted
    }
}

/// Records of [`RUN_LEN`] bytes: the plane, then a `u32` end.
pub(super) struct InlineRun;

impl RunRecord for InlineRun {
    #[inline(always)]
    fn records<'a>(runs: &Runs<'a>, run: u32, run_end: u32) -> &'a [u8] {
        let lo = (run as usize).wrapping_mul(RUN_LEN);
        let hi = (run_end as usize).wrapping_mul(RUN_LEN);
        runs.recs.get(lo..hi).unwrap_or(&[])
    }

    #[inline(always)]
    fn end(runs: &Runs<'_>, r: u32) -> u32 {
        runs.inline_end(r)
    }

    type Plane<'a> = &'a [u8; 16];

    #[inline(always)]
    fn split<'a>(
        recs: &'a [u8],
        _runs: &Runs<'a>,
        run: u32,
    ) -> Option<(u32, u32, &'a [u8; 16], &'a [u8])> {
        let (r, rest) = recs.split_first_chunk::<RUN_LEN>()?;
        Some((le_u32(r, rn::END), run, plane_at(r, 0), rest))
    }

    #[inline(always)]
    fn switch_at<'a>(w: &WalkData<'a>, k: u32, base: u32) -> (u32, &'a [u8; 16]) {
        w.switch_inline(k, base)
    }
}

// `table_record` reads a record as one little-endian word.
const _: () = assert!(tr::END == 0 && tr::PLANE == 2 && TABLE_RUN_LEN == 4);

/// The first [`TABLE_RUN_LEN`]-byte record of `recs`: its end, its plane
/// table index, and the records after it. One load for both halves
/// (`tr::END` the low, `tr::PLANE` the high): two halfword loads and a
/// shift were 4 more instructions a run test.
#[inline(always)]
fn table_record(recs: &[u8]) -> Option<(u32, u32, &[u8])> {
    let (r, rest) = recs.split_first_chunk::<TABLE_RUN_LEN>()?;
    let w = u32::from_le_bytes(*r);
    Some((w & 0xFFFF, w >> 16, rest))
}

/// Records of [`TABLE_RUN_LEN`] bytes: a `u16` end and a `u16` index into
/// the plane table, which is also the memo's number of the plane (a plane
/// that several runs share is tested once a frame with a memo).
pub(super) struct TableRun;

impl RunRecord for TableRun {
    #[inline(always)]
    fn records<'a>(runs: &Runs<'a>, run: u32, run_end: u32) -> &'a [u8] {
        let lo = (run as usize).wrapping_mul(TABLE_RUN_LEN);
        let hi = (run_end as usize).wrapping_mul(TABLE_RUN_LEN);
        runs.recs.get(lo..hi).unwrap_or(&[])
    }

    #[inline(always)]
    fn end(runs: &Runs<'_>, r: u32) -> u32 {
        runs.table_end(r)
    }

    type Plane<'a> = &'a [u8; 16];

    #[inline(always)]
    fn split<'a>(
        recs: &'a [u8],
        runs: &Runs<'a>,
        _run: u32,
    ) -> Option<(u32, u32, &'a [u8; 16], &'a [u8])> {
        let (end, i, rest) = table_record(recs)?;
        Some((end, i, table_plane(runs.planes(), i), rest))
    }

    /// An index past the table (which validation rules out) is a zero
    /// plane, never backward: tested without reading one, so that the
    /// loop keeps no fallback address in a register.
    #[inline(always)]
    fn test<'a>(
        recs: &'a [u8],
        runs: &Runs<'a>,
        _run: u32,
        face: &Facing<'_>,
    ) -> Option<(u32, bool, &'a [u8])> {
        let (end, i, rest) = table_record(recs)?;
        let backward = match runs.planes().get(i as usize) {
            Some(plane) => face.backward_at(i, plane),
            None => false,
        };
        Some((end, backward, rest))
    }

    #[inline(always)]
    fn switch_at<'a>(w: &WalkData<'a>, k: u32, _base: u32) -> (u32, &'a [u8; 16]) {
        w.switch_table(k)
    }

    /// The memo numbers its planes by their index: no counter.
    #[inline(always)]
    fn run_after(run_end: u32, rest: &[u8], _counted: u32) -> u32 {
        run_end.wrapping_sub((rest.len() / TABLE_RUN_LEN) as u32)
    }
}

/// [`TableRun`]'s records over a table of compact entries
/// ([`crate::format::FLAG_COMPACT_PLANES`]): the entry is converted to the
/// facing test's factors as it is read.
/// Without the `compact-planes` feature no tree has such a table
/// ([`Runs::is_compact`] is then the constant false), and this layout's
/// walk is never compiled.
pub(super) struct CompactRun;

impl RunRecord for CompactRun {
    #[inline(always)]
    fn records<'a>(runs: &Runs<'a>, run: u32, run_end: u32) -> &'a [u8] {
        TableRun::records(runs, run, run_end)
    }

    #[inline(always)]
    fn end(runs: &Runs<'_>, r: u32) -> u32 {
        TableRun::end(runs, r)
    }

    type Plane<'a> = CompactPlane;

    #[inline(always)]
    fn split<'a>(
        recs: &'a [u8],
        runs: &Runs<'a>,
        _run: u32,
    ) -> Option<(u32, u32, CompactPlane, &'a [u8])> {
        let (end, i, rest) = table_record(recs)?;
        Some((end, i, CompactPlane::of(&runs.compact_entry(i)), rest))
    }

    #[inline(always)]
    fn switch_at<'a>(w: &WalkData<'a>, k: u32, _base: u32) -> (u32, CompactPlane) {
        let (i, entry) = w.switch_compact(k);
        (i, CompactPlane::of(&entry))
    }

    #[inline(always)]
    fn run_after(run_end: u32, rest: &[u8], counted: u32) -> u32 {
        TableRun::run_after(run_end, rest, counted)
    }
}

/// Where a class's hand-out stands: the ids `next..end` of a passing run
/// are left, then the runs of `segs[cur..]`. Kept by value inside the walk
/// ([`super::Order::next_range`] advances it in place) and inside a
/// [`Class`]: 40 bytes, where a whole class is 68 (copying classes out of
/// the walk was a measurable part of a frame on a Cortex-M4).
#[derive(Clone, Copy, Debug)]
pub(super) struct Cursor {
    next: u32,
    end: u32,
    segs: [Seg; 2],
    cur: usize,
}

impl Cursor {
    /// Nothing left.
    pub(super) const EMPTY: Cursor = Cursor {
        next: 0,
        end: 0,
        segs: [Seg::EMPTY, Seg::EMPTY],
        cur: 2,
    };

    /// Starts on `segs`; false (and nothing to hand out) when nothing in
    /// them passes.
    #[inline]
    pub(super) fn start(&mut self, runs: &Runs<'_>, face: &Facing<'_>, segs: [Seg; 2]) -> bool {
        self.next = 0;
        self.end = 0;
        self.segs = segs;
        self.cur = 0;
        self.settle(runs, face)
    }

    /// [`Cursor::start`] for the walk's own hand-out (inlined into the
    /// out-of-line start of a class, `Order::begin`), settling with
    /// [`Seg::take_walk`]. The segments are scanned as locals and the
    /// cursor written once, at the end: written first and read back, as
    /// [`Cursor::start`] does, they went through memory for every run.
    #[inline(always)]
    pub(super) fn start_walk<R: RunRecord>(
        &mut self,
        runs: &Runs<'_>,
        face: &Facing<'_>,
        segs: [Seg; 2],
    ) -> bool {
        let [mut s0, mut s1] = segs;
        let (found, cur) = match s0.take_walk::<R>(runs, face) {
            Some(r) => (Some(r), 0),
            None => (s1.take_walk::<R>(runs, face), 1),
        };
        // With no run left after the one found (a closed volume's class is
        // mostly one bunch of one or two runs), the cursor is marked used
        // up: the walk's next call goes straight on to the next class
        // instead of testing both segments again.
        // A used-up cursor's segments are never read again (every read
        // goes through `segs.get(cur)` or skips `cur` of them), so only
        // its range and mark are written: a class start in three stores
        // instead of ten.
        match found {
            Some((next, end)) if !(s0.is_empty() && s1.is_empty()) => {
                *self = Cursor {
                    next,
                    end,
                    segs: [s0, s1],
                    cur,
                };
                true
            }
            Some((next, end)) => {
                self.next = next;
                self.end = end;
                self.cur = 2;
                true
            }
            None => {
                self.next = 0;
                self.end = 0;
                self.cur = 2;
                false
            }
        }
    }

    /// [`Cursor::settle`] with [`Seg::take_walk`]: `next..end` becomes the
    /// next passing runs in a row.
    #[inline(always)]
    fn settle_walk<R: RunRecord>(&mut self, runs: &Runs<'_>, face: &Facing<'_>) -> bool {
        while let Some(seg) = self.segs.get_mut(self.cur) {
            if let Some((start, end)) = seg.take_walk::<R>(runs, face) {
                self.next = start;
                self.end = end;
                return true;
            }
            self.cur += 1;
        }
        false
    }

    /// [`Cursor::next_range`] for the walk's own hand-out
    /// ([`super::Order::next_range`]): the rest of the current range, else
    /// the next passing runs in a row ([`Seg::take_walk`]).
    #[inline(always)]
    pub(super) fn next_range_walk<R: RunRecord>(
        &mut self,
        runs: &Runs<'_>,
        face: &Facing<'_>,
    ) -> Option<Range<u32>> {
        if self.next >= self.end && !self.settle_walk::<R>(runs, face) {
            return None;
        }
        let r = self.next..self.end;
        self.next = self.end;
        Some(r)
    }

    /// Makes `next..end` the next passing run; false when there is none.
    /// Each run is tested once.
    #[inline]
    fn settle(&mut self, runs: &Runs<'_>, face: &Facing<'_>) -> bool {
        while let Some(seg) = self.segs.get_mut(self.cur) {
            if let Some((start, end)) = seg.take(runs, face) {
                self.next = start;
                self.end = end;
                return true;
            }
            self.cur += 1;
        }
        false
    }

    /// The next range of ids (a whole run, or what is left of it).
    #[inline]
    pub(super) fn next_range(&mut self, runs: &Runs<'_>, face: &Facing<'_>) -> Option<Range<u32>> {
        if !self.pending(runs, face) {
            return None;
        }
        let r = self.next..self.end;
        self.next = self.end;
        Some(r)
    }

    /// Whether an id is left to hand out (settling on the next passing run
    /// if the current one is used up).
    #[inline]
    pub(super) fn pending(&mut self, runs: &Runs<'_>, face: &Facing<'_>) -> bool {
        self.next < self.end || self.settle(runs, face)
    }

    /// The next id.
    #[inline]
    fn next_id(&mut self, runs: &Runs<'_>, face: &Facing<'_>) -> Option<u32> {
        if !self.pending(runs, face) {
            return None;
        }
        let id = self.next;
        // next < end, so this cannot overflow.
        self.next += 1;
        Some(id)
    }

    /// Ids surely left (the rest of the current run) and an upper bound on
    /// all the ids left (every later run passing).
    fn bounds(&self, runs: &Runs<'_>) -> (u32, u32) {
        let current = self.end.saturating_sub(self.next);
        let rest = self
            .segs
            .iter()
            .skip(self.cur)
            .map(|s| s.left(runs))
            .fold(current, u32::saturating_add);
        (current, rest)
    }
}

/// One class: polygons of equal priority, already culled, as polygon ids.
///
/// Within a class no polygon can hide another, so they may be drawn in any
/// order; the ids come run by run in the order of the file. Iterate the ids
/// one by one, or take whole ranges with [`Class::next_range`]. (A renderer
/// that needs no class boundaries takes ranges straight from the walk:
/// [`super::Order::next_range`].)
#[derive(Clone, Copy, Debug)]
pub struct Class<'a> {
    runs: Runs<'a>,
    face: Facing<'a>,
    at: Cursor,
}

impl<'a> Class<'a> {
    /// The class whose hand-out stands at `at` (already settled on a
    /// passing run).
    #[inline]
    pub(super) fn resume(w: &WalkData<'a>, face: Facing<'a>, at: Cursor) -> Class<'a> {
        Class {
            runs: w.runs,
            face,
            at,
        }
    }

    /// The next range of polygon ids of this class (a whole run, or what is
    /// left of it after [`Iterator::next`]; the first range of a class from
    /// [`super::Order`] may join several runs that pass in a row, as
    /// [`super::Order::next_range`] does); `None` at the end. Every id of
    /// the range belongs to the class.
    #[inline]
    pub fn next_range(&mut self) -> Option<Range<u32>> {
        self.at.next_range(&self.runs, &self.face)
    }

    /// The polygons of this class.
    pub fn polygons(self, tree: &Tree<'a>) -> impl Iterator<Item = PolygonRef<'a>> + 'a {
        let tree = *tree;
        self.filter_map(move |id| tree.polygon(id))
    }
}

impl Iterator for Class<'_> {
    type Item = u32;

    #[inline]
    fn next(&mut self) -> Option<u32> {
        self.at.next_id(&self.runs, &self.face)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let (current, rest) = self.at.bounds(&self.runs);
        (current as usize, Some(rest as usize))
    }
}
