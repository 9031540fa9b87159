//! Unit tests of the display list (`raster/list.rs`).

extern crate std;
use super::*;

fn entry(first: i32, end: i32) -> Entry {
    Entry {
        first,
        end,
        rgb: Rgb888::new(1, 2, 3),
        id: 0x0102_0304,
        hidden: 0x8000_0000_0001_0005,
        clipped: false,
    }
}
#[test]
fn records_round_trip_in_every_layout() {
    let pts = [ScreenPt { x: -70000, y: 5 }, ScreenPt { x: 3, y: 1 << 20 }];
    let many: std::vec::Vec<u16> = (0..300).collect();
    for (ids, outlines) in [(false, false), (true, false), (false, true), (true, true)] {
        let mut buf = [0u16; 512];
        let mut l = DisplayList::new(&mut buf, ids, outlines);
        let clipped = Entry {
            clipped: true,
            ..entry(4, 5)
        };
        assert!(l.push(&entry(3, 9), Points::Indices(&[7, 8, 9])));
        assert!(l.push(&clipped, Points::Inline(&pts)));
        assert!(l.push(&entry(0, 16384), Points::Indices(&many)));
        assert!(l.push(&entry(2, 256), Points::Polygon(65535)));
        assert!(l.push(&entry(2, 257), Points::Polygon(7)));
        let a = l.record(0).unwrap();
        let b = l.record(l.next(&a)).unwrap();
        let c = l.record(l.next(&b)).unwrap();
        let d = l.record(l.next(&c)).unwrap();
        let e = l.record(l.next(&d)).unwrap();
        assert!(l.record(l.next(&e)).is_none());
        assert_eq!(l.next(&e), l.len());
        assert_eq!(
            (a.n, a.kind, l.indices(&a), l.polygon(&a)),
            (3, Kind::Indices, &[7u16, 8, 9][..], None)
        );
        assert_eq!((b.n, b.kind), (2, Kind::Inline));
        assert_eq!([l.inline_point(&b, 0), l.inline_point(&b, 1)], pts);
        assert_eq!((c.n, l.indices(&c)), (300, &many[..]));
        assert_eq!(
            (d.kind, l.polygon(&d), l.indices(&d)),
            (Kind::Polygon, Some(65535), &[][..])
        );
        assert_eq!(l.polygon(&e), Some(7));
        let want = |e: Entry| Entry {
            id: if ids { e.id } else { 0 },
            hidden: if outlines { e.hidden } else { 0 },
            ..e
        };
        assert_eq!(a.entry, want(entry(3, 9)));
        assert_eq!(b.entry, want(clipped));
        assert_eq!(c.entry, want(entry(0, 16384)));
        assert_eq!(d.entry, want(entry(2, 256)));
        assert_eq!(e.entry, want(entry(2, 257)));
        assert_eq!(
            l.len(),
            l.record_words(3, Kind::Indices, 6)
                + l.record_words(2, Kind::Inline, 1)
                + l.record_words(300, Kind::Indices, 16384)
                + l.record_words(0, Kind::Polygon, 254)
                + l.record_words(0, Kind::Polygon, 255)
        );
    }
}

