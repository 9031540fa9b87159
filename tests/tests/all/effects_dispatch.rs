//! An effect that is off runs the code of the pipeline built without it
//! (`fpt_nostd::effects`, "Off is compiled out"): which code a frame
//! picks, and that off and compiled out draw the same pixels through every
//! public draw entry that walks the tree.

use embedded_graphics::pixelcolor::Rgb565;
use fpt_frames::effects::{bare_pipeline, Bare, EFFECT_SCENE};
use fpt_nostd::effects::{compiled_for, Compiled, Effects, Pipeline, Switched, SWITCHED};
use fpt_nostd::raster::{DefaultPrecision, DepthCue, Framebuffer, Libm, Orbit, Rgb565BeFormat};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{memory_words, BandBuffer, BandBuffers, BandTransfer, Frame, TreeRenderer};
use host_sim::cli::frames::scene_tree;

const CULL: u32 = bare_pipeline(Effects::CULLING);
const LIGHT: u32 = bare_pipeline(Effects::LIGHTING);
const CUE: u32 = bare_pipeline(Effects::DEPTH_CUE);
const OUTLINE: u32 = bare_pipeline(Effects::OUTLINE);
const SMOOTH: u32 = bare_pipeline(Effects::SMOOTH);

#[test]
fn every_switched_effect_off_picks_the_code_of_the_pipeline_without_it() {
    let base = Effects::defaults(true);
    let sets = |fx: Effects| {
        [
            (
                Effects::CULLING,
                compiled_for::<Switched<CULL>>(fx),
                compiled_for::<Bare<CULL>>(fx),
            ),
            (
                Effects::LIGHTING,
                compiled_for::<Switched<LIGHT>>(fx),
                compiled_for::<Bare<LIGHT>>(fx),
            ),
            (
                Effects::DEPTH_CUE,
                compiled_for::<Switched<CUE>>(fx),
                compiled_for::<Bare<CUE>>(fx),
            ),
            (
                Effects::OUTLINE,
                compiled_for::<Switched<OUTLINE>>(fx),
                compiled_for::<Bare<OUTLINE>>(fx),
            ),
            (
                Effects::SMOOTH,
                compiled_for::<Switched<SMOOTH>>(fx),
                compiled_for::<Bare<SMOOTH>>(fx),
            ),
        ]
    };
    for (e, _, _) in sets(base) {
        assert!(SWITCHED.contains(e), "{e}");
        // The scene's effects without `e`; culling and lighting, switched
        // one by one, also with every other effect on (the extras are
        // switched as one: only when all three are off).
        let single = [Effects::CULLING, Effects::LIGHTING].contains(&e);
        let with = if single {
            &[base, Effects::ALL][..]
        } else {
            &[base][..]
        };
        for &on in with {
            let fx = on.without(e);
            let all = compiled_for::<Switched<0xff>>(fx);
            assert!(!all.contains(e), "{e} off in {fx}: {all}");
            let (_, pipeline, bare) = sets(fx).into_iter().find(|s| s.0 == e).expect("effect");
            assert_eq!(all, pipeline, "{e} off in {fx}");
            // The firmware's `bare` runs (fewer copies) run the same code.
            if on == base {
                assert_eq!(bare, pipeline, "{e} off in {fx}");
            }
        }
    }
    // On, it stays compiled in; the unswitched ones stay in when off.
    assert_eq!(compiled_for::<Switched<0xff>>(Effects::ALL), Effects::ALL);
    let fx = Effects::ALL
        .without(Effects::TWO_SIDED)
        .without(Effects::CLIPPING);
    assert_eq!(compiled_for::<Switched<0xff>>(fx), Effects::ALL);
    // One extra on keeps the other two compiled in.
    let fx = Effects::ALL.without(Effects::DEPTH_CUE);
    assert_eq!(compiled_for::<Switched<0xff>>(fx), Effects::ALL);
}

