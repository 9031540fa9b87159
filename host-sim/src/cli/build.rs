//! `fpt build` and `fpt bench-build`.

use super::{BenchBuildArgs, BuildArgs, CliError, CliResult};
use crate::build::{build, Progress};
use crate::cli_err;
use crate::output::write_atomic;
use crate::serialize::SerializeOptions;
use crate::tree::{FpTree, Method, Stats};
use fpt_nostd::effects::Effects;
use fpt_nostd::format::{UpAxis, VertexFormat};
use fpt_nostd::raster::{Libm, Orbit};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
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

/// `--vertex-format`'s default: that of [`SerializeOptions::default`],
/// the default file options.
pub fn default_vertex_format() -> String {
    SerializeOptions::default().vertex_format.name().to_string()
}

/// The `--records` choices and the record options each writes
/// (`compact`, `narrow` and `plane_table` of [`SerializeOptions`]).
const RECORDS: [(&str, [bool; 3]); 4] = [
    ("table", [true, true, true]),
    ("narrow", [true, true, false]),
    ("compact", [true, false, false]),
    ("wide", [false, false, false]),
];

/// The `--records` name of `opts`' record options, `None` for a
/// combination no name writes.
pub fn records_name(opts: &SerializeOptions) -> Option<&'static str> {
    let flags = [opts.compact, opts.narrow, opts.plane_table];
    RECORDS.iter().find(|r| r.1 == flags).map(|r| r.0)
}

/// `--records`' default: the name of [`SerializeOptions::default`]'s
/// records.
pub fn default_records() -> String {
    records_name(&SerializeOptions::default())
        .unwrap_or("narrow")
        .to_string()
}

/// `opts` with the record options of `--records NAME`.
pub fn with_records(opts: SerializeOptions, name: &str) -> Result<SerializeOptions, CliError> {
    let [compact, narrow, plane_table] = RECORDS
        .iter()
        .find(|r| r.0 == name)
        .ok_or_else(|| {
            cli_err!("unknown records '{name}' (expected table, narrow, compact or wide)")
        })?
        .1;
    Ok(SerializeOptions {
        compact,
        narrow,
        plane_table,
        ..opts
    })
}

/// Build progress on stderr. On a terminal: a bar that appears once a
/// build has run for about a second (quick builds print nothing), redrawn
/// every 200 ms with elapsed time and ETA; its total is the input polygon
/// count and never grows. Otherwise: a plain line at most every 10 s.
struct Bar {
    bar: ProgressBar,
    start: Instant,
    shown: bool,
    tty: bool,
    last_line: Instant,
    quiet: bool,
}

