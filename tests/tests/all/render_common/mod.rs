//! Helpers shared by the `render_*` tests: the no_std render of a tree as
//! source ids, and its comparison with the float64 reference z-buffer.
//!
//! The comparison is by **source face**: the reference draws the tree's
//! polygons (the builder's output, split pieces included) and its ids are
//! mapped to their source faces; our render writes `source + 1`. A pixel
//! near a split line is unsure like any outline pixel (a polygon behind the
//! face may legitimately be painted between two of its pieces, and rounding
//! can let it show by a sub-pixel sliver), but a gap along a split line is
//! a crack.
//!
//! * **wrong**: a pixel the reference is sure of (not within
//!   [`EDGE_PX`] of a relevant outline, no depth tie) shows another face
//!   (or background) in our render;
//! * **crack**: our render shows background at a pixel whose sample a
//!   drawn polygon covers such that every one of its edges within the
//!   largest rounding displacement is shared with another drawn polygon
//!   ([`is_crack`]), whether or not the pixel is sure: no rounding can
//!   uncover the background there unless the two sides of a shared edge
//!   round differently — a gap between faces sharing an edge, along a
//!   split line or at a T-junction — unlike a pixel in a genuine sub-pixel
//!   gap between two objects.
#![allow(dead_code)]

use fpt_nostd::raster::{DefaultPrecision, IdBuffer, Precision};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{near_w_for, FaceIds, Frame, TreeRenderer};
use glam::{DVec3, DVec4};
use host_sim::build::{build, NoProgress};
use host_sim::geom::{bounds, Polygon};
use host_sim::reference::{zbuffer, Camera, RefOptions, View};
use host_sim::serialize::{serialize, SerializeOptions};
use host_sim::tree::Method;

/// Outline margin within which a pixel is unsure.
pub const EDGE_PX: f64 = 0.5;

/// The outline margin for `sub` sub-pixel bits: vertices snap by up to
/// `2^-sub / 2` pixel per axis, which moves an edge by up to about
/// `0.75 · 2^-sub` pixel; [`EDGE_PX`] covers that from 2 bits on.
pub fn edge_px(sub: u32) -> f64 {
    (0.25 + 0.75 / f64::from(1u32 << sub.min(16))).max(EDGE_PX)
}
/// Walk stack of the tests.
pub const STACK: usize = 2048;
/// Vertex capacity of the tests' scratch.
pub const VERTS: usize = 256;

/// The row-major rows of a reference camera's matrix.
pub fn rows(cam: &Camera) -> [[f64; 4]; 4] {
    let m = cam.mvp();
    let mut r = [[0.0; 4]; 4];
    for (i, v) in m.iter().enumerate() {
        r[i / 4][i % 4] = *v;
    }
    r
}

/// The frame the renderer uses for a reference camera (near clip from the
/// matrix's near plane, as `fpt render --mvp` does).
pub fn frame(tree: &Tree<'_>, cam: &Camera) -> Frame {
    let r = rows(cam);
    Frame::from_f64(tree, &r, f64::from(near_w_for(&r, tree)))
}

/// File polygon id + 1 per pixel of the no_std render with precision `P`.
pub fn render_polygon_ids<P: Precision>(
    tree: &Tree<'_>,
    frame: &Frame,
    w: usize,
    h: usize,
) -> Vec<u32> {
    render_polygon_ids_with::<P>(tree, frame, (w, h), false)
}

/// [`render_polygon_ids`], drawing slivers first when `slivers`
/// (`Renderer::set_slivers`).
pub fn render_polygon_ids_with<P: Precision>(
    tree: &Tree<'_>,
    frame: &Frame,
    (w, h): (usize, usize),
    slivers: bool,
) -> Vec<u32> {
    let mut ids = vec![0u32; w * h];
    let mut sink = IdBuffer::new(&mut ids, w as u32, h as u32).expect("id buffer");
    let mut tr = Box::new(TreeRenderer::<P, VERTS>::new(w as u32, h as u32).expect("renderer"));
    tr.ids = FaceIds::Polygon;
    tr.renderer.set_slivers(slivers);
    tr.render::<STACK, _>(tree, frame, &mut sink).expect("walk");
    ids
}

/// Source id + 1 per pixel of the no_std render with precision `P`.
pub fn render_ids<P: Precision>(tree: &Tree<'_>, frame: &Frame, w: usize, h: usize) -> Vec<u32> {
    let mut ids = vec![0u32; w * h];
    let mut sink = IdBuffer::new(&mut ids, w as u32, h as u32).expect("id buffer");
    let mut tr = Box::new(TreeRenderer::<P, VERTS>::new(w as u32, h as u32).expect("renderer"));
    tr.ids = FaceIds::Source;
    tr.render::<STACK, _>(tree, frame, &mut sink).expect("walk");
    ids
}

