//! Feudal on a Cortex-M4 (QEMU netduinoplus2).
#![no_std]
#![no_main]

use cortex_m::peripheral::{syst::SystClkSource, SYST};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    hprintln!("panic: {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {}
}

#[entry]
fn main() -> ! {
    let mut p = cortex_m::Peripherals::take().unwrap();
    p.SYST.set_clock_source(SystClkSource::Core);
    p.SYST.set_reload(0x00FF_FFFF);
    p.SYST.clear_current();
    p.SYST.enable_counter();
    let t0 = SYST::get_current();
    let mut acc = 0u32;
    for i in 0..1000u32 {
        acc = acc.wrapping_mul(31).wrapping_add(i);
    }
    let t1 = SYST::get_current();
    hprintln!("hello acc={} ticks={}", acc, t0.wrapping_sub(t1) & 0xFF_FFFF);
    debug::exit(debug::EXIT_SUCCESS);
    loop {}
}
