//! `fpt render`: a tree file to a PNG through the no_std pipeline.
//!
//! ```text
//! fpt render TREE -o OUT.png [--size WxH]
//!     [--mvp M00,M01,...,M33 | [--yaw DEG] [--pitch DEG] [--distance D]
//!      [--distance-units radii|model] [--fov DEG] [--up auto|x|y|z]]
//!     [--background R,G,B] [--ids IDS.bin] [--format rgb888|rgb565|gray8|mono]
//!     [--band N] [--precision NAME] [--shade lambert|flat|grey]
//!     [--effects LIST] [--gray-levels N] [--display PANEL]
//! ```
//!
//! * `--mvp`: 16 numbers, row-major, model → clip (`clip = M·[x, y, z, 1]`;
//!   the pixel conventions are those of [`fpt_nostd::raster::camera`]). The
//!   walk's view comes from the matrix ([`fpt_nostd::render::MatrixView`])
//!   and the near clip from its near plane ([`fpt_nostd::render::near_w_for`]).
//! * Orbit ([`OrbitArgs`]): around the bounding-sphere centre, `--yaw`
//!   defaulting to 35 and `--pitch` to 25 (a three-quarter view),
//!   `--distance` in bounding radii (as `fpt build --orbit`; or model units
//!   with `--distance-units model`) defaulting to 3 or what frames the
//!   bounding sphere (`camera::framing_distance`), `--fov` (vertical, degrees) to
//!   40; `--fov 0` is parallel. The orbit is y-up
//!   ([`fpt_nostd::raster::camera`]); `--up` turns a model whose up axis
//!   is another upright first, by default the axis the tree records
//!   ([`fpt_nostd::format::UpAxis`], `fpt build --up`).
//! * `--background R,G,B`: the colour behind the model (default black).
//! * `--ids`: `W·H` little-endian `u32`, row-major from the top-left: the
//!   source face index + 1 of the polygon drawn at each pixel, 0 for
//!   background.
//! * `--band N`: draw in bands of N rows through one band buffer (the
//!   picture is identical; this exercises the firmware's path).
//! * `--precision`: the compile-time arithmetic configuration
//!   ([`PRECISIONS`], or a short name of [`ALIASES`]), for accuracy studies.
//! * `--effects`: overrides the effects the tree declares
//!   ([`fpt_nostd::effects`]): a comma-separated list of `culling,
//!   two-sided, clipping, lighting, depth-cue, dither, outline, smooth`, or `none`.
//!   `dither` only changes `gray8` and `mono` pictures.
//! * `--gray-levels`, `--display`: display simulation, see [`super::display`].
//!
//! The picture is drawn into one of our framebuffers, copied into an
//! `embedded-graphics-simulator` display and saved as PNG by it (to a
//! temporary file beside the output, then renamed, so a PNG is written
//! whole or not at all). Bad input is an error (exit status 2); any
//! finite, invertible camera renders.

