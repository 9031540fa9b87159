extern crate std;

use super::super::clip::clip_polygon;
use super::super::precision::Libm;
use super::super::tests::Rng;
use super::super::transform::{FloatPath, SCREEN_LIMIT};
use super::super::{Camera, Orbit};
use super::*;
use std::vec::Vec;

type Int = IntPath<1>;
type Flt = FloatPath<Libm>;

/// A normalised frame as `render::Frame` makes it: an orbit around a
/// sphere of radius `r` (random centre offset, distance and field of view;
/// `fov = 0`: parallel), vertices scaled by `s` so that the sphere's
/// radius is in `[2^13, 2^14]`, the matrix's columns by `1/s`, and the
/// whole matrix by a power of two. Returns the camera and `s`.
fn frame_camera(rng: &mut Rng, parallel: bool) -> (Camera, f32) {
    let r = libm::powf(10.0, rng.float(-3.0, 6.0));
    let fov = if parallel { 0.0 } else { rng.float(0.3, 1.6) };
    let o = Orbit::new(
        [0.0; 3],
        rng.float(-3.2, 3.2),
        rng.float(-1.5, 1.5),
        r * rng.float(1.2, 8.0),
        fov,
    );
    let cam = o.camera::<Libm>(rng.float(0.5, 2.0));
    let s = rng.float(8192.0, 16384.0) / r;
    let k = pow2(rng.range(-40, 40));
    let mut m = cam.matrix;
    for row in m.0.iter_mut() {
        for (j, e) in row.iter_mut().enumerate() {
            *e *= if j < 3 { k / s } else { k };
        }
    }
    (Camera::from_matrix(m, cam.near_w * k), r * s)
}

/// A random point within the ball of `radius`.
fn ball(rng: &mut Rng, radius: f32) -> [f32; 3] {
    loop {
        let p = [0; 3].map(|_| rng.float(-1.0, 1.0));
        if p.iter().map(|c| c * c).sum::<f32>() <= 1.0 {
            return p.map(|c| c * radius);
        }
    }
}

/// The exact screen position (f64) of `v` through `m`, in sub-pixel
/// units, and its `w`.
fn exact(m: &Mat4, v: [f32; 3], vp: &Viewport) -> (f64, f64, f64) {
    let row = |r: &[f32; 4]| {
        r[0] as f64 * v[0] as f64
            + r[1] as f64 * v[1] as f64
            + r[2] as f64 * v[2] as f64
            + r[3] as f64
    };
    let (x, y, w) = (row(&m.0[0]), row(&m.0[1]), row(&m.0[3]));
    let c = |n: u32| (n << vp.sub_bits()) as f64 * 0.5;
    (
        (x / w + 1.0) * c(vp.width()),
        (1.0 - y / w) * c(vp.height()),
        w,
    )
}

