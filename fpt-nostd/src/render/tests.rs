//! Tests of the tree renderer glue on small hand-made trees.

extern crate std;

use std::string::ToString;
use std::vec;
use std::vec::Vec;

use embedded_graphics::pixelcolor::{GrayColor, Rgb565, Rgb888};

use super::frame::{dot3, eval_row};
use super::*;
use crate::order::OrderError;
use crate::raster::{Camera, FramebufferError, Mat4, Precision};
use crate::raster::{
    DefaultPrecision, FixedPrecision, FloatLibm, Gray8Framebuffer, IdBuffer, Libm, Light, Orbit,
    Rgb888Framebuffer, ShadeMode,
};
use crate::reader::Tree;
use crate::test_util::{two_floors, Raw};

/// Two unit squares facing +z at z = 1 (source 10) and z = 0 (source 20),
/// stored relative to `origin`.
fn floors(origin: [f64; 3]) -> Vec<u8> {
    let mut r: Raw = two_floors();
    r.origin = origin;
    r.bytes()
}

fn tree(bytes: &[u8]) -> Tree<'_> {
    match Tree::from_bytes(bytes) {
        Ok(t) => t,
        Err(e) => panic!("{e:?}"),
    }
}

/// An orbit around the squares' centre (model coordinates).
fn orbit(origin: [f64; 3], yaw: f32, fov: f32) -> Orbit {
    let t = [
        (origin[0] + 0.5) as f32,
        (origin[1] + 0.5) as f32,
        (origin[2] + 0.5) as f32,
    ];
    Orbit::new(t, yaw, 0.0, 4.0, fov)
}

/// Ids (source + 1 or polygon + 1) of a 32 × 32 render.
fn ids<P: Precision>(t: &Tree<'_>, cam: &Camera, which: FaceIds) -> Vec<u32> {
    let mut buf = vec![0u32; 32 * 32];
    let mut sink = match IdBuffer::new(&mut buf, 32, 32) {
        Ok(s) => s,
        Err(e) => panic!("{e:?}"),
    };
    let Some(mut r) = TreeRenderer::<P, 16>::new(32, 32) else {
        panic!("renderer")
    };
    r.ids = which;
    if let Err(e) = r.render::<8, _>(t, &Frame::new(t, cam), &mut sink) {
        panic!("{e:?}");
    }
    buf
}

#[test]
fn matrix_view_recovers_orbit_eye_and_direction() {
    for (yaw, pitch) in [(0.3f32, 0.2f32), (2.5, -1.1), (-1.0, 1.5)] {
        let o = Orbit::new([1.0, -2.0, 3.0], yaw, pitch, 7.0, 0.8);
        let d = o.eye_direction::<Libm>();
        let want = [1.0 + 7.0 * d[0], -2.0 + 7.0 * d[1], 3.0 + 7.0 * d[2]];
        match MatrixView::of(&rows_f64(&o.camera::<Libm>(1.3).matrix), [1.0, -2.0, 3.0]) {
            MatrixView::Perspective { eye } => {
                for i in 0..3 {
                    assert!(
                        (eye[i] - f64::from(want[i])).abs() < 1e-4,
                        "{eye:?} {want:?}"
                    );
                }
            }
            v => panic!("{v:?}"),
        }
        let par = Orbit::new([1.0, -2.0, 3.0], yaw, pitch, 7.0, 0.0);
        match MatrixView::of(&rows_f64(&par.camera::<Libm>(1.3).matrix), [1.0, -2.0, 3.0]) {
            MatrixView::Parallel { dir } => {
                // Looking from the eye toward the target: along −d.
                let len = libm::sqrt(dot3(dir, dir));
                for i in 0..3 {
                    assert!(
                        (dir[i] / len + f64::from(d[i])).abs() < 1e-5,
                        "{dir:?} {d:?}"
                    );
                }
            }
            v => panic!("{v:?}"),
        }
    }
}

