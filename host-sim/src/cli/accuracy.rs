//! `fpt bench-accuracy --out DIR`: what accuracy costs in time.
//!
//! ```text
//! fpt bench-accuracy --out DIR [--size WxH] [--views N] [--reps N] [--no-models] [--mcu FILE] [--m0 FILE]
//! ```
//!
//! Renders the project's scenes (vise, house, bench city) and the shared
//! models (`../shared/models`, skipped when absent) from `--views` fixed
//! seeded orbit views with every configuration of [`CONFIGS`], compares
//! each picture's source ids with the exact float64 reference and writes
//! * `DIR/accuracy.csv`: header
//!   `config,wrong_pixel_frac,wrong_face_frac,max_vertex_err_px,host_rel_time,mcu_instr,m0_instr`,
//!   one row per configuration (definitions in [`eval`]);
//!   `host_rel_time` is the host time per frame (per frame the fastest of
//!   `--reps` interleaved rounds) divided by that of the default configuration
//!   (`fixed`), all measured in this one process; `mcu_instr` the mean
//!   Cortex-M4 instructions per frame of the benchmark scene over the
//!   firmware's views, read from `--mcu FILE`: the output of the
//!   firmware's `accuracy` binary (`cd firmware && cargo run --release
//!   --bin accuracy > FILE`, see [`fpt_frames::accuracy`]), whose
//!   checksums the firmware has already checked against the host's; empty
//!   without `--mcu`; `m0_instr` the same for the Cortex-M0's code
//!   (Thumb-1, no FPU, no divide) with 16 KiB of RAM, from `--m0 FILE`:
//!   the same frames drawn in 8-row bands on QEMU's `microbit`, one build
//!   per tree encoding and arithmetic (`FPT_ACCURACY_M0_OUT=FILE cargo
//!   test -p fpt-tests --test all m0_accuracy_matches_host`, see
//!   docs/accuracy.md); empty without `--m0`;
//! * `DIR/accuracy.png`: `wrong_face_frac` against time, points labelled
//!   with the configuration: `mcu_instr` relative to the default's with
//!   `--mcu` (deterministic), else `host_rel_time`.
//!
//! The `vertex-*` rows differ only in the tree's vertex storage: the
//! renderer decodes every stored vertex to `f32` and transforms it like an
//! `f32` vertex (the `q16`/`q32` integer transform of
//! [`fpt_nostd::raster::transform::VertexPath::transform_q`] is not used by
//! the tree renderer), so they measure the storage quantization only.
//!
//! [`rows_for`] computes rows for any cases and views; the integration test
//! `host-sim/tests/all/accuracy_cli.rs` checks them against `fpt render` output.

pub mod eval;
mod plot;

pub use eval::{
    camera_spec, compare_ids, draw, orbit_rows, reference_camera, reference_frame, view_counts,
    views, Case, Config, Counts, ViewSpec, CONFIGS, DEFAULT_CONFIG, FOV_DEG,
};
pub use plot::{plot, PlotPoint};

use super::render::parse_size;
use super::{CliError, CliResult};
use crate::cli_err;
use crate::output::write_atomic;
use clap::Args;
use std::fmt::Write as _;
use std::path::PathBuf;

/// The CSV header, exactly.
pub const CSV_HEADER: &str =
    "config,wrong_pixel_frac,wrong_face_frac,max_vertex_err_px,host_rel_time,mcu_instr,m0_instr";

/// Arguments of `fpt bench-accuracy`.
#[derive(Args, Debug)]
pub struct AccuracyArgs {
    /// Output folder (created if missing) for accuracy.csv and accuracy.png.
    #[arg(long)]
    pub out: PathBuf,
    /// Image size WxH in pixels.
    #[arg(long, default_value = "160x120")]
    pub size: String,
    /// Orbit views per model (fixed seed).
    #[arg(long, default_value_t = 8)]
    pub views: usize,
    /// Timing rounds (per frame the fastest is kept).
    #[arg(long, default_value_t = 40)]
    pub reps: usize,
    /// Leave out the shared models (scenes only).
    #[arg(long = "no-models")]
    pub no_models: bool,
    /// The firmware's accuracy output (`cargo run --release --bin
    /// accuracy` in firmware/), for the mcu_instr column.
    #[arg(long)]
    pub mcu: Option<PathBuf>,
    /// The Cortex-M0's lines for the same frames, in 8-row bands on QEMU
    /// microbit (`FPT_ACCURACY_M0_OUT=FILE cargo test -p fpt-tests --test
    /// all m0_accuracy_matches_host`), for the m0_instr column.
    #[arg(long)]
    pub m0: Option<PathBuf>,
}

