//! The one-way priority table of a group of polygons, kept as counts.
//!
//! Row `q` of the paper's table classifies every other member against the
//! plane of `q`; the builders only ever use its counts (front, back, cut
//! among the members still in the group) and, for the chosen polygon, the
//! row itself once. So no row is stored: a row is computed when needed
//! ([`Table::compute_row`]), its counts kept per polygon, and the row of the
//! switch polygon is recomputed when the group is divided. Memory is linear
//! in the group's size instead of the n×n table (1.2 GiB at 25,000
//! polygons).
//!
//! Counts are kept exact lazily. Removing members changes every row's
//! counts; rather than classifying each removed member against every row,
//! each row remembers how many members had been removed when its counts
//! were last exact (`stamp`). Removals only lower counts, so a row whose
//! `slack` (what must reach zero for it to matter: its cut count, or its
//! cut count plus the smaller of front and back) exceeds the removals since
//! then cannot have become absolute or separating, and is left alone. A
//! [`Watch`] orders rows by when that can first happen.
//!
//! Most rows are never counted exactly. [`Table::probe_all`] gives each row
//! lower bounds on its counts from a few boxes of the hierarchy, with the
//! number of members left undecided; the static builder counts exactly
//! only the rows whose bounds say they could become absolute, separate or
//! win the choice of the splitting plane (see `feudal.rs`). The bounds are
//! valid (each true count is at least its bound), so the rows chosen, and
//! the tree, are those of the exact table.
//!
//! Most rows are never counted at all in a large group: a row whose plane
//! cuts a member is neither absolute nor separating while that member is
//! alive. Probes and counts note such a member (the row's witness; a probe
//! first opens the row's own leaf, its neighbours on the surface, which
//! the plane of a facet on a saddle-shaped patch cuts), subgroups carry it
//! over when it comes along, and a watched row with a live witness is
//! parked on it ([`Table::watch`]) until it is removed. The choice of a
//! splitting plane probes candidates depth first ([`Table::deepen`]) before
//! counting them. None of this changes a choice: bounds stay valid, so the
//! tree is the one of the exact table.
//!
//! Rows are counted through a bounding-volume hierarchy ([`super::bvh`]),
//! so a row costs about √n classifications, and large batches of rows are
//! counted on two threads when the build has one free. Every row computed counts the relations of the
//! paper's table (one per other member), as the paper counts its cost.

use super::bvh::{Bvh, Probe, NO_WITNESS};
use super::{Ctx, Threads, Work};
use crate::geom::{Plane, Polygon, Relation, Tolerance};
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A relation of a polygon to a plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Rel {
    /// In front of the row's plane.
    Front = 0,
    /// Behind it.
    Back = 1,
    /// Cut by it.
    Cut = 2,
    /// In the plane, same orientation.
    Same = 3,
    /// In the plane, reversed orientation.
    Opposite = 4,
    /// Not computed.
    Unknown = 5,
}

/// The table of one group; members are addressed by local index.
#[derive(Clone, Debug)]
pub struct Table {
    /// Local index → polygon id in [`Ctx::polys`].
    pub ids: Vec<u32>,
    has_row: Vec<bool>,
    alive: Vec<bool>,
    /// Front, back and cut counts of each computed row as of `stamp`
    /// removals: exact when `undecided` is 0, otherwise lower bounds (see
    /// [`Table::probe_all`]).
    counts: Vec<[u32; 3]>,
    /// Alive members the bounds in `counts` left undecided, as of `stamp`.
    undecided: Vec<u32>,
    stamp: Vec<u32>,
    removed: u32,
    /// The members removed, in order: `log[stamp..]` are those a row with
    /// that stamp still counts.
    log: Vec<u32>,
    alive_count: usize,
    bvh: Bvh,
    /// Per row: a member its plane cuts (local index), or [`NO_WITNESS`].
    /// While that member is alive the row is neither absolute nor
    /// separating, whatever else is removed: such a row needs no count.
    witness: Vec<u32>,
    /// Per member: the watched rows parked on it as their witness
    /// ([`Table::watch`]), to be watched again when it is removed.
    parked: Vec<Vec<u32>>,
    /// Parked rows whose witness was removed, watched again by the next
    /// [`Table::due`].
    orphans: Vec<u32>,
    /// Per row: probed since its counts were last exact ([`Table::due`]
    /// counts a row due again rather than probe it twice).
    probed: Vec<bool>,
}

