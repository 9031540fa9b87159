//! How every firmware binary ends on a failure: one `error: ...` line on
//! the semihosting console and exit status 1 (a panic included), shared by
//! `main.rs` and `src/bin/accuracy.rs` (`src/bin/profile.rs` keeps a
//! silent handler so that its code size is a product's).

use cortex_m_semihosting::{debug, hprintln};

/// Prints `msg` and exits with failure.
pub fn fail(msg: core::fmt::Arguments<'_>) -> ! {
    hprintln!("error: {}", msg);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    fail(format_args!("panic: {}", info))
}
