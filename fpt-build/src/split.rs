//! Splitting a planar polygon, convex or concave, by a plane.
//!
//! Contract: [`split`] takes a simple planar polygon that the plane cuts
//! (some vertex beyond the tolerance on each side) and returns the simply
//! connected pieces on each side. The pieces tile the polygon: their areas
//! add up to its area, and they do not overlap. Every piece keeps the parent's
//! plane, source face and colour, so pieces of one face stay exactly coplanar.
//!
//! Vertices within the tolerance of the cutting plane are "on" it (the very
//! test the builder classifies with): the cut passes through them, so that
//! no piece is thinner than the tolerance (no slivers, no zero-area
//! fragments). They keep their position, and a crossing of an edge is the
//! point interpolated on that edge. Nothing moves a vertex, because moving
//! one would break the tiling: snapping an "on" vertex onto the line where
//! the two planes meet, within the polygon's plane, moves it by
//! `distance / sin(angle between the planes)`, which grows without bound as
//! the planes become parallel (1.7e-3, ten thousand tolerances, on a
//! curved face of `fandisk.obj`) and leaves the vertex on none of the
//! polygon's edges, so the pieces no longer cover the polygon and the
//! neighbouring face, which keeps the vertex, shows a pinhole between them.
//! Unmoved, a piece's vertices are source vertices, points on its parent's
//! edges or points on a cut (each within the tolerance of its plane, all
//! that classification needs), and a neighbouring face cut by the same
//! plane gets the very same crossing on their shared edge.
//!
//! How: a concave polygon may cross the cutting line many times. The
//! crossings, sorted along the line, pair up into the segments of the line
//! that lie inside the polygon (Jordan). A piece is traced along the boundary
//! on its side; where the boundary leaves that side, the piece follows the
//! inside segment to its other end and goes on from there. Vertices on the
//! plane are resolved by symbolic perturbation (see `sides`): each counts
//! as lying on one side (as if the plane were moved by an infinitesimal δ),
//! which makes every crossing transversal; coinciding crossings are ordered
//! by where they would move under that δ. Fragments of zero area that the
//! perturbation creates are dropped.

use crate::geom::{PointSide, Polygon, Tolerance};
use glam::DVec3;

/// The pieces of a split: those in front of the plane and those behind it.
#[derive(Clone, Debug, Default)]
pub struct Pieces {
    /// Pieces on the front side.
    pub front: Vec<Polygon>,
    /// Pieces on the back side.
    pub back: Vec<Polygon>,
}

/// One point of the boundary after crossings are inserted.
#[derive(Clone, Copy, Debug)]
struct Node {
    pos: DVec3,
    /// `true` for an original vertex on the front side, `false` for an
    /// original vertex behind (or on) the plane; crossings are neither.
    front: bool,
    /// An original vertex beyond the tolerance from the plane (crossings
    /// and vertices on the plane are not).
    off: bool,
    /// For a crossing: index into the crossing list.
    crossing: Option<usize>,
}

/// A crossing of the boundary with the cutting line.
#[derive(Clone, Copy, Debug)]
struct Crossing {
    /// Position along the line.
    t: f64,
    /// Where it would move along the line as the plane moves forward by δ.
    dt: f64,
    /// Index of the crossing node in the boundary.
    node: usize,
    /// The boundary goes from front to back here.
    leaving_front: bool,
}

/// Splits `poly` by `plane` (given as a polygon-independent [`crate::geom::Plane`]).
///
/// A polygon that the plane does not cut comes back whole on its side
/// (coplanar polygons go to the front).
pub fn split(poly: &Polygon, plane: &crate::geom::Plane, tol: Tolerance) -> Pieces {
    let n = poly.verts.len();
    let mut dist: Vec<f64> = Vec::with_capacity(n);
    let mut verts: Vec<DVec3> = Vec::with_capacity(n);
    let (mut any_front, mut any_back) = (false, false);
    for &v in &poly.verts {
        let d = plane.distance(v);
        verts.push(v);
        // A vertex within the tolerance is on the plane: distance 0 makes
        // the cut pass through it, where it is (see the module docs).
        dist.push(match plane.side_of(v, tol) {
            PointSide::Front => {
                any_front = true;
                d
            }
            PointSide::Back => {
                any_back = true;
                d
            }
            PointSide::On => 0.0,
        });
    }
    if !any_back {
        return Pieces {
            front: vec![poly.clone()],
            back: vec![],
        };
    }
    if !any_front {
        return Pieces {
            front: vec![],
            back: vec![poly.clone()],
        };
    }
    // Direction of the cutting line within the polygon's plane.
    let dir = poly.plane.normal.cross(plane.normal).normalize_or_zero();
    let front = {
        let b = Boundary::new(&verts, &dist, &sides(&dist, true), false, dir);
        b.trace(true, poly, tol)
    };
    let back = {
        let b = Boundary::new(&verts, &dist, &sides(&dist, false), true, dir);
        b.trace(false, poly, tol)
    };
    Pieces { front, back }
}