/// Rows waiting until their counts could pass a test (see the module docs).
pub struct Watch {
    heap: BinaryHeap<Reverse<(u64, u32)>>,
    slack: fn([u32; 3]) -> u32,
}

impl Watch {
    /// Watches rows for the test whose necessary condition is `slack == 0`.
    pub fn new(slack: fn([u32; 3]) -> u32) -> Watch {
        Watch {
            heap: BinaryHeap::new(),
            slack,
        }
    }
}

/// Rows counted per thread at least, when counting on two threads: a
/// thread is started per call, which on a loaded machine waits for a time
/// slice, so only large batches are worth it.
const PER_THREAD: usize = 128;

/// Applies `f` to every row of `rows`, half of them on another thread when
/// there are many and the build has one free ([`Threads`]).
fn count_rows<T: Send>(threads: &Threads, rows: &[usize], f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    if rows.len() < 2 * PER_THREAD || !threads.take() {
        return rows.iter().map(|&q| f(q)).collect();
    }
    let (a, b) = rows.split_at(rows.len() / 2);
    let f = &f;
    let (mut ra, rb) = threads.beside(
        Work::Rows,
        move || a.iter().map(|&q| f(q)).collect::<Vec<_>>(),
        || b.iter().map(|&q| f(q)).collect::<Vec<_>>(),
    );
    ra.extend(rb);
    ra
}

/// Counts with `x` classified against `plane` added (`add`) or taken out.
fn adjust(c: &mut [u32; 3], x: &Polygon, plane: &Plane, tol: Tolerance, add: bool) {
    let i = match plane.relation(&x.verts, tol) {
        Relation::Front => 0,
        Relation::Back => 1,
        Relation::Cut => 2,
        Relation::Coplanar => return,
    };
    c[i] = if add { c[i] + 1 } else { c[i] - 1 };
}

/// Boxes a probe opens ([`Table::probe_all`]): enough to decide most of a
/// group's members against a row's plane (whole boxes are decided at
/// once), far fewer than the √n or more of a full count.
const PROBE: usize = 48;

/// `stamp` of a row never counted.
const NEVER: u32 = u32::MAX;

/// Up to how many removals a row's counts are corrected one removed
/// member at a time rather than counted again through the hierarchy.
fn incremental_limit(alive: usize) -> u32 {
    // A count through the hierarchy opens about √n leaves.
    (4.0 * (alive as f64).sqrt()).max(32.0) as u32
}

impl Table {
    /// A table of `ids` with no row computed.
    pub fn new(ids: Vec<u32>, polys: &[Polygon]) -> Table {
        let m = ids.len();
        Table {
            bvh: Bvh::new(&ids, polys),
            ids,
            has_row: vec![false; m],
            alive: vec![true; m],
            counts: vec![[0; 3]; m],
            undecided: vec![0; m],
            stamp: vec![0; m],
            removed: 0,
            log: Vec::new(),
            alive_count: m,
            witness: vec![NO_WITNESS; m],
            parked: vec![Vec::new(); m],
            orphans: Vec::new(),
            probed: vec![false; m],
        }
    }

    /// Whether row `q` has a witness still alive: a member its plane cuts.
    pub fn has_live_witness(&self, q: usize) -> bool {
        let w = self.witness[q];
        w != NO_WITNESS && self.alive[w as usize]
    }

    /// Whether [`Table::refresh`] brings row `q` up to date by taking out
    /// the few members removed since it was exact, not by a count.
    fn cheap_refresh(&self, q: usize, limit: u32) -> bool {
        let stamp = self.stamp[q];
        stamp != NEVER && self.undecided[q] == 0 && self.removed - stamp <= limit
    }

    /// Number of members.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Members still in the group.
    pub fn alive_count(&self) -> usize {
        self.alive_count
    }

    /// Whether member `q` is still in the group.
    pub fn is_alive(&self, q: usize) -> bool {
        self.alive[q]
    }

    /// Whether row `q` has been computed.
    pub fn has_row(&self, q: usize) -> bool {
        self.has_row[q]
    }

