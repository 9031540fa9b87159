//! Unit tests of the reference renderer.

use super::*;

/// An axis-aligned square in the plane z = `z`, facing +z (or −z).
fn square(cx: f64, cy: f64, half: f64, z: f64, up: bool, source: u32) -> Polygon {
    let mut v = vec![
        DVec3::new(cx - half, cy - half, z),
        DVec3::new(cx + half, cy - half, z),
        DVec3::new(cx + half, cy + half, z),
        DVec3::new(cx - half, cy + half, z),
    ];
    if !up {
        v.reverse();
    }
    Polygon::new(v, source, [255, 255, 255]).unwrap()
}

/// Parallel camera above the origin looking down, [-1, 1]² on screen.
fn from_above() -> Camera {
    let p = Projection::Parallel {
        half_height: 1.0,
        near: 0.0,
        far: 10.0,
    };
    Camera::look_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y, p, 1.0).unwrap()
}

/// Perspective camera below the origin looking up.
fn from_below() -> Camera {
    let p = Projection::Perspective {
        fov_y_deg: 90.0,
        near: 0.1,
        far: 20.0,
    };
    Camera::look_at(DVec3::new(0.0, 0.0, -1.5), DVec3::ZERO, DVec3::Y, p, 1.0).unwrap()
}

/// Two overlapping squares: A (index 0, x ∈ [-0.71, 0.29]) low and B
/// (index 1, x ∈ [-0.29, 0.71]) high.
fn two_squares() -> Vec<Polygon> {
    vec![
        square(-0.21, 0.0, 0.5, 0.0, true, 0),
        square(0.21, 0.0, 0.5, 0.5, true, 1),
    ]
}

/// Pixel index of model point (x, y) under `from_above` in a 40 × 40 image.
fn px(x: f64, y: f64) -> usize {
    let i = ((x + 1.0) * 20.0) as usize;
    let j = ((1.0 - y) * 20.0) as usize;
    j * 40 + i
}

#[test]
fn zbuffer_keeps_the_nearer_of_two_overlapping_squares() {
    let polys = two_squares();
    let ids = zbuffer_ids(&polys, &from_above(), 40, 40, false);
    assert_eq!(ids[px(0.0, 0.0)], 2, "overlap: B is nearer from above");
    assert_eq!(ids[px(-0.6, 0.0)], 1, "only A");
    assert_eq!(ids[px(0.6, 0.0)], 2, "only B");
    assert_eq!(ids[px(0.9, 0.9)], 0, "background");
    // From below A is nearer; with culling both face away and vanish.
    let cam = from_below();
    let ids = zbuffer_ids(&polys, &cam, 40, 40, false);
    assert_eq!(ids[20 * 40 + 20], 1);
    let culled = zbuffer_ids(&polys, &cam, 40, 40, true);
    assert!(culled.iter().all(|&i| i == 0));
}

#[test]
fn painter_matches_zbuffer_for_a_correct_order_only() {
    let polys = two_squares();
    for (cam, good, bad) in [
        (from_above(), [0u32, 1], [1u32, 0]),
        (from_below(), [1, 0], [0, 1]),
    ] {
        let frame = zbuffer(&polys, &cam, 40, 40, RefOptions::default());
        let right = painter_ids(&polys, &[vec![good[0]], vec![good[1]]], &cam, 40, 40);
        let d = frame.diff(&right);
        assert_eq!(d.wrong, 0, "{d:?}");
        assert!(d.compared > 1000, "{d:?}");
        let wrong = painter_ids(&polys, &[vec![bad[0]], vec![bad[1]]], &cam, 40, 40);
        let d = frame.diff(&wrong);
        assert!(d.wrong > 50, "a wrong order must show: {d:?}");
    }
}

#[test]
fn outlines_are_marked_only_where_they_may_matter() {
    let polys = two_squares();
    let frame = zbuffer(&polys, &from_above(), 40, 40, RefOptions::default());
    // Column i samples x = (i + 0.5)/20 - 1. B's left edge at x = -0.29 is
    // in front: column 14 (0.3 px away) is marked, column 13 (0.7 px) is
    // not. A's right edge at x = 0.29 lies under B, clearly behind: column
    // 25 (0.3 px away) is not marked.
    let at = |i: usize| frame.near_edge[20 * 40 + i];
    assert!(at(14) && !at(13));
    assert!(!at(25) && !at(26));
    assert!(!at(20) && !at(8));
    assert!(!frame.tie.iter().any(|&t| t));
}

