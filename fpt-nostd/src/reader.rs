//! The checked, allocation-free reader of a tree file.
//!
//! # Contract
//!
//! [`Tree::from_bytes`] is the only way to get a [`Tree`], and it validates
//! the whole file once, without allocating:
//!
//! - the magic, the version, the header fields and the exact file length;
//!   the largest polygon's vertex count equals the header's
//!   `polygon_vertices`, and `scratch_vertices` is at least that plus 5;
//! - the CRC-32 over everything before the trailing checksum;
//! - the section sizes implied by the counts against the file length;
//! - every float that geometry is computed from is finite (origin, half
//!   extent, radius, `f32` vertices, run and switch planes);
//! - compact polygon records ([`crate::format::FLAG_COMPACT`]): the layout's
//!   widths (each ≤ 32 bits, ≤ 56 together), every colour index below the
//!   colour table's length and the unused bits zero; narrow records
//!   ([`crate::format::FLAG_NARROW`]): the hidden_edges width ≤ 8, all five
//!   ≤ 64 bits, the record length exactly what they need, the bits above
//!   them zero;
//! - shared switch planes ([`crate::format::FLAG_NARROW`]): every switch
//!   names a plane record below `run_count + extra_planes`, and the extra
//!   plane records have finite planes and an end of 0;
//! - a shared plane table ([`crate::format::FLAG_PLANES`], read only with
//!   the `plane-table` feature): every entry finite (compact entries,
//!   [`crate::format::FLAG_COMPACT_PLANES`]: well formed, with a finite
//!   plane unit), every run's and
//!   switch's plane index below the table's length;
//! - run offsets ([`crate::format::FLAG_RUN_OFFSETS`], exactly with the
//!   plane table): each polygon's run field is its id less its run's
//!   index;
//! - small walk records ([`crate::format::FLAG_SMALL`]; only these
//!   without the `large-trees` feature): at most 65,535 runs and 32,767
//!   switches, and a switch field of −1 or an index;
//! - every vertex index is below the vertex count, every polygon has at least
//!   3 vertices and the polygons tile the index list; every edge record
//!   (optional section) has a known kind; every corner normal (optional
//!   section) is non-zero with components in `−127..=127`;
//! - the runs tile the polygons (non-empty, in order) and every polygon's
//!   `run` field names the run that holds it;
//! - the bunch offsets tile the runs (each run, hence each polygon, is in
//!   exactly one bunch), the nodes tile the bunches (each bunch belongs to
//!   exactly one level or switch);
//! - the node graph is a tree: switches are numbered in node order, switch
//!   `k` has children `2k + 1` and `2k + 2` (the layout rule of
//!   [`crate::format`]), and a breadth-first pass by layers reaches every
//!   node; the number of layers (the depth) equals the header's `max_depth`.
//!   The pass is O(nodes): the layout rule makes the layers contiguous.
//!
//! After it succeeds, **nothing in the accessors or in the traversal
//! ([`crate::order`]) can panic, index out of range, or loop**: every read is
//! at an offset proven in range, every walk is bounded by the validated
//! counts and depth, and every polygon is reached at most once per walk.
//! Accessors that take an id return `None` for an id out of range; the field
//! readers underneath also fall back to 0 instead of panicking, so no panic
//! path is compiled in even for a bug. The bytes are borrowed, never copied,
//! and may have any alignment.
//!
//! The sections the walk reads for every view are kept as subslices of
//! exactly their validated length (`WalkData`), so reading record `i` is a
//! single range check (`get`) that the validation makes always succeed, then
//! fixed-offset reads from a copied array: no `unsafe`, no panic path, and
//! little work per record.
//!
//! # Fuzzing
//!
//! The contract is fuzzed by the `tree_walk` target of `fuzz/` (commands in
//! the crate docs): its first input byte rewrites the length field and the
//! CRC of the rest on request, so that mutated files reach the structural
//! checks; every accepted file has all its accessors read and is walked for
//! five views (one with a NaN direction), by ids and by ranges, with and
//! without back-face culling, checking ids in range, no empty class, no id
//! twice, every id when nothing is culled, the walk's own ranges equal to
//! its class ids, and then drawn with every effect
//! (outlines, depth cue, clipping off, dithering) in fixed point and f32.
//! cargo-fuzz builds it with debug assertions, overflow checks and
//! AddressSanitizer by default, so an arithmetic overflow is a crash too.
//! (`mesh_import`, in the same table, fuzzes the host's mesh parsers.)
//!
//! Runs of 2026-11-25, 600 s each on one core of a shared 2-core machine,
//! one after the other:
//!
//! | target | seeds | executions | edges | features | corpus | found |
//! |---|---|---:|---:|---:|---:|---|
//! | `tree_walk` (walk before its last change) | `seeds/tree_walk`: 7 trees | 20 880 460 | 738 | 2 187 | 213 | nothing |
//! | `mesh_import` | `seeds/mesh_import`: 4 meshes | 4 209 803 | 3 581 | 15 633 | 2 660 | nothing |
//! | `tree_walk` (final code, from the corpus above) | same | 21 259 243 | 742 | 2 206 | 181 | nothing |
//! | `tree_walk` with effects (format v2; both culling choices and a frame drawn with every effect, fixed and f32), session 2 | same, moved to v2 | 9 350 942 | 2 053 | 9 543 | 902 | nothing |
//! | the same after the vertex iterator and clip-test changes, 300 s, from that corpus | same | 5 093 905 | 2 061 | 9 461 | 539 | nothing |
//! | session 3: the walk's ranges (`Order::next_range`) checked against its class ids, short-form projection; 420 s from that corpus | same | 7 017 705 | 2 118 | 9 505 | 569 | nothing |
//! | session 23: small walk records (16-bit bunch offsets, 8-byte nodes) and the plane table, 300 s from the seeds alone, `large-trees` and `plane-table` on | 19 trees (the four `small_*` new) | 1 640 663 | 3 837 | 17 863 | 1 339 | nothing |
//!
//! (The target now also draws, so its edge and feature counts cover the
//! rasterizer and are not comparable with the first rows.)
//!
//! No crash, timeout or out-of-memory in any run. The seed trees are small
//! static, dynamic and BSP trees, open and closed, in all three vertex
//! formats, some with runs of several polygons, three (`compact_*`, session
//! 10) with compact polygon records, one of them with two colours and the
//! edge and normal sections, three (`narrow_*`, session 17, first fuzzed in session 23)
//! with narrow records and shared switch planes, four (`small_*`, session
//! 23) with small walk records, one of them with the plane table
//! (`small_table_twocubes_static`), one dynamic with `q16` vertices and the
//! depth cue, dither and outline effects, one (session 25,
//! `small_table_compact_twocubes_bsp_q16`; `tree_walk` then ran 151 s
//! from the 20 seeds, 1.88 M runs, nothing found) a BSP tree with `q16`
//! vertices and a table of compact planes, and one (session 26,
//! `offsets_table_compact_twocubes_static`) with runs of two triangles
//! and run offsets (the two older table seeds rewritten in that format;
//! `tree_walk` then ran 151 s from the 21 seeds, 320 k runs on a loaded
//! machine, 4,890 edges, 17,909 features, nothing found); the seed meshes one OBJ,
//! OFF, ASCII STL and ASCII PLY each. Of the `tree_walk` corpus after the
//! first run, 99 inputs are valid trees (walked) and the other 107 are
//! rejected with every one of the 15 kinds of [`FormatError`] between them.

