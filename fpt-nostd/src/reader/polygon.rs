//! One polygon of a [`Tree`]: [`PolygonRef`], what the public API hands
//! out (it carries a copy of the vertex decoder), and `PolygonAt`, what
//! the draw loops read (it borrows the decoder instead; see its docs for
//! why). Split out of `reader.rs`, whose [`Tree`] makes both.

#[cfg(doc)]
use super::Tree;
use super::{Geometry, Plane, RawVertex, VertexFormat, VertexIndices, Vertices};
#[cfg(feature = "compact-planes")]
use crate::format::{compact_plane, le_u32, plane_unit, rec, COMPACT_PLANE_LEN};
use crate::format::{plane_at, RUN_LEN};
use crate::raster::Normal;
/// One polygon of a [`Tree`].
#[derive(Clone, Copy, Debug)]
pub struct PolygonRef<'a> {
    pub(super) g: Geometry<'a>,
    pub(super) id: u32,
    pub(super) first: u32,
    pub(super) count: u32,
}

impl<'a> PolygonRef<'a> {
    /// Its id: its position in the file.
    pub fn id(&self) -> u32 {
        self.id
    }

    /// The same polygon borrowing this one's copy of the geometry.
    #[inline]
    fn at(&self) -> PolygonAt<'_, 'a> {
        PolygonAt::new(&self.g, self.id)
    }

    /// The face of the input mesh it came from.
    pub fn source(&self) -> u32 {
        self.at().source()
    }

    /// Its colour, RGB.
    pub fn color(&self) -> [u8; 3] {
        self.at().color()
    }

    /// Its outline mask: bit `i` set when edge `i` (vertex `i` to `i + 1`)
    /// lies inside its source face (see [`crate::format`]).
    pub fn hidden_edges(&self) -> u8 {
        self.g.polygon_hidden(self.id)
    }

    /// Whether its tree has the edge section (see [`PolygonRef::edge`]).
    #[inline]
    pub fn has_edges(&self) -> bool {
        self.g.has_edges
    }

    /// The edge record of edge `i` (vertex `i` to `i + 1`): its kind
    /// ([`crate::format::EDGE_DRAWN`], `EDGE_HIDDEN` or `EDGE_SOFT`) and
    /// the neighbour's normal (times 127). `None` without the edge section
    /// or past the polygon's last edge.
    #[inline]
    pub fn edge(&self, i: usize) -> Option<(u8, [i8; 3])> {
        if i >= self.count as usize {
            return None;
        }
        let j = (self.first as usize).checked_add(i)?;
        let r = self.g.edge_record(j)?;
        Some((r[3], [r[0] as i8, r[1] as i8, r[2] as i8]))
    }

    /// Its plane, relative to the origin (the plane of its run).
    pub fn plane(&self) -> Plane {
        self.at().plane()
    }

    /// Number of vertices (at least 3).
    pub fn vertex_count(&self) -> usize {
        self.count as usize
    }

    /// Index of its vertex `i` in the tree's vertex section (shared between
    /// polygons, so a renderer can transform each vertex once); 0 when
    /// `i ≥ vertex_count()`.
    pub fn vertex_index(&self, i: usize) -> u32 {
        if i >= self.count as usize {
            return 0;
        }
        self.g.index(self.first.wrapping_add(i as u32))
    }

    /// Vertex `i`, relative to the origin, decoded to `f32`; `[0.0; 3]` when
    /// `i ≥ vertex_count()`.
    pub fn vertex(&self, i: usize) -> [f32; 3] {
        self.g.decode(self.vertex_raw(i))
    }

    /// Vertex `i` as stored, for a fixed-point pipeline; zero in the tree's
    /// format when `i ≥ vertex_count()`.
    pub fn vertex_raw(&self, i: usize) -> RawVertex {
        if i >= self.count as usize {
            return zero_raw(self.g.format);
        }
        self.g.raw(self.vertex_index(i))
    }

