//! An ST7789 240×240 SPI display driven by `mipidsi`, showing a part that
//! turns: the tree in flash, the renderer in a `static`, each frame drawn
//! in 16-row bands that go to the display as they are finished.
//!
//! ```sh
//! cd firmware
//! cargo run --release --example st7789      # Cortex-M4F under QEMU (netduinoplus2)
//! ```
//!
//! What a real board changes: the four `stub::` values below become the
//! HAL's SPI device (mode 3, as fast as the panel takes: 62.5 MHz on an
//! ST7789), its data/command and reset pins and its delay (see
//! `examples/stub/mod.rs`); the `for` over [`FRAMES`] becomes a `loop`.
//! QEMU emulates no panel, so here the bytes only reach a checksum, which
//! the run prints.
//!
//! The band holds the panel's pixels in the CPU's order ([`Rgb565Format`])
//! because `mipidsi` takes colours and writes them big-endian itself (a
//! DMA driver would rather take [`fpt_nostd::raster::Rgb565BeFormat`]'s
//! bytes as they are: `examples/dma_bands.rs`). A display error ends the
//! frame and comes back from `try_render_banded_in` as
//! `BandError::Display`.
#![no_std]
#![no_main]

#[path = "../src/fail.rs"]
mod fail;
mod stub;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use fpt_nostd::raster::{FloatLibm, Libm, Orbit, Rgb565Format, Up};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{BandBuffer, Frame, TreeRenderer};
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use mipidsi::Builder;
use static_cell::ConstStaticCell;

use fail::fail;

/// The tree, from `fpt build part.stl -o part.fpt` (here the project's
/// vise, a z-up part).
static TREE: &[u8] = include_bytes!("../trees/vise.fpt");
/// The panel's side in pixels.
const SIZE: u32 = 240;
/// Rows per band: 240 × 16 × 2 bytes = 7.5 KiB instead of a 112.5 KiB
/// framebuffer.
const ROWS: u32 = 16;
/// The vertex capacity `fpt info trees/vise.fpt` prints
/// (`TreeRenderer<P, 56>`); the renderer checks it against the tree's
/// header and refuses a tree that needs more.
const V: usize = 56;
/// The walk stack: `fpt info` prints the tree's depth (23), a few more
/// levels leave room for a rebuilt tree.
const N: usize = 40;
/// Working memory for one walk a frame (`fpt info`: 4,032 words for the
/// vise; less gives the same picture with more walks).
const MEMORY_WORDS: usize = 6144;
/// Frames this run draws (a product loops forever).
const FRAMES: u32 = 4;

/// `f32` arithmetic with libm (the Cortex-M4F's FPU), 4 sub-pixel bits.
type Renderer = TreeRenderer<FloatLibm<4>, V>;
/// Built at compile time and taken once: never on the stack.
static RENDERER: ConstStaticCell<Renderer> =
    ConstStaticCell::new(Renderer::new(SIZE, SIZE).expect("a 240×240 renderer"));
static BAND: ConstStaticCell<[u16; (SIZE * ROWS) as usize]> =
    ConstStaticCell::new([0; (SIZE * ROWS) as usize]);
static MEMORY: ConstStaticCell<[u32; MEMORY_WORDS]> = ConstStaticCell::new([0; MEMORY_WORDS]);
/// `mipidsi`'s SPI batch buffer (pixels are converted into it).
static SPI_BUFFER: ConstStaticCell<[u8; 512]> = ConstStaticCell::new([0; 512]);

#[entry]
fn main() -> ! {
    // Validated once; after this nothing in the renderer panics.
    let tree = Tree::from_bytes(TREE).unwrap_or_else(|e| fail(format_args!("tree: {e}")));
    let r = RENDERER.take();
    let band = BAND.take();
    let memory = MEMORY.take();

    let di = SpiInterface::new(stub::Spi::default(), stub::Pin, SPI_BUFFER.take());
    let mut display = Builder::new(ST7789, di)
        .display_size(SIZE as u16, SIZE as u16)
        // Most 240×240 ST7789 modules need inverted colours.
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(stub::Pin)
        .init(&mut stub::Delay)
        .unwrap_or_else(|e| fail(format_args!("display init: {e:?}")));

    for i in 0..FRAMES {
        // An orbit that frames the tree's bounding sphere: yaw turning,
        // pitch 25°, 60° field of view; the part is z-up.
        let yaw = i as f32 * 0.3;
        let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), yaw, 0.436, 1.047, 1.0);
        let frame = Frame::relative(&tree, &orbit.camera_up::<Libm>(1.0, Up::Z));
        // The key light follows the camera.
        r.renderer.set_light(frame.light());
        let bands = BandBuffer::<Rgb565Format> {
            buf: &mut band[..],
            rows: ROWS,
            background: Rgb565::new(2, 4, 6),
        };
        let stats = r
            .try_render_banded_in::<N, _, _>(&tree, &frame, bands, &mut memory[..], |y, fb| {
                // Rows y ..= y + height − 1, all columns (inclusive ends).
                let last = (y as u32 + fb.height() - 1) as u16;
                let colors = fb.data().iter().map(|&w| Rgb565::from(RawU16::new(w)));
                display.set_pixels(0, y as u16, SIZE as u16 - 1, last, colors)
            })
            .unwrap_or_else(|e| fail(format_args!("frame {i}: {e}")));
        hprintln!(
            "frame {}: {} polygons drawn, {} skipped, {} walk(s)",
            i,
            stats.drawn,
            stats.skipped,
            stats.walks
        );
    }

    let (di, _model, _reset) = display.release();
    let (spi, _dc) = di.release();
    hprintln!(
        "st7789: {} frames, {} bytes over SPI, fnv1a {:08x}",
        FRAMES,
        spi.wire.bytes,
        spi.wire.hash
    );
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}