use super::display::{Panel, PANELS};
use super::{CliError, CliResult};
use crate::cli_err;
use crate::output::write_atomic;
use clap::Args;
use embedded_graphics::geometry::{Point, Size};
use embedded_graphics::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics::prelude::DrawTarget;
use embedded_graphics::Pixel;
use embedded_graphics_simulator::SimulatorDisplay;
use fpt_nostd::effects::Effects;
use fpt_nostd::raster::framebuffer::{BinaryFormat, Gray8Format, Rgb565Format, Rgb888Format};
use fpt_nostd::raster::transform::MAX_DIM;
use fpt_nostd::raster::{
    band_starts, DepthCue, Dither, DitherFormat, FixedMicromath, FixedPrecision, FloatLibm,
    FloatMicromath, Framebuffer, IdBuffer, IntPrecision, Light, PixelFormat, Precision,
    RenderStats, ShadeMode,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{BandBuffer, FaceIds, Frame, TreeRenderer};
use std::path::{Path, PathBuf};
use std::time::Instant;

pub use camera::{camera_of, orbit_camera, CameraSpec, OrbitArgs};

/// The names `--precision` accepts: vertex path and math library, then
/// the sub-pixel bits.
pub const PRECISIONS: [&str; 25] = [
    "fixed-subpx-0",
    "fixed-subpx-2",
    "fixed-subpx-4",
    "fixed-subpx-6",
    "fixed-subpx-8",
    "fixed-micromath-subpx-0",
    "fixed-micromath-subpx-2",
    "fixed-micromath-subpx-4",
    "fixed-micromath-subpx-6",
    "fixed-micromath-subpx-8",
    "f32-libm-subpx-0",
    "f32-libm-subpx-2",
    "f32-libm-subpx-4",
    "f32-libm-subpx-6",
    "f32-libm-subpx-8",
    "f32-micromath-subpx-0",
    "f32-micromath-subpx-2",
    "f32-micromath-subpx-4",
    "f32-micromath-subpx-6",
    "f32-micromath-subpx-8",
    "int-subpx-0",
    "int-subpx-2",
    "int-subpx-4",
    "int-subpx-6",
    "int-subpx-8",
];

/// Short names `--precision` also accepts, for the accuracy study
/// (`fpt bench-accuracy`), and the configuration each stands for:
/// `fixed` is the default; `subpx-N` is fixed point with N sub-pixel bits;
/// `f32-libm` and `f32-micromath` are the `f32` vertex paths with 4 bits;
/// `trig-libm` and `trig-micromath` are fixed point with 4 bits whose orbit
/// camera (`--yaw`/`--pitch`) is built with libm's or micromath's sine and
/// cosine (with `--mvp` there is no trigonometry and they equal `fixed`,
/// resp. `fixed-micromath-subpx-4`); `int` is the integer vertex path
/// with 4 bits.
pub const ALIASES: [(&str, &str); 11] = [
    ("fixed", "fixed-subpx-4"),
    ("subpx-0", "fixed-subpx-0"),
    ("subpx-2", "fixed-subpx-2"),
    ("subpx-4", "fixed-subpx-4"),
    ("subpx-6", "fixed-subpx-6"),
    ("subpx-8", "fixed-subpx-8"),
    ("f32-libm", "f32-libm-subpx-4"),
    ("f32-micromath", "f32-micromath-subpx-4"),
    ("trig-libm", "fixed-subpx-4"),
    ("trig-micromath", "fixed-micromath-subpx-4"),
    ("int", "int-subpx-4"),
];

/// Every name `--precision` accepts: [`PRECISIONS`], then the short names
/// of [`ALIASES`], in that order (a constant array, as clap's value parser
/// takes, built from the two lists rather than written a third time).
pub const PRECISION_NAMES: [&str; PRECISIONS.len() + ALIASES.len()] = {
    let mut out = [""; PRECISIONS.len() + ALIASES.len()];
    let mut i = 0;
    while i < PRECISIONS.len() {
        out[i] = PRECISIONS[i];
        i += 1;
    }
    let mut j = 0;
    while j < ALIASES.len() {
        out[i + j] = ALIASES[j].0;
        j += 1;
    }
    out
};

/// The full [`PRECISIONS`] name of `name` (itself unless an alias).
pub fn resolve_precision(name: &str) -> &str {
    ALIASES
        .iter()
        .find(|(a, _)| *a == name)
        .map_or(name, |(_, full)| full)
}

/// Vertices a polygon may have after clipping; larger ones are skipped
/// (and counted). Host memory is plentiful: 256 × 106 bytes.
const MAX_VERTS: usize = 256;
/// Stack frames of the walk: deeper trees are refused with an error.
const WALK_STACK: usize = 4096;

/// Arguments of `fpt render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Tree file.
    pub tree: PathBuf,
    /// Output PNG file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Image size WxH in pixels.
    #[arg(long, default_value = "320x240")]
    pub size: String,
    /// Model → clip matrix: 16 numbers, row-major, comma-separated.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["yaw", "pitch", "distance", "fov", "up"])]
    pub mvp: Option<String>,
    /// The orbit camera (when no --mvp).
    #[command(flatten)]
    pub orbit: OrbitArgs,
    /// Background, arithmetic, shading and slivers.
    #[command(flatten)]
    pub look: LookArgs,
    /// Also write the source face id + 1 of every pixel (u32 LE, 0 = none).
    #[arg(long)]
    pub ids: Option<PathBuf>,
    /// Framebuffer format: exact colour (rgb888) unless a display's storage
    /// is asked for (rgb565 quantises, gray8 and mono as the panels do).
    #[arg(long, default_value = "rgb888", value_parser = ["rgb565", "rgb888", "gray8", "mono"])]
    pub format: String,
    /// Draw in bands of N rows through one band buffer.
    #[arg(long, allow_negative_numbers = true)]
    pub band: Option<u32>,
    /// Effects instead of the tree's: comma-separated culling, two-sided,
    /// clipping, lighting, depth-cue, dither, outline, smooth; or none.
    #[arg(long)]
    pub effects: Option<String>,
    /// Grey levels of a gray8 panel (2..=256; default 256, or 16 when
    /// dithering).
    #[arg(long = "gray-levels", allow_negative_numbers = true)]
    pub gray_levels: Option<u16>,
    /// How the PNG shows the display: plain, or a panel look (oled-blue,
    /// oled-white, lcd-green, lcd-white, lcd-blue).
    #[arg(long, default_value = "plain", value_parser = PANELS)]
    pub display: String,
}

