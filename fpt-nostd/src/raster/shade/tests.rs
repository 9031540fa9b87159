//! Tests of flat shading, the intensity memo and depth cueing.

use super::*;
use embedded_graphics::pixelcolor::RgbColor;

/// The diffuse term's `i32` product is the saturating 64-bit `Fx14`
/// product it replaced, for every weight `Light::new` can hold (the
/// clamped ends included) and normals of every length and sign, unit or
/// not, tiny or huge (the general normalisation).
#[test]
fn intensity_is_the_saturating_fx14_formula() {
    let mut rng = crate::raster::tests::Rng(23);
    let reference = |l: &Light, n: Option<[Fx14; 3]>| {
        let cos = match (n, l.dir) {
            (Some(n), Some(d)) => {
                let dot: i32 = (0..3).map(|i| n[i].raw() * d[i].raw()).sum();
                Fx14::from_raw(dot >> 14)
            }
            _ => Fx14::ZERO,
        };
        (l.ambient + l.diffuse.saturating_mul(cos.max(Fx14::ZERO))).clamp(Fx14::ZERO, Fx14::ONE)
    };
    let weights = [-1.0, 0.0, 0.1, 0.25, 0.5, 0.75, 1.0, 2.0];
    for k in 0..40_000 {
        let dir = [0; 3].map(|_| rng.float(-1.0, 1.0));
        let (a, d) = (weights[k % 8], weights[(k / 8) % 8]);
        let l = Light::new(dir, a, d);
        let scale = [1.0, 1e-3, 7.0, 1e30][k % 4];
        let v = [0; 3].map(|_| rng.float(-1.0, 1.0) * scale);
        // Unit normals too, which take the fast path.
        let len = v.iter().map(|c| c * c).sum::<f32>().sqrt();
        let v = if k % 2 == 0 { v.map(|c| c / len) } else { v };
        let n = unit_from_f32(v);
        assert_eq!(l.intensity(v), reference(&l, n), "{l:?} {v:?}");
    }
}

#[test]
fn integer_rounding_is_exact() {
    // Against f64, where c · 2^frac + 0.5 is exact for these values.
    let mut x = 0x1234_5678u32;
    let check = |c: f32| {
        for frac in [14, 29] {
            let want = (f64::from(c.abs()) * f64::from(1u32 << frac) + 0.5).floor();
            let want = if c < 0.0 { -want } else { want };
            assert_eq!(f64::from(round_scaled(c, frac)), want, "{c:e} q{frac}");
        }
    };
    let check = |c: f32| {
        check(c);
        for frac in [14, 29] {
            assert_eq!(
                round_scaled_bits(c, frac),
                round_scaled_fpu(c, frac),
                "{c:e}"
            );
        }
    };
    for c in [
        0.0,
        -0.0,
        1.0,
        -1.0,
        1.999_999_9,
        0.5,
        1e-38,
        1e-45,
        3.0517578e-5,
    ] {
        check(c);
    }
    for _ in 0..200_000 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        // Every sign and exponent below 2 (bits below 0x4000_0000).
        check(f32::from_bits(x & 0xbfff_ffff));
    }
    // Exactly half a unit goes away from zero.
    check(0.5 / 16384.0);
    check(-1.5 / 16384.0);
}

/// The integer Q14 of a compact component is the rounding of the
/// exact `c · 2^14 / 32767` (in `i64`), for every `i16` but −32768
/// (which validation refuses). The `f32` normal the reader decodes
/// (`c · (1 / 32767)`, what lighting rounded before) is off by a
/// rounding of its own: where the exact value is within about 10⁻³
/// of a half (`c` even, `|c|` near 32767, the quotient just below
/// a half), it lands one unit away from the exact rounding.
#[test]
fn compact_components_round_exactly() {
    let mut off = 0;
    for c in -32767..=32767i16 {
        let q = q14_of_compact(c);
        let n = i64::from(c) << 14;
        let exact = (n.abs() * 2 + 32767) / (2 * 32767);
        assert_eq!(i64::from(q), exact * n.signum(), "{c}");
        let decoded = round_scaled(f32::from(c) * (1.0 / 32767.0), 14);
        assert!((q - decoded).abs() <= 1, "{c}");
        off += usize::from(q != decoded);
    }
    assert_eq!(off, OFF_BY_ONE);
    assert_eq!(q14_of_compact(i16::MIN), -16384);
}

/// How many of the 65,535 components [`q14_of_compact`] rounds one
/// unit away from the decoded `f32` (see the test above).
const OFF_BY_ONE: usize = 32;

