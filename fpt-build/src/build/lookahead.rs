//! A short lookahead for the choice of a splitting plane.
//!
//! When no plane separates a group, the paper takes the plane with the
//! fewest cuts (here weighed against balance, `feudal::SPLIT_WEIGHT`). That
//! score sees only the cuts the plane makes now, not the pieces its two
//! subgroups will cost later: a plane that cuts one more polygon may leave
//! two subgroups that peel off into levels or are separated without a cut,
//! where the best-scored plane leaves a knot that costs dozens of splits
//! below. What the microcontroller pays for is every output polygon (drawn
//! in each view, stored in the file), so in groups small enough
//! ([`Look::group`]) the builder builds the whole subtree of each of the
//! best few member planes ([`Look::candidates`] by the greedy score and
//! [`Look::alternatives`] by one that weighs cuts less, [`ALT_WEIGHT`]),
//! of the best auxiliary plane that cuts
//! nothing, of the best [`CUTTING`] that cut some and of the best
//! [`PIVOTS`] through an edge of the group of each kind, with
//! the greedy rule below it, counts the output polygons each one adds, and
//! keeps the cheapest (the greedy choice on a tie). Below a trial's
//! option, small groups that the greedy rule cannot separate also try a
//! plane through an edge that cuts nothing ([`TRIAL_EDGES`]), as the
//! lookahead would. The trial subtrees are
//! thrown away: the polygons they split are truncated off the working set
//! and the counters and random state restored, so the chosen subtree is
//! built again, with the lookahead in its own subgroups.
//!
//! Every candidate is a valid plane, so the order stays exact whatever is
//! chosen. The cost is bounded: a trial builds at most [`Look::group`]
//! members greedily (stopping as soon as it adds more than the best so
//! far, or at once when an earlier one added nothing), each node of the
//! tree runs at most `candidates + alternatives + CUTTING + 2 × PIVOTS + 2`
//! trials (the last the plane of a [`dominant`] member), and larger models
//! look ahead less ([`look_for`]). Larger groups run two trials at most,
//! and only when they have a dominant member ([`Look::wide`]).
//!
//! On two threads, two trials run at once when a thread is free
//! ([`cheapest`]), and a trial's subgroups may be built on two threads
//! (`feudal::build_both`); the choice is the one of a single thread. The
//! relations trials compute are not counted: the count is that of the
//! tree built, the same however the trials were scheduled.

use super::feudal::{divide, Divide, Mode};
use super::table::Table;
use super::{Ctx, Work};
use crate::geom::area;
use std::sync::atomic::{AtomicUsize, Ordering};

/// What a build looks ahead with ([`look_for`]): the largest group that
/// looks ahead, the best member planes tried by the greedy score, and the
/// best member planes tried by the [`ALT_WEIGHT`] score besides them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Look {
    /// Groups of up to this many alive members look ahead.
    pub group: usize,
    /// The best member planes tried, by the greedy score.
    pub candidates: usize,
    /// The best member planes by the [`ALT_WEIGHT`] score tried as well
    /// (those not already among the candidates).
    pub alternatives: usize,
    /// Whether groups too large to look ahead try the plane of a
    /// [`dominant`] member against the greedy choice.
    pub wide: bool,
    /// Inside a trial, groups of up to this many alive members that no
    /// member plane and no sweep of `auxiliary::best_aux` separates take
    /// the best plane through an edge that cuts nothing, if there is one
    /// ([`TRIAL_EDGES`]).
    pub trial_edges: usize,
}

