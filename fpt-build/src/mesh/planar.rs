//! Planarity of one face: keep it whole or split it into planar convex
//! pieces, never moving a vertex.
//!
//! Contract of [`planarize`]: the input is a cleaned vertex loop (no
//! consecutive repeats). A face that is too thin is [`Planarized::Degenerate`];
//! a face whose vertices are all within the planarity tolerance of its Newell
//! plane stays one polygon, concave or not ([`Planarized::Whole`]); any other
//! face is triangulated by ear clipping of its projection onto its Newell
//! plane, and adjacent triangles are then merged greedily while the union
//! stays planar and convex ([`Planarized::Split`]). Every piece keeps the
//! face's source id and colour, the face's winding, and the face's own
//! vertices where they are (within the planarity tolerance of the piece's
//! Newell plane): a vertex shared with a neighbouring face stays bit for
//! bit the neighbour's, so the seams between faces conform. The pieces tile
//! the triangulated face, so their areas add up to the face's.

use crate::geom::{self, Plane, Polygon, Rgb};
use glam::{DVec2, DVec3};
use std::collections::HashMap;

/// Faces with more vertices than this are fan-triangulated and not merged:
/// ear clipping and merging are quadratic or worse, and only hostile or very
/// unusual files have such huge non-planar faces.
const MAX_EAR_VERTS: usize = 64;

/// Absolute tolerances for one model.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tols {
    /// Largest distance of a vertex from a face's plane for the face to
    /// count as planar.
    pub planar: f64,
    /// The builder's tolerance: thinner faces are degenerate, closer
    /// vertices of a snapped polygon are merged.
    pub build: f64,
}

/// What became of one face.
#[derive(Debug)]
pub(crate) enum Planarized {
    /// No area within tolerance: drop it.
    Degenerate,
    /// Planar: one polygon.
    Whole(Polygon),
    /// Not planar: several planar pieces.
    Split(Vec<Polygon>),
}

/// Classifies and, when needed, splits the face with vertices `pts`.
pub(crate) fn planarize(pts: &[DVec3], source: u32, color: Rgb, tols: Tols) -> Planarized {
    let Some(plane) = Plane::newell(pts) else {
        return Planarized::Degenerate;
    };
    if is_thin(pts, tols.build) {
        return Planarized::Degenerate;
    }
    if max_distance(&plane, pts) <= tols.planar {
        return match kept(pts, plane, source, color, tols.build) {
            Some(p) => Planarized::Whole(p),
            None => Planarized::Degenerate,
        };
    }
    let tris: Vec<Vec<usize>> = triangulate(pts, plane.normal)
        .iter()
        .map(|t| t.to_vec())
        .collect();
    let pieces = if pts.len() <= MAX_EAR_VERTS {
        merge(pts, &tris, plane.normal, tols, usize::MAX)
    } else {
        tris
    };
    let polys: Vec<Polygon> = pieces
        .iter()
        .filter_map(|piece| {
            let vs: Vec<DVec3> = piece.iter().map(|&i| pts[i]).collect();
            if is_thin(&vs, tols.build) {
                // Zero-area triangles from collinear vertices cover nothing.
                return None;
            }
            let pl = Plane::newell(&vs)?;
            kept(&vs, pl, source, color, tols.build)
        })
        .collect();
    if polys.is_empty() {
        Planarized::Degenerate
    } else {
        Planarized::Split(polys)
    }
}

/// Whether the face is thinner than `tol`: `4·area ≤ tol·perimeter` (for a
/// triangle, about "its height on the longest side is at most `tol`").
fn is_thin(pts: &[DVec3], tol: f64) -> bool {
    let perimeter: f64 = pts
        .iter()
        .zip(pts.iter().cycle().skip(1))
        .map(|(a, b)| a.distance(*b))
        .sum();
    let a = geom::area(pts);
    !(a.is_finite() && perimeter.is_finite()) || 4.0 * a <= tol * perimeter
}

