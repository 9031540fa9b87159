//! The no_std render against the float64 reference z-buffer on the
//! project's procedural scenes (including a copy 1e3 times larger and 1e5
//! away from the origin) and on generated hard cases: polygons far larger
//! than the screen crossing the near plane, faces seen exactly edge-on,
//! a jittered triangle mesh (shared edges everywhere) and near-coplanar
//! plates. Every case: 30+ seeded views, no wrong pixel away from edges,
//! no crack (the builder leaves no T-junction: `host_sim::seams`).

use crate::render_common;

use fpt_nostd::raster::{
    FixedMicromath, FixedPrecision, FloatLibm, FloatMicromath, IntPrecision, Precision,
};
use fpt_tests::{random_cameras, Rng};
use glam::DVec3;
use host_sim::geom::{bounds, Polygon};
use host_sim::reference::{Camera, Projection};
use host_sim::scenes::{self, Scene};
use render_common::{assert_clean, check_views, check_views_with};

const VIEWS: usize = 30;
const W: usize = 96;
const H: usize = 80;

/// Asserts the tree's picture has no wrong pixel and no crack.
fn check(name: &str, polys: &[Polygon], closed: bool, cams: &[Camera]) {
    let rep = check_views(name, polys, closed, cams, W, H);
    assert_clean(name, &rep);
}

fn check_scene(s: &Scene, seed: u64) {
    let cams = random_cameras(&s.polygons, VIEWS, seed);
    check(&s.name, &s.polygons, s.closed, &cams);
}

fn scene(name: &str) -> Scene {
    match scenes::all().into_iter().find(|s| s.name == name) {
        Some(s) => s,
        None => panic!("no scene {name}"),
    }
}

#[test]
fn cube_grid() {
    check_scene(&scenes::cube_grid(), 11);
}

#[test]
fn near_coplanar_stack() {
    check_scene(&scenes::near_coplanar_stack(), 12);
}

#[test]
fn slivers() {
    check_scene(&scenes::slivers(), 13);
}

#[test]
fn open_sheet() {
    check_scene(&scenes::open_sheet(), 14);
}

#[test]
fn interpenetrating_boxes() {
    check_scene(&scenes::interpenetrating_boxes(), 15);
}

#[test]
fn gear() {
    check_scene(&scenes::gear(), 16);
}

#[test]
fn house() {
    check_scene(&scenes::house(), 17);
}

#[test]
fn vise_huge_and_far_from_the_origin() {
    check_scene(&scene("vise_huge"), 18);
}

#[test]
fn house_tiny() {
    check_scene(&scene("house_tiny"), 19);
}

fn quad(c: [DVec3; 4], source: u32) -> Polygon {
    match Polygon::new(c.to_vec(), source, [200, 180, 90]) {
        Some(p) => p,
        None => panic!("degenerate quad"),
    }
}

/// An open scene: a ground square 2e4 wide, a unit box standing on it (its
/// faces single-sided, outward) and a wall 1e3 high behind it.
fn huge_ground() -> Vec<Polygon> {
    let g = 1e4;
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mut p = vec![
        quad(
            [v(-g, -g, 0.0), v(g, -g, 0.0), v(g, g, 0.0), v(-g, g, 0.0)],
            0,
        ),
        quad(
            [
                v(-g, 5.0, 0.0),
                v(g, 5.0, 0.0),
                v(g, 5.0, 1e3),
                v(-g, 5.0, 1e3),
            ],
            1,
        ),
    ];
    let (a, b) = (v(-0.5, -0.5, 0.01), v(0.5, 0.5, 1.0));
    let c = |i: usize| {
        v(
            if i & 1 == 0 { a.x } else { b.x },
            if i & 2 == 0 { a.y } else { b.y },
            if i & 4 == 0 { a.z } else { b.z },
        )
    };
    for f in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ] {
        let n = p.len() as u32;
        p.push(quad([c(f[0]), c(f[1]), c(f[2]), c(f[3])], n));
    }
    p
}

