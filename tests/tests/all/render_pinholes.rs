//! No pinholes: the no_std render of every closed third-party model in
//! `../shared/models` leaves no background pixel inside the silhouette of
//! the input mesh. Skipped when the folder is absent, as in a fresh clone.
//!
//! The silhouette comes from the float64 reference z-buffer of the
//! **input** polygons (not the tree's pieces, which would share any defect
//! of the builder): a pixel is a pinhole when the reference covers it and
//! its eight neighbours, yet our render leaves it as background. A closed
//! mesh seen from outside covers every such pixel, whatever the rounding:
//! the top-left rule fills each sample of the union of faces that share
//! their edges exactly, so a background pixel there means that the tree's
//! pieces do not tile the input faces or that two faces' seams no longer
//! conform. Pixels next to inner edges are not excluded: that is exactly
//! where such pinholes sit (fandisk.obj showed 19–39 per 800×600 view,
//! along the edge between two curved faces, when a split moved a vertex).
//!
//! Pixels next to *silhouette* edges are not excluded either (an edge
//! whose neighbour across faces away, like the rim of a hole seen at a
//! slant): there the sub-pixel snap can wind a face seen almost edge-on
//! toward the viewer although its plane is turned away, and the culling
//! walk leaves it out; the renderer draws such slivers first when asked
//! (`Renderer::set_slivers`, which these renders turn on), and this test
//! is what holds it to zero (11 pixels over all these renders without it).
//!
//! Each model is drawn from 20 views around it (alternately parallel and
//! perspective, directions spread evenly over the sphere) at 320×240,
//! 800×600 and 1024×768, from its static tree and its BSP tree, on two
//! threads. `rocker-arm.obj`'s static build takes about a minute, so its
//! static tree has an `#[ignore]`d test of its own.

use crate::render_common;

use fpt_nostd::raster::{DefaultPrecision, FixedPrecision, Precision};
use fpt_nostd::reader::Tree;
use fpt_tests::shared_mesh;
use glam::DVec3;
use host_sim::build::{build, NoProgress};
use host_sim::geom::{bounds, Polygon};
use host_sim::reference::{zbuffer_ids, Camera, Projection};
use host_sim::serialize::{serialize, SerializeOptions};
use host_sim::tree::Method;
use render_common::{frame, render_polygon_ids_with};
use std::sync::Mutex;

/// The closed shared models (see `../shared/models/README.md`; the loader
/// also finds `wallhole.obj` closed once its faces are welded).
const CLOSED: [&str; 8] = [
    "shuttle.obj",
    "socket.off",
    "plate_holes.STL",
    "rabbit.obj",
    "wallhole.obj",
    "violin_case.obj",
    "fandisk.obj",
    "rocker-arm.obj",
];

/// Models whose static build is too slow for the default run.
const SLOW: [&str; 1] = ["rocker-arm.obj"];

/// Image sizes, all 4:3.
const SIZES: [(usize, usize); 3] = [(320, 240), (800, 600), (1024, 768)];

/// Views per model and size.
const VIEWS: usize = 20;

/// `n` cameras around `polys` from outside its bounding sphere, none
/// clipped by the near plane: directions on a Fibonacci sphere (evenly
/// spread, none along an axis), even ones parallel, odd ones perspective.
fn cameras(polys: &[Polygon], n: usize, aspect: f64) -> Vec<Camera> {
    let (lo, hi) = bounds(polys);
    let c = (lo + hi) * 0.5;
    let r = ((hi - lo).length() * 0.5).max(f64::MIN_POSITIVE);
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .filter_map(|k| {
            let z = 1.0 - (2.0 * k as f64 + 1.0) / n as f64;
            let s = (1.0 - z * z).sqrt();
            let a = golden * k as f64 + 0.3;
            let dir = DVec3::new(s * a.cos(), s * a.sin(), z);
            // Up: any axis far from the view direction.
            let up = if dir.y.abs() < 0.9 {
                DVec3::Y
            } else {
                DVec3::X
            };
            let projection = if k % 2 == 0 {
                Projection::Parallel {
                    half_height: 1.05 * r,
                    near: 0.0,
                    far: 6.0 * r,
                }
            } else {
                Projection::Perspective {
                    fov_y_deg: 55.0,
                    near: 0.05 * r,
                    far: 10.0 * r,
                }
            };
            let dist = if k % 2 == 0 { 3.0 * r } else { 2.3 * r };
            Camera::look_at(c + dir * dist, c, up, projection, aspect)
        })
        .collect()
}

/// The largest distance in pixels by which the sub-pixel snap moves an
/// edge (half a sub-pixel step per axis: `√2/2 · 2^-sub`), rounded up.
const SNAP: f64 = 0.75 / (1u32 << DefaultPrecision::SUB_BITS) as f64;

