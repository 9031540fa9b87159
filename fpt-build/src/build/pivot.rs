//! Separating planes through a mesh edge ("pivot" planes).
//!
//! A plane that cuts nothing and crosses a connected patch of a triangle
//! mesh meets the patch only along edges and at vertices: in general
//! position (no four vertices coplanar) it must contain at least one edge
//! of the patch, or it cannot get from one side of the patch to the other
//! without crossing a facet. The axis and normal sweeps of
//! `auxiliary.rs` only find such a plane when its normal happens to be
//! one of their directions; here every plane through an edge is tried at
//! once. The planes containing the line of edge `a → b` form a pencil,
//! one per angle `θ` about that line; seen along the line, each member is
//! an arc of angles (the directions from the line to its vertices), and
//! the plane at `θ` cuts the member exactly when `θ` (mod π) falls strictly
//! inside its arc. A sweep over the sorted arcs finds the angles no arc
//! covers: each is a plane through the edge that cuts nothing, and the
//! most balanced one with members on both sides is the edge's candidate.
//! A member the line pierces covers every angle, and the edge has none.
//!
//! The same sweep counts the arcs over every angle, so it also gives the
//! plane through the edge that cuts fewest members (weighed against
//! balance by the caller's score).
//!
//! Both kinds are options of the lookahead only (`lookahead::PIVOTS`):
//! taken greedily, whenever they beat the member planes, they made the
//! trees worse (see `lookahead.rs`). The arcs ignore the classification
//! tolerance, so the candidates are only proposals:
//! `auxiliary::pivot_aux` checks the best of them with the exact
//! classification. Cost: one pass over the members per distinct edge,
//! hence the limit on the group ([`GROUP`]).

use super::table::Table;
use super::Ctx;
use crate::geom::Plane;
use glam::DVec3;
use std::f64::consts::PI;

/// Groups of up to this many members try the planes through their edges
/// (the lookahead's groups in models of up to 4,096 polygons; fandisk's
/// groups of up to 1,024, one plane of each kind, gave 1,039 splittings
/// against 1,021 with this limit).
pub const GROUP: usize = 512;

/// The angles of one edge's pencil that are scored, at most (each costs a
/// pass over the members).
const GAPS: usize = 8;

/// A candidate plane with its score.
pub type Scored = ((u32, u32), Plane);

/// The arc of a member seen along the line: its start angle in `[0, π)`,
/// its length (0 when the member's plane contains the line) and the angle
/// of its middle (for its side).
#[derive(Clone, Copy)]
struct Arc {
    start: f64,
    len: f64,
    mid: f64,
}

/// The distinct edges of the members `alive`, each once, in an order that
/// does not depend on the members' order.
fn edges(t: &Table, alive: &[usize], ctx: &Ctx) -> Vec<(DVec3, DVec3)> {
    let key = |v: DVec3| v.to_array().map(f64::to_bits);
    let mut out: Vec<([u64; 3], [u64; 3])> = Vec::new();
    for &q in alive {
        let v = &ctx.polys[t.ids[q] as usize].verts;
        for (k, &a) in v.iter().enumerate() {
            let (ka, kb) = (key(a), key(v[(k + 1) % v.len()]));
            out.push(if ka < kb { (ka, kb) } else { (kb, ka) });
        }
    }
    out.sort_unstable();
    out.dedup();
    let back = |k: [u64; 3]| DVec3::from_array(k.map(f64::from_bits));
    out.into_iter().map(|(a, b)| (back(a), back(b))).collect()
}

/// The arc of `verts` about the line through `a` with unit direction
/// across `e1`, `e2`; `None` when every plane through the line cuts it,
/// `Some(None)` when it lies on the line.
fn arc(verts: &[DVec3], a: DVec3, e1: DVec3, e2: DVec3, tol: f64) -> Option<Option<Arc>> {
    let mut first = None;
    let (mut lo, mut hi) = (0.0f64, 0.0f64);
    for &x in verts {
        let p = x - a;
        let (u, v) = (p.dot(e1), p.dot(e2));
        if u * u + v * v <= tol * tol {
            continue;
        }
        let phi = v.atan2(u);
        match first {
            None => first = Some(phi),
            Some(f) => {
                let mut d = phi - f;
                if d > PI {
                    d -= 2.0 * PI;
                } else if d <= -PI {
                    d += 2.0 * PI;
                }
                lo = lo.min(d);
                hi = hi.max(d);
            }
        }
    }
    let Some(f) = first else {
        return Some(None);
    };
    if hi - lo >= PI {
        return None;
    }
    Some(Some(Arc {
        start: (f + lo).rem_euclid(PI),
        len: hi - lo,
        mid: f + 0.5 * (lo + hi),
    }))
}