/// Keeps the part of a homogeneous polygon where `f ≥ 0`.
fn clip_by(poly: &[DVec4], f: impl Fn(DVec4) -> f64) -> Vec<DVec4> {
    let mut out = Vec::with_capacity(poly.len() + 2);
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (da, db) = (f(a), f(b));
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            out.push(a + (b - a) * (da / (da - db)));
        }
    }
    out
}

/// The outline of `verts` (model coordinates) in pixel coordinates of a
/// `w × h` image, clipped to the near and far planes like the reference.
pub fn project(cam: &Camera, verts: &[DVec3], w: usize, h: usize) -> Vec<(f64, f64)> {
    let clip: Vec<DVec4> = verts.iter().map(|&v| cam.clip(v)).collect();
    let clip = clip_by(&clip_by(&clip, |c| c.z + c.w), |c| c.w - c.z);
    clip.iter()
        .filter(|c| c.w > 0.0)
        .map(|c| {
            (
                (c.x / c.w + 1.0) * 0.5 * w as f64,
                (1.0 - c.y / c.w) * 0.5 * h as f64,
            )
        })
        .collect()
}

/// Even–odd point-in-polygon test.
pub fn inside(pts: &[(f64, f64)], x: f64, y: f64) -> bool {
    let mut c = false;
    for k in 0..pts.len() {
        let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
        if (a.1 > y) != (b.1 > y) && x < a.0 + (y - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            c = !c;
        }
    }
    c
}

/// Distance from `(x, y)` to segment `a b`, and the parameter of the
/// nearest point.
pub fn seg_dist(a: (f64, f64), b: (f64, f64), x: f64, y: f64) -> (f64, f64) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((x - a.0) * dx + (y - a.1) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (a.0 + t * dx - x, a.1 + t * dy - y);
    ((qx * qx + qy * qy).sqrt(), t)
}

/// Whether the background at pixel `(i, j)` is a crack: the drawn
/// polygons of `polys` (for a closed scene, those facing the viewer) cover
/// the sample, and every edge of a drawn polygon that passes within `rho`
/// pixels of it (the largest rounding displacement) is shared, along that
/// stretch, with another drawn polygon lying across it (an edge of which is
/// collinear in 3D, within `1e-6 ×` the diagonal, and spans the nearest
/// point). Then the union covers a disc around the sample with no outline
/// in it, and the sample stays covered whatever the rounding as long as
/// shared edges round alike; a sample near any silhouette (a genuine
/// sub-pixel gap, two outlines crossing, a fold of an open surface, a
/// sliver) is not a crack.
pub fn is_crack(
    polys: &[Polygon],
    closed: bool,
    cam: &Camera,
    w: usize,
    h: usize,
    (i, j): (usize, usize),
    rho: f64,
) -> bool {
    let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
    let view = cam.view();
    let (lo, hi) = bounds(polys);
    let eps = 1e-6 * (hi - lo).length();
    let drawn: Vec<&Polygon> = polys
        .iter()
        .filter(|p| !closed || view.faces(&p.plane))
        .collect();
    let on_line = |a: DVec3, b: DVec3, c: DVec3| {
        let ab = b - a;
        let l2 = ab.length_squared();
        l2 > 0.0 && (a + ab * ((c - a).dot(ab) / l2) - c).length() <= eps
    };
    let shared = |me: usize, a: DVec3, b: DVec3, outline: &[(f64, f64)]| {
        // The point of the projected edge nearest the sample, and a point
        // just across the edge from the polygon's inside.
        let pa = project(cam, &[a], w, h);
        let pb = project(cam, &[b], w, h);
        let (Some(&pa), Some(&pb)) = (pa.first(), pb.first()) else {
            return false; // crosses the near plane: give up, not a crack
        };
        let (_, t) = seg_dist(pa, pb, x, y);
        let q = (pa.0 + t * (pb.0 - pa.0), pa.1 + t * (pb.1 - pa.1));
        let (dx, dy) = (pb.0 - pa.0, pb.1 - pa.1);
        let l = (dx * dx + dy * dy).sqrt().max(f64::MIN_POSITIVE);
        let mut u = (-dy / l * 1e-3, dx / l * 1e-3);
        if !inside(outline, q.0 - u.0, q.1 - u.1) {
            u = (-u.0, -u.1);
        }
        let across = (q.0 + u.0, q.1 + u.1);
        drawn.iter().enumerate().any(|(k, o)| {
            // The neighbour must lie across the edge: at a fold of an open
            // surface both lie on one side and the other side is open.
            k != me
                && inside(&project(cam, &o.verts, w, h), across.0, across.1)
                && (0..o.verts.len()).any(|e| {
                    let (c, d) = (o.verts[e], o.verts[(e + 1) % o.verts.len()]);
                    if !(on_line(a, b, c) && on_line(a, b, d)) {
                        return false;
                    }
                    match (
                        project(cam, &[c], w, h).first(),
                        project(cam, &[d], w, h).first(),
                    ) {
                        (Some(&pc), Some(&pd)) => seg_dist(pc, pd, q.0, q.1).0 <= 1e-6,
                        _ => false,
                    }
                })
        })
    };
    let outlines: Vec<Vec<(f64, f64)>> =
        drawn.iter().map(|p| project(cam, &p.verts, w, h)).collect();
    let covered = outlines.iter().any(|o| o.len() >= 3 && inside(o, x, y));
    covered
        && drawn
            .iter()
            .zip(&outlines)
            .enumerate()
            .all(|(me, (p, outline))| {
                let n = p.verts.len();
                if outline.len() != n {
                    // Clipped by the near or far plane: its outline there is
                    // not an edge of the mesh; only a sample far from it counts.
                    return (0..outline.len()).all(|e| {
                        seg_dist(outline[e], outline[(e + 1) % outline.len()], x, y).0 > rho
                    });
                }
                (0..n).all(|e| {
                    let (a2, b2) = (outline[e], outline[(e + 1) % n]);
                    seg_dist(a2, b2, x, y).0 > rho
                        || shared(me, p.verts[e], p.verts[(e + 1) % n], outline)
                })
            })
}

