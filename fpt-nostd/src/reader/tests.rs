extern crate std;

use std::vec::Vec;

use super::*;
use crate::format::{header as hd, NO_SWITCH};
use crate::test_util::{add_square, fix_crc, two_floors, Raw};

fn one_square() -> Raw {
    let mut r = Raw::empty();
    add_square(&mut r, 0.0, true, 7);
    r.bunches = std::vec![0, 1, 1];
    r.nodes = std::vec![[0, 1, NO_SWITCH]];
    r
}

#[test]
fn reads_a_minimal_file() {
    let mut r = one_square();
    r.flags = FLAG_CLOSED;
    r.effects = Some(0x55);
    r.origin = [1e5, 2.0, -3.0];
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert!(t.is_closed());
    assert_eq!(t.effects(), 0x55);
    assert_eq!(t.origin(), [1e5, 2.0, -3.0]);
    assert_eq!(
        (t.polygon_count(), t.vertex_count(), t.index_count()),
        (1, 4, 4)
    );
    assert_eq!(
        (t.bunch_count(), t.level_count(), t.node_count()),
        (2, 1, 1)
    );
    assert_eq!((t.switch_count(), t.max_depth()), (0, 1));
    assert_eq!(t.vertex_format(), VertexFormat::F32);
    assert_eq!(t.crc(), crc32(&bytes[..bytes.len() - 4]));
    let p = t.polygon(0).unwrap();
    assert_eq!((p.id(), p.source(), p.color()), (0, 7, [1, 2, 3]));
    assert_eq!(p.vertex_count(), 4);
    assert_eq!(
        p.plane(),
        Plane {
            normal: [0.0, 0.0, 1.0],
            d: -0.0
        }
    );
    let vs: Vec<[f32; 3]> = p.vertices().collect();
    assert_eq!(
        vs,
        std::vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0]
        ]
    );
    assert_eq!(p.vertex_model(2), [1e5 + 1.0, 3.0, -3.0]);
    assert_eq!(p.vertex_raw(1), RawVertex::F32([1.0, 0.0, 0.0]));
    // Out of range: no panic, documented fallbacks.
    assert_eq!(p.vertex(4), [0.0; 3]);
    assert!(t.polygon(1).is_none());
    assert!(t.vertex(4).is_none());
}

#[test]
fn reads_at_any_alignment() {
    let bytes = two_floors().bytes();
    for shift in 0..8 {
        let mut buf = std::vec![0xEEu8; shift];
        buf.extend_from_slice(&bytes);
        let t = Tree::from_bytes(&buf[shift..]).unwrap();
        assert_eq!(t.polygon(1).unwrap().vertex(2), [1.0, 1.0, 0.0]);
    }
}

#[test]
fn decodes_q16_and_q32() {
    let mut r = one_square();
    r.format = VertexFormat::Q16;
    r.half_extent = [2.0, 4.0, 8.0];
    r.vertex_bytes.clear();
    for q in [[32767i16, -32767, 0], [16384, 0, 1], [0, 0, 0], [-1, 2, -3]] {
        q.iter()
            .for_each(|x| r.vertex_bytes.extend_from_slice(&x.to_le_bytes()));
    }
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    let p = t.polygon(0).unwrap();
    assert_eq!(p.vertex_raw(0), RawVertex::Q16([32767, -32767, 0]));
    let v = p.vertex(0);
    assert!((v[0] - 2.0).abs() < 1e-6 && (v[1] + 4.0).abs() < 1e-6 && v[2] == 0.0);
    let m = p.vertex_model(1);
    assert!((m[0] - 2.0 * 16384.0 / 32767.0).abs() < 1e-12);

    let mut r = one_square();
    r.format = VertexFormat::Q32;
    r.shift = 20;
    r.origin = [1e6, 0.0, 0.0];
    r.vertex_bytes.clear();
    for q in [
        [1i32 << 20, -(1 << 21), 3],
        [0, 0, 0],
        [5, 6, 7],
        [i32::MAX, i32::MIN, 0],
    ] {
        q.iter()
            .for_each(|x| r.vertex_bytes.extend_from_slice(&x.to_le_bytes()));
    }
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    let p = t.polygon(0).unwrap();
    assert_eq!(p.vertex(0), [1.0, -2.0, 3.0 / (1 << 20) as f32]);
    assert_eq!(
        p.vertex_model(0),
        [1e6 + 1.0, -2.0, 3.0 / f64::from(1 << 20)]
    );
    assert_eq!(t.q32_shift(), 20);
    // The largest shift keeps 2^-shift a normal f32.
    r.shift = MAX_SHIFT;
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    let p = t.polygon(0).unwrap();
    assert!(p.vertex(2)[0] > 0.0 && p.vertex(2)[0].is_normal());
}

/// Builds `r`, applies `edit` to the bytes, fixes the checksum and parses.
fn parse_edited(r: &Raw, edit: impl FnOnce(&mut Vec<u8>)) -> Result<(), FormatError> {
    let mut b = r.bytes();
    edit(&mut b);
    fix_crc(&mut b);
    Tree::from_bytes(&b).map(|_| ())
}

