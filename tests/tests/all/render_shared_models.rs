//! The no_std render of the third-party models in `../shared/models`
//! against the float64 reference z-buffer, by source face, over seeded
//! random views (parallel, perspective from outside, from just in front of
//! a face and from inside the model). Skipped when the folder is absent, as
//! in a fresh clone.

use crate::render_common;

use fpt_tests::{random_cameras, shared_mesh};
use render_common::{assert_clean, check_views};

const VIEWS: usize = 30;
const W: usize = 96;
const H: usize = 96;

fn check(file: &str) {
    let Some(m) = shared_mesh(file) else {
        return;
    };
    let cams = random_cameras(&m.polygons, VIEWS, 0x4E4D_u64 ^ m.polygons.len() as u64);
    let rep = check_views(file, &m.polygons, m.closed, &cams, W, H);
    assert_clean(file, &rep);
}

#[test]
fn shuttle() {
    check("shuttle.obj");
}

#[test]
fn socket() {
    check("socket.off");
}

#[test]
fn wallhole() {
    check("wallhole.obj");
}

#[test]
fn teapot_open() {
    check("teapot.ply");
}

#[test]
fn rabbit() {
    check("rabbit.obj");
}
