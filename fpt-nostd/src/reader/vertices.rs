//! Reading a polygon's vertices: its indices ([`VertexIndices`]), each
//! vertex decoded by index ([`VertexDecoder`]), or both at once
//! ([`Vertices`], the drawing loop's fast path). Every read is bounds
//! checked and yields the origin (or index 0) on a failure, which a
//! validated tree never has, so nothing here can panic.

use crate::format::VertexFormat;

/// The vertices of one polygon ([`super::PolygonRef::vertices`]).
#[derive(Clone, Debug)]
pub struct Vertices<'a> {
    pub(super) indices: VertexIndices<'a>,
    pub(super) dec: VertexDecoder<'a>,
}

/// Decodes vertices of a [`super::Tree`] by index, as [`Vertices`] does
/// ([`super::Tree::vertex_decoder`]): the fast path of a vertex cache's misses.
/// An index outside the section decodes to the origin (which a validated
/// tree never has).
#[derive(Clone, Copy, Debug)]
pub struct VertexDecoder<'a> {
    pub(super) section: &'a [u8],
    /// The section as 12-byte records when it holds `f32` vertices, else
    /// empty: an `f32` vertex is then one bounds check, which also stands
    /// for the test of the format (a cache miss's decode, once a vertex).
    pub(super) f32s: &'a [[u8; 12]],
    /// The section as 6-byte records when it holds `q16` vertices and the
    /// decoder reads them as stored ([`VertexDecoder::q16_as_stored`]),
    /// else empty.
    pub(super) q16s: &'a [[u8; 6]],
    pub(super) format: VertexFormat,
    pub(super) q16_scale: [f32; 3],
    pub(super) q32_scale: f32,
    /// What every decoded vertex is multiplied by (1 but in
    /// [`VertexDecoder::scaled`]'s).
    pub(super) scale: f32,
}

