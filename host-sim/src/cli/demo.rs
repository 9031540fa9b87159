//! `fpt demo`: the first command a new user runs.
//!
//! Builds feudal priority trees for the project's own procedural scenes
//! (nothing outside the repository is read): the machinist's vise in grey
//! shading and the house with concave walls in colour (after the paper's
//! Figures 15 and 16), and the benchmark city (1,500+ polygons). For each
//! scene it serializes the tree, validates the bytes with the no_std
//! reader, renders several views through the no_std pipeline (fixed point,
//! 4 sub-pixel bits: the firmware's configuration) into the framebuffer
//! format a small display would use, and saves them as PNG; then draws the
//! vise again with optional effects (outlines, depth cue) and on simulated
//! monochrome and 4-level grey panels (ordered dithering). Last, a
//! coloured model through the path a user's file takes: a toy robot in six
//! materials is written as OBJ + MTL, read back by the mesh import (its
//! colours from `usemtl` and `Kd`), built, rendered and spun into a
//! turntable GIF. It prints the build statistics and where every file is.

use super::display::Panel;
use super::render::{render_job, save_png, save_png_as, CameraSpec, Format, Job, Look};
use super::turntable::{encode, Spin};
use super::CliResult;
use crate::build::{build, NoProgress, DEFAULT_SEED};
use crate::cli_err;
use crate::output::write_atomic;
use crate::scenes::{bench_city, house, vise, Scene};
use crate::serialize::{serialize, SerializeOptions};
use crate::tree::Method;
use clap::Args;
use embedded_graphics::pixelcolor::Rgb888;
use fpt_nostd::effects::Effects;
use fpt_nostd::format::UpAxis;
use fpt_nostd::raster::ShadeMode;
use fpt_nostd::reader::Tree;
use std::path::{Path, PathBuf};

/// Arguments of `fpt demo`.
#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Output folder (created if missing).
    #[arg(long, default_value = "out/demo")]
    pub out: PathBuf,
    /// Leave out the sliver pass (see `fpt render --help`).
    #[arg(long = "no-slivers")]
    pub no_slivers: bool,
}

/// Picture size of the demo (a common small TFT).
const W: u32 = 320;
const H: u32 = 240;
/// The arithmetic the firmware uses.
const PRECISION: &str = "fixed-subpx-4";

/// One scene of the demo and how to show it.
struct Show {
    scene: Scene,
    shade: ShadeMode,
    format: Format,
    background: Rgb888,
    /// Orbit distance in bounding radii.
    distance: f64,
    /// Orbit views: yaw, pitch, field of view (degrees; 0 = parallel).
    views: &'static [(f64, f64, f64)],
}

fn shows() -> Vec<Show> {
    vec![
        Show {
            scene: vise(),
            shade: ShadeMode::Grey(235),
            format: Format::Gray8,
            background: Rgb888::new(40, 40, 40),
            distance: 3.0,
            views: &[
                (35.0, 30.0, 40.0),
                (140.0, 25.0, 40.0),
                (-70.0, 50.0, 0.0),
                (200.0, -20.0, 40.0),
            ],
        },
        Show {
            scene: house(),
            shade: ShadeMode::Lambert,
            format: Format::Rgb565,
            background: Rgb888::new(150, 190, 225),
            distance: 3.0,
            views: &[
                (30.0, 20.0, 40.0),
                (150.0, 30.0, 40.0),
                (-110.0, 12.0, 40.0),
                (60.0, 60.0, 0.0),
            ],
        },
        Show {
            scene: bench_city(),
            shade: ShadeMode::Lambert,
            format: Format::Rgb888,
            background: Rgb888::new(30, 30, 45),
            distance: 1.9,
            views: &[(25.0, 35.0, 40.0), (200.0, 20.0, 40.0), (-45.0, 70.0, 0.0)],
        },
    ]
}

