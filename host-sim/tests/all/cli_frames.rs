//! `fpt frames --work`: one line per frame of the committed trees, with
//! counts that hang together.

use crate::common;

use common::fpt;

/// The value of `key=` in a work line.
fn field(line: &str, key: &str) -> u64 {
    line.split_whitespace()
        .find_map(|f| f.strip_prefix(key)?.strip_prefix('='))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no {key} in {line}"))
}

#[test]
fn work_lines_count_every_frame() {
    let trees = concat!(env!("CARGO_MANIFEST_DIR"), "/../firmware/trees");
    let out = fpt(&["frames", "--work", "--trees", trees]);
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().collect();
    let (scenes, views) = (fpt_frames::SCENES.len(), fpt_frames::VIEWS.len());
    assert_eq!(lines.len(), scenes * views, "{text}");
    for (i, l) in lines.iter().enumerate() {
        let want = format!(
            "work scene={} view={} ",
            fpt_frames::SCENES[i / views],
            i % views
        );
        assert!(l.starts_with(&want), "{l}");
        let (polys, verts, drawn) = (
            field(l, "polygons"),
            field(l, "vertices"),
            field(l, "drawn"),
        );
        let (spans, pixels) = (field(l, "spans"), field(l, "pixels"));
        // Every polygon has at least three vertices; a drawn polygon was
        // handed out; a span is at least one pixel and at most a row.
        assert!(drawn <= polys && polys > 0 && verts >= 3 * polys, "{l}");
        assert!(spans <= pixels && pixels <= spans * 240, "{l}");
    }
    let city = lines.iter().find(|l| l.contains("bench_city")).unwrap();
    assert!(field(city, "polygons") >= 1000, "{city}");
}

#[test]
fn work_and_accuracy_do_not_mix() {
    let out = fpt(&["frames", "--work", "--accuracy"]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
}