/// Over random normalised frames and vertices: the integer path's screen
/// point is within 1 sub-pixel unit of the exact projection (rounded)
/// for vertices on screen, within 2 in the guard band; and no farther
/// from it than the `f32` path plus one unit.
#[test]
fn tracks_the_exact_projection_on_normalised_frames() {
    let mut rng = Rng(3);
    let vp = Viewport::new(240, 240, 4).unwrap_or_else(|| panic!());
    let (mut worst_on, mut worst_guard, mut n_on) = (0.0f64, 0.0f64, 0);
    for k in 0..400 {
        let (cam, radius) = frame_camera(&mut rng, k % 5 == 0);
        let m = Int::prepare(&cam.matrix);
        let near = Int::near(&m, cam.near_w);
        for _ in 0..100 {
            let v = ball(&mut rng, radius);
            let Some(c) = Int::transform(&m, v) else {
                panic!("{v:?}")
            };
            if !<i32 as ClipNum>::inside(&c, near) {
                continue;
            }
            let (ex, ey, _) = exact(&cam.matrix, v, &vp);
            let Some(p) = Int::project_clipped(&c, &vp) else {
                panic!("{c:?}")
            };
            let err = (p.x as f64 - (ex + 0.5).floor())
                .abs()
                .max((p.y as f64 - (ey + 0.5).floor()).abs());
            let on = (0.0..=3840.0).contains(&ex) && (0.0..=3840.0).contains(&ey);
            if on {
                n_on += 1;
                worst_on = worst_on.max(err);
            } else {
                worst_guard = worst_guard.max(err);
            }
            let f = Flt::transform(&cam.matrix, v).and_then(|c| Flt::project(&c, &vp));
            if let Some(f) = f {
                let ferr = (f.x as f64 - (ex + 0.5).floor())
                    .abs()
                    .max((f.y as f64 - (ey + 0.5).floor()).abs());
                assert!(err <= ferr + 1.0, "{v:?} {p:?} {f:?} {ex} {ey}");
            }
        }
    }
    std::eprintln!(
        "int path: worst {worst_on} on screen ({n_on}), {worst_guard} in the guard band"
    );
    assert!(n_on > 10_000, "{n_on}");
    assert!(worst_on <= 1.0, "{worst_on}");
    assert!(worst_guard <= 2.0, "{worst_guard}");
}

/// q16 vertices drawn as stored through [`q16_camera`] land where their
/// decoded `f32` values do, within a unit (both round to a vertex grid,
/// in different units).
#[test]
fn q16_vertices_as_stored_match_decoded_ones() {
    let mut rng = Rng(7);
    let vp = Viewport::new(240, 240, 4).unwrap_or_else(|| panic!());
    let mut diffs = 0;
    for _ in 0..200 {
        let (cam, radius) = frame_camera(&mut rng, false);
        let half = [0; 3].map(|_| rng.float(0.3, 0.577) * radius);
        // vertex_scale 1: the frame's vertices are the decoded ones.
        let qcam = q16_camera(&cam, 1.0, half, 1);
        let (m, mq) = (Int::prepare(&cam.matrix), Int::prepare(&qcam.matrix));
        let (near, nearq) = (Int::near(&m, cam.near_w), Int::near(&mq, qcam.near_w));
        for _ in 0..50 {
            let q = [0; 3].map(|_| rng.range(-32767, 32767));
            let v: [f32; 3] = core::array::from_fn(|a| half[a] * q[a] as f32 / 32767.0);
            let (Some(a), Some(b)) = (Int::transform(&m, v), Int::transform_q(&mq, q, 1)) else {
                panic!()
            };
            if !(a.inside(near) && b.inside(nearq)) {
                continue;
            }
            let (Some(pa), Some(pb)) = (Int::project(&a, &vp), Int::project(&b, &vp)) else {
                panic!()
            };
            assert!(
                (pa.x - pb.x).abs() <= 1 && (pa.y - pb.y).abs() <= 1,
                "{pa:?} {pb:?}"
            );
            diffs += usize::from(pa != pb);
        }
    }
    std::eprintln!("q16 as stored vs decoded: {diffs} points differ (by 1)");
}

trait Inside {
    fn inside(&self, near: i32) -> bool;
}
impl Inside for ClipVert<i32> {
    fn inside(&self, near: i32) -> bool {
        <i32 as ClipNum>::inside(self, near)
    }
}

