//! Every integration test of this crate, in one binary: one link instead
//! of one per file keeps the test command's cold build short (issue 16).
//! A new test file goes in this folder with a `mod NAME;` line here;
//! `declared_modules` (in `tests/tests/all/main.rs`) fails when a file is
//! missing from the list.

mod accuracy_cli;
mod cli_build;
mod cli_demo;
mod cli_effects;
mod cli_format;
mod cli_frames;
mod cli_inputs;
mod cli_scale;
mod cli_subdivide;
mod cli_view;
mod common;
mod mcu_bench;
