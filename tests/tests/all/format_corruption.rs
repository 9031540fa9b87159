//! Stable-Rust stand-in for the `tree_walk` fuzz target: serialize small
//! trees, corrupt the bytes, and check that `Tree::from_bytes` either fails
//! or gives a tree whose accessors and walks for several views complete
//! without panicking, emitting only valid ids, each at most once per view
//! (exactly once for an open volume).
//!
//! Each corruption is tried with the CRC left as it was (the checksum must
//! catch it) and with the file length field and CRC rewritten afterwards,
//! which is what reaches the structural validation.

use crate::format_common;

use format_common::*;
use fpt_nostd::format::{crc32, header, VertexFormat};
use fpt_nostd::order::View;
use fpt_nostd::reader::Tree;
use glam::DVec3;
use host_sim::serialize::{serialize, SerializeOptions};
use proptest::prelude::*;

#[derive(Clone, Debug)]
enum Corruption {
    /// Keep this fraction of the file.
    Truncate(f64),
    /// Flip these bits (position as a fraction of the file, bit).
    Flip(Vec<(f64, u8)>),
    /// Overwrite bytes from a position.
    Overwrite(f64, Vec<u8>),
    /// Set an aligned little-endian u32 to a value.
    SetWord(f64, u32),
    /// Append bytes.
    Trailing(Vec<u8>),
}

fn corruption() -> impl Strategy<Value = Corruption> {
    let word = prop_oneof![0u32..8, Just(u32::MAX), Just(u32::MAX - 1), any::<u32>()];
    prop_oneof![
        (0.0..1.0f64).prop_map(Corruption::Truncate),
        prop::collection::vec((0.0..1.0f64, 0u8..8), 1..6).prop_map(Corruption::Flip),
        (0.0..1.0f64, prop::collection::vec(any::<u8>(), 1..24))
            .prop_map(|(p, b)| Corruption::Overwrite(p, b)),
        (0.0..1.0f64, word).prop_map(|(p, w)| Corruption::SetWord(p, w)),
        prop::collection::vec(any::<u8>(), 1..16).prop_map(Corruption::Trailing),
    ]
}

fn apply(bytes: &mut Vec<u8>, c: &Corruption) {
    let at = |f: f64, n: usize| ((f * n as f64) as usize).min(n.saturating_sub(1));
    match c {
        Corruption::Truncate(f) => bytes.truncate(at(*f, bytes.len())),
        Corruption::Flip(bits) => {
            for &(p, bit) in bits {
                let i = at(p, bytes.len());
                bytes[i] ^= 1 << bit;
            }
        }
        Corruption::Overwrite(p, b) => {
            let i = at(*p, bytes.len());
            for (k, &x) in b.iter().enumerate() {
                if let Some(slot) = bytes.get_mut(i + k) {
                    *slot = x;
                }
            }
        }
        Corruption::SetWord(p, w) => {
            let i = at(*p, bytes.len()) & !3;
            if i + 4 <= bytes.len() {
                bytes[i..i + 4].copy_from_slice(&w.to_le_bytes());
            }
        }
        Corruption::Trailing(b) => bytes.extend_from_slice(b),
    }
}

/// Makes the length field and the CRC agree with the corrupted bytes.
fn fix_length_and_crc(bytes: &mut [u8]) {
    let n = bytes.len();
    if n >= header::FILE_LEN + 4 {
        bytes[header::FILE_LEN..header::FILE_LEN + 4].copy_from_slice(&(n as u32).to_le_bytes());
    }
    if n >= 4 {
        let crc = crc32(&bytes[..n - 4]);
        bytes[n - 4..].copy_from_slice(&crc.to_le_bytes());
    }
}

const VIEWS: [View; 5] = [
    View::Parallel {
        dir: [0.3, -0.5, 0.8],
    },
    View::Parallel {
        dir: [0.0, 0.0, -1.0],
    },
    View::Parallel {
        dir: [0.0, 0.0, 0.0],
    },
    View::Perspective {
        eye: [10.0, 3.0, -2.0],
    },
    View::PerspectiveRelative {
        eye: [0.1, 0.2, 0.3],
    },
];

