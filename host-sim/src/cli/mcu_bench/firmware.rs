//! Building and running the benchmark firmware for `fpt mcu-bench`: the
//! tools it needs, the `cargo build` of `firmware/` with the `FPT_BENCH_*`
//! settings, the QEMU run, and reading what came back (the linker's
//! overflow messages, the ELF's section sizes, the lines the firmware
//! printed).
//!
//! Everything here talks to processes and files outside the host
//! simulator; what is measured and how it is checked against the host's
//! frames stays in the parent module.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use fpt_frames::orbit::OrbitLine;

use super::{Bench, Cpu};
use crate::cli::{CliError, CliResult};
use crate::cli_err;

/// Longest a firmware build may take.
const BUILD_TIMEOUT: Duration = Duration::from_secs(1800);
/// Longest a QEMU run may take.
const RUN_TIMEOUT: Duration = Duration::from_secs(3600);

/// Why the firmware cannot be built or run here, as an error naming the
/// install command.
pub(super) fn check_tools(cpu: Cpu) -> CliResult {
    if !qemu_installed() {
        return Err(cli_err!(
            "qemu-system-arm is not installed (install it with: sudo apt-get install qemu-system-arm)"
        ));
    }
    if !target_installed(cpu.target()) {
        return Err(cli_err!(
            "the Rust target {t} is not installed (install it with: rustup target add {t})",
            t = cpu.target()
        ));
    }
    Ok(())
}

/// Whether `qemu-system-arm` runs.
pub fn qemu_installed() -> bool {
    let qemu = Command::new("qemu-system-arm")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
    qemu.is_ok_and(|s| s.success())
}

/// Whether `target`'s core library is installed.
pub fn target_installed(target: &str) -> bool {
    let libdir = Command::new("rustc")
        .args(["--print", "target-libdir", "--target", target])
        .output();
    libdir.is_ok_and(|o| {
        let dir = String::from_utf8_lossy(&o.stdout).trim().to_string();
        o.status.success()
            && std::fs::read_dir(&dir).is_ok_and(|mut d| {
                d.any(|e| e.is_ok_and(|e| e.file_name().to_string_lossy().starts_with("libcore")))
            })
    })
}

/// The firmware's directory: `FPT_FIRMWARE_DIR`, or the repository's.
///
/// Made absolute: the firmware build runs in this directory with
/// `CARGO_TARGET_DIR` below it, and cargo resolves a relative target
/// directory from its own working directory, so `FPT_FIRMWARE_DIR=firmware`
/// built into `firmware/firmware/target` while the ELF was copied from
/// `firmware/target`: a stale one when that existed (measured without a
/// word of warning).
fn firmware_dir() -> PathBuf {
    firmware_dir_from(std::env::var_os("FPT_FIRMWARE_DIR"))
}

/// [`firmware_dir`] for the variable's value `var`.
fn firmware_dir_from(var: Option<std::ffi::OsString>) -> PathBuf {
    let dir = var
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../firmware"));
    std::path::absolute(&dir).unwrap_or(dir)
}

/// Runs `cmd` to completion within `limit`: exit success, stdout, stderr.
fn run_captured(
    mut cmd: Command,
    limit: Duration,
    what: &str,
) -> Result<(bool, String, String), CliError> {
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| cli_err!("starting {what}: {e}"))?;
    let reader = |s: Option<Box<dyn Read + Send>>| {
        s.map(|mut s| {
            std::thread::spawn(move || {
                let mut text = String::new();
                let _ = s.read_to_string(&mut text);
                text
            })
        })
    };
    let out = reader(child.stdout.take().map(|s| Box::new(s) as _));
    let err = reader(child.stderr.take().map(|s| Box::new(s) as _));
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait()? {
            break s;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(cli_err!("{what} did not finish in {} s", limit.as_secs()));
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let join = |h: Option<std::thread::JoinHandle<String>>| {
        h.and_then(|h| h.join().ok()).unwrap_or_default()
    };
    Ok((status.success(), join(out), join(err)))
}

/// The largest overflow per memory region in a linker's messages
/// (`... region 'FLASH' ... overflowed by N bytes`).
pub fn link_overflows(stderr: &str) -> Vec<(String, u64)> {
    let mut out: Vec<(String, u64)> = Vec::new();
    for line in stderr.lines().filter(|l| l.contains("overflowed by")) {
        let region = line
            .split("region '")
            .nth(1)
            .and_then(|r| r.split('\'').next())
            .or_else(|| {
                line.split("region `")
                    .nth(1)
                    .and_then(|r| r.split('\'').next())
            });
        let bytes = line
            .split("overflowed by ")
            .nth(1)
            .and_then(|r| r.split_whitespace().next())
            .and_then(|n| n.parse::<u64>().ok());
        if let (Some(region), Some(bytes)) = (region, bytes) {
            match out.iter_mut().find(|(r, _)| r == region) {
                Some((_, b)) => *b = (*b).max(bytes),
                None => out.push((region.to_string(), bytes)),
            }
        }
    }
    out
}

