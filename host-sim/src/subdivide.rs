//! Loop subdivision of indexed triangle meshes, so that the build-time
//! benchmark (`fpt bench-build --scaling --subdivide K`, `fpt subdivide`)
//! can measure curved, irregular meshes of 80k triangles and more made
//! from the real models at hand (issue 15: no such mesh can be
//! downloaded here).
//!
//! The scheme (Loop 1987) splits every triangle into four at its edges'
//! new vertices and moves the old vertices:
//!
//! - an interior edge `ab` (two faces, opposite vertices `c` and `d`)
//!   gets `3/8 (a + b) + 1/8 (c + d)`; any other edge (boundary,
//!   non-manifold) its midpoint;
//! - an old vertex with `n` neighbours, none across a sharp edge, becomes
//!   `(1 − n β) v + β Σ neighbours` with Loop's
//!   `β = (5/8 − (3/8 + cos(2π/n)/4)²) / n`;
//! - a vertex on exactly two sharp (boundary or non-manifold) edges
//!   becomes `3/4 v + 1/8 (a + b)` from the two vertices across them, so
//!   a boundary curve is refined on its own, as a cubic B-spline;
//! - any other vertex on sharp edges (a corner, a non-manifold vertex)
//!   stays where it is.
//!
//! Every new position is an affine combination of old ones, so a flat
//! patch stays flat; the children of a face keep its winding, so a closed,
//! consistently oriented mesh stays so.
//!
//! No crate was used: the Rust ports of OpenSubdiv found on crates.io
//! are whole libraries (topology refiners, stencil and patch tables) for
//! what takes one pass over the edges here.

use crate::geom::Polygon;
use crate::mesh::{MeshError, Model};
use std::collections::HashMap;

/// A triangle mesh as index triples into a vertex list, with one colour
/// per triangle.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Triangles, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// One colour per triangle, or none (the import's default grey).
    pub colors: Vec<[u8; 3]>,
}