#[test]
fn eye_of_an_arbitrary_matrix_zeroes_x_y_and_w() {
    let m = Mat4([
        [0.9, -0.2, 0.4, 1.5],
        [0.1, 1.1, -0.3, -0.7],
        [0.2, 0.3, 0.8, 2.0],
        [-0.3, 0.25, 0.6, 4.0],
    ]);
    let MatrixView::Perspective { eye } = MatrixView::of(&rows_f64(&m), [0.0; 3]) else {
        panic!("perspective expected")
    };
    let r = rows_f64(&m);
    for row in [0, 1, 3] {
        assert!(eval_row(r[row], eye).abs() < 1e-9, "row {row}: {eye:?}");
    }
    // Dependent x, y, w rows: no centre of projection.
    let mut flat = m;
    flat.0[1] = flat.0[0];
    assert_eq!(
        MatrixView::of(&rows_f64(&flat), [0.0; 3]),
        MatrixView::Degenerate
    );
}

#[test]
fn near_threshold_matches_the_near_plane() {
    let bytes = floors([0.0; 3]);
    let t = tree(&bytes);
    let o = Orbit::new([0.0; 3], 0.4, 0.3, 10.0, 0.9);
    let cam = o.camera::<Libm>(1.0);
    let near = near_w_for(&rows_f64(&cam.matrix), &t);
    assert!(
        (near - o.near).abs() < 1e-3 * o.near,
        "{near} vs {}",
        o.near
    );
    let par = Orbit::new([0.0; 3], 0.4, 0.3, 10.0, 0.0).camera::<Libm>(1.0);
    assert_eq!(near_w_for(&rows_f64(&par.matrix), &t), 0.5);
    // Nonsense matrices still give a positive, finite threshold.
    for m in [
        Mat4([[0.0; 4]; 4]),
        Mat4([[f32::NAN; 4]; 4]),
        Mat4([[1e30; 4]; 4]),
    ] {
        let n = near_w_for(&rows_f64(&m), &t);
        assert!(n > 0.0 && n.is_finite(), "{n}");
    }
}

#[test]
fn frame_keeps_every_projected_point_and_normalises_the_matrix() {
    let origin = [12345.5, -3000.25, 7.0];
    let bytes = floors(origin);
    let t = tree(&bytes);
    let cam = orbit(origin, 0.7, 0.9).camera::<Libm>(1.0);
    let f = Frame::new(&t, &cam);
    let big = f
        .camera
        .matrix
        .0
        .iter()
        .flatten()
        .fold(0.0f32, |m, v| m.max(v.abs()));
    assert!((8192.0..16384.0).contains(&big), "{big}");
    // Radius 2 → s = 2^-12: the radius becomes 2^13.
    assert_eq!(t.bounding_radius(), 2.0);
    assert_eq!(f.vertex_scale, 4096.0);
    let full = rows_f64(&cam.matrix);
    let mine = rows_f64(&f.camera.matrix);
    for v in [[0.0, 0.0, 1.0], [1.0, 1.0, 0.0], [0.3, -0.8, 0.5]] {
        let model = [origin[0] + v[0], origin[1] + v[1], origin[2] + v[2]];
        let a = full.map(|r| eval_row(r, model));
        let b = mine.map(|r| eval_row(r, v.map(|c| c * f64::from(f.vertex_scale))));
        for i in [0, 1] {
            assert!((a[i] / a[3] - b[i] / b[3]).abs() < 1e-3, "{a:?} {b:?}");
        }
        // w and the near threshold scale together.
        let ka = a[3] / f64::from(cam.near_w);
        let kb = b[3] / f64::from(f.camera.near_w);
        assert!((ka / kb - 1.0).abs() < 1e-3, "{ka} {kb}");
    }
}

#[test]
fn nearer_square_wins_from_either_side_far_from_the_origin() {
    for origin in [[0.0; 3], [1000.5, -2000.25, 3.0]] {
        let bytes = floors(origin);
        let t = tree(&bytes);
        for fov in [0.6, 0.0] {
            let above = orbit(origin, 0.0, fov).camera::<Libm>(1.0);
            let below = orbit(origin, core::f32::consts::PI, fov).camera::<Libm>(1.0);
            let centre = 16 * 32 + 16;
            let a = ids::<DefaultPrecision>(&t, &above, FaceIds::Source);
            let b = ids::<FloatLibm<4>>(&t, &below, FaceIds::Source);
            assert_eq!((a[centre], a[0], a[1023]), (11, 0, 0), "{origin:?} {fov}");
            assert_eq!((b[centre], b[0], b[1023]), (21, 0, 0), "{origin:?} {fov}");
            let p = ids::<FixedPrecision<0>>(&t, &above, FaceIds::Polygon);
            assert_eq!(p[centre], 1);
            // The squares coincide in x, y: from straight on, the nearer one
            // hides the other completely.
            assert!(a.iter().all(|&v| v == 0 || v == 11));
            assert!(b.iter().all(|&v| v == 0 || v == 21));
        }
    }
}

