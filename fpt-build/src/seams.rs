//! Conforming seams: polygons that meet along an edge share its vertices.
//!
//! The rasterizer's top-left rule leaves no crack between two polygons only
//! when both sides of an edge have the same two end points. The builder
//! breaks that in two ways, and [`repair_seams`] (run at the end of every
//! build) mends both: a split puts a new vertex on an edge that the
//! neighbouring face, left whole, does not have (a T-junction); and faces
//! that share a vertex in the mesh file can carry copies of it a rounding
//! error apart (each face is snapped onto its own plane at import).

use crate::geom::{bounds, vertex_key, Polygon};
use glam::{DVec3, IVec3};
use std::collections::HashMap;

/// Closes the seams between polygons that should share an edge exactly,
/// in two steps (tolerance `1e-7 ×` the scene diagonal), and returns the
/// number of vertices welded plus inserted:
/// 1. **weld**: vertices closer than the tolerance become one (the mesh
///    import snaps each face's vertices onto its own plane, so faces that
///    share a vertex in the file can end up with copies ~1e-7 apart, which
///    the serializer stores as two vertices);
/// 2. **T-junctions**: into every polygon edge, insert the vertices of
///    other polygons that lie on it, strictly between its ends. The
///    builder's splits put a new vertex on an edge that the neighbouring
///    face, left whole, does not have.
///
/// Either defect lets the two sides of one edge round to different screen
/// points (vertex snapping), which can open a sub-pixel sliver of
/// background; with one vertex shared by both polygons (the same
/// coordinates, so one vertex index in the file) the edge is shared
/// exactly and the fill's top-left rule leaves no crack. Planes are not
/// recomputed (the changes are far below any tolerance that matters).
pub fn repair_seams(polys: &mut [Polygon]) -> usize {
    if polys.is_empty() {
        return 0;
    }
    let key = vertex_key;
    let (lo, hi) = bounds(polys);
    let eps = 1e-7 * (hi - lo).length().max(f64::MIN_POSITIVE);
    // A grid over the vertices keeps every search local.
    let cell = ((hi - lo).max_element() / 64.0).max(4.0 * eps);
    let cell_of = |v: DVec3| ((v - lo) / cell).floor().as_ivec3();
    let near_cells = |a: DVec3, b: DVec3| {
        let (c0, c1) = (
            cell_of(a.min(b) - DVec3::splat(eps)),
            cell_of(a.max(b) + DVec3::splat(eps)),
        );
        (c0.x..=c1.x).flat_map(move |x| {
            (c0.y..=c1.y).flat_map(move |y| (c0.z..=c1.z).map(move |z| IVec3::new(x, y, z)))
        })
    };
    // 1. Weld: each vertex maps to the first vertex within eps.
    let mut reps: Vec<DVec3> = Vec::new();
    let mut grid: HashMap<IVec3, Vec<usize>> = HashMap::new();
    let mut map: HashMap<[u64; 3], DVec3> = HashMap::new();
    let mut changed = 0;
    for p in polys.iter() {
        for &v in &p.verts {
            if map.contains_key(&key(v)) {
                continue;
            }
            let found = near_cells(v, v)
                .flat_map(|c| {
                    grid.get(&c)
                        .into_iter()
                        .flatten()
                        .copied()
                        .collect::<Vec<_>>()
                })
                .map(|i| reps[i])
                .find(|r| (*r - v).length() <= eps);
            let r = match found {
                Some(r) => {
                    changed += 1;
                    r
                }
                None => {
                    grid.entry(cell_of(v)).or_default().push(reps.len());
                    reps.push(v);
                    v
                }
            };
            map.insert(key(v), r);
        }
    }
    for p in polys.iter_mut() {
        let welded: Vec<DVec3> = p
            .verts
            .iter()
            .map(|v| map.get(&key(*v)).copied().unwrap_or(*v))
            .collect();
        let mut w = welded.clone();
        w.dedup_by(|a, b| key(*a) == key(*b));
        while w.len() > 1 && key(w[0]) == key(w[w.len() - 1]) {
            w.pop();
        }
        // A sliver that the weld collapses (thinner than the tolerance)
        // keeps its place in the tree with its welded vertices, repeats
        // and all: it covers nothing, and its edges are its neighbours'
        // (kept unwelded, its stray copies were open edges).
        let verts = if w.len() >= 3 { w } else { welded };
        p.normals = p.normals_at(&verts);
        p.verts = verts;
    }
    // 2. T-junctions, against the welded vertices.
    for p in polys.iter_mut() {
        let n = p.verts.len();
        let mut out = Vec::with_capacity(n);
        for k in 0..n {
            let (a, b) = (p.verts[k], p.verts[(k + 1) % n]);
            out.push(a);
            let ab = b - a;
            let len2 = ab.length_squared();
            if len2 == 0.0 {
                continue;
            }
            let mut on: Vec<(f64, DVec3)> = Vec::new();
            for c in near_cells(a, b) {
                for &i in grid.get(&c).into_iter().flatten() {
                    let v = reps[i];
                    if key(v) == key(a) || key(v) == key(b) {
                        continue;
                    }
                    // Strictly between the ends, however near one of them:
                    // a vertex off to the side of an end by a little more
                    // than the weld distance stays a vertex of its own, and
                    // the neighbour that has it must find it in this edge
                    // too (or the seam keeps a sliver no one covers).
                    let t = (v - a).dot(ab) / len2;
                    if t > 0.0 && t < 1.0 && (a + ab * t - v).length() <= eps {
                        on.push((t, v));
                    }
                }
            }
            on.sort_by(|u, v| u.0.total_cmp(&v.0));
            changed += on.len();
            out.extend(on.into_iter().map(|(_, v)| v));
        }
        p.normals = p.normals_at(&out);
        p.verts = out;
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(pts: [[f64; 2]; 4], source: u32) -> Polygon {
        let v = pts.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect();
        Polygon::new(v, source, [1, 1, 1]).unwrap()
    }

    #[test]
    fn t_junction_gets_the_vertex_and_copies_are_welded() {
        // Left square whole; right side split in two at y = 0.5, so the
        // shared edge x = 1 has a vertex (1, 0.5) only on the right.
        let mut polys = vec![
            quad([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], 0),
            quad([[1.0, 0.0], [2.0, 0.0], [2.0, 0.5], [1.0, 0.5]], 1),
            quad([[1.0, 0.5], [2.0, 0.5], [2.0, 1.0], [1.0 + 1e-9, 1.0]], 1),
        ];
        let changed = repair_seams(&mut polys);
        assert_eq!(changed, 2);
        assert_eq!(polys[0].verts.len(), 5);
        assert_eq!(polys[0].verts[2], DVec3::new(1.0, 0.5, 0.0));
        // The near copy of (1, 1) became the same vertex.
        assert!(polys[2].verts.contains(&DVec3::new(1.0, 1.0, 0.0)));
        // Nothing else moves: a second pass changes nothing.
        assert_eq!(repair_seams(&mut polys), 0);
    }

    #[test]
    fn a_vertex_beside_an_end_is_inserted_too() {
        // The right face has a vertex c 0.8 tolerance below and 0.8
        // tolerance beside the corner (1, 1): too far from the corner to
        // be welded (1.13 tolerances), within the tolerance of the left
        // face's edge x = 1 and nearer its end than the tolerance. The
        // left face must get it, or the seam keeps a sliver.
        let eps = 1e-7 * 5f64.sqrt();
        let c = [1.0 + 0.8 * eps, 1.0 - 0.8 * eps];
        let right = {
            let v = [[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], c]
                .iter()
                .map(|p| DVec3::new(p[0], p[1], 0.0))
                .collect();
            Polygon::new(v, 1, [1, 1, 1]).unwrap()
        };
        let mut polys = vec![
            quad([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], 0),
            right,
        ];
        repair_seams(&mut polys);
        assert!(
            polys[0].verts.contains(&DVec3::new(c[0], c[1], 0.0)),
            "{:?}",
            polys[0].verts
        );
    }
}
