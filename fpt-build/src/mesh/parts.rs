//! Connected parts of a welded mesh: which are closed, which of the closed
//! ones wind inward, and how many edges are not shared the way a closed
//! volume shares them.
//!
//! Why: closedness decides how a model is drawn (a closed volume culls its
//! back faces), and it is decided from the face windings. A closed part
//! whose faces all wind inward (a common export error) passes the edge test
//! as well as a correct one, and culling then keeps exactly its inner walls.
//! The only test that tells them apart is the sign of the enclosed volume,
//! which is per part: a file can hold one inverted part among correct ones.
//!
//! Parts are the connected components of the faces joined across shared
//! edges (faces that only touch at a vertex stay in different parts). An
//! edge is *closed* when it is used exactly once in each direction;
//! everything else (an edge of one face, an edge of three faces, two faces
//! winding the same way across it) is a *boundary edge*. A part is closed
//! when all its edges are closed.
//!
//! A closed part with a negative volume is not inverted when it lies inside
//! an outward closed part: it is then a cavity (the inner wall of a hollow
//! solid), which must wind inward.

use super::planar::find;
use super::{OpenEdgeKind, OpenEdges, OPEN_EDGE_EXAMPLES};
use glam::DVec3;
use std::collections::HashMap;

/// What [`analyse`] found.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Parts {
    /// The part of each loop given to [`analyse`].
    pub part_of: Vec<u32>,
    /// Per part: all its edges are closed.
    pub closed: Vec<bool>,
    /// Per part: closed, and its signed volume is clearly negative (the
    /// faces wind inward).
    pub inverted: Vec<bool>,
    /// Edges of the whole mesh that are not closed.
    pub boundary_edges: usize,
    /// Those edges by kind, with the first few of each.
    pub open_edges: OpenEdges,
}

impl Parts {
    /// Number of closed parts.
    pub fn closed_count(&self) -> usize {
        self.closed.iter().filter(|&&c| c).count()
    }

    /// Number of open parts.
    pub fn open_count(&self) -> usize {
        self.closed.len() - self.closed_count()
    }

    /// Number of inverted (closed, inward-winding) parts.
    pub fn inverted_count(&self) -> usize {
        self.inverted.iter().filter(|&&c| c).count()
    }
}

/// Directed uses of an undirected edge `(a, b)` with `a < b`.
#[derive(Clone, Copy, Default)]
struct Uses {
    forward: u32,
    backward: u32,
    /// The first loop that uses the edge (all its users join its part).
    face: u32,
}