/// Distance in pixels from the sample of pixel `(i, j)` to the outline of
/// the polygon `verts` (model coordinates) as `cam` projects it into a
/// `w × h` image, clipped to the near and far planes like the reference;
/// infinite when nothing of it is in view.
pub fn outline_distance(
    cam: &Camera,
    verts: &[DVec3],
    w: usize,
    h: usize,
    i: usize,
    j: usize,
) -> f64 {
    let pts = project(cam, verts, w, h);
    let (px, py) = (i as f64 + 0.5, j as f64 + 0.5);
    let mut best = f64::INFINITY;
    for k in 0..pts.len() {
        let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
        best = best.min(seg_dist(a, b, px, py).0);
    }
    best
}

/// Totals over views.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Views compared.
    pub views: usize,
    /// Sure pixels compared.
    pub compared: usize,
    /// Unsure pixels.
    pub unsure: usize,
    /// Sure pixels that differ.
    pub wrong: usize,
    /// Background pixels inside the covered area.
    pub cracks: usize,
    /// Pixels covered by the reference.
    pub covered: usize,
    /// One line per failing view.
    pub failures: Vec<String>,
}

/// Compares our render (`ours`: file polygon id + 1 per pixel of `tree`)
/// with the reference picture of `polys` (the tree's polygons; `source`
/// fields name the faces) for `cam`, for a render with `sub` sub-pixel
/// bits. A differing pixel within [`edge_px`]`(sub)`
/// of the outline of the polygon our render drew there is an edge pixel
/// too: the reference leaves out outlines of polygons that lie behind the
/// visible face (their plane does at the sample), which misses faces that
/// cross the visible one right at their edge (self-intersecting meshes).
#[allow(clippy::too_many_arguments)]
pub fn compare(
    polys: &[Polygon],
    closed: bool,
    cam: &Camera,
    tree: &Tree<'_>,
    ours: &[u32],
    w: usize,
    h: usize,
    rep: &mut Report,
    label: &str,
    sub: u32,
) {
    let edge_px = edge_px(sub);
    // The crack test's radius: the largest edge displacement by vertex
    // snapping (half a step per axis: 0.71 · 2^-sub), with a margin.
    let rho = 0.05 + 0.75 / f64::from(1u32 << sub.min(16));
    let opt = RefOptions {
        cull_backfaces: closed,
        edge_px,
        ..RefOptions::default()
    };
    let frame = zbuffer(polys, cam, w, h, opt);
    let src = |id: u32| {
        if id == 0 {
            0
        } else {
            polys
                .get(id as usize - 1)
                .map_or(u32::MAX, |p| p.source + 1)
        }
    };
    let our_src = |id: u32| {
        if id == 0 {
            0
        } else {
            tree.polygon(id - 1).map_or(u32::MAX, |p| p.source() + 1)
        }
    };
    let near_our_edge = |id: u32, i: usize, j: usize| {
        let Some(p) = id.checked_sub(1).and_then(|k| tree.polygon(k)) else {
            return false;
        };
        let verts: Vec<DVec3> = (0..p.vertex_count())
            .map(|k| DVec3::from(p.vertex_model(k)))
            .collect();
        outline_distance(cam, &verts, w, h, i, j) <= edge_px
    };
    let want: Vec<u32> = frame.ids.iter().map(|&i| src(i)).collect();
    let (mut wrong, mut cracks, mut first) = (0, 0, None);
    rep.views += 1;
    for j in 0..h {
        for i in 0..w {
            let p = j * w + i;
            let got = our_src(ours[p]);
            if want[p] != 0 {
                rep.covered += 1;
            }
            if got == 0 && want[p] != 0 && is_crack(polys, closed, cam, w, h, (i, j), rho) {
                cracks += 1;
                first.get_or_insert(format!(
                    "crack at ({i}, {j}): reference face {}",
                    want[p] as i64 - 1
                ));
            }
            if frame.unsure(p) || (want[p] != got && near_our_edge(ours[p], i, j)) {
                rep.unsure += 1;
                continue;
            }
            rep.compared += 1;
            if want[p] != got {
                wrong += 1;
                first.get_or_insert(format!(
                    "wrong at ({i}, {j}): reference face {}, ours {}",
                    want[p] as i64 - 1,
                    got as i64 - 1
                ));
            }
        }
    }
    rep.wrong += wrong;
    rep.cracks += cracks;
    if let Some(f) = first {
        let v = match cam.view() {
            View::Parallel { dir } => format!("parallel {dir}"),
            View::Perspective { eye } => format!("eye {eye}"),
        };
        rep.failures.push(format!(
            "{label} ({v}): {wrong} wrong, {cracks} cracks; first {f}"
        ));
    }
}

