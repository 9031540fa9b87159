//! The offline builders: static and dynamic feudal preprocessing and the BSP
//! baseline.
//!
//! All three work on polygons normalised into a unit box around the origin,
//! so that the one [`Tolerance`] is the same fraction of any model's size and
//! a scaled or moved model gives the same tree; the output polygons are moved
//! back into model coordinates.

use crate::geom::Polygon;
use crate::tree::{FpTree, Method};

/// Seed used when none is given, so that builds are reproducible.
pub const DEFAULT_SEED: u64 = 0x5EED_F00D;

/// Receives progress while a tree is built: polygons placed so far, of total.
pub trait Progress {
    /// Called from time to time with `placed ≤ total`.
    fn update(&mut self, placed: usize, total: usize);
}

/// No progress reporting.
pub struct NoProgress;

impl Progress for NoProgress {
    fn update(&mut self, _placed: usize, _total: usize) {}
}

/// Builds a tree of `polygons` with `method`; `seed` drives its random choices.
pub fn build(
    polygons: Vec<Polygon>,
    closed: bool,
    method: Method,
    seed: u64,
    progress: &mut dyn Progress,
) -> FpTree {
    let _ = (seed, progress);
    todo!("builder: {} polygons, closed {closed}, {:?}", polygons.len(), method)
}
