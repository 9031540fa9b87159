//! The `fpt` command-line tool.
//!
//! Every command reports bad input as one line `error: ...` on stderr and exit
//! status 2, never a panic; files are written whole or not at all
//! ([`crate::output::write_atomic`]).

use clap::{Args, Parser, Subcommand};
use std::ffi::OsString;
use std::path::PathBuf;

pub mod accuracy;
mod bench_memory;
mod build;
mod demo;
mod display;
pub mod frames;
mod inspect;
pub mod mcu_bench;
mod render;
mod subdivide;
pub mod turntable;
pub mod view;

/// A failure reported to the user as `error: MESSAGE`, exit status 2.
#[derive(Debug)]
pub struct CliError(pub String);

impl<E: std::fmt::Display> From<E> for CliError {
    fn from(e: E) -> Self {
        CliError(e.to_string())
    }
}

/// Result of a command.
pub type CliResult = Result<(), CliError>;

/// Shorthand for an error with a formatted message.
#[macro_export]
macro_rules! cli_err {
    ($($t:tt)*) => { $crate::cli::CliError(format!($($t)*)) };
}

#[derive(Parser, Debug)]
#[command(
    name = "fpt",
    version,
    about = "Feudal priority trees: build, inspect, order, render"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Build a feudal priority tree (or a BSP tree) from a mesh file.
    Build(BuildArgs),
    /// Print the tree's output polygons as JSON, in model coordinates.
    Polygons(PolygonsArgs),
    /// Print the classes of polygons for one view, back to front, as JSON.
    Order(OrderArgs),
    /// Validate a tree file and print its header and counts.
    Info(InfoArgs),
    /// Compare static, dynamic and BSP builds on mesh files (paper's Table 6/7).
    BenchBuild(BenchBuildArgs),
    /// Time the postprocessing walk over many view directions.
    BenchOrder(BenchOrderArgs),
    /// Draw the firmware's frames on the host and print their checksums.
    Frames(frames::FramesArgs),
    /// Render a tree to PNG through the no_std pipeline.
    Render(render::RenderArgs),
    /// Render the model spinning once about its up axis as an animated GIF.
    Turntable(turntable::TurntableArgs),
    /// Open a window that orbits the model: arrow keys turn, +/- zoom, Esc
    /// quits (needs the `view` cargo feature, SDL2).
    View(view::ViewArgs),
    /// Build, render and save the demo scenes (vise, house, city) as PNG.
    Demo(demo::DemoArgs),
    /// Measure error against time of every arithmetic configuration.
    BenchAccuracy(accuracy::AccuracyArgs),
    /// Draw a tree over the standard orbit on an emulated MCU (QEMU) and
    /// print its cost, memory and checksum check as JSON.
    McuBench(mcu_bench::McuBenchArgs),
    /// Measure the working memory a tree's banded frames need and the walks
    /// that less memory costs (standard orbit, host).
    BenchMemory(bench_memory::BenchMemoryArgs),
    /// Refine a mesh by Loop subdivision (four times the triangles a step)
    /// and write it as OBJ: large curved meshes for build benchmarks.
    Subdivide(subdivide::SubdivideArgs),
}

