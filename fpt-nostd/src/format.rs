//! The flat-array tree file: layout, constants and low-level field access.
//!
//! A tree file is one byte string, written by the host serializer
//! (`fpt_build::serialize`) and read in place by [`crate::reader::Tree`] from
//! any `&[u8]`, typically `include_bytes!` in flash. Every multi-byte field
//! is **little-endian** and read with `from_le_bytes` on a subslice, so the
//! bytes may sit at any alignment and nothing is copied.
//!
//! # Layout
//!
//! `header · [layout · colours · [narrow]] · vertices · polygons · indices · [edges] · [normals] · [plane table] · runs · [extra planes] · bunches · nodes · switches · crc`
//!
//! The bracketed sections are optional: present only when the header's
//! flags say so (version 3, see below); a version 2 file never has them.
//! The layout and colour sections come with [`FLAG_COMPACT`], which also
//! makes every polygon record 8 bytes instead of 16 (see *Compact polygon
//! records* below); a file without the flag is read as before.
//!
//! Each section starts right after the previous one, padded with zero bytes
//! to a multiple of 4 (so a copy to aligned RAM could use them directly); its
//! length is fixed by the counts in the header (see [`Sections::new`]), and
//! the file length must equal the sum exactly. The sections the walk reads
//! for every view (runs, bunches, nodes, switches) are contiguous at the end,
//! after the geometry that only the renderer needs.
//!
//! ## Header (112 bytes)
//!
//! | offset | type | field | meaning |
//! |---:|---|---|---|
//! | 0 | `[u8; 4]` | magic | [`MAGIC`], `b"FPTR"` |
//! | 4 | `u16` | version | [`VERSION`] (3; version 2 had no renderer capacities and a 96-byte header, version 1 required byte 15 of a polygon to be 0) |
//! | 6 | `u16` | header_len | [`HEADER_LEN`] (112) |
//! | 8 | `u32` | file_len | total length of the file in bytes, CRC included |
//! | 12 | `u32` | flags | bit 0 [`FLAG_CLOSED`]: closed volume (back faces culled); bit 1 [`FLAG_EDGES`]: the edge section is present; bit 2 [`FLAG_NORMALS`]: the normal section is present; bit 3 [`FLAG_COMPACT`]: compact polygon records, with the layout and colour sections; bit 4 [`FLAG_NARROW`] (only with bit 3): narrow records and shared switch planes; bit 5 [`FLAG_PLANES`] (only with bit 4): a shared plane table and 4-byte runs; bit 6 [`FLAG_SMALL`]: `u16` bunch offsets and 8-byte node records; bit 7 [`FLAG_COMPACT_PLANES`] (only with bit 5): 8-byte plane table entries; bit 8 [`FLAG_RUN_OFFSETS`] (exactly with bit 5): a polygon's run field is `id − run`; other bits must be 0 |
//! | 16 | `u32` | effects | the scene's declared effects, [`crate::effects::Effects`] bits (unknown bits ignored); not checked by the reader |
//! | 20 | `u8` | vertex_format | [`VertexFormat`] code: 0 `f32`, 1 `q16`, 2 `q32` |
//! | 21 | `u8` | shift | `q32` only: fixed-point shift, `0..=126`; 0 for the other formats |
//! | 22 | `u8` | index_size | bytes per vertex index: 2 (`u16`) or 4 (`u32`) |
//! | 23 | `u8` | up_axis | [`UpAxis`] code, the model's up axis as the builder was told or guessed it: 0 `y` (also: not recorded, as in files written before it existed), 1 `x`, 2 `z`; any other value is an error |
//! | 24 | `u32` | max_depth | connecting nodes on the longest root-to-leaf path (root alone: 1) |
//! | 28 | `u32` | vertex_count | entries in the vertex section |
//! | 32 | `u32` | polygon_count | entries in the polygon section |
//! | 36 | `u32` | index_count | entries in the vertex index list |
//! | 40 | `u32` | bunch_count | bunches (the bunch section holds `bunch_count + 1` offsets) |
//! | 44 | `u32` | node_count | connecting nodes, always `2 · switch_count + 1` |
//! | 48 | `u32` | switch_count | switch nodes |
//! | 52 | `u32` | run_count | entries in the run section (runs of polygons sharing a plane) |
//! | 56 | `f64 × 3` | origin | centre of the bounding box, model coordinates; all geometry below is relative to it |
//! | 80 | `f32 × 3` | half_extent | half the bounding box size per axis (the `q16` scale) |
//! | 92 | `f32` | radius | bounding sphere: centre `origin`, this radius, covers every vertex |
//! | 96 | `u32` | polygon_vertices | vertices of the largest polygon (0 without polygons) |
//! | 100 | `u32` | scratch_vertices | the vertex capacity `V` a renderer needs so that no polygon is ever skipped: the largest [`scratch_vertices_for`] over the polygons; at least `polygon_vertices + 5`, at most 65 535 |
//! | 104 | `u32` | memory_words | the working memory (32-bit words) with which a frame needs one walk in any view, `fpt_nostd::render::memory_words` when the file was written; advice, not checked by the reader |
//! | 108 | `u32` | reserved | 0 |
//!
//! The walk's stack `N` must hold `max_depth` levels; `N`, `V` and the
//! memory are what `fpt info` prints and what
//! [`crate::reader::Tree::capacities`] returns.
//!
//! ## Vertices (`vertex_count` entries)
//!
//! A vertex is stored as its offset `x − origin` from the origin, in the
//! header's encoding ([`VertexFormat`]):
//!
//! | format | entry | decoding of one coordinate `q` on `axis` |
//! |---|---|---|
//! | `f32` | `f32 × 3`, 12 bytes | `x = origin + q` |
//! | `q16` | `i16 × 3`, 6 bytes | `x = origin + half_extent[axis] · q / 32767` |
//! | `q32` | `i32 × 3`, 12 bytes | `x = origin + q · 2^-shift` |
//!
//! Vertices shared by several polygons are stored once.
//!
//! ## Polygons (`polygon_count` entries of [`POLYGON_LEN`] = 16 bytes)
//!
//! | offset | type | field |
//! |---:|---|---|
//! | 0 | `u32` | first_index: where the polygon's vertex indices start in the index list |
//! | 4 | `u32` | run: the run holding it, whose plane is its plane |
//! | 8 | `u32` | source: the face of the input mesh it came from |
//! | 12 | `u8 × 3` | colour, RGB |
//! | 15 | `u8` | hidden_edges: bit `i` set when edge `i` (vertex `i` → `i + 1`) lies inside the source face (shared with another piece of it, or with a coplanar neighbour of the same colour), so the `outline` effect leaves it out; edges from 8 on are always drawn. A file with the edge section uses that section instead (every edge, feature edges and silhouettes) |
//!
//! The polygons tile the index list in order: polygon 0 starts at index 0 and
//! polygon `p` ends where polygon `p + 1` starts (the last one at
//! `index_count`); each has at least 3 vertices, counter-clockwise seen from
//! the front. A polygon's id is its position in this section.
//!
//! ## Compact polygon records (flag [`FLAG_COMPACT`])
//!
//! A compact file stores the same fields in [`COMPACT_POLYGON_LEN`] = 8
//! bytes a polygon: the colour becomes an index into a table of the
//! file's distinct colours, and each field takes only the bits its largest
//! value needs. Two sections follow the header:
//!
//! **Layout** ([`LAYOUT_LEN`] = 8 bytes):
//!
//! | offset | type | field |
//! |---:|---|---|
//! | 0 | `u8` | bits of first_index |
//! | 1 | `u8` | bits of run |
//! | 2 | `u8` | bits of source |
//! | 3 | `u8` | bits of the colour index |
//! | 4 | `u32` | colour_count: entries in the colour table |
//!
//! Each width is at most 32 and the four add up to at most 56; anything
//! else is `BadHeader("layout")`.
//!
//! **Colours** (`colour_count` entries of [`COLOUR_LEN`] = 3 bytes, RGB),
//! padded to 4 bytes like every section.
//!
//! A record is one little-endian `u64`; from bit 0 up: first_index, run,
//! source and colour index, each in its layout width, then (bits 56..64)
//! hidden_edges. Bits between the colour index and bit 56 are zero.
//! Every colour index must be below `colour_count` (else
//! [`FormatError::BadColour`]); the other fields mean what they mean in a
//! 16-byte record and are checked the same way.
//!
//! ## Narrow records and shared switch planes (flag [`FLAG_NARROW`])
//!
//! Written by default since session 17 (`fpt build --records compact`
//! writes the 8-byte records above, `wide` the 16-byte ones; every reader
//! of this crate takes all three). Three things change, each sized per
//! file so that small files pay for small numbers only:
//!
//! **Narrow layout** ([`NARROW_LEN`] = 8 bytes, after the colour table,
//! which thus stays at a fixed offset; the vertices follow it):
//!
//! | offset | type | field |
//! |---:|---|---|
//! | 0 | `u8` | bits of hidden_edges, `0..=8` (the largest mask's) |
//! | 1 | `u8` | record_len: bytes of one polygon record, exactly `⌈(sum of the five widths) / 8⌉`, at least 1 |
//! | 2 | `u16` | 0 |
//! | 4 | `u32` | extra_planes: plane records stored after the runs (see below) |
//!
//! The layout section's four widths are each at most 32; the five add up
//! to at most 64; anything else is `BadHeader("layout")`.
//!
//! **Polygon records** (`polygon_count` × record_len bytes): the first
//! record_len bytes of a little-endian `u64` holding, from bit 0 up,
//! first_index, run, source, colour index and hidden_edges, each in its
//! width, the bits above them zero (else [`FormatError::BadColour`]).
//! A curved model's triangles need 5 to 7 bytes instead of 8.
//!
//! **Run offsets** (flag [`FLAG_RUN_OFFSETS`], exactly with
//! [`FLAG_PLANES`]; session 26): with a plane table the run field of
//! polygon `id` holds `id − r`, `r` the run holding it. The field only
//! repeats what the runs' ends say, and `id − r` never decreases and
//! stays below the number of polygons that share a run with an earlier
//! one: 0 to 10 bits on the shared models (0 to 7 on the curved ones,
//! where nearly every polygon is a run of its own), instead of the 10 to
//! 15 bits of a plane index; a curved model's record is 4 to 6 bytes. A
//! reader finds the polygon's plane index in its run's record.
//!
//! **Shared switch planes**: a switch's plane is nearly always the plane of
//! some run (a feudal switch is a polygon's plane). The run section holds
//! `run_count + extra_planes` records of [`RUN_LEN`] bytes: the runs, then
//! the switch planes that no run has, whose end field is 0. A switch record
//! is then [`SWITCH_REF_LEN`] = 4 bytes, a `u32` index below
//! `run_count + extra_planes` of the record whose plane (its first 16 bytes)
//! is the switch's, bit for bit. The walk's facing test reads the same
//! floats as from a 16-byte switch record, so the order is the same.
//!
//! ## Plane table (flag [`FLAG_PLANES`])
//!
//! Opt-in since session 21 (`fpt build --records table`; the default
//! `narrow` writes the 20-byte runs of sessions 17 to 20), when the file
//! has at most 65,535 polygons and 65,536 distinct planes and the table
//! makes the file no larger; read only with fpt-nostd's `plane-table`
//! feature. On a curved model nearly every polygon is a run
//! of its own and a plane is shared by the pieces of one split face in
//! several bunches, so the 16 bytes of a plane were stored once per run;
//! with the table they are stored once per distinct plane:
//!
//! * the narrow layout's `extra_planes` field is the table's length `P`;
//! * the **plane table** (`P` entries of [`PLANE_LEN`] = 16 bytes: normal
//!   `f32 × 3`, offset `f32`, as a run's first 16 bytes) comes before the
//!   runs; every entry is finite, each distinct bit pattern once (the
//!   facing tests read the same floats as from a 20-byte run, so the
//!   order is the same);
//! * a **run** is [`TABLE_RUN_LEN`] = 4 bytes: `u16` end, then the `u16`
//!   index of its plane (below `P`); there are no extra plane records;
//! * a **switch record** (4 bytes) is the index of its plane's entry
//!   (below `P`);
//! * a polygon's **run field** holds its run offset (see **Run offsets** above; files of
//!   sessions 21 to 25 held the run's plane index there: they lack
//!   [`FLAG_RUN_OFFSETS`], and a reader of this version refuses them).
//!
//! `Tree::from_bytes` checks every entry finite
//! ([`FormatError::NonFinite`]`("plane table")`), every run's plane index
//! below `P` and every polygon's run offset naming its run
//! ([`FormatError::BadRuns`]), every switch index below `P`
//! ([`FormatError::BadSwitch`]). A walk with a facing memo (cores without
//! an FPU) numbers the planes by their table index, so a plane shared by
//! several runs is tested once a frame.
//!
//! **Compact planes** (flag [`FLAG_COMPACT_PLANES`], only with
//! [`FLAG_PLANES`]; session 25, `fpt build --records table --planes
//! compact`): each table entry is [`COMPACT_PLANE_LEN`] = 8 bytes, the
//! unit normal times 32767 as `i16 × 3` and an `i16` offset `e` in steps
//! of `u / 32767`, `u` = `√3 · max(half_extent)` ([`plane_unit`]); the
//! plane is `m · x + e · u = 0`. Entries are distinct (several exact
//! planes that round to one entry share it). `Tree::from_bytes` checks
//! each entry well formed ([`FormatError::BadPlane`]: no component
//! −32768, `|m|` from 32766 to 32768) and `u` finite
//! ([`FormatError::BadHeader`]`("half_extent")`). Read only with
//! fpt-nostd's `compact-planes` feature (alone, it refuses `f32` tables,
//! and the walk has no `f32` table path). The walk tests
//! `m · a + e · (u · w) > 0` on the integers, the view in fixed point
//! once a walk (see `format/planes.rs`); the builder's order was computed
//! on the exact
//! planes, which the rounded ones can contradict only for an eye within
//! about `radius / 20,000` of the plane, where the polygon is edge-on (the
//! error analysis is in `format/planes.rs`, the measured pictures in
//! `docs/tree-format-sessions.md`, "Session 25").
//!
//! ## Vertex index list (`index_count` entries of `index_size` bytes)
//!
//! `u16` or `u32` indices into the vertex section.
//!
//! ## Edges (optional: `index_count` entries of [`EDGE_LEN`] = 4 bytes)
//!
//! Present when flag [`FLAG_EDGES`] is set (the serializer writes it when
//! the scene declares the `outline` effect). Entry `j` describes the edge
//! that starts at index entry `j`: from that vertex to the next one of the
//! same polygon (the last one's wraps to the polygon's first), so every
//! edge of every polygon, whatever its vertex count, has one.
//!
//! | offset | type | field |
//! |---:|---|---|
//! | 0 | `i8 × 3` | neighbour normal: for a [`EDGE_SOFT`] edge, the unit plane normal of the polygon across the edge, times 127 and rounded; 0 otherwise |
//! | 3 | `u8` | kind: [`EDGE_DRAWN`] 0, [`EDGE_HIDDEN`] 1 or [`EDGE_SOFT`] 2; other values are rejected |
//!
//! The kinds, decided by the builder from the polygon across the edge
//! (sharing it vertex for vertex, in the opposite direction):
//! * **drawn**: a feature edge (the faces meet at a dihedral angle above
//!   the crease angle, `fpt build --crease DEG`, default 30°), a colour
//!   boundary, or a boundary of the mesh (no such neighbour);
//! * **hidden**: inside one face (as `hidden_edges` above: a piece of the
//!   same source face, or a coplanar neighbour of the same colour);
//! * **soft**: a smooth edge (same colour, dihedral angle at most the
//!   crease angle): drawn only when it is a silhouette, i.e. when its
//!   neighbour faces the other way from the viewer than the polygon does
//!   (the neighbour's facing taken at the edge's first vertex, with the
//!   stored normal).
//!
//! ## Corner normals (optional: `index_count` entries of [`NORMAL_LEN`] = 3 bytes)
//!
//! Present when flag [`FLAG_NORMALS`] is set (the serializer writes it when
//! the scene declares the `smooth` effect). Entry `j` is the vertex normal
//! of index entry `j`, a polygon's corner: `i8 × 3`, the unit normal times
//! 127 and rounded, on the polygon's front side. A vertex shared by faces
//! that meet at a crease has a different normal in each face's corner, so
//! feature edges stay sharp. Each component is in `−127..=127` and the
//! vector is not zero; anything else is rejected.
//!
//! ## Runs (`run_count` entries of [`RUN_LEN`] = 20 bytes)
//!
//! A run is a non-empty range of consecutive polygon ids that share one
//! plane (the writer groups the polygons of a bunch by their exact stored
//! plane): triangles of one flat CAD face, or the coplanar polygons of a
//! switch's on-plane bunch, are one run, and the walk tests the facing of the
//! run once instead of once per polygon, with the same result.
//!
//! | offset | type | field |
//! |---:|---|---|
//! | 0 | `f32 × 3` | plane normal `n` (unit, outward) |
//! | 12 | `f32` | plane offset `d'`, relative to the origin: `n · (x − origin) + d' = 0` |
//! | 16 | `u32` | end: one past the last polygon id of the run |
//!
//! Run `r` holds the polygons `end[r − 1] .. end[r]` (run 0 starts at 0): the
//! ends strictly increase and the last is `polygon_count`, so the runs tile
//! the polygons and each polygon's `run` field names the one run holding it.
//! There are no runs when there are no polygons.
//!
//! ## Bunches (`bunch_count + 1` entries of `u32`, or of `u16` with [`FLAG_SMALL`])
//!
//! Polygons are numbered so that every bunch is a contiguous range of runs:
//! bunch `b` holds the runs `offset[b] .. offset[b + 1]` (so the polygons
//! from the start of the first to the end of the last). The offsets start at
//! 0, never decrease and end at `run_count`, so every run, hence every
//! polygon, is in exactly one bunch. Bunches may be empty.
//!
//! ## Connecting nodes (`node_count` entries of [`NODE_LEN`] = 12 bytes, or of [`SMALL_NODE_LEN`] = 8 with [`FLAG_SMALL`])
//!
//! | offset | type | field |
//! |---:|---|---|
//! | 0 | `u32` | first_bunch |
//! | 4 | `u32` | level_count `n` |
//! | 8 | `u32` | switch: index of its switch node, or [`NO_SWITCH`] |
//!
//! A node's bunches are `first_bunch ..`: `F_1, B_1, F_2, B_2, …, F_n, B_n`,
//! then `O_k` of its switch if it has one. The nodes tile the bunch section in
//! order (node 0 starts at bunch 0, each next node where the previous ends).
//!
//! **Small walk records** (flag [`FLAG_SMALL`], session 22; written when
//! the file has at most 65,535 runs, 32,767 switches and 65,535 levels in
//! a node): a bunch offset is a `u16`, and a node record is 8 bytes:
//! `u32` first_bunch, `u16` level_count, `i16` switch (−1: none, which a
//! sign-extending load makes [`NO_SWITCH`]), so the walk reads them with
//! as many loads as the wide ones. A reader without fpt-nostd's
//! `large-trees` feature reads only such files (its walk then has one
//! layout, chosen at compile time: a choice per read cost the firmware's
//! frames 0.5 %); the host tools read both.
//!
//! **Tree layout rule.** Node 0 is the root. The nodes are stored in
//! breadth-first order: the `k`-th node (counting from 0, in storage order)
//! that has a switch owns switch `k`, and switch `k`'s children are the
//! connecting nodes `2k + 1` (the group in front of its plane, `G_f`) and
//! `2k + 2` (behind it, `G_b`). This makes the node graph a tree by
//! construction, checkable in one pass without allocation (see
//! [`crate::reader`]); a BSP tree is stored the same way, with no levels.
//!
//! ## Switch nodes (`switch_count` entries of [`SWITCH_LEN`] = 16 bytes, or of 4 with [`FLAG_NARROW`])
//!
//! | offset | type | field |
//! |---:|---|---|
//! | 0 | `f32 × 3` | plane normal |
//! | 12 | `f32` | plane offset `d'`, relative to the origin as for polygons |
//!
//! ## Checksum (4 bytes)
//!
//! The last 4 bytes are the CRC-32 (IEEE 802.3 / zlib, [`crc32`]) of all
//! bytes before them.