/// RAM of the layout that measures a Cortex-M0 stack too big for the
/// nRF51 (run on QEMU's `mps2-an385`, whose Cortex-M3 runs the same
/// Thumb-1 code with 4 MiB of RAM at the same address).
pub(super) const MEASURE_RAM_KIB: u32 = 1024;

/// The firmware features a tree needs, and only those (the default
/// features are off: the benchmark binary needs neither `full` nor
/// `band`, and what they turn on for the frame set's trees would cost the
/// walk of a tree that does not need it): `plane-table` for a tree with a
/// shared plane table of `f32` entries, `compact-planes` for one of
/// compact entries, `large-trees` for one without small walk records
/// (each feature costs every walk).
fn tree_features(tree: &std::path::Path) -> Vec<&'static str> {
    let bytes = std::fs::read(tree).unwrap_or_default();
    let mut args = vec!["--no-default-features"];
    let Ok(t) = fpt_nostd::reader::Tree::from_bytes(&bytes) else {
        return args;
    };
    let features = [
        (
            t.has_plane_table() && !t.has_compact_planes(),
            "plane-table",
        ),
        (t.has_compact_planes(), "compact-planes"),
        (!t.has_small_records(), "large-trees"),
    ];
    let wanted: Vec<&str> = features.iter().filter(|f| f.0).map(|f| f.1).collect();
    match wanted.as_slice() {
        [] => {}
        [one] => args.extend(["--features", one]),
        ["plane-table", _] => args.extend(["--features", "plane-table large-trees"]),
        _ => args.extend(["--features", "compact-planes large-trees"]),
    }
    args
}

/// Builds the benchmark firmware (with `MEASURE_RAM_KIB` of RAM if
/// `measure`); returns a private copy of its ELF.
pub(super) fn build_firmware(
    b: &Bench,
    tree_name: &str,
    measure: bool,
) -> Result<PathBuf, CliError> {
    let dir = firmware_dir();
    let sub = if measure {
        "mcu-bench-measure"
    } else {
        "mcu-bench"
    };
    let target_dir = dir.join("target").join(sub);
    let tree = std::fs::canonicalize(&b.tree)?;
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.current_dir(&dir)
        .args([
            "build",
            "--release",
            "--locked",
            "--bin",
            "bench",
            "--target",
        ])
        .arg(b.cpu.target())
        .args(tree_features(&tree))
        .env("CARGO_TARGET_DIR", &target_dir)
        .env("FPT_BENCH_TREE", &tree)
        .env("FPT_BENCH_WIDTH", b.size.0.to_string())
        .env("FPT_BENCH_HEIGHT", b.size.1.to_string())
        .env("FPT_BENCH_BAND", b.band.to_string())
        .env("FPT_BENCH_PRECISION", b.precision.name())
        .env("FPT_BENCH_FRAMES", b.frames.to_string())
        .env("FPT_BENCH_MEMORY", b.memory.unwrap_or(0).to_string())
        // The firmware's own target and linker flags must apply.
        .env_remove("CARGO_BUILD_TARGET")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .env_remove("RUSTFLAGS");
    if measure {
        cmd.env("FPT_BENCH_RAM_KIB", MEASURE_RAM_KIB.to_string());
    } else {
        cmd.env_remove("FPT_BENCH_RAM_KIB");
    }
    let (ok, _, err) = run_captured(cmd, BUILD_TIMEOUT, "the firmware build")?;
    if !ok {
        let over = link_overflows(&err);
        if !over.is_empty() {
            let what: Vec<String> = over
                .iter()
                .map(|(region, n)| {
                    let size = if region == "FLASH" {
                        b.cpu.flash()
                    } else {
                        b.cpu.ram()
                    };
                    format!("its {region} ({} KiB) overflows by {n} bytes", size / 1024)
                })
                .collect();
            return Err(cli_err!(
                "{tree_name} does not fit the {}: {}{}",
                b.cpu.name(),
                what.join(", "),
                if over.iter().any(|(r, _)| r == "RAM") {
                    " (the RAM holds the band buffer and the renderer: try a smaller --band or --size)"
                } else {
                    ""
                }
            ));
        }
        let tail: Vec<&str> = err
            .lines()
            .filter(|l| l.contains("error"))
            .take(3)
            .collect();
        return Err(cli_err!("the firmware build failed: {}", tail.join(" | ")));
    }
    let elf = target_dir
        .join(b.cpu.target())
        .join("release")
        .join("bench");
    let copy = std::env::temp_dir().join(format!(
        "fpt-mcu-bench-{}-{}-{sub}.elf",
        std::process::id(),
        b.cpu.name()
    ));
    std::fs::copy(&elf, &copy).map_err(|e| cli_err!("copying {}: {e}", elf.display()))?;
    Ok(copy)
}