fn exercise(bytes: &[u8]) -> bool {
    match Tree::from_bytes(bytes) {
        Err(e) => {
            assert!(!e.to_string().is_empty());
            false
        }
        Ok(tree) => {
            touch_all(&tree);
            for v in VIEWS {
                check_walk(&tree, v);
            }
            true
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, ..ProptestConfig::default() })]

    #[test]
    fn corrupted_files_fail_or_walk_safely(
        seed in 0u64..64,
        n in 1usize..14,
        closed: bool,
        bsp: bool,
        format in 0usize..3,
        records in 0usize..5,
        c in corruption(),
    ) {
        let t = random_tree(seed, n, closed, bsp, 1.0, DVec3::new(0.5, -2.0, 1.0));
        // Wide, compact and narrow records (shared switch planes), and the
        // plane table, of f32 or compact entries.
        let opts = SerializeOptions {
            vertex_format: VertexFormat::ALL[format],
            compact: records > 0,
            narrow: records >= 2,
            plane_table: records >= 3,
            compact_planes: records == 4,
            ..SerializeOptions::default()
        };
        let original = serialize(&t, &opts).unwrap();
        prop_assert!(exercise(&original));

        let mut bytes = original.clone();
        apply(&mut bytes, &c);
        if bytes != original {
            // Left alone, the CRC (or the length) must reject the change.
            prop_assert!(!exercise(&bytes), "corruption {c:?} accepted with the old CRC");
        }
        fix_length_and_crc(&mut bytes);
        // About a quarter pass validation (mostly changed coordinates,
        // planes and colours, or still-consistent counts) and get walked.
        exercise(&bytes);
    }
}

#[test]
fn some_corruptions_pass_validation() {
    // The structural checks are not all-rejecting: flipping a colour or
    // vertex coordinate bit of a valid file, with the CRC fixed, must be
    // accepted (so the property test above does walk corrupted trees).
    let t = random_tree(1, 8, false, false, 1.0, DVec3::ZERO);
    let wide = SerializeOptions {
        compact: false,
        ..SerializeOptions::default()
    };
    let mut bytes = serialize(&t, &wide).unwrap();
    let tree = Tree::from_bytes(&bytes).unwrap();
    // Polygon 0's colour: the polygon section follows the f32 vertices.
    let colour = fpt_nostd::format::HEADER_LEN
        + tree.vertex_count() as usize * 12
        + fpt_nostd::format::polygon::COLOR;
    bytes[colour] ^= 0x10;
    bytes[fpt_nostd::format::HEADER_LEN] ^= 0x01;
    fix_length_and_crc(&mut bytes);
    assert!(exercise(&bytes));
}

/// Where the section `name` of a valid `tree` starts.
fn section_start(tree: &Tree<'_>, name: &str) -> usize {
    let parts = tree.section_bytes();
    let at = parts.iter().position(|&(n, _)| n == name).unwrap();
    parts[..at].iter().map(|&(_, b)| b).sum()
}

/// Where the polygon section of a valid `tree` starts.
fn polygon_section(tree: &Tree<'_>) -> usize {
    section_start(tree, "polygons")
}

