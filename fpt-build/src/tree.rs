//! The feudal priority tree as the builders make it, before serialization.
//!
//! Polygon ids are indices into [`FpTree::polygons`], the output polygons
//! (after splitting). The structure follows `feudal-priority.md`: a connecting
//! node is a chain of levels, each with a front bunch `F_j` and a back bunch
//! `B_j`, and at most one switch node below its last level; a switch node has
//! a plane, the bunch of polygons lying in it, and two connecting nodes (the
//! group in front of the plane and the group behind it). A BSP tree is the
//! special case in which every connecting node has no levels.

use crate::geom::{Plane, Polygon};

/// One level `j` of a connecting node.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Level {
    /// `F_j`: absolute front priority polygons.
    pub front: Vec<u32>,
    /// `B_j`: absolute back priority polygons.
    pub back: Vec<u32>,
}

/// A connecting node: levels `1..=n`, then at most one switch node.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Connecting {
    /// Levels from the outermost (`j = 1`) inwards.
    pub levels: Vec<Level>,
    /// The switch node hanging below the last level.
    pub switch: Option<Box<Switch>>,
}

/// A switch node: the view-dependent choice of a BSP node.
#[derive(Clone, Debug, PartialEq)]
pub struct Switch {
    /// The splitting plane (the plane of the polygon it was chosen from).
    pub plane: Plane,
    /// `O_k`: polygons lying in the plane (either orientation).
    pub on: Vec<u32>,
    /// `G_f`: the group in front of the plane.
    pub front: Connecting,
    /// `G_b`: the group behind the plane.
    pub back: Connecting,
}

/// Which preprocessing made a tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Static preprocessing: whole one-way priority table first.
    Static,
    /// Dynamic preprocessing: rows computed in random order as needed.
    Dynamic,
    /// The BSP baseline (best of five random candidate planes).
    Bsp,
}

impl Method {
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Static => "static",
            Method::Dynamic => "dynamic",
            Method::Bsp => "bsp",
        }
    }
}

/// Build statistics in the shape of the paper's Tables 6 and 7.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    /// Polygons given to the builder.
    pub input_polygons: usize,
    /// Polygons in the tree (after splitting).
    pub output_polygons: usize,
    /// Polygons cut by a splitting plane.
    pub splittings: usize,
    /// Connecting nodes.
    pub connecting_nodes: usize,
    /// Switch nodes.
    pub switch_nodes: usize,
    /// Non-empty bunches (`F_j`, `B_j`, `O_k`).
    pub bunches: usize,
    /// Levels, summed over all connecting nodes.
    pub levels: usize,
    /// One-way priority relations computed (polygon against plane tests).
    pub relations: u64,
    /// Depth: the most connecting nodes on one root-to-leaf path.
    pub max_depth: usize,
    /// Wall time of the build, in milliseconds.
    pub build_ms: f64,
}

/// A built tree: the output polygons and the root connecting node.
#[derive(Clone, Debug, PartialEq)]
pub struct FpTree {
    /// Output polygons; a polygon id is an index into this list.
    pub polygons: Vec<Polygon>,
    /// Whether the model is a closed volume (back faces may be culled).
    pub closed: bool,
    /// The root connecting node.
    pub root: Connecting,
    /// How it was built.
    pub method: Method,
    /// Build statistics.
    pub stats: Stats,
}

impl Connecting {
    /// Number of connecting nodes in this subtree, including this one.
    pub fn count_connecting(&self) -> usize {
        1 + self.switch.as_ref().map_or(0, |s| {
            s.front.count_connecting() + s.back.count_connecting()
        })
    }

    /// Number of switch nodes in this subtree.
    pub fn count_switches(&self) -> usize {
        self.switch.as_ref().map_or(0, |s| {
            1 + s.front.count_switches() + s.back.count_switches()
        })
    }

    /// Most connecting nodes on one path from here down.
    pub fn depth(&self) -> usize {
        1 + self
            .switch
            .as_ref()
            .map_or(0, |s| s.front.depth().max(s.back.depth()))
    }

    /// Levels in this subtree.
    pub fn count_levels(&self) -> usize {
        self.levels.len()
            + self
                .switch
                .as_ref()
                .map_or(0, |s| s.front.count_levels() + s.back.count_levels())
    }

    /// Non-empty bunches in this subtree.
    pub fn count_bunches(&self) -> usize {
        let here = self
            .levels
            .iter()
            .map(|l| usize::from(!l.front.is_empty()) + usize::from(!l.back.is_empty()))
            .sum::<usize>();
        here + self.switch.as_ref().map_or(0, |s| {
            usize::from(!s.on.is_empty()) + s.front.count_bunches() + s.back.count_bunches()
        })
    }

    /// Calls `f` with every polygon id in this subtree.
    pub fn for_each_polygon(&self, f: &mut impl FnMut(u32)) {
        for l in &self.levels {
            l.front.iter().chain(&l.back).for_each(|&i| f(i));
        }
        if let Some(s) = &self.switch {
            s.on.iter().for_each(|&i| f(i));
            s.front.for_each_polygon(f);
            s.back.for_each_polygon(f);
        }
    }
}

impl FpTree {
    /// Fills the structural counts of `stats` from the tree itself.
    pub fn count_structure(&mut self) {
        let s = &mut self.stats;
        s.output_polygons = self.polygons.len();
        s.connecting_nodes = self.root.count_connecting();
        s.switch_nodes = self.root.count_switches();
        s.levels = self.root.count_levels();
        s.bunches = self.root.count_bunches();
        s.max_depth = self.root.depth();
    }
}