/// The pencil of planes through the line of an edge, seen along it: the
/// point `a` and the plane's axes `e1`, `e2` across the line, the arcs of
/// the members, and how many members every plane of the pencil cuts.
struct Pencil {
    a: DVec3,
    e1: DVec3,
    e2: DVec3,
    always: u32,
}

impl Pencil {
    /// The plane at angle `theta`.
    fn plane(&self, theta: f64) -> Plane {
        let normal = -theta.sin() * self.e1 + theta.cos() * self.e2;
        Plane {
            normal,
            d: -normal.dot(self.a),
        }
    }
}

/// The pencil of the edge `a → b` with the members' arcs in `arcs`
/// (those the line pierces counted in `always`).
fn pencil(
    a: DVec3,
    b: DVec3,
    t: &Table,
    alive: &[usize],
    ctx: &Ctx,
    arcs: &mut Vec<Arc>,
) -> Option<Pencil> {
    let tol = ctx.tol.0;
    let axis = (b - a).try_normalize()?;
    let e1 = axis.any_orthonormal_vector();
    let e2 = axis.cross(e1);
    arcs.clear();
    let mut always = 0;
    for &q in alive {
        match arc(&ctx.polys[t.ids[q] as usize].verts, a, e1, e2, tol) {
            Some(Some(r)) => arcs.push(r),
            Some(None) => {}
            None => always += 1,
        }
    }
    Some(Pencil { a, e1, e2, always })
}

/// The angles to try in `[0, π)`, each with the number of arcs that cover
/// it: every arc end shared by arcs on both sides (a plane through an edge
/// between two members), and the middle of every stretch between ends.
fn stretches(arcs: &[Arc]) -> Vec<(f64, u32)> {
    // (angle, +1 for a start, −1 for an end): an arc covers the open
    // interval between its ends; one that wraps past π in two.
    let mut ev: Vec<(f64, i32)> = Vec::with_capacity(2 * arcs.len() + 4);
    for r in arcs.iter().filter(|r| r.len > 0.0) {
        let end = r.start + r.len;
        if end > PI {
            ev.extend([(r.start, 1), (PI, -1), (0.0, 1), (end - PI, -1)]);
        } else {
            ev.extend([(r.start, 1), (end, -1)]);
        }
    }
    // Ends before starts at one angle: the angle itself is uncovered.
    ev.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let mut out = Vec::new();
    let mut cov = 0i32;
    let mut at = 0.0f64;
    let mut i = 0;
    while i < ev.len() {
        let x = ev[i].0;
        if x > at {
            out.push((0.5 * (at + x), cov as u32));
        }
        while i < ev.len() && ev[i].0 == x && ev[i].1 < 0 {
            cov -= 1;
            i += 1;
        }
        out.push((x, cov as u32));
        while i < ev.len() && ev[i].0 == x {
            cov += 1;
            i += 1;
        }
        at = x;
    }
    if at < PI {
        out.push((0.5 * (at + PI), cov as u32));
    }
    out
}

/// The members in front of, behind and cut by the plane at `theta`.
fn sides(arcs: &[Arc], theta: f64, always: u32) -> [u32; 3] {
    let [mut f, mut b, mut c] = [0, 0, always];
    let t = theta.rem_euclid(PI);
    for r in arcs {
        let inside = r.len > 0.0 && {
            let s = (t - r.start).rem_euclid(PI);
            s > 0.0 && s < r.len
        };
        if inside {
            c += 1;
            continue;
        }
        let s = (r.mid - theta).sin();
        if r.len == 0.0 && s.abs() < 1e-12 {
            continue;
        }
        if s > 0.0 {
            f += 1;
        } else {
            b += 1;
        }
    }
    [f, b, c]
}

/// The candidates of one kind through each distinct edge of a group.
#[derive(Default)]
pub struct Candidates {
    /// The best plane through each edge that cuts nothing, by the score.
    pub uncut: Vec<Scored>,
    /// The best plane through each edge among the [`GAPS`] angles that
    /// cut fewest, by the score.
    pub cutting: Vec<Scored>,
    /// The distinct edges (each placed every member: the relations
    /// counted, the same at any scale whatever rounding does to the arcs).
    pub edges: usize,
}

