//! `fpt-nostd`: the microcontroller side of feudal.
//!
//! `#![no_std]`, no `alloc`. Everything here works on caller-supplied storage.
//!
//! # Quickstart: a spinning part on a 240×240 display, drawn in bands
//!
//! On the host, once: `fpt build part.stl -o part.fpt` (the
//! `host-sim` crate's command-line tool). The tree's header records what a
//! renderer needs; `fpt info part.fpt` prints it ("TreeRenderer<P, 56>",
//! walk stack `N = 23`, the working memory), and the renderer checks it
//! before drawing: too small a capacity is a [`render::CapacityError`]
//! naming it and what it must be, never a polygon skipped. In the
//! firmware, the tree is bytes in flash, the renderer a `static` (its
//! constructor is a `const fn`), and every frame is one call that hands
//! finished bands of pixels, already in the panel's byte order, to the
//! display driver (a 7.5 KiB band buffer instead of a 112.5 KiB
//! framebuffer, and no depth buffer at all):
//!
//! ```
//! use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
//! use fpt_nostd::raster::{FloatLibm, Libm, Orbit, Rgb565BeFormat, Up};
//! use fpt_nostd::reader::Tree;
//! use fpt_nostd::render::{BandBuffer, BandError, Frame, TreeRenderer};
//! use static_cell::ConstStaticCell;
//!
//! // The tree from `fpt build` (here one of the project's scenes).
//! static TREE: &[u8] = include_bytes!("../../firmware/trees/vise.fpt");
//!
//! // f32 with an FPU (`IntPrecision<4>` on a Cortex-M0), 4 sub-pixel
//! // bits, and the vertex capacity `fpt info` prints for the tree.
//! type Renderer = TreeRenderer<FloatLibm<4>, 56>;
//! // Built at compile time, taken once: never on the stack.
//! static RENDERER: ConstStaticCell<Renderer> =
//!     ConstStaticCell::new(Renderer::new(240, 240).expect("a 240×240 display"));
//! static BAND: ConstStaticCell<[u16; 240 * 16]> = ConstStaticCell::new([0; 240 * 16]);
//!
//! /// What a display driver offers: write big-endian RGB565 bytes to
//! /// rows `y..` (a stub that cannot fail).
//! fn send_rows(_y: i32, _bytes: &[u8]) -> Result<(), core::convert::Infallible> {
//!     Ok(())
//! }
//!
//! fn main() -> Result<(), BandError<core::convert::Infallible>> {
//!     // Validated once; after this the walk and the fill never panic.
//!     let tree = Tree::from_bytes(TREE).expect("a valid tree");
//!     let r = RENDERER.take();
//!     let band = BAND.take();
//!     let mut memory = [0u32; 6144]; // `fpt info`: 4,032 words for one walk
//!     for i in 0..3 {
//!         // Frame the bounding sphere: yaw, pitch 25°, 60° fov; z-up part.
//!         let yaw = i as f32 * 0.1;
//!         let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), yaw, 0.436, 1.047, 1.0);
//!         let frame = Frame::relative(&tree, &orbit.camera_up::<Libm>(1.0, Up::Z));
//!         // The key light follows the camera: 25 % ambient, 75 % diffuse.
//!         r.renderer.set_light(frame.light());
//!         let bands = BandBuffer::<Rgb565BeFormat> {
//!             buf: &mut band[..],
//!             rows: 16,
//!             background: Rgb565::BLACK,
//!         };
//!         // A display error stops the frame and comes back here.
//!         let stats = r.try_render_banded_in::<64, _, _>(&tree, &frame, bands, &mut memory, |y, fb| {
//!             send_rows(y, fb.panel_bytes())
//!         })?;
//!         // Enough memory for this tree: one walk a frame, nothing skipped.
//!         assert_eq!((stats.walks, stats.skipped), (1, 0));
//!     }
//!     Ok(())
//! }
//! ```
//!
//! With less `memory` the picture is the same and the frame takes more
//! walks ([`render::memory_words`] bounds what a tree can need; `docs/small-ram.md`
//! measures what less costs). The project's firmware
//! (`firmware/src/bin/bench.rs`) is this loop on QEMU's Cortex-M4F and
//! Cortex-M0, and `fpt mcu-bench TREE` runs it for any tree and reports
//! instructions a frame, RAM and whether every frame matches the host.
//!
//! # Complete firmware to start from
//!
//! `firmware/examples/` holds three programs that CI runs under QEMU
//! (their buses are documented embedded-hal 1.0 stand-ins; swap in a
//! HAL's): `st7789.rs`, an ST7789 240×240 over SPI with the `mipidsi`
//! crate, bands handed to `set_pixels`; `dma_bands.rs`, double-buffered
//! bands for a DMA link ([`render::TreeRenderer::render_double_buffered_in`]
//! and its [`render::BandTransfer`] contract, [`render::double`]: band k+1
//! is drawn while band k is sent); `ssd1306.rs`, a 128×64 1-bit OLED on a
//! Cortex-M0, dithered ([`raster::Dither`]) with the integer vertex path.
//! `host-sim/examples/render_png.rs` draws into an `embedded-graphics`
//! `DrawTarget` on the host.
//!
//! [`prelude`] imports what these use in one line. Generic parameters
//! come in one order everywhere: the arithmetic `P`, the walk depth `N`,
//! the vertex capacity `V`, the effects `E`, then what the call draws into
//! (a sink `K` or pixel format `F`, a probe, an error type):
//! `TreeRenderer<P, V, E>`, [`render::draw_frame`]`::<P, N, V, E, K>`,
//! `r.render_banded_in::<N, F>(..)`. The project's measuring harness (its
//! frame set, checksums and probes) is the separate `fpt-frames` crate.
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
//! [`reader`] ("Fuzzing"). `cargo test -p fpt-tests --test all format_corruption`
//! runs the same checks on stable Rust as a property test over corrupted
//! files.
#![no_std]
#![deny(unsafe_code, missing_docs)]

mod cpu;
pub mod effects;
pub mod fixed;
pub mod format;
pub mod order;
pub mod prelude;
pub mod raster;
pub mod reader;
pub mod render;
/// Hand-made tree files for tests (this crate's, and the measuring
/// harness's behind the `test-util` feature); not part of the API.
#[cfg(any(test, feature = "test-util"))]
#[doc(hidden)]
#[allow(missing_docs)]
pub mod test_util;
