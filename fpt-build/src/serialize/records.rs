//! The polygon records' compact layout (bit fields as narrow as the
//! largest value of each needs, the colour table) and the switch planes
//! shared with the runs: the parts of [`super::serialize`] that decide how
//! few bytes a record and a switch take.

use std::collections::HashMap;

use fpt_nostd::format::{Counts, Narrow, Records, Sections, COMPACT_HIDDEN_SHIFT};

use super::{count_u32, planes, SerializeError, SerializeOptions};
use crate::tree::FpTree;

/// What [`Plan::new`] decides from.
pub(super) struct PlanInput<'a> {
    pub(super) tree: &'a FpTree,
    /// The file polygons (tree ids), their first indices and masks.
    pub(super) order: &'a [u32],
    pub(super) first_index: &'a [u32],
    pub(super) hidden: &'a [u8],
    /// The runs (stored plane, end) and the switch planes.
    pub(super) runs: &'a [([f32; 4], u32)],
    pub(super) switch_planes: &'a [[f32; 4]],
    pub(super) counts: &'a Counts,
    pub(super) opts: &'a SerializeOptions,
    pub(super) index_size: usize,
    /// The plane unit of compact planes
    /// ([`fpt_nostd::format::plane_unit`] of the header's half extent).
    pub(super) plane_unit: f32,
}

/// How a file stores its polygon records and planes, and its layout.
pub(super) struct Plan {
    /// The compact layout (`None`: 16-byte records).
    pub(super) layout: Option<CompactLayout>,
    /// The plane table ([`fpt_nostd::format::FLAG_PLANES`]); with it the
    /// records' run fields are run offsets
    /// ([`fpt_nostd::format::FLAG_RUN_OFFSETS`]).
    pub(super) table: Option<PlaneTable>,
    /// The switch records with shared planes: plane record or table
    /// indices (empty without).
    pub(super) switch_refs: Vec<u32>,
    /// The plane records after the runs (shared planes, no table).
    pub(super) extra_planes: Vec<[f32; 4]>,
    pub(super) records: Option<Records>,
    pub(super) sections: Sections,
}

impl Plan {
    /// The records `input.opts` asks for; with a plane table, the smaller
    /// file of with and without it (the table needs narrow records, and
    /// a file whose planes are nearly all distinct gains nothing from it).
    pub(super) fn new(input: &PlanInput<'_>) -> Result<Plan, SerializeError> {
        let o = input.opts;
        let table = (o.compact && o.narrow && o.plane_table)
            .then(|| {
                let compact = o.compact_planes.then_some(input.plane_unit);
                plane_table(input.runs, input.switch_planes, input.order.len(), compact)
            })
            .flatten();
        let without = Plan::with(input, None)?;
        match table {
            Some(t) => {
                let with = Plan::with(input, Some(t))?;
                let smaller = with.sections.file_len <= without.sections.file_len;
                Ok(if with.table.is_some() && smaller {
                    with
                } else {
                    without
                })
            }
            None => Ok(without),
        }
    }

