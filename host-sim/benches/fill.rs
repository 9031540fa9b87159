//! Fill rate of the scanline fill against plain memory writes of the same
//! pixels, into a 240×240 RGB565 framebuffer.
//!
//! Workloads (each a criterion group, throughput in pixels written, so
//! criterion's `thrpt` is pixels per second):
//! * `city_240x240`: the polygons of one painter frame of the benchmark
//!   city, already transformed, clipped, projected and shaded (captured
//!   once through the same vertex path as the renderer), in back-to-front
//!   order: many small polygons, overdraw included;
//! * `triangles_240x240`: 64 large random triangles;
//! * `fullscreen_quads_240x240`: 8 quads each covering the whole frame
//!   (the best case for per-span costs).
//!
//! Variants per group:
//! * `scanline_fill`: `fill_polygon` (edge setup, active-edge walk, spans)
//!   into an `Rgb565Framebuffer`;
//! * `span_memset`: the same spans, recorded beforehand, written with
//!   `slice::fill` into a plain `Vec<u16>`: the cost of the pixels alone;
//! * `frame_memset`: one `slice::fill` of the whole frame (throughput
//!   `W × H`): the memory bound;
//! * `painter_frame` (city only): the whole painter frame, clear + walk +
//!   transform + clip + shade + fill, per pixel written.
//!
//! Before timing, the captured city polygons are filled and must give the
//! painter's picture exactly (so the capture is the renderer's work).
//!
//! Run: `cargo bench -p host-sim --features bench --bench fill`; the check alone, each
//! benchmark run once: `cargo bench -p host-sim --features bench --bench fill -- --test`.

#[allow(dead_code)] // each benchmark uses a part of it
mod common;

use std::hint::black_box;

use common::{Bench, BACKGROUND, P, STACK, VERTS};
use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use fpt_nostd::order::for_each_polygon_back_to_front;
use fpt_nostd::raster::clip::{clip_polygon, ClipVert};
use fpt_nostd::raster::edge::Edge;
use fpt_nostd::raster::shade::{shade, ShadeMode};
use fpt_nostd::raster::transform::VertexPath;
use fpt_nostd::raster::{
    fill_polygon, FillRule, Paint, Precision, Rgb565Framebuffer, ScreenPt, SpanBounds, SpanSink,
    Viewport,
};

const W: u32 = 240;
const H: u32 = 240;

type Path = <P as Precision>::Path;
type Clip = ClipVert<<Path as VertexPath>::Scalar>;

/// A polygon ready for the scanline fill.
struct ScreenPoly {
    pts: Vec<ScreenPt>,
    color: Rgb565,
}

/// The polygons of one painter frame of `b`, back to front, through the
/// renderer's own vertex path (transform, clip, project) and shading.
fn capture(b: &Bench) -> Vec<ScreenPoly> {
    let tree = b.tree();
    let frame = b.frame(W, H);
    let light = common::light(&frame);
    let m = Path::prepare(&frame.camera.matrix);
    let near = Path::near(&m, frame.camera.near_w);
    let vp = Viewport::new(W, H, P::SUB_BITS).expect("viewport");
    let view = frame.view.local(&tree);
    let two_sided = !tree.is_closed();
    let s = frame.vertex_scale;
    let mut out = Vec::new();
    for_each_polygon_back_to_front::<STACK>(&tree, frame.view, |p| {
        let clip: Option<Vec<Clip>> = p
            .vertices()
            .map(|v| Path::transform(&m, [v[0] * s, v[1] * s, v[2] * s]))
            .collect();
        let Some(mut a) = clip else { return };
        let n = a.len();
        // Clipping adds at most one vertex per plane (5) to a convex polygon.
        a.resize(n + 8, Clip::default());
        let mut scratch = vec![Clip::default(); n + 8];
        let Ok(c) = clip_polygon(&mut a, n, &mut scratch, near) else {
            return;
        };
        if c.verts.len() < 3 {
            return;
        }
        let pts: Option<Vec<ScreenPt>> = c.verts.iter().map(|v| Path::project(v, &vp)).collect();
        let Some(pts) = pts else { return };
        let plane = p.plane();
        let normal = if two_sided && !view.is_backward(&plane) {
            plane.normal.map(|c| -c)
        } else {
            plane.normal
        };
        let rgb = shade(ShadeMode::default(), &light, normal, p.color());
        out.push(ScreenPoly {
            pts,
            color: Rgb565::from(rgb),
        });
    })
    .expect("walk stack");
    out
}

/// Scanline-fills `polys` into `fb`; returns the spans emitted.
fn fill_all<K: SpanSink<Color = Rgb565>>(
    polys: &[ScreenPoly],
    edges: &mut [Edge],
    active: &mut [u16],
    sink: &mut K,
) -> usize {
    let clip = SpanBounds::of_size(W, H);
    let mut spans = 0;
    for p in polys {
        spans += fill_polygon(
            &p.pts,
            P::SUB_BITS,
            FillRule::NonZero,
            &clip,
            edges,
            active,
            p.color,
            sink,
        )
        .expect("scratch capacity");
    }
    spans
}

/// A recorded span: row, columns, raw colour.
#[derive(Clone, Copy)]
struct Span {
    y: u32,
    x0: u32,
    x1: u32,
    c: u16,
}

/// Records spans instead of painting them.
struct Recorder(Vec<Span>);

impl SpanSink for Recorder {
    type Color = Rgb565;
    fn color(&self, paint: &Paint) -> Rgb565 {
        Rgb565::from(paint.rgb)
    }
    fn bounds(&self) -> SpanBounds {
        SpanBounds::of_size(W, H)
    }
    fn span(&mut self, y: i32, x0: i32, x1: i32, c: Rgb565) {
        self.0.push(Span {
            y: y as u32,
            x0: x0 as u32,
            x1: x1 as u32,
            c: common::raw565(c),
        });
    }
}