/// The static tree of a z-up model, serialized with its up axis recorded
/// (so `fpt render TREE` shows it upright) and written to `out/NAME.fpt`.
fn build_z_up(
    name: &str,
    polygons: Vec<crate::geom::Polygon>,
    closed: bool,
    out: &Path,
) -> Result<(crate::tree::FpTree, Vec<u8>, PathBuf), super::CliError> {
    let tree = build(
        polygons,
        closed,
        Method::Static,
        DEFAULT_SEED,
        &mut NoProgress,
    );
    let opts = SerializeOptions {
        up: UpAxis::Z,
        ..SerializeOptions::default()
    };
    let bytes = serialize(&tree, &opts)?;
    let path = out.join(format!("{name}.fpt"));
    write_atomic(&path, &bytes).map_err(|e| cli_err!("{}: {e}", path.display()))?;
    Ok((tree, bytes, path))
}

/// Builds, checks, renders and reports one scene.
fn demo_scene(show: &Show, out: &Path, slivers: bool) -> CliResult {
    let s = &show.scene;
    let (tree, bytes, tree_path) = build_z_up(&s.name, s.polygons.clone(), s.closed, out)?;
    let t = Tree::from_bytes(&bytes)
        .map_err(|e| cli_err!("{}: the serialized tree does not validate: {e}", s.name))?;
    let st = &tree.stats;
    println!(
        "{}: {} {} polygons -> {} ({} splittings); {} connecting / {} switch nodes, {} levels, \
         {} relations, depth {}; built in {:.1} ms; {} bytes -> {}",
        s.name,
        if s.closed { "closed," } else { "open," },
        st.input_polygons,
        st.output_polygons,
        st.splittings,
        st.connecting_nodes,
        st.switch_nodes,
        st.levels,
        st.relations,
        st.max_depth,
        st.build_ms,
        bytes.len(),
        tree_path.display()
    );
    for (k, &(yaw, pitch, fov)) in show.views.iter().enumerate() {
        let job = Job {
            w: W,
            h: H,
            camera: CameraSpec::Orbit {
                yaw,
                pitch,
                distance: Some(show.distance),
                fov,
                up: UpAxis::Z,
            },
            format: show.format,
            band: None,
            look: Look {
                background: show.background,
                shade: show.shade,
                slivers,
            },
            ids: false,
            effects: None,
            gray_levels: None,
        };
        let r = render_job(&t, &job, PRECISION)?;
        let png = out.join(format!("{}_{}.png", s.name, k + 1));
        save_png(&r.image, W, H, &png)?;
        let proj = if fov > 0.0 { "perspective" } else { "parallel" };
        println!(
            "  {}  yaw {yaw:>4}° pitch {pitch:>3}° {proj:<11} {} polygons drawn, {:.2} ms",
            png.display(),
            r.stats.drawn,
            r.ms
        );
    }
    Ok(())
}

/// One effect picture: name, effects, storage, grey levels, panel look,
/// size.
type Shot = (
    &'static str,
    Effects,
    Format,
    Option<u16>,
    Panel,
    (u32, u32),
);

/// The vise again with the optional stages a scene can declare (see
/// `fpt_nostd::effects`), and on simulated small panels.
fn demo_effects(out: &Path, slivers: bool) -> CliResult {
    let path = out.join("vise.fpt");
    let bytes = std::fs::read(&path).map_err(|e| cli_err!("{}: {e}", path.display()))?;
    let t = Tree::from_bytes(&bytes).map_err(|e| cli_err!("{}: {e}", path.display()))?;
    let base = Effects::from_bits(t.effects());
    println!("effects (the vise declares {base}):");
    let shots: [Shot; 4] = [
        (
            "outline",
            base.with(Effects::OUTLINE),
            Format::Rgb888,
            None,
            Panel::Plain,
            (W, H),
        ),
        (
            "depth_cue",
            base.with(Effects::DEPTH_CUE),
            Format::Rgb888,
            None,
            Panel::Plain,
            (W, H),
        ),
        (
            "oled_dither",
            base.with(Effects::DITHER),
            Format::Mono,
            None,
            Panel::OledBlue,
            (128, 64),
        ),
        (
            "lcd_gray4",
            base.with(Effects::DITHER),
            Format::Gray8,
            Some(4),
            Panel::LcdWhite,
            (128, 96),
        ),
    ];
    for (name, effects, format, gray_levels, panel, (w, h)) in shots {
        let job = Job {
            w,
            h,
            camera: CameraSpec::Orbit {
                yaw: 35.0,
                pitch: 25.0,
                distance: Some(2.2),
                fov: 40.0,
                up: UpAxis::Z,
            },
            format,
            band: None,
            look: Look {
                background: Rgb888::new(0, 0, 0),
                shade: ShadeMode::Lambert,
                slivers,
            },
            ids: false,
            effects: Some(effects),
            gray_levels,
        };
        let r = render_job(&t, &job, PRECISION)?;
        let png = out.join(format!("vise_{name}.png"));
        save_png_as(&r.image, w, h, &png, panel)?;
        println!("  {}  {w}x{h} {effects}", png.display());
    }
    Ok(())
}

