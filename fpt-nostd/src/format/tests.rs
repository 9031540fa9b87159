//! Tests of the layout constants and field readers.

use super::*;

#[test]
fn crc32_is_the_zlib_one() {
    // The standard check value of CRC-32/ISO-HDLC.
    assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    assert_eq!(crc32(b""), 0);
}

#[test]
fn vertex_format_names_round_trip() {
    for f in VertexFormat::ALL {
        assert_eq!(VertexFormat::from_name(f.name()), Some(f));
        assert_eq!(VertexFormat::from_code(f.code()), Some(f));
    }
    assert_eq!(VertexFormat::from_name("f64"), None);
    assert_eq!(VertexFormat::from_code(3), None);
}

#[test]
fn sections_are_padded_and_ordered() {
    let c = Counts {
        vertices: 3,
        polygons: 1,
        indices: 3,
        bunches: 1,
        nodes: 1,
        switches: 0,
        runs: 1,
        edges: 0,
        normals: 0,
        small: false,
    };
    let s = Sections::new(&c, VertexFormat::Q16, 2).unwrap();
    assert_eq!(s.vertices, HEADER_LEN);
    assert_eq!(s.polygons, HEADER_LEN + 20); // 18 bytes padded to 20
    assert_eq!(s.indices, s.polygons + POLYGON_LEN);
    assert_eq!(s.runs, s.indices + 8); // 6 bytes padded to 8
    assert_eq!(s.edges, s.runs);
    let with_edges = Sections::new(&Counts { edges: 3, ..c }, VertexFormat::Q16, 2).unwrap();
    assert_eq!(with_edges.edges, s.edges);
    assert_eq!(with_edges.runs, s.runs + 3 * EDGE_LEN);
    assert_eq!(with_edges.file_len, s.file_len + 3 * EDGE_LEN);
    let both = Counts {
        edges: 3,
        normals: 3,
        ..c
    };
    let both = Sections::new(&both, VertexFormat::Q16, 2).unwrap();
    assert_eq!(both.normals, with_edges.runs);
    assert_eq!(both.runs, both.normals + 12); // 9 bytes padded to 12
    assert_eq!(s.bunches, s.runs + RUN_LEN);
    assert_eq!(s.nodes, s.bunches + 8);
    assert_eq!(s.switches, s.nodes + NODE_LEN);
    // Small walk records: two u16 offsets, an 8-byte node.
    let small = Sections::new(&Counts { small: true, ..c }, VertexFormat::Q16, 2).unwrap();
    assert_eq!(small.nodes, small.bunches + 4);
    assert_eq!(small.switches, small.nodes + SMALL_NODE_LEN);
    assert_eq!(s.crc, s.switches);
    assert_eq!(s.file_len, s.crc + CRC_LEN);
    let huge = Counts {
        vertices: u32::MAX,
        ..c
    };
    assert_eq!(Sections::new(&huge, VertexFormat::F32, 4), None);
    let max_bunches = Counts {
        bunches: u32::MAX,
        ..c
    };
    assert_eq!(Sections::new(&max_bunches, VertexFormat::F32, 4), None);
    // Compact: layout and colours after the header, 8-byte polygons.
    let k = Sections::with_compact(&c, VertexFormat::Q16, 2, Some(2)).unwrap();
    assert_eq!((k.layout, k.colours), (HEADER_LEN, HEADER_LEN + LAYOUT_LEN));
    assert_eq!(k.vertices, k.colours + 8); // 6 bytes padded to 8
    assert_eq!(k.indices, k.polygons + COMPACT_POLYGON_LEN);
    assert_eq!(k.file_len, s.file_len + LAYOUT_LEN + 8 - 8);
    assert_eq!((s.layout, s.colours), (HEADER_LEN, HEADER_LEN));
}

#[test]
fn readers_do_not_panic_out_of_range() {
    let b = [1u8, 2, 3, 4, 5];
    assert_eq!(rd_u32(&b, 0), 0x0403_0201);
    assert_eq!(rd_u32(&b, 2), 0);
    assert_eq!(rd_u32(&b, usize::MAX), 0);
    assert_eq!(rd_u8(&b, 9), 0);
    assert_eq!(rd_i16(&b, 3), 0x0504);
    let s = [1u8, 0, 0, 0, 2, 0, 0, 0, 3];
    assert_eq!(le_u32(&rec::<4>(&s, 1), 0), 2);
    assert_eq!(rec::<4>(&s, 2), [0; 4]); // only one byte left
    assert_eq!(rec::<4>(&s, usize::MAX), [0; 4]);
    assert_eq!(le_u32(&[7u8; 4], 1), 0); // field past the record
    assert_eq!(le_f32(&1.5f32.to_le_bytes(), 0), 1.5);
}