impl Bar {
    fn new() -> Bar {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(
            "{spinner} building [{bar:40}] {pos}/{len} input polygons placed, {elapsed}, ETA {eta}",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        Bar {
            bar,
            start: Instant::now(),
            shown: false,
            tty: std::io::stderr().is_terminal(),
            last_line: Instant::now(),
            quiet: false,
        }
    }

    /// A bar that shows only on a terminal (benchmarks print tables).
    fn quiet() -> Bar {
        let mut b = Bar::new();
        b.quiet = true;
        b
    }
}

impl Progress for Bar {
    fn update(&mut self, placed: usize, total: usize) {
        self.bar.set_length(total as u64);
        self.bar.set_position(placed as u64);
        let elapsed = self.start.elapsed();
        if self.tty {
            if !self.shown && elapsed > Duration::from_secs(1) {
                self.bar.set_draw_target(ProgressDrawTarget::stderr());
                self.bar.enable_steady_tick(Duration::from_millis(200));
                self.shown = true;
            }
        } else if !self.quiet && self.last_line.elapsed() >= Duration::from_secs(10) {
            self.last_line = Instant::now();
            let pct = 100.0 * placed as f64 / total.max(1) as f64;
            eprintln!(
                "building: {placed} of {total} input polygons placed ({pct:.0} %), {:.0} s",
                elapsed.as_secs_f64()
            );
        }
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// Heap a build of `polygons` input polygons needs, about, in bytes:
/// measured peaks (`fpt bench-build --scaling`) are 1.0–1.9 KiB per input
/// polygon; this allows 3 KiB and 16 MiB besides.
pub fn build_estimate(polygons: usize) -> usize {
    (16 << 20) + polygons.saturating_mul(3 << 10)
}

/// Refuses a build that will not fit `--max-memory`, and tells the
/// allocator what the build needs for its message if memory runs out.
fn check_memory(a: &BuildArgs, polygons: usize) -> CliResult {
    let need = crate::memory::in_use() + build_estimate(polygons);
    let mib = need.div_ceil(1 << 20);
    if let Some(max) = a.max_memory {
        let max = usize::try_from(max)
            .unwrap_or(usize::MAX)
            .saturating_mul(1 << 20);
        if need > max {
            return Err(cli_err!(
                "not enough memory to build this mesh (needs about {mib} MiB)"
            ));
        }
        crate::memory::set_limit(max);
    }
    crate::memory::set_build_estimate(mib);
    Ok(())
}

/// Why the mesh is open and what that costs, when it is: the edges that
/// make it open, by kind, with the first few of each as end positions.
fn open_lines(report: &crate::mesh::ImportReport) -> Vec<String> {
    let n = report.boundary_edges;
    if n == 0 {
        return Vec::new();
    }
    let mut lines = vec![format!(
        "note: the mesh is open: {n} edge{} not shared by exactly two faces winding \
         opposite ways; an open tree draws both sides of every face in every view \
         (no back-face culling)",
        if n == 1 { " is" } else { "s are" }
    )];
    lines.extend(
        report
            .open_edge_lines()
            .into_iter()
            .map(|l| format!("note:   {l}")),
    );
    lines
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
        // As `fpt info` counts them: the bunches the file stores (every
        // level's `F_j` and `B_j` and every switch's `O_k`, empty or not),
        // and those that hold polygons (the paper's count, `Stats::bunches`).
        "bunches": 2 * levels + switch_nodes,
        "nonempty_bunches": bunches,
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

/// The up axis `fpt build --up NAME` records for `mesh`: `auto` is the
/// format's ([`crate::mesh::MeshFormat::up_axis`]: z for STL, y for the
/// others).
pub fn up_axis_for(name: &str, mesh: &Path) -> Result<UpAxis, CliError> {
    if name == "auto" {
        let format = mesh
            .extension()
            .and_then(|e| e.to_str())
            .and_then(crate::mesh::MeshFormat::from_extension);
        return Ok(format.map_or(UpAxis::Y, |f| f.up_axis()));
    }
    UpAxis::from_name(name)
        .ok_or_else(|| cli_err!("unknown up axis '{name}' (expected auto, x, y or z)"))
}

/// `fpt build`.
pub fn run(a: &BuildArgs) -> CliResult {
    let method = parse_method(&a.method)?;
    let vertex_format = parse_vertex_format(&a.vertex_format)?;
    // Checked before the build, which can take minutes: compact entries
    // exist only in a plane table, and silently writing 16-byte planes
    // would hide that the option did nothing.
    if a.planes.as_deref() == Some("compact") && a.records != "table" {
        return Err(cli_err!(
            "--planes compact needs --records table (compact planes are plane table entries)"
        ));
    }
    let up = up_axis_for(&a.up, &a.mesh)?;
    let color = match &a.color {
        Some(c) => Some(super::render::parse_rgb("--color", c)?),
        None => None,
    };
    // Smooth shading interpolates vertex normals across a polygon: a
    // merged flat face would be shaded differently from its triangles.
    let smooth = match &a.effects {
        Some(list) => Effects::parse(list)
            .map_err(|e| cli_err!("--effects: {e}"))?
            .contains(Effects::SMOOTH),
        None => false,
    };
    let options = crate::mesh::ImportOptions {
        keep_orientation: a.keep_orientation,
        no_merge: a.no_merge || smooth,
    };
    // Reading the mesh is part of building it: running out of memory there
    // gets the same message (with what was in use when it ran out).
    crate::memory::set_build_estimate(1);
    let mut model = crate::mesh::load_with(&a.mesh, &options)
        .map_err(|e| cli_err!("{}: {e}", a.mesh.display()))?;
    if let Some(c) = color {
        for p in &mut model.polygons {
            p.color = c;
        }
    }
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
        if !model.closed {
            for l in open_lines(&model.report) {
                eprintln!("{l}");
            }
        }
        model.closed
    };
    check_memory(a, model.polygons.len())?;
    crate::memory::reset_peak();
    let tree = {
        let mut bar = Bar::new();
        build(model.polygons, closed, method, a.seed, &mut bar)
    };
    crate::memory::set_build_estimate(0);
    let peak = crate::memory::peak().map_or_else(String::new, |p| {
        format!(", peak heap {:.1} MiB", p as f64 / f64::from(1 << 20))
    });
    let effects = scene_effects(a, &tree)?;
    if !(0.0..=180.0).contains(&a.crease) {
        return Err(cli_err!(
            "--crease: {} is not an angle from 0 to 180 degrees",
            a.crease
        ));
    }
    let opts = with_records(
        SerializeOptions {
            vertex_format,
            effects: Some(effects.bits()),
            up,
            crease_deg: a.crease,
            // Unless told, a table's entries are the default's.
            compact_planes: match a.planes.as_deref() {
                Some(p) => p == "compact",
                None => SerializeOptions::default().compact_planes,
            },
            ..SerializeOptions::default()
        },
        &a.records,
    )?;
    let bytes = crate::serialize::serialize(&tree, &opts)?;
    // Stats first: if it cannot be written, no tree file appears either.
    if let Some(path) = &a.stats {
        let text = serde_json::to_string_pretty(&stats_json(&tree, a.seed))?;
        write_atomic(path, text.as_bytes()).map_err(|e| cli_err!("{}: {e}", path.display()))?;
    }
    write_atomic(&a.output, &bytes).map_err(|e| cli_err!("{}: {e}", a.output.display()))?;
    let s = &tree.stats;
    println!("effects: {effects}; up axis: {}", up.name());
    println!(
        "{}: {} {} tree, {} -> {} polygons, {} splittings, {} switch nodes, depth {}, {:.1} ms, {} bytes{peak}",
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

/// The least-squares slope of `ln y` against `ln x`: the exponent `k` of
/// `y ≈ c·x^k`; `None` with fewer than two distinct sizes.
pub fn growth_exponent(points: &[(f64, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let sxx: f64 = pts.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    (pts.len() >= 2 && sxx > 1e-12).then(|| sxy / sxx)
}

/// CPU time of this process so far, all threads (the builder counts rows
/// on several), in seconds; `None` where `/proc/self/stat` is not there.
/// Unlike the wall-clock build time it does not grow with the load other
/// programs put on a shared machine.
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which may hold spaces), from `state`:
    // `utime` and `stime` are the 12th and 13th, in ticks of 1/100 s
    // (USER_HZ, fixed at 100 for this interface).
    let rest = stat.rsplit_once(')')?.1;
    let mut fields = rest.split_whitespace().skip(11);
    let utime: f64 = fields.next()?.parse().ok()?;
    let stime: f64 = fields.next()?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

/// Starts a new peak of this process's resident memory (Linux
/// `/proc/self/clear_refs`, 5: resets `VmHWM`); false where that cannot
/// be done, and then [`peak_rss_mib`] would be the peak of the whole run.
fn reset_peak_rss() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// The peak resident memory of this process since [`reset_peak_rss`]
/// (`VmHWM`), in MiB: unlike the heap peak it counts the loaded meshes,
/// the allocator's slack and the threads' stacks, what `/usr/bin/time`
/// reports and the memory target is about.
fn peak_rss_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let kib: f64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))?
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kib / 1024.0)
}

/// `fpt bench-build --scaling`: the static build against size, for the
/// meshes given (and their subdivisions, `--subdivide K`) or for faceted
/// tori.
fn bench_scaling(a: &BenchBuildArgs) -> CliResult {
    let mut inputs: Vec<(String, Vec<crate::geom::Polygon>, bool)> = Vec::new();
    if a.subdivide.is_some() && a.meshes.is_empty() {
        return Err(cli_err!(
            "--subdivide needs mesh files (the tori are not subdivided)"
        ));
    }
    if a.meshes.is_empty() {
        let mut size = 760usize;
        while size <= a.max_polygons.max(760) {
            // A torus of about `size` quads, twice as many around as across.
            let minor = ((size as f64 / 2.0).sqrt()).round().max(3.0) as usize;
            let major = (size / minor).max(3);
            let scene = crate::scenes::torus(major, minor);
            inputs.push((format!("torus {major}×{minor}"), scene.polygons, true));
            size *= 2;
        }
    } else {
        for path in &a.meshes {
            let model = crate::mesh::load(path).map_err(|e| cli_err!("{}: {e}", path.display()))?;
            let name = path
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
            let k = a.subdivide.unwrap_or(0);
            for (name, m) in super::subdivide::levels(&name, path, model, k)? {
                inputs.push((name, m.polygons, m.closed));
            }
        }
    }
    println!(
        "| input | polygons | output | out/in | build s | CPU s | peak heap MiB | peak RSS MiB | bytes/polygon |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let (mut times, mut cpus, mut peaks) = (Vec::new(), Vec::new(), Vec::new());
    for (name, polygons, closed) in inputs {
        let n = polygons.len();
        crate::memory::reset_peak();
        let base = crate::memory::in_use();
        let rss_reset = reset_peak_rss();
        let cpu0 = process_cpu_seconds();
        let t = build(
            polygons,
            closed,
            Method::Static,
            crate::build::DEFAULT_SEED,
            &mut Bar::quiet(),
        );
        let cpu = cpu0.zip(process_cpu_seconds()).map(|(a, b)| b - a);
        let peak =
            crate::memory::peak().map(|p| p.saturating_sub(base) as f64 / f64::from(1 << 20));
        let rss = peak_rss_mib().filter(|_| rss_reset);
        let bytes = crate::serialize::serialize(&t, &SerializeOptions::default())?;
        let s = &t.stats;
        let secs = s.build_ms / 1e3;
        times.push((n as f64, secs));
        if let Some(c) = cpu {
            cpus.push((n as f64, c));
        }
        if let Some(p) = peak {
            peaks.push((n as f64, p));
        }
        println!(
            "| {name} | {n} | {} | {:.2} | {secs:.2} | {} | {} | {} | {:.1} |",
            s.output_polygons,
            s.output_polygons as f64 / n.max(1) as f64,
            cpu.map_or_else(|| "-".to_string(), |c| format!("{c:.2}")),
            peak.map_or_else(|| "-".to_string(), |p| format!("{p:.1}")),
            rss.map_or_else(|| "-".to_string(), |r| format!("{r:.0}")),
            bytes.len() as f64 / s.output_polygons.max(1) as f64,
        );
    }
    let show = |e: Option<f64>| e.map_or_else(|| "-".to_string(), |e| format!("{e:.2}"));
    println!(
        "fitted growth: build time ~ n^{}, CPU time ~ n^{}, peak heap ~ n^{}",
        show(growth_exponent(&times)),
        show(growth_exponent(&cpus)),
        show(growth_exponent(&peaks))
    );
    Ok(())
}

/// `fpt bench-build`: static, dynamic and BSP side by side per model.
pub fn bench(a: &BenchBuildArgs) -> CliResult {
    if a.scaling {
        return bench_scaling(a);
    }
    if a.subdivide.is_some() {
        return Err(cli_err!("--subdivide needs --scaling"));
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `fpt build`'s defaults are the default file options, and every
    /// `--records` name writes the options it is the name of.
    #[test]
    fn cli_defaults_are_the_default_file_options() {
        let d = SerializeOptions::default();
        assert_eq!(
            parse_vertex_format(&default_vertex_format()).ok(),
            Some(d.vertex_format)
        );
        assert_eq!(with_records(d, &default_records()).ok(), Some(d));
        for (name, _) in RECORDS {
            let o = with_records(d, name).expect("a --records name");
            assert_eq!(records_name(&o), Some(name));
        }
        assert!(with_records(d, "nope").is_err());
    }
}