/// The largest distance of a vertex from `plane`.
fn max_distance(plane: &Plane, pts: &[DVec3]) -> f64 {
    pts.iter()
        .map(|&p| plane.distance(p).abs())
        .fold(0.0, f64::max)
}

/// The polygon of `pts` in `plane` (which passes within the planarity
/// tolerance of every point); points within `tol` of their predecessor are
/// dropped, and `None` is returned if fewer than three are left. Nothing is
/// moved onto the plane (see the module docs).
fn kept(pts: &[DVec3], plane: Plane, source: u32, color: Rgb, tol: f64) -> Option<Polygon> {
    let mut verts: Vec<DVec3> = Vec::with_capacity(pts.len());
    for &q in pts {
        if verts.last().is_none_or(|l| l.distance(q) > tol) {
            verts.push(q);
        }
    }
    while verts.len() > 1 && verts[0].distance(verts[verts.len() - 1]) <= tol {
        verts.pop();
    }
    (verts.len() >= 3).then_some(Polygon {
        verts,
        plane,
        source,
        color,
        // The file's normals are attached by the caller (`prepare`), by
        // position: every vertex here is one of the face's own.
        normals: None,
    })
}

/// Twice the signed area of the 2D triangle `a b c` (positive when
/// counter-clockwise).
fn cross2(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - b)
}

/// Triangles (indices into `pts`, counter-clockwise about `normal`) covering
/// the projection of the loop onto the plane with `normal`.
///
/// Ear clipping: a vertex is an ear when it turns left and no other vertex of
/// the remaining loop lies in its triangle. When no ear is found (the
/// projection of a warped face may cross itself), the vertex turning most to
/// the left is clipped anyway, so this always ends.
pub fn triangulate(pts: &[DVec3], normal: DVec3) -> Vec<[usize; 3]> {
    let n = pts.len();
    if n < 3 {
        return Vec::new();
    }
    if n > MAX_EAR_VERTS {
        return (1..n - 1).map(|i| [0, i, i + 1]).collect();
    }
    // A right-handed frame (u, v, normal): counter-clockwise in 2D is
    // counter-clockwise about the normal.
    let u = normal.any_orthonormal_vector();
    let v = normal.cross(u);
    let c = geom::centroid(pts);
    let p2: Vec<DVec2> = pts
        .iter()
        .map(|&p| DVec2::new((p - c).dot(u), (p - c).dot(v)))
        .collect();
    let mut idx: Vec<usize> = (0..n).collect();
    let mut tris = Vec::with_capacity(n - 2);
    while idx.len() > 3 {
        let m = idx.len();
        let corner = |i: usize| (idx[(i + m - 1) % m], idx[i], idx[(i + 1) % m]);
        let ear = (0..m).find(|&i| {
            let (a, b, c) = corner(i);
            is_ear(&p2, &idx, a, b, c)
        });
        let ear = ear.unwrap_or_else(|| {
            (0..m)
                .max_by(|&i, &j| {
                    let (a, b, c) = corner(i);
                    let (d, e, f) = corner(j);
                    cross2(p2[a], p2[b], p2[c]).total_cmp(&cross2(p2[d], p2[e], p2[f]))
                })
                .unwrap_or(0)
        });
        let (a, b, c) = corner(ear);
        tris.push([a, b, c]);
        idx.remove(ear);
    }
    tris.push([idx[0], idx[1], idx[2]]);
    tris
}

/// Whether corner `a b c` is convex and holds no other vertex of the loop.
fn is_ear(p2: &[DVec2], idx: &[usize], a: usize, b: usize, c: usize) -> bool {
    let (pa, pb, pc) = (p2[a], p2[b], p2[c]);
    if cross2(pa, pb, pc) <= 0.0 {
        return false;
    }
    !idx.iter().any(|&j| {
        let q = p2[j];
        j != a
            && j != b
            && j != c
            && q != pa
            && q != pb
            && q != pc
            && cross2(pa, pb, q) >= 0.0
            && cross2(pb, pc, q) >= 0.0
            && cross2(pc, pa, q) >= 0.0
    })
}