/// Which vertices count as front when the pieces on one side are traced
/// (`front_trace`), given the distances with the "on" vertices at 0.
///
/// A run of on vertices where the boundary only touches the plane (a front
/// or a back vertex on both ends) counts as the other side: moving the
/// plane by an infinitesimal δ that way, the traced side never touches
/// itself there (front pieces see the plane moved forward, back pieces
/// moved back). A run where the boundary goes through (a front vertex on
/// one end, a back vertex on the other) counts as front for both traces:
/// its vertices keep their positions, so they are not collinear, and the
/// two sides must cut it at the same vertex (the one next to the back
/// vertex), or the wedge between their two cuts would belong to neither.
fn sides(dist: &[f64], front_trace: bool) -> Vec<bool> {
    let n = dist.len();
    let mut out: Vec<bool> = dist.iter().map(|&d| d > 0.0).collect();
    // Start right after a vertex off the plane, so that every run of on
    // vertices is met whole.
    let Some(start) = dist.iter().position(|&d| d != 0.0) else {
        return out;
    };
    let mut k = 1;
    while k <= n {
        let i = (start + k) % n;
        if dist[i] != 0.0 {
            k += 1;
            continue;
        }
        let before = dist[(start + k - 1) % n] > 0.0;
        let mut len = 0;
        while dist[(start + k + len) % n] == 0.0 {
            len += 1;
        }
        let after = dist[(start + k + len) % n] > 0.0;
        let front = if before == after { !front_trace } else { true };
        for m in 0..len {
            out[(start + k + m) % n] = front;
        }
        k += len;
    }
    out
}

/// The boundary with its crossings inserted and paired, for one perturbation.
struct Boundary {
    nodes: Vec<Node>,
    crossings: Vec<Crossing>,
    partner: Vec<usize>,
}

impl Boundary {
    /// `front[i]`: whether vertex `i` counts as front (see [`sides`]);
    /// `on_front`: the direction of the perturbation where a crossing has
    /// no vertex on the plane (the plane moved back by δ, or forward).
    fn new(verts: &[DVec3], dist: &[f64], front: &[bool], on_front: bool, dir: DVec3) -> Boundary {
        let n = verts.len();
        let mut nodes: Vec<Node> = Vec::with_capacity(n + 8);
        let mut crossings: Vec<Crossing> = Vec::new();
        for i in 0..n {
            let j = (i + 1) % n;
            let (a, b) = (verts[i], verts[j]);
            let (da, db) = (dist[i], dist[j]);
            let (fa, fb) = (front[i], front[j]);
            nodes.push(Node {
                pos: a,
                front: fa,
                off: da != 0.0,
                crossing: None,
            });
            if fa != fb {
                // f: the front end, g: the back end.
                let (f, df, g, dg) = if fa { (a, da, b, db) } else { (b, db, a, da) };
                // Where an end is on the plane, the way it was perturbed.
                let (front_g, front_f) = if fa { (fb, fa) } else { (fa, fb) };
                let (pos, moved_back) = if dg == 0.0 {
                    (g, front_g)
                } else if df == 0.0 {
                    (f, front_f)
                } else {
                    (
                        // Interpolated from the front end: a point of the
                        // edge, the same for both faces that share it.
                        f + (g - f) * (df / (df - dg)),
                        on_front,
                    )
                };

                // The crossing of the plane at d = ±δ lies at
                // f + (df ∓ δ)/(df − dg)·(g − f): its motion along the line.
                let motion = (g - f).dot(dir) / (df - dg);
                crossings.push(Crossing {
                    t: pos.dot(dir),
                    dt: if moved_back { motion } else { -motion },
                    node: nodes.len(),
                    leaving_front: fa,
                });
                nodes.push(Node {
                    pos,
                    front: false,
                    off: false,
                    crossing: Some(crossings.len() - 1),
                });
            }
        }
        // Sort along the line; pairs (0,1), (2,3), ... are the inside segments.
        let mut order: Vec<usize> = (0..crossings.len()).collect();
        order.sort_by(|&x, &y| {
            let (cx, cy) = (&crossings[x], &crossings[y]);
            cx.t.total_cmp(&cy.t).then(cx.dt.total_cmp(&cy.dt))
        });
        let mut partner = vec![usize::MAX; crossings.len()];
        for pair in order.chunks(2) {
            if let [a, b] = *pair {
                partner[a] = b;
                partner[b] = a;
            }
        }
        Boundary {
            nodes,
            crossings,
            partner,
        }
    }