/// The options `fpt render`, `fpt turntable` and `fpt view` share about
/// how a picture looks.
#[derive(Args, Debug)]
pub struct LookArgs {
    /// Background colour R,G,B (0–255 each).
    #[arg(long, default_value = "0,0,0")]
    pub background: String,
    /// Arithmetic configuration (vertex path, math library, sub-pixel bits).
    #[arg(long, default_value = "fixed-subpx-4", value_parser = PRECISION_NAMES)]
    pub precision: String,
    /// Shading: lambert (face colours lit), flat (unlit) or grey.
    #[arg(long, default_value = "lambert", value_parser = ["lambert", "flat", "grey"])]
    pub shade: String,
    /// Leave out the sliver pass: without it, a face seen almost edge-on
    /// that the sub-pixel snap winds toward the viewer is culled, and a
    /// closed model can show single background pixels along its
    /// silhouette edges (the firmware's default; it saves about a sixth of
    /// a frame).
    #[arg(long = "no-slivers")]
    pub no_slivers: bool,
}

/// [`LookArgs`] checked: how a [`Job`] paints, beside its geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Look {
    /// Background colour.
    pub background: Rgb888,
    /// Shading mode.
    pub shade: ShadeMode,
    /// Whether the renderer draws slivers (`Renderer::set_slivers`): on
    /// for the pictures of the host commands, so that a closed model shows
    /// no background pixel inside its silhouette; off for the accuracy
    /// study, which measures the plain pipeline a firmware runs by default.
    pub slivers: bool,
}

impl LookArgs {
    /// The checked background, shading and sliver choice (the precision
    /// name is checked where it is used, by [`render_job`]).
    pub fn parse(&self) -> Result<Look, CliError> {
        let [r, g, b] = parse_rgb("--background", &self.background)?;
        Ok(Look {
            background: Rgb888::new(r, g, b),
            shade: parse_shade(&self.shade)?,
            slivers: !self.no_slivers,
        })
    }
}

/// Pixel format of the framebuffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// 16-bit colour.
    Rgb565,
    /// 24-bit colour.
    Rgb888,
    /// 8-bit grey.
    Gray8,
    /// 1 bit per pixel.
    Mono,
}

impl Format {
    /// Parses a `--format` name.
    pub fn parse(s: &str) -> Result<Format, CliError> {
        match s {
            "rgb565" => Ok(Format::Rgb565),
            "rgb888" => Ok(Format::Rgb888),
            "gray8" => Ok(Format::Gray8),
            "mono" => Ok(Format::Mono),
            _ => Err(cli_err!(
                "unknown format '{s}' (expected rgb565, rgb888, gray8 or mono)"
            )),
        }
    }
}

/// Everything about one picture but the tree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Job {
    /// Width in pixels.
    pub w: u32,
    /// Height in pixels.
    pub h: u32,
    /// The camera.
    pub camera: CameraSpec,
    /// Framebuffer format.
    pub format: Format,
    /// Rows per band, `None` for the full-frame path.
    pub band: Option<u32>,
    /// Background, shading and slivers.
    pub look: Look,
    /// Whether to produce the id buffer too.
    pub ids: bool,
    /// Effects instead of the tree's.
    pub effects: Option<Effects>,
    /// Grey levels of a `Gray8` panel (`None`: 256, or 16 when dithering).
    pub gray_levels: Option<u16>,
}

/// A finished picture: the framebuffer storage of its format.
#[derive(Clone, Debug, PartialEq)]
pub enum Image {
    /// `Rgb565` storage words.
    Rgb565(Vec<u16>),
    /// `r, g, b` bytes.
    Rgb888(Vec<u8>),
    /// Luma bytes.
    Gray8(Vec<u8>),
    /// Packed bits, MSB first, rows padded to bytes.
    Mono(Vec<u8>),
}

