//! Static and dynamic feudal preprocessing (`feudal-priority.md`, "Static
//! preprocessing" and "Dynamic preprocessing").
//!
//! One connecting node is built per group of polygons. Static computes the
//! whole one-way priority table of the group first; dynamic computes rows in
//! a random order and acts on each as soon as it shows an absolute priority
//! polygon or a separating plane, then finishes what is left statically.

use super::auxiliary::{best_aux, cutting_aux, pivot_aux, pivot_uncut, AuxPlane};
use super::lookahead;
use super::pivot;
use super::table::{Rel, Table, Watch};
use super::{Ctx, Work};
use crate::geom::Plane;
use crate::tree::{Connecting, Level, Switch};
use std::cmp::Ordering;

/// Which preprocessing drives a group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Whole table first.
    Static,
    /// Rows in random order, acted on as they come.
    Dynamic,
}

/// Builds the connecting node of the group in `table`.
pub fn build_group(mut table: Table, mode: Mode, ctx: &mut Ctx) -> Connecting {
    if ctx.trial_over() {
        // A lookahead trial that cannot win: its tree is thrown away.
        return Connecting::default();
    }
    let mut levels = Vec::new();
    if mode == Mode::Dynamic {
        if let Some(s) = dynamic_phase(&mut table, &mut levels, ctx) {
            let switch = make_switch(table, s, mode, ctx);
            return Connecting {
                levels,
                switch: Some(Box::new(switch)),
            };
        }
    }
    // Static from step 1 on (for dynamic: every remaining row is known, so
    // this computes nothing new).
    // Rows are counted when needed (see `table.rs`).
    // Nothing this function holds while the subtrees below are built may
    // be as large as the group: the recursion is as deep as the tree (858
    // on a 92,000-triangle mesh), and per-member lists kept on its path
    // made the peak heap grow as n^1.7 (see `make_switch_on`).
    table.mark_rows(&(0..table.len()).collect::<Vec<usize>>(), ctx);
    extract_levels(&mut table, &mut levels, ctx);
    if table.alive_count() == 0 {
        return Connecting {
            levels,
            switch: None,
        };
    }
    let switch = if let Some(s) = choose_separator(&mut table, ctx) {
        make_switch(table, s, mode, ctx)
    } else {
        let look = lookahead::applies(&table, ctx);
        let k = if look { ctx.look.candidates } else { 1 };
        let mut aux = best_aux(&table, ctx, split_score);
        if aux.is_none() && ctx.in_trial() && table.alive_count() <= ctx.look.trial_edges {
            // The trial's stand-in for the lookahead's edge planes
            // (`lookahead::TRIAL_EDGES`).
            aux = pivot_uncut(&table, ctx, split_score);
        }
        // Without a lookahead only the better of the best member plane and
        // the best auxiliary plane is used: members that cannot beat the
        // auxiliary plane need not be counted.
        let cap = if look {
            None
        } else {
            aux.as_ref().map(|a| a.score)
        };
        let splitters = choose_splitters(&mut table, ctx, k, cap);
        let member_score = splitters.first().map(|&s| {
            let [f, b, c] = table.counts(s);
            split_score(f, b, c)
        });
        // The paper's greedy choice: the better-scored of the best member
        // plane and the best auxiliary plane.
        let mut options: Vec<Divide> = Vec::new();
        match aux {
            Some(a) if member_score.is_none_or(|m| a.score < m) => {
                options.push(Divide::Aux(a));
                options.extend(splitters.into_iter().map(Divide::Member));
            }
            a => {
                options.extend(splitters.into_iter().map(Divide::Member));
                options.extend(a.map(Divide::Aux));
            }
        }
        if look && ctx.look.alternatives > 0 {
            let alternatives = choose_alternatives(&mut table, ctx, ctx.look.alternatives);
            for s in alternatives {
                if !options
                    .iter()
                    .any(|o| matches!(o, Divide::Member(m) if *m == s))
                {
                    options.push(Divide::Member(s));
                }
            }
        }
        if look {
            let n = lookahead::CUTTING;
            options.extend(
                cutting_aux(&table, ctx, split_score, n)
                    .into_iter()
                    .map(Divide::Aux),
            );
        }
        if look && table.alive_count() <= pivot::GROUP {
            // Planes through an edge of the group, one family cutting
            // nothing and one cutting few (`pivot.rs`): judged only by
            // their trials (the greedy rule below takes them for worse).
            options.extend(
                pivot_aux(&table, ctx, split_score, lookahead::PIVOTS)
                    .into_iter()
                    .map(Divide::Aux),
            );
        }
        // The plane of a member that holds a large share of the group's
        // area (`lookahead::dominant`): an option of the lookahead, and
        // tried against the greedy choice in larger groups too.
        let wide = !look && ctx.look.wide && !ctx.in_trial();
        if look || wide {
            if wide {
                options.truncate(1);
            }
            if let Some(m) = lookahead::dominant(&table, ctx) {
                if !options
                    .iter()
                    .any(|o| matches!(o, Divide::Member(x) if *x == m))
                {
                    options.push(Divide::Member(m));
                }
            }
        }
        let pick = if (look || wide) && options.len() > 1 {
            lookahead::cheapest(&table, &options, mode, ctx)
        } else {
            0
        };
        let chosen = options.swap_remove(pick);
        // The other options' auxiliary planes hold a relation per member.
        drop(options);
        divide(table, chosen, mode, ctx)
    };
    Connecting {
        levels,
        switch: Some(Box::new(switch)),
    }
}

