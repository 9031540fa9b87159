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
//! * Sizes, in 16-bit words: a header of 4, plus 1 with outlines, plus 2
//!   with ids, plus 1 per vertex (by index) or 4 per vertex (inline); a
//!   polygon of more than 255 vertices adds 1. A triangle of a frame
//!   without outlines or ids takes 7 words (14 bytes).
//!
//! Header layout: `[first | inline << 15, end | clipped << 15, r | g << 8,
//! b | n << 8]`, `first..end` the rows (both in `0..=2^14`, the largest
//! viewport), `n = 0` meaning "the next word holds the vertex count".

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

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
    pub hidden: u8,
    /// Whether clipping changed it (its edges are no longer the stored
    /// ones, so outlines draw every edge).
    pub clipped: bool,
}

/// Where a record's screen points are.
#[derive(Clone, Copy, Debug)]
pub enum Points<'a> {
    /// Vertex indices into the frame's vertex cache (each below 2^16).
    Indices(&'a [u16]),
    /// The points themselves.
    Inline(&'a [ScreenPt]),
}

/// A record read back: its entry and where its points start.
#[derive(Clone, Copy, Debug)]
pub struct Record {
    /// The fixed part.
    pub entry: Entry,
    /// Vertex count.
    pub n: usize,
    /// Points stored inline (else vertex indices).
    pub inline: bool,
    body: usize,
    next: usize,
}

/// Bit 15 of the first two header words.
const FLAG: u16 = 0x8000;

/// A list of records in caller storage (see the module docs).
#[derive(Debug)]
pub struct DisplayList<'m> {
    buf: &'m mut [u16],
    len: usize,
    peak: usize,
    ids: bool,
    outlines: bool,
    /// Groups in the table at the top of `buf` (see [`GROUP`]).
    groups: usize,
    /// Records in the last group.
    in_group: usize,
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
    /// asked (they cost 2 and 1 words a record).
    pub fn new(buf: &'m mut [u16], ids: bool, outlines: bool) -> Self {
        DisplayList {
            buf,
            len: 0,
            peak: 0,
            ids,
            outlines,
            groups: 0,
            in_group: 0,
        }
    }

    /// Empties the list (the storage is kept).
    pub fn clear(&mut self) {
        self.len = 0;
        self.groups = 0;
        self.in_group = 0;
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
        self.peak
    }

    /// Words a record of `n` points takes.
    pub fn record_words(&self, n: usize, inline: bool) -> usize {
        4 + usize::from(n > 255)
            + usize::from(self.outlines)
            + 2 * usize::from(self.ids)
            + n * if inline { 4 } else { 1 }
    }

    /// Appends a record; `false` (and nothing written) when it does not
    /// fit or a field is out of range (rows outside `0..=2^14`, more than
    /// 65 535 points).
    pub fn push(&mut self, e: &Entry, pts: Points<'_>) -> bool {
        let (n, inline) = match pts {
            Points::Indices(ix) => (ix.len(), false),
            Points::Inline(p) => (p.len(), true),
        };
        let rows_ok = |r: i32| (0..=1 << 14).contains(&r);
        if !rows_ok(e.first) || !rows_ok(e.end) || n > usize::from(u16::MAX) {
            return false;
        }
        let words = self.record_words(n, inline);
        let table = 4 * (self.groups + usize::from(self.in_group == 0));
        if self.len + words + table > self.buf.len() {
            return false;
        }
        let Some(out) = self.buf.get_mut(self.len..self.len + words) else {
            return false;
        };
        let n8 = if n > 255 { 0 } else { n as u16 };
        let mut k = 4;
        out[0] = e.first as u16 | if inline { FLAG } else { 0 };
        out[1] = e.end as u16 | if e.clipped { FLAG } else { 0 };
        out[2] = u16::from(e.rgb.r()) | u16::from(e.rgb.g()) << 8;
        out[3] = u16::from(e.rgb.b()) | n8 << 8;
        if n > 255 {
            out[k] = n as u16;
            k += 1;
        }
        if self.outlines {
            out[k] = u16::from(e.hidden);
            k += 1;
        }
        if self.ids {
            out[k] = e.id as u16;
            out[k + 1] = (e.id >> 16) as u16;
            k += 2;
        }
        match pts {
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
        self.note(at, e.first as u16, e.end as u16, self.len);
        self.peak = self.peak.max(self.len + 4 * self.groups);
        true
    }

    /// The record at word `at` (0 for the first), or `None` at the end.
    #[inline]
    pub fn record(&self, at: usize) -> Option<Record> {
        let (h, n, body) = self.head(at)?;
        let [h0, h1, h2, h3] = h;
        // The optional words sit right before the points: the outline
        // mask, then the id.
        let mut k = body - at - usize::from(self.outlines) - 2 * usize::from(self.ids);
        let hidden = if self.outlines {
            k += 1;
            *self.buf.get(at + k - 1)? as u8
        } else {
            0
        };
        let id = if self.ids {
            k += 2;
            u32::from(*self.buf.get(at + k - 2)?) | u32::from(*self.buf.get(at + k - 1)?) << 16
        } else {
            0
        };
        let inline = h0 & FLAG != 0;
        let next = body + n * if inline { 4 } else { 1 };
        Some(Record {
            entry: Entry {
                first: i32::from(h0 & !FLAG),
                end: i32::from(h1 & !FLAG),
                rgb: Rgb888::new(h2 as u8, (h2 >> 8) as u8, h3 as u8),
                id,
                hidden,
                clipped: h1 & FLAG != 0,
            },
            n,
            inline,
            body,
            next,
        })
    }

    /// The fixed header words of the record at word `at`, its vertex count
    /// and where its points start. `None` at the end.
    #[inline(always)]
    fn head(&self, at: usize) -> Option<([u16; 4], usize, usize)> {
        let h = self.buf.get(at..self.len)?;
        let &[h0, h1, h2, h3, ..] = h else {
            return None;
        };
        let mut k = 4 + usize::from(self.outlines) + 2 * usize::from(self.ids);
        let mut n = usize::from(h3 >> 8);
        if n == 0 {
            n = usize::from(*h.get(4)?);
            k += 1;
        }
        Some(([h0, h1, h2, h3], n, at + k))
    }

    /// The rows `(first, end)` of the record at word `at` and where the
    /// next one starts, from its first words only: the quick test a band
    /// makes of every record. `None` at the end.
    #[inline(always)]
    pub fn rows_at(&self, at: usize) -> Option<(i32, i32, usize)> {
        let ([h0, h1, ..], n, body) = self.head(at)?;
        let per = if h0 & FLAG != 0 { 4 } else { 1 };
        Some((i32::from(h0 & !FLAG), i32::from(h1 & !FLAG), body + n * per))
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

    /// The vertex indices of a record stored by index (empty for an
    /// inline one).
    #[inline]
    pub fn indices(&self, r: &Record) -> &[u16] {
        if r.inline {
            return &[];
        }
        self.buf.get(r.body..r.body + r.n).unwrap_or(&[])
    }

    /// Drops every record whose first row is at or below `cut`, keeping
    /// the others in order (compacting in place).
    pub fn retain_rows_below(&mut self, cut: i32) {
        let (mut read, mut write) = (0, 0);
        while let Some(r) = self.record(read) {
            let words = r.next - read;
            if r.entry.first < cut {
                self.buf.copy_within(read..r.next, write);
                write += words;
            }
            read = r.next;
        }
        self.len = write;
        // The groups again, over the records kept (fewer entries than
        // before, so they fit).
        self.groups = 0;
        self.in_group = 0;
        let mut at = 0;
        while let Some((first, end, next)) = self.rows_at(at) {
            self.note(at, first as u16, end as u16, self.len);
            at = next;
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    fn entry(first: i32, end: i32) -> Entry {
        Entry {
            first,
            end,
            rgb: Rgb888::new(1, 2, 3),
            id: 0x0102_0304,
            hidden: 0b101,
            clipped: first % 2 == 1,
        }
    }

    #[test]
    fn records_round_trip_in_every_layout() {
        let pts = [ScreenPt { x: -70000, y: 5 }, ScreenPt { x: 3, y: 1 << 20 }];
        let many: std::vec::Vec<u16> = (0..300).collect();
        for (ids, outlines) in [(false, false), (true, false), (false, true), (true, true)] {
            let mut buf = [0u16; 512];
            let mut l = DisplayList::new(&mut buf, ids, outlines);
            assert!(l.push(&entry(3, 9), Points::Indices(&[7, 8, 9])));
            assert!(l.push(&entry(4, 5), Points::Inline(&pts)));
            assert!(l.push(&entry(0, 16384), Points::Indices(&many)));
            let a = l.record(0).unwrap();
            let b = l.record(l.next(&a)).unwrap();
            let c = l.record(l.next(&b)).unwrap();
            assert!(l.record(l.next(&c)).is_none());
            assert_eq!(l.next(&c), l.len());
            assert_eq!(
                (a.n, a.inline, l.indices(&a)),
                (3, false, &[7u16, 8, 9][..])
            );
            assert_eq!((b.n, b.inline), (2, true));
            assert_eq!([l.inline_point(&b, 0), l.inline_point(&b, 1)], pts);
            assert_eq!((c.n, l.indices(&c)), (300, &many[..]));
            let want = |e: Entry| Entry {
                id: if ids { e.id } else { 0 },
                hidden: if outlines { e.hidden } else { 0 },
                ..e
            };
            assert_eq!(a.entry, want(entry(3, 9)));
            assert_eq!(b.entry, want(entry(4, 5)));
            assert_eq!(c.entry, want(entry(0, 16384)));
            assert_eq!(
                l.len(),
                l.record_words(3, false) + l.record_words(2, true) + l.record_words(300, false)
            );
        }
    }

    #[test]
    fn a_full_list_refuses_whole_records() {
        // A triangle takes 7 words, and its group's entry 4.
        let mut buf = [0u16; 11];
        let mut l = DisplayList::new(&mut buf, false, false);
        assert!(l.push(&entry(0, 1), Points::Indices(&[1, 2, 3])));
        assert!(!l.push(&entry(0, 1), Points::Indices(&[1, 2, 3])));
        assert!(!l.push(&entry(-1, 1), Points::Indices(&[1])));
        assert!(!l.push(&entry(0, 1 << 15), Points::Indices(&[1])));
        assert_eq!((l.len(), l.peak(), l.groups()), (7, 11, 1));
    }

    #[test]
    fn groups_cover_their_records() {
        let mut buf = [0u16; 1024];
        let mut l = DisplayList::new(&mut buf, false, false);
        let n = 2 * GROUP + 3;
        for i in 0..n as i32 {
            assert!(l.push(&entry(i, i + 2), Points::Indices(&[1, 2, 3])));
        }
        assert_eq!(l.groups(), 3);
        let mut seen = 0;
        for g in 0..l.groups() {
            let (first, end, start, stop) = l.group(g).unwrap();
            let mut at = start;
            while at < stop {
                let (f, e, next) = l.rows_at(at).unwrap();
                assert!(f >= first && e <= end);
                seen += 1;
                at = next;
            }
        }
        assert_eq!(seen, n);
        assert_eq!(l.group(0).map(|g| (g.0, g.1)), Some((0, GROUP as i32 + 1)));
        // Compaction rebuilds the groups over what is kept.
        l.retain_rows_below(GROUP as i32 + 2);
        assert_eq!(l.groups(), 2);
        assert_eq!(
            l.group(1).map(|g| (g.0, g.1)),
            Some((GROUP as i32, GROUP as i32 + 3))
        );
    }

    #[test]
    fn retain_keeps_order() {
        let mut buf = [0u16; 64];
        let mut l = DisplayList::new(&mut buf, false, false);
        for (i, first) in [0, 20, 5, 40, 15].into_iter().enumerate() {
            assert!(l.push(&entry(first, first + 3), Points::Indices(&[i as u16; 3])));
        }
        l.retain_rows_below(16);
        let mut at = 0;
        let mut kept = std::vec::Vec::new();
        while let Some(r) = l.record(at) {
            kept.push((r.entry.first, l.indices(&r)[0]));
            at = l.next(&r);
        }
        assert_eq!(kept, [(0, 0), (5, 2), (15, 4)]);
        assert_eq!(l.len(), 21);
    }
}
