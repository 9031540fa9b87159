//! The no_std render of the third-party models in `../shared/models`
//! against the float64 reference z-buffer, by source face, over seeded
//! random views (parallel, perspective from outside, from just in front of
//! a face and from inside the model). Skipped when the folder is absent, as
//! in a fresh clone.

mod render_common;

use fpt_tests::random_cameras;
use render_common::{assert_clean, check_views};
use std::path::{Path, PathBuf};

const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/models");
const VIEWS: usize = 30;
const W: usize = 96;
const H: usize = 96;

fn model(file: &str) -> Option<PathBuf> {
    if !Path::new(MODELS).is_dir() {
        println!("skipping: ../shared/models not found");
        return None;
    }
    let p = Path::new(MODELS).join(file);
    if !p.is_file() {
        println!("skipping: ../shared/models/{file} not found");
        return None;
    }
    Some(p)
}

fn check(file: &str) {
    let Some(path) = model(file) else {
        return;
    };
    let m = match host_sim::mesh::load(&path) {
        Ok(m) => m,
        Err(e) => panic!("{file}: {e}"),
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
