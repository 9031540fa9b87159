//! The measurements of the accuracy study: cases, views, configurations,
//! error counts against the float64 reference, host timing.
//!
//! Definitions (per configuration, summed over every case and view):
//! * the **reference** of a view is [`zbuffer`] of the case's *input*
//!   polygons (not the tree's split pieces) through the exact `f64` orbit
//!   matrix [`orbit_rows`], back faces culled for closed cases as the walk
//!   does; its polygon ids are mapped to source ids (`source + 1`, 0 for
//!   background), which is what `fpt render --ids` writes;
//! * `wrong_face` counts every pixel whose rendered source id differs from
//!   the reference's; `wrong_face_frac = wrong_face / pixels`;
//! * `wrong_sure` counts the differing pixels the reference is sure of (not
//!   within 0.5 px of a relevant outline, no depth tie:
//!   [`RefFrame::unsure`]); `wrong_pixel_frac = wrong_sure / sure`: errors
//!   that rounding at an outline cannot explain;
//! * `max_vertex_err_px`: over every vertex of the tree whose exact
//!   projection lies inside the image and in front of the eye, the largest
//!   distance in pixels between the configuration's screen position (the
//!   renderer's own [`VertexPath`] transform and projection, snapped to its
//!   sub-pixel grid, of the stored vertex) and the exact `f64` projection
//!   of the builder's `f64` vertex.

use crate::build::{build, NoProgress, DEFAULT_SEED};
use crate::cli::render::{render_job, resolve_precision, CameraSpec, Format, Job, Look};
use crate::cli::CliError;
use crate::cli_err;
use crate::geom::Polygon;
use crate::reference::{zbuffer, Camera, RefFrame, RefOptions};
use crate::serialize::{polygon_order, serialize, SerializeOptions};
use crate::tree::Method;
use embedded_graphics::pixelcolor::Rgb888;
use fpt_nostd::effects::AllEffects;
use fpt_nostd::format::VertexFormat;
use fpt_nostd::raster::clip::ClipVert;
use fpt_nostd::raster::framebuffer::Rgb565Format;
use fpt_nostd::raster::int_path::q16_camera;
use fpt_nostd::raster::transform::{VertexPath, Viewport};
use fpt_nostd::raster::{
    FixedMicromath, FixedPrecision, FloatLibm, FloatMicromath, Framebuffer, IdBuffer, IntPrecision,
    Light, Precision, ShadeMode, SpanSink,
};
use fpt_nostd::reader::{PolygonRef, RawVertex, Tree};
use fpt_nostd::render::{draw_frame, FaceIds, Frame, TreeRenderer};
use glam::DVec3;
use std::time::Instant;

/// Vertical field of view of every view, degrees.
pub const FOV_DEG: f64 = 40.0;

/// One row of the study: what it renders with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Config {
    /// Row name in the CSV (also accepted by `fpt render --precision`
    /// unless it is a `vertex-*` row).
    pub name: &'static str,
    /// The `fpt render --precision` name it renders with.
    pub precision: &'static str,
    /// Vertex storage of the tree file.
    pub vertex: VertexFormat,
    /// The camera is the orbit built with the configuration's trigonometry
    /// (`fpt render --yaw --pitch`) instead of the exact matrix (`--mvp`).
    pub orbit_trig: bool,
    /// The q16 tree's vertices are drawn as stored, not decoded to `f32`
    /// (the integer path's raw q16 input, `VertexPath::RAW_Q16_FRAC`): not a `fpt render` mode.
    pub raw_q16: bool,
}

const fn row(name: &'static str, precision: &'static str) -> Config {
    Config {
        name,
        precision,
        vertex: VertexFormat::F32,
        orbit_trig: false,
        raw_q16: false,
    }
}

