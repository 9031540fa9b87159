//! OFF (Geomview Object File Format) reader, ASCII only.
//!
//! Accepted: a first keyword `OFF` with optional `C`, `N`, `ST` prefixes
//! (`COFF`, `NOFF`, `STCNOFF`, ...; extra per-vertex data after x y z is
//! ignored), `#` comments anywhere, blank lines, and the counts
//! `vertices faces [edges]` either on the keyword's line or on the next
//! record. Then one record (line) per vertex and one per face:
//! `n i₁ … iₙ [r g b [a]]`, colours as integers 0–255 or as floats 0–1.
//! Faces are numbered in file order. `OFF BINARY`, `4OFF` and `nOFF` are
//! rejected.

use super::{capped_capacity, MeshError, RawMesh};
use crate::geom::DEFAULT_COLOR;

const FORMAT: &str = "OFF";

/// One non-empty line with comments removed, and its 1-based number.
struct Record<'a> {
    line: usize,
    words: Vec<&'a str>,
}

/// Parses an OFF file.
pub(crate) fn parse(bytes: &[u8]) -> Result<RawMesh, MeshError> {
    let text = String::from_utf8_lossy(bytes);
    let mut records = text.split('\n').enumerate().filter_map(|(k, l)| {
        let words: Vec<&str> = l
            .split('#')
            .next()
            .unwrap_or("")
            .split_whitespace()
            .collect();
        (!words.is_empty()).then_some(Record { line: k + 1, words })
    });

    let head = records
        .next()
        .ok_or_else(|| MeshError::parse(FORMAT, "the file is empty"))?;
    check_keyword(&head)?;
    let (counts, counts_line) = if head.words.len() > 1 {
        if head.words[1].eq_ignore_ascii_case("BINARY") {
            return Err(MeshError::parse_at(
                FORMAT,
                head.line,
                "binary OFF is not supported",
            ));
        }
        (head.words[1..].to_vec(), head.line)
    } else {
        let r = records
            .next()
            .ok_or_else(|| MeshError::parse(FORMAT, "missing the vertex and face counts"))?;
        (r.words, r.line)
    };
    let count = |k: usize| -> Result<u64, MeshError> {
        let w = counts.get(k).ok_or_else(|| {
            MeshError::parse_at(FORMAT, counts_line, "missing the vertex and face counts")
        })?;
        w.parse::<u64>()
            .map_err(|_| MeshError::parse_at(FORMAT, counts_line, format!("bad count {w:?}")))
    };
    let (nv, nf) = (count(0)?, count(1)?);
    if nv > u64::from(u32::MAX) {
        return Err(MeshError::parse(
            FORMAT,
            format!("too many vertices ({nv})"),
        ));
    }

    // A vertex record takes at least 6 bytes ("0 0 0\n"), a face 2.
    let mut raw = RawMesh {
        vertices: Vec::with_capacity(capped_capacity(nv, bytes.len(), 6)),
        faces: Vec::with_capacity(capped_capacity(nf, bytes.len(), 2)),
        ..RawMesh::default()
    };
    for _ in 0..nv {
        let r = records.next().ok_or_else(|| {
            MeshError::parse(FORMAT, format!("the file ends before its {nv} vertices"))
        })?;
        if r.words.len() < 3 {
            return Err(MeshError::parse_at(
                FORMAT,
                r.line,
                "a vertex needs 3 coordinates",
            ));
        }
        let mut p = [0.0; 3];
        for (c, w) in p.iter_mut().zip(&r.words) {
            *c = w.parse().map_err(|_| {
                MeshError::parse_at(FORMAT, r.line, format!("bad coordinate {w:?}"))
            })?;
        }
        raw.vertices.push(p);
    }
    let mut colors = Vec::with_capacity(raw.faces.capacity());
    let mut any_color = false;
    for _ in 0..nf {
        let r = records.next().ok_or_else(|| {
            MeshError::parse(FORMAT, format!("the file ends before its {nf} faces"))
        })?;
        let bad = |msg: String| MeshError::parse_at(FORMAT, r.line, msg);
        let n: usize = r.words[0]
            .parse()
            .map_err(|_| bad(format!("bad vertex count {:?}", r.words[0])))?;
        let rest = &r.words[1..];
        if rest.len() < n {
            return Err(bad(format!("the face lists fewer than its {n} vertices")));
        }
        let face = rest[..n]
            .iter()
            .map(|w| {
                w.parse::<u32>()
                    .map_err(|_| bad(format!("bad vertex index {w:?}")))
            })
            .collect::<Result<Vec<u32>, _>>()?;
        let color = parse_color(&rest[n..]);
        any_color |= color.is_some();
        colors.push(color.unwrap_or(DEFAULT_COLOR));
        raw.faces.push(face);
    }
    raw.colors = any_color.then_some(colors);
    Ok(raw)
}

