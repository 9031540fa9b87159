//! A 128×64 SSD1306 1-bit OLED over I2C (the `ssd1306` crate) on a
//! Cortex-M0 with 16 KiB of RAM: the part is shaded, ordered-dithered to
//! black and white ([`Dither`]: a 4×4 Bayer pattern fixed to the screen)
//! and sent page by page.
//!
//! ```sh
//! cd firmware
//! cargo run --release --target thumbv6m-none-eabi --example ssd1306   # nRF51822 under QEMU (microbit)
//! ```
//!
//! The whole frame is 1 KiB ([`BinaryFormat`]: one bit a pixel, rows
//! top to bottom, the leftmost pixel in the most significant bit); the
//! SSD1306 takes pages of 8 rows, one byte a column with the top row in
//! bit 0, so [`page`] turns eight rows into the 128 bytes of a page. The
//! arithmetic is the integer vertex path ([`IntPrecision`]), which needs
//! no FPU. What a real board changes: `stub::I2c` becomes the HAL's I2C
//! (400 kHz), and the `for` over [`FRAMES`] a `loop`; QEMU emulates no
//! OLED, so here the bytes reach a checksum, which the run prints.
#![no_std]
#![no_main]

#[path = "../src/fail.rs"]
mod fail;
mod stub;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use embedded_graphics::pixelcolor::BinaryColor;
use fpt_nostd::raster::{
    BinaryFormat, BinaryFramebuffer, Dither, Framebuffer, IntPrecision, Libm, Orbit, Up,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{Frame, TreeRenderer};
use ssd1306::command::AddrMode;
use ssd1306::prelude::*;
use ssd1306::{I2CDisplayInterface, Ssd1306};
use static_cell::ConstStaticCell;

use fail::fail;

/// The tree (the project's vise, a z-up part).
static TREE: &[u8] = include_bytes!("../trees/vise.fpt");
const WIDTH: u32 = 128;
const HEIGHT: u32 = 64;
/// `fpt info trees/vise.fpt`: `TreeRenderer<P, 56>`, depth 23.
const V: usize = 56;
const N: usize = 40;
const FRAMES: u32 = 4;
/// Bytes of the 1-bit frame: 64 rows of 16 bytes.
const FRAME_BYTES: usize = (WIDTH / 8 * HEIGHT) as usize;

/// Integer vertex path, 4 sub-pixel bits: no floating point in the
/// per-vertex work (the Cortex-M0 has no FPU).
type Renderer = TreeRenderer<IntPrecision<4>, V>;
static RENDERER: ConstStaticCell<Renderer> =
    ConstStaticCell::new(Renderer::new(WIDTH, HEIGHT).expect("a 128×64 renderer"));
static PIXELS: ConstStaticCell<[u8; FRAME_BYTES]> = ConstStaticCell::new([0; FRAME_BYTES]);

/// Page `p` (rows `8p .. 8p + 8`) of `fb` in the SSD1306's layout: byte
/// `x` holds column `x`, row `8p + i` in bit `i`.
fn page(fb: &Framebuffer<'_, BinaryFormat>, p: u32, out: &mut [u8; WIDTH as usize]) {
    out.fill(0);
    for i in 0..8 {
        let Some(row) = fb.row(8 * p + i) else {
            continue;
        };
        for (x, byte) in out.iter_mut().enumerate() {
            let bit = (row[x / 8] >> (7 - x % 8)) & 1;
            *byte |= bit << i;
        }
    }
}

#[entry]
fn main() -> ! {
    let tree = Tree::from_bytes(TREE).unwrap_or_else(|e| fail(format_args!("tree: {e}")));
    let r = RENDERER.take();
    let mut fb = BinaryFramebuffer::new(PIXELS.take(), WIDTH, HEIGHT)
        .unwrap_or_else(|e| fail(format_args!("frame buffer: {e}")));

    let interface = I2CDisplayInterface::new(stub::I2c::default());
    let mut display = Ssd1306::new(interface, DisplaySize128x64, DisplayRotation::Rotate0);
    // Horizontal addressing: the pages follow each other, so one draw
    // area takes the whole frame.
    display
        .init_with_addr_mode(AddrMode::Horizontal)
        .unwrap_or_else(|e| fail(format_args!("display init: {e:?}")));

    let mut bytes = [0u8; WIDTH as usize];
    for i in 0..FRAMES {
        let yaw = i as f32 * 0.3;
        let aspect = WIDTH as f32 / HEIGHT as f32;
        let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), yaw, 0.436, 0.8, aspect);
        let frame = Frame::relative(&tree, &orbit.camera_up::<Libm>(aspect, Up::Z));
        r.renderer.set_light(frame.light());
        fb.fill_all(BinaryColor::Off);
        // Two levels (on/off) with ordered dithering: the grey of each
        // face becomes a density of lit pixels.
        let stats = r
            .render::<N, _>(&tree, &frame, &mut Dither::new(&mut fb, 2))
            .unwrap_or_else(|e| fail(format_args!("frame {i}: {e}")));
        display
            .set_draw_area((0, 0), (WIDTH as u8, HEIGHT as u8))
            .unwrap_or_else(|e| fail(format_args!("draw area: {e:?}")));
        for p in 0..HEIGHT / 8 {
            page(&fb, p, &mut bytes);
            display
                .draw(&bytes)
                .unwrap_or_else(|e| fail(format_args!("page {p}: {e:?}")));
        }
        let lit: u32 = fb.data().iter().map(|b| b.count_ones()).sum();
        hprintln!(
            "frame {}: {} polygons drawn, {} of {} pixels lit",
            i,
            stats.drawn,
            lit,
            WIDTH * HEIGHT
        );
    }
    let i2c = display.release().release();
    hprintln!(
        "ssd1306: {} frames, {} bytes over I2C, fnv1a {:08x}",
        FRAMES,
        i2c.wire.bytes,
        i2c.wire.hash
    );
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}