    /// The plan with `table` if the narrow records hold its indices.
    fn with(input: &PlanInput<'_>, table: Option<PlaneTable>) -> Result<Plan, SerializeError> {
        let o = input.opts;
        // The values of a record's run field: with the table run offsets
        // (`id − run`, from 0 to the polygons less the runs: every run has
        // a polygon, see `FLAG_RUN_OFFSETS`), else the run's index.
        let run_values = match &table {
            Some(_) => input.order.len().saturating_sub(input.runs.len()) + 1,
            None => input.runs.len(),
        };
        let layout = o
            .compact
            .then(|| {
                let (tree, order) = (input.tree, input.order);
                compact_layout(
                    tree,
                    order,
                    input.first_index,
                    run_values,
                    input.hidden,
                    o.narrow,
                )
            })
            .flatten();
        let narrow = layout.as_ref().is_some_and(|l| l.narrow.is_some());
        if table.is_some() && !narrow {
            return Plan::with(input, None);
        }
        // Shared switch planes: each switch names its entry of the plane
        // table, or the first run with its exact plane, or a plane record
        // after the runs.
        let (switch_refs, extra_planes) = match &table {
            Some(t) => (t.switch_plane.clone(), Vec::new()),
            None if narrow => share_planes(input.runs, input.switch_planes)?,
            None => (Vec::new(), Vec::new()),
        };
        let records = layout.as_ref().map(|l| Records {
            colours: l.colours.len() as u32,
            narrow: l.narrow.map(|(_, record_len)| Narrow {
                record_len,
                extra_planes: table.as_ref().map_or(extra_planes.len(), |t| t.len) as u32,
                table: table.is_some(),
                compact_planes: table.as_ref().is_some_and(|t| t.compact),
            }),
        });
        let sections = Sections::with_records(
            input.counts,
            o.vertex_format,
            input.index_size,
            records.as_ref(),
        )
        .ok_or(SerializeError::TooLarge)?;
        Ok(Plan {
            layout,
            table,
            switch_refs,
            extra_planes,
            records,
            sections,
        })
    }
}

/// The compact record layout of a file (see [`fpt_nostd::format`]).
pub(super) struct CompactLayout {
    /// Bits of first_index, run, source and colour index.
    pub(super) widths: [u8; 4],
    /// The distinct colours, in order of first use by file polygons.
    pub(super) colours: Vec<[u8; 3]>,
    /// Each colour's position in `colours`.
    pub(super) colour_index: HashMap<[u8; 3], u32>,
    /// Narrow records ([`fpt_nostd::format::FLAG_NARROW`]): the bits of
    /// hidden_edges and the record length in bytes.
    pub(super) narrow: Option<(u8, u8)>,
}

impl CompactLayout {
    /// The record of one polygon: the four fields from bit 0 up, each in
    /// its width, and the outline mask in the top byte (narrow records:
    /// right after them, in its own width).
    pub(super) fn pack(&self, fields: [u32; 4], hidden: u8) -> u64 {
        let mut r = 0u64;
        let mut shift = 0u32;
        for (f, w) in fields.into_iter().zip(self.widths) {
            debug_assert!(u64::from(f) < 1u64 << w);
            r |= u64::from(f) << shift;
            shift += u32::from(w);
        }
        if self.narrow.is_some() {
            debug_assert!(shift + u32::from(bits(u32::from(hidden))) <= 64);
            return r | u64::from(hidden).wrapping_shl(shift);
        }
        r | u64::from(hidden) << COMPACT_HIDDEN_SHIFT
    }
}

/// The switch records of a file with shared planes: for each switch plane,
/// the index of the first run with that exact plane (bit for bit), or of a
/// plane record after the runs; and those extra planes, each stored once.
#[allow(clippy::type_complexity)]
fn share_planes(
    runs: &[([f32; 4], u32)],
    switch_planes: &[[f32; 4]],
) -> Result<(Vec<u32>, Vec<[f32; 4]>), SerializeError> {
    let key = |p: &[f32; 4]| p.map(f32::to_bits);
    let mut index: HashMap<[u32; 4], u32> = HashMap::new();
    for (r, (plane, _)) in runs.iter().enumerate() {
        index.entry(key(plane)).or_insert(count_u32(r)?);
    }
    let mut extra = Vec::new();
    let mut refs = Vec::with_capacity(switch_planes.len());
    for p in switch_planes {
        let next = count_u32(runs.len() + extra.len())?;
        let i = *index.entry(key(p)).or_insert_with(|| {
            extra.push(*p);
            next
        });
        refs.push(i);
    }
    Ok((refs, extra))
}

