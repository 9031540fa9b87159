//! The band index of a [`DisplayList`]: built once a walk from the
//! records (`index_bands`), it gives each band the offsets of the records
//! touching it (`band`), so that a band's replay reads only its own
//! records; plus what the band loop does with the list's spare words
//! (`replay_parts`, `note_spare_used`) and the retain of records below a
//! row (`retain_rows_below`). Split out of `list.rs`, whose module docs
//! state the list's layout.

use super::{head_in, BandIndex, DisplayList, Tally, BY_POLYGON, LONG_ROWS};

impl<'m> DisplayList<'m> {
    /// Builds the **band index** of the records, in the words the records
    /// and the group table leave free: for each of the bands of `rows` rows
    /// from row `y` up to row `cut`, the offsets of the records touching it,
    /// in the order they were pushed (a record touching several bands is
    /// listed in each). [`DisplayList::band`] then hands a band its own
    /// records instead of a scan of every group that overlaps it (most of
    /// whose records miss the band: records come in walk order, not row
    /// order). `false`, and no index, when it does not fit (or the records
    /// take 2^16 words or more, the entries being `u16`): the replay scans,
    /// as without an index. Any push or retain drops the index.
    ///
    /// When the pushes kept a tally of the same bands
    /// ([`DisplayList::tally_bands`]), the counts come from it and the
    /// records are read once (to place them), else twice (to count them
    /// first).
    ///
    /// Out of line: it runs once a walk, and kept apart it adds nothing to
    /// the stack frame of the band loop that calls it.
    #[inline(never)]
    pub fn index_bands(&mut self, y: i32, rows: i32, cut: i32) -> bool {
        self.index = None;
        if rows <= 0 || cut <= y || self.len > usize::from(u16::MAX) {
            return false;
        }
        let bands = ((cut - y + rows - 1) / rows) as usize;
        let at = self.len;
        // The group table takes the top `4 * groups` words.
        let free = self.buf.len().saturating_sub(self.table_words());
        if at + bands + 1 > free {
            return false;
        }
        // The bands a record touches, clamped to the indexed ones (none
        // when it misses them all).
        // A shift for the usual band heights (a power of two): a division
        // is a library call of dozens of instructions on a Cortex-M0, two
        // a record.
        let shift = (rows as u32)
            .is_power_of_two()
            .then(|| rows.trailing_zeros());
        let band_of = |row: i32| match shift {
            Some(s) => (row >> s) as usize,
            None => (row / rows) as usize,
        };
        let span = |first: i32, end: i32| -> Option<(usize, usize)> {
            if end <= y || first >= cut || end <= first {
                return None;
            }
            Some((band_of(first.max(y) - y), band_of(end.min(cut) - 1 - y)))
        };
        // Counting sort: counts in cursors 1..=bands, then their prefix
        // sums, then each record placed at its bands' cursors (which end
        // up at each band's end).
        let extra = self.extra;
        let rows_at =
            |buf: &[u16], at: usize| head_in(buf, extra, at).map(|h| (h.first, h.end, h.next));
        // The tally of the same bands, when the pushes kept one: the counts
        // without a pass over the records.
        let t = &self.tally;
        let tallied = t.on && t.y == y && t.cut == cut && shift == Some(t.shift);
        let (head, tail) = self.buf.split_at_mut(at);
        let (cursors, entries) = tail.split_at_mut(bands + 1);
        let total = match t.counts.get(..bands).filter(|_| tallied) {
            Some(counts) => {
                cursors[0] = 0;
                cursors[1..].copy_from_slice(counts);
                counts.iter().map(|&c| usize::from(c)).sum()
            }
            None => {
                cursors.fill(0);
                let mut r = 0;
                let mut total = 0usize;
                while let Some((first, end, next)) = rows_at(head, r) {
                    if let Some((b0, b1)) = span(first, end) {
                        for c in &mut cursors[b0 + 1..=b1 + 1] {
                            *c += 1;
                        }
                        total += b1 + 1 - b0;
                    }
                    r = next;
                }
                total
            }
        };
        if at + bands + 1 + total > free || total > usize::from(u16::MAX) {
            return false;
        }
        for b in 1..=bands {
            cursors[b] += cursors[b - 1];
        }
        // Placed by a loop of its own for each way of finding a row's band
        // (a shift, the usual case, or a division): with the choice made
        // inside, the loop kept its values on the stack (measured on a
        // Cortex-M4F, socket's 16-row bands).
        let (first_row, last_row) = (y, cut);
        match shift {
            Some(s) => place(
                head,
                extra,
                cursors,
                entries,
                (first_row, last_row),
                |row| (row >> s) as usize,
            ),
            None => place(
                head,
                extra,
                cursors,
                entries,
                (first_row, last_row),
                |row| (row / rows) as usize,
            ),
        }
        let end = at + bands + 1 + total;
        self.index = Some(BandIndex {
            y,
            rows,
            bands,
            at,
            end,
        });
        self.peak = self.peak.max(at + bands + 1 + total + self.table_words());
        true
    }

    /// The offsets of the records touching the band that starts at row
    /// `y0`, in push order, when the band index covers it
    /// ([`DisplayList::index_bands`]); `None` otherwise.
    #[inline]
    pub fn band(&self, y0: i32) -> Option<&[u16]> {
        let ix = self.index?;
        let k = y0 - ix.y;
        if k < 0 || k % ix.rows != 0 {
            return None;
        }
        let b = (k / ix.rows) as usize;
        if b >= ix.bands {
            return None;
        }
        // After the fill, cursor `b` is band `b`'s end and band `b - 1`'s
        // cursor its start.
        let cursors = self.buf.get(ix.at..ix.at + ix.bands + 1)?;
        let start = if b == 0 {
            0
        } else {
            usize::from(cursors[b - 1])
        };
        let stop = usize::from(cursors[b]);
        let base = ix.at + ix.bands + 1;
        self.buf.get(base + start..base + stop)
    }