/// Greedily merges adjacent loops (triangles of one face here, the faces
/// of a coplanar region in `super::coplanar`) into larger pieces while the
/// union is planar within `tols.planar`, convex and has at most
/// `max_verts` vertices. Loops index `pts`; two loops are adjacent when one
/// has the edge `a→b` and the other `b→a`, and an edge is taken for at most
/// one loop in each direction. Returns the pieces as loops of indices into
/// `pts`, every vertex kept (a merge drops only the shared edge).
pub(crate) fn merge(
    pts: &[DVec3],
    loops: &[Vec<usize>],
    normal: DVec3,
    tols: Tols,
    max_verts: usize,
) -> Vec<Vec<usize>> {
    let mut pieces: Vec<Option<Vec<usize>>> = loops.iter().cloned().map(Some).collect();
    let mut parent: Vec<usize> = (0..loops.len()).collect();
    let mut edge_tri: HashMap<(usize, usize), usize> = HashMap::new();
    for (t, l) in loops.iter().enumerate() {
        for e in loop_edges(l) {
            edge_tri.insert(e, t);
        }
    }
    // Shared edges in loop order, so the result does not depend on the
    // hash map's iteration order.
    let diagonals: Vec<(usize, usize)> = loops
        .iter()
        .flat_map(|l| loop_edges(l))
        .filter(|&(a, b)| a < b && edge_tri.contains_key(&(b, a)))
        .collect();
    for (a, b) in diagonals {
        let (Some(&ta), Some(&tb)) = (edge_tri.get(&(a, b)), edge_tri.get(&(b, a))) else {
            continue;
        };
        let (p, q) = (find(&mut parent, ta), find(&mut parent, tb));
        if p == q {
            continue;
        }
        let (Some(lp), Some(lq)) = (pieces[p].as_ref(), pieces[q].as_ref()) else {
            continue;
        };
        let Some(merged) = splice(lp, lq, a, b) else {
            continue;
        };
        if merged.len() <= max_verts && planar_and_convex(pts, &merged, normal, tols) {
            pieces[p] = Some(merged);
            pieces[q] = None;
            parent[q] = p;
        }
    }
    pieces.into_iter().flatten().collect()
}

/// The root of `x`'s set in the union-find forest `parent` (halving the
/// path on the way).
pub(crate) fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// The directed edges of a loop, edge `k` from vertex `k` to `k + 1`.
pub(crate) fn loop_edges(l: &[usize]) -> impl Iterator<Item = (usize, usize)> + '_ {
    (0..l.len()).map(move |k| (l[k], l[(k + 1) % l.len()]))
}

/// Joins loop `p` (which has the edge `a→b`) and loop `q` (which has `b→a`)
/// across that edge. `None` if the edge is not where expected or the result
/// would visit a vertex twice.
fn splice(p: &[usize], q: &[usize], a: usize, b: usize) -> Option<Vec<usize>> {
    let pb = (0..p.len()).find(|&i| p[i] == b && p[(i + p.len() - 1) % p.len()] == a)?;
    let qa = (0..q.len()).find(|&i| q[i] == a && q[(i + q.len() - 1) % q.len()] == b)?;
    // p from b round to a, then q's vertices strictly between a and b.
    let mut out: Vec<usize> = (0..p.len()).map(|k| p[(pb + k) % p.len()]).collect();
    out.extend((1..q.len() - 1).map(|k| q[(qa + k) % q.len()]));
    let mut seen = out.clone();
    seen.sort_unstable();
    seen.dedup();
    (seen.len() == out.len()).then_some(out)
}

