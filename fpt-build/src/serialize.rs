//! The serializer of the flat tree format read by `fpt_nostd::reader`.
//!
//! The layout is documented (field by field) in [`fpt_nostd::format`]; this
//! module writes it from an in-memory [`FpTree`]:
//!
//! - connecting nodes go in breadth-first order, which is the layout rule of
//!   the format (the `k`-th node with a switch owns switch `k`, whose children
//!   are nodes `2k + 1` and `2k + 2`);
//! - polygons are **renumbered** so that every bunch is a contiguous range of
//!   ids: file id `i` is tree polygon [`polygon_order`]`(tree)[i]`. Nodes
//!   are taken in storage order, and within a node the bunches
//!   `F_1, B_1, …, F_n, B_n, O`; within a bunch (whose order is free) the
//!   polygons with the same plane are made consecutive, in order of first
//!   appearance;
//! - each maximal sequence of polygons of one bunch with the same stored
//!   plane becomes one *run* (the plane is stored once, in the run): the walk
//!   tests a run's facing once for all of its polygons;
//! - geometry is stored relative to the bounding box centre (`origin`, in
//!   `f64`), planes re-expressed as `n · (x − origin) + d' = 0` with `d'`
//!   computed in `f64` before rounding to `f32`;
//! - vertices are encoded in the chosen [`VertexFormat`] and deduplicated by
//!   their encoding, which merges every pair of exactly equal vertices (and,
//!   for `q16`, vertices that quantize to the same point);
//! - vertex indices are `u16` when there are at most 65 536 vertices;
//! - polygon records are compact (8 bytes: bit fields as narrow as the
//!   largest value of each needs, colours in a table of the distinct ones
//!   in order of first use) unless [`SerializeOptions::compact`] is off or
//!   the fields need more than 56 bits together;
//! - with [`SerializeOptions::narrow`] (the default), a record takes only
//!   the bytes its five fields need, and a switch's plane is the index of
//!   a plane record: the first run with that exact plane, or one stored
//!   after the runs ([`fpt_nostd::format::FLAG_NARROW`]);
//! - bunch offsets are `u16` and node records 8 bytes when the tree has
//!   at most 65,535 runs, 32,767 switches and 65,535 levels in a node
//!   ([`fpt_nostd::format::FLAG_SMALL`]);
//! - with [`SerializeOptions::plane_table`] too (opt-in), every
//!   distinct run and switch plane is stored once in a table, a run is
//!   4 bytes (`u16` end, `u16` plane index), and a polygon's run field and
//!   a switch record name table entries
//!   ([`fpt_nostd::format::FLAG_PLANES`]; files of more than 65,535
//!   polygons keep the 20-byte runs).
//!
//! Every tree whose bunches hold each polygon exactly once, with at least 3
//! finite vertices each, serializes; the output passes
//! `fpt_nostd::reader::Tree::from_bytes`.

use std::collections::HashMap;
use std::fmt;

pub use fpt_nostd::format::VertexFormat;
use fpt_nostd::format::{
    crc32, header as h, polygon as pg, Counts, UpAxis, FLAG_CLOSED, HEADER_LEN, MAGIC, NO_SWITCH,
    POLYGON_LEN, RUN_LEN, VERSION,
};
use fpt_nostd::format::{COMPACT_POLYGON_LEN, FLAG_COMPACT};
use fpt_nostd::format::{EDGE_LEN, FLAG_EDGES, FLAG_NORMALS, NORMAL_LEN};
use fpt_nostd::format::{FLAG_COMPACT_PLANES, FLAG_PLANES, TABLE_RUN_LEN};
use fpt_nostd::format::{FLAG_NARROW, NARROW_LEN, SWITCH_REF_LEN};
use fpt_nostd::format::{FLAG_RUN_OFFSETS, FLAG_SMALL, SMALL_MAX_RUNS, SMALL_MAX_SWITCHES};
use glam::DVec3;

