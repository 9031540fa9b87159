//! The layout sections of a compact file (see [`crate::format`]): the
//! fields' widths, the colour count and, with [`FLAG_NARROW`], the record
//! length and the extra planes (or, with [`FLAG_PLANES`], the plane
//! table's length), checked once at load.

use super::CompactFields;
use crate::format::{
    rd, rd_u16, rd_u32, FormatError, Narrow, Records, COLOUR_LEN, COMPACT_HIDDEN_SHIFT, CRC_LEN,
    FLAG_COMPACT, FLAG_COMPACT_PLANES, FLAG_NARROW, FLAG_PLANES, HEADER_LEN, LAYOUT_LEN,
    NARROW_LEN,
};

/// The fields of the polygon records and what the records add to the
/// sections, from the layout sections of `bytes` (whose header flags are
/// `flags`): default fields and `None` for 16-byte records.
pub(super) fn read(
    bytes: &[u8],
    flags: u32,
) -> Result<(CompactFields, Option<Records>), FormatError> {
    if flags & FLAG_COMPACT == 0 {
        return Ok((CompactFields::default(), None));
    }
    if bytes.len() < HEADER_LEN + LAYOUT_LEN + CRC_LEN {
        return Err(FormatError::SectionSizes);
    }
    let w = rd::<4>(bytes, HEADER_LEN);
    let colours = rd_u32(bytes, HEADER_LEN + 4);
    let sum: u32 = w.iter().map(|&x| u32::from(x)).sum();
    let bad = Err(FormatError::BadHeader("layout"));
    if w.iter().any(|&x| x > 32) {
        return bad;
    }
    if flags & FLAG_NARROW == 0 {
        // The compact records of sessions 10 to 16: 8 bytes, hidden_edges
        // in the top byte.
        if sum > COMPACT_HIDDEN_SHIFT {
            return bad;
        }
        let mut f = CompactFields::new([w[0], w[1], w[2], w[3], 8]);
        f.shift[4] = COMPACT_HIDDEN_SHIFT as u8;
        let records = Records {
            colours,
            narrow: None,
        };
        return Ok((f, Some(records)));
    }
    // The narrow layout follows the colour table (padded to 4 bytes).
    let at = (HEADER_LEN + LAYOUT_LEN) as u64 + u64::from(colours) * COLOUR_LEN as u64;
    let at = usize::try_from((at + 3) & !3).map_err(|_| FormatError::SectionSizes)?;
    let ext: [u8; NARROW_LEN] = at
        .checked_add(NARROW_LEN + CRC_LEN)
        .filter(|&end| end <= bytes.len())
        .map(|_| rd(bytes, at))
        .ok_or(FormatError::SectionSizes)?;
    let (hidden, record_len) = (ext[0], ext[1]);
    let total = sum + u32::from(hidden);
    // The record length is exactly what the fields need: one encoding.
    let needed = total.div_ceil(8).max(1);
    if hidden > 8 || total > 64 || u32::from(record_len) != needed {
        return bad;
    }
    if rd_u16(&ext, 2) != 0 {
        return bad;
    }
    let records = Records {
        colours,
        narrow: Some(Narrow {
            record_len,
            extra_planes: rd_u32(&ext, 4),
            table: flags & FLAG_PLANES != 0,
            compact_planes: flags & FLAG_COMPACT_PLANES != 0,
        }),
    };
    let f = CompactFields::new([w[0], w[1], w[2], w[3], hidden]);
    Ok((f, Some(records)))
}
