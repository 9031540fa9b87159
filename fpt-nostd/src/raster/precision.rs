//! Compile-time choice of arithmetic: which vertex path (fixed point or
//! `f32`), which math library (libm or micromath's fast approximations) and
//! how many sub-pixel bits screen coordinates keep.
//!
//! Everything is resolved at compile time through [`Precision`], so an
//! accuracy study can instantiate the same renderer several times
//! (`Renderer<FixedPrecision<4>>`, `Renderer<FloatLibm<8>>`,
//! `Renderer<FloatMicromath<0>>`, ...) and compare the pictures, and firmware
//! pays only for the configuration it uses.
//!
//! What each part decides:
//! * [`Precision::Path`] — the arithmetic of the vertex transform, clipping
//!   and the perspective divide ([`FixedPath`], [`FloatPath`] or
//!   [`IntPath`]).
//! * [`Precision::Math`] — trigonometry for cameras and, on the float path,
//!   the reciprocal and floor used by the divide ([`Libm`] or [`Micromath`]).
//! * [`Precision::SUB_BITS`] — sub-pixel bits of screen coordinates, 0..=8.
//!   Vertices are snapped to `2^-SUB_BITS` pixel before scan conversion;
//!   the scan conversion itself is exact for the snapped vertices.

use core::marker::PhantomData;

use super::int_path::IntPath;
use super::transform::{FixedPath, FloatPath, VertexPath};

/// The scalar functions the rasterizer needs from a math library.
///
/// Implementations must be total: any `f32` in, some `f32` out, no panic.
pub trait MathFns {
    /// Sine (radians).
    fn sin(x: f32) -> f32;
    /// Cosine (radians).
    fn cos(x: f32) -> f32;
    /// Tangent (radians).
    fn tan(x: f32) -> f32;
    /// Square root.
    fn sqrt(x: f32) -> f32;
    /// Reciprocal `1/x` (may be approximate).
    fn recip(x: f32) -> f32;
    /// Largest integer `<= x` (callers only pass values well inside `i32`).
    fn floor(x: f32) -> f32;
}

/// Correctly rounded (or nearly) functions from the `libm` crate.
#[derive(Clone, Copy, Debug, Default)]
pub struct Libm;

impl MathFns for Libm {
    fn sin(x: f32) -> f32 {
        libm::sinf(x)
    }
    fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
    fn tan(x: f32) -> f32 {
        libm::tanf(x)
    }
    fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    fn recip(x: f32) -> f32 {
        1.0 / x
    }
    fn floor(x: f32) -> f32 {
        libm::floorf(x)
    }
}

/// Fast approximations from the `micromath` crate (smaller and faster on a
/// Cortex-M0, a few ulps to ~1e-3 relative error).
///
/// The calls go through `<f32 as F32Ext>::...` explicitly: in a test build
/// `std` is linked and its inherent `f32::sin` would otherwise silently win
/// method resolution, and the study would compare libm against libm.
#[derive(Clone, Copy, Debug, Default)]
pub struct Micromath;

impl MathFns for Micromath {
    fn sin(x: f32) -> f32 {
        <f32 as micromath::F32Ext>::sin(x)
    }
    fn cos(x: f32) -> f32 {
        <f32 as micromath::F32Ext>::cos(x)
    }
    fn tan(x: f32) -> f32 {
        <f32 as micromath::F32Ext>::tan(x)
    }
    fn sqrt(x: f32) -> f32 {
        <f32 as micromath::F32Ext>::sqrt(x)
    }
    fn recip(x: f32) -> f32 {
        <f32 as micromath::F32Ext>::recip(x)
    }
    fn floor(x: f32) -> f32 {
        <f32 as micromath::F32Ext>::floor(x)
    }
}