use core::fmt;

use crate::raster::proof::VertexBound;

use crate::format::{
    crc32, header as h, rd, rd_f32, rd_f32x3, rd_f64, rd_u16, rd_u32, rd_u8, Counts, FormatError,
    Sections, UpAxis, VertexFormat, CRC_LEN, FLAG_CLOSED, HEADER_LEN, MAGIC, MAX_SHIFT, NODE_LEN,
    POLYGON_LEN, Q16_MAX, RUN_LEN, SWITCH_LEN, VERSION,
};
use crate::format::{plane_unit, COMPACT_PLANE_LEN, FLAG_COMPACT_PLANES};
use crate::format::{COMPACT_POLYGON_LEN, FLAG_COMPACT, FLAG_NARROW, SWITCH_REF_LEN};
use crate::format::{FLAG_EDGES, FLAG_NORMALS, NORMAL_LEN};
use crate::format::{FLAG_PLANES, FLAG_RUN_OFFSETS, PLANE_LEN, TABLE_RUN_LEN};
use crate::format::{FLAG_SMALL, SMALL_MAX_RUNS, SMALL_MAX_SWITCHES, SMALL_NODE_LEN};

/// A validated tree file, read in place.
#[derive(Clone, Copy, Debug)]
pub struct Tree<'a> {
    g: Geometry<'a>,
    w: WalkData<'a>,
    counts: Counts,
    level_count: u32,
    flags: u32,
    effects: u32,
    max_depth: u32,
    radius: f32,
    /// Bounds of the decoded vertices, computed when the file is read
    /// (the header's radius is not checked against them).
    vertex_bound: VertexBound,
    up: UpAxis,
    capacities: Capacities,
    /// The corner normal section (`index_count` records of
    /// [`NORMAL_LEN`] bytes), empty without it.
    normals: &'a [u8],
    /// Where each section starts (validated against the length).
    sections: Sections,
}