/// `span_memset`'s work: each span as one `slice::fill`.
fn replay(spans: &[Span], buf: &mut [u16]) {
    for s in spans {
        let row = (s.y * W) as usize;
        buf[row + s.x0 as usize..row + s.x1 as usize].fill(s.c);
    }
}

/// Deterministic pseudo-random numbers (64-bit LCG, high bits).
struct Lcg(u64);

impl Lcg {
    fn below(&mut self, n: u32) -> i32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 33) % u64::from(n)) as i32
    }
}

/// Sub-pixel coordinates of the point `(x, y)` in pixels.
fn pt(x: i32, y: i32) -> ScreenPt {
    ScreenPt {
        x: x << P::SUB_BITS,
        y: y << P::SUB_BITS,
    }
}

/// 64 triangles with vertices anywhere in a margin of 48 px around the
/// frame (most cover a large part of it), random colours.
fn triangles() -> Vec<ScreenPoly> {
    let mut r = Lcg(0x5eed);
    let margin = 48 << P::SUB_BITS;
    (0..64)
        .map(|_| {
            let mut v = || ScreenPt {
                x: r.below((W + 96) << P::SUB_BITS) - margin,
                y: r.below((H + 96) << P::SUB_BITS) - margin,
            };
            let pts = vec![v(), v(), v()];
            let c = r.below(0x10000) as u16;
            ScreenPoly {
                pts,
                color: Rgb565::from(RawU16::new(c)),
            }
        })
        .collect()
}

/// 8 quads each exactly covering the frame.
fn fullscreen_quads() -> Vec<ScreenPoly> {
    (0..8u16)
        .map(|k| ScreenPoly {
            pts: vec![
                pt(0, 0),
                pt(0, H as i32),
                pt(W as i32, H as i32),
                pt(W as i32, 0),
            ],
            color: Rgb565::from(RawU16::new(0x1234 + k)),
        })
        .collect()
}

/// The `scanline_fill`, `span_memset` and `frame_memset` variants of one
/// workload; returns the pixels it writes.
fn fill_variants(g: &mut BenchmarkGroup<'_, WallTime>, polys: &[ScreenPoly]) -> u64 {
    let mut edges = vec![Edge::default(); VERTS];
    let mut active = vec![0u16; VERTS];
    let mut rec = Recorder(Vec::new());
    fill_all(polys, &mut edges, &mut active, &mut rec);
    let spans = rec.0;
    let pixels: u64 = spans.iter().map(|s| u64::from(s.x1 - s.x0)).sum();
    let mut buf = vec![0u16; (W * H) as usize];

    g.throughput(Throughput::Elements(pixels));
    g.bench_function("scanline_fill", |b| {
        b.iter(|| {
            let mut fb = Rgb565Framebuffer::new(&mut buf, W, H).expect("framebuffer");
            fill_all(polys, &mut edges, &mut active, &mut fb)
        })
    });
    g.bench_function("span_memset", |b| {
        b.iter(|| replay(black_box(&spans), &mut buf))
    });
    g.throughput(Throughput::Elements(u64::from(W * H)));
    g.bench_function("frame_memset", |b| {
        b.iter(|| black_box(&mut buf[..]).fill(black_box(0x5aa5)))
    });
    eprintln!(
        "{} polygons, {} spans, {} pixels written ({:.2} per frame pixel, {:.1} per span)",
        polys.len(),
        spans.len(),
        pixels,
        pixels as f64 / f64::from(W * H),
        pixels as f64 / spans.len().max(1) as f64
    );
    pixels
}

fn fill_rate(c: &mut Criterion) {
    let city = common::benches()
        .into_iter()
        .next()
        .expect("the city comes first");
    let polys = capture(&city);

    // The capture must be exactly the painter's work.
    let tree = city.tree();
    let frame = city.frame(W, H);
    let mut tr = common::painter(W, H, &frame);
    let mut painted = vec![0u16; (W * H) as usize];
    common::paint(&mut tr, &tree, &frame, &mut painted, W, H);
    let mut replayed = vec![0u16; (W * H) as usize];
    {
        let mut fb = Rgb565Framebuffer::new(&mut replayed, W, H).expect("framebuffer");
        fb.fill_all(BACKGROUND);
        let mut edges = vec![Edge::default(); VERTS];
        let mut active = vec![0u16; VERTS];
        fill_all(&polys, &mut edges, &mut active, &mut fb);
    }
    assert!(
        replayed == painted,
        "the captured polygons do not reproduce the painter frame"
    );

    let mut g = c.benchmark_group(format!("fill/city_{W}x{H}"));
    eprint!("city: ");
    let pixels = fill_variants(&mut g, &polys);
    g.throughput(Throughput::Elements(pixels));
    g.bench_function("painter_frame", |b| {
        b.iter(|| common::paint(&mut tr, &tree, &frame, &mut painted, W, H))
    });
    g.finish();

    let mut g = c.benchmark_group(format!("fill/triangles_{W}x{H}"));
    eprint!("triangles: ");
    fill_variants(&mut g, &triangles());
    g.finish();

    let mut g = c.benchmark_group(format!("fill/fullscreen_quads_{W}x{H}"));
    eprint!("fullscreen quads: ");
    fill_variants(&mut g, &fullscreen_quads());
    g.finish();
}

criterion_group! {
    name = benches;
    config = common::criterion();
    targets = fill_rate
}
criterion_main!(benches);