fn put_u32(b: &mut [u8], off: usize, x: u32) {
    b[off..off + 4].copy_from_slice(&x.to_le_bytes());
}

#[test]
fn rejects_bad_headers() {
    let r = one_square();
    let ok = r.bytes();
    assert_eq!(
        Tree::from_bytes(&ok[..50]).unwrap_err(),
        FormatError::TooShort
    );
    assert_eq!(
        parse_edited(&r, |b| b[0] = b'X'),
        Err(FormatError::BadMagic)
    );
    assert_eq!(
        parse_edited(&r, |b| b[hd::VERSION] = 1),
        Err(FormatError::UnsupportedVersion(1))
    );
    assert_eq!(
        parse_edited(&r, |b| b.extend_from_slice(&[0; 4])),
        Err(FormatError::LengthMismatch)
    );
    let mut bad = ok.clone();
    bad[hd::RADIUS] ^= 1;
    assert_eq!(Tree::from_bytes(&bad).unwrap_err(), FormatError::Checksum);
    assert_eq!(
        parse_edited(&r, |b| b[hd::FLAGS] = 16),
        Err(FormatError::BadHeader("flags"))
    );
    // Without the `large-trees` feature, only small walk records.
    if !cfg!(feature = "large-trees") {
        assert_eq!(
            parse_edited(&r, |b| b[hd::FLAGS] = 0),
            Err(FormatError::BadHeader("flags"))
        );
    }
    // The compact flag on a file without its layout: the section sizes no
    // longer add up, or the layout read from the vertices is invalid, or
    // (here, one polygon: 8 bytes of layout for 8 of record) its colour
    // table is empty.
    let e = parse_edited(&r, |b| {
        b[hd::FLAGS] = (crate::format::FLAG_COMPACT | crate::format::FLAG_SMALL) as u8
    });
    assert!(
        matches!(
            e,
            Err(FormatError::SectionSizes
                | FormatError::BadHeader("layout")
                | FormatError::BadColour(_))
        ),
        "{e:?}"
    );
    assert_eq!(
        parse_edited(&r, |b| b[hd::VERTEX_FORMAT] = 3),
        Err(FormatError::BadHeader("vertex_format"))
    );
    assert_eq!(
        parse_edited(&r, |b| b[hd::SHIFT] = 1),
        Err(FormatError::BadHeader("shift"))
    );
    assert_eq!(
        parse_edited(&r, |b| b[hd::INDEX_SIZE] = 3),
        Err(FormatError::BadHeader("index_size"))
    );
    assert_eq!(
        parse_edited(&r, |b| put_u32(b, hd::POLYGON_COUNT, 2)),
        Err(FormatError::SectionSizes)
    );
    assert_eq!(
        parse_edited(&r, |b| put_u32(b, hd::VERTEX_COUNT, u32::MAX)),
        Err(FormatError::SectionSizes)
    );
    assert_eq!(
        parse_edited(&r, |b| b[hd::RADIUS..hd::RADIUS + 4]
            .copy_from_slice(&f32::NAN.to_le_bytes())),
        Err(FormatError::NonFinite("header"))
    );
    assert_eq!(
        parse_edited(&r, |b| put_u32(b, hd::MAX_DEPTH, 2)),
        Err(FormatError::DepthMismatch)
    );
}

#[test]
fn rejects_bad_geometry() {
    let mut r = one_square();
    r.indices[2] = 4;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::IndexOutOfRange
    );

    let mut r = one_square();
    r.vertex_bytes[0..4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::NonFinite("vertices")
    );

    let mut r = one_square();
    r.runs[0].0[3] = f32::NAN;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::NonFinite("run planes")
    );

    // Two polygons whose ranges do not tile: the second starts too early.
    let mut r = one_square();
    r.add_polygon([0.0, 0.0, 1.0, 0.0], &[0, 1, 2], 1);
    r.bunches = std::vec![0, 2, 2];
    assert!(Tree::from_bytes(&r.bytes()).is_ok());
    r.polys[1].0 = 2;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::BadPolygon(0)
    );
    // A last polygon with 2 vertices.
    let mut r = one_square();
    r.indices.truncate(2);
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::BadPolygon(0)
    );
}

