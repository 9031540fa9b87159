//! `fpt mcu-bench TREE`: draws a tree over the standard orbit
//! ([`fpt_frames::orbit`]) on an emulated microcontroller and prints
//! one JSON object with its cost, its memory and whether every frame's
//! checksum equals the host's.
//!
//! ```text
//! fpt mcu-bench TREE [--cpu m4f|m0] [--size WxH] [--band ROWS]
//!                    [--precision NAME] [--frames N] [--clock MHZ]
//! ```
//!
//! It builds the firmware's `bench` binary (`firmware/src/bin/bench.rs`)
//! for the CPU's target with the tree and the settings handed to
//! `firmware/build.rs` in `FPT_BENCH_*` variables (`cargo build --release`
//! in `firmware/`, target directory `firmware/target/mcu-bench`; the
//! firmware directory can be moved with `FPT_FIRMWARE_DIR`), runs it under
//! QEMU with `-icount shift=0`, and draws the same frames on the host with
//! the same `no_std` code. The CPUs ([`Cpu`]):
//!
//! | `--cpu` | target | QEMU machine | flash | RAM | default `--band` | default `--clock` |
//! |---|---|---|---:|---:|---:|---:|
//! | `m4f` | `thumbv7em-none-eabihf` | `netduinoplus2` (STM32F405) | 1 MiB | 128 KiB | 0 (full frame) | 168 MHz |
//! | `m0` | `thumbv6m-none-eabi` | `microbit` (nRF51822) | 256 KiB | 16 KiB | 8 | 64 MHz (an STM32G0-class M0+; the nRF51 runs at 16) |
//!
//! Other defaults: `--size 240x240 --precision f32-libm --frames 100`;
//! `--memory`: what the frames need, or on the Cortex-M0, when its 16 KiB
//! cannot hold that, what a probe run of the firmware measured they leave
//! beside its statics, its stack peak and a 256 B margin ([`memory`]; the
//! JSON says which in `memory_from` and gives the probe's figures in
//! `memory_probe`).
//! `fps_at_clock` is `clock / instr_median` at one instruction per cycle
//! (an upper bound: loads, branches and multiplies can take more).
//!
//! Failures are one line `error: ...` and exit status 2: bad options, a
//! tree that does not validate, QEMU or the Rust target missing (the
//! message names the install command), a tree that does not fit the
//! CPU's flash or RAM (which, and by how much: statics from the linker; a
//! stack that outgrows the RAM the statics leave is detected by the
//! firmware — after every frame, or by the hard fault it causes — and
//! measured by relinking the same firmware with 1 MiB of RAM and running
//! it on QEMU's `mps2-an385`, a Cortex-M3 that runs the same Thumb-1
//! code), or checksums that differ (the JSON is printed first).

use std::path::{Path, PathBuf};

use clap::Args;
use fpt_frames::orbit::{
    band_rows, band_words, frame_crc, OrbitPrecision, PrecisionVisitor, MAX_VERTS,
};
use fpt_nostd::raster::Precision;
use fpt_nostd::reader::Tree;
use fpt_nostd::render::TreeRenderer;
use serde_json::json;

use super::{CliError, CliResult};
use crate::cli_err;

mod firmware;
mod memory;

use firmware::{build_firmware, check_tools, parse_run, run_qemu, MEASURE_RAM_KIB};
pub use firmware::{elf_sections, link_overflows, qemu_installed, target_installed};

/// Walk stack of the host's check (the firmware's is the tree's depth).
const HOST_DEPTH: usize = 256;