use crate::edges::{edge_kinds, hidden_edges, FaceKey, DEFAULT_CREASE_DEG};
use crate::geom::Plane;
use crate::normals::stored_corner_normals;
use crate::tree::{Connecting, FpTree};
use records::{Plan, PlanInput};

/// Choices made when writing a file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SerializeOptions {
    /// How vertices are encoded.
    pub vertex_format: VertexFormat,
    /// The scene's effects ([`fpt_nostd::effects::Effects`] bits), stored
    /// as they are; `None` stores the defaults for the tree's kind
    /// ([`fpt_nostd::effects::Effects::defaults`]).
    pub effects: Option<u32>,
    /// The model's up axis, recorded for viewers (header byte 23).
    pub up: UpAxis,
    /// The crease angle in degrees: two faces meeting at a sharper angle
    /// have a feature edge between them (the `outline` effect's edge
    /// section, written when the effects include `outline`).
    pub crease_deg: f32,
    /// Write compact polygon records (8 bytes each, with a colour table;
    /// [`fpt_nostd::format::FLAG_COMPACT`]) when the fields fit in 56
    /// bits (first index, run, source face and colour index together; a
    /// mesh of a million faces still fits); `false` writes the 16-byte
    /// records of the files made before compact records existed.
    pub compact: bool,
    /// With `compact`: narrow records and shared switch planes
    /// ([`fpt_nostd::format::FLAG_NARROW`]), when the five fields fit in
    /// 64 bits; `false` writes the 8-byte records of sessions 10 to 16.
    pub narrow: bool,
    /// With `narrow`: a shared plane table and 4-byte runs
    /// ([`fpt_nostd::format::FLAG_PLANES`]), when the file has at most
    /// 65,535 polygons and 65,536 distinct planes and is no larger for
    /// it; `false` (the default: the walk reads a table file's runs at a
    /// cost, see `docs/tree-format.md`) writes the 20-byte runs of
    /// session 17.
    pub plane_table: bool,
    /// With `plane_table`: compact table entries, 8 bytes instead of 16
    /// ([`fpt_nostd::format::FLAG_COMPACT_PLANES`]: planes rounded to
    /// about radius / 20,000); `false` writes the `f32` planes.
    pub compact_planes: bool,
}

impl Default for SerializeOptions {
    fn default() -> Self {
        SerializeOptions {
            vertex_format: VertexFormat::F32,
            effects: None,
            up: UpAxis::Y,
            crease_deg: DEFAULT_CREASE_DEG,
            compact: true,
            narrow: true,
            plane_table: true,
            compact_planes: true,
        }
    }
}

/// Why a tree cannot be written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SerializeError {
    /// A bunch names a polygon id beyond the polygon list.
    UnknownPolygon(u32),
    /// A polygon is in more than one bunch.
    DuplicatePolygon(u32),
    /// A polygon is in no bunch.
    UnplacedPolygon(u32),
    /// A polygon has fewer than 3 vertices.
    DegeneratePolygon(u32),
    /// A coordinate or a plane is not finite (or overflows `f32`).
    NonFinite,
    /// The model is too large for the chosen vertex format.
    OutOfRange(&'static str),
    /// The file would be larger than the format's `u32` sizes allow.
    TooLarge,
    /// The written file does not validate (a bug of the serializer: every
    /// tree that serializes should pass the reader).
    Invalid(fpt_nostd::format::FormatError),
}

impl fmt::Display for SerializeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SerializeError::UnknownPolygon(i) => write!(f, "bunch names unknown polygon {i}"),
            SerializeError::DuplicatePolygon(i) => write!(f, "polygon {i} is in two bunches"),
            SerializeError::UnplacedPolygon(i) => write!(f, "polygon {i} is in no bunch"),
            SerializeError::DegeneratePolygon(i) => {
                write!(f, "polygon {i} has fewer than 3 vertices")
            }
            SerializeError::NonFinite => f.write_str("non-finite coordinate or plane"),
            SerializeError::OutOfRange(why) => write!(f, "model out of range: {why}"),
            SerializeError::TooLarge => f.write_str("tree too large for the file format"),
            SerializeError::Invalid(e) => write!(f, "the written tree does not validate: {e}"),
        }
    }
}

