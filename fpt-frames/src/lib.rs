//! `fpt-frames`: the project's measuring harness, not part of the
//! renderer's API. The firmware's frame set: the same frames, drawn by the
//! same code, on the Cortex-M4 and Cortex-M0 (`firmware/`) and on the host
//! (`fpt frames`, `fpt mcu-bench`), so that their checksums can be
//! compared bit for bit, and the probes that measure the phases of a
//! frame. `#![no_std]`, no `alloc`, like the renderer it measures
//! (`fpt-nostd`); a product needs none of it (see `fpt-nostd`'s
//! quickstart and `firmware/examples/`).
//!
//! # Contract
//!
//! * **Scenes and views.** A caller supplies the tree of each scene named
//!   in [`SCENES`] (the firmware embeds the committed files
//!   `firmware/trees/NAME.fpt`, the host builds them); every scene is drawn
//!   from each of the [`VIEWS`], orbit cameras around the tree's
//!   bounding-sphere centre at a distance proportional to its radius, so
//!   that one list of views frames every scene.
//! * **Pictures.** [`WIDTH`] × [`HEIGHT`] RGB565, cleared to [`BACKGROUND`],
//!   drawn with [`FramePrecision`] (the project's default arithmetic) and
//!   the frame's key light. [`render_full`] draws into a caller-supplied
//!   full framebuffer; [`render_banded`] draws the same picture through a
//!   [`BAND_ROWS`]-row band buffer, with the working memory the caller
//!   gives (one walk a frame when it suffices; `fpt_nostd::render::cached`).
//! * **Checksum.** [`PixelCrc`]: the CRC-32 (IEEE 802.3 / zlib, the same as
//!   the tree files' [`fpt_nostd::format::crc32`]) of the pixels' RGB565 storage
//!   values as **little-endian** `u16`, row-major from the top-left pixel.
//!   The banded render feeds the bands to it top to bottom, so its checksum
//!   equals the full frame's.
//! * **Determinism.** Everything is `f32`/`f64` IEEE arithmetic, integer
//!   arithmetic and the pure-Rust `libm` (no `std` math, no FMA contraction
//!   in Rust), so the host and a Cortex-M4F produce identical pixels.
//! * **Reporting.** [`FrameLine`] is the one line per frame both sides
//!   print: `frame scene=NAME view=K crc=XXXXXXXX` (8 lowercase hex digits);
//!   the firmware appends its cost fields to it.
//!
//! # Probes
//!
//! The renders take a [`Probe`]: hooks at the boundaries between the
//! phases of a frame ([`Phase`]: tree walk, transform, fill). Every hook has
//! an empty default body and the probe is a generic parameter, so with
//! [`NoProbe`] they compile to nothing. The draw loops are the product's
//! own ([`TreeRenderer::render_probed`] and
//! [`TreeRenderer::render_banded_probed`], the loops of
//! [`fpt_nostd::render::TreeRenderer::render_cached`] and
//! [`fpt_nostd::render::TreeRenderer::render_banded_in`]), which call the
//! hooks: the fill phase starts when a prepared polygon (transformed,
//! clipped, projected, shaded) is handed to the scan conversion.
#![no_std]
#![deny(unsafe_code, missing_docs)]

use core::fmt;

use embedded_graphics::pixelcolor::Rgb565;

