//! The accuracy study's configurations on the Cortex-M4 (QEMU): the
//! `mcu_instr` column of `fpt bench-accuracy`.
//!
//! `cargo run --release --bin accuracy` (in `firmware/`) draws the
//! benchmark scene from every view with every configuration of
//! [`fpt_frames::accuracy::CONFIGS`] (the `vertex-q16`/`vertex-q32`
//! rows from the trees stored in that encoding) and prints one line per
//! frame,
//!
//! ```text
//! accuracy config=NAME view=K crc=XXXXXXXX instr=N
//! ```
//!
//! measured like the frame set's `instr` (SysTick under `-icount`, see the
//! main binary's `clock`), then `stack_peak=BYTES`. It exits with failure
//! if a checksum differs from the host's (`trees/accuracy.txt`, written by
//! `fpt frames --export firmware/trees`). Feed the output to
//! `fpt bench-accuracy --mcu FILE`.
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

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};

use fpt_frames::accuracy::{render_config, vertex_format, AccuracyLine, CONFIGS};
use fpt_frames::{FRAME_WORDS, VIEWS};
use fpt_nostd::format::VertexFormat;
use fpt_nostd::reader::Tree;

use clock::Clock;
use fail::fail;
use probe::TotalProbe;

/// The benchmark scene's trees, by vertex encoding.
static TREES: [(VertexFormat, &[u8]); 3] = [
    (
        VertexFormat::F32,
        include_bytes!("../../trees/bench_city.fpt"),
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

/// The host's lines for the same frames.
static EXPECTED: &str = include_str!("../../trees/accuracy.txt");

static mut FRAME: [u16; FRAME_WORDS] = [0; FRAME_WORDS];

fn expected_crc(config: &str, view: u32) -> Option<u32> {
    EXPECTED
        .lines()
        .filter_map(AccuracyLine::parse)
        .find(|l| l.config == config && l.view == view)
        .map(|l| l.crc)
}

/// One measured frame; `false` if its checksum is not the host's.
#[inline(never)]
fn frame(clock: &Clock, config: &str, tree: &Tree<'_>, k: usize, buf: &mut [u16]) -> bool {
    let probe = TotalProbe::default();
    let crc = match render_config(config, tree, &VIEWS[k], buf, &probe) {
        Ok(c) => c,
        Err(e) => fail(format_args!("{config} view {k}: {e}")),
    };
    let line = AccuracyLine {
        config,
        view: k as u32,
        crc,
    };
    hprintln!("{} instr={}", line, clock.instr(probe.ticks()));
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
    // SAFETY: the only reference to FRAME, taken once here.
    let buf: &mut [u16] = unsafe { &mut *core::ptr::addr_of_mut!(FRAME) };
    let mut ok = true;
    for config in CONFIGS {
        let want = vertex_format(config);
        let Some((_, bytes)) = TREES.iter().find(|(f, _)| *f == want) else {
            fail(format_args!("no tree for {config}"))
        };
        let tree = match Tree::from_bytes(bytes) {
            Ok(t) => t,
            Err(e) => fail(format_args!("{config}: {e}")),
        };
        for k in 0..VIEWS.len() {
            ok &= frame(&clock, config, &tree, k, buf);
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
