//! The price of each effect, measured the same way on the firmware and
//! checked on the host: the benchmark scene drawn with an effect on, with
//! it off, and through a pipeline compiled without it
//! ([`fpt_nostd::effects`]).
//!
//! * **Scene and view**: [`EFFECT_SCENE`] from view [`EFFECT_VIEW`] of
//!   [`super::VIEWS`], with the frame set's precision, light and
//!   background.
//! * **Effects**: the scene's declared set `base` (its tree's header) with
//!   the measured effect added (`on`) or removed (`off`, and `bare`, whose
//!   pipeline type leaves it out: [`bare_pipeline`]). `off` and `bare` run
//!   the same flags, so they must draw the same pixels; the firmware checks
//!   their checksums agree.
//! * **Target**: `dither` is measured on a 240×240 `BinaryColor`
//!   framebuffer (ordered dithering through [`fpt_nostd::raster::Dither`] when
//!   on, the plain threshold when off); every other effect on the frame
//!   set's RGB565 framebuffer. The checksum is the CRC-32 of the
//!   framebuffer's storage (`u16` little-endian, or the packed bytes).

use embedded_graphics::pixelcolor::{BinaryColor, Rgb888};

use super::{clear, FrameError, FramePrecision, PixelCrc, Probe, ViewSpec, AMBIENT, DIFFUSE};
use super::{Phase, HEIGHT, MAX_VERTS, WALK_DEPTH, WIDTH};
use fpt_nostd::effects::{Compiled, Effects};
use fpt_nostd::raster::{
    BinaryFramebuffer, DepthCue, Dither, Light, Renderer, Rgb565Framebuffer, Scratch, SpanSink,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{draw_frame, FaceIds, Frame};

/// The scene the effects are measured on.
pub const EFFECT_SCENE: &str = "bench_city";
/// Its view (index into [`super::VIEWS`]).
pub const EFFECT_VIEW: usize = 0;
/// Bytes of the `BinaryColor` framebuffer of the `dither` measurement.
pub const MONO_BYTES: usize = (WIDTH as usize).div_ceil(8) * HEIGHT as usize;

/// Where an effect measurement draws.
#[derive(Debug)]
pub enum EffectTarget<'a> {
    /// The RGB565 frame ([`super::FRAME_WORDS`] words).
    Rgb565(&'a mut [u16]),
    /// A `BinaryColor` frame ([`MONO_BYTES`] bytes), ordered-dithered or
    /// thresholded.
    Mono {
        /// The packed pixels.
        buf: &'a mut [u8],
        /// Dither (else threshold).
        dither: bool,
    },
}

/// The effects of the `on` and `off` runs of effect `e` for a scene that
/// declares `base`.
pub fn on_off(base: Effects, e: Effects) -> (Effects, Effects) {
    (base.with(e), base.without(e))
}

/// The bits of a pipeline with every effect but `e`: the `BITS` of
/// [`Bare`] for the `bare` run.
pub const fn bare_pipeline(e: Effects) -> u32 {
    Effects::ALL.without(e).bits()
}

/// The pipeline of a `bare` run: the effects with bits `BITS`, as
/// [`fpt_nostd::effects::Pipeline`], but switching only
/// [`fpt_nostd::effects::EXTRAS`] ([`Compiled::SWITCHED`]): two copies of
/// the walk-and-fill, not up to eight, for the firmware's flash. The code a
/// `bare` run executes is the same as through a `Pipeline` (the scene
/// declares culling and lighting, which a `bare` run leaves on unless it
/// measures them; `tests/tests/all/effects_pipeline.rs` checks it with
/// [`fpt_nostd::effects::compiled_for`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bare<const BITS: u32>;

impl<const BITS: u32> Compiled for Bare<BITS> {
    const SET: Effects = Effects::from_bits(BITS);
    const SWITCHED: Effects = fpt_nostd::effects::EXTRAS;
}

/// Whether pipeline `E` draws into the `BinaryColor` target: the pipelines
/// of the `dither` measurement (every effect, or every one but dithering).
/// Only those hold the copies of the walk-and-fill for it.
const fn mono_pipeline<E: Compiled>() -> bool {
    E::SET.with(Effects::DITHER).bits() == Effects::ALL.bits()
}

/// Whether pipeline `E` draws into the RGB565 target: all but the one
/// without dithering, which only the `dither` measurement uses.
const fn rgb_pipeline<E: Compiled>() -> bool {
    E::SET.contains(Effects::DITHER)
}

/// Draws the effect scene's view with `effects` through `renderer` (whose
/// type fixes the compiled-in stages) and `scratch` into `target`; returns
/// the checksum. `probe` sees one start (before the frame set-up) and one
/// stop (before the checksum). [`FrameError::Target`]: a target the
/// pipeline is not for (the `BinaryColor` one is only for the pipelines
/// of the `dither` measurement, the RGB565 one for all others).
pub fn render_effect<E: Compiled, Pr: Probe>(
    renderer: &mut Renderer<FramePrecision, E>,
    scratch: &mut Scratch<FramePrecision, MAX_VERTS>,
    tree: &Tree<'_>,
    view: &ViewSpec,
    effects: Effects,
    target: EffectTarget<'_>,
    probe: &Pr,
) -> Result<u32, FrameError> {
    probe.start(Phase::Xform);
    let frame = view.frame(tree);
    renderer.set_camera(&frame.camera);
    renderer.set_light(Light::new(frame.key_light(), AMBIENT, DIFFUSE));
    renderer.set_effects(Some(effects));
    let (near, far) = frame.depth_range(tree);
    renderer.set_depth_cue(DepthCue {
        near,
        far,
        fog: Rgb888::from(super::BACKGROUND),
        ..DepthCue::default()
    });
    let mut crc = PixelCrc::new();
    match target {
        EffectTarget::Rgb565(buf) => {
            // A constant: the code below is not compiled for such a pipeline.
            if !const { rgb_pipeline::<E>() } {
                probe.stop();
                return Err(FrameError::Target);
            }
            // A failure ends the measurement as well.
            let mut fb =
                Rgb565Framebuffer::new(buf, WIDTH, HEIGHT).inspect_err(|_| probe.stop())?;
            clear(&mut fb);
            let drawn = draw(renderer, scratch, tree, &frame, &mut fb);
            probe.stop();
            drawn?;
            crc.update(fb.data());
        }
        EffectTarget::Mono { buf, dither } => {
            if !const { mono_pipeline::<E>() } {
                probe.stop();
                return Err(FrameError::Target);
            }
            let mut fb =
                BinaryFramebuffer::new(buf, WIDTH, HEIGHT).inspect_err(|_| probe.stop())?;
            fb.fill_all(BinaryColor::Off);
            // Only a pipeline with the stage dithers (and only those hold
            // the copy that does).
            let drawn = if const { E::SET.contains(Effects::DITHER) } && dither {
                draw(
                    renderer,
                    scratch,
                    tree,
                    &frame,
                    &mut Dither::new(&mut fb, 2),
                )
            } else {
                draw(renderer, scratch, tree, &frame, &mut fb)
            };
            probe.stop();
            drawn?;
            crc.update_bytes(fb.data());
        }
    }
    Ok(crc.finish())
}

#[inline(never)]
fn draw<E: Compiled, K: SpanSink>(
    renderer: &mut Renderer<FramePrecision, E>,
    scratch: &mut Scratch<FramePrecision, MAX_VERTS>,
    tree: &Tree<'_>,
    frame: &Frame,
    sink: &mut K,
) -> Result<(), FrameError> {
    draw_frame::<FramePrecision, WALK_DEPTH, MAX_VERTS, E, K>(
        tree,
        frame,
        renderer,
        scratch,
        FaceIds::Source,
        sink,
    )?;
    Ok(())
}