/// Arguments of `fpt mcu-bench`.
#[derive(Args, Debug)]
pub struct McuBenchArgs {
    /// Tree file.
    pub tree: PathBuf,
    /// The emulated CPU: m4f (Cortex-M4F, QEMU netduinoplus2) or m0
    /// (Cortex-M0, QEMU microbit).
    #[arg(long, default_value = "m4f", value_parser = ["m4f", "m0"])]
    pub cpu: String,
    /// Display size WxH.
    #[arg(long, default_value = "240x240")]
    pub size: String,
    /// Rows per band, 0 for a full framebuffer [default: 0 on m4f, 8 on m0].
    // Negative values get clap's "invalid value" message, not "unexpected
    // argument" (here and below).
    #[arg(long, allow_negative_numbers = true)]
    pub band: Option<u32>,
    /// Vertex arithmetic: f32-libm, fixed or int.
    #[arg(long, default_value = "f32-libm", value_parser = OrbitPrecision::NAMES)]
    pub precision: String,
    /// Frames of the orbit.
    #[arg(long, default_value_t = fpt_frames::orbit::DEFAULT_FRAMES,
          allow_negative_numbers = true,
          value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub frames: u32,
    /// Clock in MHz for fps_at_clock [default: 168 on m4f, 64 on m0].
    // Negative values reach the check that says what is wrong with them.
    #[arg(long, allow_negative_numbers = true)]
    pub clock: Option<f64>,
    /// Words of working memory (vertex cache, display list, facing memo;
    /// see docs/small-ram.md) [default: what a frame of the tree
    /// needs; on m0, when 16 KiB cannot hold that, what a probe run
    /// measured they leave beside the statics, the stack peak and a
    /// 256 B margin].
    #[arg(long, allow_negative_numbers = true)]
    pub memory: Option<usize>,
}

/// An emulated microcontroller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cpu {
    /// Cortex-M4F: STM32F405-class, QEMU `netduinoplus2`.
    M4f,
    /// Cortex-M0: nRF51822, QEMU `microbit`.
    M0,
}

impl Cpu {
    /// The `--cpu` name.
    pub fn name(self) -> &'static str {
        match self {
            Cpu::M4f => "m4f",
            Cpu::M0 => "m0",
        }
    }

    fn parse(s: &str) -> Option<Cpu> {
        [Cpu::M4f, Cpu::M0].into_iter().find(|c| c.name() == s)
    }

    /// The Rust target.
    pub fn target(self) -> &'static str {
        match self {
            Cpu::M4f => "thumbv7em-none-eabihf",
            Cpu::M0 => "thumbv6m-none-eabi",
        }
    }

    /// QEMU's `-machine` and `-cpu`.
    fn qemu(self) -> [&'static str; 4] {
        match self {
            Cpu::M4f => ["-machine", "netduinoplus2", "-cpu", "cortex-m4"],
            Cpu::M0 => ["-machine", "microbit", "-cpu", "cortex-m0"],
        }
    }

    /// Flash bytes (the firmware's memory layout).
    pub fn flash(self) -> u64 {
        match self {
            Cpu::M4f => 1024 * 1024,
            Cpu::M0 => 256 * 1024,
        }
    }

    /// RAM bytes.
    pub fn ram(self) -> u64 {
        match self {
            Cpu::M4f => 128 * 1024,
            Cpu::M0 => 16 * 1024,
        }
    }

    fn default_band(self) -> u32 {
        match self {
            Cpu::M4f => 0,
            // 16 KiB: a 16-row band (7.5 KiB) leaves the working memory a
            // tenth of what a frame of socket needs, an 8-row band
            // (3.75 KiB) three fifths, and the frame takes fewer walks.
            Cpu::M0 => 8,
        }
    }

    fn default_clock(self) -> f64 {
        match self {
            Cpu::M4f => 168.0,
            Cpu::M0 => 64.0,
        }
    }
}

/// `WxH` as two positive numbers.
pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), CliError> {
    let bad = || cli_err!("--size wants WxH (e.g. 240x240), got '{s}'");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 || w > 4096 || h > 4096 {
        return Err(cli_err!("--size {s}: each side must be 1 to 4096 pixels"));
    }
    Ok((w, h))
}