#[test]
fn open_models_light_the_side_turned_to_the_viewer() {
    let bytes = floors([0.0; 3]);
    let t = tree(&bytes);
    let below = orbit([0.0; 3], core::f32::consts::PI, 0.6).camera::<Libm>(1.0);
    let mut px = vec![0u8; 32 * 32];
    let Some(mut r) = TreeRenderer::<DefaultPrecision, 16>::new(32, 32) else {
        panic!("renderer")
    };
    r.renderer.set_shade_mode(ShadeMode::Grey(200));
    // Light from below, where the viewer is: the seen side of the z = 0
    // square (normal +z) must be lit although its normal points away.
    r.renderer.set_light(Light::new([0.0, 0.0, -1.0], 0.0, 1.0));
    let mut fb = match Gray8Framebuffer::new(&mut px, 32, 32) {
        Ok(f) => f,
        Err(e) => panic!("{e:?}"),
    };
    let stats = match r.render::<8, _>(&t, &Frame::new(&t, &below), &mut fb) {
        Ok(s) => s,
        Err(e) => panic!("{e:?}"),
    };
    assert_eq!(stats.drawn, 2);
    assert_eq!(fb.pixel(16, 16).map(|c| c.luma()), Some(200));
    assert_eq!(fb.pixel(0, 0).map(|c| c.luma()), Some(0));
}

#[test]
fn bands_put_together_are_the_full_frame() {
    let bytes = floors([5.0, 6.0, 7.0]);
    let t = tree(&bytes);
    let (w, h) = (40u32, 30u32);
    for yaw in [0.4f32, 2.9] {
        let cam = orbit([5.0, 6.0, 7.0], yaw, 0.7).camera::<Libm>(w as f32 / h as f32);
        let Some(mut r) = TreeRenderer::<DefaultPrecision, 16>::new(w, h) else {
            panic!("renderer")
        };
        r.renderer.set_shade_mode(ShadeMode::Flat);
        let mut full = vec![0u8; (3 * w * h) as usize];
        let mut fb = match Rgb888Framebuffer::new(&mut full, w, h) {
            Ok(f) => f,
            Err(e) => panic!("{e:?}"),
        };
        if let Err(e) = r.render::<8, _>(&t, &Frame::new(&t, &cam), &mut fb) {
            panic!("{e:?}");
        }
        for rows in [1u32, 7, 30, 64] {
            let mut banded = vec![0xFFu8; (3 * w * h) as usize];
            let mut buf = vec![0u8; (3 * w * rows) as usize];
            let band = BandBuffer::<crate::raster::framebuffer::Rgb888Format> {
                buf: &mut buf,
                rows,
                background: Rgb888::new(0, 0, 0),
            };
            let res = r.render_banded::<8, _>(&t, &Frame::new(&t, &cam), band, |y0, fb| {
                let start = 3 * y0 as usize * w as usize;
                let d = fb.data();
                banded[start..start + d.len()].copy_from_slice(d);
            });
            assert!(res.is_ok(), "{res:?}");
            assert_eq!(banded, full, "yaw {yaw}, {rows} rows");
        }
        assert!(full.iter().any(|&p| p != 0));
    }
}