/// Well-formed compact normals (length 32766 to 32768) take the
/// short path: the components rounded one by one, and lit within a
/// rounding unit of the `f32` normals they decode to; other lengths
/// are normalised as integers. Flipping is exact.
#[cfg(feature = "compact-planes")]
#[test]
fn compact_normals_take_the_short_path() {
    let mut rng = crate::raster::tests::Rng(41);
    let light = Light::new([0.3, -0.5, 0.8], 0.25, 0.75);
    let mut seen = 0;
    while seen < 200_000 {
        let v = [0; 3].map(|_| rng.float(-1.0, 1.0));
        let len = v.iter().map(|c| c * c).sum::<f32>().sqrt();
        if len <= 1e-3 {
            continue;
        }
        let m = v.map(|c| libm::roundf(c / len * 32767.0) as i16);
        let len2: i64 = m.iter().map(|&c| i64::from(c).pow(2)).sum();
        if !(32766 * 32766..=32768 * 32768).contains(&len2) {
            continue;
        }
        seen += 1;
        let q = m.map(q14_of_compact);
        let qlen2: u32 = q.iter().map(|c| c.unsigned_abs().pow(2)).sum();
        assert!(qlen2.abs_diff(1 << 28) <= 1 << 16, "{m:?}");
        assert_eq!(unit_from_compact(m), Some(q.map(Fx14::from_raw)));
        let f = Normal::from_compact(m).to_f32();
        let (lit, decoded) = (
            light.intensity_of(Normal::from_compact(m)),
            light.intensity(f),
        );
        assert!((lit.raw() - decoded.raw()).abs() <= 1, "{m:?}");
        let back = Normal::from_compact(m).flipped();
        assert_eq!(back.to_f32(), f.map(|c| -c));
        let Some(b) = back.as_compact() else {
            panic!("{back:?}")
        };
        assert_eq!(unit_from_compact(b), Some(q.map(|c| Fx14::from_raw(-c))));
    }
    // An `f32` normal flips by its sign bits, as `-c` does.
    for v in [[0.0f32, -0.0, 1.0], [0.6, -0.8, 1e-30]] {
        let back = Normal::from_f32(v).flipped();
        assert_eq!(
            back.as_f32().map(|b| b.map(f32::to_bits)),
            Some(v.map(|c| (-c).to_bits()))
        );
        assert_eq!(back.as_compact(), None);
    }
    // The extreme lengths of a well-formed entry, on an axis and off.
    for m in [
        [32767i16, 0, 0],
        [0, -32766, 0],
        [18918, 18918, 18918],
        [-18917, 18918, -18918],
    ] {
        assert_eq!(
            unit_from_compact(m),
            Some(m.map(|c| Fx14::from_raw(q14_of_compact(c))))
        );
    }
    // Any other length: normalised (as `intensity_q`), zero: none.
    for m in [
        [0i16, 0, 1],
        [3, 4, 0],
        [-32768, -32768, -32768],
        [100, -200, 50],
    ] {
        assert_eq!(
            light.intensity_of(Normal::from_compact(m)),
            light.intensity_q(m.map(i32::from)),
            "{m:?}"
        );
    }
    assert_eq!(unit_from_compact([0; 3]), None);
}

/// The memo gives what lighting gives, whichever form a normal comes
/// in, with `f32` and compact normals of the same words in turn (a
/// subnormal `f32` is a small integer's pattern).
#[cfg(feature = "compact-planes")]
#[test]
fn memo_keys_both_forms_apart() {
    let light = Light::new([0.0, 0.6, 0.8], 0.25, 0.75);
    let memo = IntensityMemo::EMPTY;
    let c = [200, 100, 50];
    let normals = [
        Normal::from_compact([0, 0, 32767]),
        Normal::from_f32([0.0, 0.0, f32::from_bits(32767)]),
        Normal::from_f32([0.0, 0.0, 1.0]),
        Normal::from_compact([0, 0, -32767]),
        Normal::from_compact([0, 19660, 26214]),
        Normal::from_f32([0.0, f32::from_bits(19660), f32::from_bits(26214)]),
        // The packed words of the one before, in an `f32` normal.
        Normal::from_f32([f32::from_bits(19660 << 16), f32::from_bits(26214), 1.0]),
    ];
    for _ in 0..3 {
        for n in normals {
            let want = shade_color(ShadeMode::Lambert, c, light.intensity_of(n));
            assert_eq!(memo.shade(ShadeMode::Lambert, &light, n, c), want, "{n:?}");
        }
    }
}

