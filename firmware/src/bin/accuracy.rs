//! The accuracy study's configurations on the MCU: the `mcu_instr`
//! (Cortex-M4F) and `m0_instr` (Cortex-M0) columns of
//! `fpt bench-accuracy`.
//!
//! * Feature `full` (the default; Cortex-M4F, QEMU `netduinoplus2`):
//!   `cargo run --release --bin accuracy` (in `firmware/`) draws the
//!   benchmark scene from every view with every configuration of
//!   [`fpt_frames::accuracy::CONFIGS`] into a whole 240×240 frame (the
//!   `vertex-q16`/`vertex-q32`/`int-q16` rows from the trees stored in that
//!   encoding, all three embedded).
//! * Feature `band` (the Cortex-M0 of QEMU `microbit`: 16 KiB of RAM, 256
//!   KiB of flash): the same frames drawn band by band, as a 16 KiB part
//!   must, from the one tree `FPT_BENCH_TREE`, with `FPT_BENCH_BAND` rows
//!   a band and `FPT_BENCH_MEMORY` words of working memory, for the
//!   configurations `FPT_ACCURACY_CONFIGS` (comma-separated; `build.rs`)
//!   that draw that tree's encoding. Only their arithmetics are compiled
//!   in ([`fpt_frames::accuracy::render_config_in`]): the flash holds a
//!   `bench_city` tree and one arithmetic's walk-and-fill, so every
//!   configuration takes twelve builds
//!   ([`fpt_frames::accuracy::one_arithmetic_builds`], run by the test
//!   `m0_accuracy_matches_host`), e.g.
//!
//!   ```text
//!   FPT_BENCH_TREE=trees/bench_city.q16.fpt FPT_ACCURACY_CONFIGS=int-q16 \
//!     FPT_BENCH_BAND=8 FPT_BENCH_MEMORY=512 cargo run --release \
//!     --bin accuracy --target thumbv6m-none-eabi \
//!     --no-default-features --features band
//!   ```
//!
//! Output: one line per frame,
//!
//! ```text
//! accuracy config=NAME view=K crc=XXXXXXXX instr=N
//! ```
//!
//! measured like the frame set's `instr` (SysTick under `-icount`, see the
//! main binary's `clock`; in bands the checksumming of each band is taken
//! out), then `static_ram=BYTES` and `stack_peak=BYTES`. It exits with
//! failure if a checksum differs from the host's (`trees/accuracy.txt`,
//! written by `fpt frames --export firmware/trees`; a band frame's
//! checksum is the full frame's) or the stack reached the statics. Feed
//! the output to `fpt bench-accuracy --mcu FILE` (`--m0 FILE` for the
//! band builds' lines put together).
#![no_std]
#![no_main]

#[allow(dead_code)] // the calibration report belongs to the frame set
#[path = "../clock.rs"]
mod clock;
#[path = "../fail.rs"]
mod fail;
#[allow(dead_code)] // the phase probe belongs to the frame set
#[path = "../probe.rs"]
mod probe;
#[allow(dead_code)]
#[path = "../stack.rs"]
mod stack;

#[cfg(feature = "band")]
#[path = "../bench_buffers.rs"]
mod bench_buffers;
#[cfg(feature = "band")]
#[allow(dead_code)]
mod config {
    include!(concat!(env!("OUT_DIR"), "/bench_config.rs"));
}

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hprintln};

use fpt_frames::accuracy::{render_config_in, vertex_format, AccuracyLine, CONFIGS};
use fpt_frames::VIEWS;
use fpt_nostd::reader::Tree;
use target::Drawn;

use clock::Clock;
use fail::fail;
use probe::TotalProbe;

/// The host's lines for the same frames.
static EXPECTED: &str = include_str!("../../trees/accuracy.txt");

fn expected_crc(config: &str, view: u32) -> Option<u32> {
    EXPECTED
        .lines()
        .filter_map(AccuracyLine::parse)
        .find(|l| l.config == config && l.view == view)
        .map(|l| l.crc)
}

/// Where the frames are drawn: a whole frame.
#[cfg(not(feature = "band"))]
mod target {
    use fpt_frames::accuracy::Full;
    use fpt_frames::FRAME_WORDS;

    /// The target of a frame.
    pub type Drawn<'a> = Full<'a>;

    /// The arithmetics compiled in: all.
    pub const SET: u32 = fpt_frames::accuracy::ALL_ARITHMETICS;

    /// Every configuration is drawn.
    pub fn chosen(_config: &str) -> bool {
        true
    }
    use fpt_nostd::format::VertexFormat;

    /// The benchmark scene's trees, by vertex encoding.
    static TREES: [(VertexFormat, &[u8]); 3] = [
        (
            VertexFormat::F32,
            include_bytes!("../../trees/bench_city.f32.fpt"),
        ),
        (
            VertexFormat::Q16,
            include_bytes!("../../trees/bench_city.q16.fpt"),
        ),
        (
            VertexFormat::Q32,
            include_bytes!("../../trees/bench_city.q32.fpt"),
        ),
    ];

