//! Inputs that used to go wrong quietly, run through the real binary:
//! closed parts that wind inward, open and closed parts mixed, `--closed`
//! on a mesh with holes, grey levels through a panel look, and the wording
//! of messages about bad values and files.

use crate::common;

use common::{colours, error_line, fpt, s, stderr, tmp, CUBE_OBJ};
use glam::DVec3;
use host_sim::mesh::{load_bytes, ImportOptions, MeshFormat};
use host_sim::reference::{zbuffer, Camera, Projection, RefOptions};
use std::path::{Path, PathBuf};
use std::process::Output;

fn write(name: &str, text: &str) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// OBJ text of unit cubes at `offsets` (faces outward, or inward for the
/// cubes whose flag is set), then extra `tail` lines.
fn cubes_obj(cubes: &[(DVec3, bool)], tail: &str) -> String {
    let mut text = String::new();
    for (k, &(at, inward)) in cubes.iter().enumerate() {
        for i in 0..8 {
            let p = at + DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2));
            text += &format!("v {} {} {}\n", p.x, p.y, p.z);
        }
        let base = 8 * k + 1;
        for f in [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [1, 3, 7, 5],
            [0, 4, 6, 2],
        ] {
            let mut f: Vec<usize> = f.iter().map(|i| i + base).collect();
            if inward {
                f.reverse();
            }
            let f: Vec<String> = f.iter().map(ToString::to_string).collect();
            text += &format!("f {}\n", f.join(" "));
        }
    }
    text + tail
}

/// Three cubes in a row, the middle one inside out.
fn three_cubes_one_inverted() -> String {
    cubes_obj(
        &[
            (DVec3::new(-2.5, 0.0, 0.0), false),
            (DVec3::new(-0.5, 0.0, 0.0), true),
            (DVec3::new(1.5, 0.0, 0.0), false),
        ],
        "",
    )
}

fn build(mesh: &Path, tree: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["build", s(mesh), "-o", s(tree)];
    args.extend_from_slice(extra);
    fpt(&args)
}

fn warnings(out: &Output) -> Vec<String> {
    stderr(out)
        .lines()
        .filter(|l| l.starts_with("warning: "))
        .map(str::to_string)
        .collect()
}