mod error;
mod planes;
mod sections;
pub use error::FormatError;
pub(crate) use planes::INV_SCALE as COMPACT_INV_SCALE;
pub use planes::{
    compact_fields, compact_plane, compact_plane_ok, compact_side, plane_unit, COMPACT_PLANE_LEN,
};
pub use sections::{Counts, Narrow, Records, Sections};

/// The first four bytes of every tree file.
pub const MAGIC: [u8; 4] = *b"FPTR";
/// The format version this crate reads and writes.
pub const VERSION: u16 = 3;
/// Length of the header in bytes.
pub const HEADER_LEN: usize = 112;
/// Length of one polygon record.
pub const POLYGON_LEN: usize = 16;
/// Length of one compact polygon record ([`FLAG_COMPACT`]).
pub const COMPACT_POLYGON_LEN: usize = 8;
/// Length of the layout section of a compact file.
pub const LAYOUT_LEN: usize = 8;
/// Length of one colour table entry.
pub const COLOUR_LEN: usize = 3;
/// Header flag: compact polygon records, with the layout and colour
/// sections.
pub const FLAG_COMPACT: u32 = 1 << 3;
/// Bit of a compact record where hidden_edges starts; the other fields
/// fit below it.
pub const COMPACT_HIDDEN_SHIFT: u32 = 56;
/// Header flag (with [`FLAG_COMPACT`] only): narrow records and shared
/// switch planes: polygon records of the layout's length, a 16-byte
/// layout section, and switch records that name a plane record.
pub const FLAG_NARROW: u32 = 1 << 4;
/// Length of the narrow layout section of a file with [`FLAG_NARROW`]
/// (after the colour table).
pub const NARROW_LEN: usize = 8;
/// Length of one switch record of a file with [`FLAG_NARROW`]: the index
/// of its plane record.
pub const SWITCH_REF_LEN: usize = 4;
/// Header flag (with [`FLAG_NARROW`] only): a shared plane table. Every
/// distinct run and switch plane is stored once ([`PLANE_LEN`] bytes) in
/// a table before the runs, a run is a [`TABLE_RUN_LEN`]-byte record
/// (`u16` end, `u16` plane index), and a polygon's run field and a
/// switch record hold plane indices.
pub const FLAG_PLANES: u32 = 1 << 5;
/// Header flag (set exactly when [`FLAG_PLANES`] is): a polygon record's
/// run field holds `id − run`, how many polygons before it share a run
/// with an earlier one (0 for every polygon of a curved model whose
/// polygons are runs of their own), instead of its run's plane index: a
/// narrower field. The polygon's plane is its run's.
pub const FLAG_RUN_OFFSETS: u32 = 1 << 8;
/// Length of one plane table entry ([`FLAG_PLANES`]): normal, offset.
pub const PLANE_LEN: usize = 16;
/// Header flag (with [`FLAG_PLANES`] only): compact plane table entries,
/// [`COMPACT_PLANE_LEN`] bytes each (`i16` normal and offset, see
/// [`compact_side`]), instead of [`PLANE_LEN`].
pub const FLAG_COMPACT_PLANES: u32 = 1 << 7;
/// Length of one run record with a plane table ([`FLAG_PLANES`]).
pub const TABLE_RUN_LEN: usize = 4;
/// Byte offsets inside a run record of a file with a plane table.
pub mod table_run {
    /// `u16` one past the last polygon id of the run.
    pub const END: usize = 0;
    /// `u16` index of the run's plane in the plane table.
    pub const PLANE: usize = 2;
}
/// Length of one run record.
pub const RUN_LEN: usize = 20;
/// Length of one connecting node record.
pub const NODE_LEN: usize = 12;
/// Length of one connecting node record with [`FLAG_SMALL`].
pub const SMALL_NODE_LEN: usize = 8;
/// Header flag: small walk records, `u16` bunch offsets and 8-byte node
/// records ([`SMALL_NODE_LEN`]).
pub const FLAG_SMALL: u32 = 1 << 6;
/// Largest run count of a file with [`FLAG_SMALL`].
pub const SMALL_MAX_RUNS: u32 = u16::MAX as u32;
/// Largest switch count of a file with [`FLAG_SMALL`] (a switch index is
/// an `i16`).
pub const SMALL_MAX_SWITCHES: u32 = i16::MAX as u32;
/// Length of one switch node record.
pub const SWITCH_LEN: usize = 16;
/// Length of the trailing checksum.
pub const CRC_LEN: usize = 4;
/// Header flag: the model is a closed volume.
pub const FLAG_CLOSED: u32 = 1;
/// Header flag: the edge section is present.
pub const FLAG_EDGES: u32 = 1 << 1;
/// Length of one edge record.
pub const EDGE_LEN: usize = 4;
/// Header flag: the corner normal section is present.
pub const FLAG_NORMALS: u32 = 1 << 2;
/// Length of one corner normal record.
pub const NORMAL_LEN: usize = 3;
/// Edge kind: an outline (feature edge, colour or mesh boundary).
pub const EDGE_DRAWN: u8 = 0;
/// Edge kind: inside a face, never drawn.
pub const EDGE_HIDDEN: u8 = 1;
/// Edge kind: a smooth edge, drawn only as a silhouette.
pub const EDGE_SOFT: u8 = 2;
/// The `switch` field of a connecting node without a switch.
pub const NO_SWITCH: u32 = u32::MAX;
/// Largest `q32` shift (keeps `2^-shift` a normal `f32`).
pub const MAX_SHIFT: u8 = 126;
/// Largest magnitude of a `q16` coordinate.
pub const Q16_MAX: i16 = 32767;

