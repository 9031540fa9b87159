//! The tiling contract of a built tree: the pieces of every source polygon
//! tile exactly that polygon, and the seams between faces conform.
//!
//! A builder may cut a face, weld copies of a vertex and insert a
//! neighbour's vertex into an edge (a T-junction), but each of those keeps
//! every vertex where it was or puts it on an edge or on a cut, within the
//! tolerance. A vertex moved anywhere else uncovers part of the face, and
//! the neighbouring face, which kept the vertex, shows background through
//! the gap. [`check_tiling`] tests, per source face:
//!
//! * **inside**: every piece vertex lies within `eps` of the face (of one
//!   of its input polygons: a non-planar face comes in as several), in its
//!   plane and inside its outline or on it;
//! * **area**: the pieces' areas add up to the face's, within `eps` times
//!   its perimeter (the area a boundary moved by `eps` sweeps);
//!
//! which together leave no room for a gap (a gap would need an overlap of
//! the same area elsewhere, or a vertex outside). Moving a vertex along a
//! cut can keep the area (a shear), which the inside test catches.
//!
//! [`open_edges`] tests conformity: in a closed model, every edge of an
//! output polygon must be used, with the same two end points bit for bit,
//! by another polygon in the opposite direction (the fill's top-left rule
//! then leaves no crack along it).

use glam::{DVec2, DVec3};
use host_sim::geom::{area, Polygon};
use std::collections::{BTreeMap, HashMap};

/// What [`check_tiling`] found.
#[derive(Clone, Debug, Default)]
pub struct TilingReport {
    /// Source faces checked (with at least one input polygon).
    pub faces: usize,
    /// Output polygons checked.
    pub pieces: usize,
    /// Largest distance of a piece vertex outside its face, over `eps`
    /// when there is a failure.
    pub worst_outside: f64,
    /// Largest relative area difference of a face and its pieces.
    pub worst_area_rel: f64,
    /// One line per failing face (at most a few are kept).
    pub failures: Vec<String>,
    /// Failing faces in all.
    pub failed: usize,
}

/// Distance from `p` to the segment `a b`.
fn seg_distance(a: DVec3, b: DVec3, p: DVec3) -> f64 {
    let ab = b - a;
    let l2 = ab.length_squared();
    let t = if l2 > 0.0 {
        ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t - p).length()
}

