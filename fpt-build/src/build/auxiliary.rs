//! Auxiliary splitting planes: when no polygon's plane separates a group,
//! a plane through vertices of the group often does.
//!
//! The paper splits only by polygon planes. On tessellated models that is
//! costly: a countersunk hole is a cylinder of facets under a cone of facets,
//! every facet's plane cuts facets of the other surface, and the hole costs
//! dozens of splits — yet the horizontal plane through the rim between them
//! cuts nothing. A switch node does not need a polygon in its plane (its
//! `O_k` bunch is then empty): it is a separating plane like any other, and
//! the walk treats it the same way. So when the best polygon plane would
//! split, the builder also looks for planes that cut nothing, scored by the
//! same rule, and takes the best one if it beats the polygon plane.
//!
//! For a direction `u`, every member covers an interval of `u · x`; sorted
//! by their low ends, the intervals leave a gap wherever a low end is not
//! below every high end before it, and a plane `u · x = c` in a gap cuts
//! nothing. One sweep finds every gap of a direction and keeps the most
//! balanced. Directions tried:
//!
//! - the three axes, in every group (CAD parts: the plane of a countersunk
//!   hole's rim);
//! - in groups of up to [`EDGE_GROUP`] members, each member's normal (its
//!   plane moved past its neighbours) and, for each edge, the normal of the
//!   plane through the edge perpendicular to the member: on a saddle-shaped
//!   patch of a curved mesh, where every facet's plane cuts a neighbour,
//!   such a plane often runs along edges between the facets;
//! - in groups of up to [`PAIR_GROUP`], the cross products of edges of two
//!   members: with the normals, the directions in which two disjoint convex
//!   polygons can always be separated (separating axis theorem), so two
//!   members that do not intersect are never split against each other.
//!
//! The larger the group, the rarer such a plane and the dearer the search,
//! hence the limits (`fpt bench-build`: the limits of 64 and 12 find as many
//! planes on the shared models as 256 do, at a fraction of the time).
//! The best few gaps are checked with the exact classification through the
//! group's bounding-volume hierarchy; every candidate direction counts its
//! classifications as one-way relations.

use super::pivot;
use super::table::{Rel, Table};
use super::Ctx;
use crate::geom::Plane;
use glam::DVec3;
use std::cmp::Ordering;

/// Groups of up to this many members also try member normals and edge
/// normals.
pub const EDGE_GROUP: usize = 64;

/// Groups of up to this many members also try cross products of edges.
pub const PAIR_GROUP: usize = 12;

/// The best candidates checked by the exact classification, at most.
const VERIFIED: usize = 8;

/// A chosen auxiliary plane and the relation of every member to it.
#[derive(Clone)]
pub struct AuxPlane {
    /// The plane.
    pub plane: Plane,
    /// Relation of each member (by local index; `Unknown` for dead ones).
    pub rels: Vec<Rel>,
    /// Its score, comparable with a polygon plane's.
    pub score: (u32, u32),
}

/// The candidate normals of a group: the axes always; in groups of up to
/// [`EDGE_GROUP`] members also every member's normal and, for each edge of a
/// member, the normal perpendicular to the edge in the member's plane; in
/// groups of up to [`PAIR_GROUP`] also the cross products of edges of two
/// members (with the others, the directions in which two disjoint convex
/// polygons can always be separated).
fn directions(t: &Table, alive: &[usize], ctx: &Ctx) -> Vec<DVec3> {
    let mut out = vec![DVec3::X, DVec3::Y, DVec3::Z];
    if alive.len() > EDGE_GROUP {
        return out;
    }
    let mut edges = Vec::new();
    for &q in alive {
        let p = &ctx.polys[t.ids[q] as usize];
        out.push(p.plane.normal);
        for (k, &a) in p.verts.iter().enumerate() {
            let e = p.verts[(k + 1) % p.verts.len()] - a;
            out.extend((e.cross(p.plane.normal)).try_normalize());
            edges.push((q, e));
        }
    }
    if alive.len() <= PAIR_GROUP {
        for (i, &(p, e)) in edges.iter().enumerate() {
            for &(q, f) in &edges[i + 1..] {
                if p != q {
                    out.extend(e.cross(f).try_normalize());
                }
            }
        }
    }
    out
}

/// The interval `[min, max]` of `u · v` over the vertices `verts`.
fn interval(u: DVec3, verts: &[DVec3]) -> (f64, f64) {
    verts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            let d = u.dot(*x);
            (lo.min(d), hi.max(d))
        })
}