/// `Some(true)` for absolute front priority, `Some(false)` for absolute
/// back; `q`'s counts must be exact.
fn absolute(t: &Table, q: usize) -> Option<bool> {
    if !t.is_alive(q) || !t.has_row(q) {
        return None;
    }
    let [front, back, cut] = t.counts(q);
    if cut != 0 {
        None
    } else if front == 0 {
        Some(true)
    } else if back == 0 {
        Some(false)
    } else {
        None
    }
}

/// What must fall to zero for a row to become absolute: its cut count and
/// the smaller of its front and back counts.
fn absolute_slack([f, b, c]: [u32; 3]) -> u32 {
    c.saturating_add(f.min(b))
}

/// What must fall to zero for a row to become absolute or separating.
fn cut_slack([_, _, c]: [u32; 3]) -> u32 {
    c
}

/// Puts `q` into the front (`front`) or back bunch of `level`, with the
/// polygons in its plane: same orientation to the same bunch, reversed to
/// the opposite one.
fn bunch(l: &mut Level, front: bool) -> &mut Vec<u32> {
    if front {
        &mut l.front
    } else {
        &mut l.back
    }
}

/// The members taken into the level being built, in order, with a mark
/// per member: a level of the whole outer half of a large mesh takes tens
/// of thousands, too many to look each one up in the list.
struct Taken {
    list: Vec<usize>,
    mark: Vec<bool>,
}

impl Taken {
    /// None taken of a group of `n` members.
    fn new(n: usize) -> Taken {
        Taken {
            list: Vec::new(),
            mark: vec![false; n],
        }
    }

    fn contains(&self, q: usize) -> bool {
        self.mark[q]
    }

    fn push(&mut self, q: usize) {
        self.mark[q] = true;
        self.list.push(q);
    }

    /// Forgets the members taken (for the next level).
    fn clear(&mut self) {
        for &q in &self.list {
            self.mark[q] = false;
        }
        self.list.clear();
    }
}

/// Puts `q` and the untaken polygons in its plane into `level`, and them
/// into `taken`.
fn take(t: &Table, q: usize, front: bool, level: &mut Level, taken: &mut Taken, ctx: &Ctx) {
    bunch(level, front).push(t.ids[q]);
    taken.push(q);
    for (p, r) in t.coplanar(q, ctx) {
        if taken.contains(p) {
            continue;
        }
        bunch(level, front == (r == Rel::Same)).push(t.ids[p]);
        taken.push(p);
    }
}