/// The rows, in CSV order. `fixed` is the default configuration (the
/// reference of `host_rel_time`); `vertex-f32`, `subpx-4` and `trig-libm`
/// render with the same arithmetic and differ only in what they vary;
/// `int` and `int-q16` are the integer vertex path on the `f32` tree and
/// on the q16 tree drawn as stored.
pub const CONFIGS: [Config; 15] = [
    Config {
        vertex: VertexFormat::F32,
        ..row("vertex-f32", "fixed-subpx-4")
    },
    Config {
        vertex: VertexFormat::Q16,
        ..row("vertex-q16", "fixed-subpx-4")
    },
    Config {
        vertex: VertexFormat::Q32,
        ..row("vertex-q32", "fixed-subpx-4")
    },
    row("fixed", "fixed-subpx-4"),
    row("f32-libm", "f32-libm-subpx-4"),
    row("f32-micromath", "f32-micromath-subpx-4"),
    row("subpx-0", "fixed-subpx-0"),
    row("subpx-2", "fixed-subpx-2"),
    row("subpx-4", "fixed-subpx-4"),
    row("subpx-6", "fixed-subpx-6"),
    row("subpx-8", "fixed-subpx-8"),
    Config {
        orbit_trig: true,
        ..row("trig-libm", "fixed-subpx-4")
    },
    Config {
        orbit_trig: true,
        ..row("trig-micromath", "fixed-micromath-subpx-4")
    },
    row("int", "int-subpx-4"),
    Config {
        vertex: VertexFormat::Q16,
        raw_q16: true,
        ..row("int-q16", "int-subpx-4")
    },
];

/// The default configuration's row name.
pub const DEFAULT_CONFIG: &str = "fixed";

/// An orbit view: degrees about the y axis and of elevation, at 3× the
/// bounding radius from the tree's centre, [`FOV_DEG`] field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewSpec {
    /// Degrees about the y axis.
    pub yaw: f64,
    /// Degrees of elevation.
    pub pitch: f64,
}

/// `n` views from a fixed seed: yaw in [0, 360), pitch in [−60, 60].
pub fn views(n: usize) -> Vec<ViewSpec> {
    let mut s: u64 = 0x00AC_C0DE;
    let mut next = move || {
        // SplitMix64: deterministic and well spread.
        s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = s;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let yaw = (360.0 * next()).round();
            let pitch = (120.0 * next() - 60.0).round();
            ViewSpec { yaw, pitch }
        })
        .collect()
}

/// The file options of the study's trees (its cases' and the firmware's
/// `bench_city.*.fpt`): the configuration's vertex encoding and narrow
/// records without the plane table, pinned rather than the default file
/// options so that the study's figures (its `m0_instr` column) do not
/// move when the defaults do; the records change no picture.
pub fn tree_options(vertex_format: VertexFormat) -> SerializeOptions {
    SerializeOptions {
        vertex_format,
        compact: true,
        narrow: true,
        plane_table: false,
        compact_planes: false,
        ..SerializeOptions::default()
    }
}

/// One model: its input polygons, and its tree in every vertex format.
#[derive(Clone, Debug)]
pub struct Case {
    /// Scene or file name.
    pub name: String,
    /// The input polygons (`source` = input face index).
    pub polygons: Vec<Polygon>,
    /// Closed volume (back faces culled).
    pub closed: bool,
    /// Tree file bytes per vertex format, in [`VertexFormat::ALL`] order.
    pub trees: Vec<(VertexFormat, Vec<u8>)>,
    /// The builder's exact vertices of every file polygon, by file id.
    pub exact: Vec<Vec<DVec3>>,
}

