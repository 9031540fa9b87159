//! The one-way priority table of a group of polygons.
//!
//! Row `q` holds the relation of every other polygon `p` of the group to the
//! plane of `q`, and the counts of its front, back and cut columns among the
//! polygons still in the group. Rows are computed on demand (dynamic
//! preprocessing computes them lazily, static all at once); every relation
//! actually computed is counted, as the paper counts its cost.

use super::Ctx;

/// A relation as stored in the table.
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

impl Rel {
    fn flipped(self) -> Rel {
        match self {
            Rel::Front => Rel::Back,
            Rel::Back => Rel::Front,
            Rel::Same => Rel::Opposite,
            Rel::Opposite => Rel::Same,
            r => r,
        }
    }
}

/// The table of one group; members are addressed by local index.
#[derive(Clone, Debug)]
pub struct Table {
    /// Local index → polygon id in [`Ctx::polys`].
    pub ids: Vec<u32>,
    m: usize,
    rel: Vec<Rel>,
    has_row: Vec<bool>,
    alive: Vec<bool>,
    /// Front, back and cut counts of each computed row among alive members.
    counts: Vec<[u32; 3]>,
    alive_count: usize,
}

impl Table {
    /// A table of `ids` with no row computed.
    pub fn new(ids: Vec<u32>) -> Table {
        let m = ids.len();
        Table {
            ids,
            m,
            rel: vec![Rel::Unknown; m * m],
            has_row: vec![false; m],
            alive: vec![true; m],
            counts: vec![[0; 3]; m],
            alive_count: m,
        }
    }

    /// Number of members.
    pub fn len(&self) -> usize {
        self.m
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

    /// Relation of `p` to the plane of `q`.
    pub fn rel(&self, q: usize, p: usize) -> Rel {
        self.rel[q * self.m + p]
    }

    /// Front, back and cut counts of row `q` among alive members.
    pub fn counts(&self, q: usize) -> [u32; 3] {
        self.counts[q]
    }

    /// Computes row `q` against the alive members. A polygon in the plane
    /// of an already computed row copies that row instead (the paper's
    /// shortcut for coplanar polygons: no relation computed).
    pub fn compute_row(&mut self, q: usize, ctx: &mut Ctx) {
        if self.has_row[q] {
            return;
        }
        let m = self.m;
        let twin = (0..m).find(|&p| {
            p != q
                && self.alive[p]
                && self.has_row[p]
                && matches!(self.rel(p, q), Rel::Same | Rel::Opposite)
        });
        if let Some(p) = twin {
            let flip = self.rel(p, q) == Rel::Opposite;
            for x in 0..m {
                self.rel[q * m + x] = if x == q {
                    Rel::Unknown
                } else if x == p {
                    // Coplanarity is symmetric, orientation included.
                    self.rel(p, q)
                } else if flip {
                    self.rel(p, x).flipped()
                } else {
                    self.rel(p, x)
                };
            }
            // Entries copied from p's row for members p never saw (pieces
            // made later) are unknown: compute those.
            for x in 0..m {
                if x != q && self.alive[x] && self.rel[q * m + x] == Rel::Unknown {
                    self.rel[q * m + x] = ctx.relation(self.ids[x], self.ids[q]);
                }
            }
        } else {
            let qid = self.ids[q];
            for p in 0..m {
                if p != q && self.alive[p] {
                    self.rel[q * m + p] = ctx.relation(self.ids[p], qid);
                }
            }
        }
        self.has_row[q] = true;
        self.recount(q);
    }

    fn recount(&mut self, q: usize) {
        let mut c = [0u32; 3];
        for p in 0..self.m {
            if p != q && self.alive[p] {
                let r = self.rel(q, p) as usize;
                if r < 3 {
                    c[r] += 1;
                }
            }
        }
        self.counts[q] = c;
    }

    /// Takes member `p` out of the group, updating the computed rows.
    pub fn remove(&mut self, p: usize) {
        if !self.alive[p] {
            return;
        }
        self.alive[p] = false;
        self.alive_count -= 1;
        for q in 0..self.m {
            if self.alive[q] && self.has_row[q] {
                let r = self.rel(q, p) as usize;
                if r < 3 {
                    self.counts[q][r] -= 1;
                }
            }
        }
    }

    /// The table of a subgroup: `members` (local indices of this table) and
    /// new `pieces` (polygon id, local index of the polygon it was split
    /// from). Rows known here stay known; entries that involve a piece are
    /// taken from its parent where the plane is the same, else computed.
    pub fn subtable(&self, members: &[usize], pieces: &[(u32, usize)], ctx: &mut Ctx) -> Table {
        let mut ids: Vec<u32> = members.iter().map(|&i| self.ids[i]).collect();
        ids.extend(pieces.iter().map(|&(id, _)| id));
        let mut t = Table::new(ids);
        let m = t.m;
        // Origin in this table of each new member: (old index, is piece).
        let origin: Vec<(usize, bool)> = members
            .iter()
            .map(|&i| (i, false))
            .chain(pieces.iter().map(|&(_, parent)| (parent, true)))
            .collect();
        for q in 0..m {
            let oq = origin[q].0;
            if !self.has_row[oq] {
                continue;
            }
            // A piece lies in its parent's plane: the parent's row is its row.
            for (p, &(op, p_piece)) in origin.iter().enumerate() {
                if p == q {
                    continue;
                }
                let r = if op == oq {
                    Rel::Same
                } else if !p_piece {
                    self.rel(oq, op)
                } else {
                    ctx.relation(t.ids[p], t.ids[q])
                };
                t.rel[q * m + p] = r;
            }
            t.has_row[q] = true;
        }
        for q in 0..m {
            if t.has_row[q] {
                t.recount(q);
            }
        }
        t
    }
}