/// Analyses index loops (welded vertex ids into `positions`, no
/// consecutive repeats) into parts. Loops with fewer than three vertices
/// are each a part of their own, open. Linear in the number of corners
/// (hash maps aside).
pub(crate) fn analyse(loops: &[Vec<u32>], positions: &[DVec3]) -> Parts {
    let n = loops.len();
    let mut parent: Vec<usize> = (0..n).collect();
    let mut edges: HashMap<(u32, u32), Uses> = HashMap::new();
    for (fi, l) in loops.iter().enumerate() {
        let fi = u32::try_from(fi).unwrap_or(u32::MAX);
        for (k, &a) in l.iter().enumerate() {
            let b = l[(k + 1) % l.len()];
            if a == b {
                continue;
            }
            let e = edges.entry((a.min(b), a.max(b))).or_insert(Uses {
                face: fi,
                ..Uses::default()
            });
            if a < b {
                e.forward += 1;
            } else {
                e.backward += 1;
            }
            let (ra, rb) = (
                find(&mut parent, e.face as usize),
                find(&mut parent, fi as usize),
            );
            if ra != rb {
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    // Dense part numbers, in order of each part's first loop.
    let mut number: HashMap<usize, u32> = HashMap::new();
    let part_of: Vec<u32> = (0..n)
        .map(|i| {
            let root = find(&mut parent, i);
            let next = u32::try_from(number.len()).unwrap_or(u32::MAX);
            *number.entry(root).or_insert(next)
        })
        .collect();
    let parts = number.len();
    let mut closed = vec![true; parts];
    for l in loops.iter().zip(&part_of).filter(|(l, _)| l.len() < 3) {
        closed[*l.1 as usize] = false;
    }
    let mut boundary_edges = 0;
    for u in edges.values() {
        if !(u.forward == 1 && u.backward == 1) {
            boundary_edges += 1;
            if let Some(&p) = part_of.get(u.face as usize) {
                closed[p as usize] = false;
            }
        }
    }
    let open_edges = open_edges(loops, positions, &edges);
    let boxes = bounding_boxes(loops, positions, &part_of, parts);
    let mut inverted: Vec<bool> = signed_volumes(loops, positions, &part_of, &boxes)
        .iter()
        .zip(&closed)
        .map(|(&(volume, magnitude), &c)| c && volume < -VOLUME_REL * magnitude)
        .collect();
    if inverted.contains(&true) {
        keep_cavities(loops, positions, &part_of, &boxes, &mut inverted, &closed);
    }
    Parts {
        part_of,
        closed,
        inverted,
        boundary_edges,
        open_edges,
    }
}

/// The edges that are not closed, by kind, with the first few of each in
/// the order the loops use them (not the hash map's order, so the same
/// file always names the same edges).
fn open_edges(
    loops: &[Vec<u32>],
    positions: &[DVec3],
    edges: &HashMap<(u32, u32), Uses>,
) -> OpenEdges {
    let mut out = OpenEdges::default();
    /// The kind of a not-closed edge.
    fn of<'a>(out: &'a mut OpenEdges, u: &Uses) -> Option<&'a mut OpenEdgeKind> {
        match (u.forward + u.backward, u.forward == 1) {
            (2, true) => None,
            (1, _) => Some(&mut out.boundary),
            (2, false) => Some(&mut out.misoriented),
            _ => Some(&mut out.non_manifold),
        }
    }
    for u in edges.values() {
        if let Some(k) = of(&mut out, u) {
            k.count += 1;
        }
    }
    let mut named: Vec<(u32, u32)> = Vec::new();
    for l in loops {
        for (k, &a) in l.iter().enumerate() {
            let b = l[(k + 1) % l.len()];
            let key = (a.min(b), a.max(b));
            let Some(u) = edges.get(&key) else {
                continue;
            };
            let Some(kind) = of(&mut out, u) else {
                continue;
            };
            let Some(slot) = kind.first.iter_mut().find(|s| s.is_none()) else {
                continue;
            };
            if named.contains(&key) {
                continue;
            }
            named.push(key);
            *slot = Some([at(positions, a).to_array(), at(positions, b).to_array()]);
        }
        // Every kind is named in full (or the scan goes on to the end).
        if named.len() == 3 * OPEN_EDGE_EXAMPLES {
            break;
        }
    }
    out
}

/// A closed part counts as inverted when its signed volume is below
/// `−VOLUME_REL ×` the sum of the magnitudes of its terms: far above the
/// rounding of the sum, far below any real solid (a flat "volume" of two
/// faces back to back has a signed volume of zero up to rounding and is
/// left alone).
const VOLUME_REL: f64 = 1e-9;

/// The position of vertex `i` (the origin for an index out of range, which
/// [`super::prepare`] never passes).
fn at(positions: &[DVec3], i: u32) -> DVec3 {
    positions.get(i as usize).copied().unwrap_or(DVec3::ZERO)
}

/// Per part: the corners of its bounding box, and the factor that scales
/// its size to 1 (for sums that must not depend on the model's scale).
type Box3 = (DVec3, DVec3, f64);

fn bounding_boxes(
    loops: &[Vec<u32>],
    positions: &[DVec3],
    part_of: &[u32],
    parts: usize,
) -> Vec<Box3> {
    let mut out = vec![
        (
            DVec3::splat(f64::INFINITY),
            DVec3::splat(f64::NEG_INFINITY),
            1.0
        );
        parts
    ];
    for (l, &p) in loops.iter().zip(part_of) {
        let b = &mut out[p as usize];
        for &i in l {
            b.0 = b.0.min(at(positions, i));
            b.1 = b.1.max(at(positions, i));
        }
    }
    for b in &mut out {
        let size = (b.1 - b.0).max_element();
        if size.is_finite() && size > 0.0 {
            b.2 = 1.0 / size;
        }
    }
    out
}

/// The triangles of a loop fanned from its first vertex.
fn fan(l: &[u32]) -> impl Iterator<Item = (u32, u32, u32)> + '_ {
    let first = l.first().copied().unwrap_or(0);
    l.get(1..)
        .unwrap_or(&[])
        .windows(2)
        .map(move |w| (first, w[0], w[1]))
}

/// Per part: six times the signed volume enclosed by its loops (positive
/// when the faces wind counter-clockwise seen from outside), and the sum of
/// the absolute values of the terms. Positions are taken relative to the
/// part's box and divided by its size first, so neither the distance from
/// the coordinate origin nor the model's scale costs precision or
/// overflows.
fn signed_volumes(
    loops: &[Vec<u32>],
    positions: &[DVec3],
    part_of: &[u32],
    boxes: &[Box3],
) -> Vec<(f64, f64)> {
    let mut out = vec![(0.0, 0.0); boxes.len()];
    for (l, &p) in loops.iter().zip(part_of) {
        let (lo, _, inv) = boxes[p as usize];
        let rel = |i: u32| (at(positions, i) - lo) * inv;
        for (a, b, c) in fan(l) {
            let t = rel(a).dot(rel(b).cross(rel(c)));
            out[p as usize].0 += t;
            out[p as usize].1 += t.abs();
        }
    }
    out
}