use fpt_nostd::order::OrderError;
use fpt_nostd::raster::{
    FloatLibm, FramebufferError, Libm, Light, Mat4, Orbit, RenderStats, Rgb565Format,
    Rgb565Framebuffer, SpanSink, Up,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{BandBuffer, CapacityError, Frame, RenderError, TreeRenderer};
pub use fpt_nostd::render::{NoProbe, Phase, Probe};

/// Frame width in pixels.
pub const WIDTH: u32 = 240;
/// Frame height in pixels.
pub const HEIGHT: u32 = 240;
/// A build for a core without atomic read-modify-write, i.e. the
/// Cortex-M0 (`thumbv6m-none-eabi`), whose 16 KiB of RAM draw only the
/// vise: it gets smaller bands and the vise's vertex capacity.
const SMALL_RAM: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));
/// Rows per band of [`render_banded`]: 16, 12 on the Cortex-M0 (the
/// picture is the same whatever the band).
pub const BAND_ROWS: u32 = if SMALL_RAM { 12 } else { 16 };
/// `u16` words of a full frame.
pub const FRAME_WORDS: usize = (WIDTH * HEIGHT) as usize;
/// `u16` words of a band buffer.
pub const BAND_WORDS: usize = (WIDTH * BAND_ROWS) as usize;
/// Vertex capacity of the per-polygon scratch: what the scenes' trees
/// need (`fpt info`, [`fpt_nostd::reader::Capacities::vertices`]): house 99,
/// vise 62, bench_city 29 (session 11's builder); on the Cortex-M0, which
/// draws only the vise, 62. A tree that needs more is refused
/// ([`fpt_nostd::render::CapacityError`]).
pub const MAX_VERTS: usize = if SMALL_RAM { 62 } else { 99 };
/// Stack frames of the tree walk: the scenes' trees are at most 37 deep
/// (a deeper tree is refused with [`fpt_nostd::render::CapacityError`]).
pub const WALK_DEPTH: usize = 40;
/// The arithmetic of the frames: the `f32` vertex path with libm, 4
/// sub-pixel bits. On a Cortex-M4F the FPU makes it about 5× cheaper in
/// transform than the fixed-point path, whose `f32 → 16.16` conversions go
/// through soft `f64` and whose divide is a 64-bit library division.
pub type FramePrecision = FloatLibm<4>;
/// The renderer and its scratch buffers, as the frames use them.
pub type FrameRenderer = TreeRenderer<FramePrecision, MAX_VERTS>;
/// The scenes, in the order they are drawn.
pub const SCENES: [&str; 3] = ["vise", "house", "bench_city"];
/// The colour of pixels no polygon covers.
pub const BACKGROUND: Rgb565 = Rgb565::new(4, 10, 12);
/// Ambient and diffuse weights of the key light.
const AMBIENT: f32 = Light::AMBIENT;
const DIFFUSE: f32 = Light::DIFFUSE;

/// The model rotation that stands a z-up model up in the y-up orbit
/// convention: `(x, y, z) → (x, z, −y)`.
pub const Z_UP: Mat4 = Up::Z.model();

/// One view: an orbit around the tree's bounding-sphere centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewSpec {
    /// Rotation about the y axis, radians.
    pub yaw: f32,
    /// Elevation, radians.
    pub pitch: f32,
    /// Eye distance in bounding radii.
    pub distance: f32,
    /// Vertical field of view in radians; `0` is a parallel projection.
    pub fov: f32,
}

/// The views every scene is drawn from: three perspective views around
/// the model, one parallel view, and one close-up with the eye inside the
/// bounding sphere (exercises near-plane and guard-band clipping).
pub const VIEWS: [ViewSpec; 5] = [
    ViewSpec {
        yaw: 0.6,
        pitch: 0.45,
        distance: 1.9,
        fov: 0.9,
    },
    ViewSpec {
        yaw: 2.5,
        pitch: 0.3,
        distance: 1.8,
        fov: 0.9,
    },
    ViewSpec {
        yaw: -2.0,
        pitch: 0.8,
        distance: 2.0,
        fov: 0.9,
    },
    ViewSpec {
        yaw: -0.7,
        pitch: 0.35,
        distance: 1.8,
        fov: 0.0,
    },
    ViewSpec {
        yaw: 1.3,
        pitch: 0.5,
        distance: 0.9,
        fov: 1.2,
    },
];

impl ViewSpec {
    /// The orbit for `tree`, in coordinates relative to its origin.
    pub fn orbit(&self, tree: &Tree<'_>) -> Orbit {
        let d = self.distance * tree.bounding_radius();
        Orbit::new([0.0; 3], self.yaw, self.pitch, d, self.fov)
    }

    /// What the renderer and the walk need for this view of `tree`.
    ///
    /// The scenes are z-up (their ground is the xy plane) while orbits are
    /// y-up, so the orbit camera sees the model turned by [`Z_UP`] (whose
    /// entries are 0 and ±1: the product with it is exact).
    pub fn frame(&self, tree: &Tree<'_>) -> Frame {
        let aspect = WIDTH as f32 / HEIGHT as f32;
        let camera = self.orbit(tree).camera::<Libm>(aspect).with_model(&Z_UP);
        Frame::relative(tree, &camera)
    }
}

/// Why a frame could not be drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// The tree is deeper than [`WALK_DEPTH`].
    Order(OrderError),
    /// The caller's buffer is smaller than [`FRAME_WORDS`] (full) or
    /// [`BAND_WORDS`] (band).
    Buffer(FramebufferError),
    /// Not a configuration of [`accuracy::CONFIGS`].
    UnknownConfig,
    /// [`WALK_DEPTH`] or [`MAX_VERTS`] is smaller than the tree needs.
    Capacity(CapacityError),
    /// An effect measurement's target that its pipeline is not built for
    /// ([`effects::render_effect`]).
    Target,
}