/// The output of [`render_job`].
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The picture.
    pub image: Image,
    /// Source face id + 1 per pixel (empty unless asked for).
    pub ids: Vec<u32>,
    /// The renderer's counters for the picture.
    pub stats: RenderStats,
    /// Milliseconds spent drawing the picture.
    pub ms: f64,
}

/// Draws `job` with `tree` using arithmetic `name` (one of
/// [`PRECISION_NAMES`]).
pub fn render_job(tree: &Tree<'_>, job: &Job, name: &str) -> Result<Rendered, CliError> {
    match resolve_precision(name) {
        "fixed-subpx-0" => render_with::<FixedPrecision<0>>(tree, job),
        "fixed-subpx-2" => render_with::<FixedPrecision<2>>(tree, job),
        "fixed-subpx-4" => render_with::<FixedPrecision<4>>(tree, job),
        "fixed-subpx-6" => render_with::<FixedPrecision<6>>(tree, job),
        "fixed-subpx-8" => render_with::<FixedPrecision<8>>(tree, job),
        "fixed-micromath-subpx-0" => render_with::<FixedMicromath<0>>(tree, job),
        "fixed-micromath-subpx-2" => render_with::<FixedMicromath<2>>(tree, job),
        "fixed-micromath-subpx-4" => render_with::<FixedMicromath<4>>(tree, job),
        "fixed-micromath-subpx-6" => render_with::<FixedMicromath<6>>(tree, job),
        "fixed-micromath-subpx-8" => render_with::<FixedMicromath<8>>(tree, job),
        "f32-libm-subpx-0" => render_with::<FloatLibm<0>>(tree, job),
        "f32-libm-subpx-2" => render_with::<FloatLibm<2>>(tree, job),
        "f32-libm-subpx-4" => render_with::<FloatLibm<4>>(tree, job),
        "f32-libm-subpx-6" => render_with::<FloatLibm<6>>(tree, job),
        "f32-libm-subpx-8" => render_with::<FloatLibm<8>>(tree, job),
        "f32-micromath-subpx-0" => render_with::<FloatMicromath<0>>(tree, job),
        "f32-micromath-subpx-2" => render_with::<FloatMicromath<2>>(tree, job),
        "f32-micromath-subpx-4" => render_with::<FloatMicromath<4>>(tree, job),
        "f32-micromath-subpx-6" => render_with::<FloatMicromath<6>>(tree, job),
        "f32-micromath-subpx-8" => render_with::<FloatMicromath<8>>(tree, job),
        "int-subpx-0" => render_with::<IntPrecision<0>>(tree, job),
        "int-subpx-2" => render_with::<IntPrecision<2>>(tree, job),
        "int-subpx-4" => render_with::<IntPrecision<4>>(tree, job),
        "int-subpx-6" => render_with::<IntPrecision<6>>(tree, job),
        "int-subpx-8" => render_with::<IntPrecision<8>>(tree, job),
        _ => Err(cli_err!(
            "unknown precision '{name}' (expected one of {}, or a short name: {})",
            PRECISIONS.join(", "),
            ALIASES.map(|(a, _)| a).join(", ")
        )),
    }
}

