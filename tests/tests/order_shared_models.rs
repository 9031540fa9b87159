//! Every builder's order against the exact z-buffer on the third-party
//! models in `../shared/models` (skipped when that folder is absent, as in a
//! fresh clone of the project).

use fpt_tests::assert_orders;
use std::path::{Path, PathBuf};

const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/models");
const VIEWS: usize = 60;
const SIZE: usize = 96;

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
    assert_orders(file, &m.polygons, m.closed, VIEWS, SIZE);
}

macro_rules! model_tests {
    ($($name:ident => $file:expr),* $(,)?) => {
        $(
            #[test]
            fn $name() {
                check($file);
            }
        )*
    };
}

model_tests!(
    shuttle => "shuttle.obj",
    socket => "socket.off",
    plate_holes => "plate_holes.STL",
    rabbit => "rabbit.obj",
    wallhole => "wallhole.obj",
    teapot => "teapot.ply",
    suzanne => "suzanne.obj",
    violin_case => "violin_case.obj",
);