#[test]
fn coincident_faces_are_ties() {
    let polys = vec![
        square(0.0, 0.0, 0.5, 0.2, true, 0),
        square(0.1, 0.0, 0.5, 0.2, true, 1),
    ];
    let frame = zbuffer(&polys, &from_above(), 40, 40, RefOptions::default());
    assert!(frame.tie[px(0.0, 0.0)]);
    assert!(!frame.tie[px(-0.45, 0.0)]);
}

#[test]
fn polygon_reaching_behind_the_eye_is_drawn_in_front_only() {
    // A long floor under a perspective eye, reaching far behind it, and a
    // wall in front: the floor fills the lower half up to the wall.
    let p = Projection::Perspective {
        fov_y_deg: 90.0,
        near: 0.01,
        far: 100.0,
    };
    let cam = Camera::look_at(DVec3::ZERO, -DVec3::Z, DVec3::Y, p, 1.0).unwrap();
    let floor = Polygon::new(
        vec![
            DVec3::new(-10.0, -1.0, 10.0),
            DVec3::new(10.0, -1.0, 10.0),
            DVec3::new(10.0, -1.0, -10.0),
            DVec3::new(-10.0, -1.0, -10.0),
        ],
        0,
        [0; 3],
    )
    .unwrap();
    let wall = Polygon::new(
        vec![
            DVec3::new(-1.0, -2.0, -2.0),
            DVec3::new(1.0, -2.0, -2.0),
            DVec3::new(1.0, 2.0, -2.0),
            DVec3::new(-1.0, 2.0, -2.0),
        ],
        1,
        [0; 3],
    )
    .unwrap();
    let polys = vec![floor, wall];
    let frame = zbuffer(&polys, &cam, 32, 32, RefOptions::default());
    // Bottom row, centre: the floor just ahead of the eye.
    assert_eq!(frame.ids[31 * 32 + 16], 1);
    // Centre: the wall, which hides the floor beyond z = -2.
    assert_eq!(frame.ids[17 * 32 + 16], 2);
    // Top left corner: nothing (the wall spans ±0.5 of the screen).
    assert_eq!(frame.ids[0], 0);
    // The floor is in front of the wall's lower part only where the ray
    // meets the floor before z = -2: rows below the image of (y=-1, z=-2).
    assert_eq!(frame.ids[25 * 32 + 16], 1);
}

#[test]
fn camera_from_matrix_renders_like_look_at() {
    let polys = two_squares();
    let cam = from_below();
    let again = Camera::from_mvp(cam.mvp()).unwrap();
    let a = zbuffer_ids(&polys, &cam, 24, 24, false);
    let b = zbuffer_ids(&polys, &again, 24, 24, false);
    assert_eq!(a, b);
    assert!(a.contains(&1) && a.contains(&2));
}

#[test]
fn culled_faces_seen_almost_edge_on_make_their_outline_unsure() {
    // A quad in the plane x = 0.01 tilted by 1e-9 rad, turned just away
    // from a camera looking straight down: culled, yet a walk rounding its
    // facing test differently could draw it along the line x = 0.01.
    let mut v = vec![
        DVec3::new(0.01 - 1e-9 * -0.5, -0.5, -0.5),
        DVec3::new(0.01 - 1e-9 * -0.5, 0.5, -0.5),
        DVec3::new(0.01 - 1e-9 * 0.5, 0.5, 0.5),
        DVec3::new(0.01 - 1e-9 * 0.5, -0.5, 0.5),
    ];
    let cam = from_above();
    let p = Polygon::new(v.clone(), 0, [0; 3]).unwrap();
    if cam.view().faces(&p.plane) {
        v.reverse();
    }
    let polys = vec![Polygon::new(v, 0, [0; 3]).unwrap()];
    assert!(!cam.view().faces(&polys[0].plane));
    let opt = RefOptions {
        cull_backfaces: true,
        ..RefOptions::default()
    };
    let frame = zbuffer(&polys, &cam, 40, 40, opt);
    assert!(frame.ids.iter().all(|&i| i == 0));
    // Column 20 samples x = 0.025, 0.3 px from the line; column 22 is far.
    assert!(frame.near_edge[20 * 40 + 20] && !frame.near_edge[20 * 40 + 22]);
    let strict = RefOptions {
        edge_on_rel: 0.0,
        ..opt
    };
    let frame = zbuffer(&polys, &cam, 40, 40, strict);
    assert!(!frame.near_edge.contains(&true));
}