/// The largest group inside a lookahead trial that looks for a plane
/// through an edge that cuts nothing (`auxiliary::pivot_uncut`) when the
/// greedy rule's sweeps find none ([`Look::trial_edges`]).
///
/// A trial stands for the subtree the option will get, but the subtree
/// is built with the lookahead, whose edge planes ([`PIVOTS`]) separate
/// many small groups that the trial's greedy rule cuts: the trial
/// overcounts those options whose subgroups the edge planes would
/// separate, and picks others. With the edge plane in the trials' small
/// groups the estimate is closer (`fpt build`, the nine shared models
/// without rocker-arm, splittings and CPU s of the nine builds against
/// 2,475 in 25.4 s): up to 16 members 2,467 in 32.3 s; 24, 2,418 in
/// 32.6 s; 32, 2,408 in 36.1 s (2,418 in 33.1 s only when the sweeps
/// find nothing); **48, when they find nothing, 2,351 in 38.2 s**; 64
/// whenever it beats them, 2,339 in 75.2 s; 48 in models of more than
/// [`TRIAL_EDGES_MODEL`] polygons (kept), 2,348 in 36.3 s; rocker-arm
/// 8,919 → 8,520 in 9.2 → 13.1 s. Taken greedily outside the
/// trials, such planes made the tree worse (see [`PIVOTS`]).
pub const TRIAL_EDGES: usize = 48;

/// Auxiliary planes that cut members tried (`auxiliary::cutting_aux`).
pub const CUTTING: usize = 2;

/// Planes through an edge of the group (`pivot.rs`) tried, of each of
/// the two kinds (cutting nothing, cutting few), in groups of up to
/// `pivot::GROUP` members.
///
/// Such a plane is not a polygon's, and a group that no member plane
/// separates often has one that cuts nothing through a chain of its
/// edges. As the greedy choice (the best of them with the axis and
/// normal sweeps in `auxiliary::best_aux`, in every group of up to 64)
/// they made the tree worse (`fpt build`, the nine shared models without
/// rocker-arm: 3,238 → 3,430 splittings), as lookahead options they
/// make it better, judged by the pieces their subtrees add: one of each
/// kind in groups of up to 64, 2,803; up to 512, 2,554; **two of each**,
/// 2,516; one cutting nothing only, 2,941 (up to 64) and 2,811 (up to
/// 512); one cutting few only, 2,975 (up to 64).
pub const PIVOTS: usize = 2;

/// The weight of a cut against imbalance in the alternatives' score (the
/// greedy one is `feudal::SPLIT_WEIGHT`, 8). Neither weight is best on
/// every model (`fpt bench-build`: rabbit 227 splits at 8, 204 at 4;
/// socket 133 and 175), and the trial of the subtree, not the score,
/// decides: so the lookahead tries the best planes of both.
pub const ALT_WEIGHT: u32 = 4;

/// Models of up to this many input polygons look ahead the widest
/// ([`SMALL`]): the curved shared models (450–2,300 polygons) build in
/// seconds with it.
pub const SMALL_MODEL: usize = 4096;

/// Models of up to this many input polygons (and more than
/// [`SMALL_MODEL`]) look ahead in larger groups, with fewer candidates
/// ([`MEDIUM`]): fandisk (5,750 triangles) goes from 1,690 splittings
/// without a lookahead to 1,409, its build from about 1.2 to 5 CPU seconds.
pub const MEDIUM_MODEL: usize = 8192;

/// The lookahead of models of up to [`SMALL_MODEL`] polygons: twelve
/// greedy candidates and two alternatives (`fpt build` on the shared
/// models: four candidates and no alternatives 1,973 splittings, eight
/// 1,882 at about 1.5× the CPU time, twelve 1,829 at 1.3× more; sixteen
/// gain nothing more).
pub const SMALL: Look = Look {
    group: 512,
    candidates: 12,
    alternatives: 2,
    wide: true,
    trial_edges: TRIAL_EDGES,
};

/// The lookahead of models of up to [`MEDIUM_MODEL`] polygons: groups of
/// up to 1,024 members, four greedy candidates and two alternatives.
///
/// In such a model a third of the splittings were made in groups of more
/// than 512 members (fandisk: 473 of 1,483), which the small models'
/// limit leaves greedy. `fpt build` on fandisk, splittings and CPU
/// seconds against 1,483 in 4.0 s with groups of 512 and no alternatives:
/// groups of 1,024 1,435 in 4.4 s, with two alternatives **1,409 in 4.8
/// s**, with four 1,407 in 5.5 s, with six candidates 1,405 in 6.1 s,
/// with twelve 1,391 in 9.2 s; groups of 2,048 1,423–1,427 in 5.9–6.3 s,
/// of 8,192 (every group) 1,448 with two candidates in 5.2 s, 1,406 with
/// twelve in about 25 s (wall). The small models keep groups of 512:
/// 1,024 there gives 1,855 splittings on the six small curved and CAD
/// models against 1,829 (suzanne 545 → 563, violin_case 646 → 654).
pub const MEDIUM: Look = Look {
    group: 1024,
    candidates: 4,
    alternatives: 2,
    wide: true,
    trial_edges: TRIAL_EDGES,
};

