//! The firmware's frames against the host's, bit for bit.
//!
//! * `committed_trees_are_fresh`: the trees the firmware embeds
//!   (`firmware/trees/*.fpt`) and the expected lines next to them
//!   (`frames.txt`) are exactly what `fpt frames --export firmware/trees`
//!   produces now, so they cannot go stale.
//! * `firmware_matches_host`: runs the firmware under QEMU in both features
//!   (`cargo run --release` in `firmware/`, once with `full`, once with
//!   `band`) and compares its `frame scene=… view=… crc=…` lines with the
//!   host's for the same trees, and checks that `full` prints an `effect`
//!   line with the three costs for every effect, and runs the `accuracy`
//!   binary, whose lines must be the host's too.
//! * `m0_firmware_matches_host`: the same for the Cortex-M0 build
//!   (`--target thumbv6m-none-eabi`, feature `band`, QEMU `microbit`),
//!   which embeds the scene that fits its flash (vise), and
//!   checks that its statics and measured stack peak fit its 16 KiB of RAM.
//! * `m0_accuracy_matches_host`: the `accuracy` binary's `band` build on
//!   the Cortex-M0 (QEMU `microbit`, 16 KiB of RAM, 256 KiB of flash), one
//!   build per tree encoding and arithmetic: every configuration's
//!   checksums equal the host's and each build fits the RAM (the `m0_instr`
//!   column of the accuracy study).
//!
//! The firmware tests are skipped, with a message, when
//! `qemu-system-arm` or the thumb target is missing — unless
//! `FPT_REQUIRE_FIRMWARE=1` is set (CI sets it), which turns a missing
//! tool into a failure.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use fpt_frames::accuracy::{in_build, one_arithmetic_builds, AccuracyLine, CONFIGS};
use fpt_frames::{FrameLine, SCENES, VIEWS};
use host_sim::cli::frames::{
    accuracy_lines, accuracy_tree_file, accuracy_trees, expected_text, frame_lines,
    read_accuracy_trees, read_trees, scene_trees, ACCURACY_FILE, EXPECTED_FILE,
};
use host_sim::cli::mcu_bench::{qemu_installed, target_installed};

const REGENERATE: &str =
    "regenerate with: cargo run --release -p host-sim --bin fpt -- frames --export firmware/trees";

/// Longest a firmware build and run may take.
const FIRMWARE_TIMEOUT: Duration = Duration::from_secs(1200);

fn firmware_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("firmware")
}

fn trees_dir() -> PathBuf {
    firmware_dir().join("trees")
}

fn ok<T, E: std::fmt::Debug>(r: Result<T, E>, what: &str) -> T {
    r.unwrap_or_else(|e| panic!("{what}: {e:?}"))
}

#[test]
fn committed_trees_are_fresh() {
    let built = ok(scene_trees(), "building the scenes' trees");
    let committed = ok(read_trees(&trees_dir()), "reading firmware/trees");
    for ((name, new), (_, old)) in built.iter().zip(&committed) {
        assert!(
            new == old,
            "firmware/trees/{name}.fpt differs from the tree built now ({} vs {} bytes); {REGENERATE}",
            old.len(),
            new.len()
        );
    }
    let lines = ok(frame_lines(&built), "drawing the frames");
    assert_eq!(lines.len(), SCENES.len() * VIEWS.len());
    let expected = ok(
        std::fs::read_to_string(trees_dir().join(EXPECTED_FILE)),
        "reading frames.txt",
    );
    assert!(
        expected == expected_text(&lines),
        "firmware/trees/{EXPECTED_FILE} is stale; {REGENERATE}"
    );
    // The accuracy binary's trees (every vertex encoding) and lines.
    let built = ok(accuracy_trees(), "building the accuracy trees");
    let committed = ok(
        read_accuracy_trees(&trees_dir()),
        "reading the accuracy trees",
    );
    for ((f, new), (_, old)) in built.iter().zip(&committed) {
        assert!(
            new == old,
            "firmware/trees/{} is stale; {REGENERATE}",
            accuracy_tree_file(*f)
        );
    }
    let lines = ok(accuracy_lines(&built), "drawing the accuracy frames");
    let expected = ok(
        std::fs::read_to_string(trees_dir().join(ACCURACY_FILE)),
        "reading accuracy.txt",
    );
    assert!(
        expected == expected_text(&lines),
        "firmware/trees/{ACCURACY_FILE} is stale; {REGENERATE}"
    );
}

