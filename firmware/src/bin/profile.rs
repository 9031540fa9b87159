//! One `bench_city` frame (view 0, full frame) and nothing else, drawn the
//! way a product would: through a pipeline compiled with only the stages
//! the scene declares (culling, clipping, lighting), no probes. The target
//! for an instruction profile under QEMU and for measuring the renderer's
//! code size (`.text` attributed to `fpt-nostd`). It checks its checksum
//! against the frame set's (`trees/frames.txt`).
//!
//! ```text
//! cargo build --release --bin profile
//! qemu-system-arm -machine netduinoplus2 -cpu cortex-m4 -nographic \
//!     -semihosting-config enable=on,target=native -icount shift=0 \
//!     -d in_asm,exec,nochain -D /tmp/exec.log \
//!     -kernel target/thumbv7em-none-eabihf/release/profile
//! python3 tools/profile.py /tmp/exec.log target/thumbv7em-none-eabihf/release/profile
//! ```
//!
//! (`tools/profile.py` weighs every executed translation block by its
//! instruction count and sums per function.)
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};

use fpt_frames::{
    FrameLine, FramePrecision, PixelCrc, BACKGROUND, FRAME_WORDS, HEIGHT, MAX_VERTS, VIEWS,
    WALK_DEPTH, WIDTH,
};
use fpt_nostd::effects::{Effects, Pipeline};
use fpt_nostd::raster::{Light, Rgb565Framebuffer};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::TreeRenderer;
use static_cell::ConstStaticCell;

/// The scene's declared effects, and nothing else, compiled in.
type Product = Pipeline<{ Effects::defaults(true).bits() }>;

static TREE: &[u8] = include_bytes!("../../trees/bench_city.fpt");
static EXPECTED: &str = include_str!("../../trees/frames.txt");
static mut FRAME: [u16; FRAME_WORDS] = [0; FRAME_WORDS];
/// The `full` firmware's working memory (`src/main.rs`, `MEMORY_WORDS`):
/// the vertex cache its frame lines are measured with.
static MEMORY: ConstStaticCell<[u32; 868]> = ConstStaticCell::new([0; 868]);

/// Halts with a failure exit and prints nothing: what a product's
/// `panic-halt`-style handler costs. Not the shared `fail.rs` handler on
/// purpose: formatting the panic message makes every bounds check's panic
/// path heavier and would inflate the code size this binary measures.
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

/// The renderer, in a static like the frame set's (`src/main.rs`): its
/// scratch buffers on the stack, beside the 112.5 KiB frame, overflowed
/// the RAM into the frame (a bus fault on a pixel read as an address);
/// call once.
#[inline(never)]
fn renderer() -> Option<&'static mut TreeRenderer<FramePrecision, MAX_VERTS, Product>> {
    static RENDERER: ConstStaticCell<Option<TreeRenderer<FramePrecision, MAX_VERTS, Product>>> =
        ConstStaticCell::new(TreeRenderer::new(WIDTH, HEIGHT));
    RENDERER.take().as_mut()
}

#[entry]
fn main() -> ! {
    // SAFETY: the only reference to FRAME, taken once here.
    let buf: &mut [u16] = unsafe { &mut *core::ptr::addr_of_mut!(FRAME) };
    let ok = match (
        Tree::from_bytes(TREE),
        renderer(),
        Rgb565Framebuffer::new(buf, WIDTH, HEIGHT),
    ) {
        (Ok(tree), Some(r), Ok(mut fb)) => {
            let frame = VIEWS[0].frame(&tree);
            // The frame set's light (`fpt_frames`).
            r.renderer
                .set_light(Light::new(frame.key_light(), 0.25, 0.75));
            fb.fill_all(BACKGROUND);
            let memory = MEMORY.take();
            let drawn = r
                .render_cached::<WALK_DEPTH, _>(&tree, &frame, memory, &mut fb)
                .is_ok();
            let mut crc = PixelCrc::new();
            crc.update(fb.data());
            let crc = crc.finish();
            hprintln!("crc={:08x}", crc);
            let want = EXPECTED
                .lines()
                .filter_map(FrameLine::parse)
                .find(|l| l.scene == "bench_city" && l.view == 0)
                .map(|l| l.crc);
            drawn && want == Some(crc)
        }
        _ => false,
    };
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::wfi();
    }
}
