//! One `bench_city` frame (view 0, feature-independent, full frame) and
//! nothing else: the target for an instruction profile under QEMU.
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

use fpt_nostd::frames::{render_full, FrameRenderer, NoProbe, FRAME_WORDS, HEIGHT, VIEWS, WIDTH};
use fpt_nostd::reader::Tree;

static TREE: &[u8] = include_bytes!("../../trees/bench_city.fpt");
static mut FRAME: [u16; FRAME_WORDS] = [0; FRAME_WORDS];

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

#[entry]
fn main() -> ! {
    // SAFETY: the only reference to FRAME, taken once here.
    let buf: &mut [u16] = unsafe { &mut *core::ptr::addr_of_mut!(FRAME) };
    let ok = match (Tree::from_bytes(TREE), FrameRenderer::new(WIDTH, HEIGHT)) {
        (Ok(tree), Some(mut r)) => render_full(&mut r, &tree, &VIEWS[0], buf, &NoProbe)
            .map(|o| hprintln!("crc={:08x}", o.crc))
            .is_ok(),
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