impl Case {
    /// Builds `polygons` (static method, default seed) and serializes the
    /// tree in every vertex format.
    pub fn new(name: &str, polygons: Vec<Polygon>, closed: bool) -> Result<Case, CliError> {
        let tree = build(
            polygons.clone(),
            closed,
            Method::Static,
            DEFAULT_SEED,
            &mut NoProgress,
        );
        let order = polygon_order(&tree).map_err(|e| cli_err!("{name}: {e}"))?;
        let exact = order
            .iter()
            .map(|&t| {
                tree.polygons
                    .get(t as usize)
                    .map(|p| p.verts.clone())
                    .ok_or_else(|| cli_err!("{name}: bad polygon order"))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut trees = Vec::new();
        for vertex_format in VertexFormat::ALL {
            let opts = tree_options(vertex_format);
            let bytes = serialize(&tree, &opts).map_err(|e| cli_err!("{name}: {e}"))?;
            trees.push((vertex_format, bytes));
        }
        Ok(Case {
            name: name.to_string(),
            polygons,
            closed,
            trees,
            exact,
        })
    }

    /// The tree file of vertex format `f`.
    pub fn tree_bytes(&self, f: VertexFormat) -> Result<&[u8], CliError> {
        self.trees
            .iter()
            .find(|(g, _)| *g == f)
            .map(|(_, b)| b.as_slice())
            .ok_or_else(|| cli_err!("{}: no {} tree", self.name, f.name()))
    }
}

/// The exact `f64` model → clip matrix (row-major) of `view` for `tree` in
/// a `w × h` image: the orbit `fpt render --yaw --pitch --fov 40` builds in
/// `f32` ([`fpt_nostd::raster::Orbit::camera`]), computed in `f64` around
/// the tree's centre in model coordinates.
pub fn orbit_rows(tree: &Tree<'_>, view: ViewSpec, w: u32, h: u32) -> [[f64; 4]; 4] {
    let r = tree.bounding_radius();
    let r = if r.is_finite() && r > 0.0 { r } else { 1.0 };
    // The same f32 values the renderer's orbit starts from.
    let dist32 = 3.0 * r;
    let (dist, near, far) = (
        f64::from(dist32),
        f64::from(dist32 * 1e-3),
        f64::from(dist32 * 1e3),
    );
    let (sy, cy) = view.yaw.to_radians().sin_cos();
    let (sp, cp) = view.pitch.to_radians().sin_cos();
    let t = tree.origin();
    let right = [cy, 0.0, -sy];
    let up = [-sy * sp, cp, -cy * sp];
    let fwd = [-cp * sy, -sp, -cp * cy];
    let eye = [0, 1, 2].map(|i| t[i] - dist * fwd[i]);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let rowv = |a: [f64; 3]| [a[0], a[1], a[2], -dot(a, eye)];
    let (xr, yr, dr) = (rowv(right), rowv(up), rowv(fwd));
    let aspect = f64::from(w) / f64::from(h);
    let focal = 1.0 / (0.5 * FOV_DEG.to_radians()).tan();
    let a = (far + near) / (far - near);
    let b = -2.0 * far * near / (far - near);
    let sc = |k: f64, r: [f64; 4], c: f64| [k * r[0], k * r[1], k * r[2], k * r[3] + c];
    [
        sc(focal / aspect, xr, 0.0),
        sc(focal, yr, 0.0),
        sc(a, dr, b),
        dr,
    ]
}

/// The reference camera of row-major rows `r`.
pub fn reference_camera(r: &[[f64; 4]; 4]) -> Result<Camera, CliError> {
    let mut flat = [0.0; 16];
    for (i, v) in flat.iter_mut().enumerate() {
        *v = r[i / 4][i % 4];
    }
    Camera::from_mvp(flat).ok_or_else(|| cli_err!("singular view matrix"))
}

/// The reference picture of `case` through `cam`, with ids mapped to
/// source ids (`source + 1`, 0 = background).
pub fn reference_frame(case: &Case, cam: &Camera, w: u32, h: u32) -> RefFrame {
    let opt = RefOptions {
        cull_backfaces: case.closed,
        ..RefOptions::default()
    };
    let mut f = zbuffer(&case.polygons, cam, w as usize, h as usize, opt);
    for id in f.ids.iter_mut() {
        if *id > 0 {
            *id = case
                .polygons
                .get(*id as usize - 1)
                .map_or(u32::MAX, |p| p.source + 1);
        }
    }
    f
}

/// Error counts of one or more views (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Counts {
    /// Pixels compared.
    pub pixels: u64,
    /// Pixels showing another source face than the reference.
    pub wrong_face: u64,
    /// Pixels the reference is sure of.
    pub sure: u64,
    /// Sure pixels showing another source face.
    pub wrong_sure: u64,
    /// Largest vertex position error, pixels.
    pub max_vertex_err_px: f64,
}

impl Counts {
    /// Adds `o` to these counts (the maximum for the vertex error).
    pub fn add(&mut self, o: &Counts) {
        self.pixels += o.pixels;
        self.wrong_face += o.wrong_face;
        self.sure += o.sure;
        self.wrong_sure += o.wrong_sure;
        self.max_vertex_err_px = self.max_vertex_err_px.max(o.max_vertex_err_px);
    }

    /// `wrong_sure / sure` (0 when nothing is sure).
    pub fn wrong_pixel_frac(&self) -> f64 {
        ratio(self.wrong_sure, self.sure)
    }

    /// `wrong_face / pixels` (0 when there are none).
    pub fn wrong_face_frac(&self) -> f64 {
        ratio(self.wrong_face, self.pixels)
    }
}

fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 {
        0.0
    } else {
        a as f64 / b as f64
    }
}

