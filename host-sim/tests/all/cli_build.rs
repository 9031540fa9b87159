//! `fpt build` run as the real binary: good meshes give a tree and a stats
//! file; bad input of any kind gives exit status 2, one `error: ` line, and
//! no output file.

use crate::common;

use common::{fpt, s, tmp, CUBE_OBJ};
use std::path::PathBuf;
use std::process::{Command, Output};

fn write(name: &str, text: &[u8]) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Exit status 2, exactly one line on stderr starting with `error: `.
fn assert_error(out: &Output, what: &str) {
    assert_eq!(out.status.code(), Some(2), "{what}: status");
    let err = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{what}: stderr {err:?}");
    assert!(lines[0].starts_with("error: "), "{what}: {err:?}");
}

#[test]
fn builds_tree_and_stats_with_every_method() {
    let mesh = write("cube.obj", CUBE_OBJ.as_bytes());
    for method in ["static", "dynamic", "bsp"] {
        let out_tree = tmp(&format!("cube-{method}.fpt"));
        let stats = tmp(&format!("cube-{method}.json"));
        let out = fpt(&[
            "build",
            s(&mesh),
            "-o",
            s(&out_tree),
            "--method",
            method,
            "--stats",
            s(&stats),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&stats).unwrap()).unwrap();
        for key in [
            "input_polygons",
            "output_polygons",
            "splittings",
            "connecting_nodes",
            "switch_nodes",
            "relations",
            "max_depth",
            "build_ms",
            "closed",
        ] {
            assert!(v.get(key).is_some(), "{method}: stats lack {key}");
        }
        assert_eq!(v["input_polygons"], 6);
        assert_eq!(v["closed"], true);
        let info = fpt(&["info", s(&out_tree)]);
        assert!(info.status.success());
    }
    // --open overrides the detected closed volume.
    let out_tree = tmp("cube-open.fpt");
    let stats = tmp("cube-open.json");
    let out = fpt(&[
        "build",
        s(&mesh),
        "-o",
        s(&out_tree),
        "--open",
        "--stats",
        s(&stats),
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&stats).unwrap()).unwrap();
    assert_eq!(v["closed"], false);
}