    /// Front, back and cut counts of row `q` among alive members: exact
    /// after [`Table::compute_row`], [`Table::refresh`] or [`Table::due`]
    /// and until the next removal.
    pub fn counts(&self, q: usize) -> [u32; 3] {
        debug_assert!(self.is_exact(q), "stale or bounded counts of row {q}");
        self.counts[q]
    }

    /// Whether the counts of row `q` are exact now.
    pub fn is_exact(&self, q: usize) -> bool {
        self.stamp[q] == self.removed && self.undecided[q] == 0
    }

    /// Lower bounds on the front, back and cut counts of row `q` and the
    /// number of members they leave undecided, valid after
    /// [`Table::probe_all`] and until the next removal.
    pub fn bounds(&self, q: usize) -> ([u32; 3], u32) {
        debug_assert_eq!(self.stamp[q], self.removed, "stale bounds of row {q}");
        (self.counts[q], self.undecided[q])
    }

    /// Makes the counts of `rows` (computed ones) exact.
    pub fn refresh(&mut self, rows: &[usize], ctx: &Ctx) {
        let rows: Vec<usize> = rows
            .iter()
            .copied()
            .filter(|&q| self.has_row[q] && !self.is_exact(q))
            .collect();
        let limit = incremental_limit(self.alive_count);
        let (polys, tol) = (&ctx.polys, ctx.tol);
        let counts = count_rows(ctx.threads, &rows, |q| {
            let plane = polys[self.ids[q] as usize].plane;
            if self.cheap_refresh(q, limit) {
                // Take out the members removed since the counts were exact.
                let mut c = self.counts[q];
                for &x in &self.log[self.stamp[q] as usize..] {
                    adjust(
                        &mut c,
                        &polys[self.ids[x as usize] as usize],
                        &plane,
                        tol,
                        false,
                    );
                }
                let w = if self.has_live_witness(q) {
                    self.witness[q]
                } else {
                    NO_WITNESS
                };
                (c, w)
            } else {
                self.bvh.counts_witness(&plane, q, &self.alive, tol)
            }
        });
        for (q, (c, w)) in rows.into_iter().zip(counts) {
            self.counts[q] = c;
            self.undecided[q] = 0;
            self.stamp[q] = self.removed;
            self.witness[q] = w;
            self.probed[q] = false;
        }
    }

    /// Gives every alive computed row bounds as of now: rows whose counts
    /// are not exact now are probed ([`Bvh::probe`], about [`PROBE`] boxes
    /// each) instead of counted, which is all the builders need of most
    /// rows: a row that cannot become absolute yet, or whose score cannot
    /// beat the best one, never needs its exact counts. With `witnessed`
    /// false, rows with a live witness ([`Table::has_live_witness`]) are
    /// left as they are: a test that needs an uncut row skips them.
    pub fn probe_all(&mut self, ctx: &Ctx, witnessed: bool) {
        let rows: Vec<usize> = (0..self.len())
            .filter(|&q| self.alive[q] && self.has_row[q] && self.stamp[q] != self.removed)
            .filter(|&q| witnessed || !self.has_live_witness(q))
            .collect();
        self.probe(&rows, ctx);
    }

    /// Probes `rows` (alive, computed): bounds as of now, and a witness if
    /// the probe finds one (else the old one, if alive).
    fn probe(&mut self, rows: &[usize], ctx: &Ctx) {
        let (polys, tol) = (&ctx.polys, ctx.tol);
        let found = count_rows(ctx.threads, rows, |q| {
            let plane = polys[self.ids[q] as usize].plane;
            // The row's own leaf, and its last witness's.
            let seeds = [q as u32, self.witness[q]];
            self.bvh.probe(&plane, q, &self.alive, tol, PROBE, &seeds)
        });
        self.take_probes(rows, found);
    }

    /// Probes `rows` (alive, computed, not exact) depth first
    /// ([`Bvh::probe_deep`], about `budget` boxes and members each): bounds
    /// as of now that show most rows unable to win the choice of a
    /// splitting plane without counting them.
    pub fn deepen(&mut self, rows: &[usize], ctx: &Ctx, budget: usize) {
        let (polys, tol) = (&ctx.polys, ctx.tol);
        let found = count_rows(ctx.threads, rows, |q| {
            let plane = polys[self.ids[q] as usize].plane;
            self.bvh.probe_deep(&plane, q, &self.alive, tol, budget)
        });
        self.take_probes(rows, found);
    }

