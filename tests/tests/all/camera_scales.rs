//! Any scale through the library: a caller who builds the renderer's frame
//! with the public camera path (`Frame::from_f64` for a row-major `f64`
//! matrix, `Frame::new` for the `f32` camera when its matrix fits `f32`)
//! for a unit cube scaled by 1e-30 … 1e38 and moved by up to 1e10 of its
//! size gets the unit cube's picture: the same source id at every pixel
//! off the outlines; and so does the library's orbit
//! (`Orbit::camera`/`camera_up` around the bounding-sphere centre through
//! `Frame::relative`, and around the centre in model coordinates through
//! `Frame::new`), which composes in model space normalised by the
//! distance. (`host-sim/tests/all/cli_scale.rs` checks the same through
//! `fpt render`.)

use crate::render_common;

use fpt_nostd::raster::{Camera as RasterCamera, DefaultPrecision, Libm, Mat4, Orbit, Up};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{near_w_for, Frame};
use glam::DVec3;
use host_sim::build::{build, NoProgress};
use host_sim::reference::{differences_off_outlines, Camera, Projection};
use host_sim::serialize::{serialize, SerializeOptions};
use host_sim::tree::Method;
use render_common::render_ids;

const W: usize = 96;
const H: usize = 72;

/// The tree of the cube `offset + scale · [0, 1]^3`, faces outward.
fn cube(scale: f64, offset: DVec3) -> Vec<u8> {
    let v: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            let c = DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2));
            (offset + scale * c).to_array()
        })
        .collect();
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [1, 3, 7, 5],
        [0, 4, 6, 2],
    ]
    .map(|f| f.to_vec())
    .to_vec();
    let m = host_sim::mesh::from_faces(&v, &faces, None).expect("cube");
    let t = build(m.polygons, m.closed, Method::Static, 1, &mut NoProgress);
    serialize(&t, &SerializeOptions::default()).expect("serialize")
}

/// The unit cube's camera moved to the model `offset + scale · unit`:
/// `M · S(1/scale) · T(−offset)`, row-major.
fn rows(scale: f64, offset: DVec3, projection: Projection) -> [[f64; 4]; 4] {
    let cam = Camera::look_at(
        DVec3::new(2.2, 1.9, 2.6),
        DVec3::splat(0.5),
        DVec3::Y,
        projection,
        W as f64 / H as f64,
    )
    .expect("camera");
    let m = cam.mvp();
    let mut r = [[0.0; 4]; 4];
    for (i, row) in m.chunks_exact(4).enumerate() {
        let xyz = DVec3::new(row[0], row[1], row[2]);
        r[i] = [
            row[0] / scale,
            row[1] / scale,
            row[2] / scale,
            row[3] - xyz.dot(offset) / scale,
        ];
    }
    r
}

