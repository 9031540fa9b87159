//! Golden-image checks on real trees (the house and the vise): the fast
//! framebuffer path, the generic embedded-graphics `DrawTarget` path and
//! the band path give the same pixels, in every pixel format; and
//! `fpt render --mvp ... --ids` writes exactly the library's id buffer.

use crate::render_common;

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Size};
use embedded_graphics::pixelcolor::{BinaryColor, Gray8, PixelColor, Rgb565, Rgb888};
use embedded_graphics::Pixel;
use fpt_nostd::effects::Effects;
use fpt_nostd::raster::framebuffer::{BinaryFormat, Gray8Format, Rgb565Format, Rgb888Format};
use fpt_nostd::raster::{
    DefaultPrecision, DepthCue, DrawTargetSink, Framebuffer, Light, PixelFormat, RenderStats,
    ShadeMode,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{memory_words_for, BandBuffer, Frame, TreeRenderer};
use fpt_tests::random_cameras;
use host_sim::scenes;
use render_common::{build_tree, frame, render_ids, STACK, VERTS};

const W: u32 = 72;
const H: u32 = 53;

/// A display that only knows single pixels (every other method is the
/// embedded-graphics default), like a minimal driver.
struct PixelDisplay<C> {
    px: Vec<C>,
}

impl<C: PixelColor> OriginDimensions for PixelDisplay<C> {
    fn size(&self) -> Size {
        Size::new(W, H)
    }
}

impl<C: PixelColor> DrawTarget for PixelDisplay<C> {
    type Color = C;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            if p.x >= 0 && p.y >= 0 && (p.x as u32) < W && (p.y as u32) < H {
                self.px[(p.y as u32 * W + p.x as u32) as usize] = c;
            }
        }
        Ok(())
    }
}

fn renderer(
    tree: &Tree<'_>,
    f: &Frame,
    fx: Option<Effects>,
) -> Box<TreeRenderer<DefaultPrecision, VERTS>> {
    let mut r = Box::new(TreeRenderer::new(W, H).expect("renderer"));
    r.renderer.set_shade_mode(ShadeMode::Lambert);
    r.renderer
        .set_light(Light::new([0.3, 0.5, 0.8], 0.25, 0.75));
    r.renderer.set_effects(fx);
    let (near, far) = f.depth_range(tree);
    r.renderer.set_depth_cue(DepthCue {
        near,
        far,
        ..DepthCue::default()
    });
    r
}

/// The three paths in format `F`; panics on the first difference.
/// Returns whether anything but the background was drawn.
fn paths<F: PixelFormat>(
    tree: &Tree<'_>,
    f: &Frame,
    fx: Option<Effects>,
    bg: F::Color,
    label: &str,
) -> bool
where
    F::Word: Default + PartialEq + core::fmt::Debug,
    F::Color: PartialEq + core::fmt::Debug,
{
    let mut r = renderer(tree, f, fx);
    let mut fast = vec![F::Word::default(); Framebuffer::<F>::required_len(W, H)];
    let mut fb = Framebuffer::<F>::new(&mut fast, W, H).expect("fb");
    fb.fill_all(bg);
    let stats = r.render::<STACK, _>(tree, f, &mut fb).expect("walk");
    let fast_px: Vec<F::Color> = (0..H)
        .flat_map(|y| (0..W).map(move |x| (x, y)))
        .filter_map(|(x, y)| fb.pixel(x, y))
        .collect();
    assert!(stats.drawn > 0, "{label}: nothing drawn");

    let mut disp = PixelDisplay {
        px: vec![bg; (W * H) as usize],
    };
    let mut sink = DrawTargetSink::new(&mut disp);
    r.render::<STACK, _>(tree, f, &mut sink).expect("walk");
    assert!(sink.finish().is_ok());
    assert!(disp.px == fast_px, "{label}: DrawTarget path differs");

    // Bands, with working memory from none to all a frame needs (the
    // display list overflows and the renderer walks again, or draws a
    // band as it walks): the same pixels and counters.
    let need = memory_words_for(tree, fx.unwrap_or(Effects::from_bits(tree.effects())));
    for rows in [1u32, 8, 13, H] {
        for words in [0, 40, need / 3, need] {
            let mut memory = vec![0u32; words];
            let mut banded = vec![F::Word::default(); fast.len()];
            let stride = F::words_per_row(W);
            let mut buf = vec![F::Word::default(); stride * rows as usize];
            let band = BandBuffer::<F> {
                buf: &mut buf,
                rows,
                background: bg,
            };
            let s = r
                .render_banded_in::<STACK, F>(tree, f, band, &mut memory, |y0, b| {
                    let at = y0 as usize * stride;
                    banded[at..at + b.data().len()].copy_from_slice(b.data());
                })
                .expect("bands");
            assert!(
                banded == fast,
                "{label}: bands of {rows} rows, {words} words differ"
            );
            // (Spans may differ: a band cuts a polygon's run of rows.)
            let counts = |s: RenderStats| (s.drawn, s.invisible, s.skipped, s.clipped);
            assert_eq!(
                counts(s),
                counts(stats),
                "{label}: {rows} rows, {words} words"
            );
            if words == need {
                assert_eq!(s.walks, 1, "{label}: {rows} rows");
            }
        }
    }
    // The full frame with a vertex cache of any size: below the tree's
    // vertex count a tagged cache (1 word: none; 2: one entry, evicted by
    // nearly every vertex), then indexed.
    let verts = tree.vertex_count() as usize;
    for words in [1, 2, 3, 64, need / 5, verts - 1, verts, need] {
        let mut memory = vec![0u32; words];
        let mut cached = vec![F::Word::default(); fast.len()];
        let mut fb = Framebuffer::<F>::new(&mut cached, W, H).expect("fb");
        fb.fill_all(bg);
        r.render_cached::<STACK, _>(tree, f, &mut memory, &mut fb)
            .expect("walk");
        assert!(cached == fast, "{label}: cache of {words} words differs");
    }
    fast_px.iter().any(|&c| c != bg)
}