/// Whether the exact picture of `polys` (the union of their projections,
/// which is what the reference covers) has background within `rho` pixels
/// of the sample of pixel `(i, j)`: then the silhouette itself passes
/// within the snap's reach of the sample, and no renderer that snaps its
/// vertices can promise to cover it (plate_holes.STL, view 18, 320×240:
/// a notch of background between samples, 0.008 px from (126, 178)'s).
/// Found along the edges within `rho`: where the covered region ends, a
/// point just beside an edge is uncovered. Sampled (nine points on each
/// edge's chord through the disc), so it can only miss background, which
/// makes the test stricter, never more lenient.
fn background_near(
    polys: &[Polygon],
    cam: &Camera,
    (w, h): (usize, usize),
    (i, j): (usize, usize),
    rho: f64,
) -> bool {
    let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
    let outlines: Vec<Vec<(f64, f64)>> = polys
        .iter()
        .map(|p| render_common::project(cam, &p.verts, w, h))
        .filter(|o| o.len() >= 3)
        .collect();
    let covered = |qx: f64, qy: f64| outlines.iter().any(|o| render_common::inside(o, qx, qy));
    outlines.iter().any(|o| {
        (0..o.len()).any(|e| {
            let (a, b) = (o[e], o[(e + 1) % o.len()]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let l = (dx * dx + dy * dy).sqrt();
            if l == 0.0 || render_common::seg_dist(a, b, x, y).0 > rho {
                return false;
            }
            // The chord of the disc along the edge's line, within the edge.
            let (ux, uy) = (dx / l, dy / l);
            let t = (x - a.0) * ux + (y - a.1) * uy;
            let off = (x - a.0) * uy - (y - a.1) * ux;
            let half = (rho * rho - off * off).max(0.0).sqrt();
            let (t0, t1) = ((t - half).max(0.0), (t + half).min(l));
            let eps = 1e-6;
            (0..9).any(|k| {
                let t = t0 + (t1 - t0) * k as f64 / 8.0;
                let (qx, qy) = (a.0 + ux * t, a.1 + uy * t);
                !covered(qx - uy * eps, qy + ux * eps) || !covered(qx + uy * eps, qy - ux * eps)
            })
        })
    })
}

/// Background pixels of `ours` where `reference` covers the pixel and its
/// eight neighbours.
fn background_inside(reference: &[u32], ours: &[u32], w: usize, h: usize) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for j in 1..h.saturating_sub(1) {
        for i in 1..w.saturating_sub(1) {
            if ours[j * w + i] != 0 {
                continue;
            }
            if (j - 1..=j + 1).all(|y| (i - 1..=i + 1).all(|x| reference[y * w + x] != 0)) {
                out.push((i, j));
            }
        }
    }
    out
}

/// One model: its trees (`methods`) drawn from every view at every size.
/// Returns the failures.
fn check(file: &str, methods: &[Method]) -> Vec<String> {
    let Some(m) = shared_mesh(file) else {
        return Vec::new();
    };
    assert!(m.closed, "{file}: the loader finds it open");
    let start = std::time::Instant::now();
    let trees: Vec<(Method, Vec<u8>)> = methods
        .iter()
        .map(|&method| {
            let t = build(m.polygons.clone(), true, method, 7, &mut NoProgress);
            let bytes = serialize(&t, &SerializeOptions::default()).expect("serialize");
            (method, bytes)
        })
        .collect();
    let mut failures = Vec::new();
    let mut totals = vec![0usize; trees.len()];
    let mut within_snap = vec![0usize; trees.len()];
    let mut covered = 0usize;
    for &(w, h) in &SIZES {
        for (k, cam) in cameras(&m.polygons, VIEWS, w as f64 / h as f64)
            .iter()
            .enumerate()
        {
            let reference = zbuffer_ids(&m.polygons, cam, w, h, false);
            covered += reference.iter().filter(|&&id| id != 0).count();
            for (t, (method, bytes)) in trees.iter().enumerate() {
                let tree = Tree::from_bytes(bytes).expect("tree");
                let f = frame(&tree, cam);
                let ours = render_polygon_ids_with::<DefaultPrecision>(&tree, &f, (w, h), true);
                let (holes, at_edge): (Vec<_>, Vec<_>) = background_inside(&reference, &ours, w, h)
                    .into_iter()
                    .partition(|&px| !background_near(&m.polygons, cam, (w, h), px, SNAP));
                totals[t] += holes.len();
                within_snap[t] += at_edge.len();
                if let Some((i, j)) = holes.first() {
                    failures.push(format!(
                        "{file} {} {w}x{h} view {k}: {} pinholes, first at ({i}, {j})",
                        method.name(),
                        holes.len()
                    ));
                }
            }
        }
    }
    let counts: Vec<String> = trees
        .iter()
        .zip(totals.iter().zip(&within_snap))
        .map(|((method, _), (n, e))| {
            format!("{} {n} (+{e} within the snap of background)", method.name())
        })
        .collect();
    println!(
        "{file}: {} views x {} sizes, {covered} px covered; pinholes: {}; {:.1} s",
        VIEWS,
        SIZES.len(),
        counts.join(", "),
        start.elapsed().as_secs_f64()
    );
    failures
}

