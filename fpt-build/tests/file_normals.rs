//! Vertex normals written in the mesh file (OBJ `vn`, PLY `nx ny nz`)
//! reach the tree's corner normal section when the scene declares
//! `smooth`: each corner stores its file normal (quantized as every
//! normal is), the vertices that splitting adds get the normal
//! interpolated along their parent's edge, faces without normals in the
//! file get the crease-angle normals, and normals that point against
//! their face's winding are turned with it.

use fpt_build::build::{build, NoProgress, DEFAULT_SEED};
use fpt_build::mesh::{load_bytes, MeshFormat, Model};
use fpt_build::serialize::{serialize, SerializeOptions};
use fpt_build::tree::Method;
use fpt_nostd::effects::Effects;
use fpt_nostd::reader::Tree;

/// A normal as the tree stores it: unit, times 127, rounded.
fn q(n: [f64; 3]) -> [i8; 3] {
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|c| (c / len * 127.0).round() as i8)
}

fn normalize(n: [f64; 3]) -> [f64; 3] {
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    n.map(|c| c / len)
}

/// The tree of `model` with `smooth` declared (crease 30°).
fn smooth_tree(model: Model) -> Vec<u8> {
    let tree = build(
        model.polygons,
        model.closed,
        Method::Static,
        DEFAULT_SEED,
        &mut NoProgress,
    );
    let opts = SerializeOptions {
        effects: Some(Effects::defaults(model.closed).with(Effects::SMOOTH).bits()),
        ..SerializeOptions::default()
    };
    serialize(&tree, &opts).expect("serialize")
}

/// Every stored corner: its source face, model position and normal.
fn corners(bytes: &[u8]) -> Vec<(u32, [f64; 3], [i8; 3])> {
    let t = Tree::from_bytes(bytes).expect("valid tree");
    assert!(t.has_normals());
    let o = t.origin();
    let mut out = Vec::new();
    for id in 0..t.polygon_count() {
        let p = t.polygon(id).expect("polygon");
        for i in 0..p.vertex_count() {
            let v = p.vertex(i);
            let pos = [0, 1, 2].map(|k| o[k] + f64::from(v[k]));
            out.push((p.source(), pos, t.corner_normal(id, i).expect("normal")));
        }
    }
    out
}

/// Whether two stored normals differ by at most one step per component
/// (the positions went through `f32`, so a quantized value on a rounding
/// boundary may land on either side).
fn close(a: [i8; 3], b: [i8; 3]) -> bool {
    a.iter()
        .zip(&b)
        .all(|(x, y)| (i16::from(*x) - i16::from(*y)).abs() <= 1)
}

