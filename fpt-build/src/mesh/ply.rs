//! PLY reader (ASCII, binary little and big endian), through `ply-rs`.
//!
//! Uses the `vertex` element's `x y z` (any numeric type) and the `face`
//! element's `vertex_indices` (or `vertex_index`) list. Colours: a face's
//! own `red green blue` when the face element has them, else the mean of
//! its vertices' `red green blue` when every one of its vertices has them
//! (smooth vertex colours become flat face colours), else the default grey;
//! integer channels are 0–255, float channels 0–1. Vertex normals: the
//! `vertex` element's `nx ny nz` (any numeric type) become every corner's
//! normal at that vertex, for the `smooth` effect (see
//! [`super::from_faces_normals`]). Other elements and properties are
//! ignored. Faces are numbered in file order.
//!
//! `ply-rs` trusts its input more than we may: a number in the header too
//! large for u64 makes it panic, and an element count far beyond the data
//! makes it loop that many times. So the header is checked here first:
//! no digit run longer than 19 (always fits u64) outside comments, and no
//! element count larger than the bytes after the header (every element of
//! a property-less element still reads at least a line or fails). Then
//! `ply-rs`'s work is bounded by the input size.

use super::{MeshError, RawMesh};
use crate::geom::DEFAULT_COLOR;
use ply_rs::parser::Parser;
use ply_rs::ply::{DefaultElement, Property};

const FORMAT: &str = "PLY";

/// Parses a PLY file.
pub(crate) fn parse(bytes: &[u8]) -> Result<RawMesh, MeshError> {
    check_header(bytes)?;
    let parser = Parser::<DefaultElement>::new();
    let ply = parser
        .read_ply(&mut &bytes[..])
        .map_err(|e| MeshError::parse(FORMAT, one_line(&e.to_string())))?;

    let mut raw = RawMesh::default();
    let vertices = ply.payload.get("vertex").map_or(&[][..], |v| &v[..]);
    raw.vertices.reserve(vertices.len());
    let mut vertex_colors = Vec::with_capacity(vertices.len());
    let mut vertex_normals = Vec::with_capacity(vertices.len());
    for (k, v) in vertices.iter().enumerate() {
        let coord = |name: &str| {
            v.get(name).and_then(scalar).ok_or_else(|| {
                MeshError::parse(FORMAT, format!("vertex {k} has no numeric {name:?}"))
            })
        };
        raw.vertices.push([coord("x")?, coord("y")?, coord("z")?]);
        vertex_colors.push(rgb_of(v));
        let [nx, ny, nz] = ["nx", "ny", "nz"].map(|c| v.get(c).and_then(scalar));
        vertex_normals.push(nx.zip(ny).zip(nz).map(|((x, y), z)| [x, y, z]));
    }
    let faces = ply.payload.get("face").map_or(&[][..], |f| &f[..]);
    raw.faces.reserve(faces.len());
    let mut colors = Vec::with_capacity(faces.len());
    let mut any_color = false;
    for (k, f) in faces.iter().enumerate() {
        let list = f
            .get("vertex_indices")
            .or_else(|| f.get("vertex_index"))
            .ok_or_else(|| {
                MeshError::parse(FORMAT, format!("face {k} has no vertex_indices list"))
            })?;
        let indices = index_list(list).ok_or_else(|| {
            MeshError::parse(
                FORMAT,
                format!("face {k}: vertex indices must be a list of non-negative integers"),
            )
        })?;
        let own = rgb_of(f).or_else(|| mean_color(&indices, &vertex_colors));
        any_color |= own.is_some();
        colors.push(own.unwrap_or(DEFAULT_COLOR));
        raw.faces.push(indices);
    }
    raw.colors = any_color.then_some(colors);
    if vertex_normals.iter().any(Option::is_some) {
        // A face has normals when each of its vertices has one (an index
        // out of range has none: the import reports it).
        raw.normals = raw
            .faces
            .iter()
            .map(|f| {
                f.iter()
                    .map(|&i| vertex_normals.get(i as usize).copied().flatten())
                    .collect()
            })
            .collect();
    }
    Ok(raw)
}

