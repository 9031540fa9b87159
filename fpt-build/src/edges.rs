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
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (p, l) in loops.iter().enumerate() {
        for (a, b) in edges(l) {
            by_edge.entry((a, b)).or_default().push(p);
        }
    }
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
}
