//! End-to-end tests of the renderer: transform → clip → fill through every
//! precision configuration and every kind of target.

extern crate std;

use std::vec;
use std::vec::Vec;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Size};
use embedded_graphics::pixelcolor::{Gray8, Rgb565, Rgb888, RgbColor};
use embedded_graphics::Pixel;

use super::band::{band_starts, Band};
use super::camera::{Camera, Mat4, Orbit};
use super::framebuffer::{
    BinaryFramebuffer, Framebuffer, Gray8Framebuffer, PixelFormat, Rgb565Framebuffer,
    Rgb888Framebuffer,
};
use super::int_path::IntPath;
use super::precision::{
    Config, FixedPrecision, FloatLibm, FloatMicromath, IntPrecision, Libm, Precision,
};

/// The integer path with a vertex grid of 2^-8 (coordinates to ±128):
/// these scenes are in model units, not a normalised frame.
type Int8<const SUB: u32> = Config<IntPath<8>, Libm, SUB>;
use super::renderer::{Face, Outcome, RenderStats, Renderer, Scratch, SkipReason};
use super::scan::SpanSink;
use super::shade::{Light, ShadeMode};
use super::sink::{DrawTargetSink, IdBuffer};
use super::tests::{CountSink, Rng};

/// A model polygon.
#[derive(Clone, Debug)]
struct Poly {
    verts: Vec<[f32; 3]>,
    face: Face,
}

/// A jittered, triangulated grid in the plane y = 0 covering
/// `[-extent, extent]²`; interior vertices are shared bit-for-bit.
fn ground(n: usize, extent: f32, rng: &mut Rng) -> Vec<Poly> {
    let step = 2.0 * extent / n as f32;
    let mut pts = vec![vec![[0.0f32; 3]; n + 1]; n + 1];
    for (j, row) in pts.iter_mut().enumerate() {
        for (i, p) in row.iter_mut().enumerate() {
            let interior = i > 0 && i < n && j > 0 && j < n;
            let jit = if interior { 0.3 * step } else { 0.0 };
            let x = -extent + i as f32 * step + rng.float(-jit, jit);
            let z = -extent + j as f32 * step + rng.float(-jit, jit);
            *p = [x, 0.0, z];
        }
    }
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (pts[j][i], pts[j][i + 1], pts[j + 1][i + 1], pts[j + 1][i]);
            let id = out.len() as u32;
            let color = [(40 + 13 * i % 200) as u8, (60 + 29 * j % 190) as u8, 150];
            let face = |id| Face {
                normal: [0.0, 1.0, 0.0].into(),
                color,
                id,
                hidden_edges: 0,
            };
            out.push(Poly {
                verts: vec![a, b, c],
                face: face(id),
            });
            out.push(Poly {
                verts: vec![a, c, d],
                face: face(id + 1),
            });
        }
    }
    out
}

/// An axis-aligned box as six quads (outward normals).
fn cube(c: [f32; 3], h: f32, first_id: u32) -> Vec<Poly> {
    let v = |sx: f32, sy: f32, sz: f32| [c[0] + sx * h, c[1] + sy * h, c[2] + sz * h];
    let quads = [
        (
            [1.0, 0.0, 0.0],
            [
                v(1., -1., -1.),
                v(1., 1., -1.),
                v(1., 1., 1.),
                v(1., -1., 1.),
            ],
        ),
        (
            [-1.0, 0.0, 0.0],
            [
                v(-1., -1., -1.),
                v(-1., -1., 1.),
                v(-1., 1., 1.),
                v(-1., 1., -1.),
            ],
        ),
        (
            [0.0, 1.0, 0.0],
            [
                v(-1., 1., -1.),
                v(-1., 1., 1.),
                v(1., 1., 1.),
                v(1., 1., -1.),
            ],
        ),
        (
            [0.0, -1.0, 0.0],
            [
                v(-1., -1., -1.),
                v(1., -1., -1.),
                v(1., -1., 1.),
                v(-1., -1., 1.),
            ],
        ),
        (
            [0.0, 0.0, 1.0],
            [
                v(-1., -1., 1.),
                v(1., -1., 1.),
                v(1., 1., 1.),
                v(-1., 1., 1.),
            ],
        ),
        (
            [0.0, 0.0, -1.0],
            [
                v(-1., -1., -1.),
                v(-1., 1., -1.),
                v(1., 1., -1.),
                v(1., -1., -1.),
            ],
        ),
    ];
    quads
        .iter()
        .enumerate()
        .map(|(k, (n, q))| Poly {
            verts: q.to_vec(),
            face: Face {
                normal: (*n).into(),
                color: [200, (40 * k) as u8, 90],
                id: first_id + k as u32,
                hidden_edges: 0,
            },
        })
        .collect()
}

