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
mod pivot;
mod rng;
mod table;

pub use rng::Rng;
use table::Rel;

use crate::geom::{bounds, Plane, Polygon, Relation, Tolerance};
use crate::split::split;
use crate::tree::{Connecting, FpTree, Method, Stats};
use glam::DVec3;
use std::sync::atomic::{AtomicIsize, AtomicUsize, Ordering};
use std::sync::Mutex;
use table::Table;

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

/// Where the placed share of input polygons goes: one per build, shared by
/// the threads building parts of it.
pub(crate) trait Report: Sync {
    /// Adds `placed` input polygons' worth to the total reported.
    fn add(&self, placed: f64);
}

/// The [`Report`] of a build: the share placed so far and the caller's
/// [`Progress`], behind a lock (several threads place polygons).
pub(crate) struct Reporter<'p> {
    state: Mutex<(f64, &'p mut dyn Progress)>,
    total: usize,
}

impl<'p> Reporter<'p> {
    /// Reports to `progress`, out of `total` input polygons.
    pub fn new(progress: &'p mut dyn Progress, total: usize) -> Reporter<'p> {
        Reporter {
            state: Mutex::new((0.0, progress)),
            total,
        }
    }
}

impl Report for Reporter<'_> {
    fn add(&self, placed: f64) {
        // A poisoned lock means another thread panicked: the build is
        // being torn down, progress no longer matters.
        if let Ok(mut s) = self.state.lock() {
            s.0 += placed;
            let placed = (s.0.round() as usize).min(self.total);
            s.1.update(placed, self.total);
        }
    }
}

/// The threads a build may run at once: a budget of tokens, one per
/// running thread. A thread that hands work to another takes a token for
/// it ([`Threads::take`]); each of the two gives its token back as soon as
/// its part is done, so that while one waits for the other, the one still
/// working can hand work on (else a thread waiting at the top of the tree
/// would keep the second core idle for the rest of the build). The one
/// that goes on afterwards takes its token back unconditionally: the count
/// may go below zero for a moment (one thread too many), never further.
pub(crate) struct Threads {
    free: AtomicIsize,
    /// Work handed to another thread so far, by [`Work`] (the tests check
    /// that each kind is run beside another).
    handed: [AtomicUsize; 3],
}

/// What a thread is started for ([`Threads::beside`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Work {
    /// The group in front of a switch node (`feudal.rs`).
    Subtree = 0,
    /// A lookahead trial (`lookahead.rs`).
    Trial = 1,
    /// Half a batch of rows (`table.rs`).
    Rows = 2,
}

/// Stack of every thread a build starts: the builders recurse once per
/// switch node, and a BSP tree of a hostile model can be thousands deep,
/// more than a default thread stack holds.
const STACK: usize = 512 << 20;

impl Threads {
    /// A budget of `n` threads in all (the caller's included).
    pub fn new(n: usize) -> Threads {
        Threads {
            free: AtomicIsize::new(n.saturating_sub(1).min(isize::MAX as usize) as isize),
            handed: Default::default(),
        }
    }

    /// Takes one thread from the budget, if one is free; the caller then
    /// runs [`Threads::beside`], which gives it back.
    pub fn take(&self) -> bool {
        self.free
            .fetch_update(Ordering::AcqRel, Ordering::Acquire, |f| {
                (f > 0).then_some(f - 1)
            })
            .is_ok()
    }

    /// Runs `a` on another thread and `b` on this one, after a token was
    /// taken with [`Threads::take`]; each gives its token back when done
    /// (see [`Threads`]). When no thread can be started
    /// (no memory for its stack), `a` runs here after `b`: the result is
    /// the same, only later. A panic in `a` is passed on.
    pub fn beside<A: Send, B>(
        &self,
        work: Work,
        a: impl FnOnce() -> A + Send,
        b: impl FnOnce() -> B,
    ) -> (A, B) {
        self.handed[work as usize].fetch_add(1, Ordering::Relaxed);
        let job = Mutex::new(Some(a));
        let run = || {
            let a = job.lock().unwrap_or_else(|e| e.into_inner()).take();
            let ra = a.map(|a| a());
            self.free.fetch_add(1, Ordering::AcqRel);
            ra
        };
        let (ra, rb) = std::thread::scope(|s| {
            let h = std::thread::Builder::new()
                .stack_size(STACK)
                .spawn_scoped(s, run);
            let rb = b();
            self.free.fetch_add(1, Ordering::AcqRel);
            let ra = match h {
                Ok(h) => h.join(),
                Err(_) => Ok(run()),
            };
            (ra, rb)
        });
        self.free.fetch_sub(1, Ordering::AcqRel);
        match ra {
            // `a` ran exactly once, on the thread or here: the job was
            // there to take (nothing else takes it).
            Ok(Some(ra)) => (ra, rb),
            Ok(None) => unreachable!("the job of `beside` ran twice"),
            Err(e) => std::panic::resume_unwind(e),
        }
    }