/// A unit cube whose vertex `i` is at the bits of `i` (x = bit 0, y = bit
/// 1, z = bit 2); faces outward, counter-clockwise, 0-based.
const CUBE_FACES: [[usize; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

fn cube_vertex(i: usize) -> [f64; 3] {
    [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64]
}

/// The diagonal from the cube's centre through vertex `i`: what a
/// smoothing exporter writes for a cube, far from any crease normal.
fn diagonal(i: usize) -> [f64; 3] {
    normalize(cube_vertex(i).map(|c| c - 0.5))
}

/// The cube as OBJ; faces in `with_vn` use `v//n` corners (normal `i`
/// is vertex `i`'s diagonal), the others plain `v`.
fn cube_obj(with_vn: &[usize]) -> String {
    let mut s = String::from("# cube with vertex normals\n");
    for i in 0..8 {
        let [x, y, z] = cube_vertex(i);
        s += &format!("v {x} {y} {z}\n");
    }
    for i in 0..8 {
        let [x, y, z] = diagonal(i);
        s += &format!("vn {x} {y} {z}\n");
    }
    for (k, f) in CUBE_FACES.iter().enumerate() {
        s.push('f');
        for &i in f {
            if with_vn.contains(&k) {
                s += &format!(" {}//{}", i + 1, i + 1);
            } else {
                s += &format!(" {}", i + 1);
            }
        }
        s.push('\n');
    }
    s
}

/// The vertex of the cube at `pos`.
fn cube_index(pos: [f64; 3]) -> usize {
    let b = pos.map(|c| usize::from(c > 0.5));
    b[0] | b[1] << 1 | b[2] << 2
}

#[test]
fn obj_vn_normals_are_stored_as_the_file_gives_them() {
    let all: Vec<usize> = (0..6).collect();
    let m = load_bytes(MeshFormat::Obj, cube_obj(&all).as_bytes()).expect("cube");
    assert!(m.closed);
    let c = corners(&smooth_tree(m));
    assert_eq!(c.len(), 24);
    for &(source, pos, n) in &c {
        assert!(
            close(n, q(diagonal(cube_index(pos)))),
            "face {source} at {pos:?}: {n:?}"
        );
    }
    // Faces 0 and 1 without `vn` (and the file's `vn` records still
    // there): their corners get the crease normals, the face's own (the
    // cube's faces meet at 90°, more than the 30° crease).
    let m = load_bytes(MeshFormat::Obj, cube_obj(&[2, 3, 4, 5]).as_bytes()).expect("cube");
    let mut computed = 0;
    for (source, pos, n) in corners(&smooth_tree(m)) {
        let want = match source {
            0 => [0, 0, -127],
            1 => [0, 0, 127],
            _ => q(diagonal(cube_index(pos))),
        };
        computed += usize::from(source < 2);
        assert!(close(n, want), "face {source} at {pos:?}: {n:?}");
    }
    assert_eq!(computed, 8);
}

#[test]
fn obj_corners_may_name_different_normals_for_one_vertex() {
    // A flat-shaded cube written with `v//n`: each face's corners name
    // its own normal, so a vertex has three; each corner keeps its own.
    // And the normals given against the winding (all negated) are turned
    // to the side the faces face.
    let face_normals = [
        [0.0, 0.0, -1.0],
        [0.0, 0.0, 1.0],
        [0.0, -1.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
    ];
    for sign in [1.0, -1.0] {
        let mut s = String::new();
        for i in 0..8 {
            let [x, y, z] = cube_vertex(i);
            s += &format!("v {x} {y} {z}\n");
        }
        for n in face_normals {
            // Tilted a little toward +x +y so the file's normals are not
            // the computed ones.
            let t = normalize([n[0] + 0.2, n[1] + 0.1, n[2]]);
            s += &format!("vn {} {} {}\n", sign * t[0], sign * t[1], sign * t[2]);
        }
        for (k, f) in CUBE_FACES.iter().enumerate() {
            s.push('f');
            for &i in f {
                s += &format!(" {}//{}", i + 1, k as i64 - 6);
            }
            s.push('\n');
        }
        let m = load_bytes(MeshFormat::Obj, s.as_bytes()).expect("cube");
        for (source, pos, n) in corners(&smooth_tree(m)) {
            let f = face_normals[source as usize];
            let want = q(normalize([f[0] + 0.2, f[1] + 0.1, f[2]]));
            assert!(
                close(n, want),
                "sign {sign}, face {source} at {pos:?}: {n:?}"
            );
        }
    }
}

/// An ASCII PLY of the cube with `nx ny nz` per vertex (the diagonals).
fn cube_ply() -> String {
    let mut s = String::from(
        "ply\nformat ascii 1.0\nelement vertex 8\n\
         property float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\n\
         element face 6\nproperty list uchar int vertex_indices\nend_header\n",
    );
    for i in 0..8 {
        let [x, y, z] = cube_vertex(i);
        let [a, b, c] = diagonal(i);
        s += &format!("{x} {y} {z} {a} {b} {c}\n");
    }
    for f in CUBE_FACES {
        s += &format!("4 {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    s
}

#[test]
fn ply_normals_are_stored_as_the_file_gives_them() {
    let m = load_bytes(MeshFormat::Ply, cube_ply().as_bytes()).expect("cube");
    let c = corners(&smooth_tree(m));
    assert_eq!(c.len(), 24);
    for (source, pos, n) in c {
        assert!(
            close(n, q(diagonal(cube_index(pos)))),
            "face {source} at {pos:?}: {n:?}"
        );
    }
    // Without the normal properties: the crease normals (the faces' own).
    let plain = cube_ply().replace(
        "property float nx\nproperty float ny\nproperty float nz\n",
        "",
    );
    let plain: String = plain
        .lines()
        .map(|l| {
            let w: Vec<&str> = l.split(' ').collect();
            if w.len() == 6 {
                format!("{} {} {}\n", w[0], w[1], w[2])
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    let m = load_bytes(MeshFormat::Ply, plain.as_bytes()).expect("plain cube");
    for (source, _, n) in corners(&smooth_tree(m)) {
        let axis = [0, 1, 2].iter().filter(|&&k| n[k] != 0).count();
        assert_eq!(axis, 1, "face {source}: a face normal, got {n:?}");
    }
}

/// A vertex of a test file: position and normal.
type Corner = ([f64; 3], [f64; 3]);

/// Two squares crossing at right angles (planes x = 0, facing +x, and
/// y = 0, facing −y; both spanning z in [−1, 1]), open, each corner with
/// its own normal from the PLY file (on the side its face faces): no order draws them without cutting one by the
/// other's plane, whose new vertices lie halfway along its edges.
fn cross_ply() -> (String, Vec<Corner>) {
    let verts: Vec<Corner> = vec![
        ([0.0, -1.0, -1.0], [1.0, -0.6, -0.3]),
        ([0.0, 1.0, -1.0], [1.0, 0.5, -0.2]),
        ([0.0, 1.0, 1.0], [1.0, 0.4, 0.6]),
        ([0.0, -1.0, 1.0], [1.0, -0.3, 0.5]),
        ([-1.0, 0.0, -1.0], [-0.4, -1.0, -0.5]),
        ([1.0, 0.0, -1.0], [0.7, -1.0, -0.1]),
        ([1.0, 0.0, 1.0], [0.2, -1.0, 0.8]),
        ([-1.0, 0.0, 1.0], [-0.6, -1.0, 0.3]),
    ];
    let mut s = String::from(
        "ply\nformat ascii 1.0\nelement vertex 8\n\
         property double x\nproperty double y\nproperty double z\n\
         property double nx\nproperty double ny\nproperty double nz\n\
         element face 2\nproperty list uchar int vertex_indices\nend_header\n",
    );
    for (p, n) in &verts {
        s += &format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], n[0], n[1], n[2]);
    }
    s += "4 0 1 2 3\n4 4 5 6 7\n";
    (s, verts)
}

#[test]
fn split_vertices_get_normals_interpolated_along_the_edge() {
    let (text, verts) = cross_ply();
    let m = load_bytes(MeshFormat::Ply, text.as_bytes()).expect("cross");
    assert!(!m.closed);
    let c = corners(&smooth_tree(m));
    assert!(c.len() > 8, "one square is split: {} corners", c.len());
    let mut interpolated = 0;
    for (source, pos, n) in c {
        let face = &verts[4 * source as usize..4 * source as usize + 4];
        let dist =
            |a: [f64; 3], b: [f64; 3]| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
        let want = match face.iter().find(|(p, _)| dist(*p, pos) < 1e-6) {
            Some(&(_, fn_)) => q(normalize(fn_)),
            None => {
                // On an edge of the face: the normals of its ends, mixed
                // by where it lies.
                let (k, t) = (0..4)
                    .map(|k| {
                        let (a, b) = (face[k].0, face[(k + 1) % 4].0);
                        let len = dist(a, b);
                        let t = dist(a, pos) / len;
                        let off = (dist(a, pos) + dist(pos, b) - len).abs();
                        (k, t, off)
                    })
                    .filter(|&(_, _, off)| off < 1e-6)
                    .map(|(k, t, _)| (k, t))
                    .next()
                    .unwrap_or_else(|| panic!("face {source}: {pos:?} is on no edge"));
                let (na, nb) = (normalize(face[k].1), normalize(face[(k + 1) % 4].1));
                interpolated += 1;
                q([0, 1, 2].map(|i| na[i] + (nb[i] - na[i]) * t))
            }
        };
        assert!(
            close(n, want),
            "face {source} at {pos:?}: {n:?}, want {want:?}"
        );
    }
    assert!(interpolated >= 2, "the cut's ends are new vertices");
}