    /// Its vertices in order, relative to the origin, decoded like
    /// [`PolygonRef::vertex`]: the fast path for drawing. The polygon's index range and the vertex section
    /// are sliced once; each vertex then costs one range check on its
    /// index and one on its record (both always pass on a validated tree;
    /// a failing one yields the origin, as [`PolygonRef::vertex`] does).
    pub fn vertices(&self) -> Vertices<'a> {
        Vertices {
            indices: self.vertex_indices(),
            dec: self.g.decoder(),
        }
    }

    /// The indices of its vertices in the tree's vertex section, in order
    /// (what [`PolygonRef::vertex_index`] gives for each `i`): the key of
    /// a per-frame vertex cache.
    pub fn vertex_indices(&self) -> VertexIndices<'a> {
        self.g.indices_of(self.first, self.count)
    }

    /// Vertex `i` in model coordinates (origin + offset, in `f64`, exact for
    /// every format); the origin when `i ≥ vertex_count()`.
    pub fn vertex_model(&self, i: usize) -> [f64; 3] {
        self.g.decode_model(self.vertex_raw(i))
    }
}

/// Polygon `id` of a tree as the draw loops read it: what [`PolygonRef`]
/// gives of it (id, source, colour, plane, vertex indices), borrowing the
/// tree's geometry instead of copying it. A `PolygonRef` carries a copy of
/// the geometry (about 100 bytes); the full frame's walk, where the whole
/// pipeline is inlined, made that copy with `memcpy` for every polygon
/// (10 % of a `socket.off` frame on the Cortex-M4F).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PolygonAt<'t, 'a> {
    g: &'t Geometry<'a>,
    id: u32,
    /// Its compact record, read once when it is made (0 for 16-byte
    /// records): a draw reads four of its fields (plane, colour, source,
    /// first index), and loading and range-checking the record for each
    /// cost the Cortex-M4F frame more than the bit fields themselves.
    rec: u64,
    /// The low 32 bits of the next polygon's compact record (read with
    /// this one's: its first index ends this one's index range); unused
    /// for the last polygon.
    next: u32,
    /// With a plane table, the index of its plane entry (see
    /// [`Geometry::plane_index`]; else 0): read where the record is, while
    /// the id is at hand (read in [`PolygonAt::plane`], which then needed
    /// the id too, it cost the Cortex-M4F socket frame 0.35 % more).
    table_plane: u32,
}

impl<'t, 'a> PolygonAt<'t, 'a> {
    /// Its id.
    #[inline]
    pub(crate) fn id(&self) -> u32 {
        self.id
    }

    /// Polygon `id` of `g`, its compact record read once.
    #[inline(always)]
    pub(super) fn new(g: &'t Geometry<'a>, id: u32) -> PolygonAt<'t, 'a> {
        let (rec, next) = if g.compact {
            // Both records in one read: the polygon section is followed by
            // at least the index list, so 16 bytes from the last record
            // are still in the file (and `next` is then unused). Eight
            // bytes each, whatever the record length (≤ 8): the fields'
            // masks drop the next record's bits.
            // Borrowed, not copied: the next record's bytes are then read
            // straight from the file (a copy to the stack, to be read at a
            // variable offset, cost more than the bit fields).
            let off = g.polygon_off(id);
            let r: &[u8; 16] = off
                .checked_add(16)
                .and_then(|end| g.bytes.get(off..end))
                .and_then(|s| s.try_into().ok())
                .unwrap_or(&[0; 16]);
            // The next record starts `rec_len` (1 to 8) bytes in: written
            // so that the compiler sees it is at most 8, and the slice
            // below needs no check (a general variable slice of `r` cost
            // the Cortex-M4F frame 0.2 %). Only its first index is read,
            // which is at most 32 bits from its start.
            let at = usize::from(g.rec_len.wrapping_sub(1) & 7) + 1;
            let lo: [u8; 8] = r.get(..8).and_then(|h| h.try_into().ok()).unwrap_or([0; 8]);
            let nx: [u8; 4] = r
                .get(at..at + 4)
                .and_then(|h| h.try_into().ok())
                .unwrap_or([0; 4]);
            (u64::from_le_bytes(lo), u32::from_le_bytes(nx))
        } else {
            (0, 0)
        };
        let table_plane = if g.has_table() {
            g.plane_index(id, g.field_of(rec, 1))
        } else {
            0
        };
        PolygonAt {
            g,
            id,
            rec,
            next,
            table_plane,
        }
    }