impl TriMesh {
    /// The triangle mesh of imported polygons: vertices that are equal
    /// bit for bit become one (the import welds shared vertices and never
    /// moves them, so neighbouring polygons share theirs exactly), and
    /// polygons of more than three vertices are cut into triangles by
    /// [`crate::mesh::triangulate`] (ear clipping in their plane, so
    /// concave faces are cut right).
    pub fn from_polygons(polygons: &[Polygon]) -> TriMesh {
        let mut index: HashMap<[u64; 3], u32> = HashMap::new();
        let mut mesh = TriMesh::default();
        for p in polygons {
            let ids: Vec<u32> = p
                .verts
                .iter()
                .map(|v| {
                    let key = [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
                    *index.entry(key).or_insert_with(|| {
                        mesh.vertices.push(v.to_array());
                        // Meshes past 4 G vertices cannot be loaded anyway.
                        (mesh.vertices.len() - 1) as u32
                    })
                })
                .collect();
            let tris = if ids.len() == 3 {
                vec![[0, 1, 2]]
            } else {
                crate::mesh::triangulate(&p.verts, p.plane.normal)
            };
            for [a, b, c] in tris {
                mesh.triangles.push([ids[a], ids[b], ids[c]]);
                mesh.colors.push(p.color);
            }
        }
        mesh
    }

    /// The mesh as a [`Model`] for the builders, through the import's
    /// common pipeline ([`crate::mesh::from_faces`]: welding, degenerate
    /// faces dropped, closedness decided).
    pub fn to_model(&self) -> Result<Model, MeshError> {
        let faces: Vec<Vec<u32>> = self.triangles.iter().map(|t| t.to_vec()).collect();
        let colors = (!self.colors.is_empty()).then_some(&self.colors[..]);
        crate::mesh::from_faces(&self.vertices, &faces, colors)
    }

    /// One step of Loop subdivision (see the module docs): four times the
    /// triangles, the children of triangle `i` at `4i..4i + 4` with its
    /// colour; the old vertices keep their indices, edge vertices follow
    /// in the order the triangles first use their edges.
    pub fn loop_subdivide(&self) -> TriMesh {
        let nv = self.vertices.len();
        let p = |i: u32| self.vertices[i as usize];
        // Each undirected edge once: its ends, the vertices opposite it
        // (the first two) and how many triangles use it.
        struct Edge {
            ends: [u32; 2],
            opposite: [u32; 2],
            faces: u32,
        }
        let mut edges: Vec<Edge> = Vec::with_capacity(self.triangles.len() * 3 / 2 + 3);
        let mut edge_of: HashMap<u64, u32> = HashMap::with_capacity(edges.capacity());
        let mut tri_edges: Vec<[u32; 3]> = Vec::with_capacity(self.triangles.len());
        for t in &self.triangles {
            let mut e3 = [0u32; 3];
            for k in 0..3 {
                let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
                let id = *edge_of.entry(key).or_insert_with(|| {
                    edges.push(Edge {
                        ends: [a, b],
                        opposite: [c, c],
                        faces: 0,
                    });
                    (edges.len() - 1) as u32
                });
                let e = &mut edges[id as usize];
                if e.faces == 1 {
                    e.opposite[1] = c;
                }
                e.faces += 1;
                e3[k] = id;
            }
            tri_edges.push(e3);
        }

        // Sums over each vertex's neighbours, all of them and those across
        // sharp edges, in one pass over the edges (each neighbour once).
        let mut sum = vec![[0.0f64; 3]; nv];
        let mut count = vec![0u32; nv];
        let mut sharp_sum = vec![[0.0f64; 3]; nv];
        let mut sharp_count = vec![0u32; nv];
        for e in &edges {
            let sharp = e.faces != 2;
            for (v, w) in [(e.ends[0], e.ends[1]), (e.ends[1], e.ends[0])] {
                let (v, q) = (v as usize, p(w));
                add(&mut sum[v], q, 1.0);
                count[v] += 1;
                if sharp {
                    add(&mut sharp_sum[v], q, 1.0);
                    sharp_count[v] += 1;
                }
            }
        }

        let mut vertices = Vec::with_capacity(nv + edges.len());
        for (v, &pos) in self.vertices.iter().enumerate() {
            let mut out = [0.0; 3];
            match (sharp_count[v], count[v]) {
                (0, 0) => out = pos,
                (0, n) => {
                    let beta = loop_beta(n);
                    add(&mut out, pos, 1.0 - f64::from(n) * beta);
                    add(&mut out, sum[v], beta);
                }
                (2, _) => {
                    add(&mut out, pos, 0.75);
                    add(&mut out, sharp_sum[v], 0.125);
                }
                _ => out = pos,
            }
            vertices.push(out);
        }
        for e in &edges {
            let mut out = [0.0; 3];
            let [a, b] = e.ends;
            if e.faces == 2 {
                let [c, d] = e.opposite;
                add(&mut out, p(a), 0.375);
                add(&mut out, p(b), 0.375);
                add(&mut out, p(c), 0.125);
                add(&mut out, p(d), 0.125);
            } else {
                add(&mut out, p(a), 0.5);
                add(&mut out, p(b), 0.5);
            }
            vertices.push(out);
        }

        let mut triangles = Vec::with_capacity(4 * self.triangles.len());
        let mut colors = Vec::with_capacity(4 * self.triangles.len());
        for (i, (t, e3)) in self.triangles.iter().zip(&tri_edges).enumerate() {
            let [a, b, c] = *t;
            // Edge k runs from corner k to corner k + 1.
            let [ab, bc, ca] = e3.map(|e| nv as u32 + e);
            triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
            if let Some(&color) = self.colors.get(i) {
                colors.extend([color; 4]);
            }
        }
        TriMesh {
            vertices,
            triangles,
            colors,
        }
    }
}

/// Loop's weight of each of a vertex's `n` neighbours (`n ≥ 1`): 1/16
/// for the regular valence 6, 3/16 for 3.
fn loop_beta(n: u32) -> f64 {
    let n = f64::from(n);
    let c = 0.375 + 0.25 * (std::f64::consts::TAU / n).cos();
    (0.625 - c * c) / n
}

/// `acc += w · q`.
fn add(acc: &mut [f64; 3], q: [f64; 3], w: f64) {
    for (a, q) in acc.iter_mut().zip(q) {
        *a += w * q;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use std::collections::HashSet;

    /// The tetrahedron on the origin and the unit axes, faces outward.
    fn tetrahedron() -> TriMesh {
        TriMesh {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
            colors: vec![[1, 2, 3]; 4],
        }
    }

    /// Every directed edge once and its reverse once: closed (watertight)
    /// and consistently oriented.
    fn assert_closed_oriented(m: &TriMesh) {
        let mut directed = HashSet::new();
        for t in &m.triangles {
            for k in 0..3 {
                assert!(directed.insert((t[k], t[(k + 1) % 3])), "edge used twice");
            }
        }
        for &(a, b) in &directed {
            assert!(directed.contains(&(b, a)), "edge {a}-{b} has one side only");
        }
    }

    /// Six times the signed volume the triangles enclose.
    fn volume6(m: &TriMesh) -> f64 {
        let v = |i: u32| DVec3::from(m.vertices[i as usize]);
        m.triangles
            .iter()
            .map(|&[a, b, c]| v(a).dot(v(b).cross(v(c))))
            .sum()
    }

    fn has_vertex(m: &TriMesh, p: [f64; 3]) -> bool {
        m.vertices
            .iter()
            .any(|q| q.iter().zip(p).all(|(a, b)| (a - b).abs() < 1e-15))
    }

    #[test]
    fn beta_is_loops() {
        assert!((loop_beta(6) - 1.0 / 16.0).abs() < 1e-15);
        assert!((loop_beta(3) - 3.0 / 16.0).abs() < 1e-15);
    }

    #[test]
    fn tetrahedron_step_by_hand() {
        let s = tetrahedron().loop_subdivide();
        // 4 old vertices and 6 edge vertices; 4 × 4 triangles.
        assert_eq!(s.vertices.len(), 10);
        assert_eq!(s.triangles.len(), 16);
        assert_eq!(s.colors, vec![[1, 2, 3]; 16]);
        // Valence 3: β = 3/16, the vertex keeps 1 − 3β = 7/16.
        assert_eq!(s.vertices[0], [3.0 / 16.0; 3]);
        assert_eq!(s.vertices[1], [7.0 / 16.0, 3.0 / 16.0, 3.0 / 16.0]);
        // Edge 0-1, opposite vertices 2 and 3.
        assert!(has_vertex(&s, [3.0 / 8.0, 1.0 / 8.0, 1.0 / 8.0]));
        // Edge 2-3, opposite 0 and 1.
        assert!(has_vertex(&s, [1.0 / 8.0, 3.0 / 8.0, 3.0 / 8.0]));
    }

    #[test]
    fn one_triangle_follows_the_boundary_rules() {
        let m = TriMesh {
            vertices: vec![[0.0, 0.0, 0.0], [8.0, 0.0, 0.0], [0.0, 8.0, 0.0]],
            triangles: vec![[0, 1, 2]],
            colors: Vec::new(),
        };
        let s = m.loop_subdivide();
        assert_eq!(s.triangles.len(), 4);
        assert!(s.colors.is_empty());
        // 3/4 v + 1/8 of its two boundary neighbours.
        assert_eq!(s.vertices[0], [1.0, 1.0, 0.0]);
        assert_eq!(s.vertices[1], [6.0, 1.0, 0.0]);
        // Midpoints, in the order the edges are first used: 0-1, 1-2, 2-0.
        assert_eq!(s.vertices[3], [4.0, 0.0, 0.0]);
        assert_eq!(s.vertices[4], [4.0, 4.0, 0.0]);
        assert_eq!(s.vertices[5], [0.0, 4.0, 0.0]);
        // The middle child and the corner children keep the winding.
        assert_eq!(
            s.triangles,
            vec![[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]]
        );
    }

    #[test]
    fn a_closed_mesh_stays_closed_and_outward() {
        let mut m = tetrahedron();
        for level in 1..=3 {
            let next = m.loop_subdivide();
            assert_eq!(next.triangles.len(), 4 * m.triangles.len());
            assert_closed_oriented(&next);
            // Smoothing shrinks the volume, never turns it inside out.
            let (before, after) = (volume6(&m), volume6(&next));
            assert!(after > 0.0 && after < before, "level {level}: {after}");
            m = next;
        }
        let model = m.to_model().unwrap();
        assert!(model.closed);
        assert_eq!(model.polygons.len(), 256);
    }

    #[test]
    fn a_flat_patch_stays_flat() {
        // An irregular 5×5 grid on the plane z = 0.5 x − 0.25 y + 2.
        let n = 5u32;
        let mut m = TriMesh::default();
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (f64::from(i) + 0.1 * f64::from(j % 3), f64::from(j) * 1.3);
                m.vertices.push([x, y, 0.5 * x - 0.25 * y + 2.0]);
            }
        }
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let a = j * n + i;
                m.triangles.push([a, a + 1, a + n + 1]);
                m.triangles.push([a, a + n + 1, a + n]);
            }
        }
        let s = m.loop_subdivide().loop_subdivide();
        assert_eq!(s.triangles.len(), 16 * m.triangles.len());
        for v in &s.vertices {
            assert!(
                (v[2] - (0.5 * v[0] - 0.25 * v[1] + 2.0)).abs() < 1e-12,
                "{v:?}"
            );
        }
        // Boundary vertices move along the boundary, never out of the patch.
        assert!(s.vertices.iter().all(|v| v[0] >= 0.0 && v[1] >= 0.0));
        assert!(!s.to_model().unwrap().closed);
    }

    #[test]
    fn polygons_are_indexed_and_triangulated() {
        // The unit cube of quads: 8 shared vertices, 12 triangles, closed.
        let cube = crate::mesh::load_bytes(
            crate::mesh::MeshFormat::Obj,
            b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
              f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n",
        )
        .unwrap();
        let m = TriMesh::from_polygons(&cube.polygons);
        assert_eq!((m.vertices.len(), m.triangles.len()), (8, 12));
        assert_closed_oriented(&m);
        assert!(volume6(&m) > 0.0);
        let s = m.loop_subdivide();
        assert_closed_oriented(&s);
        // V − E + F stays 2: 8 + 18 edge vertices, 48 triangles.
        assert_eq!((s.vertices.len(), s.triangles.len()), (26, 48));
        assert!(s.to_model().unwrap().closed);

        // A concave L: six vertices, four triangles, none outside it.
        let l = crate::mesh::load_bytes(
            crate::mesh::MeshFormat::Obj,
            b"v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n",
        )
        .unwrap();
        let m = TriMesh::from_polygons(&l.polygons);
        assert_eq!((m.vertices.len(), m.triangles.len()), (6, 4));
        let area2: f64 = m
            .triangles
            .iter()
            .map(|&[a, b, c]| {
                let v = |i: u32| DVec3::from(m.vertices[i as usize]);
                (v(b) - v(a)).cross(v(c) - v(a)).z
            })
            .sum();
        assert!((area2 - 6.0).abs() < 1e-12, "twice the L's area 3: {area2}");
    }
}
