//! The working memory `fpt mcu-bench` gives the firmware when `--memory`
//! is not given.
//!
//! On the Cortex-M4F (128 KiB) a run gets what the frames need: the most
//! any frame of the orbit used on the host with all it could want. On the
//! Cortex-M0 (16 KiB) that is rarely there, and the words are chosen in
//! two steps:
//!
//! 1. an estimate ([`estimate`]): what the RAM leaves beside the band
//!    buffer, the renderer's scratch and a 4 KiB reserve for the stack and
//!    the other statics;
//! 2. when the estimate is less than the frames need, it is **measured**
//!    ([`measured`]): a probe run of the firmware built with the estimate
//!    gives its statics besides the memory (`static_ram` less the
//!    estimate's bytes: no memory size changes them) and its stack peak
//!    (painted, every frame of the orbit); the memory is then what the RAM
//!    leaves beside those and [`MARGIN`] bytes, at most what the frames
//!    need.
//!
//! The run that is reported measures its statics and stack again, and
//! fails with the overflow measured if they outgrew the RAM. The stack
//! does not grow with the memory: socket's 8-row bands peak at 4,104 B
//! with 200, 700 and 1,635 words (the list overflowing, a band drawn as
//! the walk goes, plain replays) and 4,044 B with none.

use super::{band_words, Bench, Cpu};

/// Bytes of RAM the measured memory leaves free beside the probe run's
/// stack peak: for the paths the standard orbit does not take. The orbit's
/// frames take the deepest ones the firmware has (the band loop's frame,
/// the replay's 368 B and a fill's below it); clipping at the near plane,
/// which the orbit never needs, is a 176 B frame below the band loop
/// (`clip_polygon`, `llvm-objdump -d` of the `bench` ELF), shallower than
/// the replay. 256 B covers it with room to spare (a quarter of the
/// stack growth one inlining can bring, docs/small-ram.md).
pub(super) const MARGIN: u64 = 256;

/// The first guess (see the module docs): the frames' need (`used`), on the
/// Cortex-M0 at most what its RAM leaves beside the band buffer, the
/// renderer's scratch (as `build.rs` sizes it: 106 B a vertex) and 4 KiB
/// for the stack and the other statics.
pub(super) fn estimate(b: &Bench, max_vertices: usize, used: usize) -> usize {
    if b.cpu != Cpu::M0 {
        return used;
    }
    let verts = max_vertices.max(16);
    let band = 2 * band_words(b.size.0, b.size.1, b.band);
    let left = (b.cpu.ram() as usize).saturating_sub(band + 106 * verts + 4 * 1024);
    used.min(left / 4)
}

/// The memory a probe run with `estimate` words measured room for (see the
/// module docs): `static_ram` and `stack_peak` are the probe's, `ram` the
/// RAM's size, `used` what the frames need. `None` when the statics and
/// the stack leave no word.
pub(super) fn measured(
    ram: u64,
    estimate: usize,
    (static_ram, stack_peak): (u64, u64),
    used: usize,
) -> Option<usize> {
    let others = static_ram.checked_sub(4 * estimate as u64)?;
    let room = ram.checked_sub(others + stack_peak + MARGIN)?;
    let words = (room / 4) as usize;
    (words > 0).then_some(words.min(used))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_measured_memory_leaves_the_margin() {
        // Socket's probe: 1,635 words, 11,892 B of statics, a 4,104 B
        // stack, 4,896 words wanted.
        let words = measured(16384, 1635, (11892, 4104), 4896).unwrap();
        let total = 11892 - 4 * 1635 + 4 * words as u64 + 4104;
        assert!(
            total + MARGIN <= 16384 && total + MARGIN + 4 > 16384,
            "{words}"
        );
        // Never more than the frames need.
        assert_eq!(measured(16384, 1635, (11892, 4104), 1000), Some(1000));
        // No room: none.
        assert_eq!(measured(16384, 1635, (11892, 16000), 4896), None);
        assert_eq!(measured(16384, 1635, (100, 4104), 4896), None);
    }
}
