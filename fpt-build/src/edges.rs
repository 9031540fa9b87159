//! Which polygon edges are outlines: the serializer's input to the
//! `outline` effect (the `hidden_edges` byte of a polygon record, see
//! `fpt_nostd::format`).
//!
//! Splitting (concave faces, cuts by separating planes) breaks an input
//! face into pieces; the outline of the face is the pieces' edges that are
//! not shared with another piece. After the builder's welding and
//! T-junction repair (`crate::seams`) neighbouring pieces share their
//! edges vertex for vertex, so an edge `a → b` is inside the face exactly
//! when another polygon has the edge `b → a` and is either a piece of the
//! same input face, or coplanar with the same colour (a flat CAD face that
//! arrived as triangles). Anything else, including an edge that only
//! partly overlaps its neighbour's, stays an outline: at worst a line too
//! many, never a missing silhouette.
//!
//! **Feature edges** (the optional edge section of a file, written when
//! the scene declares `outline`; [`edge_kinds`]): every edge of every
//! polygon gets a kind. Inner edges as above are hidden; an edge shared
//! with a neighbour of the same colour whose plane turns by at most the
//! crease angle is *soft* (drawn only as a silhouette, so a tessellated
//! curved surface shows its outline, not its facets); the rest (sharper
//! than the crease, a colour change, a mesh boundary) are drawn.
//!
//! Only 8 bits are stored per polygon: edges from the 9th on are always
//! outlines. That is not rare once seams are repaired (T-junction vertices
//! lengthen loops): counted with [`lost_inner_edges`] on the procedural
//! scenes, 62 of 2,276 inner edges of the vise are drawn (2.7 %), 135 of
//! 3,928 of the house (3.4 %), 213 of 2,788 of `bench_city` (7.6 %).
//! Rotating such loops would fit more, but would break the one-to-one order
//! of the builder's and the file's vertices that the accuracy study relies
//! on; a wider mask would change the format.

use std::collections::HashMap;

/// What decides whether two polygons belong to one visible face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FaceKey {
    /// The input face the polygon came from.
    pub source: u32,
    /// Its stored plane, bit for bit.
    pub plane: [u32; 4],
    /// Its colour.
    pub color: [u8; 3],
}

impl FaceKey {
    fn same_face(&self, o: &FaceKey) -> bool {
        self.source == o.source || (self.plane == o.plane && self.color == o.color)
    }
}

/// For polygons given as vertex id loops with their [`FaceKey`]s: which
/// edges are inner edges (`true`), per loop, edge `i` from vertex `i` to
/// `i + 1`.
pub fn inner_edges(loops: &[&[u32]], keys: &[FaceKey]) -> Vec<Vec<bool>> {
    let by_edge = edge_map(loops);
    loops
        .iter()
        .enumerate()
        .map(|(p, l)| {
            let inner: Vec<bool> = edges(l)
                .map(|(a, b)| {
                    a != b
                        && by_edge.get(&(b, a)).is_some_and(|qs| {
                            qs.iter().any(|&q| q != p && keys[q].same_face(&keys[p]))
                        })
                })
                .collect();
            inner
        })
        .collect()
}

/// The stored masks of [`inner_edges`]: bit `i` for edge `i < 8`.
pub fn hidden_edges(loops: &[&[u32]], keys: &[FaceKey]) -> Vec<u8> {
    inner_edges(loops, keys)
        .iter()
        .map(|inner| {
            inner
                .iter()
                .take(8)
                .enumerate()
                .fold(0u8, |m, (i, &b)| m | (u8::from(b) << i))
        })
        .collect()
}

/// How many inner edges the masks cannot hold (index 8 and beyond): those
/// are drawn as outlines.
pub fn lost_inner_edges(loops: &[&[u32]], keys: &[FaceKey]) -> usize {
    inner_edges(loops, keys)
        .iter()
        .map(|inner| inner.iter().skip(8).filter(|&&b| b).count())
        .sum()
}

/// The default crease angle in degrees (`fpt build --crease`).
pub const DEFAULT_CREASE_DEG: f32 = 30.0;

/// The kind of every edge of every loop, as the file's edge section stores
/// it (`fpt_nostd::format`): `(kind, neighbour normal × 127)`, edge `i`
/// from vertex `i` to `i + 1`. `normals` are the loops' unit plane
/// normals; an edge whose neighbour of the same colour turns by at most
/// `crease_deg` degrees is soft.
pub fn edge_kinds(
    loops: &[&[u32]],
    keys: &[FaceKey],
    normals: &[[f32; 3]],
    crease_deg: f32,
) -> Vec<Vec<(u8, [i8; 3])>> {
    use fpt_nostd::format::{EDGE_DRAWN, EDGE_HIDDEN, EDGE_SOFT};
    let by_edge = edge_map(loops);
    let cos_crease = f64::from(crease_deg).to_radians().cos();
    let dot = |a: &[f32; 3], b: &[f32; 3]| {
        (0..3)
            .map(|k| f64::from(a[k]) * f64::from(b[k]))
            .sum::<f64>()
    };
    loops
        .iter()
        .enumerate()
        .map(|(p, l)| {
            edges(l)
                .map(|(a, b)| {
                    let across: Vec<usize> = if a == b {
                        vec![]
                    } else {
                        by_edge
                            .get(&(b, a))
                            .map(|qs| qs.iter().copied().filter(|&q| q != p).collect())
                            .unwrap_or_default()
                    };
                    if across.iter().any(|&q| keys[q].same_face(&keys[p])) {
                        return (EDGE_HIDDEN, [0; 3]);
                    }
                    // The smoothest neighbour of the same colour.
                    let soft = across
                        .iter()
                        .filter(|&&q| keys[q].color == keys[p].color)
                        .map(|&q| (dot(&normals[p], &normals[q]), q))
                        .filter(|&(c, _)| c >= cos_crease)
                        .max_by(|x, y| x.0.total_cmp(&y.0));
                    match soft {
                        Some((_, q)) => (
                            EDGE_SOFT,
                            normals[q].map(|c| (c * 127.0).round().clamp(-127.0, 127.0) as i8),
                        ),
                        None => (EDGE_DRAWN, [0; 3]),
                    }
                })
                .collect()
        })
        .collect()
}

