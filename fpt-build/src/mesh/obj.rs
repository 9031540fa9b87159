//! Wavefront OBJ reader: `v`, `vn` and `f` records, through `tobj`.
//!
//! A first pass over the text does what `tobj` does not: it joins lines
//! ending in `\` with the next one, accepts CRLF, strips `#` comments, keeps
//! only `v`, `vn` and `f` records (so `g`, `o`, `s`, `vt`, `l`, ... are
//! ignored whatever their content), reduces `v/t/n` and `v//n` face corners
//! to `v//n` (absolute indices) or to the position index, and checks every
//! position number and index with the line it is on, so errors name their
//! line. `tobj` then reads the cleaned text with `triangulate: false` so
//! n-gons stay whole, and `single_index: false`, which keeps each corner's
//! own normal index (`Mesh::normal_indices`).
//!
//! Vertex normals (for the `smooth` effect): a face whose every corner
//! names a `vn` record that exists gets those normals, one per corner
//! (see [`super::from_faces_normals`]); a face with a corner without one
//! (`v`, `v/t`) or naming a missing one gets none, and its normals are
//! computed with the crease angle. Normals are optional data, so a
//! malformed `vn` record is no error: it stands as a zero normal, which
//! leaves the faces that use it without normals.
//!
//! Materials: the first pass also notes the `mtllib` file names and the
//! `usemtl` material of every face ([`ObjMaterials`]). Parsing bytes alone
//! gives no colours; [`apply_materials`], which [`super::load_with`] calls
//! with the OBJ's folder, reads the material files found there (through
//! `tobj::load_mtl_buf`) and gives each face its material's diffuse colour
//! `Kd` (0–1 per channel, scaled to 0–255). Faces without a material, or
//! whose material is defined in no file read, keep the default grey.
//!
//! Faces keep file order (across all groups and objects): face `i` is the
//! `i`-th `f` record of the file. Negative indices count back from the last
//! vertex defined so far.

use super::{MeshError, RawMesh};
use crate::geom::DEFAULT_COLOR;
use std::collections::HashMap;
use std::path::Path;

const FORMAT: &str = "OBJ";

/// No material (a face before any `usemtl`, or after an empty one).
const NO_MATERIAL: u32 = u32::MAX;

/// The materials an OBJ file names.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct ObjMaterials {
    /// The file names of its `mtllib` records, in order, without repeats.
    pub libs: Vec<String>,
    /// The material names its `usemtl` records use, in first-use order.
    pub names: Vec<String>,
    /// For every face in file order: its index in `names`, or
    /// [`NO_MATERIAL`].
    pub face: Vec<u32>,
}

/// What [`apply_materials`] could not do, for the import report.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct MaterialReport {
    /// `mtllib` files that do not exist next to the OBJ.
    pub missing_files: usize,
    /// Materials used by `usemtl` with a `Kd` in no file read (counted only
    /// when `mtllib` names files and every one was found).
    pub undefined: usize,
}

/// Gives every face of `raw` the `Kd` colour of its `usemtl` material,
/// reading the `mtllib` files from `dir`. Leaves `raw.colors` alone when no
/// face gets a material colour. A material file that exists but is not a
/// valid MTL file is an error naming it.
pub(crate) fn apply_materials(raw: &mut RawMesh, dir: &Path) -> Result<MaterialReport, MeshError> {
    let m = &raw.obj_materials;
    let mut report = MaterialReport::default();
    if m.names.is_empty() {
        return Ok(report);
    }
    let mut kd: HashMap<String, [u8; 3]> = HashMap::new();
    for lib in &m.libs {
        let path = dir.join(lib);
        let bytes = match std::fs::read(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                report.missing_files += 1;
                continue;
            }
            Err(e) => {
                return Err(MeshError::parse("MTL", format!("{}: {e}", path.display())));
            }
        };
        let (materials, _) = tobj::load_mtl_buf(&mut &bytes[..])
            .map_err(|e| MeshError::parse("MTL", format!("{}: {e}", path.display())))?;
        for mat in materials {
            if let Some(d) = mat.diffuse {
                // The first definition of a name wins, as in file order.
                kd.entry(mat.name).or_insert(d.map(channel));
            }
        }
    }
    let colours: Vec<Option<[u8; 3]>> = m.names.iter().map(|n| kd.get(n).copied()).collect();
    if report.missing_files == 0 && !m.libs.is_empty() {
        report.undefined = colours.iter().filter(|c| c.is_none()).count();
    }
    if colours.iter().all(Option::is_none) {
        return Ok(report);
    }
    let face_colour = |&i: &u32| {
        colours
            .get(i as usize)
            .copied()
            .flatten()
            .unwrap_or(DEFAULT_COLOR)
    };
    raw.colors = Some(m.face.iter().map(face_colour).collect());
    Ok(report)
}

