//! STL reader, binary and ASCII.
//!
//! Binary and ASCII are told apart by size only: a file is binary iff its
//! length is `84 + 50·n`, `n` being the little-endian u32 at offset 80.
//! Binary files often start with "solid" too (CAD exporters write it into
//! the 80-byte header), so that word proves nothing. `stl_io` decides by that
//! word, so binary files are read here (the layout is trivial) and only
//! ASCII files are handed to `stl_io`.
//!
//! Every triangle gets its own three vertices; welding joins them.

use super::{MeshError, RawMesh};

const FORMAT: &str = "STL";

/// Parses an STL file.
pub(crate) fn parse(bytes: &[u8]) -> Result<RawMesh, MeshError> {
    match binary_count(bytes) {
        Some(n) => parse_binary(bytes, n),
        None => parse_ascii(bytes),
    }
}

/// The triangle count when `bytes` has the exact size of a binary STL.
fn binary_count(bytes: &[u8]) -> Option<usize> {
    let n = u32::from_le_bytes(bytes.get(80..84)?.try_into().ok()?);
    let expected = 84u64 + 50 * u64::from(n);
    (bytes.len() as u64 == expected).then_some(n as usize)
}

/// Reads `n` binary triangles (the size has been checked by the caller).
fn parse_binary(bytes: &[u8], n: usize) -> Result<RawMesh, MeshError> {
    if n.saturating_mul(3) > u32::MAX as usize {
        return Err(MeshError::parse(FORMAT, "too many triangles"));
    }
    let mut raw = RawMesh {
        vertices: Vec::with_capacity(3 * n),
        faces: Vec::with_capacity(n),
        ..RawMesh::default()
    };
    let f32_at = |rec: &[u8], off: usize| -> f64 {
        let b = [rec[off], rec[off + 1], rec[off + 2], rec[off + 3]];
        f64::from(f32::from_le_bytes(b))
    };
    // Record: normal (3 × f32, ignored: the winding decides), 3 vertices
    // (3 × f32 each), u16 attribute.
    for rec in bytes[84..].chunks_exact(50) {
        let first = raw.vertices.len() as u32;
        for k in 0..3 {
            let off = 12 + 12 * k;
            raw.vertices
                .push([f32_at(rec, off), f32_at(rec, off + 4), f32_at(rec, off + 8)]);
        }
        raw.faces.push(vec![first, first + 1, first + 2]);
    }
    Ok(raw)
}