impl From<CapacityError> for FrameError {
    fn from(e: CapacityError) -> Self {
        FrameError::Capacity(e)
    }
}

impl From<RenderError> for FrameError {
    fn from(e: RenderError) -> Self {
        match e {
            RenderError::Order(e) => FrameError::Order(e),
            RenderError::Band(e) => FrameError::Buffer(e),
            RenderError::Capacity(e) => FrameError::Capacity(e),
        }
    }
}

impl From<OrderError> for FrameError {
    fn from(e: OrderError) -> Self {
        FrameError::Order(e)
    }
}

impl From<FramebufferError> for FrameError {
    fn from(e: FramebufferError) -> Self {
        FrameError::Buffer(e)
    }
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FrameError::Order(e) => write!(f, "{e}"),
            FrameError::Buffer(e) => write!(f, "frame buffer: {e:?}"),
            FrameError::UnknownConfig => f.write_str("unknown accuracy configuration"),
            FrameError::Capacity(e) => write!(f, "{e}"),
            FrameError::Target => f.write_str("no code for this effect target"),
        }
    }
}

/// The result of one frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rendered {
    /// [`PixelCrc`] of the frame.
    pub crc: u32,
    /// The renderer's counters (a polygon counts once a frame, banded or
    /// not; spans are summed over the bands).
    pub stats: RenderStats,
}

static CRC32: crc::Crc<u32> = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC);

/// The frame checksum (see the module docs for the byte order).
pub struct PixelCrc {
    digest: crc::Digest<'static, u32>,
}

impl fmt::Debug for PixelCrc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("PixelCrc")
    }
}

impl Default for PixelCrc {
    fn default() -> Self {
        Self::new()
    }
}

impl PixelCrc {
    /// The checksum of no pixels.
    pub fn new() -> PixelCrc {
        PixelCrc {
            digest: CRC32.digest(),
        }
    }

    /// Adds `words` (RGB565 storage values, row-major) to the checksum.
    pub fn update(&mut self, words: &[u16]) {
        // A few pixels at a time through a small stack buffer: the byte
        // order is explicit, and the stack stays small on the firmware.
        let mut bytes = [0u8; 32];
        for chunk in words.chunks(16) {
            for (b, w) in bytes.chunks_exact_mut(2).zip(chunk) {
                b.copy_from_slice(&w.to_le_bytes());
            }
            self.digest.update(&bytes[..2 * chunk.len()]);
        }
    }

    /// Adds raw bytes (e.g. a packed `BinaryColor` frame).
    pub fn update_bytes(&mut self, bytes: &[u8]) {
        self.digest.update(bytes);
    }

    /// The CRC-32.
    pub fn finish(self) -> u32 {
        self.digest.finalize()
    }
}

/// Draws view `view` of `tree` into `buf` (at least [`FRAME_WORDS`]
/// words, a `WIDTH × HEIGHT` RGB565 image on return) and checksums it.
/// `memory` is the vertex cache ([`fpt_nostd::render::memory_words`]; any
/// length, empty included: the picture is the same).
pub fn render_full<Pr: Probe>(
    r: &mut FrameRenderer,
    tree: &Tree<'_>,
    view: &ViewSpec,
    buf: &mut [u16],
    memory: &mut [u32],
    probe: &Pr,
) -> Result<Rendered, FrameError> {
    probe.start(Phase::Xform);
    let frame = setup(r, tree, view);
    probe.enter(Phase::Fill);
    let mut fb = Rgb565Framebuffer::new(buf, WIDTH, HEIGHT)?;
    clear(&mut fb);
    let drawn = draw_tree(r, tree, &frame, memory, &mut fb, probe);
    probe.stop();
    let stats = drawn?;
    let mut crc = PixelCrc::new();
    crc.update(fb.data());
    Ok(Rendered {
        crc: crc.finish(),
        stats,
    })
}