/// The coloured model: written as OBJ + MTL, imported, built, rendered
/// and spun.
fn demo_coloured(out: &Path, slivers: bool) -> CliResult {
    let scene = crate::scenes::robot();
    let (obj, mtl) = crate::mesh::write_obj_mtl(&scene.polygons, "robot.mtl");
    let obj_path = out.join("robot.obj");
    for (path, text) in [(out.join("robot.mtl"), mtl), (obj_path.clone(), obj)] {
        write_atomic(&path, text.as_bytes()).map_err(|e| cli_err!("{}: {e}", path.display()))?;
    }
    let model =
        crate::mesh::load(&obj_path).map_err(|e| cli_err!("{}: {e}", obj_path.display()))?;
    let mut materials: Vec<[u8; 3]> = model.polygons.iter().map(|p| p.color).collect();
    materials.sort_unstable();
    materials.dedup();
    let (tree, bytes, tree_path) = build_z_up("robot", model.polygons, model.closed, out)?;
    let t = Tree::from_bytes(&bytes)
        .map_err(|e| cli_err!("robot: the serialized tree does not validate: {e}"))?;
    let st = &tree.stats;
    println!(
        "robot: {} written as OBJ + MTL and read back: {} materials, {} polygons -> {}; \
         {} bytes -> {}",
        obj_path.display(),
        materials.len(),
        st.input_polygons,
        st.output_polygons,
        bytes.len(),
        tree_path.display()
    );
    let look = Look {
        background: Rgb888::new(30, 34, 44),
        shade: ShadeMode::Lambert,
        slivers,
    };
    let camera = |yaw: f64, pitch: f64| CameraSpec::Orbit {
        yaw,
        pitch,
        distance: Some(3.0),
        fov: 40.0,
        up: UpAxis::Z,
    };
    let job = Job {
        w: W,
        h: H,
        camera: camera(35.0, 25.0),
        format: Format::Rgb888,
        band: None,
        look,
        ids: false,
        effects: None,
        gray_levels: None,
    };
    let r = render_job(&t, &job, PRECISION)?;
    let png = out.join("robot_1.png");
    save_png(&r.image, W, H, &png)?;
    println!(
        "  {}  yaw   35° pitch  25° perspective {} polygons drawn, {:.2} ms",
        png.display(),
        r.stats.drawn,
        r.ms
    );
    let spin = Spin {
        w: 160,
        h: 120,
        frames: 36,
        fps: 12,
        camera: camera(35.0, 20.0),
        look,
    };
    let gif = encode(&t, &spin, PRECISION)?;
    let gif_path = out.join("robot_spin.gif");
    write_atomic(&gif_path, &gif).map_err(|e| cli_err!("{}: {e}", gif_path.display()))?;
    println!(
        "  {}  {}x{} turntable, {} frames at {} fps, {} bytes",
        gif_path.display(),
        spin.w,
        spin.h,
        spin.frames,
        spin.fps,
        gif.len()
    );
    Ok(())
}

/// `fpt demo`.
pub fn run(a: &DemoArgs) -> CliResult {
    std::fs::create_dir_all(&a.out).map_err(|e| cli_err!("{}: {e}", a.out.display()))?;
    println!(
        "feudal demo: {W}x{H} renders through the no_std pipeline ({PRECISION}), written to {}",
        a.out.display()
    );
    for show in shows() {
        demo_scene(&show, &a.out, !a.no_slivers)?;
    }
    demo_effects(&a.out, !a.no_slivers)?;
    demo_coloured(&a.out, !a.no_slivers)?;
    println!(
        "render a tree yourself: fpt render {} -o view.png [--yaw 30 --pitch 20]; \
         spin it: fpt turntable {} -o spin.gif",
        a.out.join("house.fpt").display(),
        a.out.join("robot.fpt").display()
    );
    Ok(())
}