/// A shared plane table ([`fpt_nostd::format::FLAG_PLANES`]): every
/// distinct run and switch plane once (bit for bit, so that the facing
/// tests and the order are the builder's; with compact entries, every
/// distinct entry once), the runs' planes first in order of first use,
/// then the switch planes no run has.
pub(super) struct PlaneTable {
    /// The entries as stored, one after the other.
    pub(super) bytes: Vec<u8>,
    /// How many.
    pub(super) len: usize,
    /// Whether they are compact ([`fpt_nostd::format::FLAG_COMPACT_PLANES`]).
    pub(super) compact: bool,
    /// Each run's entry.
    pub(super) run_plane: Vec<u32>,
    /// Each switch's entry.
    pub(super) switch_plane: Vec<u32>,
}

/// The plane table of a file with `polygons` polygons, these runs and
/// switch planes, with compact entries for a file of plane unit `u` if
/// `compact` is `Some(u)`, or `None` when its `u16` run
/// records cannot hold it (more than 65,535 polygons or 65,536 planes) or
/// a plane has no compact entry.
fn plane_table(
    runs: &[([f32; 4], u32)],
    switch_planes: &[[f32; 4]],
    polygons: usize,
    compact: Option<f32>,
) -> Option<PlaneTable> {
    if polygons > usize::from(u16::MAX) {
        return None;
    }
    let mut index: HashMap<Vec<u8>, u32> = HashMap::new();
    let mut bytes = Vec::new();
    let mut len = 0usize;
    let mut entry = |p: &[f32; 4]| -> Option<u32> {
        let e: Vec<u8> = match compact {
            Some(unit) => planes::encode(*p, unit)?.to_vec(),
            None => p.iter().flat_map(|x| x.to_le_bytes()).collect(),
        };
        Some(*index.entry(e).or_insert_with_key(|e| {
            bytes.extend_from_slice(e);
            len += 1;
            len as u32 - 1
        }))
    };
    let run_plane: Vec<u32> = runs.iter().map(|(p, _)| entry(p)).collect::<Option<_>>()?;
    let switch_plane: Vec<u32> = switch_planes
        .iter()
        .map(&mut entry)
        .collect::<Option<_>>()?;
    (len <= 1 << 16).then_some(PlaneTable {
        bytes,
        len,
        compact: compact.is_some(),
        run_plane,
        switch_plane,
    })
}

/// Bits to hold every value up to `max`.
pub(super) fn bits(max: u32) -> u8 {
    (32 - max.leading_zeros()) as u8
}

/// The narrowest compact layout for the file polygons `order` (with their
/// index ranges and masks as computed for the file, and a run field that
/// takes `planes` values: the run offsets or the runs), or
/// `None` when the fields need more than the 56 bits below the mask.
fn compact_layout(
    tree: &FpTree,
    order: &[u32],
    first_index: &[u32],
    planes: usize,
    hidden: &[u8],
    narrow: bool,
) -> Option<CompactLayout> {
    debug_assert_eq!(order.len(), hidden.len());
    let mut colours = Vec::new();
    let mut colour_index = HashMap::new();
    let mut max_source = 0u32;
    for &id in order {
        let p = &tree.polygons[id as usize];
        max_source = max_source.max(p.source);
        colour_index.entry(p.color).or_insert_with(|| {
            colours.push(p.color);
            (colours.len() - 1) as u32
        });
    }
    let widths = [
        bits(first_index.last().copied().unwrap_or(0)),
        bits(u32::try_from(planes.saturating_sub(1)).ok()?),
        bits(max_source),
        bits(u32::try_from(colours.len().saturating_sub(1)).ok()?),
    ];
    let used: u32 = widths.iter().map(|&w| u32::from(w)).sum();
    let hidden_bits = bits(u32::from(hidden.iter().copied().max().unwrap_or(0)));
    let total = used + u32::from(hidden_bits);
    // Narrow when the five fields fit a u64, else the 8-byte records.
    let narrow = (narrow && total <= 64).then(|| (hidden_bits, total.div_ceil(8).max(1) as u8));
    (used <= COMPACT_HIDDEN_SHIFT || narrow.is_some()).then_some(CompactLayout {
        widths,
        colours,
        colour_index,
        narrow,
    })
}
