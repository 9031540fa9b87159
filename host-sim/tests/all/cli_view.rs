//! The picture a new user gets, through the real binary: colours from the
//! mesh file (OBJ materials, PLY face and vertex colours) or `--color`,
//! `--background`, the default camera of `fpt render`, the up axis a build
//! records, distances in bounding radii, negative angles, `fpt turntable`'s
//! GIF, `fpt view` without its cargo feature, and `error: ...` with exit
//! status 2 for every bad value.

use crate::common;

use common::{colours, error_line, fpt, s, stderr, tmp, CUBE_OBJ};
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::{Point, RgbColor};
use embedded_graphics_simulator::SimulatorDisplay;
use std::path::{Path, PathBuf};
use std::process::Output;

fn write(name: &str, text: &str) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn build(mesh: &Path, tree: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["build", s(mesh), "-o", s(tree)];
    args.extend_from_slice(extra);
    fpt(&args)
}

fn ok(out: &Output, what: &str) {
    assert!(out.status.success(), "{what}: {}", stderr(out));
}

/// The colour of every polygon of `tree`, by `fpt polygons`, with its
/// source face.
fn polygon_colours(tree: &Path) -> Vec<(u64, [u8; 3])> {
    let out = fpt(&["polygons", s(tree)]);
    ok(&out, "polygons");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["polygons"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let c = p["color"].as_array().unwrap();
            let c = [0, 1, 2].map(|i| c[i].as_u64().unwrap() as u8);
            (p["source"].as_u64().unwrap(), c)
        })
        .collect()
}

/// A unit cube in OBJ whose bottom and top use material `red`, the four
/// sides `blue`, with `mtllib cube.mtl`.
const MATERIAL_CUBE: &str = "mtllib cube.mtl\n\
    v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
    usemtl red\nf 1 4 3 2\nf 5 6 7 8\n\
    usemtl blue\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

#[test]
fn obj_materials_colour_the_faces() {
    let dir = tmp("mtl");
    std::fs::create_dir_all(&dir).unwrap();
    let obj = dir.join("cube.obj");
    std::fs::write(&obj, MATERIAL_CUBE).unwrap();
    std::fs::write(
        dir.join("cube.mtl"),
        "# two materials\nnewmtl red\nKa 0 0 0\nKd 0.8 0.1 0.1\n\nnewmtl blue\nKd 0.2 0.3 0.9\n",
    )
    .unwrap();
    let tree = dir.join("cube.fpt");
    let out = build(&obj, &tree, &[]);
    ok(&out, "build");
    assert!(stderr(&out).is_empty(), "{}", stderr(&out));
    let (red, blue) = ([204, 26, 26], [51, 77, 230]);
    for (source, c) in polygon_colours(&tree) {
        assert_eq!(c, if source < 2 { red } else { blue }, "face {source}");
    }
    // Unlit, on a chosen background, the picture shows exactly those.
    let png = dir.join("cube.png");
    let out = fpt(&[
        "render",
        s(&tree),
        "-o",
        s(&png),
        "--size",
        "64x48",
        "--shade",
        "flat",
        "--background",
        "10,20,30",
    ]);
    ok(&out, "render");
    let c = colours(&png);
    let want = [
        Rgb888::new(10, 20, 30),
        Rgb888::new(204, 26, 26),
        Rgb888::new(51, 77, 230),
    ];
    assert_eq!(c, want.into_iter().collect(), "{c:?}");

    // `--color` paints the whole mesh.
    let out = build(&obj, &tree, &["--color", "1,2,3"]);
    ok(&out, "build --color");
    assert!(polygon_colours(&tree).iter().all(|&(_, c)| c == [1, 2, 3]));

    // Without the material file: grey, and one warning line saying why.
    std::fs::remove_file(dir.join("cube.mtl")).unwrap();
    let out = build(&obj, &tree, &[]);
    ok(&out, "build without mtl");
    assert_eq!(
        stderr(&out).trim(),
        "warning: 1 material file named by mtllib was not found next to the OBJ file; \
         faces without a material colour are grey"
    );
    assert!(polygon_colours(&tree)
        .iter()
        .all(|&(_, c)| c == [200, 200, 200]));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn ply_face_and_vertex_colours() {
    // A tetrahedron with a colour per vertex; face 0 gets one of its own.
    let ply = write(
        "coloured.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\n\
         property float x\nproperty float y\nproperty float z\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face 4\nproperty list uchar int vertex_indices\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n\
         0 0 0 0 0 0\n1 0 0 240 0 0\n0 1 0 0 240 0\n0 0 1 0 0 240\n\
         3 0 2 1 7 8 9\n3 0 1 3 0 0 0\n3 1 2 3 0 0 0\n3 0 3 2 0 0 0\n",
    );
    // Face colours (the second to fourth are black, given explicitly).
    let tree = tmp("coloured.fpt");
    ok(&build(&ply, &tree, &[]), "build");
    for (source, c) in polygon_colours(&tree) {
        assert_eq!(c, if source == 0 { [7, 8, 9] } else { [0, 0, 0] });
    }
    // Vertex colours only: each face the mean of its corners.
    let vertex_only = write(
        "vertex-coloured.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\n\
         property float x\nproperty float y\nproperty float z\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face 4\nproperty list uchar int vertex_indices\nend_header\n\
         0 0 0 0 0 0\n1 0 0 240 0 0\n0 1 0 0 240 0\n0 0 1 0 0 240\n\
         3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n",
    );
    ok(&build(&vertex_only, &tree, &[]), "build vertex colours");
    let want = [[80, 80, 0], [80, 0, 80], [80, 80, 80], [0, 80, 80]];
    for (source, c) in polygon_colours(&tree) {
        assert_eq!(c, want[source as usize], "face {source}");
    }
}

/// The header byte `up_axis` of a tree file.
fn up_code(tree: &Path) -> u8 {
    std::fs::read(tree).unwrap()[fpt_nostd::format::header::UP_AXIS]
}

/// A closed box 1 × 2 × 4 as ASCII STL (no two axes alike, so every up
/// axis shows it differently).
fn box_stl() -> String {
    let v = [
        [0., 0., 0.],
        [1., 0., 0.],
        [1., 1., 0.],
        [0., 1., 0.],
        [0., 0., 1.],
        [1., 0., 1.],
        [1., 1., 1.],
        [0., 1., 1.],
    ];
    let quads = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    let mut t = String::from("solid cube\n");
    for q in quads {
        for tri in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            t += "facet normal 0 0 0\nouter loop\n";
            for i in tri {
                let p: [f64; 3] = v[i];
                t += &format!("vertex {} {} {}\n", p[0], 2.0 * p[1], 4.0 * p[2]);
            }
            t += "endloop\nendfacet\n";
        }
    }
    t + "endsolid cube\n"
}

