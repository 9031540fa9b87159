//! Renders a tree file to a PNG through `embedded-graphics-simulator`,
//! with the same `no_std` renderer a firmware links: the host-side way to
//! see what a display will show.
//!
//! ```text
//! cargo run --release -p host-sim --example render_png -- firmware/trees/vise.fpt vise.png
//! ```
//!
//! Slivers are drawn (`Renderer::set_slivers`): a closed model shows no
//! background pixel inside its silhouette where the sub-pixel snap turns a
//! face seen almost edge-on toward the viewer. `--no-slivers` leaves that
//! pass out, as a firmware does unless it turns it on.
//!
//! The renderer draws through [`DrawTargetSink`], which turns every span
//! into an `embedded-graphics` `fill_solid` on any `DrawTarget`: here the
//! simulator's display, on a microcontroller a display driver's.
use std::process::ExitCode;

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use fpt_nostd::raster::{DrawTargetSink, FloatLibm, Libm, Light, Orbit};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{Frame, TreeRenderer};

/// Display size.
const W: u32 = 240;
const H: u32 = 240;
/// Vertex capacity (`fpt info` prints what a tree needs) and walk depth.
const VERTS: usize = 64;
const DEPTH: usize = 1024;

fn run(tree_path: &str, out: &str, slivers: bool) -> Result<(), String> {
    let bytes = std::fs::read(tree_path).map_err(|e| format!("reading {tree_path}: {e}"))?;
    let tree = Tree::from_bytes(&bytes).map_err(|e| format!("{tree_path}: {e}"))?;
    let mut r = Box::new(TreeRenderer::<FloatLibm<4>, VERTS>::new(W, H).ok_or("display size")?);
    // A three-quarter view from 2.1 bounding radii, 60° field of view.
    let deg = core::f32::consts::PI / 180.0;
    let orbit = Orbit::new(
        [0.0; 3],
        35.0 * deg,
        25.0 * deg,
        2.1 * tree.bounding_radius(),
        60.0 * deg,
    );
    let frame = Frame::relative(&tree, &orbit.camera::<Libm>(W as f32 / H as f32));
    r.renderer
        .set_light(Light::new(frame.key_light(), 0.25, 0.75));
    r.renderer.set_slivers(slivers);

    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(W, H));
    let mut sink = DrawTargetSink::new(&mut display);
    let stats = r
        .render::<DEPTH, _>(&tree, &frame, &mut sink)
        .map_err(|e| format!("{tree_path}: {e}"))?;
    sink.finish()
        .map_err(|_| "the display refused a span".to_string())?;
    if stats.skipped > 0 {
        return Err(format!(
            "{} polygons skipped: raise VERTS (fpt info {tree_path} says what it needs)",
            stats.skipped
        ));
    }
    display
        .to_rgb_output_image(&OutputSettings::default())
        .save_png(out)
        .map_err(|e| format!("writing {out}: {e}"))?;
    println!("{out}: {} polygons drawn", stats.drawn);
    Ok(())
}

fn main() -> ExitCode {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let before = args.len();
    args.retain(|a| a != "--no-slivers");
    let slivers = args.len() == before;
    let (tree, out) = match args.as_slice() {
        [t] if !t.starts_with('-') => (t.as_str(), "render.png"),
        [t, o] if !t.starts_with('-') && !o.starts_with('-') => (t.as_str(), o.as_str()),
        _ => {
            eprintln!("error: usage: render_png TREE.fpt [OUT.png] [--no-slivers]");
            return ExitCode::from(2);
        }
    };
    match run(tree, out, slivers) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