fn render_with<P: Precision>(tree: &Tree<'_>, job: &Job) -> Result<Rendered, CliError> {
    let mut tr = Box::new(
        TreeRenderer::<P, MAX_VERTS>::new(job.w, job.h)
            .ok_or_else(|| cli_err!("bad image size {}x{}", job.w, job.h))?,
    );
    let frame = job.camera.frame::<P::Math>(tree, job.w, job.h);
    tr.renderer.set_shade_mode(job.look.shade);
    tr.renderer
        .set_light(Light::new(frame.key_light(), 0.25, 0.75));
    tr.renderer.set_effects(job.effects);
    tr.renderer.set_slivers(job.look.slivers);
    let (near, far) = frame.depth_range(tree);
    tr.renderer.set_depth_cue(DepthCue {
        near,
        far,
        fog: job.look.background,
        ..DepthCue::default()
    });
    let fx = job.effects.unwrap_or(Effects::from_bits(tree.effects()));
    let dither = fx.contains(Effects::DITHER);
    let start = Instant::now();
    let bg = job.look.background;
    let (image, stats) = match job.format {
        Format::Rgb565 => {
            let (v, s) = draw::<P, Rgb565Format>(&mut tr, tree, &frame, job, bg.into())?;
            (Image::Rgb565(v), s)
        }
        Format::Rgb888 => {
            let (v, s) = draw::<P, Rgb888Format>(&mut tr, tree, &frame, job, bg)?;
            (Image::Rgb888(v), s)
        }
        Format::Gray8 if dither || job.gray_levels.is_some() => {
            let levels = job.gray_levels.unwrap_or(if dither { 16 } else { 256 });
            let (v, s) =
                draw_dithered::<P, Gray8Format>(&mut tr, tree, &frame, job, levels, dither)?;
            (Image::Gray8(v), s)
        }
        Format::Gray8 => {
            let (v, s) = draw::<P, Gray8Format>(&mut tr, tree, &frame, job, bg.into())?;
            (Image::Gray8(v), s)
        }
        Format::Mono if dither => {
            let (v, s) = draw_dithered::<P, BinaryFormat>(&mut tr, tree, &frame, job, 2, true)?;
            (Image::Mono(v), s)
        }
        Format::Mono => {
            let (v, s) = draw::<P, BinaryFormat>(&mut tr, tree, &frame, job, bg.into())?;
            (Image::Mono(v), s)
        }
    };
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let mut ids = Vec::new();
    if job.ids {
        ids = vec![0u32; job.w as usize * job.h as usize];
        let mut sink =
            IdBuffer::new(&mut ids, job.w, job.h).map_err(|e| cli_err!("id buffer: {e}"))?;
        tr.ids = FaceIds::Source;
        tr.render::<WALK_STACK, _>(tree, &frame, &mut sink)?;
    }
    Ok(Rendered {
        image,
        ids,
        stats,
        ms,
    })
}

/// Draws into a new framebuffer of format `F`: directly, or band by band.
fn draw<P: Precision, F: PixelFormat>(
    tr: &mut TreeRenderer<P, MAX_VERTS>,
    tree: &Tree<'_>,
    frame: &Frame,
    job: &Job,
    background: F::Color,
) -> Result<(Vec<F::Word>, RenderStats), CliError>
where
    F::Word: Default,
{
    let mut out = vec![F::Word::default(); Framebuffer::<F>::required_len(job.w, job.h)];
    let stats = match job.band {
        None => {
            let mut fb = Framebuffer::<F>::new(&mut out, job.w, job.h)
                .map_err(|e| cli_err!("framebuffer: {e}"))?;
            fb.fill_all(background);
            tr.render::<WALK_STACK, _>(tree, frame, &mut fb)?
        }
        Some(rows) => {
            let rows = rows.clamp(1, job.h);
            let stride = F::words_per_row(job.w);
            let mut buf = vec![F::Word::default(); stride * rows as usize];
            let band = BandBuffer::<F> {
                buf: &mut buf,
                rows,
                background,
            };
            tr.render_banded::<WALK_STACK, F>(tree, frame, band, |y0, fb| {
                let d = fb.data();
                let at = y0 as usize * stride;
                if let Some(dst) = out.get_mut(at..at + d.len()) {
                    dst.copy_from_slice(d);
                }
            })?
        }
    };
    Ok((out, stats))
}

/// Draws through a [`Dither`] sink to `levels` levels (ordered when
/// `ordered`, else rounded), full frame or band by band; the background is
/// dithered like any colour (each band is cleared by drawing it).
fn draw_dithered<P: Precision, F: DitherFormat>(
    tr: &mut TreeRenderer<P, MAX_VERTS>,
    tree: &Tree<'_>,
    frame: &Frame,
    job: &Job,
    levels: u16,
    ordered: bool,
) -> Result<(Vec<F::Word>, RenderStats), CliError>
where
    F::Word: Default,
{
    let stride = F::words_per_row(job.w);
    let rows = job.band.unwrap_or(job.h).clamp(1, job.h);
    let mut out = vec![F::Word::default(); Framebuffer::<F>::required_len(job.w, job.h)];
    let mut buf = vec![F::Word::default(); stride * rows as usize];
    let mut total = RenderStats::default();
    for y0 in band_starts(job.h, rows) {
        let n = rows.min(job.h - y0 as u32);
        let mut fb =
            Framebuffer::<F>::new(&mut buf, job.w, n).map_err(|e| cli_err!("framebuffer: {e}"))?;
        let mut sink = Dither::band(&mut fb, y0, levels);
        if !ordered {
            sink = sink.rounding();
        }
        let paint = fpt_nostd::raster::Paint {
            rgb: job.look.background,
            id: 0,
        };
        let bg = fpt_nostd::raster::SpanSink::color(&sink, &paint);
        for y in y0..y0 + n as i32 {
            fpt_nostd::raster::SpanSink::span(&mut sink, y, 0, job.w as i32, bg);
        }
        let s = tr.render::<WALK_STACK, _>(tree, frame, &mut sink)?;
        total += s;
        let d = fb.data();
        let at = y0 as usize * stride;
        if let Some(dst) = out.get_mut(at..at + d.len()) {
            dst.copy_from_slice(d);
        }
    }
    Ok((out, total))
}