#[test]
fn framebuffer_draw_target_and_bands_agree() {
    for s in [scenes::house(), scenes::vise()] {
        let built = build_tree(&s.polygons, s.closed);
        let tree = Tree::from_bytes(&built.bytes).expect("tree");
        for (k, cam) in random_cameras(&s.polygons, 8, 5).iter().enumerate() {
            let f = frame(&tree, cam);
            // The tree's own effects, and every effect at once (outlines
            // cross band boundaries; clipping off drops polygons alike).
            for fx in [None, Some(Effects::ALL), Some(Effects::NONE)] {
                let label = format!("{} view {k} {fx:?}", s.name);
                paths::<Rgb565Format>(&tree, &f, fx, Rgb565::new(3, 7, 9), &label);
                // (The shaded picture may be all dark, i.e. all Off in mono.)
                assert!(
                    paths::<Rgb888Format>(&tree, &f, fx, Rgb888::new(10, 20, 30), &label),
                    "{label}: empty"
                );
                paths::<Gray8Format>(&tree, &f, fx, Gray8::new(17), &label);
                paths::<BinaryFormat>(&tree, &f, fx, BinaryColor::Off, &label);
            }
        }
    }
}

#[test]
fn fpt_render_ids_match_the_library() {
    let s = scenes::house();
    let built = build_tree(&s.polygons, s.closed);
    let tree = Tree::from_bytes(&built.bytes).expect("tree");
    let dir = std::env::temp_dir().join(format!("fpt-render-paths-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let tp = dir.join("house.fpt");
    std::fs::write(&tp, &built.bytes).expect("write");
    for (k, cam) in random_cameras(&s.polygons, 6, 9).iter().enumerate() {
        let mvp: Vec<String> = cam.mvp().iter().map(|v| format!("{v:e}")).collect();
        let (png, ids) = (dir.join(format!("{k}.png")), dir.join(format!("{k}.bin")));
        let args = [
            "fpt".to_string(),
            "render".into(),
            tp.to_string_lossy().into_owned(),
            "-o".into(),
            png.to_string_lossy().into_owned(),
            "--size".into(),
            format!("{W}x{H}"),
            "--mvp".into(),
            mvp.join(","),
            "--ids".into(),
            ids.to_string_lossy().into_owned(),
            // The library's default pipeline (`render_ids`) has no sliver
            // pass; `fpt render` draws slivers unless told not to.
            "--no-slivers".into(),
        ];
        assert_eq!(host_sim::cli::main_with_args(args), 0, "view {k}");
        let bytes = std::fs::read(&ids).expect("ids");
        let got: Vec<u32> = bytes
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        let want =
            render_ids::<DefaultPrecision>(&tree, &frame(&tree, cam), W as usize, H as usize);
        assert_eq!(got, want, "view {k}");
        assert!(want.iter().any(|&v| v != 0));
    }
    let _ = std::fs::remove_dir_all(&dir);
}
