//! Host side of feudal: the `fpt` command-line tool, the reference
//! renderer and the simulator. Mesh import, the tree builders and the
//! serializer are the [`fpt_build`] crate, re-exported here under their
//! own names.
#![deny(unsafe_code, missing_docs)]

pub use fpt_build::{build, edges, geom, mesh, scenes, seams, serialize, split, tree};

pub mod cli;
pub mod memory;
pub mod output;
pub mod reference;
pub mod subdivide;