/// Even–odd point-in-polygon test of `p` against `poly`, in the plane of
/// the polygon projected along its normal's largest axis.
fn contains(poly: &Polygon, p: DVec3) -> bool {
    let n = poly.plane.normal.abs();
    let flat = |v: DVec3| {
        if n.x >= n.y && n.x >= n.z {
            DVec2::new(v.y, v.z)
        } else if n.y >= n.z {
            DVec2::new(v.z, v.x)
        } else {
            DVec2::new(v.x, v.y)
        }
    };
    let q = flat(p);
    let pts: Vec<DVec2> = poly.verts.iter().map(|&v| flat(v)).collect();
    let mut inside = false;
    for k in 0..pts.len() {
        let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
        if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}

/// How far `p` lies outside `poly`: 0 inside (within `eps` of its plane),
/// else the distance to its outline or its plane, whichever is larger.
fn outside_distance(poly: &Polygon, p: DVec3, eps: f64) -> f64 {
    let off_plane = poly.plane.distance(p).abs();
    if off_plane <= eps && contains(poly, p) {
        return 0.0;
    }
    let n = poly.verts.len();
    let to_outline = (0..n)
        .map(|k| seg_distance(poly.verts[k], poly.verts[(k + 1) % n], p))
        .fold(f64::INFINITY, f64::min);
    to_outline.max(off_plane)
}

fn perimeter(poly: &Polygon) -> f64 {
    let n = poly.verts.len();
    (0..n)
        .map(|k| poly.verts[k].distance(poly.verts[(k + 1) % n]))
        .sum()
}

/// Checks that `pieces` (a tree's output polygons) tile the faces of
/// `input` (the polygons the tree was built from), grouped by `source`,
/// with the absolute tolerance `eps` (see the module docs).
pub fn check_tiling(input: &[Polygon], pieces: &[Polygon], eps: f64) -> TilingReport {
    let mut faces: BTreeMap<u32, (Vec<&Polygon>, Vec<&Polygon>)> = BTreeMap::new();
    for p in input {
        faces.entry(p.source).or_default().0.push(p);
    }
    for q in pieces {
        faces.entry(q.source).or_default().1.push(q);
    }
    let mut rep = TilingReport {
        pieces: pieces.len(),
        ..TilingReport::default()
    };
    for (source, (parts, out)) in &faces {
        let mut why = Vec::new();
        if parts.is_empty() {
            why.push(format!("{} pieces of a face not in the input", out.len()));
        } else {
            rep.faces += 1;
            // Inside: the worst vertex of all pieces.
            let mut worst = (0.0f64, DVec3::ZERO);
            for v in out.iter().flat_map(|q| q.verts.iter().copied()) {
                let d = parts
                    .iter()
                    .map(|p| outside_distance(p, v, eps))
                    .fold(f64::INFINITY, f64::min);
                if d > worst.0 {
                    worst = (d, v);
                }
            }
            rep.worst_outside = rep.worst_outside.max(worst.0);
            if worst.0 > eps {
                why.push(format!(
                    "piece vertex {} lies {:.3e} outside the face",
                    worst.1, worst.0
                ));
            }
            // Area.
            let want: f64 = parts.iter().map(|p| area(&p.verts)).sum();
            let got: f64 = out.iter().map(|q| area(&q.verts)).sum();
            let slack = eps * parts.iter().map(|p| perimeter(p)).sum::<f64>();
            let rel = (got - want).abs() / want.max(f64::MIN_POSITIVE);
            rep.worst_area_rel = rep.worst_area_rel.max(rel);
            if (got - want).abs() > slack {
                why.push(format!(
                    "pieces' area {got:.6e}, face's {want:.6e} ({:+.3} %)",
                    100.0 * (got - want) / want
                ));
            }
        }
        if !why.is_empty() {
            rep.failed += 1;
            if rep.failures.len() < 5 {
                rep.failures.push(format!(
                    "source {source} ({} pieces): {}",
                    out.len(),
                    why.join("; ")
                ));
            }
        }
    }
    rep
}

/// The directed edges of `polys` that no polygon uses in the opposite
/// direction with the very same end points: none in a closed model whose
/// seams conform. Returns how many, and the first few as text.
pub fn open_edges(polys: &[Polygon]) -> (usize, Vec<String>) {
    let key = |v: DVec3| [v.x, v.y, v.z].map(|c| (c + 0.0).to_bits());
    let mut count: HashMap<([u64; 3], [u64; 3]), i64> = HashMap::new();
    for p in polys {
        let n = p.verts.len();
        for k in 0..n {
            let (a, b) = (key(p.verts[k]), key(p.verts[(k + 1) % n]));
            if a != b {
                *count.entry((a, b)).or_insert(0) += 1;
            }
        }
    }
    let mut open = 0;
    let mut first = Vec::new();
    for (&(a, b), &c) in &count {
        let back = count.get(&(b, a)).copied().unwrap_or(0);
        if c != back {
            open += 1;
            if first.len() < 5 {
                let v = |k: [u64; 3]| DVec3::from(k.map(f64::from_bits));
                first.push(format!(
                    "edge {} -> {} used {c} times, back {back} times",
                    v(a),
                    v(b)
                ));
            }
        }
    }
    (open, first)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(pts: [[f64; 2]; 3], source: u32) -> Polygon {
        let v = pts.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect();
        Polygon::new(v, source, [1, 1, 1]).unwrap()
    }

    #[test]
    fn exact_pieces_pass_and_moved_or_lost_ones_fail() {
        let face = tri([[0.0, 0.0], [1.0, 0.0], [0.3, 1.0]], 4);
        // Cut through the apex and the middle of the base.
        let left = tri([[0.0, 0.0], [0.5, 0.0], [0.3, 1.0]], 4);
        let right = tri([[0.5, 0.0], [1.0, 0.0], [0.3, 1.0]], 4);
        let ok = check_tiling(
            std::slice::from_ref(&face),
            &[left.clone(), right.clone()],
            1e-9,
        );
        assert_eq!((ok.faces, ok.failed), (1, 0), "{:?}", ok.failures);
        // The apex moved along the base's direction (a shear: same area).
        let sheared = [
            tri([[0.0, 0.0], [0.5, 0.0], [0.299, 1.0]], 4),
            tri([[0.5, 0.0], [1.0, 0.0], [0.299, 1.0]], 4),
        ];
        let bad = check_tiling(std::slice::from_ref(&face), &sheared, 1e-9);
        assert_eq!(bad.failed, 1);
        assert!(bad.failures[0].contains("outside"), "{:?}", bad.failures);
        // A piece lost.
        let lost = check_tiling(std::slice::from_ref(&face), &[left], 1e-9);
        assert!(lost.failures[0].contains("area"), "{:?}", lost.failures);
        // A piece of a face that was not in the input.
        let stray = tri([[0.5, 0.0], [1.0, 0.0], [0.3, 1.0]], 9);
        assert_eq!(check_tiling(&[face], &[right, stray], 1e-9).failed, 2);
    }

    #[test]
    fn open_edges_finds_a_t_junction() {
        // Two triangles sharing the edge (0,0)-(1,1) form a closed "pillow"
        // with their mirror images; a vertex inserted on one side only
        // opens the edge.
        let a = tri([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], 0);
        let mut b = a.clone();
        b.verts.reverse();
        assert_eq!(open_edges(&[a.clone(), b.clone()]).0, 0);
        b.verts.insert(1, DVec3::new(1.0, 0.5, 0.0));
        assert_eq!(open_edges(&[a, b]).0, 3);
    }
}
