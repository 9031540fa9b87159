//! `fpt-nostd`: the microcontroller side of feudal.
//!
//! `#![no_std]`, no `alloc`. Everything here works on caller-supplied storage.
//!
//! # Quickstart: a spinning part on a 240×240 display, drawn in bands
//!
//! On the host, once: `fpt build part.stl -o part.fpt` (the
//! `host-sim` crate's command-line tool; `fpt info part.fpt` prints the
//! renderer's capacities for the tree: the walk depth `N`, the polygon
//! vertex capacity `V` and the working memory). In the firmware, the tree
//! is bytes in flash; every frame is one call that hands finished bands of
//! RGB565 pixels to the display (a 7.5 KiB band buffer instead of a
//! 112.5 KiB framebuffer, and no depth buffer at all):
//!
//! ```
//! use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
//! use fpt_nostd::raster::{FloatLibm, Libm, Light, Orbit, Rgb565Format};
//! use fpt_nostd::reader::Tree;
//! use fpt_nostd::render::{BandBuffer, Frame, RenderError, TreeRenderer};
//!
//! // The tree from `fpt build` (here one of the project's scenes).
//! static TREE: &[u8] = include_bytes!("../../firmware/trees/vise.fpt");
//!
//! /// What a display driver offers: rows `y..` of RGB565 pixels (a stub).
//! fn send_rows(_y: i32, _pixels: &[u16]) {}
//!
//! fn main() -> Result<(), RenderError> {
//!     // Validated once; after this the walk and the fill never panic.
//!     let tree = Tree::from_bytes(TREE).expect("a valid tree");
//!     // f32 with an FPU (`IntPrecision<4>` on a Cortex-M0), 4 sub-pixel
//!     // bits, and the vertex capacity `fpt info` prints for this tree
//!     // ("TreeRenderer<P, 61>": its largest polygon has 20 vertices, and
//!     // clipping adds some; too small a capacity skips polygons, which
//!     // `stats.skipped` counts). On an MCU put it in a `static`.
//!     let mut r = TreeRenderer::<FloatLibm<4>, 64>::new(240, 240).expect("size");
//!     let mut band = [0u16; 240 * 16]; // 16 rows
//!     let mut memory = [0u32; 4096]; // vertex cache and display list
//!     for i in 0..3 {
//!         // Orbit the bounding sphere: yaw, pitch 25°, 2.1 radii, 60° fov.
//!         let yaw = i as f32 * 0.1;
//!         let orbit = Orbit::new([0.0; 3], yaw, 0.436, 2.1 * tree.bounding_radius(), 1.047);
//!         let frame = Frame::relative(&tree, &orbit.camera::<Libm>(1.0));
//!         // A light from the eye: 25 % ambient, 75 % diffuse.
//!         r.renderer.set_light(Light::new(frame.key_light(), 0.25, 0.75));
//!         let bands = BandBuffer::<Rgb565Format> {
//!             buf: &mut band,
//!             rows: 16,
//!             background: Rgb565::BLACK,
//!         };
//!         // The walk's stack holds 64 levels (the tree's depth at most).
//!         let stats = r.render_banded_in::<Rgb565Format, 64>(
//!             &tree,
//!             &frame,
//!             bands,
//!             &mut memory,
//!             |y, fb| send_rows(y, fb.data()),
//!         )?;
//!         // Enough memory for this tree: one walk a frame, nothing skipped.
//!         assert_eq!((stats.walks, stats.skipped), (1, 0));
//!     }
//!     Ok(())
//! }
//! ```
//!
//! With less `memory` the picture is the same and the frame takes more
//! walks ([`render::memory_words`] bounds what a tree can need; the README's
//! "Small RAM" section measures what less costs). The project's firmware
//! (`firmware/src/bin/bench.rs`) is this loop on QEMU's Cortex-M4F and
//! Cortex-M0, and `fpt mcu-bench TREE` runs it for any tree and reports
//! instructions a frame, RAM and whether every frame matches the host.
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