#[test]
fn band_buffer_too_small_is_an_error_not_a_panic() {
    let bytes = floors([0.0; 3]);
    let t = tree(&bytes);
    let cam = orbit([0.0; 3], 0.0, 0.6).camera::<Libm>(1.0);
    let Some(mut r) = TreeRenderer::<DefaultPrecision, 16>::new(32, 32) else {
        panic!("renderer")
    };
    let mut buf = vec![0u16; 10];
    let band = BandBuffer::<crate::raster::framebuffer::Rgb565Format> {
        buf: &mut buf,
        rows: 4,
        background: Rgb565::new(0, 0, 0),
    };
    let res = r.render_banded::<8, _>(&t, &Frame::new(&t, &cam), band, |_, _| {});
    assert_eq!(
        res,
        Err(RenderError::Band(FramebufferError::BufferTooSmall))
    );
}

#[test]
fn degenerate_cameras_render_without_error() {
    let bytes = floors([0.0; 3]);
    let t = tree(&bytes);
    let mats = [
        Mat4([[0.0; 4]; 4]),
        Mat4([[f32::NAN; 4]; 4]),
        Mat4([[f32::INFINITY; 4]; 4]),
        Mat4([[3e38; 4]; 4]),
        Mat4([[1e-38; 4]; 4]),
        Mat4::IDENTITY,
    ];
    for m in mats {
        for near in [f32::NAN, -1.0, 0.0, 1e-30, 1.0, f32::INFINITY] {
            let cam = Camera::from_matrix(m, near);
            let _ = ids::<DefaultPrecision>(&t, &cam, FaceIds::Source);
            let _ = ids::<FloatLibm<8>>(&t, &cam, FaceIds::Polygon);
        }
    }
}

#[test]
fn a_tree_deeper_than_the_stack_is_refused() {
    let bytes = floors([0.0; 3]);
    let t = tree(&bytes);
    let cam = orbit([0.0; 3], 0.0, 0.6).camera::<Libm>(1.0);
    let Some(mut r) = TreeRenderer::<DefaultPrecision, 16>::new(8, 8) else {
        panic!("renderer")
    };
    let mut buf = vec![0u32; 64];
    let mut sink = match IdBuffer::new(&mut buf, 8, 8) {
        Ok(s) => s,
        Err(e) => panic!("{e:?}"),
    };
    let res = r.render::<1, _>(&t, &Frame::new(&t, &cam), &mut sink);
    assert_eq!(
        res,
        Err(RenderError::Capacity(CapacityError::WalkDepth {
            need: 2,
            have: 1
        }))
    );
    // The walk itself refuses it too (for callers of `Order`).
    assert_eq!(
        crate::order::Order::<1>::check_depth(&t),
        Err(OrderError::StackTooSmall {
            depth: 2,
            capacity: 1
        })
    );
}

#[test]
fn too_small_a_vertex_capacity_is_refused_before_drawing() {
    let bytes = floors([0.0; 3]);
    let t = tree(&bytes);
    let cam = orbit([0.0; 3], 0.0, 0.6).camera::<Libm>(1.0);
    let need = t.capacities().vertices;
    // Quads: the header asks for 4 + 5.
    assert_eq!((t.capacities().polygon_vertices, need), (4, 9));
    let Some(mut r) = TreeRenderer::<DefaultPrecision, 8>::new(8, 8) else {
        panic!("renderer")
    };
    let mut buf = vec![0u32; 64];
    let mut sink = match IdBuffer::new(&mut buf, 8, 8) {
        Ok(s) => s,
        Err(e) => panic!("{e:?}"),
    };
    let res = r.render::<16, _>(&t, &Frame::new(&t, &cam), &mut sink);
    let err = RenderError::Capacity(CapacityError::Vertices { need: 9, have: 8 });
    assert_eq!(res, Err(err));
    assert_eq!(
        err.to_string(),
        "vertex capacity V = 8 is too small for the tree's polygons: V must be at least 9 \
         (TreeRenderer<P, 9>)"
    );
    // Nothing was drawn.
    assert!(buf.iter().all(|&w| w == 0));
}

