//! The standard orbit: the one definition of the frames `fpt mcu-bench`
//! draws, shared by the firmware (`firmware/src/bin/bench.rs`) and the host
//! check, so that their checksums can be compared bit for bit.
//!
//! # Definition
//!
//! Frame `i` of `n` of a tree on a `width × height` RGB565 display:
//!
//! * perspective, vertical field of view [`FOV_DEGREES`] (60°), aspect
//!   `width / height`;
//! * the eye at [`DISTANCE`] (2.1) bounding radii from the bounding-sphere
//!   centre, looking at that centre, pitch [`PITCH_DEGREES`] (25°), yaw
//!   `360° · i / n`, the model's y axis up (no rotation of the model);
//! * lit by [`fpt_nostd::render::Frame::key_light`] (ambient [`AMBIENT`], diffuse
//!   [`DIFFUSE`]); drawn with the tree's declared effects;
//! * background [`BACKGROUND`], RGB565 (2, 4, 6);
//! * checksummed as [`super::PixelCrc`] (the firmware frames' checksum:
//!   little-endian RGB565 words, row-major), band by band.
//!
//! The camera is derived with [`Libm`] trigonometry whatever the vertex
//! arithmetic ([`OrbitPrecision`]), so every precision sees the same view.
//!
//! # Drawing
//!
//! [`draw_band_frame`] is the one call into the renderer (today
//! [`TreeRenderer::render_banded`]); the firmware and the host both go
//! through it, so a new band API is a change in one place.

use core::fmt;

use embedded_graphics::pixelcolor::Rgb565;

use super::PixelCrc;
use fpt_nostd::raster::framebuffer::Rgb565Format;
use fpt_nostd::raster::{
    FixedPrecision, FloatLibm, Framebuffer, IntPrecision, Libm, Light, Orbit, Precision,
    RenderStats,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{BandBuffer, Frame, RenderError, TreeRenderer};

/// Vertical field of view, degrees.
pub const FOV_DEGREES: f32 = 60.0;
/// Eye distance from the bounding-sphere centre, in bounding radii.
pub const DISTANCE: f32 = 2.1;
/// Elevation of the eye, degrees.
pub const PITCH_DEGREES: f32 = 25.0;
/// Frames of one orbit unless told otherwise.
pub const DEFAULT_FRAMES: u32 = 100;
/// The colour of pixels no polygon covers: RGB565 (2, 4, 6).
pub const BACKGROUND: Rgb565 = Rgb565::new(2, 4, 6);
/// Ambient weight of the key light ([`Light::AMBIENT`]).
pub const AMBIENT: f32 = Light::AMBIENT;
/// Diffuse weight of the key light ([`Light::DIFFUSE`]).
pub const DIFFUSE: f32 = Light::DIFFUSE;
/// Vertex capacity of the host's scratch for the orbit: more than the
/// trees of the project's scenes and shared models need (house 99); a
/// tree that needs more is refused ([`fpt_nostd::render::CapacityError`]). The
/// firmware takes the tree's own ([`fpt_nostd::reader::Capacities`]).
pub const MAX_VERTS: usize = 256;

/// The orbit of frame `i` of `n` (`n = 0` is taken as 1), in coordinates
/// relative to the tree's bounding-sphere centre.
pub fn orbit(tree: &Tree<'_>, i: u32, n: u32) -> Orbit {
    let deg = core::f32::consts::PI / 180.0;
    let yaw = 2.0 * core::f32::consts::PI * (i as f32 / n.max(1) as f32);
    let distance = DISTANCE * tree.bounding_radius();
    Orbit::new(
        [0.0; 3],
        yaw,
        PITCH_DEGREES * deg,
        distance,
        FOV_DEGREES * deg,
    )
}

/// What the renderer and the walk need for frame `i` of `n` of `tree` on a
/// `width × height` display.
///
/// Out of line: its `f64` camera set-up (software floating point on a
/// Cortex-M) has large temporaries, which inlined into
/// [`draw_band_frame`] would stay on the stack below the whole band loop
/// (on a 16 KiB Cortex-M0 the stack is what decides the working memory).
#[inline(never)]
pub fn frame(tree: &Tree<'_>, i: u32, n: u32, width: u32, height: u32) -> Frame {
    let aspect = width as f32 / height.max(1) as f32;
    let camera = orbit(tree, i, n).camera::<Libm>(aspect);
    Frame::relative(tree, &camera)
}

/// The vertex arithmetic of a benchmark, by name (`fpt mcu-bench
/// --precision NAME`; the firmware's `FPT_BENCH_PRECISION`). A new
/// precision is one more variant here and one more arm in
/// [`OrbitPrecision::visit`] and [`OrbitPrecision::type_path`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrbitPrecision {
    /// `f32` vertex path with libm, 4 sub-pixel bits ([`FloatLibm<4>`]).
    F32Libm,
    /// 16.16 fixed-point vertex path, 4 sub-pixel bits
    /// ([`FixedPrecision<4>`]).
    Fixed,
    /// The integer path for cores without an FPU: 32-bit multiplies and
    /// no division per vertex, 4 sub-pixel bits ([`IntPrecision<4>`]).
    Int,
}