/// Rejects headers that would make `ply-rs` panic or loop far beyond the
/// input (see the module doc).
fn check_header(bytes: &[u8]) -> Result<(), MeshError> {
    let mut pos = 0usize;
    let mut counts: Vec<(usize, u64)> = Vec::new();
    for line_no in 1.. {
        let end = bytes[pos..]
            .iter()
            .position(|&b| b == b'\n')
            .map(|i| pos + i + 1);
        let line = String::from_utf8_lossy(&bytes[pos..end.unwrap_or(bytes.len())]);
        let t = line.trim();
        if !(t.starts_with("comment") || t.starts_with("obj_info")) && longest_digit_run(t) > 19 {
            return Err(MeshError::parse_at(FORMAT, line_no, "number too large"));
        }
        if t.starts_with("element") {
            if let Some(n) = t.split_whitespace().nth(2).and_then(|w| w.parse().ok()) {
                counts.push((line_no, n));
            }
        }
        if t == "end_header" {
            let payload = (bytes.len() - end.unwrap_or(bytes.len())) as u64;
            return match counts.iter().find(|&&(_, n)| n > payload + 1) {
                Some(&(at, n)) => Err(MeshError::parse_at(
                    FORMAT,
                    at,
                    format!("{n} elements cannot fit in the {payload} bytes after the header"),
                )),
                None => Ok(()),
            };
        }
        match end {
            Some(e) => pos = e,
            None => break,
        }
    }
    Err(MeshError::parse(FORMAT, "no end_header line"))
}

/// Length of the longest run of ASCII digits in `s`.
fn longest_digit_run(s: &str) -> usize {
    s.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

/// `ply-rs` messages span lines and quote whole input lines: squeeze to one
/// short line.
fn one_line(msg: &str) -> String {
    let s = msg.split_whitespace().collect::<Vec<_>>().join(" ");
    match s.char_indices().nth(200) {
        Some((i, _)) => format!("{}…", &s[..i]),
        None => s,
    }
}

/// A numeric scalar property as f64.
fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(x) => f64::from(x),
        Property::UChar(x) => f64::from(x),
        Property::Short(x) => f64::from(x),
        Property::UShort(x) => f64::from(x),
        Property::Int(x) => f64::from(x),
        Property::UInt(x) => f64::from(x),
        Property::Float(x) => f64::from(x),
        Property::Double(x) => x,
        _ => return None,
    })
}

/// An element's `red green blue` colour, when it has all three.
fn rgb_of(e: &DefaultElement) -> Option<[u8; 3]> {
    let [r, g, b] = ["red", "green", "blue"].map(|c| e.get(c).and_then(color_channel));
    Some([r?, g?, b?])
}

/// The mean colour of vertices `indices` (rounded), when every one has a
/// colour (an index out of range has none: the import reports it).
fn mean_color(indices: &[u32], colors: &[Option<[u8; 3]>]) -> Option<[u8; 3]> {
    if indices.is_empty() {
        return None;
    }
    let mut sum = [0u64; 3];
    for &i in indices {
        let c = colors.get(i as usize).copied().flatten()?;
        for (s, x) in sum.iter_mut().zip(c) {
            *s += u64::from(x);
        }
    }
    let n = indices.len() as u64;
    Some(sum.map(|s| ((s + n / 2) / n) as u8))
}

/// A colour channel: integers are 0–255 (clamped), floats 0–1.
fn color_channel(p: &Property) -> Option<u8> {
    match *p {
        Property::Float(_) | Property::Double(_) => {
            let x = scalar(p)?;
            x.is_finite()
                .then(|| (x.clamp(0.0, 1.0) * 255.0).round() as u8)
        }
        _ => scalar(p).map(|x| x.clamp(0.0, 255.0) as u8),
    }
}

