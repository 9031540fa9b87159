//! `fpt-nostd`: the microcontroller side of feudal.
//!
//! `#![no_std]`, no `alloc`. Everything here works on caller-supplied storage.
//!
//! # Tree files
//!
//! [`format`] documents the flat tree file field by field (a table of every
//! field). [`reader::Tree::from_bytes`] validates a file once, in place (any
//! `&[u8]`, e.g. `include_bytes!` in flash) and without allocating; after
//! that, [`order::Order`] walks it back to front for any view with no panic
//! path (the contract is in [`reader`]).
//!
//! Untrusted files: the `tree_walk` fuzz target (in `fuzz/`) feeds arbitrary
//! bytes to the reader and the walk, `mesh_import` to the host's mesh
//! parsers. With cargo-fuzz (`cargo install cargo-fuzz`), on stable Rust
//! (`RUSTC_BOOTSTRAP=1` lets it accept the nightly flags), one after the
//! other:
//!
//! ```text
//! cd fuzz
//! mkdir -p corpus/tree_walk corpus/mesh_import
//! RUSTC_BOOTSTRAP=1 cargo fuzz run tree_walk corpus/tree_walk seeds/tree_walk -- -max_total_time=600
//! RUSTC_BOOTSTRAP=1 cargo fuzz run mesh_import corpus/mesh_import seeds/mesh_import -- -max_total_time=600
//! ```
//!
//! `seeds/` holds a few small valid inputs (serialized trees behind a control
//! byte, tiny meshes behind a format byte); `corpus/` is where libFuzzer keeps
//! what it finds (not versioned). What the runs found is recorded in
//! [`reader`] ("Fuzzing"). `cargo test -p fpt-tests --test format_corruption`
//! runs the same checks on stable Rust as a property test over corrupted
//! files.
#![no_std]
#![deny(unsafe_code, missing_docs)]

pub mod effects;
pub mod fixed;
pub mod format;
pub mod frames;
pub mod order;
pub mod raster;
pub mod reader;
pub mod render;
#[cfg(test)]
mod test_util;
