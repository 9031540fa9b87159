//! Builder tests: the tree's defining invariants hold for every method, and
//! the static tree does not depend on scale, position or input order.

use super::*;
use crate::geom::{area, Relation};
use crate::tree::Level;

/// The six outward faces of an axis-aligned box.
pub(crate) fn cuboid(lo: DVec3, hi: DVec3, source0: u32) -> Vec<Polygon> {
    let c = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let (a, b) = (lo, hi);
    let faces = [
        [
            c(a.x, a.y, a.z),
            c(a.x, b.y, a.z),
            c(b.x, b.y, a.z),
            c(b.x, a.y, a.z),
        ], // -z
        [
            c(a.x, a.y, b.z),
            c(b.x, a.y, b.z),
            c(b.x, b.y, b.z),
            c(a.x, b.y, b.z),
        ], // +z
        [
            c(a.x, a.y, a.z),
            c(b.x, a.y, a.z),
            c(b.x, a.y, b.z),
            c(a.x, a.y, b.z),
        ], // -y
        [
            c(a.x, b.y, a.z),
            c(a.x, b.y, b.z),
            c(b.x, b.y, b.z),
            c(b.x, b.y, a.z),
        ], // +y
        [
            c(a.x, a.y, a.z),
            c(a.x, a.y, b.z),
            c(a.x, b.y, b.z),
            c(a.x, b.y, a.z),
        ], // -x
        [
            c(b.x, a.y, a.z),
            c(b.x, b.y, a.z),
            c(b.x, b.y, b.z),
            c(b.x, a.y, b.z),
        ], // +x
    ];
    faces
        .iter()
        .enumerate()
        .map(|(i, f)| Polygon::new(f.to_vec(), source0 + i as u32, [200, 200, 200]).unwrap())
        .collect()
}

/// Three thin boards in cyclic overlap (each above the next at one end).
pub(crate) fn cyclic_boards() -> Vec<Polygon> {
    let mut v = cuboid(DVec3::new(0.0, 0.0, 0.0), DVec3::new(6.0, 1.0, 0.2), 0);
    v.extend(cuboid(
        DVec3::new(0.0, 0.0, 0.3),
        DVec3::new(1.0, 6.0, 0.5),
        6,
    ));
    v.extend(cuboid(
        DVec3::new(-0.5, 4.0, -0.4),
        DVec3::new(6.0, 5.0, -0.1),
        12,
    ));
    // The third board tilts up so that it passes above the first one.
    for p in v.iter_mut().skip(12) {
        for q in &mut p.verts {
            q.z += 0.12 * q.x;
        }
        p.plane = Plane::newell(&p.verts).unwrap();
    }
    v
}

fn interpenetrating() -> Vec<Polygon> {
    let mut v = cuboid(DVec3::ZERO, DVec3::splat(2.0), 0);
    v.extend(cuboid(DVec3::splat(1.0), DVec3::splat(3.0), 6));
    v.extend(cuboid(
        DVec3::new(-1.0, 0.5, 0.5),
        DVec3::new(4.0, 1.5, 1.5),
        12,
    ));
    v
}

fn all_ids(c: &Connecting) -> Vec<u32> {
    let mut v = Vec::new();
    c.for_each_polygon(&mut |i| v.push(i));
    v
}

/// Checks absolute priorities and switch partitions over the whole tree.
fn check_invariants(tree: &FpTree, c: &Connecting, tol: Tolerance) {
    let rel = |p: u32, q_plane: &Plane| q_plane.relation(&tree.polygons[p as usize].verts, tol);
    for (j, level) in c.levels.iter().enumerate() {
        // The group when level j was found: this level and everything inside.
        let inner = Connecting {
            levels: c.levels[j..].to_vec(),
            switch: c.switch.clone(),
        };
        let group = all_ids(&inner);
        for (bunch, forbidden) in [
            (&level.front, Relation::Front),
            (&level.back, Relation::Back),
        ] {
            for &q in bunch {
                let plane = tree.polygons[q as usize].plane;
                for &p in &group {
                    let r = rel(p, &plane);
                    assert!(
                        p == q || (r != forbidden && r != Relation::Cut),
                        "polygon {p} is {r:?} of {q} in a bunch that forbids it"
                    );
                }
            }
        }
    }
    if let Some(s) = &c.switch {
        for &p in &s.on {
            assert_eq!(rel(p, &s.plane), Relation::Coplanar);
        }
        for p in all_ids(&s.front) {
            assert!(matches!(
                rel(p, &s.plane),
                Relation::Front | Relation::Coplanar
            ));
        }
        for p in all_ids(&s.back) {
            assert!(matches!(
                rel(p, &s.plane),
                Relation::Back | Relation::Coplanar
            ));
        }
        check_invariants(tree, &s.front, tol);
        check_invariants(tree, &s.back, tol);
    }
}

