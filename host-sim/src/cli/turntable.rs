//! `fpt turntable`: the model spinning once about its up axis, as an
//! animated GIF.
//!
//! ```text
//! fpt turntable TREE -o spin.gif [--frames N] [--size WxH] [--fps N]
//!     [--yaw DEG] [--pitch DEG] [--distance D] [--distance-units radii|model]
//!     [--fov DEG] [--up auto|x|y|z] [--background R,G,B]
//!     [--shade lambert|flat|grey] [--precision NAME]
//! ```
//!
//! Frame `k` of `N` is the orbit view of `fpt render` with the same options
//! ([`super::render::OrbitArgs`]; by default the three-quarter view that
//! frames the model) turned by `360° · k / N`, drawn by the same `no_std`
//! renderer ([`super::render::render_job`]) into an exact 24-bit
//! framebuffer. Each frame gets its own palette: its exact colours when
//! there are at most 256 (flat faces usually), otherwise a NeuQuant
//! quantisation (the `gif` crate's). The GIF loops forever. It is built in
//! memory and written whole or not at all.

use super::render::{
    open_tree, orbit_camera, parse_size, read_tree, render_job, CameraSpec, Format, Image, Job,
    Look, LookArgs, OrbitArgs,
};
use super::{CliError, CliResult};
use crate::cli_err;
use crate::output::write_atomic;
use clap::Args;
use fpt_nostd::reader::Tree;
use std::path::PathBuf;

/// Most frames a turntable may have.
pub const MAX_FRAMES: u32 = 3600;
/// Frame rates a GIF can show: its delays are in hundredths of a second,
/// and viewers slow down delays under 2.
pub const FPS_RANGE: std::ops::RangeInclusive<u32> = 1..=50;
/// Largest side of a turntable picture (a GIF stores sizes in 16 bits, and
/// a turntable is meant to be small).
pub const MAX_SIDE: u32 = 4096;

/// Arguments of `fpt turntable`.
#[derive(Args, Debug)]
pub struct TurntableArgs {
    /// Tree file.
    pub tree: PathBuf,
    /// Output GIF file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Frames in one turn (1–3600).
    #[arg(long, default_value_t = 36, allow_negative_numbers = true)]
    pub frames: u32,
    /// Picture size WxH in pixels (each side at most 4096).
    #[arg(long, default_value = "160x120")]
    pub size: String,
    /// Frames per second (1–50).
    #[arg(long, default_value_t = 12, allow_negative_numbers = true)]
    pub fps: u32,
    /// The orbit of the first frame.
    #[command(flatten)]
    pub orbit: OrbitArgs,
    /// Background, arithmetic, shading and slivers.
    #[command(flatten)]
    pub look: LookArgs,
}

/// The GIF delay of one frame at `fps`, in hundredths of a second.
fn delay_of(fps: u32) -> u16 {
    ((100 + fps / 2) / fps.max(1)).clamp(2, 100) as u16
}

/// One turntable: picture size, frames, rate, the first frame's camera
/// and how the model is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spin {
    /// Width in pixels (at most [`MAX_SIDE`]).
    pub w: u32,
    /// Height in pixels (at most [`MAX_SIDE`]).
    pub h: u32,
    /// Frames in one turn.
    pub frames: u32,
    /// Frames per second.
    pub fps: u32,
    /// The camera of frame 0; an orbit's yaw advances by `360° / frames`
    /// each frame.
    pub camera: CameraSpec,
    /// Background, shading and slivers of every frame.
    pub look: Look,
}

/// `fpt turntable`.
pub fn run(a: &TurntableArgs) -> CliResult {
    let (w, h) = parse_size(&a.size)?;
    if w > MAX_SIDE || h > MAX_SIDE {
        return Err(cli_err!(
            "--size: a turntable is at most {MAX_SIDE} pixels a side, got {w}x{h}"
        ));
    }
    if !(1..=MAX_FRAMES).contains(&a.frames) {
        return Err(cli_err!(
            "--frames must be in 1..={MAX_FRAMES}, got {}",
            a.frames
        ));
    }
    if !FPS_RANGE.contains(&a.fps) {
        return Err(cli_err!(
            "--fps must be in {}..={}, got {}",
            FPS_RANGE.start(),
            FPS_RANGE.end(),
            a.fps
        ));
    }
    let look = a.look.parse()?;
    let bytes = read_tree(&a.tree)?;
    let tree = open_tree(&bytes, &a.tree)?;
    let spin = Spin {
        w,
        h,
        frames: a.frames,
        fps: a.fps,
        camera: orbit_camera(&a.orbit, &tree, w, h)?,
        look,
    };
    let gif = encode(&tree, &spin, &a.look.precision)?;
    write_atomic(&a.output, &gif).map_err(|e| cli_err!("{}: {e}", a.output.display()))?;
    println!(
        "{}: {w}x{h}, {} frames at {} fps ({} ms a frame), {} bytes",
        a.output.display(),
        a.frames,
        a.fps,
        10 * u32::from(delay_of(a.fps)),
        gif.len()
    );
    Ok(())
}

/// Draws the frames of `spin` with arithmetic `precision` (a
/// `--precision` name) and encodes the GIF in memory.
pub fn encode(tree: &Tree<'_>, spin: &Spin, precision: &str) -> Result<Vec<u8>, CliError> {
    let (w, h) = (spin.w, spin.h);
    let (gw, gh) = (
        u16::try_from(w).map_err(|_| cli_err!("--size: {w} is too wide for a GIF"))?,
        u16::try_from(h).map_err(|_| cli_err!("--size: {h} is too tall for a GIF"))?,
    );
    let mut out = Vec::new();
    {
        let mut enc =
            gif::Encoder::new(&mut out, gw, gh, &[]).map_err(|e| cli_err!("GIF encoder: {e}"))?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(|e| cli_err!("GIF encoder: {e}"))?;
        for k in 0..spin.frames {
            let camera = match spin.camera {
                CameraSpec::Orbit {
                    yaw,
                    pitch,
                    distance,
                    fov,
                    up,
                } => CameraSpec::Orbit {
                    yaw: yaw + 360.0 * f64::from(k) / f64::from(spin.frames),
                    pitch,
                    distance,
                    fov,
                    up,
                },
                other => other,
            };
            let job = Job {
                w,
                h,
                camera,
                format: Format::Rgb888,
                band: None,
                look: spin.look,
                ids: false,
                effects: None,
                gray_levels: None,
            };
            let Image::Rgb888(rgb) = render_job(tree, &job, precision)?.image else {
                return Err(cli_err!("the renderer returned no 24-bit picture"));
            };
            let mut frame = gif::Frame::from_rgb_speed(gw, gh, &rgb, 10);
            frame.delay = delay_of(spin.fps);
            enc.write_frame(&frame)
                .map_err(|e| cli_err!("GIF encoder: {e}"))?;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delays_are_hundredths_of_a_second() {
        assert_eq!(delay_of(12), 8);
        assert_eq!(delay_of(10), 10);
        assert_eq!(delay_of(50), 2);
        assert_eq!(delay_of(1), 100);
        assert_eq!(delay_of(25), 4);
    }
}