/// Renders `tree` through `mvp` (16 row-major numbers) and returns its
/// source-id buffer.
fn render_ids(tree: &Path, extra: &[&str], w: usize, h: usize) -> Vec<u32> {
    let ids = tmp(&format!(
        "{}-ids.bin",
        tree.file_name().unwrap().to_string_lossy()
    ));
    let png = tmp("ids-picture.png");
    let size = format!("{w}x{h}");
    let mut args = vec!["render", s(tree), "-o", s(&png), "--size", &size];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--ids", s(&ids)]);
    let out = fpt(&args);
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    std::fs::read(&ids)
        .unwrap()
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

#[test]
fn inside_out_part_is_flipped_with_one_warning_and_matches_a_zbuffer() {
    let text = three_cubes_one_inverted();
    let mesh = write("three.obj", &text);
    let tree = tmp("three.fpt");
    let out = build(&mesh, &tree, &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        warnings(&out),
        ["warning: 1 of 3 closed parts was inside out; flipped it (--keep-orientation keeps it)"]
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("closed static tree"));
    let kept = tmp("three-kept.fpt");
    let out = build(&mesh, &kept, &["--keep-orientation"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        warnings(&out),
        [
            "warning: 1 of 3 closed parts is inside out; kept as it is (--keep-orientation): \
          its inner walls are drawn"
        ]
    );

    // The z-buffer of the input as written (no culling: orientation plays
    // no part), ids mapped to source faces like `--ids`.
    let input = load_bytes(MeshFormat::Obj, text.as_bytes()).unwrap();
    let (w, h) = (160usize, 120usize);
    let cam = Camera::look_at(
        DVec3::new(2.0, 3.5, 6.0),
        DVec3::new(0.0, 0.5, 0.5),
        DVec3::Y,
        Projection::Perspective {
            fov_y_deg: 45.0,
            near: 0.1,
            far: 100.0,
        },
        w as f64 / h as f64,
    )
    .unwrap();
    let mut reference = zbuffer(&input.polygons, &cam, w, h, RefOptions::default());
    for id in reference.ids.iter_mut().filter(|id| **id != 0) {
        *id = input.polygons[*id as usize - 1].source + 1;
    }
    let mvp: Vec<String> = cam.mvp().iter().map(|v| format!("{v:e}")).collect();
    let mvp = mvp.join(",");
    let flipped = reference.diff(&render_ids(&tree, &["--mvp", &mvp], w, h));
    assert!(flipped.compared > w * h / 2, "{flipped:?}");
    assert_eq!(flipped.wrong, 0, "{flipped:?}");
    // Kept inside out, the middle cube shows its far walls: the test can
    // tell.
    let inside_out = reference.diff(&render_ids(&kept, &["--mvp", &mvp], w, h));
    assert!(inside_out.wrong > 100, "{inside_out:?}");
}

#[test]
fn a_whole_mesh_inside_out_is_flipped_too() {
    let text = cubes_obj(&[(DVec3::ZERO, true)], "");
    let mesh = write("inward.obj", &text);
    let out = build(&mesh, &tmp("inward.fpt"), &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        warnings(&out),
        ["warning: 1 of 1 closed part was inside out; flipped it (--keep-orientation keeps it)"]
    );
    let m = load_bytes(MeshFormat::Obj, text.as_bytes()).unwrap();
    for p in &m.polygons {
        let c = p.verts.iter().copied().sum::<DVec3>() / p.verts.len() as f64;
        assert!(p.plane.normal.dot(c - DVec3::splat(0.5)) > 0.0);
    }
    let opts = ImportOptions {
        keep_orientation: true,
        ..ImportOptions::default()
    };
    let m = host_sim::mesh::from_faces_with(
        &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        &[vec![0, 1, 2], vec![0, 3, 1], vec![1, 3, 2], vec![0, 2, 3]],
        None,
        &opts,
    )
    .unwrap();
    assert_eq!(
        (m.report.closed_parts, m.report.inverted_parts),
        (1, 1),
        "a tetrahedron wound inward"
    );
    assert!(m.report.orientation_kept);
}

#[test]
fn correct_meshes_get_no_warning() {
    let mesh = write("good.obj", CUBE_OBJ);
    let out = build(&mesh, &tmp("good.fpt"), &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(warnings(&out), Vec::<String>::new());
    // An open sheet alone is an ordinary open model.
    let sheet = write(
        "sheet.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
    );
    let out = build(&sheet, &tmp("sheet.fpt"), &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(warnings(&out), Vec::<String>::new());
}

#[test]
fn mixed_open_and_closed_parts_and_forced_closed_are_warned() {
    // A cube and, apart, a square sheet (4 boundary edges).
    let sheet = "v 5 0 0\nv 6 0 0\nv 6 1 0\nv 5 1 0\nf 9 10 11 12\n";
    let mesh = write("mixed.obj", &cubes_obj(&[(DVec3::ZERO, false)], sheet));
    let out = build(&mesh, &tmp("mixed.fpt"), &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        warnings(&out),
        [
            "warning: the mesh mixes 1 closed part with 1 open part (4 boundary edges); \
          it is built open: every face is drawn from both sides, none is culled"
        ]
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("open static tree"));
    let out = build(&mesh, &tmp("mixed-closed.fpt"), &["--closed"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let w = warnings(&out);
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(
        w[1].starts_with(
            "warning: --closed on a mesh with 4 boundary edges: back faces are culled"
        ),
        "{w:?}"
    );
    // --closed on a closed mesh says nothing.
    let cube = write("closed.obj", CUBE_OBJ);
    let out = build(&cube, &tmp("closed.fpt"), &["--closed"]);
    assert_eq!(warnings(&out), Vec::<String>::new());
}

/// The colours of a PNG.
/// A unit cube in OFF whose x faces are white, y faces mid grey and z
/// faces dark grey: drawn unlit to 4 grey levels with dithering, it uses all
/// four (white alone; 128 between levels 1 and 2; 40 between 0 and 1).
const GREY_CUBE_OFF: &str = "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n\
    4 0 3 2 1 40 40 40\n4 4 5 6 7 40 40 40\n4 0 1 5 4 128 128 128\n4 2 3 7 6 128 128 128\n\
    4 1 2 6 5 255 255 255\n4 3 0 4 7 255 255 255\n";

#[test]
fn panel_looks_keep_four_grey_levels() {
    let mesh = write("panel.off", GREY_CUBE_OFF);
    let tree = tmp("panel.fpt");
    assert!(build(&mesh, &tree, &[]).status.success());
    for panel in [
        "plain",
        "lcd-green",
        "lcd-white",
        "lcd-blue",
        "oled-blue",
        "oled-white",
    ] {
        let png = tmp(&format!("panel-{panel}.png"));
        let out = fpt(&[
            "render",
            s(&tree),
            "-o",
            s(&png),
            "--size",
            "64x48",
            "--yaw",
            "30",
            "--pitch",
            "20",
            "--format",
            "gray8",
            "--gray-levels",
            "4",
            "--shade",
            "flat",
            "--effects",
            "culling,dither",
            "--display",
            panel,
        ]);
        assert!(out.status.success(), "{panel}: {}", stderr(&out));
        let c = colours(&png);
        assert_eq!(c.len(), 4, "{panel}: {c:?}");
        // Mono stays two colours.
        let out = fpt(&[
            "render",
            s(&tree),
            "-o",
            s(&png),
            "--size",
            "64x48",
            "--yaw",
            "30",
            "--pitch",
            "20",
            "--format",
            "mono",
            "--shade",
            "flat",
            "--display",
            panel,
        ]);
        assert!(out.status.success(), "{panel}: {}", stderr(&out));
        assert_eq!(colours(&png).len(), 2, "{panel}");
    }
}

#[test]
fn bad_values_say_what_is_wrong() {
    let mesh = write("values.obj", CUBE_OBJ);
    let tree = tmp("values.fpt");
    assert!(build(&mesh, &tree, &[]).status.success());
    let png = tmp("values.png");
    let render = |extra: &[&str]| {
        let mut args = vec![
            "render",
            s(&tree),
            "-o",
            s(&png),
            "--yaw",
            "30",
            "--pitch",
            "20",
        ];
        args.extend_from_slice(extra);
        fpt(&args)
    };
    let e = error_line(&render(&["--fov", "-10"]), "--fov -10");
    assert!(
        e.contains("--fov must be in [0, 180) degrees, got -10"),
        "{e}"
    );
    let e = error_line(&render(&["--distance", "-3"]), "--distance -3");
    assert!(
        e.contains("--distance must be a positive number, got -3"),
        "{e}"
    );
    let e = error_line(&render(&["--band", "-1"]), "--band -1");
    assert!(e.contains("'-1'") && e.contains("--band"), "{e}");
    assert!(!e.contains("unexpected argument"), "{e}");
    let e = error_line(&render(&["--gray-levels", "-4"]), "--gray-levels -4");
    assert!(!e.contains("unexpected argument"), "{e}");
}

#[test]
fn file_errors_are_sentences() {
    // A tree file cut short: the reader's reason in words.
    let mesh = write("cut.obj", CUBE_OBJ);
    let tree = tmp("cut.fpt");
    assert!(build(&mesh, &tree, &[]).status.success());
    let mut bytes = std::fs::read(&tree).unwrap();
    bytes.truncate(bytes.len() - 7);
    let cut = tmp("cut-short.fpt");
    std::fs::write(&cut, bytes).unwrap();
    let png = tmp("cut.png");
    let out = fpt(&[
        "render",
        s(&cut),
        "-o",
        s(&png),
        "--yaw",
        "0",
        "--pitch",
        "0",
    ]);
    let e = error_line(&out, "cut tree");
    assert!(
        e.ends_with("not a valid tree file: file length differs from the header's"),
        "{e}"
    );
    assert!(!png.exists());

    // Text that is no OBJ at all.
    let junk = write(
        "junk.obj",
        "hello world\nthis is not a mesh\n# comment\n\nvertex 1 2 3\n",
    );
    let e = error_line(&build(&junk, &tmp("junk.fpt"), &[]), "junk");
    assert!(
        e.ends_with("no faces found in the OBJ file (3 lines not understood)"),
        "{e}"
    );
    let points = write("points.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
    let e = error_line(&build(&points, &tmp("points.fpt"), &[]), "points");
    assert!(e.ends_with("no faces found in the OBJ file"), "{e}");

    // A cube and one stray vertex at 1e30 that a face uses.
    let stray = write("stray.obj", &format!("{CUBE_OBJ}v 0 1e30 0\nf 1 2 9\n"));
    let e = error_line(&build(&stray, &tmp("stray.fpt"), &[]), "stray");
    assert!(
        e.contains("vertex 8 (from 0) at (0, 1e30, 0) is out of range"),
        "{e}"
    );
}
