//! Time in instructions: SysTick on the core clock, extended to 64 bits,
//! calibrated against a loop of known length.
//!
//! Under `-icount shift=0` QEMU advances its virtual clock by 2^0 ns per
//! executed instruction, and the SysTick counts at the core clock
//! (168 MHz on `netduinoplus2`), so one tick is 1000/168 ≈ 5.95
//! instructions. Rather than trusting that figure, [`Clock::calibrate`]
//! times an assembly loop of exactly 9 instructions per iteration (7 `nop`,
//! `subs`, `bne`) for N and for 2N iterations: the difference is exactly
//! 9N instructions in (T(2N) − T(N)) ticks, whatever the call overhead.
//! Every reading is then converted with that ratio; a single reading is
//! exact to within one tick (about 6 instructions on the M4, 63 on the
//! M0, which has no cycle counter to do better with).
//!
//! The counter is 24 bits wide (2^24 ticks ≈ 100 M instructions). The
//! SysTick exception counts the wraps, and [`now`] combines the count with
//! the current value, retrying if a wrap is counted while it reads and
//! adding the wrap that is pending but not yet counted; so readings never
//! go backwards, however long the measured code runs.

use core::sync::atomic::{AtomicU32, Ordering};

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::{SCB, SYST};
use cortex_m_rt::exception;

/// The SysTick reload value: the full 24-bit range.
const RELOAD: u32 = 0x00FF_FFFF;
/// Ticks per wrap.
const PERIOD: u64 = RELOAD as u64 + 1;
/// Iterations of the shorter calibration run.
const CAL_ITERS: u32 = 500_000;
/// Instructions per iteration of [`spin`].
const CAL_LOOP_INSTR: u64 = 9;

/// Wraps of the SysTick counter since [`Clock::start`].
static WRAPS: AtomicU32 = AtomicU32::new(0);

#[exception]
fn SysTick() {
    // Load and store rather than `fetch_add`, which the Cortex-M0 lacks:
    // this handler is the only writer, and it cannot interrupt itself.
    WRAPS.store(WRAPS.load(Ordering::Relaxed) + 1, Ordering::Relaxed);
}

/// Ticks since [`Clock::start`], monotonic (see the module docs).
#[inline(always)]
pub fn now() -> u64 {
    loop {
        let w1 = WRAPS.load(Ordering::Relaxed);
        let cur = SYST::get_current();
        let pending = SCB::is_pendst_pending();
        let w2 = WRAPS.load(Ordering::Relaxed);
        if w1 == w2 {
            // A pending, uncounted wrap happened before `cur` was read if
            // the counter has just been reloaded (is high).
            let late = u64::from(pending && cur > RELOAD / 2);
            return (u64::from(w1) + late) * PERIOD + u64::from(RELOAD - cur);
        }
    }
}

/// 9 instructions per iteration, `n ≥ 1` iterations.
#[inline(never)]
fn spin(n: u32) {
    // SAFETY: register-only loop; touches no memory and no stack.
    unsafe {
        core::arch::asm!(
            "2:",
            "nop", "nop", "nop", "nop", "nop", "nop", "nop",
            "subs {n}, {n}, #1",
            "bne 2b",
            n = inout(reg) n.max(1) => _,
            options(nomem, nostack),
        );
    }
}

/// The calibrated clock.
#[derive(Clone, Copy, Debug)]
pub struct Clock {
    /// Instructions of the calibration (the numerator of the ratio).
    pub cal_instr: u64,
    /// Ticks they took (the denominator).
    pub cal_ticks: u64,
}

impl Clock {
    /// The start-up of a measuring binary: takes the core peripherals and
    /// starts the clock ([`Clock::start`]), or ends the run with a failure
    /// saying which of the two was impossible.
    pub fn take_and_start() -> Clock {
        let Some(mut p) = cortex_m::Peripherals::take() else {
            crate::fail::fail(format_args!("peripherals already taken"))
        };
        let Some(clock) = Clock::start(&mut p.SYST) else {
            crate::fail::fail(format_args!("SysTick does not count"))
        };
        clock
    }

    /// Starts the SysTick on the core clock with its wrap interrupt and
    /// calibrates it; `None` if the counter does not run.
    pub fn start(syst: &mut SYST) -> Option<Clock> {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_interrupt();
        syst.enable_counter();
        // The cleared counter reads 0 until its first reload; readings
        // only make sense from then on.
        if !(0..1000).any(|_| SYST::get_current() != 0) {
            return None;
        }
        Clock::calibrate()
    }

    fn calibrate() -> Option<Clock> {
        let time = |n: u32| {
            let t0 = now();
            spin(n);
            now() - t0
        };
        let (one, two) = (time(CAL_ITERS), time(2 * CAL_ITERS));
        let cal_ticks = two.checked_sub(one).filter(|&t| t > 0)?;
        Some(Clock {
            cal_instr: CAL_LOOP_INSTR * u64::from(CAL_ITERS),
            cal_ticks,
        })
    }

    /// `ticks` in instructions, rounded to nearest.
    pub fn instr(&self, ticks: u64) -> u64 {
        (ticks * self.cal_instr + self.cal_ticks / 2) / self.cal_ticks
    }

    /// Instructions per 1000 ticks (for the log).
    pub fn instr_per_kilotick(&self) -> u64 {
        self.instr(1000)
    }
}
