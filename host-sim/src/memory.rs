//! Heap accounting for the `fpt` tool: the peak a build reached, a limit,
//! and running out of memory as an error instead of an abort.
//!
//! [`Counting`] wraps the system allocator; `fpt` installs it as the global
//! allocator. It keeps the bytes in use and their peak (so `fpt
//! bench-build` reports each build's peak heap, which the process's peak
//! RSS cannot do for several builds in one run), refuses allocations past
//! [`set_limit`] (`fpt build --max-memory`), and when an allocation fails
//! during a build it prints `error: not enough memory to build this mesh
//! (needs about N MiB)` and exits with status 2. The standard library
//! would abort (status 134); since output files are written whole at the
//! end ([`crate::output::write_atomic`]), exiting during the build leaves
//! no partial file.
//!
//! Without the allocator installed (library users, tests) the counters
//! stay at zero and [`peak`] returns `None`.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static LIMIT: AtomicUsize = AtomicUsize::new(usize::MAX);
/// The estimate of the build under way, in MiB; 0 outside a build.
static BUILD_MIB: AtomicUsize = AtomicUsize::new(0);
static INSTALLED: AtomicBool = AtomicBool::new(false);

/// The counting allocator (see the module docs).
pub struct Counting;

impl Counting {
    fn grant(&self, size: usize) -> bool {
        let now = IN_USE.fetch_add(size, Relaxed) + size;
        if now > LIMIT.load(Relaxed) {
            IN_USE.fetch_sub(size, Relaxed);
            return false;
        }
        PEAK.fetch_max(now, Relaxed);
        true
    }

    fn failed(&self, size: usize) -> ! {
        let mib = BUILD_MIB
            .load(Relaxed)
            .max((IN_USE.load(Relaxed) + size) >> 20)
            .max(1);
        let msg = if BUILD_MIB.load(Relaxed) > 0 {
            format_no_alloc(
                b"error: not enough memory to build this mesh (needs about ",
                mib,
            )
        } else {
            format_no_alloc(b"error: out of memory (needs about ", mib)
        };
        exit_with(&msg.0[..msg.1])
    }
}

/// `prefix`, `mib` in decimal, ` MiB)` and a newline, without allocating.
fn format_no_alloc(prefix: &[u8], mib: usize) -> ([u8; 128], usize) {
    let mut buf = [0u8; 128];
    let mut n = 0;
    for &b in prefix.iter().take(80) {
        buf[n] = b;
        n += 1;
    }
    let mut digits = [0u8; 20];
    let (mut k, mut v) = (0, mib);
    loop {
        digits[k] = b'0' + (v % 10) as u8;
        k += 1;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    while k > 0 {
        k -= 1;
        buf[n] = digits[k];
        n += 1;
    }
    for &b in b" MiB)\n" {
        buf[n] = b;
        n += 1;
    }
    (buf, n)
}

#[cfg(unix)]
fn exit_with(msg: &[u8]) -> ! {
    // SAFETY: write(2) and _exit(2) are async-signal-safe and allocate
    // nothing; the buffer is valid for its length.
    #[allow(unsafe_code)]
    unsafe {
        libc::write(2, msg.as_ptr().cast(), msg.len());
        libc::_exit(2)
    }
}

#[cfg(not(unix))]
fn exit_with(msg: &[u8]) -> ! {
    use std::io::Write;
    let _ = std::io::stderr().write_all(msg);
    std::process::exit(2)
}

// SAFETY: every call is forwarded to the system allocator with the same
// layout; the counters only decide whether to forward an allocation.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !self.grant(layout.size()) {
            self.failed(layout.size());
        }
        // SAFETY: the caller's contract is passed on unchanged.
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            self.failed(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !self.grant(layout.size()) {
            self.failed(layout.size());
        }
        // SAFETY: as in `alloc`.
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            self.failed(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        IN_USE.fetch_sub(layout.size(), Relaxed);
        // SAFETY: as in `alloc`.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old && !self.grant(new_size - old) {
            self.failed(new_size);
        }
        // SAFETY: as in `alloc`.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            self.failed(new_size);
        }
        if new_size < old {
            IN_USE.fetch_sub(old - new_size, Relaxed);
        }
        p
    }
}

/// Records that [`Counting`] is the global allocator (`fpt` calls it first).
pub fn installed() {
    INSTALLED.store(true, Relaxed);
}

/// Limits the heap to `bytes` (`fpt build --max-memory`).
pub fn set_limit(bytes: usize) {
    LIMIT.store(bytes, Relaxed);
}

/// The heap limit set, if any.
pub fn limit() -> Option<usize> {
    Some(LIMIT.load(Relaxed)).filter(|&l| l != usize::MAX)
}

/// Starts measuring a peak from the bytes in use now.
pub fn reset_peak() {
    PEAK.store(IN_USE.load(Relaxed), Relaxed);
}

/// The peak heap since [`reset_peak`], or `None` without the allocator.
pub fn peak() -> Option<usize> {
    INSTALLED.load(Relaxed).then(|| PEAK.load(Relaxed))
}

/// Heap bytes in use now (0 without the allocator).
pub fn in_use() -> usize {
    IN_USE.load(Relaxed)
}

/// Marks a build of about `mib` MiB as under way (0: none), for the
/// message when memory runs out.
pub fn set_build_estimate(mib: usize) {
    BUILD_MIB.store(mib, Relaxed);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn message_is_formatted_without_allocating() {
        let (buf, n) = format_no_alloc(b"error: x (needs about ", 1234);
        assert_eq!(&buf[..n], b"error: x (needs about 1234 MiB)\n");
        let (buf, n) = format_no_alloc(b"a ", 0);
        assert_eq!(&buf[..n], b"a 0 MiB)\n");
    }
}