impl std::error::Error for SerializeError {}

/// The connecting nodes in breadth-first (storage) order.
fn nodes_bfs(root: &Connecting) -> Vec<&Connecting> {
    let mut nodes = vec![root];
    let mut i = 0;
    while let Some(c) = nodes.get(i).copied() {
        if let Some(s) = &c.switch {
            nodes.push(&s.front);
            nodes.push(&s.back);
        }
        i += 1;
    }
    nodes
}

/// The bunches of one node in storage order: `F_1, B_1, …, F_n, B_n, O`.
fn node_bunches(c: &Connecting) -> impl Iterator<Item = &[u32]> {
    c.levels
        .iter()
        .flat_map(|l| [l.front.as_slice(), l.back.as_slice()])
        .chain(c.switch.iter().map(|s| s.on.as_slice()))
}

/// The exact bits of a plane, to group equal planes.
fn plane_key(p: &Plane) -> [u64; 4] {
    // `+ 0.0` makes -0.0 into 0.0: equal planes get equal keys.
    let n = p.normal + DVec3::ZERO;
    [n.x, n.y, n.z, p.d + 0.0].map(f64::to_bits)
}

/// The tree polygon id of every file polygon id: the renumbering that makes
/// each bunch a contiguous range, with the polygons of one plane consecutive
/// within their bunch. Fails unless the bunches hold every polygon of `tree`
/// exactly once.
pub fn polygon_order(tree: &FpTree) -> Result<Vec<u32>, SerializeError> {
    let n = tree.polygons.len();
    let mut seen = vec![false; n];
    let mut order = Vec::with_capacity(n);
    let mut first_seen: HashMap<[u64; 4], usize> = HashMap::new();
    for c in nodes_bfs(&tree.root) {
        for bunch in node_bunches(c) {
            let start = order.len();
            for &id in bunch {
                let slot = seen
                    .get_mut(id as usize)
                    .ok_or(SerializeError::UnknownPolygon(id))?;
                if std::mem::replace(slot, true) {
                    return Err(SerializeError::DuplicatePolygon(id));
                }
                order.push(id);
            }
            // Group by plane, keeping the order of first appearance (stable).
            first_seen.clear();
            let planes = &tree.polygons;
            let rank = |id: u32, first_seen: &mut HashMap<[u64; 4], usize>| {
                let next = first_seen.len();
                *first_seen
                    .entry(plane_key(&planes[id as usize].plane))
                    .or_insert(next)
            };
            let mut keyed: Vec<(usize, u32)> = order[start..]
                .iter()
                .map(|&id| (rank(id, &mut first_seen), id))
                .collect();
            keyed.sort_by_key(|&(r, _)| r);
            for (slot, (_, id)) in order[start..].iter_mut().zip(keyed) {
                *slot = id;
            }
        }
    }
    if let Some(i) = seen.iter().position(|&s| !s) {
        return Err(SerializeError::UnplacedPolygon(i as u32));
    }
    Ok(order)
}

/// `n` as a `u32` count or id.
fn count_u32(n: usize) -> Result<u32, SerializeError> {
    u32::try_from(n).map_err(|_| SerializeError::TooLarge)
}

fn put_u32(out: &mut Vec<u8>, x: u32) {
    out.extend_from_slice(&x.to_le_bytes());
}