/// What a renderer needs to draw a tree, from its header (see
/// [`crate::format`]): checked by every drawing function of
/// [`crate::render`] before it draws ([`crate::render::CapacityError`]).
///
/// ```
/// # let bytes: &[u8] = include_bytes!("../../firmware/trees/vise.fpt");
/// let tree = fpt_nostd::reader::Tree::from_bytes(bytes).unwrap();
/// let c = tree.capacities();
/// // What to write: `TreeRenderer<P, V>` and `render_banded_in::<F, N>`.
/// assert!(c.vertices >= c.polygon_vertices + 5);
/// assert_eq!(c.walk_depth, tree.max_depth());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Capacities {
    /// The walk's stack `N`: the tree's depth ([`Tree::max_depth`]).
    pub walk_depth: u32,
    /// The scratch's vertex capacity `V`
    /// ([`crate::format::scratch_vertices_for`] of the polygon that needs
    /// most): with it no polygon is ever skipped for want of room.
    pub vertices: u32,
    /// Vertices of the largest polygon.
    pub polygon_vertices: u32,
    /// Working memory words for one walk a frame in any view (advice: less
    /// gives the same picture with more walks; see
    /// [`crate::render::memory_words`]).
    pub memory_words: u32,
}

impl fmt::Display for Capacities {
    /// `N = 49, V = 25, memory 9845 words`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "N = {}, V = {}, memory {} words",
            self.walk_depth, self.vertices, self.memory_words
        )
    }
}

fn finite3_f32(v: [f32; 3]) -> bool {
    v.iter().all(|x| x.is_finite())
}

impl<'a> Tree<'a> {
    /// Validates `bytes` as a tree file (see the module docs for what is
    /// checked) and returns the tree read in place.
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Tree<'a>, FormatError> {
        let len = bytes.len();
        if len < HEADER_LEN + CRC_LEN {
            return Err(FormatError::TooShort);
        }
        if rd::<4>(bytes, h::MAGIC) != MAGIC {
            return Err(FormatError::BadMagic);
        }
        let version = rd_u16(bytes, h::VERSION);
        if version != VERSION {
            return Err(FormatError::UnsupportedVersion(version));
        }
        if usize::from(rd_u16(bytes, h::HEADER_LEN)) != HEADER_LEN {
            return Err(FormatError::BadHeader("header_len"));
        }
        if u64::from(rd_u32(bytes, h::FILE_LEN)) != len as u64 {
            return Err(FormatError::LengthMismatch);
        }
        let (body, stored) = bytes
            .split_at_checked(len - CRC_LEN)
            .ok_or(FormatError::TooShort)?;
        if crc32(body) != rd_u32(stored, 0) {
            return Err(FormatError::Checksum);
        }