/// Why the firmware cannot run here for `target`, if it cannot.
fn missing_tool(target: &str) -> Option<String> {
    if !qemu_installed() {
        return Some("qemu-system-arm is not installed".into());
    }
    if !target_installed(target) {
        return Some(format!(
            "the {target} target is not installed (rustup target add {target})"
        ));
    }
    None
}

/// Skips (with a message) or, under `FPT_REQUIRE_FIRMWARE=1`, fails when
/// the firmware cannot run for `target`; `true` if it can.
fn can_run(test: &str, target: &str) -> bool {
    let Some(why) = missing_tool(target) else {
        return true;
    };
    if std::env::var("FPT_REQUIRE_FIRMWARE").is_ok_and(|v| v == "1") {
        panic!("FPT_REQUIRE_FIRMWARE=1 but {why}");
    }
    fpt_tests::skipping(&format!("{test}: {why}"));
    false
}

/// `cargo run --release ARGS` in `firmware/`: exit success and stdout.
fn run_firmware(args: &[&str]) -> (bool, String) {
    run_firmware_with(args, &[])
}

/// [`run_firmware`] with environment variables `env` set.
fn run_firmware_with(args: &[&str], env: &[(&str, &str)]) -> (bool, String) {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut child = ok(
        Command::new(cargo)
            .current_dir(firmware_dir())
            .args(["run", "--release", "--locked"])
            .args(args)
            // The firmware's own target and linker flags must apply.
            .env_remove("CARGO_BUILD_TARGET")
            .env_remove("CARGO_ENCODED_RUSTFLAGS")
            .envs(env.iter().copied())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn(),
        "starting cargo run in firmware/",
    );
    let mut stdout = child.stdout.take().map(|mut s| {
        std::thread::spawn(move || {
            let mut text = String::new();
            let _ = s.read_to_string(&mut text);
            text
        })
    });
    let start = Instant::now();
    let status = loop {
        if let Some(s) = ok(child.try_wait(), "waiting for the firmware") {
            break s;
        }
        if start.elapsed() > FIRMWARE_TIMEOUT {
            let _ = child.kill();
            panic!("firmware {args:?} did not finish in {FIRMWARE_TIMEOUT:?}");
        }
        std::thread::sleep(Duration::from_millis(100));
    };
    let text = stdout
        .take()
        .and_then(|h| h.join().ok())
        .unwrap_or_default();
    (status.success(), text)
}

#[test]
fn firmware_matches_host() {
    if !can_run("firmware_matches_host", "thumbv7em-none-eabihf") {
        return;
    }
    // The host draws the very trees the firmware embeds.
    let trees = ok(read_trees(&trees_dir()), "reading firmware/trees");
    let host = ok(frame_lines(&trees), "drawing the frames on the host");
    for args in [
        &[][..],
        &["--no-default-features", "--features", "band"][..],
    ] {
        let (success, out) = run_firmware(args);
        let firmware: Vec<String> = out
            .lines()
            .filter_map(FrameLine::parse)
            .map(|l| l.to_string())
            .collect();
        assert_eq!(
            firmware, host,
            "firmware {args:?} frames differ from the host's; its output:\n{out}"
        );
        // Every frame line carries its cost, and the run ends with the
        // stack measurement.
        for l in out.lines().filter(|l| l.starts_with("frame ")) {
            for field in [" instr=", " post=", " xform=", " fill="] {
                assert!(l.contains(field), "{l}");
            }
        }
        assert!(
            out.lines().any(|l| l.starts_with("stack_peak=")),
            "no stack_peak line:\n{out}"
        );
        // `full` measures every effect on, off and compiled out.
        if args.is_empty() {
            for (name, _) in fpt_nostd::effects::Effects::NAMED {
                let line = out
                    .lines()
                    .find(|l| l.starts_with(&format!("effect name={name} ")))
                    .unwrap_or_else(|| panic!("no effect line for {name}:\n{out}"));
                for field in ["on", "off", "bare"] {
                    let v = line
                        .split_ascii_whitespace()
                        .find_map(|t| t.strip_prefix(&format!("{field}=")))
                        .and_then(|v| v.parse::<u64>().ok());
                    assert!(v.is_some_and(|v| v > 0), "{line}");
                }
            }
        }
        assert!(success, "firmware {args:?} exited with failure:\n{out}");
    }
    // The accuracy configurations: same checksums as the host, a cost each.
    let host = ok(
        accuracy_lines(&ok(read_accuracy_trees(&trees_dir()), "accuracy trees")),
        "drawing the accuracy frames on the host",
    );
    let (success, out) = run_firmware(&["--bin", "accuracy"]);
    check_accuracy(&host, success, &out, "Cortex-M4");
}