    /// Stores what probes of `rows` found: bounds as of now, and a witness
    /// if the probe found one (else the old one, if alive).
    fn take_probes(&mut self, rows: &[usize], found: Vec<Probe>) {
        for (&q, p) in rows.iter().zip(found) {
            self.counts[q] = p.counts;
            self.undecided[q] = p.undecided;
            self.stamp[q] = self.removed;
            self.probed[q] = true;
            if p.witness != NO_WITNESS {
                self.witness[q] = p.witness;
            } else if !self.has_live_witness(q) {
                self.witness[q] = NO_WITNESS;
            }
        }
    }

    /// Makes the counts of every alive computed row exact.
    #[cfg(test)]
    pub fn refresh_all(&mut self, ctx: &Ctx) {
        let rows: Vec<usize> = (0..self.len()).filter(|&q| self.alive[q]).collect();
        self.refresh(&rows, ctx);
    }

    /// Computes the rows `qs` (those not computed yet) against the alive
    /// members.
    pub fn compute_rows(&mut self, qs: &[usize], ctx: &mut Ctx) {
        let mut new = Vec::new();
        for &q in qs {
            if !self.has_row[q] && self.alive[q] {
                self.has_row[q] = true;
                // Not yet counted: `refresh` below counts it.
                self.stamp[q] = NEVER;
                ctx.relations += self.alive_count.saturating_sub(1) as u64;
                new.push(q);
            }
        }
        self.refresh(&new, ctx);
    }

    /// Marks the rows `qs` (those not computed yet) computed, without
    /// counting them: their counts are bounded or counted when needed
    /// ([`Table::probe_all`], [`Table::refresh`]).
    pub fn mark_rows(&mut self, qs: &[usize], ctx: &mut Ctx) {
        for &q in qs {
            if !self.has_row[q] && self.alive[q] {
                self.has_row[q] = true;
                self.stamp[q] = NEVER;
                ctx.relations += self.alive_count.saturating_sub(1) as u64;
            }
        }
    }

    /// Computes row `q` against the alive members.
    pub fn compute_row(&mut self, q: usize, ctx: &mut Ctx) {
        self.compute_rows(&[q], ctx);
    }

    /// Takes member `p` out of the group.
    pub fn remove(&mut self, p: usize) {
        if !self.alive[p] {
            return;
        }
        self.alive[p] = false;
        self.alive_count -= 1;
        self.removed += 1;
        self.log.push(p as u32);
        self.bvh.remove(p);
        let rows = std::mem::take(&mut self.parked[p]);
        self.orphans.extend(rows);
    }

    /// The alive members other than `q` in the plane of `q`, ascending,
    /// with their orientation against it.
    pub fn coplanar(&self, q: usize, ctx: &Ctx) -> Vec<(usize, Rel)> {
        if self.alive[q] && self.is_exact(q) {
            // Exact counts of an alive row cover every other alive member
            // not in its plane: when they cover all, none is in it.
            let [f, b, c] = self.counts[q];
            if (f + b + c) as usize + 1 == self.alive_count {
                return Vec::new();
            }
        }
        let plane = ctx.polys[self.ids[q] as usize].plane;
        self.bvh
            .coplanar(&plane, q, &self.alive, ctx.tol)
            .into_iter()
            .map(|p| {
                let n = ctx.polys[self.ids[p] as usize].plane.normal;
                (
                    p,
                    if n.dot(plane.normal) >= 0.0 {
                        Rel::Same
                    } else {
                        Rel::Opposite
                    },
                )
            })
            .collect()
    }

    /// Front, back and cut counts of the alive members against `plane`
    /// (any plane, not only a member's).
    pub fn plane_counts(&self, plane: &Plane, ctx: &Ctx) -> [u32; 3] {
        self.bvh.counts(plane, usize::MAX, &self.alive, ctx.tol)
    }

    /// Starts watching every alive computed row with `w` (rows parked for
    /// an earlier watch are parked afresh).
    pub fn start_watch(&mut self, w: &mut Watch) {
        self.parked.iter_mut().for_each(Vec::clear);
        self.orphans.clear();
        for q in 0..self.len() {
            if self.alive[q] && self.has_row[q] {
                self.watch(w, q);
            }
        }
    }