/// Draws the same frame as [`render_full`] through `band` (at least
/// [`BAND_WORDS`] words) one [`BAND_ROWS`]-row band at a time, with
/// `memory` as the frame's working memory (vertex cache and display list,
/// [`fpt_nostd::render::memory_words`]; any length: the picture is the same),
/// checksumming each band as it is finished (outside the probe's
/// start/stop).
pub fn render_banded<Pr: Probe>(
    r: &mut FrameRenderer,
    tree: &Tree<'_>,
    view: &ViewSpec,
    band: &mut [u16],
    memory: &mut [u32],
    probe: &Pr,
) -> Result<Rendered, FrameError> {
    fpt_nostd::render::check_capacities::<WALK_DEPTH, MAX_VERTS>(tree)?;
    probe.start(Phase::Xform);
    let frame = setup(r, tree, view);
    let mut crc = PixelCrc::new();
    let band = BandBuffer::<Rgb565Format> {
        buf: band,
        rows: BAND_ROWS,
        background: BACKGROUND,
    };
    let stats =
        r.render_banded_probed::<WALK_DEPTH, _, _>(tree, &frame, band, memory, probe, |_, fb| {
            crc.update(fb.data());
            true
        })?;
    Ok(Rendered {
        crc: crc.finish(),
        stats,
    })
}

/// Fills `fb` with [`BACKGROUND`]. Not inlined: with the band's constant
/// size the optimiser unrolled the fill into 12 KiB of code.
#[inline(never)]
fn clear(fb: &mut Rgb565Framebuffer<'_>) {
    fb.fill_all(BACKGROUND);
}

/// Derives the frame, sets the camera and the light, zeroes the counters.
fn setup(r: &mut FrameRenderer, tree: &Tree<'_>, view: &ViewSpec) -> Frame {
    let frame = view.frame(tree);
    r.renderer.set_camera(&frame.camera);
    r.renderer
        .set_light(Light::new(frame.key_light(), AMBIENT, DIFFUSE));
    r.renderer.reset_stats();
    frame
}

/// The full frame's draw loop ([`TreeRenderer::render_probed`]: the one
/// of [`TreeRenderer::render_cached`]) with the probe's hooks, into
/// `sink`.
///
/// Not inlined: inlining it into its callers let the optimiser duplicate
/// the whole pipeline (+24 KiB of `.text` on the Cortex-M4) for no
/// measurable gain.
#[inline(never)]
fn draw_tree<K: SpanSink, Pr: Probe>(
    r: &mut FrameRenderer,
    tree: &Tree<'_>,
    frame: &Frame,
    memory: &mut [u32],
    sink: &mut K,
    probe: &Pr,
) -> Result<RenderStats, FrameError> {
    Ok(r.render_probed::<WALK_DEPTH, _, _>(tree, frame, memory, sink, probe)?)
}

/// The line both sides print for a frame: `frame scene=NAME view=K
/// crc=XXXXXXXX`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameLine<'a> {
    /// The scene's name (one of [`SCENES`]).
    pub scene: &'a str,
    /// The index into [`VIEWS`].
    pub view: u32,
    /// The frame's [`PixelCrc`].
    pub crc: u32,
}

impl fmt::Display for FrameLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "frame scene={} view={} crc={:08x}",
            self.scene, self.view, self.crc
        )
    }
}

impl<'a> FrameLine<'a> {
    /// Reads the first three fields of a line as [`FrameLine`]'s `Display`
    /// writes them; anything after them (the firmware's cost fields) is
    /// ignored. `None` for any other line.
    pub fn parse(line: &'a str) -> Option<FrameLine<'a>> {
        let (scene, view, crc) = parse_checksum_line(line, "frame", "scene=")?;
        Some(FrameLine { scene, view, crc })
    }
}

/// The fields of a checksum line `TAG KEY=NAME view=K crc=XXXXXXXX …`
/// (a frame line or an accuracy line): the non-empty name, the view and
/// the eight-digit hexadecimal checksum; anything after them is ignored.
/// `None` for any other line.
pub(crate) fn parse_checksum_line<'a>(
    line: &'a str,
    tag: &str,
    key: &str,
) -> Option<(&'a str, u32, u32)> {
    let mut it = line.split_ascii_whitespace();
    if it.next()? != tag {
        return None;
    }
    let name = it.next()?.strip_prefix(key)?;
    let view = it.next()?.strip_prefix("view=")?.parse().ok()?;
    let crc = it.next()?.strip_prefix("crc=")?;
    if crc.len() != 8 || name.is_empty() {
        return None;
    }
    let crc = u32::from_str_radix(crc, 16).ok()?;
    Some((name, view, crc))
}

pub mod accuracy;
pub mod effects;
pub mod orbit;
#[cfg(test)]
mod tests;
pub mod work;