/// Byte offsets of the header fields (see the table in the module docs).
pub mod header {
    /// `[u8; 4]` magic.
    pub const MAGIC: usize = 0;
    /// `u16` version.
    pub const VERSION: usize = 4;
    /// `u16` header length.
    pub const HEADER_LEN: usize = 6;
    /// `u32` file length.
    pub const FILE_LEN: usize = 8;
    /// `u32` flags.
    pub const FLAGS: usize = 12;
    /// `u32` effect flags.
    pub const EFFECTS: usize = 16;
    /// `u8` vertex format code.
    pub const VERTEX_FORMAT: usize = 20;
    /// `u8` q32 shift.
    pub const SHIFT: usize = 21;
    /// `u8` bytes per vertex index.
    pub const INDEX_SIZE: usize = 22;
    /// `u8` up axis code ([`super::UpAxis`]).
    pub const UP_AXIS: usize = 23;
    /// `u32` maximum depth.
    pub const MAX_DEPTH: usize = 24;
    /// `u32` vertex count.
    pub const VERTEX_COUNT: usize = 28;
    /// `u32` polygon count.
    pub const POLYGON_COUNT: usize = 32;
    /// `u32` index count.
    pub const INDEX_COUNT: usize = 36;
    /// `u32` bunch count.
    pub const BUNCH_COUNT: usize = 40;
    /// `u32` connecting node count.
    pub const NODE_COUNT: usize = 44;
    /// `u32` switch node count.
    pub const SWITCH_COUNT: usize = 48;
    /// `u32` run count.
    pub const RUN_COUNT: usize = 52;
    /// `f64 × 3` origin.
    pub const ORIGIN: usize = 56;
    /// `f32 × 3` half extent.
    pub const HALF_EXTENT: usize = 80;
    /// `f32` bounding sphere radius.
    pub const RADIUS: usize = 92;
    /// `u32` vertices of the largest polygon.
    pub const POLYGON_VERTICES: usize = 96;
    /// `u32` the vertex capacity a renderer needs.
    pub const SCRATCH_VERTICES: usize = 100;
    /// `u32` working memory words for one walk a frame.
    pub const MEMORY_WORDS: usize = 104;
    /// `u32` reserved, 0.
    pub const RESERVED32: usize = 108;
}