fn put_plane(out: &mut Vec<u8>, p: [f32; 4]) {
    for x in p {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

/// Writes `tree` in the flat format (see the module docs).
pub fn serialize(tree: &FpTree, opts: &SerializeOptions) -> Result<Vec<u8>, SerializeError> {
    let order = polygon_order(tree)?;
    let nodes = nodes_bfs(&tree.root);
    let too_large = |_| SerializeError::TooLarge;

    // Geometry: bounding box, encoder, deduplicated vertices.
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for (i, p) in tree.polygons.iter().enumerate() {
        if p.verts.len() < 3 {
            return Err(SerializeError::DegeneratePolygon(i as u32));
        }
        for &v in &p.verts {
            if !v.is_finite() {
                return Err(SerializeError::NonFinite);
            }
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if tree.polygons.is_empty() {
        (lo, hi) = (DVec3::ZERO, DVec3::ZERO);
    }
    let enc = Encoder::new(opts.vertex_format, lo, hi)?;
    let mut vertex_ids: HashMap<Vec<u8>, u32> = HashMap::new();
    let mut vertex_bytes = Vec::new();
    let mut indices: Vec<u32> = Vec::new();
    let mut first_index = Vec::with_capacity(order.len());
    let mut radius = 0f64;
    // The renderer's capacities (`fpt_nostd::format`, header bytes 96..).
    let mut polygon_vertices = 0u32;
    let mut scratch_vertices = 0u32;
    for &id in &order {
        first_index.push(u32::try_from(indices.len()).map_err(too_large)?);
        let p = &tree.polygons[id as usize];
        let n = u32::try_from(p.verts.len()).map_err(too_large)?;
        let stored: Vec<DVec3> = p
            .verts
            .iter()
            .map(|&v| enc.encode(v).map(|b| enc.decode(&b)))
            .collect::<Result<_, _>>()?;
        // Reflex in the exact or in the stored geometry (which the renderer
        // transforms): either may be the one a clip plane meets.
        let reflex = (0..p.verts.len())
            .filter(|&i| {
                is_reflex(&p.verts, i, p.plane.normal) || is_reflex(&stored, i, p.plane.normal)
            })
            .count();
        polygon_vertices = polygon_vertices.max(n);
        scratch_vertices = scratch_vertices.max(fpt_nostd::format::scratch_vertices_for(
            n,
            u32::try_from(reflex).map_err(too_large)?,
        ));
        for &v in &p.verts {
            let bytes = enc.encode(v)?;
            let next = u32::try_from(vertex_ids.len()).map_err(too_large)?;
            let vid = *vertex_ids.entry(bytes).or_insert_with_key(|b| {
                // The sphere must hold both the exact and the stored vertex.
                radius = radius
                    .max((v - enc.origin).length())
                    .max(enc.decode(b).length());
                vertex_bytes.extend_from_slice(b);
                next
            });
            indices.push(vid);
        }
    }
    let index_size = if vertex_ids.len() <= 1 << 16 { 2 } else { 4 };

    // The stored plane of every file polygon, and the runs: maximal
    // sequences of one bunch with bit-identical stored planes.
    let planes = order
        .iter()
        .map(|&id| enc.plane(&tree.polygons[id as usize].plane))
        .collect::<Result<Vec<_>, _>>()?;
    let mut runs: Vec<([f32; 4], u32)> = Vec::new();
    let mut run_of = vec![0u32; order.len()];
    let mut switch_planes = Vec::new();
    let mut node_recs = Vec::with_capacity(nodes.len());
    let mut bunch_offsets = vec![0u32];
    let mut placed = 0usize;
    for c in &nodes {
        let first_bunch = u32::try_from(bunch_offsets.len() - 1).map_err(too_large)?;
        for b in node_bunches(c) {
            let start = placed;
            placed += b.len(); // ≤ polygon count, checked by polygon_order
            for fid in start..placed {
                let end = count_u32(fid + 1)?;
                let bits = |p: &[f32; 4]| p.map(f32::to_bits);
                match runs.last_mut() {
                    Some((plane, e)) if fid > start && bits(plane) == bits(&planes[fid]) => {
                        *e = end;
                    }
                    _ => runs.push((planes[fid], end)),
                }
                run_of[fid] = count_u32(runs.len() - 1)?;
            }
            bunch_offsets.push(count_u32(runs.len())?);
        }
        let switch = match &c.switch {
            Some(s) => {
                switch_planes.push(enc.plane(&s.plane)?);
                u32::try_from(switch_planes.len() - 1).map_err(too_large)?
            }
            None => NO_SWITCH,
        };
        let levels = u32::try_from(c.levels.len()).map_err(too_large)?;
        node_recs.push([first_bunch, levels, switch]);
    }

    let effects = opts
        .effects
        .unwrap_or(fpt_nostd::effects::Effects::defaults(tree.closed).bits());
    let outline = effects & fpt_nostd::effects::Effects::OUTLINE.bits() != 0;
    let smooth = effects & fpt_nostd::effects::Effects::SMOOTH.bits() != 0;
    // Every file polygon's vertex ids, and its stored plane's normal.
    let ends = first_index
        .iter()
        .skip(1)
        .map(|&f| f as usize)
        .chain([indices.len()]);
    let loops: Vec<&[u32]> = first_index
        .iter()
        .zip(ends)
        .map(|(&f, e)| &indices[f as usize..e])
        .collect();
    let plane_normals: Vec<[f32; 3]> = planes.iter().map(|p| [p[0], p[1], p[2]]).collect();
    // Outline masks, and the edge section's kinds with outlines (see
    // `crate::edges`).
    let (hidden, kinds) = {
        let keys: Vec<FaceKey> = order
            .iter()
            .zip(&planes)
            .map(|(&id, plane)| {
                let p = &tree.polygons[id as usize];
                FaceKey {
                    source: p.source,
                    plane: plane.map(f32::to_bits),
                    color: p.color,
                }
            })
            .collect();
        let kinds = if outline {
            edge_kinds(&loops, &keys, &plane_normals, opts.crease_deg)
        } else {
            vec![]
        };
        (hidden_edges(&loops, &keys), kinds)
    };

    let count = |n: usize| u32::try_from(n).map_err(too_large);
    let counts = Counts {
        vertices: count(vertex_ids.len())?,
        polygons: count(order.len())?,
        indices: count(indices.len())?,
        bunches: count(bunch_offsets.len() - 1)?,
        nodes: count(node_recs.len())?,
        switches: count(switch_planes.len())?,
        runs: count(runs.len())?,
        edges: if outline { count(indices.len())? } else { 0 },
        normals: if smooth { count(indices.len())? } else { 0 },
        // Small walk records whenever their fields hold the tree (what
        // a firmware reads without the `large-trees` feature).
        small: runs.len() <= SMALL_MAX_RUNS as usize
            && switch_planes.len() <= SMALL_MAX_SWITCHES as usize
            && node_recs.iter().all(|n| n[1] <= u32::from(u16::MAX)),
    };
    let plan = Plan::new(&PlanInput {
        tree,
        order: &order,
        first_index: &first_index,
        hidden: &hidden,
        runs: &runs,
        switch_planes: &switch_planes,
        counts: &counts,
        opts,
        index_size,
        plane_unit: fpt_nostd::format::plane_unit(enc.half_extent),
    })?;
    let Plan {
        layout,
        table,
        switch_refs,
        extra_planes,
        records,
        sections: s,
    } = plan;

    let mut out = Vec::with_capacity(s.file_len);
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&(HEADER_LEN as u16).to_le_bytes());
    put_u32(&mut out, s.file_len as u32);
    let edge_flag = if outline { FLAG_EDGES } else { 0 };
    let normal_flag = if smooth { FLAG_NORMALS } else { 0 };
    put_u32(
        &mut out,
        edge_flag
            | normal_flag
            | if tree.closed { FLAG_CLOSED } else { 0 }
            | if layout.is_some() { FLAG_COMPACT } else { 0 }
            | if records.is_some_and(|r| r.narrow.is_some()) {
                FLAG_NARROW
            } else {
                0
            }
            // A table's records hold run offsets.
            | match &table {
                Some(t) if t.compact => FLAG_PLANES | FLAG_RUN_OFFSETS | FLAG_COMPACT_PLANES,
                Some(_) => FLAG_PLANES | FLAG_RUN_OFFSETS,
                None => 0,
            }
            | if counts.small { FLAG_SMALL } else { 0 },
    );
    put_u32(&mut out, effects);
    out.extend_from_slice(&[
        opts.vertex_format.code(),
        enc.shift,
        index_size as u8,
        opts.up.code(),
    ]);
    put_u32(&mut out, count(tree.root.depth())?);
    for c in [
        counts.vertices,
        counts.polygons,
        counts.indices,
        counts.bunches,
        counts.nodes,
        counts.switches,
        counts.runs,
    ] {
        put_u32(&mut out, c);
    }
    for x in enc.origin.to_array() {
        out.extend_from_slice(&x.to_le_bytes());
    }
    for x in enc.half_extent {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out.extend_from_slice(&round_up_f32(radius).to_le_bytes());
    debug_assert_eq!(out.len(), h::RADIUS + 4);
    if scratch_vertices > u32::from(u16::MAX) {
        return Err(SerializeError::TooLarge);
    }
    // The working memory is filled in below, once the file can be read.
    let scratch_vertices = scratch_vertices.max(polygon_vertices + 5);
    for x in [polygon_vertices, scratch_vertices, 0, 0] {
        put_u32(&mut out, x);
    }
    debug_assert_eq!(out.len(), HEADER_LEN);

    if let Some(l) = &layout {
        out.extend_from_slice(&l.widths);
        put_u32(&mut out, l.colours.len() as u32);
        debug_assert_eq!(out.len(), s.colours);
        l.colours.iter().for_each(|c| out.extend_from_slice(c));
        if let Some((hidden_bits, record_len)) = l.narrow {
            out.resize(s.narrow, 0);
            out.extend_from_slice(&[hidden_bits, record_len, 0, 0]);
            put_u32(
                &mut out,
                records.and_then(|r| r.narrow).map_or(0, |n| n.extra_planes),
            );
            debug_assert_eq!(out.len(), s.narrow + NARROW_LEN);
        }
    }
    out.resize(s.vertices, 0);
    out.extend_from_slice(&vertex_bytes);
    out.resize(s.polygons, 0);
    for (i, (((&id, &first), &run), &mask)) in order
        .iter()
        .zip(&first_index)
        .zip(&run_of)
        .zip(&hidden)
        .enumerate()
    {
        let p = &tree.polygons[id as usize];
        let start = out.len();
        match &layout {
            Some(l) => {
                let colour = l.colour_index[&p.color];
                // With a plane table, the run offset.
                let run = if table.is_some() {
                    count_u32(i)? - run
                } else {
                    run
                };
                let r = l.pack([first, run, p.source, colour], mask).to_le_bytes();
                let len = l
                    .narrow
                    .map_or(COMPACT_POLYGON_LEN, |(_, n)| usize::from(n));
                out.extend_from_slice(&r[..len]);
            }
            None => {
                put_u32(&mut out, first);
                put_u32(&mut out, run);
                put_u32(&mut out, p.source);
                out.extend_from_slice(&[p.color[0], p.color[1], p.color[2], mask]);
                debug_assert_eq!(out.len() - start, POLYGON_LEN);
                debug_assert_eq!(pg::COLOR + 4, POLYGON_LEN);
            }
        }
    }
    out.resize(s.indices, 0);
    for &i in &indices {
        if index_size == 2 {
            out.extend_from_slice(&(i as u16).to_le_bytes());
        } else {
            put_u32(&mut out, i);
        }
    }
    out.resize(s.edges, 0);
    for &(kind, n) in kinds.iter().flatten() {
        out.extend_from_slice(&[n[0] as u8, n[1] as u8, n[2] as u8, kind]);
    }
    debug_assert_eq!(out.len(), s.edges + counts.edges as usize * EDGE_LEN);
    out.resize(s.normals, 0);
    if smooth {
        // The stored positions: the normals match what is drawn.
        let positions: Vec<DVec3> = vertex_bytes
            .chunks_exact(opts.vertex_format.vertex_len())
            .map(|b| enc.decode(b))
            .collect();
        // The mesh file's normals where the polygons carry them.
        let file: Vec<Option<&[DVec3]>> = order
            .iter()
            .map(|&id| tree.polygons[id as usize].normals.as_deref())
            .collect();
        let crease = opts.crease_deg;
        for n in stored_corner_normals(&loops, &plane_normals, &positions, crease, &file) {
            out.extend_from_slice(&n.map(|c| c as u8));
        }
    }
    debug_assert_eq!(out.len(), s.normals + counts.normals as usize * NORMAL_LEN);
    out.resize(s.planes, 0);
    if let Some(t) = &table {
        out.extend_from_slice(&t.bytes);
        debug_assert_eq!(out.len(), s.planes + t.bytes.len());
    }
    out.resize(s.runs, 0);
    for (&(plane, end), r) in runs.iter().zip(0..) {
        match &table {
            // Both fit: at most 65,535 polygons and 65,536 planes.
            Some(t) => {
                out.extend_from_slice(&(end as u16).to_le_bytes());
                out.extend_from_slice(&(t.run_plane[r] as u16).to_le_bytes());
            }
            None => {
                put_plane(&mut out, plane);
                put_u32(&mut out, end);
            }
        }
    }
    for &plane in &extra_planes {
        put_plane(&mut out, plane);
        put_u32(&mut out, 0);
    }
    let run_len = if table.is_some() {
        TABLE_RUN_LEN
    } else {
        RUN_LEN
    };
    debug_assert_eq!(
        out.len(),
        s.runs + runs.len() * run_len + extra_planes.len() * RUN_LEN
    );
    out.resize(s.bunches, 0);
    for &o in &bunch_offsets {
        if counts.small {
            // At most the run count, which fits.
            out.extend_from_slice(&(o as u16).to_le_bytes());
        } else {
            put_u32(&mut out, o);
        }
    }
    out.resize(s.nodes, 0);
    for &[first_bunch, levels, switch] in &node_recs {
        put_u32(&mut out, first_bunch);
        if counts.small {
            // Checked above; NO_SWITCH becomes −1.
            out.extend_from_slice(&(levels as u16).to_le_bytes());
            out.extend_from_slice(&(switch as i32 as i16).to_le_bytes());
        } else {
            put_u32(&mut out, levels);
            put_u32(&mut out, switch);
        }
    }
    out.resize(s.switches, 0);
    if records.is_some_and(|r| r.narrow.is_some()) {
        switch_refs.iter().for_each(|&i| put_u32(&mut out, i));
        debug_assert_eq!(out.len(), s.switches + switch_refs.len() * SWITCH_REF_LEN);
    } else {
        switch_planes.iter().for_each(|&p| put_plane(&mut out, p));
    }
    out.resize(s.crc, 0);
    let crc = crc32(&out);
    put_u32(&mut out, crc);
    debug_assert_eq!(out.len(), s.file_len);
    // What bands need, as the renderer computes it from the file.
    let words = match fpt_nostd::reader::Tree::from_bytes(&out) {
        Ok(t) => fpt_nostd::render::memory_words(&t),
        Err(e) => return Err(SerializeError::Invalid(e)),
    };
    let words = u32::try_from(words).map_err(too_large)?;
    out[h::MEMORY_WORDS..h::MEMORY_WORDS + 4].copy_from_slice(&words.to_le_bytes());
    let crc = crc32(&out[..s.crc]);
    out[s.crc..].copy_from_slice(&crc.to_le_bytes());
    Ok(out)
}

/// Whether vertex `i` of the loop `verts` (counter-clockwise around
/// `normal`) is reflex: the loop turns clockwise there by more than
/// rounding (`f64`, relative 1e-9) explains. A straight vertex (collinear
/// neighbours, as the seams' inserted vertices are) is not.
fn is_reflex(verts: &[DVec3], i: usize, normal: DVec3) -> bool {
    let n = verts.len();
    let (a, b, c) = (verts[(i + n - 1) % n], verts[i], verts[(i + 1) % n]);
    let (u, v) = (b - a, c - b);
    u.cross(v).dot(normal) < -1e-9 * u.length() * v.length()
}

mod encoder;
use encoder::{round_up_f32, Encoder};
mod planes;
mod records;
#[cfg(test)]
mod tests;