    /// How many times `work` was handed to another thread.
    #[cfg(test)]
    pub fn handed(&self, work: Work) -> usize {
        self.handed[work as usize].load(Ordering::Relaxed)
    }
}

/// State of one build, or of one part of it built on another thread
/// ([`Ctx::detach`]): the working polygons and the counters.
pub(crate) struct Ctx<'a> {
    /// Working polygons in normalised coordinates; pieces are appended.
    pub polys: Vec<Polygon>,
    pub tol: Tolerance,
    pub relations: u64,
    pub splittings: usize,
    pub rng: Rng,
    /// Share of an input polygon each polygon stands for.
    weight: Vec<f64>,
    report: &'a dyn Report,
    /// Inside a trial build (`lookahead.rs`): no progress, no lookahead.
    trial: bool,
    /// In a trial: the working polygons and splittings at its start, and
    /// the output polygons it may add before it is cut short.
    trial_base: (usize, usize, usize),
    /// In a trial run beside an earlier one: the fewest output polygons an
    /// earlier trial added (set when it finishes); this trial is cut short
    /// once it adds as many (it could not win).
    cap: Option<&'a AtomicUsize>,
    /// How this build looks ahead (`lookahead.rs`).
    pub look: lookahead::Look,
    /// The threads this build may still start.
    pub threads: &'a Threads,
}

/// What a trial build must give back ([`Ctx::begin_trial`]).
pub(crate) struct Trial {
    polys: usize,
    splittings: usize,
    relations: u64,
    rng: Rng,
}

impl<'a> Ctx<'a> {
    /// A context for a build of `polys` (normalised) with tolerance `tol`.
    pub fn new(
        polys: Vec<Polygon>,
        tol: Tolerance,
        seed: u64,
        report: &'a dyn Report,
        threads: &'a Threads,
    ) -> Ctx<'a> {
        let n = polys.len();
        Ctx {
            polys,
            tol,
            relations: 0,
            splittings: 0,
            rng: Rng::new(seed),
            weight: vec![1.0; n],
            report,
            trial: false,
            trial_base: (0, 0, 0),
            cap: None,
            look: lookahead::look_for(n),
            threads,
        }
    }

    /// A context for building the group of `t` on another thread: a copy
    /// of its members' polygons only, renumbered `0..t.len()` (in `t`
    /// too), with no relations or splittings counted yet. Returns it with
    /// the members' ids here, for [`Ctx::attach`].
    ///
    /// The builders never look at a polygon's id, only at its geometry and
    /// at local indices, so the part is built exactly as it would be here.
    pub fn detach(&self, t: &mut Table) -> (Ctx<'a>, Vec<u32>) {
        let local = (0..t.len() as u32).collect();
        let ids = std::mem::replace(&mut t.ids, local);
        let mut child = Ctx {
            polys: ids
                .iter()
                .map(|&id| self.polys[id as usize].clone())
                .collect(),
            tol: self.tol,
            relations: 0,
            splittings: 0,
            rng: self.rng.clone(),
            weight: ids.iter().map(|&id| self.weight[id as usize]).collect(),
            report: self.report,
            trial: false,
            trial_base: (0, 0, 0),
            cap: None,
            look: self.look,
            threads: self.threads,
        };
        if self.trial {
            // A part of a trial: it may add what the trial has left, and
            // is cut short as an earlier trial beside it says. If the part
            // is cut short, the trial's count (with the part's pieces,
            // `attach`) is over its limit too.
            let (polys, splits, limit) = self.trial_base;
            let added = (self.polys.len() - polys).saturating_sub(self.splittings - splits);
            child.trial = true;
            child.trial_base = (child.polys.len(), 0, limit.saturating_sub(added));
            child.cap = self.cap;
        }
        (child, ids)
    }

    /// Takes back the work of a context made by [`Ctx::detach`] (with the
    /// members' `ids`): the pieces it split off are appended here, its
    /// counters added, and the polygon ids of its connecting node `c`
    /// renumbered into this context.
    pub fn attach(&mut self, child: Ctx, ids: &[u32], c: &mut Connecting) {
        let m = ids.len();
        let base = self.polys.len();
        self.polys.extend(child.polys.into_iter().skip(m));
        self.weight.extend(child.weight.into_iter().skip(m));
        self.relations += child.relations;
        self.splittings += child.splittings;
        renumber(c, &|id| match ids.get(id as usize) {
            Some(&id) => id,
            None => (base + id as usize - m) as u32,
        });
    }

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

    /// Starts a trial build: what it splits, draws and counts (relations
    /// included: the count is that of the tree built, whatever trials were
    /// run on which thread) is undone by [`Ctx::end_trial`].
    /// A trial that would add more than `limit` output polygons is cut
    /// short ([`Ctx::trial_over`]): it cannot win.
    pub fn begin_trial(&mut self, limit: usize) -> Trial {
        self.trial = true;
        self.trial_base = (self.polys.len(), self.splittings, limit);
        Trial {
            polys: self.polys.len(),
            splittings: self.splittings,
            relations: self.relations,
            rng: self.rng.clone(),
        }
    }

    /// Whether the trial running has added more output polygons than its
    /// limit (or as many as an earlier trial beside it, [`Ctx::cap`]): the
    /// builders then stop (the trial's tree is thrown away).
    pub fn trial_over(&self) -> bool {
        let (polys, splits, limit) = self.trial_base;
        let limit = match self.cap {
            Some(c) => limit.min(c.load(Ordering::Acquire).saturating_sub(1)),
            None => limit,
        };
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
        self.relations = t.relations;
        self.rng = t.rng;
        self.trial = false;
        pieces.saturating_sub(splits)
    }

    /// Records that the polygons `ids` have their place in the tree.
    pub fn placed(&mut self, ids: impl IntoIterator<Item = u32>) {
        if self.trial {
            return;
        }
        let w: f64 = ids.into_iter().map(|id| self.weight[id as usize]).sum();
        self.report.add(w);
    }
}

