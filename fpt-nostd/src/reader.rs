//! The checked, allocation-free reader of a tree file.
//!
//! # Contract
//!
//! [`Tree::from_bytes`] is the only way to get a [`Tree`], and it validates
//! the whole file once, without allocating:
//!
//! - the magic, the version, the header fields and the exact file length;
//! - the CRC-32 over everything before the trailing checksum;
//! - the section sizes implied by the counts against the file length;
//! - every float that geometry is computed from is finite (origin, half
//!   extent, radius, `f32` vertices, polygon and switch planes);
//! - every vertex index is below the vertex count, every polygon has at least
//!   3 vertices and the polygons tile the index list;
//! - the bunch offsets tile the polygons (each polygon is in exactly one
//!   bunch), the nodes tile the bunches (each bunch belongs to exactly one
//!   level or switch);
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

use crate::format::{
    crc32, header as h, node as nd, polygon as pg, rd, rd_f32, rd_f32x3, rd_f64, rd_i16, rd_i32,
    rd_u16, rd_u32, rd_u8, Counts, FormatError, Sections, VertexFormat, CRC_LEN, FLAG_CLOSED,
    HEADER_LEN, MAGIC, MAX_SHIFT, NODE_LEN, NO_SWITCH, POLYGON_LEN, Q16_MAX, SWITCH_LEN, VERSION,
};

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

    fn is_finite(&self) -> bool {
        self.normal.iter().all(|x| x.is_finite()) && self.d.is_finite()
    }
}

/// A vertex as stored, before decoding (see [`VertexFormat`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RawVertex {
    /// `f32` offset from the origin.
    F32([f32; 3]),
    /// `q16`: offset `half_extent[axis] · q / 32767`.
    Q16([i16; 3]),
    /// `q32`: offset `q · 2^-shift`.
    Q32([i32; 3]),
}

/// What decoding a vertex needs; copied into every [`PolygonRef`].
#[derive(Clone, Copy, Debug)]
struct Geometry<'a> {
    bytes: &'a [u8],
    vertices: usize,
    polygons: usize,
    indices: usize,
    polygon_count: u32,
    index_count: u32,
    format: VertexFormat,
    index_size: u8,
    shift: u8,
    origin: [f64; 3],
    half_extent: [f32; 3],
    /// `half_extent / 32767`, per axis.
    q16_scale: [f32; 3],
    /// `2^-shift`.
    q32_scale: f32,
}

impl<'a> Geometry<'a> {
    #[inline]
    fn index(&self, j: u32) -> u32 {
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
    fn vertex_off(&self, v: u32) -> usize {
        self.vertices
            .wrapping_add((v as usize).wrapping_mul(self.format.vertex_len()))
    }

    #[inline]
    fn raw(&self, v: u32) -> RawVertex {
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
    fn decode(&self, r: RawVertex) -> [f32; 3] {
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
    fn decode_model(&self, r: RawVertex) -> [f64; 3] {
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

    #[inline]
    fn plane_at(&self, off: usize) -> Plane {
        Plane {
            normal: rd_f32x3(self.bytes, off),
            d: rd_f32(self.bytes, off.wrapping_add(12)),
        }
    }

    #[inline]
    fn polygon_off(&self, id: u32) -> usize {
        self.polygons
            .wrapping_add((id as usize).wrapping_mul(POLYGON_LEN))
    }

    /// The index range `first..end` of polygon `id < polygon_count`.
    #[inline]
    fn polygon_range(&self, id: u32) -> (u32, u32) {
        let first = rd_u32(
            self.bytes,
            self.polygon_off(id).wrapping_add(pg::FIRST_INDEX),
        );
        let end = if id < self.polygon_count.saturating_sub(1) {
            rd_u32(
                self.bytes,
                self.polygon_off(id.wrapping_add(1))
                    .wrapping_add(pg::FIRST_INDEX),
            )
        } else {
            self.index_count
        };
        (first, end)
    }
}

/// The polygon planes by id: all that culling a class needs, small enough
/// to copy into every class (unlike the whole [`Tree`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlaneTable<'a> {
    bytes: &'a [u8],
    base: usize,
}

impl PlaneTable<'_> {
    /// The plane of polygon `id < polygon_count`.
    #[inline]
    pub(crate) fn plane(&self, id: u32) -> Plane {
        let off = self
            .base
            .wrapping_add((id as usize).wrapping_mul(POLYGON_LEN))
            .wrapping_add(pg::NORMAL);
        Plane {
            normal: rd_f32x3(self.bytes, off),
            d: rd_f32(self.bytes, off.wrapping_add(12)),
        }
    }
}

/// One connecting node record.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NodeRec {
    pub first_bunch: u32,
    pub level_count: u32,
    pub switch: u32,
}

/// A validated tree file, read in place.
#[derive(Clone, Copy, Debug)]
pub struct Tree<'a> {
    g: Geometry<'a>,
    bunches: usize,
    nodes: usize,
    switches: usize,
    counts: Counts,
    level_count: u32,
    flags: u32,
    effects: u32,
    max_depth: u32,
    radius: f32,
}

