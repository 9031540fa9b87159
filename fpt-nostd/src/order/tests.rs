extern crate std;

use std::vec::Vec;

use super::*;
use crate::format::FLAG_CLOSED;
use crate::test_util::{add_square, two_floors, Raw};

fn classes<const N: usize>(t: &Tree<'_>, v: View) -> Vec<Vec<u32>> {
    Order::<N>::new(t, v)
        .unwrap()
        .map(|c| c.collect())
        .collect()
}

const DOWN_Z: View = View::Parallel {
    dir: [0.0, 0.0, -1.0],
};
const UP_Z: View = View::Parallel {
    dir: [0.0, 0.0, 1.0],
};

#[test]
fn switch_puts_the_far_side_first() {
    let bytes = two_floors().bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    // Looking down: the switch plane faces the viewer, so the back group
    // (id 1, z = 0) is far.
    assert_eq!(classes::<2>(&t, DOWN_Z), [[1], [0]]);
    assert_eq!(classes::<2>(&t, UP_Z), [[0], [1]]);
    assert_eq!(
        classes::<2>(&t, View::perspective([0.5, 0.5, 10.0])),
        [[1], [0]]
    );
    assert_eq!(
        classes::<2>(&t, View::perspective([0.5, 0.5, -10.0])),
        [[0], [1]]
    );
    // Eye between the floors: the switch is backward (front group near).
    assert_eq!(
        classes::<2>(&t, View::perspective([0.5, 0.5, 0.75])),
        [[1], [0]]
    );
    // Eye exactly on the switch plane: a tie is forward, so G_f is far.
    assert_eq!(
        classes::<2>(&t, View::perspective([0.5, 0.5, 0.5])),
        [[0], [1]]
    );
    // Edge-on parallel view: also forward.
    assert_eq!(
        classes::<2>(&t, View::parallel([1.0, 0.0, 0.0])),
        [[0], [1]]
    );
}

#[test]
fn closed_volumes_cull_forward_faces() {
    let mut r = two_floors();
    r.flags = FLAG_CLOSED;
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    // Both squares face up: seen from below, both are culled.
    assert_eq!(classes::<2>(&t, DOWN_Z), [[1], [0]]);
    assert!(classes::<2>(&t, UP_Z).is_empty());
    // The eye between them sees only the lower one's front.
    assert_eq!(classes::<2>(&t, View::perspective([0.5, 0.5, 0.75])), [[1]]);
}

/// One connecting node, level 1: F_1 = {0: up at z=1, 1: down at z=0},
/// B_1 = {2: up at z=2}; no switch.
fn one_level(closed: bool) -> Raw {
    let mut r = Raw::empty();
    add_square(&mut r, 1.0, true, 0);
    add_square(&mut r, 0.0, false, 1);
    add_square(&mut r, 2.0, true, 2);
    r.bunches = std::vec![0, 2, 3];
    r.nodes = std::vec![[0, 1, NO_SWITCH]];
    r.flags = if closed { FLAG_CLOSED } else { 0 };
    r
}

#[test]
fn levels_follow_the_pseudo_code() {
    let bytes = one_level(false).bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    // Down: {backward of B_1} ∪ {forward of F_1}; up: {backward of F_1} ∪ {forward of B_1}.
    // Looking down: backward = 0 and 2 (they face +z), forward = 1.
    assert_eq!(classes::<1>(&t, DOWN_Z), [std::vec![2, 1], std::vec![0]]);
    assert_eq!(classes::<1>(&t, UP_Z), [std::vec![0], std::vec![1, 2]]);
    let bytes = one_level(true).bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert_eq!(classes::<1>(&t, DOWN_Z), [[2], [0]]);
    assert_eq!(classes::<1>(&t, UP_Z), [[1]]);
}

#[test]
fn on_plane_bunch_is_culled_per_face() {
    // Root: no levels, switch at z = 0 with O = {0 up, 1 down}.
    let mut r = Raw::empty();
    add_square(&mut r, 0.0, true, 0);
    add_square(&mut r, 0.0, false, 1);
    r.bunches = std::vec![0, 2];
    r.nodes = std::vec![[0, 0, 0], [1, 0, NO_SWITCH], [1, 0, NO_SWITCH]];
    r.switches = std::vec![[0.0, 0.0, 1.0, 0.0]];
    r.max_depth = 2;
    let open = r.bytes();
    r.flags = FLAG_CLOSED;
    let closed = r.bytes();
    let t = Tree::from_bytes(&open).unwrap();
    assert_eq!(classes::<2>(&t, DOWN_Z), [[0, 1]]);
    let t = Tree::from_bytes(&closed).unwrap();
    assert_eq!(classes::<2>(&t, DOWN_Z), [[0]]);
    assert_eq!(classes::<2>(&t, UP_Z), [[1]]);
}

