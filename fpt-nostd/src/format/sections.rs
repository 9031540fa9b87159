//! Where each section of a tree file starts, computed from the header's
//! counts.
//!
//! The one place that turns the counts of [`Counts`] (and, for compact
//! files, the sizes of [`Records`]) into byte offsets: the serializer lays
//! a file out with [`Sections`], and the reader checks that the file's
//! length equals [`Sections::file_len`] before it reads any section, so the
//! writer and the reader cannot disagree on the layout. Every section is
//! padded to a multiple of 4 bytes; see the parent module for the order.

use super::{
    VertexFormat, COLOUR_LEN, COMPACT_PLANE_LEN, COMPACT_POLYGON_LEN, CRC_LEN, EDGE_LEN,
    HEADER_LEN, LAYOUT_LEN, NARROW_LEN, NODE_LEN, NORMAL_LEN, PLANE_LEN, POLYGON_LEN, RUN_LEN,
    SMALL_NODE_LEN, SWITCH_LEN, SWITCH_REF_LEN, TABLE_RUN_LEN,
};
#[cfg(doc)]
use super::{FLAG_COMPACT, FLAG_COMPACT_PLANES, FLAG_NARROW, FLAG_PLANES, FLAG_SMALL};

/// Entry counts of the sections, as stored in the header.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Vertices.
    pub vertices: u32,
    /// Polygons.
    pub polygons: u32,
    /// Vertex indices.
    pub indices: u32,
    /// Bunches.
    pub bunches: u32,
    /// Connecting nodes.
    pub nodes: u32,
    /// Switch nodes.
    pub switches: u32,
    /// Runs of polygons sharing a plane.
    pub runs: u32,
    /// Edge records: 0 without the edge section, else the index count.
    pub edges: u32,
    /// Corner normal records: 0 without the normal section, else the
    /// index count.
    pub normals: u32,
    /// Small walk records ([`FLAG_SMALL`]): `u16` bunch offsets and
    /// 8-byte node records.
    pub small: bool,
}

/// What compact polygon records add to a file's sections (see
/// [`Sections::with_records`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Records {
    /// Entries in the colour table.
    pub colours: u32,
    /// With [`FLAG_NARROW`]: the record length and the extra planes.
    pub narrow: Option<Narrow>,
}

/// The sizes [`FLAG_NARROW`] sets (from its 16-byte layout section).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Narrow {
    /// Bytes of one polygon record, 1 to 8.
    pub record_len: u8,
    /// Plane records after the runs: the switch planes that no run has;
    /// with `table`, the entries of the plane table instead.
    pub extra_planes: u32,
    /// A shared plane table ([`FLAG_PLANES`]): `extra_planes` planes of
    /// [`PLANE_LEN`] bytes before the runs, runs of [`TABLE_RUN_LEN`].
    pub table: bool,
    /// With `table`: compact entries of [`COMPACT_PLANE_LEN`] bytes
    /// ([`FLAG_COMPACT_PLANES`]).
    pub compact_planes: bool,
}

/// Byte offsets of the sections of a file, computed from its counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sections {
    /// Start of the layout section (where the vertices start in a file
    /// without compact records).
    pub layout: usize,
    /// Start of the colour table (ditto).
    pub colours: usize,
    /// Start of the narrow layout section ([`FLAG_NARROW`]; where the
    /// vertices start without it).
    pub narrow: usize,
    /// Start of the vertex section.
    pub vertices: usize,
    /// Start of the polygon section.
    pub polygons: usize,
    /// Start of the index list.
    pub indices: usize,
    /// Start of the edge section (where the next section starts when it
    /// is absent).
    pub edges: usize,
    /// Start of the corner normal section (where the plane table or the
    /// runs start when it is absent).
    pub normals: usize,
    /// Start of the plane table ([`FLAG_PLANES`]; where the runs start
    /// without it).
    pub planes: usize,
    /// Start of the runs.
    pub runs: usize,
    /// Start of the bunch offsets.
    pub bunches: usize,
    /// Start of the connecting nodes.
    pub nodes: usize,
    /// Start of the switch nodes.
    pub switches: usize,
    /// Start of the checksum.
    pub crc: usize,
    /// Length of the whole file.
    pub file_len: usize,
}

