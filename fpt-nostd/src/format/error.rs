//! Why a byte string is not a valid tree file: what
//! [`crate::reader::Tree::from_bytes`] returns.

use core::fmt;

#[cfg(doc)]
use super::{FLAG_NARROW, MAGIC};

/// Why a byte string is not a valid tree file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormatError {
    /// Shorter than a header and a checksum.
    TooShort,
    /// The first four bytes are not [`MAGIC`].
    BadMagic,
    /// A version this reader does not know.
    UnsupportedVersion(u16),
    /// The header's file length differs from the length of the bytes.
    LengthMismatch,
    /// The stored CRC-32 differs from the one computed over the bytes.
    Checksum,
    /// A header field has a value outside its range; names the field.
    BadHeader(&'static str),
    /// The counts in the header do not add up to the file length.
    SectionSizes,
    /// An edge record's kind is not one of the known kinds.
    BadEdge(u32),
    /// A corner normal record is zero or has a component of −128.
    BadNormal(u32),
    /// This polygon's colour index is not below the colour table's length
    /// (compact records).
    BadColour(u32),
    /// A float that must be finite is not; names the section.
    NonFinite(&'static str),
    /// A vertex index is not below the vertex count.
    IndexOutOfRange,
    /// This polygon's index range is empty, too short or out of order.
    BadPolygon(u32),
    /// The run ends or the polygons' run fields do not tile the polygons.
    BadRuns,
    /// The bunch offsets do not tile the runs.
    BadBunches,
    /// This connecting node breaks the bunch tiling or the switch numbering.
    BadNode(u32),
    /// This switch names a plane record past the runs and extra planes
    /// ([`FLAG_NARROW`]).
    BadSwitch(u32),
    /// This entry of a compact plane table is not well formed (a
    /// component of −32768, or a normal whose largest component is not
    /// ±32767).
    BadPlane(u32),
    /// Some connecting nodes cannot be reached from the root.
    NotATree,
    /// The header's maximum depth differs from the tree's depth.
    DepthMismatch,
}

impl fmt::Display for FormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FormatError::TooShort => f.write_str("file too short for a tree header"),
            FormatError::BadMagic => f.write_str("not a tree file (bad magic)"),
            FormatError::UnsupportedVersion(v) => write!(f, "unsupported format version {v}"),
            FormatError::LengthMismatch => f.write_str("file length differs from the header's"),
            FormatError::Checksum => f.write_str("CRC-32 mismatch (file corrupted)"),
            FormatError::BadHeader(field) => write!(f, "invalid header field {field}"),
            FormatError::SectionSizes => {
                f.write_str("section sizes do not add up to the file length")
            }
            FormatError::BadEdge(j) => write!(f, "invalid kind of edge record {j}"),
            FormatError::BadNormal(j) => write!(f, "invalid corner normal record {j}"),
            FormatError::BadColour(p) => write!(f, "colour index of polygon {p} out of range"),
            FormatError::NonFinite(what) => write!(f, "non-finite number in {what}"),
            FormatError::IndexOutOfRange => f.write_str("vertex index out of range"),
            FormatError::BadPolygon(p) => write!(f, "invalid vertex range of polygon {p}"),
            FormatError::BadRuns => f.write_str("plane runs do not tile the polygons"),
            FormatError::BadBunches => f.write_str("bunch offsets do not tile the runs"),
            FormatError::BadNode(n) => write!(f, "invalid connecting node {n}"),
            FormatError::BadSwitch(k) => write!(f, "switch {k} names no plane record"),
            FormatError::BadPlane(i) => write!(f, "invalid compact plane table entry {i}"),
            FormatError::NotATree => f.write_str("node graph is not a tree"),
            FormatError::DepthMismatch => f.write_str("tree depth differs from the header's"),
        }
    }
}
