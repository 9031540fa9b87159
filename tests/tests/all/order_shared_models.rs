//! Every builder's order against the exact z-buffer on the third-party
//! models in `../shared/models` (skipped when that folder is absent, as in a
//! fresh clone of the project).

use fpt_tests::{assert_orders, shared_mesh};

const VIEWS: usize = 60;
const SIZE: usize = 96;

fn check(file: &str) {
    let Some(m) = shared_mesh(file) else {
        return;
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

/// fandisk.obj (5,750 triangles) is the one shared model between the
/// small models' lookahead and the large ones' (`lookahead::MEDIUM` in
/// `fpt-build`): its order is checked like the others', but its static and
/// dynamic builds take seconds each, so it runs on request
/// (`cargo test -p fpt-tests --test all order_shared_models -- --ignored`).
#[test]
#[ignore = "fandisk.obj's feudal builds take several seconds each"]
fn fandisk() {
    check("fandisk.obj");
}
