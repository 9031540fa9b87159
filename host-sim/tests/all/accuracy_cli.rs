//! The accuracy numbers are honest: `fpt render --precision NAME --ids` run
//! as the real binary, compared here with the float64 reference by this
//! file's own loop, gives exactly the counts that `fpt bench-accuracy`'s
//! library ([`host_sim::cli::accuracy`]) reports for the same view; and
//! `fpt bench-accuracy` itself writes the CSV and the PNG.

use host_sim::cli::accuracy::{
    orbit_rows, reference_camera, rows_for, view_counts, views, Case, Config, Counts, ViewSpec,
    CONFIGS, CSV_HEADER, FOV_DEG,
};
use host_sim::reference::{zbuffer, RefOptions};
use std::path::{Path, PathBuf};

use crate::common;

use common::{fpt, tmp};

const W: u32 = 96;
const H: u32 = 72;

fn s(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

fn config(name: &str) -> Config {
    *CONFIGS
        .iter()
        .find(|c| c.name == name)
        .expect("configuration")
}

/// Pixel counts of `ids` against the reference of `case` seen through
/// `rows`, computed here without the library's comparison.
fn independent_counts(case: &Case, rows: &[[f64; 4]; 4], ids: &[u32]) -> Counts {
    let cam = reference_camera(rows).expect("camera");
    let opt = RefOptions {
        cull_backfaces: case.closed,
        ..RefOptions::default()
    };
    let f = zbuffer(&case.polygons, &cam, W as usize, H as usize, opt);
    let mut c = Counts::default();
    assert_eq!(ids.len(), f.ids.len());
    for (i, &got) in ids.iter().enumerate() {
        let want = match f.ids[i] {
            0 => 0,
            k => case.polygons[k as usize - 1].source + 1,
        };
        c.pixels += 1;
        if want != got {
            c.wrong_face += 1;
        }
        if !(f.near_edge[i] || f.tie[i]) {
            c.sure += 1;
            if want != got {
                c.wrong_sure += 1;
            }
        }
    }
    c
}

/// Renders `view` of the tree file `tree` with `fpt render` as `config`
/// does and returns the ids it wrote.
fn cli_ids(
    tree: &Path,
    tag: &str,
    config: &Config,
    view: ViewSpec,
    rows: &[[f64; 4]; 4],
) -> Vec<u32> {
    let ids = tmp(&format!("{tag}.ids"));
    let mut args: Vec<String> = vec![
        "render".into(),
        s(tree),
        "-o".into(),
        s(&tmp(&format!("{tag}.png"))),
        "--size".into(),
        format!("{W}x{H}"),
        "--precision".into(),
        // The row's own name (an alias) for render-time rows; vertex rows
        // differ by the tree file and render with the default arithmetic.
        if config.name.starts_with("vertex-") {
            config.precision.into()
        } else {
            config.name.into()
        },
        "--ids".into(),
        s(&ids),
        // The study measures the plain pipeline; `fpt render` draws
        // slivers unless told not to.
        "--no-slivers".into(),
    ];
    if config.orbit_trig {
        args.push(format!("--yaw={}", view.yaw));
        args.push(format!("--pitch={}", view.pitch));
        args.push(format!("--fov={FOV_DEG}"));
    } else {
        let flat: Vec<String> = rows.iter().flatten().map(|v| format!("{v:?}")).collect();
        args.push(format!("--mvp={}", flat.join(",")));
    }
    let out = fpt(&args);
    assert!(
        out.status.success(),
        "{tag}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let raw = std::fs::read(&ids).expect("ids file");
    assert_eq!(raw.len(), (W * H * 4) as usize);
    raw.chunks_exact(4)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

/// For each configuration and view: the CLI's ids, compared here, equal
/// the library's ids and counts; and the library's row for these views is
/// the sum of those counts.
fn check_case(case: &Case, tree_file: &Path, names: &[&str], vs: &[ViewSpec]) {
    let bytes = std::fs::read(tree_file).expect("tree file");
    let tree = fpt_nostd::reader::Tree::from_bytes(&bytes).expect("valid tree");
    let configs: Vec<Config> = names.iter().map(|n| config(n)).collect();
    let rows_lib = rows_for(std::slice::from_ref(case), &configs, vs, W, H).expect("rows");
    for (config, row) in configs.iter().zip(&rows_lib) {
        let mut sum = Counts::default();
        for (k, &v) in vs.iter().enumerate() {
            let rows = orbit_rows(&tree, v, W, H);
            let tag = format!("{}-{}-{k}", case.name, config.name);
            let ids = cli_ids(tree_file, &tag, config, v, &rows);
            let mine = independent_counts(case, &rows, &ids);
            let cam = reference_camera(&rows).expect("camera");
            let reference = host_sim::cli::accuracy::reference_frame(case, &cam, W, H);
            let (lib, lib_ids) = view_counts(case, config, v, &reference, &cam).expect("counts");
            assert_eq!(lib_ids, ids, "{tag}: library and CLI render differ");
            assert_eq!(
                (mine.pixels, mine.wrong_face, mine.sure, mine.wrong_sure),
                (lib.pixels, lib.wrong_face, lib.sure, lib.wrong_sure),
                "{tag}"
            );
            sum.add(&mine);
        }
        if config.name == "subpx-0" {
            // Whole-pixel snapping always costs some pixels: the equalities
            // above compare real errors, not zeros.
            assert!(sum.wrong_face > 0, "{sum:?}");
        }
        let r = &row.counts;
        assert_eq!(
            (sum.pixels, sum.wrong_face, sum.sure, sum.wrong_sure),
            (r.pixels, r.wrong_face, r.sure, r.wrong_sure),
            "{}: row",
            config.name
        );
        assert!(
            (r.wrong_face_frac() - sum.wrong_face as f64 / sum.pixels as f64).abs() < 1e-15,
            "{}",
            config.name
        );
    }
}

#[test]
fn fpt_render_ids_give_the_errors_the_study_reports() {
    let scene = host_sim::scenes::house();
    let case = Case::new(&scene.name, scene.polygons, scene.closed).expect("house");
    let tree_file = tmp("house.fpt");
    std::fs::write(
        &tree_file,
        case.tree_bytes(fpt_nostd::format::VertexFormat::F32)
            .expect("f32"),
    )
    .expect("write tree");
    let vs = views(2);
    check_case(
        &case,
        &tree_file,
        &["subpx-0", "f32-micromath", "trig-micromath"],
        &vs,
    );
}

#[test]
fn a_tree_from_fpt_build_q16_gives_the_vertex_q16_row() {
    let Some(model) = [PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../shared/models/shuttle.obj"
    ))]
    .into_iter()
    .find(|p| p.is_file()) else {
        // Not `println!`: the harness swallows what a passing test prints.
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "skipping: ../shared/models/shuttle.obj not found"
        );
        return;
    };
    let m = host_sim::mesh::load(&model).expect("shuttle loads");
    let case = Case::new("shuttle.obj", m.polygons, m.closed).expect("shuttle");
    let tree_file = tmp("shuttle-q16.fpt");
    let out = fpt(&[
        "build".into(),
        s(&model),
        "-o".into(),
        s(&tree_file),
        "--vertex-format".into(),
        "q16".into(),
        // The study pins narrow records (`accuracy::eval::tree_options`),
        // the default before session 27.
        "--records".into(),
        "narrow".into(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The study's q16 tree is the one `fpt build --vertex-format q16
    // --records narrow` writes.
    let built = std::fs::read(&tree_file).expect("tree");
    assert_eq!(
        built.as_slice(),
        case.tree_bytes(fpt_nostd::format::VertexFormat::Q16)
            .expect("q16")
    );
    check_case(&case, &tree_file, &["vertex-q16"], &views(1));
}

#[test]
fn bench_accuracy_writes_the_csv_and_the_plot() {
    let out_dir = tmp("bench");
    let out = fpt(&[
        "bench-accuracy".into(),
        "--out".into(),
        s(&out_dir),
        "--size".into(),
        "48x36".into(),
        "--views".into(),
        "1".into(),
        "--reps".into(),
        "1".into(),
        "--no-models".into(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(out_dir.join("accuracy.csv")).expect("csv");
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], CSV_HEADER);
    assert_eq!(lines.len(), CONFIGS.len() + 1);
    for (line, c) in lines[1..].iter().zip(CONFIGS) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 7, "{line}");
        assert_eq!(f[0], c.name);
        for v in &f[1..5] {
            let x: f64 = v.parse().expect("number");
            assert!(x.is_finite() && x >= 0.0, "{line}");
        }
    }
    let fixed = lines
        .iter()
        .find(|l| l.starts_with("fixed,"))
        .expect("fixed row");
    assert!(fixed.ends_with(",1.000,,"), "{fixed}");
    let png = std::fs::read(out_dir.join("accuracy.png")).expect("png");
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");

    // With the firmware's output, mcu_instr is the mean over its views.
    let mcu = out_dir.join("mcu.txt");
    let mut text = String::new();
    for c in CONFIGS {
        for k in 0..fpt_frames::VIEWS.len() {
            text.push_str(&format!(
                "accuracy config={} view={k} crc=00000000 instr={}\n",
                c.name,
                if c.name == "fixed" { 100 + 10 * k } else { 7 }
            ));
        }
    }
    std::fs::write(&mcu, &text).expect("mcu file");
    // And the Cortex-M0's output, m0_instr.
    let m0 = out_dir.join("m0.txt");
    std::fs::write(
        &m0,
        text.replace("instr=7", "instr=9")
            .replace("instr=1", "instr=3"),
    )
    .expect("m0 file");
    let args = |m: &Path| -> Vec<String> {
        [
            "bench-accuracy",
            "--out",
            &s(&out_dir),
            "--size",
            "48x36",
            "--views",
            "1",
            "--reps",
            "1",
            "--no-models",
            "--mcu",
            &s(m),
            "--m0",
            &s(&m0),
        ]
        .map(String::from)
        .to_vec()
    };
    let out = fpt(&args(&mcu));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(out_dir.join("accuracy.csv")).expect("csv");
    let fixed = csv
        .lines()
        .find(|l| l.starts_with("fixed,"))
        .expect("fixed");
    assert!(fixed.ends_with(",1.000,120,320"), "{fixed}");
    let other = csv
        .lines()
        .find(|l| l.starts_with("f32-libm,"))
        .expect("f32-libm");
    assert!(other.ends_with(",7,9"), "{other}");
    // A firmware output missing a configuration is an error (exit 2).
    std::fs::write(&mcu, text.replace("config=subpx-8", "config=other")).expect("mcu");
    let out = fpt(&args(&mcu));
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("subpx-8"));
}