/// Planes a polygon is clipped against (the near plane and four
/// guard-band planes, see [`crate::raster::clip`]).
const CLIP_PLANES: u32 = 5;

/// The vertex capacity that a polygon of `vertices` vertices, `reflex` of
/// them reflex (interior angle above 180°; 0 for a convex polygon), needs
/// at every stage of the renderer: `vertices + 5 · (reflex + 1)`,
/// saturating.
///
/// Why: a line meets the inside of a simple polygon with `r` reflex
/// vertices in at most `r + 1` segments, so clipping it against one plane
/// crosses its boundary at most `2(r + 1)` times and adds at most `r + 1`
/// vertices (a crossing pair adds two and removes at least one outside
/// vertex), and the vertices a clip adds are convex. Five planes: at most
/// `5(r + 1)` more. A convex polygon: `vertices + 5`.
///
/// ```
/// use fpt_nostd::format::scratch_vertices_for;
/// assert_eq!(scratch_vertices_for(4, 0), 9); // a quad
/// assert_eq!(scratch_vertices_for(6, 1), 16); // an L-shaped face
/// ```
pub const fn scratch_vertices_for(vertices: u32, reflex: u32) -> u32 {
    vertices.saturating_add(CLIP_PLANES.saturating_mul(reflex.saturating_add(1)))
}

