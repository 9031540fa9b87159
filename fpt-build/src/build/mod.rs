//! The offline builders: static and dynamic feudal preprocessing and the BSP
//! baseline.
//!
//! All three work on polygons normalised into a box of size 1 around the
//! origin, so that the one [`Tolerance`] is the same fraction of any model's
//! size and a scaled or moved model gives the same tree. Polygons that were
//! never split come out exactly as they came in; pieces and planes are moved
//! back into model coordinates.

mod auxiliary;
mod bsp;
mod bvh;
mod feudal;
mod lookahead;
mod rng;
mod table;

pub use rng::Rng;
use table::Rel;

use crate::geom::{bounds, Plane, Polygon, Relation, Tolerance};
use crate::split::split;
use crate::tree::{Connecting, FpTree, Method, Stats};
use glam::DVec3;

/// Seed used when none is given, so that builds are reproducible.
pub const DEFAULT_SEED: u64 = 0x5EED_F00D;

/// Receives progress while a tree is built, in input polygons: a piece of
/// a split polygon counts as its share of it, so `total` (the input
/// polygon count) never grows and `placed` never goes back.
pub trait Progress: Send {
    /// Called from time to time with the (share of) input polygons placed
    /// in the tree so far, of `total`.
    fn update(&mut self, placed: usize, total: usize);
}

/// No progress reporting.
pub struct NoProgress;

impl Progress for NoProgress {
    fn update(&mut self, _placed: usize, _total: usize) {}
}

/// State shared by one build: the working polygons and the counters.
pub(crate) struct Ctx<'a> {
    /// Working polygons in normalised coordinates; pieces are appended.
    pub polys: Vec<Polygon>,
    pub tol: Tolerance,
    pub relations: u64,
    pub splittings: usize,
    pub rng: Rng,
    /// Share of an input polygon each polygon stands for.
    weight: Vec<f64>,
    placed: f64,
    total: usize,
    progress: &'a mut dyn Progress,
    /// Inside a trial build (`lookahead.rs`): no progress, no lookahead.
    trial: bool,
    /// In a trial: the working polygons and splittings at its start, and
    /// the output polygons it may add before it is cut short.
    trial_base: (usize, usize, usize),
    /// The largest group that looks ahead (`lookahead.rs`).
    pub look_group: usize,
}

/// What a trial build must give back ([`Ctx::begin_trial`]).
pub(crate) struct Trial {
    polys: usize,
    splittings: usize,
    rng: Rng,
}