/// Arguments of `fpt build`.
#[derive(Args, Debug)]
pub struct BuildArgs {
    /// Mesh file: OBJ, OFF, STL (binary or ASCII) or PLY.
    pub mesh: PathBuf,
    /// Output tree file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Preprocessing method: static, dynamic or bsp.
    #[arg(long, default_value = "static")]
    pub method: String,
    /// Seed of the random choices of dynamic preprocessing and BSP.
    #[arg(long, default_value_t = crate::build::DEFAULT_SEED, allow_negative_numbers = true)]
    pub seed: u64,
    /// Treat the mesh as a closed volume (back faces culled).
    #[arg(long, conflicts_with = "open")]
    pub closed: bool,
    /// Treat the mesh as an open volume (both sides drawn).
    #[arg(long)]
    pub open: bool,
    /// Leave closed parts whose faces wind inward as they are (by default
    /// they are turned outward, with a warning).
    #[arg(long = "keep-orientation")]
    pub keep_orientation: bool,
    /// Keep one polygon per face of the file: do not merge neighbouring
    /// coplanar faces of one colour into convex polygons (merged by
    /// default, except for trees declaring `smooth`).
    #[arg(long = "no-merge")]
    pub no_merge: bool,
    /// Write the build statistics to this JSON file.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// Vertex encoding in the tree file: f32, q16 or q32.
    #[arg(long = "vertex-format", default_value_t = build::default_vertex_format(), value_parser = ["f32", "q16", "q32"])]
    pub vertex_format: String,
    /// The scene's effects, stored in the file: comma-separated culling,
    /// two-sided, clipping, lighting, depth-cue, dither, outline, smooth; or none.
    /// Default: culling (closed) or two-sided (open), clipping, lighting.
    #[arg(long)]
    pub effects: Option<String>,
    /// The orbit the scene is seen from, DIST,FOV or DIST,FOV,ASPECT: distance from
    /// the bounding-sphere centre in bounding radii, vertical field of view
    /// in degrees (0: parallel), viewport width/height (default 1). When no
    /// view of that orbit can need clipping, the default effects leave
    /// clipping out.
    #[arg(long, allow_hyphen_values = true)]
    pub orbit: Option<String>,
    /// Heap the build may use, in MiB: a mesh that needs more is refused
    /// with an error (exit status 2) before or while building.
    #[arg(long = "max-memory", value_parser = clap::value_parser!(u64).range(1..))]
    pub max_memory: Option<u64>,
    /// The model's up axis, recorded in the tree for `fpt render` and
    /// `fpt turntable`: auto (z for STL files, y for the others), x, y or z.
    #[arg(long, default_value = "auto", value_parser = ["auto", "x", "y", "z"])]
    pub up: String,
    /// One colour R,G,B (0–255 each) for the whole mesh, instead of the
    /// file's (OBJ materials' Kd, PLY face or vertex colours) or grey.
    #[arg(long)]
    pub color: Option<String>,
    /// The crease angle in degrees, 0 to 180: with the outline effect, an
    /// edge between faces meeting at a sharper angle is drawn, a smoother
    /// one only where it is a silhouette; with the smooth effect, vertex
    /// normals are averaged only over faces within this angle.
    #[arg(long, default_value_t = 30.0, allow_hyphen_values = true)]
    pub crease: f32,
    /// Polygon records: `narrow` (bit fields in as few bytes as they need,
    /// a colour table, and switch planes shared with the 20-byte runs),
    /// `table` (narrow records, and every distinct plane stored once in a
    /// table that 4-byte runs and the switches index: smaller files, the
    /// default), `compact` (8 bytes a polygon and a colour table,
    /// as files of sessions 10–16) or `wide` (16 bytes, as files written
    /// before compact records existed); for comparisons and older
    /// readers. `table` falls back to `narrow` beyond 65,535 polygons,
    /// `narrow` and `compact` to `wide` when the fields do not fit.
    #[arg(long, default_value_t = build::default_records(), value_parser = ["narrow", "table", "compact", "wide"])]
    pub records: String,
    /// Plane table entries (with `--records table`): `f32` (normal and
    /// offset, 16 bytes) or `compact` (an `i16` normal and offset, 8
    /// bytes: the planes rounded to about radius / 20,000, which can
    /// change the facing of a polygon seen edge-on only). `compact`
    /// without `--records table` is an error: other record layouts keep
    /// their `f32` planes in the runs. Default: `compact` with the
    /// table, else `f32`.
    #[arg(long, value_parser = ["f32", "compact"])]
    pub planes: Option<String>,
}

/// Arguments of `fpt polygons`.
#[derive(Args, Debug)]
pub struct PolygonsArgs {
    /// Tree file.
    pub tree: PathBuf,
}

/// Arguments of `fpt order`.
#[derive(Args, Debug)]
pub struct OrderArgs {
    /// Tree file.
    pub tree: PathBuf,
    /// Parallel projection looking along X,Y,Z (from the viewer into the scene).
    #[arg(long = "view-dir", allow_hyphen_values = true, conflicts_with = "eye")]
    pub view_dir: Option<String>,
    /// Perspective viewpoint X,Y,Z.
    #[arg(long, allow_hyphen_values = true)]
    pub eye: Option<String>,
}