fn scene() -> Vec<Poly> {
    let mut rng = Rng(2024);
    let mut s = ground(12, 30.0, &mut rng);
    let n = s.len() as u32;
    s.extend(cube([0.5, 1.0, -1.0], 1.0, n));
    s
}

const W: u32 = 96;
const H: u32 = 64;

fn orbit() -> Orbit {
    Orbit::new([0.0, 0.5, 0.0], 0.6, 0.35, 6.0, 1.1)
}

fn render<P: Precision, K: SpanSink>(cam: &Camera, polys: &[Poly], sink: &mut K) -> RenderStats {
    let mut r = match Renderer::<P>::new(W, H, cam) {
        Some(r) => r,
        None => panic!("renderer"),
    };
    r.set_light(Light::new([0.3, 1.0, 0.5], 0.2, 0.8));
    let mut scratch = Scratch::<P, 64>::new();
    for p in polys {
        r.draw_polygon(&mut scratch, p.verts.iter().copied(), &p.face, sink);
    }
    r.stats()
}

/// Ray-cast reference: does the ray through pixel centre (i, j) hit the
/// plane y = 0 inside `[-extent, extent]²` at depth ≥ `near`? Independent
/// of the rasterizer (built from the orbit angles, libm trig).
fn ground_hit(o: &Orbit, near: f32, extent: f32, i: u32, j: u32) -> bool {
    let (sy, cy) = (libm::sin(o.yaw as f64), libm::cos(o.yaw as f64));
    let (sp, cp) = (libm::sin(o.pitch as f64), libm::cos(o.pitch as f64));
    let right = [cy, 0.0, -sy];
    let up = [-sy * sp, cp, -cy * sp];
    let fwd = [-cp * sy, -sp, -cp * cy];
    let d = o.distance as f64;
    let eye: Vec<f64> = (0..3).map(|k| o.target[k] as f64 - d * fwd[k]).collect();
    let focal = 1.0 / libm::tan(0.5 * o.fov as f64);
    let aspect = W as f64 / H as f64;
    let nx = (i as f64 + 0.5) / W as f64 * 2.0 - 1.0;
    let ny = 1.0 - (j as f64 + 0.5) / H as f64 * 2.0;
    let dir: Vec<f64> = (0..3)
        .map(|k| fwd[k] + nx * aspect / focal * right[k] + ny / focal * up[k])
        .collect();
    if dir[1] >= 0.0 {
        return false;
    }
    let t = -eye[1] / dir[1]; // depth along fwd, since dir·fwd = 1
    let (x, z) = (eye[0] + t * dir[0], eye[2] + t * dir[2]);
    t >= near as f64 && x.abs() <= extent as f64 && z.abs() <= extent as f64
}

/// Coverage against the reference: no crack (every pixel well inside the
/// reference region written), no leak (nothing well outside), and
/// disagreement only on the region's boundary, where snapping vertices to
/// sub-pixels legitimately moves edges. Returns (interior pixels,
/// boundary disagreements, pixels written more than once).
///
/// Overdraw is counted rather than forbidden: the fill itself never paints
/// a pixel twice across a shared edge (proved exactly in `tests.rs`), but
/// snapping a tiny far-away triangle to the pixel grid can fold it over its
/// neighbour, which then legitimately overlap. Callers bound it per
/// configuration.
fn check_ground<P: Precision>(o: &Orbit, cam: &Camera, extent: f32) -> (usize, usize, usize) {
    let mut rng = Rng(5);
    let polys = ground(16, extent, &mut rng);
    let mut s = CountSink::new(W as i32, H as i32);
    let stats = render::<P, _>(cam, &polys, &mut s);
    assert!(stats.clipped > 0, "the test must exercise near clipping");
    let refm: Vec<bool> = (0..W * H)
        .map(|k| ground_hit(o, cam.near_w, extent, k % W, k / W))
        .collect();
    let at = |x: i64, y: i64| {
        x < 0 || y < 0 || x >= W as i64 || y >= H as i64 || refm[(y * W as i64 + x) as usize]
    };
    let (mut inside, mut boundary_diffs, mut over) = (0, 0, 0);
    for y in 0..H as i64 {
        for x in 0..W as i64 {
            let c = s.at(x as i32, y as i32);
            over += (c > 1) as usize;
            let r = at(x, y);
            let interior = (-1..=1).all(|dy| (-1..=1).all(|dx| at(x + dx, y + dy) == r));
            if interior {
                assert_eq!(c >= 1, r, "crack or leak at ({x},{y})");
                inside += r as usize;
            } else if (c >= 1) != r {
                boundary_diffs += 1;
            }
        }
    }
    (inside, boundary_diffs, over)
}

