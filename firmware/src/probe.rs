//! The two measuring probes of a frame ([`fpt_frames::Probe`]).
//!
//! Each frame is drawn twice:
//!
//! 1. with [`TotalProbe`], which only reads the clock at the frame's
//!    start/stop hooks (a few times per frame, one pair per band): the
//!    per-polygon hooks stay empty and compile to nothing, so this run
//!    costs what an unmeasured frame costs. It gives `instr`.
//! 2. with [`PhaseProbe`], which also reads the clock at every phase
//!    boundary (three times per polygon) and charges the time since the
//!    previous reading to the phase being left. It gives the parts.
//!
//! The second run is slower by the marks' own cost: the reads and the
//! bookkeeping, and the optimisations the marks prevent around them.
//! [`PhaseProbe::parts`] removes it: the extra time over the first run,
//! divided by the number of marks, is taken as the cost of one mark and
//! charged to the phase a mark enters (the clock is read first, the
//! bookkeeping after). The corrected parts then add up to `instr`; the
//! per-mark cost is reported so that its stability can be checked. The
//! split is an estimate (see `docs/cortex-m4.md` for a cross-check).

use core::cell::Cell;

use cortex_m::peripheral::SYST;
use fpt_frames::{Phase, Probe};

use crate::clock::now;

/// The SysTick counter's 24 bits.
const COUNTER_MASK: u32 = 0x00FF_FFFF;

/// Frame time only (see the module docs).
#[derive(Debug, Default)]
pub struct TotalProbe {
    since: Cell<u64>,
    total: Cell<u64>,
}

impl TotalProbe {
    /// Ticks between the start and stop hooks, summed.
    pub fn ticks(&self) -> u64 {
        self.total.get()
    }
}

impl Probe for TotalProbe {
    #[inline(always)]
    fn start(&self, _phase: Phase) {
        self.since.set(now());
    }
    #[inline(always)]
    fn stop(&self) {
        self.total
            .set(self.total.get() + now().wrapping_sub(self.since.get()));
    }
}

/// Time per phase (see the module docs).
///
/// Its marks read the raw 24-bit SysTick value only (one load) and keep
/// 24-bit differences, which stays exact because consecutive marks are far
/// less than 2^24 ticks (about 100 M instructions) apart: at most one
/// polygon, one buffer clear or the frame setup lies between two of them.
/// The cheaper the mark, the less it disturbs the code it measures.
#[derive(Debug)]
pub struct PhaseProbe {
    last: Cell<u32>,
    cur: Cell<Phase>,
    ticks: [Cell<u64>; 3],
    marks: [Cell<u32>; 3],
}

impl Default for PhaseProbe {
    fn default() -> Self {
        PhaseProbe {
            last: Cell::new(0),
            cur: Cell::new(Phase::Post),
            ticks: Default::default(),
            marks: Default::default(),
        }
    }
}

/// A frame's parts in instructions, indexed like [`Phase::ALL`].
#[derive(Clone, Copy, Debug)]
pub struct Parts {
    /// Post, transform, fill.
    pub instr: [u64; 3],
    /// The removed cost of one mark, in instructions (see the module docs).
    pub mark_cost: u64,
}

impl PhaseProbe {
    /// Charges the ticks since the last mark to the current phase; the
    /// counter counts down.
    #[inline(always)]
    fn charge(&self, now: u32) {
        let c = &self.ticks[self.cur.get() as usize];
        let d = self.last.get().wrapping_sub(now) & COUNTER_MASK;
        c.set(c.get() + u64::from(d));
        self.last.set(now);
    }

    /// The parts in instructions, given the unmarked frame's `total` (in
    /// instructions) and a ticks → instructions conversion.
    pub fn parts(&self, total: u64, instr: impl Fn(u64) -> u64) -> Parts {
        let raw: [u64; 3] = core::array::from_fn(|i| instr(self.ticks[i].get()));
        let marks: [u64; 3] = core::array::from_fn(|i| u64::from(self.marks[i].get()));
        let (sum, n) = (raw.iter().sum::<u64>(), marks.iter().sum::<u64>());
        let extra = sum.saturating_sub(total);
        // extra · k / n, rounded (0 when there are no marks).
        let share = |k: u64| (extra * k + n / 2).checked_div(n).unwrap_or(0);
        // Never more than the phase has.
        let strip = |i: usize| raw[i].saturating_sub(share(marks[i]));
        let (post, xform) = (strip(0), strip(1));
        // Rounding leftovers go to the fill, so that the parts add up.
        let fill = total.saturating_sub(post + xform);
        Parts {
            instr: [post, xform, fill],
            mark_cost: share(1),
        }
    }
}

impl Probe for PhaseProbe {
    #[inline(always)]
    fn start(&self, phase: Phase) {
        self.last.set(SYST::get_current());
        self.cur.set(phase);
    }
    #[inline(always)]
    fn enter(&self, phase: Phase) {
        self.charge(SYST::get_current());
        self.cur.set(phase);
        let m = &self.marks[phase as usize];
        m.set(m.get() + 1);
    }
    #[inline(always)]
    fn stop(&self) {
        self.charge(SYST::get_current());
    }
}
