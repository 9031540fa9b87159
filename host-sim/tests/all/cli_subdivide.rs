//! `fpt bench-build --scaling --subdivide K` and `fpt subdivide`: Loop
//! subdivision levels are measured as rows of their own, the OBJ that
//! `fpt subdivide` writes is the very mesh the benchmark builds, real
//! models (n-gons, non-planar quads) stay closed, and bad options are
//! one `error: ` line with exit status 2.

use crate::common;

use common::{error_line, fpt, s, tmp};
use host_sim::subdivide::TriMesh;
use std::path::PathBuf;

/// A closed octahedron of 8 triangles, faces outward.
const OCTAHEDRON_OBJ: &str = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

fn octahedron(name: &str) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, OCTAHEDRON_OBJ).unwrap();
    p
}

/// The table row of `input` from `fpt bench-build --scaling`: its cells.
fn row(stdout: &str, input: &str) -> Vec<String> {
    stdout
        .lines()
        .map(|l| {
            l.split('|')
                .map(|c| c.trim().to_string())
                .filter(|c| !c.is_empty())
                .collect::<Vec<_>>()
        })
        .find(|cells| cells.first().map(String::as_str) == Some(input))
        .unwrap_or_else(|| panic!("no row {input:?} in {stdout}"))
}

#[test]
fn scaling_measures_every_level_and_the_written_obj_is_that_mesh() {
    let mesh = octahedron("octa.obj");
    let out = fpt(&["bench-build", "--scaling", "--subdivide", "2", s(&mesh)]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("peak RSS MiB"), "{text}");
    assert_eq!(row(&text, "octa.obj")[1], "8");
    assert_eq!(row(&text, "octa.obj Loop 1")[1], "32");
    let level2 = row(&text, "octa.obj Loop 2");
    assert_eq!(level2[1], "128");
    assert!(text.contains("fitted growth"), "{text}");

    // `fpt subdivide` writes level 2; building it gives the row's output.
    let obj = tmp("octa-2.obj");
    let out = fpt(&["subdivide", s(&mesh), "-o", s(&obj), "--levels", "2"]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let written = std::fs::read_to_string(&obj).unwrap();
    assert_eq!(written.lines().filter(|l| l.starts_with("f ")).count(), 128);
    let tree = tmp("octa-2.fpt");
    let out = fpt(&["build", s(&obj), "-o", s(&tree)]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let expect = format!("closed static tree, 128 -> {} polygons", level2[2]);
    assert!(said.contains(&expect), "{said} (expected {expect})");
}

#[test]
fn bad_subdivision_options_are_one_error_line() {
    let mesh = octahedron("octa-bad.obj");
    let out = fpt(&["bench-build", "--subdivide", "1", s(&mesh)]);
    assert!(error_line(&out, "no --scaling").contains("--subdivide needs --scaling"));
    let out = fpt(&["bench-build", "--scaling", "--subdivide", "1"]);
    assert!(error_line(&out, "no meshes").contains("needs mesh files"));
    let out = fpt(&["bench-build", "--scaling", "--subdivide", "9", s(&mesh)]);
    error_line(&out, "too many levels");
    let out = fpt(&["bench-build", "--scaling", "--subdivide", "-1", s(&mesh)]);
    error_line(&out, "negative levels");

    let obj = tmp("octa-bad-out.obj");
    let _ = std::fs::remove_file(&obj);
    // 8 × 4^8 = 524,288 triangles is allowed; 4 Mi is the cap.
    let big = tmp("octa-big.obj");
    let out = fpt(&["subdivide", s(&mesh), "-o", s(&big), "--levels", "4"]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let out = fpt(&["subdivide", s(&big), "-o", s(&obj), "--levels", "8"]);
    let line = error_line(&out, "too many triangles");
    assert!(line.contains("would make 134217728 triangles"), "{line}");
    let out = fpt(&["subdivide", "/no/such/mesh.obj", "-o", s(&obj)]);
    error_line(&out, "missing mesh");
    let out = fpt(&["subdivide", s(&mesh), "-o", s(&obj), "--levels", "0"]);
    error_line(&out, "zero levels");
    assert!(!obj.exists(), "no output file after an error");
}

/// Real models with quads, n-gons and non-planar faces (split by the
/// import) stay closed one level down: the polygons' shared vertices are
/// found again bit for bit.
#[test]
fn shared_models_stay_closed() {
    let Some(dir) = [PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/models"
    ))]
    .into_iter()
    .find(|p| p.is_dir()) else {
        // Not `println!`: the harness swallows what a passing test prints.
        use std::io::Write;
        let _ = writeln!(std::io::stderr(), "skipping: ../shared/models not found");
        return;
    };
    for name in [
        "shuttle.obj",
        "socket.off",
        "violin_case.obj",
        "fandisk.obj",
    ] {
        // The file's faces, as `fpt subdivide` takes them (merged coplanar
        // polygons keep straight-through vertices, which ear clipping can
        // cut into triangles of no area).
        let whole = host_sim::mesh::ImportOptions {
            no_merge: true,
            ..Default::default()
        };
        let m = host_sim::mesh::load_with(&dir.join(name), &whole).unwrap();
        assert!(m.closed, "{name}");
        let tri = TriMesh::from_polygons(&m.polygons);
        let next = tri.loop_subdivide();
        assert_eq!(next.triangles.len(), 4 * tri.triangles.len(), "{name}");
        let sub = next.to_model().unwrap();
        assert!(sub.closed, "{name} after one step");
        assert_eq!(sub.report.dropped_degenerate, 0, "{name}");
    }
}