        let flags = rd_u32(bytes, h::FLAGS);
        // A plane table only with the feature of its kind of entries.
        let planes = if cfg!(any(feature = "plane-table", feature = "compact-planes")) {
            FLAG_PLANES
        } else {
            0
        } | if cfg!(feature = "compact-planes") {
            FLAG_COMPACT_PLANES
        } else {
            0
        };
        let f32_table = flags & FLAG_PLANES != 0 && flags & FLAG_COMPACT_PLANES == 0;
        let known = FLAG_CLOSED
            | FLAG_EDGES
            | FLAG_NORMALS
            | FLAG_COMPACT
            | FLAG_NARROW
            | planes
            | FLAG_SMALL
            | FLAG_RUN_OFFSETS;
        // Without the `large-trees` feature, only small walk records: the
        // walk then reads one layout.
        let large = cfg!(feature = "large-trees");
        if flags & !known != 0
            || (!large && flags & FLAG_SMALL == 0)
            || (flags & FLAG_NARROW != 0 && flags & FLAG_COMPACT == 0)
            || (flags & FLAG_PLANES != 0 && flags & FLAG_NARROW == 0)
            || (flags & FLAG_COMPACT_PLANES != 0 && flags & FLAG_PLANES == 0)
            || (flags & FLAG_PLANES != 0) != (flags & FLAG_RUN_OFFSETS != 0)
            || (f32_table && !cfg!(feature = "plane-table"))
        {
            return Err(FormatError::BadHeader("flags"));
        }
        let format = VertexFormat::from_code(rd_u8(bytes, h::VERTEX_FORMAT))
            .ok_or(FormatError::BadHeader("vertex_format"))?;
        let shift = rd_u8(bytes, h::SHIFT);
        let shift_ok = match format {
            VertexFormat::Q32 => shift <= MAX_SHIFT,
            _ => shift == 0,
        };
        if !shift_ok {
            return Err(FormatError::BadHeader("shift"));
        }
        let index_size = rd_u8(bytes, h::INDEX_SIZE);
        if index_size != 2 && index_size != 4 {
            return Err(FormatError::BadHeader("index_size"));
        }
        let up =
            UpAxis::from_code(rd_u8(bytes, h::UP_AXIS)).ok_or(FormatError::BadHeader("up_axis"))?;
        let counts = Counts {
            vertices: rd_u32(bytes, h::VERTEX_COUNT),
            polygons: rd_u32(bytes, h::POLYGON_COUNT),
            indices: rd_u32(bytes, h::INDEX_COUNT),
            bunches: rd_u32(bytes, h::BUNCH_COUNT),
            nodes: rd_u32(bytes, h::NODE_COUNT),
            switches: rd_u32(bytes, h::SWITCH_COUNT),
            runs: rd_u32(bytes, h::RUN_COUNT),
            edges: 0,
            normals: 0,
            small: flags & FLAG_SMALL != 0,
        };
        let optional = |flag: u32| if flags & flag != 0 { counts.indices } else { 0 };
        let counts = Counts {
            edges: optional(FLAG_EDGES),
            normals: optional(FLAG_NORMALS),
            ..counts
        };
        // A compact file's layout: read before the section sizes, which
        // depend on its colour count.
        let compact = flags & FLAG_COMPACT != 0;
        let (widths, records) = layout::read(bytes, flags)?;
        let colour_count = records.map(|r| r.colours);
        let s = Sections::with_records(&counts, format, usize::from(index_size), records.as_ref())
            .ok_or(FormatError::SectionSizes)?;
        let narrow = records.and_then(|r| r.narrow);
        let extra_planes = narrow.map_or(0, |n| n.extra_planes);
        if s.file_len != len {
            return Err(FormatError::SectionSizes);
        }
        if u64::from(counts.nodes) != 2 * u64::from(counts.switches) + 1 {
            return Err(FormatError::NotATree);
        }
        // What small records can number (a node's levels are checked
        // against the bunches they tile).
        if counts.small && (counts.runs > SMALL_MAX_RUNS || counts.switches > SMALL_MAX_SWITCHES) {
            return Err(FormatError::BadHeader("flags"));
        }