#[test]
fn relative_and_f64_frames_give_the_same_picture() {
    let origin = [250.0, -40.5, 9.25];
    let bytes = floors(origin);
    let t = tree(&bytes);
    for yaw in [0.3f32, 2.8] {
        // The same orbit around the squares' centre, in model coordinates
        // and relative to the origin (the centre is (0.5, 0.5, 0.5) off it).
        let model = orbit(origin, yaw, 0.7).camera::<Libm>(1.0);
        let rel = Orbit::new([0.5, 0.5, 0.5], yaw, 0.0, 4.0, 0.7).camera::<Libm>(1.0);
        let render = |f: &Frame| {
            let mut buf = vec![0u32; 32 * 32];
            let mut sink = match IdBuffer::new(&mut buf, 32, 32) {
                Ok(s) => s,
                Err(e) => panic!("{e:?}"),
            };
            let Some(mut r) = TreeRenderer::<DefaultPrecision, 16>::new(32, 32) else {
                panic!("renderer")
            };
            if let Err(e) = r.render::<8, _>(&t, f, &mut sink) {
                panic!("{e:?}");
            }
            buf
        };
        let a = render(&Frame::new(&t, &model));
        let b = render(&Frame::relative(&t, &rel));
        let c = render(&Frame::from_f64(
            &t,
            &rows_f64(&model.matrix),
            f64::from(model.near_w),
        ));
        assert_eq!(a, c);
        // f32 rounding of the model-space matrix may move an edge by a
        // sub-pixel amount: allow a few edge pixels.
        let diff = a.iter().zip(&b).filter(|(x, y)| x != y).count();
        assert!(diff <= 8, "{diff}");
        assert!(a.iter().filter(|&&v| v != 0).count() > 50);
    }
}

#[test]
fn key_light_comes_from_the_viewer_up_and_left() {
    let bytes = floors([0.0; 3]);
    let t = tree(&bytes);
    for fov in [0.7f32, 0.0] {
        // Eye on +z, y up, x right.
        let cam = Orbit::new([0.0; 3], 0.0, 0.0, 5.0, fov).camera::<Libm>(1.0);
        let l = Frame::new(&t, &cam).key_light();
        assert!(l[2] > 0.5 && l[1] > 0.3 && l[0] < -0.2, "{l:?}");
    }
    let degenerate = Camera::from_matrix(Mat4([[0.0; 4]; 4]), 1.0);
    assert_eq!(Frame::new(&t, &degenerate).key_light(), [0.0, 0.0, 1.0]);
}

/// The band walk loads a polygon's points without its vertex indices
/// (`Renderer::load_cached_bare`) and, for a polygon whose own index does
/// not fit 16 bits, reads them from the tree (`renderer::vertex_indices`):
/// the indices `Renderer::load_cached` leaves in `scratch.active`, and the
/// same points.
#[test]
fn indices_from_the_tree_are_those_the_load_leaves() {
    let bytes = floors([0.0; 3]);
    let t = tree(&bytes);
    let Some(mut r) = TreeRenderer::<DefaultPrecision, 16>::new(8, 8) else {
        panic!("renderer")
    };
    let mut words = vec![0u32; t.vertex_count() as usize];
    let mut cache = crate::raster::vcache::VertexCache::new(&mut words);
    cache.clear();
    for v in 0..t.vertex_count() {
        let p = crate::raster::ScreenPt {
            x: 3 * v as i32 - 7,
            y: 11 - 2 * v as i32,
        };
        cache.set(v, Some(p));
    }
    for i in 0..t.polygon_count() {
        let vs = t.polygon_vertex_indices(i);
        let loaded = r
            .renderer
            .load_cached(&mut r.scratch, &mut cache, vs.clone(), |_| None);
        let Some((n, true)) = loaded else {
            panic!("{loaded:?}")
        };
        let (want, pts) = (
            r.scratch.active()[..n].to_vec(),
            r.scratch.screen()[..n].to_vec(),
        );
        r.scratch.active_mut().fill(u16::MAX);
        let bare = r.renderer.load_cached_bare(
            &mut r.scratch,
            &mut cache,
            vs,
            (|v: u32| v, |_: &_, _| None),
        );
        assert_eq!(bare, Some((n, true)));
        assert_eq!(&r.scratch.screen()[..n], &pts[..]);
        assert!(r.scratch.active().iter().all(|&a| a == u16::MAX));
        crate::raster::renderer::vertex_indices(&t, i, r.scratch.active_mut());
        assert_eq!(&r.scratch.active()[..n], &want[..], "polygon {i}");
        assert!(n >= 3);
    }
}