    /// Traces the pieces on one side (`front`), see the module docs.
    fn trace(&self, front: bool, parent: &Polygon, tol: Tolerance) -> Vec<Polygon> {
        let (nodes, crossings, partner) = (&self.nodes, &self.crossings, &self.partner);
        let m = nodes.len();
        let mut used = vec![false; m];
        let mut pieces = Vec::new();
        // A side's pieces start at its original vertices (including those on
        // the plane that count as that side).
        for start in 0..m {
            if used[start] || nodes[start].crossing.is_some() || nodes[start].front != front {
                continue;
            }
            let mut verts: Vec<DVec3> = Vec::new();
            let mut off = false;
            let mut i = start;
            // Each step either moves along the boundary or jumps across an inside
            // segment; 2m steps bound any trace of a well-formed boundary.
            for _ in 0..2 * m + 2 {
                used[i] = true;
                verts.push(nodes[i].pos);
                off |= nodes[i].off;
                if let Some(c) = nodes[i].crossing {
                    // Leaving this side here? Then jump to the segment's other end.
                    if crossings[c].leaving_front == front {
                        let Some(&other) = partner.get(c) else { break };
                        let Some(oc) = crossings.get(other) else {
                            break;
                        };
                        i = oc.node;
                        used[i] = true;
                        verts.push(nodes[i].pos);
                    }
                }
                i = (i + 1) % m;
                if i == start {
                    break;
                }
            }
            if let Some(p) = finish_piece(verts, off, parent, tol) {
                pieces.push(p);
            }
        }
        pieces
    }
}

