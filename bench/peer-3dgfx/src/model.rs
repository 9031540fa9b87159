//! The model in flash: `model.bin` from the build script, decoded at
//! compile time into the array types the peer's `Geometry` borrows
//! (`&[[f32; 3]]`, `&[[usize; 3]]`). Decoding in `const` keeps the arrays in
//! flash and needs no `unsafe` reinterpretation of the bytes.

use crate::config::{NF, NV};

/// Byte offsets of the three sections (see `build.rs`).
const VERTS_AT: usize = 8;
const TRIS_AT: usize = VERTS_AT + NV * 12;
const NORMALS_AT: usize = (TRIS_AT + NF * 6).div_ceil(4) * 4;

/// Vertices, world units, relative to the bounding-sphere centre.
pub static VERTICES: [[f32; 3]; NV] = f32x3::<NV>(VERTS_AT);
/// Triangles (counter-clockwise seen from outside).
pub static FACES: [[usize; 3]; NF] = faces();
/// Unit outward face normals.
pub static NORMALS: [[f32; 3]; NF] = f32x3::<NF>(NORMALS_AT);

const fn u32_at(at: usize) -> u32 {
    u32::from_le_bytes([BIN_C[at], BIN_C[at + 1], BIN_C[at + 2], BIN_C[at + 3]])
}

/// `model.bin`, read only at compile time (a `static` could not be read
/// in `const` code; the bytes themselves are not kept in the image).
const BIN_C: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/model.bin"));

const fn f32x3<const N: usize>(at: usize) -> [[f32; 3]; N] {
    let mut out = [[0.0; 3]; N];
    let mut i = 0;
    while i < N {
        let mut k = 0;
        while k < 3 {
            out[i][k] = f32::from_bits(u32_at(at + (i * 3 + k) * 4));
            k += 1;
        }
        i += 1;
    }
    out
}

const fn faces() -> [[usize; 3]; NF] {
    // The counts in the header must be the ones the arrays were sized with.
    assert!(u32_at(0) as usize == NV && u32_at(4) as usize == NF);
    let mut out = [[0; 3]; NF];
    let mut i = 0;
    while i < NF {
        let mut k = 0;
        while k < 3 {
            let at = TRIS_AT + (i * 3 + k) * 2;
            out[i][k] = u16::from_le_bytes([BIN_C[at], BIN_C[at + 1]]) as usize;
            k += 1;
        }
        i += 1;
    }
    out
}

/// The length of `model.bin` is what the three sections add up to.
const _: () = assert!(BIN_C.len() == NORMALS_AT + NF * 12);