#[test]
fn integer_vertices_go_onto_the_grid() {
    let m = Int::prepare(&Mat4::IDENTITY);
    let t = |v: [i32; 3], frac: u32| Int::transform_q(&m, v, frac);
    // frac = VB: as they are; more: rounded half up; fewer: shifted up.
    assert_eq!(t([3, -4, 5], 1), Int::transform(&m, [1.5, -2.0, 2.5]));
    assert_eq!(t([3 << 15, -2 << 16, 1 << 14], 16), t([3, -4, 1], 1));
    assert_eq!(t([5, -5, 7], 2), t([3, -2, 4], 1));
    assert_eq!(t([3, -4, 0], 0), t([6, -8, 0], 1));
    // Saturation at ±2^14 (the grid's ±2^15), never wrapping.
    assert_eq!(
        t([i32::MAX, i32::MIN, 0], 0),
        t([1 << 15, -(1 << 15), 0], 1)
    );
    assert_eq!(t([i32::MAX, i32::MIN, 1], 62), t([0, 0, 0], 1));
    assert_eq!(t([1, 1, 1], 63), None);
    assert_eq!(Int::transform(&m, [f32::NAN, 0.0, 0.0]), None);
    assert_eq!(Int::transform(&m, [0.0, f32::INFINITY, 0.0]), None);
    assert_eq!(
        Int::transform(&m, [1e30, -1e30, 0.0]),
        t([1 << 15, -(1 << 15), 0], 1)
    );
}

#[test]
fn projection_follows_the_pixel_convention() {
    let vp = Viewport::new(200, 100, 4).unwrap_or_else(|| panic!());
    for w in [1, 3, 1000, 40_000, 1 << 20, (1 << 28) + 12345] {
        for ((nx, ny), want) in [
            ((-1, 1), (0, 0)),
            ((1, -1), (3200, 1600)),
            ((0, 0), (1600, 800)),
            ((4, -4), (8000, 4000)),
        ] {
            let v = ClipVert {
                x: nx * w,
                y: ny * w,
                w,
            };
            let p = Int::project(&v, &vp);
            assert_eq!(
                p,
                Some(ScreenPt {
                    x: want.0,
                    y: want.1
                }),
                "{v:?}"
            );
            assert_eq!(Int::project_clipped(&v, &vp), p);
        }
    }
    let z = ClipVert { x: 0, y: 0, w: 0 };
    assert_eq!(Int::project(&z, &vp), None);
    assert_eq!(Int::project(&ClipVert { w: -5, ..z }, &vp), None);
}

/// Unclipped garbage may be rejected but never overflows; inside
/// vertices project the same both ways; every viewport size.
#[test]
fn extreme_clip_values_project_within_limits() {
    let mut rng = Rng(9);
    let vals = [
        i32::MIN,
        i32::MIN + 1,
        -1,
        0,
        1,
        2,
        1 << 28,
        i32::MAX - 1,
        i32::MAX,
    ];
    for &(w, h, sub) in &[
        (240, 240, 4),
        (1, 1, 0),
        (MAX, 3, 8),
        (MAX, MAX, 8),
        (320, 240, 8),
    ] {
        let vp = Viewport::new(w, h, sub).unwrap_or_else(|| panic!());
        for &x in &vals {
            for &y in &vals {
                for &cw in &vals {
                    let v = ClipVert { x, y, w: cw };
                    let p = Int::project(&v, &vp);
                    assert_eq!(p.is_some(), cw > 0);
                    if let Some(p) = p {
                        assert!(p.x.abs() <= SCREEN_LIMIT && p.y.abs() <= SCREEN_LIMIT);
                    }
                    if v.inside(1) {
                        assert_eq!(Int::project_clipped(&v, &vp), p, "{v:?}");
                    }
                }
            }
        }
        for _ in 0..2000 {
            let cw = rng.range(1, i32::MAX / 4) >> rng.range(0, 30);
            let g = (cw * 4) as i64;
            let mut c = || ((rng.next() % (2 * g as u64 + 1)) as i64 - g) as i32;
            let v = ClipVert {
                x: c(),
                y: c(),
                w: cw,
            };
            assert_eq!(Int::project_clipped(&v, &vp), Int::project(&v, &vp));
        }
    }
}

const MAX: u32 = super::super::transform::MAX_DIM;