/// Clears `inverted` for the parts that are cavities: an inward-winding
/// closed part inside an outward one is the inner wall of a hollow solid,
/// modelled right. Inside means a vertex of it has winding number about 1
/// with respect to the outer part (the sum of the solid angles of the outer
/// part's triangles seen from it, over 4π); only parts whose box holds the
/// inverted part's box are tried, so unrelated parts cost nothing.
fn keep_cavities(
    loops: &[Vec<u32>],
    positions: &[DVec3],
    part_of: &[u32],
    boxes: &[Box3],
    inverted: &mut [bool],
    closed: &[bool],
) {
    let mut loops_of: Vec<Vec<usize>> = vec![Vec::new(); boxes.len()];
    for (k, &p) in part_of.iter().enumerate() {
        loops_of[p as usize].push(k);
    }
    let holds =
        |outer: &Box3, inner: &Box3| outer.0.cmple(inner.0).all() && inner.1.cmple(outer.1).all();
    for i in 0..boxes.len() {
        if !inverted[i] {
            continue;
        }
        let Some(&q) = loops_of[i].first().and_then(|&k| loops[k].first()) else {
            continue;
        };
        let q = at(positions, q);
        let inside = (0..boxes.len()).any(|j| {
            j != i
                && closed[j]
                && !inverted[j]
                && holds(&boxes[j], &boxes[i])
                && winding_number(
                    q,
                    loops_of[j].iter().map(|&k| &loops[k][..]),
                    positions,
                    &boxes[j],
                ) > 0.5
        });
        if inside {
            inverted[i] = false;
        }
    }
}

