//! Property tests: no input makes the importer panic, and whatever it accepts
//! satisfies the output contract (finite, planar polygons with valid source
//! ids).

use super::{load_bytes, MeshFormat, Model};
use proptest::prelude::*;

/// Checks the output contract on an accepted model.
fn check_model(m: &Model) {
    assert!(!m.polygons.is_empty());
    let (lo, hi) = crate::geom::bounds(&m.polygons);
    let diag = (hi - lo).length();
    for p in &m.polygons {
        assert!(p.verts.len() >= 3);
        assert!((p.source as usize) < m.report.faces_read);
        assert!(p.plane.normal.is_finite() && (p.plane.normal.length() - 1.0).abs() < 1e-9);
        for v in &p.verts {
            assert!(v.is_finite());
            // Within the planarity tolerance (relative to the diagonal of
            // the used vertices, at least this one).
            let tol = super::prepare::PLANAR_REL * diag.max(1e-300);
            assert!(p.plane.distance(*v).abs() <= tol * (1.0 + 1e-9));
        }
    }
    assert!(m.report.dropped_degenerate <= m.report.faces_read);
    // The part counts agree with the closedness and with each other; an
    // inverted part is always a closed one.
    let r = &m.report;
    assert!(r.closed_parts + r.open_parts >= 1);
    assert!(r.inverted_parts <= r.closed_parts);
    if m.closed {
        assert_eq!((r.open_parts, r.boundary_edges), (0, 0), "{r:?}");
    } else {
        assert!(r.boundary_edges > 0 && r.open_parts > 0, "{r:?}");
    }
}

fn run(format: MeshFormat, bytes: &[u8]) {
    if let Ok(m) = load_bytes(format, bytes) {
        check_model(&m);
    }
}

/// Valid samples of every format, the seeds of the mutation tests.
fn samples() -> Vec<(MeshFormat, Vec<u8>)> {
    let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0.3\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n\
               g a\nf 1//1 2//1 3//1 4//1\nf -1 1 2 \\\n 3\nf 1/1 5/1 4/1\n";
    vec![
        (MeshFormat::Obj, obj.as_bytes().to_vec()),
        (
            MeshFormat::Off,
            b"OFF 4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3 255 0 0\n3 1 2 3\n4 0 3 2 1\n"
                .to_vec(),
        ),
        (
            MeshFormat::Stl,
            super::stl::tests::binary(b"solid x", &super::stl::tests::TETRA),
        ),
        (
            MeshFormat::Stl,
            super::stl::tests::ascii("solid t", &super::stl::tests::TETRA).into_bytes(),
        ),
        (MeshFormat::Ply, super::ply::tests::ascii_tetra().into_bytes()),
        (MeshFormat::Ply, super::ply::tests::binary_tetra(false)),
        (MeshFormat::Ply, super::ply::tests::binary_tetra(true)),
        // Two tetrahedra, the second wound inward (flipped on import), and
        // a square sheet: closed, inverted and open parts in one file.
        (
            MeshFormat::Off,
            b"OFF 12 9 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 0\n4 0 0\n3 1 0\n3 0 1\n\
              6 0 0\n7 0 0\n7 1 0\n6 1 0\n\
              3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n\
              3 4 5 6\n3 4 7 5\n3 5 7 6\n3 4 6 7\n4 8 9 10 11\n"
                .to_vec(),
        ),
    ]
}

#[test]
fn samples_are_valid() {
    for (format, bytes) in samples() {
        let m = load_bytes(format, &bytes).unwrap_or_else(|e| panic!("{format:?}: {e}"));
        check_model(&m);
    }
}

/// One edit of a byte string.
#[derive(Clone, Debug)]
enum Edit {
    Set(usize, u8),
    Insert(usize, Vec<u8>),
    Remove(usize, usize),
    Truncate(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    // Bytes that matter to the parsers are more likely than others.
    let byte = prop_oneof![
        any::<u8>(),
        prop::sample::select(b"0123456789-+.e /\\#\n\r\tvfOFsolidplyendx".to_vec()),
    ];
    // Truncation spoils most files, so it is the rarest edit.
    prop_oneof![
        4 => (any::<usize>(), byte.clone()).prop_map(|(i, b)| Edit::Set(i, b)),
        3 => (any::<usize>(), prop::collection::vec(byte, 1..12)).prop_map(|(i, b)| Edit::Insert(i, b)),
        2 => (any::<usize>(), 1..20usize).prop_map(|(i, n)| Edit::Remove(i, n)),
        1 => any::<usize>().prop_map(Edit::Truncate),
    ]
}

fn apply(bytes: &mut Vec<u8>, e: &Edit) {
    let len = bytes.len().max(1);
    match e {
        Edit::Set(i, b) => {
            if !bytes.is_empty() {
                bytes[i % len] = *b;
            }
        }
        Edit::Insert(i, b) => {
            let at = i % (bytes.len() + 1);
            bytes.splice(at..at, b.iter().copied());
        }
        Edit::Remove(i, n) => {
            let at = i % len;
            let end = (at + n).min(bytes.len());
            if at < end {
                bytes.drain(at..end);
            }
        }
        Edit::Truncate(i) => bytes.truncate(i % len),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(
        format in prop::sample::select(MeshFormat::ALL.to_vec()),
        bytes in prop::collection::vec(any::<u8>(), 0..600),
    ) {
        run(format, &bytes);
    }

    #[test]
    fn mutated_valid_files_never_panic(
        sample in 0..8usize,
        edits in prop::collection::vec(edit(), 1..4),
    ) {
        let (format, mut bytes) = samples().swap_remove(sample);
        for e in &edits {
            apply(&mut bytes, e);
        }
        run(format, &bytes);
    }

    #[test]
    fn random_obj_like_text_never_panics(
        words in prop::collection::vec(
            prop::sample::select(vec![
                "v", "f", "1", "2", "3", "-1", "-4", "0", "0.5", "1e308", "-1e308", "nan",
                "inf", "1/2", "1//3", "2/", "/", "\\", "\n", "\r\n", "#", "g", "o", " ",
            ]),
            0..80,
        ),
    ) {
        run(MeshFormat::Obj, words.join(" ").as_bytes());
    }

    #[test]
    fn random_off_faces_never_panic(
        coords in prop::collection::vec(-3i8..3, 15),
        faces in prop::collection::vec(prop::collection::vec(0u8..6, 0..8), 1..6),
    ) {
        // Faces of any shape (repeated, collinear, warped) over five vertices
        // on a coarse grid, plus one index out of range now and then.
        let mut s = format!("OFF\n5 {} 0\n", faces.len());
        for c in coords.chunks(3) {
            s.push_str(&format!("{} {} {}\n", c[0], c[1], c[2]));
        }
        for f in &faces {
            s.push_str(&f.len().to_string());
            for i in f {
                s.push_str(&format!(" {i}"));
            }
            s.push('\n');
        }
        run(MeshFormat::Off, s.as_bytes());
    }
}