/// Copies a framebuffer into a simulator display.
fn to_display<F: PixelFormat>(
    data: &mut [F::Word],
    w: u32,
    h: u32,
) -> Result<SimulatorDisplay<F::Color>, CliError>
where
    F::Color: PixelColor,
{
    let fb = Framebuffer::<F>::new(data, w, h).map_err(|e| cli_err!("framebuffer: {e}"))?;
    let base = fb.pixel(0, 0).ok_or_else(|| cli_err!("empty image"))?;
    let mut d = SimulatorDisplay::with_default_color(Size::new(w, h), base);
    let pixels = (0..h).flat_map(|y| (0..w).map(move |x| (x, y)));
    let _ = d.draw_iter(pixels.filter_map(|(x, y)| {
        fb.pixel(x, y)
            .map(|c| Pixel(Point::new(x as i32, y as i32), c))
    }));
    Ok(d)
}

/// Saves `image` (`w × h`) as a PNG through the simulator, atomically,
/// one image pixel per display pixel.
pub fn save_png(image: &Image, w: u32, h: u32, path: &Path) -> CliResult {
    save_png_as(image, w, h, path, Panel::Plain)
}

/// [`save_png`] with a panel look ([`Panel::output`]).
pub fn save_png_as(image: &Image, w: u32, h: u32, path: &Path, panel: Panel) -> CliResult {
    let out = match image.clone() {
        Image::Rgb565(mut v) => panel.output(&to_display::<Rgb565Format>(&mut v, w, h)?),
        Image::Rgb888(mut v) => panel.output(&to_display::<Rgb888Format>(&mut v, w, h)?),
        Image::Gray8(mut v) => panel.output(&to_display::<Gray8Format>(&mut v, w, h)?),
        Image::Mono(mut v) => panel.output(&to_display::<BinaryFormat>(&mut v, w, h)?),
    };
    let name = path
        .file_name()
        .map_or_else(|| "out.png".into(), |n| n.to_string_lossy().into_owned());
    let tmp = path.with_file_name(format!(".{name}.{}.tmp.png", std::process::id()));
    let saved = out
        .save_png(&tmp)
        .map_err(|e| cli_err!("{}: {e}", path.display()))
        .and_then(|()| {
            std::fs::rename(&tmp, path).map_err(|e| cli_err!("{}: {e}", path.display()))
        });
    if saved.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    saved
}

/// Parses `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32), CliError> {
    let (a, b) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| cli_err!("--size needs WxH, got '{s}'"))?;
    let p = |t: &str| -> Result<u32, CliError> {
        let v: u32 = t
            .trim()
            .parse()
            .map_err(|_| cli_err!("--size: '{t}' is not a whole number"))?;
        if v == 0 || v > MAX_DIM {
            return Err(cli_err!("--size: {v} is outside 1..={MAX_DIM}"));
        }
        Ok(v)
    };
    Ok((p(a)?, p(b)?))
}

/// Parses and checks a `--mvp` matrix: 16 finite numbers, representable
/// in `f32`, invertible.
pub fn parse_mvp(s: &str) -> Result<[[f64; 4]; 4], CliError> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 16 {
        return Err(cli_err!("--mvp needs 16 numbers, got {}", parts.len()));
    }
    let mut flat = [0.0f64; 16];
    for (o, p) in flat.iter_mut().zip(&parts) {
        let v: f64 = p
            .trim()
            .parse()
            .map_err(|_| cli_err!("--mvp: '{p}' is not a number"))?;
        if !v.is_finite() || v.abs() > f64::from(f32::MAX) {
            return Err(cli_err!("--mvp: '{p}' is not a finite f32 number"));
        }
        *o = v;
    }
    if crate::reference::Camera::from_mvp(flat).is_none() {
        return Err(cli_err!("--mvp: the matrix is singular"));
    }
    let mut rows = [[0.0; 4]; 4];
    for (i, v) in flat.iter().enumerate() {
        rows[i / 4][i % 4] = *v;
    }
    Ok(rows)
}