        let origin = [0, 8, 16].map(|o| rd_f64(bytes, h::ORIGIN + o));
        let half_extent = rd_f32x3(bytes, h::HALF_EXTENT);
        let radius = rd_f32(bytes, h::RADIUS);
        if !origin.iter().all(|x| x.is_finite()) || !finite3_f32(half_extent) || !radius.is_finite()
        {
            return Err(FormatError::NonFinite("header"));
        }
        if half_extent.iter().any(|&x| x < 0.0) {
            return Err(FormatError::BadHeader("half_extent"));
        }
        if radius < 0.0 {
            return Err(FormatError::BadHeader("radius"));
        }

        // The walk's sections, sliced to their exact lengths: in range, since
        // the section sizes add up to the file length.
        let section = |start: usize, count: u32, len: usize| {
            (count as usize)
                .checked_mul(len)
                .and_then(|n| start.checked_add(n))
                .and_then(|end| bytes.get(start..end))
                .ok_or(FormatError::SectionSizes)
        };
        let shared = narrow.is_some();
        let table = narrow.is_some_and(|n| n.table);
        let compact_planes = narrow.is_some_and(|n| n.compact_planes);
        if compact_planes && !plane_unit(half_extent).is_finite() {
            return Err(FormatError::BadHeader("half_extent"));
        }
        let switch_len = if shared { SWITCH_REF_LEN } else { SWITCH_LEN };
        let plane_len = if compact_planes {
            COMPACT_PLANE_LEN
        } else {
            PLANE_LEN
        };
        let runs = if table {
            Runs::new(
                section(s.runs, counts.runs, TABLE_RUN_LEN)?,
                section(s.planes, extra_planes, plane_len)?,
                table,
                compact_planes,
            )
        } else {
            let records = counts.runs.saturating_add(extra_planes);
            Runs::new(section(s.runs, records, RUN_LEN)?, &[], table, false)
        };
        let run_recs = runs.recs;
        let w = WalkData {
            runs,
            bunches: section(
                s.bunches,
                counts.bunches.saturating_add(1),
                if counts.small { 2 } else { 4 },
            )?,
            nodes: section(
                s.nodes,
                counts.nodes,
                if counts.small {
                    SMALL_NODE_LEN
                } else {
                    NODE_LEN
                },
            )?,
            #[cfg(feature = "large-trees")]
            small: counts.small,
            switches: section(s.switches, counts.switches, switch_len)?,
            shared,
        };
        let rec_len = match (compact, narrow) {
            (_, Some(n)) => usize::from(n.record_len),
            (true, None) => COMPACT_POLYGON_LEN,
            (false, None) => POLYGON_LEN,
        };
        let g = Geometry {
            bytes,
            has_edges: counts.edges != 0,
            compact,
            fields: widths,
            rec_len: rec_len as u8,
            vertices: s.vertices,
            polygons: s.polygons,
            indices: s.indices,
            planes: if table { runs.plane_bytes() } else { runs.recs },
            plane_len: if table { plane_len } else { RUN_LEN } as u8,
            runs: run_recs,
            polygon_count: counts.polygons,
            index_count: counts.indices,
            format,
            index_size,
            shift,
            origin,
            half_extent,
            q16_scale: half_extent.map(|x| x / f32::from(Q16_MAX)),
            // 2^-shift from its bits: exact, and `powi` is not in core.
            q32_scale: f32::from_bits((127 - u32::from(shift.min(MAX_SHIFT))) << 23),
        };
        let mut tree = Tree {
            g,
            w,
            counts,
            level_count: 0,
            flags,
            effects: rd_u32(bytes, h::EFFECTS),
            max_depth: rd_u32(bytes, h::MAX_DEPTH),
            radius,
            vertex_bound: VertexBound::EMPTY,
            up,
            capacities: Capacities {
                walk_depth: rd_u32(bytes, h::MAX_DEPTH),
                vertices: rd_u32(bytes, h::SCRATCH_VERTICES),
                polygon_vertices: rd_u32(bytes, h::POLYGON_VERTICES),
                memory_words: rd_u32(bytes, h::MEMORY_WORDS),
            },
            normals: section(s.normals, counts.normals, NORMAL_LEN)?,
            sections: s,
        };
        if rd_u32(bytes, h::RESERVED32) != 0 {
            return Err(FormatError::BadHeader("reserved"));
        }
        tree.vertex_bound = tree.check_vertices()?;
        if tree.check_polygons()? != tree.capacities.polygon_vertices {
            return Err(FormatError::BadHeader("polygon_vertices"));
        }
        let v = tree.capacities.vertices;
        if v < tree.capacities.polygon_vertices.saturating_add(5) || v > u32::from(u16::MAX) {
            return Err(FormatError::BadHeader("scratch_vertices"));
        }
        tree.check_colours(colour_count.unwrap_or(0))?;
        tree.check_edges()?;
        tree.check_normals()?;
        tree.check_runs()?;
        tree.check_bunches()?;
        tree.level_count = tree.check_nodes()?;
        tree.check_switches(if table { 0 } else { extra_planes })?;
        tree.check_depth()?;
        Ok(tree)
    }

    /// The format version of the file (the reader takes only
    /// [`crate::format::VERSION`]).
    pub fn version(&self) -> u16 {
        rd_u16(self.g.bytes, h::VERSION)
    }

    /// Whether the polygon records are compact (8 bytes, with a colour
    /// table; see [`crate::format`]).
    pub fn is_compact(&self) -> bool {
        self.g.compact
    }

    /// Entries in the colour table of a compact file (0 otherwise).
    pub fn colour_count(&self) -> u32 {
        if self.g.compact {
            rd_u32(self.g.bytes, HEADER_LEN + 4)
        } else {
            0
        }
    }

    /// Bytes of one polygon record: 16, 8 (compact) or the narrow layout's
    /// record length ([`FLAG_NARROW`]).
    pub fn record_len(&self) -> usize {
        usize::from(self.g.rec_len)
    }

    /// Whether the switch records name shared plane records
    /// ([`FLAG_NARROW`]).
    pub fn has_shared_planes(&self) -> bool {
        self.w.shared
    }

    /// Whether the polygon records' run fields are run offsets, `id −
    /// run` ([`FLAG_RUN_OFFSETS`]: narrower records).
    pub fn has_run_offsets(&self) -> bool {
        self.flags & FLAG_RUN_OFFSETS != 0
    }

    /// Whether the bunch offsets and node records are small ones
    /// ([`FLAG_SMALL`]).
    pub fn has_small_records(&self) -> bool {
        self.w.small()
    }

    /// Whether the run and switch planes are in a shared plane table
    /// ([`FLAG_PLANES`]).
    pub fn has_plane_table(&self) -> bool {
        self.w.runs.is_table()
    }

    /// Whether the plane table's entries are compact
    /// ([`crate::format::FLAG_COMPACT_PLANES`]).
    pub fn has_compact_planes(&self) -> bool {
        self.w.runs.is_compact()
    }

    /// What the facing test scales the view's `w` by: the plane unit with
    /// compact planes (their offsets are in its steps), else 1.
    #[inline]
    pub(crate) fn facing_scale(&self) -> f32 {
        if self.w.runs.is_compact() {
            plane_unit(self.g.half_extent)
        } else {
            1.0
        }
    }

    /// Entries of the plane table (0 without one).
    pub fn plane_table_len(&self) -> u32 {
        (self.w.runs.plane_bytes().len() / self.w.runs.plane_len()) as u32
    }

    /// What the compact records add to the sections
    /// ([`Sections::with_records`]); `None` for 16-byte records.
    pub fn records(&self) -> Option<crate::format::Records> {
        self.g.compact.then(|| crate::format::Records {
            colours: self.colour_count(),
            narrow: self.w.shared.then(|| crate::format::Narrow {
                record_len: self.g.rec_len,
                extra_planes: if self.w.runs.is_table() {
                    self.plane_table_len()
                } else {
                    self.extra_plane_count()
                },
                table: self.w.runs.is_table(),
                compact_planes: self.w.runs.is_compact(),
            }),
        })
    }

    /// Plane records stored after the runs for switches whose plane no run
    /// has (0 without [`FLAG_NARROW`], and with a plane table).
    pub fn extra_plane_count(&self) -> u32 {
        if self.w.runs.is_table() {
            return 0;
        }
        (self.w.runs.recs.len() / RUN_LEN).saturating_sub(self.counts.runs as usize) as u32
    }

    /// Bytes of each section, in file order, with its name (padding
    /// counted in the section it follows; the header includes nothing
    /// else): what `fpt info` prints. Sections a file does not have are
    /// left out.
    pub fn section_bytes(&self) -> [(&'static str, usize); 15] {
        let s = self.sections;
        let n = self.g.bytes.len();
        [
            ("header", s.layout),
            ("layout", s.colours - s.layout),
            ("colours", s.narrow - s.colours),
            ("narrow layout", s.vertices - s.narrow),
            ("vertices", s.polygons - s.vertices),
            ("polygons", s.indices - s.polygons),
            ("indices", s.edges - s.indices),
            ("edges", s.normals - s.edges),
            ("normals", s.planes - s.normals),
            ("plane table", s.runs - s.planes),
            ("runs", s.bunches - s.runs),
            ("bunches", s.nodes - s.bunches),
            ("nodes", s.switches - s.nodes),
            ("switches", s.crc - s.switches),
            ("crc", n.saturating_sub(s.crc)),
        ]
    }

    /// Whether the file has the edge section (every edge's outline kind,
    /// see [`crate::format`]): the `outline` effect was declared.
    pub fn has_edges(&self) -> bool {
        self.g.has_edges
    }

    /// Whether the model is a closed volume (back faces are culled).
    pub fn is_closed(&self) -> bool {
        self.flags & FLAG_CLOSED != 0
    }

    /// The scene's effect flags, as stored.
    pub fn effects(&self) -> u32 {
        self.effects
    }

    /// The model's up axis as the builder recorded it ([`UpAxis::Y`] for
    /// files that record none).
    pub fn up_axis(&self) -> UpAxis {
        self.up
    }

    /// The origin (bounding box centre) in model coordinates; every vertex
    /// and plane is relative to it.
    pub fn origin(&self) -> [f64; 3] {
        self.g.origin
    }

    /// Half the bounding box size per axis.
    pub fn half_extent(&self) -> [f32; 3] {
        self.g.half_extent
    }

    /// Radius of the bounding sphere centred on the origin.
    pub fn bounding_radius(&self) -> f32 {
        self.radius
    }

    /// Bounds of the vertices as [`Tree::vertex_decoder`] decodes them
    /// (relative to the origin): per axis and of the squared length,
    /// computed from every vertex when the file was read. The float
    /// transform proves from them, once a frame, that its per-vertex
    /// checks cannot fire ([`crate::raster::proof`]).
    pub fn vertex_bound(&self) -> VertexBound {
        self.vertex_bound
    }

    /// The vertex encoding.
    pub fn vertex_format(&self) -> VertexFormat {
        self.g.format
    }

    /// The `q32` shift (0 for the other formats).
    pub fn q32_shift(&self) -> u8 {
        self.g.shift
    }

    /// Bytes per vertex index (2 or 4).
    pub fn index_size(&self) -> u8 {
        self.g.index_size
    }

    /// Connecting nodes on the longest root-to-leaf path.
    pub fn max_depth(&self) -> u32 {
        self.max_depth
    }

    /// What a renderer needs for this tree (see [`Capacities`]).
    pub fn capacities(&self) -> Capacities {
        self.capacities
    }

    /// Number of polygons; ids are `0..polygon_count()`.
    pub fn polygon_count(&self) -> u32 {
        self.counts.polygons
    }

    /// Number of distinct stored vertices.
    pub fn vertex_count(&self) -> u32 {
        self.counts.vertices
    }

    /// Length of the vertex index list.
    pub fn index_count(&self) -> u32 {
        self.counts.indices
    }

    /// Number of bunches, empty ones included.
    pub fn bunch_count(&self) -> u32 {
        self.counts.bunches
    }

    /// Number of bunches that hold at least one polygon: what the
    /// builder's statistics count (`fpt build --stats`), while
    /// [`Tree::bunch_count`] also counts the empty `F_j`, `B_j` and `O_k`
    /// that the node layout stores.
    pub fn nonempty_bunch_count(&self) -> u32 {
        let mut n = 0;
        for b in 0..self.counts.bunches {
            let (start, end) = self.w.bunch(b);
            n += u32::from(end > start);
        }
        n
    }

    /// Number of levels over all connecting nodes.
    pub fn level_count(&self) -> u32 {
        self.level_count
    }

    /// Number of connecting nodes.
    pub fn node_count(&self) -> u32 {
        self.counts.nodes
    }

    /// Number of switch nodes.
    pub fn switch_count(&self) -> u32 {
        self.counts.switches
    }

    /// The file's bytes.
    pub fn as_bytes(&self) -> &'a [u8] {
        self.g.bytes
    }

    /// The stored CRC-32.
    pub fn crc(&self) -> u32 {
        let b = self.g.bytes;
        rd_u32(b, b.len().saturating_sub(CRC_LEN))
    }

    /// Polygon `id`, or `None` if `id ≥ polygon_count()`.
    pub fn polygon(&self, id: u32) -> Option<PolygonRef<'a>> {
        if id >= self.counts.polygons {
            return None;
        }
        let (first, end) = self.g.polygon_range(id);
        Some(PolygonRef {
            g: self.g,
            id,
            first,
            count: end.saturating_sub(first),
        })
    }

    /// The vertex indices of polygon `id` (what
    /// [`PolygonRef::vertex_indices`] gives), without making the
    /// [`PolygonRef`]: a band's replay of the display list reads them for
    /// every polygon it fills, and a `PolygonRef` carries the whole
    /// vertex decoder (about 100 bytes to copy on a 32-bit core). Empty
    /// when `id ≥ polygon_count()`.
    #[inline]
    pub fn polygon_vertex_indices(&self, id: u32) -> VertexIndices<'a> {
        match self.polygon_at(id) {
            Some(p) => p.vertex_indices(),
            None => VertexIndices {
                indices: &[],
                wide: false,
            },
        }
    }

    /// Polygon `id` borrowing the tree ([`PolygonAt`]), or `None` if
    /// `id ≥ polygon_count()`.
    #[inline]
    pub(crate) fn polygon_at(&self, id: u32) -> Option<PolygonAt<'_, 'a>> {
        (id < self.counts.polygons).then(|| PolygonAt::new(&self.g, id))
    }

    /// Stored vertex `v` relative to the origin, decoded to `f32`.
    pub fn vertex(&self, v: u32) -> Option<[f32; 3]> {
        self.vertex_raw(v).map(|r| self.g.decode(r))
    }

    /// A decoder of vertices by index ([`VertexDecoder`]).
    pub fn vertex_decoder(&self) -> VertexDecoder<'a> {
        self.g.decoder()
    }

    /// Stored vertex `v` as stored.
    pub fn vertex_raw(&self, v: u32) -> Option<RawVertex> {
        (v < self.counts.vertices).then(|| self.g.raw(v))
    }

    /// Decodes a raw vertex of this tree to `f32`, relative to the origin.
    pub fn decode(&self, r: RawVertex) -> [f32; 3] {
        self.g.decode(r)
    }

    /// Decodes a raw vertex of this tree to model coordinates in `f64`.
    pub fn decode_model(&self, r: RawVertex) -> [f64; 3] {
        self.g.decode_model(r)
    }

    /// Number of runs of polygons sharing a plane (each bunch is a range of
    /// runs; the walk tests a run's facing once for all its polygons).
    pub fn run_count(&self) -> u32 {
        self.counts.runs
    }

    /// The sections the walk reads.
    #[inline]
    pub(crate) fn walk_data(&self) -> WalkData<'a> {
        self.w
    }
}

mod geometry;
use geometry::{CompactFields, Geometry};
mod layout;
mod normals;
mod plane;
pub use plane::{Plane, RawVertex};
mod polygon;
pub(crate) use polygon::PolygonAt;
pub use polygon::PolygonRef;
mod validate;
mod walk_data;
pub(crate) use walk_data::{table_plane, Runs, WalkData};
mod vertices;
pub use vertices::{VertexDecoder, VertexIndices, Vertices};

#[cfg(test)]
mod tests;