#[test]
fn perspective_views_relative_and_absolute_agree() {
    let mut r = two_floors();
    r.origin = [1e5, -1e5, 1e5];
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    // Eye 0.25 above the switch plane (z = origin + 0.5): f32 model
    // coordinates near 1e5 cannot express this, the f64 and relative ones can.
    let rel = View::perspective_relative([0.5, 0.5, 0.75]);
    let abs = View::perspective_f64(&t, [1e5 + 0.5, -1e5 + 0.5, 1e5 + 0.75]);
    assert_eq!(rel, abs);
    assert_eq!(classes::<2>(&t, rel), [[1], [0]]);
    let below = View::perspective_f64(&t, [1e5 + 0.5, -1e5 + 0.5, 1e5 + 0.25]);
    assert_eq!(classes::<2>(&t, below), [[0], [1]]);
    // The f32 model-coordinate eye goes through the same one subtraction.
    let coarse = View::perspective([1e5, -1e5, 1e5 + 8.0]);
    assert_eq!(coarse.local(&t), LocalView::Eye([0.0, 0.0, 8.0]));
}

#[test]
fn stack_must_hold_the_depth() {
    let bytes = two_floors().bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert_eq!(
        Order::<1>::new(&t, DOWN_Z).unwrap_err(),
        OrderError::StackTooSmall {
            depth: 2,
            capacity: 1
        }
    );
    assert!(Order::<2>::new(&t, DOWN_Z).is_ok());
}

#[test]
fn for_each_visits_polygons_in_order() {
    let bytes = one_level(false).bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    let mut seen = Vec::new();
    for_each_polygon_back_to_front::<4>(&t, DOWN_Z, |p| seen.push((p.id(), p.source()))).unwrap();
    assert_eq!(seen, [(2, 2), (1, 1), (0, 0)]);
    let r = for_each_polygon_back_to_front::<0>(&t, DOWN_Z, |_| {});
    assert!(r.is_err());
}

#[test]
fn empty_tree_yields_nothing() {
    let bytes = Raw::empty().bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert!(classes::<1>(&t, DOWN_Z).is_empty());
}

#[test]
fn class_size_hint_bounds_the_count() {
    let bytes = one_level(false).bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    for c in Order::<1>::new(&t, DOWN_Z).unwrap() {
        let (lo, hi) = c.size_hint();
        let n = c.count();
        assert!(lo <= n && n <= hi.unwrap());
    }
}

/// Root level 1: F_1 = {0, 1 up at z = 1 (one run), 2 down at z = 0,
/// 3, 4 up at z = 1 (one run)}, B_1 = {}; 5 runs → 3 runs.
fn runs_in_a_bunch(closed: bool) -> Raw {
    let mut r = Raw::empty();
    add_square(&mut r, 1.0, true, 0);
    add_square(&mut r, 1.0, true, 1);
    add_square(&mut r, 0.0, false, 2);
    add_square(&mut r, 1.0, true, 3);
    add_square(&mut r, 1.0, true, 4);
    r.bunches = std::vec![0, 5, 5];
    r.nodes = std::vec![[0, 1, NO_SWITCH]];
    r.merge_runs(3);
    r.merge_runs(0);
    r.flags = if closed { FLAG_CLOSED } else { 0 };
    r
}

#[test]
fn runs_are_tested_once_and_emitted_whole() {
    let bytes = runs_in_a_bunch(true).bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert_eq!(t.run_count(), 3);
    // Closed, looking down: F_1's backward faces on the way up, by run.
    assert_eq!(classes::<1>(&t, DOWN_Z), [[0, 1, 3, 4]]);
    assert_eq!(classes::<1>(&t, UP_Z), [[2]]);
    let mut c = Order::<1>::new(&t, DOWN_Z).unwrap().next().unwrap();
    // Starting the class tested run 1 (polygon 2, facing away) with run
    // 0, the walk joining passing runs in a row: only run 2 is untested.
    assert_eq!(c.size_hint(), (2, Some(4)));
    assert_eq!(c.next(), Some(0));
    assert_eq!(c.next_range(), Some(1..2));
    assert_eq!(c.next_range(), Some(3..5));
    assert_eq!((c.next_range(), c.next()), (None, None));
    // Open: on the way down the forward faces of F_1, then the backward.
    let bytes = runs_in_a_bunch(false).bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert_eq!(
        classes::<1>(&t, DOWN_Z),
        [std::vec![2], std::vec![0, 1, 3, 4]]
    );
}