/// The settings of one run, checked.
#[derive(Clone, Debug)]
struct Bench {
    tree: PathBuf,
    cpu: Cpu,
    size: (u32, u32),
    band: u32,
    precision: OrbitPrecision,
    frames: u32,
    clock: f64,
    /// Words of working memory; `None`: chosen from the tree.
    memory: Option<usize>,
    /// The most working memory a frame used on the host (with all it
    /// could want).
    needed: usize,
    /// How `memory` was chosen: `--memory`, the frames' need, the
    /// estimate or measured ([`memory`]).
    memory_from: &'static str,
    /// The probe run of a measured memory: its words, statics and stack
    /// peak.
    probe: Option<(usize, u64, u64)>,
}

impl Bench {
    fn from_args(a: &McuBenchArgs) -> Result<Bench, CliError> {
        let cpu = Cpu::parse(&a.cpu).ok_or_else(|| cli_err!("unknown --cpu '{}'", a.cpu))?;
        let precision = OrbitPrecision::parse(&a.precision)
            .ok_or_else(|| cli_err!("unknown --precision '{}'", a.precision))?;
        let clock = a.clock.unwrap_or(cpu.default_clock());
        if !(clock.is_finite() && clock > 0.0) {
            return Err(cli_err!("--clock must be a positive number of MHz"));
        }
        Ok(Bench {
            tree: a.tree.clone(),
            cpu,
            size: parse_size(&a.size)?,
            band: a.band.unwrap_or(cpu.default_band()),
            precision,
            frames: a.frames,
            clock,
            memory: a.memory,
            needed: 0,
            memory_from: "--memory",
            probe: None,
        })
    }
}

/// The host's checksums of every frame (the visitor of
/// [`OrbitPrecision::visit`]).
struct HostCrcs<'t> {
    tree: &'t Tree<'t>,
    size: (u32, u32),
    band: u32,
    frames: u32,
}

impl PrecisionVisitor for HostCrcs<'_> {
    /// Every frame's checksum and the most working memory a frame used.
    type Output = Result<(Vec<u32>, usize), CliError>;
    fn visit<P: Precision>(self) -> Self::Output {
        let (w, h) = self.size;
        let mut r = TreeRenderer::<P, MAX_VERTS>::new(w, h)
            .ok_or_else(|| cli_err!("the renderer cannot draw {w}x{h}"))?;
        let mut buf = vec![0u16; band_words(w, h, self.band)];
        // The host draws with all the memory a frame needs (the picture
        // does not depend on it).
        let mut memory = vec![0u32; fpt_nostd::render::memory_words(self.tree)];
        let mut used = 0;
        let crcs = (0..self.frames)
            .map(|i| {
                frame_crc::<P, HOST_DEPTH, MAX_VERTS>(
                    &mut r,
                    self.tree,
                    (i, self.frames),
                    (&mut buf, &mut memory),
                    self.band,
                )
                .map(|(crc, stats)| {
                    used = used.max(stats.memory_used as usize);
                    crc
                })
                .map_err(|e| cli_err!("host frame {i}: {e}"))
            })
            .collect::<Result<Vec<u32>, CliError>>()?;
        Ok((crcs, used))
    }
}

/// The largest polygon's vertex capacity as the firmware's renderer has
/// it (`build.rs`: twice the largest polygon's vertices and 8).
fn max_vertices(tree: &Tree<'_>) -> usize {
    (0..tree.polygon_count())
        .filter_map(|i| tree.polygon(i))
        .map(|p| 2 * p.vertex_count() + 8)
        .max()
        .unwrap_or(0)
}

/// The probe run of [`memory::measured`]: the firmware built with
/// `b.memory` words and run over the whole orbit; its statics and stack
/// peak, or `None` when it did not run through (the reported run then
/// says why).
fn probe(b: &Bench, name: &str) -> Result<Option<(u64, u64)>, CliError> {
    let elf = build_firmware(b, name, false)?;
    let run = run_qemu(b.cpu.qemu(), &elf, b.frames);
    let _ = std::fs::remove_file(&elf);
    let Ok((true, out)) = run else {
        return Ok(None);
    };
    let r = parse_run(&out);
    Ok(match (r.error, r.static_ram, r.stack_peak) {
        (None, Some(s), Some(p)) => Some((s, p)),
        _ => None,
    })
}

