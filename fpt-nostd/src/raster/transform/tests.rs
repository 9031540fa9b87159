//! Tests of the vertex paths (`super`): transforms, projections and floors.

use super::super::precision::{Libm, Micromath};
use super::*;

type Fix = FixedPath<16>;
type Flt = FloatPath<Libm>;

fn sample_matrix() -> Mat4 {
    Mat4([
        [1.2, 0.1, -0.3, 0.5],
        [0.0, 0.9, 0.4, -0.25],
        [0.3, 0.2, 1.0, 2.0],
        [-0.1, 0.05, 0.8, 4.0],
    ])
}

#[test]
fn fixed_transform_tracks_float() {
    let m = sample_matrix();
    let (mf, mx) = (Flt::prepare(&m), Fix::prepare(&m));
    for v in [[0.0, 0.0, 0.0], [1.5, -2.25, 3.0], [-100.0, 40.0, 7.5]] {
        let a = Flt::transform(&mf, v).unwrap_or_default();
        let b = Fix::transform(&mx, v).unwrap_or_default();
        for (p, q) in [(a.x, b.x), (a.y, b.y), (a.w, b.w)] {
            assert!((p - q.to_f32()).abs() < 1e-2 * (1.0 + p.abs()), "{p} {q:?}");
        }
    }
}

#[test]
fn q_vertices_match_float_vertices() {
    let m = sample_matrix();
    let mx = Fix::prepare(&m);
    let a = Fix::transform(&mx, [1.5, -2.0, 0.25]);
    assert_eq!(Fix::transform_q(&mx, [3 << 15, -2 << 16, 1 << 14], 16), a);
    assert_eq!(
        Fix::transform_q(&mx, [3, -4, 0], 1),
        Fix::transform(&mx, [1.5, -2.0, 0.0])
    );
    let q32 = Fix::transform_q(&mx, [1 << 30, 0, 0], 32);
    assert_eq!(q32, Fix::transform(&mx, [0.25, 0.0, 0.0]));
    assert_eq!(Fix::transform_q(&mx, [1, 1, 1], 63), None);
    let b = Flt::transform_q(&m, [3 << 15, -2 << 16, 1 << 14], 16);
    assert_eq!(b, Flt::transform(&m, [1.5, -2.0, 0.25]));
}

#[test]
fn non_finite_and_huge_are_rejected_or_saturated() {
    let m = sample_matrix();
    assert_eq!(Flt::transform(&m, [f32::NAN, 0.0, 0.0]), None);
    assert_eq!(Flt::transform(&m, [f32::INFINITY, 0.0, 0.0]), None);
    assert_eq!(Flt::transform(&m, [3e37, 3e37, 0.0]), None);
    assert!(Flt::transform(&m, [1e30, 0.0, 0.0]).is_some());
    let mx = Fix::prepare(&m);
    assert_eq!(Fix::transform(&mx, [0.0, f32::NAN, 0.0]), None);
    // Saturates to the 16.16 range instead of wrapping.
    let a = Fix::transform(&mx, [1e9, -1e9, 0.0]);
    assert_eq!(a, Fix::transform_q(&mx, [i32::MAX, i32::MIN, 0], 16));
    assert!(a.is_some());
}

#[test]
fn projection_follows_pixel_convention() {
    let vp =
        Viewport::new(200, 100, 4).unwrap_or(Viewport::new(1, 1, 0).unwrap_or_else(|| panic!()));
    // ndc (-1, 1) is the top-left corner, (1, -1) the bottom-right.
    let corners = [
        ((-1.0, 1.0), (0, 0)),
        ((1.0, -1.0), (3200, 1600)),
        ((0.0, 0.0), (1600, 800)),
    ];
    for ((nx, ny), (ex, ey)) in corners {
        for w in [0.5f32, 2.0, 7.0] {
            let f = ClipVert {
                x: nx * w,
                y: ny * w,
                w,
            };
            let s = Flt::project(&f, &vp);
            assert_eq!(s, Some(ScreenPt { x: ex, y: ey }));
            let g = |v: f32| FxWide::<16>::try_from_f32(v).unwrap_or_default();
            let s = Fix::project(
                &ClipVert {
                    x: g(f.x),
                    y: g(f.y),
                    w: g(f.w),
                },
                &vp,
            );
            assert_eq!(s, Some(ScreenPt { x: ex, y: ey }));
            assert_eq!(
                FloatPath::<Micromath>::project(&f, &vp),
                Some(ScreenPt { x: ex, y: ey })
            );
        }
    }
    assert_eq!(
        Flt::project(
            &ClipVert {
                x: 0.0,
                y: 0.0,
                w: 0.0
            },
            &vp
        ),
        None
    );
    let z = FxWide::<16>::ZERO;
    assert_eq!(Fix::project(&ClipVert { x: z, y: z, w: z }, &vp), None);
}

#[test]
fn projection_of_extreme_fixed_values_does_not_overflow() {
    let vp = Viewport::new(MAX_DIM, MAX_DIM, 8)
        .unwrap_or(Viewport::new(1, 1, 0).unwrap_or_else(|| panic!()));
    let big = FxWide::<16>::from_raw(i64::MAX);
    let one = FxWide::<16>::from_raw(1);
    for (x, w) in [(big, one), (big, big), (FxWide::from_raw(i64::MIN), one)] {
        let p = Fix::project(&ClipVert { x, y: x, w }, &vp);
        // Unclipped garbage may be rejected, but never overflows.
        assert!(p.is_none_or(|p| p.x.abs() <= SCREEN_LIMIT && p.y.abs() <= SCREEN_LIMIT));
    }
}