impl Ctx<'_> {
    /// One one-way priority relation: polygon `p` against the plane of `q`.
    pub fn relation(&mut self, p: u32, q: u32) -> Rel {
        let plane = self.polys[q as usize].plane;
        self.relation_to_plane(p, &plane)
    }

    /// One one-way priority relation: polygon `p` against `plane`.
    pub fn relation_to_plane(&mut self, p: u32, plane: &Plane) -> Rel {
        self.relations += 1;
        self.classify(p, plane)
    }

    /// Polygon `p` against `plane`, not counted as a relation.
    pub fn classify(&self, p: u32, plane: &Plane) -> Rel {
        let pp = &self.polys[p as usize];
        match plane.relation(&pp.verts, self.tol) {
            Relation::Front => Rel::Front,
            Relation::Back => Rel::Back,
            Relation::Cut => Rel::Cut,
            Relation::Coplanar if pp.plane.normal.dot(plane.normal) >= 0.0 => Rel::Same,
            Relation::Coplanar => Rel::Opposite,
        }
    }

    /// Splits polygon `id` by `plane`; returns the ids of the pieces in
    /// front and behind.
    pub fn split(&mut self, id: u32, plane: &Plane) -> (Vec<u32>, Vec<u32>) {
        let pieces = split(&self.polys[id as usize], plane, self.tol);
        self.splittings += 1;
        // The pieces share their polygon's weight, so the total stays.
        let share =
            self.weight[id as usize] / (pieces.front.len() + pieces.back.len()).max(1) as f64;
        for _ in 0..pieces.front.len() + pieces.back.len() {
            self.weight.push(share);
        }
        let push = |v: Vec<Polygon>, polys: &mut Vec<Polygon>| -> Vec<u32> {
            v.into_iter()
                .map(|p| {
                    polys.push(p);
                    (polys.len() - 1) as u32
                })
                .collect()
        };
        let f = push(pieces.front, &mut self.polys);
        let b = push(pieces.back, &mut self.polys);
        (f, b)
    }

    /// Whether a trial build is running.
    pub fn in_trial(&self) -> bool {
        self.trial
    }

    /// Starts a trial build: what it splits and draws is undone by
    /// [`Ctx::end_trial`] (the relations it computes stay counted: they
    /// are work done).
    /// A trial that would add more than `limit` output polygons is cut
    /// short ([`Ctx::trial_over`]): it cannot win.
    pub fn begin_trial(&mut self, limit: usize) -> Trial {
        self.trial = true;
        self.trial_base = (self.polys.len(), self.splittings, limit);
        Trial {
            polys: self.polys.len(),
            splittings: self.splittings,
            rng: self.rng.clone(),
        }
    }

    /// Whether the trial running has added more output polygons than its
    /// limit: the builders then stop (the trial's tree is thrown away).
    pub fn trial_over(&self) -> bool {
        let (polys, splits, limit) = self.trial_base;
        self.trial && (self.polys.len() - polys).saturating_sub(self.splittings - splits) > limit
    }

    /// Ends a trial build; returns the output polygons it added (each split
    /// replaces one polygon by its pieces).
    pub fn end_trial(&mut self, t: Trial) -> usize {
        let pieces = self.polys.len() - t.polys;
        let splits = self.splittings - t.splittings;
        self.polys.truncate(t.polys);
        self.weight.truncate(t.polys);
        self.splittings = t.splittings;
        self.rng = t.rng;
        self.trial = false;
        pieces.saturating_sub(splits)
    }

    /// Records that the polygons `ids` have their place in the tree.
    pub fn placed(&mut self, ids: impl IntoIterator<Item = u32>) {
        if self.trial {
            return;
        }
        for id in ids {
            self.placed += self.weight[id as usize];
        }
        let placed = (self.placed.round() as usize).min(self.total);
        self.progress.update(placed, self.total);
    }
}