/// Checks the first keyword: `[ST][C][N]OFF`.
fn check_keyword(head: &Record) -> Result<(), MeshError> {
    let k = head.words[0];
    let ok = k
        .strip_suffix("OFF")
        .map(|prefix| {
            let p = prefix.strip_prefix("ST").unwrap_or(prefix);
            let p = p.strip_prefix('C').unwrap_or(p);
            let p = p.strip_prefix('N').unwrap_or(p);
            p.is_empty()
        })
        .unwrap_or(false);
    if ok {
        Ok(())
    } else {
        Err(MeshError::parse_at(
            FORMAT,
            head.line,
            format!("expected the keyword OFF, found {k:?}"),
        ))
    }
}

/// A face colour from the words after the indices: `r g b [a]` as integers
/// 0–255 or floats 0–1. Anything else (nothing, a colour-map index) is no
/// colour.
fn parse_color(words: &[&str]) -> Option<[u8; 3]> {
    if words.len() != 3 && words.len() != 4 {
        return None;
    }
    let rgb = &words[..3];
    if let Ok(v) = rgb
        .iter()
        .map(|w| w.parse::<u8>())
        .collect::<Result<Vec<_>, _>>()
    {
        return Some([v[0], v[1], v[2]]);
    }
    let v = rgb
        .iter()
        .map(|w| w.parse::<f64>())
        .collect::<Result<Vec<_>, _>>()
        .ok()?;
    if v.iter().all(|x| (0.0..=1.0).contains(x)) {
        let c = |x: f64| (x * 255.0).round() as u8;
        Some([c(v[0]), c(v[1]), c(v[2])])
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{load_bytes, MeshFormat};

    const TETRA: &str = "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n\
                         3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

    #[test]
    fn tetrahedron_is_closed() {
        let m = load_bytes(MeshFormat::Off, TETRA.as_bytes()).unwrap();
        assert_eq!(m.report.faces_read, 4);
        assert!(m.closed);
        assert!(m.polygons.iter().all(|p| p.color == DEFAULT_COLOR));
    }

    #[test]
    fn counts_on_the_keyword_line_and_comments() {
        let text = "# a comment\nOFF 4 4 0 # counts here\n\n0 0 0\n1 0 0 # x\n0 1 0\n\
                    # between\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(raw.vertices.len(), 4);
        assert_eq!(raw.faces[3], vec![0, 3, 2]);
        assert!(load_bytes(MeshFormat::Off, text.as_bytes()).unwrap().closed);
    }

    #[test]
    fn crlf_and_missing_edge_count() {
        let text = TETRA.replace("4 4 6", "4 4").replace('\n', "\r\n");
        assert_eq!(parse(text.as_bytes()).unwrap().faces.len(), 4);
    }

    #[test]
    fn prefixed_keywords_and_face_colours() {
        let text = "COFF\n3 2 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n\
                    3 0 1 2 255 0 0\n3 0 2 1 0.0 1.0 0.0 1.0\n";
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(raw.colors, Some(vec![[255, 0, 0], [0, 255, 0]]));
        let m = load_bytes(MeshFormat::Off, text.as_bytes()).unwrap();
        assert_eq!(m.polygons[1].color, [0, 255, 0]);
        assert!(parse(TETRA.replace("OFF", "NOFF").as_bytes()).is_ok());
        assert!(parse(TETRA.replace("OFF", "STCNOFF").as_bytes()).is_ok());
    }

    #[test]
    fn errors() {
        let cases: [(&str, Option<usize>); 8] = [
            ("", None),
            ("PLY\n", Some(1)),
            ("4OFF\n", Some(1)),
            ("OFF BINARY\n", Some(1)),
            ("OFF\n3 x 0\n", Some(2)),
            ("OFF\n2 0 0\n0 0 0\n", None),
            ("OFF 1 1 0\n0 0\n", Some(2)),
            ("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", Some(5)),
        ];
        for (text, line) in cases {
            match parse(text.as_bytes()) {
                Err(MeshError::Parse {
                    format: "OFF",
                    line: l,
                    ..
                }) => assert_eq!(l, line, "{text:?}"),
                other => panic!("{text:?}: {other:?}"),
            }
        }
        assert!(matches!(
            load_bytes(
                MeshFormat::Off,
                b"OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"
            ),
            Err(MeshError::BadIndex {
                face: 0,
                index: 7,
                ..
            })
        ));
    }

    #[test]
    fn lying_counts_do_not_allocate() {
        // Would need terabytes if the counts were trusted.
        let e = parse(b"OFF 4000000000 9999999999999 0\n0 0 0\n").unwrap_err();
        assert!(e.to_string().contains("ends before"), "{e}");
    }
}
