//! `fpt-nostd`: the microcontroller side of feudal.
//!
//! `#![no_std]`, no `alloc`. Everything here works on caller-supplied storage.
#![no_std]
#![deny(unsafe_code, missing_docs)]

pub mod format;
pub mod order;
pub mod reader;
#[cfg(test)]
mod test_util;
pub mod fixed;
pub mod raster;
