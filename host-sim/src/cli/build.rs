//! `fpt build` and `fpt bench-build`.

use super::{BenchBuildArgs, BuildArgs, CliError, CliResult};
use crate::build::{build, Progress};
use crate::cli_err;
use crate::output::write_atomic;
use crate::tree::{FpTree, Method, Stats};
use fpt_nostd::effects::Effects;
use fpt_nostd::format::VertexFormat;
use fpt_nostd::raster::{Libm, Orbit};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Parses a method name.
pub fn parse_method(s: &str) -> Result<Method, CliError> {
    match s {
        "static" => Ok(Method::Static),
        "dynamic" => Ok(Method::Dynamic),
        "bsp" => Ok(Method::Bsp),
        _ => Err(cli_err!(
            "unknown method '{s}' (expected static, dynamic or bsp)"
        )),
    }
}

/// Parses a vertex encoding name: `f32`, `q16` or `q32`.
pub fn parse_vertex_format(s: &str) -> Result<VertexFormat, CliError> {
    VertexFormat::ALL
        .into_iter()
        .find(|f| f.name() == s)
        .ok_or_else(|| cli_err!("unknown vertex format '{s}' (expected f32, q16 or q32)"))
}

/// A progress bar on stderr that appears only once a build has run for
/// about a second, so quick builds print nothing.
struct Bar {
    bar: ProgressBar,
    start: Instant,
    shown: bool,
}

impl Bar {
    fn new() -> Bar {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(
            "{spinner} building [{bar:40}] {pos}/{len} polygons placed",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        Bar {
            bar,
            start: Instant::now(),
            shown: false,
        }
    }
}

impl Progress for Bar {
    fn update(&mut self, placed: usize, total: usize) {
        if !self.shown && self.start.elapsed() > Duration::from_secs(1) {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
            self.shown = true;
        }
        self.bar.set_length(total as u64);
        self.bar.set_position(placed as u64);
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// The statistics as the JSON object `fpt build --stats` writes.
pub fn stats_json(tree: &FpTree, seed: u64) -> serde_json::Value {
    let Stats {
        input_polygons,
        output_polygons,
        splittings,
        connecting_nodes,
        switch_nodes,
        bunches,
        levels,
        relations,
        max_depth,
        build_ms,
    } = tree.stats.clone();
    serde_json::json!({
        "method": tree.method.name(),
        "seed": seed,
        "closed": tree.closed,
        "input_polygons": input_polygons,
        "output_polygons": output_polygons,
        "splittings": splittings,
        "connecting_nodes": connecting_nodes,
        "switch_nodes": switch_nodes,
        "bunches": bunches,
        "levels": levels,
        "relations": relations,
        "max_depth": max_depth,
        "build_ms": build_ms,
    })
}

/// Parses `--orbit DIST,FOV[,ASPECT]` (distance in bounding radii, field
/// of view in degrees, aspect ratio).
pub fn parse_orbit(s: &str) -> Result<(f32, f32, f32), CliError> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let num = |t: &str| -> Result<f32, CliError> {
        t.parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| cli_err!("--orbit: '{t}' is not a number"))
    };
    let (d, fov, aspect) = match parts.as_slice() {
        [d, f] => (num(d)?, num(f)?, 1.0),
        [d, f, a] => (num(d)?, num(f)?, num(a)?),
        _ => return Err(cli_err!("--orbit needs DIST,FOV[,ASPECT], got '{s}'")),
    };
    if d <= 0.0 || !(0.0..180.0).contains(&fov) || aspect <= 0.0 {
        return Err(cli_err!(
            "--orbit: distance and aspect must be positive and the field of view in [0, 180) degrees"
        ));
    }
    Ok((d, fov, aspect))
}

/// The effects `fpt build` stores: `--effects` as given, or the defaults
/// of the tree's kind, without clipping when `--orbit` proves it is never
/// needed ([`fpt_nostd::raster::Orbit::never_clips`], which depends only on
/// the distance in bounding radii). Prints what the orbit proves.
fn scene_effects(a: &BuildArgs, tree: &FpTree) -> Result<Effects, CliError> {
    let given = match &a.effects {
        Some(list) => Some(Effects::parse(list).map_err(|e| cli_err!("--effects: {e}"))?),
        None => None,
    };
    let mut effects = given.unwrap_or(Effects::defaults(tree.closed));
    if let Some(o) = &a.orbit {
        let (d, fov, aspect) = parse_orbit(o)?;
        // The proof depends only on the distance in radii, so it is made
        // for a sphere of radius 1: in model units `d × radius` overflows
        // `f32` for a model of radius 1e38.
        let orbit = Orbit::new([0.0; 3], 0.0, 0.0, d, fov.to_radians());
        if orbit.never_clips::<Libm>(1.0, aspect) {
            println!("orbit {d},{fov},{aspect}: no view needs clipping");
            if given.is_none() {
                effects = effects.without(Effects::CLIPPING);
            }
        } else {
            println!("orbit {d},{fov},{aspect}: some views may need clipping");
        }
    }
    Ok(effects)
}

/// The warning for `--closed` on a mesh with boundary edges: the tree culls
/// back faces, which is right only for a closed volume; through a hole the
/// viewer sees the inside, whose faces point away and are culled, so the
/// background shows through.
fn forced_closed_line(report: &crate::mesh::ImportReport) -> Option<String> {
    let n = report.boundary_edges;
    (n > 0).then(|| {
        format!(
            "warning: --closed on a mesh with {n} boundary edge{}: back faces are culled, \
             so wherever the inside shows (through a hole, or an open part's far side) \
             the background shows instead",
            if n == 1 { "" } else { "s" }
        )
    })
}

/// `fpt build`.
pub fn run(a: &BuildArgs) -> CliResult {
    let method = parse_method(&a.method)?;
    let vertex_format = parse_vertex_format(&a.vertex_format)?;
    let options = crate::mesh::ImportOptions {
        keep_orientation: a.keep_orientation,
    };
    let model = crate::mesh::load_with(&a.mesh, &options)
        .map_err(|e| cli_err!("{}: {e}", a.mesh.display()))?;
    for w in model.report.warning_lines() {
        eprintln!("{w}");
    }
    let closed = if a.closed {
        if let Some(w) = forced_closed_line(&model.report) {
            eprintln!("{w}");
        }
        true
    } else if a.open {
        false
    } else {
        model.closed
    };
    let tree = {
        let mut bar = Bar::new();
        build(model.polygons, closed, method, a.seed, &mut bar)
    };
    let effects = scene_effects(a, &tree)?;
    if !(0.0..=180.0).contains(&a.crease) {
        return Err(cli_err!(
            "--crease: {} is not an angle from 0 to 180 degrees",
            a.crease
        ));
    }
    let opts = crate::serialize::SerializeOptions {
        vertex_format,
        effects: Some(effects.bits()),
        crease_deg: a.crease,
    };
    let bytes = crate::serialize::serialize(&tree, &opts)?;
    // Stats first: if it cannot be written, no tree file appears either.
    if let Some(path) = &a.stats {
        let text = serde_json::to_string_pretty(&stats_json(&tree, a.seed))?;
        write_atomic(path, text.as_bytes()).map_err(|e| cli_err!("{}: {e}", path.display()))?;
    }
    write_atomic(&a.output, &bytes).map_err(|e| cli_err!("{}: {e}", a.output.display()))?;
    let s = &tree.stats;
    println!("effects: {effects}");
    println!(
        "{}: {} {} tree, {} -> {} polygons, {} splittings, {} switch nodes, depth {}, {:.1} ms, {} bytes",
        a.output.display(),
        if closed { "closed" } else { "open" },
        method.name(),
        s.input_polygons,
        s.output_polygons,
        s.splittings,
        s.switch_nodes,
        s.max_depth,
        s.build_ms,
        bytes.len()
    );
    Ok(())
}

/// The shared models folder: `../shared/models` from the working directory
/// or from the workspace.
pub fn shared_models_dir() -> Option<PathBuf> {
    [
        PathBuf::from("../shared/models"),
        PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/models")),
    ]
    .into_iter()
    .find(|p| p.is_dir())
}

/// The mesh files of a folder, sorted by name.
fn meshes_in(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.extension()
                .and_then(|e| e.to_str())
                .and_then(crate::mesh::MeshFormat::from_extension)
                .is_some()
        })
        .collect();
    v.sort();
    v
}

