//! The structural checks of [`Tree::from_bytes`], one pass per section, in
//! the order the sections depend on each other (see the contract in
//! [`crate::reader`]). Each is linear in its section and allocates nothing.

use super::{finite3_f32, Tree};
use crate::format::{compact_plane_ok, EDGE_SOFT};
use crate::format::{rd_f32x3, rd_u64, FormatError, VertexFormat, COMPACT_HIDDEN_SHIFT, NO_SWITCH};
use crate::raster::proof::VertexBound;

impl Tree<'_> {
    /// `f32` vertices finite; every vertex index below the vertex count.
    /// Returns the bounds of the decoded vertices (one more pass over them,
    /// at load time, so that no frame needs one).
    pub(super) fn check_vertices(&self) -> Result<VertexBound, FormatError> {
        if self.g.format == VertexFormat::F32 {
            for v in 0..self.counts.vertices {
                if !finite3_f32(rd_f32x3(self.g.bytes, self.g.vertex_off(v))) {
                    return Err(FormatError::NonFinite("vertices"));
                }
            }
        }
        let dec = self.g.decoder();
        let bound =
            (0..self.counts.vertices as usize).fold(VertexBound::EMPTY, |b, v| b.with(dec.get(v)));
        for j in 0..self.counts.indices {
            if self.g.index(j) >= self.counts.vertices {
                return Err(FormatError::IndexOutOfRange);
            }
        }
        Ok(bound)
    }

    /// The polygons tile the index list with at least 3 indices each;
    /// returns the largest vertex count (0 without polygons).
    pub(super) fn check_polygons(&self) -> Result<u32, FormatError> {
        let mut prev = 0u32;
        let mut largest = 0u32;
        for p in 0..self.counts.polygons {
            let first = self.g.polygon_first(p);
            if p == 0 {
                if first != 0 {
                    return Err(FormatError::BadPolygon(0));
                }
            } else {
                match first.checked_sub(prev) {
                    Some(n) if n >= 3 => largest = largest.max(n),
                    _ => return Err(FormatError::BadPolygon(p - 1)),
                }
            }
            prev = first;
        }
        match self.counts.polygons.checked_sub(1) {
            Some(last) => match self.counts.indices.checked_sub(prev) {
                Some(n) if n >= 3 => Ok(largest.max(n)),
                _ => Err(FormatError::BadPolygon(last)),
            },
            None if self.counts.indices != 0 => Err(FormatError::BadHeader("index_count")),
            None => Ok(0),
        }
    }

    /// Compact records: every colour index is below the colour count, and
    /// the bits between the fields and the end of the record (8-byte
    /// records: between the colour index and hidden_edges) are zero (so a
    /// file has one encoding). Nothing to check for 16-byte records.
    pub(super) fn check_colours(&self, colour_count: u32) -> Result<(), FormatError> {
        if !self.g.compact {
            return Ok(());
        }
        let (lo, hi) = if self.w.shared {
            let bits = u32::from(self.g.rec_len) * 8;
            (self.g.fields.record_bits().min(bits), bits)
        } else {
            (
                self.g.fields.used_bits().min(COMPACT_HIDDEN_SHIFT),
                COMPACT_HIDDEN_SHIFT,
            )
        };
        // Bits lo..hi of the record (hi ≤ 64, lo ≤ hi).
        let spare = u64::MAX.checked_shr(64 - (hi - lo)).unwrap_or(0);
        for p in 0..self.counts.polygons {
            let r = rd_u64(self.g.bytes, self.g.polygon_off(p));
            let padding = r.checked_shr(lo).unwrap_or(0) & spare;
            if self.g.polygon_colour_index(p) >= colour_count || padding != 0 {
                return Err(FormatError::BadColour(p));
            }
        }
        Ok(())
    }

    /// Every edge record has a known kind.
    pub(super) fn check_edges(&self) -> Result<(), FormatError> {
        for j in 0..self.counts.edges {
            match self.g.edge_record(j as usize) {
                Some(r) if r[3] <= EDGE_SOFT => {}
                _ => return Err(FormatError::BadEdge(j)),
            }
        }
        Ok(())
    }

    /// The runs tile the polygons (non-empty, in order, the last ending at
    /// the polygon count), their planes are finite, and each polygon's `run`
    /// field names the run holding it. With a plane table
    /// ([`crate::format::FLAG_PLANES`]): every table entry is finite, every
    /// run's plane index is below the table's length, and each polygon's
    /// `run` field is the polygon's id less its run's index (run offsets,
    /// [`crate::format::FLAG_RUN_OFFSETS`]); compact entries
    /// ([`crate::format::FLAG_COMPACT_PLANES`]) well formed instead of
    /// finite.
    pub(super) fn check_runs(&self) -> Result<(), FormatError> {
        let runs = self.w.runs;
        let table_len = self.plane_table_len();
        for i in 0..table_len {
            if runs.is_compact() {
                if !compact_plane_ok(&runs.compact_entry(i)) {
                    return Err(FormatError::BadPlane(i));
                }
            } else if !self.w.table_plane(i).is_finite() {
                return Err(FormatError::NonFinite("plane table"));
            }
        }
        // What a polygon of a run holds: its offset from the run with a
        // plane table (see `Geometry::plane_index`), else the run.
        let table = runs.is_table();
        let mut start = 0u32;
        for r in 0..self.counts.runs {
            if table {
                if runs.plane_index(r) >= table_len {
                    return Err(FormatError::BadRuns);
                }
            } else if !self.w.run_plane(r).is_finite() {
                return Err(FormatError::NonFinite("run planes"));
            }
            let end = self.w.run_end(r);
            if end <= start || end > self.counts.polygons {
                return Err(FormatError::BadRuns);
            }
            for p in start..end {
                let field = self.g.polygon_run(p);
                let run = if table {
                    p.checked_sub(field)
                } else {
                    Some(field)
                };
                if run != Some(r) {
                    return Err(FormatError::BadRuns);
                }
            }
            start = end;
        }
        // Also rejects runs for no polygons, or polygons in no run.
        if start != self.counts.polygons {
            return Err(FormatError::BadRuns);
        }
        Ok(())
    }

    /// The bunch offsets start at 0, never decrease and end at the run count.
    pub(super) fn check_bunches(&self) -> Result<(), FormatError> {
        let mut prev = 0u32;
        for b in 0..=self.counts.bunches {
            let off = self.w.bunch_offset(b);
            if (b == 0 && off != 0) || off < prev {
                return Err(FormatError::BadBunches);
            }
            prev = off;
        }
        if prev != self.counts.runs {
            return Err(FormatError::BadBunches);
        }
        Ok(())
    }

    /// Checks the bunch tiling and the switch numbering; returns the total
    /// number of levels.
    pub(super) fn check_nodes(&self) -> Result<u32, FormatError> {
        let mut bunch = 0u64;
        let mut next_switch = 0u32;
        let mut levels = 0u64;
        for i in 0..self.counts.nodes {
            let n = self.w.node(i);
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

    /// Switch planes finite. With shared planes, every switch names a plane
    /// record below `run_count + extra` (an entry of the plane table with
    /// one), and the `extra` records after the runs have finite planes and
    /// an end field of 0.
    pub(super) fn check_switches(&self, extra: u32) -> Result<(), FormatError> {
        let runs = self.counts.runs;
        for i in runs..runs.saturating_add(extra) {
            let (plane, end) = self.w.plane_record(i);
            if !plane.is_finite() {
                return Err(FormatError::NonFinite("extra planes"));
            }
            if end != 0 {
                return Err(FormatError::BadRuns);
            }
        }
        // What a switch record may name: a plane record, or with a plane
        // table an entry of it.
        let records = if self.w.runs.is_table() {
            u64::from(self.plane_table_len())
        } else {
            u64::from(runs) + u64::from(extra)
        };
        for k in 0..self.counts.switches {
            if let Some(i) = self.w.switch_plane_index(k) {
                if u64::from(i) >= records {
                    return Err(FormatError::BadSwitch(k));
                }
            }
            // Compact entries were checked with the table.
            if !self.w.runs.is_compact() && !self.w.switch_plane(k).is_finite() {
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
    pub(super) fn check_depth(&self) -> Result<(), FormatError> {
        let (mut start, mut end, mut depth) = (0u32, 1u32, 0u32);
        while start < end {
            depth += 1;
            let switches = (start..end)
                .filter(|&i| self.w.node(i).switch != NO_SWITCH)
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
}
