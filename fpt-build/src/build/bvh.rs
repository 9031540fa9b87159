//! A bounding-volume hierarchy over the members of a group, that classifies
//! whole clusters of polygons against a plane at once.
//!
//! A row of the one-way priority table only needs its counts (how many
//! members lie in front of the row's plane, behind it, or are cut by it).
//! A box whose every corner is beyond the tolerance on one side holds only
//! polygons on that side, so its members are counted in one step; only the
//! boxes the plane passes through are opened. On a tessellated surface a
//! plane crosses about √n of n facets' boxes, so a row costs about √n
//! instead of n classifications and the whole table about n^1.5.
//!
//! Exactness: a box is decided only when its nearest corner is beyond the
//! tolerance by [`MARGIN`], far more than the rounding of either distance
//! (coordinates are normalised into a unit box), so every vertex inside
//! gets the same answer from [`crate::geom::Plane::side_of`]. Everything
//! else is classified polygon by polygon with the very test the table used.

use crate::geom::{Plane, Polygon, Relation, Tolerance};
use glam::DVec3;

/// How far beyond the tolerance a box corner must lie for the box to be
/// decided whole: covers the rounding of the distances (about 1e-16 for
/// coordinates of size 1).
const MARGIN: f64 = 1e-12;

/// Members per leaf, at most.
const LEAF: usize = 6;

/// No member found cut ([`Bvh::counts_witness`], [`Bvh::probe`]).
pub const NO_WITNESS: u32 = u32::MAX;

/// What a [`Bvh::probe`] found.
#[derive(Clone, Copy, Debug)]
pub struct Probe {
    /// Lower bounds on the front, back and cut counts.
    pub counts: [u32; 3],
    /// Alive members left undecided.
    pub undecided: u32,
    /// A member the plane cuts, or [`NO_WITNESS`].
    pub witness: u32,
}

#[derive(Clone, Copy, Debug)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Alive members below.
    alive: u32,
    /// Leaf: `first..first + count` in `order`; inner: `count == 0` and the
    /// children are `first` and `first + 1`.
    first: u32,
    count: u32,
    parent: u32,
}

/// The hierarchy of one group; members are local indices `0..n`.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
    leaf_of: Vec<u32>,
    /// The members' vertices, copied in `order`: member `order[k]` has
    /// `verts[vstart[k]..vstart[k + 1]]`. Counting a row classifies the
    /// members of every leaf the plane passes through; reading them from one
    /// array in leaf order, instead of through each polygon's own vertex
    /// allocation, is most of a count's time saved (cache misses). Linear
    /// memory: one copy of each member's vertices per group.
    verts: Vec<DVec3>,
    vstart: Vec<u32>,
}

/// The range of `n · x + d` over the box `lo..hi`.
fn box_range(plane: &Plane, lo: DVec3, hi: DVec3) -> (f64, f64) {
    let (mut min, mut max) = (plane.d, plane.d);
    for (n, (l, h)) in plane
        .normal
        .to_array()
        .into_iter()
        .zip(lo.to_array().into_iter().zip(hi.to_array()))
    {
        let (a, b) = (n * l, n * h);
        min += a.min(b);
        max += a.max(b);
    }
    (min, max)
}