/// The `accuracy` binary's run (`success`, output `out`) against the
/// host's lines: the same checksums, a cost for each, exit success.
fn check_accuracy(host: &[String], success: bool, out: &str, cpu: &str) {
    let firmware: Vec<String> = out
        .lines()
        .filter_map(AccuracyLine::parse)
        .map(|l| l.to_string())
        .collect();
    assert_eq!(
        firmware, host,
        "{cpu} accuracy frames differ; output:\n{out}"
    );
    assert!(out
        .lines()
        .filter(|l| l.starts_with("accuracy "))
        .all(|l| AccuracyLine::instr(l).is_some_and(|n| n > 0)));
    assert!(
        success,
        "{cpu} accuracy firmware exited with failure:\n{out}"
    );
}

/// The scenes the Cortex-M0 firmware embeds (those that fit its flash).
const M0_SCENES: [&str; 1] = ["vise"];
/// The Cortex-M0's RAM (QEMU `microbit`, nRF51822).
const M0_RAM: usize = 16 * 1024;

/// The Cortex-M0 firmware (`--target thumbv6m-none-eabi`, feature `band`,
/// QEMU `microbit`): the host's lines for the scenes it embeds, and its
/// statics plus its measured stack peak within the 16 KiB of RAM.
#[test]
fn m0_firmware_matches_host() {
    if !can_run("m0_firmware_matches_host", "thumbv6m-none-eabi") {
        return;
    }
    let trees = ok(read_trees(&trees_dir()), "reading firmware/trees");
    let host: Vec<String> = ok(frame_lines(&trees), "drawing the frames on the host")
        .into_iter()
        .filter(|l| FrameLine::parse(l).is_some_and(|f| M0_SCENES.contains(&f.scene)))
        .collect();
    assert_eq!(host.len(), M0_SCENES.len() * VIEWS.len());
    let args = [
        "--target",
        "thumbv6m-none-eabi",
        "--no-default-features",
        "--features",
        "band",
    ];
    let (success, out) = run_firmware(&args);
    let firmware: Vec<String> = out
        .lines()
        .filter_map(FrameLine::parse)
        .map(|l| l.to_string())
        .collect();
    assert_eq!(firmware, host, "M0 frames differ from the host's:\n{out}");
    let value = |key: &str| {
        out.lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|v| v.trim().parse::<usize>().ok())
            .unwrap_or_else(|| panic!("no {key} line:\n{out}"))
    };
    let (statics, stack) = (value("static_ram="), value("stack_peak="));
    assert!(
        statics + stack <= M0_RAM,
        "M0 RAM: {statics} B static + {stack} B stack > {M0_RAM} B"
    );
    assert!(success, "M0 firmware exited with failure:\n{out}");
}

/// Rows per band of the Cortex-M0's accuracy frames (`fpt mcu-bench
/// --cpu m0`'s default: a 16-row band, 7.5 KiB, would leave the working
/// memory nothing).
const M0_ACCURACY_BAND: &str = "8";
/// Words of working memory of the Cortex-M0's accuracy frames: what the
/// largest build's statics and stack leave of the 16 KiB with a margin
/// (the fixed-point builds: 3,856 B of statics besides the memory and a
/// 7,528 B stack peak, each configuration's renderer and scratch on it,
/// leave 1,186 words with `fpt mcu-bench`'s 256 B margin); the same for
/// every configuration, so that they take the same walks. A frame of
/// `bench_city` needs 13,099 for one walk (`fpt info`).
const M0_ACCURACY_MEMORY: &str = "1152";