/// Any finite or non-finite matrix, any vertex: no panic, and clip values
/// within the documented bound.
#[test]
fn extreme_matrices_and_vertices_never_overflow() {
    let mut rng = Rng(13);
    let special = [
        0.0,
        -0.0,
        1e-45,
        1e-30,
        1e30,
        3e38,
        -3e38,
        f32::NAN,
        f32::INFINITY,
    ];
    let bound = (1 << 28) + (1 << 16);
    for k in 0..3000 {
        let mut m = Mat4::IDENTITY;
        for e in m.0.iter_mut().flatten() {
            *e = if rng.range(0, 5) == 0 {
                special[rng.range(0, special.len() as i32 - 1) as usize]
            } else {
                rng.float(-1.0, 1.0) * libm::powf(10.0, rng.float(-20.0, 20.0))
            };
        }
        let p = Int::prepare(&m);
        let near = Int::near(&p, rng.float(0.0, 10.0));
        assert!(near >= 1);
        let v = if k % 2 == 0 {
            [0; 3].map(|_| rng.next() as i32)
        } else {
            [0; 3].map(|_| rng.range(-(1 << 15), 1 << 15))
        };
        let c = Int::transform_q(&p, v, 1).unwrap_or_else(|| panic!());
        for s in [c.x, c.y, c.w] {
            assert!(s.abs() <= bound, "{m:?} {v:?} {c:?}");
        }
        assert!(!Int::depth(&p, c.w).is_nan());
        let vf = [0; 3].map(|_| special[rng.range(0, special.len() as i32 - 1) as usize]);
        let _ = Int::transform(&p, vf);
    }
}

/// The interpolation parameter is the exact floor.
#[test]
fn clip_parameter_is_exact() {
    let mut rng = Rng(17);
    let edge = [0, 1, 2, 12345, i32::MAX - 1, i32::MAX];
    let mut cases: Vec<(i32, i32)> = Vec::new();
    for &a in &edge {
        for &b in &[-1, -2, -77777, i32::MIN + 1, i32::MIN] {
            cases.push((a, b));
        }
    }
    for _ in 0..20_000 {
        let a = rng.range(0, i32::MAX) >> rng.range(0, 31);
        let b = -(rng.range(1, i32::MAX) >> rng.range(0, 30)).max(1);
        cases.push((a, b));
    }
    for (a, b) in cases {
        let want = ((a as u128) << 30) / (a as i128 - b as i128) as u128;
        assert_eq!(clip_param(a, b) as u128, want, "{a} {b}");
    }
    // Outside the contract: clamped, total.
    assert_eq!(clip_param(-5, -3), 0);
    assert_eq!(clip_param(5, 3), (5u64 << 30).div_euclid(6) as u32);
}

/// Clipping with the integer scalar, from random triangles across the
/// near plane and the guard band: every output vertex is in front of the
/// near plane and inside the guard band up to rounding, and projects alike
/// both ways.
#[test]
fn clipping_keeps_every_vertex_inside() {
    let mut rng = Rng(21);
    let vp = Viewport::new(240, 240, 4).unwrap_or_else(|| panic!());
    let mut clipped = 0;
    for k in 0..20_000 {
        let scale = [1 << 4, 1 << 12, 1 << 20, 1 << 28][k % 4];
        let near = rng.range(1, 1 << 10);
        let pt = |rng: &mut Rng| ClipVert {
            x: rng.range(-scale, scale),
            y: rng.range(-scale, scale),
            w: rng.range(-scale / 2, scale),
        };
        let (p, q, r1, r2) = (pt(&mut rng), pt(&mut rng), pt(&mut rng), pt(&mut rng));
        let run = |tri: [ClipVert<i32>; 3]| {
            let mut a = [ClipVert::default(); 16];
            let mut b = [ClipVert::default(); 16];
            a[..3].copy_from_slice(&tri);
            clip_polygon(&mut a, 3, &mut b, near).map(|c| (c.verts.to_vec(), c.clipped))
        };
        let (Ok((t1, c1)), Ok((t2, _))) = (run([p, q, r1]), run([q, p, r2])) else {
            panic!()
        };
        clipped += usize::from(c1);
        for v in t1.iter().chain(&t2) {
            // In front of the near plane exactly (interpolation stays
            // between the endpoints); on a guard plane up to the rounding
            // of the later passes, which the projection's clamp absorbs.
            assert!(v.w >= near, "{v:?}");
            let g = 4 * v.w as i64 + 32;
            assert!((v.x as i64).abs() <= g && (v.y as i64).abs() <= g, "{v:?}");
            let pp = Int::project(v, &vp);
            assert!(pp.is_some());
            assert_eq!(Int::project_clipped(v, &vp), pp);
        }
    }
    assert!(clipped > 5_000, "{clipped}");
}