#[test]
fn huge_polygons_crossing_the_near_plane() {
    let polys = huge_ground();
    let mut rng = Rng(21);
    let mut cams = Vec::new();
    while cams.len() < VIEWS {
        // Eyes a little above the ground near the box, looking down across
        // the ground (which then reaches behind the eye and far off screen).
        // Parallel views keep all of the ground between their near and far
        // planes: the renderer does not near-clip a parallel view.
        let eye = DVec3::new(
            rng.range(-4.0, 4.0),
            rng.range(-4.0, 3.0),
            rng.range(0.05, 3.0),
        );
        let target = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(0.0, 0.8),
        );
        let proj = if cams.len() % 4 == 3 {
            Projection::Parallel {
                half_height: rng.range(1.0, 4.0),
                near: -1e5,
                far: 1e5,
            }
        } else {
            Projection::Perspective {
                fov_y_deg: rng.range(40.0, 110.0),
                near: 1e-3,
                far: 1e5,
            }
        };
        let eye = if matches!(proj, Projection::Parallel { .. }) {
            target + (eye - target) * 20.0
        } else {
            eye
        };
        if let Some(c) = Camera::look_at(eye, target, DVec3::Z, proj, W as f64 / H as f64) {
            cams.push(c);
        }
    }
    check("huge_ground", &polys, false, &cams);
}

#[test]
fn faces_seen_exactly_edge_on() {
    let s = scenes::cube_grid();
    let (lo, hi) = bounds(&s.polygons);
    let c = (lo + hi) * 0.5;
    let r = (hi - lo).length() * 0.5;
    let mut cams = Vec::new();
    // Parallel views along the axes: every axis-aligned face is either
    // straight on or exactly edge-on.
    for dir in [
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ] {
        let up = if dir.z.abs() > 0.5 {
            DVec3::Y
        } else {
            DVec3::Z
        };
        let p = Projection::Parallel {
            half_height: r,
            near: 0.0,
            far: 6.0 * r,
        };
        cams.extend(Camera::look_at(
            c - dir * 3.0 * r,
            c,
            up,
            p,
            W as f64 / H as f64,
        ));
    }
    // Perspective eyes exactly in the planes of faces (a vertex's
    // coordinate), looking across them.
    let mut rng = Rng(22);
    while cams.len() < VIEWS {
        let v = s.polygons[rng.below(s.polygons.len())].verts[0];
        let axis = rng.below(3);
        let mut eye = c + rng.unit() * (2.5 * r);
        eye[axis] = v[axis];
        let mut target = c + rng.unit() * (0.3 * r);
        target[axis] = v[axis];
        let p = Projection::Perspective {
            fov_y_deg: 60.0,
            near: 1e-3 * r,
            far: 20.0 * r,
        };
        cams.extend(Camera::look_at(
            eye,
            target,
            rng.unit(),
            p,
            W as f64 / H as f64,
        ));
    }
    check("cube_grid_edge_on", &s.polygons, s.closed, &cams);
}

/// A jittered 14 × 14 height field of triangles (open): every interior
/// edge shared by two triangles, every interior vertex by six.
fn triangle_terrain() -> Vec<Polygon> {
    let n = 14;
    let mut rng = Rng(23);
    let mut pts = vec![vec![DVec3::ZERO; n + 1]; n + 1];
    for (j, row) in pts.iter_mut().enumerate() {
        for (i, p) in row.iter_mut().enumerate() {
            let jit = if i > 0 && i < n && j > 0 && j < n {
                0.3
            } else {
                0.0
            };
            *p = DVec3::new(
                i as f64 + rng.range(-jit, jit),
                j as f64 + rng.range(-jit, jit),
                (i as f64 * 0.7).sin() * (j as f64 * 0.5).cos() * 1.5 + rng.range(-0.2, 0.2),
            );
        }
    }
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (pts[j][i], pts[j][i + 1], pts[j + 1][i + 1], pts[j + 1][i]);
            for t in [[a, b, c], [a, c, d]] {
                let k = out.len() as u32;
                out.extend(Polygon::new(t.to_vec(), k, [90, 160, 70]));
            }
        }
    }
    out
}

#[test]
fn shared_edges_of_a_triangle_mesh() {
    let polys = triangle_terrain();
    let cams = random_cameras(&polys, VIEWS, 24);
    check("terrain", &polys, false, &cams);
}

fn precision<P: Precision>(label: &str) {
    let s = scenes::interpenetrating_boxes();
    let cams = random_cameras(&s.polygons, VIEWS, 25);
    let rep = check_views_with::<P>(label, &s.polygons, s.closed, &cams, W, H);
    assert_clean(label, &rep);
}

#[test]
fn every_arithmetic_configuration() {
    precision::<FixedPrecision<0>>("fixed-subpx-0");
    precision::<FixedPrecision<8>>("fixed-subpx-8");
    precision::<FixedMicromath<4>>("fixed-micromath-subpx-4");
    precision::<FloatLibm<2>>("f32-libm-subpx-2");
    precision::<FloatLibm<6>>("f32-libm-subpx-6");
    precision::<FloatMicromath<4>>("f32-micromath-subpx-4");
    precision::<IntPrecision<4>>("int-subpx-4");
    precision::<IntPrecision<8>>("int-subpx-8");
}