/// The walk's own hand-out joins runs that pass in a row (ids in a row)
/// into one range; a run that fails between them splits it; the ids and
/// their order are the classes'.
#[test]
fn passing_runs_in_a_row_are_one_range() {
    // Root level 1: F_1 = {0 up at z = 1, 1 up at z = 2, 2 down at z = 0,
    // 3 up at z = 3}, four runs (no two polygons share a plane).
    let mut r = Raw::empty();
    add_square(&mut r, 1.0, true, 0);
    add_square(&mut r, 2.0, true, 1);
    add_square(&mut r, 0.0, false, 2);
    add_square(&mut r, 3.0, true, 3);
    r.bunches = std::vec![0, 4, 4];
    r.nodes = std::vec![[0, 1, NO_SWITCH]];
    r.flags = FLAG_CLOSED;
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    assert_eq!(t.run_count(), 4);
    let ranges = |v: View| {
        let mut order = Order::<1>::new(&t, v).unwrap();
        let mut out = Vec::new();
        while let Some(ids) = order.next_range() {
            out.push(ids);
        }
        out
    };
    assert_eq!(ranges(DOWN_Z), [0..2, 3..4]);
    assert_eq!(classes::<1>(&t, DOWN_Z), [[0, 1, 3]]);
    assert_eq!(ranges(UP_Z), std::vec![2..3]);
    // A class from the walk: the same ranges.
    let mut c = Order::<1>::new(&t, DOWN_Z).unwrap().next().unwrap();
    assert_eq!(c.next_range(), Some(0..2));
    assert_eq!(c.next_range(), Some(3..4));
    assert_eq!(c.next_range(), None);
}

#[test]
fn open_on_plane_bunch_is_one_range() {
    // Root: switch at z = 0 with O = {0, 1 up (one run), 2 down}; open.
    let mut r = Raw::empty();
    add_square(&mut r, 0.0, true, 0);
    add_square(&mut r, 0.0, true, 1);
    add_square(&mut r, 0.0, false, 2);
    r.bunches = std::vec![0, 3];
    r.nodes = std::vec![[0, 0, 0], [1, 0, NO_SWITCH], [1, 0, NO_SWITCH]];
    r.switches = std::vec![[0.0, 0.0, 1.0, 0.0]];
    r.max_depth = 2;
    r.merge_runs(0);
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    let mut c = Order::<2>::new(&t, DOWN_Z).unwrap().next().unwrap();
    assert_eq!(c.size_hint(), (3, Some(3)));
    assert_eq!(c.next_range(), Some(0..3));
    assert_eq!(c.next_range(), None);
}

#[test]
fn empty_leaves_are_skipped_but_full_ones_walked() {
    // A BSP-shaped chain: root switch 0 (z = 0.5) → front leaf empty, back
    // node 2 with switch 1 (z = 0.25) → both leaves empty. O_0 = {0 at
    // z = 0.5}, O_1 = {1 at z = 0.25}.
    let mut r = Raw::empty();
    add_square(&mut r, 0.5, true, 0);
    add_square(&mut r, 0.25, true, 1);
    r.nodes = std::vec![
        [0, 0, 0],
        [1, 0, NO_SWITCH],
        [1, 0, 1],
        [2, 0, NO_SWITCH],
        [2, 0, NO_SWITCH],
    ];
    r.bunches = std::vec![0, 1, 2];
    r.switches = std::vec![[0.0, 0.0, 1.0, -0.5], [0.0, 0.0, 1.0, -0.25]];
    r.max_depth = 3;
    let bytes = r.bytes();
    let t = Tree::from_bytes(&bytes).unwrap();
    // Looking down, back groups are far: O_1 (lower) first.
    assert_eq!(classes::<3>(&t, DOWN_Z), [[1], [0]]);
    assert_eq!(classes::<3>(&t, UP_Z), [[0], [1]]);
    // The stack holds exactly the depth even when leaves are skipped.
    assert!(Order::<2>::new(&t, DOWN_Z).is_err());
}

