//! What decoding a tree's polygons and vertices needs (`Geometry`, copied
//! into every [`PolygonRef`]) and where the fields of a compact record
//! sit (`CompactFields`). Split out of `reader.rs`, which makes a
//! `Geometry` once in [`Tree::from_bytes`].

#[cfg(doc)]
use super::{PolygonRef, Tree};
use super::{RawVertex, VertexDecoder, VertexFormat, VertexIndices};
use crate::format::{
    polygon as pg, rd, rd_f32x3, rd_i16, rd_i32, rd_u16, rd_u32, rd_u64, rd_u8, table_run as tr,
    COLOUR_LEN, EDGE_LEN, HEADER_LEN, LAYOUT_LEN, Q16_MAX, RUN_LEN, TABLE_RUN_LEN,
};
#[cfg(doc)]
use crate::format::{FLAG_COMPACT, FLAG_NARROW, FLAG_PLANES};
/// What decoding a vertex needs; copied into every [`PolygonRef`].
#[derive(Clone, Copy, Debug)]
pub(super) struct Geometry<'a> {
    pub(super) bytes: &'a [u8],
    /// Whether the edge section is present (it starts after the index
    /// list, see [`Geometry::edge_record`]). A flag, not a slice: this
    /// struct is copied into every polygon the walk hands out, and two
    /// more words cost 3.8 % of a `bench_city` frame on the Cortex-M4.
    pub(super) has_edges: bool,
    /// Whether the polygon records are compact ([`FLAG_COMPACT`]): 8
    /// bytes, bit fields described by `fields`, colours in a table.
    pub(super) compact: bool,
    /// The compact layout's fields (first_index, run, source, colour
    /// index), each as where it starts in the record and the mask of its
    /// width: computed once from the layout section, so that reading a
    /// field in the walk is one shift and one mask (adding up the widths
    /// and building the mask for every field read cost the Cortex-M4F
    /// walk 1.6–2.0 % of a frame). All zero for 16-byte records.
    pub(super) fields: CompactFields,
    /// Bytes of one polygon record: 16, 8 for compact records, the
    /// layout's record_len with [`FLAG_NARROW`]. A byte, like the next
    /// field: this struct is copied into every [`PolygonRef`].
    pub(super) rec_len: u8,
    pub(super) vertices: usize,
    pub(super) polygons: usize,
    pub(super) indices: usize,
    /// The section a polygon's run field indexes for its plane: the run
    /// records, or the plane table ([`FLAG_PLANES`], where that field is
    /// a plane index).
    pub(super) planes: &'a [u8],
    /// Bytes of one entry of `planes` (the plane at its start), 8 for
    /// compact entries ([`crate::format::FLAG_COMPACT_PLANES`]).
    pub(super) plane_len: u8,
    /// The run records (read for a polygon's plane index with a plane
    /// table, see [`Geometry::plane_index`]).
    pub(super) runs: &'a [u8],

    pub(super) polygon_count: u32,
    pub(super) index_count: u32,
    pub(super) format: VertexFormat,
    pub(super) index_size: u8,
    pub(super) shift: u8,
    pub(super) origin: [f64; 3],
    pub(super) half_extent: [f32; 3],
    /// `half_extent / 32767`, per axis.
    pub(super) q16_scale: [f32; 3],
    /// `2^-shift`.
    pub(super) q32_scale: f32,
}

/// Where each field of a compact polygon record starts and the mask of its
/// width (see [`Geometry::compact_field`]).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct CompactFields {
    /// First bit of first_index, run, source, colour index and
    /// hidden_edges.
    pub(super) shift: [u8; 5],
    /// `2^width − 1` of the first four.
    pub(super) mask: [u32; 4],
    /// `2^width − 1` of hidden_edges (at most 8 bits).
    pub(super) hidden_mask: u8,
}

