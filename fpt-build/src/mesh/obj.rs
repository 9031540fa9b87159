//! Wavefront OBJ reader: `v` and `f` records, through `tobj`.
//!
//! A first pass over the text does what `tobj` does not: it joins lines
//! ending in `\` with the next one, accepts CRLF, strips `#` comments, keeps
//! only `v` and `f` records (so `g`, `o`, `s`, `usemtl`, `mtllib`, `vt`, `vn`,
//! `l`, ... are ignored whatever their content), reduces `v/t/n` and `v//n`
//! face corners to the position index, and checks every number and index
//! with the line it is on, so errors name their line. `tobj` then reads the
//! cleaned text with `triangulate: false` so n-gons stay whole.
//!
//! Faces keep file order (across all groups and objects): face `i` is the
//! `i`-th `f` record of the file. Negative indices count back from the last
//! vertex defined so far.

use super::{MeshError, RawMesh};

const FORMAT: &str = "OBJ";

/// Parses an OBJ file.
pub(crate) fn parse(bytes: &[u8]) -> Result<RawMesh, MeshError> {
    let text = String::from_utf8_lossy(bytes);
    let (clean, unknown_lines) = preprocess(&text)?;
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: false,
        ignore_points: false,
        ignore_lines: false,
    };
    // No `mtllib` record reaches tobj, so the material loader is never used.
    let (models, _materials) = tobj::load_obj_buf(&mut clean.as_bytes(), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| MeshError::parse(FORMAT, e.to_string()))?;

    let mut raw = RawMesh {
        unknown_lines,
        ..RawMesh::default()
    };
    for model in &models {
        let mesh = &model.mesh;
        let offset = raw.vertices.len();
        raw.vertices
            .extend(mesh.positions.chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        let index = |i: u32| -> Result<u32, MeshError> {
            u32::try_from(offset + i as usize)
                .map_err(|_| MeshError::parse(FORMAT, "too many vertices"))
        };
        // tobj leaves `face_arities` empty when every face is a triangle.
        let arities: Vec<usize> = if mesh.face_arities.is_empty() {
            vec![3; mesh.indices.len() / 3]
        } else {
            mesh.face_arities.iter().map(|&a| a as usize).collect()
        };
        let mut start = 0usize;
        for arity in arities {
            let corners = mesh
                .indices
                .get(start..start + arity)
                .ok_or_else(|| MeshError::parse(FORMAT, "inconsistent face data"))?;
            raw.faces.push(
                corners
                    .iter()
                    .map(|&i| index(i))
                    .collect::<Result<_, _>>()?,
            );
            start += arity;
        }
    }
    Ok(raw)
}

/// Joins continuation lines and keeps only checked, simplified `v` and `f`
/// records, one per line; also returns the number of logical lines that are
/// no OBJ statement at all ([`KEYWORDS`]), which tells a file of another
/// kind from an OBJ file without faces.
fn preprocess(text: &str) -> Result<(String, usize), MeshError> {
    let mut out = String::with_capacity(text.len().min(1 << 26));
    let mut logical = String::new();
    let mut first_line = 1usize;
    let mut vertices = 0u64;
    let mut unknown = 0usize;
    for (k, raw) in text.split('\n').enumerate() {
        let line = raw.strip_suffix('\r').unwrap_or(raw);
        if logical.is_empty() {
            first_line = k + 1;
        }
        if let Some(head) = line.trim_end().strip_suffix('\\') {
            logical.push_str(head);
            logical.push(' ');
            continue;
        }
        logical.push_str(line);
        unknown += usize::from(!record(&logical, first_line, &mut vertices, &mut out)?);
        logical.clear();
    }
    if !logical.is_empty() {
        unknown += usize::from(!record(&logical, first_line, &mut vertices, &mut out)?);
    }
    Ok((out, unknown))
}

/// The statements of the OBJ format (geometry, grouping, display and
/// free-form ones); a line starting with anything else is not understood.
const KEYWORDS: [&str; 34] = [
    "v",
    "vt",
    "vn",
    "vp",
    "f",
    "fo",
    "l",
    "p",
    "g",
    "o",
    "s",
    "mg",
    "usemtl",
    "mtllib",
    "usemap",
    "maplib",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "lod",
    "shadow_obj",
    "trace_obj",
    "call",
];

