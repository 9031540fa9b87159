//! The display list: a frame's polygons, ready to fill, recorded once and
//! replayed into each band.
//!
//! Band rendering without it walks the tree, transforms, clips, projects
//! and shades every polygon once per band; with it, all of that happens
//! once a frame, and a band costs only the fill of the polygons that touch
//! its rows. A record holds what the fill needs and nothing else: the rows
//! the polygon may touch, its shaded colour, its id and outline mask when
//! the frame needs them, and its screen points, either as indices into
//! the frame's [`super::vcache::VertexCache`] (the common case: every
//! vertex inside the clip planes and cached) or inline (a clipped polygon,
//! or a vertex the cache does not hold).
//!
//! # Contract
//!
//! * Storage: the caller's `&mut [u16]` (any length); [`DisplayList::push`]
//!   writes a record whole or not at all and says which, so a full list
//!   never loses a polygon silently: the caller decides what to do
//!   (render what it has and continue, see [`crate::render`]).
//! * Records keep the order they were pushed in (back to front), and
//!   [`DisplayList::retain_rows_below`] drops records in place without
//!   reordering the rest.
//! * Sizes, in 16-bit words: a header of 3, plus 1 when the polygon spans
//!   more than 254 rows, plus 4 with outlines (the 64-bit mask), plus 2 with ids; then the
//!   points: a polygon whose every vertex is cached is stored by its
//!   **polygon index** (1 word; the replay reads its vertex indices from
//!   the tree, which is in flash, not RAM), else a count word and 1 word a
//!   vertex (by index) or 4 a vertex (inline). A triangle of a frame
//!   without outlines or ids takes 4 words (8 bytes): on a 16 KiB
//!   Cortex-M0 the list is what decides how many walks a frame takes, so
//!   the common record is kept as small as it can be while still holding
//!   the shaded colour exactly.
//!
//! Header layout: `[first | kind << 14, r | g << 8, b | rows << 8]`,
//! `first` the first row (below 2^14, the largest viewport), `kind` 0 (by
//! polygon), 1 (by vertex index), 2 (inline) or 3 (inline, clipped),
//! `rows = end - first` when below 255, else 255 and the next word holds
//! `end`.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use super::carry::CARRY;
use super::transform::ScreenPt;

/// One recorded polygon's fixed part.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry {
    /// First row the polygon may touch.
    pub first: i32,
    /// One past the last row it may touch.
    pub end: i32,
    /// Its shaded colour.
    pub rgb: Rgb888,
    /// Its id (0 unless the list stores ids).
    pub id: u32,
    /// Its outline mask (0 unless the list stores outlines).
    pub hidden: u64,
    /// Whether clipping changed it (its edges are no longer the stored
    /// ones, so outlines draw every edge).
    pub clipped: bool,
}

/// Where a record's screen points are.
#[derive(Clone, Copy, Debug)]
pub enum Points<'a> {
    /// Polygon `i` of the tree (below 2^16), every vertex of which is in
    /// the frame's vertex cache: the replay reads its vertex indices from
    /// the tree.
    Polygon(u16),
    /// Vertex indices into the frame's vertex cache (each below 2^16).
    Indices(&'a [u16]),
    /// The points themselves.
    Inline(&'a [ScreenPt]),
}

/// How a record stores its points (see [`Points`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// By polygon index: [`DisplayList::polygon`].
    Polygon,
    /// By vertex indices: [`DisplayList::indices`].
    Indices,
    /// Inline: [`DisplayList::inline_point`].
    Inline,
}

/// A record read back: its entry and where its points start.
#[derive(Clone, Copy, Debug)]
pub struct Record {
    /// The fixed part.
    pub entry: Entry,
    /// Vertex count (0 for a record by polygon: the tree has it).
    pub n: usize,
    /// How the points are stored.
    pub kind: Kind,
    body: usize,
    next: usize,
}

/// `kind` values of the header's third word.
const BY_POLYGON: u16 = 0;
const BY_INDEX: u16 = 1;
const INLINE: u16 = 2;
const INLINE_CLIPPED: u16 = 3;
/// `rows` value saying that the next word holds the end row.
const LONG_ROWS: u16 = 255;
/// Words of a record's outline mask (a `u64`, see [`super::outline`]).
const MASK_WORDS: usize = 4;