/// Static step 2: peel off all absolute priority polygons, level by level.
fn extract_levels(t: &mut Table, levels: &mut Vec<Level>, ctx: &mut Ctx) {
    let mut watch = Watch::new(absolute_slack);
    // Rows with a live witness are parked uncounted (`Table::watch`).
    t.probe_all(ctx, false);
    t.start_watch(&mut watch);
    let mut taken = Taken::new(t.len());
    loop {
        let due = t.due(&mut watch, ctx);
        let mut level = Level::default();
        taken.clear();
        for &q in &due {
            if taken.contains(q) {
                continue;
            }
            if let Some(front) = absolute(t, q) {
                take(t, q, front, &mut level, &mut taken, ctx);
            }
        }
        if level.front.is_empty() && level.back.is_empty() {
            return;
        }
        finish_level(t, &taken.list);
        for q in due {
            if t.is_alive(q) {
                t.watch(&mut watch, q);
            }
        }
        ctx.placed(taken.list.iter().map(|&q| t.ids[q]));
        levels.push(level);
    }
}

/// Removes the `taken` members from the group.
fn finish_level(t: &mut Table, taken: &[usize]) {
    for &q in taken {
        t.remove(q);
    }
}

/// Dynamic steps 1 and 2. Returns the separating member if one was found
/// (the caller makes the switch node); levels found go into `levels`.
fn dynamic_phase(t: &mut Table, levels: &mut Vec<Level>, ctx: &mut Ctx) -> Option<usize> {
    let mut order: Vec<usize> = (0..t.len())
        .filter(|&q| t.is_alive(q) && !t.has_row(q))
        .collect();
    ctx.rng.shuffle(&mut order);
    // Rows known from the parent group are examined as they were there
    // (watched from bounds: they are counted when due).
    let mut watch = Watch::new(cut_slack);
    t.probe_all(ctx, false);
    t.start_watch(&mut watch);
    let mut taken = Taken::new(t.len());
    for q in order {
        if !t.is_alive(q) {
            continue;
        }
        t.compute_row(q, ctx);
        t.watch(&mut watch, q);
        // Examine the new row, then re-examine the earlier ones after every
        // removal: a removal may make them absolute or separating. Only rows
        // whose cut count the removals may have emptied can have changed.
        loop {
            let due = t.due(&mut watch, ctx);
            let first = due.contains(&q).then_some(q);
            let mut found = None;
            for r in first.into_iter().chain(due.iter().copied()) {
                if let Some(front) = absolute(t, r) {
                    found = Some(Err((r, front)));
                    break;
                }
                if t.counts(r)[2] == 0 {
                    found = Some(Ok(r));
                    break;
                }
            }
            match found {
                Some(Ok(r)) => return Some(r),
                Some(Err((r, front))) => {
                    let mut level = Level::default();
                    taken.clear();
                    take(t, r, front, &mut level, &mut taken, ctx);
                    finish_level(t, &taken.list);
                    for d in due {
                        if t.is_alive(d) {
                            t.watch(&mut watch, d);
                        }
                    }
                    ctx.placed(taken.list.iter().map(|&q| t.ids[q]));
                    levels.push(level);
                }
                None => {
                    for d in due {
                        t.watch(&mut watch, d);
                    }
                    break;
                }
            }
        }
    }
    None
}

/// Orders candidates deterministically and independently of input order:
/// by the polygon's plane, then its centroid.
fn geometric_key(ctx: &Ctx, id: u32) -> [f64; 7] {
    let p = &ctx.polys[id as usize];
    let c = crate::geom::centroid(&p.verts);
    let n = p.plane.normal;
    [n.x, n.y, n.z, p.plane.d, c.x, c.y, c.z]
}

fn key_cmp(a: &[f64; 7], b: &[f64; 7]) -> Ordering {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.total_cmp(y))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}

/// Rows counted exactly at once by [`best_by`]: enough for the counting to
/// use both cores when many rows could win, few enough that little is
/// counted beyond the rows needed.
const BATCH: usize = 256;