#[test]
fn compact_records_are_validated() {
    use fpt_nostd::format::{FormatError, HEADER_LEN};
    let mut out_of_range = 0;
    for seed in 0..16 {
        let mut t = random_tree(seed, 8, seed % 2 == 0, false, 1.0, DVec3::ZERO);
        // Three colours: a 2-bit colour index with room for a bad one.
        for (i, p) in t.polygons.iter_mut().enumerate() {
            p.color = [(i % 3) as u8 * 40, 7, 9];
        }
        let compact = SerializeOptions {
            narrow: false,
            ..SerializeOptions::default()
        };
        let bytes = serialize(&t, &compact).unwrap();
        let tree = Tree::from_bytes(&bytes).unwrap();
        assert!(tree.is_compact() && !tree.has_shared_planes());
        let w: [u8; 4] = bytes[HEADER_LEN..HEADER_LEN + 4].try_into().unwrap();
        let used: u32 = w.iter().map(|&x| u32::from(x)).sum();
        assert!(used < 56, "small trees leave spare bits");
        let polys = polygon_section(&tree);
        // A width above 32, or widths over 56 bits together.
        assert_eq!(
            reject(&bytes, &|b| b[HEADER_LEN] = 33),
            Some(FormatError::BadHeader("layout"))
        );
        assert_eq!(
            reject(&bytes, &|b| b[HEADER_LEN..HEADER_LEN + 4]
                .copy_from_slice(&[32, 24, 1, 0])),
            Some(FormatError::BadHeader("layout"))
        );
        // A set bit between the colour index and the outline mask.
        let last = polygon_section(&tree) + 8 * (tree.polygon_count() as usize - 1);
        let r = u64::from_le_bytes(bytes[last..last + 8].try_into().unwrap());
        let spare = r | 1 << 55;
        assert_eq!(
            reject(&bytes, &|b| b[last..last + 8]
                .copy_from_slice(&spare.to_le_bytes())),
            Some(FormatError::BadColour(tree.polygon_count() - 1))
        );
        // A colour index past the table, where its width leaves room.
        let shift = u32::from(w[0]) + u32::from(w[1]) + u32::from(w[2]);
        let count = tree.colour_count();
        if count < 1 << w[3] {
            let r = u64::from_le_bytes(bytes[polys..polys + 8].try_into().unwrap());
            let mask = ((1u64 << w[3]) - 1) << shift;
            let bad = (r & !mask) | u64::from(count) << shift;
            assert_eq!(
                reject(&bytes, &|b| b[polys..polys + 8]
                    .copy_from_slice(&bad.to_le_bytes())),
                Some(FormatError::BadColour(0))
            );
            out_of_range += 1;
        }
        // A changed colour table entry is a valid file with another colour.
        let table = HEADER_LEN + fpt_nostd::format::LAYOUT_LEN;
        let mut b = bytes.clone();
        b[table] ^= 0x10;
        fix_length_and_crc(&mut b);
        assert!(exercise(&b));
    }
    assert!(out_of_range > 0, "no tree left room for a bad colour index");
}