/// A list of records in caller storage (see the module docs).
#[derive(Debug)]
pub struct DisplayList<'m> {
    buf: &'m mut [u16],
    len: usize,
    peak: usize,
    ids: bool,
    outlines: bool,
    /// Words of the optional fields (outline mask, id) in every record.
    extra: usize,
    /// Groups in the table at the top of `buf` (see [`GROUP`]).
    groups: usize,
    /// Records in the last group.
    in_group: usize,
    /// The band index, when built and still valid ([`DisplayList::index_bands`]).
    index: Option<BandIndex>,
    /// The records a band, counted as they are pushed ([`DisplayList::tally_bands`]).
    tally: Tally,
    /// Records pushed while the tally counts: their group entries are
    /// written only if a replay scans the groups ([`DisplayList::seal`]).
    recs: usize,
}

/// Bands a list counts its records in as they are pushed: enough for the
/// usual frames (240 rows in 16-row bands are 15 bands, in 8-row bands 30);
/// none on cores without an FPU, which rarely have room for the band index
/// (see [`CARRY`]) and whose stack is the tightest.
const TALLY: usize = if CARRY { 32 } else { 0 };

/// Records a band ([`TALLY`] bands of `1 << shift` rows from row `y`,
/// rows clamped to `cut`), counted by [`DisplayList::push`] for
/// [`DisplayList::index_bands`], which then skips its counting pass (a
/// decode of every record: about a third of the index's cost).
#[derive(Clone, Copy, Debug)]
struct Tally {
    /// Whether the counts are those of the records in the list.
    on: bool,
    y: i32,
    cut: i32,
    shift: u32,
    counts: [u16; TALLY],
}

impl Tally {
    const OFF: Tally = Tally {
        on: false,
        y: 0,
        cut: 0,
        shift: 0,
        counts: [0; TALLY],
    };
}

/// Where the band index sits in the free words between the records and
/// the group table: `bands` cursors, then the entries (record offsets),
/// band after band.
#[derive(Clone, Copy, Debug)]
struct BandIndex {
    /// First row of band 0.
    y: i32,
    /// Rows a band.
    rows: i32,
    /// Bands indexed.
    bands: usize,
    /// Where the cursors start (the entries follow them).
    at: usize,
    /// One past the last entry: the free words start here.
    end: usize,
}

/// Records per group. Every [`GROUP`] consecutive records share an entry
/// of 4 words at the top of the storage (growing down): the rows they
/// touch together and where they start. A band skips the groups that miss
/// its rows without reading their records: the walk visits the tree's
/// subtrees, which are spatially compact, one after the other, so a group
/// covers few rows. (Scanning every record in every band cost a third of
/// the bands' overhead.)
pub const GROUP: usize = 16;

impl<'m> DisplayList<'m> {
    /// An empty list over `buf`, storing ids and outline masks only when
    /// asked (they cost 2 and 4 words a record).
    pub fn new(buf: &'m mut [u16], ids: bool, outlines: bool) -> Self {
        DisplayList {
            buf,
            len: 0,
            peak: 0,
            ids,
            outlines,
            extra: MASK_WORDS * usize::from(outlines) + 2 * usize::from(ids),
            groups: 0,
            in_group: 0,
            index: None,
            tally: Tally::OFF,
            recs: 0,
        }
    }

    /// Empties the list (the storage is kept).
    pub fn clear(&mut self) {
        self.peak = self.peak();
        self.recs = 0;
        self.len = 0;
        self.groups = 0;
        self.in_group = 0;
        self.index = None;
        self.tally.on = false;
    }

    /// Counts, from now on, the records pushed per band of `rows` rows
    /// from row `y` up to row `cut`, for [`DisplayList::index_bands`] of
    /// the same bands (called on an empty list; only for power-of-two
    /// band heights and at most `TALLY` bands; anything else, or a
    /// [`DisplayList::retain_rows_below`], leaves the index to count).
    ///
    /// While it counts, the pushes leave the group table unwritten (its
    /// room is kept): with the band index no replay reads it, and
    /// [`DisplayList::seal`] writes it for one that does (the index did
    /// not fit, or a single band).
    pub fn tally_bands(&mut self, y: i32, rows: i32, cut: i32) {
        let bands = if rows > 0 {
            (cut - y + rows - 1) / rows
        } else {
            0
        };
        self.tally.on = self.len == 0
            && TALLY > 0
            && rows > 0
            && (rows as u32).is_power_of_two()
            && (1..=TALLY as i32).contains(&bands);
        if self.tally.on {
            self.tally.y = y;
            self.tally.cut = cut;
            self.tally.shift = rows.trailing_zeros();
            self.tally.counts = [0; TALLY];
        }
    }