/// The pixel counts of source ids `ids` against `reference` (no vertex
/// error). Fails when the sizes differ.
pub fn compare_ids(reference: &RefFrame, ids: &[u32]) -> Result<Counts, CliError> {
    if ids.len() != reference.ids.len() {
        return Err(cli_err!(
            "{} ids for a {}x{} reference",
            ids.len(),
            reference.w,
            reference.h
        ));
    }
    let mut c = Counts::default();
    for (i, (&want, &got)) in reference.ids.iter().zip(ids).enumerate() {
        c.pixels += 1;
        let wrong = want != got;
        c.wrong_face += u64::from(wrong);
        if !reference.unsure(i) {
            c.sure += 1;
            c.wrong_sure += u64::from(wrong);
        }
    }
    Ok(c)
}

/// The camera `config` renders `view` with.
pub fn camera_spec(config: &Config, tree: &Tree<'_>, view: ViewSpec, w: u32, h: u32) -> CameraSpec {
    if config.orbit_trig {
        CameraSpec::Orbit {
            yaw: view.yaw,
            pitch: view.pitch,
            distance: None,
            fov: FOV_DEG,
            up: fpt_nostd::format::UpAxis::Y,
        }
    } else {
        CameraSpec::Mvp(orbit_rows(tree, view, w, h))
    }
}

/// The job of a measurement: rgb565, lambert shading, black background,
/// full-frame path, optionally with ids, no sliver pass (the study measures
/// the plain pipeline, which is what a firmware runs by default).
pub fn job(camera: CameraSpec, w: u32, h: u32, ids: bool) -> Job {
    Job {
        w,
        h,
        camera,
        format: Format::Rgb565,
        band: None,
        look: Look {
            background: Rgb888::new(0, 0, 0),
            shade: ShadeMode::Lambert,
            slivers: false,
        },
        ids,
        effects: None,
        gray_levels: None,
    }
}

/// The counts of `config` on one view of `case`, given the view's
/// reference picture and exact camera; also returns the rendered ids.
pub fn view_counts(
    case: &Case,
    config: &Config,
    view: ViewSpec,
    reference: &RefFrame,
    cam: &Camera,
) -> Result<(Counts, Vec<u32>), CliError> {
    let (w, h) = (reference.w as u32, reference.h as u32);
    let bytes = case.tree_bytes(config.vertex)?;
    let tree = Tree::from_bytes(bytes).map_err(|e| cli_err!("{}: {e}", case.name))?;
    let spec = camera_spec(config, &tree, view, w, h);
    let ids = if config.raw_q16 {
        render_raw_q16(&tree, &job(spec, w, h, true))?
    } else {
        render_job(&tree, &job(spec, w, h, true), config.precision)?.ids
    };
    let mut c = compare_ids(reference, &ids)?;
    c.max_vertex_err_px = if config.raw_q16 {
        max_vertex_error_raw_q16(&tree, &spec, &case.exact, cam, w, h)?
    } else {
        vertex_error(config.precision, &tree, &spec, &case.exact, cam, w, h)?
    };
    Ok((c, ids))
}

/// The integer path of the `raw_q16` rows.
type RawQ16 = IntPrecision<4>;

/// [`render_job`] for a `raw_q16` row (rgb565 only, full frame): the
/// picture with the q16 tree's vertices as stored (the integer path's
/// `VertexPath::RAW_Q16_FRAC`);
/// returns the ids when the job asks for them.
pub fn render_raw_q16(tree: &Tree<'_>, job: &Job) -> Result<Vec<u32>, CliError> {
    type P = RawQ16;
    let (w, h) = (job.w, job.h);
    let mut tr = Box::new(
        TreeRenderer::<P, RAW_VERTS>::new(w, h).ok_or_else(|| cli_err!("bad size {w}x{h}"))?,
    );
    let frame = job.camera.frame::<<P as Precision>::Math>(tree, w, h);
    tr.renderer.set_shade_mode(job.look.shade);
    tr.renderer
        .set_light(Light::new(frame.key_light(), 0.25, 0.75));
    tr.renderer.set_effects(job.effects);
    let mut px = vec![0u16; Framebuffer::<Rgb565Format>::required_len(w, h)];
    let mut fb = Framebuffer::<Rgb565Format>::new(&mut px, w, h)
        .map_err(|e| cli_err!("framebuffer: {e:?}"))?;
    fb.fill_all(job.look.background.into());
    fn draw<K: SpanSink>(
        tr: &mut TreeRenderer<RawQ16, RAW_VERTS>,
        tree: &Tree<'_>,
        frame: &Frame,
        sink: &mut K,
    ) -> Result<(), CliError> {
        // The integer path draws a q16 tree's vertices as stored
        // (`VertexPath::RAW_Q16_FRAC`).
        draw_frame::<RawQ16, RAW_STACK, RAW_VERTS, AllEffects, _>(
            tree,
            frame,
            &mut tr.renderer,
            &mut tr.scratch,
            FaceIds::Source,
            sink,
        )
        .map(|_| ())
        .map_err(|e| cli_err!("{e}"))
    }
    draw(&mut tr, tree, &frame, &mut fb)?;
    std::hint::black_box(&px);
    let mut ids = Vec::new();
    if job.ids {
        ids = vec![0u32; w as usize * h as usize];
        let mut sink = IdBuffer::new(&mut ids, w, h).map_err(|e| cli_err!("id buffer: {e:?}"))?;
        draw(&mut tr, tree, &frame, &mut sink)?;
    }
    Ok(ids)
}