    /// Starts watching row `q` (alive, computed, with exact counts or bounds
    /// as of its stamp: the slack of lower bounds is at most the true one,
    /// so the row is due no later than it could first pass). A row with a
    /// live witness cannot pass until the witness is removed: it is parked
    /// on it instead, and watched again then.
    pub fn watch(&mut self, w: &mut Watch, q: usize) {
        if self.has_live_witness(q) {
            self.parked[self.witness[q] as usize].push(q as u32);
            return;
        }
        let at = if self.stamp[q] == NEVER {
            0
        } else {
            u64::from(self.stamp[q]) + u64::from((w.slack)(self.counts[q]))
        };
        w.heap.push(Reverse((at, q as u32)));
    }

    /// The watched rows whose slack the removals may have used up, with
    /// exact counts, ascending; they are no longer watched.
    ///
    /// A row due whose counts a refresh would have to count again through
    /// the hierarchy is probed first, once: if the probe finds a member it
    /// cuts, or bounds that still leave slack, it is watched again
    /// uncounted. Every row that could pass is among those returned.
    pub fn due(&mut self, w: &mut Watch, ctx: &Ctx) -> Vec<usize> {
        for r in std::mem::take(&mut self.orphans) {
            let r = r as usize;
            if self.alive[r] && self.has_row[r] {
                self.watch(w, r);
            }
        }
        let mut v = Vec::new();
        while let Some(&Reverse((at, q))) = w.heap.peek() {
            if at > u64::from(self.removed) {
                break;
            }
            w.heap.pop();
            let q = q as usize;
            if self.alive[q] {
                v.push(q);
            }
        }
        v.sort_unstable();
        v.dedup();
        let limit = incremental_limit(self.alive_count);
        let probe: Vec<usize> = v
            .iter()
            .copied()
            .filter(|&q| {
                !self.is_exact(q)
                    && !self.probed[q]
                    && self.stamp[q] != self.removed
                    && !self.cheap_refresh(q, limit)
            })
            .collect();
        self.probe(&probe, ctx);
        let mut rows = Vec::with_capacity(v.len());
        for q in v {
            let waits = self.has_live_witness(q)
                || (self.stamp[q] == self.removed
                    && !self.is_exact(q)
                    && (w.slack)(self.counts[q]) > 0);
            if waits {
                self.watch(w, q);
            } else {
                rows.push(q);
            }
        }
        self.refresh(&rows, ctx);
        rows
    }

    /// The table of a subgroup: `members` (local indices of this table) and
    /// new `pieces` (polygon id, local index of the polygon it was split
    /// from). A member keeps its row (computed or not); a piece lies in its
    /// parent's plane and has its parent's. Counts are derived from this
    /// table's, when they are exact and the members left out are fewer
    /// than those kept (take out what left, add the pieces); other rows are
    /// left uncounted (bounded or counted when the subgroup needs them).
    pub fn subtable(&self, members: &[usize], pieces: &[(u32, usize)], ctx: &mut Ctx) -> Table {
        let mut ids: Vec<u32> = members.iter().map(|&i| self.ids[i]).collect();
        ids.extend(pieces.iter().map(|&(id, _)| id));
        let mut t = Table::new(ids, &ctx.polys);
        let origin: Vec<usize> = members
            .iter()
            .copied()
            .chain(pieces.iter().map(|&(_, parent)| parent))
            .collect();
        let mut kept = vec![false; self.len()];
        for &i in members {
            kept[i] = true;
        }
        // Alive members that do not come along (local index here, id).
        let gone: Vec<usize> = (0..self.len())
            .filter(|&i| self.alive[i] && !kept[i])
            .collect();
        let mut rows = Vec::new();
        for (q, &o) in origin.iter().enumerate() {
            if self.has_row[o] {
                t.has_row[q] = true;
                t.stamp[q] = NEVER;
                rows.push(q);
            }
        }
        // Entries of a known row against the new pieces are new relations.
        ctx.relations += (rows.len() * pieces.len()) as u64;
        t.carry_witnesses(self, members, pieces, &origin, ctx);
        if gone.len() + pieces.len() < t.len() {
            let gone_ids: Vec<u32> = gone.iter().map(|&i| self.ids[i]).collect();
            let piece_ids: Vec<u32> = pieces.iter().map(|&(id, _)| id).collect();
            let gone_bvh = Bvh::new(&gone_ids, &ctx.polys);
            let piece_bvh = Bvh::new(&piece_ids, &ctx.polys);
            let (all_gone, all_pieces) = (vec![true; gone.len()], vec![true; pieces.len()]);
            let (polys, tol) = (&ctx.polys, ctx.tol);
            let n_members = members.len();
            let exact: Vec<usize> = rows
                .iter()
                .copied()
                .filter(|&q| self.is_exact(origin[q]))
                .collect();
            let counts = count_rows(ctx.threads, &exact, |q| {
                let o = origin[q];
                let plane = polys[t.ids[q] as usize].plane;
                // A piece's row is its parent's, which did not count the
                // parent itself; the parent is among those gone.
                let skip_gone = gone.binary_search(&o).unwrap_or(usize::MAX);
                let skip_piece = q.checked_sub(n_members).unwrap_or(usize::MAX);
                let c = self.counts[o];
                let g = gone_bvh.counts(&plane, skip_gone, &all_gone, tol);
                let p = piece_bvh.counts(&plane, skip_piece, &all_pieces, tol);
                [c[0] - g[0] + p[0], c[1] - g[1] + p[1], c[2] - g[2] + p[2]]
            });
            for (q, c) in exact.into_iter().zip(counts) {
                t.counts[q] = c;
                t.stamp[q] = 0;
            }
        }
        // The other rows stay uncounted until the subgroup's builder asks
        // for bounds or counts.
        t
    }
}