    /// Adds a record of rows `first..end` to the tally (when counting).
    #[inline(always)]
    fn count(&mut self, first: i32, end: i32) {
        let t = &mut self.tally;
        if TALLY == 0 || !t.on {
            return;
        }
        let (f, e) = (first.max(t.y), end.min(t.cut));
        if e <= f {
            return;
        }
        let b0 = ((f - t.y) >> t.shift) as usize;
        let b1 = ((e - 1 - t.y) >> t.shift) as usize;
        if b0 == b1 {
            // A record of one band (most of them): no loop.
            if let Some(c) = t.counts.get_mut(b0) {
                *c = c.wrapping_add(1);
            }
        } else if let Some(c) = t.counts.get_mut(b0..=b1) {
            for c in c {
                *c = c.wrapping_add(1);
            }
        }
    }

    /// Whether the group table waits for [`DisplayList::seal`] (see
    /// [`DisplayList::tally_bands`]).
    #[inline(always)]
    fn lazy(&self) -> bool {
        TALLY > 0 && self.tally.on
    }

    /// Words the group table takes (or will take, when written late).
    #[inline(always)]
    fn table_words(&self) -> usize {
        if self.lazy() {
            4 * self.recs.div_ceil(GROUP)
        } else {
            4 * self.groups
        }
    }

    /// Words the group table takes once the next record is added.
    #[inline(always)]
    fn table_after_push(&self) -> usize {
        if self.lazy() {
            4 * (self.recs / GROUP + 1)
        } else {
            4 * (self.groups + usize::from(self.in_group == 0))
        }
    }

    /// Adds the record at `at` (rows `first..end`) to the group table, or
    /// (while the table waits) to the records it will hold.
    #[inline(always)]
    fn add(&mut self, at: usize, first: i32, end: i32) {
        if self.lazy() {
            self.count(first, end);
            self.recs += 1;
        } else {
            // Room for the entry was checked by the caller.
            self.note(at, first as u16, end as u16, self.len);
        }
    }

    /// Writes the group table when the pushes left it waiting (see
    /// [`DisplayList::tally_bands`]): a replay without the band index scans
    /// the groups. The tally stops (an index made later counts).
    pub fn seal(&mut self) {
        if !self.lazy() {
            return;
        }
        self.peak = self.peak();
        self.tally.on = false;
        self.groups = 0;
        self.in_group = 0;
        let mut at = 0;
        while let Some(h) = self.head(at) {
            // Room for every entry was kept by the pushes.
            self.note(at, h.first as u16, h.end as u16, self.len);
            at = h.next;
        }
    }

    /// Where group `g`'s entry starts.
    fn group_at(&self, g: usize) -> usize {
        self.buf.len().wrapping_sub(4 * (g + 1))
    }

    /// Adds the record at `at` (rows `first..end`) to the group table;
    /// `false` when a new entry does not fit below the records' end `top`.
    fn note(&mut self, at: usize, first: u16, end: u16, top: usize) -> bool {
        if self.in_group == 0 {
            let g = self.groups;
            let e = self.group_at(g);
            if e < top || e > self.buf.len() {
                return false;
            }
            if let Some(w) = self.buf.get_mut(e..e + 4) {
                w.copy_from_slice(&[first, end, at as u16, (at >> 16) as u16]);
            }
            self.groups += 1;
        } else if let Some(w) = self.buf.get_mut(self.group_at(self.groups - 1)..) {
            w[0] = w[0].min(first);
            w[1] = w[1].max(end);
        }
        self.in_group = (self.in_group + 1) % GROUP;
        true
    }

    /// Number of groups (see [`GROUP`]).
    pub fn groups(&self) -> usize {
        self.groups
    }

