//! `fpt polygons`, `fpt order`, `fpt info` and `fpt bench-order`: all of them
//! read the serialized tree through `fpt-nostd`.

use super::{BenchOrderArgs, CliResult, InfoArgs, OrderArgs, PolygonsArgs};

/// `fpt polygons`.
pub fn polygons(_a: &PolygonsArgs) -> CliResult {
    Err(crate::cli_err!("not implemented yet"))
}

/// `fpt order`.
pub fn order(_a: &OrderArgs) -> CliResult {
    Err(crate::cli_err!("not implemented yet"))
}

/// `fpt info`.
pub fn info(_a: &InfoArgs) -> CliResult {
    Err(crate::cli_err!("not implemented yet"))
}

/// `fpt bench-order`.
pub fn bench_order(_a: &BenchOrderArgs) -> CliResult {
    Err(crate::cli_err!("not implemented yet"))
}