impl CompactFields {
    /// The fields of a layout with these widths (each ≤ 32: validated by
    /// the caller; a wider one would only give a wrong mask, not a panic).
    pub(super) fn new(widths: [u8; 5]) -> CompactFields {
        let mut f = CompactFields::default();
        let mut at = 0u8;
        let mut masks = [0u32; 5];
        for ((shift, mask), &w) in f.shift.iter_mut().zip(&mut masks).zip(&widths) {
            *shift = at;
            *mask = 1u64.wrapping_shl(u32::from(w)).wrapping_sub(1) as u32;
            at = at.wrapping_add(w);
        }
        f.mask = [masks[0], masks[1], masks[2], masks[3]];
        f.hidden_mask = masks[4] as u8;
        f
    }

    /// Bits used by the first four fields together.
    pub(super) fn used_bits(&self) -> u32 {
        u32::from(self.shift[3]) + self.mask[3].count_ones()
    }

    /// Bits used by all five fields (hidden_edges included).
    pub(super) fn record_bits(&self) -> u32 {
        u32::from(self.shift[4]) + self.hidden_mask.count_ones()
    }
}

impl<'a> Geometry<'a> {
    #[inline]
    pub(super) fn index(&self, j: u32) -> u32 {
        let j = j as usize;
        if self.index_size == 2 {
            u32::from(rd_u16(
                self.bytes,
                self.indices.wrapping_add(j.wrapping_mul(2)),
            ))
        } else {
            rd_u32(self.bytes, self.indices.wrapping_add(j.wrapping_mul(4)))
        }
    }

    #[inline]
    pub(super) fn vertex_off(&self, v: u32) -> usize {
        self.vertices
            .wrapping_add((v as usize).wrapping_mul(self.format.vertex_len()))
    }

    #[inline]
    pub(super) fn raw(&self, v: u32) -> RawVertex {
        let (b, o) = (self.bytes, self.vertex_off(v));
        match self.format {
            VertexFormat::F32 => RawVertex::F32(rd_f32x3(b, o)),
            VertexFormat::Q16 => RawVertex::Q16([
                rd_i16(b, o),
                rd_i16(b, o.wrapping_add(2)),
                rd_i16(b, o.wrapping_add(4)),
            ]),
            VertexFormat::Q32 => RawVertex::Q32([
                rd_i32(b, o),
                rd_i32(b, o.wrapping_add(4)),
                rd_i32(b, o.wrapping_add(8)),
            ]),
        }
    }