/// Builds a tree of `polygons` with `method`; `seed` drives its random choices.
pub fn build(
    polygons: Vec<Polygon>,
    closed: bool,
    method: Method,
    seed: u64,
    progress: &mut dyn Progress,
) -> FpTree {
    let start = std::time::Instant::now();
    let input_polygons = polygons.len();
    let (lo, hi) = bounds(&polygons);
    let (center, scale) = if input_polygons == 0 {
        (DVec3::ZERO, 1.0)
    } else {
        let ext = (hi - lo).max_element();
        ((lo + hi) * 0.5, if ext > 0.0 { ext } else { 1.0 })
    };
    let work: Vec<Polygon> = polygons
        .iter()
        .map(|p| Polygon {
            verts: p.verts.iter().map(|&v| (v - center) / scale).collect(),
            plane: Plane {
                normal: p.plane.normal,
                d: (p.plane.d + p.plane.normal.dot(center)) / scale,
            },
            source: p.source,
            color: p.color,
            // Normals are directions: the same after a uniform scale.
            normals: p.normals.clone(),
        })
        .collect();
    let diag = if input_polygons == 0 {
        1.0
    } else {
        ((hi - lo) / scale).length()
    };
    let mut ctx = Ctx {
        polys: work,
        tol: Tolerance::for_diagonal(diag),
        relations: 0,
        splittings: 0,
        rng: Rng::new(seed),
        weight: vec![1.0; input_polygons],
        placed: 0.0,
        total: input_polygons,
        progress,
        trial: false,
        trial_base: (0, 0, 0),
        look_group: lookahead::group_limit(input_polygons),
    };
    let ids: Vec<u32> = (0..input_polygons as u32).collect();
    // The builders recurse once per switch node; a BSP tree of a hostile
    // model can be thousands deep, more than a default thread stack holds.
    // Without the memory for such a stack (a memory limit), build on this
    // thread rather than fail.
    let job = std::sync::Mutex::new(Some((ids, &mut ctx)));
    let run = || match job.lock().ok().and_then(|mut j| j.take()) {
        Some((ids, ctx)) => match method {
            Method::Static => {
                let t = table::Table::new(ids, &ctx.polys);
                feudal::build_group(t, feudal::Mode::Static, ctx)
            }
            Method::Dynamic => {
                let t = table::Table::new(ids, &ctx.polys);
                feudal::build_group(t, feudal::Mode::Dynamic, ctx)
            }
            Method::Bsp => bsp::build_bsp(ids, ctx),
        },
        None => Connecting::default(),
    };
    let root = std::thread::scope(|s| {
        match std::thread::Builder::new()
            .stack_size(512 << 20)
            .spawn_scoped(s, run)
        {
            Ok(h) => h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)),
            Err(_) => run(),
        }
    });
    let (relations, splittings) = (ctx.relations, ctx.splittings);
    let work = ctx.polys;

    // Number the output polygons in tree pre-order and bring them back to
    // model coordinates.
    let mut remap = vec![u32::MAX; work.len()];
    let mut order = Vec::new();
    root.for_each_polygon(&mut |id| {
        remap[id as usize] = order.len() as u32;
        order.push(id);
    });
    // A piece keeps the vertices it shares with its parent: map them back to
    // the exact input coordinates rather than through `center + v · scale`,
    // whose rounding would make near-duplicates of shared vertices (and
    // hairline gaps between a piece and its unsplit neighbour).
    let key = |v: DVec3| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()];
    let mut exact: std::collections::HashMap<[u64; 3], DVec3> = std::collections::HashMap::new();
    for (orig, norm) in polygons.iter().zip(&work) {
        for (&o, &n) in orig.verts.iter().zip(&norm.verts) {
            exact.insert(key(n), o);
        }
    }
    let mut originals: Vec<Option<Polygon>> = polygons.into_iter().map(Some).collect();
    let mut out: Vec<Polygon> = order
        .iter()
        .map(|&id| {
            let id = id as usize;
            match originals.get_mut(id).and_then(Option::take) {
                Some(p) => p,
                None => {
                    let p = &work[id];
                    Polygon {
                        verts: p
                            .verts
                            .iter()
                            .map(|&v| exact.get(&key(v)).copied().unwrap_or(center + v * scale))
                            .collect(),
                        plane: denormalize(&p.plane, center, scale),
                        source: p.source,
                        color: p.color,
                        normals: p.normals.clone(),
                    }
                }
            }
        })
        .collect();
    crate::seams::repair_seams(&mut out);
    let root = remap_tree(root, &remap, center, scale);
    let mut tree = FpTree {
        polygons: out,
        closed,
        root,
        method,
        stats: Stats {
            input_polygons,
            splittings,
            relations,
            ..Stats::default()
        },
    };
    tree.count_structure();
    tree.stats.build_ms = start.elapsed().as_secs_f64() * 1e3;
    tree
}

fn denormalize(p: &Plane, center: DVec3, scale: f64) -> Plane {
    Plane {
        normal: p.normal,
        d: p.d * scale - p.normal.dot(center),
    }
}

fn remap_tree(mut c: Connecting, remap: &[u32], center: DVec3, scale: f64) -> Connecting {
    let map = |v: &mut Vec<u32>| v.iter_mut().for_each(|id| *id = remap[*id as usize]);
    for l in &mut c.levels {
        map(&mut l.front);
        map(&mut l.back);
    }
    if let Some(s) = c.switch.as_mut() {
        map(&mut s.on);
        s.plane = denormalize(&s.plane, center, scale);
        s.front = remap_tree(std::mem::take(&mut s.front), remap, center, scale);
        s.back = remap_tree(std::mem::take(&mut s.back), remap, center, scale);
    }
    c
}

#[cfg(test)]
mod tests;