/// One CSV row.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Configuration name.
    pub config: String,
    /// The error counts over every case and view.
    pub counts: Counts,
    /// Host time per frame relative to the default configuration.
    pub host_rel_time: Option<f64>,
    /// Cortex-M4 instructions per frame (mean over the firmware's views).
    pub mcu_instr: Option<u64>,
    /// Cortex-M0 instructions per frame (the same frames).
    pub m0_instr: Option<u64>,
}

impl Row {
    /// The row as a CSV line (no newline).
    pub fn csv(&self) -> String {
        let opt = |v: Option<String>| v.unwrap_or_default();
        format!(
            "{},{:.8},{:.8},{:.4},{},{},{}",
            self.config,
            self.counts.wrong_pixel_frac(),
            self.counts.wrong_face_frac(),
            self.counts.max_vertex_err_px,
            opt(self.host_rel_time.map(|t| format!("{t:.3}"))),
            opt(self.mcu_instr.map(|n| n.to_string())),
            opt(self.m0_instr.map(|n| n.to_string()))
        )
    }
}

/// The project's scenes, then the shared models when `models` is true and
/// the folder exists.
pub fn default_cases(models: bool) -> Result<Vec<Case>, CliError> {
    let mut cases = Vec::new();
    for s in [
        crate::scenes::vise(),
        crate::scenes::house(),
        crate::scenes::bench_city(),
    ] {
        cases.push(Case::new(&s.name, s.polygons, s.closed)?);
    }
    if models {
        if let Some(dir) = super::build::shared_models_dir() {
            let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
                .map_err(|e| cli_err!("{}: {e}", dir.display()))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    p.extension()
                        .and_then(|e| crate::mesh::MeshFormat::from_extension(&e.to_string_lossy()))
                        .is_some()
                })
                .collect();
            files.sort();
            for f in files {
                let m = crate::mesh::load(&f).map_err(|e| cli_err!("{}: {e}", f.display()))?;
                let name = f
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                cases.push(Case::new(&name, m.polygons, m.closed)?);
            }
        }
    }
    Ok(cases)
}

/// The error counts of every configuration of `configs` over `cases` and
/// `views` at `w × h` (no timing: `host_rel_time` and `mcu_instr` empty).
/// The reference picture of each view is computed once for all rows.
pub fn rows_for(
    cases: &[Case],
    configs: &[Config],
    views: &[ViewSpec],
    w: u32,
    h: u32,
) -> Result<Vec<Row>, CliError> {
    let mut rows: Vec<Row> = configs
        .iter()
        .map(|c| Row {
            config: c.name.to_string(),
            counts: Counts::default(),
            host_rel_time: None,
            mcu_instr: None,
            m0_instr: None,
        })
        .collect();
    for case in cases {
        let f32_tree = case.tree_bytes(fpt_nostd::format::VertexFormat::F32)?;
        let tree = fpt_nostd::reader::Tree::from_bytes(f32_tree)
            .map_err(|e| cli_err!("{}: {e}", case.name))?;
        for &v in views {
            let cam = reference_camera(&orbit_rows(&tree, v, w, h))?;
            let reference = reference_frame(case, &cam, w, h);
            for (config, row) in configs.iter().zip(rows.iter_mut()) {
                let (c, _) = view_counts(case, config, v, &reference, &cam)?;
                row.counts.add(&c);
            }
        }
    }
    Ok(rows)
}

/// The mean `instr` per configuration of the firmware's accuracy output
/// `text` (lines `accuracy config=NAME view=K crc=XXXXXXXX instr=N`).
/// Every configuration of [`CONFIGS`] must appear, with the same views.
pub fn mcu_means(text: &str) -> Result<Vec<(String, u64)>, CliError> {
    let mut out = Vec::new();
    for c in &CONFIGS {
        let costs: Vec<u64> = text
            .lines()
            .filter(|l| {
                fpt_frames::accuracy::AccuracyLine::parse(l).is_some_and(|p| p.config == c.name)
            })
            .map(|l| {
                fpt_frames::accuracy::AccuracyLine::instr(l)
                    .ok_or_else(|| cli_err!("--mcu: no instr= in '{l}'"))
            })
            .collect::<Result<_, _>>()?;
        if costs.len() != fpt_frames::VIEWS.len() {
            return Err(cli_err!(
                "--mcu: {} lines for {}, expected one per view ({})",
                costs.len(),
                c.name,
                fpt_frames::VIEWS.len()
            ));
        }
        let n = costs.len() as u64;
        out.push((c.name.to_string(), (costs.iter().sum::<u64>() + n / 2) / n));
    }
    Ok(out)
}