#[test]
fn runs_share_a_plane_and_tile_the_polygons() {
    // Two coplanar squares in one run, one bunch.
    let mut r = one_square();
    add_square(&mut r, 0.0, true, 8);
    r.bunches = std::vec![0, 2, 2];
    r.merge_runs(0);
    assert_eq!((r.runs.len(), r.bunches.clone()), (1, std::vec![0, 1, 1]));
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert_eq!((t.run_count(), t.polygon_count()), (1, 2));
    assert_eq!(t.polygon(1).unwrap().plane(), t.polygon(0).unwrap().plane());

    // A polygon naming the wrong run.
    let mut bad = r.clone();
    bad.runs = std::vec![(bad.runs[0].0, 1), (bad.runs[0].0, 2)];
    bad.bunches = std::vec![0, 2, 2];
    bad.polys[1].1 = 0;
    assert_eq!(
        Tree::from_bytes(&bad.bytes()).unwrap_err(),
        FormatError::BadRuns
    );
    bad.polys[1].1 = 1;
    assert!(Tree::from_bytes(&bad.bytes()).is_ok());
    // An empty run, a run past the polygons, runs that stop short.
    for ends in [[0, 2], [1, 3], [1, 1]] {
        let mut e = bad.clone();
        e.runs[0].1 = ends[0];
        e.runs[1].1 = ends[1];
        assert_eq!(
            Tree::from_bytes(&e.bytes()).unwrap_err(),
            FormatError::BadRuns,
            "{ends:?}"
        );
    }
    // Runs without polygons.
    let mut e = Raw::empty();
    e.runs.push(([0.0, 0.0, 1.0, 0.0], 0));
    e.bunches = std::vec![0];
    assert_eq!(
        Tree::from_bytes(&e.bytes()).unwrap_err(),
        FormatError::BadRuns
    );
    // Bunch offsets must end at the run count, not the polygon count.
    let mut e = r;
    e.bunches = std::vec![0, 2, 2];
    assert_eq!(
        Tree::from_bytes(&e.bytes()).unwrap_err(),
        FormatError::BadBunches
    );
}

#[test]
fn rejects_bad_bunches_and_nodes() {
    let mut r = one_square();
    r.bunches = std::vec![0, 1, 0];
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::BadBunches
    );
    r.bunches = std::vec![1, 1, 1];
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::BadBunches
    );
    // Two levels claimed, one level of bunches present.
    let mut r = one_square();
    r.nodes[0][1] = 2;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::BadNode(0)
    );

    let ok = two_floors();
    assert!(Tree::from_bytes(&ok.bytes()).is_ok());
    // Node 2 does not start where node 1 ends.
    let mut r = ok.clone();
    r.nodes[2][0] = 2;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::BadNode(2)
    );
    // Switch numbered out of order.
    let mut r = ok.clone();
    r.nodes[0][2] = 1;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::BadNode(0)
    );
    // The switch moved to node 1: it would be its own child (1 = 2·0 + 1).
    let mut r = ok.clone();
    r.nodes = std::vec![[0, 0, NO_SWITCH], [0, 1, 0], [3, 1, NO_SWITCH]];
    r.bunches = std::vec![0, 0, 1, 1, 2, 2];
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::NotATree
    );
    // Node count not 2 · switches + 1.
    let mut r = ok.clone();
    r.switches.push([0.0, 0.0, 1.0, 0.0]);
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::NotATree
    );
    // Non-finite switch plane.
    let mut r = ok;
    r.switches[0][0] = f32::NAN;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::NonFinite("switch planes")
    );
}

#[test]
fn depth_is_counted_by_layers() {
    // A chain: root switch 0 → node 2 (back) has switch 1 → nodes 3, 4.
    let mut r = Raw::empty();
    r.nodes = std::vec![
        [0, 0, 0],
        [1, 0, NO_SWITCH],
        [1, 0, 1],
        [2, 0, NO_SWITCH],
        [2, 0, NO_SWITCH],
    ];
    r.switches = std::vec![[1.0, 0.0, 0.0, 0.0]; 2];
    r.bunches = std::vec![0, 0, 0];
    r.max_depth = 3;
    assert!(Tree::from_bytes(&r.bytes()).is_ok());
    r.max_depth = 2;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::DepthMismatch
    );
}

#[test]
fn errors_display_without_alloc() {
    use core::fmt::Write;
    struct Buf([u8; 64], usize);
    impl Write for Buf {
        fn write_str(&mut self, s: &str) -> core::fmt::Result {
            let end = self.1 + s.len();
            self.0
                .get_mut(self.1..end)
                .ok_or(core::fmt::Error)?
                .copy_from_slice(s.as_bytes());
            self.1 = end;
            Ok(())
        }
    }
    let mut b = Buf([0; 64], 0);
    write!(b, "{}", FormatError::BadNode(12)).unwrap();
    assert_eq!(&b.0[..b.1], b"invalid connecting node 12");
}

#[test]
fn reads_u32_indices() {
    let mut r = one_square();
    r.index_size = 4;
    r.indices = std::vec![3, 2, 1, 0];
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert_eq!(t.index_size(), 4);
    let p = t.polygon(0).unwrap();
    assert_eq!((p.vertex_index(0), p.vertex_index(3)), (3, 0));
    assert_eq!(p.vertex(0), [0.0, 1.0, 0.0]);
    r.indices[1] = 70_000;
    assert_eq!(
        Tree::from_bytes(&r.bytes()).unwrap_err(),
        FormatError::IndexOutOfRange
    );
}