fn check_tree(tree: &FpTree, input: &[Polygon]) {
    let ids = all_ids(&tree.root);
    let mut sorted = ids.clone();
    sorted.sort();
    assert_eq!(sorted, (0..tree.polygons.len() as u32).collect::<Vec<_>>());
    // Area of each source face is preserved by splitting.
    let mut before = std::collections::HashMap::new();
    for p in input {
        *before.entry(p.source).or_insert(0.0) += area(&p.verts);
    }
    let mut after = std::collections::HashMap::new();
    for p in &tree.polygons {
        *after.entry(p.source).or_insert(0.0) += area(&p.verts);
    }
    for (s, a) in before {
        let b = after.get(&s).copied().unwrap_or(0.0);
        assert!((a - b).abs() < 1e-9 * a.max(1.0), "source {s}: {a} vs {b}");
    }
    let (lo, hi) = bounds(input);
    check_invariants(tree, &tree.root, Tolerance(1e-6 * (hi - lo).length()));
    assert_eq!(tree.stats.output_polygons, tree.polygons.len());
    assert_eq!(tree.stats.connecting_nodes, 2 * tree.stats.switch_nodes + 1);
}

fn build_all(input: &[Polygon]) -> Vec<FpTree> {
    [Method::Static, Method::Dynamic, Method::Bsp]
        .into_iter()
        .map(|m| build(input.to_vec(), true, m, DEFAULT_SEED, &mut NoProgress))
        .collect()
}

#[test]
fn convex_box_is_one_level() {
    let input = cuboid(DVec3::ZERO, DVec3::ONE, 0);
    let t = build(input.clone(), true, Method::Static, 1, &mut NoProgress);
    assert_eq!(t.root.levels.len(), 1);
    assert_eq!(t.root.levels[0].front.len(), 6);
    assert!(t.root.switch.is_none());
    assert_eq!(t.stats.relations, 30);
    check_tree(&t, &input);
}

#[test]
fn cyclic_boards_need_a_split_and_keep_invariants() {
    let input = cyclic_boards();
    for t in build_all(&input) {
        check_tree(&t, &input);
    }
    // Polygon planes alone cannot order the cycle without a split; the
    // static builder's planes through edges of the group (`pivot.rs`)
    // may, and never need more.
    let bsp = build(input.clone(), true, Method::Bsp, 1, &mut NoProgress);
    assert!(
        bsp.stats.splittings >= 1,
        "cyclic overlap cannot be ordered by polygon planes without a split"
    );
    let st = build(input, true, Method::Static, 1, &mut NoProgress);
    assert!(st.stats.splittings <= bsp.stats.splittings);
}

#[test]
fn interpenetrating_boxes_keep_invariants() {
    let input = interpenetrating();
    for t in build_all(&input) {
        check_tree(&t, &input);
        assert!(t.stats.splittings > 0);
    }
}

#[test]
fn bsp_has_only_switch_nodes() {
    let t = build(interpenetrating(), true, Method::Bsp, 3, &mut NoProgress);
    fn no_levels(c: &Connecting) -> bool {
        c.levels.is_empty()
            && c.switch
                .as_ref()
                .is_none_or(|s| no_levels(&s.front) && no_levels(&s.back))
    }
    assert!(no_levels(&t.root));
}

/// The shape of a tree: bunch sizes and nesting, without coordinates.
fn shape(c: &Connecting) -> String {
    let lv: Vec<String> = c
        .levels
        .iter()
        .map(|Level { front, back }| format!("{}/{}", front.len(), back.len()))
        .collect();
    match &c.switch {
        None => format!("[{}]", lv.join(",")),
        Some(s) => format!(
            "[{}]S{}({} | {})",
            lv.join(","),
            s.on.len(),
            shape(&s.front),
            shape(&s.back)
        ),
    }
}

fn transformed(input: &[Polygon], scale: f64, offset: DVec3) -> Vec<Polygon> {
    input
        .iter()
        .map(|p| {
            let verts = p.verts.iter().map(|&v| v * scale + offset).collect();
            Polygon::new(verts, p.source, p.color).unwrap()
        })
        .collect()
}

#[test]
fn structure_survives_scaling_and_moving() {
    let mut input = interpenetrating();
    input.extend(transformed(
        &cyclic_boards(),
        0.5,
        DVec3::new(5.0, 0.0, 0.0),
    ));
    for method in [Method::Static, Method::Dynamic, Method::Bsp] {
        let base = build(input.clone(), true, method, 9, &mut NoProgress);
        for (s, o) in [(1e-4, DVec3::ZERO), (1e3, DVec3::splat(1e5))] {
            let t = build(transformed(&input, s, o), true, method, 9, &mut NoProgress);
            assert_eq!(shape(&t.root), shape(&base.root), "{method:?} at scale {s}");
            assert_eq!(t.stats.splittings, base.stats.splittings);
            assert_eq!(t.stats.relations, base.stats.relations);
        }
    }
}