/// Runs `fpt mcu-bench`.
pub fn run(a: &McuBenchArgs) -> CliResult {
    let mut b = Bench::from_args(a)?;
    let bytes =
        std::fs::read(&b.tree).map_err(|e| cli_err!("reading {}: {e}", b.tree.display()))?;
    let tree = Tree::from_bytes(&bytes).map_err(|e| cli_err!("{}: {e}", b.tree.display()))?;

    let name = b
        .tree
        .file_stem()
        .map_or("the tree".into(), |s| s.to_string_lossy().into_owned());
    if tree.max_depth() as usize > HOST_DEPTH {
        return Err(cli_err!(
            "{name} is {} deep; the host check walks at most {HOST_DEPTH}",
            tree.max_depth()
        ));
    }
    let (host, used) = b.precision.visit(HostCrcs {
        tree: &tree,
        size: b.size,
        band: b.band,
        frames: b.frames,
    })?;
    b.needed = used;
    check_tools(b.cpu)?;
    if b.memory.is_none() {
        let guess = memory::estimate(&b, max_vertices(&tree), used);
        b.memory = Some(guess);
        b.memory_from = "the frames' need";
        if guess < used {
            b.memory_from = "estimate";
            if let Some(m) = probe(&b, &name)? {
                if let Some(words) = memory::measured(b.cpu.ram(), guess, m, used) {
                    b.memory = Some(words);
                    b.memory_from = "measured";
                    b.probe = Some((guess, m.0, m.1));
                }
            }
        }
    }
    let elf = build_firmware(&b, &name, false)?;
    let result = measure(&b, &name, &elf, &host, &tree);
    let _ = std::fs::remove_file(&elf);
    result
}

/// The error for a Cortex-M0 stack that overflowed, measured: the same
/// firmware linked with more RAM, run on `mps2-an385`. It says by how much
/// the statics and the stack exceed the RAM, or why that could not be
/// measured.
fn stack_overflow_error(b: &Bench, name: &str, why: &str) -> CliError {
    let ram = b.cpu.ram();
    let head = format!(
        "{name} does not fit the {}'s RAM ({} KiB)",
        b.cpu.name(),
        ram / 1024
    );
    let measured = (|| {
        if b.cpu != Cpu::M0 {
            return Err(cli_err!("only the m0's stack is measured apart"));
        }
        let elf = build_firmware(b, name, true)?;
        let run = run_qemu(
            ["-machine", "mps2-an385", "-cpu", "cortex-m3"],
            &elf,
            b.frames,
        );
        let _ = std::fs::remove_file(&elf);
        let (ok, out) = run?;
        let r = parse_run(&out);
        match (ok, r.static_ram, r.stack_peak) {
            (true, Some(s), Some(p)) => Ok((s, p)),
            _ => Err(cli_err!(
                "{}",
                r.error.as_deref().unwrap_or("no measurement")
            )),
        }
    })();
    match measured {
        Ok((statics, peak)) => cli_err!(
            "{head}: static {statics} B + stack {peak} B = {} B, over by {} bytes \
             ({why}; stack measured with {MEASURE_RAM_KIB} KiB of RAM on QEMU mps2-an385); \
             try a smaller --band or --size",
            statics + peak,
            (statics + peak).saturating_sub(ram)
        ),
        Err(CliError(e)) => cli_err!(
            "{head}: the stack outgrew the RAM the statics leave ({why}), by an amount \
             that could not be measured ({e}); try a smaller --band or --size"
        ),
    }
}