/// Checks one logical line and appends its simplified form to `out` when it
/// is a `v` or `f` record. `vertices` counts the `v` records so far, to
/// resolve and check indices. Returns whether the line is understood: blank,
/// a comment or an OBJ statement ([`KEYWORDS`]).
fn record(line: &str, at: usize, vertices: &mut u64, out: &mut String) -> Result<bool, MeshError> {
    let line = line.split('#').next().unwrap_or("");
    let mut words = line.split_whitespace();
    match words.next() {
        Some("v") => {
            let coords: Vec<&str> = words.collect();
            // x y z, optionally w (homogeneous) or r g b (colour, dropped).
            let keep = match coords.len() {
                3 | 6 | 7 => 3,
                4 => 4,
                n => {
                    return Err(MeshError::parse_at(
                        FORMAT,
                        at,
                        format!("a vertex needs 3 coordinates, found {n} numbers"),
                    ))
                }
            };
            out.push('v');
            for (i, c) in coords[..keep].iter().enumerate() {
                let x: f64 = c.parse().map_err(|_| {
                    MeshError::parse_at(FORMAT, at, format!("bad vertex coordinate {c:?}"))
                })?;
                if i == 3 && x == 0.0 {
                    return Err(MeshError::parse_at(FORMAT, at, "vertex weight w is 0"));
                }
                out.push(' ');
                out.push_str(c);
            }
            out.push('\n');
            *vertices += 1;
        }
        Some("f") => {
            out.push('f');
            for corner in words {
                let v = corner.split('/').next().unwrap_or("");
                let i: i64 = v.parse().map_err(|_| {
                    MeshError::parse_at(FORMAT, at, format!("bad face corner {corner:?}"))
                })?;
                let n = i128::from(*vertices);
                let resolved = if i < 0 {
                    n + i128::from(i)
                } else {
                    i128::from(i) - 1
                };
                if !(0..n).contains(&resolved) {
                    return Err(MeshError::parse_at(
                        FORMAT,
                        at,
                        format!("face uses vertex {i}, but only {n} vertices are defined so far"),
                    ));
                }
                // Absolute 1-based index: tobj then need not resolve anything.
                out.push(' ');
                out.push_str(&(resolved + 1).to_string());
            }
            out.push('\n');
        }
        Some(k) => return Ok(KEYWORDS.contains(&k)),
        None => {}
    }
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{load_bytes, MeshFormat};

    fn faces(text: &str) -> Vec<Vec<u32>> {
        parse(text.as_bytes()).unwrap().faces
    }

    #[test]
    fn index_forms_and_negative_indices() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
                    f 1/1/1 2/1/1 3/1/1\nf 1//1 3//1 4//1\nf -4 -2 -1\nf 1/1 2/1 4/1\n";
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(raw.vertices.len(), 4);
        let f: Vec<Vec<[f64; 3]>> = raw
            .faces
            .iter()
            .map(|f| f.iter().map(|&i| raw.vertices[i as usize]).collect())
            .collect();
        let c = |x: f64, y: f64| [x, y, 0.0];
        assert_eq!(f[0], vec![c(0., 0.), c(1., 0.), c(1., 1.)]);
        assert_eq!(f[1], vec![c(0., 0.), c(1., 1.), c(0., 1.)]);
        assert_eq!(f[2], vec![c(0., 0.), c(1., 1.), c(0., 1.)]);
        assert_eq!(f[3], vec![c(0., 0.), c(1., 0.), c(0., 1.)]);
    }

    #[test]
    fn negative_indices_are_relative_to_vertices_so_far() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf -3 -2 -1\n";
        let raw = parse(text.as_bytes()).unwrap();
        let first: Vec<[f64; 3]> = raw.faces[0]
            .iter()
            .map(|&i| raw.vertices[i as usize])
            .collect();
        let second: Vec<[f64; 3]> = raw.faces[1]
            .iter()
            .map(|&i| raw.vertices[i as usize])
            .collect();
        assert_eq!(first[0], [0.0, 0.0, 0.0]);
        assert_eq!(second[0], [5.0, 5.0, 5.0]);
    }

    #[test]
    fn crlf_continuations_comments_and_ignored_records() {
        let text = "# header\r\nmtllib x.mtl\r\nusemtl \r\no thing\r\ng a b\r\ns off\r\n\
                    v 0 0 0 # corner\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0 0.5 0.5 0.5\r\n\
                    l 1 2\r\nf 1 2 \\\r\n  3 4\r\ng other\r\nf 4 3 2\r\n";
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(raw.faces, vec![vec![0, 1, 2, 3], vec![3, 2, 1]]);
        assert_eq!(raw.vertices[3], [0.0, 1.0, 0.0]);
    }

    #[test]
    fn ngons_stay_whole_and_faces_keep_file_order_across_groups() {
        let text = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n\
                    g a\nf 1 2 3 4 5 6\ng b\nf 1 2 3\no c\nf 1 3 4\n";
        let m = load_bytes(MeshFormat::Obj, text.as_bytes()).unwrap();
        assert_eq!(m.report.faces_read, 3);
        let sources: Vec<u32> = m.polygons.iter().map(|p| p.source).collect();
        assert_eq!(sources, vec![0, 1, 2]);
        assert_eq!(m.polygons[0].verts.len(), 6, "concave hexagon kept whole");
    }

    #[test]
    fn homogeneous_weight_divides() {
        let f = parse(b"v 2 4 6 2\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(f.vertices[0], [1.0, 2.0, 3.0]);
    }

    #[test]
    fn point_and_line_faces_are_read_then_dropped() {
        assert_eq!(
            faces("v 0 0 0\nv 1 0 0\nf 1\nf 1 2\n"),
            vec![vec![0], vec![0, 1]]
        );
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1\nf 1 2\nf 1 2 3\n";
        let m = load_bytes(MeshFormat::Obj, text.as_bytes()).unwrap();
        assert_eq!(m.report.faces_read, 3);
        assert_eq!(m.report.dropped_degenerate, 2);
        assert_eq!(m.polygons[0].source, 2);
    }

    #[test]
    fn errors_name_their_line() {
        let cases: [(&str, usize); 6] = [
            ("v 0 0 0\nv 1 0\n", 2),
            ("v 0 0 x\n", 1),
            ("v 0 0 0\nf 1 2 3\n", 2),
            ("v 0 0 0\n\nf 0\n", 3),
            ("v 0 0 0\nf -2\n", 2),
            ("v 0 0 0\nf 1/2/3/4 a\n", 2),
        ];
        for (text, line) in cases {
            match parse(text.as_bytes()) {
                Err(MeshError::Parse {
                    format: "OBJ",
                    line: Some(l),
                    ..
                }) => {
                    assert_eq!(l, line, "{text:?}")
                }
                other => panic!("{text:?}: {other:?}"),
            }
        }
        // A continuation keeps the number of the line the record starts on.
        match parse(b"v 0 0 0\nf 1 \\\n 9\n") {
            Err(MeshError::Parse { line: Some(2), .. }) => {}
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn huge_indices_are_errors_not_panics() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\nf 1 2 -9223372036854775808\n";
        assert!(parse(text.as_bytes()).is_err());
        assert!(parse(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n").is_err());
    }

    #[test]
    fn no_faces_is_reported_with_the_lines_not_understood() {
        let no_faces = |text: &[u8]| match load_bytes(MeshFormat::Obj, text) {
            Err(MeshError::NoFaces {
                format: "OBJ",
                unknown_lines,
            }) => unknown_lines,
            other => panic!("{other:?}"),
        };
        assert_eq!(no_faces(b"v 0 0 0\n"), 0);
        assert_eq!(no_faces(b""), 0);
        // Statements of the format (even ones ignored here) are understood.
        assert_eq!(
            no_faces(b"# c\no x\ng a\nvt 0 0\nl 1 2\nusemtl m\ncstype bezier\n"),
            0
        );
        assert_eq!(
            no_faces(b"solid x\n  facet normal 0 0 1\nendsolid\n\nv 1 2 3\n"),
            3
        );
        let e = load_bytes(MeshFormat::Obj, b"<html>\n<body>\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "no faces found in the OBJ file (2 lines not understood)"
        );
    }
}
