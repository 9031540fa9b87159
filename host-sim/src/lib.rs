//! Host side of feudal: mesh import, the feudal priority tree builders, the
//! serializer of the flat format, and the `fpt` command-line tool.
#![deny(unsafe_code, missing_docs)]

pub mod build;
pub mod cli;
pub mod edges;
pub mod geom;
pub mod memory;
pub mod mesh;
pub mod output;
pub mod reference;
pub mod scenes;
pub mod seams;
pub mod serialize;
pub mod split;
pub mod tree;
