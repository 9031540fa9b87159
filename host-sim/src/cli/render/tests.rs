//! Tests of `fpt render`: argument checks, exit statuses and the files.

use super::*;
use crate::build::{build, NoProgress};
use crate::cli::main_with_args;
use crate::scenes;
use crate::serialize::{serialize, SerializeOptions};
use std::path::PathBuf;

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("fpt-render-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    if let Err(e) = std::fs::create_dir_all(&d) {
        panic!("{}: {e}", d.display());
    }
    d
}

/// The house scene's tree file in `dir`.
fn house_tree(dir: &Path) -> PathBuf {
    let s = scenes::house();
    let t = build(
        s.polygons,
        s.closed,
        crate::tree::Method::Static,
        1,
        &mut NoProgress,
    );
    let bytes = match serialize(&t, &SerializeOptions::default()) {
        Ok(b) => b,
        Err(e) => panic!("{e}"),
    };
    let p = dir.join("house.fpt");
    if let Err(e) = std::fs::write(&p, bytes) {
        panic!("{e}");
    }
    p
}

fn fpt(args: &[&str]) -> i32 {
    let mut v = vec!["fpt", "render"];
    v.extend_from_slice(args);
    main_with_args(v)
}

fn read(p: &Path) -> Vec<u8> {
    std::fs::read(p).unwrap_or_default()
}

#[test]
fn sizes_and_matrices_are_checked() {
    assert_eq!(parse_size("320x240").ok(), Some((320, 240)));
    assert_eq!(parse_size("8X9").ok(), Some((8, 9)));
    for bad in ["0x10", "10x0", "10", "ax3", "-1x4", "99999x2"] {
        assert!(parse_size(bad).is_err(), "{bad}");
    }
    let id = "1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1";
    assert!(parse_mvp(id).is_ok());
    assert!(parse_mvp("1,0,0,0,0,1,0,0,0,0,1,0,0,0,0").is_err());
    assert!(parse_mvp("1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,NaN").is_err());
    assert!(parse_mvp("1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,inf").is_err());
    assert!(parse_mvp("1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1e300").is_err());
    // Two equal rows: singular.
    assert!(parse_mvp("1,0,0,0,1,0,0,0,0,0,1,0,0,0,0,1").is_err());
    assert!(parse_mvp("0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0").is_err());
}