#[test]
fn static_tree_ignores_input_order() {
    let input = interpenetrating();
    let mut rev = input.clone();
    rev.reverse();
    let a = build(input, true, Method::Static, 1, &mut NoProgress);
    let b = build(rev, true, Method::Static, 1, &mut NoProgress);
    assert_eq!(shape(&a.root), shape(&b.root));
    assert_eq!(a.stats.splittings, b.stats.splittings);
}

#[test]
fn dynamic_computes_fewer_relations_than_static() {
    let mut input = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let lo = DVec3::new(i as f64 * 2.0, j as f64 * 2.0, 0.0);
            input.extend(cuboid(lo, lo + DVec3::ONE, (input.len()) as u32));
        }
    }
    let st = build(input.clone(), true, Method::Static, 1, &mut NoProgress);
    let dy = build(input.clone(), true, Method::Dynamic, 1, &mut NoProgress);
    check_tree(&dy, &input);
    assert!(
        dy.stats.relations < st.stats.relations,
        "{} vs {}",
        dy.stats.relations,
        st.stats.relations
    );
}

#[test]
fn same_seed_same_tree() {
    let input = interpenetrating();
    for m in [Method::Dynamic, Method::Bsp] {
        let a = build(input.clone(), true, m, 5, &mut NoProgress);
        let b = build(input.clone(), true, m, 5, &mut NoProgress);
        assert_eq!(a.root, b.root);
        assert_eq!(a.polygons, b.polygons);
    }
}

#[test]
fn empty_input_gives_empty_tree() {
    let t = build(Vec::new(), true, Method::Static, 1, &mut NoProgress);
    assert!(t.polygons.is_empty());
    assert_eq!(t.stats.connecting_nodes, 1);
}

#[test]
fn pieces_keep_exact_input_vertices() {
    let input = transformed(&interpenetrating(), 1.37, DVec3::new(1e3, -7.1, 0.3));
    let inputs: Vec<DVec3> = input.iter().flat_map(|p| p.verts.clone()).collect();
    for t in build_all(&input) {
        assert!(t.stats.splittings > 0);
        for p in &t.polygons {
            for v in &p.verts {
                let near = inputs.iter().find(|u| (**u - *v).length() < 1e-9);
                if let Some(u) = near {
                    assert_eq!(u, v, "a vertex shared with the input moved by rounding");
                }
            }
        }
    }
}

#[test]
fn auxiliary_plane_separates_torus_halves() {
    let input = crate::scenes::torus(24, 12).polygons;
    let t = build(input.clone(), true, Method::Static, 1, &mut NoProgress);
    check_tree(&t, &input);
    fn aux_switches(c: &Connecting) -> usize {
        c.switch.as_ref().map_or(0, |s| {
            usize::from(s.on.is_empty()) + aux_switches(&s.front) + aux_switches(&s.back)
        })
    }
    assert!(aux_switches(&t.root) > 0, "no switch on an auxiliary plane");
    // BSP uses polygon planes only.
    let b = build(input, true, Method::Bsp, 1, &mut NoProgress);
    assert_eq!(aux_switches(&b.root), 0);
}

/// The tree, and so its file, is the same byte for byte on one thread and
/// on two (static and dynamic builds, with and without lookahead, large
/// groups split between the threads), and its counters too; the two-thread
/// builds did hand each kind of work to the other thread (else this would
/// compare two one-thread builds), the one-thread builds none.
#[test]
fn two_threads_build_the_one_thread_tree() {
    use crate::serialize::serialize;
    let scenes = [
        crate::scenes::vise(),
        crate::scenes::house(),
        crate::scenes::torus(80, 40),
    ];
    let mut handed = [0; 3];
    for scene in &scenes {
        for method in [Method::Static, Method::Dynamic] {
            let run = |n: usize| {
                let threads = Threads::new(n);
                let tree = build_in(
                    scene.polygons.clone(),
                    scene.closed,
                    method,
                    DEFAULT_SEED,
                    &mut NoProgress,
                    &threads,
                );
                let bytes = serialize(&tree, &Default::default()).expect("serializes");
                let kinds = [Work::Subtree, Work::Trial, Work::Rows].map(|w| threads.handed(w));
                (tree, bytes, kinds)
            };
            let (one, one_bytes, one_handed) = run(1);
            let (two, two_bytes, two_handed) = run(2);
            let what = format!("{} {method:?}", scene.name);
            assert_eq!(one_handed, [0; 3], "{what}");
            assert!(one_bytes == two_bytes, "{what}: the files differ");
            assert_eq!(one.stats.splittings, two.stats.splittings, "{what}");
            assert_eq!(one.stats.relations, two.stats.relations, "{what}");
            for (h, k) in handed.iter_mut().zip(two_handed) {
                *h += k;
            }
        }
    }
    assert!(handed.iter().all(|&k| k > 0), "handed {handed:?}");
}