/// An integer list property as vertex indices; `None` for a float list or a
/// negative index.
fn index_list(p: &Property) -> Option<Vec<u32>> {
    fn conv<T: Copy>(v: &[T]) -> Option<Vec<u32>>
    where
        u32: TryFrom<T>,
    {
        v.iter().map(|&x| u32::try_from(x).ok()).collect()
    }
    match p {
        Property::ListChar(v) => conv(v),
        Property::ListUChar(v) => conv(v),
        Property::ListShort(v) => conv(v),
        Property::ListUShort(v) => conv(v),
        Property::ListInt(v) => conv(v),
        Property::ListUInt(v) => conv(v),
        _ => None,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::mesh::{load_bytes, MeshFormat};

    pub(crate) const TETRA_V: [[f32; 3]; 4] =
        [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
    pub(crate) const TETRA_F: [[i32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];

    pub(crate) fn ascii_tetra() -> String {
        let mut s = String::from(
            "ply\nformat ascii 1.0\ncomment made by a test\nelement vertex 4\n\
             property float x\nproperty float y\nproperty float z\n\
             element face 4\nproperty list uchar int vertex_indices\nend_header\n",
        );
        for v in TETRA_V {
            s.push_str(&format!("{} {} {}\n", v[0], v[1], v[2]));
        }
        for f in TETRA_F {
            s.push_str(&format!("3 {} {} {}\n", f[0], f[1], f[2]));
        }
        s
    }

    /// A binary tetrahedron; `big` picks the byte order. Faces use
    /// `vertex_index` with uint indices and carry a colour.
    pub(crate) fn binary_tetra(big: bool) -> Vec<u8> {
        let order = if big { "big" } else { "little" };
        let mut b = format!(
            "ply\nformat binary_{order}_endian 1.0\nelement vertex 4\n\
             property double x\nproperty double y\nproperty double z\n\
             element face 4\nproperty list uchar uint vertex_index\n\
             property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
        )
        .into_bytes();
        for v in TETRA_V {
            for c in v {
                let c = f64::from(c);
                b.extend_from_slice(&if big {
                    c.to_be_bytes()
                } else {
                    c.to_le_bytes()
                });
            }
        }
        for (k, f) in TETRA_F.iter().enumerate() {
            b.push(3);
            for &i in f {
                let i = i as u32;
                b.extend_from_slice(&if big {
                    i.to_be_bytes()
                } else {
                    i.to_le_bytes()
                });
            }
            b.extend_from_slice(&[10 * k as u8, 1, 2]);
        }
        b
    }

    #[test]
    fn ascii_ply() {
        let m = load_bytes(MeshFormat::Ply, ascii_tetra().as_bytes()).unwrap();
        assert_eq!(m.report.faces_read, 4);
        assert!(m.closed);
        assert!(m.polygons.iter().all(|p| p.color == DEFAULT_COLOR));
    }

    #[test]
    fn binary_ply_both_byte_orders_with_face_colours() {
        for big in [false, true] {
            let raw = parse(&binary_tetra(big)).unwrap();
            assert_eq!(raw.vertices[3], [0.0, 0.0, 1.0], "big endian: {big}");
            assert_eq!(raw.faces[2], vec![1, 2, 3]);
            let m = load_bytes(MeshFormat::Ply, &binary_tetra(big)).unwrap();
            assert!(m.closed);
            for p in &m.polygons {
                assert_eq!(p.color, [10 * p.source as u8, 1, 2]);
            }
        }
    }

    #[test]
    fn crlf_header() {
        let text = ascii_tetra().replace('\n', "\r\n");
        assert_eq!(parse(text.as_bytes()).unwrap().faces.len(), 4);
    }

    #[test]
    fn hostile_headers_are_rejected_not_panicking() {
        let huge_number =
            ascii_tetra().replace("element vertex 4", "element vertex 99999999999999999999999");
        assert!(parse(huge_number.as_bytes()).is_err());
        let huge_version = ascii_tetra().replace("1.0", "184467440737095516160.0");
        assert!(parse(huge_version.as_bytes()).is_err());
        // No properties and a count far beyond the data: would loop.
        let empty_element =
            "ply\nformat binary_little_endian 1.0\nelement junk 1000000000000000000\nend_header\n";
        let e = parse(empty_element.as_bytes()).unwrap_err();
        assert!(e.to_string().contains("cannot fit"), "{e}");
        assert!(parse(b"ply\nformat ascii 1.0\n").is_err());
    }

    #[test]
    fn bad_faces() {
        let neg = ascii_tetra().replace("3 0 2 1", "3 0 -2 1");
        assert!(parse(neg.as_bytes()).is_err());
        let out = ascii_tetra().replace("3 0 2 1", "3 0 9 1");
        assert!(matches!(
            load_bytes(MeshFormat::Ply, out.as_bytes()),
            Err(MeshError::BadIndex {
                face: 0,
                index: 9,
                ..
            })
        ));
        let short = ascii_tetra().replace("3 0 2 1\n", "3 0 2\n");
        let e = parse(short.as_bytes()).unwrap_err();
        assert!(!e.to_string().contains('\n'));
    }

    #[test]
    fn point_cloud_has_no_faces() {
        let s = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
                 property float z\nend_header\n1 2 3\n";
        assert!(matches!(
            load_bytes(MeshFormat::Ply, s.as_bytes()),
            Err(MeshError::NoFaces { .. })
        ));
    }

    #[test]
    fn vertex_colours_become_face_colours_and_face_colours_win() {
        // Vertex colours only: each face gets its vertices' mean.
        let text = "ply\nformat ascii 1.0\nelement vertex 4\n\
             property float x\nproperty float y\nproperty float z\n\
             property uchar red\nproperty uchar green\nproperty uchar blue\n\
             element face 4\nproperty list uchar int vertex_indices\nend_header\n\
             0 0 0 0 0 0\n1 0 0 255 0 0\n0 1 0 0 255 0\n0 0 1 0 0 255\n\
             3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
        let m = load_bytes(MeshFormat::Ply, text.as_bytes()).unwrap();
        let by_source = |m: &crate::mesh::Model, k: u32| {
            m.polygons.iter().find(|p| p.source == k).unwrap().color
        };
        assert_eq!(by_source(&m, 0), [85, 85, 0]);
        assert_eq!(by_source(&m, 2), [85, 85, 85]);
        // Float vertex channels are 0-1.
        let float = text
            .replace("uchar red", "float red")
            .replace("uchar green", "float green")
            .replace("uchar blue", "float blue")
            .replace("1 0 0 255 0 0", "1 0 0 1.0 0 0")
            .replace("0 1 0 0 255 0", "0 1 0 0 1.0 0")
            .replace("0 0 1 0 0 255", "0 0 1 0 0 1.0");
        let m = load_bytes(MeshFormat::Ply, float.as_bytes()).unwrap();
        assert_eq!(by_source(&m, 0), [85, 85, 0]);
        // A face colour wins over its vertices'.
        let both = text
            .replace(
                "vertex_indices\nend_header",
                "vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header",
            )
            .replace("3 0 2 1\n", "3 0 2 1 9 8 7\n")
            .replace("3 0 1 3\n", "3 0 1 3 1 2 3\n")
            .replace("3 1 2 3\n", "3 1 2 3 1 2 3\n")
            .replace("3 0 3 2\n", "3 0 3 2 1 2 3\n");
        let m = load_bytes(MeshFormat::Ply, both.as_bytes()).unwrap();
        assert_eq!(by_source(&m, 0), [9, 8, 7]);
    }
}