#[test]
fn ground_grid_through_near_plane_has_no_crack_or_overdraw() {
    let o = orbit();
    let cam = o.camera::<super::precision::Libm>(W as f32 / H as f32);
    for (inside, diffs, over, max_over) in [
        with(check_ground::<FixedPrecision<4>>(&o, &cam, 40.0), 0),
        with(check_ground::<FixedPrecision<0>>(&o, &cam, 40.0), 20),
        with(check_ground::<FloatLibm<8>>(&o, &cam, 40.0), 0),
        with(check_ground::<FloatLibm<2>>(&o, &cam, 40.0), 0),
        with(check_ground::<Int8<4>>(&o, &cam, 40.0), 0),
        with(check_ground::<Int8<0>>(&o, &cam, 40.0), 20),
    ] {
        assert!(inside > (W * H / 3) as usize, "{inside}");
        assert!(diffs < 2 * W as usize, "{diffs}");
        assert!(over <= max_over, "{over} pixels overdrawn");
    }
}

fn with((a, b, c): (usize, usize, usize), d: usize) -> (usize, usize, usize, usize) {
    (a, b, c, d)
}

#[test]
fn visible_near_clip_cuts_the_floor_at_the_right_place() {
    // A large near distance puts the clip line inside the picture.
    let o = orbit();
    let mut cam = o.camera::<super::precision::Libm>(W as f32 / H as f32);
    cam.near_w = 3.5;
    let (inside, _, _) = check_ground::<FloatLibm<4>>(&o, &cam, 40.0);
    let (inside_fx, _, _) = check_ground::<FixedPrecision<4>>(&o, &cam, 40.0);
    assert!(inside > 500 && inside_fx > 500);
    // And the region really is smaller than without the cut.
    let full = (0..W * H)
        .filter(|k| ground_hit(&o, 0.006, 40.0, k % W, k / W))
        .count();
    let cut = (0..W * H)
        .filter(|k| ground_hit(&o, 3.5, 40.0, k % W, k / W))
        .count();
    assert!(cut + 200 < full, "{cut} {full}");
}

#[test]
fn polygon_behind_the_eye_draws_nothing() {
    let o = orbit();
    let e = o.eye_direction::<super::precision::Libm>();
    // A triangle well behind the eye, facing it.
    let behind = |s: f32| {
        [
            o.target[0] + 9.0 * e[0] + s,
            o.target[1] + 9.0 * e[1],
            o.target[2] + 9.0 * e[2],
        ]
    };
    let tri = [
        behind(-1.0),
        behind(1.0),
        [behind(0.0)[0], behind(0.0)[1] + 1.0, behind(0.0)[2]],
    ];
    let mut r = Renderer::<FixedPrecision<4>>::new(W, H, &o.camera::<super::precision::Libm>(1.5));
    let Some(r) = r.as_mut() else { panic!() };
    let mut s = CountSink::new(W as i32, H as i32);
    let mut scratch = Scratch::<FixedPrecision<4>, 16>::new();
    let face = Face {
        normal: e.into(),
        color: [255; 3],
        id: 0,
        hidden_edges: 0,
    };
    assert_eq!(
        r.draw_polygon(&mut scratch, tri, &face, &mut s),
        Outcome::Invisible
    );
    assert!(s.count.iter().all(|&c| c == 0));
}

