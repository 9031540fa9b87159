//! Coplanar regions: neighbouring faces of one flat surface merged into
//! convex polygons (issue 15).
//!
//! CAD exports describe each flat face as many triangles (STL always). The
//! renderer walks, transforms, culls and fills every polygon separately, and
//! a flat face drawn as a few convex polygons gives the very same pixels:
//! the same plane and colour, and the seams inside it partition the pixels
//! exactly under the fill rule whichever way the region is cut.
//!
//! Contract of [`merge_coplanar`]:
//! - a **region** is a connected set of polygons linked by edges that
//!   are manifold (the directed edge `a→b` in exactly one polygon and
//!   `b→a` in exactly one other), whose two polygons have the same colour,
//!   the same file normals at the edge's ends (both without, or equal), and
//!   the same plane: every vertex of each within the planarity tolerance
//!   of the other's plane, normals on the same side;
//! - each region is merged greedily by [`super::planar::merge`] (the
//!   splitter of non-planar faces), so every piece is convex, has at most
//!   [`MAX_MERGED_VERTS`] vertices and every vertex within the planarity
//!   tolerance of its own Newell plane; no vertex is moved or dropped (a
//!   merge removes only the shared edge), so a neighbour's vertex on a
//!   merged edge stays a vertex of it and the seams stay free of
//!   T-junctions; the pieces tile the region, so the areas add up;
//! - a polygon that merges with nothing is returned unchanged; a merged
//!   piece gets its Newell plane, the region's colour, the vertex normals
//!   of its members by position, and the **source** id of the region's
//!   first face (the smallest id): picking a merged polygon names one face
//!   of the flat region it lies on. Every polygon of a region, merged or
//!   not, gets that id, so the outline effect (`crate::edges`, which hides
//!   edges between polygons of one source) does not draw the seams inside
//!   a flat face;
//! - the pieces of a region take the place of its first polygon, in the
//!   order of the input otherwise.

use super::planar::{self, find, loop_edges, Tols};
use crate::geom::{vertex_key, Plane, Polygon};
use glam::DVec3;
use std::collections::HashMap;

/// The most vertices a merged polygon may have: the outline mask of a
/// polygon record holds the edges `0..8` (`crate::edges::hidden_edges`), so
/// up to 8 every seam inside a region stays hidden; it also bounds the
/// renderer's per-polygon buffers (the header's vertex capacity `n + 5` for
/// a convex polygon). Polygons that have more vertices on their own are left
/// as they are.
pub const MAX_MERGED_VERTS: usize = 8;

/// Merges the coplanar regions of `polys` (see the module docs) and returns
/// the polygons that result.
pub(crate) fn merge_coplanar(polys: Vec<Polygon>, tols: Tols, max_verts: usize) -> Vec<Polygon> {
    let key = vertex_key;
    let mut id_of: HashMap<[u64; 3], usize> = HashMap::new();
    let loops: Vec<Vec<usize>> = polys
        .iter()
        .map(|p| {
            p.verts
                .iter()
                .map(|&v| {
                    let n = id_of.len();
                    *id_of.entry(key(v)).or_insert(n)
                })
                .collect()
        })
        .collect();
    // Directed edge → (its polygon, how many polygons have it).
    let mut owner: HashMap<(usize, usize), (usize, u32)> = HashMap::new();
    for (i, l) in loops.iter().enumerate() {
        for e in loop_edges(l) {
            owner.entry(e).or_insert((i, 0)).1 += 1;
        }
    }
    let mut parent: Vec<usize> = (0..polys.len()).collect();
    for (p, l) in loops.iter().enumerate() {
        for (k, (a, b)) in loop_edges(l).enumerate() {
            let (Some(&(_, 1)), Some(&(q, 1))) = (owner.get(&(a, b)), owner.get(&(b, a))) else {
                continue;
            };
            let kb = (k + 1) % l.len();
            if q != p && same_surface(&polys[p], &polys[q], (k, kb), (a, b), &loops[q], tols) {
                let (rp, rq) = (find(&mut parent, p), find(&mut parent, q));
                // The smaller index as root: the region's first polygon.
                parent[rp.max(rq)] = rp.min(rq);
            }
        }
    }
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); polys.len()];
    for p in 0..polys.len() {
        let r = find(&mut parent, p);
        members[r].push(p);
    }
    let mut slots: Vec<Option<Polygon>> = polys.into_iter().map(Some).collect();
    let mut out = Vec::with_capacity(slots.len());
    for region in members.iter().filter(|m| !m.is_empty()) {
        if let [only] = region[..] {
            out.extend(slots[only].take());
            continue;
        }
        let group: Vec<Polygon> = region.iter().filter_map(|&i| slots[i].take()).collect();
        let group_loops: Vec<&[usize]> = region.iter().map(|&i| &loops[i][..]).collect();
        out.extend(merge_region(group, &group_loops, tols, max_verts));
    }
    out
}