/// Runs the built firmware, checks it, prints the JSON.
fn measure(b: &Bench, name: &str, elf: &Path, host: &[u32], tree: &Tree<'_>) -> CliResult {
    let sections = std::fs::read(elf)
        .ok()
        .and_then(|bytes| elf_sections(&bytes))
        .ok_or_else(|| cli_err!("cannot read the sections of {}", elf.display()))?;
    let size_of = |n: &str| {
        sections
            .iter()
            .filter(|(s, _)| s == n)
            .map(|(_, v)| v)
            .sum::<u64>()
    };
    let (text, rodata) = (size_of(".text"), size_of(".rodata"));
    let flash_used = size_of(".vector_table") + text + rodata + size_of(".data");
    let (ok, out) = match run_qemu(b.cpu.qemu(), elf, b.frames) {
        Ok(r) => r,
        // A hang on the 16 KiB part is most likely a stack overflow.
        Err(CliError(e)) if b.cpu == Cpu::M0 => {
            return Err(stack_overflow_error(b, name, &e));
        }
        Err(e) => return Err(e),
    };
    let run = parse_run(&out);
    let ram = b.cpu.ram();
    if let Some(e) = run
        .error
        .as_deref()
        .filter(|e| e.contains("stack overflow") || e.contains("hard fault"))
    {
        return Err(stack_overflow_error(b, name, e));
    }
    if !ok || run.error.is_some() {
        return Err(cli_err!(
            "the firmware failed: {}",
            run.error.as_deref().unwrap_or("no error message")
        ));
    }
    let (Some(ram_static), Some(stack_peak)) = (run.static_ram, run.stack_peak) else {
        return Err(cli_err!(
            "the firmware's output has no static_ram/stack_peak"
        ));
    };
    let crc_match = run.frames.len() == host.len()
        && run
            .frames
            .iter()
            .zip(host)
            .enumerate()
            .all(|(i, ((l, _), h))| l.frame == i as u32 && l.crc == *h);
    let mut instr: Vec<u64> = run.frames.iter().map(|(_, n)| *n).collect();
    instr.sort_unstable();
    if instr.is_empty() {
        return Err(cli_err!("the firmware printed no frames"));
    }
    let median = if instr.len() % 2 == 1 {
        instr[instr.len() / 2] as f64
    } else {
        (instr[instr.len() / 2 - 1] + instr[instr.len() / 2]) as f64 / 2.0
    };
    let fps = b.clock * 1e6 / median;
    let report = json!({
        "tree": name,
        "polygons": tree.polygon_count(),
        "walk_depth": tree.max_depth(),
        "cpu": b.cpu.name(),
        "target": b.cpu.target(),
        "width": b.size.0,
        "height": b.size.1,
        "band": b.band,
        "band_rows": band_rows(b.band, b.size.1),
        "precision": b.precision.name(),
        "frames": b.frames,
        "memory_words": b.memory.unwrap_or(0),
        "memory_needed": b.needed,
        "memory_from": b.memory_from,
        "memory_probe": b.probe.map(|(words, statics, stack)| json!({
            "memory_words": words,
            "ram_static": statics,
            "stack_peak": stack,
            "margin": memory::MARGIN,
        })),
        "instr_median": median,
        "instr_min": instr[0],
        "instr_max": instr[instr.len() - 1],
        "ram_static": ram_static,
        "stack_peak": stack_peak,
        "ram_total": ram_static + stack_peak,
        "ram_size": ram,
        "text": text,
        "rodata": rodata,
        "flash_used": flash_used,
        "flash_size": b.cpu.flash(),
        "clock_mhz": b.clock,
        "fps_at_clock": (fps * 100.0).round() / 100.0,
        "crc_match": crc_match,
    });
    println!("{}", serde_json::to_string_pretty(&report)?);
    if !crc_match {
        return Err(cli_err!(
            "the firmware's checksums differ from the host's ({} frames printed, {} expected)",
            run.frames.len(),
            host.len()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_refuse() {
        assert_eq!(parse_size("240x240").unwrap(), (240, 240));
        assert_eq!(parse_size("320X200").unwrap(), (320, 200));
        for bad in ["240", "0x10", "ax1", "10x", "5000x10"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }
}