/// The six axis normals take six distinct memo entries, as `f32`
/// vectors and as compact ones (see `IntensityMemo::entry`).
#[test]
fn memo_entries_of_axis_normals_differ() {
    let memo = IntensityMemo::EMPTY;
    let slot = |n: Normal| {
        let e = memo.entry(n.bits).expect("a memo on the host");
        (e as *const Cell<[u32; 4]>).addr()
    };
    let axes: [[i16; 3]; 6] = core::array::from_fn(|k| {
        let mut v = [0i16; 3];
        v[k / 2] = if k % 2 == 0 { 1 } else { -1 };
        v
    });
    let distinct = |mut slots: [usize; 6]| {
        slots.sort_unstable();
        slots.windows(2).all(|w| w[0] != w[1])
    };
    assert!(distinct(
        axes.map(|v| slot(Normal::from_f32(v.map(f32::from))))
    ));
    #[cfg(feature = "compact-planes")]
    assert!(distinct(
        axes.map(|v| slot(Normal::from_compact(v.map(|c| c * 32767))))
    ));
}

#[test]
fn unit_vectors_have_unit_length() {
    for v in [
        [3.0, 4.0, 0.0],
        [1e-20, -2e-20, 5e-21],
        [1e30, 1.0, -1e30],
        [0.0, 0.0, -7.0],
    ] {
        let Some(u) = unit_from_f32(v) else {
            panic!("{v:?}")
        };
        let len2: i64 = u.iter().map(|c| c.raw() as i64 * c.raw() as i64).sum();
        let one = 1i64 << 28;
        assert!((len2 - one).abs() < one / 2000, "{v:?} {u:?}");
    }
    assert_eq!(unit_from_f32([0.0; 3]), None);
    // The unit fast path agrees with the square-root path to one Q14
    // unit (scaled copies take the slow path).
    for v in [[0.6f32, 0.8, 0.0], [0.48, 0.6, 0.64], [-0.36, 0.48, -0.8]] {
        let (Some(fast), Some(slow)) = (unit_from_f32(v), unit_from_f32(v.map(|c| c * 3.0))) else {
            panic!("{v:?}")
        };
        for k in 0..3 {
            assert!((fast[k].raw() - slow[k].raw()).abs() <= 1, "{v:?}");
        }
    }
    assert_eq!(unit_from_f32([f32::NAN, 1.0, 0.0]), None);
    let u = unit_from_ints([3, 4, 0]).unwrap_or_default();
    assert_eq!(u.map(|c| c.raw()), [9830, 13107, 0]); // 0.6, 0.8 in Q14
}

#[test]
fn lambert_terms() {
    let light = Light::new([0.0, 0.0, 2.0], 0.2, 0.8);
    let near = |a: Fx14, b: f32| (a.to_f32() - b).abs() < 1e-3;
    assert!(near(light.intensity([0.0, 0.0, 5.0]), 1.0));
    assert!(near(light.intensity([1.0, 0.0, 0.0]), 0.2));
    assert!(near(light.intensity([0.0, 0.0, -1.0]), 0.2)); // one-sided
    let cos60 = [libm::sqrtf(3.0), 0.0, 1.0]; // 60° from the light
    assert!(near(light.intensity(cos60), 0.2 + 0.8 * 0.5));
    assert!(near(light.intensity([0.0; 3]), 0.2));
    assert_eq!(
        light.intensity_q([0, 0, 1 << 16]),
        light.intensity([0.0, 0.0, 1.0])
    );
    // Ambient + diffuse over 1 saturates at 1.
    let hot = Light::new([0.0, 1.0, 0.0], 0.9, 0.9);
    assert_eq!(hot.intensity([0.0, 1.0, 0.0]), Fx14::ONE);
    // No light direction: ambient only.
    let amb = Light::new([0.0; 3], 0.3, 1.0);
    assert!(near(amb.intensity([0.0, 1.0, 0.0]), 0.3));
}

#[test]
fn modes() {
    let light = Light::new([0.0, 0.0, 1.0], 0.0, 1.0);
    let c = [200, 100, 50];
    assert_eq!(
        shade(ShadeMode::Flat, &light, [1.0, 0.0, 0.0], c),
        Rgb888::new(200, 100, 50)
    );
    let half = [libm::sqrtf(3.0), 0.0, 1.0];
    let l = shade(ShadeMode::Lambert, &light, half, c);
    assert_eq!((l.r(), l.g(), l.b()), (100, 50, 25));
    let g = shade(ShadeMode::Grey(255), &light, half, c);
    assert!(g.r() == g.g() && g.g() == g.b() && (127..=128).contains(&g.r()));
    let dark = shade(ShadeMode::Lambert, &light, [0.0, 0.0, -1.0], c);
    assert_eq!(dark, Rgb888::new(0, 0, 0));
}
