//! Helpers shared by the `format_*` tests: random hand-made trees, a
//! reference walk of the in-memory tree, and checks of a walk's output.
#![allow(dead_code)]

use fpt_nostd::order::{Order, View};
use fpt_nostd::reader::Tree;
use glam::DVec3;
use host_sim::geom::{Plane, Polygon};
use host_sim::tree::{Connecting, FpTree, Level, Method, Stats, Switch};

/// A small deterministic generator (xorshift64*), so that a failing seed
/// reproduces.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in `0..n` (n > 0).
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
    /// Uniform in `[-1, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    pub fn chance(&mut self, p: f64) -> bool {
        (self.unit() + 1.0) / 2.0 < p
    }
}

/// A random polygon with corners on a coarse grid (so that polygons share
/// vertices), scaled by `scale` and moved by `offset`.
fn random_polygon(rng: &mut Rng, scale: f64, offset: DVec3, source: u32) -> Polygon {
    loop {
        let mut g = || {
            DVec3::new(
                rng.below(9) as f64,
                rng.below(9) as f64,
                rng.below(9) as f64,
            ) - 4.0
        };
        let a = g();
        let (u, v) = (g() - a, g() - a);
        let verts = if rng.chance(0.5) {
            vec![a, a + u, a + v]
        } else {
            vec![a, a + u, a + u + v, a + v]
        };
        let verts: Vec<DVec3> = verts.into_iter().map(|p| p * scale + offset).collect();
        let color = [
            rng.below(256) as u8,
            rng.below(256) as u8,
            rng.below(256) as u8,
        ];
        if let Some(p) = Polygon::new(verts, source, color) {
            if host_sim::geom::area(&p.verts) > 1e-3 * scale * scale {
                return p;
            }
        }
    }
}

/// Takes up to `max` ids from the end of `pool`.
fn take(rng: &mut Rng, pool: &mut Vec<u32>, max: u64) -> Vec<u32> {
    let n = rng.below(max + 1).min(pool.len() as u64) as usize;
    pool.split_off(pool.len() - n)
}

fn random_connecting(
    rng: &mut Rng,
    pool: &mut Vec<u32>,
    polys: &[Polygon],
    depth: u32,
    bsp: bool,
) -> Connecting {
    let mut c = Connecting::default();
    if !bsp {
        for _ in 0..rng.below(3) {
            let front = take(rng, pool, 2);
            let back = take(rng, pool, 2);
            c.levels.push(Level { front, back });
        }
    }
    if depth < 5 && !pool.is_empty() && rng.chance(if bsp { 0.9 } else { 0.6 }) {
        let on = take(rng, pool, 2);
        // The plane of a polygon, as the builders do, or of a random one.
        let plane = match on.first() {
            Some(&id) => polys[id as usize].plane,
            None => polys[rng.below(polys.len() as u64) as usize].plane,
        };
        let front = random_connecting(rng, pool, polys, depth + 1, bsp);
        let back = random_connecting(rng, pool, polys, depth + 1, bsp);
        c.switch = Some(Box::new(Switch {
            plane,
            on,
            front,
            back,
        }));
    }
    c
}