/// The offsets along unit `u` at which a plane `u · x = c` cuts no member
/// and has members on both sides, as the best `(balance, c)` by `|f − b|`:
/// the members' intervals along `u`, sorted by their low ends, leave a gap
/// wherever a low end is not below the highest high end before it.
fn best_gap(u: DVec3, t: &Table, alive: &[usize], ctx: &Ctx) -> Option<(u32, f64)> {
    let tol = ctx.tol.0;
    let mut iv: Vec<(f64, f64)> = alive
        .iter()
        .map(|&q| interval(u, &ctx.polys[t.ids[q] as usize].verts))
        .collect();
    iv.sort_by(|a, b| a.0.total_cmp(&b.0));
    let m = iv.len();
    let mut best: Option<(u32, f64)> = None;
    let mut top = f64::NEG_INFINITY;
    for k in 1..m {
        top = top.max(iv[k - 1].1);
        let lo = iv[k].0;
        if lo < top - tol {
            continue;
        }
        let c = if lo > top { 0.5 * (lo + top) } else { top };
        let balance = (k as u32).abs_diff((m - k) as u32);
        if best.is_none_or(|(b, _)| balance < b) {
            best = Some((balance, c));
        }
    }
    best
}

/// Orders planes independently of the members' order.
fn plane_cmp(a: &Plane, b: &Plane) -> Ordering {
    a.normal
        .to_array()
        .iter()
        .chain([a.d].iter())
        .zip(b.normal.to_array().iter().chain([b.d].iter()))
        .map(|(x, y)| x.total_cmp(y))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}

/// The best auxiliary plane for the group that cuts nothing and leaves
/// members on both sides, scored by `score(f, b, c)`.
pub fn best_aux(
    t: &Table,
    ctx: &mut Ctx,
    score: impl Fn(u32, u32, u32) -> (u32, u32),
) -> Option<AuxPlane> {
    let alive: Vec<usize> = (0..t.len()).filter(|&q| t.is_alive(q)).collect();
    if alive.len() < 2 {
        return None;
    }
    // The best gap in each direction, best first; the first that the
    // exact classification confirms is taken (the gaps are found on
    // projected intervals, whose rounding may differ).
    let mut candidates: Vec<(u32, Plane)> = directions(t, &alive, ctx)
        .into_iter()
        .filter_map(|u| {
            best_gap(u, t, &alive, ctx).map(|(balance, c)| (balance, Plane { normal: u, d: -c }))
        })
        .collect();
    ctx.relations += (candidates.len() * alive.len()) as u64;
    candidates.sort_by(|a, b| a.0.cmp(&b.0).then_with(|| plane_cmp(&a.1, &b.1)));
    let mut best: Option<((u32, u32), Plane)> = None;
    for (_, plane) in candidates.into_iter().take(VERIFIED) {
        let [f, b, cut] = t.plane_counts(&plane, ctx);
        // Only separating planes: one that cuts polygons slices the
        // group by an arbitrary coordinate, which on organic shapes
        // multiplies splits; and it must put something on each side.
        if cut != 0 || f == 0 || b == 0 {
            continue;
        }
        let s = score(f, b, cut);
        let better = best
            .as_ref()
            .is_none_or(|(bs, bp)| s < *bs || (s == *bs && plane_cmp(&plane, bp).is_lt()));
        if better {
            best = Some((s, plane));
        }
    }
    let (score, plane) = best?;
    let mut rels = vec![Rel::Unknown; t.len()];
    for &q in &alive {
        rels[q] = ctx.classify(t.ids[q], &plane);
    }
    Some(AuxPlane { plane, rels, score })
}

/// The offset along unit `u` where a plane `u · x = c` has the best
/// `score(f, b, c)` among planes between two distinct interval ends, with
/// members on both sides: the counts of a plane are those of the intervals
/// wholly above it, wholly below it and across it.
fn best_cutting(
    u: DVec3,
    t: &Table,
    alive: &[usize],
    ctx: &Ctx,
    score: &impl Fn(u32, u32, u32) -> (u32, u32),
) -> Option<((u32, u32), f64)> {
    let tol = ctx.tol.0;
    let (mut lo, mut hi): (Vec<f64>, Vec<f64>) = alive
        .iter()
        .map(|&q| interval(u, &ctx.polys[t.ids[q] as usize].verts))
        .unzip();
    lo.sort_by(f64::total_cmp);
    hi.sort_by(f64::total_cmp);
    let mut ends: Vec<f64> = lo.iter().chain(&hi).copied().collect();
    ends.sort_by(f64::total_cmp);
    let m = alive.len() as u32;
    let mut best: Option<((u32, u32), f64)> = None;
    for w in ends.windows(2) {
        if w[1] - w[0] <= 4.0 * tol {
            continue;
        }
        let c = 0.5 * (w[0] + w[1]);
        let front = (lo.len() - lo.partition_point(|&x| x <= c)) as u32;
        let back = hi.partition_point(|&x| x < c) as u32;
        if front == 0 || back == 0 {
            continue;
        }
        let s = score(front, back, m - front - back);
        if best.is_none_or(|(b, _)| s < b) {
            best = Some((s, c));
        }
    }
    best
}

