//! `fpt build` and `fpt bench-build`.

use super::{BenchBuildArgs, BuildArgs, CliResult};

/// `fpt build`.
pub fn run(_a: &BuildArgs) -> CliResult {
    Err(crate::cli_err!("fpt build is not implemented yet"))
}

/// `fpt bench-build`.
pub fn bench(_a: &BenchBuildArgs) -> CliResult {
    Err(crate::cli_err!("fpt bench-build is not implemented yet"))
}