#[test]
fn integer_floor_equals_libm_floor() {
    for x in [
        0.0f32, -0.0, 0.5, -0.5, 1.0, -1.0, 1.5, -1.5, 3839.999, -7.25, 8388607.5, -8388607.5,
        3.0e9, -3.0e9, 1e-30, -1e-30,
    ] {
        let want = libm::floorf(x).clamp(i32::MIN as f32, i32::MAX as f32) as i32;
        assert_eq!(floor_to_i32(x), want, "{x}");
    }
}

/// The floor of the projection's bounded points (`|x| < 2^30`) equals the
/// general one, the saturation apart (never reached there).
#[test]
fn bounded_floor_equals_the_general_floor() {
    // Magnitudes from 2^-20 to 2^29, with fractions and neighbours.
    let mut x = 1.0e-6f32;
    while x < 5.0e8 {
        for a in [x, x + 0.5, x * 1.37, f32::from_bits(x.to_bits() + 1)] {
            for v in [a, -a] {
                assert_eq!(floor_bounded(v), floor_to_i32(v), "{v}");
            }
        }
        x *= 1.618;
    }
    for v in [
        0.0f32, -0.0, 0.5, -0.5, -1.0, -1.5, 1e-30, -1e-30, 8388607.5, -8388607.5,
    ] {
        assert_eq!(floor_bounded(v), floor_to_i32(v), "{v}");
    }
}

#[test]
fn viewport_limits() {
    assert!(Viewport::new(0, 10, 0).is_none());
    assert!(Viewport::new(10, MAX_DIM + 1, 0).is_none());
    assert!(Viewport::new(10, 10, 9).is_none());
    assert!(Viewport::new(MAX_DIM, MAX_DIM, 8).is_some());
}

/// The unchecked projection of inside vertices is the checked one, for
/// both reciprocals, every sub-pixel count and extreme viewports,
/// vertices on the guard planes and the near plane included.
#[test]
fn projecting_pipeline_vertices_skips_only_checks() {
    fn check<M: MathFns>(rng: &mut crate::raster::tests::Rng) {
        for &(w, h) in &[(240, 240), (1, 1), (MAX_DIM, 3), (MAX_DIM, MAX_DIM)] {
            for sub in 0..=8 {
                let vp = Viewport::new(w, h, sub).unwrap();
                for k in 0..400 {
                    let near = FloatPath::<M>::near(&Mat4::IDENTITY, 0.01);
                    let cw = match k % 4 {
                        0 => near,
                        1 => rng.float(near, 2.0),
                        2 => rng.float(1.0, 1e6),
                        _ => rng.float(1e-6, 1e-3).max(near),
                    };
                    let g = GUARD as f32 * cw;
                    let (x, y) = match k % 3 {
                        0 => (g, -g),
                        1 => (rng.float(-g, g), rng.float(-g, g)),
                        _ => (rng.float(-1.0, 1.0) * cw, g),
                    };
                    let v = ClipVert { x, y, w: cw };
                    assert!(<f32 as ClipNum>::inside(&v, near), "{v:?}");
                    assert_eq!(
                        FloatPath::<M>::project_clipped(&v, &vp),
                        FloatPath::<M>::project(&v, &vp),
                        "{v:?} {w}x{h} sub {sub}"
                    );
                    assert_eq!(
                        FloatPath::<M>::project_inside(&v, &vp),
                        FloatPath::<M>::project(&v, &vp),
                        "{v:?} {w}x{h} sub {sub}"
                    );
                }
            }
        }
    }
    let mut rng = crate::raster::tests::Rng(5);
    check::<Libm>(&mut rng);
    check::<Micromath>(&mut rng);
}

/// Vertices made by clipping project the same both ways: random
/// triangles across the near plane and the guard band, coordinates up
/// to the transform's limit.
#[test]
fn projecting_clipped_vertices_skips_only_checks() {
    use super::super::clip::clip_polygon;
    let mut rng = crate::raster::tests::Rng(11);
    let vp = Viewport::new(240, 240, 4).unwrap();
    let near = Flt::near(&Mat4::IDENTITY, 0.05);
    let mut clipped = 0;
    for k in 0..20_000 {
        let scale = [1.0, 100.0, 1e6, 1e30, 1e36][k % 5];
        let mut a = [ClipVert::default(); 16];
        let mut b = [ClipVert::default(); 16];
        for v in a.iter_mut().take(3) {
            *v = ClipVert {
                x: rng.float(-1.0, 1.0) * scale,
                y: rng.float(-1.0, 1.0) * scale,
                w: rng.float(-0.5, 1.0) * scale,
            };
        }
        let Ok(c) = clip_polygon(&mut a, 3, &mut b, near) else {
            continue;
        };
        clipped += usize::from(c.clipped);
        for v in c.verts {
            let p = Flt::project(v, &vp);
            assert!(p.is_some(), "{v:?}");
            assert_eq!(Flt::project_clipped(v, &vp), p, "{v:?}");
        }
    }
    assert!(clipped > 5_000, "{clipped}");
}