    /// The list for a replay, and the free words it leaves as `u32`s (the
    /// carried triangles of `raster::carry`): with a band index, a list
    /// over the records and the index only (a band reads its records
    /// through the index, never the group table) and the words between
    /// the index and the group table; without one, the list itself and
    /// no words. No words either when they are not 4-byte aligned (a
    /// list over storage that did not start as `u32`s).
    pub fn replay_parts(&mut self) -> (DisplayList<'_>, &mut [u32]) {
        if self.index.is_none() {
            self.seal();
        }
        let (len, extra, ids, outlines) = (self.len, self.extra, self.ids, self.outlines);
        let Some(ix) = self.index else {
            return (
                DisplayList {
                    buf: &mut *self.buf,
                    len,
                    peak: 0,
                    ids,
                    outlines,
                    extra,
                    groups: self.groups,
                    in_group: self.in_group,
                    index: None,
                    tally: Tally::OFF,
                    recs: 0,
                },
                &mut [],
            );
        };
        let top = self.buf.len().saturating_sub(self.table_words());
        // Even offsets of storage that was `u32`s are 4-byte aligned.
        let lo = ix.end.next_multiple_of(2).min(top);
        let hi = lo + (top - lo) / 2 * 2;
        let (low, rest) = self.buf.split_at_mut(lo);
        let spare = rest.get_mut(..hi - lo).unwrap_or(&mut []);
        let words = bytemuck::try_cast_slice_mut::<u16, u32>(spare).unwrap_or(&mut []);
        let view = DisplayList {
            buf: low,
            len,
            peak: 0,
            ids,
            outlines,
            extra,
            // The replay of an indexed list reads no group.
            groups: 0,
            in_group: 0,
            index: Some(ix),
            tally: Tally::OFF,
            recs: 0,
        };
        (view, words)
    }

    /// Counts `words` (`u32`s) of the free words [`DisplayList::replay_parts`]
    /// lent as used, in [`DisplayList::peak`].
    pub fn note_spare_used(&mut self, words: usize) {
        if let Some(ix) = self.index {
            let used = ix.end.next_multiple_of(2) + 2 * words + self.table_words();
            self.peak = self.peak.max(used.min(self.buf.len()));
        }
    }

    /// Drops every record whose first row is at or below `cut`, keeping
    /// the others in order (compacting in place).
    ///
    /// One pass: the group table is rebuilt as the records are kept (it
    /// has fewer entries than before, so each new entry lands on an old one
    /// already passed), and each run of kept records moves in one copy
    /// (the leading run stays put). A frame short of memory calls this at
    /// every overflow of a walk; on a Cortex-M0 a copy per record (a
    /// `memmove` call each) and a second pass for the groups made it cost
    /// about as much as the walk it saves (measured, docs/small-ram.md).
    pub fn retain_rows_below(&mut self, cut: i32) {
        self.peak = self.peak();
        self.index = None;
        self.tally.on = false;
        self.groups = 0;
        self.in_group = 0;
        // `write`: where the kept records end; `run`: where the run of
        // kept records not yet moved starts (in the old layout).
        let (mut read, mut write, mut run) = (0, 0, 0);
        while let Some(h) = self.head(read) {
            if h.first < cut {
                // The record lands at `write + (read - run)` once its run
                // moves.
                let at = write + (read - run);
                self.note(at, h.first as u16, h.end as u16, at);
            } else {
                if run < read {
                    self.buf.copy_within(run..read, write);
                    write += read - run;
                }
                run = h.next;
            }
            read = h.next;
        }
        if run < read {
            self.buf.copy_within(run..read, write);
            write += read - run;
        }
        self.len = write;
    }
}

/// The placement pass of [`DisplayList::index_bands`]: writes each record
/// of `records` (offset `r`) at the cursors of the bands `y..cut` it
/// touches (`band_of` a row relative to `y`), advancing them. The common
/// record (by polygon, fewer than 255 rows, no optional words: 4 words) is
/// decoded straight, the others by [`head_in`].
#[inline(always)]
fn place(
    records: &[u16],
    extra: usize,
    cursors: &mut [u16],
    entries: &mut [u16],
    (y, cut): (i32, i32),
    band_of: impl Fn(i32) -> usize,
) {
    let quick = extra == 0;
    let mut r = 0;
    loop {
        let (first, end, next) = match records.get(r..r + 4) {
            Some(&[w0, _, w2, _]) if quick && w0 >> 14 == BY_POLYGON && w2 >> 8 != LONG_ROWS => {
                let first = i32::from(w0 & 0x3fff);
                (first, first + i32::from(w2 >> 8), r + 4)
            }
            _ => match head_in(records, extra, r) {
                Some(h) => (h.first, h.end, h.next),
                None => break,
            },
        };
        if end > y && first < cut && end > first {
            let (b0, b1) = (band_of(first.max(y) - y), band_of(end.min(cut) - 1 - y));
            if b0 == b1 {
                // A record of one band (most of them): no loop.
                if let Some(c) = cursors.get_mut(b0) {
                    if let Some(e) = entries.get_mut(usize::from(*c)) {
                        *e = r as u16;
                    }
                    *c += 1;
                }
            } else if let Some(cs) = cursors.get_mut(b0..=b1) {
                for c in cs {
                    if let Some(e) = entries.get_mut(usize::from(*c)) {
                        *e = r as u16;
                    }
                    *c += 1;
                }
            }
        }
        r = next;
    }
}
