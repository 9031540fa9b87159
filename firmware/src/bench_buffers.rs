//! The static buffers of a build that `build.rs` sizes from the
//! `FPT_BENCH_*` variables (its `bench_config.rs`, which the including
//! binary has as `mod config`): the band (or frame) buffer and the frame's
//! working memory. Shared by the `bench` binary (`fpt mcu-bench`) and the
//! `accuracy` binary's `band` build (the study's Cortex-M0 column).

use core::mem::MaybeUninit;

use super::config::{BUF_WORDS, MEMORY_WORDS};

/// The band (or frame) buffer, zeroed; call once.
///
/// It is the last static (section `.uninit`, after `.bss`), right below the
/// stack: a stack that outgrows its room scribbles over pixels before it
/// reaches the renderer or the clock, so the run survives to report the
/// overflow (checked after every frame) instead of hanging.
pub fn buffer() -> &'static mut [u16] {
    #[link_section = ".uninit.fpt_bench_buf"]
    static mut BUF: MaybeUninit<[u16; BUF_WORDS]> = MaybeUninit::uninit();
    // SAFETY: called once, from `main`; no other reference to BUF exists.
    // The words are zeroed in place before the slice is made.
    unsafe {
        let p = core::ptr::addr_of_mut!(BUF).cast::<u16>();
        core::ptr::write_bytes(p, 0, BUF_WORDS);
        core::slice::from_raw_parts_mut(p, BUF_WORDS)
    }
}

/// The frame's working memory (`FPT_BENCH_MEMORY` words); call once.
pub fn memory() -> &'static mut [u32] {
    static mut MEMORY: [u32; MEMORY_WORDS] = [0; MEMORY_WORDS];
    // SAFETY: called once, from `main`; no other reference to MEMORY
    // exists.
    unsafe { &mut *core::ptr::addr_of_mut!(MEMORY) }
}
