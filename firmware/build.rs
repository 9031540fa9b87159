//! The memory layout of the target, and the benchmark binary's
//! configuration.
//!
//! * Layout: puts the target's `memory.x` where cortex-m-rt's `link.x`
//!   finds it — the top-level `../memory.x` (STM32F405-class, QEMU
//!   `netduinoplus2`) for the Cortex-M4 (`thumbv7em-none-eabihf`), or
//!   `memory-m0.x` (nRF51822, QEMU `microbit`: 256 KiB flash, 16 KiB RAM)
//!   for the Cortex-M0 (`thumbv6m-none-eabi`, which also gets
//!   `--cfg fpt_armv6m`) — and links with `link.x` (here rather than in
//!   `.cargo/config.toml`'s `rustflags`, which a `RUSTFLAGS` variable in
//!   the environment would replace).
//!   `FPT_BENCH_RAM_KIB` replaces the RAM's length (for `fpt mcu-bench`'s
//!   measurement of a stack that does not fit), `FPT_BENCH_FLASH_KIB` the
//!   flash's (to see by how much a build outgrows it).
//! * `src/bin/accuracy.rs`'s `band` build (the accuracy study's Cortex-M0
//!   column) takes its tree, band and memory from the same variables, and
//!   its configurations from `FPT_ACCURACY_CONFIGS`.
//! * `src/bin/bench.rs` (`fpt mcu-bench`): writes `bench_config.rs` into
//!   `OUT_DIR` from the environment (see [`BenchConfig`]).
use std::{env, fs, path::PathBuf};

use fpt_frames::accuracy::{arithmetic, CONFIGS};
use fpt_frames::orbit::{band_words, OrbitPrecision};
use fpt_nostd::reader::Tree;

/// The benchmark's configuration, from `FPT_BENCH_*` variables.
struct BenchConfig {
    /// `FPT_BENCH_TREE`: the tree file (default `trees/vise.fpt`).
    tree: PathBuf,
    /// `FPT_BENCH_WIDTH`, `FPT_BENCH_HEIGHT` (default 240 × 240).
    size: (u32, u32),
    /// `FPT_BENCH_BAND`: rows per band, 0 for a full frame (default 16).
    band: u32,
    /// `FPT_BENCH_PRECISION`: an `OrbitPrecision` name (default f32-libm).
    precision: OrbitPrecision,
    /// `FPT_BENCH_FRAMES`: frames of the orbit (default 8).
    frames: u32,
    /// `FPT_BENCH_MEMORY`: words of working memory (vertex cache and
    /// display list; default 0).
    memory: usize,
    /// `FPT_ACCURACY_CONFIGS`: the accuracy configurations the `accuracy`
    /// binary's `band` build compiles and draws, comma-separated (default:
    /// all of `fpt_frames::accuracy::CONFIGS`; 256 KiB of flash holds a
    /// `bench_city` tree and the code of a few).
    accuracy: Vec<String>,
}

const VARS: [&str; 10] = [
    "FPT_BENCH_RAM_KIB",
    "FPT_BENCH_FLASH_KIB",
    "FPT_BENCH_TREE",
    "FPT_BENCH_WIDTH",
    "FPT_BENCH_HEIGHT",
    "FPT_BENCH_BAND",
    "FPT_BENCH_PRECISION",
    "FPT_BENCH_FRAMES",
    "FPT_BENCH_MEMORY",
    "FPT_ACCURACY_CONFIGS",
];

fn number(var: &str, default: u32) -> u32 {
    match env::var(var) {
        Ok(v) => v
            .parse()
            .unwrap_or_else(|_| panic!("{var}={v} is not a number")),
        Err(_) => default,
    }
}

