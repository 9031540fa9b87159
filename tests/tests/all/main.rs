//! Every integration test of this crate, in one binary: one link instead
//! of one per file keeps the test command's cold build short (issue 16).
//! A new test file goes in this folder with a `mod NAME;` line here;
//! `declared_modules` fails when a file is missing from the list.

mod camera_scales;
mod effects_dispatch;
mod effects_golden;
mod effects_pipeline;
mod firmware_crc;
mod format_common;
mod format_corruption;
mod format_roundtrip;
mod orbit_frames;
mod order_scenes;
mod order_shared_models;
mod outline_features;
mod render_common;
mod render_hard_cases;
mod render_paths;
mod render_pinholes;
mod render_properties;
mod render_shared_models;
mod render_slivers;
mod smooth;
mod tiling_shared_models;

/// Every `.rs` file of this folder and of `host-sim/tests/all` is declared
/// in its `main.rs` (a file that is not would silently never run).
#[test]
fn declared_modules() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for dir in [root.join("tests/all"), root.join("../host-sim/tests/all")] {
        let main = std::fs::read_to_string(dir.join("main.rs")).unwrap();
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            let is_mod =
                path.extension().is_some_and(|e| e == "rs") || path.join("mod.rs").exists();
            if is_mod && name != "main" {
                let line = format!("\nmod {name};");
                assert!(
                    main.contains(&line),
                    "{}: {name} is not declared",
                    dir.display()
                );
            }
        }
    }
}
