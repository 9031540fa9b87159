//! The offline half of feudal: mesh import, the feudal priority tree
//! builders and the serializer of the flat tree file that
//! [`fpt_nostd`] walks on the microcontroller.
//!
//! The pipeline, one module a stage: [`mesh`] (OBJ, OFF, STL, PLY into
//! planar polygons, welded, closedness decided) → [`build`] (static,
//! dynamic or BSP preprocessing into a [`tree::FpTree`], splitting with
//! [`split`]) → [`serialize`] (the bytes of the tree file). `fpt build` in
//! `host-sim` is this crate plus a command line; this crate alone is what a
//! firmware's `build.rs` needs to turn a mesh into a tree at build time,
//! with none of the tool's CLI, plotting or simulator dependencies.
//!
//! # In a `build.rs`
//!
//! ```
//! use fpt_build::{build, mesh, serialize};
//!
//! fn main() -> Result<(), Box<dyn std::error::Error>> {
//!     // In a build.rs: `mesh::load(Path::new("part.stl"))?` and
//!     // `println!("cargo:rerun-if-changed=part.stl")`; here a
//!     // tetrahedron given as OBJ text.
//!     let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
//!     let model = mesh::load_bytes(mesh::MeshFormat::Obj, obj)?;
//!     let tree = build::build(
//!         model.polygons,
//!         model.closed,
//!         fpt_build::tree::Method::Static,
//!         build::DEFAULT_SEED,
//!         &mut build::NoProgress,
//!     );
//!     let bytes = serialize::serialize(&tree, &serialize::SerializeOptions::default())?;
//!     // std::fs::write(Path::new(&std::env::var("OUT_DIR")?).join("part.fpt"), &bytes)?;
//!     // and in the firmware: include_bytes!(concat!(env!("OUT_DIR"), "/part.fpt"))
//!     assert!(fpt_nostd::reader::Tree::from_bytes(&bytes).is_ok());
//!     Ok(())
//! }
//! ```
//!
//! The same bytes as `fpt build part.obj -o part.fpt` with default options
//! (tested in `host-sim/tests/all/cli_build.rs`; `fpt-build/examples/build_rs.rs`
//! is the same recipe as a program). For an STL file `fpt build` also
//! records z as the model's up axis (header byte 23, read by viewers such
//! as `fpt render`): `SerializeOptions { up: MeshFormat::Stl.up_axis(),
//! ..Default::default() }` gives its bytes.
#![deny(unsafe_code, missing_docs)]

pub mod build;
pub mod edges;
pub mod geom;
pub mod mesh;
pub mod normals;
pub mod scenes;
pub mod seams;
pub mod serialize;
pub mod split;
pub mod tree;
