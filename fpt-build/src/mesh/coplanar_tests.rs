//! Tests of the coplanar region merge, through the mesh import.

use crate::geom::{area, Polygon};
use crate::mesh::{from_faces, from_faces_with, ImportOptions, Model};
use glam::DVec3;

const NO_MERGE: ImportOptions = ImportOptions {
    keep_orientation: false,
    no_merge: true,
};

/// Whether `p` is convex (collinear vertices allowed) about its plane and
/// every vertex within `tol` of it.
fn convex_and_planar(p: &Polygon, tol: f64) -> bool {
    let n = p.verts.len();
    (0..n).all(|i| {
        let (a, b, c) = (p.verts[i], p.verts[(i + 1) % n], p.verts[(i + 2) % n]);
        (b - a).cross(c - b).dot(p.plane.normal) >= -1e-12 && p.plane.distance(a).abs() <= tol
    })
}

fn total_area(m: &Model) -> f64 {
    m.polygons.iter().map(|p| area(&p.verts)).sum()
}

/// Every vertex of `m` is one of `verts`, bit for bit.
fn no_vertex_moved(m: &Model, verts: &[[f64; 3]]) -> bool {
    m.polygons
        .iter()
        .flat_map(|p| &p.verts)
        .all(|v| verts.contains(&v.to_array()))
}

/// An `n × n` grid of unit squares in z = 0, each cut into two triangles.
fn grid(n: u32) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let verts = (0..=n)
        .flat_map(|y| (0..=n).map(move |x| [f64::from(x), f64::from(y), 0.0]))
        .collect();
    let at = |x: u32, y: u32| y * (n + 1) + x;
    let faces = (0..n)
        .flat_map(|y| (0..n).map(move |x| (x, y)))
        .flat_map(|(x, y)| {
            [
                vec![at(x, y), at(x + 1, y), at(x + 1, y + 1)],
                vec![at(x, y), at(x + 1, y + 1), at(x, y + 1)],
            ]
        })
        .collect();
    (verts, faces)
}

#[test]
fn triangulated_grid_merges_into_convex_pieces_that_tile_it() {
    let (v, f) = grid(4);
    let m = from_faces(&v, &f, None).unwrap();
    let whole = from_faces_with(&v, &f, None, &NO_MERGE).unwrap();
    assert_eq!(whole.polygons.len(), 32);
    assert_eq!(whole.report.coplanar_merged, 0);
    assert!(m.polygons.len() < 10, "{} pieces", m.polygons.len());
    assert_eq!(m.report.coplanar_merged, 32 - m.polygons.len());
    assert!((total_area(&m) - 16.0).abs() < 1e-12);
    assert!(no_vertex_moved(&m, &v));
    for p in &m.polygons {
        assert!(p.verts.len() <= super::MAX_MERGED_VERTS);
        assert!(convex_and_planar(p, 0.0));
        assert_eq!(p.source, 0, "the region's first face");
        assert!((p.plane.normal - DVec3::Z).length() < 1e-12);
    }
    // Every grid vertex stays a vertex of some piece: interior vertices
    // too (a merge drops no vertex).
    let used: Vec<[f64; 3]> = m
        .polygons
        .iter()
        .flat_map(|p| p.verts.iter().map(|v| v.to_array()))
        .collect();
    assert!(v.iter().all(|x| used.contains(x)));
}

#[test]
fn triangulated_cube_becomes_six_quads() {
    let v: Vec<[f64; 3]> = (0..8)
        .map(|i| [f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)])
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [1, 3, 7, 5],
        [0, 4, 6, 2],
    ];
    let f: Vec<Vec<u32>> = quads
        .iter()
        .flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]])
        .collect();
    let m = from_faces(&v, &f, None).unwrap();
    assert!(m.closed);
    assert_eq!(m.polygons.len(), 6);
    let mut sources: Vec<u32> = m.polygons.iter().map(|p| p.source).collect();
    sources.sort_unstable();
    assert_eq!(sources, vec![0, 2, 4, 6, 8, 10]);
    assert!((total_area(&m) - 6.0).abs() < 1e-12);
    assert!(m.polygons.iter().all(|p| p.verts.len() == 4));
    assert!(crate::mesh::is_closed(&m.polygons, 1e-9));
}