impl VertexDecoder<'_> {
    /// This decoder with every vertex multiplied by `s` as it is decoded
    /// (`x · s` rounded once, as a caller multiplying would): for a walk
    /// whose matrix does not take the scale and whose code multiplies
    /// nothing. Every vertex then takes the cold decode.
    #[must_use]
    pub(crate) fn scaled(self, s: f32) -> Self {
        VertexDecoder {
            f32s: &[],
            q16s: &[],
            scale: s,
            ..self
        }
    }

    /// This decoder with a q16 tree's vertices read as stored: each axis's
    /// `i16` converted to `f32` (exact), not multiplied by the per-axis
    /// scale, which the caller folds into its matrix instead
    /// ([`VertexDecoder::q16_scale`]): a float walk's decode without the
    /// cold call and its six multiplications. Unchanged for another
    /// format (or a scaled decoder).
    #[must_use]
    pub(crate) fn q16_as_stored(self) -> Self {
        let q16s = match self.format {
            VertexFormat::Q16 if self.scale == 1.0 => self.section.as_chunks::<6>().0,
            _ => &[],
        };
        VertexDecoder { q16s, ..self }
    }

    /// What each axis of a q16 tree's stored values is multiplied by as
    /// [`VertexDecoder::get`] decodes them (`half_extent / 32767`).
    pub(crate) fn q16_scale(&self) -> [f32; 3] {
        self.q16_scale
    }

    /// Vertex `v` of a q16 tree as stored (`i16` per axis, widened);
    /// zero for another format or an index outside the section.
    #[inline]
    pub fn raw_q16(&self, v: usize) -> [i32; 3] {
        let at = v.wrapping_mul(6);
        match (self.format, self.section.get(at..at.wrapping_add(6))) {
            (VertexFormat::Q16, Some(&[a, b, c, d, e, f])) => [
                i32::from(i16::from_le_bytes([a, b])),
                i32::from(i16::from_le_bytes([c, d])),
                i32::from(i16::from_le_bytes([e, f])),
            ],
            _ => [0; 3],
        }
    }

    /// Vertex `v`, relative to the origin, decoded to `f32` (a q16 tree's
    /// as stored for a decoder made so: `VertexDecoder::q16_as_stored`).
    #[inline]
    pub fn get(&self, v: usize) -> [f32; 3] {
        match self.f32s.get(v) {
            Some(r) => {
                let w = |k: usize| f32::from_le_bytes([r[k], r[k + 1], r[k + 2], r[k + 3]]);
                [w(0), w(4), w(8)]
            }
            None => self.get_packed(v),
        }
    }

    /// Vertex `v` of a decoder made by [`VertexDecoder::q16_as_stored`]:
    /// its stored values converted to `f32`, inline (the origin for
    /// another decoder or an index outside the section). For a loop over
    /// a q16 tree's vertices of its own (a proven frame's prefill).
    #[inline(always)]
    pub(crate) fn get_q16_as_stored(&self, v: usize) -> [f32; 3] {
        match self.q16s.get(v) {
            Some(&[a, b, c, d, e, f]) => {
                [[a, b], [c, d], [e, f]].map(|h| f32::from(i16::from_le_bytes(h)))
            }
            None => [0.0; 3],
        }
    }

    /// [`VertexDecoder::get`] of the formats other than `f32` (and of an
    /// index outside the section). Out of line and cold: the walks that
    /// inline `get` keep only the `f32` read (an inline q16 read there
    /// made the default trees' frames 1.1 % dearer, session 25). A q16
    /// tree's values as stored are read first: no format match, no
    /// multiplication.
    #[cold]
    #[inline(never)]
    fn get_packed(&self, v: usize) -> [f32; 3] {
        if v < self.q16s.len() {
            return self.get_q16_as_stored(v);
        }
        self.get_unscaled(v).map(|c| c * self.scale)
    }

    /// [`VertexDecoder::get_packed`] before the decoder's scale.
    #[inline(always)]
    fn get_unscaled(&self, v: usize) -> [f32; 3] {
        let at = v.wrapping_mul(self.format.vertex_len());
        let f = |r: &[u8], k: usize| -> [u8; 4] {
            let mut o = [0; 4];
            if let Some(s) = r.get(k..k + 4) {
                o.copy_from_slice(s);
            }
            o
        };
        match self.format {
            VertexFormat::F32 => match self.section.get(at..at.wrapping_add(12)) {
                Some(r) => [0, 4, 8].map(|k| f32::from_le_bytes(f(r, k))),
                None => [0.0; 3],
            },
            VertexFormat::Q32 => match self.section.get(at..at.wrapping_add(12)) {
                Some(r) => [0, 4, 8].map(|k| i32::from_le_bytes(f(r, k)) as f32 * self.q32_scale),
                None => [0.0; 3],
            },
            VertexFormat::Q16 => match self.section.get(at..at.wrapping_add(6)) {
                Some(r) => {
                    let q = |k: usize| f32::from(i16::from_le_bytes([r[k], r[k + 1]]));
                    [
                        q(0) * self.q16_scale[0],
                        q(2) * self.q16_scale[1],
                        q(4) * self.q16_scale[2],
                    ]
                }
                None => [0.0; 3],
            },
        }
    }
}

impl Iterator for Vertices<'_> {
    type Item = [f32; 3];

    #[inline]
    fn next(&mut self) -> Option<[f32; 3]> {
        let v = self.indices.next()?;
        Some(self.dec.get(v as usize))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.indices.indices.len() / if self.indices.wide { 4 } else { 2 };
        (n, Some(n))
    }
}

/// The vertex indices of one polygon ([`super::PolygonRef::vertex_indices`]).
#[derive(Clone, Debug)]
pub struct VertexIndices<'a> {
    pub(super) indices: &'a [u8],
    pub(super) wide: bool,
}

impl<'a> VertexIndices<'a> {
    /// The indices as stored when they are 2 bytes each (little-endian),
    /// `None` when they are 4: for a caller that reads them in a loop of
    /// its own (the band replay reads a polygon's indices in every band
    /// it touches; the iterator's per-index width test and slice
    /// splitting cost more than the reads).
    #[inline]
    pub(crate) fn narrow(&self) -> Option<&'a [u8]> {
        (!self.wide).then_some(self.indices)
    }
}

impl Iterator for VertexIndices<'_> {
    type Item = u32;

    #[inline]
    fn next(&mut self) -> Option<u32> {
        if self.wide {
            let (&[a, b, c, d], rest) = self.indices.split_first_chunk::<4>()?;
            self.indices = rest;
            Some(u32::from_le_bytes([a, b, c, d]))
        } else {
            let (&[a, b], rest) = self.indices.split_first_chunk::<2>()?;
            self.indices = rest;
            Some(u32::from(u16::from_le_bytes([a, b])))
        }
    }
}
