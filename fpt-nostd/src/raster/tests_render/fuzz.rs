//! Property tests of the renderer: random cameras (orbits far and near,
//! arbitrary matrices, non-finite numbers) and random polygons through
//! every precision configuration never panic and never paint a pixel twice
//! within one polygon.
//!
//! Apart from the end-to-end scenes of the parent module because they share
//! nothing with them but the renderer: their inputs come from `proptest`
//! strategies, not from a scene.

use super::*;
use proptest::prelude::*;

fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![
        8 => -1.0e3f32..1.0e3,
        2 => (-30.0f32..30.0).prop_map(|e| libm::powf(10.0, e)),
        2 => (-30.0f32..30.0).prop_map(|e| -libm::powf(10.0, e)),
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(0.0f32),
    ]
}

fn orbit_s() -> impl Strategy<Value = Orbit> {
    (
        prop::array::uniform3(-100.0f32..100.0),
        -20.0f32..20.0,
        -3.2f32..3.2,
        -8.0f32..12.0,
        -0.5f32..3.3,
    )
        .prop_map(|(t, yaw, pitch, logd, fov)| {
            Orbit::new(t, yaw, pitch, libm::powf(10.0, logd), fov)
        })
}

fn run_all<P: Precision>(cam: &Camera, polys: &[Vec<[f32; 3]>]) {
    let mut r = Renderer::<P>::new(40, 30, cam).unwrap_or_else(|| panic!());
    let mut scratch = Scratch::<P, 24>::new();
    for (k, v) in polys.iter().enumerate() {
        let mut s = CountSink::new(40, 30);
        let face = Face {
            normal: v.first().copied().unwrap_or_default().into(),
            color: [1; 3],
            id: k as u32,
            hidden_edges: 0,
        };
        r.draw_polygon(&mut scratch, v.iter().copied(), &face, &mut s);
        assert!(
            s.count.iter().all(|&c| c <= 1),
            "overdraw within one polygon"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]
    #[test]
    fn random_cameras_and_polygons_never_panic(
        o in orbit_s(),
        m in prop::array::uniform16(coord()),
        near in coord(),
        polys in prop::collection::vec(prop::collection::vec(prop::array::uniform3(coord()), 0..30), 1..6),
    ) {
        let aspect = 40.0 / 30.0;
        let mat = Mat4([[m[0], m[1], m[2], m[3]], [m[4], m[5], m[6], m[7]], [m[8], m[9], m[10], m[11]], [m[12], m[13], m[14], m[15]]]);
        for cam in [o.camera::<super::super::precision::Libm>(aspect), Camera::from_matrix(mat, near)] {
            run_all::<FixedPrecision<0>>(&cam, &polys);
            run_all::<FixedPrecision<8>>(&cam, &polys);
            run_all::<FloatLibm<8>>(&cam, &polys);
            run_all::<FloatMicromath<3>>(&cam, &polys);
            run_all::<Int8<0>>(&cam, &polys);
            run_all::<IntPrecision<8>>(&cam, &polys);
        }
    }
}