#[test]
fn a_full_list_refuses_whole_records() {
    // A triangle by polygon takes 4 words, and its group's entry 4.
    let mut buf = [0u16; 8];
    let mut l = DisplayList::new(&mut buf, false, false);
    assert!(l.push(&entry(0, 1), Points::Polygon(3)));
    assert!(!l.push(&entry(0, 1), Points::Polygon(4)));
    assert!(!l.push(&entry(-1, 1), Points::Indices(&[1])));
    assert!(!l.push(&entry(0, 1 << 15), Points::Indices(&[1])));
    assert!(!l.push(&entry(1 << 14, 1 << 14), Points::Indices(&[1])));
    assert!(!l.push(&entry(3, 2), Points::Indices(&[1])));
    assert_eq!((l.len(), l.peak(), l.groups()), (4, 8, 1));
    // A clipped polygon's points are not the tree's: inline only.
    let mut buf = [0u16; 64];
    let mut l = DisplayList::new(&mut buf, false, false);
    let clipped = Entry {
        clipped: true,
        ..entry(0, 1)
    };
    assert!(!l.push(&clipped, Points::Polygon(3)));
    assert!(!l.push(&clipped, Points::Indices(&[1, 2, 3])));
    assert!(l.is_empty());
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

/// The offsets of the records touching rows `[y0, y1)`, by a scan.
fn scan(l: &DisplayList<'_>, y0: i32, y1: i32) -> std::vec::Vec<u16> {
    let mut at = 0;
    let mut out = std::vec::Vec::new();
    while let Some((first, end, next)) = l.rows_at(at) {
        if end > y0 && first < y1 {
            out.push(at as u16);
        }
        at = next;
    }
    out
}

#[test]
fn band_index_lists_each_bands_records_in_order() {
    let mut buf = [0u16; 1024];
    let mut l = DisplayList::new(&mut buf, false, false);
    // Rows out of order, one empty, one above and one across the
    // indexed rows, one long.
    let rows = [
        (20, 23),
        (0, 40),
        (5, 5),
        (33, 34),
        (2, 9),
        (15, 17),
        (60, 90),
        (0, 300),
    ];
    for (i, &(first, end)) in rows.iter().enumerate() {
        let pts = if i % 2 == 0 {
            Points::Polygon(i as u16)
        } else {
            Points::Indices(&[1, 2, 3])
        };
        assert!(l.push(&entry(first, end), pts));
    }
    assert_eq!(l.band(8), None);
    assert!(l.index_bands(8, 8, 48));
    for y0 in (8..48).step_by(8) {
        assert_eq!(l.band(y0).unwrap(), &scan(&l, y0, y0 + 8)[..], "band {y0}");
    }
    // Not a band start, or outside the indexed bands.
    assert_eq!((l.band(0), l.band(12), l.band(48)), (None, None, None));
    let peak = l.peak();
    assert!(peak > l.len() + 4 * l.groups());
    // A push drops the index.
    assert!(l.push(&entry(9, 10), Points::Polygon(1)));
    assert_eq!(l.band(8), None);
    // An index that does not fit is not built: the list is unchanged.
    let mut small = [0u16; 44];
    let mut l = DisplayList::new(&mut small, false, false);
    for i in 0..9 {
        assert!(l.push(&entry(0, 240), Points::Polygon(i)));
    }
    let len = l.len();
    assert!(!l.index_bands(0, 16, 240));
    assert_eq!((l.band(0), l.len()), (None, len));
    assert!(l.record(0).is_some());
}

/// The tally the pushes keep gives the very index the counting pass
/// gives (records of every kind, rows above, across and below the
/// indexed bands), and a retain or other bands fall back to counting.
#[test]
fn tallied_index_equals_the_counted_one() {
    let pts = [ScreenPt { x: 1, y: 2 }; 3];
    let rows = [
        (20, 23),
        (0, 40),
        (5, 5),
        (33, 34),
        (2, 9),
        (15, 17),
        (60, 90),
        (0, 300),
        (47, 48),
        (48, 49),
        (3, 260),
    ];
    let fill = |l: &mut DisplayList<'_>| {
        for (i, &(first, end)) in rows.iter().enumerate() {
            let p = match i % 3 {
                0 => Points::Polygon(i as u16),
                1 => Points::Indices(&[1, 2, 3]),
                _ => Points::Inline(&pts),
            };
            assert!(l.push(&entry(first, end), p));
        }
    };
    for (y, band, cut) in [(8, 8, 48), (0, 16, 240), (4, 4, 44), (0, 1, 32)] {
        let mut a = [0u16; 1024];
        let mut b = [0u16; 1024];
        let mut tallied = DisplayList::new(&mut a, false, false);
        tallied.tally_bands(y, band, cut);
        assert!(tallied.tally.on);
        fill(&mut tallied);
        let mut counted = DisplayList::new(&mut b, false, false);
        fill(&mut counted);
        assert!(!counted.tally.on);
        assert!(tallied.index_bands(y, band, cut));
        assert!(counted.index_bands(y, band, cut));
        for y0 in (y..cut).step_by(band as usize) {
            // The scan's records but the empty one (5, 5), which the
            // index leaves out.
            let mut want = scan(&counted, y0, y0 + band);
            want.retain(|&at| counted.rows_at(at.into()).is_some_and(|(f, e, _)| e > f));
            assert_eq!(counted.band(y0).unwrap(), &want[..], "band {y0}");
            assert_eq!(tallied.band(y0).unwrap(), &want[..], "band {y0}");
        }
        assert_eq!(tallied.peak(), counted.peak());
    }
    // Not a power of two, too many bands, or a retain: no tally.
    let mut a = [0u16; 1024];
    let mut l = DisplayList::new(&mut a, false, false);
    l.tally_bands(0, 12, 240);
    assert!(!l.tally.on);
    l.tally_bands(0, 1, 240);
    assert!(!l.tally.on);
    l.tally_bands(0, 16, 240);
    fill(&mut l);
    l.retain_rows_below(40);
    assert!(!l.tally.on);
    assert!(l.index_bands(0, 16, 48));
    for y0 in [16, 32] {
        assert_eq!(l.band(y0).unwrap(), &scan(&l, y0, y0 + 16)[..]);
    }
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
    assert_eq!(l.len(), 3 * 7);
}