impl Bvh {
    /// Builds the hierarchy of the polygons `polys[ids[i]]`.
    pub fn new(ids: &[u32], polys: &[Polygon]) -> Bvh {
        let n = ids.len();
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * n.div_ceil(LEAF) + 1),
            order: (0..n as u32).collect(),
            leaf_of: vec![0; n],
            verts: Vec::new(),
            vstart: Vec::new(),
        };
        if n == 0 {
            return bvh;
        }
        let bounds: Vec<(DVec3, DVec3)> = ids
            .iter()
            .map(|&id| {
                let v = &polys[id as usize].verts;
                let lo = v.iter().fold(DVec3::INFINITY, |a, &b| a.min(b));
                let hi = v.iter().fold(DVec3::NEG_INFINITY, |a, &b| a.max(b));
                (lo, hi)
            })
            .collect();
        bvh.nodes.push(Node {
            lo: DVec3::ZERO,
            hi: DVec3::ZERO,
            alive: n as u32,
            first: 0,
            count: n as u32,
            parent: u32::MAX,
        });
        // Top-down, median split on the widest axis of the centres.
        let mut stack = vec![0usize];
        while let Some(k) = stack.pop() {
            let (first, count) = (bvh.nodes[k].first as usize, bvh.nodes[k].count as usize);
            let slice = &mut bvh.order[first..first + count];
            let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            let (mut clo, mut chi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            for &i in slice.iter() {
                let (a, b) = bounds[i as usize];
                lo = lo.min(a);
                hi = hi.max(b);
                let c = (a + b) * 0.5;
                clo = clo.min(c);
                chi = chi.max(c);
            }
            bvh.nodes[k].lo = lo;
            bvh.nodes[k].hi = hi;
            if count <= LEAF {
                for &i in slice.iter() {
                    bvh.leaf_of[i as usize] = k as u32;
                }
                continue;
            }
            let axis = (chi - clo).max_position();
            let key = |i: &u32| {
                let (a, b) = bounds[*i as usize];
                a[axis] + b[axis]
            };
            let mid = count / 2;
            slice.select_nth_unstable_by(mid, |x, y| key(x).total_cmp(&key(y)));
            let left = bvh.nodes.len();
            for (f, c) in [(first, mid), (first + mid, count - mid)] {
                bvh.nodes.push(Node {
                    lo: DVec3::ZERO,
                    hi: DVec3::ZERO,
                    alive: c as u32,
                    first: f as u32,
                    count: c as u32,
                    parent: k as u32,
                });
            }
            bvh.nodes[k].first = left as u32;
            bvh.nodes[k].count = 0;
            stack.push(left);
            stack.push(left + 1);
        }
        bvh.vstart.reserve(n + 1);
        bvh.vstart.push(0);
        for &i in &bvh.order {
            bvh.verts
                .extend_from_slice(&polys[ids[i as usize] as usize].verts);
            bvh.vstart.push(bvh.verts.len() as u32);
        }
        bvh
    }

    /// Takes member `i` out of the alive counts.
    pub fn remove(&mut self, i: usize) {
        let mut k = self.leaf_of[i];
        while k != u32::MAX {
            let node = &mut self.nodes[k as usize];
            node.alive -= 1;
            k = node.parent;
        }
    }

    /// Visits the alive members whose boxes `plane` may not decide whole:
    /// calls `whole(side)` with `alive` count for boxes wholly in front
    /// (`true`) or behind, and `each(i, verts)` for the members of the
    /// other leaves, with their vertices.
    fn visit(
        &self,
        plane: &Plane,
        tol: Tolerance,
        mut whole: impl FnMut(bool, u32),
        mut each: impl FnMut(usize, &[DVec3]),
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let lim = tol.0 + MARGIN;
        let mut stack = Vec::with_capacity(64);
        stack.push(0u32);
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k as usize];
            if node.alive == 0 {
                continue;
            }
            let (min, max) = box_range(plane, node.lo, node.hi);
            if min > lim {
                whole(true, node.alive);
            } else if max < -lim {
                whole(false, node.alive);
            } else if node.count == 0 {
                stack.push(node.first);
                stack.push(node.first + 1);
            } else {
                let f = node.first as usize;
                for k in f..f + node.count as usize {
                    let v = &self.verts[self.vstart[k] as usize..self.vstart[k + 1] as usize];
                    each(self.order[k] as usize, v);
                }
            }
        }
    }

    /// Front, back and cut counts of the alive members other than `skip`
    /// against `plane` (coplanar ones count in none).
    pub fn counts(&self, plane: &Plane, skip: usize, alive: &[bool], tol: Tolerance) -> [u32; 3] {
        self.counts_witness(plane, skip, alive, tol).0
    }

    /// [`Bvh::counts`], with a member the plane cuts if any ([`NO_WITNESS`]
    /// otherwise): a witness that the row is neither absolute nor
    /// separating for as long as that member stays alive.
    pub fn counts_witness(
        &self,
        plane: &Plane,
        skip: usize,
        alive: &[bool],
        tol: Tolerance,
    ) -> ([u32; 3], u32) {
        let mut c = [0u32; 3];
        let mut leaf = [0u32; 3];
        let mut witness = NO_WITNESS;
        self.visit(
            plane,
            tol,
            |front, n| c[usize::from(!front)] += n,
            |i, verts| {
                if i == skip || !alive[i] {
                    return;
                }
                match plane.relation(verts, tol) {
                    Relation::Front => leaf[0] += 1,
                    Relation::Back => leaf[1] += 1,
                    Relation::Cut => {
                        leaf[2] += 1;
                        witness = witness.min(i as u32);
                    }
                    Relation::Coplanar => {}
                }
            },
        );
        ([c[0] + leaf[0], c[1] + leaf[1], leaf[2]], witness)
    }

    /// Classifies the alive members other than `skip` of `leaf` against
    /// `plane` into `found`'s counts, noting a cut one as its witness;
    /// returns how many members it looked at.
    fn classify_leaf(
        &self,
        leaf: &Node,
        plane: &Plane,
        skip: usize,
        alive: &[bool],
        tol: Tolerance,
        found: &mut Probe,
    ) -> usize {
        let f = leaf.first as usize;
        for k in f..f + leaf.count as usize {
            let i = self.order[k] as usize;
            if i == skip || !alive[i] {
                continue;
            }
            let v = &self.verts[self.vstart[k] as usize..self.vstart[k + 1] as usize];
            match plane.relation(v, tol) {
                Relation::Front => found.counts[0] += 1,
                Relation::Back => found.counts[1] += 1,
                Relation::Cut => {
                    found.counts[2] += 1;
                    found.witness = found.witness.min(i as u32);
                }
                Relation::Coplanar => {}
            }
        }
        leaf.count as usize
    }

    /// Lower bounds on the front, back and cut counts of the alive members
    /// other than `skip` against `plane`, found by opening at most about
    /// `budget` boxes (largest first) and classifying the members of the
    /// leaves opened, with the number of alive members left undecided (0:
    /// the counts are exact, as [`Bvh::counts`] gives them) and a member
    /// found cut, if any ([`NO_WITNESS`] otherwise).
    ///
    /// The leaves of the members `seeds` are opened first: a row's own
    /// leaf holds its neighbours on the surface, and on a saddle-shaped
    /// patch the plane of a facet cuts some of those, which a probe from
    /// the root rarely reaches (in a large group 48 boxes end far above
    /// the leaves); the leaf of the row's last witness holds one it cut.
    /// Every member counted is counted by the same test as in
    /// [`Bvh::counts`], so each true count is at least its bound and at most
    /// its bound plus the undecided.
    pub fn probe(
        &self,
        plane: &Plane,
        skip: usize,
        alive: &[bool],
        tol: Tolerance,
        budget: usize,
        seeds: &[u32],
    ) -> Probe {
        let mut found = Probe {
            counts: [0; 3],
            undecided: 0,
            witness: NO_WITNESS,
        };
        if self.nodes.is_empty() {
            return found;
        }
        let lim = tol.0 + MARGIN;
        let mut spent = 0;
        // Seed leaves classified already: skipped when the walk reaches
        // them. A leaf the plane does not decide whole lies in boxes it
        // does not decide either (each box holds its children's), so the
        // walk opens every box down to it and counts none of its members
        // twice; a leaf decided whole is left to the walk.
        let mut opened = [u32::MAX; 2];
        for (slot, &s) in seeds.iter().take(opened.len()).enumerate() {
            let Some(&k) = self.leaf_of.get(s as usize) else {
                continue;
            };
            let leaf = &self.nodes[k as usize];
            let (min, max) = box_range(plane, leaf.lo, leaf.hi);
            if leaf.alive == 0 || min > lim || max < -lim || opened.contains(&k) {
                continue;
            }
            opened[slot] = k;
            spent += self.classify_leaf(leaf, plane, skip, alive, tol, &mut found);
        }
        // Largest undecided box first: each step decides as many members
        // as it can, so the undecided remainder falls fastest.
        let mut heap = std::collections::BinaryHeap::with_capacity(2 * budget + 2);
        heap.push((self.nodes[0].alive, 0u32));
        while spent < budget {
            let Some((_, k)) = heap.pop() else {
                break;
            };
            spent += 1;
            let node = &self.nodes[k as usize];
            if node.alive == 0 || opened.contains(&k) {
                continue;
            }
            let (min, max) = box_range(plane, node.lo, node.hi);
            if min > lim {
                found.counts[0] += node.alive;
            } else if max < -lim {
                found.counts[1] += node.alive;
            } else if node.count == 0 {
                for child in [node.first, node.first + 1] {
                    heap.push((self.nodes[child as usize].alive, child));
                }
            } else {
                spent += self.classify_leaf(node, plane, skip, alive, tol, &mut found);
            }
        }
        // `skip` may sit in an undecided box: it is not one of the others,
        // but counting it as undecided only loosens the bounds. So do the
        // seed leaves still in the heap.
        found.undecided = heap
            .iter()
            .filter(|&&(_, k)| !opened.contains(&k))
            .map(|&(a, _)| a)
            .sum();
        found
    }

    /// Lower bounds as [`Bvh::probe`] gives them, found depth first:
    /// boxes the plane passes through are opened down to their leaves, so
    /// the members it cuts (which lie in those leaves) are found early. A
    /// row whose score is mostly its cuts is shown unable to win by a few
    /// dozen leaves, where a count opens every leaf along the plane.
    pub fn probe_deep(
        &self,
        plane: &Plane,
        skip: usize,
        alive: &[bool],
        tol: Tolerance,
        budget: usize,
    ) -> Probe {
        let mut found = Probe {
            counts: [0; 3],
            undecided: 0,
            witness: NO_WITNESS,
        };
        let mut stack = Vec::with_capacity(64);
        if !self.nodes.is_empty() {
            stack.push(0u32);
        }
        let lim = tol.0 + MARGIN;
        let mut spent = 0;
        while spent < budget {
            let Some(k) = stack.pop() else {
                break;
            };
            spent += 1;
            let node = &self.nodes[k as usize];
            if node.alive == 0 {
                continue;
            }
            let (min, max) = box_range(plane, node.lo, node.hi);
            if min > lim {
                found.counts[0] += node.alive;
            } else if max < -lim {
                found.counts[1] += node.alive;
            } else if node.count == 0 {
                stack.push(node.first);
                stack.push(node.first + 1);
            } else {
                spent += self.classify_leaf(node, plane, skip, alive, tol, &mut found);
            }
        }
        found.undecided = stack.iter().map(|&k| self.nodes[k as usize].alive).sum();
        found
    }

    /// The alive members other than `skip` that lie in `plane`, in
    /// ascending order.
    pub fn coplanar(
        &self,
        plane: &Plane,
        skip: usize,
        alive: &[bool],
        tol: Tolerance,
    ) -> Vec<usize> {
        let mut v = Vec::new();
        self.visit(
            plane,
            tol,
            |_, _| {},
            |i, verts| {
                if i != skip && alive[i] && plane.relation(verts, tol) == Relation::Coplanar {
                    v.push(i);
                }
            },
        );
        v.sort_unstable();
        v
    }
}