fn huge_triangle<P: Precision>(scale: f32, fov: f32) -> Vec<u32> {
    let o = Orbit::new([0.0; 3], 0.2, 0.1, 10.0, fov);
    let tri = [
        [-scale, -scale, 0.0],
        [scale, -scale, 0.0],
        [0.0, scale, 0.0],
    ];
    let mut s = CountSink::new(W as i32, H as i32);
    let cam = o.camera::<P::Math>(W as f32 / H as f32);
    let face = Face {
        normal: [0.0, 0.0, 1.0].into(),
        color: [1, 2, 3],
        id: 0,
        hidden_edges: 0,
    };
    render::<P, _>(
        &cam,
        &[Poly {
            verts: tri.to_vec(),
            face,
        }],
        &mut s,
    );
    s.count
}

fn huge_triangle_covers<P: Precision>(scale: f32, fov: f32) {
    let c = huge_triangle::<P>(scale, fov);
    let bad = c.iter().filter(|&&c| c != 1).count();
    assert_eq!(
        bad,
        0,
        "{} scale {scale} fov {fov}",
        core::any::type_name::<P>()
    );
}

#[test]
fn huge_triangles_cover_the_whole_screen_without_overflow() {
    for fov in [1.0, 0.0] {
        // Fixed point transforms exactly (1e9 and 1e30 saturate to the
        // 16.16 range, ±32768, still far beyond the view).
        huge_triangle_covers::<FixedPrecision<8>>(1e9, fov);
        huge_triangle_covers::<FixedPrecision<0>>(1e9, fov);
        huge_triangle_covers::<FixedPrecision<4>>(1e30, fov);
        huge_triangle_covers::<FloatLibm<8>>(1e6, fov);
        // The integer path saturates vertices at its grid's range (±128,
        // resp. ±2^14), still far beyond the view.
        huge_triangle_covers::<Int8<8>>(100.0, fov);
        huge_triangle_covers::<Int8<4>>(1e9, fov);
        huge_triangle_covers::<IntPrecision<8>>(1e30, fov);
        huge_triangle_covers::<FloatMicromath<4>>(1e6, fov);
    }
    // f32 with a parallel camera: w = 1, no near clip, still covers.
    huge_triangle_covers::<FloatLibm<8>>(1e9, 0.0);
    huge_triangle_covers::<FloatLibm<8>>(1e30, 0.0);
    // f32 in perspective at 1e9+: the transform rounds by more than the
    // eye's distance to the plane (see clip.rs), so only "no overflow, no
    // panic, no overdraw" can be asked.
    for s in [1e9, 1e20, 1e30, 3e38] {
        assert!(huge_triangle::<FloatLibm<8>>(s, 1.0)
            .iter()
            .all(|&c| c <= 1));
        assert!(huge_triangle::<FloatMicromath<0>>(s, 1.0)
            .iter()
            .all(|&c| c <= 1));
    }
}

#[test]
fn band_rendering_equals_full_frame() {
    let polys = scene();
    let cam = orbit().camera::<super::precision::Libm>(W as f32 / H as f32);
    let mut full = vec![0u16; (W * H) as usize];
    {
        let Ok(mut fb) = Rgb565Framebuffer::new(&mut full, W, H) else {
            panic!()
        };
        render::<FixedPrecision<4>, _>(&cam, &polys, &mut fb);
    }
    assert!(full.iter().filter(|&&p| p != 0).count() > (W * H / 2) as usize);
    for rows in [1u32, 7, 16] {
        let mut banded = vec![0u16; (W * H) as usize];
        let mut band_buf = vec![0u16; (W * rows) as usize];
        for y0 in band_starts(H, rows) {
            band_buf.fill(0);
            {
                let Ok(mut fb) = Rgb565Framebuffer::new(&mut band_buf, W, rows) else {
                    panic!()
                };
                let mut band = Band::new(&mut fb, y0);
                render::<FixedPrecision<4>, _>(&cam, &polys, &mut band);
            }
            let n = (rows.min(H - y0 as u32) * W) as usize;
            let at = y0 as usize * W as usize;
            banded[at..at + n].copy_from_slice(&band_buf[..n]);
        }
        assert_eq!(banded, full, "bands of {rows}");
    }
}