/// Reads an ASCII STL with `stl_io`.
fn parse_ascii(bytes: &[u8]) -> Result<RawMesh, MeshError> {
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    let body = &bytes[start..];
    if !body.starts_with(b"solid") {
        return Err(MeshError::parse(
            FORMAT,
            "neither binary (the size does not match the triangle count at offset 80) \
             nor ASCII (no leading \"solid\")",
        ));
    }
    // stl_io wants the first line to start with "solid " exactly; a bare
    // "solid" line (no name) is just as valid, so give it a neutral one.
    let rest = body
        .iter()
        .position(|&b| b == b'\n')
        .map_or(&[][..], |i| &body[i + 1..]);
    let mut text = Vec::with_capacity(rest.len() + 8);
    text.extend_from_slice(b"solid x\n");
    text.extend_from_slice(rest);
    let mut cursor = std::io::Cursor::new(text);
    let reader = stl_io::create_stl_reader(&mut cursor)
        .map_err(|e| MeshError::parse(FORMAT, e.to_string()))?;
    let mut raw = RawMesh::default();
    for tri in reader {
        let tri = tri.map_err(|e| MeshError::parse(FORMAT, e.to_string()))?;
        let first = u32::try_from(raw.vertices.len())
            .map_err(|_| MeshError::parse(FORMAT, "too many triangles"))?;
        for v in tri.vertices {
            raw.vertices
                .push([f64::from(v[0]), f64::from(v[1]), f64::from(v[2])]);
        }
        raw.faces.push(vec![first, first + 1, first + 2]);
    }
    Ok(raw)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::mesh::{load_bytes, MeshFormat};

    /// The four faces of a tetrahedron, counter-clockwise from outside.
    pub(crate) const TETRA: [[[f32; 3]; 3]; 4] = [
        [[0., 0., 0.], [0., 1., 0.], [1., 0., 0.]],
        [[0., 0., 0.], [1., 0., 0.], [0., 0., 1.]],
        [[1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
        [[0., 0., 0.], [0., 0., 1.], [0., 1., 0.]],
    ];

    /// A binary STL of `tris` whose header starts with `header`.
    pub(crate) fn binary(header: &[u8], tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut b = vec![b' '; 80];
        b[..header.len()].copy_from_slice(header);
        b.extend_from_slice(&(tris.len() as u32).to_le_bytes());
        for t in tris {
            b.extend_from_slice(&[0u8; 12]);
            for v in t {
                for c in v {
                    b.extend_from_slice(&c.to_le_bytes());
                }
            }
            b.extend_from_slice(&[0, 0]);
        }
        b
    }

    pub(crate) fn ascii(first_line: &str, tris: &[[[f32; 3]; 3]]) -> String {
        let mut s = format!("{first_line}\n");
        for t in tris {
            s.push_str("  facet normal 0 0 0\n    outer loop\n");
            for v in t {
                s.push_str(&format!("      vertex {} {} {}\n", v[0], v[1], v[2]));
            }
            s.push_str("    endloop\n  endfacet\n");
        }
        s.push_str("endsolid x\n");
        s
    }

    #[test]
    fn binary_starting_with_solid_is_read_as_binary() {
        let b = binary(b"solid trap", &TETRA);
        let m = load_bytes(MeshFormat::Stl, &b).unwrap();
        assert_eq!(m.report.faces_read, 4);
        assert_eq!(m.report.welded_vertices, 12 - 4);
        assert!(m.closed);
    }

    #[test]
    fn ascii_starting_with_solid_is_read_as_ascii() {
        let text = ascii("solid tetra", &TETRA);
        let m = load_bytes(MeshFormat::Stl, text.as_bytes()).unwrap();
        assert_eq!(m.report.faces_read, 4);
        assert!(m.closed);
        // Bare "solid", leading blank lines and CRLF.
        let text = format!("\r\n{}", ascii("solid", &TETRA).replace('\n', "\r\n"));
        assert_eq!(parse(text.as_bytes()).unwrap().faces.len(), 4);
    }

    #[test]
    fn binary_and_ascii_give_the_same_polygons() {
        let a = load_bytes(MeshFormat::Stl, ascii("solid a", &TETRA).as_bytes()).unwrap();
        let b = load_bytes(MeshFormat::Stl, &binary(b"", &TETRA)).unwrap();
        assert_eq!(a.polygons, b.polygons);
    }

    #[test]
    fn a_byte_too_many_makes_it_not_binary() {
        let mut b = binary(b"solid x", &TETRA);
        b.push(b'\n');
        // Now judged ASCII; its binary body is not valid ASCII STL.
        assert!(matches!(
            parse(&b),
            Err(MeshError::Parse { format: "STL", .. })
        ));
        let mut b = binary(b"binary", &TETRA);
        b.push(0);
        let e = parse(&b).unwrap_err();
        assert!(e.to_string().contains("neither binary"), "{e}");
    }

    #[test]
    fn empty_and_truncated() {
        assert!(matches!(
            load_bytes(MeshFormat::Stl, &binary(b"solid", &[])),
            Err(MeshError::NoFaces { .. })
        ));
        assert!(parse(b"").is_err());
        let text = ascii("solid t", &TETRA);
        assert!(parse(&text.as_bytes()[..text.len() / 2]).is_err());
    }

    #[test]
    fn binary_keeps_the_winding() {
        let m = load_bytes(MeshFormat::Stl, &binary(b"", &TETRA[..1])).unwrap();
        // (0,0,0) (0,1,0) (1,0,0) is clockwise seen from +z: normal -z.
        assert!(m.polygons[0].plane.normal.z < -0.99);
    }
}
