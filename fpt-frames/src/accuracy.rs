//! The accuracy study's configurations on the MCU: the cost half of
//! `fpt bench-accuracy`'s rows (its `mcu_instr` column), measured by the
//! firmware's feature `accuracy` and checked against the host bit for bit.
//!
//! * **Configurations**: [`CONFIGS`], the rows of `fpt bench-accuracy`,
//!   each one arithmetic ([`fpt_nostd::raster::Precision`]) and, for
//!   `vertex-q16`/`vertex-q32`, the benchmark tree stored in that encoding
//!   ([`vertex_format`]). `trig-*` build the orbit camera with the
//!   configuration's own trigonometry; the others with `libm`. `int` is
//!   the integer vertex path ([`fpt_nostd::raster::int_path`]) on the `f32`
//!   tree; `int-q16` the same path on the q16 tree with its vertices
//!   drawn as stored (`VertexPath::RAW_Q16_FRAC`: no decoding to `f32`), the
//!   configuration of a core without an FPU.
//! * **Frames**: [`ACCURACY_SCENE`] from every view of [`super::VIEWS`],
//!   240×240 RGB565, cleared to [`super::BACKGROUND`], key light, the
//!   tree's declared effects. [`AccuracyLine`] is the line both sides print
//!   (the firmware appends `instr=N`).
//! * Each configuration renders with its own [`Renderer`] and [`Scratch`]
//!   on the stack (a few KiB: the largest, fixed point, is 106 bytes a
//!   vertex), so nothing stays allocated between configurations.

use core::fmt;

use super::{clear, FrameError, PixelCrc, Probe, ViewSpec, AMBIENT, DIFFUSE, Z_UP};
use super::{Phase, HEIGHT, WALK_DEPTH, WIDTH};
use fpt_nostd::effects::AllEffects;
use fpt_nostd::format::VertexFormat;
use fpt_nostd::raster::{
    Camera, FixedMicromath, FixedPrecision, FloatLibm, FloatMicromath, FramebufferError,
    IntPrecision, Libm, Light, Mat4, MathFns, Precision, Renderer, Rgb565Framebuffer, Scratch,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{draw_frame, FaceIds, Frame};

/// The scene of the measurement.
pub const ACCURACY_SCENE: &str = "bench_city";

/// The study's vertex capacity: what [`ACCURACY_SCENE`]'s trees need (38,
/// from their headers; `fpt info`), not the frame set's
/// [`super::MAX_VERTS`]. Why smaller: the Cortex-M4 firmware keeps the
/// whole 115 KiB frame in its 128 KiB of RAM, and the renderer's scratch
/// of `MAX_VERTS` vertices took its stack to within a kilobyte of the
/// frame (14,808 of 15,856 bytes), past it once the renderer grew. A tree
/// that needs more is refused (`FrameError::Capacity`), never drawn
/// wrong.
pub const ACCURACY_VERTS: usize = 40;

/// The configurations, in `fpt bench-accuracy`'s row order.
pub const CONFIGS: [&str; 15] = [
    "vertex-f32",
    "vertex-q16",
    "vertex-q32",
    "fixed",
    "f32-libm",
    "f32-micromath",
    "subpx-0",
    "subpx-2",
    "subpx-4",
    "subpx-6",
    "subpx-8",
    "trig-libm",
    "trig-micromath",
    "int",
    "int-q16",
];

/// The vertex encoding of the tree configuration `name` draws.
pub fn vertex_format(name: &str) -> VertexFormat {
    match name {
        "vertex-q16" | "int-q16" => VertexFormat::Q16,
        "vertex-q32" => VertexFormat::Q32,
        _ => VertexFormat::F32,
    }
}

/// Draws view `view` of `tree` (in the configuration's
/// [`vertex_format`]) with configuration `name` into the full frame `buf`;
/// returns the checksum ([`PixelCrc`]). `probe` sees one start (before the
/// camera set-up) and one stop (before the checksum).
pub fn render_config<Pr: Probe>(
    name: &str,
    tree: &Tree<'_>,
    view: &ViewSpec,
    buf: &mut [u16],
    probe: &Pr,
) -> Result<u32, FrameError> {
    // (`int-q16` gets the q16 tree: `vertex_format`; the integer path
    // draws it as stored.)
    let f = |_q16: bool| Frame1 { tree, view };
    match name {
        "vertex-f32" | "vertex-q16" | "vertex-q32" | "fixed" | "subpx-4" => {
            render_with::<FixedPrecision<4>, Libm, Pr>(f(false), buf, probe)
        }
        "f32-libm" => render_with::<FloatLibm<4>, Libm, Pr>(f(false), buf, probe),
        "f32-micromath" => render_with::<FloatMicromath<4>, Libm, Pr>(f(false), buf, probe),
        "subpx-0" => render_with::<FixedPrecision<0>, Libm, Pr>(f(false), buf, probe),
        "subpx-2" => render_with::<FixedPrecision<2>, Libm, Pr>(f(false), buf, probe),
        "subpx-6" => render_with::<FixedPrecision<6>, Libm, Pr>(f(false), buf, probe),
        "subpx-8" => render_with::<FixedPrecision<8>, Libm, Pr>(f(false), buf, probe),
        "trig-libm" => render_with::<FixedPrecision<4>, Libm, Pr>(f(false), buf, probe),
        "trig-micromath" => render_with::<
            FixedMicromath<4>,
            <FixedMicromath<4> as Precision>::Math,
            Pr,
        >(f(false), buf, probe),
        "int" => render_with::<IntPrecision<4>, Libm, Pr>(f(false), buf, probe),
        "int-q16" => render_with::<IntPrecision<4>, Libm, Pr>(f(true), buf, probe),
        _ => Err(FrameError::UnknownConfig),
    }
}

/// What one frame of the study draws: a view of a tree, with the q16
/// vertices as stored or decoded.
#[derive(Clone, Copy)]
struct Frame1<'t, 'b, 'v> {
    tree: &'t Tree<'b>,
    view: &'v ViewSpec,
}

