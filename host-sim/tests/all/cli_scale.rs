//! Any scale the builder accepts renders: a unit cube scaled by 1e-30 …
//! 1e38 and moved by up to 1e30 is built and drawn through every camera
//! form (`--yaw/--pitch`, with `--distance`, parallel, `--mvp`, the `f32`
//! vertex path, every up axis, an eye next to `f32`'s largest number),
//! and each picture's id buffer is the unit cube's: the orbit forms are
//! the library's `Orbit::camera_up` (composed in model space normalised
//! by the distance). A model the `f64` input cannot hold (a unit cube
//! 1e30 from the origin) is refused at build time, an eye whose distance
//! is beyond `f32` at render time.

use crate::common;

use common::{fpt, s, tmp};
use glam::DVec3;
use host_sim::reference::{differences_off_outlines, Camera, Projection};
use std::path::{Path, PathBuf};

const W: usize = 96;
const H: usize = 72;

/// The direction models are moved in (all three coordinates change).
const OFFSET_DIR: DVec3 = DVec3::new(1.0, -0.7, 0.3);

/// OBJ of the cube `offset + scale · [0, 1]^3`, faces outward.
fn cube_obj(scale: f64, offset: DVec3) -> String {
    let mut text = String::new();
    for i in 0..8 {
        let c = DVec3::new(f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2));
        let p = offset + scale * c;
        text += &format!("v {:e} {:e} {:e}\n", p.x, p.y, p.z);
    }
    text + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 2 4 8 6\nf 1 5 7 3\n"
}

/// Builds the cube; the tree's path, or the build's output on failure.
fn build(name: &str, scale: f64, offset: DVec3) -> Result<PathBuf, std::process::Output> {
    let mesh = tmp(&format!("{name}.obj"));
    std::fs::write(&mesh, cube_obj(scale, offset)).unwrap();
    let tree = tmp(&format!("{name}.fpt"));
    let out = fpt(&["build", s(&mesh), "-o", s(&tree)]);
    if out.status.success() {
        Ok(tree)
    } else {
        Err(out)
    }
}