#[test]
fn builds_record_the_up_axis_and_renders_use_it() {
    let obj = write("up.obj", CUBE_OBJ);
    let stl = write("up.stl", &box_stl());
    let t = |n: &str| tmp(n);
    ok(&build(&obj, &t("up-obj.fpt"), &[]), "obj");
    ok(&build(&stl, &t("up-stl.fpt"), &[]), "stl");
    ok(&build(&stl, &t("up-stl-y.fpt"), &["--up", "y"]), "stl y");
    ok(&build(&obj, &t("up-obj-x.fpt"), &["--up", "x"]), "obj x");
    assert_eq!(up_code(&t("up-obj.fpt")), 0, "OBJ: y");
    assert_eq!(up_code(&t("up-stl.fpt")), 2, "STL: z");
    assert_eq!(up_code(&t("up-stl-y.fpt")), 0);
    assert_eq!(up_code(&t("up-obj-x.fpt")), 1);
    let info = fpt(&["info", s(&t("up-stl.fpt"))]);
    assert!(String::from_utf8_lossy(&info.stdout).contains("up axis:           z"));

    // `--up auto` (the default) is what the tree records; the STL tree
    // seen with its default equals the y-up tree seen with `--up z`.
    let render = |tree: &str, png: &str, extra: &[&str]| -> Vec<u8> {
        let png = t(png);
        let tree = t(tree);
        let mut args = vec!["render", s(&tree), "-o", s(&png), "--size", "48x36"];
        args.extend_from_slice(extra);
        ok(&fpt(&args), png.to_str().unwrap());
        std::fs::read(&png).unwrap()
    };
    let a = render("up-stl.fpt", "up-a.png", &[]);
    let b = render("up-stl-y.fpt", "up-b.png", &["--up", "z"]);
    let c = render("up-stl-y.fpt", "up-c.png", &[]);
    assert_eq!(a, b);
    assert_ne!(a, c, "the up axis changes the picture");
    let x = render("up-stl.fpt", "up-x.png", &["--up", "x"]);
    assert_ne!(a, x);
}

