//! What the target core does in hardware, as constants the arithmetic
//! picks its form by: floating point, integer division, 64-bit products.
//! Every choice made on them gives the same results (each pair of forms is
//! tested against the other on the host); only the cost differs. Stable
//! Rust names few ARM features in `cfg`, hence the proxies below.

/// Whether the target has hardware floating point: hosted targets, ARM
/// hard-float ABIs, RISC-V with F.
pub(crate) const HAS_FPU: bool = cfg!(any(
    not(target_os = "none"),
    target_abi = "eabihf",
    target_feature = "f"
));

/// Whether the target divides integers in hardware: hosted targets, ARM
/// cores with 32-bit compare-and-swap atomics (ARMv7-M and ARMv8-M: those
/// with a divider; ARMv6-M has neither) and RISC-V with M. Stable Rust
/// names no ARM feature for the divider, hence the atomics; a core this
/// misjudges takes the other, equally exact, set-up.
pub(crate) const HAS_DIV: bool = cfg!(any(
    not(target_os = "none"),
    all(target_arch = "arm", target_has_atomic = "32"),
    target_feature = "m"
));

/// Whether the target multiplies 32 × 32 → 64 bits in hardware (`smull`,
/// `smulwb` on ARMv7-M): as [`HAS_DIV`]. Without it (a Cortex-M0) an
/// `i64` product is a call of about 40 instructions, and the forms that
/// need only 32-bit products are used instead. (ARMv8-M Baseline divides
/// but has no long multiply: misjudged here, it takes the calls.)
pub(crate) const HAS_LONG_MUL: bool = HAS_DIV;