/// Runs `jobs` on two threads and panics listing the failures, if any.
fn run(jobs: Vec<(&'static str, Vec<Method>)>) {
    let queue = Mutex::new(jobs);
    let failures = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| loop {
                let Some((file, methods)) = queue.lock().expect("queue").pop() else {
                    break;
                };
                let f = check(file, &methods);
                failures.lock().expect("failures").extend(f);
            });
        }
    });
    let failures = failures.into_inner().expect("failures");
    assert!(
        failures.is_empty(),
        "{} views with pinholes:\n{}",
        failures.len(),
        failures
            .iter()
            .take(20)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

#[test]
fn closed_models_show_no_pinholes() {
    // The queue pops from the back, where the largest models are.
    let jobs = CLOSED
        .iter()
        .map(|&file| {
            let methods = if SLOW.contains(&file) {
                vec![Method::Bsp]
            } else {
                vec![Method::Static, Method::Bsp]
            };
            (file, methods)
        })
        .collect();
    run(jobs);
}

#[test]
#[ignore = "rocker-arm.obj's static build takes about a minute"]
fn slow_static_trees_show_no_pinholes() {
    run(SLOW.iter().map(|&f| (f, vec![Method::Static])).collect());
}

/// The background pixels inside the silhouette that the renders showed
/// before the sliver pass (file, size, view, pixel): slivers with surface
/// behind them, which the test counts; and the one sample the exact
/// silhouette passes within the snap's reach of, which it does not.
#[test]
fn only_background_within_the_snap_is_set_apart() {
    /// File, image size, view, pixel, whether set apart.
    type Case = (&'static str, (usize, usize), usize, (usize, usize), bool);
    let cases: [Case; 5] = [
        ("plate_holes.STL", (320, 240), 4, (185, 194), false),
        ("violin_case.obj", (800, 600), 6, (518, 221), false),
        ("fandisk.obj", (1024, 768), 17, (394, 389), false),
        ("fandisk.obj", (320, 240), 17, (120, 121), false),
        ("plate_holes.STL", (320, 240), 18, (126, 178), true),
    ];
    for (file, (w, h), k, px, near) in cases {
        let Some(m) = shared_mesh(file) else {
            return;
        };
        let cam = &cameras(&m.polygons, VIEWS, w as f64 / h as f64)[k];
        assert_eq!(
            background_near(&m.polygons, cam, (w, h), px, SNAP),
            near,
            "{file} {w}x{h} view {k} {px:?}"
        );
    }
}

/// The one sample set apart is the sub-pixel snap's, not a missing face:
/// with slivers drawn, the default 4 sub-pixel bits leave it as background
/// (so the exclusion cannot be dropped: the sliver pass covers what the
/// culling walk leaves out, not a notch of the exact picture's background
/// that the snap moves over the sample), and 8 bits, whose snap reaches
/// 16 times less far, cover it and leave no background pixel inside the
/// silhouette at all.
#[test]
fn the_sample_set_apart_is_covered_with_a_finer_snap() {
    let file = "plate_holes.STL";
    let Some(m) = shared_mesh(file) else {
        return;
    };
    let (w, h) = (320, 240);
    let px = (126, 178);
    let cam = &cameras(&m.polygons, VIEWS, w as f64 / h as f64)[18];
    let reference = zbuffer_ids(&m.polygons, cam, w, h, false);
    assert_eq!(DefaultPrecision::SUB_BITS, 4);
    let mut shown = 0;
    for method in [Method::Static, Method::Bsp] {
        let t = build(m.polygons.clone(), true, method, 7, &mut NoProgress);
        let bytes = serialize(&t, &SerializeOptions::default()).expect("serialize");
        let tree = Tree::from_bytes(&bytes).expect("tree");
        let f = frame(&tree, cam);
        let at4 = render_polygon_ids_with::<DefaultPrecision>(&tree, &f, (w, h), true);
        let holes4 = background_inside(&reference, &at4, w, h);
        assert!(
            holes4.iter().all(|&p| p == px),
            "{} at 4 bits: {holes4:?}",
            method.name()
        );
        shown += holes4.len();
        let at8 = render_polygon_ids_with::<FixedPrecision<8>>(&tree, &f, (w, h), true);
        let holes8 = background_inside(&reference, &at8, w, h);
        assert!(holes8.is_empty(), "{} at 8 bits: {holes8:?}", method.name());
    }
    assert!(
        shown > 0,
        "the sample is covered at 4 bits now: drop the exclusion"
    );
}

#[test]
fn background_inside_needs_the_pixel_and_its_neighbours_covered() {
    // 5×4 picture: the reference covers all but the right column.
    let (w, h) = (5, 4);
    let reference: Vec<u32> = (0..w * h).map(|p| u32::from(p % w != 4)).collect();
    let mut ours = vec![7u32; w * h];
    assert!(background_inside(&reference, &ours, w, h).is_empty());
    // Background at (1, 1): all eight neighbours covered. At (3, 2): its
    // right neighbours are outside the silhouette.
    ours[w + 1] = 0;
    ours[2 * w + 3] = 0;
    assert_eq!(background_inside(&reference, &ours, w, h), vec![(1, 1)]);
}
