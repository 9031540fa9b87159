//! Every builder's order against the exact z-buffer on the procedural
//! scenes: no wrong pixel away from outlines, for 100 random views each
//! (parallel, perspective, close and inside), and well-formed classes.

use fpt_tests::{
    assert_orders, check_order, order_classes, random_cameras, NostdWalk, OrderSource,
};
use host_sim::build::{build, NoProgress};
use host_sim::reference::View;
use host_sim::scenes::{self, Scene};
use host_sim::tree::Method;

const VIEWS: usize = 100;
const SIZE: usize = 96;

fn check(scene: &Scene) {
    assert_orders(&scene.name, &scene.polygons, scene.closed, VIEWS, SIZE);
}

macro_rules! scene_tests {
    ($($name:ident),* $(,)?) => {
        $(
            #[test]
            fn $name() {
                check(&scenes::$name());
            }
        )*
    };
}

scene_tests!(
    vise,
    house,
    bench_city,
    cyclic_boards,
    interpenetrating_boxes,
    gear,
    cube_grid,
    near_coplanar_stack,
    slivers,
    open_sheet,
);

#[test]
fn tiny_coordinates() {
    let mut s = scenes::scaled(&scenes::interpenetrating_boxes(), 1e-4, glam::DVec3::ZERO);
    s.name = "interpenetrating_boxes x1e-4".into();
    check(&s);
    let mut s = scenes::scaled(&scenes::gear(), 1e-4, glam::DVec3::new(0.0, 3e-4, 0.0));
    s.name = "gear x1e-4".into();
    check(&s);
}

#[test]
fn huge_far_off_coordinates() {
    let off = glam::DVec3::splat(1e5);
    let mut s = scenes::scaled(&scenes::cyclic_boards(), 1e3, off);
    s.name = "cyclic_boards x1e3 +1e5".into();
    check(&s);
    let mut s = scenes::scaled(&scenes::vise(), 1e3, off);
    s.name = "vise x1e3 +1e5".into();
    check(&s);
}

/// An order source that draws the classes nearest first.
struct Reversed<'a>(&'a host_sim::tree::FpTree);

impl OrderSource for Reversed<'_> {
    fn classes(&mut self, view: &View) -> Vec<Vec<u32>> {
        let mut c = order_classes(self.0, view);
        c.reverse();
        c
    }
}

#[test]
fn a_wrong_order_is_caught() {
    // The check must be able to fail: the reversed order of a correct tree
    // shows wrong pixels in most views of a scene with depth complexity.
    let s = scenes::cube_grid();
    let tree = build(
        s.polygons.clone(),
        s.closed,
        Method::Static,
        7,
        &mut NoProgress,
    );
    let cams = random_cameras(&s.polygons, 20, 3);
    let rep = check_order(&tree, &mut Reversed(&tree), &cams, 48, 48);
    assert!(rep.wrong > 500, "{rep:?}");
    assert!(rep.failures.len() >= 10, "{rep:?}");
}

#[test]
fn nostd_walk_matches_the_reference_walk() {
    // The product's walk of the serialized tree emits the same classes as
    // the digest's walk of the in-memory tree (order within a class aside).
    for s in [
        scenes::house(),
        scenes::open_sheet(),
        scenes::cyclic_boards(),
    ] {
        for method in [Method::Static, Method::Dynamic, Method::Bsp] {
            let tree = build(s.polygons.clone(), s.closed, method, 7, &mut NoProgress);
            let mut nostd = NostdWalk::new(&tree);
            for (k, cam) in random_cameras(&s.polygons, 30, 11).iter().enumerate() {
                let sorted = |mut c: Vec<Vec<u32>>| {
                    c.iter_mut().for_each(|v| v.sort_unstable());
                    c
                };
                let want = sorted(order_classes(&tree, &cam.view()));
                let got = sorted(nostd.classes(&cam.view()));
                assert_eq!(got, want, "{} {method:?} view {k}", s.name);
            }
        }
    }
}