#[test]
fn the_walks_facing_test_is_the_local_views() {
    // Facing must agree with LocalView::is_backward bit for bit, for
    // awkward values too: signed zeros, ties, huge and tiny planes (finite,
    // as validation makes them), and views with infinities and NaN.
    let vals = [
        0.0f32,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -3.25,
        1e-30,
        -1e-30,
        3e38,
        -3e38,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        0.1,
        -0.7,
    ];
    let mut state = 0x1234_5678_9abc_def0u64;
    let mut pick = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        vals[(state % vals.len() as u64) as usize]
    };
    for i in 0..20_000 {
        let mut finite = || loop {
            let x = pick();
            if x.is_finite() {
                return x;
            }
        };
        let normal = [finite(), finite(), finite()];
        let d = finite();
        let v = [pick(), pick(), pick()];
        let view = if i % 2 == 0 {
            LocalView::Parallel(v)
        } else {
            LocalView::Eye(v)
        };
        let mut rec = [0u8; 16];
        for (k, x) in normal.iter().chain([d].iter()).enumerate() {
            rec[4 * k..4 * k + 4].copy_from_slice(&x.to_le_bytes());
        }
        let plane = Plane { normal, d };
        assert_eq!(
            facing::Facing::of(&view, &[], 1.0).backward(&rec),
            view.is_backward(&plane),
            "{view:?} {plane:?}"
        );
        // Through a memo: the same answer the first time and from memory.
        let memo = [core::cell::Cell::new(0u32)];
        let face = facing::Facing::of(&view, &memo, 1.0);
        let k = (i % 16) as u32;
        assert_eq!(face.backward_at(k, &rec), view.is_backward(&plane));
        assert_eq!(memo[0].get() >> (2 * k) & 2, 2, "remembered");
        assert_eq!(face.backward_at(k, &rec), view.is_backward(&plane));
    }
}

#[test]
fn a_memo_changes_no_order() {
    let floors = two_floors().bytes();
    let runs = runs_in_a_bunch(true).bytes();
    let views = [
        DOWN_Z,
        UP_Z,
        View::perspective([0.5, 0.5, 10.0]),
        View::perspective([0.5, 0.5, 0.5]),
    ];
    for bytes in [&floors, &runs] {
        let t = Tree::from_bytes(bytes).unwrap();
        for v in views {
            let want = classes::<4>(&t, v);
            // Full, too short and empty memos; each walked twice (the
            // second walk answers from the memo).
            for n in [memo_words(&t), 0] {
                let mut words = std::vec![0u32; n];
                let memo = core::cell::Cell::from_mut(&mut words[..]).as_slice_of_cells();
                for _ in 0..2 {
                    let got: Vec<Vec<u32>> = Order::<4>::with_memo(&t, v, t.is_closed(), memo)
                        .unwrap()
                        .map(|c| c.collect())
                        .collect();
                    assert_eq!(got, want, "{v:?} memo {n}");
                }
            }
            assert!(memo_words(&t) >= 1);
        }
    }
}

#[cfg(feature = "compact-planes")]
#[test]
fn a_compact_entrys_fixed_point_test_is_its_f32_test_but_on_near_ties() {
    // The walk tests a compact entry in fixed point (facing::CompactPlane);
    // the exact sign of `m · a + e · w` (f64) must agree with it whenever
    // the value is farther from 0 than the fixed point's error (below
    // `M / 512`, `M` the largest of |a| and |w|, facing::fixed_view), and an
    // exact tie (0) must be forward.
    use crate::format::compact_side;
    let mut state = 0x0dd_ba11_cafe_f00du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let scales = [1e-3f32, 1.0, 37.5, 1e4, 3e7];
    for i in 0..50_000 {
        let mut entry = [0u8; 8];
        for k in 0..4 {
            // Every i16 but −32768, and often a small one or zero.
            let r = next();
            let v = match r % 4 {
                0 => 0,
                1 => (r >> 8) as i16 % 8,
                _ => ((r >> 8) as i16).max(-32767),
            };
            entry[2 * k..2 * k + 2].copy_from_slice(&v.to_le_bytes());
        }
        let s = scales[(next() % 5) as usize];
        let mut coord = || ((next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) as f32 * s;
        let v = [coord(), coord(), coord()];
        let view = if i % 2 == 0 {
            LocalView::Parallel(v)
        } else {
            LocalView::Eye(v)
        };
        let unit = [0.5f32, 1.0, 173.2][(next() % 3) as usize];
        let face = facing::Facing::of(&view, &[], unit);
        let got = face.backward(facing::CompactPlane::of(&entry));
        let m = compact_side(&entry).map(f64::from);
        let (a, w) = match view {
            LocalView::Parallel(d) => (d.map(|x| -f64::from(x)), 0.0),
            LocalView::Eye(e) => (e.map(f64::from), f64::from(unit)),
        };
        let terms = [m[0] * a[0], m[1] * a[1], m[2] * a[2], m[3] * w];
        let sum: f64 = terms.iter().sum();
        let big = a
            .iter()
            .chain([w].iter())
            .fold(0.0f64, |m, x| m.max(x.abs()));
        if sum == 0.0 {
            assert!(!got, "a tie is forward: {entry:?} {view:?}");
        } else if sum.abs() > big / 256.0 {
            assert_eq!(got, sum > 0.0, "{entry:?} {view:?} {unit}");
        }
    }
}
