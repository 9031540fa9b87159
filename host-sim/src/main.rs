//! `fpt`: build, inspect, order and render feudal priority trees.

/// Counts the heap (peak memory of builds), enforces `--max-memory`, and
/// turns running out of memory into `error: ...` and status 2.
#[global_allocator]
static ALLOCATOR: host_sim::memory::Counting = host_sim::memory::Counting;

fn main() {
    host_sim::memory::installed();
    restore_sigpipe();
    std::process::exit(host_sim::cli::main_with_args(std::env::args_os()));
}

/// Rust starts programs with SIGPIPE ignored, so printing into a pipe whose
/// reader has gone (`fpt order TREE ... | head`) would panic in `println!`.
/// Restoring the default makes `fpt` end quietly there, like other Unix
/// tools.
#[cfg(unix)]
fn restore_sigpipe() {
    // SAFETY: called first thing in `main`, before any other thread exists;
    // setting a signal's disposition to its default has no other effect.
    #[allow(unsafe_code)]
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

#[cfg(not(unix))]
fn restore_sigpipe() {}