/// Whether the loop is planar within `tols.planar` and convex (collinear
/// vertices allowed), facing the same way as `normal`.
fn planar_and_convex(pts: &[DVec3], lp: &[usize], normal: DVec3, tols: Tols) -> bool {
    let vs: Vec<DVec3> = lp.iter().map(|&i| pts[i]).collect();
    let Some(plane) = Plane::newell(&vs) else {
        return false;
    };
    if plane.normal.dot(normal) <= 0.0 || max_distance(&plane, &vs) > tols.planar {
        return false;
    }
    let n = vs.len();
    (0..n).all(|i| {
        let (x, y, z) = (vs[i], vs[(i + 1) % n], vs[(i + 2) % n]);
        let len = x.distance(y);
        // Signed distance of z from the line x→y, positive on the left.
        len > 0.0 && (y - x).cross(z - y).dot(plane.normal) / len >= -tols.build
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOLS: Tols = Tols {
        planar: 5e-8,
        build: 1e-7,
    };

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    fn total_area(polys: &[Polygon]) -> f64 {
        polys.iter().map(|p| geom::area(&p.verts)).sum()
    }

    #[test]
    fn planar_concave_face_stays_whole() {
        // An L-shaped hexagon.
        let l = [
            v(0., 0., 0.),
            v(2., 0., 0.),
            v(2., 1., 0.),
            v(1., 1., 0.),
            v(1., 2., 0.),
            v(0., 2., 0.),
        ];
        match planarize(&l, 7, [1, 2, 3], TOLS) {
            Planarized::Whole(p) => {
                assert_eq!(p.verts.len(), 6);
                assert_eq!(p.source, 7);
                assert_eq!(p.color, [1, 2, 3]);
                assert!((p.plane.normal - DVec3::Z).length() < 1e-12);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn faces_keep_their_vertices() {
        // Noise within the planarity tolerance: whole, nothing moved.
        let q = [
            v(0., 0., 0.),
            v(1., 0., 3e-8),
            v(1., 1., 0.),
            v(0., 1., -2e-8),
        ];
        let Planarized::Whole(p) = planarize(&q, 0, [0; 3], TOLS) else {
            panic!("split");
        };
        assert_eq!(p.verts, q.to_vec());
        for &x in &p.verts {
            assert!(p.plane.distance(x).abs() <= TOLS.planar);
        }
        // Above it: cut between its own vertices, none moved.
        let q = [
            v(0., 0., 0.),
            v(1., 0., 3e-6),
            v(1., 1., 0.),
            v(0., 1., -2e-6),
        ];
        let Planarized::Split(pieces) = planarize(&q, 0, [0; 3], TOLS) else {
            panic!("whole");
        };
        for p in &pieces {
            for x in &p.verts {
                assert!(q.contains(x), "{x} moved");
                assert!(p.plane.distance(*x).abs() <= TOLS.planar);
            }
        }
    }

    #[test]
    fn warped_quad_splits_keeping_source_and_area() {
        let q = [v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.1), v(0., 1., 0.)];
        let Planarized::Split(pieces) = planarize(&q, 42, [9, 9, 9], TOLS) else {
            panic!("not split");
        };
        assert_eq!(pieces.len(), 2);
        assert!(pieces
            .iter()
            .all(|p| p.source == 42 && p.color == [9, 9, 9]));
        assert!(
            pieces.iter().all(|p| p.plane.normal.z > 0.9),
            "winding kept"
        );
        // The two triangles of the diagonal chosen, in 3D.
        let tri = |a: DVec3, b: DVec3, c: DVec3| 0.5 * (b - a).cross(c - a).length();
        let d02 = tri(q[0], q[1], q[2]) + tri(q[0], q[2], q[3]);
        let d13 = tri(q[0], q[1], q[3]) + tri(q[1], q[2], q[3]);
        let a = total_area(&pieces);
        assert!(
            (a - d02).abs() < 1e-12 || (a - d13).abs() < 1e-12,
            "{a} vs {d02} / {d13}"
        );
    }

    #[test]
    fn warped_ngon_merges_back_into_few_convex_pieces() {
        // A regular 12-gon in z = 0 with one vertex lifted: the rest is
        // planar and convex, so merging should leave only a few pieces.
        let mut g: Vec<DVec3> = (0..12)
            .map(|i| {
                let t = i as f64 * std::f64::consts::TAU / 12.0;
                v(t.cos(), t.sin(), 0.0)
            })
            .collect();
        g[5].z = 0.2;
        let flat_area = geom::area(&g.iter().map(|p| v(p.x, p.y, 0.0)).collect::<Vec<_>>());
        let Planarized::Split(pieces) = planarize(&g, 3, [0; 3], TOLS) else {
            panic!("not split");
        };
        assert!(pieces.len() <= 4, "{} pieces", pieces.len());
        assert!(pieces.iter().all(|p| p.source == 3));
        let a = total_area(&pieces);
        assert!(
            a >= flat_area - 1e-12 && a < flat_area * 1.05,
            "{a} vs {flat_area}"
        );
        for p in &pieces {
            for &x in &p.verts {
                assert!(p.plane.distance(x).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn warped_concave_face_triangulates_inside_the_outline() {
        // An L-shape with its inner corner pushed up: the ear clipper must
        // not produce a triangle across the notch.
        let l = [
            v(0., 0., 0.),
            v(2., 0., 0.),
            v(2., 1., 0.),
            v(1., 1., 0.3),
            v(1., 2., 0.),
            v(0., 2., 0.),
        ];
        let Planarized::Split(pieces) = planarize(&l, 0, [0; 3], TOLS) else {
            panic!("not split");
        };
        // The projection onto z = 0 has area 3: a triangle across the notch
        // would cover more.
        let projected: f64 = pieces
            .iter()
            .map(|p| geom::area(&p.verts.iter().map(|q| v(q.x, q.y, 0.)).collect::<Vec<_>>()))
            .sum();
        assert!((projected - 3.0).abs() < 1e-9, "{projected}");
    }

    #[test]
    fn thin_and_collinear_faces_are_degenerate() {
        let line = [v(0., 0., 0.), v(1., 0., 0.), v(2., 0., 0.)];
        assert!(matches!(
            planarize(&line, 0, [0; 3], TOLS),
            Planarized::Degenerate
        ));
        let thin = [v(0., 0., 0.), v(1., 0., 0.), v(0.5, 1e-8, 0.)];
        assert!(matches!(
            planarize(&thin, 0, [0; 3], TOLS),
            Planarized::Degenerate
        ));
    }

    #[test]
    fn collinear_vertices_in_a_planar_face_are_kept() {
        let sq = [
            v(0., 0., 0.),
            v(0.5, 0., 0.),
            v(1., 0., 0.),
            v(1., 1., 0.),
            v(0., 1., 0.),
        ];
        let Planarized::Whole(p) = planarize(&sq, 0, [0; 3], TOLS) else {
            panic!()
        };
        assert_eq!(p.verts.len(), 5);
    }

    #[test]
    fn huge_warped_face_is_fanned_quickly() {
        let n = 5000;
        let ring: Vec<DVec3> = (0..n)
            .map(|i| {
                let t = i as f64 * std::f64::consts::TAU / n as f64;
                v(t.cos(), t.sin(), 0.1 * (7.0 * t).sin())
            })
            .collect();
        let Planarized::Split(pieces) = planarize(&ring, 0, [0; 3], TOLS) else {
            panic!("not split");
        };
        assert_eq!(pieces.len(), n - 2);
    }

    #[test]
    fn splice_joins_two_triangles() {
        assert_eq!(splice(&[0, 1, 2], &[0, 2, 3], 2, 0), Some(vec![0, 1, 2, 3]));
        assert_eq!(splice(&[0, 1, 2], &[0, 2, 3], 0, 2), None);
    }
}