/// The budgets of the depth-first probes ([`Table::deepen`]) a candidate
/// row gets in [`best_by`] before it is counted: most rows that cannot win
/// are shown so by the first (a few leaves along the row's plane), most of
/// the rest by the second; a count opens every leaf along the plane.
const DEEPER: [usize; 2] = [64, 384];

/// `(score, key, index)` of a candidate, compared lexicographically.
type Rank = ((u32, u32), [f64; 7], usize);

fn rank_cmp(a: &Rank, b: &Rank) -> Ordering {
    a.0.cmp(&b.0)
        .then_with(|| key_cmp(&a.1, &b.1))
        .then(a.2.cmp(&b.2))
}

/// Picks the `k` alive members minimising `score`, best first, ties broken
/// geometrically, then by index (the first one): the first is the member
/// the full table would give.
///
/// Lazily: every row gets bounds ([`Table::probe_all`]); `bound(lower
/// counts, undecided)` must be at most the row's score (`None`: the row
/// cannot qualify). Rows are counted exactly in ascending order of bound
/// and stop being counted once the next bound is above the `k`-th best
/// exact score: every row left has a score at least its bound, so none is
/// better. With `uncut`, only rows that cut nothing qualify: rows with a
/// live witness (a member they cut) are left out unprobed.
fn best_by(
    t: &mut Table,
    ctx: &Ctx,
    k: usize,
    uncut: bool,
    score: impl Fn([u32; 3]) -> Option<(u32, u32)>,
    bound: impl Fn([u32; 3], u32) -> Option<(u32, u32)>,
) -> Vec<usize> {
    t.probe_all(ctx, !uncut);
    let mut cands: Vec<Rank> = (0..t.len())
        .filter(|&q| t.is_alive(q) && t.has_row(q))
        .filter(|&q| !(uncut && t.has_live_witness(q)))
        .filter_map(|q| {
            let (c, u) = t.bounds(q);
            bound(c, u).map(|b| (b, geometric_key(ctx, t.ids[q]), q))
        })
        .collect();
    cands.sort_unstable_by(rank_cmp);
    // The best `k` exact ranks so far, ascending.
    let mut best: Vec<Rank> = Vec::new();
    let mut next = 0;
    while next < cands.len() {
        let end = cands[next..]
            .iter()
            .take(BATCH)
            .take_while(|c| best.len() < k || rank_cmp(c, &best[k - 1]).is_lt())
            .count();
        if end == 0 {
            break;
        }
        let mut batch: Vec<(usize, [f64; 7])> =
            cands[next..next + end].iter().map(|c| (c.2, c.1)).collect();
        next += end;
        // Deeper bounds first, twice deeper: a row they show unable to
        // beat the `k`-th best so far (which only gets better) is never
        // counted.
        for budget in DEEPER {
            let shallow: Vec<usize> = batch
                .iter()
                .map(|c| c.0)
                .filter(|&q| !t.is_exact(q))
                .collect();
            if shallow.is_empty() {
                break;
            }
            t.deepen(&shallow, ctx, budget);
            batch.retain(|&(q, key)| {
                let (counts, u) = t.bounds(q);
                bound(counts, u)
                    .is_some_and(|b| best.len() < k || rank_cmp(&(b, key, q), &best[k - 1]).is_lt())
            });
        }
        let rows: Vec<usize> = batch.iter().map(|c| c.0).collect();
        t.refresh(&rows, ctx);
        for &(q, key) in &batch {
            let Some(s) = score(t.counts(q)) else {
                continue;
            };
            let r = (s, key, q);
            let at = best.partition_point(|b| rank_cmp(b, &r).is_lt());
            if at < k {
                best.insert(at, r);
                best.truncate(k);
            }
        }
    }
    best.into_iter().map(|b| b.2).collect()
}

/// At least `|f - b|` for counts at least `f` and `b` with `u` members
/// undecided (all of them could join the smaller side).
fn balance_bound(f: u32, b: u32, u: u32) -> u32 {
    f.abs_diff(b).saturating_sub(u)
}