/// A random tree of `n ≥ 1` polygons: the structure is arbitrary (not a
/// correct feudal tree), which is all the format and the walk care about.
/// `bsp`: every connecting node has no levels.
pub fn random_tree(
    seed: u64,
    n: usize,
    closed: bool,
    bsp: bool,
    scale: f64,
    offset: DVec3,
) -> FpTree {
    let mut rng = Rng::new(seed);
    let polygons: Vec<Polygon> = (0..n)
        .map(|i| random_polygon(&mut rng, scale, offset, i as u32))
        .collect();
    let mut pool: Vec<u32> = (0..n as u32).collect();
    // Shuffle, so that bunches hold scattered ids.
    for i in (1..pool.len()).rev() {
        pool.swap(i, rng.below(i as u64 + 1) as usize);
    }
    let mut root = random_connecting(&mut rng, &mut pool, &polygons, 1, bsp);
    // Whatever is left goes where it fits: a level, or a switch's O.
    if !pool.is_empty() {
        if bsp {
            let mut c = &mut root;
            while c.switch.is_some() {
                c = &mut c.switch.as_mut().unwrap().back;
            }
            let plane = polygons[pool[0] as usize].plane;
            c.switch = Some(Box::new(Switch {
                plane,
                on: std::mem::take(&mut pool),
                front: Connecting::default(),
                back: Connecting::default(),
            }));
        } else {
            root.levels.push(Level {
                front: std::mem::take(&mut pool),
                back: vec![],
            });
        }
    }
    let mut t = FpTree {
        polygons,
        closed,
        root,
        method: if bsp { Method::Bsp } else { Method::Static },
        stats: Stats::default(),
    };
    t.count_structure();
    t
}

/// A view in `f64` model coordinates, for the reference walk.
#[derive(Clone, Copy, Debug)]
pub enum RefView {
    Dir(DVec3),
    Eye(DVec3),
}

impl RefView {
    /// The value whose sign is the facing test: negative `n · dir`, or
    /// `n · eye + d`; positive means backward.
    pub fn facing(&self, p: &Plane) -> f64 {
        match *self {
            RefView::Dir(d) => -p.normal.dot(d),
            RefView::Eye(e) => p.distance(e),
        }
    }

    pub fn backward(&self, p: &Plane) -> bool {
        self.facing(p) > 0.0
    }

    /// The same view for the no_std walk of `tree`.
    pub fn to_view(self, tree: &Tree<'_>) -> View {
        match self {
            RefView::Dir(d) => View::parallel(d.to_array().map(|x| x as f32)),
            RefView::Eye(e) => View::perspective_f64(tree, e.to_array()),
        }
    }

    /// The smallest |facing value| over every plane of `t`: views closer to a
    /// tie than the rounding of the stored `f32` planes are ambiguous.
    pub fn margin(&self, t: &FpTree) -> f64 {
        let mut m = f64::INFINITY;
        for p in &t.polygons {
            m = m.min(self.facing(&p.plane).abs());
        }
        fn switches(c: &Connecting, f: &mut dyn FnMut(&Plane)) {
            if let Some(s) = &c.switch {
                f(&s.plane);
                switches(&s.front, f);
                switches(&s.back, f);
            }
        }
        switches(&t.root, &mut |p| m = m.min(self.facing(p).abs()));
        m
    }
}

/// The reference walk: the digest's pseudo-code, recursively, over the
/// in-memory tree, in tree ids; empty classes dropped.
pub fn reference_classes(t: &FpTree, v: &RefView) -> Vec<Vec<u32>> {
    fn visit(t: &FpTree, v: &RefView, c: &Connecting, out: &mut Vec<Vec<u32>>) {
        let back = |ids: &[u32]| -> Vec<u32> {
            ids.iter()
                .copied()
                .filter(|&i| v.backward(&t.polygons[i as usize].plane))
                .collect()
        };
        let fwd = |ids: &[u32]| -> Vec<u32> {
            if t.closed {
                vec![]
            } else {
                ids.iter()
                    .copied()
                    .filter(|&i| !v.backward(&t.polygons[i as usize].plane))
                    .collect()
            }
        };
        let mut push = |mut class: Vec<u32>, more: Vec<u32>| {
            class.extend(more);
            if !class.is_empty() {
                out.push(class);
            }
        };
        for l in &c.levels {
            push(back(&l.back), fwd(&l.front));
        }
        if let Some(s) = &c.switch {
            let (far, near) = if v.backward(&s.plane) {
                (&s.back, &s.front)
            } else {
                (&s.front, &s.back)
            };
            visit(t, v, far, out);
            let on = if t.closed { back(&s.on) } else { s.on.clone() };
            if !on.is_empty() {
                out.push(on);
            }
            visit(t, v, near, out);
        }
        for l in c.levels.iter().rev() {
            let mut class = back(&l.front);
            class.extend(fwd(&l.back));
            if !class.is_empty() {
                out.push(class);
            }
        }
    }
    let mut out = Vec::new();
    visit(t, v, &t.root, &mut out);
    out
}