/// One frame with arithmetic `P` and orbit trigonometry `T`.
#[inline(never)]
fn render_with<P: Precision, T: MathFns, Pr: Probe>(
    f: Frame1<'_, '_, '_>,
    buf: &mut [u16],
    probe: &Pr,
) -> Result<u32, FrameError> {
    let Frame1 { tree, view, .. } = f;
    let identity = Camera::from_matrix(Mat4::IDENTITY, 1.0);
    // `Renderer::new` refuses only a side that is 0 or too large: the
    // frame's size, reported as such.
    let Some(mut renderer) = Renderer::<P, AllEffects>::new(WIDTH, HEIGHT, &identity) else {
        return Err(FrameError::Buffer(FramebufferError::BadSize));
    };
    let mut scratch = Scratch::<P, ACCURACY_VERTS>::new();
    probe.start(Phase::Xform);
    let aspect = WIDTH as f32 / HEIGHT as f32;
    let camera = view.orbit(tree).camera::<T>(aspect).with_model(&Z_UP);
    let frame = Frame::relative(tree, &camera);
    renderer.set_light(Light::new(frame.key_light(), AMBIENT, DIFFUSE));
    // A failure ends the measurement as well.
    let mut fb = Rgb565Framebuffer::new(buf, WIDTH, HEIGHT).inspect_err(|_| probe.stop())?;
    clear(&mut fb);
    // A q16 tree with the integer path is drawn as stored (see
    // `VertexPath::RAW_Q16_FRAC`).
    let drawn = draw_frame::<P, WALK_DEPTH, ACCURACY_VERTS, AllEffects, _>(
        tree,
        &frame,
        &mut renderer,
        &mut scratch,
        FaceIds::Source,
        &mut fb,
    );
    probe.stop();
    drawn?;
    let mut crc = PixelCrc::new();
    crc.update(fb.data());
    Ok(crc.finish())
}

/// `accuracy config=NAME view=K crc=XXXXXXXX`: one configuration's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AccuracyLine<'a> {
    /// The configuration.
    pub config: &'a str,
    /// The view.
    pub view: u32,
    /// The frame's checksum.
    pub crc: u32,
}

impl fmt::Display for AccuracyLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "accuracy config={} view={} crc={:08x}",
            self.config, self.view, self.crc
        )
    }
}

impl<'a> AccuracyLine<'a> {
    /// Parses the start of a line (trailing fields, such as the firmware's
    /// `instr=N`, are ignored); `None` if it is not one.
    pub fn parse(line: &'a str) -> Option<AccuracyLine<'a>> {
        let (config, view, crc) = super::parse_checksum_line(line, "accuracy", "config=")?;
        Some(AccuracyLine { config, view, crc })
    }

    /// The `instr=N` field of a firmware line, if any.
    pub fn instr(line: &str) -> Option<u64> {
        line.split_ascii_whitespace()
            .find_map(|t| t.strip_prefix("instr="))
            .and_then(|v| v.parse().ok())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn lines_round_trip_and_carry_the_firmware_cost() {
        let l = AccuracyLine {
            config: "subpx-2",
            view: 3,
            crc: 0xdead_beef,
        };
        let text = l.to_string() + " instr=1234";
        assert_eq!(AccuracyLine::parse(&text), Some(l));
        assert_eq!(AccuracyLine::instr(&text), Some(1234));
        assert_eq!(
            AccuracyLine::parse("frame scene=x view=0 crc=00000000"),
            None
        );
        assert_eq!(AccuracyLine::parse("accuracy config=x view=0 crc=0"), None);
    }

    #[test]
    fn every_configuration_is_known_and_others_are_not() {
        let mut buf = [0u16; 4];
        let bytes = fpt_nostd::test_util::Raw::empty().bytes();
        let tree = Tree::from_bytes(&bytes).unwrap_or_else(|e| panic!("{e:?}"));
        let view = &super::super::VIEWS[0];
        for c in CONFIGS {
            // The buffer is too small: every known name gets that far.
            let r = render_config(c, &tree, view, &mut buf, &super::super::NoProbe);
            assert!(matches!(r, Err(FrameError::Buffer(_))), "{c}: {r:?}");
        }
        let r = render_config("nope", &tree, view, &mut buf, &super::super::NoProbe);
        assert_eq!(r, Err(FrameError::UnknownConfig));
    }
}