/// Step 4: a separating plane (empty cut column), the most balanced one.
fn choose_separator(t: &mut Table, ctx: &Ctx) -> Option<usize> {
    best_by(
        t,
        ctx,
        1,
        true,
        |[f, b, c]| (c == 0).then_some((0, f.abs_diff(b))),
        |[f, b, c], u| (c == 0).then_some((0, balance_bound(f, b, u))),
    )
    .first()
    .copied()
}

/// How many polygons of imbalance one split is worth when choosing a
/// splitting plane.
///
/// The paper ranks candidates by fewest cuts, then balance. On tessellated
/// meshes (cylinders, cones, fillets) that rule keeps choosing a facet that
/// cuts two or three neighbours to peel off one polygon, hundreds of times
/// over; weighing one cut against eight polygons of imbalance instead
/// roughly thirds the splits on `socket.off` (481 → 155) and halves them on
/// `shuttle.obj`, `rabbit.obj` and `suzanne.obj` (`fpt bench-build`).
pub const SPLIT_WEIGHT: u32 = 8;

/// The rank of a splitting plane with `f` polygons in front, `b` behind
/// and `c` cut: lower is better (see [`SPLIT_WEIGHT`]).
fn split_score(f: u32, b: u32, c: u32) -> (u32, u32) {
    (
        c.saturating_mul(SPLIT_WEIGHT).saturating_add(f.abs_diff(b)),
        c,
    )
}

/// Step 5: the fewest cuts, weighed against balance (see [`SPLIT_WEIGHT`]):
/// the best `k` members, best first (never empty while a member is alive,
/// without a `cap`). With a `cap` (the score of a plane that wins unless a
/// member scores at most as well), rows that cannot score within it are
/// not counted; the first member returned is still the best one if any
/// scores within the cap, and none may be returned if none does.
fn choose_splitters(t: &mut Table, ctx: &Ctx, k: usize, cap: Option<(u32, u32)>) -> Vec<usize> {
    // Each true count is at least its bound, so the score is at least the
    // score of the cut bound with the balance bound (see `split_score`).
    let best = best_by(
        t,
        ctx,
        k,
        false,
        |[f, b, c]| Some(split_score(f, b, c)),
        |[f, b, c], u| {
            let bound = (
                c.saturating_mul(SPLIT_WEIGHT)
                    .saturating_add(balance_bound(f, b, u)),
                c,
            );
            cap.is_none_or(|cap| bound <= cap).then_some(bound)
        },
    );
    if best.is_empty() && cap.is_none() {
        return (0..t.len()).find(|&q| t.is_alive(q)).into_iter().collect();
    }
    best
}

/// The best `k` members by a score that weighs a cut as
/// [`lookahead::ALT_WEIGHT`] polygons of imbalance, best first: candidates
/// for the lookahead besides [`choose_splitters`]' (see `lookahead.rs`).
fn choose_alternatives(t: &mut Table, ctx: &Ctx, k: usize) -> Vec<usize> {
    let w = lookahead::ALT_WEIGHT;
    best_by(
        t,
        ctx,
        k,
        false,
        |[f, b, c]| Some((c.saturating_mul(w).saturating_add(f.abs_diff(b)), c)),
        |[f, b, c], u| {
            Some((
                c.saturating_mul(w).saturating_add(balance_bound(f, b, u)),
                c,
            ))
        },
    )
}

/// A way to divide a group that no plane separates.
#[derive(Clone)]
pub(super) enum Divide {
    /// The plane of a member (local index).
    Member(usize),
    /// An auxiliary plane.
    Aux(AuxPlane),
}

/// Makes the switch node of `d`.
pub(super) fn divide(t: Table, d: Divide, mode: Mode, ctx: &mut Ctx) -> Switch {
    match d {
        Divide::Member(s) => make_switch(t, s, mode, ctx),
        Divide::Aux(a) => {
            let rels = a.rels;
            make_switch_on(t, a.plane, None, |_, p, _| rels[p], mode, ctx)
        }
    }
}