impl BenchConfig {
    fn from_env() -> BenchConfig {
        let tree = env::var_os("FPT_BENCH_TREE")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from("trees/vise.fpt"));
        let precision = env::var("FPT_BENCH_PRECISION").unwrap_or_else(|_| "f32-libm".into());
        let precision = OrbitPrecision::parse(&precision)
            .unwrap_or_else(|| panic!("FPT_BENCH_PRECISION={precision} is not a precision"));
        let size = (
            number("FPT_BENCH_WIDTH", 240),
            number("FPT_BENCH_HEIGHT", 240),
        );
        assert!(size.0 > 0 && size.1 > 0, "empty display");
        let accuracy: Vec<String> = match env::var("FPT_ACCURACY_CONFIGS") {
            Ok(v) => v.split(',').map(|c| c.trim().to_string()).collect(),
            Err(_) => CONFIGS.iter().map(|c| c.to_string()).collect(),
        };
        for c in &accuracy {
            assert!(
                arithmetic(c).is_some(),
                "FPT_ACCURACY_CONFIGS: {c} is not an accuracy configuration"
            );
        }
        BenchConfig {
            tree: fs::canonicalize(&tree)
                .unwrap_or_else(|e| panic!("FPT_BENCH_TREE={}: {e}", tree.display())),
            size,
            band: number("FPT_BENCH_BAND", 16),
            precision,
            frames: number("FPT_BENCH_FRAMES", 8).max(1),
            memory: number("FPT_BENCH_MEMORY", 0) as usize,
            accuracy,
        }
    }

    /// The Rust source of `bench_config.rs`.
    fn source(&self) -> String {
        let bytes =
            fs::read(&self.tree).unwrap_or_else(|e| panic!("reading {}: {e}", self.tree.display()));
        let tree =
            Tree::from_bytes(&bytes).unwrap_or_else(|e| panic!("{}: {e}", self.tree.display()));
        let name = self
            .tree
            .file_stem()
            .map_or("tree".into(), |s| s.to_string_lossy().into_owned());
        let (w, h) = self.size;
        format!(
            "/// The tree's file name without extension.\n\
             pub const NAME: &str = {name:?};\n\
             /// The tree file ({path}).\n\
             pub static TREE: &[u8] = include_bytes!({path:?});\n\
             /// Display width.\n\
             pub const WIDTH: u32 = {w};\n\
             /// Display height.\n\
             pub const HEIGHT: u32 = {h};\n\
             /// Rows per band (0: full frame).\n\
             pub const BAND: u32 = {band};\n\
             /// `u16` words of the band buffer.\n\
             pub const BUF_WORDS: usize = {words};\n\
             /// Frames of the orbit.\n\
             pub const FRAMES: u32 = {frames};\n\
             /// Walk stack frames: the tree's depth.\n\
             pub const WALK_DEPTH: usize = {depth};\n\
             /// The precision's name.\n\
             pub const PRECISION: &str = {pname:?};\n\
             /// Words of working memory (vertex cache, display list).\n\
             pub const MEMORY_WORDS: usize = {memory};\n\
             /// Vertex capacity of the scratch: what the tree's header\n\
             /// says it needs.\n\
             pub const VERTS: usize = {verts};\n\
             /// The vertex arithmetic.\n\
             pub type BenchPrecision = {ptype};\n\
             /// The accuracy configurations of the `band` build.\n\
             pub const ACCURACY_CONFIGS: &[&str] = &{accuracy:?};\n",
            path = self.tree.display().to_string(),
            band = self.band,
            words = band_words(w, h, self.band),
            frames = self.frames,
            depth = tree.max_depth().max(1),
            pname = self.precision.name(),
            memory = self.memory,
            verts = tree.capacities().vertices,
            ptype = self.precision.type_path(),
            accuracy = self.accuracy,
        )
    }
}

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    let target = env::var("TARGET").expect("TARGET");
    println!("cargo::rustc-check-cfg=cfg(fpt_armv6m)");
    let memory = if target.starts_with("thumbv6m") {
        println!("cargo::rustc-cfg=fpt_armv6m");
        "memory-m0.x"
    } else {
        "../memory.x"
    };
    let mut layout = fs::read_to_string(memory).unwrap_or_else(|e| panic!("reading {memory}: {e}"));
    // `fpt mcu-bench` measures a Cortex-M0 stack that outgrows the 16 KiB
    // by relinking with more RAM and running on QEMU's mps2-an385.
    // `FPT_BENCH_FLASH_KIB`: how far past the 256 KiB a build reaches.
    for (region, var) in [
        ("RAM", "FPT_BENCH_RAM_KIB"),
        ("FLASH", "FPT_BENCH_FLASH_KIB"),
    ] {
        let Ok(kib) = env::var(var) else {
            continue;
        };
        let line = layout
            .lines()
            .find(|l| l.trim_start().starts_with(region))
            .unwrap_or_else(|| panic!("a {region} line in the layout"))
            .to_string();
        let (head, _) = line.split_once("LENGTH").expect("LENGTH");
        layout = layout.replace(&line, &format!("{head}LENGTH = {kib}K"));
    }
    fs::write(out.join("memory.x"), layout).expect("writing memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg=-Tlink.x");
    println!("cargo:rerun-if-changed=../memory.x");
    println!("cargo:rerun-if-changed=memory-m0.x");
    println!("cargo:rerun-if-changed=build.rs");

    let bench = BenchConfig::from_env();
    fs::write(out.join("bench_config.rs"), bench.source()).expect("writing bench_config.rs");
    for var in VARS {
        println!("cargo:rerun-if-env-changed={var}");
    }
    println!("cargo:rerun-if-changed={}", bench.tree.display());
}
