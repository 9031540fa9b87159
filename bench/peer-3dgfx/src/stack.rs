//! Stack high-water mark by painting, and the static RAM in use.
//!
//! cortex-m-rt puts the statics (`.data`, `.bss`, `.uninit`) at the bottom
//! of RAM and the stack above them, from `_stack_start` (the top of RAM)
//! down to `_stack_end` (the end of the statics). [`paint`], called first
//! thing in `main`, fills the unused stack — from `_stack_end` up to the
//! current stack pointer — with [`PATTERN`]; everything below the stack
//! pointer is free at that moment, and the loop is assembly that uses only
//! registers, so it overwrites nothing live. [`peak`] later finds the
//! lowest word that no longer holds the pattern: the deepest the stack has
//! been, including exception frames. A pushed word that happens to equal
//! the pattern would be missed only if it were the deepest one; with a
//! 32-bit pattern that is improbable.
//!
//! `main` paints twice: at reset, and again after start-up (when the
//! SysTick interrupt is already running: an exception taken while painting
//! stacks its frame below the SP, which the loop may then paint over; the
//! frame is dead by then, so that is harmless), so that the start-up peak
//! and the peak while drawing frames are reported apart.

/// What unused stack words hold.
pub const PATTERN: u32 = 0xDEAD_BEEF;

extern "C" {
    /// Top of the stack (initial SP), from cortex-m-rt's `link.x`.
    static _stack_start: u32;
    /// Bottom of the stack region: the end of the statics.
    static _stack_end: u32;
    /// Start of `.data`: the first static, at the start of RAM.
    static __sdata: u32;
}

fn stack_top() -> usize {
    // Only the address of the linker symbol is taken (no read).
    core::ptr::addr_of!(_stack_start) as usize
}

fn stack_bottom() -> usize {
    // Only the address of the linker symbol is taken (no read).
    core::ptr::addr_of!(_stack_end) as usize
}

/// Bytes of RAM taken by statics (`.data` + `.bss` + `.uninit`).
pub fn static_ram() -> usize {
    // Only the address of the linker symbol is taken (no read).
    let start = core::ptr::addr_of!(__sdata) as usize;
    stack_bottom() - start
}

/// Fills the free stack below the stack pointer with [`PATTERN`].
#[inline(always)]
pub fn paint() {
    let bottom = stack_bottom();
    // SAFETY: writes whole words from `_stack_end` (4-aligned, asserted by
    // link.x) up to but excluding the current SP: memory that belongs to
    // no static and no live stack frame. Only registers are used.
    // The Cortex-M0 (Thumb-1) has no post-indexed store: store, then add.
    #[cfg(not(peer_armv6m))]
    unsafe {
        core::arch::asm!(
            "mov {sp}, sp",
            "2:",
            "cmp {p}, {sp}",
            "bhs 3f",
            "str {pat}, [{p}], #4",
            "b 2b",
            "3:",
            p = inout(reg) bottom => _,
            sp = out(reg) _,
            pat = in(reg) PATTERN,
            options(nostack),
        );
    }
    // SAFETY: as above.
    #[cfg(peer_armv6m)]
    unsafe {
        core::arch::asm!(
            "mov {sp}, sp",
            "2:",
            "cmp {p}, {sp}",
            "bhs 3f",
            "str {pat}, [{p}]",
            "adds {p}, #4",
            "b 2b",
            "3:",
            p = inout(reg) bottom => _,
            sp = out(reg) _,
            pat = in(reg) PATTERN,
            options(nostack),
        );
    }
}

/// The deepest stack use since [`paint`], in bytes.
pub fn peak() -> usize {
    let (bottom, top) = (stack_bottom(), stack_top());
    let mut p = bottom;
    while p < top {
        // SAFETY: `p` is a 4-aligned address inside the stack region,
        // below the current SP or inside live frames; reading a word there
        // is always allowed (volatile: the compiler knows nothing of it).
        let w = unsafe { core::ptr::read_volatile(p as *const u32) };
        if w != PATTERN {
            break;
        }
        p += 4;
    }
    top - p
}

/// Bytes between the end of the statics and the top of RAM: the most the
/// stack can take.
pub fn room() -> usize {
    stack_top() - stack_bottom()
}

/// Whether the stack has reached the end of the statics since [`paint`]
/// (its lowest word is no longer the pattern): it may have overwritten
/// them, and its peak is unknown.
pub fn overflowed() -> bool {
    peak() >= room()
}