/// The alive members of the group, when it is worth proposing `n > 0`
/// lookahead options in it ([`cutting_aux`], [`pivot_aux`]): at least
/// three (with two, each member's plane is already an option).
fn alive_members(t: &Table, n: usize) -> Option<Vec<usize>> {
    let alive: Vec<usize> = (0..t.len()).filter(|&q| t.is_alive(q)).collect();
    (alive.len() >= 3 && n > 0).then_some(alive)
}

/// Up to `n` auxiliary planes that cut members, the best by `score(f, b,
/// c)` first: candidates for the lookahead (`lookahead.rs`), which judges
/// them by the pieces their subtrees create rather than by their cuts.
pub fn cutting_aux(
    t: &Table,
    ctx: &mut Ctx,
    score: impl Fn(u32, u32, u32) -> (u32, u32),
    n: usize,
) -> Vec<AuxPlane> {
    let Some(alive) = alive_members(t, n) else {
        return Vec::new();
    };
    let candidates: Vec<((u32, u32), Plane)> = directions(t, &alive, ctx)
        .into_iter()
        .filter_map(|u| {
            best_cutting(u, t, &alive, ctx, &score).map(|(s, c)| (s, Plane { normal: u, d: -c }))
        })
        .collect();
    ctx.relations += (candidates.len() * alive.len()) as u64;
    verified(t, ctx, &alive, candidates, &score, false, n)
}

/// The best `n` of `candidates` (sorted best first) by their exact counts
/// and `score`, of the first [`VERIFIED`]: with members on both sides, and
/// cutting nothing if `uncut`, else something.
fn verified(
    t: &Table,
    ctx: &mut Ctx,
    alive: &[usize],
    mut candidates: Vec<((u32, u32), Plane)>,
    score: &impl Fn(u32, u32, u32) -> (u32, u32),
    uncut: bool,
    n: usize,
) -> Vec<AuxPlane> {
    candidates.sort_by(|a, b| a.0.cmp(&b.0).then_with(|| plane_cmp(&a.1, &b.1)));
    let mut out: Vec<((u32, u32), Plane)> = Vec::new();
    for (_, plane) in candidates.into_iter().take(VERIFIED) {
        let [f, b, cut] = t.plane_counts(&plane, ctx);
        if (cut == 0) != uncut || f == 0 || b == 0 {
            continue;
        }
        out.push((score(f, b, cut), plane));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0).then_with(|| plane_cmp(&a.1, &b.1)));
    out.truncate(n);
    out.into_iter()
        .map(|(score, plane)| {
            let mut rels = vec![Rel::Unknown; t.len()];
            for &q in alive {
                rels[q] = ctx.classify(t.ids[q], &plane);
            }
            AuxPlane { plane, rels, score }
        })
        .collect()
}

/// Up to `n` planes through edges of the group (`pivot.rs`) of each
/// kind, the best by `score(f, b, c)` first: those that cut nothing, then
/// those that cut some; candidates for the lookahead.
pub fn pivot_aux(
    t: &Table,
    ctx: &mut Ctx,
    score: impl Fn(u32, u32, u32) -> (u32, u32),
    n: usize,
) -> Vec<AuxPlane> {
    let Some(alive) = alive_members(t, n) else {
        return Vec::new();
    };
    let c = pivot::candidates(t, &alive, ctx, &score, true);
    ctx.relations += (c.edges * alive.len()) as u64;
    let mut out = verified(t, ctx, &alive, c.uncut, &score, true, n);
    out.extend(verified(t, ctx, &alive, c.cutting, &score, false, n));
    out
}

/// The best plane through an edge of the group that cuts nothing, by
/// `score(f, b, c)` (`pivot.rs`): what a lookahead trial takes when no
/// sweep of [`best_aux`] finds a plane that cuts nothing
/// (`lookahead::Look::trial_edges`).
pub fn pivot_uncut(
    t: &Table,
    ctx: &mut Ctx,
    score: impl Fn(u32, u32, u32) -> (u32, u32),
) -> Option<AuxPlane> {
    let alive = alive_members(t, 1)?;
    let c = pivot::candidates(t, &alive, ctx, &score, false);
    ctx.relations += (c.edges * alive.len()) as u64;
    verified(t, ctx, &alive, c.uncut, &score, true, 1).pop()
}