/// One polygon of a [`Tree`].
#[derive(Clone, Copy, Debug)]
pub struct PolygonRef<'a> {
    g: Geometry<'a>,
    id: u32,
    first: u32,
    count: u32,
}

impl<'a> PolygonRef<'a> {
    /// Its id: its position in the file.
    pub fn id(&self) -> u32 {
        self.id
    }

    /// The face of the input mesh it came from.
    pub fn source(&self) -> u32 {
        rd_u32(
            self.g.bytes,
            self.g.polygon_off(self.id).wrapping_add(pg::SOURCE),
        )
    }

    /// Its colour, RGB.
    pub fn color(&self) -> [u8; 3] {
        let c: [u8; 4] = rd(
            self.g.bytes,
            self.g.polygon_off(self.id).wrapping_add(pg::COLOR),
        );
        [c[0], c[1], c[2]]
    }

    /// Its plane, relative to the origin.
    pub fn plane(&self) -> Plane {
        self.g
            .plane_at(self.g.polygon_off(self.id).wrapping_add(pg::NORMAL))
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

    /// Vertex `i` in model coordinates (origin + offset, in `f64`, exact for
    /// every format); the origin when `i ≥ vertex_count()`.
    pub fn vertex_model(&self, i: usize) -> [f64; 3] {
        self.g.decode_model(self.vertex_raw(i))
    }

    /// The vertices in order, relative to the origin.
    pub fn vertices(&self) -> impl Iterator<Item = [f32; 3]> + 'a {
        let p = *self;
        (0..p.vertex_count()).map(move |i| p.vertex(i))
    }
}

