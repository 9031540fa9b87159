//! What a firmware's `build.rs` does to turn a mesh into a tree at build
//! time, as a program:
//! `cargo run -p fpt-build --example build_rs -- MESH OUT.fpt`.
//!
//! In a real `build.rs` the paths come from the crate (`MESH` next to
//! `Cargo.toml`, `OUT` in `OUT_DIR`), the build script prints
//! `cargo:rerun-if-changed=MESH`, and the firmware embeds the result with
//! `include_bytes!(concat!(env!("OUT_DIR"), "/part.fpt"))`. The bytes are
//! those of `fpt build MESH -o OUT.fpt` with default options (tested in
//! `host-sim/tests/all/cli_build.rs`).

use fpt_build::{build, mesh, serialize, tree::Method};
use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [mesh_path, out] = args.as_slice() else {
        eprintln!("usage: build_rs MESH OUT.fpt");
        std::process::exit(2);
    };
    if let Err(e) = mesh_to_tree(Path::new(mesh_path), Path::new(out)) {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

/// The whole recipe: load, build, serialize, write.
fn mesh_to_tree(mesh_path: &Path, out: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let model = mesh::load(mesh_path).map_err(|e| format!("{}: {e}", mesh_path.display()))?;
    let tree = build::build(
        model.polygons,
        model.closed,
        Method::Static,
        build::DEFAULT_SEED,
        &mut build::NoProgress,
    );
    let bytes = serialize::serialize(&tree, &serialize::SerializeOptions::default())?;
    std::fs::write(out, bytes)?;
    println!("{} -> {}", mesh_path.display(), out.display());
    Ok(())
}