/// A DrawTarget with nothing but `draw_iter` (all defaults).
struct Plain<C> {
    px: Vec<C>,
}
impl<C: embedded_graphics::pixelcolor::PixelColor> OriginDimensions for Plain<C> {
    fn size(&self) -> Size {
        Size::new(W, H)
    }
}
impl<C: embedded_graphics::pixelcolor::PixelColor> DrawTarget for Plain<C> {
    type Color = C;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(&mut self, it: I) -> Result<(), Self::Error> {
        for Pixel(p, c) in it {
            if p.x >= 0 && p.y >= 0 && (p.x as u32) < W && (p.y as u32) < H {
                self.px[(p.y as u32 * W + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

fn fast_equals_generic<F: PixelFormat>(
    storage: &mut [F::Word],
    storage2: &mut [F::Word],
    bg: F::Color,
) where
    F::Color: PartialEq + core::fmt::Debug,
{
    let polys = scene();
    let cam = orbit().camera::<super::precision::Libm>(W as f32 / H as f32);
    let Ok(mut fast) = Framebuffer::<F>::new(storage, W, H) else {
        panic!()
    };
    let _ = fast.clear(bg);
    render::<FixedPrecision<4>, _>(&cam, &polys, &mut fast);
    let mut plain = Plain {
        px: vec![bg; (W * H) as usize],
    };
    let mut sink = DrawTargetSink::new(&mut plain);
    render::<FixedPrecision<4>, _>(&cam, &polys, &mut sink);
    assert!(sink.finish().is_ok());
    let Ok(mut via_dt) = Framebuffer::<F>::new(storage2, W, H) else {
        panic!()
    };
    let _ = via_dt.clear(bg);
    let mut sink = DrawTargetSink::new(&mut via_dt);
    render::<FixedPrecision<4>, _>(&cam, &polys, &mut sink);
    let mut differing = 0;
    for y in 0..H {
        for x in 0..W {
            let a = fast.pixel(x, y);
            assert_eq!(a, Some(plain.px[(y * W + x) as usize]), "({x},{y})");
            assert_eq!(a, via_dt.pixel(x, y));
            differing += (a != Some(bg)) as usize;
        }
    }
    assert!(differing > (W * H / 2) as usize);
}

#[test]
fn fast_framebuffer_path_equals_generic_draw_target() {
    let n = (W * H) as usize;
    fast_equals_generic::<super::framebuffer::Rgb565Format>(
        &mut vec![0; n],
        &mut vec![0; n],
        Rgb565::BLACK,
    );
    fast_equals_generic::<super::framebuffer::Rgb888Format>(
        &mut vec![0; 3 * n],
        &mut vec![0; 3 * n],
        Rgb888::BLACK,
    );
    fast_equals_generic::<super::framebuffer::Gray8Format>(
        &mut vec![0; n],
        &mut vec![0; n],
        Gray8::new(0),
    );
    let nb = BinaryFramebuffer::required_len(W, H);
    fast_equals_generic::<super::framebuffer::BinaryFormat>(
        &mut vec![0; nb],
        &mut vec![0; nb],
        embedded_graphics::pixelcolor::BinaryColor::Off,
    );
}

#[test]
fn shading_modes_and_id_buffer() {
    let polys = cube([0.0, 0.0, 0.0], 1.0, 10);
    let cam = Orbit::new([0.0; 3], 0.7, 0.5, 6.0, 0.9)
        .camera::<super::precision::Libm>(W as f32 / H as f32);
    let mut buf = vec![0u8; 3 * (W * H) as usize];
    let mut ids = vec![0u32; (W * H) as usize];
    for mode in [ShadeMode::Grey(230), ShadeMode::Lambert, ShadeMode::Flat] {
        buf.fill(0);
        let Ok(mut fb) = Rgb888Framebuffer::new(&mut buf, W, H) else {
            panic!()
        };
        let mut r = Renderer::<FixedPrecision<4>>::new(W, H, &cam).unwrap_or_else(|| panic!());
        r.set_shade_mode(mode);
        r.set_light(Light::new([0.3, 1.0, 0.5], 0.2, 0.8));
        let mut scratch = Scratch::<FixedPrecision<4>, 16>::new();
        let Ok(mut idb) = IdBuffer::new(&mut ids, W, H) else {
            panic!()
        };
        // Front faces only (the tree walk would cull the others).
        let eye =
            Orbit::new([0.0; 3], 0.7, 0.5, 6.0, 0.9).eye_direction::<super::precision::Libm>();
        for p in polys.iter().filter(|p| {
            (0..3)
                .map(|k| p.face.normal.to_f32()[k] * eye[k])
                .sum::<f32>()
                > 0.0
        }) {
            r.draw_polygon(&mut scratch, p.verts.iter().copied(), &p.face, &mut fb);
            r.draw_polygon(&mut scratch, p.verts.iter().copied(), &p.face, &mut idb);
        }
        let mut seen = std::collections::BTreeSet::new();
        for y in 0..H {
            for x in 0..W {
                let (Some(c), Some(id)) = (fb.pixel(x, y), idb.get(x, y)) else {
                    panic!()
                };
                if id == 0 {
                    assert_eq!(c, Rgb888::BLACK);
                    continue;
                }
                let face = &polys[(id - 11) as usize].face;
                seen.insert(id);
                let expect = super::shade::shade(
                    mode,
                    &Light::new([0.3, 1.0, 0.5], 0.2, 0.8),
                    face.normal.to_f32(),
                    face.color,
                );
                assert_eq!(c, expect);
                if let ShadeMode::Grey(_) = mode {
                    assert!(c.r() == c.g() && c.g() == c.b());
                }
            }
        }
        assert_eq!(seen.len(), 3, "three faces of a cube are visible");
    }
}

#[test]
fn capacity_and_non_finite_skips() {
    let cam = orbit().camera::<super::precision::Libm>(1.5);
    let mut r = Renderer::<FloatLibm<4>>::new(W, H, &cam).unwrap_or_else(|| panic!());
    let mut s = CountSink::new(W as i32, H as i32);
    let mut scratch = Scratch::<FloatLibm<4>, 8>::new();
    let face = Face {
        normal: [0.0, 1.0, 0.0].into(),
        color: [9; 3],
        id: 1,
        hidden_edges: 0,
    };
    let circle = |n: usize| {
        (0..n).map(move |k| {
            let a = k as f32 / n as f32 * core::f32::consts::TAU;
            [libm::cosf(a), 0.0, libm::sinf(a)]
        })
    };
    assert!(matches!(
        r.draw_polygon(&mut scratch, circle(8), &face, &mut s),
        Outcome::Drawn { .. }
    ));
    let o = r.draw_polygon(&mut scratch, circle(9), &face, &mut s);
    assert_eq!(o, Outcome::Skipped(SkipReason::TooManyVertices));
    let bad = [[0.0, 0.0, 0.0], [1.0, f32::NAN, 0.0], [0.0, 0.0, 1.0]];
    assert_eq!(
        r.draw_polygon(&mut scratch, bad, &face, &mut s),
        Outcome::Skipped(SkipReason::NonFinite)
    );
    // A comb crossing the near plane many times outgrows 8 slots.
    let comb: Vec<[f32; 3]> = (0..4)
        .flat_map(|k| [[k as f32, 0.0, -3.0], [k as f32 + 0.5, 0.0, 9.0]])
        .collect();
    let o = r.draw_polygon(&mut scratch, comb.iter().copied(), &face, &mut s);
    assert_eq!(o, Outcome::Skipped(SkipReason::ClipCapacity));
    assert_eq!(r.stats().skipped, 3);
    assert!(r.draw_polygon(&mut scratch, [[0.0; 3]; 2], &face, &mut s) == Outcome::Invisible);
}

#[test]
fn precision_configurations_agree_closely() {
    // A small accuracy study: id buffers of several configurations
    // against f32 + libm with 8 sub-pixel bits.
    let polys = scene();
    let o = orbit();
    let ids = |f: &dyn Fn(&mut IdBuffer)| {
        let mut v = vec![0u32; (W * H) as usize];
        let Ok(mut b) = IdBuffer::new(&mut v, W, H) else {
            panic!()
        };
        f(&mut b);
        v
    };
    let cam_l = o.camera::<super::precision::Libm>(W as f32 / H as f32);
    let cam_m = o.camera::<super::precision::Micromath>(W as f32 / H as f32);
    let reference = ids(&|b| {
        render::<FloatLibm<8>, _>(&cam_l, &polys, b);
    });
    let diff = |v: &[u32]| v.iter().zip(&reference).filter(|(a, b)| a != b).count();
    let results = [
        (
            "fixed16.16 sub8",
            diff(&ids(&|b| {
                render::<FixedPrecision<8>, _>(&cam_l, &polys, b);
            })),
        ),
        (
            "fixed16.16 sub4",
            diff(&ids(&|b| {
                render::<FixedPrecision<4>, _>(&cam_l, &polys, b);
            })),
        ),
        (
            "fixed16.16 sub0",
            diff(&ids(&|b| {
                render::<FixedPrecision<0>, _>(&cam_l, &polys, b);
            })),
        ),
        (
            "f32 libm sub2",
            diff(&ids(&|b| {
                render::<FloatLibm<2>, _>(&cam_l, &polys, b);
            })),
        ),
        (
            "int sub4",
            diff(&ids(&|b| {
                render::<Int8<4>, _>(&cam_l, &polys, b);
            })),
        ),
        (
            "f32 micromath sub4",
            diff(&ids(&|b| {
                render::<FloatMicromath<4>, _>(&cam_m, &polys, b);
            })),
        ),
    ];
    for (name, d) in results {
        std::eprintln!(
            "accuracy: {name}: {d} of {} pixels differ from f32+libm sub8",
            W * H
        );
    }
    let total = (W * H) as usize;
    assert!(results[0].1 < total / 100, "{results:?}");
    assert!(results[1].1 < total / 50, "{results:?}");
    assert!(results[2].1 < total / 8, "{results:?}");
    assert!(results[4].1 < total / 50, "{results:?}");
    assert!(results[5].1 < total / 4, "{results:?}");
    // Coarser sub-pixels cannot be more accurate than finer ones here.
    assert!(results[0].1 <= results[2].1);
}

#[test]
fn gray_and_binary_framebuffers_match_rgb_conversion() {
    let polys = scene();
    let cam = orbit().camera::<super::precision::Libm>(W as f32 / H as f32);
    let n = (W * H) as usize;
    let (mut rgb, mut gray, mut bin) = (
        vec![0u8; 3 * n],
        vec![0u8; n],
        vec![0u8; BinaryFramebuffer::required_len(W, H)],
    );
    let (Ok(mut f1), Ok(mut f2), Ok(mut f3)) = (
        Rgb888Framebuffer::new(&mut rgb, W, H),
        Gray8Framebuffer::new(&mut gray, W, H),
        BinaryFramebuffer::new(&mut bin, W, H),
    ) else {
        panic!()
    };
    render::<FixedPrecision<4>, _>(&cam, &polys, &mut f1);
    render::<FixedPrecision<4>, _>(&cam, &polys, &mut f2);
    render::<FixedPrecision<4>, _>(&cam, &polys, &mut f3);
    let mut on = 0;
    for y in 0..H {
        for x in 0..W {
            let (Some(c), Some(g), Some(b)) = (f1.pixel(x, y), f2.pixel(x, y), f3.pixel(x, y))
            else {
                panic!()
            };
            assert_eq!(g, Gray8::from(c));
            assert_eq!(b, embedded_graphics::pixelcolor::BinaryColor::from(c));
            on += b.is_on() as usize;
        }
    }
    assert!(on > 0 && on < n);
}

#[test]
fn matrix_camera_matches_orbit_camera() {
    let o = orbit();
    let cam = o.camera::<super::precision::Libm>(W as f32 / H as f32);
    let polys = scene();
    let mut a = CountSink::new(W as i32, H as i32);
    let mut b = CountSink::new(W as i32, H as i32);
    let mut r = Renderer::<FloatLibm<4>>::new(W, H, &Camera::from_matrix(Mat4::IDENTITY, 0.1))
        .unwrap_or_else(|| panic!());
    r.set_orbit(&o);
    let mut scratch = Scratch::<FloatLibm<4>, 64>::new();
    for p in &polys {
        r.draw_polygon(&mut scratch, p.verts.iter().copied(), &p.face, &mut a);
    }
    render::<FloatLibm<4>, _>(&cam, &polys, &mut b);
    assert_eq!(a.id, b.id);
}

mod fuzz;
