//! Test-only writer of raw tree files, field by field, so that the unit
//! tests can build files the host serializer would never write (bad
//! numbering, cycles, ...) with a correct checksum.

extern crate std;

use std::vec::Vec;

use crate::format::{
    crc32, Counts, Sections, VertexFormat, FLAG_SMALL, HEADER_LEN, MAGIC, VERSION,
};

/// Every field of a file, unchecked.
#[derive(Clone, Debug)]
pub struct Raw {
    pub flags: u32,
    /// Declared effects; `None`: the defaults for `flags`.
    pub effects: Option<u32>,
    pub format: VertexFormat,
    pub shift: u8,
    pub index_size: u8,
    pub max_depth: u32,
    pub origin: [f64; 3],
    pub half_extent: [f32; 3],
    pub radius: f32,
    /// Encoded vertices, `format.vertex_len()` bytes each.
    pub vertex_bytes: Vec<u8>,
    /// First index, run, source, colour.
    pub polys: Vec<(u32, u32, u32, [u8; 3])>,
    /// Plane `[nx, ny, nz, d]` and end of every run.
    pub runs: Vec<([f32; 4], u32)>,
    pub indices: Vec<u32>,
    pub bunches: Vec<u32>,
    pub nodes: Vec<[u32; 3]>,
    pub switches: Vec<[f32; 4]>,
    /// Small walk records ([`crate::format::FLAG_SMALL`], set in
    /// `flags` when the file is written): `u16` bunch offsets, 8-byte
    /// nodes. On by default: a reader without the `large-trees` feature
    /// reads only these.
    pub small: bool,
}

impl Raw {
    /// An empty open tree: a root with no levels.
    pub fn empty() -> Raw {
        Raw {
            flags: 0,
            effects: None,
            format: VertexFormat::F32,
            shift: 0,
            index_size: 2,
            max_depth: 1,
            origin: [0.0; 3],
            half_extent: [1.0; 3],
            radius: 2.0,
            vertex_bytes: Vec::new(),
            polys: Vec::new(),
            runs: Vec::new(),
            indices: Vec::new(),
            bunches: std::vec![0],
            nodes: std::vec![[0, 0, u32::MAX]],
            switches: Vec::new(),
            small: true,
        }
    }

    /// Appends `f32` vertices.
    pub fn add_f32_vertices(&mut self, vs: &[[f32; 3]]) {
        for v in vs {
            for x in v {
                self.vertex_bytes.extend_from_slice(&x.to_le_bytes());
            }
        }
    }

    /// Appends a polygon over `idx` (appended to the index list), in a run
    /// of its own: run ids equal polygon ids until [`Raw::merge_runs`].
    pub fn add_polygon(&mut self, plane: [f32; 4], idx: &[u32], source: u32) {
        let id = self.polys.len() as u32;
        self.polys
            .push((self.indices.len() as u32, id, source, [1, 2, 3]));
        self.runs.push((plane, id + 1));
        self.indices.extend_from_slice(idx);
    }

    /// Merges run `r + 1` into run `r` (keeping run `r`'s plane) and
    /// renumbers the polygons' run fields and the bunch offsets (which must
    /// not separate the two runs).
    pub fn merge_runs(&mut self, r: usize) {
        let end = self.runs.remove(r + 1).1;
        self.runs[r].1 = end;
        for p in &mut self.polys {
            if p.1 as usize > r {
                p.1 -= 1;
            }
        }
        for b in &mut self.bunches {
            if *b as usize > r {
                *b -= 1;
            }
        }
    }