/// Byte offsets inside a polygon record.
pub mod polygon {
    /// `u32` first index.
    pub const FIRST_INDEX: usize = 0;
    /// `u32` run holding the polygon.
    pub const RUN: usize = 4;
    /// `u32` source face.
    pub const SOURCE: usize = 8;
    /// `u8 × 3` colour, then one zero byte.
    pub const COLOR: usize = 12;
}

/// Byte offsets inside a run record.
pub mod run {
    /// `f32 × 3` normal.
    pub const NORMAL: usize = 0;
    /// `f32` plane offset relative to the origin.
    pub const D: usize = 12;
    /// `u32` one past the last polygon id of the run.
    pub const END: usize = 16;
}

/// Byte offsets inside a connecting node record.
pub mod node {
    /// `u32` first bunch.
    pub const FIRST_BUNCH: usize = 0;
    /// `u32` number of levels (`u16` with [`super::FLAG_SMALL`]).
    pub const LEVEL_COUNT: usize = 4;
    /// `u32` switch index or [`super::NO_SWITCH`] (`i16` at byte 6 with
    /// [`super::FLAG_SMALL`], −1 for none).
    pub const SWITCH: usize = 8;
    /// `i16` switch index of a small record.
    pub const SMALL_SWITCH: usize = 6;
}

