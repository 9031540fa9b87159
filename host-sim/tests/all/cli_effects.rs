//! Scene effects through the real binary: `fpt build --effects/--orbit`
//! stores them, `fpt info` shows them, `fpt render --effects` overrides
//! them and simulates displays only when asked; bad names are errors with
//! exit status 2 and no output file.

use crate::common;

use common::{fpt, s, tmp, CUBE_OBJ};
use std::path::Path;
use std::process::Output;

fn stdout(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn effects_line(tree: &Path) -> String {
    let info = stdout(&fpt(&["info", s(tree)]));
    info.lines()
        .find(|l| l.starts_with("effects:"))
        .expect("effects line")
        .to_string()
}

/// Exit status 2, one `error: ` line naming `what`, and no `file`.
fn assert_refused(out: &Output, what: &str, file: &Path) {
    assert_eq!(out.status.code(), Some(2), "{what}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(what), "{err}");
    assert!(!file.exists(), "{} was written", file.display());
}

#[test]
fn build_stores_the_declared_effects_and_what_the_orbit_proves() {
    let mesh = tmp("cube.obj");
    std::fs::write(&mesh, CUBE_OBJ).unwrap();
    let tree = tmp("cube.fpt");
    let build =
        |extra: &[&str]| stdout(&fpt(&[&["build", s(&mesh), "-o", s(&tree)], extra].concat()));
    build(&[]);
    assert!(effects_line(&tree).ends_with("(culling,clipping,lighting)"));
    // A far orbit never needs clipping: it is left out of the defaults.
    let out = build(&["--orbit", "3,40"]);
    assert!(out.contains("no view needs clipping"), "{out}");
    assert!(effects_line(&tree).ends_with("(culling,lighting)"));
    // Inside the bounding sphere it does.
    let out = build(&["--orbit", "0.5,40"]);
    assert!(out.contains("may need clipping"), "{out}");
    assert!(effects_line(&tree).ends_with("(culling,clipping,lighting)"));
    // An explicit list is stored as given.
    build(&["--effects", "outline, dither"]);
    assert!(effects_line(&tree).ends_with("(dither,outline)"));
    build(&["--effects", "none"]);
    assert!(effects_line(&tree).ends_with("(none)"));
    // Unknown names and bad orbits: exit 2, no file.
    let fresh = tmp("never.fpt");
    let out = fpt(&[
        "build",
        s(&mesh),
        "-o",
        s(&fresh),
        "--effects",
        "lighting,fog",
    ]);
    assert_refused(&out, "unknown effect `fog`", &fresh);
    let out = fpt(&["build", s(&mesh), "-o", s(&fresh), "--orbit", "3"]);
    assert_refused(&out, "--orbit", &fresh);
    let out = fpt(&["build", s(&mesh), "-o", s(&fresh), "--orbit", "-1,40"]);
    assert_refused(&out, "--orbit", &fresh);
}

#[test]
fn render_overrides_effects_and_simulates_displays_when_asked() {
    let mesh = tmp("cube2.obj");
    std::fs::write(&mesh, CUBE_OBJ).unwrap();
    let tree = tmp("cube2.fpt");
    stdout(&fpt(&["build", s(&mesh), "-o", s(&tree)]));
    let view = ["--yaw", "30", "--pitch", "20", "--size", "40x30"];
    let render = |out: &Path, extra: &[&str]| {
        let mut a = vec!["render", s(&tree), "-o", s(out)];
        a.extend_from_slice(&view);
        a.extend_from_slice(extra);
        fpt(&a)
    };
    let plain = tmp("plain.png");
    stdout(&render(&plain, &[]));
    let outlined = tmp("outlined.png");
    stdout(&render(
        &outlined,
        &["--effects", "culling,clipping,lighting,outline"],
    ));
    assert_ne!(
        std::fs::read(&plain).unwrap(),
        std::fs::read(&outlined).unwrap()
    );
    let unlit = tmp("unlit.png");
    stdout(&render(&unlit, &["--effects", "none"]));
    assert_ne!(
        std::fs::read(&plain).unwrap(),
        std::fs::read(&unlit).unwrap()
    );
    // A panel look: 3× pixels with a 1-pixel gap, 40×30 → 159×119.
    let oled = tmp("oled.png");
    stdout(&render(
        &oled,
        &[
            "--format",
            "mono",
            "--effects",
            "culling,lighting,dither",
            "--display",
            "oled-blue",
        ],
    ));
    let png = std::fs::read(&oled).unwrap();
    let (w, h) = (
        u32::from_be_bytes(png[16..20].try_into().unwrap()),
        u32::from_be_bytes(png[20..24].try_into().unwrap()),
    );
    assert_eq!((w, h), (40 * 3 + 39, 30 * 3 + 29));
    let grey = tmp("grey.png");
    stdout(&render(&grey, &["--format", "gray8", "--gray-levels", "4"]));
    // Dithering and outlines through a band buffer: the same picture.
    for (format, effects) in [
        ("mono", "culling,lighting,dither"),
        ("gray8", "culling,lighting,dither,outline"),
        ("rgb565", "culling,lighting,depth-cue,outline"),
    ] {
        let (full, banded) = (tmp("full.png"), tmp("banded.png"));
        let args = ["--format", format, "--effects", effects];
        stdout(&render(&full, &args));
        let mut with_band = args.to_vec();
        with_band.extend_from_slice(&["--band", "7"]);
        stdout(&render(&banded, &with_band));
        assert_eq!(
            std::fs::read(&full).unwrap(),
            std::fs::read(&banded).unwrap(),
            "{format} {effects}"
        );
    }
    // Bad names and values: exit 2, no file.
    let never = tmp("never.png");
    assert_refused(
        &render(&never, &["--effects", "shadows"]),
        "unknown effect",
        &never,
    );
    assert_refused(
        &render(&never, &["--effects", ""]),
        "unknown effect",
        &never,
    );
    assert_refused(
        &render(&never, &["--gray-levels", "1"]),
        "--gray-levels",
        &never,
    );
    assert_refused(&render(&never, &["--display", "crt"]), "crt", &never);
}