/// Removes repeated points and collinear spikes; drops zero-area fragments.
/// `off`: the piece has a vertex beyond the tolerance from the plane.
fn finish_piece(
    mut verts: Vec<DVec3>,
    off: bool,
    parent: &Polygon,
    tol: Tolerance,
) -> Option<Polygon> {
    verts.dedup();
    while verts.len() > 1 && verts.first() == verts.last() {
        verts.pop();
    }
    if verts.len() < 3 {
        return None;
    }
    // A piece narrower than the tolerance is a sliver of rounding noise.
    // Not one with a vertex beyond the tolerance from the cut and three
    // sides longer than the tolerance, however small its area: the seam
    // repair's weld (the same distance) cannot collapse it, and its
    // neighbours keep those sides (the face across its source edge keeps
    // the vertex and the crossings around it), so dropping it left a hole.
    // In `shuttle.obj`'s BSP tree: a vertex 1.12 tolerances in front of a
    // cut, a triangle of 0.92 tolerance² with sides of 1.3 to 1.6
    // tolerances, three open edges. (A needle whose base is shorter than
    // the tolerance still goes: the weld would make it a segment.)
    let n = verts.len();
    let long = (0..n)
        .filter(|&k| (verts[(k + 1) % n] - verts[k]).length() > tol.0)
        .count();
    let real = off && long >= 3;
    if !real && crate::geom::area(&verts) <= tol.0 * tol.0 {
        return None;
    }
    Some(Polygon {
        normals: parent.normals_at(&verts),
        verts,
        plane: parent.plane,
        source: parent.source,
        color: parent.color,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{area, Plane, Relation};
    use proptest::prelude::*;

    fn poly(pts: &[(f64, f64)]) -> Polygon {
        let verts = pts.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect();
        Polygon::new(verts, 7, [1, 2, 3]).unwrap()
    }

    fn vertical(x: f64) -> Plane {
        Plane {
            normal: DVec3::X,
            d: -x,
        }
    }

    const TOL: Tolerance = Tolerance(1e-9);

    fn total(ps: &[Polygon]) -> f64 {
        ps.iter().map(|p| area(&p.verts)).sum()
    }

    #[test]
    fn a_tip_just_beyond_the_tolerance_is_kept_however_small() {
        // A spike whose tip is 1.2 tolerances in front of the cut: the
        // front piece is a triangle of 0.72 tolerance², but its sides (1.2
        // and 1.34 tolerances) are longer than the tolerance, so the seam
        // repair cannot weld it away and the face across the spike's edges
        // keeps the tip. Dropped, it was a hole (shuttle.obj's BSP tree,
        // three open edges).
        let tip = 0.5 + 1.2 * TOL.0;
        let spike = poly(&[(0.0, 0.25), (tip, 0.5), (0.0, 0.75)]);
        let p = split(&spike, &vertical(0.5), TOL);
        assert_eq!((p.front.len(), p.back.len()), (1, 1));
        assert!(p.front[0].verts.contains(&DVec3::new(tip, 0.5, 0.0)));
        // The tip's triangle: height 1.2 tolerances, base as long.
        let want = 0.5 * (1.2 * TOL.0).powi(2);
        let got = area(&p.front[0].verts);
        assert!((got - want).abs() < 1e-3 * want, "{got:e} {want:e}");
        // A needle, its base shorter than the tolerance, is still dropped:
        // the weld would make it a segment.
        let needle = poly(&[(0.0, 0.4), (tip, 0.5), (0.0, 0.6)]);
        let p = split(&needle, &vertical(0.5), TOL);
        assert_eq!((p.front.len(), p.back.len()), (0, 1));
    }

    #[test]
    fn square_splits_in_two() {
        let sq = poly(&[(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (0.0, 1.0)]);
        let p = split(&sq, &vertical(0.5), TOL);
        assert_eq!((p.front.len(), p.back.len()), (1, 1));
        assert!((area(&p.front[0].verts) - 1.5).abs() < 1e-12);
        assert!((area(&p.back[0].verts) - 0.5).abs() < 1e-12);
        assert_eq!(p.front[0].source, 7);
        assert_eq!(p.front[0].plane, sq.plane);
    }

    #[test]
    fn comb_splits_into_several_pieces() {
        // A comb with three teeth pointing right; a cut through the teeth
        // leaves three pieces in front and one behind.
        let comb = poly(&[
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (3.0, 2.0),
            (3.0, 3.0),
            (1.0, 3.0),
            (1.0, 4.0),
            (3.0, 4.0),
            (3.0, 5.0),
            (0.0, 5.0),
        ]);
        let p = split(&comb, &vertical(2.0), TOL);
        assert_eq!(p.front.len(), 3);
        assert_eq!(p.back.len(), 1);
        let a = area(&comb.verts);
        assert!((total(&p.front) + total(&p.back) - a).abs() < 1e-9);
        assert!((total(&p.front) - 3.0).abs() < 1e-9);
    }

    #[test]
    fn vertex_on_plane_gives_no_sliver() {
        // Diamond touching the plane with its right vertex within tolerance:
        // not cut at all.
        let d = poly(&[(0.0, 0.0), (1.0, -1.0), (2.0 - 1e-12, 0.0), (1.0, 1.0)]);
        assert_eq!(vertical(2.0).relation(&d.verts, TOL), Relation::Back);
        // Cut through two vertices exactly: two triangles, nothing else.
        let p = split(&d, &vertical(1.0), TOL);
        assert_eq!((p.front.len(), p.back.len()), (1, 1));
        assert_eq!(p.front[0].verts.len(), 3);
        assert_eq!(p.back[0].verts.len(), 3);
    }

    #[test]
    fn concave_vertex_touching_line_from_front() {
        // A "W" bottom whose middle notch vertex lies exactly on the cut.
        let w = poly(&[
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 1.0),
            (3.0, 0.0),
            (4.0, 0.0),
            (4.0, 3.0),
            (0.0, 3.0),
        ]);
        let cut = Plane {
            normal: DVec3::Y,
            d: -1.0,
        };
        let p = split(&w, &cut, TOL);
        assert_eq!(p.front.len(), 1);
        assert_eq!(p.back.len(), 2);
        assert!((total(&p.front) + total(&p.back) - area(&w.verts)).abs() < 1e-9);
    }

    /// Distance from `p` to the segment `a b`.
    fn seg_distance(a: DVec3, b: DVec3, p: DVec3) -> f64 {
        let ab = b - a;
        let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
        (a + ab * t - p).length()
    }

    /// Whether `p` is within `eps` of an edge of `poly`, or inside it on
    /// the line where `plane` meets the polygon's plane: the only places a
    /// piece vertex may come from. (On the line but outside the parent is
    /// not enough: moving a vertex along the cut can keep the area.)
    fn from_parent_or_cut(poly: &Polygon, plane: &Plane, p: DVec3, eps: f64) -> bool {
        let n = poly.verts.len();
        let on_edge =
            (0..n).any(|i| seg_distance(poly.verts[i], poly.verts[(i + 1) % n], p) <= eps);
        let on_cut = plane.distance(p).abs() <= 1e-12 && poly.plane.distance(p).abs() <= 1e-12;
        on_edge || (on_cut && contains(&poly.verts, p))
    }

    #[test]
    fn nearly_parallel_cut_keeps_on_vertices_in_place() {
        // Fandisk face 2893: a cutting plane 8e-5 rad from the triangle's
        // own plane passes within the tolerance of one vertex. Snapping
        // that vertex onto the line where the two planes meet moved it
        // d / sin(angle) = 1e-3 along the triangle's plane, off every edge,
        // and left part of the triangle uncovered next to its neighbour.
        let tri = poly(&[(0.0, 0.0), (1.0, 0.0), (0.3, 1.0)]);
        let tol = Tolerance(1e-7);
        let angle: f64 = 8e-5;
        // Plane tilted by `angle` about a line parallel to y, shifted so that
        // the apex (0.3, 1) is 0.8·tol in front of it (on, within the
        // tolerance), (1, 0) in front and (0, 0) behind.
        let normal = DVec3::new(angle.sin(), 0.0, angle.cos());
        let apex = DVec3::new(0.3, 1.0, 0.0);
        let plane = Plane {
            normal,
            d: 0.8 * tol.0 - normal.dot(apex),
        };
        assert_eq!(plane.side_of(apex, tol), PointSide::On);
        assert_eq!(plane.relation(&tri.verts, tol), Relation::Cut);
        let pieces = split(&tri, &plane, tol);
        let all: Vec<&Polygon> = pieces.front.iter().chain(&pieces.back).collect();
        assert!(!pieces.front.is_empty() && !pieces.back.is_empty());
        for p in &all {
            for &v in &p.verts {
                assert!(
                    from_parent_or_cut(&tri, &plane, v, tol.0),
                    "piece vertex {v} is on no edge of the parent nor on the cut"
                );
            }
        }
        let sum: f64 = all.iter().map(|p| area(&p.verts)).sum();
        assert!(
            (sum - area(&tri.verts)).abs() < 1e-9,
            "{sum} vs {}",
            area(&tri.verts)
        );
    }

    #[test]
    fn run_of_on_vertices_is_cut_at_one_vertex_by_both_sides() {
        // A quad whose two top vertices are both within the tolerance of a
        // nearly parallel cut, on either side of it and not collinear with
        // the crossing on the left edge. The front side used to cut the run
        // at its first vertex and the back side at its last, so the wedge
        // between the two cuts belonged to neither.
        let q = poly(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.9, 1.0)]);
        let tol = Tolerance(1e-7);
        // Distance 1e-6·x − 4.5e-7·y − 5e-7 (a plane 1e-6 rad from the
        // quad's): (1, 1) at +0.5·tol and (0.9, 1) at −0.5·tol are on,
        // (1, 0) is in front, (0, 0) behind; the cut crosses the bottom
        // edge at x = 0.5.
        let (a, b, c) = (1e-6, -4.5e-7, -5e-7);
        let len = DVec3::new(a, b, 1.0).length();
        let plane = Plane {
            normal: DVec3::new(a, b, 1.0) / len,
            d: c / len,
        };
        for (x, y) in [(1.0, 1.0), (0.9, 1.0)] {
            assert_eq!(plane.side_of(DVec3::new(x, y, 0.0), tol), PointSide::On);
        }
        let pieces = split(&q, &plane, tol);
        assert!(!pieces.front.is_empty() && !pieces.back.is_empty());
        let all: Vec<&Polygon> = pieces.front.iter().chain(&pieces.back).collect();
        let sum: f64 = all.iter().map(|p| area(&p.verts)).sum();
        let want = area(&q.verts);
        assert!((sum - want).abs() < 1e-12, "pieces cover {sum} of {want}");
        for p in &all {
            for &v in &p.verts {
                assert!(from_parent_or_cut(&q, &plane, v, tol.0), "{v}");
            }
        }
    }

    /// A random star-shaped (so simple, often concave) polygon.
    fn star(radii: &[f64], phase: f64) -> Polygon {
        let n = radii.len();
        let pts: Vec<(f64, f64)> = radii
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let a = phase + i as f64 * std::f64::consts::TAU / n as f64;
                (r * a.cos(), r * a.sin())
            })
            .collect();
        poly(&pts)
    }

    proptest! {
        #[test]
        fn pieces_on_correct_side_and_area_preserved(
            radii in prop::collection::vec(0.2f64..1.0, 3..16),
            phase in 0.0f64..1.0,
            angle in 0.0f64..std::f64::consts::TAU,
            offset in -0.5f64..0.5,
            tilt in -0.9f64..0.9,
        ) {
            let pg = star(&radii, phase);
            let n = DVec3::new(angle.cos(), angle.sin(), tilt).normalize();
            let plane = Plane { normal: n, d: offset };
            let tol = Tolerance(1e-7);
            let pieces = split(&pg, &plane, tol);
            for f in &pieces.front {
                prop_assert!(matches!(plane.relation(&f.verts, tol), Relation::Front | Relation::Coplanar));
                prop_assert!(f.verts.iter().all(|&v| pg.plane.distance(v).abs() < 1e-9));
            }
            for b in &pieces.back {
                prop_assert!(matches!(plane.relation(&b.verts, tol), Relation::Back | Relation::Coplanar));
            }
            let before = area(&pg.verts);
            let after = total(&pieces.front) + total(&pieces.back);
            prop_assert!((before - after).abs() < 1e-9 * before.max(1.0), "{before} vs {after}");
            // No overlaps and nothing lost: sample points in the plane and
            // check that each point inside the parent lies in exactly one piece.
            for k in 0..200 {
                let x = -1.0 + 2.0 * ((k * 37 % 200) as f64 + 0.5) / 200.0;
                let y = -1.0 + 2.0 * ((k * 91 % 200) as f64 + 0.5) / 200.0;
                let p = DVec3::new(x, y, 0.0);
                let inside = contains(&pg.verts, p);
                let count = pieces.front.iter().chain(&pieces.back).filter(|q| contains(&q.verts, p)).count();
                if on_any_edge(&pieces, p) { continue; }
                prop_assert_eq!(count, usize::from(inside));
            }
        }
    }

    fn contains(verts: &[DVec3], p: DVec3) -> bool {
        let mut inside = false;
        let n = verts.len();
        for i in 0..n {
            let (a, b) = (verts[i], verts[(i + 1) % n]);
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if p.x < x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    fn on_any_edge(pieces: &Pieces, p: DVec3) -> bool {
        pieces.front.iter().chain(&pieces.back).any(|q| {
            let n = q.verts.len();
            (0..n).any(|i| {
                let (a, b) = (q.verts[i], q.verts[(i + 1) % n]);
                let ab = b - a;
                let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
                (a + ab * t - p).length() < 1e-6
            })
        })
    }
}