    /// The tree stored as `format`.
    pub fn tree_bytes(format: VertexFormat) -> Option<&'static [u8]> {
        TREES.iter().find(|(f, _)| *f == format).map(|t| t.1)
    }

    /// The frame buffer; call once.
    pub fn buffers() -> &'static mut [u16] {
        static mut FRAME: [u16; FRAME_WORDS] = [0; FRAME_WORDS];
        // SAFETY: called once, from `main`; no other reference to FRAME.
        unsafe { &mut *core::ptr::addr_of_mut!(FRAME) }
    }

    /// The target of one frame.
    pub fn target<'a>(buf: &'a mut &'static mut [u16]) -> Drawn<'a> {
        Full(buf)
    }
}

/// Where the frames are drawn: bands, and the working memory.
#[cfg(feature = "band")]
mod target {
    use super::config::{ACCURACY_CONFIGS, BAND, TREE};
    use fpt_frames::accuracy::Bands;
    use fpt_nostd::format::VertexFormat;

    /// The target of a frame.
    pub type Drawn<'a> = Bands<'a>;

    /// The arithmetics compiled in: those of `FPT_ACCURACY_CONFIGS`.
    pub const SET: u32 = fpt_frames::accuracy::arithmetics(ACCURACY_CONFIGS);

    /// Whether `config` is one of `FPT_ACCURACY_CONFIGS`.
    pub fn chosen(config: &str) -> bool {
        ACCURACY_CONFIGS.contains(&config)
    }
    use fpt_nostd::reader::Tree;

    /// The tree of this build (`FPT_BENCH_TREE`) if it is stored as
    /// `format`.
    pub fn tree_bytes(format: VertexFormat) -> Option<&'static [u8]> {
        Tree::from_bytes(TREE)
            .is_ok_and(|t| t.vertex_format() == format)
            .then_some(TREE)
    }

    /// The band buffer and the working memory
    /// (`bench_buffers`, the `bench` binary's); call once.
    pub fn buffers() -> (&'static mut [u16], &'static mut [u32]) {
        (
            super::bench_buffers::buffer(),
            super::bench_buffers::memory(),
        )
    }

    /// The target of one frame.
    pub fn target<'a>(
        (buf, memory): &'a mut (&'static mut [u16], &'static mut [u32]),
    ) -> Drawn<'a> {
        Bands {
            buf,
            rows: BAND,
            memory,
        }
    }
}

/// One measured frame; `false` if its checksum is not the host's.
#[inline(never)]
fn frame(clock: &Clock, config: &str, tree: &Tree<'_>, k: usize, target: Drawn<'_>) -> bool {
    let probe = TotalProbe::default();
    let crc =
        match render_config_in::<{ target::SET }, _, _>(config, tree, &VIEWS[k], target, &probe) {
            Ok(c) => c,
            Err(e) => fail(format_args!("{config} view {k}: {e}")),
        };
    let line = AccuracyLine {
        config,
        view: k as u32,
        crc,
    };
    hprintln!("{} instr={}", line, clock.instr(probe.ticks()));
    if stack::overflowed() {
        fail(format_args!(
            "stack overflow: the stack reached the statics ({} B of RAM left for it)",
            stack::room()
        ));
    }
    if expected_crc(config, k as u32) == Some(crc) {
        true
    } else {
        hprintln!(
            "error: {} view {}: crc {:08x} is not the host's (trees/accuracy.txt)",
            config,
            k,
            crc
        );
        false
    }
}

#[entry]
fn main() -> ! {
    stack::paint();
    let clock = Clock::take_and_start();
    let mut bufs = target::buffers();
    let mut ok = true;
    // Every chosen configuration that draws one of the embedded trees.
    for config in CONFIGS.into_iter().filter(|c| target::chosen(c)) {
        let want = vertex_format(config);
        let Some(bytes) = target::tree_bytes(want) else {
            continue;
        };
        let tree = match Tree::from_bytes(bytes) {
            Ok(t) => t,
            Err(e) => fail(format_args!("{config}: {e}")),
        };
        for k in 0..VIEWS.len() {
            ok &= frame(&clock, config, &tree, k, target::target(&mut bufs));
        }
    }
    hprintln!("static_ram={}", stack::static_ram());
    hprintln!("stack_peak={}", stack::peak());
    if !ok {
        fail(format_args!("checksums differ from trees/accuracy.txt"));
    }
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}

#[exception]
unsafe fn HardFault(ef: &ExceptionFrame) -> ! {
    fail(format_args!(
        "hard fault at pc {:#010x} (a stack overflow?)",
        ef.pc()
    ))
}