/// The classes of the no_std walk, each mapped to tree ids through
/// `order` (file id → tree id).
pub fn nostd_classes(tree: &Tree<'_>, view: View, order: &[u32]) -> Vec<Vec<u32>> {
    Order::<1024>::new(tree, view)
        .expect("depth within 1024")
        .map(|c| c.map(|id| order[id as usize]).collect())
        .collect()
}

/// Sorts every class: ids within a class have no order.
pub fn normalized(mut classes: Vec<Vec<u32>>) -> Vec<Vec<u32>> {
    classes.iter_mut().for_each(|c| c.sort_unstable());
    classes
}

/// Walks `tree` for `view` and checks the contract: ids in range, each at
/// most once, every one exactly once for an open volume. Returns how many
/// were emitted.
pub fn check_walk(tree: &Tree<'_>, view: View) -> usize {
    let Ok(order) = Order::<1024>::new(tree, view) else {
        return 0;
    };
    let n = tree.polygon_count() as usize;
    let mut seen = vec![false; n];
    let mut emitted = 0;
    for class in order {
        let mut any = false;
        for id in class {
            assert!((id as usize) < n, "id {id} out of range {n}");
            assert!(!seen[id as usize], "id {id} emitted twice");
            seen[id as usize] = true;
            emitted += 1;
            any = true;
        }
        assert!(any, "empty class emitted");
    }
    if !tree.is_closed() {
        assert_eq!(emitted, n, "open volume: every polygon exactly once");
    }
    check_ranges(tree, view);
    emitted
}

/// The walk's ranges ([`Order::next_range`]) give the ids of its classes in
/// the same order, and so does any mix of ranges and classes.
fn check_ranges(tree: &Tree<'_>, view: View) {
    let walk = || Order::<1024>::new(tree, view).expect("walked above");
    let by_class: Vec<u32> = walk().flatten().collect();
    let mut order = walk();
    let mut by_range = Vec::new();
    while let Some(r) = order.next_range() {
        assert!(!r.is_empty(), "empty range");
        by_range.extend(r);
    }
    assert_eq!(by_range, by_class, "ranges against classes");
    // Alternate: one range, then the rest of its class as a class.
    let mut order = walk();
    let mut mixed = Vec::new();
    while let Some(r) = order.next_range() {
        mixed.extend(r);
        match order.next() {
            Some(rest) => mixed.extend(rest),
            None => break,
        }
    }
    assert_eq!(mixed, by_class, "ranges mixed with classes");
}

/// Touches every accessor of every polygon.
pub fn touch_all(tree: &Tree<'_>) {
    let mut acc = 0f64;
    for id in 0..tree.polygon_count() {
        let p = tree.polygon(id).expect("id in range");
        assert!(p.vertex_count() >= 3);
        acc += f64::from(p.plane().d) + f64::from(p.source()) + f64::from(p.color()[0]);
        for i in 0..p.vertex_count() {
            assert!(p.vertex_index(i) < tree.vertex_count());
            acc += f64::from(p.vertex(i)[0]) + p.vertex_model(i)[1];
            let _ = p.vertex_raw(i);
        }
        acc += p.vertices().map(|v| f64::from(v[2])).sum::<f64>();
    }
    std::hint::black_box(acc);
}

/// Some views for a model of size about `scale` around `centre`.
pub fn some_views(rng: &mut Rng, scale: f64, centre: DVec3, n: usize) -> Vec<RefView> {
    (0..n)
        .map(|i| {
            let d = DVec3::new(rng.unit(), rng.unit(), rng.unit());
            if i % 2 == 0 && d.length() > 1e-3 {
                RefView::Dir(d)
            } else {
                RefView::Eye(centre + d * scale * 8.0)
            }
        })
        .collect()
}
