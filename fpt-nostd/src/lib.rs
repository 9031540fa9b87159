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
//! Untrusted files: `cargo +nightly fuzz run tree_walk` from the repository
//! root fuzzes the reader and the walk (needs `cargo install cargo-fuzz`); on
//! stable Rust, `cargo test -p fpt-tests --test format_corruption` runs the
//! same checks as a property test over corrupted files.
#![no_std]
#![deny(unsafe_code, missing_docs)]

pub mod format;
pub mod order;
pub mod reader;
#[cfg(test)]
mod test_util;
pub mod fixed;
pub mod raster;