impl Table {
    /// Carries the witnesses of `parent`'s rows into this subtable of it
    /// (see [`Table::subtable`]): a witness that came along, or a piece of
    /// one that was split, if the row's plane still cuts it (one
    /// classification each, by the very test of a count).
    fn carry_witnesses(
        &mut self,
        parent: &Table,
        members: &[usize],
        pieces: &[(u32, usize)],
        origin: &[usize],
        ctx: &Ctx,
    ) {
        let mut pos = vec![NO_WITNESS; parent.len()];
        for (k, &i) in members.iter().enumerate() {
            pos[i] = k as u32;
        }
        // Pieces of one polygon are contiguous: the first one's index.
        let mut first_piece = vec![NO_WITNESS; parent.len()];
        for (j, &(_, from)) in pieces.iter().enumerate().rev() {
            first_piece[from] = (members.len() + j) as u32;
        }
        for (q, &o) in origin.iter().enumerate() {
            let w = parent.witness[o];
            if !self.has_row[q] || w == NO_WITNESS || !parent.alive[w as usize] {
                continue;
            }
            let w = w as usize;
            let plane = ctx.polys[self.ids[q] as usize].plane;
            let cut = |x: usize| ctx.classify(self.ids[x], &plane) == Rel::Cut;
            let found = if pos[w] != NO_WITNESS {
                Some(pos[w] as usize).filter(|&x| cut(x))
            } else if first_piece[w] != NO_WITNESS {
                (first_piece[w] as usize..self.len())
                    .take_while(|&x| pieces[x - members.len()].1 == w)
                    .find(|&x| cut(x))
            } else {
                None
            };
            if let Some(x) = found {
                self.witness[q] = x as u32;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{NoProgress, Reporter};
    use crate::geom::bounds;
    use glam::DVec3;

    /// Row `q` of the paper's full table, counted polygon by polygon.
    fn full_row(t: &Table, q: usize, ctx: &Ctx) -> [u32; 3] {
        let plane = ctx.polys[t.ids[q] as usize].plane;
        let mut c = [0; 3];
        for p in (0..t.len()).filter(|&p| p != q && t.is_alive(p)) {
            match ctx.classify(t.ids[p], &plane) {
                Rel::Front => c[0] += 1,
                Rel::Back => c[1] += 1,
                Rel::Cut => c[2] += 1,
                _ => {}
            }
        }
        c
    }

    fn check(t: &Table, ctx: &Ctx) {
        let mut rows = 0;
        for q in (0..t.len()).filter(|&q| t.is_alive(q) && t.has_row(q)) {
            assert_eq!(t.counts(q), full_row(t, q, ctx), "row {q}");
            rows += 1;
        }
        assert!(rows > 0);
    }

    /// Probes every row stale after removals (breadth first from the
    /// row's own leaf, or depth first with a `deep` budget) and checks that
    /// each true count lies between its bound and its bound plus the
    /// undecided, and that some probe did leave members undecided (else
    /// this tests nothing of the bounds).
    fn check_bounds(t: &mut Table, ctx: &Ctx, deep: Option<usize>) {
        match deep {
            Some(budget) => {
                let rows: Vec<usize> = (0..t.len())
                    .filter(|&q| t.is_alive(q) && t.has_row(q) && !t.is_exact(q))
                    .collect();
                t.deepen(&rows, ctx, budget);
            }
            None => t.probe_all(ctx, true),
        }
        let mut loose = 0;
        for q in (0..t.len()).filter(|&q| t.is_alive(q) && t.has_row(q)) {
            let (lo, u) = t.bounds(q);
            let exact = full_row(t, q, ctx);
            for i in 0..3 {
                assert!(lo[i] <= exact[i] && exact[i] <= lo[i] + u, "row {q}");
            }
            loose += usize::from(u > 0);
        }
        assert!(loose > 0);
    }

    /// Every live witness is a member its row's plane cuts, and some rows
    /// have one (the torus's inner half is saddle-shaped: each facet's
    /// plane cuts some other facet).
    fn check_witnesses(t: &Table, ctx: &Ctx) {
        let mut witnessed = 0;
        for q in (0..t.len()).filter(|&q| t.is_alive(q) && t.has_live_witness(q)) {
            let plane = ctx.polys[t.ids[q] as usize].plane;
            let w = t.witness[q];
            assert_ne!(w as usize, q);
            assert_eq!(ctx.classify(t.ids[w as usize], &plane), Rel::Cut, "row {q}");
            witnessed += 1;
        }
        assert!(witnessed > 0);
    }

    /// The counts kept through the hierarchy, through removals (corrected
    /// one by one, or counted again) and through subtables (from the
    /// parent's counts, or counted again) equal the full table's.
    #[test]
    fn counts_match_the_full_table() {
        let mut progress = NoProgress;
        let polys = crate::scenes::torus(30, 14).polygons;
        let (lo, hi) = bounds(&polys);
        let n = polys.len();
        let reporter = Reporter::new(&mut progress, n);
        let threads = Threads::new(2);
        let mut ctx = Ctx::new(
            polys,
            Tolerance::for_diagonal((hi - lo).length()),
            7,
            &reporter,
            &threads,
        );
        let mut t = Table::new((0..n as u32).collect(), &ctx.polys);
        let all: Vec<usize> = (0..n).collect();
        t.compute_rows(&all, &mut ctx);
        check(&t, &ctx);
        for removals in [3, 150] {
            for _ in 0..removals {
                let p = ctx.rng.below(n);
                t.remove(p);
            }
            check_bounds(&mut t, &ctx, None);
            check_witnesses(&t, &ctx);
            check_bounds(&mut t, &ctx, Some(16));
            check_witnesses(&t, &ctx);
            t.refresh_all(&ctx);
            check(&t, &ctx);
            check_witnesses(&t, &ctx);
        }
        // A plane that leaves most of the torus in front of it.
        let x = lo.x + 0.2 * (hi.x - lo.x);
        let plane = Plane {
            normal: DVec3::X,
            d: -x,
        };
        let (mut front, mut pieces) = (Vec::new(), Vec::new());
        for p in (0..t.len()).filter(|&p| t.is_alive(p)) {
            match ctx.classify(t.ids[p], &plane) {
                Rel::Front => front.push(p),
                Rel::Cut => {
                    let (f, _) = ctx.split(t.ids[p], &plane);
                    pieces.extend(f.into_iter().map(|id| (id, p)));
                }
                _ => {}
            }
        }
        assert!(!pieces.is_empty());
        // Most members kept: from the parent's counts; few: counted again.
        for keep in [front.len(), 5] {
            let mut sub = t.subtable(&front[..keep], &pieces, &mut ctx);
            // Rows derived from the parent are exact already; the others
            // are left uncounted and counted here.
            // Witnesses carried from the parent are checked before any
            // count of the subgroup could replace them.
            if keep > 5 {
                check_witnesses(&sub, &ctx);
            }
            sub.refresh_all(&ctx);
            check(&sub, &ctx);
        }
    }
}