/// Everything one pipeline draws of the effect scene with `fx`, through
/// every public entry that walks: [`TreeRenderer::render`],
/// `render_cached`, `render_banded`, `render_banded_in` and
/// `render_double_buffered_in` (the last four with and without memory).
fn pictures<E: Compiled>(tree: &Tree<'_>, frame: &Frame, fx: Effects) -> Vec<Vec<u16>> {
    const W: u32 = 120;
    const H: u32 = 96;
    const ROWS: u32 = 16;
    let mut r = Box::new(TreeRenderer::<DefaultPrecision, 64, E>::new(W, H).expect("renderer"));
    r.renderer.set_effects(Some(fx));
    let (near, far) = frame.depth_range(tree);
    r.renderer.set_depth_cue(DepthCue {
        near,
        far,
        ..DepthCue::default()
    });
    let mut out = Vec::new();
    let full = |r: &mut TreeRenderer<DefaultPrecision, 64, E>, memory: Option<&mut [u32]>| {
        let mut buf = vec![0u16; (W * H) as usize];
        let mut fb = Framebuffer::<Rgb565BeFormat>::new(&mut buf, W, H).expect("fb");
        match memory {
            None => r.render::<64, _>(tree, frame, &mut fb),
            Some(m) => r.render_cached::<64, _>(tree, frame, m, &mut fb),
        }
        .expect("frame");
        buf
    };
    let mut memory = vec![0u32; memory_words(tree)];
    out.push(full(&mut r, None));
    out.push(full(&mut r, Some(&mut memory)));
    // Bands, put together into one frame of big-endian words.
    for words in [0, memory.len(), 300] {
        let mut frame_words = vec![0u16; (W * H) as usize];
        let mut band = vec![0u16; (W * ROWS) as usize];
        let b = BandBuffer::<Rgb565BeFormat> {
            buf: &mut band,
            rows: ROWS,
            background: Rgb565::new(0, 0, 0),
        };
        let m = &mut memory[..words];
        r.render_banded_in::<64, _>(tree, frame, b, m, |y, fb| {
            let at = y as usize * W as usize;
            let px = fb.data();
            frame_words[at..at + px.len()].copy_from_slice(px);
        })
        .expect("bands");
        out.push(frame_words);
    }
    // Two buffers in turns.
    struct Link<'b> {
        rows: Vec<(i32, Vec<u16>)>,
        in_flight: Option<Framebuffer<'b, Rgb565BeFormat>>,
        y: i32,
    }
    impl<'b> BandTransfer<'b, Rgb565BeFormat> for Link<'b> {
        type Error = ();
        fn start(&mut self, y: i32, band: Framebuffer<'b, Rgb565BeFormat>) -> Result<(), ()> {
            self.y = y;
            self.in_flight = Some(band);
            Ok(())
        }
        fn finish(&mut self) -> Result<Framebuffer<'b, Rgb565BeFormat>, ()> {
            let band = self.in_flight.take().ok_or(())?;
            self.rows.push((self.y, band.data().to_vec()));
            Ok(band)
        }
    }
    for words in [0, memory.len()] {
        let (mut a, mut b) = (
            vec![0u16; (W * ROWS) as usize],
            vec![0u16; (W * ROWS) as usize],
        );
        let mut bands = BandBuffers::<Rgb565BeFormat> {
            front: &mut a,
            back: &mut b,
            rows: ROWS,
            background: Rgb565::new(0, 0, 0),
        };
        let mut link = Link {
            rows: Vec::new(),
            in_flight: None,
            y: 0,
        };
        let m = &mut memory[..words];
        r.render_double_buffered_in::<64, _, _>(tree, frame, &mut bands, m, &mut link)
            .expect("double");
        let mut frame_words = vec![0u16; (W * H) as usize];
        for (y, px) in link.rows {
            let at = y as usize * W as usize;
            frame_words[at..at + px.len()].copy_from_slice(&px);
        }
        out.push(frame_words);
    }
    out
}

/// A pipeline's [`pictures`].
type Pictures = fn(&Tree<'_>, &Frame, Effects) -> Vec<Vec<u16>>;

#[test]
fn off_and_compiled_out_draw_alike_through_every_entry() {
    let bytes = scene_tree(EFFECT_SCENE).expect("scene");
    let tree = Tree::from_bytes(&bytes).expect("tree");
    let base = Effects::from_bits(tree.effects());
    let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), 0.7, 0.45, 1.2, 1.25);
    let frame = Frame::relative(
        &tree,
        &orbit.camera::<Libm>(1.25).with_model(&fpt_frames::Z_UP),
    );
    // Compiled out: a `Pipeline` built without the effect (on a hosted
    // target it switches nothing, so it is one copy; a `Switched` one here
    // made this test binary take 4 minutes more to compile).
    let cases: [(Effects, Pictures); 5] = [
        (Effects::CULLING, pictures::<Pipeline<CULL>>),
        (Effects::LIGHTING, pictures::<Pipeline<LIGHT>>),
        (Effects::DEPTH_CUE, pictures::<Pipeline<CUE>>),
        (Effects::OUTLINE, pictures::<Pipeline<OUTLINE>>),
        (Effects::SMOOTH, pictures::<Pipeline<SMOOTH>>),
    ];
    for (e, bare) in cases {
        let on = pictures::<Switched<0xff>>(&tree, &frame, base.with(e));
        let off = pictures::<Switched<0xff>>(&tree, &frame, base.without(e));
        // Every entry draws the same picture.
        assert!(off.iter().all(|p| *p == off[0]), "{e}: entries differ");
        assert!(on.iter().all(|p| *p == on[0]), "{e} on: entries differ");
        assert_eq!(
            off,
            bare(&tree, &frame, base.without(e)),
            "{e}: off and bare differ"
        );
        // Lighting, depth cueing and outlines show (a frame that drew
        // nothing would pass the rest).
        if [Effects::LIGHTING, Effects::DEPTH_CUE, Effects::OUTLINE].contains(&e) {
            assert_ne!(on[0], off[0], "{e}: on and off draw alike");
        }
        assert!(off[0].iter().any(|&w| w != 0), "{e}: an empty picture");
    }
}
