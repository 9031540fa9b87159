//! Property tests of the tree renderer over random cameras: orbits with
//! any parameters and matrices with any entries (huge, tiny, zero rows,
//! non-finite, singular) and any near threshold. Whatever the camera:
//! no panic, in every arithmetic configuration, through id buffers, bands
//! and packed framebuffers; the counters account for every polygon the
//! walk emits; and a sane orbit skips no polygon.

use crate::render_common;

use embedded_graphics::pixelcolor::BinaryColor;
use fpt_nostd::order::for_each_polygon_back_to_front;
use fpt_nostd::raster::framebuffer::BinaryFormat;
use fpt_nostd::raster::{
    Camera, DefaultPrecision, FixedPrecision, FloatLibm, FloatMicromath, IdBuffer, IntPrecision,
    Libm, Mat4, Orbit, Precision, RenderStats,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{near_w_for, rows_f64, BandBuffer, Frame, TreeRenderer};
use proptest::prelude::*;
use render_common::{build_tree, STACK, VERTS};
use std::sync::OnceLock;

const W: u32 = 40;
const H: u32 = 30;

/// The house's tree (closed, concave walls) and an open scene's.
fn trees() -> &'static [Vec<u8>; 2] {
    static T: OnceLock<[Vec<u8>; 2]> = OnceLock::new();
    T.get_or_init(|| {
        let h = host_sim::scenes::house();
        let o = host_sim::scenes::open_sheet();
        [
            build_tree(&h.polygons, h.closed).bytes,
            build_tree(&o.polygons, o.closed).bytes,
        ]
    })
}

fn draw<P: Precision>(tree: &Tree<'_>, f: &Frame) -> RenderStats {
    let mut ids = vec![0u32; (W * H) as usize];
    let mut sink = IdBuffer::new(&mut ids, W, H).expect("ids");
    let mut r = Box::new(TreeRenderer::<P, VERTS>::new(W, H).expect("renderer"));
    let stats = r.render::<STACK, _>(tree, f, &mut sink).expect("walk");
    assert!(ids.iter().all(|&v| v <= tree.polygon_count()));
    let mut buf = vec![0u8; (W as usize).div_ceil(8) * 7];
    let band = BandBuffer::<BinaryFormat> {
        buf: &mut buf,
        rows: 7,
        background: BinaryColor::Off,
    };
    r.render_banded::<STACK, _>(tree, f, band, |_, _| {})
        .expect("bands");
    stats
}

/// Renders in four configurations; checks the counters against the walk.
fn check(tree: &Tree<'_>, f: &Frame) -> RenderStats {
    let mut emitted = 0u32;
    for_each_polygon_back_to_front::<STACK>(tree, f.view, |_| emitted += 1).expect("walk");
    let s = draw::<DefaultPrecision>(tree, f);
    assert_eq!(s.drawn + s.invisible + s.skipped, emitted, "{s:?}");
    for t in [
        draw::<FixedPrecision<0>>(tree, f),
        draw::<FloatLibm<8>>(tree, f),
        draw::<FloatMicromath<2>>(tree, f),
        draw::<IntPrecision<4>>(tree, f),
    ] {
        assert_eq!(t.drawn + t.invisible + t.skipped, emitted, "{t:?}");
    }
    s
}

fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -10.0f32..10.0,
        1 => -1e30f32..1e30,
        1 => -1e-30f32..1e-30,
        1 => Just(0.0f32),
        1 => prop::num::f32::ANY,
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn any_matrix_renders_without_panic(
        entries in prop::array::uniform16(any_f32()),
        zero_row in prop::option::of(0usize..4),
        near in any_f32(),
        which in 0usize..2,
        derived_near in any::<bool>(),
    ) {
        let bytes = &trees()[which];
        let tree = Tree::from_bytes(bytes).expect("tree");
        let mut m = Mat4([[0.0; 4]; 4]);
        for (i, v) in entries.iter().enumerate() {
            m.0[i / 4][i % 4] = *v;
        }
        if let Some(r) = zero_row {
            m.0[r] = [0.0; 4];
        }
        let near = if derived_near { near_w_for(&rows_f64(&m), &tree) } else { near };
        check(&tree, &Frame::new(&tree, &Camera::from_matrix(m, near)));
    }

    #[test]
    fn any_orbit_renders_without_panic(
        yaw in any_f32(),
        pitch in any_f32(),
        distance in any_f32(),
        fov in any_f32(),
        which in 0usize..2,
    ) {
        let bytes = &trees()[which];
        let tree = Tree::from_bytes(bytes).expect("tree");
        let o = Orbit::new([0.0; 3], yaw, pitch, distance, fov);
        check(&tree, &Frame::relative(&tree, &o.camera::<Libm>(W as f32 / H as f32)));
    }

    #[test]
    fn sane_orbits_draw_everything_they_are_given(
        yaw in -7.0f32..7.0,
        pitch in -1.6f32..1.6,
        dist in 0.05f32..10.0,
        fov in prop_oneof![Just(0.0f32), 0.2f32..2.5],
        which in 0usize..2,
    ) {
        let bytes = &trees()[which];
        let tree = Tree::from_bytes(bytes).expect("tree");
        // From far outside to deep inside the model.
        let o = Orbit::new([0.0; 3], yaw, pitch, dist * tree.bounding_radius(), fov);
        let s = check(&tree, &Frame::relative(&tree, &o.camera::<Libm>(W as f32 / H as f32)));
        prop_assert_eq!(s.skipped, 0, "{:?}", s);
    }
}
