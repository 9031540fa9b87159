//! Set-up shared by the benchmarks: the scenes built into tree files, the
//! cameras (the `fpt demo` views, z-up models), and the painter path as the
//! product runs it (`TreeRenderer` with the default fixed-point precision
//! into an RGB565 framebuffer).
//!
//! Everything here runs once before timing; what the benchmarks time is in
//! the closures they pass to criterion.

use std::collections::HashSet;
use std::time::Duration;

use criterion::Criterion;
use embedded_graphics::pixelcolor::{IntoStorage, Rgb565};
use fpt_nostd::order::Order;
use fpt_nostd::raster::{
    DefaultPrecision, Libm, Light, Orbit, Paint, RenderStats, Renderer, Rgb565Framebuffer, Scratch,
    SpanBounds, SpanSink,
};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{Frame, TreeRenderer};
use host_sim::build::{build, NoProgress};
use host_sim::scenes::Scene;
use host_sim::serialize::{serialize, SerializeOptions};
use host_sim::tree::Method;

/// The arithmetic of both paths: the product default (16.16 fixed-point
/// vertices, 4 sub-pixel bits).
pub type P = DefaultPrecision;
/// Vertex capacity of the per-polygon scratch (as `fpt render` uses).
pub const VERTS: usize = 64;
/// Walk stack capacity used while timing (the memory figures use the
/// tree's own depth instead: that is what firmware would allocate).
pub const STACK: usize = 256;
/// Background colour of every frame.
pub const BACKGROUND: Rgb565 = Rgb565::new(4, 8, 6);

/// An orbit view: yaw, pitch, vertical field of view (degrees), and the
/// distance in bounding radii.
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// Rotation about the up axis, degrees.
    pub yaw: f32,
    /// Elevation, degrees.
    pub pitch: f32,
    /// Vertical field of view, degrees (0 = parallel).
    pub fov: f32,
    /// Eye distance in bounding radii.
    pub distance: f32,
}

/// A scene, its tree file, and the view it is benchmarked from.
pub struct Bench {
    /// The input scene (what a z-buffer renderer would store).
    pub scene: Scene,
    /// The serialized static tree of the scene.
    pub bytes: Vec<u8>,
    /// The camera.
    pub view: View,
}

impl Bench {
    /// Builds and serializes the static tree of `scene` (seed 7, as the
    /// tests use).
    pub fn new(scene: Scene, view: View) -> Bench {
        let t = build(
            scene.polygons.clone(),
            scene.closed,
            Method::Static,
            7,
            &mut NoProgress,
        );
        let bytes = serialize(&t, &SerializeOptions::default()).expect("serialize the tree");
        Bench { scene, bytes, view }
    }

    /// The tree file, parsed.
    pub fn tree(&self) -> Tree<'_> {
        Tree::from_bytes(&self.bytes).expect("the serialized tree validates")
    }

    /// The frame of this bench's view in a `w × h` image.
    pub fn frame(&self, w: u32, h: u32) -> Frame {
        let tree = self.tree();
        let v = self.view;
        let r = tree.bounding_radius();
        let o = Orbit::new(
            [0.0; 3],
            v.yaw.to_radians(),
            v.pitch.to_radians(),
            v.distance * r,
            v.fov.to_radians(),
        );
        let mut cam = o.camera::<Libm>(w as f32 / h as f32);
        // The scenes are z-up, the orbit y-up: the same exact column
        // permutation as `fpt render --z-up`.
        for row in cam.matrix.0.iter_mut() {
            *row = [row[0], -row[2], row[1], row[3]];
        }
        Frame::relative(&tree, &cam)
    }
}

/// The three scenes with the views of `fpt demo`.
pub fn benches() -> Vec<Bench> {
    let view = |yaw, pitch, distance| View {
        yaw,
        pitch,
        fov: 40.0,
        distance,
    };
    vec![
        Bench::new(host_sim::scenes::bench_city(), view(25.0, 35.0, 1.9)),
        Bench::new(host_sim::scenes::vise(), view(35.0, 30.0, 3.0)),
        Bench::new(host_sim::scenes::house(), view(30.0, 20.0, 3.0)),
    ]
}