    /// Group `g`: the rows `(first, end)` its records touch together, and
    /// the words `start..stop` they take.
    #[inline]
    pub fn group(&self, g: usize) -> Option<(i32, i32, usize, usize)> {
        if g >= self.groups {
            return None;
        }
        let e = self.group_at(g);
        let &[first, end, lo, hi] = self.buf.get(e..e + 4)? else {
            return None;
        };
        let start = usize::from(lo) | usize::from(hi) << 16;
        let stop = if g + 1 < self.groups {
            let n = self.group_at(g + 1);
            match self.buf.get(n + 2..n + 4) {
                Some(&[lo, hi]) => usize::from(lo) | usize::from(hi) << 16,
                _ => self.len,
            }
        } else {
            self.len
        };
        Some((i32::from(first), i32::from(end), start, stop))
    }

    /// Words in use.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no record is stored.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The most words in use since the list was made.
    pub fn peak(&self) -> usize {
        // Records and the group table only grow between a clear and a
        // retain, which note the peak: the pushes need not.
        self.peak.max(self.len + self.table_words())
    }

    /// Words a record takes: `n` points stored `kind`, spanning `rows`
    /// rows.
    pub fn record_words(&self, n: usize, kind: Kind, rows: i32) -> usize {
        3 + usize::from(rows >= i32::from(LONG_ROWS))
            + self.extra
            + match kind {
                Kind::Polygon => 1,
                Kind::Indices => 1 + n,
                Kind::Inline => 1 + 4 * n,
            }
    }

    /// Appends a record; `false` (and nothing written) when it does not
    /// fit or a field is out of range (a first row outside `0..2^14`, an
    /// end row outside `0..=2^14` or above it, more than 65 535 points). A clipped polygon must be
    /// stored inline (its points are not the tree's).
    ///
    /// The common record is written in line (the walk pushes one for
    /// every polygon it draws: the call costs more than the writing),
    /// the others out of line.
    #[inline(always)]
    pub fn push(&mut self, e: &Entry, pts: Points<'_>) -> bool {
        // The common record first, written straight (a frame records every
        // polygon it draws): by polygon, not clipped, fewer than 255 rows,
        // no optional words. The same 4 words as the general path below.
        if let (Points::Polygon(i), false) = (pts, e.clipped) {
            if let Some(pushed) = self.push_polygon((e.first, e.end), e.rgb, i) {
                return pushed;
            }
        }
        self.push_general(e, pts)
    }

    /// [`DisplayList::push`] of polygon `i`, not clipped, of rows
    /// `first..end` and colour `rgb`, when it takes the common record
    /// (`Some`: whether it was written); `None`, nothing written, when it
    /// does not (optional words, or rows out of its range): then
    /// [`DisplayList::push`] stores it. The one test of which polygons
    /// take the common record (`push` asks it too). The band walk makes the polygon's
    /// [`Entry`] only then: made for every polygon, in memory for the
    /// general push, it cost the walk more than the record.
    #[inline(always)]
    pub fn push_polygon(&mut self, (first, end): (i32, i32), rgb: Rgb888, i: u16) -> Option<bool> {
        let rows = end.wrapping_sub(first);
        let short = self.extra == 0
            && (0..1 << 14).contains(&first)
            && end <= 1 << 14
            && (0..i32::from(LONG_ROWS)).contains(&rows);
        short.then(|| self.push_short((first, end), rgb, rows as u16, i))
    }

    /// [`DisplayList::push`] of a record by polygon `i` spanning `rows`
    /// (below 255) rows, without optional words (checked by the caller).
    #[inline(always)]
    fn push_short(&mut self, (first, end): (i32, i32), rgb: Rgb888, rows: u16, i: u16) -> bool {
        let at = self.len;
        let table = self.table_after_push();
        if at + 4 + table > self.buf.len() {
            return false;
        }
        let Some(out) = self.buf.get_mut(at..at + 4) else {
            return false;
        };
        out.copy_from_slice(&[
            first as u16 | BY_POLYGON << 14,
            u16::from(rgb.r()) | u16::from(rgb.g()) << 8,
            u16::from(rgb.b()) | rows << 8,
            i,
        ]);
        self.index = None;
        self.len = at + 4;
        self.add(at, first, end);
        true
    }