#[test]
fn every_scale_and_offset_draws_like_the_unit_cube_through_the_library() {
    let projections = [
        Projection::Perspective {
            fov_y_deg: 40.0,
            near: 0.05,
            far: 50.0,
        },
        Projection::Parallel {
            half_height: 1.2,
            near: 0.0,
            far: 50.0,
        },
    ];
    let unit = cube(1.0, DVec3::ZERO);
    let unit_tree = Tree::from_bytes(&unit).expect("tree");
    let offset_dir = DVec3::new(1.0, -0.7, 0.3);
    let mut checked = 0;
    for projection in projections {
        let r = rows(1.0, DVec3::ZERO, projection);
        let frame = Frame::from_f64(&unit_tree, &r, f64::from(near_w_for(&r, &unit_tree)));
        let want = render_ids::<DefaultPrecision>(&unit_tree, &frame, W, H);
        let faces: std::collections::HashSet<u32> = want.iter().copied().collect();
        assert_eq!(faces.len(), 4, "background and three faces");
        for scale in [1e-30, 1e-20, 1e-10, 1.0, 1e10, 1e20, 1e30, 1e38] {
            for ratio in [0.0, 1.0, 1e5, 1e10] {
                let offset = ratio * scale * offset_dir;
                if !offset.is_finite() || offset.abs().max_element() > 1e30 {
                    continue;
                }
                let bytes = cube(scale, offset);
                let tree = Tree::from_bytes(&bytes).expect("tree");
                let r = rows(scale, offset, projection);
                let near = f64::from(near_w_for(&r, &tree));
                let got =
                    render_ids::<DefaultPrecision>(&tree, &Frame::from_f64(&tree, &r, near), W, H);
                let wrong = differences_off_outlines(&want, &got, W);
                assert_eq!(
                    wrong, 0,
                    "from_f64 {scale:e} {ratio:e}: {wrong} pixels differ"
                );
                checked += 1;
                // The f32 camera, where its matrix is normal f32 numbers.
                let m32 = r.map(|row| row.map(|v| v as f32));
                let fits = m32
                    .iter()
                    .flatten()
                    .all(|v| v.is_finite() && (*v == 0.0 || v.is_normal()));
                if fits && offset == DVec3::ZERO {
                    let cam = RasterCamera::from_matrix(Mat4(m32), near as f32);
                    let got = render_ids::<DefaultPrecision>(&tree, &Frame::new(&tree, &cam), W, H);
                    let wrong = differences_off_outlines(&want, &got, W);
                    assert_eq!(wrong, 0, "Frame::new {scale:e}: {wrong} pixels differ");
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 40, "{checked} renders compared");
}

/// The library's orbit of `tree` (distance in bounding radii), around its
/// bounding-sphere centre: `Frame::relative`.
fn orbit_frame(tree: &Tree<'_>, (yaw, pitch, fov, up): (f32, f32, f32, Up), radii: f32) -> Frame {
    let o = Orbit::new([0.0; 3], yaw, pitch, radii * tree.bounding_radius(), fov);
    Frame::relative(tree, &o.camera_up::<Libm>(W as f32 / H as f32, up))
}

#[test]
fn every_scale_and_offset_draws_like_the_unit_cube_through_the_library_orbit() {
    // Yaw, pitch, fov (0: parallel), up axis.
    let views = [
        (0.5, 0.35, 0.7, Up::Y),
        (-1.05, 0.6, 0.0, Up::Y),
        (2.3, -0.4, 1.2, Up::Z),
        (0.9, 0.2, 0.5, Up::X),
    ];
    let unit = cube(1.0, DVec3::ZERO);
    let unit_tree = Tree::from_bytes(&unit).expect("tree");
    let offset_dir = DVec3::new(1.0, -0.7, 0.3);
    let mut checked = 0;
    for view in views {
        let want =
            render_ids::<DefaultPrecision>(&unit_tree, &orbit_frame(&unit_tree, view, 3.0), W, H);
        let faces: std::collections::HashSet<u32> = want.iter().copied().collect();
        assert!(
            faces.len() >= 3,
            "{view:?}: background and two or three faces"
        );
        for scale in [1e-30, 1e-20, 1e-10, 1.0, 1e10, 1e20, 1e30, 1e38] {
            for ratio in [0.0, 1.0, 1e5, 1e10] {
                let offset = ratio * scale * offset_dir;
                if !offset.is_finite() || offset.abs().max_element() > 1e30 {
                    continue;
                }
                let bytes = cube(scale, offset);
                let tree = Tree::from_bytes(&bytes).expect("tree");
                // 3 and 3.9 radii: at 1e38 the eye is then 3.4e38 model
                // units away, next to f32's largest number.
                for radii in [3.0, 3.9] {
                    let unit_want = if radii == 3.0 {
                        want.clone()
                    } else {
                        render_ids::<DefaultPrecision>(
                            &unit_tree,
                            &orbit_frame(&unit_tree, view, radii),
                            W,
                            H,
                        )
                    };
                    let got = render_ids::<DefaultPrecision>(
                        &tree,
                        &orbit_frame(&tree, view, radii),
                        W,
                        H,
                    );
                    let wrong = differences_off_outlines(&unit_want, &got, W);
                    assert_eq!(
                        wrong, 0,
                        "orbit {view:?} {radii} radii, {scale:e} {ratio:e}: {wrong} pixels differ"
                    );
                    checked += 1;
                }
                // In model coordinates, around the centre (`Frame::new`),
                // y up: where the centre is an exact enough `f32`.
                let (yaw, pitch, fov, up) = view;
                if ratio == 0.0 && up == Up::Y {
                    let c = tree.origin().map(|v| v as f32);
                    let o = Orbit::new(c, yaw, pitch, 3.0 * tree.bounding_radius(), fov);
                    let cam = o.camera::<Libm>(W as f32 / H as f32);
                    let got = render_ids::<DefaultPrecision>(&tree, &Frame::new(&tree, &cam), W, H);
                    let wrong = differences_off_outlines(&want, &got, W);
                    assert_eq!(
                        wrong, 0,
                        "Frame::new orbit {view:?} {scale:e}: {wrong} pixels differ"
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 100, "{checked} renders compared");
}