/// Something generic over the precision, for [`OrbitPrecision::visit`].
pub trait PrecisionVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with the precision as a type.
    fn visit<P: Precision>(self) -> Self::Output;
}

impl OrbitPrecision {
    /// Every precision, in the order of [`OrbitPrecision::NAMES`].
    pub const ALL: [OrbitPrecision; 3] = [
        OrbitPrecision::F32Libm,
        OrbitPrecision::Fixed,
        OrbitPrecision::Int,
    ];
    /// Their names.
    pub const NAMES: [&'static str; 3] = ["f32-libm", "fixed", "int"];

    /// The name (`f32-libm`, `fixed`).
    pub fn name(self) -> &'static str {
        match self {
            OrbitPrecision::F32Libm => "f32-libm",
            OrbitPrecision::Fixed => "fixed",
            OrbitPrecision::Int => "int",
        }
    }

    /// The precision called `name`, if any.
    pub fn parse(name: &str) -> Option<OrbitPrecision> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The Rust path of the type (for code generated by the firmware's
    /// build script).
    pub fn type_path(self) -> &'static str {
        match self {
            OrbitPrecision::F32Libm => "fpt_nostd::raster::FloatLibm<4>",
            OrbitPrecision::Fixed => "fpt_nostd::raster::FixedPrecision<4>",
            OrbitPrecision::Int => "fpt_nostd::raster::IntPrecision<4>",
        }
    }

    /// Calls `v` with the precision as a type.
    pub fn visit<V: PrecisionVisitor>(self, v: V) -> V::Output {
        match self {
            OrbitPrecision::F32Libm => v.visit::<FloatLibm<4>>(),
            OrbitPrecision::Fixed => v.visit::<FixedPrecision<4>>(),
            OrbitPrecision::Int => v.visit::<IntPrecision<4>>(),
        }
    }
}