/// The light `fpt render` uses for `frame`.
pub fn light(frame: &Frame) -> Light {
    Light::new(frame.key_light(), 0.25, 0.75)
}

/// The painter path's renderer for `w × h`, lit as `fpt render` lights it.
pub fn painter(w: u32, h: u32, frame: &Frame) -> Box<TreeRenderer<P, VERTS>> {
    let mut tr = Box::new(TreeRenderer::<P, VERTS>::new(w, h).expect("renderer size"));
    tr.renderer.set_light(light(frame));
    tr
}

/// One painter frame: clear, walk, draw. Returns the renderer's counters.
pub fn paint(
    tr: &mut TreeRenderer<P, VERTS>,
    tree: &Tree<'_>,
    frame: &Frame,
    buf: &mut [u16],
    w: u32,
    h: u32,
) -> RenderStats {
    let mut fb = Rgb565Framebuffer::new(buf, w, h).expect("framebuffer size");
    fb.fill_all(BACKGROUND);
    tr.render::<STACK, _>(tree, frame, &mut fb)
        .expect("walk stack")
}

/// A sink that forwards to `inner` and counts the pixels it is given.
pub struct Counting<K> {
    /// The real target.
    pub inner: K,
    /// Pixels received so far.
    pub pixels: u64,
}

impl<K: SpanSink> SpanSink for Counting<K> {
    type Color = K::Color;
    fn color(&self, paint: &Paint) -> K::Color {
        self.inner.color(paint)
    }
    fn bounds(&self) -> SpanBounds {
        self.inner.bounds()
    }
    fn span(&mut self, y: i32, x0: i32, x1: i32, c: K::Color) {
        self.pixels += (x1 - x0).max(0) as u64;
        self.inner.span(y, x0, x1, c);
    }
}

/// Pixels the painter writes for one frame (overdraw included).
pub fn painted_pixels(b: &Bench, w: u32, h: u32) -> u64 {
    let tree = b.tree();
    let frame = b.frame(w, h);
    let mut tr = painter(w, h, &frame);
    let mut buf = vec![0u16; (w * h) as usize];
    let fb = Rgb565Framebuffer::new(&mut buf, w, h).expect("framebuffer size");
    let mut sink = Counting {
        inner: fb,
        pixels: 0,
    };
    tr.render::<STACK, _>(&tree, &frame, &mut sink)
        .expect("walk stack");
    sink.pixels
}

/// `c` as stored in an RGB565 framebuffer.
pub fn raw565(c: Rgb565) -> u16 {
    c.into_storage()
}

/// Bytes of the walk stack sized for `depth` frames (`Order<N>` with
/// `N = depth`), derived from two instances since `N` is a constant.
pub fn walk_stack_bytes(depth: u32) -> usize {
    let one = std::mem::size_of::<Order<'static, 1>>();
    let per = std::mem::size_of::<Order<'static, 2>>() - one;
    one - per + per * depth as usize
}

/// Bytes of the polygon renderer state plus its scratch, used by both paths.
pub fn pipeline_bytes() -> usize {
    std::mem::size_of::<Renderer<P>>() + std::mem::size_of::<Scratch<P, VERTS>>()
}

/// A compact mesh a z-buffer renderer would store for `scene`: unique
/// `f32` vertices (12 B), `u16` indices (2 B), and per face a normal
/// (12 B), a colour (3 B) and a vertex count (1 B).
pub fn mesh_bytes(scene: &Scene) -> usize {
    let mut unique = HashSet::new();
    let mut indices = 0usize;
    for p in &scene.polygons {
        indices += p.verts.len();
        for v in &p.verts {
            unique.insert([v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]);
        }
    }
    12 * unique.len() + 2 * indices + 16 * scene.polygons.len()
}

/// The criterion settings of the frame and fill benchmarks: 20 samples
/// after half a second of warm-up, two seconds of measurement each.
pub fn criterion() -> Criterion {
    Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}