fn zero_raw(f: VertexFormat) -> RawVertex {
    match f {
        VertexFormat::F32 => RawVertex::F32([0.0; 3]),
        VertexFormat::Q16 => RawVertex::Q16([0; 3]),
        VertexFormat::Q32 => RawVertex::Q32([0; 3]),
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
        if flags & !FLAG_CLOSED != 0 {
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
        if rd_u8(bytes, h::RESERVED8) != 0 || rd_u32(bytes, h::RESERVED32) != 0 {
            return Err(FormatError::BadHeader("reserved"));
        }
        let counts = Counts {
            vertices: rd_u32(bytes, h::VERTEX_COUNT),
            polygons: rd_u32(bytes, h::POLYGON_COUNT),
            indices: rd_u32(bytes, h::INDEX_COUNT),
            bunches: rd_u32(bytes, h::BUNCH_COUNT),
            nodes: rd_u32(bytes, h::NODE_COUNT),
            switches: rd_u32(bytes, h::SWITCH_COUNT),
        };
        let s = Sections::new(&counts, format, usize::from(index_size))
            .ok_or(FormatError::SectionSizes)?;
        if s.file_len != len {
            return Err(FormatError::SectionSizes);
        }
        if u64::from(counts.nodes) != 2 * u64::from(counts.switches) + 1 {
            return Err(FormatError::NotATree);
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

        let g = Geometry {
            bytes,
            vertices: s.vertices,
            polygons: s.polygons,
            indices: s.indices,
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
            bunches: s.bunches,
            nodes: s.nodes,
            switches: s.switches,
            counts,
            level_count: 0,
            flags,
            effects: rd_u32(bytes, h::EFFECTS),
            max_depth: rd_u32(bytes, h::MAX_DEPTH),
            radius,
        };
        tree.check_vertices()?;
        tree.check_polygons()?;
        tree.check_bunches()?;
        tree.level_count = tree.check_nodes()?;
        tree.check_switches()?;
        tree.check_depth()?;
        Ok(tree)
    }

    fn check_vertices(&self) -> Result<(), FormatError> {
        if self.g.format == VertexFormat::F32 {
            for v in 0..self.counts.vertices {
                if !finite3_f32(rd_f32x3(self.g.bytes, self.g.vertex_off(v))) {
                    return Err(FormatError::NonFinite("vertices"));
                }
            }
        }
        for j in 0..self.counts.indices {
            if self.g.index(j) >= self.counts.vertices {
                return Err(FormatError::IndexOutOfRange);
            }
        }
        Ok(())
    }

    fn check_polygons(&self) -> Result<(), FormatError> {
        let b = self.g.bytes;
        let mut prev = 0u32;
        for p in 0..self.counts.polygons {
            let rec = self.g.polygon_off(p);
            if !self.g.plane_at(rec.wrapping_add(pg::NORMAL)).is_finite() {
                return Err(FormatError::NonFinite("polygon planes"));
            }
            if rd_u8(b, rec.wrapping_add(pg::COLOR + 3)) != 0 {
                return Err(FormatError::BadPolygon(p));
            }
            let first = rd_u32(b, rec.wrapping_add(pg::FIRST_INDEX));
            if p == 0 {
                if first != 0 {
                    return Err(FormatError::BadPolygon(0));
                }
            } else if first.checked_sub(prev).is_none_or(|n| n < 3) {
                return Err(FormatError::BadPolygon(p - 1));
            }
            prev = first;
        }
        match self.counts.polygons.checked_sub(1) {
            Some(last) if self.counts.indices.checked_sub(prev).is_none_or(|n| n < 3) => {
                Err(FormatError::BadPolygon(last))
            }
            None if self.counts.indices != 0 => Err(FormatError::BadHeader("index_count")),
            _ => Ok(()),
        }
    }

    fn check_bunches(&self) -> Result<(), FormatError> {
        let mut prev = 0u32;
        for b in 0..=self.counts.bunches {
            let off = self.bunch_offset(b);
            if (b == 0 && off != 0) || off < prev {
                return Err(FormatError::BadBunches);
            }
            prev = off;
        }
        if prev != self.counts.polygons {
            return Err(FormatError::BadBunches);
        }
        Ok(())
    }

    /// Checks the bunch tiling and the switch numbering; returns the total
    /// number of levels.
    fn check_nodes(&self) -> Result<u32, FormatError> {
        let mut bunch = 0u64;
        let mut next_switch = 0u32;
        let mut levels = 0u64;
        for i in 0..self.counts.nodes {
            let n = self.node(i);
            if u64::from(n.first_bunch) != bunch {
                return Err(FormatError::BadNode(i));
            }
            let has_switch = n.switch != NO_SWITCH;
            if has_switch {
                if n.switch != next_switch || next_switch >= self.counts.switches {
                    return Err(FormatError::BadNode(i));
                }
                next_switch += 1;
            }
            bunch += 2 * u64::from(n.level_count) + u64::from(has_switch);
            levels += u64::from(n.level_count);
            if bunch > u64::from(self.counts.bunches) {
                return Err(FormatError::BadNode(i));
            }
        }
        if bunch != u64::from(self.counts.bunches) {
            return Err(FormatError::BadBunches);
        }
        if next_switch != self.counts.switches {
            return Err(FormatError::NotATree);
        }
        // levels ≤ bunches / 2, so it fits.
        u32::try_from(levels).map_err(|_| FormatError::BadBunches)
    }

    fn check_switches(&self) -> Result<(), FormatError> {
        for k in 0..self.counts.switches {
            if !self.switch_plane(k).is_finite() {
                return Err(FormatError::NonFinite("switch planes"));
            }
        }
        Ok(())
    }

    /// Breadth-first by layers. With the numbering checked by
    /// [`Self::check_nodes`], the switches of one layer are consecutive and
    /// their children are exactly the next nodes in storage order: layer
    /// `L + 1` is `end_L .. end_L + 2 · (switches in layer L)`. So a layer is
    /// a range, the pass needs no memory, and reaching `node_count` proves
    /// every node has exactly one parent above it: a tree.
    fn check_depth(&self) -> Result<(), FormatError> {
        let (mut start, mut end, mut depth) = (0u32, 1u32, 0u32);
        while start < end {
            depth += 1;
            let switches = (start..end)
                .filter(|&i| self.node(i).switch != NO_SWITCH)
                .count() as u32;
            start = end;
            // end = 1 + 2 · (switches so far) ≤ 1 + 2 · switch_count = node_count.
            end = end.saturating_add(switches.saturating_mul(2));
            if end > self.counts.nodes {
                return Err(FormatError::NotATree);
            }
        }
        if end != self.counts.nodes {
            return Err(FormatError::NotATree);
        }
        if depth != self.max_depth {
            return Err(FormatError::DepthMismatch);
        }
        Ok(())
    }

    /// Whether the model is a closed volume (back faces are culled).
    pub fn is_closed(&self) -> bool {
        self.flags & FLAG_CLOSED != 0
    }

    /// The scene's effect flags, as stored.
    pub fn effects(&self) -> u32 {
        self.effects
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

    /// Stored vertex `v` relative to the origin, decoded to `f32`.
    pub fn vertex(&self, v: u32) -> Option<[f32; 3]> {
        self.vertex_raw(v).map(|r| self.g.decode(r))
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

    // Internal accessors for the traversal: callers pass validated indices.

    /// Connecting node `i < node_count`.
    #[inline]
    pub(crate) fn node(&self, i: u32) -> NodeRec {
        let b = self.g.bytes;
        let o = self.nodes.wrapping_add((i as usize).wrapping_mul(NODE_LEN));
        NodeRec {
            first_bunch: rd_u32(b, o.wrapping_add(nd::FIRST_BUNCH)),
            level_count: rd_u32(b, o.wrapping_add(nd::LEVEL_COUNT)),
            switch: rd_u32(b, o.wrapping_add(nd::SWITCH)),
        }
    }

    /// Offset `b ≤ bunch_count` of the bunch section.
    #[inline]
    pub(crate) fn bunch_offset(&self, b: u32) -> u32 {
        rd_u32(
            self.g.bytes,
            self.bunches.wrapping_add((b as usize).wrapping_mul(4)),
        )
    }

    /// The polygon ids of bunch `b < bunch_count`.
    #[inline]
    pub(crate) fn bunch(&self, b: u32) -> (u32, u32) {
        (self.bunch_offset(b), self.bunch_offset(b.wrapping_add(1)))
    }

    /// The plane of switch `k < switch_count`.
    #[inline]
    pub(crate) fn switch_plane(&self, k: u32) -> Plane {
        self.g.plane_at(
            self.switches
                .wrapping_add((k as usize).wrapping_mul(SWITCH_LEN)),
        )
    }

    /// The polygon planes, for the walk's culling.
    #[inline]
    pub(crate) fn planes(&self) -> PlaneTable<'a> {
        PlaneTable {
            bytes: self.g.bytes,
            base: self.g.polygons,
        }
    }
}

#[cfg(test)]
mod tests;