/// How vertex coordinates are encoded (chosen when the file is built).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VertexFormat {
    /// `f32` offsets from the origin: 12 bytes a vertex.
    F32,
    /// `i16` quantized in the bounding box: 6 bytes a vertex.
    Q16,
    /// `i32` fixed point with a global shift: 12 bytes a vertex.
    Q32,
}

impl VertexFormat {
    /// All formats, in code order.
    pub const ALL: [VertexFormat; 3] = [VertexFormat::F32, VertexFormat::Q16, VertexFormat::Q32];

    /// The code stored in the header.
    pub const fn code(self) -> u8 {
        match self {
            VertexFormat::F32 => 0,
            VertexFormat::Q16 => 1,
            VertexFormat::Q32 => 2,
        }
    }

    /// The format with header code `c`.
    pub const fn from_code(c: u8) -> Option<VertexFormat> {
        match c {
            0 => Some(VertexFormat::F32),
            1 => Some(VertexFormat::Q16),
            2 => Some(VertexFormat::Q32),
            _ => None,
        }
    }

    /// Bytes per vertex.
    pub const fn vertex_len(self) -> usize {
        match self {
            VertexFormat::F32 | VertexFormat::Q32 => 12,
            VertexFormat::Q16 => 6,
        }
    }

    /// The command-line name: `f32`, `q16` or `q32`.
    pub const fn name(self) -> &'static str {
        match self {
            VertexFormat::F32 => "f32",
            VertexFormat::Q16 => "q16",
            VertexFormat::Q32 => "q32",
        }
    }

    /// The format called `name` (as [`VertexFormat::name`] spells it).
    pub fn from_name(name: &str) -> Option<VertexFormat> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// The model's up axis, recorded in the header by the builder so that a