/// Vertex capacity and walk stack of [`render_raw_q16`] (as `fpt render`).
const RAW_VERTS: usize = 256;
const RAW_STACK: usize = 4096;

/// [`max_vertex_error`] of a `raw_q16` row: the stored q16 values through
/// the integer path's [`q16_camera`] of the frame.
pub fn max_vertex_error_raw_q16(
    tree: &Tree<'_>,
    spec: &CameraSpec,
    exact: &[Vec<DVec3>],
    cam: &Camera,
    w: u32,
    h: u32,
) -> Result<f64, CliError> {
    type P = RawQ16;
    let frame: Frame = spec.frame::<<P as Precision>::Math>(tree, w, h);
    let qc = q16_camera(&frame.camera, frame.vertex_scale, tree.half_extent(), 1);
    let m = <P as Precision>::Path::prepare(&qc.matrix);
    vertex_error_with::<P>(tree, exact, cam, w, h, |p, i| match p.vertex_raw(i) {
        RawVertex::Q16(q) => <P as Precision>::Path::transform_q(&m, q.map(i32::from), 1),
        _ => None,
    })
}

/// [`max_vertex_error`] for a precision name.
fn vertex_error(
    name: &str,
    tree: &Tree<'_>,
    spec: &CameraSpec,
    exact: &[Vec<DVec3>],
    cam: &Camera,
    w: u32,
    h: u32,
) -> Result<f64, CliError> {
    let f = match resolve_precision(name) {
        "fixed-subpx-0" => max_vertex_error::<FixedPrecision<0>>,
        "fixed-subpx-2" => max_vertex_error::<FixedPrecision<2>>,
        "fixed-subpx-4" => max_vertex_error::<FixedPrecision<4>>,
        "fixed-subpx-6" => max_vertex_error::<FixedPrecision<6>>,
        "fixed-subpx-8" => max_vertex_error::<FixedPrecision<8>>,
        "fixed-micromath-subpx-4" => max_vertex_error::<FixedMicromath<4>>,
        "f32-libm-subpx-4" => max_vertex_error::<FloatLibm<4>>,
        "f32-micromath-subpx-4" => max_vertex_error::<FloatMicromath<4>>,
        "int-subpx-4" => max_vertex_error::<IntPrecision<4>>,
        other => return Err(cli_err!("no vertex error for precision '{other}'")),
    };
    f(tree, spec, exact, cam, w, h)
}

/// The largest distance in pixels between where configuration `P` puts a
/// vertex of `tree` (as the renderer does: the frame of `spec` with `P`'s
/// trigonometry, `P::Path`'s transform and projection of the stored
/// vertex) and the exact projection through `cam` of the builder's vertex
/// (`exact`, by file polygon id); only vertices whose exact projection is
/// inside the image and in front of the eye count.
pub fn max_vertex_error<P: Precision>(
    tree: &Tree<'_>,
    spec: &CameraSpec,
    exact: &[Vec<DVec3>],
    cam: &Camera,
    w: u32,
    h: u32,
) -> Result<f64, CliError> {
    let frame: Frame = spec.frame::<P::Math>(tree, w, h);
    let m = P::Path::prepare(&frame.camera.matrix);
    let s = frame.vertex_scale;
    vertex_error_with::<P>(tree, exact, cam, w, h, |p, i| {
        let v = p.vertex(i);
        P::Path::transform(&m, [v[0] * s, v[1] * s, v[2] * s])
    })
}

