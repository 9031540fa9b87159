//! Effects as pipeline stages: the firmware's `effect` measurement run on
//! the host (same code, same scene), and the builder's clipping proof.

use fpt_frames::effects::{
    bare_pipeline, on_off, render_effect, EffectTarget, EFFECT_SCENE, EFFECT_VIEW, MONO_BYTES,
};
use fpt_frames::{FramePrecision, NoProbe, ViewSpec, FRAME_WORDS, HEIGHT, MAX_VERTS, VIEWS, WIDTH};
use fpt_nostd::effects::{AllEffects, Compiled, Effects, Pipeline};
use fpt_nostd::raster::{
    Camera, DefaultPrecision, Libm, Mat4, Orbit, Renderer, Rgb565Framebuffer, Scratch,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{Frame, TreeRenderer};
use host_sim::cli::frames::scene_tree;

/// The checksum of the effect scene drawn with `fx` through pipeline `E`.
fn crc<E: Compiled>(tree: &Tree<'_>, fx: Effects, mono: bool) -> u32 {
    let camera = Camera::from_matrix(Mat4::IDENTITY, 1.0);
    let mut r = Renderer::<FramePrecision, E>::new(WIDTH, HEIGHT, &camera).expect("renderer");
    let mut scratch = Box::new(Scratch::<FramePrecision, MAX_VERTS>::new());
    let mut words = vec![0u16; FRAME_WORDS];
    let mut bytes = vec![0u8; MONO_BYTES];
    let target = if mono {
        EffectTarget::Mono {
            buf: &mut bytes,
            dither: fx.contains(Effects::DITHER),
        }
    } else {
        EffectTarget::Rgb565(&mut words)
    };
    let view = &VIEWS[EFFECT_VIEW];
    render_effect(&mut r, &mut scratch, tree, view, fx, target, &NoProbe).expect("render")
}

fn bare(i: usize, tree: &Tree<'_>, fx: Effects, mono: bool) -> u32 {
    const B: [u32; 8] = [
        bare_pipeline(Effects::CULLING),
        bare_pipeline(Effects::TWO_SIDED),
        bare_pipeline(Effects::CLIPPING),
        bare_pipeline(Effects::LIGHTING),
        bare_pipeline(Effects::DEPTH_CUE),
        bare_pipeline(Effects::DITHER),
        bare_pipeline(Effects::OUTLINE),
        bare_pipeline(Effects::SMOOTH),
    ];
    match i {
        0 => crc::<Pipeline<{ B[0] }>>(tree, fx, mono),
        1 => crc::<Pipeline<{ B[1] }>>(tree, fx, mono),
        2 => crc::<Pipeline<{ B[2] }>>(tree, fx, mono),
        3 => crc::<Pipeline<{ B[3] }>>(tree, fx, mono),
        4 => crc::<Pipeline<{ B[4] }>>(tree, fx, mono),
        5 => crc::<Pipeline<{ B[5] }>>(tree, fx, mono),
        6 => crc::<Pipeline<{ B[6] }>>(tree, fx, mono),
        _ => crc::<Pipeline<{ B[7] }>>(tree, fx, mono),
    }
}

#[test]
fn off_and_compiled_out_draw_alike_and_each_visible_effect_shows() {
    let bytes = scene_tree(EFFECT_SCENE).expect("scene");
    let tree = Tree::from_bytes(&bytes).expect("tree");
    let base = Effects::from_bits(tree.effects());
    assert_eq!(base, Effects::defaults(true), "a closed scene's defaults");
    for (i, (name, e)) in Effects::NAMED.iter().enumerate() {
        let mono = *e == Effects::DITHER;
        let (on_fx, off_fx) = on_off(base, *e);
        let on = crc::<AllEffects>(&tree, on_fx, mono);
        let off = crc::<AllEffects>(&tree, off_fx, mono);
        assert_eq!(
            off,
            bare(i, &tree, off_fx, mono),
            "{name}: off and bare differ"
        );
        // Culling only saves work on a closed scene seen from outside: the
        // back faces drawn first are all covered. Two-sided lighting has
        // no back face to light when culling. This view needs no clipping.
        // The scene's tree has no corner normals: smooth shading draws it
        // flat.
        let invisible = [
            Effects::CULLING,
            Effects::TWO_SIDED,
            Effects::CLIPPING,
            Effects::SMOOTH,
        ];
        let visible = !invisible.contains(e);
        assert_eq!(on != off, visible, "{name}: on {on:08x}, off {off:08x}");
    }
}

/// Draws `tree` from `orbit` (z up, like the frame set) with `fx`; the
/// picture and how many polygons were clipped.
fn draw(tree: &Tree<'_>, orbit: &Orbit, fx: Effects) -> (Vec<u16>, u32) {
    let cam = orbit.camera::<Libm>(1.0).with_model(&fpt_frames::Z_UP);
    let frame = Frame::relative(tree, &cam);
    let mut tr = Box::new(TreeRenderer::<DefaultPrecision, 64>::new(96, 96).expect("renderer"));
    tr.renderer.set_effects(Some(fx));
    let mut buf = vec![0u16; 96 * 96];
    let mut fb = Rgb565Framebuffer::new(&mut buf, 96, 96).expect("fb");
    let stats = tr.render::<64, _>(tree, &frame, &mut fb).expect("walk");
    (buf, stats.clipped)
}

#[test]
fn an_orbit_proven_free_of_clipping_never_clips_and_one_too_close_does() {
    let bytes = scene_tree("vise").expect("scene");
    let tree = Tree::from_bytes(&bytes).expect("tree");
    let r = tree.bounding_radius();
    let with = Effects::defaults(true);
    let without = with.without(Effects::CLIPPING);
    let views = |d: f32, fov: f32| {
        (0..24).map(move |k| {
            let yaw = k as f32 * 0.9;
            let pitch = ((k * 7) % 11) as f32 * 0.28 - 1.4;
            Orbit::new([0.0; 3], yaw, pitch, d * r, fov)
        })
    };
    // Proven: every view draws the same picture without the clipping stage.
    let far = ViewSpec {
        yaw: 0.0,
        pitch: 0.0,
        distance: 1.25,
        fov: 1.2,
    };
    let probe = far.orbit(&tree);
    assert!(probe.never_clips::<Libm>(r, 1.0));
    for o in views(far.distance, far.fov) {
        let (a, clipped) = draw(&tree, &o, with);
        assert_eq!(clipped, 0, "{o:?}");
        assert!(a == draw(&tree, &o, without).0, "{o:?}");
    }
    // Too close (inside the bounding sphere): not proven, and it clips.
    let near = Orbit::new([0.0; 3], 0.0, 0.0, 0.9 * r, 1.2);
    assert!(!near.never_clips::<Libm>(r, 1.0));
    let clipped: u32 = views(0.9, 1.2).map(|o| draw(&tree, &o, with).1).sum();
    assert!(clipped > 0);
    // In front of the eye, but zoomed in so far that the sphere leaves the
    // guard band (the same distance with a wide view is fine).
    let zoomed = Orbit::new([0.0; 3], 0.0, 0.0, 1.05 * r, 0.3);
    assert!(!zoomed.never_clips::<Libm>(r, 1.0));
    assert!(Orbit::new([0.0; 3], 0.0, 0.0, 1.05 * r, 2.0).never_clips::<Libm>(r, 1.0));
    let clipped: u32 = views(1.05, 0.3).map(|o| draw(&tree, &o, with).1).sum();
    assert!(clipped > 0);
    // Parallel: only the guard band matters.
    let flat = Orbit::new([0.0; 3], 0.0, 0.0, 2.0 * r, 0.0);
    assert!(flat.never_clips::<Libm>(r, 1.0));
    assert!(!Orbit::new([0.0; 3], 0.0, 0.0, 0.4 * r, 0.0).never_clips::<Libm>(r, 1.0));
}