/// The lookahead of larger models: only groups of up to 64 members.
/// rocker-arm (20,088 triangles) has thousands of split groups, and
/// looking ahead in those of up to 512 members took its build from 6 s to
/// 85 s; up to 64, to about 12 s (eight candidates there: 24 s). Nor
/// do its larger groups try a [`dominant`] member's plane: on rocker-arm
/// that took 8.9 to 19.2 CPU s for 9 more splittings.
pub const LARGE: Look = Look {
    group: 64,
    candidates: 4,
    alternatives: 0,
    wide: false,
    trial_edges: TRIAL_EDGES,
};

/// Models of up to this many input polygons do not try edge planes in
/// their trials ([`Look::trial_edges`]): the small inputs gained nothing
/// from them and some lost (`fpt build`, splittings: the scene vise, 321
/// polygons, 267 → 304; rabbit, 678, 187 → 192; shuttle, 449, 67 → 65;
/// the scene house, 723, 642 → 642 in a different tree), where every
/// larger shared model gained (see [`TRIAL_EDGES`]).
pub const TRIAL_EDGES_MODEL: usize = 768;

/// The lookahead of a build of `n` input polygons.
pub fn look_for(n: usize) -> Look {
    let look = if n <= SMALL_MODEL {
        SMALL
    } else if n <= MEDIUM_MODEL {
        MEDIUM
    } else {
        LARGE
    };
    if n <= TRIAL_EDGES_MODEL {
        Look {
            trial_edges: 0,
            ..look
        }
    } else {
        look
    }
}

/// A member is dominant when its area is at least this fraction (1/N) of
/// its group's ([`dominant`]).
pub const DOMINANT: f64 = 50.0;

/// The member of the largest area, when that is at least 1/[`DOMINANT`]
/// of the group's area: its plane is tried as one more option.
///
/// A large polygon under or beside many others (the ground slab of
/// `bench_city`, a vise's base plate) is cut by nearly every plane that
/// divides the group, once per piece: the greedy rule splits the city's
/// 1,800 polygons by vertical planes between the lots and cuts the
/// ground's top face into 250 pieces, where its own plane, taken first,
/// cuts only the 172 sides of the annexes sunk into it (4 each, which no
/// order avoids) and leaves every building above it separable without a
/// cut. Its score (172 cuts) ranks that plane last, so it is only found
/// by trying it: in groups too large to look ahead (and not inside a
/// trial) of models up to [`MEDIUM_MODEL`] polygons ([`Look::wide`]) the
/// greedy choice and this plane are both tried ([`cheapest`]), and in the
/// lookahead it is one more option. A curved mesh, whose facets are all
/// small, rarely has a dominant member.
pub fn dominant(t: &Table, ctx: &Ctx) -> Option<usize> {
    let mut total = 0.0;
    let mut best: Option<(f64, usize)> = None;
    for q in (0..t.len()).filter(|&q| t.is_alive(q)) {
        let a = area(&ctx.polys[t.ids[q] as usize].verts);
        total += a;
        if best.is_none_or(|(x, _)| a > x) {
            best = Some((a, q));
        }
    }
    best.filter(|&(a, _)| a * DOMINANT >= total).map(|(_, q)| q)
}

/// Whether the choice in the group of `t` looks ahead: small enough groups,
/// and not inside a trial (trials are greedy).
pub fn applies(t: &Table, ctx: &Ctx) -> bool {
    !ctx.in_trial() && t.alive_count() <= ctx.look.group
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
    // Nothing adds fewer than none: a later option could not win.
    while i < options.len() && best.0 > 0 {
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