/// Arguments of `fpt info`.
#[derive(Args, Debug)]
pub struct InfoArgs {
    /// Tree file.
    pub tree: PathBuf,
}

/// Arguments of `fpt bench-build`.
#[derive(Args, Debug)]
pub struct BenchBuildArgs {
    /// Mesh files (default: the shared models in ../shared/models).
    pub meshes: Vec<PathBuf>,
    /// Builds per method and model; times are averaged.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    pub runs: u32,
    /// Build time, peak heap, output polygons and bytes per polygon of the
    /// static build against size, with fitted growth exponents: for the
    /// meshes given, or for faceted tori of 760 to 70,000 polygons.
    #[arg(long)]
    pub scaling: bool,
    /// With --scaling and no meshes: the largest torus, in polygons.
    #[arg(long = "max-polygons", default_value_t = 70_000)]
    pub max_polygons: usize,
    /// With --scaling and meshes: measure each mesh also after 1 to K steps
    /// of Loop subdivision (each four times the triangles; faces of more
    /// than three vertices are cut into triangles first), as `NAME Loop k`.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(0..=8))]
    pub subdivide: Option<u32>,
}

/// Arguments of `fpt bench-order`.
#[derive(Args, Debug)]
pub struct BenchOrderArgs {
    /// Tree file.
    pub tree: PathBuf,
    /// Number of view directions spread over the sphere.
    #[arg(long, default_value_t = 1000, allow_negative_numbers = true)]
    pub views: u32,
    /// Repeat the walks over all views until this many seconds have passed.
    #[arg(
        long = "min-seconds",
        default_value_t = 0.5,
        allow_negative_numbers = true
    )]
    pub min_seconds: f64,
}

/// Parses `X,Y,Z` into three finite numbers.
pub fn parse_vec3(what: &str, s: &str) -> Result<[f64; 3], CliError> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(cli_err!("{what} needs three numbers X,Y,Z, got '{s}'"));
    }
    let mut out = [0.0; 3];
    for (o, p) in out.iter_mut().zip(parts) {
        let v: f64 = p
            .trim()
            .parse()
            .map_err(|_| cli_err!("{what}: '{p}' is not a number"))?;
        if !v.is_finite() {
            return Err(cli_err!("{what}: '{p}' is not finite"));
        }
        *o = v;
    }
    Ok(out)
}

/// Runs `fpt` with `args` (the first is the program name); returns the exit status.
pub fn main_with_args<I, T>(args: I) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                print!("{e}");
                return 0;
            }
            // clap's message spans several lines; the contract is one line:
            // keep what comes before the usage text, joined.
            let text = e.to_string();
            let first: Vec<&str> = text
                .lines()
                .take_while(|l| !l.starts_with("Usage:"))
                .map(str::trim)
                .filter(|l| !l.is_empty() && !l.starts_with("For more information"))
                .collect();
            let first = first.join(" ");
            let first = first.trim_start_matches("error: ");
            eprintln!("error: {first}");
            return 2;
        }
    };
    let result = match cli.command {
        Command::Build(a) => build::run(&a),
        Command::Polygons(a) => inspect::polygons(&a),
        Command::Order(a) => inspect::order(&a),
        Command::Info(a) => inspect::info(&a),
        Command::BenchBuild(a) => build::bench(&a),
        Command::BenchOrder(a) => inspect::bench_order(&a),
        Command::Frames(a) => frames::run(&a),
        Command::Render(a) => render::run(&a),
        Command::Turntable(a) => turntable::run(&a),
        Command::View(a) => view::run(&a),
        Command::Demo(a) => demo::run(&a),
        Command::BenchAccuracy(a) => accuracy::run(&a),
        Command::McuBench(a) => mcu_bench::run(&a),
        Command::BenchMemory(a) => bench_memory::run(&a),
        Command::Subdivide(a) => subdivide::run(&a),
    };
    match result {
        Ok(()) => 0,
        Err(CliError(msg)) => {
            let one_line = msg.replace('\n', " ");
            eprintln!("error: {one_line}");
            2
        }
    }
}