/// The winding number of the closed surface `loops` around `q` (1 inside
/// an outward surface, 0 outside), with positions scaled by `b` first.
fn winding_number<'a>(
    q: DVec3,
    loops: impl Iterator<Item = &'a [u32]>,
    positions: &[DVec3],
    b: &Box3,
) -> f64 {
    let (lo, _, inv) = *b;
    let rel = |i: u32| (at(positions, i) - q) * inv;
    let q_lo = (q - lo) * inv;
    if !q_lo.is_finite() {
        return 0.0;
    }
    let mut total = 0.0;
    for l in loops {
        for (a, b, c) in fan(l) {
            let (a, b, c) = (rel(a), rel(b), rel(c));
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            // Van Oosterom and Strackee: tan(Ω/2) = det / denominator.
            let det = a.dot(b.cross(c));
            let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
            total += 2.0 * det.atan2(den);
        }
    }
    total / (4.0 * std::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit cube loops (outward), its corners moved by `at`.
    fn cube(at: DVec3, first: u32) -> (Vec<DVec3>, Vec<Vec<u32>>) {
        let v: Vec<DVec3> = (0..8)
            .map(|i| at + DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)))
            .collect();
        let f = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [1, 3, 7, 5],
            [0, 4, 6, 2],
        ];
        let loops = f
            .iter()
            .map(|l| l.iter().map(|&i| i + first).collect())
            .collect();
        (v, loops)
    }

    #[test]
    fn outward_cube_is_one_closed_part_not_inverted() {
        let (v, l) = cube(DVec3::ZERO, 0);
        let p = analyse(&l, &v);
        assert_eq!(p.closed, vec![true]);
        assert_eq!(p.inverted, vec![false]);
        assert_eq!(p.boundary_edges, 0);
        assert_eq!(p.part_of, vec![0; 6]);
    }

    #[test]
    fn one_inverted_cube_of_three_far_from_the_origin_at_any_scale() {
        for scale in [1e-30, 1.0, 1e30] {
            let mut v = Vec::new();
            let mut loops = Vec::new();
            for k in 0..3u32 {
                let at = DVec3::new(1e6 + 3.0 * f64::from(k), 0.0, 0.0);
                let (cv, mut cl) = cube(at, v.len() as u32);
                if k == 1 {
                    cl.iter_mut().for_each(|l| l.reverse());
                }
                v.extend(cv.into_iter().map(|p| p * scale));
                loops.extend(cl);
            }
            let p = analyse(&loops, &v);
            assert_eq!(p.closed, vec![true; 3], "{scale}");
            assert_eq!(p.inverted, vec![false, true, false], "{scale}");
            assert_eq!(p.inverted_count(), 1);
            assert_eq!(p.part_of[6..12], [1; 6]);
        }
    }

    #[test]
    fn a_cavity_winding_inward_inside_a_solid_is_left_alone() {
        // A 3×3×3 box (outward) with a unit cube hole inside (inward), and
        // apart, an inward unit cube that really is inside out.
        let (mut v, mut loops) = cube(DVec3::ZERO, 0);
        v.iter_mut().for_each(|p| *p *= 3.0);
        let (cv, mut cl) = cube(DVec3::ONE, 8);
        cl.iter_mut().for_each(|l| l.reverse());
        let (fv, mut fl) = cube(DVec3::new(10.0, 0.0, 0.0), 16);
        fl.iter_mut().for_each(|l| l.reverse());
        v.extend(cv.into_iter().chain(fv));
        loops.extend(cl.into_iter().chain(fl));
        let p = analyse(&loops, &v);
        assert_eq!(p.closed, vec![true; 3]);
        assert_eq!(p.inverted, vec![false, false, true]);
    }

    #[test]
    fn winding_number_is_one_inside_and_zero_outside() {
        let (v, l) = cube(DVec3::ZERO, 0);
        let v: Vec<DVec3> = v.into_iter().map(|p| p * 1e20).collect();
        let b = bounding_boxes(&l, &v, &[0; 6], 1)[0];
        let w = |q: DVec3| winding_number(q, l.iter().map(|l| &l[..]), &v, &b);
        assert!((w(DVec3::new(0.5, 0.3, 0.9) * 1e20) - 1.0).abs() < 1e-9);
        assert!(w(DVec3::new(2.0, 0.5, 0.5) * 1e20).abs() < 1e-9);
    }

    #[test]
    fn open_parts_and_boundary_edges_are_counted() {
        let (v, mut l) = cube(DVec3::ZERO, 0);
        l.pop(); // a box without its lid: 4 boundary edges
        let (v2, l2) = cube(DVec3::splat(5.0), 8);
        let v: Vec<DVec3> = v.into_iter().chain(v2).collect();
        l.extend(l2);
        let p = analyse(&l, &v);
        assert_eq!(p.closed, vec![false, true]);
        assert_eq!((p.open_count(), p.closed_count()), (1, 1));
        assert_eq!(p.boundary_edges, 4);
        assert_eq!(p.inverted, vec![false, false]);
        let e = p.open_edges;
        assert_eq!(
            (e.boundary.count, e.non_manifold.count, e.misoriented.count),
            (4, 0, 0)
        );
        // Three rim edges of the lidless box are named: the removed face
        // is the one at x = 0, so is the rim.
        let named: Vec<[[f64; 3]; 2]> = e.boundary.first.iter().flatten().copied().collect();
        assert_eq!(named.len(), 3);
        for [a, b] in &named {
            assert!(a != b && a[0] == 0.0 && b[0] == 0.0, "{named:?}");
        }
        assert!(e.non_manifold.first.iter().all(Option::is_none));
    }

    #[test]
    fn non_manifold_and_misoriented_edges_are_counted_apart() {
        // Three triangles on the edge 0-1 (a fin on a two-triangle sheet).
        let v = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(0.0, -1.0, 0.0),
            DVec3::Z,
        ];
        let p = analyse(&[vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]], &v);
        let e = p.open_edges;
        assert_eq!(e.non_manifold.count, 1);
        assert_eq!(e.non_manifold.first[0], Some([[0.0; 3], [1.0, 0.0, 0.0]]));
        assert_eq!(e.boundary.count, 6);
        assert_eq!(p.boundary_edges, 7);
        // A cube with one face flipped: its four edges are wound the same
        // way by both their faces.
        let (v, mut l) = cube(DVec3::ZERO, 0);
        l[0].reverse();
        let e = analyse(&l, &v).open_edges;
        assert_eq!(
            (e.boundary.count, e.non_manifold.count, e.misoriented.count),
            (0, 0, 4)
        );
    }

    #[test]
    fn flat_back_to_back_pair_is_closed_but_not_inverted() {
        let v = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
        let p = analyse(&[vec![0, 1, 2], vec![0, 2, 1]], &v);
        assert_eq!(p.closed, vec![true]);
        assert_eq!(p.inverted, vec![false]);
    }

    #[test]
    fn a_flipped_face_makes_its_edges_boundary() {
        let (v, mut l) = cube(DVec3::ZERO, 0);
        l[0].reverse();
        let p = analyse(&l, &v);
        assert_eq!(p.closed, vec![false]);
        assert_eq!(p.boundary_edges, 4);
    }

    #[test]
    fn faces_touching_at_a_vertex_are_separate_parts() {
        let v = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(0.0, -1.0, 0.0),
        ];
        let p = analyse(&[vec![0, 1, 2], vec![0, 3, 4], vec![7, 7]], &v);
        assert_eq!(p.part_of, vec![0, 1, 2]);
        assert_eq!(p.closed, vec![false; 3]);
    }
}
