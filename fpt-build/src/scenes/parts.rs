//! Building blocks of the procedural scenes: closed parts made of indexed
//! vertices, so that faces sharing an edge share its two vertices exactly.
//!
//! Every part here is a closed volume with outward faces counter-clockwise
//! seen from outside, provided that the 2D regions handed to [`extrude`] are
//! conforming partitions (pieces meet edge to edge, no T-junctions).

use crate::geom::Rgb;
use glam::{DVec2, DVec3};
use std::collections::HashMap;

/// A closed part: vertices and faces (vertex indices, colour).
#[derive(Clone, Debug, Default)]
pub(crate) struct Part {
    /// Vertex positions.
    pub verts: Vec<DVec3>,
    /// Faces as vertex indices, counter-clockwise seen from outside.
    pub faces: Vec<(Vec<usize>, Rgb)>,
}

/// The bit pattern of a coordinate, with −0 taken as +0.
fn key(x: f64) -> u64 {
    (x + 0.0).to_bits()
}

impl Part {
    /// Adds a vertex, returning its index.
    pub fn vert(&mut self, p: DVec3) -> usize {
        self.verts.push(p);
        self.verts.len() - 1
    }

    /// Adds a face.
    pub fn face(&mut self, idx: Vec<usize>, color: Rgb) {
        self.faces.push((idx, color));
    }

    /// The part moved by `frame`; faces are reversed when the frame is
    /// left-handed so that they stay outward.
    pub fn placed(mut self, frame: &Frame) -> Part {
        for v in &mut self.verts {
            *v = frame.apply(*v);
        }
        if frame.u.cross(frame.v).dot(frame.w) < 0.0 {
            for (f, _) in &mut self.faces {
                f.reverse();
            }
        }
        self
    }
}

/// An affine frame: local `(x, y, z)` ↦ `origin + x·u + y·v + z·w`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    /// Image of the local origin.
    pub origin: DVec3,
    /// Image of the local x axis.
    pub u: DVec3,
    /// Image of the local y axis.
    pub v: DVec3,
    /// Image of the local z axis.
    pub w: DVec3,
}

impl Frame {
    /// The right-handed frame with `u`, `v` and `w = u × v`.
    pub fn new(origin: DVec3, u: DVec3, v: DVec3) -> Frame {
        Frame {
            origin,
            u,
            v,
            w: u.cross(v),
        }
    }

    /// Maps a local point.
    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.origin + self.u * p.x + self.v * p.y + self.w * p.z
    }
}

/// A small deterministic random generator (SplitMix64) for the scenes.
pub(crate) struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }
}

/// Twice the signed area of a 2D polygon (positive when counter-clockwise).
pub(crate) fn signed_area2(p: &[DVec2]) -> f64 {
    (0..p.len())
        .map(|i| p[i].perp_dot(p[(i + 1) % p.len()]))
        .sum()
}

/// The prism over a 2D region between `z0 < z1` (local coordinates): the
/// region is given as a conforming partition into simple pieces (any
/// winding; each is made counter-clockwise). Caps are the pieces; a side
/// quad stands on every boundary edge of the region (an edge used by one
/// piece only).
pub(crate) fn extrude(pieces: &[Vec<DVec2>], z0: f64, z1: f64, cap: Rgb, side: Rgb) -> Part {
    let mut part = Part::default();
    let mut index: HashMap<(u64, u64), (usize, usize)> = HashMap::new();
    let mut loops: Vec<Vec<(usize, usize)>> = Vec::new();
    for piece in pieces {
        let mut pts = piece.clone();
        if signed_area2(&pts) < 0.0 {
            pts.reverse();
        }
        let ids = pts
            .iter()
            .map(|p| {
                *index.entry((key(p.x), key(p.y))).or_insert_with(|| {
                    let b = part.vert(p.extend(z0));
                    let t = part.vert(p.extend(z1));
                    (b, t)
                })
            })
            .collect();
        loops.push(ids);
    }
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for l in &loops {
        for i in 0..l.len() {
            *directed
                .entry((l[i].0, l[(i + 1) % l.len()].0))
                .or_default() += 1;
        }
    }
    for l in &loops {
        part.face(l.iter().map(|p| p.1).collect(), cap);
        part.face(l.iter().rev().map(|p| p.0).collect(), cap);
    }
    for l in &loops {
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            if !directed.contains_key(&(b.0, a.0)) {
                // The region lies left of a → b; the quad faces right, out.
                part.face(vec![a.0, b.0, b.1, a.1], side);
            }
        }
    }
    part
}

