//! One frame of the frame set drawn exactly as the frame set draws it
//! (`src/main.rs`: the same renderer type, working memory and draw
//! function; feature `full` or `band`), once and without probes: the
//! target for comparing the instruction profiles of the two modes under
//! QEMU. The scene and view are chosen when building:
//! `FPT_PROFILE_SCENE` (`vise`, `house` or `bench_city`, the default) and
//! `FPT_PROFILE_VIEW` (0–4, default 0). It checks its checksum against the
//! frame set's (`trees/frames.txt`) and exits with a failure when it
//! differs.
//!
//! ```text
//! FPT_PROFILE_VIEW=4 cargo build --release --no-default-features --features band --bin profile_set
//! qemu-system-arm -machine netduinoplus2 -cpu cortex-m4 -nographic \
//!     -semihosting-config enable=on,target=native -icount shift=0 \
//!     -d in_asm,exec,nochain -D /tmp/band.log \
//!     -kernel target/thumbv7em-none-eabihf/release/profile_set
//! python3 ../tools/profile_phases.py /tmp/band.log target/thumbv7em-none-eabihf/release/profile_set
//! ```
//!
//! (the same with the default feature for the full frame, into another
//! log and a copy of the ELF, then `profile_phases.py` with both pairs
//! for the difference by phase).
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use fpt_frames::{FrameLine, FrameRenderer, NoProbe, HEIGHT, VIEWS, WIDTH};
use fpt_nostd::reader::Tree;
use static_cell::ConstStaticCell;

#[cfg(feature = "band")]
use fpt_frames::{render_banded as draw, BAND_WORDS as WORDS};
#[cfg(feature = "full")]
use fpt_frames::{render_full as draw, FRAME_WORDS as WORDS};

/// The scene drawn: `FPT_PROFILE_SCENE` when building.
const SCENE: &str = match option_env!("FPT_PROFILE_SCENE") {
    Some(s) => s,
    None => "bench_city",
};

/// Its tree, as the frame set embeds it.
static TREE: &[u8] = match SCENE.as_bytes() {
    b"vise" => include_bytes!("../../trees/vise.fpt"),
    b"house" => include_bytes!("../../trees/house.fpt"),
    _ => include_bytes!("../../trees/bench_city.fpt"),
};
static EXPECTED: &str = include_str!("../../trees/frames.txt");

/// The frame set's working memory (`src/main.rs`, `MEMORY_WORDS`, Cortex-M4).
#[cfg(feature = "band")]
const MEMORY_WORDS: usize = 10 * 1024;
/// The frame set's working memory (`src/main.rs`, `MEMORY_WORDS`).
#[cfg(feature = "full")]
const MEMORY_WORDS: usize = 868;

static BUF: ConstStaticCell<[u16; WORDS]> = ConstStaticCell::new([0; WORDS]);
static MEMORY: ConstStaticCell<[u32; MEMORY_WORDS]> = ConstStaticCell::new([0; MEMORY_WORDS]);

/// Halts with a failure exit, printing nothing (as `profile.rs`: a
/// formatted panic message would weigh on every bounds check's path).
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

/// The renderer, in a static like the frame set's; call once.
#[inline(never)]
fn renderer() -> Option<&'static mut FrameRenderer> {
    static RENDERER: ConstStaticCell<Option<FrameRenderer>> =
        ConstStaticCell::new(FrameRenderer::new(WIDTH, HEIGHT));
    RENDERER.take().as_mut()
}

/// The view drawn: `FPT_PROFILE_VIEW` when building (0 unless 1–4).
fn view() -> u32 {
    match option_env!("FPT_PROFILE_VIEW") {
        Some("1") => 1,
        Some("2") => 2,
        Some("3") => 3,
        Some("4") => 4,
        _ => 0,
    }
}

#[entry]
fn main() -> ! {
    let k = view();
    let (buf, memory) = (BUF.take(), MEMORY.take());
    let crc = match (Tree::from_bytes(TREE), renderer(), VIEWS.get(k as usize)) {
        (Ok(tree), Some(r), Some(v)) => draw(r, &tree, v, buf, memory, &NoProbe)
            .ok()
            .map(|out| out.crc),
        _ => None,
    };
    let want = EXPECTED
        .lines()
        .filter_map(FrameLine::parse)
        .find(|l| l.scene == SCENE && l.view == k)
        .map(|l| l.crc);
    if let Some(crc) = crc {
        hprintln!("scene={} view={} crc={:08x}", SCENE, k, crc);
    }
    debug::exit(if crc.is_some() && crc == want {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::wfi();
    }
}