/// An OBJ text of `polygons` (each with its own vertices, which the import
/// welds again) using materials named after their colours, and the text of
/// the material file `mtl_name` it refers to, with a `Kd` per colour that
/// reads back as exactly that colour. For the demo and tests: a coloured
/// model that goes through the import as a user's files would.
pub fn write_obj_mtl(polygons: &[crate::geom::Polygon], mtl_name: &str) -> (String, String) {
    use std::fmt::Write;
    let name = |c: [u8; 3]| format!("rgb_{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
    let mut obj = format!("# written by fpt\nmtllib {mtl_name}\n");
    let mut mtl = String::from("# written by fpt\n");
    let mut seen: Vec<[u8; 3]> = Vec::new();
    let mut current = None;
    let mut next = 1usize;
    for p in polygons {
        if !seen.contains(&p.color) {
            seen.push(p.color);
            let [r, g, b] = p.color.map(|x| f64::from(x) / 255.0);
            let _ = write!(mtl, "newmtl {}\nKd {r:.6} {g:.6} {b:.6}\n", name(p.color));
        }
        if current != Some(p.color) {
            current = Some(p.color);
            let _ = writeln!(obj, "usemtl {}", name(p.color));
        }
        for v in &p.verts {
            let _ = writeln!(obj, "v {} {} {}", v.x, v.y, v.z);
        }
        obj.push('f');
        for i in 0..p.verts.len() {
            let _ = write!(obj, " {}", next + i);
        }
        obj.push('\n');
        next += p.verts.len();
    }
    (obj, mtl)
}

/// A `Kd` channel (0–1, clamped; NaN is 0) as 0–255.
fn channel(x: f64) -> u8 {
    if x.is_nan() {
        return 0;
    }
    (x.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Parses an OBJ file.
pub(crate) fn parse(bytes: &[u8]) -> Result<RawMesh, MeshError> {
    let text = String::from_utf8_lossy(bytes);
    let (clean, unknown_lines, obj_materials, face_normals) = preprocess(&text)?;
    let any_normals = face_normals.iter().any(|&f| f);
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
        obj_materials,
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
            if any_normals {
                let has = face_normals.get(raw.faces.len()).copied().unwrap_or(false);
                raw.normals.push(
                    has.then(|| corner_normals(mesh, start..start + arity))
                        .flatten(),
                );
            }
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

/// The normals of the corners `range` of `mesh` (one per corner, through
/// `tobj`'s `normal_indices`), when every one is there.
fn corner_normals(mesh: &tobj::Mesh, range: std::ops::Range<usize>) -> Option<Vec<[f64; 3]>> {
    mesh.normal_indices
        .get(range)?
        .iter()
        .map(|&n| {
            let n = n as usize;
            mesh.normals
                .get(3 * n..3 * n + 3)
                .map(|c| [c[0], c[1], c[2]])
        })
        .collect()
}

/// What the first pass has seen so far.
#[derive(Default)]
struct Pass {
    /// `v` records so far, to resolve and check indices.
    vertices: u64,
    /// `vn` records so far, to resolve normal indices.
    normals: u64,
    /// For every face so far: whether each of its corners names a normal.
    face_normals: Vec<bool>,
    /// The current `usemtl` material (index into `materials.names`).
    current: Option<u32>,
    /// Where each name is in `materials.names`.
    index: HashMap<String, u32>,
    materials: ObjMaterials,
}

/// What [`preprocess`] returns: the cleaned text, the number of lines not
/// understood, the materials named and, per face, whether it has normals.
type Preprocessed = (String, usize, ObjMaterials, Vec<bool>);

/// Joins continuation lines and keeps only checked, simplified `v`, `vn`
/// and `f` records, one per line; also returns the number of logical lines
/// that are no OBJ statement at all ([`KEYWORDS`]), which tells a file of
/// another kind from an OBJ file without faces, the materials named, and
/// for every face whether all its corners name a normal.
fn preprocess(text: &str) -> Result<Preprocessed, MeshError> {
    let mut out = String::with_capacity(text.len().min(1 << 26));
    let mut logical = String::new();
    let mut first_line = 1usize;
    let mut pass = Pass::default();
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
        unknown += usize::from(!record(&logical, first_line, &mut pass, &mut out)?);
        logical.clear();
    }
    if !logical.is_empty() {
        unknown += usize::from(!record(&logical, first_line, &mut pass, &mut out)?);
    }
    Ok((out, unknown, pass.materials, pass.face_normals))
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

/// The 0-based index of OBJ index `i` (1-based, or negative counting back
/// from the last of the `n` records so far), when it names one of them.
fn resolve(i: i64, n: u64) -> Option<u64> {
    let n = i128::from(n);
    let r = if i < 0 {
        n + i128::from(i)
    } else {
        i128::from(i) - 1
    };
    u64::try_from(r).ok().filter(|&r| i128::from(r) < n)
}

/// Checks one logical line and appends its simplified form to `out` when it
/// is a `v`, `vn` or `f` record; notes `mtllib` and `usemtl` in `pass`. Returns
/// whether the line is understood: blank, a comment or an OBJ statement
/// ([`KEYWORDS`]).
fn record(line: &str, at: usize, pass: &mut Pass, out: &mut String) -> Result<bool, MeshError> {
    let line = line.split('#').next().unwrap_or("");
    let mut words = line.split_whitespace();
    let vertices = &mut pass.vertices;
    match words.next() {
        Some("mtllib") => {
            for lib in words {
                if !pass.materials.libs.iter().any(|l| l == lib) {
                    pass.materials.libs.push(lib.to_string());
                }
            }
        }
        Some("usemtl") => {
            // The name is the rest of the line, as `newmtl` names are.
            let name = line.trim_start()["usemtl".len()..].trim();
            let names = &mut pass.materials.names;
            pass.current = if name.is_empty() {
                None
            } else {
                let next = u32::try_from(names.len()).unwrap_or(NO_MATERIAL);
                let i = *pass.index.entry(name.to_string()).or_insert(next);
                if i == next {
                    names.push(name.to_string());
                }
                Some(i)
            };
        }
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
        Some("vn") => {
            let coords: Vec<&str> = words.collect();
            let ok = coords.len() == 3 && coords.iter().all(|c| c.parse::<f64>().is_ok());
            // A malformed normal keeps its place (later indices count it)
            // as a zero vector, which no face's normals may contain.
            out.push_str("vn ");
            out.push_str(&if ok { coords.join(" ") } else { "0 0 0".into() });
            out.push('\n');
            pass.normals += 1;
        }
        Some("f") => {
            pass.materials
                .face
                .push(pass.current.unwrap_or(NO_MATERIAL));
            // The corners as `p//n` when every one names an existing
            // normal, else as `p` alone; absolute 1-based indices, so that
            // tobj need not resolve anything.
            let (mut plain, mut with_normals) = (String::from("f"), String::from("f"));
            let mut all_normals = true;
            for corner in words {
                let mut parts = corner.split('/');
                let v = parts.next().unwrap_or("");
                let i: i64 = v.parse().map_err(|_| {
                    MeshError::parse_at(FORMAT, at, format!("bad face corner {corner:?}"))
                })?;
                let resolved = resolve(i, *vertices).ok_or_else(|| {
                    let n = *vertices;
                    MeshError::parse_at(
                        FORMAT,
                        at,
                        format!("face uses vertex {i}, but only {n} vertices are defined so far"),
                    )
                })?;
                plain.push_str(&format!(" {}", resolved + 1));
                let normal = parts
                    .nth(1)
                    .and_then(|n| n.parse::<i64>().ok())
                    .and_then(|n| resolve(n, pass.normals));
                match normal {
                    Some(n) => with_normals.push_str(&format!(" {}//{}", resolved + 1, n + 1)),
                    None => all_normals = false,
                }
            }
            out.push_str(if all_normals { &with_normals } else { &plain });
            out.push('\n');
            pass.face_normals.push(all_normals);
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
    fn faces_get_normals_only_when_every_corner_names_a_valid_one() {
        // Face 0: all corners name normals (the 2nd by a negative index);
        // face 1: one corner has none; face 2: one names a missing normal;
        // face 3: uses the malformed `vn` (a zero vector, no error).
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0.6 0.8\nvn 1 2\n\
                    f 1//1 2//-2 3/5/2\nf 1//1 2 3//2\nf 1//1 2//9 3//2\nf 1//1 2//3 3//3\n";
        let raw = parse(text.as_bytes()).unwrap();
        assert_eq!(raw.faces.len(), 4);
        assert_eq!(
            raw.normals[0],
            Some(vec![[0.0, 0.0, 1.0], [0.0, 0.6, 0.8], [0.0, 0.6, 0.8]])
        );
        assert_eq!(raw.normals[1], None);
        assert_eq!(raw.normals[2], None);
        assert_eq!(raw.normals[3].as_ref().map(|n| n[1]), Some([0.0; 3]));
        // The zero normal leaves face 3 without normals after the import;
        // face 0 keeps its own.
        let m = load_bytes(MeshFormat::Obj, text.as_bytes()).unwrap();
        let normals: Vec<bool> = m.polygons.iter().map(|p| p.normals.is_some()).collect();
        assert_eq!(normals, [true, false, false, false]);
        // A file without `vn` gives no normal list at all.
        assert!(parse(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
            .unwrap()
            .normals
            .is_empty());
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
        let whole = crate::mesh::ImportOptions {
            no_merge: true,
            ..Default::default()
        };
        let m = parse(text.as_bytes())
            .unwrap()
            .into_model(MeshFormat::Obj, &whole)
            .unwrap();
        assert_eq!(m.report.faces_read, 3);
        let sources: Vec<u32> = m.polygons.iter().map(|p| p.source).collect();
        assert_eq!(sources, vec![0, 1, 2]);
        assert_eq!(m.polygons[0].verts.len(), 6, "concave hexagon kept whole");
        // Merged by default: the two triangles are coplanar neighbours of
        // one colour across their edge 1-3 (the hexagon overlaps them, its
        // edges 1-2, 2-3 and 3-4 running the same way as theirs: no
        // manifold edge joins it to them).
        let m = load_bytes(MeshFormat::Obj, text.as_bytes()).unwrap();
        let sources: Vec<u32> = m.polygons.iter().map(|p| p.source).collect();
        assert_eq!(sources, vec![0, 1]);
        assert_eq!(m.polygons[1].verts.len(), 4);
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

    /// A unit cube whose first three faces use material `red`, the next
    /// two `blue` and the last none (after an empty `usemtl`).
    const MATERIAL_CUBE: &str = "mtllib cube.mtl other.mtl\n\
        v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
        usemtl red\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nusemtl blue\nf 2 3 7 6\n\
        usemtl red\nusemtl blue\nf 3 4 8 7\nusemtl\nf 4 1 5 8\n";

    #[test]
    fn usemtl_is_noted_per_face() {
        let raw = parse(MATERIAL_CUBE.as_bytes()).unwrap();
        let m = &raw.obj_materials;
        assert_eq!(m.libs, ["cube.mtl", "other.mtl"]);
        assert_eq!(m.names, ["red", "blue"]);
        assert_eq!(m.face, [0, 0, 0, 1, 1, NO_MATERIAL]);
        // From bytes alone no colour is given.
        assert!(raw.colors.is_none());
    }

    fn scratch(name: &str) -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("fpt-obj-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn kd_of_the_material_files_colours_the_faces() {
        let d = scratch("kd");
        std::fs::write(
            d.join("cube.mtl"),
            "newmtl red\nKa 0 0 0\nKd 1 0 0.25\n\nnewmtl blue\nKd 0 0 1\n",
        )
        .unwrap();
        // `other.mtl` redefines red: the first definition wins.
        std::fs::write(d.join("other.mtl"), "newmtl red\nKd 0 1 0\n").unwrap();
        let mut raw = parse(MATERIAL_CUBE.as_bytes()).unwrap();
        let report = apply_materials(&mut raw, &d).unwrap();
        assert_eq!(report, MaterialReport::default());
        let (r, b, g) = ([255, 0, 64], [0, 0, 255], DEFAULT_COLOR);
        assert_eq!(raw.colors.unwrap(), [r, r, r, b, b, g]);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn missing_or_incomplete_material_files_are_reported() {
        let d = scratch("missing");
        // Only one of the two files, defining one of the two materials.
        std::fs::write(d.join("cube.mtl"), "newmtl blue\nKd 0 0 1\n").unwrap();
        let mut raw = parse(MATERIAL_CUBE.as_bytes()).unwrap();
        let report = apply_materials(&mut raw, &d).unwrap();
        assert_eq!(report.missing_files, 1);
        let g = DEFAULT_COLOR;
        assert_eq!(raw.colors.unwrap(), [g, g, g, [0, 0, 255], [0, 0, 255], g]);
        // Both files, `red` nowhere: one undefined material.
        std::fs::write(d.join("other.mtl"), "newmtl green\nKd 0 1 0\n").unwrap();
        let mut raw = parse(MATERIAL_CUBE.as_bytes()).unwrap();
        let report = apply_materials(&mut raw, &d).unwrap();
        assert_eq!((report.missing_files, report.undefined), (0, 1));
        // No file at all: no colour, one missing... two missing files.
        let empty = scratch("none");
        let mut raw = parse(MATERIAL_CUBE.as_bytes()).unwrap();
        let report = apply_materials(&mut raw, &empty).unwrap();
        assert_eq!(report.missing_files, 2);
        assert!(raw.colors.is_none());
        // A material file that is no MTL file is an error naming it.
        std::fs::write(empty.join("cube.mtl"), "newmtl a\nKd 1 x 0\n").unwrap();
        let mut raw = parse(MATERIAL_CUBE.as_bytes()).unwrap();
        let e = apply_materials(&mut raw, &empty).unwrap_err().to_string();
        assert!(
            e.starts_with("invalid MTL file: ") && e.contains("cube.mtl"),
            "{e}"
        );
        let _ = std::fs::remove_dir_all(&d);
        let _ = std::fs::remove_dir_all(&empty);
    }

    #[test]
    fn written_obj_and_mtl_read_back_with_their_colours() {
        let scene = crate::scenes::robot();
        let d = scratch("written");
        let (obj, mtl) = write_obj_mtl(&scene.polygons, "robot.mtl");
        std::fs::write(d.join("robot.obj"), obj).unwrap();
        std::fs::write(d.join("robot.mtl"), mtl).unwrap();
        let m = crate::mesh::load(&d.join("robot.obj")).unwrap();
        assert!(m.closed);
        assert_eq!(m.report.warning_lines(), Vec::<String>::new());
        for p in &m.polygons {
            assert_eq!(p.color, scene.polygons[p.source as usize].color);
        }
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn kd_channels_are_clamped_and_rounded() {
        assert_eq!(channel(0.5), 128);
        assert_eq!(channel(-1.0), 0);
        assert_eq!(channel(7.0), 255);
        assert_eq!(channel(f64::NAN), 0);
    }
}