#[test]
fn different_colours_and_planes_stay_apart() {
    let (v, f) = grid(1);
    let m = from_faces(&v, &f, Some(&[[1, 2, 3], [1, 2, 4]])).unwrap();
    assert_eq!(m.polygons.len(), 2);
    // The second triangle lifted far above the planarity tolerance.
    let mut bent = v.clone();
    bent[2][2] = 1e-3;
    let m = from_faces(&bent, &f, None).unwrap();
    assert_eq!(m.polygons.len(), 2);
    // Noise within it: merged, nothing moved.
    bent[2][2] = 1e-9;
    let m = from_faces(&bent, &f, None).unwrap();
    assert_eq!(m.polygons.len(), 1);
    assert!(no_vertex_moved(&m, &bent));
    assert!(convex_and_planar(&m.polygons[0], 0.5e-7 * 2f64.sqrt()));
}

#[test]
fn a_neighbours_vertex_on_a_merged_edge_stays_a_vertex() {
    // A square of two triangles whose bottom edge has a vertex at
    // (0.5, 0) that a face in another plane shares: the merged square
    // keeps it, so the seam has no T-junction.
    let v = vec![
        [0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.5, 0.0, -1.0],
    ];
    let f = vec![
        vec![0, 1, 2, 3],
        vec![0, 3, 4],
        vec![0, 5, 1],
        vec![1, 5, 2],
    ];
    let m = from_faces(&v, &f, None).unwrap();
    let flat: Vec<&Polygon> = m
        .polygons
        .iter()
        .filter(|p| p.plane.normal.z > 0.5)
        .collect();
    assert_eq!(flat.len(), 1);
    assert_eq!(flat[0].verts.len(), 5);
    assert!(flat[0].verts.contains(&DVec3::new(0.5, 0.0, 0.0)));
    // The two faces below are coplanar too: merged across their edge.
    assert_eq!(m.polygons.len(), 2);
}

#[test]
fn concave_union_is_not_merged_and_cap_bounds_pieces() {
    // An L of three unit squares: the union is concave, so two pieces.
    let v = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 2.0, 0.0],
        [1.0, 2.0, 0.0],
    ];
    let f = vec![vec![0, 1, 4, 5], vec![1, 2, 3, 4], vec![5, 4, 7, 6]];
    let m = from_faces(&v, &f, None).unwrap();
    assert_eq!(m.polygons.len(), 2);
    assert!((total_area(&m) - 3.0).abs() < 1e-12);
    assert!(m.polygons.iter().all(|p| convex_and_planar(p, 0.0)));
    // A 40-gon fanned from its centre: pieces of at most 8 vertices.
    let n = 40;
    let mut v = vec![[0.0; 3]];
    v.extend((0..n).map(|i| {
        let t = f64::from(i) * std::f64::consts::TAU / f64::from(n);
        [t.cos(), t.sin(), 0.0]
    }));
    let f: Vec<Vec<u32>> = (0..n).map(|i| vec![0, 1 + i, 1 + (i + 1) % n]).collect();
    let m = from_faces(&v, &f, None).unwrap();
    let fan = from_faces_with(&v, &f, None, &NO_MERGE).unwrap();
    assert!(m.polygons.len() < 10, "{}", m.polygons.len());
    assert!(m.polygons.iter().all(|p| p.verts.len() <= 8));
    assert!((total_area(&m) - total_area(&fan)).abs() < 1e-12);
    assert!(m.polygons.iter().all(|p| convex_and_planar(p, 1e-15)));
}

#[test]
fn non_manifold_edges_are_not_merged_across() {
    // Two coplanar triangles sharing an edge that a third face (a fin)
    // uses as well: no merge.
    let v = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.5, 0.5, 1.0],
    ];
    let f = vec![vec![0, 1, 2], vec![0, 2, 3], vec![2, 0, 4]];
    assert_eq!(from_faces(&v, &f, None).unwrap().polygons.len(), 3);
}