#[test]
fn bad_input_is_one_error_line_and_no_file() {
    let good = write("good.obj", CUBE_OBJ.as_bytes());
    let cases: Vec<(&str, PathBuf, Vec<&str>)> = vec![
        ("missing mesh", tmp("does-not-exist.obj"), vec![]),
        ("unknown extension", write("mesh.xyz", b"hello"), vec![]),
        (
            "malformed obj",
            write("bad.obj", b"v 0 0\nf 1 2 3\n"),
            vec![],
        ),
        (
            "index out of range",
            write("idx.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
            vec![],
        ),
        (
            "non-finite vertex",
            write("nan.obj", b"v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
            vec![],
        ),
        ("empty mesh", write("empty.off", b"OFF\n0 0 0\n"), vec![]),
        ("truncated stl", write("trunc.stl", &[0u8; 90]), vec![]),
        ("unknown method", good.clone(), vec!["--method", "octree"]),
        (
            "unknown vertex format",
            good.clone(),
            vec!["--vertex-format", "f16"],
        ),
        ("unknown option", good.clone(), vec!["--frobnicate"]),
        ("bad seed", good.clone(), vec!["--seed", "-1"]),
        ("closed and open", good.clone(), vec!["--closed", "--open"]),
        (
            "compact planes without a table",
            good.clone(),
            vec!["--planes", "compact", "--records", "narrow"],
        ),
    ];
    for (what, mesh, extra) in cases {
        let out_tree = tmp(&format!("out-{}.fpt", what.replace(' ', "-")));
        let mut args = vec!["build", s(&mesh), "-o", s(&out_tree)];
        args.extend(extra);
        let out = fpt(&args);
        assert_error(&out, what);
        assert!(!out_tree.exists(), "{what}: a partial output file was left");
    }
}

#[test]
fn unwritable_stats_leaves_no_tree() {
    let good = write("good2.obj", CUBE_OBJ.as_bytes());
    let out_tree = tmp("never.fpt");
    let stats = tmp("no/such/dir/stats.json");
    let out = fpt(&["build", s(&good), "-o", s(&out_tree), "--stats", s(&stats)]);
    assert_error(&out, "unwritable stats");
    assert!(!out_tree.exists());
}

#[test]
fn degenerate_faces_are_counted_in_one_warning() {
    let text = format!("{CUBE_OBJ}f 1 1 2\nf 1 2 2 1\n");
    let mesh = write("degenerate.obj", text.as_bytes());
    let out_tree = tmp("degenerate.fpt");
    let out = fpt(&["build", s(&mesh), "-o", s(&out_tree)]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let warnings: Vec<&str> = err.lines().filter(|l| l.contains("warning")).collect();
    assert_eq!(warnings.len(), 1, "{err}");
    assert!(warnings[0].contains('2'), "{err}");
}

#[test]
fn closed_stdout_is_not_a_panic() {
    // A reader that goes away (`fpt ... | head`) must not make fpt panic.
    let mut child = Command::new(env!("CARGO_BIN_EXE_fpt"))
        .args(["bench-build", "--scaling"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("running fpt");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("waiting for fpt");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
}

/// A mesh that needs more heap than `--max-memory` allows is refused with
/// the needs in MiB, status 2, and no tree file.
#[test]
fn too_little_memory_is_an_error_without_output() {
    // A flat strip of 120 quads: open, and small.
    let mut obj = String::new();
    let n = 120;
    for i in 0..=n {
        for j in 0..=1 {
            obj.push_str(&format!("v {i} {j} 0\n"));
        }
    }
    for i in 0..n {
        let a = 2 * i + 1;
        obj.push_str(&format!("f {} {} {} {}\n", a, a + 2, a + 3, a + 1));
    }
    let mesh = write("strip.obj", obj.as_bytes());
    let out_tree = tmp("strip-nomem.fpt");
    let _ = std::fs::remove_file(&out_tree);
    let out = fpt(&["build", s(&mesh), "-o", s(&out_tree), "--max-memory", "1"]);
    let err = String::from_utf8_lossy(&out.stderr);
    let last = err.lines().last().unwrap_or_default();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        last.starts_with("error: not enough memory to build this mesh (needs about ")
            && last.ends_with(" MiB)"),
        "{err}"
    );
    assert!(!out_tree.exists());
    // With room enough it builds, and says why the strip is open.
    let out = fpt(&["build", s(&mesh), "-o", s(&out_tree), "--max-memory", "200"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the mesh is open: 242 edges")
            && err.contains("draws both sides of every face in every view"),
        "{err}"
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("peak heap"));
}

/// Running out of memory while building (here a virtual memory limit the
/// estimate does not know of) is the same error, not an abort.
#[cfg(target_os = "linux")]
#[test]
fn running_out_of_memory_while_building_is_an_error() {
    let mesh = tmp("big-torus.obj");
    let out_tree = tmp("big-torus.fpt");
    let _ = std::fs::remove_file(&out_tree);
    // A torus of 40,000 quads.
    let (big, small, nu, nv) = (3.0f64, 1.0f64, 400usize, 100usize);
    let mut obj = String::new();
    for i in 0..nu {
        for j in 0..nv {
            let (u, v) = (
                i as f64 / nu as f64 * std::f64::consts::TAU,
                j as f64 / nv as f64 * std::f64::consts::TAU,
            );
            let r = big + small * v.cos();
            obj.push_str(&format!(
                "v {} {} {}\n",
                r * u.cos(),
                r * u.sin(),
                small * v.sin()
            ));
        }
    }
    let id = |i: usize, j: usize| (i % nu) * nv + (j % nv) + 1;
    for i in 0..nu {
        for j in 0..nv {
            obj.push_str(&format!(
                "f {} {} {} {}\n",
                id(i, j),
                id(i + 1, j),
                id(i + 1, j + 1),
                id(i, j + 1)
            ));
        }
    }
    std::fs::write(&mesh, obj).unwrap();
    let exe = env!("CARGO_BIN_EXE_fpt");
    let script = format!(
        "ulimit -v 30000 && exec '{exe}' build '{}' -o '{}'",
        mesh.display(),
        out_tree.display()
    );
    let out = Command::new("sh").arg("-c").arg(script).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.lines()
            .last()
            .is_some_and(|l| l.starts_with("error: not enough memory to build this mesh")),
        "{err}"
    );
    assert!(!out_tree.exists());
}

/// The `build.rs` recipe of `fpt_build`'s crate docs (load, build with the
/// default seed, serialize with default options) writes the very bytes of
/// `fpt build` with default options.
#[test]
fn the_build_rs_recipe_gives_fpt_builds_bytes() {
    let mesh = write("recipe-cube.obj", CUBE_OBJ.as_bytes());
    let out_tree = tmp("recipe-cube.fpt");
    let out = fpt(&["build", s(&mesh), "-o", s(&out_tree)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let model = fpt_build::mesh::load(&mesh).expect("cube loads");
    let tree = fpt_build::build::build(
        model.polygons,
        model.closed,
        fpt_build::tree::Method::Static,
        fpt_build::build::DEFAULT_SEED,
        &mut fpt_build::build::NoProgress,
    );
    let bytes = fpt_build::serialize::serialize(&tree, &Default::default()).expect("serializes");
    assert_eq!(std::fs::read(&out_tree).expect("tree written"), bytes);
}

/// An open mesh: the build says how many boundary and non-manifold edges
/// it has, counted apart, names the first few by their end positions, and
/// says what an open tree costs.
#[test]
fn build_says_why_a_mesh_is_open() {
    // A box of side 2.5 without its top (4 rim edges of one face), with a
    // fin hanging from a bottom edge (that edge has three faces; the fin's
    // two other edges have one).
    let obj = "v 0 0 0\nv 2.5 0 0\nv 2.5 2.5 0\nv 0 2.5 0\n\
               v 0 0 2.5\nv 2.5 0 2.5\nv 2.5 2.5 2.5\nv 0 2.5 2.5\nv 1.25 -1 -1\n\
               f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nf 1 2 9\n";
    let mesh = write("open-box-fin.obj", obj.as_bytes());
    let out_tree = tmp("open-box-fin.fpt");
    let out = fpt(&["build", s(&mesh), "-o", s(&out_tree)]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let lines: Vec<&str> = err.lines().collect();
    let at = |start: &str| {
        lines
            .iter()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no line {start:?} in {err}"))
            .to_string()
    };
    let head = at("note: the mesh is open: 7 edges are not shared");
    assert!(
        head.contains("draws both sides of every face in every view"),
        "{err}"
    );
    assert_eq!(
        at("note:   6 boundary"),
        "note:   6 boundary edges (of one face only), the first at \
         (2.5, 0, 2.5)-(0, 0, 2.5); (2.5, 2.5, 2.5)-(2.5, 0, 2.5); \
         (0, 2.5, 2.5)-(2.5, 2.5, 2.5)"
    );
    assert_eq!(
        at("note:   1 non-manifold"),
        "note:   1 non-manifold edge (of three or more faces), the first at \
         (2.5, 0, 0)-(0, 0, 0)"
    );
    assert!(!err.contains("inconsistently wound"), "{err}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("open static tree"));
}