/// Renumbers every polygon id of `c` through `map`.
fn renumber(c: &mut Connecting, map: &dyn Fn(u32) -> u32) {
    let apply = |v: &mut Vec<u32>| v.iter_mut().for_each(|id| *id = map(*id));
    for l in &mut c.levels {
        apply(&mut l.front);
        apply(&mut l.back);
    }
    if let Some(s) = c.switch.as_mut() {
        apply(&mut s.on);
        renumber(&mut s.front, map);
        renumber(&mut s.back, map);
    }
}

/// The threads a build uses when none is asked for: `FPT_BUILD_THREADS` if
/// set to a positive number, else every core.
pub fn default_threads() -> usize {
    std::env::var("FPT_BUILD_THREADS")
        .ok()
        .and_then(|s| s.trim().parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from))
}

/// Builds a tree of `polygons` with `method`; `seed` drives its random
/// choices. Uses [`default_threads`] threads; the tree does not depend on
/// how many ([`build_with_threads`]).
pub fn build(
    polygons: Vec<Polygon>,
    closed: bool,
    method: Method,
    seed: u64,
    progress: &mut dyn Progress,
) -> FpTree {
    build_with_threads(polygons, closed, method, seed, progress, default_threads())
}

/// [`build`] on at most `threads` threads (0 counts as 1). The static
/// builder builds the two sides of a switch node, the lookahead's trial
/// subtrees and large batches of rows on separate threads when one is
/// free; the tree, and so its file, is byte for byte the same for any
/// number of threads (tested). The dynamic builder's random choices run
/// in one sequence, so it builds its subtrees one after the other.
pub fn build_with_threads(
    polygons: Vec<Polygon>,
    closed: bool,
    method: Method,
    seed: u64,
    progress: &mut dyn Progress,
    threads: usize,
) -> FpTree {
    let threads = Threads::new(threads.max(1));
    build_in(polygons, closed, method, seed, progress, &threads)
}

/// [`build_with_threads`] with the thread budget `threads`.
pub(crate) fn build_in(
    polygons: Vec<Polygon>,
    closed: bool,
    method: Method,
    seed: u64,
    progress: &mut dyn Progress,
    threads: &Threads,
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
    let reporter = Reporter::new(progress, input_polygons);
    let mut ctx = Ctx::new(
        work,
        Tolerance::for_diagonal(diag),
        seed,
        &reporter,
        threads,
    );
    let ids: Vec<u32> = (0..input_polygons as u32).collect();
    // The builders recurse once per switch node: build on a thread with a
    // stack for that ([`STACK`]). Without the memory for such a stack (a
    // memory limit), build on this thread rather than fail.
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
            .stack_size(STACK)
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