impl fmt::Display for OrbitPrecision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Rows per band actually used: `band`, or the whole height for 0 (a
/// full frame) or a band taller than the display.
pub fn band_rows(band: u32, height: u32) -> u32 {
    if band == 0 || band > height {
        height
    } else {
        band
    }
}

/// `u16` words of the band buffer of a `width × height` display drawn
/// `band` rows at a time (0: full frame).
pub fn band_words(width: u32, height: u32, band: u32) -> usize {
    width as usize * band_rows(band, height) as usize
}

/// Draws frame `i` of `n` of `tree` into `r`'s viewport (its size is the
/// display's) through `buf` (at least [`band_words`] words), `band` rows at
/// a time (0: full frame), handing every finished band's pixels to `emit`
/// top to bottom. `memory` is the frame's working memory (vertex cache and,
/// for bands, display list: [`fpt_nostd::render::memory_words`]; any length,
/// the picture is the same). The walk's stack holds `N` frames (at least
/// the tree's `max_depth`). Returns the renderer's counters.
///
/// This is the one place that calls the renderer for the orbit frames.
pub fn draw_band_frame<P: Precision, const N: usize, const V: usize>(
    r: &mut TreeRenderer<P, V>,
    tree: &Tree<'_>,
    (i, n): (u32, u32),
    (buf, memory): (&mut [u16], &mut [u32]),
    band: u32,
    mut emit: impl FnMut(&[u16]),
) -> Result<RenderStats, RenderError> {
    let vp = r.renderer.viewport();
    let (width, height) = (vp.width(), vp.height());
    let frame = frame(tree, i, n, width, height);
    r.renderer
        .set_light(Light::new(frame.key_light(), AMBIENT, DIFFUSE));
    let rows = band_rows(band, height);
    if rows >= height {
        // A full frame: the vertex cache only (no display list to replay).
        let mut fb =
            Framebuffer::<Rgb565Format>::new(buf, width, height).map_err(RenderError::Band)?;
        fb.fill_all(BACKGROUND);
        let stats = r.render_cached::<N, _>(tree, &frame, memory, &mut fb)?;
        emit(fb.data());
        return Ok(stats);
    }
    let band = BandBuffer::<Rgb565Format> {
        buf,
        rows,
        background: BACKGROUND,
    };
    r.render_banded_in::<N, Rgb565Format>(tree, &frame, band, memory, |_, fb| emit(fb.data()))
}

/// The checksum of frame `i` of `n` and the renderer's counters (see
/// [`draw_band_frame`]).
pub fn frame_crc<P: Precision, const N: usize, const V: usize>(
    r: &mut TreeRenderer<P, V>,
    tree: &Tree<'_>,
    (i, n): (u32, u32),
    bufs: (&mut [u16], &mut [u32]),
    band: u32,
) -> Result<(u32, RenderStats), RenderError> {
    let mut crc = PixelCrc::new();
    let stats = draw_band_frame::<P, N, V>(r, tree, (i, n), bufs, band, |px| crc.update(px))?;
    Ok((crc.finish(), stats))
}

/// The line the benchmark firmware prints per frame:
/// `orbit frame=I crc=XXXXXXXX` (the firmware appends `instr=N`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OrbitLine {
    /// The frame's index in the orbit.
    pub frame: u32,
    /// Its checksum.
    pub crc: u32,
}

impl fmt::Display for OrbitLine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "orbit frame={} crc={:08x}", self.frame, self.crc)
    }
}

impl OrbitLine {
    /// Reads a line as `Display` writes it, with an optional `instr=N`
    /// after it: the line and the instruction count. `None` for any other
    /// line.
    pub fn parse(line: &str) -> Option<(OrbitLine, Option<u64>)> {
        let mut it = line.split_ascii_whitespace();
        if it.next()? != "orbit" {
            return None;
        }
        let frame = it.next()?.strip_prefix("frame=")?.parse().ok()?;
        let crc = it.next()?.strip_prefix("crc=")?;
        if crc.len() != 8 {
            return None;
        }
        let crc = u32::from_str_radix(crc, 16).ok()?;
        let instr = it
            .next()
            .and_then(|t| t.strip_prefix("instr="))
            .and_then(|v| v.parse().ok());
        Some((OrbitLine { frame, crc }, instr))
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn precision_names_round_trip() {
        for (p, name) in OrbitPrecision::ALL.iter().zip(OrbitPrecision::NAMES) {
            assert_eq!(p.name(), name);
            assert_eq!(OrbitPrecision::parse(name), Some(*p));
        }
        assert_eq!(OrbitPrecision::parse("f64"), None);
    }

    #[test]
    fn band_rows_full_and_clamped() {
        assert_eq!(band_rows(0, 240), 240);
        assert_eq!(band_rows(16, 240), 16);
        assert_eq!(band_rows(500, 240), 240);
        assert_eq!(band_words(240, 240, 16), 240 * 16);
    }

    #[test]
    fn orbit_line_round_trips() {
        let l = OrbitLine {
            frame: 7,
            crc: 0x0012_abcd,
        };
        let s = std::format!("{l}");
        assert_eq!(s, "orbit frame=7 crc=0012abcd");
        assert_eq!(OrbitLine::parse(&s), Some((l, None)));
        let with = std::format!("{s} instr=123");
        assert_eq!(OrbitLine::parse(&with), Some((l, Some(123))));
        assert_eq!(OrbitLine::parse("orbit frame=1 crc=123"), None);
        assert_eq!(OrbitLine::parse("frame scene=a view=1 crc=00000000"), None);
    }
}