/// Parses a `--shade` name.
pub fn parse_shade(s: &str) -> Result<ShadeMode, CliError> {
    match s {
        "lambert" => Ok(ShadeMode::Lambert),
        "flat" => Ok(ShadeMode::Flat),
        "grey" | "gray" => Ok(ShadeMode::Grey(235)),
        _ => Err(cli_err!(
            "unknown shading '{s}' (expected lambert, flat or grey)"
        )),
    }
}

/// Parses a colour `R,G,B` (three whole numbers 0–255) for `what`.
pub fn parse_rgb(what: &str, s: &str) -> Result<[u8; 3], CliError> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [r, g, b] = parts.as_slice() else {
        return Err(cli_err!(
            "{what} needs R,G,B (three numbers 0-255), got '{s}'"
        ));
    };
    let c = |t: &str| -> Result<u8, CliError> {
        t.parse::<u8>()
            .map_err(|_| cli_err!("{what}: '{t}' is not a whole number in 0-255"))
    };
    Ok([c(r)?, c(g)?, c(b)?])
}

/// Reads a tree file (validated by [`open_tree`]).
pub fn read_tree(path: &Path) -> Result<Vec<u8>, CliError> {
    std::fs::read(path).map_err(|e| cli_err!("{}: {e}", path.display()))
}

/// Validates the bytes of tree file `path`, refusing models too large to
/// render.
pub fn open_tree<'a>(bytes: &'a [u8], path: &Path) -> Result<Tree<'a>, CliError> {
    let tree = Tree::from_bytes(bytes)
        .map_err(|e| cli_err!("{}: not a valid tree file: {e}", path.display()))?;
    // `fpt build` refuses such models ([`crate::mesh::MAX_SIZE`]); a file
    // from elsewhere would be drawn blank (the orbit's eye overflows f32).
    let radius = f64::from(tree.bounding_radius());
    if radius > 0.5 * crate::mesh::MAX_SIZE {
        return Err(cli_err!(
            "{}: the model is too large to render: its bounding radius is {radius:e}, more than {:e}",
            path.display(),
            0.5 * crate::mesh::MAX_SIZE
        ));
    }
    Ok(tree)
}

/// `fpt render`.
pub fn run(a: &RenderArgs) -> CliResult {
    let (w, h) = parse_size(&a.size)?;
    let look = a.look.parse()?;
    let format = Format::parse(&a.format)?;
    let effects = match &a.effects {
        Some(list) => Some(Effects::parse(list).map_err(|e| cli_err!("--effects: {e}"))?),
        None => None,
    };
    let panel = Panel::parse(&a.display)?;
    if let Some(n) = a.gray_levels {
        if !(2..=256).contains(&n) {
            return Err(cli_err!("--gray-levels must be in 2..=256, got {n}"));
        }
    }
    if a.band == Some(0) {
        return Err(cli_err!("--band must be at least 1"));
    }
    let bytes = read_tree(&a.tree)?;
    let tree = open_tree(&bytes, &a.tree)?;
    let camera = camera_of(a.mvp.as_deref(), &a.orbit, &tree, w, h)?;
    let job = Job {
        w,
        h,
        camera,
        format,
        band: a.band,
        look,
        ids: a.ids.is_some(),
        effects,
        gray_levels: a.gray_levels,
    };
    let r = render_job(&tree, &job, &a.look.precision)?;
    if let Some(path) = &a.ids {
        let raw: Vec<u8> = r.ids.iter().flat_map(|v| v.to_le_bytes()).collect();
        write_atomic(path, &raw).map_err(|e| cli_err!("{}: {e}", path.display()))?;
    }
    save_png_as(&r.image, w, h, &a.output, panel)?;
    let s = r.stats;
    println!(
        "{}: {w}x{h} {}, {} polygons drawn ({} clipped, {} invisible, {} skipped), {} spans, {:.2} ms",
        a.output.display(),
        a.look.precision,
        s.drawn,
        s.clipped,
        s.invisible,
        s.skipped,
        s.spans,
        r.ms
    );
    Ok(())
}

mod camera;
#[cfg(test)]
mod tests;