/// Which polygons have each directed edge.
fn edge_map(loops: &[&[u32]]) -> HashMap<(u32, u32), Vec<usize>> {
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (p, l) in loops.iter().enumerate() {
        for (a, b) in edges(l) {
            by_edge.entry((a, b)).or_default().push(p);
        }
    }
    by_edge
}

fn edges(l: &[u32]) -> impl Iterator<Item = (u32, u32)> + '_ {
    let n = l.len();
    (0..n).map(move |i| (l[i], l[(i + 1) % n]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(source: u32, plane: u32) -> FaceKey {
        FaceKey {
            source,
            plane: [plane, 0, 0, 0],
            color: [1, 2, 3],
        }
    }

    #[test]
    fn shared_edges_of_one_face_are_hidden_and_others_are_not() {
        // A square 0-1-2-3 split along 0-2 into two triangles of face 7,
        // and a neighbour of another face and plane across edge 1-2.
        let a = [0u32, 1, 2];
        let b = [0u32, 2, 3];
        let c = [2u32, 1, 4];
        let loops: Vec<&[u32]> = vec![&a, &b, &c];
        let keys = [key(7, 1), key(7, 1), key(8, 2)];
        let h = hidden_edges(&loops, &keys);
        assert_eq!(h[0], 0b100); // edge 2: 2 → 0
        assert_eq!(h[1], 0b001); // edge 0: 0 → 2
        assert_eq!(h[2], 0); // 2 → 1 is shared with another face
                             // Coplanar and same colour counts as one face even across sources.
        let keys = [key(7, 1), key(9, 1), key(8, 2)];
        assert_eq!(hidden_edges(&loops, &keys)[1], 0b001);
        let mut other = key(9, 1);
        other.color = [0, 0, 0];
        let keys = [key(7, 1), other, key(8, 2)];
        assert_eq!(hidden_edges(&loops, &keys)[1], 0);
    }

    #[test]
    fn inner_edges_past_the_eighth_are_counted_as_lost() {
        // A 10-gon whose edge 9 → 0 (index 9) is shared with a piece of the
        // same face, and whose edge 0 → 1 is shared with another.
        let big: Vec<u32> = (0..10).collect();
        let tri = [0u32, 9, 20];
        let tri2 = [1u32, 0, 21];
        let loops: Vec<&[u32]> = vec![&big, &tri, &tri2];
        let keys = [key(1, 1), key(1, 1), key(1, 1)];
        assert_eq!(hidden_edges(&loops, &keys)[0], 0b1);
        assert_eq!(lost_inner_edges(&loops, &keys), 1);
    }

    #[test]
    fn edge_kinds_follow_the_crease_angle() {
        use fpt_nostd::format::{EDGE_DRAWN, EDGE_HIDDEN, EDGE_SOFT};
        // Polygon 0 shares edge 0 → 1 with polygon 1 (turned by 20°),
        // edge 1 → 2 with polygon 2 (turned by 60°), edge 2 → 0 with
        // polygon 3, a piece of its own face; polygon 4 is a 10-gon whose
        // edge 9 (9 → 0) is shared with polygon 5 of the same face.
        let (s, c) = 20f32.to_radians().sin_cos();
        let (s6, c6) = 60f32.to_radians().sin_cos();
        let n0 = [0.0, 0.0, 1.0];
        let normals = [n0, [s, 0.0, c], [s6, 0.0, c6], n0, n0, n0];
        let l0 = [0u32, 1, 2];
        let l1 = [1u32, 0, 3];
        let l2 = [2u32, 1, 4];
        let l3 = [0u32, 2, 5];
        let big: Vec<u32> = (10..20).collect();
        let l5 = [10u32, 19, 30];
        let loops: Vec<&[u32]> = vec![&l0, &l1, &l2, &l3, &big, &l5];
        let keys = [
            key(1, 1),
            key(2, 2),
            key(3, 3),
            key(1, 1),
            key(4, 4),
            key(4, 4),
        ];
        let k = edge_kinds(&loops, &keys, &normals, 30.0);
        let n1 = [(s * 127.0).round() as i8, 0, (c * 127.0).round() as i8];
        assert_eq!(
            k[0],
            vec![(EDGE_SOFT, n1), (EDGE_DRAWN, [0; 3]), (EDGE_HIDDEN, [0; 3])]
        );
        // A smaller crease makes the 20° edge a feature edge.
        assert_eq!(
            edge_kinds(&loops, &keys, &normals, 10.0)[0][0].0,
            EDGE_DRAWN
        );
        // Every edge of the 10-gon has its kind, the 10th included.
        assert_eq!(k[4].len(), 10);
        assert_eq!(k[4][9].0, EDGE_HIDDEN);
        assert!(k[4][..9].iter().all(|e| e.0 == EDGE_DRAWN));
        // A different colour is always an outline.
        let mut other = key(2, 2);
        other.color = [9, 9, 9];
        let keys = [key(1, 1), other, key(3, 3), key(1, 1), key(4, 4), key(4, 4)];
        assert_eq!(
            edge_kinds(&loops, &keys, &normals, 30.0)[0][0].0,
            EDGE_DRAWN
        );
    }
}