/// viewer (`fpt render`, `fpt turntable`) shows the model upright without
/// being told. The renderer itself does not use it: it only draws through
/// the camera it is given.
///
/// ```
/// use fpt_nostd::format::UpAxis;
/// assert_eq!(UpAxis::from_code(0), Some(UpAxis::Y));
/// assert_eq!(UpAxis::Z.code(), 2);
/// assert_eq!(UpAxis::from_name("x"), Some(UpAxis::X));
/// assert_eq!(UpAxis::from_code(3), None);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum UpAxis {
    /// `+y` is up (code 0, also files that record nothing).
    #[default]
    Y,
    /// `+x` is up (code 1).
    X,
    /// `+z` is up (code 2), as in most CAD files.
    Z,
}

impl UpAxis {
    /// All axes, in code order.
    pub const ALL: [UpAxis; 3] = [UpAxis::Y, UpAxis::X, UpAxis::Z];

    /// The code stored in the header.
    pub const fn code(self) -> u8 {
        match self {
            UpAxis::Y => 0,
            UpAxis::X => 1,
            UpAxis::Z => 2,
        }
    }

    /// The axis with header code `c`.
    pub const fn from_code(c: u8) -> Option<UpAxis> {
        match c {
            0 => Some(UpAxis::Y),
            1 => Some(UpAxis::X),
            2 => Some(UpAxis::Z),
            _ => None,
        }
    }