/// The accuracy configurations on the Cortex-M0 with 16 KiB of RAM (QEMU
/// `microbit`; Thumb-1, software floating point, no divide): each drawn in
/// [`M0_ACCURACY_BAND`]-row bands with [`M0_ACCURACY_MEMORY`] words of
/// working memory by the `accuracy` binary's `band` build, one build per
/// tree encoding and arithmetic (256 KiB of flash hold a `bench_city` tree
/// and one: [`one_arithmetic_builds`]). Every checksum equals the host's,
/// every frame has a cost, and every build's statics and stack peak fit
/// the 16 KiB. With `FPT_ACCURACY_M0_OUT=FILE` the lines are also written
/// to FILE, in the host's order, then a `build tree=… configs=…
/// static_ram=… stack_peak=…` line per build: the `m0_instr` column of the
/// accuracy study (`fpt bench-accuracy --m0 FILE`).
#[test]
fn m0_accuracy_matches_host() {
    if !can_run("m0_accuracy_matches_host", "thumbv6m-none-eabi") {
        return;
    }
    let host: Vec<String> = ok(
        accuracy_lines(&ok(read_accuracy_trees(&trees_dir()), "accuracy trees")),
        "drawing the accuracy frames on the host",
    );
    // Its own target folder: the builds' variables would otherwise make
    // the other Cortex-M0 tests rebuild.
    let target_dir = firmware_dir().join("target").join("m0-accuracy");
    let mut out = String::new();
    let mut ram = Vec::new();
    for (format, arithmetic) in one_arithmetic_builds() {
        let configs: Vec<&str> = in_build(format, arithmetic).collect();
        let tree = format!("trees/{}", accuracy_tree_file(format));
        let (success, text) = run_firmware_with(
            &[
                "--bin",
                "accuracy",
                "--target",
                "thumbv6m-none-eabi",
                "--no-default-features",
                "--features",
                "band",
            ],
            &[
                ("FPT_BENCH_TREE", &tree),
                ("FPT_ACCURACY_CONFIGS", &configs.join(",")),
                ("FPT_BENCH_BAND", M0_ACCURACY_BAND),
                ("FPT_BENCH_MEMORY", M0_ACCURACY_MEMORY),
                ("CARGO_TARGET_DIR", &target_dir.to_string_lossy()),
            ],
        );
        assert!(
            success,
            "Cortex-M0 accuracy build {configs:?} exited with failure:\n{text}"
        );
        let value = |key: &str| {
            text.lines()
                .find_map(|l| l.strip_prefix(key))
                .and_then(|v| v.trim().parse::<usize>().ok())
                .unwrap_or_else(|| panic!("no {key} line:\n{text}"))
        };
        let (statics, stack) = (value("static_ram="), value("stack_peak="));
        assert!(
            statics + stack <= M0_RAM,
            "M0 accuracy {configs:?}: {statics} B static + {stack} B stack > {M0_RAM} B"
        );
        out.push_str(&text);
        ram.push(format!(
            "build tree={tree} configs={} static_ram={statics} stack_peak={stack}",
            configs.join(",")
        ));
    }
    // The builds' lines in the host's order (configurations, then views).
    let key = |l: &AccuracyLine| (CONFIGS.iter().position(|c| *c == l.config), l.view);
    let mut lines: Vec<&str> = out
        .lines()
        .filter(|l| AccuracyLine::parse(l).is_some())
        .collect();
    lines.sort_by_key(|l| AccuracyLine::parse(l).map(|p| key(&p)));
    let sorted = lines.join("\n") + "\n";
    check_accuracy(&host, true, &sorted, "Cortex-M0");
    if let Some(path) = std::env::var_os("FPT_ACCURACY_M0_OUT") {
        // Each build's RAM after the frames (`fpt bench-accuracy` reads
        // the `accuracy` lines only).
        let text = sorted + &ram.join("\n") + "\n";
        ok(std::fs::write(&path, text), "writing FPT_ACCURACY_M0_OUT");
    }
}
