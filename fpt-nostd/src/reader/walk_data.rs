//! The sections the walk reads for every view ([`WalkData`]): runs,
//! bunch offsets, connecting nodes and switch records, each sliced by
//! `Tree::from_bytes` to exactly its validated length, so that every read
//! here is in range for an index the validation allowed (an index past the
//! end reads zeros instead of panicking; see the module docs of
//! `crate::reader` for the no-panic contract).

use super::Plane;
use crate::format::COMPACT_PLANE_LEN;
// `WalkData::node` reads a small node's level count and switch as one word.
const _: () =
    assert!(nd::SMALL_SWITCH == nd::LEVEL_COUNT + 2 && SMALL_NODE_LEN == nd::LEVEL_COUNT + 4);

use crate::format::{
    le_u32, node as nd, plane_at, rec, run as rn, table_run as tr, NODE_LEN, NO_SWITCH, PLANE_LEN,
    RUN_LEN, SMALL_NODE_LEN, SWITCH_LEN, SWITCH_REF_LEN, TABLE_RUN_LEN,
};
#[cfg(doc)]
use crate::format::{FLAG_COMPACT_PLANES, FLAG_NARROW, FLAG_PLANES, FLAG_SMALL};

/// The run section as the walk reads it: [`RUN_LEN`]-byte records (plane,
/// `u32` end), or with a plane table ([`FLAG_PLANES`]) [`TABLE_RUN_LEN`]-byte
/// records (`u16` end, `u16` index of a [`PLANE_LEN`]-byte plane of
/// `planes`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Runs<'a> {
    /// The run records (with shared switch planes and no table, followed
    /// by the extra plane records).
    pub(crate) recs: &'a [u8],
    /// The plane table, empty without one. Only with the `plane-table`
    /// feature, like `table`: without it the walk carries what it did
    /// before the table (two more words made the firmware's stack 64
    /// bytes deeper and its frames with effects 0.6 % dearer).
    #[cfg(feature = "plane-table")]
    planes: &'a [[u8; PLANE_LEN]],
    /// The compact plane table, empty without one (entries, like
    /// `planes`).
    #[cfg(feature = "compact-planes")]
    compact_planes: &'a [[u8; COMPACT_PLANE_LEN]],
    /// Whether the runs index the plane table.
    #[cfg(any(feature = "plane-table", feature = "compact-planes"))]
    table: bool,
    /// Whether the table's entries are compact ([`FLAG_COMPACT_PLANES`]).
    #[cfg(all(feature = "plane-table", feature = "compact-planes"))]
    compact: bool,
}