    #[inline]
    pub(super) fn decoder(&self) -> VertexDecoder<'a> {
        let section = self.bytes.get(self.vertices..).unwrap_or(&[]);
        VertexDecoder {
            section,
            f32s: match self.format {
                VertexFormat::F32 => section.as_chunks::<12>().0,
                _ => &[],
            },
            q16s: &[],
            format: self.format,
            q16_scale: self.q16_scale,
            q32_scale: self.q32_scale,
            scale: 1.0,
        }
    }

    #[inline]
    pub(super) fn decode(&self, r: RawVertex) -> [f32; 3] {
        match r {
            RawVertex::F32(p) => p,
            RawVertex::Q16(q) => {
                let s = self.q16_scale;
                [
                    f32::from(q[0]) * s[0],
                    f32::from(q[1]) * s[1],
                    f32::from(q[2]) * s[2],
                ]
            }
            RawVertex::Q32(q) => q.map(|c| c as f32 * self.q32_scale),
        }
    }

    /// Model coordinates, decoded in `f64` (exact for `q32`).
    pub(super) fn decode_model(&self, r: RawVertex) -> [f64; 3] {
        let rel = match r {
            RawVertex::F32(p) => p.map(f64::from),
            RawVertex::Q16(q) => {
                let mut o = [0.0; 3];
                for a in 0..3 {
                    o[a] = f64::from(self.half_extent[a]) * f64::from(q[a]) / f64::from(Q16_MAX);
                }
                o
            }
            RawVertex::Q32(q) => {
                // 2^-shift exactly, built from its bits (shift ≤ 126).
                let s = f64::from_bits((1023 - u64::from(self.shift)) << 52);
                q.map(|c| f64::from(c) * s)
            }
        };
        [
            self.origin[0] + rel[0],
            self.origin[1] + rel[1],
            self.origin[2] + rel[2],
        ]
    }

    /// Record `j` of the edge section, `None` without it or past its end.
    #[inline]
    pub(super) fn edge_record(&self, j: usize) -> Option<[u8; EDGE_LEN]> {
        if !self.has_edges || j >= self.index_count as usize {
            return None;
        }
        // The section follows the index list, padded to 4 bytes.
        let end = self
            .indices
            .checked_add((self.index_count as usize).checked_mul(usize::from(self.index_size))?)?;
        let start = end.checked_add(3)? & !3;
        let at = start.checked_add(j.checked_mul(EDGE_LEN)?)?;
        self.bytes
            .get(at..at.checked_add(EDGE_LEN)?)?
            .try_into()
            .ok()
    }

    #[inline]
    pub(super) fn polygon_off(&self, id: u32) -> usize {
        self.polygons
            .wrapping_add((id as usize).wrapping_mul(usize::from(self.rec_len)))
    }

    /// Field `k` (0 first_index, 1 run, 2 source, 3 colour index) of the
    /// compact record of polygon `id`, with the shift and mask computed
    /// once per tree. Wrapping shifts: the widths are validated (each ≤ 32,
    /// sum ≤ 56), and a bug yields a wrong number, never a panic.
    #[inline(always)]
    pub(super) fn compact_field(&self, id: u32, k: usize) -> u32 {
        self.field_of(self.compact_record(id), k)
    }

    /// The compact record of polygon `id`, as one `u64` (0 past the end).
    #[inline(always)]
    pub(super) fn compact_record(&self, id: u32) -> u64 {
        rd_u64(self.bytes, self.polygon_off(id))
    }

    /// Field `k` of the compact record `r` (see [`Geometry::compact_field`];
    /// `k` = 4 is hidden_edges).
    #[inline(always)]
    pub(super) fn field_of(&self, r: u64, k: usize) -> u32 {
        let f = &self.fields;
        if k >= 4 {
            let h = r.wrapping_shr(u32::from(f.shift[4])) as u32;
            return h & u32::from(f.hidden_mask);
        }
        if k == 0 {
            // first_index starts at bit 0: no shift at all.
            return (r as u32) & f.mask[0];
        }
        (r.wrapping_shr(u32::from(f.shift[k])) as u32) & f.mask[k]
    }

    /// Field `k` of polygon `id` (see [`Geometry::compact_field`]), at byte
    /// `wide` of a 16-byte record.
    #[inline(always)]
    pub(super) fn polygon_field(&self, id: u32, k: usize, wide: usize) -> u32 {
        if self.compact {
            self.compact_field(id, k)
        } else {
            rd_u32(self.bytes, self.polygon_off(id).wrapping_add(wide))
        }
    }

    /// The run field of polygon `id`.
    #[inline]
    pub(super) fn polygon_run(&self, id: u32) -> u32 {
        self.polygon_field(id, 1, pg::RUN)
    }

    /// Whether the file has a plane table ([`FLAG_PLANES`]): a constant
    /// false without the plane-table features.
    #[inline(always)]
    pub(super) fn has_table(&self) -> bool {
        cfg!(any(feature = "plane-table", feature = "compact-planes"))
            && usize::from(self.plane_len) != RUN_LEN
    }

    /// The index of polygon `id`'s entry in the plane table, from its run
    /// field `field`, a run offset ([`crate::format::FLAG_RUN_OFFSETS`]):
    /// the plane index in the record of its run `id − field`. Any value
    /// on a corrupt file (a read out of range is 0); validation checks
    /// that every polygon's offset names its run. Without a table the
    /// field is the run, whose record holds the plane.
    ///
    /// Run offsets go with the table only, so that the test of them is
    /// the table's, a constant without the plane-table features: a flag
    /// of their own tested in the draw loop cost the Cortex-M4F socket
    /// frame of a narrow tree 0.6 to 1.1 % (session 26).
    #[inline(always)]
    pub(super) fn plane_index(&self, id: u32, field: u32) -> u32 {
        let run = id.wrapping_sub(field) as usize;
        // The records as such: one comparison for the run (a read at an
        // offset in the file was two more and an overflow test, for each
        // drawn polygon).
        let (recs, _) = self.runs.as_chunks::<TABLE_RUN_LEN>();
        let r = recs.get(run).unwrap_or(&[0; TABLE_RUN_LEN]);
        u32::from(u16::from_le_bytes([r[tr::PLANE], r[tr::PLANE + 1]]))
    }

    /// The first_index field of polygon `id`.
    #[inline]
    pub(super) fn polygon_first(&self, id: u32) -> u32 {
        self.polygon_field(id, 0, pg::FIRST_INDEX)
    }

    /// The source field of polygon `id`.
    #[inline]
    pub(super) fn polygon_source(&self, id: u32) -> u32 {
        self.polygon_field(id, 2, pg::SOURCE)
    }

    /// The colour index of a compact polygon `id` (0 otherwise).
    #[inline]
    pub(super) fn polygon_colour_index(&self, id: u32) -> u32 {
        if self.compact {
            self.compact_field(id, 3)
        } else {
            0
        }
    }

    /// The colour of polygon `id`: from the colour table of a compact
    /// file, which starts at a fixed offset after the layout.
    #[inline]
    pub(super) fn polygon_color(&self, id: u32) -> [u8; 3] {
        if self.compact {
            self.table_colour(self.polygon_colour_index(id))
        } else {
            let c: [u8; 4] = rd(self.bytes, self.polygon_off(id).wrapping_add(pg::COLOR));
            [c[0], c[1], c[2]]
        }
    }

    /// Entry `c` of a compact file's colour table, which starts at a fixed
    /// offset after the layout.
    #[inline(always)]
    pub(super) fn table_colour(&self, c: u32) -> [u8; 3] {
        let at = (HEADER_LEN + LAYOUT_LEN).wrapping_add((c as usize).wrapping_mul(COLOUR_LEN));
        // Four bytes, one load: the table is padded to 4 bytes and the
        // vertices follow it, so the fourth is always in the file.
        let c: [u8; 4] = rd(self.bytes, at);
        [c[0], c[1], c[2]]
    }

    /// The hidden_edges mask of polygon `id`.
    #[inline]
    pub(super) fn polygon_hidden(&self, id: u32) -> u8 {
        if self.compact {
            self.compact_field(id, 4) as u8
        } else {
            rd_u8(self.bytes, self.polygon_off(id).wrapping_add(pg::COLOR + 3))
        }
    }

    /// Index-list entries `first..first + count` (empty when out of range).
    #[inline]
    pub(super) fn indices_of(&self, first: u32, count: u32) -> VertexIndices<'a> {
        let size = usize::from(self.index_size);
        let lo = self
            .indices
            .wrapping_add((first as usize).wrapping_mul(size));
        let hi = lo.wrapping_add((count as usize).wrapping_mul(size));
        VertexIndices {
            indices: self.bytes.get(lo..hi).unwrap_or(&[]),
            wide: size == 4,
        }
    }

    /// The index range `first..end` of polygon `id < polygon_count`.
    #[inline]
    pub(super) fn polygon_range(&self, id: u32) -> (u32, u32) {
        let first = self.polygon_first(id);
        let end = if id < self.polygon_count.saturating_sub(1) {
            self.polygon_first(id.wrapping_add(1))
        } else {
            self.index_count
        };
        (first, end)
    }
}