/// An axis-aligned box; its corners are exactly the given coordinates.
pub(crate) fn cuboid(lo: DVec3, hi: DVec3, color: Rgb) -> Part {
    let sq = vec![
        DVec2::new(lo.x, lo.y),
        DVec2::new(hi.x, lo.y),
        DVec2::new(hi.x, hi.y),
        DVec2::new(lo.x, hi.y),
    ];
    extrude(&[sq], lo.z, hi.z, color, color)
}

/// A box (parallelepiped) with centre `c` and half-axis vectors `a`, `b`, `e`.
pub(crate) fn oriented_box(c: DVec3, a: DVec3, b: DVec3, e: DVec3, color: Rgb) -> Part {
    let sq = [
        DVec2::new(-1.0, -1.0),
        DVec2::new(1.0, -1.0),
        DVec2::new(1.0, 1.0),
        DVec2::new(-1.0, 1.0),
    ];
    let frame = Frame {
        origin: c,
        u: a,
        v: b,
        w: e,
    };
    extrude(&[sq.to_vec()], -1.0, 1.0, color, color).placed(&frame)
}

/// A regular `n`-gon of radius `r` around `c`, counter-clockwise, its first
/// vertex at angle `phase` (radians).
pub(crate) fn ngon(c: DVec2, r: f64, n: usize, phase: f64) -> Vec<DVec2> {
    (0..n)
        .map(|i| {
            let a = phase + std::f64::consts::TAU * i as f64 / n as f64;
            c + DVec2::new(a.cos(), a.sin()) * r
        })
        .collect()
}

/// A right prism over a regular `n`-gon: axis from `base` along `axis`
/// (its length is the height), radius `r`.
pub(crate) fn cylinder(base: DVec3, axis: DVec3, r: f64, n: usize, color: Rgb) -> Part {
    let h = axis.length();
    let w = axis / h;
    let u = w.any_orthonormal_vector();
    let frame = Frame::new(base, u, w.cross(u));
    extrude(&[ngon(DVec2::ZERO, r, n, 0.0)], 0.0, h, color, color).placed(&frame)
}

/// A pyramid over a regular `n`-gon in a horizontal plane at `base`, apex
/// `height` above (or below, when negative) the centre.
pub(crate) fn pyramid(base: DVec3, r: f64, n: usize, height: f64, color: Rgb) -> Part {
    let mut part = Part::default();
    let mut ring: Vec<usize> = ngon(DVec2::ZERO, r, n, 0.0)
        .into_iter()
        .map(|p| part.vert(base + p.extend(0.0)))
        .collect();
    let apex = part.vert(base + DVec3::Z * height);
    if height < 0.0 {
        ring.reverse();
    }
    for i in 0..n {
        part.face(vec![ring[i], ring[(i + 1) % n], apex], color);
    }
    ring.reverse();
    part.face(ring, color);
    part
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extrude_counts_faces_of_a_partitioned_ring() {
        // A square ring cut into four trapezoids: 8 caps, 4 + 4 sides.
        let o = [(-2.0, -2.0), (2.0, -2.0), (2.0, 2.0), (-2.0, 2.0)].map(|(x, y)| DVec2::new(x, y));
        let i = o.map(|p| p * 0.5);
        let pieces: Vec<Vec<DVec2>> = (0..4)
            .map(|k| vec![o[k], o[(k + 1) % 4], i[(k + 1) % 4], i[k]])
            .collect();
        let part = extrude(&pieces, 0.0, 1.0, [0; 3], [1; 3]);
        assert_eq!(part.faces.len(), 16);
        assert_eq!(part.faces.iter().filter(|f| f.1 == [1; 3]).count(), 8);
        assert_eq!(part.verts.len(), 16);
    }
}