impl<'a> Runs<'a> {
    /// The runs `recs`, indexing the plane table `planes` if `table` (a
    /// table is refused without the `plane-table` feature, before this),
    /// of compact entries if `compact`.
    #[inline]
    pub(crate) fn new(recs: &'a [u8], planes: &'a [u8], table: bool, compact: bool) -> Runs<'a> {
        #[cfg(not(all(feature = "plane-table", feature = "compact-planes")))]
        let _ = compact;
        #[cfg(not(any(feature = "plane-table", feature = "compact-planes")))]
        let _ = (planes, table);
        Runs {
            recs,
            // Entries, not bytes: an index is then checked against the
            // table's length with one comparison (the section is a whole
            // number of entries, so nothing is dropped).
            #[cfg(feature = "plane-table")]
            planes: if compact {
                &[]
            } else {
                bytemuck::try_cast_slice(planes).unwrap_or(&[])
            },
            #[cfg(feature = "compact-planes")]
            compact_planes: if compact {
                bytemuck::try_cast_slice(planes).unwrap_or(&[])
            } else {
                &[]
            },
            #[cfg(any(feature = "plane-table", feature = "compact-planes"))]
            table,
            #[cfg(all(feature = "plane-table", feature = "compact-planes"))]
            compact: table && compact,
        }
    }

    /// Whether the plane table's entries are compact: never without the
    /// `compact-planes` feature, always with a table with it alone (the
    /// reader then refuses `f32` tables), so that a firmware built for
    /// one kind of entry has the walk of that kind only.
    #[inline(always)]
    pub(crate) fn is_compact(&self) -> bool {
        #[cfg(all(feature = "compact-planes", feature = "plane-table"))]
        return self.compact;
        #[cfg(all(feature = "compact-planes", not(feature = "plane-table")))]
        return self.is_table();
        #[cfg(not(feature = "compact-planes"))]
        false
    }

    /// Bytes of one plane table entry.
    #[inline(always)]
    pub(crate) fn plane_len(&self) -> usize {
        if self.is_compact() {
            COMPACT_PLANE_LEN
        } else {
            PLANE_LEN
        }
    }

    /// Compact entry `i` of the table (zeros past its end).
    #[inline(always)]
    pub(crate) fn compact_entry(&self, i: u32) -> [u8; COMPACT_PLANE_LEN] {
        self.compact_planes()
            .get(i as usize)
            .copied()
            .unwrap_or([0; COMPACT_PLANE_LEN])
    }

    /// Whether the runs index a plane table: never without the
    /// `plane-table` feature, so that the walk's choice of layout is
    /// compiled out.
    #[inline(always)]
    pub(crate) fn is_table(&self) -> bool {
        #[cfg(any(feature = "plane-table", feature = "compact-planes"))]
        return self.table;
        #[cfg(not(any(feature = "plane-table", feature = "compact-planes")))]
        false
    }

    /// The plane table's entries (none without one).
    #[inline(always)]
    pub(crate) fn planes(&self) -> &'a [[u8; PLANE_LEN]] {
        #[cfg(feature = "plane-table")]
        return self.planes;
        #[cfg(not(feature = "plane-table"))]
        &[]
    }

    /// The compact plane table's entries (none without one).
    #[inline(always)]
    pub(crate) fn compact_planes(&self) -> &'a [[u8; COMPACT_PLANE_LEN]] {
        #[cfg(feature = "compact-planes")]
        return self.compact_planes;
        #[cfg(not(feature = "compact-planes"))]
        &[]
    }

    /// The plane table's bytes, of either kind of entry.
    #[inline(always)]
    pub(crate) fn plane_bytes(&self) -> &'a [u8] {
        if self.is_compact() {
            self.compact_planes().as_flattened()
        } else {
            self.planes().as_flattened()
        }
    }

    /// One past the last polygon of run `r < run_count`.
    #[inline(always)]
    pub(crate) fn end(&self, r: u32) -> u32 {
        if self.is_table() {
            self.table_end(r)
        } else {
            self.inline_end(r)
        }
    }

    /// [`Runs::end`] of [`RUN_LEN`]-byte records.
    #[inline(always)]
    pub(crate) fn inline_end(&self, r: u32) -> u32 {
        le_u32(&rec::<RUN_LEN>(self.recs, r as usize), rn::END)
    }

    /// [`Runs::end`] of [`TABLE_RUN_LEN`]-byte records.
    #[inline(always)]
    pub(crate) fn table_end(&self, r: u32) -> u32 {
        let [a, b, _, _] = rec::<TABLE_RUN_LEN>(self.recs, r as usize);
        u32::from(u16::from_le_bytes([a, b]))
    }

    /// The memo's number and the 16 bytes of the plane of run `r <
    /// run_count`: the run itself and its record without a table, the
    /// plane index and the table entry with one.
    #[inline(always)]
    pub(crate) fn plane(&self, r: u32) -> (u32, &'a [u8; 16]) {
        if self.is_table() {
            let i = self.plane_index(r);
            (i, table_plane(self.planes(), i))
        } else {
            (r, plane_at(self.recs, (r as usize).wrapping_mul(RUN_LEN)))
        }
    }

    /// The plane index of run `r` with a table (0 without one).
    #[inline(always)]
    pub(crate) fn plane_index(&self, r: u32) -> u32 {
        let rr = rec::<TABLE_RUN_LEN>(self.recs, r as usize);
        u32::from(u16::from_le_bytes([rr[tr::PLANE], rr[tr::PLANE + 1]]))
    }
}

/// Entry `i` of the plane table `planes` (zeros past its end).
#[inline(always)]
pub(crate) fn table_plane(planes: &[[u8; PLANE_LEN]], i: u32) -> &[u8; PLANE_LEN] {
    planes.get(i as usize).unwrap_or(&[0; PLANE_LEN])
}

/// Offsets `b` and `b + 1` of the bunch section `s`, of `L / 2` bytes
/// each (zeros out of range).
#[inline(always)]
fn pair<const L: usize>(s: &[u8], b: u32) -> [u8; L] {
    let start = (b as usize).wrapping_mul(L / 2);
    start
        .checked_add(L)
        .and_then(|end| s.get(start..end))
        .and_then(|s| s.try_into().ok())
        .unwrap_or([0; L])
}