/// `fpt bench-accuracy`.
pub fn run(a: &AccuracyArgs) -> CliResult {
    let (w, h) = parse_size(&a.size)?;
    if a.views == 0 {
        return Err(cli_err!("--views must be at least 1"));
    }
    let read = |p: &Option<PathBuf>| -> Result<Option<Vec<(String, u64)>>, CliError> {
        let Some(path) = p else {
            return Ok(None);
        };
        let text =
            std::fs::read_to_string(path).map_err(|e| cli_err!("{}: {e}", path.display()))?;
        mcu_means(&text)
            .map(Some)
            .map_err(|CliError(e)| cli_err!("{}: {e}", path.display()))
    };
    let mcu = read(&a.mcu)?;
    let m0 = read(&a.m0)?;
    std::fs::create_dir_all(&a.out).map_err(|e| cli_err!("{}: {e}", a.out.display()))?;
    let cases = default_cases(!a.no_models)?;
    let vs = views(a.views);
    let mut rows = rows_for(&cases, &CONFIGS, &vs, w, h)?;
    let secs = eval::host_seconds(&cases, &CONFIGS, &vs, w, h, a.reps)?;
    let base = CONFIGS
        .iter()
        .position(|c| c.name == DEFAULT_CONFIG)
        .and_then(|i| secs.get(i).copied())
        .ok_or_else(|| cli_err!("no default configuration"))?;
    for (row, s) in rows.iter_mut().zip(&secs) {
        row.host_rel_time = Some(s / base);
        let mean = |m: &Option<Vec<(String, u64)>>| {
            m.iter()
                .flatten()
                .find(|(n, _)| *n == row.config)
                .map(|m| m.1)
        };
        row.mcu_instr = mean(&mcu);
        row.m0_instr = mean(&m0);
    }
    let mut csv = String::new();
    let _ = writeln!(csv, "{CSV_HEADER}");
    for r in &rows {
        let _ = writeln!(csv, "{}", r.csv());
    }
    let csv_path = a.out.join("accuracy.csv");
    write_atomic(&csv_path, csv.as_bytes()).map_err(|e| cli_err!("{}: {e}", csv_path.display()))?;
    // Time on the plot: the Cortex-M4F's instructions when given
    // (deterministic), else the host's wall time (noisy on a loaded
    // machine), both relative to the default configuration.
    let mcu_base = rows
        .iter()
        .find(|r| r.config == DEFAULT_CONFIG)
        .and_then(|r| r.mcu_instr);
    let x_of = |r: &Row| match mcu_base {
        Some(b) => r.mcu_instr.map_or(f64::NAN, |n| n as f64 / b as f64),
        None => r.host_rel_time.unwrap_or(f64::NAN),
    };
    let x_title = match mcu_base {
        Some(_) => {
            "Cortex-M4F instructions per frame / default (fixed-subpx-4), bench_city 240x240"
        }
        None => "host time per frame / default (fixed-subpx-4)",
    };
    let points: Vec<PlotPoint> = rows
        .iter()
        .map(|r| PlotPoint {
            label: r.config.clone(),
            x: x_of(r),
            y: r.counts.wrong_face_frac(),
        })
        .collect();
    let png = a.out.join("accuracy.png");
    plot(
        &points,
        &format!(
            "Accuracy against time: {} models x {} views, {w}x{h}",
            cases.len(),
            vs.len()
        ),
        x_title,
        "pixels showing another face than the f64 reference (wrong_face_frac, %)",
        &png,
    )?;
    print!("{csv}");
    println!(
        "{}: {} cases x {} views at {w}x{h}, base {:.3} ms/frame; wrote {} and {}",
        a.out.display(),
        cases.len(),
        vs.len(),
        base * 1e3,
        csv_path.display(),
        png.display()
    );
    Ok(())
}

#[cfg(test)]
mod tests;