impl Sections {
    /// The layout of a file with `counts`, `format` vertices and indices of
    /// `index_size` bytes; `None` if its length overflows `u32`.
    pub fn new(counts: &Counts, format: VertexFormat, index_size: usize) -> Option<Sections> {
        Sections::with_compact(counts, format, index_size, None)
    }

    /// The layout of a file as [`Sections::new`], with compact polygon
    /// records and a colour table of `colours` entries when `colours` is
    /// `Some` ([`FLAG_COMPACT`]).
    pub fn with_compact(
        counts: &Counts,
        format: VertexFormat,
        index_size: usize,
        colours: Option<u32>,
    ) -> Option<Sections> {
        let records = colours.map(|colours| Records {
            colours,
            narrow: None,
        });
        Sections::with_records(counts, format, index_size, records.as_ref())
    }

    /// The layout of a file as [`Sections::new`], with the compact records
    /// `records` describes (`None`: 16-byte records).
    pub fn with_records(
        counts: &Counts,
        format: VertexFormat,
        index_size: usize,
        records: Option<&Records>,
    ) -> Option<Sections> {
        // u64 arithmetic: every product of a u32 count and a record length
        // fits, so only the final length needs checking.
        fn next(start: u64, count: u32, len: usize) -> u64 {
            let end = start + u64::from(count) * len as u64;
            (end + 3) & !3
        }
        let l = HEADER_LEN as u64;
        let (ct, nw, v, poly_len) = match records {
            Some(r) => {
                let ct = l + LAYOUT_LEN as u64;
                let nw = next(ct, r.colours, COLOUR_LEN);
                match r.narrow {
                    Some(n) => (ct, nw, nw + NARROW_LEN as u64, usize::from(n.record_len)),
                    None => (ct, nw, nw, COMPACT_POLYGON_LEN),
                }
            }
            None => (l, l, l, POLYGON_LEN),
        };
        // Shared switch planes: the plane records not of a run follow the
        // runs, and a switch record is the index of one; with a plane
        // table, every plane is in the table before the runs.
        let (table, extra, switch_len) = match records.and_then(|r| r.narrow) {
            Some(n) if n.table => (n.extra_planes, 0, SWITCH_REF_LEN),
            Some(n) => (0, n.extra_planes, SWITCH_REF_LEN),
            None => (0, 0, SWITCH_LEN),
        };
        let (run_len, plane_len) = match records.and_then(|r| r.narrow) {
            Some(n) if n.table && n.compact_planes => (TABLE_RUN_LEN, COMPACT_PLANE_LEN),
            Some(n) if n.table => (TABLE_RUN_LEN, PLANE_LEN),
            _ => (RUN_LEN, PLANE_LEN),
        };
        let plane_records = counts.runs.checked_add(extra)?;
        let p = next(v, counts.vertices, format.vertex_len());
        let i = next(p, counts.polygons, poly_len);
        let e = next(i, counts.indices, index_size);
        let nm = next(e, counts.edges, EDGE_LEN);
        let pt = next(nm, counts.normals, NORMAL_LEN);
        let r = next(pt, table, plane_len);
        let b = next(r, plane_records, run_len);
        let (bunch_len, node_len) = if counts.small {
            (2, SMALL_NODE_LEN)
        } else {
            (4, NODE_LEN)
        };
        let n = next(b, counts.bunches.checked_add(1)?, bunch_len);
        let s = next(n, counts.nodes, node_len);
        let c = next(s, counts.switches, switch_len);
        let end = c + CRC_LEN as u64;
        if end > u64::from(u32::MAX) {
            return None;
        }
        // Every value is ≤ end ≤ u32::MAX, so the conversions are exact on
        // targets with a usize of 32 bits or more.
        let cv = |x: u64| usize::try_from(x).ok();
        Some(Sections {
            layout: cv(l)?,
            colours: cv(ct)?,
            narrow: cv(nw)?,
            vertices: cv(v)?,
            polygons: cv(p)?,
            indices: cv(i)?,
            edges: cv(e)?,
            normals: cv(nm)?,
            planes: cv(pt)?,
            runs: cv(r)?,
            bunches: cv(b)?,
            nodes: cv(n)?,
            switches: cv(s)?,
            crc: cv(c)?,
            file_len: cv(end)?,
        })
    }
}