/// Makes the switch node on the plane of member `s`: its coplanar bunch, and
/// the groups in front and behind, splitting the polygons it cuts.
fn make_switch(t: Table, s: usize, mode: Mode, ctx: &mut Ctx) -> Switch {
    let plane = ctx.polys[t.ids[s] as usize].plane;
    // The row of `s` again: its counts were kept, not its entries.
    make_switch_on(
        t,
        plane,
        Some(s),
        move |c, _, id| c.classify(id, &plane),
        mode,
        ctx,
    )
}

/// Makes a switch node on `plane`, given the relation `rel(ctx, p, id)` of
/// each member (local index `p`, polygon `id`) to it (`Unknown` ones are computed); `member` is the polygon
/// the plane was taken from, if any.
fn make_switch_on(
    t: Table,
    plane: Plane,
    member: Option<usize>,
    rel: impl Fn(&Ctx, usize, u32) -> Rel,
    mode: Mode,
    ctx: &mut Ctx,
) -> Switch {
    let mut on: Vec<u32> = member.map(|s| t.ids[s]).into_iter().collect();
    let (mut front, mut back) = (Vec::new(), Vec::new());
    let (mut front_pieces, mut back_pieces) = (Vec::new(), Vec::new());
    for p in 0..t.len() {
        if Some(p) == member || !t.is_alive(p) {
            continue;
        }
        let pid = t.ids[p];
        let r = match rel(ctx, p, pid) {
            Rel::Unknown => ctx.relation_to_plane(pid, &plane),
            r => r,
        };
        match r {
            Rel::Front => front.push(p),
            Rel::Back => back.push(p),
            Rel::Same | Rel::Opposite => on.push(pid),
            Rel::Cut | Rel::Unknown => {
                let (f, b) = ctx.split(pid, &plane);
                front_pieces.extend(f.into_iter().map(|id| (id, p)));
                back_pieces.extend(b.into_iter().map(|id| (id, p)));
            }
        }
    }
    ctx.placed(on.iter().copied());
    let ft = t.subtable(&front, &front_pieces, ctx);
    let bt = t.subtable(&back, &back_pieces, ctx);
    // Freed before the subtrees are built, not after: every switch node on
    // the path down holds its frame, and these lists (and `rel`, which may
    // hold a relation per member) are the whole group's. Kept, they summed
    // to the group sizes along the path: 700 of the 780 MiB peak heap of a
    // 92,000-triangle subdivided fandisk, which grew as n^1.7.
    drop((t, front, back, front_pieces, back_pieces, rel));
    let (front, back) = build_both(ft, bt, mode, ctx);
    Switch {
        plane,
        on,
        front,
        back,
    }
}

/// Both subgroups of a switch node need at least this many members for
/// the front one to be built on another thread: below, copying its
/// polygons and starting a thread cost about what building it does.
const FORK: usize = 32;

/// Builds the groups in front of (`ft`) and behind (`bt`) a switch node,
/// the front one on another thread when one is free and both groups are
/// large enough ([`FORK`]). The two are independent: the front one is
/// built on a copy of its polygons ([`Ctx::detach`]) and its pieces
/// appended afterwards, so the tree is the one built on one thread (the
/// dynamic builder draws random numbers in one sequence through both, so
/// it never splits them). In a lookahead trial the front part may add
/// what the trial has left; if it is cut short, so is the trial.
fn build_both(ft: Table, bt: Table, mode: Mode, ctx: &mut Ctx) -> (Connecting, Connecting) {
    let big = ft.alive_count().min(bt.alive_count()) >= FORK;
    if mode != Mode::Static || !big || !ctx.threads.take() {
        let front = build_group(ft, mode, ctx);
        return (front, build_group(bt, mode, ctx));
    }
    let mut ft = ft;
    let (mut part, ids) = ctx.detach(&mut ft);
    let threads = ctx.threads;
    let ((mut front, part), back) = threads.beside(
        Work::Subtree,
        move || {
            let front = build_group(ft, mode, &mut part);
            (front, part)
        },
        || build_group(bt, mode, ctx),
    );
    ctx.attach(part, &ids, &mut front);
    (front, back)
}