/// A segment crossing the near plane, cut from both of its triangles:
/// the same point (the clipper interpolates from the inside endpoint).
#[test]
fn shared_edge_cuts_are_bit_identical() {
    let near = 37;
    let (p, q) = (
        ClipVert {
            x: 300,
            y: 700,
            w: -770,
        },
        ClipVert {
            x: 1100,
            y: -200,
            w: 2900,
        },
    );
    let (r1, r2) = (
        ClipVert {
            x: -100,
            y: 300,
            w: 2000,
        },
        ClipVert {
            x: 2000,
            y: -300,
            w: 1300,
        },
    );
    let run = |tri: [ClipVert<i32>; 3]| {
        let mut a = [ClipVert::default(); 16];
        let mut b = [ClipVert::default(); 16];
        a[..3].copy_from_slice(&tri);
        clip_polygon(&mut a, 3, &mut b, near).map_or(Vec::new(), |c| c.verts.to_vec())
    };
    let (t1, t2) = (run([p, q, r1]), run([q, p, r2]));
    let new: Vec<_> = t1.iter().filter(|v| ![p, q, r1].contains(v)).collect();
    assert_eq!(
        new.iter().filter(|v| t2.contains(v)).count(),
        1,
        "{t1:?} {t2:?}"
    );
}

/// `near` and `depth` convert between the path's per-frame units and the
/// camera's: a clip `w` comes back as the `f32` path's `w` (to the
/// units' resolution), the near threshold as `near_w`.
#[test]
fn near_and_depth_are_in_camera_units() {
    let mut rng = Rng(29);
    for k in 0..300 {
        let (cam, radius) = frame_camera(&mut rng, k % 7 == 0);
        let m = Int::prepare(&cam.matrix);
        let near = Int::near(&m, cam.near_w);
        let back = Int::depth(&m, near);
        assert!(
            (back - cam.near_w).abs() <= 1e-3 * cam.near_w.abs() + Int::depth(&m, 1),
            "{back} {}",
            cam.near_w
        );
        for _ in 0..20 {
            let v = ball(&mut rng, radius);
            let (Some(a), Some(b)) = (Int::transform(&m, v), Flt::transform(&cam.matrix, v)) else {
                panic!()
            };
            let d = Int::depth(&m, a.w);
            // The bound B of IntMatrix is about 2^28 units: 2^-14 of it
            // covers the vertex grid and the entries' rounding.
            let scale = Int::depth(&m, 1 << 28);
            assert!((d - b.w).abs() <= scale * 2e-4, "{d} {} {scale}", b.w);
        }
    }
}

/// The division-free reciprocal, for every input of its range: at most 2
/// below `2^31 / w`, never above (so `r ≤ 2^16`, the projection's bound).
#[test]
fn the_reciprocal_is_within_two_units_from_below() {
    let mut worst = 0.0f64;
    for w in 1u32 << 15..1 << 16 {
        let exact = 2f64.powi(31) / w as f64;
        let r = recip(w) as f64;
        assert!(r <= exact && exact - r <= 2.0, "{w}: {r} vs {exact}");
        worst = worst.max(exact - r);
    }
    assert!(worst >= 0.5, "{worst}");
}