/// The loop of [`max_vertex_error`], with vertex `i` of polygon `p` put
/// into clip space by `clip`.
fn vertex_error_with<P: Precision>(
    tree: &Tree<'_>,
    exact: &[Vec<DVec3>],
    cam: &Camera,
    w: u32,
    h: u32,
    clip: impl Fn(&PolygonRef<'_>, usize) -> Option<ClipVert<Scalar<P>>>,
) -> Result<f64, CliError> {
    let vp = Viewport::new(w, h, P::SUB_BITS).ok_or_else(|| cli_err!("bad size {w}x{h}"))?;
    let unit = f64::from(1u32 << P::SUB_BITS);
    let mut worst = 0.0f64;
    for id in 0..tree.polygon_count() {
        let p = tree
            .polygon(id)
            .ok_or_else(|| cli_err!("polygon {id} missing"))?;
        let ex = exact
            .get(id as usize)
            .filter(|e| e.len() == p.vertex_count())
            .ok_or_else(|| cli_err!("polygon {id}: vertices do not match the builder's"))?;
        for (i, e) in ex.iter().enumerate() {
            let c = cam.clip(*e);
            // Behind the eye (or NaN): not a visible vertex.
            if c.w.is_nan() || c.w <= 0.0 {
                continue;
            }
            let x = (c.x / c.w + 1.0) * 0.5 * f64::from(w);
            let y = (1.0 - c.y / c.w) * 0.5 * f64::from(h);
            if !((0.0..=f64::from(w)).contains(&x) && (0.0..=f64::from(h)).contains(&y)) {
                continue;
            }
            let screen = clip(&p, i).and_then(|cv| P::Path::project(&cv, &vp));
            let err = match screen {
                Some(pt) => (f64::from(pt.x) / unit - x).hypot(f64::from(pt.y) / unit - y),
                // A visible vertex the path cannot place is as wrong as can be.
                None => f64::INFINITY,
            };
            worst = worst.max(err);
        }
    }
    Ok(worst)
}

/// The clip scalar of configuration `P`.
type Scalar<P> = <<P as Precision>::Path as VertexPath>::Scalar;

/// Draws `view` of the tree file `tree` as `config` does when timed (the
/// unit [`host_seconds`] times): rgb565, lambert, no ids. For benchmarks.
pub fn draw(
    tree: &Tree<'_>,
    config: &Config,
    view: ViewSpec,
    w: u32,
    h: u32,
) -> Result<(), CliError> {
    let spec = camera_spec(config, tree, view, w, h);
    if config.raw_q16 {
        return render_raw_q16(tree, &job(spec, w, h, false)).map(|_| ());
    }
    render_job(tree, &job(spec, w, h, false), config.precision).map(|_| ())
}

/// Host seconds per frame of every configuration: `reps` rounds, each
/// rendering every (case, view) once per configuration, configurations
/// interleaved within a round (starting one later each round) so that
/// drift and position hit all alike; per configuration and frame the
/// fastest of the rounds (the one least disturbed by other processes),
/// averaged over the frames. Times the whole `render::render_job` (frame
/// derivation included), ids off.
pub fn host_seconds(
    cases: &[Case],
    configs: &[Config],
    views: &[ViewSpec],
    w: u32,
    h: u32,
    reps: usize,
) -> Result<Vec<f64>, CliError> {
    // Parse the trees and derive the jobs outside the timed part.
    let mut work: Vec<Vec<(Tree<'_>, Job)>> = Vec::new();
    for config in configs {
        let mut jobs = Vec::new();
        for case in cases {
            let bytes = case.tree_bytes(config.vertex)?;
            let tree = Tree::from_bytes(bytes).map_err(|e| cli_err!("{}: {e}", case.name))?;
            for &v in views {
                let spec = camera_spec(config, &tree, v, w, h);
                jobs.push((tree, job(spec, w, h, false)));
            }
        }
        work.push(jobs);
    }
    let mut best: Vec<Vec<f64>> = work
        .iter()
        .map(|jobs| vec![f64::INFINITY; jobs.len()])
        .collect();
    let n = configs.len();
    for rep in 0..reps.max(1) {
        for k in 0..n {
            let i = (k + rep) % n;
            let (Some(config), Some(jobs), Some(out)) =
                (configs.get(i), work.get(i), best.get_mut(i))
            else {
                continue;
            };
            for ((tree, j), t) in jobs.iter().zip(out.iter_mut()) {
                let start = Instant::now();
                if config.raw_q16 {
                    std::hint::black_box(render_raw_q16(tree, j)?);
                } else {
                    std::hint::black_box(render_job(tree, j, config.precision)?);
                }
                *t = t.min(start.elapsed().as_secs_f64());
            }
        }
    }
    Ok(best
        .into_iter()
        .map(|t| t.iter().sum::<f64>() / t.len().max(1) as f64)
        .collect())
}