    /// The file, with its checksum.
    pub fn bytes(&self) -> Vec<u8> {
        let vlen = self.format.vertex_len();
        let counts = Counts {
            vertices: (self.vertex_bytes.len() / vlen) as u32,
            polygons: self.polys.len() as u32,
            indices: self.indices.len() as u32,
            bunches: self.bunches.len().saturating_sub(1) as u32,
            nodes: self.nodes.len() as u32,
            switches: self.switches.len() as u32,
            runs: self.runs.len() as u32,
            edges: 0,
            normals: 0,
            small: self.small,
        };
        let isz = usize::from(self.index_size).max(2);
        let s = Sections::new(&counts, self.format, isz).unwrap();
        let mut o = Vec::new();
        o.extend_from_slice(&MAGIC);
        o.extend_from_slice(&VERSION.to_le_bytes());
        o.extend_from_slice(&(HEADER_LEN as u16).to_le_bytes());
        let u32s = |o: &mut Vec<u8>, xs: &[u32]| {
            xs.iter()
                .for_each(|x| o.extend_from_slice(&x.to_le_bytes()))
        };
        let effects = self.effects.unwrap_or(
            crate::effects::Effects::defaults(self.flags & crate::format::FLAG_CLOSED != 0).bits(),
        );
        let small = if self.small { FLAG_SMALL } else { 0 };
        u32s(&mut o, &[s.file_len as u32, self.flags | small, effects]);
        o.extend_from_slice(&[self.format.code(), self.shift, self.index_size, 0]);
        u32s(
            &mut o,
            &[
                self.max_depth,
                counts.vertices,
                counts.polygons,
                counts.indices,
                counts.bunches,
                counts.nodes,
                counts.switches,
                counts.runs,
            ],
        );
        self.origin
            .iter()
            .for_each(|x| o.extend_from_slice(&x.to_le_bytes()));
        self.half_extent
            .iter()
            .for_each(|x| o.extend_from_slice(&x.to_le_bytes()));
        o.extend_from_slice(&self.radius.to_le_bytes());
        // Capacities: the largest polygon (the polygons tile the indices),
        // and the convex bound for the scratch.
        let firsts: Vec<u32> = self.polys.iter().map(|p| p.0).collect();
        let largest = (0..firsts.len())
            .map(|k| {
                let end = firsts.get(k + 1).copied().unwrap_or(counts.indices);
                end.saturating_sub(firsts[k])
            })
            .max()
            .unwrap_or(0);
        u32s(&mut o, &[largest, largest + 5, 0, 0]);
        o.extend_from_slice(&self.vertex_bytes);
        o.resize(s.polygons, 0);
        for (first, run, source, c) in &self.polys {
            u32s(&mut o, &[*first, *run, *source]);
            o.extend_from_slice(&[c[0], c[1], c[2], 0]);
        }
        o.resize(s.indices, 0);
        for &i in &self.indices {
            if isz == 2 {
                o.extend_from_slice(&(i as u16).to_le_bytes());
            } else {
                o.extend_from_slice(&i.to_le_bytes());
            }
        }
        o.resize(s.runs, 0);
        for (plane, end) in &self.runs {
            plane
                .iter()
                .for_each(|x| o.extend_from_slice(&x.to_le_bytes()));
            u32s(&mut o, &[*end]);
        }
        o.resize(s.bunches, 0);
        for &b in &self.bunches {
            if self.small {
                o.extend_from_slice(&(b as u16).to_le_bytes());
            } else {
                o.extend_from_slice(&b.to_le_bytes());
            }
        }
        o.resize(s.nodes, 0);
        for &[first, levels, switch] in &self.nodes {
            if self.small {
                u32s(&mut o, &[first]);
                o.extend_from_slice(&(levels as u16).to_le_bytes());
                o.extend_from_slice(&(switch as i32 as i16).to_le_bytes());
            } else {
                u32s(&mut o, &[first, levels, switch]);
            }
        }
        o.resize(s.switches, 0);
        for p in &self.switches {
            p.iter().for_each(|x| o.extend_from_slice(&x.to_le_bytes()));
        }
        o.resize(s.crc, 0);
        let crc = crc32(&o);
        o.extend_from_slice(&crc.to_le_bytes());
        o
    }
}

/// Rewrites the trailing checksum after an edit.
pub fn fix_crc(b: &mut [u8]) {
    let n = b.len() - 4;
    let crc = crc32(&b[..n]);
    b[n..].copy_from_slice(&crc.to_le_bytes());
}

/// A square in the plane `z = z` facing `+z` (`up`) or `-z`, over 4 new
/// vertices.
pub fn add_square(r: &mut Raw, z: f32, up: bool, source: u32) {
    let base = (r.vertex_bytes.len() / 12) as u32;
    r.add_f32_vertices(&[[0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z]]);
    if up {
        r.add_polygon(
            [0.0, 0.0, 1.0, -z],
            &[base, base + 1, base + 2, base + 3],
            source,
        );
    } else {
        r.add_polygon(
            [0.0, 0.0, -1.0, z],
            &[base + 3, base + 2, base + 1, base],
            source,
        );
    }
}

/// Two squares facing up, id 0 at z = 1 and id 1 at z = 0, split by a
/// switch at z = 0.5 facing up: id 0 is in its front group (node 1), id 1 in
/// its back group (node 2), each as `F_1`. Open volume, depth 2.
pub fn two_floors() -> Raw {
    let mut r = Raw::empty();
    add_square(&mut r, 1.0, true, 10); // id 0 → in G_f, node 1
    add_square(&mut r, 0.0, true, 20); // id 1 → in G_b, node 2
                                       // Bunches: node 0 has only O (empty); node 1: F_1 = {0}, B_1 = {};
                                       // node 2: F_1 = {1}, B_1 = {}.
    r.bunches = std::vec![0, 0, 1, 1, 2, 2];
    r.nodes = std::vec![[0, 0, 0], [1, 1, u32::MAX], [3, 1, u32::MAX]];
    r.switches = std::vec![[0.0, 0.0, 1.0, -0.5]];
    r.max_depth = 2;
    r
}
