//! Double-buffered bands for a DMA display link: band k+1 is drawn into
//! one buffer while band k, in the other, is still on its way to a
//! 240×240 MIPI-DCS panel (ST7789, ILI9341, ...), through
//! `TreeRenderer::render_double_buffered_in` and a [`BandTransfer`].
//!
//! ```sh
//! cd firmware
//! cargo run --release --example dma_bands   # Cortex-M4F under QEMU (netduinoplus2)
//! ```
//!
//! The link's contract (`fpt_nostd::render::double`): `start` gets each
//! finished band by value and returns at once, `finish` waits for the
//! transfer and gives the band back; at most one transfer is in flight
//! and none when the frame returns. [`SpiDma`] below is the driver's shape:
//! on a real board `start` writes the panel's window (CASET, RASET, RAMWR)
//! over SPI and starts a DMA stream from `band.panel_bytes()` (big-endian
//! RGB565, [`Rgb565BeFormat`]: no per-pixel swap), and `finish` waits for
//! the stream's transfer-complete flag. QEMU emulates neither the panel
//! nor that DMA, so here the stand-in sends the bytes to a checksum in
//! `finish`. The buffers are `'static` (`ConstStaticCell`), so the driver
//! may hold a band for as long as its DMA reads it.
//!
//! Each frame is also drawn through one buffer
//! (`try_render_banded_in`); the run fails unless both send the same
//! bytes.
#![no_std]
#![no_main]

#[path = "../src/fail.rs"]
mod fail;
mod stub;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use embedded_graphics::pixelcolor::Rgb565;
use fpt_nostd::raster::{FloatLibm, Framebuffer, Libm, Orbit, Rgb565BeFormat, Up};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{BandBuffer, BandBuffers, BandTransfer, Frame, TreeRenderer};
use static_cell::ConstStaticCell;

use fail::fail;

/// The tree (the project's vise, a z-up part).
static TREE: &[u8] = include_bytes!("../trees/vise.fpt");
const SIZE: u32 = 240;
const ROWS: u32 = 16;
/// `fpt info trees/vise.fpt`: `TreeRenderer<P, 56>`, depth 23.
const V: usize = 56;
const N: usize = 40;
/// One walk a frame (`fpt info`: 4,032 words).
const MEMORY_WORDS: usize = 6144;
const FRAMES: u32 = 3;
const BAND_WORDS: usize = (SIZE * ROWS) as usize;

type Renderer = TreeRenderer<FloatLibm<4>, V>;
static RENDERER: ConstStaticCell<Renderer> =
    ConstStaticCell::new(Renderer::new(SIZE, SIZE).expect("a 240×240 renderer"));
/// The two band buffers: one is drawn while the other is sent.
static FRONT: ConstStaticCell<[u16; BAND_WORDS]> = ConstStaticCell::new([0; BAND_WORDS]);
static BACK: ConstStaticCell<[u16; BAND_WORDS]> = ConstStaticCell::new([0; BAND_WORDS]);
static MEMORY: ConstStaticCell<[u32; MEMORY_WORDS]> = ConstStaticCell::new([0; MEMORY_WORDS]);

/// A MIPI-DCS panel behind SPI with a DMA stream (the stand-in's shape:
/// see the module docs).
struct SpiDma {
    /// The SPI bus (commands are short and sent by the CPU).
    spi: stub::Spi,
    /// The band the DMA is reading, with its first row.
    in_flight: Option<(i32, Framebuffer<'static, Rgb565BeFormat>)>,
}

/// What can go wrong on the link (the stand-in never fails).
#[derive(Debug)]
enum LinkError {
    /// `finish` without a transfer: a broken contract.
    Idle,
}

impl SpiDma {
    /// The panel's command `cmd` with its arguments (the data/command pin
    /// low for `cmd`, high for the arguments: a stand-in here).
    fn command(&mut self, cmd: u8, args: &[u8]) {
        self.spi.wire.write(&[cmd]);
        self.spi.wire.write(args);
    }
}

impl SpiDma {
    /// Opens the panel's window on rows `y .. y + rows`, all columns, for
    /// the pixels that follow.
    fn window(&mut self, y: i32, rows: u32) {
        let (x1, y0, y1) = (SIZE as u16 - 1, y as u16, (y as u32 + rows - 1) as u16);
        let be = |v: u16| v.to_be_bytes();
        let [c0, c1] = be(x1);
        let ([a0, a1], [b0, b1]) = (be(y0), be(y1));
        self.command(0x2a, &[0, 0, c0, c1]); // CASET
        self.command(0x2b, &[a0, a1, b0, b1]); // RASET
        self.command(0x2c, &[]); // RAMWR: the pixels follow
    }
}

impl BandTransfer<'static, Rgb565BeFormat> for SpiDma {
    type Error = LinkError;

