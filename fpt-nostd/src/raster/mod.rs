//! The rasterizer: flat-shaded polygons to framebuffers, bands or any
//! embedded-graphics `DrawTarget`, with no depth buffer (the priority tree
//! gives the drawing order), no allocation and no panics on any input.
//!
//! One stage per module, each taking plain data:
//!
//! | stage | module | in → out |
//! |---|---|---|
//! | arithmetic choice | [`precision`] | [`Precision`]: vertex path, math library, sub-pixel bits |
//! | camera | [`camera`] | orbit parameters or a matrix → [`Camera`] |
//! | transform / divide | [`transform`], [`int_path`] | model `[f32; 3]` or q-ints → clip vertex → [`ScreenPt`] |
//! | clipping | [`clip`] | clip polygon → polygon inside near plane and guard band |
//! | edge setup | [`edge`] | screen polygon → exact stepped edges |
//! | scan conversion | [`scan`] | edges → spans to a [`SpanSink`] |
//! | shading | [`shade`] | normal + colour (+ depth cue) → `Rgb888` |
//! | smooth shading | [`gouraud`] | corner normals → colour plane → spans in runs of equal colour |
//! | outlines | [`outline`] | screen polygon → one-pixel edge lines |
//! | dithering | [`dither`] | spans → ordered-dithered grey or mono pixels |
//! | targets | [`framebuffer`], [`sink`], [`band`] | spans → pixels |
//! | pipeline | [`renderer`] | one polygon through all of the above |
//!
//! Guarantees the stages build on each other for:
//! * Clipping happens in clip space, before any conversion to screen
//!   integers, so screen coordinates are bounded (guard band) and no
//!   fixed-point value can overflow whatever the camera or the input.
//! * Shared edges: identical clip intersections (clip), identical
//!   projections (transform) and exact crossings with a top-left ownership
//!   rule (edge) mean that polygons sharing an edge leave no crack and
//!   paint no pixel twice.
//! * Bands: the fill is exact from any starting row, so banded output is
//!   identical to full-frame output.
//!
//! One polygon through the pipeline (a tree renderer,
//! [`crate::render::TreeRenderer`], does this for each polygon the walk
//! hands out, back to front):
//! ```
//! use fpt_nostd::raster::{Camera, DefaultPrecision, Face, Mat4, Outcome, Renderer};
//! use fpt_nostd::raster::{Rgb565Framebuffer, Scratch};
//! let camera = Camera::from_matrix(Mat4::IDENTITY, 1e-3);
//! let mut r = Renderer::<DefaultPrecision>::new(32, 24, &camera).unwrap();
//! let mut scratch = Scratch::<DefaultPrecision, 16>::new();
//! let mut pixels = [0u16; 32 * 24];
//! let mut fb = Rgb565Framebuffer::new(&mut pixels, 32, 24).unwrap();
//! let face = Face { normal: [0.0, 0.0, 1.0].into(), color: [255, 128, 0], id: 7, hidden_edges: 0 };
//! // A triangle in clip space (the identity camera), counter-clockwise.
//! let tri = [[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.0, 0.5, 0.0]];
//! let out = r.draw_polygon(&mut scratch, tri, &face, &mut fb);
//! assert!(matches!(out, Outcome::Drawn { spans } if spans > 0));
//! ```

pub mod band;
pub mod camera;
pub(crate) mod carry;
mod chain;
pub mod clip;
pub mod dither;
pub mod edge;
pub mod framebuffer;
pub mod gouraud;
pub mod int_path;
pub mod list;
pub mod outline;
pub mod precision;
pub mod proof;
pub mod renderer;
pub mod scan;
pub mod shade;
pub mod sink;
pub mod transform;
pub mod vcache;

#[cfg(test)]
pub(crate) mod tests;
#[cfg(test)]
mod tests_render;

pub use band::{band_starts, Band};
pub use camera::{Camera, Mat4, Orbit, Up};
pub use dither::{Dither, DitherFormat};
pub use framebuffer::{
    BinaryFormat, BinaryFramebuffer, Framebuffer, FramebufferError, Gray8Format, Gray8Framebuffer,
    PixelFormat, Rgb565BeFormat, Rgb565Format, Rgb565Framebuffer, Rgb888Format, Rgb888Framebuffer,
};
pub use precision::{
    Config, DefaultPrecision, FixedMicromath, FixedPrecision, FloatLibm, FloatMicromath,
    IntPrecision, Libm, MathFns, Micromath, Precision,
};
pub use renderer::{Face, Outcome, RenderStats, Renderer, Scratch, SkipReason};
pub use scan::{fill_polygon, FillRule, Paint, SpanBounds, SpanSink};
pub use shade::{DepthCue, Light, Normal, ShadeMode};
pub use sink::{DrawTargetSink, IdBuffer};
pub use transform::{ScreenPt, Viewport};