/// The one-pass retain leaves the very records and groups that pushing
/// the kept records into an empty list gives, for mixed record kinds
/// and several groups, whatever rows are cut (kept runs at the start,
/// in the middle and at the end).
#[test]
fn retain_equals_a_list_pushed_again() {
    let firsts: std::vec::Vec<i32> = (0..3 * GROUP as i32 + 5).map(|i| (i * 37) % 50).collect();
    let pts = [
        ScreenPt { x: 1, y: 2 },
        ScreenPt { x: 3, y: 4 },
        ScreenPt { x: 5, y: 6 },
    ];
    let push = |l: &mut DisplayList<'_>, i: usize, first: i32| {
        let e = entry(first, first + 1 + (i as i32 % 3) * 200);
        let ix = [i as u16, 1, 2];
        let p = match i % 3 {
            0 => Points::Polygon(i as u16),
            1 => Points::Indices(&ix),
            _ => Points::Inline(&pts),
        };
        assert!(l.push(&e, p));
    };
    for cut in [0, 1, 10, 25, 49, 50] {
        let mut buf = [0u16; 2048];
        let mut l = DisplayList::new(&mut buf, false, false);
        for (i, &f) in firsts.iter().enumerate() {
            push(&mut l, i, f);
        }
        l.retain_rows_below(cut);
        let mut want_buf = [0u16; 2048];
        let mut want = DisplayList::new(&mut want_buf, false, false);
        for (i, &f) in firsts.iter().enumerate() {
            if f < cut {
                push(&mut want, i, f);
            }
        }
        assert_eq!(
            (l.len(), l.groups()),
            (want.len(), want.groups()),
            "cut {cut}"
        );
        assert_eq!(l.buf[..l.len()], want.buf[..want.len()], "cut {cut}");
        for g in 0..l.groups() {
            assert_eq!(l.group(g), want.group(g), "cut {cut} group {g}");
        }
    }
}