#[test]
fn render_defaults_negative_angles_and_distance_units() {
    let obj = write("defaults.obj", CUBE_OBJ);
    let tree = tmp("defaults.fpt");
    ok(&build(&obj, &tree, &[]), "build");
    let render = |png: &str, extra: &[&str]| -> Vec<u8> {
        let png = tmp(png);
        let mut args = vec!["render", s(&tree), "-o", s(&png), "--size", "64x48"];
        args.extend_from_slice(extra);
        ok(&fpt(&args), &format!("{extra:?}"));
        std::fs::read(&png).unwrap()
    };
    // No camera option: the three-quarter view at 3 radii.
    let default = render("d0.png", &[]);
    let explicit = render(
        "d1.png",
        &["--yaw", "35", "--pitch", "25", "--distance", "3"],
    );
    assert_eq!(default, explicit);
    // The whole cube is in the picture: no model pixel on the border.
    let d = SimulatorDisplay::<Rgb888>::load_png(tmp("d0.png")).unwrap();
    let black = Rgb888::new(0, 0, 0);
    let px = |x: i32, y: i32| d.get_pixel(Point::new(x, y));
    assert!((0..64).all(|x| px(x, 0) == black && px(x, 47) == black));
    assert!((0..48).all(|y| px(0, y) == black && px(63, y) == black));
    assert!(colours(&tmp("d0.png")).len() > 2, "the cube is drawn");
    // Negative angles in both spellings.
    let neg = render("neg1.png", &["--pitch", "-20", "--yaw=-30"]);
    let neg2 = render("neg2.png", &["--pitch=-20", "--yaw", "-30"]);
    assert_eq!(neg, neg2);
    assert_ne!(neg, default);
    // `--distance` is in bounding radii: the same view in model units.
    // The cube's bounding radius is √3/2 (the file stores it rounded up).
    let t = fpt_nostd::reader::Tree::from_bytes(&std::fs::read(&tree).unwrap())
        .unwrap()
        .bounding_radius();
    let model = format!("{}", 4.0 * f64::from(t));
    let radii = render("r4.png", &["--distance", "4"]);
    let units = render(
        "m4.png",
        &["--distance", &model, "--distance-units", "model"],
    );
    assert_eq!(radii, units);
    assert_ne!(radii, default);
    // A tall picture: the default moves back so the cube still fits.
    let png = tmp("tall.png");
    ok(
        &fpt(&["render", s(&tree), "-o", s(&png), "--size", "30x80"]),
        "tall",
    );
    let d = SimulatorDisplay::<Rgb888>::load_png(&png).unwrap();
    assert!(
        (0..80)
            .all(|y| d.get_pixel(Point::new(0, y)) == black
                && d.get_pixel(Point::new(29, y)) == black)
    );
}

#[test]
fn bad_values_are_one_line_errors_and_leave_no_file() {
    let obj = write("bad.obj", CUBE_OBJ);
    let tree = tmp("bad.fpt");
    ok(&build(&obj, &tree, &[]), "build");
    let png = tmp("bad.png");
    let gif = tmp("bad.gif");
    let junk = write("junk.fpt", "not a tree");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["render", s(&tree), "-o", s(&png), "--pitch", "abc"],
            "'abc'",
        ),
        (
            vec!["render", s(&tree), "-o", s(&png), "--yaw", "inf"],
            "--yaw and --pitch must be finite",
        ),
        (vec!["render", s(&tree), "-o", s(&png), "--up", "w"], "'w'"),
        (
            vec!["render", s(&tree), "-o", s(&png), "--background", "1,2"],
            "--background needs R,G,B",
        ),
        (
            vec!["render", s(&tree), "-o", s(&png), "--background", "0,0,256"],
            "'256' is not a whole number in 0-255",
        ),
        (
            vec!["render", s(&tree), "-o", s(&png), "--distance", "-2"],
            "--distance must be a positive number, got -2",
        ),
        (
            vec!["render", s(&tree), "-o", s(&png), "--distance", "1e39"],
            "--distance is too large",
        ),
        (
            vec![
                "render",
                s(&tree),
                "-o",
                s(&png),
                "--distance-units",
                "parsecs",
            ],
            "'parsecs'",
        ),
        (
            vec!["render", s(&tree), "-o", s(&png), "--fov", "-5"],
            "--fov must be in [0, 180) degrees",
        ),
        (vec!["build", s(&obj), "-o", s(&tree), "--up", "q"], "'q'"),
        (
            vec!["build", s(&obj), "-o", s(&tree), "--color", "255,0,-1"],
            "'-1' is not a whole number",
        ),
        (
            vec!["build", s(&obj), "-o", s(&tree), "--color", "red"],
            "--color needs R,G,B",
        ),
        (
            vec!["turntable", s(&tree), "-o", s(&gif), "--frames", "0"],
            "--frames must be in 1..=3600, got 0",
        ),
        (
            vec!["turntable", s(&tree), "-o", s(&gif), "--frames", "-4"],
            "'-4'",
        ),
        (
            vec!["turntable", s(&tree), "-o", s(&gif), "--fps", "99"],
            "--fps must be in 1..=50, got 99",
        ),
        (
            vec!["turntable", s(&tree), "-o", s(&gif), "--size", "5000x10"],
            "at most 4096 pixels a side",
        ),
        (
            vec!["turntable", s(&tree), "-o", s(&gif), "--pitch", "x"],
            "'x'",
        ),
        (
            vec!["turntable", s(&junk), "-o", s(&gif)],
            "not a valid tree file",
        ),
        (
            vec!["turntable", "/nonexistent/t.fpt", "-o", s(&gif)],
            "/nonexistent/t.fpt",
        ),
    ];
    for (args, want) in cases {
        let e = error_line(&fpt(&args), &format!("{args:?}"));
        assert!(e.contains(want), "{args:?}: {e}");
        assert!(!e.contains("unexpected argument"), "{args:?}: {e}");
    }
    assert!(!png.exists() && !gif.exists());
    // The bad build left the good tree as it was.
    assert!(fpt_nostd::reader::Tree::from_bytes(&std::fs::read(&tree).unwrap()).is_ok());
}

