//! `fpt demo`, the README's first command, through the real binary: every
//! picture and tree it announces exists and is a PNG or a valid tree.

use std::process::Command;

#[test]
fn demo_writes_every_file_it_lists() {
    let dir = std::env::temp_dir().join(format!("fpt-demo-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_fpt"))
        .args(["demo", "--out", dir.to_str().unwrap()])
        .output()
        .expect("running fpt demo");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let (mut pngs, mut gifs) = (0, 0);
    for word in text.split_whitespace() {
        let p = std::path::Path::new(word);
        if !p.starts_with(&dir) || ![".png", ".fpt", ".gif"].iter().any(|e| word.ends_with(e)) {
            continue;
        }
        let bytes = std::fs::read(p).unwrap_or_else(|e| panic!("{word}: {e}"));
        if word.ends_with(".png") {
            assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "{word}");
            pngs += 1;
        } else if word.ends_with(".gif") {
            assert!(bytes.starts_with(b"GIF89a"), "{word}");
            gifs += 1;
        } else if word.ends_with(".fpt") {
            assert!(
                fpt_nostd::reader::Tree::from_bytes(&bytes).is_ok(),
                "{word}"
            );
        }
    }
    // Four vise, four house and three city views, four effect pictures,
    // the robot; its turntable.
    assert_eq!((pngs, gifs), (16, 1), "{text}");
    assert!(dir.join("robot.obj").exists() && dir.join("robot.mtl").exists());
    for name in [
        "vise_outline",
        "vise_depth_cue",
        "vise_oled_dither",
        "vise_lcd_gray4",
    ] {
        assert!(dir.join(format!("{name}.png")).exists(), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
