//! Puts the top-level `memory.x` where cortex-m-rt's `link.x` finds it, and
//! links with `link.x` (here rather than in `.cargo/config.toml`'s
//! `rustflags`, which a `RUSTFLAGS` variable in the environment would
//! replace).
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    let memory = fs::read("../memory.x").expect("reading ../memory.x");
    fs::write(out.join("memory.x"), memory).expect("writing memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rustc-link-arg=-Tlink.x");
    println!("cargo:rerun-if-changed=../memory.x");
    println!("cargo:rerun-if-changed=build.rs");
}
