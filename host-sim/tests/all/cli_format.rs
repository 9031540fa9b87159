//! `fpt info`, `fpt polygons`, `fpt order` and `fpt bench-order` on tree
//! files written by the serializer, run as the real binary.

use std::path::PathBuf;

use crate::common;

use common::fpt;

use glam::DVec3;
use host_sim::build::{build, NoProgress};
use host_sim::geom::Polygon;
use host_sim::serialize::{serialize, SerializeOptions, VertexFormat};
use host_sim::tree::Method;
use serde_json::Value;

const ORIGIN: DVec3 = DVec3::new(1e5, -2e5, 3e5);

/// The unit cube `[0, 1]^3` moved by `ORIGIN`, faces outward; source i is
/// the face with normal `±axis`: 0 −x, 1 +x, 2 −y, 3 +y, 4 −z, 5 +z.
fn cube() -> Vec<Polygon> {
    let c = |x: f64, y: f64, z: f64| DVec3::new(x, y, z) + ORIGIN;
    let faces = [
        [c(0., 0., 0.), c(0., 0., 1.), c(0., 1., 1.), c(0., 1., 0.)],
        [c(1., 0., 0.), c(1., 1., 0.), c(1., 1., 1.), c(1., 0., 1.)],
        [c(0., 0., 0.), c(1., 0., 0.), c(1., 0., 1.), c(0., 0., 1.)],
        [c(0., 1., 0.), c(0., 1., 1.), c(1., 1., 1.), c(1., 1., 0.)],
        [c(0., 0., 0.), c(0., 1., 0.), c(1., 1., 0.), c(1., 0., 0.)],
        [c(0., 0., 1.), c(1., 0., 1.), c(1., 1., 1.), c(0., 1., 1.)],
    ];
    faces
        .iter()
        .enumerate()
        .map(|(i, f)| Polygon::new(f.to_vec(), i as u32, [9, 9, 9]).unwrap())
        .collect()
}

/// Writes the cube's tree in `format` to a fresh temporary file.
fn cube_file(name: &str, format: VertexFormat) -> PathBuf {
    let tree = build(cube(), true, Method::Static, 1, &mut NoProgress);
    let opts = SerializeOptions {
        vertex_format: format,
        effects: Some(3),
        ..SerializeOptions::default()
    };
    let bytes = serialize(&tree, &opts).unwrap();
    let path =
        std::env::temp_dir().join(format!("fpt-cli-format-{}-{name}.fpt", std::process::id()));
    std::fs::write(&path, bytes).unwrap();
    path
}