#[test]
fn renders_png_and_ids_identically_with_and_without_bands() {
    let d = scratch("bands");
    let tree = house_tree(&d);
    let t = tree.to_string_lossy().into_owned();
    let (a, b) = (d.join("a.png"), d.join("b.png"));
    let (ia, ib) = (d.join("a.bin"), d.join("b.bin"));
    let common = ["--size", "64x48", "--yaw", "30", "--pitch", "20"];
    let pa = a.to_string_lossy().into_owned();
    let pia = ia.to_string_lossy().into_owned();
    let mut args = vec![t.as_str(), "-o", &pa, "--ids", &pia];
    args.extend_from_slice(&common);
    assert_eq!(fpt(&args), 0);
    let pb = b.to_string_lossy().into_owned();
    let pib = ib.to_string_lossy().into_owned();
    let mut args = vec![t.as_str(), "-o", &pb, "--ids", &pib, "--band", "5"];
    args.extend_from_slice(&common);
    assert_eq!(fpt(&args), 0);
    let png = read(&a);
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
    assert_eq!(png, read(&b));
    let ids = read(&ia);
    assert_eq!(ids.len(), 64 * 48 * 4);
    assert_eq!(ids, read(&ib));
    let words: Vec<u32> = ids
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let faces = scenes::house().polygons.len() as u32;
    assert!(words.iter().all(|&v| v <= faces));
    let covered = words.iter().filter(|&&v| v != 0).count();
    assert!(covered > 64 * 48 / 10 && covered < 64 * 48, "{covered}");
    // No temporary file is left behind.
    let left = std::fs::read_dir(&d).map_or(0, |r| r.count());
    assert_eq!(left, 5);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn every_format_and_precision_renders() {
    let d = scratch("formats");
    let tree = house_tree(&d);
    let t = tree.to_string_lossy().into_owned();
    let o = d.join("x.png").to_string_lossy().into_owned();
    let base = [
        t.as_str(),
        "-o",
        &o,
        "--size",
        "40x30",
        "--yaw",
        "10",
        "--pitch",
        "5",
    ];
    for f in ["rgb565", "rgb888", "gray8", "mono"] {
        assert_eq!(fpt(&[&base[..], &["--format", f]].concat()), 0, "{f}");
    }
    for p in PRECISIONS {
        let args = [&base[..], &["--precision", p, "--fov", "0"]].concat();
        assert_eq!(fpt(&args), 0, "{p}");
    }
    // A matrix camera, and one with the eye inside the model.
    let mvp = "1,0,0,0,0,1,0,0,0,0,-1,-0.2,0,0,-1,0";
    assert_eq!(fpt(&[t.as_str(), "-o", &o, "--mvp", mvp]), 0);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bad_input_exits_with_status_2() {
    let d = scratch("bad");
    let tree = house_tree(&d);
    let t = tree.to_string_lossy().into_owned();
    let o = d.join("x.png").to_string_lossy().into_owned();
    let junk = d.join("junk.fpt");
    let _ = std::fs::write(&junk, b"not a tree");
    let j = junk.to_string_lossy().into_owned();
    let cases: Vec<Vec<&str>> = vec![
        vec![&t, "-o", &o, "--size", "0x10", "--yaw", "0", "--pitch", "0"],
        vec![
            &t, "-o", &o, "--format", "rgb444", "--yaw", "0", "--pitch", "0",
        ],
        vec![
            &t,
            "-o",
            &o,
            "--precision",
            "double",
            "--yaw",
            "0",
            "--pitch",
            "0",
        ],
        vec![&t, "-o", &o, "--mvp", "1,0,0,0,1,0,0,0,0,0,1,0,0,0,0,1"],
        vec![&t, "-o", &o, "--mvp", "1,2,3"],
        vec![&t, "-o", &o, "--yaw", "nan"],
        vec![&t, "-o", &o, "--up", "w"],
        vec![&t, "-o", &o, "--background", "0,0,256"],
        vec![&t, "-o", &o, "--distance", "0"],
        vec![&t, "-o", &o, "--yaw", "0", "--pitch", "0", "--band", "0"],
        vec![
            &t,
            "-o",
            &o,
            "--yaw",
            "0",
            "--pitch",
            "0",
            "--distance",
            "-1",
        ],
        vec![&t, "-o", &o, "--yaw", "0", "--pitch", "0", "--fov", "180"],
        vec![&j, "-o", &o, "--yaw", "0", "--pitch", "0"],
        vec![
            "/nonexistent/tree.fpt",
            "-o",
            &o,
            "--yaw",
            "0",
            "--pitch",
            "0",
        ],
    ];
    for c in cases {
        assert_eq!(fpt(&c), 2, "{c:?}");
    }
    assert!(!Path::new(&o).exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn slivers_are_drawn_unless_no_slivers_is_given() {
    // Whole-pixel snapping (0 sub-pixel bits) winds many faces seen almost
    // edge-on toward the viewer: the culling walk leaves them out, and the
    // sliver pass, on by default, draws them.
    let d = scratch("slivers");
    let tree = house_tree(&d);
    let t = tree.to_string_lossy().into_owned();
    let o = d.join("o.png").to_string_lossy().into_owned();
    let ids = d.join("ids.bin");
    let i = ids.to_string_lossy().into_owned();
    let render = |yaw: &str, extra: &[&str]| {
        let mut args = vec![
            t.as_str(),
            "-o",
            o.as_str(),
            "--size",
            "64x48",
            "--precision",
            "fixed-subpx-0",
            "--pitch",
            "17",
            "--yaw",
            yaw,
            "--ids",
            i.as_str(),
        ];
        args.extend_from_slice(extra);
        assert_eq!(fpt(&args), 0, "{args:?}");
        read(&ids)
    };
    let background = |raw: &[u8]| raw.chunks_exact(4).filter(|c| c == &[0; 4]).count();
    let mut differ = 0;
    for k in 0..36 {
        let yaw = (k * 10 + 3).to_string();
        let (on, off) = (render(&yaw, &[]), render(&yaw, &["--no-slivers"]));
        assert!(background(&on) <= background(&off), "yaw {yaw}");
        differ += usize::from(on != off);
    }
    assert!(differ > 0, "the sliver pass never changed a picture");
}