/// A complete arithmetic configuration (see module docs).
pub trait Precision {
    /// Sub-pixel bits of screen coordinates (0..=8).
    const SUB_BITS: u32;
    /// Math library for cameras (and the float path's divide).
    type Math: MathFns;
    /// Vertex transform / clip / divide arithmetic.
    type Path: VertexPath;
}

/// The generic configuration: vertex path `Pa`, math library `M`, `SUB`
/// sub-pixel bits. Use the aliases below for the usual combinations.
#[derive(Clone, Copy, Debug, Default)]
pub struct Config<Pa, M, const SUB: u32>(PhantomData<(Pa, M)>);

impl<Pa: VertexPath, M: MathFns, const SUB: u32> Precision for Config<Pa, M, SUB> {
    // Evaluated when the configuration is used: more than 8 sub-pixel bits
    // would break the documented i64 headroom of edge setup (scan.rs).
    const SUB_BITS: u32 = {
        assert!(SUB <= 8, "at most 8 sub-pixel bits are supported");
        SUB
    };
    type Math = M;
    type Path = Pa;
}

/// Fixed-point vertex path (16.16 model coordinates and matrix), libm for
/// camera trigonometry. The default for firmware without an FPU.
pub type FixedPrecision<const SUB: u32 = 4> = Config<FixedPath<16>, Libm, SUB>;
/// Fixed-point vertex path with micromath camera trigonometry (no libm
/// linked at all).
pub type FixedMicromath<const SUB: u32 = 4> = Config<FixedPath<16>, Micromath, SUB>;
/// Integer vertex path (32-bit multiplies, one 32-bit division a vertex:
/// see [`super::int_path`]), libm for camera trigonometry. For cores
/// without an FPU; expects the renderer's normalised frames
/// ([`crate::render::Frame`]: vertices within `±2^14`).
pub type IntPrecision<const SUB: u32 = 4> = Config<IntPath<1>, Libm, SUB>;
/// `f32` vertex path with libm: the accuracy reference.
pub type FloatLibm<const SUB: u32 = 4> = Config<FloatPath<Libm>, Libm, SUB>;
/// `f32` vertex path with micromath's fast reciprocal, floor and trig.
pub type FloatMicromath<const SUB: u32 = 4> = Config<FloatPath<Micromath>, Micromath, SUB>;
/// The configuration the rest of the project uses unless it says otherwise.
pub type DefaultPrecision = FixedPrecision<4>;

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn micromath_is_really_used_and_close_to_libm() {
        let mut max_diff = 0.0f32;
        for i in -50..50 {
            let x = i as f32 * 0.0731;
            assert!(close(Micromath::sin(x), Libm::sin(x), 2e-3));
            assert!(close(Micromath::cos(x), Libm::cos(x), 2e-3));
            max_diff = max_diff.max((Micromath::sin(x) - Libm::sin(x)).abs());
            if (-0.7..0.7).contains(&x) {
                // The range camera half-fovs use.
                assert!(
                    close(
                        Micromath::tan(x),
                        Libm::tan(x),
                        2e-2 * (1.0 + Libm::tan(x).abs())
                    ),
                    "{x}"
                );
            }
            let y = 0.37 + i as f32 * 1.7 + 50.0 * 1.7;
            assert!(close(Micromath::recip(y) * y, 1.0, 1e-4));
            // micromath's sqrt is a bit trick with ~5-7 % error (documented).
            assert!(close(
                Micromath::sqrt(y),
                Libm::sqrt(y),
                0.08 * Libm::sqrt(y)
            ));
            assert_eq!(Micromath::floor(x * 10.0), Libm::floor(x * 10.0));
        }
        // If this were std/libm in disguise the difference would be zero.
        assert!(max_diff > 0.0);
    }

    #[test]
    fn sub_bits_come_from_the_configuration() {
        assert_eq!(FixedPrecision::<0>::SUB_BITS, 0);
        assert_eq!(FloatLibm::<8>::SUB_BITS, 8);
        assert_eq!(DefaultPrecision::SUB_BITS, 4);
    }
}