    /// The command-line name: `x`, `y` or `z`.
    pub const fn name(self) -> &'static str {
        match self {
            UpAxis::Y => "y",
            UpAxis::X => "x",
            UpAxis::Z => "z",
        }
    }

    /// The axis called `name` (as [`UpAxis::name`] spells it).
    pub fn from_name(name: &str) -> Option<UpAxis> {
        Self::ALL.into_iter().find(|a| a.name() == name)
    }
}

/// The CRC-32 of `bytes` (IEEE 802.3, the one of zlib and PNG).
pub fn crc32(bytes: &[u8]) -> u32 {
    const CRC: crc::Crc<u32> = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC);
    CRC.checksum(bytes)
}

// Field readers. They never panic: a read past the end yields 0. The reader
// only reads at offsets that validation has proven in range, so the fallback
// is never taken on a validated file; it exists so that no panic path is
// compiled in at all.

/// Reads `N` bytes at `off`, or zeros if out of range.
#[inline]
pub(crate) fn rd<const N: usize>(b: &[u8], off: usize) -> [u8; N] {
    off.checked_add(N)
        .and_then(|end| b.get(off..end))
        .and_then(|s| s.try_into().ok())
        .unwrap_or([0; N])
}

/// `u8` at `off`.
#[inline]
pub(crate) fn rd_u8(b: &[u8], off: usize) -> u8 {
    b.get(off).copied().unwrap_or(0)
}

/// Little-endian `u16` at `off`.
#[inline]
pub(crate) fn rd_u16(b: &[u8], off: usize) -> u16 {
    u16::from_le_bytes(rd(b, off))
}

/// Little-endian `u32` at `off`.
#[inline]
pub(crate) fn rd_u32(b: &[u8], off: usize) -> u32 {
    u32::from_le_bytes(rd(b, off))
}

/// Little-endian `i16` at `off`.
#[inline]
pub(crate) fn rd_i16(b: &[u8], off: usize) -> i16 {
    i16::from_le_bytes(rd(b, off))
}

/// Little-endian `i32` at `off`.
#[inline]
pub(crate) fn rd_i32(b: &[u8], off: usize) -> i32 {
    i32::from_le_bytes(rd(b, off))
}

/// Little-endian `f32` at `off`.
#[inline]
pub(crate) fn rd_f32(b: &[u8], off: usize) -> f32 {
    f32::from_le_bytes(rd(b, off))
}

/// Little-endian `f64` at `off`.
#[inline]
pub(crate) fn rd_f64(b: &[u8], off: usize) -> f64 {
    f64::from_le_bytes(rd(b, off))
}

/// Record `i` of `L` bytes of a section `s` (a subslice holding whole
/// records), or zeros if out of range. With `s` sliced once to its validated
/// length, this is one comparison, and the fields are then read from a
/// fixed-size array with no further checks.
#[inline(always)]
pub(crate) fn rec<const L: usize>(s: &[u8], i: usize) -> [u8; L] {
    let start = i.wrapping_mul(L);
    start
        .checked_add(L)
        .and_then(|end| s.get(start..end))
        .and_then(|r| r.try_into().ok())
        .unwrap_or([0; L])
}

/// The 16 bytes of a plane (normal, offset) at byte `at` of section `s`,
/// borrowed in place, or zeros if out of range: a run's or a switch's
/// plane as the walk reads it (a copy of the whole record, as [`rec`]
/// makes, kept its zero fallback in registers: session 20, the firmware's
/// full frames 0.5–11 k cheaper a view).
#[inline(always)]
pub(crate) fn plane_at(s: &[u8], at: usize) -> &[u8; 16] {
    s.get(at..)
        .and_then(|r| r.first_chunk::<16>())
        .unwrap_or(&[0; 16])
}

/// Little-endian `u64` at `off`.
#[inline]
pub(crate) fn rd_u64(b: &[u8], off: usize) -> u64 {
    u64::from_le_bytes(rd(b, off))
}

/// Little-endian `u32` at byte `at` of a record, or 0 past its end (with a
/// constant `at`, the check folds away).
#[inline(always)]
pub(crate) fn le_u32<const L: usize>(r: &[u8; L], at: usize) -> u32 {
    match r.get(at..at + 4).and_then(|b| b.try_into().ok()) {
        Some(b) => u32::from_le_bytes(b),
        None => 0,
    }
}

/// Little-endian `f32` at byte `at` of a record.
#[inline(always)]
pub(crate) fn le_f32<const L: usize>(r: &[u8; L], at: usize) -> f32 {
    f32::from_bits(le_u32(r, at))
}

/// Three little-endian `f32` at `off`.
#[inline]
pub(crate) fn rd_f32x3(b: &[u8], off: usize) -> [f32; 3] {
    [
        rd_f32(b, off),
        rd_f32(b, off.wrapping_add(4)),
        rd_f32(b, off.wrapping_add(8)),
    ]
}

#[cfg(test)]
mod tests;