/// `fpt bench-build --scaling`: build time against polygon count.
fn bench_scaling() -> CliResult {
    println!("| polygons | method | output | splittings | relations | build ms |");
    println!("|---|---|---|---|---|---|");
    for (major, minor) in [(38, 20), (54, 28), (78, 39), (110, 55), (156, 78)] {
        let scene = crate::scenes::torus(major, minor);
        for method in [Method::Static, Method::Dynamic, Method::Bsp] {
            let mut bar = Bar::new();
            let seed = crate::build::DEFAULT_SEED;
            let t = build(scene.polygons.clone(), true, method, seed, &mut bar);
            let s = &t.stats;
            println!(
                "| {} | {} | {} | {} | {} | {:.1} |",
                s.input_polygons,
                method.name(),
                s.output_polygons,
                s.splittings,
                s.relations,
                s.build_ms
            );
        }
    }
    Ok(())
}

/// `fpt bench-build`: static, dynamic and BSP side by side per model.
pub fn bench(a: &BenchBuildArgs) -> CliResult {
    if a.scaling {
        return bench_scaling();
    }
    let meshes = if a.meshes.is_empty() {
        let dir = shared_models_dir()
            .ok_or_else(|| cli_err!("no meshes given and ../shared/models not found"))?;
        meshes_in(&dir)
    } else {
        a.meshes.clone()
    };
    let runs = a.runs.max(1);
    println!("| model | closed | method | input | output | splittings | relations | switch | connecting | levels | depth | build ms |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for path in meshes {
        let model = crate::mesh::load(&path).map_err(|e| cli_err!("{}: {e}", path.display()))?;
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        for method in [Method::Static, Method::Dynamic, Method::Bsp] {
            // Averages over `runs` seeds (random methods vary by seed).
            let mut sum = Stats::default();
            for r in 0..runs {
                let seed = crate::build::DEFAULT_SEED.wrapping_add(u64::from(r));
                let mut bar = Bar::new();
                let t = build(model.polygons.clone(), model.closed, method, seed, &mut bar);
                let s = t.stats;
                sum.input_polygons = s.input_polygons;
                sum.output_polygons += s.output_polygons;
                sum.splittings += s.splittings;
                sum.relations += s.relations;
                sum.switch_nodes += s.switch_nodes;
                sum.connecting_nodes += s.connecting_nodes;
                sum.levels += s.levels;
                sum.max_depth += s.max_depth;
                sum.build_ms += s.build_ms;
            }
            let n = runs as usize;
            println!(
                "| {name} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.1} |",
                model.closed,
                method.name(),
                sum.input_polygons,
                sum.output_polygons / n,
                sum.splittings / n,
                sum.relations / u64::from(runs),
                sum.switch_nodes / n,
                sum.connecting_nodes / n,
                sum.levels / n,
                sum.max_depth / n,
                sum.build_ms / f64::from(runs),
            );
        }
    }
    Ok(())
}
