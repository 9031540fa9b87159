//! Auxiliary splitting planes: when no polygon's plane separates a group,
//! an axis-aligned plane through vertices of the group often does.
//!
//! The paper splits only by polygon planes. On tessellated CAD parts that is
//! costly: a countersunk hole is a cylinder of facets under a cone of facets,
//! every facet's plane cuts facets of the other surface, and the hole costs
//! dozens of splits — yet the horizontal plane through the rim between them
//! cuts nothing. A switch node does not need a polygon in its plane (its
//! `O_k` bunch is then empty): it is a separating plane like any other, and
//! the walk treats it the same way. So when the best polygon plane would
//! split, the builder also scores axis-aligned planes through the group's
//! vertex coordinates (all of them, or evenly spaced samples in large
//! groups) by the same rule, and takes the better one. Every candidate
//! tested counts its classifications as one-way relations.

use super::table::{Rel, Table};
use super::Ctx;
use crate::geom::Plane;
use glam::DVec3;

/// Candidate planes per axis, at most.
const PER_AXIS: usize = 16;

/// A chosen auxiliary plane and the relation of every member to it.
pub struct AuxPlane {
    /// The plane.
    pub plane: Plane,
    /// Relation of each member (by local index; `Unknown` for dead ones).
    pub rels: Vec<Rel>,
    /// Its score, comparable with a polygon plane's.
    pub score: (u32, u32),
}

/// The best axis-aligned plane for the group, scored by `score(f, b, c)`.
pub fn best_aux(
    t: &Table,
    ctx: &mut Ctx,
    score: impl Fn(u32, u32, u32) -> (u32, u32),
) -> Option<AuxPlane> {
    let alive: Vec<usize> = (0..t.len()).filter(|&q| t.is_alive(q)).collect();
    if alive.len() < 2 {
        return None;
    }
    let mut best: Option<AuxPlane> = None;
    for normal in [DVec3::X, DVec3::Y, DVec3::Z] {
        let mut coords: Vec<f64> = alive
            .iter()
            .flat_map(|&q| {
                ctx.polys[t.ids[q] as usize]
                    .verts
                    .iter()
                    .map(move |v| v.dot(normal))
            })
            .collect();
        coords.sort_by(f64::total_cmp);
        coords.dedup_by(|a, b| (*a - *b).abs() <= ctx.tol.0);
        // Planes through the outermost coordinates separate nothing.
        if coords.len() < 3 {
            continue;
        }
        let inner = &coords[1..coords.len() - 1];
        let step = inner.len().div_ceil(PER_AXIS).max(1);
        for &c in inner.iter().step_by(step) {
            let plane = Plane { normal, d: -c };
            let mut rels = vec![Rel::Unknown; t.len()];
            let (mut f, mut b, mut cut) = (0u32, 0u32, 0u32);
            for &q in &alive {
                let r = ctx.relation_to_plane(t.ids[q], &plane);
                match r {
                    Rel::Front => f += 1,
                    Rel::Back => b += 1,
                    Rel::Cut => cut += 1,
                    _ => {}
                }
                rels[q] = r;
            }
            // Only separating planes: one that cuts polygons slices the
            // group by an arbitrary coordinate, which on organic shapes
            // multiplies splits; and it must put something on each side.
            if cut != 0 || f == 0 || b == 0 {
                continue;
            }
            let s = score(f, b, cut);
            if best.as_ref().is_none_or(|x| s < x.score) {
                best = Some(AuxPlane {
                    plane,
                    rels,
                    score: s,
                });
            }
        }
    }
    best
}