    /// [`DisplayList::push`] of any record.
    #[inline(never)]
    fn push_general(&mut self, e: &Entry, pts: Points<'_>) -> bool {
        let (n, kind) = match pts {
            Points::Polygon(_) => (0, Kind::Polygon),
            Points::Indices(ix) => (ix.len(), Kind::Indices),
            Points::Inline(p) => (p.len(), Kind::Inline),
        };
        if !(0..1 << 14).contains(&e.first)
            || e.end > 1 << 14
            || e.end < e.first
            || n > usize::from(u16::MAX)
            || (e.clipped && kind != Kind::Inline)
        {
            return false;
        }
        // The index would overlap the new record (and miss it).
        self.index = None;
        let rows = e.end - e.first;
        let words = self.record_words(n, kind, rows);
        let table = self.table_after_push();
        if self.len + words + table > self.buf.len() {
            return false;
        }
        let Some(out) = self.buf.get_mut(self.len..self.len + words) else {
            return false;
        };
        let code = match kind {
            Kind::Polygon => BY_POLYGON,
            Kind::Indices => BY_INDEX,
            Kind::Inline if e.clipped => INLINE_CLIPPED,
            Kind::Inline => INLINE,
        };
        let long = rows >= i32::from(LONG_ROWS);
        let rows_code = if long { LONG_ROWS } else { rows as u16 };
        out[0] = e.first as u16 | code << 14;
        out[1] = u16::from(e.rgb.r()) | u16::from(e.rgb.g()) << 8;
        out[2] = u16::from(e.rgb.b()) | rows_code << 8;
        let mut k = 3;
        if long {
            out[k] = e.end as u16;
            k += 1;
        }
        if kind != Kind::Polygon {
            out[k] = n as u16;
            k += 1;
        }
        if self.outlines {
            for (w, o) in out[k..k + MASK_WORDS].iter_mut().enumerate() {
                *o = (e.hidden >> (16 * w)) as u16;
            }
            k += MASK_WORDS;
        }
        if self.ids {
            out[k] = e.id as u16;
            out[k + 1] = (e.id >> 16) as u16;
            k += 2;
        }
        match pts {
            Points::Polygon(i) => out[k] = i,
            Points::Indices(ix) => out[k..k + n].copy_from_slice(ix),
            Points::Inline(p) => {
                for (o, p) in out[k..k + 4 * n].chunks_exact_mut(4).zip(p) {
                    o.copy_from_slice(&[
                        p.x as u16,
                        (p.x >> 16) as u16,
                        p.y as u16,
                        (p.y >> 16) as u16,
                    ]);
                }
            }
        }
        let at = self.len;
        self.len += words;
        // Room for the entry was checked above.
        self.add(at, e.first, e.end);
        true
    }

    /// The record at word `at` (0 for the first), or `None` at the end.
    ///
    /// The common record is decoded in line (the replay reads one for
    /// every band a polygon touches: the call and the copy of the record
    /// out of it cost more than the decoding), the others out of line.
    #[inline(always)]
    pub fn record(&self, at: usize) -> Option<Record> {
        // The common record (by polygon, fewer than 255 rows, no optional
        // words: 4 words) decoded straight.
        if self.extra == 0 && at + 4 <= self.len {
            if let Some(&[w0, w1, w2, _]) = self.buf.get(at..at + 4) {
                if w0 >> 14 == BY_POLYGON && w2 >> 8 != LONG_ROWS {
                    let first = i32::from(w0 & 0x3fff);
                    return Some(Record {
                        entry: Entry {
                            first,
                            end: first + i32::from(w2 >> 8),
                            rgb: Rgb888::new(w1 as u8, (w1 >> 8) as u8, w2 as u8),
                            id: 0,
                            hidden: 0,
                            clipped: false,
                        },
                        n: 0,
                        kind: Kind::Polygon,
                        body: at + 3,
                        next: at + 4,
                    });
                }
            }
        }
        self.record_general(at)
    }

