//! The polygon records' compact layout (bit fields as narrow as the
//! largest value of each needs, the colour table) and the switch planes
//! shared with the runs: the parts of [`super::serialize`] that decide how
//! few bytes a record and a switch take.

use std::collections::HashMap;

use fpt_nostd::format::COMPACT_HIDDEN_SHIFT;

use super::{count_u32, SerializeError};
use crate::tree::FpTree;

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
pub(super) fn share_planes(
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

/// Bits to hold every value up to `max`.
pub(super) fn bits(max: u32) -> u8 {
    (32 - max.leading_zeros()) as u8
}

/// The narrowest compact layout for the file polygons `order` (with their
/// index ranges, runs and masks as computed for the file), or `None` when
/// the fields need more than the 56 bits below the mask.
pub(super) fn compact_layout(
    tree: &FpTree,
    order: &[u32],
    first_index: &[u32],
    runs: &[([f32; 4], u32)],
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
        bits(u32::try_from(runs.len().saturating_sub(1)).ok()?),
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