/// A built tree: its polygons (the builder's output, which the reference
/// draws; `source` names the input face) and its file.
pub struct Built {
    /// The tree's polygons, in the tree's numbering.
    pub polygons: Vec<Polygon>,
    /// The serialized file.
    pub bytes: Vec<u8>,
}

/// The serialized static tree of `polys` (the builder repairs its seams).
pub fn build_tree(polys: &[Polygon], closed: bool) -> Built {
    let t = build(polys.to_vec(), closed, Method::Static, 7, &mut NoProgress);
    let bytes = serialize(&t, &SerializeOptions::default()).expect("serialize");
    Built {
        polygons: t.polygons,
        bytes,
    }
}

/// Renders the tree of `polys` for every camera with the default
/// precision and compares with the reference of the tree's own polygons
/// (so split lines are outlines too, and pixels near them unsure);
/// prints a summary line and returns the report.
pub fn check_views(
    name: &str,
    polys: &[Polygon],
    closed: bool,
    cams: &[Camera],
    w: usize,
    h: usize,
) -> Report {
    check_views_with::<DefaultPrecision>(name, polys, closed, cams, w, h)
}

/// [`check_views`] with precision `P`.
pub fn check_views_with<P: Precision>(
    name: &str,
    polys: &[Polygon],
    closed: bool,
    cams: &[Camera],
    w: usize,
    h: usize,
) -> Report {
    let built = build_tree(polys, closed);
    let tree = Tree::from_bytes(&built.bytes).expect("tree");
    let mut rep = Report::default();
    for (k, cam) in cams.iter().enumerate() {
        let f = frame(&tree, cam);
        let ours = render_polygon_ids::<P>(&tree, &f, w, h);
        let label = format!("{name} view {k}");
        compare(
            &built.polygons,
            closed,
            cam,
            &tree,
            &ours,
            w,
            h,
            &mut rep,
            &label,
            P::SUB_BITS,
        );
    }
    println!(
        "{name}: {} -> {} polygons, {} views at {w}x{h}: {} px compared, {} unsure, {} covered, \
         {} wrong, {} cracks",
        polys.len(),
        built.polygons.len(),
        rep.views,
        rep.compared,
        rep.unsure,
        rep.covered,
        rep.wrong,
        rep.cracks
    );
    rep
}

/// Panics listing the first failures of `rep`, if any.
pub fn assert_clean(name: &str, rep: &Report) {
    assert!(
        rep.views > 0 && rep.compared > 0,
        "{name}: nothing compared"
    );
    assert!(
        rep.failures.is_empty(),
        "{name}: {} wrong pixels, {} cracks:\n{}",
        rep.wrong,
        rep.cracks,
        rep.failures
            .iter()
            .take(8)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}