/// One connecting node record.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NodeRec {
    pub first_bunch: u32,
    pub level_count: u32,
    pub switch: u32,
    /// No levels and no switch (an empty leaf): one comparison of a small
    /// node's second word (both fields tested apart were five
    /// instructions).
    pub empty: bool,
}

/// The sections the walk reads for every view, each sliced to exactly its
/// validated length (see the module docs): small enough to copy into every
/// walk and class.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WalkData<'a> {
    /// `run_count` run records and the plane table ([`Runs`]).
    pub(crate) runs: Runs<'a>,
    /// `bunch_count + 1` offsets (`u32`, or `u16` with small records).
    pub(super) bunches: &'a [u8],
    /// `node_count` records of [`NODE_LEN`] bytes, or of
    /// [`SMALL_NODE_LEN`] with `small`.
    pub(super) nodes: &'a [u8],
    /// Small walk records ([`FLAG_SMALL`]): `u16` bunch offsets, 8-byte
    /// nodes. Only with the `large-trees` feature: without it every file
    /// has them, and the walk reads one layout.
    #[cfg(feature = "large-trees")]
    pub(super) small: bool,
    /// `switch_count` records of [`SWITCH_LEN`] bytes, or of
    /// [`SWITCH_REF_LEN`] with shared planes ([`FLAG_NARROW`]).
    pub(super) switches: &'a [u8],
    /// Whether the switch records index plane records ([`FLAG_NARROW`]):
    /// without a plane table, `runs` then holds `run_count + extra_planes`
    /// records, the runs and then the extra planes (the walk reads a run
    /// only by an index below `run_count`, so the extra ones are only ever
    /// read as planes); with one ([`FLAG_PLANES`]), they index the table.
    pub(super) shared: bool,
}

impl<'a> WalkData<'a> {
    /// Whether the bunch offsets and nodes are small records: always
    /// without the `large-trees` feature (the reader refuses other files),
    /// so that the walk's choice of layout is compiled out.
    #[inline(always)]
    pub(crate) fn small(&self) -> bool {
        #[cfg(feature = "large-trees")]
        return self.small;
        #[cfg(not(feature = "large-trees"))]
        true
    }

    /// Connecting node `i < node_count`.
    #[inline(always)]
    pub(crate) fn node(&self, i: u32) -> NodeRec {
        if self.small() {
            let r = rec::<SMALL_NODE_LEN>(self.nodes, i as usize);
            // Both `u16` fields of the second word from one read of it
            // (two-byte reads of the copy were put together byte by byte).
            let w = le_u32(&r, nd::LEVEL_COUNT);
            NodeRec {
                first_bunch: le_u32(&r, nd::FIRST_BUNCH),
                level_count: w & 0xFFFF,
                // Sign-extended (the high half, shifted down arithmetically):
                // −1 is NO_SWITCH.
                switch: ((w as i32) >> 16) as u32,
                empty: w == 0xFFFF_0000,
            }
        } else {
            let r = rec::<NODE_LEN>(self.nodes, i as usize);
            let (level_count, switch) = (le_u32(&r, nd::LEVEL_COUNT), le_u32(&r, nd::SWITCH));
            NodeRec {
                first_bunch: le_u32(&r, nd::FIRST_BUNCH),
                level_count,
                switch,
                empty: level_count == 0 && switch == NO_SWITCH,
            }
        }
    }

    /// The runs `start..end` of bunch `b < bunch_count`.
    #[inline(always)]
    pub(crate) fn bunch(&self, b: u32) -> (u32, u32) {
        // Offsets b and b + 1: one read of both.
        if self.small() {
            let [a0, a1, b0, b1] = pair::<4>(self.bunches, b);
            (
                u32::from(u16::from_le_bytes([a0, a1])),
                u32::from(u16::from_le_bytes([b0, b1])),
            )
        } else {
            let r = pair::<8>(self.bunches, b);
            (le_u32(&r, 0), le_u32(&r, 4))
        }
    }

    /// Offset `b ≤ bunch_count` of the bunch section.
    #[inline]
    pub(crate) fn bunch_offset(&self, b: u32) -> u32 {
        if self.small() {
            let [lo, hi] = rec::<2>(self.bunches, b as usize);
            u32::from(u16::from_le_bytes([lo, hi]))
        } else {
            le_u32(&rec::<4>(self.bunches, b as usize), 0)
        }
    }