/// Sizes of an ELF32 little-endian file's sections, by name.
pub fn elf_sections(bytes: &[u8]) -> Option<Vec<(String, u64)>> {
    let u16_at = |o: usize| Some(u16::from_le_bytes(bytes.get(o..o + 2)?.try_into().ok()?));
    let u32_at = |o: usize| Some(u32::from_le_bytes(bytes.get(o..o + 4)?.try_into().ok()?));
    if bytes.get(..6)? != b"\x7fELF\x01\x01" {
        return None;
    }
    let shoff = u32_at(0x20)? as usize;
    let shentsize = u16_at(0x2E)? as usize;
    let shnum = u16_at(0x30)? as usize;
    let shstrndx = u16_at(0x32)? as usize;
    let header = |i: usize| shoff + i * shentsize;
    let strtab = u32_at(header(shstrndx) + 16)? as usize;
    let mut out = Vec::with_capacity(shnum);
    for i in 0..shnum {
        let h = header(i);
        let name_at = strtab + u32_at(h)? as usize;
        let name = bytes.get(name_at..)?;
        let end = name.iter().position(|&c| c == 0)?;
        let name = String::from_utf8_lossy(&name[..end]).into_owned();
        out.push((name, u64::from(u32_at(h + 20)?)));
    }
    Some(out)
}

/// What the firmware printed.
#[derive(Debug, Default)]
pub(super) struct Run {
    pub(super) frames: Vec<(OrbitLine, u64)>,
    pub(super) static_ram: Option<u64>,
    pub(super) stack_peak: Option<u64>,
    pub(super) error: Option<String>,
}

pub(super) fn parse_run(out: &str) -> Run {
    let mut run = Run::default();
    let num = |l: &str, key: &str| l.strip_prefix(key).and_then(|v| v.trim().parse().ok());
    for l in out.lines() {
        if let Some((line, Some(instr))) = OrbitLine::parse(l) {
            run.frames.push((line, instr));
        } else if let Some(v) = num(l, "static_ram=") {
            run.static_ram = Some(v);
        } else if let Some(v) = num(l, "stack_peak=") {
            run.stack_peak = Some(v);
        } else if let Some(e) = l.strip_prefix("error: ") {
            run.error.get_or_insert_with(|| e.trim().to_string());
        }
    }
    run
}

/// Runs `elf` under QEMU's `machine` (`-machine`, `-cpu` arguments) with
/// `-icount shift=0` and semihosting: exit success and stdout.
pub(super) fn run_qemu(
    machine: [&str; 4],
    elf: &Path,
    frames: u32,
) -> Result<(bool, String), CliError> {
    let mut cmd = Command::new("qemu-system-arm");
    cmd.args(machine).args([
        "-nographic",
        "-semihosting-config",
        "enable=on,target=native",
        "-icount",
        "shift=0",
        "-kernel",
    ]);
    cmd.arg(elf);
    // A Cortex-M0 frame takes a second or two of QEMU time; a run that
    // takes far longer has hung (e.g. after a stack overflow).
    let limit = (120 + 30 * u64::from(frames)).min(RUN_TIMEOUT.as_secs());
    let (ok, out, _) = run_captured(cmd, Duration::from_secs(limit), "QEMU")?;
    Ok((ok, out))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_relative_firmware_dir_is_made_absolute() {
        let cwd = std::env::current_dir().unwrap();
        assert_eq!(
            firmware_dir_from(Some("firmware".into())),
            cwd.join("firmware")
        );
        assert!(firmware_dir_from(None).is_absolute());
    }

    #[test]
    fn linker_overflows_are_read() {
        let err = "rust-lld: error: section '.text' will not fit in region 'FLASH': overflowed by 100 bytes\n\
                   rust-lld: error: section '.rodata' will not fit in region 'FLASH': overflowed by 5000 bytes\n\
                   rust-lld: error: section '.bss' will not fit in region 'RAM': overflowed by 12 bytes\n";
        assert_eq!(
            link_overflows(err),
            vec![("FLASH".to_string(), 5000), ("RAM".to_string(), 12)]
        );
        assert!(link_overflows("error: something else").is_empty());
    }

    #[test]
    fn run_output_is_read() {
        let out =
            "calib x\norbit frame=0 crc=0000abcd instr=100\norbit frame=1 crc=00000001 instr=300\n\
                   static_ram=11000\nstack_peak_startup=1 stack_peak_frames=2\nstack_peak=4000\n";
        let r = parse_run(out);
        assert_eq!(r.frames.len(), 2);
        assert_eq!(r.frames[1].1, 300);
        assert_eq!((r.static_ram, r.stack_peak), (Some(11000), Some(4000)));
        assert!(r.error.is_none());
    }
}