/// The best of `angles` by `score(f, b, c)` (by the arcs) with members on
/// both sides, cutting nothing if `uncut`.
fn best_angle(
    arcs: &[Arc],
    p: &Pencil,
    angles: impl Iterator<Item = f64>,
    uncut: bool,
    score: &impl Fn(u32, u32, u32) -> (u32, u32),
) -> Option<Scored> {
    let mut best: Option<((u32, u32), f64)> = None;
    for theta in angles {
        let [f, b, c] = sides(arcs, theta, p.always);
        if f == 0 || b == 0 || (uncut && c > 0) {
            continue;
        }
        let s = score(f, b, c);
        if best.is_none_or(|(x, _)| s < x) {
            best = Some((s, theta));
        }
    }
    best.map(|(s, theta)| (s, p.plane(theta)))
}

/// For each distinct edge of the members `alive`, the best plane through
/// it by `score(f, b, c)` (by the arcs) with members on both sides, of
/// each kind: among the planes that cut nothing (none when a member lies
/// across the edge's line), and, if `cutting`, among the [`GAPS`] angles
/// that cut fewest. One pass: the edges are found, and each edge's arcs
/// built and swept, once for both kinds.
pub fn candidates(
    t: &Table,
    alive: &[usize],
    ctx: &Ctx,
    score: &impl Fn(u32, u32, u32) -> (u32, u32),
    cutting: bool,
) -> Candidates {
    let mut arcs = Vec::with_capacity(alive.len());
    let edges = edges(t, alive, ctx);
    let mut out = Candidates {
        edges: edges.len(),
        ..Candidates::default()
    };
    for (a, b) in edges {
        let Some(p) = pencil(a, b, t, alive, ctx, &mut arcs) else {
            continue;
        };
        let mut st = stretches(&arcs);
        if p.always == 0 {
            let gaps = st.iter().filter(|s| s.1 == 0).take(GAPS).map(|s| s.0);
            out.uncut.extend(best_angle(&arcs, &p, gaps, true, score));
        }
        if !cutting {
            continue;
        }
        st.sort_by(|x, y| x.1.cmp(&y.1).then(x.0.total_cmp(&y.0)));
        let fewest = st.iter().take(GAPS).map(|s| s.0);
        out.cutting
            .extend(best_angle(&arcs, &p, fewest, false, score));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-9;

    /// The arc of `verts` about the z axis.
    fn z_arc(verts: &[[f64; 3]]) -> Option<Option<Arc>> {
        let v: Vec<DVec3> = verts.iter().map(|&p| DVec3::from_array(p)).collect();
        arc(&v, DVec3::ZERO, DVec3::X, DVec3::Y, TOL)
    }

    #[test]
    fn a_member_on_the_line_has_an_empty_arc_and_a_pierced_one_none() {
        // A triangle with an edge on the axis: its plane contains the line.
        let r = z_arc(&[[0., 0., 0.], [0., 0., 1.], [1., 1., 0.5]])
            .unwrap()
            .unwrap();
        assert_eq!(r.len, 0.0);
        assert!((r.start - PI / 4.0).abs() < 1e-12);
        // A triangle around the axis: every plane through it cuts it.
        assert!(z_arc(&[[1., 0., 0.], [-1., 1., 0.], [-1., -1., 0.]]).is_none());
        // On the axis only.
        assert!(z_arc(&[[0., 0., 0.], [0., 0., 1.]]).unwrap().is_none());
    }

    #[test]
    fn an_arc_past_pi_wraps() {
        // Directions at 170° and 200°: the arc starts at 170° mod 180°.
        let d = |deg: f64| [deg.to_radians().cos(), deg.to_radians().sin(), 0.];
        let r = z_arc(&[d(170.), d(200.), [0., 0., 1.]]).unwrap().unwrap();
        assert!((r.start - 170f64.to_radians()).abs() < 1e-12);
        assert!((r.len - 30f64.to_radians()).abs() < 1e-12);
        // The plane at 5° cuts it (inside the wrapped arc), at 40° not.
        let [f, b, c] = sides(&[r], 5f64.to_radians(), 0);
        assert_eq!((f, b, c), (0, 0, 1));
        let [f, b, c] = sides(&[r], 40f64.to_radians(), 0);
        assert_eq!(f + b, 1);
        assert_eq!(c, 0);
    }

    #[test]
    fn touching_arcs_leave_a_gap_at_their_common_end() {
        let arcs = [
            Arc {
                start: 0.2,
                len: 0.3,
                mid: 0.35,
            },
            Arc {
                start: 0.5,
                len: 0.4,
                mid: 0.7,
            },
        ];
        let st = stretches(&arcs);
        assert!(st.contains(&(0.5, 0)));
        // Inside either arc the stretch is covered once.
        assert!(st.iter().any(|&(t, c)| t > 0.2 && t < 0.5 && c == 1));
        // The plane at the common end has one arc on each side.
        let [f, b, c] = sides(&arcs, 0.5, 0);
        assert_eq!((f, b, c), (1, 1, 0));
    }
}