/// While the tally counts, the pushes leave the group table to
/// [`DisplayList::seal`]: the same records fit (its room is kept), the
/// sealed table equals the one written push by push, and so do the peak,
/// the free words a replay gets and the records a scan finds.
#[test]
fn a_sealed_group_table_equals_the_one_written_as_pushed() {
    if TALLY == 0 {
        return;
    }
    let pts = [ScreenPt { x: 1, y: 2 }; 3];
    // Every kind, short and long, until the list is full (several group
    // entries, the last one partial).
    let push = |l: &mut DisplayList<'_>, i: usize| {
        let first = (i * 7 % 200) as i32;
        let e = entry(
            first,
            first + (i % 5) as i32 * 20 + i32::from(i.is_multiple_of(13)) * 300,
        );
        let p = match i % 4 {
            0 | 1 => Points::Polygon(i as u16),
            2 => Points::Indices(&[4, 5, 6]),
            _ => Points::Inline(&pts),
        };
        l.push(&e, p)
    };
    for size in [40, 97, 160, 333, 600] {
        let mut a = std::vec![0u16; size];
        let mut b = std::vec![0u16; size];
        let mut lazy = DisplayList::new(&mut a, false, false);
        lazy.tally_bands(0, 16, 240);
        let mut eager = DisplayList::new(&mut b, false, false);
        let mut pushed = 0;
        for i in 0..200 {
            let (x, y) = (push(&mut lazy, i), push(&mut eager, i));
            assert_eq!(x, y, "size {size}, record {i}");
            pushed += usize::from(x);
        }
        // Full, and the larger ones over several group entries.
        assert!(
            pushed < 200 && (size < 300 || pushed > GROUP),
            "size {size}: {pushed}"
        );
        assert!(lazy.lazy() && lazy.groups() == 0);
        assert_eq!(lazy.peak(), eager.peak(), "size {size}");
        let spare_lazy = lazy.replay_parts().1.len();
        let spare_eager = eager.replay_parts().1.len();
        assert_eq!(spare_lazy, spare_eager);
        // `replay_parts` without an index sealed it.
        assert!(!lazy.lazy());
        assert_eq!(lazy.groups(), eager.groups());
        for g in 0..eager.groups() {
            assert_eq!(lazy.group(g), eager.group(g), "size {size}, group {g}");
        }
        for y0 in (0..240).step_by(16) {
            assert_eq!(scan(&lazy, y0, y0 + 16), scan(&eager, y0, y0 + 16));
        }
        assert_eq!(lazy.peak(), eager.peak());
        // Pushes after the seal write the table as they go.
        let more = (push(&mut lazy, 7), push(&mut eager, 7));
        assert_eq!(more.0, more.1);
        assert_eq!(lazy.groups(), eager.groups());
        lazy.clear();
        eager.clear();
        assert_eq!(lazy.peak(), eager.peak());
    }
}

/// `DisplayList::push_polygon` (the band walk's common record from its
/// parts) takes exactly the polygons `push` stores as the common 4-word
/// record, and writes the same words, tally and groups; the others it
/// leaves, unwritten, to `push`.
#[test]
fn push_polygon_is_the_common_push() {
    let cases = [
        (0, 1),
        (3, 9),
        (7, 7),
        (0, 254),
        (0, 255),
        (2, 300),
        (-1, 4),
        (16383, 16384),
        (16384, 16390),
        (5, 3),
    ];
    for (ids, outlines) in [(false, false), (true, false), (false, true)] {
        for size in [40usize, 64, 512] {
            let (mut a, mut b) = (std::vec![0u16; size], std::vec![0u16; size]);
            let mut la = DisplayList::new(&mut a, ids, outlines);
            let mut lb = DisplayList::new(&mut b, ids, outlines);
            la.tally_bands(0, 16, 240);
            lb.tally_bands(0, 16, 240);
            for (k, &(first, end)) in cases.iter().cycle().take(40).enumerate() {
                let e = entry(first, end);
                let i = k as u16 * 7;
                let before = lb.len();
                let pushed = lb.push(&e, Points::Polygon(i));
                match la.push_polygon((first, end), e.rgb, i) {
                    Some(p) => {
                        assert_eq!(p, pushed, "{first}..{end}");
                        assert!(!p || lb.len() == before + 4);
                    }
                    None => {
                        assert!(!pushed || lb.len() != before + 4 || ids || outlines);
                        assert_eq!(la.push(&e, Points::Polygon(i)), pushed);
                    }
                }
                assert_eq!(la.len(), lb.len());
                assert_eq!(la.peak(), lb.peak());
            }
            la.seal();
            lb.seal();
            assert_eq!(la.groups(), lb.groups());
            assert_eq!(la.index_bands(0, 16, 240), lb.index_bands(0, 16, 240));
            assert_eq!(la.band(32), lb.band(32));
            assert_eq!(a, b);
        }
    }
}