#[test]
fn narrow_sections_follow_the_colours_and_share_planes() {
    let c = Counts {
        vertices: 3,
        polygons: 3,
        indices: 9,
        bunches: 1,
        nodes: 3,
        switches: 1,
        runs: 2,
        edges: 0,
        normals: 0,
        small: false,
    };
    let compact = Sections::with_compact(&c, VertexFormat::Q16, 2, Some(2)).unwrap();
    let records = Records {
        colours: 2,
        narrow: Some(Narrow {
            record_len: 5,
            extra_planes: 1,
            table: false,
            compact_planes: false,
        }),
    };
    let n = Sections::with_records(&c, VertexFormat::Q16, 2, Some(&records)).unwrap();
    // The colour table stays where it was; the narrow layout follows it.
    assert_eq!(n.colours, compact.colours);
    assert_eq!(n.narrow, compact.vertices);
    assert_eq!(n.vertices, n.narrow + NARROW_LEN);
    assert_eq!(compact.narrow, compact.vertices);
    // Three 5-byte records, padded to 16; the runs and one extra plane;
    // one 4-byte switch record.
    assert_eq!(n.indices, n.polygons + 16);
    assert_eq!(n.bunches, n.runs + 3 * RUN_LEN);
    assert_eq!(n.crc, n.switches + SWITCH_REF_LEN);
    assert_eq!(compact.crc, compact.switches + SWITCH_LEN);
    // A plane table of two planes before the runs, two 4-byte runs.
    let table = Records {
        colours: 2,
        narrow: Some(Narrow {
            record_len: 5,
            extra_planes: 2,
            table: true,
            compact_planes: false,
        }),
    };
    let t = Sections::with_records(&c, VertexFormat::Q16, 2, Some(&table)).unwrap();
    assert_eq!(t.planes, n.runs);
    assert_eq!(t.runs, t.planes + 2 * PLANE_LEN);
    assert_eq!(t.bunches, t.runs + 2 * TABLE_RUN_LEN);
    assert_eq!(t.crc, t.switches + SWITCH_REF_LEN);
    assert_eq!(n.planes, n.runs);
}

#[test]
fn compact_planes_decode_and_validate() {
    use super::{compact_plane, compact_plane_ok, compact_side, plane_unit, COMPACT_PLANE_LEN};
    let entry = |v: [i16; 4]| {
        let mut r = [0u8; COMPACT_PLANE_LEN];
        for (c, x) in r.chunks_exact_mut(2).zip(v) {
            c.copy_from_slice(&x.to_le_bytes());
        }
        r
    };
    let unit = plane_unit([2.0, 1.0, 0.5]);
    assert_eq!(unit, 2.0 * 1.732_050_8);
    // m = (0, 0, 32767), e = −3: the plane z = 3 · unit / 32767.
    let r = entry([0, 0, 32767, -3]);
    assert!(compact_plane_ok(&r));
    assert_eq!(compact_side(&r), [0.0, 0.0, 32767.0, -3.0]);
    let (n, d) = compact_plane(&r, unit);
    assert_eq!(n, [0.0, 0.0, 1.0]);
    assert!((d - -3.0 * unit / 32767.0).abs() < 1e-9);
    // A diagonal normal, rounded: unit length within 3·10⁻⁵.
    let c = 18918; // 32767 / √3
    let r = entry([c, -c, c, 0]);
    assert!(compact_plane_ok(&r));
    let (n, _) = compact_plane(&r, unit);
    let len: f32 = n.iter().map(|c| c * c).sum();
    assert!((len - 1.0).abs() < 6e-5 && n[1] < 0.0);
    // Ill-formed: zero, too short or too long a normal, a component −32768.
    assert!(!compact_plane_ok(&entry([0, 0, 0, 0])));
    assert!(!compact_plane_ok(&entry([16383, 0, 0, 0])));
    assert!(!compact_plane_ok(&entry([32767, 300, 0, 0])));
    assert!(!compact_plane_ok(&entry([c - 2, -c, c, 0])));
    assert!(!compact_plane_ok(&entry([-32768, 0, 0, 0])));
    assert!(!compact_plane_ok(&entry([32767, 0, 0, i16::MIN])));
    assert!(compact_plane_ok(&entry([-32767, 5, -7, 32767])));
    // Zeros (past the end of a table) decode to zeros.
    assert_eq!(compact_plane(&[0u8; 8], unit), ([0.0; 3], 0.0));
}

#[test]
fn compact_plane_table_is_half_as_long() {
    let c = Counts {
        vertices: 4,
        polygons: 3,
        indices: 9,
        bunches: 2,
        nodes: 3,
        switches: 1,
        runs: 2,
        edges: 0,
        normals: 0,
        small: false,
    };
    let table = |compact_planes| Records {
        colours: 2,
        narrow: Some(Narrow {
            record_len: 5,
            extra_planes: 3,
            table: true,
            compact_planes,
        }),
    };
    let t = Sections::with_records(&c, VertexFormat::Q16, 2, Some(&table(false))).unwrap();
    let s = Sections::with_records(&c, VertexFormat::Q16, 2, Some(&table(true))).unwrap();
    assert_eq!(t.runs, t.planes + 3 * PLANE_LEN);
    // 3 · 8 = 24 bytes, a multiple of 4.
    assert_eq!(s.runs, s.planes + 3 * super::COMPACT_PLANE_LEN);
    assert_eq!(t.file_len - s.file_len, 24);
}

/// The integer conversion of an `i16` to `f32` (what the facing test of
/// a compact entry uses without an FPU) gives the bits of `f32::from` for
/// every `i16`.
#[test]
fn i16_to_f32_in_integers_is_exact() {
    for c in i16::MIN..=i16::MAX {
        let want = f32::from(c).to_bits();
        assert_eq!(super::planes::f32_of_i16_bits(c).to_bits(), want, "{c}");
    }
}
