//! A plane and a stored vertex as the reader hands them out (split out of
//! `reader.rs`).

use crate::format::le_f32;

/// A plane `normal · (x − origin) + d = 0`, relative to the tree's origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal, pointing to the front side.
    pub normal: [f32; 3],
    /// Offset relative to the origin.
    pub d: f32,
}

impl Plane {
    /// `normal · p + d` for a point `p` relative to the origin: positive on
    /// the front side.
    #[inline]
    pub fn eval(&self, p: [f32; 3]) -> f32 {
        self.normal_dot(p) + self.d
    }

    /// `normal · v`.
    #[inline]
    pub fn normal_dot(&self, v: [f32; 3]) -> f32 {
        self.normal[0] * v[0] + self.normal[1] * v[1] + self.normal[2] * v[2]
    }

    pub(super) fn is_finite(&self) -> bool {
        self.normal.iter().all(|x| x.is_finite()) && self.d.is_finite()
    }

    /// The plane of a 16-byte record: normal, then offset.
    #[inline(always)]
    pub(super) fn from_record<const L: usize>(r: &[u8; L]) -> Plane {
        Plane {
            normal: [le_f32(r, 0), le_f32(r, 4), le_f32(r, 8)],
            d: le_f32(r, 12),
        }
    }
}

/// A vertex as stored, before decoding (see [`crate::format::VertexFormat`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RawVertex {
    /// `f32` offset from the origin.
    F32([f32; 3]),
    /// `q16`: offset `half_extent[axis] · q / 32767`.
    Q16([i16; 3]),
    /// `q32`: offset `q · 2^-shift`.
    Q32([i32; 3]),
}