/// Whether `p` and `q`, which share the edge `a→b` (`p`'s vertices `ka`,
/// `kb`; `q` has `b→a`), lie on one surface: same colour, same normals at
/// `a` and `b`, each within the planarity tolerance of the other's plane.
fn same_surface(
    p: &Polygon,
    q: &Polygon,
    (ka, kb): (usize, usize),
    (a, b): (usize, usize),
    q_loop: &[usize],
    tols: Tols,
) -> bool {
    let normal_at = |poly: &Polygon, k: usize| poly.normals.as_ref().map(|n| n[k]);
    let q_at = |v: usize| q_loop.iter().position(|&x| x == v);
    let (Some(qa), Some(qb)) = (q_at(a), q_at(b)) else {
        return false;
    };
    let within = |s: &Polygon, t: &Polygon| {
        t.verts
            .iter()
            .all(|&v| s.plane.distance(v).abs() <= tols.planar)
    };
    p.color == q.color
        && normal_at(p, ka) == normal_at(q, qa)
        && normal_at(p, kb) == normal_at(q, qb)
        && p.plane.normal.dot(q.plane.normal) > 0.0
        && within(p, q)
        && within(q, p)
}

/// The convex pieces of one region (its polygons and their vertex-id
/// loops, the first polygon first).
fn merge_region(
    group: Vec<Polygon>,
    loops: &[&[usize]],
    tols: Tols,
    max_verts: usize,
) -> Vec<Polygon> {
    // Local vertex indices, and each vertex's position and normal.
    let mut local: HashMap<usize, usize> = HashMap::new();
    let mut pts: Vec<DVec3> = Vec::new();
    let mut normals: Vec<Option<DVec3>> = Vec::new();
    let local_loops: Vec<Vec<usize>> = group
        .iter()
        .zip(loops)
        .map(|(p, l)| {
            l.iter()
                .enumerate()
                .map(|(k, id)| {
                    *local.entry(*id).or_insert_with(|| {
                        pts.push(p.verts[k]);
                        normals.push(p.normals.as_ref().map(|n| n[k]));
                        pts.len() - 1
                    })
                })
                .collect()
        })
        .collect();
    let source = group.iter().map(|p| p.source).min().unwrap_or(0);
    let (normal, color) = (group[0].plane.normal, group[0].color);
    let pieces = planar::merge(&pts, &local_loops, normal, tols, max_verts);
    // A piece equal to a member's loop (same start: `merge` keeps an
    // unmerged loop as it is) is that member, plane and all.
    let mut whole: HashMap<&[usize], Polygon> =
        local_loops.iter().map(Vec::as_slice).zip(group).collect();
    pieces
        .iter()
        .filter_map(|piece| {
            if let Some(mut p) = whole.remove(piece.as_slice()) {
                p.source = source;
                return Some(p);
            }
            let verts: Vec<DVec3> = piece.iter().map(|&i| pts[i]).collect();
            let plane = Plane::newell(&verts)?;
            let vertex_normals: Option<Vec<DVec3>> = piece.iter().map(|&i| normals[i]).collect();
            Some(Polygon {
                verts,
                plane,
                source,
                color,
                normals: vertex_normals,
            })
        })
        .collect()
}

#[cfg(test)]
#[path = "coplanar_tests.rs"]
mod tests;
