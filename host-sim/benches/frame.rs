//! Frame time of the painter path (priority-tree walk, back to front, with
//! overdraw, no depth buffer) against a z-buffer path built from the same
//! pipeline (input faces in input order, back faces culled by the same
//! test, a `u16` depth buffer cleared and tested per pixel; see
//! `common/zbuf.rs`), on the city, the vise and the house at 240×240 and
//! 320×240 RGB565. A third variant is the painter drawing through a
//! 16-row band buffer instead of a full framebuffer.
//!
//! Before timing, each configuration is checked: the z-buffer picture
//! must agree with the painter's on at least 99 % of the pixels (both
//! paths cover exactly the same pixels; they may differ only where depth
//! quantisation decides an interpenetration), no face may lie behind the
//! eye, and the banded picture must equal the full-frame one exactly. A
//! table of the memory each path needs and of the work per frame is
//! printed to stderr.
//!
//! Run: `cargo bench -p host-sim --features bench --bench frame` (about 1.5 minutes); the
//! checks alone, each benchmark run once: `cargo bench -p host-sim --features bench --bench
//! frame -- --test`.

#[allow(dead_code)] // each benchmark uses a part of it
mod common;
#[path = "common/zbuf.rs"]
mod zbuf;

use std::hint::black_box;

use common::{Bench, BACKGROUND, STACK};
use criterion::{criterion_group, criterion_main, Criterion};
use fpt_nostd::raster::framebuffer::Rgb565Format;
use fpt_nostd::render::BandBuffer;
use zbuf::{ZMesh, ZRenderer, ZTarget};

/// Image sizes compared.
const SIZES: [(u32, u32); 2] = [(240, 240), (320, 240)];
/// Rows per band of the banded painter.
const BAND_ROWS: u32 = 16;

/// The painter picture drawn band by band, put together.
fn banded_picture(b: &Bench, w: u32, h: u32) -> Vec<u16> {
    let tree = b.tree();
    let frame = b.frame(w, h);
    let mut tr = common::painter(w, h, &frame);
    let mut band = vec![0u16; (w * BAND_ROWS) as usize];
    let mut out = vec![0u16; (w * h) as usize];
    let bb = BandBuffer::<Rgb565Format> {
        buf: &mut band,
        rows: BAND_ROWS,
        background: BACKGROUND,
    };
    tr.render_banded::<STACK, _>(&tree, &frame, bb, |y0, fb| {
        let at = y0 as usize * w as usize;
        let data = fb.data();
        out[at..at + data.len()].copy_from_slice(data);
    })
    .expect("walk stack");
    out
}

/// Checks one configuration (see the module docs) and prints its row.
fn check(b: &Bench, w: u32, h: u32) {
    let tree = b.tree();
    let frame = b.frame(w, h);
    let n = (w * h) as usize;
    let mut tr = common::painter(w, h, &frame);
    let mut painted = vec![0u16; n];
    let ps = common::paint(&mut tr, &tree, &frame, &mut painted, w, h);
    let bg = common::raw565(BACKGROUND);
    let covered = painted.iter().filter(|&&c| c != bg).count();
    assert!(
        covered > n / 20,
        "{}: the view shows almost nothing",
        b.scene.name
    );
    assert!(
        banded_picture(b, w, h) == painted,
        "{}: banded picture differs from the full frame",
        b.scene.name
    );

    let mesh = ZMesh::new(&b.scene, tree.origin());
    let mut zr = ZRenderer::new(w, h, &frame);
    let (mut color, mut depth) = (vec![0u16; n], vec![0u16; n]);
    let mut t = ZTarget::new(&mut color, &mut depth, w, h);
    let zs = zr.draw(
        &mesh,
        &frame,
        &frame.view.local(&tree),
        tree.bounding_radius(),
        &mut t,
        bg,
    );
    let same = painted.iter().zip(&color).filter(|(a, b)| a == b).count();
    let agree = same as f64 / n as f64;
    assert_eq!(zs.behind, 0, "{}: a face behind the eye", b.scene.name);
    assert_eq!(
        ps.skipped + zr.skipped(),
        0,
        "{}: skipped polygons",
        b.scene.name
    );
    assert!(
        agree >= 0.99,
        "{}: z-buffer and painter agree on only {:.3} % of the pixels",
        b.scene.name,
        100.0 * agree
    );

    let painter_px = common::painted_pixels(b, w, h);
    let walk = common::walk_stack_bytes(tree.max_depth());
    let pipe = common::pipeline_bytes();
    let fb = 2 * n;
    let band = 2 * (w * BAND_ROWS) as usize;
    eprintln!(
        "{:<10} {:>3}x{:<3} | {:>5} faces {:>6} B mesh | {:>5} polys {:>6} B tree, depth {:>3} \
         | drawn: painter {:>4} polys, z-buffer {:>4} faces ({} culled) \
         | painter {:>6} B (fb {} + walk {} + pipe {}), banded {:>5} B | z-buffer {:>6} B \
         (fb {} + depth {} + pipe {}) | covered {:>5} px, painter writes {:>6} px ({:.2}x), \
         z tests {:>6} writes {:>6} px | agree {:.2} %",
        b.scene.name,
        w,
        h,
        mesh.len(),
        common::mesh_bytes(&b.scene),
        tree.polygon_count(),
        b.bytes.len(),
        tree.max_depth(),
        ps.drawn,
        zr.drawn(),
        zs.culled,
        fb + walk + pipe,
        fb,
        walk,
        pipe,
        band + walk + pipe,
        fb + fb + pipe,
        fb,
        fb,
        pipe,
        covered,
        painter_px,
        painter_px as f64 / covered as f64,
        zs.tested,
        zs.written,
        100.0 * agree,
    );
}

fn frame_time(c: &mut Criterion) {
    let benches = common::benches();
    for b in &benches {
        for (w, h) in SIZES {
            check(b, w, h);
        }
    }
    for b in &benches {
        for (w, h) in SIZES {
            let tree = b.tree();
            let frame = b.frame(w, h);
            let view = frame.view.local(&tree);
            let radius = tree.bounding_radius();
            let n = (w * h) as usize;
            let bg = common::raw565(BACKGROUND);
            let mesh = ZMesh::new(&b.scene, tree.origin());
            let mut tr = common::painter(w, h, &frame);
            let mut zr = ZRenderer::new(w, h, &frame);
            let (mut color, mut depth) = (vec![0u16; n], vec![0u16; n]);
            let mut band = vec![0u16; (w * BAND_ROWS) as usize];

            let mut g = c.benchmark_group(format!("frame/{}_{w}x{h}", b.scene.name));
            g.bench_function("painter", |bch| {
                bch.iter(|| common::paint(&mut tr, &tree, &frame, &mut color, w, h))
            });
            g.bench_function("painter_band16", |bch| {
                bch.iter(|| {
                    let bb = BandBuffer::<Rgb565Format> {
                        buf: &mut band,
                        rows: BAND_ROWS,
                        background: BACKGROUND,
                    };
                    // A display driver would send each band out here.
                    tr.render_banded::<STACK, _>(&tree, &frame, bb, |_, fb| {
                        black_box(fb.data());
                    })
                    .expect("walk stack")
                })
            });
            g.bench_function("zbuffer", |bch| {
                bch.iter(|| {
                    let mut t = ZTarget::new(&mut color, &mut depth, w, h);
                    zr.draw(&mesh, &frame, &view, radius, &mut t, bg)
                })
            });
            g.finish();
        }
    }
}

criterion_group! {
    name = benches;
    config = common::criterion();
    targets = frame_time
}
criterion_main!(benches);
