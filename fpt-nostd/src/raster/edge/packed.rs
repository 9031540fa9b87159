//! [`Dda32`]'s state packed in three words ([`Packed`]), for the row loops
//! of the triangles and chains and for the band carry's kept edges.

use super::{Dda32, ScreenPt, Stepper};

/// Bits of [`Packed`]'s excess field.
const PACK_K: u32 = 20;

/// Whether [`Packed`] steps every edge within ±[`SMALL`](super::SMALL) exactly at `sub`
/// sub-pixel bits: 3 and 4 (the default, `DefaultPrecision`). The
/// monotone chains ([`super::super::chain`]) take it there; with other `sub`
/// polygons of more than three corners take the general fill (the same
/// spans).
#[inline(always)]
pub(crate) fn packs(sub: u32) -> bool {
    (3..=4).contains(&sub)
}

/// [`Dda32`]'s state in three words instead of five, for the row loops of
/// the triangles and chains: a row loop between two edges keeps both
/// steppers live, and five words each with the row's address, its column
/// bounds and the colour were more values than a Cortex-M4 has registers
/// (every row reloaded four of them from the stack). Packed, a stepper is
/// one word of state and two constants, and a row's step is an add, a bit
/// test and a conditional add.
///
/// [`Dda32`] keeps the crossing `c` and its excess `g` (`0 ≤ g < D`); a row
/// adds `qs` to `c`, takes `rs` from `g` and, when `g` drops below 0, adds
/// `D` back and one more to `c`. Here `w = c·2^K + g`, and a row adds
/// `step = qs·2^K − rs` (wrapping): that is `(c + qs)·2^K + (g − rs)` when
/// `g ≥ rs`, and `(c + qs − 1)·2^K + (2^K + g − rs)` when not (the low
/// field borrowed from `c`). With `D ≤ 2^(K−1)` the low field is below
/// `2^(K−1)` in the first case and above it in the second (`rs < D`), so
/// bit `K − 1` tells them apart, and adding `fix = 2^K + D` turns the
/// second into `(c + qs + 1)·2^K + (g − rs + D)`: [`Dda32`]'s next state.
/// The crossing is `w >> K` while `c` fits the `32 − K` high bits.
///
/// Where that holds ([`packs`]): for endpoints within ±[`SMALL`](super::SMALL) at `sub`
/// sub-pixel bits, `D = dy·2^(sub+1) < 2^(15+sub)`, and every crossing of
/// an active row lies between the endpoints' columns, `|c| ≤ 2^(13−sub)`.
/// With `K = 20`, `D ≤ 2^19` needs `sub ≤ 4` and `−2^11 ≤ c < 2^11` needs
/// `sub ≥ 3`. The row loops step both edges once more after a run's last
/// row; an edge that ended there may leave that range, is never read
/// again, and the arithmetic wraps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Packed {
    /// `c·2^K + g`.
    w: i32,
    /// `qs·2^K − rs`, wrapping.
    step: i32,
    /// `2^K + D`.
    fix: i32,
}

impl Packed {
    /// [`Dda32::start`], packed: for endpoints within ±[`SMALL`](super::SMALL) and `sub`
    /// where [`packs`] holds.
    #[inline(always)]
    pub(crate) fn start(t: ScreenPt, b: ScreenPt, sub: u32, y: i32) -> Packed {
        Packed::of(&Dda32::start(t, b, sub, y))
    }

    /// [`Packed::start`] with the start always inlined (the triangles').
    #[inline(always)]
    pub(crate) fn start_inline(t: ScreenPt, b: ScreenPt, sub: u32, y: i32) -> Packed {
        Packed::of(&Dda32::start_inline(t, b, sub, y))
    }

    /// `d` packed (where [`packs`] holds and its edge is within ±[`SMALL`](super::SMALL)).
    #[inline(always)]
    pub(crate) fn of(d: &Dda32) -> Packed {
        Packed {
            w: d.c.wrapping_shl(PACK_K).wrapping_add(d.g),
            step: d.qs.wrapping_shl(PACK_K).wrapping_sub(d.rs),
            fix: (1 << PACK_K) + d.d,
        }
    }

    /// The state as three words, for keeping it in caller memory between
    /// bands (`super::carry`); [`Packed::from_words`] reads it back.
    #[inline(always)]
    pub(crate) fn to_words(self) -> [u32; 3] {
        [self.w, self.step, self.fix].map(|w| w as u32)
    }

    /// The state [`Packed::to_words`] wrote.
    #[inline(always)]
    pub(crate) fn from_words([w, step, fix]: [u32; 3]) -> Packed {
        Packed {
            w: w as i32,
            step: step as i32,
            fix: fix as i32,
        }
    }
}

impl Stepper for Packed {
    #[inline(always)]
    fn crossing(&self) -> i32 {
        self.w >> PACK_K
    }
    #[inline(always)]
    fn step(&mut self) {
        let w = self.w.wrapping_add(self.step);
        self.w = if w & (1 << (PACK_K - 1)) != 0 {
            w.wrapping_add(self.fix)
        } else {
            w
        };
    }
}
