//! Every integration test of this crate, in one binary: one link instead
//! of one per file keeps the test command's cold build short (issue 16).
//! A new test file goes in this folder with a `mod NAME;` line here;
//! `declared_modules` fails when a file is missing from the list.

mod accuracy_cli;
mod cli_build;
mod cli_demo;
mod cli_effects;
mod cli_format;
mod cli_frames;
mod cli_inputs;
mod cli_scale;
mod cli_view;
mod common;
mod mcu_bench;

/// Every `.rs` file in this folder is declared above (a file that is not
/// would silently never run).
#[test]
fn declared_modules() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(DIR);
    let main = std::fs::read_to_string(dir.join("main.rs")).unwrap();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let is_mod = path.extension().is_some_and(|e| e == "rs") || path.join("mod.rs").exists();
        if is_mod && name != "main" {
            assert!(
                main.contains(&format!("\nmod {name};")),
                "{name} is not declared in main.rs"
            );
        }
    }
}
const DIR: &str = "tests/all";