    fn start(
        &mut self,
        y: i32,
        band: Framebuffer<'static, Rgb565BeFormat>,
    ) -> Result<(), LinkError> {
        self.window(y, band.height());
        // Real driver: point the DMA stream at band.panel_bytes() (address
        // and length), enable it and return; the band stays here until
        // `finish`.
        self.in_flight = Some((y, band));
        Ok(())
    }

    fn finish(&mut self) -> Result<Framebuffer<'static, Rgb565BeFormat>, LinkError> {
        // Real driver: wait for the stream's transfer-complete flag (or
        // an interrupt that set it), then for the SPI to be idle.
        let (_y, band) = self.in_flight.take().ok_or(LinkError::Idle)?;
        self.spi.wire.write(band.panel_bytes());
        Ok(band)
    }
}

#[entry]
fn main() -> ! {
    let tree = Tree::from_bytes(TREE).unwrap_or_else(|e| fail(format_args!("tree: {e}")));
    let r = RENDERER.take();
    let memory = MEMORY.take();
    let mut link = SpiDma {
        spi: stub::Spi::default(),
        in_flight: None,
    };
    let background = Rgb565::new(2, 4, 6);
    // Lent to the link for each frame and back in `bands` after it.
    let mut bands = BandBuffers::<Rgb565BeFormat> {
        front: FRONT.take(),
        back: BACK.take(),
        rows: ROWS,
        background,
    };
    for i in 0..FRAMES {
        let yaw = i as f32 * 0.3;
        let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), yaw, 0.436, 1.047, 1.0);
        let frame = Frame::relative(&tree, &orbit.camera_up::<Libm>(1.0, Up::Z));
        r.renderer.set_light(frame.light());

        let before = link.spi.wire;
        let stats = r
            .render_double_buffered_in::<N, _, _>(
                &tree,
                &frame,
                &mut bands,
                &mut memory[..],
                &mut link,
            )
            .unwrap_or_else(|e| fail(format_args!("frame {i}: {e}")));
        let double = link.spi.wire;

        // The same frame through one buffer, each band sent before the
        // next is drawn: the same bytes must reach the panel.
        let mut single = before;
        let one = BandBuffer::<Rgb565BeFormat> {
            buf: &mut bands.front[..],
            rows: ROWS,
            background,
        };
        r.render_banded_in::<N, _>(&tree, &frame, one, &mut memory[..], |y, fb| {
            let mut dma = SpiDma {
                spi: stub::Spi { wire: single },
                in_flight: None,
            };
            dma.window(y, fb.height());
            dma.spi.wire.write(fb.panel_bytes());
            single = dma.spi.wire;
        })
        .unwrap_or_else(|e| fail(format_args!("frame {i} (one buffer): {e}")));
        if (single.bytes, single.hash) != (double.bytes, double.hash) {
            fail(format_args!(
                "frame {i}: double and single buffering sent different bytes"
            ));
        }
        hprintln!(
            "frame {}: {} polygons drawn, {} walk(s), {} bytes sent, the same as through one buffer",
            i,
            stats.drawn,
            stats.walks,
            double.bytes - before.bytes
        );
    }
    hprintln!(
        "dma_bands: {} frames, {} bytes over SPI, fnv1a {:08x}",
        FRAMES,
        link.spi.wire.bytes,
        link.spi.wire.hash
    );
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}