/// The id buffer of a render of `tree` with camera arguments `camera`.
fn ids(tree: &Path, camera: &[String]) -> Vec<u32> {
    let ids = tmp("scale-ids.bin");
    let png = tmp("scale.png");
    let size = format!("{W}x{H}");
    let mut args: Vec<&str> = vec!["render", s(tree), "-o", s(&png), "--size", &size];
    args.extend(camera.iter().map(String::as_str));
    args.extend(["--ids", s(&ids)]);
    let out = fpt(&args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::read(&ids)
        .unwrap()
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// The model → clip matrix of the unit cube's camera, moved to the model
/// `offset + scale · unit`: `M · S(1/scale) · T(−offset)`, row-major.
fn mvp(scale: f64, offset: DVec3) -> String {
    let cam = Camera::look_at(
        DVec3::new(2.2, 1.9, 2.6),
        DVec3::splat(0.5),
        DVec3::Y,
        Projection::Perspective {
            fov_y_deg: 40.0,
            near: 0.05,
            far: 50.0,
        },
        W as f64 / H as f64,
    )
    .unwrap();
    let m = cam.mvp();
    let mut out = Vec::with_capacity(16);
    for row in m.chunks_exact(4) {
        let xyz = DVec3::new(row[0], row[1], row[2]);
        let moved = row[3] - xyz.dot(offset) / scale;
        out.extend([row[0] / scale, row[1] / scale, row[2] / scale, moved]);
    }
    let text: Vec<String> = out.iter().map(|v| format!("{v:e}")).collect();
    text.join(",")
}

/// The camera forms, for a model of `scale` at `offset`.
fn cameras(scale: f64, offset: DVec3) -> Vec<(&'static str, Vec<String>)> {
    let args = |a: &[&str]| -> Vec<String> { a.iter().map(|a| a.to_string()).collect() };
    let distance = format!("{:e}", 2.5 * scale);
    vec![
        ("orbit", args(&["--yaw", "30", "--pitch", "20"])),
        (
            "distance",
            args(&[
                "--yaw",
                "-60",
                "--pitch",
                "35",
                "--distance",
                &distance,
                "--distance-units",
                "model",
            ]),
        ),
        (
            "distance-radii",
            args(&["--yaw", "-60", "--pitch", "35", "--distance", "2.5"]),
        ),
        (
            "parallel",
            args(&["--yaw", "30", "--pitch", "20", "--fov", "0"]),
        ),
        (
            "f32-libm",
            args(&["--yaw", "30", "--pitch", "20", "--precision", "f32-libm"]),
        ),
        (
            "up-z",
            args(&["--yaw", "30", "--pitch", "20", "--up", "z", "--band", "16"]),
        ),
        ("up-x", args(&["--yaw", "30", "--pitch", "20", "--up", "x"])),
        (
            // Eye 3.9 radii away: 3.4e38 model units for the 1e38 cube,
            // next to f32's largest number.
            "far",
            args(&[
                "--yaw",
                "-60",
                "--pitch",
                "35",
                "--distance",
                "3.9",
                "--fov",
                "0",
            ]),
        ),
        ("mvp", vec!["--mvp".to_string(), mvp(scale, offset)]),
    ]
}

#[test]
fn every_scale_and_offset_draws_like_the_unit_cube() {
    let unit = build("unit", 1.0, DVec3::ZERO).unwrap();
    let reference: Vec<(&str, Vec<u32>)> = cameras(1.0, DVec3::ZERO)
        .into_iter()
        .map(|(name, args)| (name, ids(&unit, &args)))
        .collect();
    for (name, r) in &reference {
        let drawn = r.iter().filter(|&&v| v != 0).count();
        assert!(
            drawn > W * H / 10,
            "{name}: unit cube covers {drawn} pixels"
        );
        let faces: std::collections::HashSet<u32> = r.iter().copied().collect();
        assert_eq!(faces.len(), 4, "{name}: background and three faces");
    }
    let scales = [1e-30, 1e-20, 1e-10, 1.0, 1e10, 1e20, 1e30, 1e38];
    // 0 and 1e-27, 1e-24, ..., 1e30.
    let offsets = std::iter::once(0.0).chain((-9..=10).map(|k| 10f64.powi(3 * k)));
    let mut models = 0;
    for scale in scales {
        for offset in offsets.clone() {
            // Moved by 0, or by 1 to 1e10 sizes (f64 keeps such a cube
            // exact to 1e-6 of its size, far below a pixel).
            let ratio = offset / scale;
            if offset != 0.0 && !(1.0..=1e10).contains(&ratio) {
                continue;
            }
            let at = offset * OFFSET_DIR;
            let name = format!("cube-{scale:e}-{offset:e}");
            let tree = build(&name, scale, at)
                .unwrap_or_else(|out| panic!("{name}: {}", String::from_utf8_lossy(&out.stderr)));
            for ((form, args), (_, want)) in cameras(scale, at).iter().zip(&reference) {
                let got = ids(&tree, args);
                let wrong = differences_off_outlines(want, &got, W);
                assert_eq!(wrong, 0, "{name} {form}: {wrong} pixels differ");
            }
            models += 1;
        }
    }
    assert!(models >= 30, "{models} models swept");
    println!("{models} models, {} camera forms each", reference.len());
}

#[test]
fn an_orbit_proof_does_not_depend_on_the_scale() {
    for (scale, at) in [(1.0, 0.0), (1e38, 0.0), (1e-30, 1e-25)] {
        let mesh = tmp(&format!("orbit-{scale:e}.obj"));
        std::fs::write(&mesh, cube_obj(scale, at * OFFSET_DIR)).unwrap();
        let tree = tmp(&format!("orbit-{scale:e}.fpt"));
        for (orbit, says) in [
            ("4,40", "no view needs clipping"),
            ("1.2,40", "some views may need clipping"),
        ] {
            let out = fpt(&["build", s(&mesh), "-o", s(&tree), "--orbit", orbit]);
            let text = String::from_utf8_lossy(&out.stdout);
            assert!(out.status.success(), "{scale:e}");
            assert!(text.contains(says), "{scale:e} {orbit}: {text}");
        }
    }
}

#[test]
fn an_eye_beyond_f32_is_refused_with_one_line() {
    let tree = build("far-eye", 1e38, DVec3::ZERO).unwrap();
    let png = tmp("far-eye.png");
    for distance in ["4", "1e30"] {
        let out = fpt(&["render", s(&tree), "-o", s(&png), "--distance", distance]);
        assert_eq!(out.status.code(), Some(2), "{distance}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("error: --distance is too large"), "{err}");
    }
    // The same distance in radii is fine for an ordinary model.
    let unit = build("far-eye-unit", 1.0, DVec3::ZERO).unwrap();
    let out = fpt(&["render", s(&unit), "-o", s(&png), "--distance", "1e30"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_cube_the_input_cannot_hold_is_refused_at_build_time() {
    // 1e30 away, a unit cube's corners round to one point in f64.
    let out = build("lost", 1.0, 1e30 * OFFSET_DIR).unwrap_err();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("error: "), "{err}");
    // Beyond 1e38 the renderer's camera would overflow f32: refused too,
    // and so are sizes whose squares overflow f64.
    for scale in [2e38, 1e39, 1e100, 1e200] {
        let out = build("huge", scale, DVec3::ZERO).unwrap_err();
        assert_eq!(out.status.code(), Some(2), "{scale:e}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains("error: ") && err.contains("the model is too large"),
            "{err}"
        );
    }
}
