//! The BSP tree baseline, as the paper compared against: each splitting
//! plane is the best of five random candidate polygons, by fewest splits.
//! Every node is a switch node (connecting nodes without levels).

use super::table::Rel;
use super::Ctx;
use crate::tree::{Connecting, Switch};

/// Candidates tried per node.
pub const CANDIDATES: usize = 5;

/// Builds the BSP subtree of the polygons `ids`.
pub fn build_bsp(ids: Vec<u32>, ctx: &mut Ctx) -> Connecting {
    if ids.is_empty() {
        return Connecting::default();
    }
    let n = ids.len();
    // Distinct random candidates: a partial Fisher–Yates over the indices.
    let mut idx: Vec<usize> = (0..n).collect();
    let k = CANDIDATES.min(n);
    for i in 0..k {
        let j = i + ctx.rng.below(n - i);
        idx.swap(i, j);
    }
    let mut best: Option<(usize, usize, Vec<Rel>)> = None;
    for &c in &idx[..k] {
        let cid = ids[c];
        let rels: Vec<Rel> = (0..n)
            .map(|p| {
                if p == c {
                    Rel::Same
                } else {
                    ctx.relation(ids[p], cid)
                }
            })
            .collect();
        let cuts = rels.iter().filter(|&&r| r == Rel::Cut).count();
        if best.as_ref().is_none_or(|b| cuts < b.1) {
            best = Some((c, cuts, rels));
        }
    }
    let Some((c, _, rels)) = best else {
        return Connecting::default();
    };
    let plane = ctx.polys[ids[c] as usize].plane;
    let (mut on, mut front, mut back) = (Vec::new(), Vec::new(), Vec::new());
    for (p, rel) in rels.into_iter().enumerate() {
        let pid = ids[p];
        match rel {
            Rel::Front => front.push(pid),
            Rel::Back => back.push(pid),
            Rel::Same | Rel::Opposite | Rel::Unknown => on.push(pid),
            Rel::Cut => {
                let (f, b) = ctx.split(pid, &plane);
                front.extend(f);
                back.extend(b);
            }
        }
    }
    ctx.placed(on.iter().copied());
    Connecting {
        levels: Vec::new(),
        switch: Some(Box::new(Switch {
            plane,
            on,
            front: build_bsp(front, ctx),
            back: build_bsp(back, ctx),
        })),
    }
}