#[test]
fn turntable_writes_a_looping_gif_of_n_frames() {
    let obj = write(
        "spin.obj",
        MATERIAL_CUBE.replace("mtllib cube.mtl\n", "").as_str(),
    );
    let tree = tmp("spin.fpt");
    ok(&build(&obj, &tree, &["--color", "200,120,40"]), "build");
    let gif = tmp("spin.gif");
    let out = fpt(&[
        "turntable",
        s(&tree),
        "-o",
        s(&gif),
        "--frames",
        "12",
        "--size",
        "40x30",
        "--fps",
        "20",
        "--background",
        "0,0,64",
    ]);
    ok(&out, "turntable");
    let bytes = std::fs::read(&gif).unwrap();
    assert!(bytes.starts_with(b"GIF89a"));
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut d = opts.read_info(&bytes[..]).unwrap();
    assert_eq!((d.width(), d.height()), (40, 30));
    let mut frames = Vec::new();
    while let Some(f) = d.read_next_frame().unwrap() {
        assert_eq!((f.width, f.height, f.delay), (40, 30, 5));
        frames.push(f.buffer.to_vec());
    }
    assert_eq!(frames.len(), 12);
    // The corner is the background; the cube turns: frames differ.
    for f in &frames {
        assert_eq!(&f[..4], &[0, 0, 64, 255]);
    }
    assert_ne!(frames[0], frames[1]);
    // Frame 0 is `fpt render` of the same view.
    let png = tmp("spin0.png");
    ok(
        &fpt(&[
            "render",
            s(&tree),
            "-o",
            s(&png),
            "--size",
            "40x30",
            "--background",
            "0,0,64",
        ]),
        "render",
    );
    let p = SimulatorDisplay::<Rgb888>::load_png(&png).unwrap();
    for (i, px) in frames[0].chunks_exact(4).enumerate() {
        let c = p.get_pixel(Point::new((i % 40) as i32, (i / 40) as i32));
        assert_eq!(&px[..3], &[c.r(), c.g(), c.b()], "pixel {i}");
    }
}

/// Without the `view` cargo feature (the default build), `fpt view` is an
/// error naming the feature, exit status 2, and opens nothing.
#[cfg(not(feature = "view"))]
#[test]
fn view_without_the_feature_names_it() {
    let obj = write("view.obj", CUBE_OBJ);
    let tree = tmp("view.fpt");
    ok(&build(&obj, &tree, &[]), "build");
    let out = fpt(&["view", s(&tree)]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let e = error_line(&out, "view");
    assert!(
        e.contains("`view` cargo feature") && e.contains("--features view"),
        "{e}"
    );
    // The options are those of `fpt render`'s orbit: they parse.
    let out = fpt(&[
        "view",
        s(&tree),
        "--yaw=-30",
        "--size",
        "64x48",
        "--frames",
        "2",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(error_line(&out, "view").contains("`view` cargo feature"));
}
