//! Procedural test scenes: the paper's two objects re-made (a machinist's
//! vise base, a house), a benchmark city, and hard cases for the builders.
//!
//! Contract:
//! - Every polygon is planar and simple (convex or concave, never with a
//!   hole), counter-clockwise seen from outside, with an outward normal;
//!   `source` is its index in the scene (from 0); colours mean something.
//! - A scene with `closed == true` is a union of closed parts listed in
//!   [`Scene::parts`]: in each part every edge is used by exactly two faces,
//!   in opposite directions (shared vertices are bit-identical, no
//!   T-junctions). Parts may touch or interpenetrate.
//! - No two faces of a scene lie in the same plane, facing the same way, with
//!   overlapping areas (that would be a z-fight no order can settle); faces
//!   that touch face opposite ways.
//! - Everything is deterministic: the same call gives the same polygons.

mod city;
mod hard;
mod house;
pub(crate) mod parts;
mod robot;
mod torus;
mod vise;

pub use city::bench_city;
pub use hard::{
    cube_grid, cyclic_boards, gear, interpenetrating_boxes, near_coplanar_stack, open_sheet,
    slivers,
};
pub use house::house;
pub use robot::robot;
pub use torus::torus;
pub use vise::vise;

use crate::geom::{vertex_key, Polygon};
use glam::DVec3;
use parts::Part;
use std::collections::HashMap;
use std::ops::Range;

/// A named list of polygons.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Short name, e.g. `vise` or `house_tiny`.
    pub name: String,
    /// The polygons; `polygons[i].source == i`.
    pub polygons: Vec<Polygon>,
    /// Whether the scene is a closed volume (back faces may be culled).
    pub closed: bool,
    /// Index ranges of `polygons` that form one part each (closed ones when
    /// `closed`).
    pub parts: Vec<Range<usize>>,
}

/// Collects parts into a scene, numbering the faces.
#[derive(Default)]
pub(crate) struct SceneBuilder {
    polygons: Vec<Polygon>,
    parts: Vec<Range<usize>>,
}

impl SceneBuilder {
    /// Appends the faces of `part` as one part. Degenerate faces (a bug in
    /// the scene) are left out; the closedness tests then point at it.
    pub fn add(&mut self, part: Part) {
        let start = self.polygons.len();
        for (idx, color) in part.faces {
            let verts: Vec<DVec3> = idx.iter().map(|&i| part.verts[i]).collect();
            let source = self.polygons.len() as u32;
            if let Some(p) = Polygon::new(verts, source, color) {
                self.polygons.push(p);
            }
        }
        self.parts.push(start..self.polygons.len());
    }

    /// Appends several parts.
    pub fn add_all(&mut self, parts: impl IntoIterator<Item = Part>) {
        parts.into_iter().for_each(|p| self.add(p));
    }

    /// The finished scene.
    pub fn finish(self, name: &str, closed: bool) -> Scene {
        Scene {
            name: name.to_string(),
            polygons: self.polygons,
            closed,
            parts: self.parts,
        }
    }
}

/// Every scene, the large and the hard ones, plus two scaled copies for
/// tiny (×1e-4) and huge, far-off (×1e3, moved by 1e5) coordinates.
pub fn all() -> Vec<Scene> {
    let mut v = vec![
        vise(),
        house(),
        bench_city(),
        cyclic_boards(),
        interpenetrating_boxes(),
        gear(),
        cube_grid(),
        near_coplanar_stack(),
        slivers(),
        open_sheet(),
    ];
    let mut tiny = scaled(&v[1], 1e-4, DVec3::ZERO);
    tiny.name = "house_tiny".into();
    let mut huge = scaled(&v[0], 1e3, DVec3::splat(1e5));
    huge.name = "vise_huge".into();
    v.push(tiny);
    v.push(huge);
    v
}

/// The scene with every vertex `p` moved to `p·scale + offset` (`scale > 0`)
/// and the planes recomputed. Equal vertices stay equal, so closed parts
/// stay closed. The name gets a `_scaled` suffix.
pub fn scaled(scene: &Scene, scale: f64, offset: DVec3) -> Scene {
    let polygons = scene
        .polygons
        .iter()
        .filter_map(|p| {
            let verts = p.verts.iter().map(|&v| v * scale + offset).collect();
            Polygon::new(verts, p.source, p.color)
        })
        .collect();
    Scene {
        name: format!("{}_scaled", scene.name),
        polygons,
        closed: scene.closed,
        parts: scene.parts.clone(),
    }
}

/// What is wrong with the edges of `polys` as one closed volume: empty when
/// every directed edge (by bit-identical end points) occurs exactly once and
/// its reverse exactly once. Lists at most `limit` problems.
pub fn closed_defects(polys: &[Polygon], limit: usize) -> Vec<String> {
    type Key = [u64; 3];
    let k = vertex_key;
    let mut count: HashMap<(Key, Key), (usize, usize)> = HashMap::new();
    for (pi, p) in polys.iter().enumerate() {
        let n = p.verts.len();
        for i in 0..n {
            let e = (k(p.verts[i]), k(p.verts[(i + 1) % n]));
            count.entry(e).or_insert((0, pi)).0 += 1;
        }
    }
    let mut out = Vec::new();
    for (&(a, b), &(n, pi)) in &count {
        let back = count.get(&(b, a)).map_or(0, |c| c.0);
        if n != 1 || back != 1 {
            let f = |k: Key| k.map(f64::from_bits);
            out.push(format!(
                "edge {:?} -> {:?} of polygon {pi}: {n} times, reverse {back} times",
                f(a),
                f(b)
            ));
            if out.len() >= limit {
                break;
            }
        }
    }
    out.sort();
    out
}

#[cfg(test)]
mod tests;
