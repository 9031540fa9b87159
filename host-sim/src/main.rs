//! `fpt`: build, inspect, order and render feudal priority trees.

fn main() {
    std::process::exit(host_sim::cli::main_with_args(std::env::args_os()));
}