#[test]
fn narrow_records_and_shared_planes_are_validated() {
    use fpt_nostd::format::{FormatError, FLAG_COMPACT, HEADER_LEN};
    let mut spare_bits = 0;
    for seed in 0..16 {
        // BSP trees: every node a switch, so there are switch records.
        let t = random_tree(seed, 8, seed % 2 == 0, true, 1.0, DVec3::ZERO);
        let narrow = SerializeOptions {
            plane_table: false,
            compact_planes: false,
            ..SerializeOptions::default()
        };
        let bytes = serialize(&t, &narrow).unwrap();
        let tree = Tree::from_bytes(&bytes).unwrap();
        assert!(tree.has_shared_planes() && tree.switch_count() > 0);
        assert!(!tree.has_plane_table());
        let ext = section_start(&tree, "narrow layout");
        let len = tree.record_len();
        assert!((1..=8).contains(&len));
        assert_eq!(usize::from(bytes[ext + 1]), len);
        // The record length must be exactly what the widths need, the
        // hidden_edges width at most 8, the reserved bytes zero.
        let layout = Some(FormatError::BadHeader("layout"));
        assert_eq!(reject(&bytes, &|b| b[ext + 1] += 1), layout);
        assert_eq!(reject(&bytes, &|b| b[ext] = 9), layout);
        assert_eq!(reject(&bytes, &|b| b[ext + 2] = 1), layout);
        // The narrow flag needs the compact one.
        let flags = Some(FormatError::BadHeader("flags"));
        assert_eq!(reject(&bytes, &|b| b[12] &= !(FLAG_COMPACT as u8)), flags);
        // A set bit above the fields, inside the last record.
        let w: u32 = bytes[HEADER_LEN..HEADER_LEN + 4]
            .iter()
            .map(|&x| u32::from(x))
            .sum::<u32>()
            + u32::from(bytes[ext]);
        let last = polygon_section(&tree) + len * (tree.polygon_count() as usize - 1);
        if w < 8 * len as u32 {
            let bit = w as usize;
            let last_poly = tree.polygon_count() - 1;
            assert_eq!(
                reject(&bytes, &|b| b[last + bit / 8] |= 1 << (bit % 8)),
                Some(FormatError::BadColour(last_poly))
            );
            spare_bits += 1;
        }
        // A switch naming a plane record past the runs and extra planes.
        let sw = section_start(&tree, "switches");
        let past = tree.run_count() + tree.extra_plane_count();
        assert_eq!(
            reject(&bytes, &|b| b[sw..sw + 4]
                .copy_from_slice(&past.to_le_bytes())),
            Some(FormatError::BadSwitch(0))
        );
        // Naming another run's plane is a valid file (another order).
        let mut b = bytes.clone();
        b[sw..sw + 4].copy_from_slice(&0u32.to_le_bytes());
        fix_length_and_crc(&mut b);
        assert!(exercise(&b));
        // An extra plane (made here from the last run record) must have an
        // end of 0 and a finite plane.
        let runs = section_start(&tree, "runs");
        let with_extra = |end: u32, nan: bool| {
            let mut b = bytes.clone();
            let at = runs + 20 * tree.run_count() as usize;
            let mut rec = b[at - 20..at].to_vec();
            rec[16..20].copy_from_slice(&end.to_le_bytes());
            if nan {
                rec[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
            }
            let e = tree.extra_plane_count() as usize;
            b.splice(at + 20 * e..at + 20 * e, rec);
            let n = tree.extra_plane_count() + 1;
            b[ext + 4..ext + 8].copy_from_slice(&n.to_le_bytes());
            fix_length_and_crc(&mut b);
            b
        };
        assert!(exercise(&with_extra(0, false)));
        assert_eq!(
            Tree::from_bytes(&with_extra(1, false)).err(),
            Some(FormatError::BadRuns)
        );
        assert_eq!(
            Tree::from_bytes(&with_extra(0, true)).err(),
            Some(FormatError::NonFinite("extra planes"))
        );
    }
    assert!(spare_bits > 0, "no tree left a spare bit in its records");
}

#[test]
fn run_offsets_are_validated() {
    use fpt_nostd::format::{FormatError, FLAG_RUN_OFFSETS, HEADER_LEN};
    let flags = Some(FormatError::BadHeader("flags"));
    let bit = (FLAG_RUN_OFFSETS >> 8) as u8;
    let mut nonzero = 0;
    // Random trees (no two polygons coplanar: every run one polygon) and
    // the vise scene (coplanar faces: runs of several polygons).
    let vise = host_sim::scenes::vise();
    let vise = host_sim::build::build(
        vise.polygons,
        vise.closed,
        host_sim::tree::Method::Static,
        host_sim::build::DEFAULT_SEED,
        &mut host_sim::build::NoProgress,
    );
    let random =
        (0..16).map(|seed| random_tree(seed, 8, seed % 2 == 0, seed % 3 == 0, 1.0, DVec3::ZERO));
    for (seed, t) in random.chain(std::iter::once(vise)).enumerate() {
        // Without the table, no run offsets, and the flag is refused.
        let narrow = SerializeOptions {
            plane_table: false,
            compact_planes: false,
            ..SerializeOptions::default()
        };
        let narrow = serialize(&t, &narrow).unwrap();
        let tree = Tree::from_bytes(&narrow).unwrap();
        assert!(!tree.has_plane_table() && !tree.has_run_offsets());
        assert_eq!(reject(&narrow, &|b| b[13] |= bit), flags);
        let opts = SerializeOptions {
            plane_table: true,
            compact_planes: false,
            ..SerializeOptions::default()
        };
        let bytes = serialize(&t, &opts).unwrap();
        let tree = Tree::from_bytes(&bytes).unwrap();
        assert!(tree.has_plane_table() && tree.has_run_offsets());
        // A table without the flag: a file of sessions 21 to 25.
        assert_eq!(reject(&bytes, &|b| b[13] &= !bit), flags);
        let (w0, w1) = (
            u32::from(bytes[HEADER_LEN]),
            u32::from(bytes[HEADER_LEN + 1]),
        );
        let len = tree.record_len();
        let polys = polygon_section(&tree);
        let field = |b: &[u8], p: usize| {
            let mut r = [0u8; 8];
            r[..len].copy_from_slice(&b[polys + len * p..polys + len * (p + 1)]);
            (u64::from_le_bytes(r) >> w0) as u32 & ((1u32 << w1) - 1)
        };
        // The last polygon's offset is the polygons less the runs.
        let last = tree.polygon_count() as usize - 1;
        let offset = tree.polygon_count() - tree.run_count();
        assert_eq!(field(&bytes, last), offset);
        if w1 == 0 {
            continue;
        }
        nonzero += 1;
        // Another offset names another run (or none): rejected.
        for p in [0, last] {
            let edit = |b: &mut Vec<u8>| {
                let at = polys + len * p;
                let mut r = [0u8; 8];
                r[..len].copy_from_slice(&b[at..at + len]);
                let v = u64::from_le_bytes(r) ^ 1 << w0;
                b[at..at + len].copy_from_slice(&v.to_le_bytes()[..len]);
            };
            assert_eq!(
                reject(&bytes, &edit),
                Some(FormatError::BadRuns),
                "{seed} {p}"
            );
        }
    }
    assert!(nonzero > 0, "no tree had a run of several polygons");
}

/// The error `bytes` edited by `edit` (its length and crc fixed up) load
/// with, if any.
fn reject(bytes: &[u8], edit: &dyn Fn(&mut Vec<u8>)) -> Option<fpt_nostd::format::FormatError> {
    let mut b = bytes.to_vec();
    edit(&mut b);
    fix_length_and_crc(&mut b);
    Tree::from_bytes(&b).err()
}

#[test]
fn plane_tables_are_validated() {
    use fpt_nostd::format::{FormatError, FLAG_NARROW, PLANE_LEN, TABLE_RUN_LEN};
    for seed in 0..16 {
        // BSP trees: every node a switch, so there are switch records.
        let t = random_tree(seed, 8, seed % 2 == 0, true, 1.0, DVec3::ZERO);
        let table = SerializeOptions {
            plane_table: true,
            compact_planes: false,
            ..SerializeOptions::default()
        };
        let bytes = serialize(&t, &table).unwrap();
        let tree = Tree::from_bytes(&bytes).unwrap();
        assert!(tree.has_plane_table() && tree.switch_count() > 0);
        let planes = tree.plane_table_len();
        assert!(planes > 0 && planes <= tree.run_count() + tree.switch_count());
        assert_eq!(tree.extra_plane_count(), 0);
        // The table needs the narrow records.
        let flags = Some(FormatError::BadHeader("flags"));
        assert_eq!(reject(&bytes, &|b| b[12] &= !(FLAG_NARROW as u8)), flags);
        // A run naming a plane past the table.
        let runs = section_start(&tree, "runs");
        let past = u16::try_from(planes).unwrap();
        assert_eq!(
            reject(&bytes, &|b| b[runs + 2..runs + 4]
                .copy_from_slice(&past.to_le_bytes())),
            Some(FormatError::BadRuns)
        );
        // A run end that breaks the tiling.
        let last = runs + TABLE_RUN_LEN * (tree.run_count() as usize - 1);
        assert_eq!(
            reject(&bytes, &|b| b[last..last + 2]
                .copy_from_slice(&0u16.to_le_bytes())),
            Some(FormatError::BadRuns)
        );
        // A switch naming a plane past the table.
        let sw = section_start(&tree, "switches");
        assert_eq!(
            reject(&bytes, &|b| b[sw..sw + 4]
                .copy_from_slice(&planes.to_le_bytes())),
            Some(FormatError::BadSwitch(0))
        );
        // Naming another entry is a valid file (another order).
        let mut b = bytes.clone();
        b[sw..sw + 4].copy_from_slice(&0u32.to_le_bytes());
        fix_length_and_crc(&mut b);
        assert!(exercise(&b));
        // A table entry that is not finite.
        let table = section_start(&tree, "plane table");
        assert_eq!(
            reject(&bytes, &|b| b[table + PLANE_LEN - 4..table + PLANE_LEN]
                .copy_from_slice(&f32::INFINITY.to_le_bytes())),
            Some(FormatError::NonFinite("plane table"))
        );
        // A polygon's run offset naming another run: see
        // `run_offsets_are_validated`.
    }
}

#[test]
fn compact_plane_tables_are_validated() {
    use fpt_nostd::format::{FormatError, COMPACT_PLANE_LEN, FLAG_COMPACT_PLANES, FLAG_PLANES};
    for seed in 0..16 {
        let t = random_tree(seed, 8, seed % 2 == 0, true, 1.0, DVec3::ZERO);
        let opts = SerializeOptions {
            plane_table: true,
            compact_planes: true,
            ..SerializeOptions::default()
        };
        let bytes = serialize(&t, &opts).unwrap();
        let tree = Tree::from_bytes(&bytes).unwrap();
        assert!(tree.has_plane_table() && tree.has_compact_planes());
        let planes = tree.plane_table_len() as usize;
        let table = section_start(&tree, "plane table");
        assert_eq!(
            section_start(&tree, "runs") - table,
            (planes * COMPACT_PLANE_LEN).next_multiple_of(4)
        );
        // Every entry reads back as a unit plane (within 3·10⁻⁵).
        for id in 0..tree.polygon_count() {
            let n = tree.polygon(id).unwrap().plane().normal;
            let len = n.iter().map(|c| c * c).sum::<f32>().sqrt();
            assert!((len - 1.0).abs() < 6e-5);
        }
        // The compact flag needs the table.
        let flags = Some(FormatError::BadHeader("flags"));
        assert_eq!(reject(&bytes, &|b| b[12] &= !(FLAG_PLANES as u8)), flags);
        // Without the flag, the sizes no longer add up.
        assert_eq!(
            reject(&bytes, &|b| b[12] &= !(FLAG_COMPACT_PLANES as u8)),
            Some(FormatError::SectionSizes)
        );
        // A component of −32768, in the normal or the offset.
        let last = table + (planes - 1) * COMPACT_PLANE_LEN;
        for at in [0, 2, 4, 6] {
            assert_eq!(
                reject(&bytes, &|b| b[last + at..last + at + 2]
                    .copy_from_slice(&i16::MIN.to_le_bytes())),
                Some(FormatError::BadPlane(planes as u32 - 1))
            );
        }
        // A normal whose largest component is not ±32767 (zero, halved).
        assert_eq!(
            reject(&bytes, &|b| b[table..table + 6].fill(0)),
            Some(FormatError::BadPlane(0))
        );
        assert_eq!(
            reject(&bytes, &|b| for k in 0..3 {
                let at = table + 2 * k;
                let c = i16::from_le_bytes([b[at], b[at + 1]]) / 2;
                b[at..at + 2].copy_from_slice(&c.to_le_bytes());
            }),
            Some(FormatError::BadPlane(0))
        );
        // Another well-formed offset is a valid file (another order).
        let mut b = bytes.clone();
        b[table + 6..table + 8].copy_from_slice(&32767i16.to_le_bytes());
        fix_length_and_crc(&mut b);
        assert!(exercise(&b));
        // A half extent whose plane unit is not finite.
        let he = fpt_nostd::format::header::HALF_EXTENT;
        assert_eq!(
            reject(&bytes, &|b| b[he..he + 4]
                .copy_from_slice(&f32::MAX.to_le_bytes())),
            Some(FormatError::BadHeader("half_extent"))
        );
    }
}
