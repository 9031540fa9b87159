//! `fpt mcu-bench`: bad options and missing tools are one `error:` line
//! with exit status 2 (always checked); on a machine with QEMU and both
//! thumb targets, a committed tree drawn on the emulated Cortex-M0 and
//! Cortex-M4F reports every field with `crc_match: true`, and a stack, a
//! tree and a frame too big for the Cortex-M0 exit 2 saying which
//! memories overflow and by how much. The QEMU part is skipped with a message when a tool is missing,
//! and fails instead under `FPT_REQUIRE_FIRMWARE=1` (as in CI).

use crate::common;

use std::process::{Command, Output};

use common::fpt;
use host_sim::cli::mcu_bench::target_installed;

fn tree(name: &str) -> String {
    format!("{}/../firmware/trees/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Exit status 2 and exactly one line on stderr, starting `error: `.
fn assert_error(out: &Output, what: &str) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{what}: {out:?}");
    assert!(
        err.starts_with("error: ") && err.trim_end().lines().count() == 1,
        "{what}: {err}"
    );
    err
}

#[test]
fn bad_options_exit_2() {
    let vise = tree("vise.fpt");
    for args in [
        &["--cpu", "m3"][..],
        &["--size", "0x10"][..],
        &["--size", "240"][..],
        &["--precision", "f64"][..],
        &["--frames", "0"][..],
        &["--band", "-1"][..],
        &["--clock", "0"][..],
    ] {
        let mut all = vec!["mcu-bench", vise.as_str()];
        all.extend_from_slice(args);
        assert_error(&fpt(&all), &format!("{args:?}"));
    }
    // A negative clock is a value the check explains, not an unknown flag.
    let out = fpt(&["mcu-bench", vise.as_str(), "--clock", "-5"]);
    assert_error(&out, "--clock -5");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--clock must be a positive number"), "{err}");
    // Negative counts say the value is invalid, not that a flag is unknown.
    for flag in ["--band", "--frames", "--memory"] {
        let out = fpt(&["mcu-bench", vise.as_str(), flag, "-1"]);
        let err = assert_error(&out, &format!("{flag} -1"));
        assert!(err.contains("invalid value '-1'"), "{flag}: {err}");
    }
    for flag in ["--band", "--frames", "--memory"] {
        let out = fpt(&["bench-memory", vise.as_str(), flag, "-1"]);
        let err = assert_error(&out, &format!("bench-memory {flag} -1"));
        assert!(err.contains("invalid value '-1'"), "{flag}: {err}");
    }
    let out = fpt(&["mcu-bench", "/nonexistent/tree.fpt"]);
    assert_error(&out, "missing tree");
    let out = fpt(&["mcu-bench", &tree("frames.txt"), "--frames", "1"]);
    assert_error(&out, "not a tree");
}

#[test]
fn missing_qemu_names_the_install_command() {
    // No PATH: neither QEMU nor anything else can be found.
    let out = Command::new(env!("CARGO_BIN_EXE_fpt"))
        .args(["mcu-bench", &tree("vise.fpt"), "--frames", "1"])
        .args(["--size", "32x32"])
        .env("PATH", "")
        .output()
        .expect("running fpt");
    let err = assert_error(&out, "no QEMU");
    assert!(err.contains("apt-get install qemu-system-arm"), "{err}");
}

/// Skips (with a message) or, under `FPT_REQUIRE_FIRMWARE=1`, fails when
/// QEMU or a thumb target is missing; `true` if the firmware can run.
fn can_run() -> bool {
    let qemu = Command::new("qemu-system-arm").arg("--version").output();
    let why = if !qemu.is_ok_and(|o| o.status.success()) {
        Some("qemu-system-arm is not installed".to_string())
    } else {
        ["thumbv6m-none-eabi", "thumbv7em-none-eabihf"]
            .into_iter()
            .find(|t| !target_installed(t))
            .map(|t| format!("the {t} target is not installed"))
    };
    let Some(why) = why else { return true };
    if std::env::var("FPT_REQUIRE_FIRMWARE").is_ok_and(|v| v == "1") {
        panic!("FPT_REQUIRE_FIRMWARE=1 but {why}");
    }
    println!("SKIPPED mcu_bench_runs_on_qemu: {why}");
    false
}

/// Runs `fpt mcu-bench` successfully and returns its JSON.
fn bench(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["mcu-bench"];
    all.extend_from_slice(args);
    let out = fpt(&all);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{args:?}: {out:?}");
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{args:?}: {e}: {text}"))
}

// One test, so that its firmware builds (which share a target directory)
// run one after the other.
#[test]
fn mcu_bench_runs_on_qemu() {
    if !can_run() {
        return;
    }
    let vise = tree("vise.fpt");
    // 768 words of working memory: with the default (what 16 KiB leave
    // beside a 4 KiB stack reserve) the vise's f32 pipeline (software
    // floats: a 5.4 KiB stack since session 8's sliver pass) does not fit.
    let m0 = bench(&[
        &vise, "--cpu", "m0", "--size", "96x64", "--band", "8", "--frames", "3", "--memory", "768",
    ]);
    let m4 = bench(&[
        &vise,
        "--precision",
        "fixed",
        "--size",
        "64x48",
        "--frames",
        "2",
    ]);
    for (j, cpu, band, frames, w, h, precision) in [
        (&m0, "m0", 8, 3, 96, 64, "f32-libm"),
        (&m4, "m4f", 0, 2, 64, 48, "fixed"),
    ] {
        assert_eq!(j["cpu"], cpu, "{j}");
        assert_eq!(j["band"], band, "{j}");
        assert_eq!(j["frames"], frames, "{j}");
        assert_eq!(
            (j["width"].clone(), j["height"].clone()),
            (w.into(), h.into())
        );
        assert_eq!(j["precision"], precision, "{j}");
        assert_eq!(j["crc_match"], true, "{j}");
        for key in [
            "instr_median",
            "instr_min",
            "instr_max",
            "ram_static",
            "stack_peak",
            "text",
            "rodata",
            "fps_at_clock",
        ] {
            assert!(j[key].as_f64().is_some_and(|v| v > 0.0), "{key}: {j}");
        }
        let min = j["instr_min"].as_f64().unwrap();
        let max = j["instr_max"].as_f64().unwrap();
        let median = j["instr_median"].as_f64().unwrap();
        assert!(min <= median && median <= max, "{j}");
        let ram = j["ram_static"].as_u64().unwrap() + j["stack_peak"].as_u64().unwrap();
        assert!(ram <= j["ram_size"].as_u64().unwrap(), "{j}");
    }
    // 320×240 in 14-row bands (8.75 KiB; with the renderer's 61-vertex
    // scratch that the vise's header asks for): the statics fit the
    // Cortex-M0's RAM, the stack does not; the overflow is measured on a machine with
    // more RAM.
    let out = fpt(&[
        "mcu-bench",
        &vise,
        "--cpu",
        "m0",
        "--size",
        "320x240",
        "--band",
        "14",
        "--frames",
        "1",
    ]);
    let err = assert_error(&out, "stack too big for the M0");
    assert!(
        err.contains("vise does not fit the m0's RAM (16 KiB)"),
        "{err}"
    );
    let over: String = err
        .split("over by ")
        .nth(1)
        .unwrap_or_else(|| panic!("no overflow amount: {err}"))
        .chars()
        .take_while(char::is_ascii_digit)
        .collect();
    assert!(over.parse::<u64>().is_ok_and(|b| b > 0), "{err}");
    // A 7,200-quad torus (a 395 KiB tree) in a full 240×240 frame
    // (112.5 KiB) overflows both the Cortex-M0's flash and its RAM.
    let (obj, big) = (common::tmp("torus.obj"), common::tmp("torus.fpt"));
    std::fs::write(&obj, torus_obj(120, 60)).expect("writing torus.obj");
    let built = fpt(&["build", common::s(&obj), "-o", common::s(&big), "--closed"]);
    assert!(built.status.success(), "{built:?}");
    let out = fpt(&[
        "mcu-bench",
        common::s(&big),
        "--cpu",
        "m0",
        "--band",
        "0",
        "--frames",
        "1",
    ]);
    let err = assert_error(&out, "too big for the M0");
    assert!(err.contains("torus does not fit the m0"), "{err}");
    for region in ["FLASH (256 KiB)", "RAM (16 KiB)"] {
        let at = err
            .find(&format!("its {region} overflows by "))
            .unwrap_or_else(|| panic!("no {region} overflow: {err}"));
        let bytes: String = err[at..]
            .split("overflows by ")
            .nth(1)
            .unwrap_or_default()
            .chars()
            .take_while(char::is_ascii_digit)
            .collect();
        assert!(bytes.parse::<u64>().is_ok_and(|b| b > 1000), "{err}");
    }
}

/// A closed torus of `n × m` quads, as OBJ.
fn torus_obj(n: usize, m: usize) -> String {
    use std::f64::consts::TAU;
    let mut s = String::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (TAU * i as f64 / n as f64, TAU * j as f64 / m as f64);
            let ring = 3.0 + v.cos();
            s += &format!("v {} {} {}\n", ring * u.cos(), ring * u.sin(), v.sin());
        }
    }
    let id = |i: usize, j: usize| (i % n) * m + (j % m) + 1;
    for i in 0..n {
        for j in 0..m {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            s += &format!("f {} {} {} {}\n", q[0], q[1], q[2], q[3]);
        }
    }
    s
}