    /// One past the last polygon of run `r < run_count`.
    #[inline(always)]
    pub(crate) fn run_end(&self, r: u32) -> u32 {
        self.runs.end(r)
    }

    /// The plane of run `r < run_count`.
    #[inline]
    pub(crate) fn run_plane(&self, r: u32) -> Plane {
        Plane::from_record(self.runs.plane(r).1)
    }

    /// The record of switch `k < switch_count`: its plane's normal and
    /// offset (with shared planes, the first 16 bytes of the plane record
    /// or table entry it names; one bounds check either way), borrowed
    /// from the tree: a copy kept its zero fallback in registers (session
    /// 20: the firmware full frames 0.5–2.6 k cheaper).
    #[inline(always)]
    pub(crate) fn switch_record(&self, k: u32) -> &'a [u8; SWITCH_LEN] {
        self.switch_at(k, 0).1
    }

    /// The memo's number of the plane of switch `k` and its record
    /// ([`WalkData::switch_record`]): `base + k` (`base` the run count,
    /// the switches numbered after the runs), or with a plane table the
    /// entry's index, as the runs number their planes.
    #[inline(always)]
    pub(crate) fn switch_at(&self, k: u32, base: u32) -> (u32, &'a [u8; SWITCH_LEN]) {
        if self.runs.is_table() {
            self.switch_table(k)
        } else {
            self.switch_inline(k, base)
        }
    }

    /// [`WalkData::switch_at`] without a plane table.
    #[inline(always)]
    pub(crate) fn switch_inline(&self, k: u32, base: u32) -> (u32, &'a [u8; SWITCH_LEN]) {
        let no = base.wrapping_add(k);
        if self.shared {
            let i = self.switch_ref(k);
            (
                no,
                plane_at(self.runs.recs, (i as usize).wrapping_mul(RUN_LEN)),
            )
        } else {
            (
                no,
                plane_at(self.switches, (k as usize).wrapping_mul(SWITCH_LEN)),
            )
        }
    }

    /// The plane record or table entry that shared switch record `k`
    /// names ([`SWITCH_REF_LEN`] bytes; 0 past the end).
    #[inline(always)]
    fn switch_ref(&self, k: u32) -> u32 {
        le_u32(&rec::<SWITCH_REF_LEN>(self.switches, k as usize), 0)
    }

    /// [`WalkData::switch_at`] with a plane table (whose files always
    /// have shared switch planes, [`FLAG_NARROW`]).
    #[inline(always)]
    pub(crate) fn switch_table(&self, k: u32) -> (u32, &'a [u8; SWITCH_LEN]) {
        let i = self.switch_ref(k);
        (i, table_plane(self.runs.planes(), i))
    }

    /// The plane index of switch `k` with shared planes (`None` without
    /// them or past the end).
    #[inline]
    pub(crate) fn switch_plane_index(&self, k: u32) -> Option<u32> {
        let at = (k as usize).checked_mul(SWITCH_REF_LEN)?;
        let r = self.switches.get(at..at.checked_add(SWITCH_REF_LEN)?)?;
        self.shared
            .then(|| u32::from_le_bytes(r.try_into().unwrap_or([0; 4])))
    }

    /// Plane record `i` of the shared planes without a table
    /// (`run_count + extra_planes` of them): its plane and end field.
    #[inline]
    pub(crate) fn plane_record(&self, i: u32) -> (Plane, u32) {
        let r = rec::<RUN_LEN>(self.runs.recs, i as usize);
        (Plane::from_record(&r), le_u32(&r, rn::END))
    }

    /// Entry `i` of the plane table ([`FLAG_PLANES`]).
    #[inline]
    pub(crate) fn table_plane(&self, i: u32) -> Plane {
        Plane::from_record(table_plane(self.runs.planes(), i))
    }

    /// The plane of switch `k < switch_count`.
    #[inline]
    pub(crate) fn switch_plane(&self, k: u32) -> Plane {
        Plane::from_record(self.switch_record(k))
    }

    /// With compact planes: the table index of switch `k`'s plane (its
    /// memo number) and its entry.
    #[inline(always)]
    pub(crate) fn switch_compact(&self, k: u32) -> (u32, [u8; COMPACT_PLANE_LEN]) {
        let i = self.switch_ref(k);
        (i, self.runs.compact_entry(i))
    }
}
