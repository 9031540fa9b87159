//! A short lookahead for the choice of a splitting plane.
//!
//! When no plane separates a group, the paper takes the plane with the
//! fewest cuts (here weighed against balance, `feudal::SPLIT_WEIGHT`). That
//! score sees only the cuts the plane makes now, not the pieces its two
//! subgroups will cost later: a plane that cuts one more polygon may leave
//! two subgroups that peel off into levels or are separated without a cut,
//! where the best-scored plane leaves a knot that costs dozens of splits
//! below. What the microcontroller pays for is every output polygon (drawn
//! in each view, stored in the file), so in groups of up to
//! [`GROUP`] members the builder builds the whole subtree of each of the
//! best [`CANDIDATES`] member planes, of the best auxiliary plane that cuts
//! nothing and of the best [`CUTTING`] that cut some, with
//! the greedy rule below it, counts the output polygons each one adds, and
//! keeps the cheapest (the greedy choice on a tie). The trial subtrees are
//! thrown away: the polygons they split are truncated off the working set
//! and the counters and random state restored, so the chosen subtree is
//! built again, with the lookahead in its own subgroups.
//!
//! Every candidate is a valid plane, so the order stays exact whatever is
//! chosen. The cost is bounded: a trial builds at most [`GROUP`] members
//! greedily (stopping as soon as it adds more than the best so far), each
//! node of the tree runs at most `CANDIDATES + CUTTING + 1` trials, and
//! large models look ahead only in small groups ([`group_limit`]).
//!
//! On two threads, two trials run at once when a thread is free
//! ([`cheapest`]), and a trial's subgroups may be built on two threads
//! (`feudal::build_both`); the choice is the one of a single thread. The
//! relations trials compute are not counted: the count is that of the
//! tree built, the same however the trials were scheduled.

use super::feudal::{divide, Divide, Mode};
use super::table::Table;
use super::{Ctx, Work};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The best member planes tried, by the greedy score.
pub const CANDIDATES: usize = 4;

/// Groups of up to this many alive members look ahead.
pub const GROUP: usize = 512;

/// Auxiliary planes that cut members tried (`auxiliary::cutting_aux`).
pub const CUTTING: usize = 2;

/// In models of more than [`LARGE_MODEL`] input polygons, only groups of
/// up to this many members look ahead: rocker-arm (20,088 triangles) has
/// thousands of split groups, and looking ahead in those of up to 512
/// members took its build from 6 s to 85 s; up to 64, to about 12 s.
pub const LARGE_GROUP: usize = 64;

/// Models of more input polygons than this look ahead in groups of up to
/// [`LARGE_GROUP`] members only.
pub const LARGE_MODEL: usize = 4096;

/// The largest group that looks ahead in a build of `n` input polygons.
pub fn group_limit(n: usize) -> usize {
    if n > LARGE_MODEL {
        LARGE_GROUP
    } else {
        GROUP
    }
}

/// Whether the choice in the group of `t` looks ahead: small enough groups,
/// and not inside a trial (trials are greedy).
pub fn applies(t: &Table, ctx: &Ctx) -> bool {
    !ctx.in_trial() && t.alive_count() <= ctx.look_group
}

/// The index of the option in `options` whose subtree adds the fewest
/// output polygons (the first on a tie).
///
/// When a thread is free, two trials run at once: the later one on a copy
/// of the group ([`Ctx::detach`]), cut short by the earlier one's count as
/// soon as that is known ([`Ctx::trial_over`]). Either trial returns its
/// true count or more than the best count of the trials before it, so the
/// running minimum, taken in order, picks the option a single thread
/// picks.
pub fn cheapest(t: &Table, options: &[Divide], mode: Mode, ctx: &mut Ctx) -> usize {
    let mut best = (usize::MAX, 0);
    let mut i = 0;
    while i < options.len() {
        let limit = best.0.saturating_sub(1);
        if i + 1 < options.len() && ctx.threads.take() {
            let mut copy = t.clone();
            let (mut part, _) = ctx.detach(&mut copy);
            let cap = AtomicUsize::new(best.0);
            let later = options[i + 1].clone();
            let threads = ctx.threads;
            let (second, first) = threads.beside(
                Work::Trial,
                || {
                    part.cap = Some(&cap);
                    let trial = part.begin_trial(limit);
                    let _ = divide(copy, later, mode, &mut part);
                    part.end_trial(trial)
                },
                || {
                    let added = trial(t, &options[i], limit, mode, ctx);
                    cap.fetch_min(added, Ordering::AcqRel);
                    added
                },
            );
            for (added, k) in [(first, i), (second, i + 1)] {
                if added < best.0 {
                    best = (added, k);
                }
            }
            i += 2;
        } else {
            let added = trial(t, &options[i], limit, mode, ctx);
            if added < best.0 {
                best = (added, i);
            }
            i += 1;
        }
    }
    best.1
}

/// The output polygons the subtree of `d` adds, or more than `limit` if
/// it adds more (it is cut short).
fn trial(t: &Table, d: &Divide, limit: usize, mode: Mode, ctx: &mut Ctx) -> usize {
    let trial = ctx.begin_trial(limit);
    let _ = divide(t.clone(), d.clone(), mode, ctx);
    ctx.end_trial(trial)
}
