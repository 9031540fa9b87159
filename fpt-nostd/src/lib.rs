//! `fpt-nostd`: the microcontroller side of feudal.
//!
//! `#![no_std]`, no `alloc`. Everything here works on caller-supplied storage.
#![no_std]
#![deny(unsafe_code, missing_docs)]