fn json_ok(args: &[&str]) -> Value {
    let out = fpt(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Exit status 2 and one line `error: ...` on stderr; returns the line.
fn fails(args: &[&str]) -> String {
    let out = fpt(args);
    assert_eq!(out.status.code(), Some(2), "{args:?}");
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.starts_with("error: "), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    err
}

/// The source face of every id, from `fpt polygons`.
fn sources_by_id(path: &str) -> Vec<u64> {
    let v = json_ok(&["polygons", path]);
    v["polygons"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["source"].as_u64().unwrap())
        .collect()
}

/// The classes of `fpt order`, as source faces.
fn order_sources(path: &str, view: &[&str]) -> Vec<Vec<u64>> {
    let sources = sources_by_id(path);
    let mut args = vec!["order", path];
    args.extend_from_slice(view);
    let v = json_ok(&args);
    v["classes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let mut s: Vec<u64> = c
                .as_array()
                .unwrap()
                .iter()
                .map(|id| sources[id.as_u64().unwrap() as usize])
                .collect();
            s.sort_unstable();
            s
        })
        .collect()
}

#[test]
fn polygons_prints_model_coordinates() {
    let path = cube_file("polygons", VertexFormat::F32);
    let v = json_ok(&["polygons", path.to_str().unwrap()]);
    assert_eq!(v["closed"], Value::Bool(true));
    let polys = v["polygons"].as_array().unwrap();
    assert_eq!(polys.len(), 6);
    let mut sources: Vec<u64> = Vec::new();
    for (i, p) in polys.iter().enumerate() {
        assert_eq!(p["id"].as_u64(), Some(i as u64));
        let source = p["source"].as_u64().unwrap();
        sources.push(source);
        let verts = p["vertices"].as_array().unwrap();
        assert_eq!(verts.len(), 4);
        // The face with normal ±axis has that coordinate constant.
        let axis = source as usize / 2;
        let side = (source % 2) as f64;
        for vert in verts {
            let xyz: Vec<f64> = vert
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            // Exact: offsets of ±0.5 from the f64 origin are exact in f32.
            assert_eq!(xyz[axis], ORIGIN[axis] + side, "{p}");
            for a in 0..3 {
                assert!(xyz[a] == ORIGIN[a] || xyz[a] == ORIGIN[a] + 1.0, "{p}");
            }
        }
    }
    sources.sort_unstable();
    assert_eq!(sources, [0, 1, 2, 3, 4, 5]);
    std::fs::remove_file(path).ok();
}

#[test]
fn order_culls_and_sorts_for_both_projections() {
    let path = cube_file("order", VertexFormat::Q16);
    let p = path.to_str().unwrap();
    // Looking down: only +z faces the viewer; the sides are edge-on (forward).
    assert_eq!(order_sources(p, &["--view-dir", "0,0,-1"]), [[5]]);
    // Looking along (-1,-1,-2): +x, +y and +z face the viewer.
    let seen: Vec<u64> = order_sources(p, &["--view-dir", "-1,-1,-2"]).concat();
    let mut seen = seen;
    seen.sort_unstable();
    assert_eq!(seen, [1, 3, 5]);
    // An eye above the top face's centre, in f64 model coordinates.
    let eye = format!("{},{},{}", ORIGIN.x + 0.5, ORIGIN.y + 0.5, ORIGIN.z + 5.0);
    assert_eq!(order_sources(p, &["--eye", &eye]), [[5]]);
    // An eye just outside the -x face: only that face.
    let eye = format!("{},{},{}", ORIGIN.x - 0.01, ORIGIN.y + 0.5, ORIGIN.z + 0.5);
    assert_eq!(order_sources(p, &["--eye", &eye]), [[0]]);
    std::fs::remove_file(path).ok();
}

#[test]
fn info_describes_the_file() {
    let path = cube_file("info", VertexFormat::Q32);
    let out = fpt(&["info", path.to_str().unwrap()]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let field = |name: &str| {
        text.lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_else(|| panic!("no {name} in {text}"))
            .split_once(':')
            .unwrap()
            .1
            .trim()
            .to_string()
    };
    assert_eq!(field("volume"), "closed");
    assert_eq!(field("polygons"), "6");
    assert_eq!(field("vertices"), "8");
    // Six faces, six planes: one run each.
    assert_eq!(field("plane runs"), "6");
    assert_eq!(field("effects"), "0x00000003 (culling,two-sided)");
    assert!(field("vertex format").starts_with("q32"));
    let size = std::fs::metadata(&path).unwrap().len();
    assert!(field("format").contains(&format!("{size} bytes")));
    // The renderer's capacities for this tree, from its header: convex
    // quads (4 vertices) need a scratch of 4 + 5 = 9, the walk its depth.
    let depth = field("max depth");
    let needs = field("renderer needs");
    assert!(
        needs.starts_with("TreeRenderer<P, 9> (vertex capacity V = 9), walk stack N = "),
        "{needs}"
    );
    assert!(needs.contains(&format!("N = {depth} (")), "{needs}");
    assert_eq!(field("largest polygon"), "4 vertices");
    std::fs::remove_file(path).ok();
}

#[test]
fn bench_order_reports_per_view_figures() {
    let path = cube_file("bench", VertexFormat::F32);
    let v = json_ok(&[
        "bench-order",
        path.to_str().unwrap(),
        "--views",
        "64",
        "--min-seconds",
        "0.05",
    ]);
    assert_eq!(v["views"].as_u64(), Some(64));
    assert_eq!(v["polygons"].as_u64(), Some(6));
    assert!(v["ns_per_view"].as_f64().unwrap() > 0.0);
    // A generic direction sees exactly 3 faces of a cube.
    let emitted = v["emitted_per_view"].as_f64().unwrap();
    assert!((2.5..=3.0).contains(&emitted), "{emitted}");
    assert!(v["classes_per_view"].as_f64().unwrap() >= 1.0);
    assert!(v["passes"].as_u64().unwrap() >= 1);
    // The tree's counts, as `fpt info` gives them.
    assert_eq!(v["runs"].as_u64(), Some(6));
    let (nodes, switches) = (
        v["nodes"].as_u64().unwrap(),
        v["switches"].as_u64().unwrap(),
    );
    assert_eq!(nodes, 2 * switches + 1);
    assert!(v["bunches"].as_u64().unwrap() >= 1 && v["levels"].as_u64().is_some());
    std::fs::remove_file(path).ok();
}

#[test]
fn bad_files_and_arguments_exit_2() {
    let path = cube_file("bad", VertexFormat::F32);
    let p = path.to_str().unwrap();
    fails(&["order", p]);
    assert!(fails(&["order", p, "--view-dir", "0,0,0"]).contains("non-zero"));
    fails(&["order", p, "--view-dir", "0,0,1", "--eye", "1,2,3"]);
    fails(&["order", p, "--view-dir", "0,nan,1"]);
    fails(&["bench-order", p, "--views", "0"]);

    let mut bytes = std::fs::read(&path).unwrap();
    bytes[120] ^= 0x40;
    let corrupt = path.with_extension("corrupt");
    std::fs::write(&corrupt, &bytes).unwrap();
    let c = corrupt.to_str().unwrap();
    assert!(fails(&["info", c]).contains("CRC"));
    fails(&["order", c, "--view-dir", "0,0,1"]);
    fails(&["polygons", c]);
    fails(&["bench-order", c]);

    std::fs::write(&corrupt, &bytes[..bytes.len() / 2]).unwrap();
    fails(&["info", c]);
    std::fs::write(&corrupt, b"not a tree").unwrap();
    assert!(fails(&["info", c]).contains("too short"));
    fails(&["info", "/nonexistent/tree.fpt"]);
    std::fs::remove_file(path).ok();
    std::fs::remove_file(corrupt).ok();
}

/// Boxes of several heights on a 3 × 3 grid, as one OBJ: a concave scene
/// whose trees have switch nodes and empty bunches.
fn boxes_obj() -> String {
    let mut obj = String::new();
    let mut base = 0;
    for i in 0..9 {
        let (x, z) = (f64::from(i % 3) * 1.5, f64::from(i / 3) * 1.5);
        let h = 1.0 + f64::from((i * 5) % 4) * 0.7;
        for (dx, dy, dz) in [
            (0., 0., 0.),
            (1., 0., 0.),
            (1., h, 0.),
            (0., h, 0.),
            (0., 0., 1.),
            (1., 0., 1.),
            (1., h, 1.),
            (0., h, 1.),
        ] {
            obj += &format!("v {} {} {}\n", x + dx, dy, z + dz);
        }
        for f in [
            [1, 4, 3, 2],
            [5, 6, 7, 8],
            [1, 2, 6, 5],
            [2, 3, 7, 6],
            [3, 4, 8, 7],
            [4, 1, 5, 8],
        ] {
            let f = f.map(|v| (v + base).to_string());
            obj += &format!("f {}\n", f.join(" "));
        }
        base += 8;
    }
    obj
}

/// `fpt info`'s counts as name → number (the first number of each line).
fn info_counts(tree: &str) -> std::collections::HashMap<String, u64> {
    let out = fpt(&["info", tree]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut m = std::collections::HashMap::new();
    for line in text.lines() {
        let Some((key, rest)) = line.split_once(':') else {
            continue;
        };
        if let Some(n) = rest.split_whitespace().next().and_then(|w| w.parse().ok()) {
            m.insert(key.trim().to_string(), n);
        }
        // "bunches: N (M non-empty)"
        if key.trim() == "bunches" {
            let m2 = rest
                .split('(')
                .nth(1)
                .and_then(|r| r.split_whitespace().next());
            m.insert(
                "non-empty bunches".to_string(),
                m2.and_then(|w| w.parse().ok()).expect("non-empty count"),
            );
        }
    }
    m
}

/// Issue 15 item 7: the stats file of `fpt build --stats` and `fpt info`
/// of the tree it wrote agree on every count they both give (the stats
/// file used to count only the non-empty bunches, `fpt info` all the
/// stored ones: 76 against 129 on a CAD part).
#[test]
fn info_and_stats_agree_on_every_count() {
    let dir = std::env::temp_dir();
    let mesh = dir.join(format!("fpt-cli-format-{}-boxes.obj", std::process::id()));
    std::fs::write(&mesh, boxes_obj()).unwrap();
    let mut saw_empty = false;
    for method in ["static", "dynamic", "bsp"] {
        let tree = dir.join(format!(
            "fpt-cli-format-{}-boxes-{method}.fpt",
            std::process::id()
        ));
        let stats = dir.join(format!(
            "fpt-cli-format-{}-boxes-{method}.json",
            std::process::id()
        ));
        let out = fpt(&[
            "build",
            mesh.to_str().unwrap(),
            "-o",
            tree.to_str().unwrap(),
            "--method",
            method,
            "--stats",
            stats.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: Value = serde_json::from_slice(&std::fs::read(&stats).unwrap()).unwrap();
        let info = info_counts(tree.to_str().unwrap());
        for (stat, line) in [
            ("output_polygons", "polygons"),
            ("connecting_nodes", "connecting nodes"),
            ("switch_nodes", "switch nodes"),
            ("levels", "levels"),
            ("bunches", "bunches"),
            ("nonempty_bunches", "non-empty bunches"),
            ("max_depth", "max depth"),
        ] {
            assert_eq!(
                v[stat].as_u64(),
                info.get(line).copied(),
                "{method}: stats {stat} against info {line}"
            );
        }
        let closed = info_volume_closed(tree.to_str().unwrap());
        assert_eq!(v["closed"].as_bool(), Some(closed), "{method}: volume");
        // bench-order's JSON gives the same counts.
        let b = json_ok(&["bench-order", tree.to_str().unwrap(), "--views", "4"]);
        for key in ["bunches", "nonempty_bunches", "levels", "switch_nodes"] {
            let k = if key == "switch_nodes" {
                "switches"
            } else {
                key
            };
            assert_eq!(b[k].as_u64(), v[key].as_u64(), "{method}: bench-order {k}");
        }
        saw_empty |= v["bunches"].as_u64() > v["nonempty_bunches"].as_u64();
        std::fs::remove_file(tree).ok();
        std::fs::remove_file(stats).ok();
    }
    // The case the issue saw: empty bunches stored, so the two counts differ.
    assert!(saw_empty, "no tree of the boxes has an empty bunch");
    std::fs::remove_file(mesh).ok();
}

/// Whether `fpt info` says the volume is closed.
fn info_volume_closed(tree: &str) -> bool {
    let out = fpt(&["info", tree]);
    let text = String::from_utf8(out.stdout).unwrap();
    text.lines()
        .find_map(|l| l.strip_prefix("volume:"))
        .map(|v| v.trim() == "closed")
        .expect("a volume line")
}