    /// [`DisplayList::record`] of any record.
    #[inline(never)]
    fn record_general(&self, at: usize) -> Option<Record> {
        let h = self.head(at)?;
        // The optional words sit right before the points: the outline
        // mask, then the id.
        let mut k = h.body - self.extra;
        let hidden = if self.outlines {
            let words = self.buf.get(k..k + MASK_WORDS)?;
            k += MASK_WORDS;
            words
                .iter()
                .enumerate()
                .fold(0u64, |m, (w, &x)| m | u64::from(x) << (16 * w))
        } else {
            0
        };
        let id = if self.ids {
            k += 2;
            u32::from(*self.buf.get(k - 2)?) | u32::from(*self.buf.get(k - 1)?) << 16
        } else {
            0
        };
        let (w1, w2) = h.colour;
        Some(Record {
            entry: Entry {
                first: h.first,
                end: h.end,
                rgb: Rgb888::new(w1 as u8, (w1 >> 8) as u8, w2 as u8),
                id,
                hidden,
                clipped: h.clipped,
            },
            n: h.n,
            kind: h.kind,
            body: h.body,
            next: h.next,
        })
    }

    /// The header of the record at word `at`. `None` at the end.
    #[inline(always)]
    fn head(&self, at: usize) -> Option<Head> {
        head_in(self.buf.get(..self.len)?, self.extra, at)
    }

    /// The rows `(first, end)` of the record at word `at` and where the
    /// next one starts, from its first words only: the quick test a band
    /// makes of every record. `None` at the end.
    #[inline(always)]
    pub fn rows_at(&self, at: usize) -> Option<(i32, i32, usize)> {
        let h = self.head(at)?;
        Some((h.first, h.end, h.next))
    }

    /// Where the record after `r` starts.
    #[inline]
    pub fn next(&self, r: &Record) -> usize {
        r.next
    }

    /// Point `i` of an inline record.
    #[inline]
    pub fn inline_point(&self, r: &Record, i: usize) -> ScreenPt {
        let at = r.body + 4 * i;
        match self.buf.get(at..at + 4) {
            Some(&[a, b, c, d]) => ScreenPt {
                x: (u32::from(a) | u32::from(b) << 16) as i32,
                y: (u32::from(c) | u32::from(d) << 16) as i32,
            },
            _ => ScreenPt::default(),
        }
    }

    /// The vertex indices of a record stored by index (empty for the
    /// others).
    #[inline]
    pub fn indices(&self, r: &Record) -> &[u16] {
        if r.kind != Kind::Indices {
            return &[];
        }
        self.buf.get(r.body..r.body + r.n).unwrap_or(&[])
    }

    /// The polygon index of a record stored by polygon (`None` for the
    /// others).
    #[inline]
    pub fn polygon(&self, r: &Record) -> Option<u32> {
        if r.kind != Kind::Polygon {
            return None;
        }
        self.buf.get(r.body).map(|&i| u32::from(i))
    }
}

/// The header of the record at word `at` of `records` (the words in use;
/// `extra`: the optional words of every record). `None` at the end.
#[inline(always)]
fn head_in(records: &[u16], extra: usize, at: usize) -> Option<Head> {
    let h = records.get(at..)?;
    let &[w0, w1, w2, ..] = h else {
        return None;
    };
    let first = i32::from(w0 & 0x3fff);
    let code = w0 >> 14;
    let rows = w2 >> 8;
    let mut k = 3;
    let end = if rows == LONG_ROWS {
        k += 1;
        i32::from(*h.get(3)?)
    } else {
        first + i32::from(rows)
    };
    let (kind, n) = if code == BY_POLYGON {
        (Kind::Polygon, 0)
    } else {
        k += 1;
        let n = usize::from(*h.get(k - 1)?);
        (
            if code == BY_INDEX {
                Kind::Indices
            } else {
                Kind::Inline
            },
            n,
        )
    };
    let body = at + k + extra;
    let next = body
        + match kind {
            Kind::Polygon => 1,
            Kind::Indices => n,
            Kind::Inline => 4 * n,
        };
    Some(Head {
        first,
        end,
        colour: (w1, w2),
        kind,
        clipped: code == INLINE_CLIPPED,
        n,
        body,
        next,
    })
}

/// A record's header, decoded.
#[derive(Clone, Copy)]
struct Head {
    first: i32,
    end: i32,
    /// The second and third words (`r | g << 8`, `b | ...`).
    colour: (u16, u16),
    kind: Kind,
    clipped: bool,
    n: usize,
    body: usize,
    next: usize,
}

mod index;

#[cfg(test)]
mod tests;