    /// [`PolygonRef::source`].
    #[inline]
    pub(crate) fn source(&self) -> u32 {
        if self.g.compact {
            self.g.field_of(self.rec, 2)
        } else {
            self.g.polygon_source(self.id)
        }
    }

    /// [`PolygonRef::color`].
    #[inline]
    pub(crate) fn color(&self) -> [u8; 3] {
        if self.g.compact {
            self.g.table_colour(self.g.field_of(self.rec, 3))
        } else {
            self.g.polygon_color(self.id)
        }
    }

    /// The index of its plane: a plane table entry's (read with the
    /// record), else its run's.
    #[inline(always)]
    fn plane_index(&self) -> u32 {
        if self.g.has_table() {
            self.table_plane
        } else if self.g.compact {
            self.g.field_of(self.rec, 1)
        } else {
            self.g.polygon_run(self.id)
        }
    }

    /// [`PolygonRef::plane`].
    #[inline]
    pub(crate) fn plane(&self) -> Plane {
        let r = self.plane_index();
        // A constant record length without the `plane-table` feature.
        let len = if cfg!(any(feature = "plane-table", feature = "compact-planes")) {
            usize::from(self.g.plane_len)
        } else {
            RUN_LEN
        };
        let at = (r as usize).wrapping_mul(len);
        #[cfg(feature = "compact-planes")]
        if len == COMPACT_PLANE_LEN {
            let entry = rec::<COMPACT_PLANE_LEN>(self.g.planes, r as usize);
            let (normal, d) = compact_plane(&entry, plane_unit(self.g.half_extent));
            return Plane { normal, d };
        }
        Plane::from_record(plane_at(self.g.planes, at))
    }

    /// The normal lighting reads: a compact plane entry's integers as
    /// stored (no conversion to `f32`: on a core without an FPU its four
    /// software conversions and products were a tenth of a frame, for a
    /// Q14 rounding that is exact in integers), else the plane's normal.
    #[inline(always)]
    pub(crate) fn normal(&self) -> Normal {
        #[cfg(feature = "compact-planes")]
        if self.g.plane_len == COMPACT_PLANE_LEN as u8 {
            // The table as entries: one comparison for the index (`rec`'s
            // overflow and range tests were more a drawn polygon).
            let (entries, _) = self.g.planes.as_chunks::<COMPACT_PLANE_LEN>();
            let entry = entries
                .get(self.plane_index() as usize)
                .unwrap_or(&[0; COMPACT_PLANE_LEN]);
            return Normal::from_entry_words(le_u32(entry, 0), le_u32(entry, 4));
        }
        Normal::from_f32(self.plane().normal)
    }

    /// [`PolygonRef::vertex_indices`].
    #[inline]
    pub(crate) fn vertex_indices(&self) -> VertexIndices<'a> {
        let (first, end) = if self.g.compact {
            let first = self.g.field_of(self.rec, 0);
            let end = if self.id < self.g.polygon_count.saturating_sub(1) {
                self.g.field_of(u64::from(self.next), 0)
            } else {
                self.g.index_count
            };
            (first, end)
        } else {
            self.g.polygon_range(self.id)
        };
        self.g.indices_of(first, end.saturating_sub(first))
    }
}

fn zero_raw(f: VertexFormat) -> RawVertex {
    match f {
        VertexFormat::F32 => RawVertex::F32([0.0; 3]),
        VertexFormat::Q16 => RawVertex::Q16([0; 3]),
        VertexFormat::Q32 => RawVertex::Q32([0; 3]),
    }
}
