//! An exact float64 reference renderer with no tree, to check draw orders.
//!
//! Contract:
//! - Every pixel is sampled once at its centre (see [`camera`] for the
//!   matrix and pixel conventions). Coverage is an exact even–odd
//!   point-in-polygon test on the polygon clipped to the near and far planes
//!   and projected, in `f64`; polygons partly behind the eye are handled by
//!   that clipping. Output ids are polygon index + 1, `0` for background.
//! - [`zbuffer`] keeps, per pixel, the covering polygon nearest along the
//!   pixel's ray (distance measured in model units from the near plane), with
//!   optional back-face culling by [`View::faces`] — the very test the tree
//!   walk uses.
//! - [`painter_ids`] draws polygons in a given back-to-front order of classes
//!   (later overwrite earlier) with the same coverage test and no depth test:
//!   the picture a tree order produces. With a correct order the two agree on
//!   every pixel that the [`RefFrame`] does not mark as unsure.
//! - A pixel is unsure when its result could depend on rounding: `near_edge`
//!   (its sample lies within `edge_px` of the outline of a polygon that is not
//!   clearly behind the visible surface there: by more than the depth the two
//!   planes change over `edge_px` pixels, so that a face touching the visible
//!   one along that outline counts) or `tie` (the two nearest
//!   covering polygons are within `tie_rel × scene diagonal` in depth, e.g.
//!   where faces touch or coincide). With culling, the outlines of culled
//!   polygons seen almost edge-on (`|n · dir| ≤ edge_on_rel`, or the eye
//!   within `edge_on_rel × scene diagonal` of the plane) count too: a walk
//!   that tests facing with other rounding (`f32`) may draw them.
//! - Cost is O(pixels × polygons) in the worst case, pruned by each polygon's
//!   screen bounding box.

pub mod camera;
mod raster;

pub use camera::{Camera, Projection, View};

use crate::geom::{bounds, Polygon};
use glam::DVec3;
use raster::Screen;

/// Options of [`zbuffer`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefOptions {
    /// Skip polygons that do not face the viewer (closed volumes).
    pub cull_backfaces: bool,
    /// Pixels whose sample is within this many pixels of a relevant outline
    /// are marked `near_edge`.
    pub edge_px: f64,
    /// Depth differences below `tie_rel × scene diagonal` are ties.
    pub tie_rel: f64,
    /// A culled polygon seen within this of edge-on (see the module docs)
    /// still marks its outline as unsure.
    pub edge_on_rel: f64,
}

impl Default for RefOptions {
    fn default() -> Self {
        RefOptions {
            cull_backfaces: false,
            edge_px: 0.5,
            tie_rel: 1e-6,
            edge_on_rel: 1e-6,
        }
    }
}

/// A reference picture with the pixels whose result is not certain.
#[derive(Clone, Debug, PartialEq)]
pub struct RefFrame {
    /// Per pixel, row by row from the top: polygon index + 1, 0 = background.
    pub ids: Vec<u32>,
    /// The sample lies near the outline of a polygon that may be visible.
    pub near_edge: Vec<bool>,
    /// The two nearest covering polygons are at (almost) the same depth.
    pub tie: Vec<bool>,
    /// Width in pixels.
    pub w: usize,
    /// Height in pixels.
    pub h: usize,
}

/// How a picture compares with a [`RefFrame`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Diff {
    /// Pixels compared (not unsure).
    pub compared: usize,
    /// Pixels left out because they are unsure.
    pub unsure: usize,
    /// Compared pixels that differ.
    pub wrong: usize,
    /// The first wrong pixel: x, y, reference id, other id.
    pub first_wrong: Option<(usize, usize, u32, u32)>,
}

impl RefFrame {
    /// Whether pixel `i` (row-major index) is unsure.
    pub fn unsure(&self, i: usize) -> bool {
        self.near_edge[i] || self.tie[i]
    }

    /// Compares `ids` (same size) with this frame on the sure pixels.
    pub fn diff(&self, ids: &[u32]) -> Diff {
        let mut d = Diff::default();
        for (i, (&want, &got)) in self.ids.iter().zip(ids).enumerate() {
            if self.unsure(i) {
                d.unsure += 1;
                continue;
            }
            d.compared += 1;
            if want != got {
                d.wrong += 1;
                if d.first_wrong.is_none() {
                    d.first_wrong = Some((i % self.w, i / self.w, want, got));
                }
            }
        }
        d
    }
}

/// The pixel rays of a camera: near point and near→far vector per pixel.
struct Rays {
    origin: Vec<DVec3>,
    dir: Vec<DVec3>,
    /// Model length of `dir`, to turn the ray parameter into a distance.
    len: Vec<f64>,
}

impl Rays {
    fn new(cam: &Camera, w: usize, h: usize) -> Rays {
        let n = w * h;
        let mut r = Rays {
            origin: Vec::with_capacity(n),
            dir: Vec::with_capacity(n),
            len: Vec::with_capacity(n),
        };
        for j in 0..h {
            for i in 0..w {
                let x = (i as f64 + 0.5) / w as f64 * 2.0 - 1.0;
                let y = 1.0 - (j as f64 + 0.5) / h as f64 * 2.0;
                let a = cam.unproject(DVec3::new(x, y, -1.0));
                let b = cam.unproject(DVec3::new(x, y, 1.0));
                let (a, b) = match (a, b) {
                    (Some(a), Some(b)) => (a, b),
                    _ => (DVec3::NAN, DVec3::NAN),
                };
                r.origin.push(a);
                r.dir.push(b - a);
                r.len.push((b - a).length());
            }
        }
        r
    }

    /// Distance from the near plane at which ray `p` meets the polygon's
    /// plane; NaN or infinite when it runs parallel to it.
    fn depth(&self, poly: &Polygon, p: usize) -> f64 {
        let n = poly.plane.normal;
        let t = -(n.dot(self.origin[p]) + poly.plane.d) / n.dot(self.dir[p]);
        t * self.len[p]
    }
}

impl Rays {
    /// How much the depth of `poly`'s plane changes from ray `p` to its
    /// neighbours (the larger of one column and one row; NaN when a ray
    /// runs parallel to the plane).
    fn step(&self, poly: &Polygon, p: usize, w: usize, h: usize) -> f64 {
        let (i, j) = (p % w.max(1), p / w.max(1));
        let col = if i + 1 < w {
            p + 1
        } else {
            p.saturating_sub(1)
        };
        let row = if j + 1 < h {
            p + w
        } else {
            p.saturating_sub(w)
        };
        let z = self.depth(poly, p);
        (self.depth(poly, col) - z)
            .abs()
            .max((self.depth(poly, row) - z).abs())
    }
}

/// One polygon that takes part, with its projection.
struct Candidate<'a> {
    id: u32,
    poly: &'a Polygon,
    screen: Screen,
    /// Drawn; otherwise culled but so close to edge-on that a walk with
    /// other rounding may draw it, so its outline still makes pixels unsure.
    drawn: bool,
}

/// Whether the view sees `plane` within `rel` of edge-on: `|n · dir| ≤ rel`
/// for a parallel view, the eye within `rel × diag` of the plane otherwise.
fn edge_on(view: &View, plane: &crate::geom::Plane, rel: f64, diag: f64) -> bool {
    match *view {
        View::Parallel { dir } => plane.normal.dot(dir).abs() <= rel,
        View::Perspective { eye } => plane.distance(eye).abs() <= rel * diag,
    }
}

/// The polygons that take part, with their projections.
fn candidates<'a>(
    polys: &'a [Polygon],
    cam: &Camera,
    w: usize,
    h: usize,
    opt: &RefOptions,
    diag: f64,
) -> Vec<Candidate<'a>> {
    let view = cam.view();
    polys
        .iter()
        .enumerate()
        .filter_map(|(k, poly)| {
            let drawn = !opt.cull_backfaces || view.faces(&poly.plane);
            if !drawn && !edge_on(&view, &poly.plane, opt.edge_on_rel, diag) {
                return None;
            }
            let screen = Screen::project(cam, &poly.verts, w, h)?;
            Some(Candidate {
                id: k as u32 + 1,
                poly,
                screen,
                drawn,
            })
        })
        .collect()
}

/// The exact z-buffer picture of `polys` with the unsure pixels marked.
pub fn zbuffer(polys: &[Polygon], cam: &Camera, w: usize, h: usize, opt: RefOptions) -> RefFrame {
    let n = w * h;
    let rays = Rays::new(cam, w, h);
    let (lo, hi) = bounds(polys);
    let diag = if polys.is_empty() {
        0.0
    } else {
        (hi - lo).length()
    };
    let slack = opt.tie_rel * diag;
    let mut ids = vec![0u32; n];
    let mut best = vec![f64::INFINITY; n];
    let mut second = vec![f64::INFINITY; n];
    let cands = candidates(polys, cam, w, h, &opt, diag);
    for part in cands.iter().filter(|p| p.drawn) {
        let (poly, s) = (part.poly, &part.screen);
        let Some((i0, i1, j0, j1)) = s.pixel_box(w, h, 0.0) else {
            continue;
        };
        for j in j0..=j1 {
            for i in i0..=i1 {
                if !s.covers(i as f64 + 0.5, j as f64 + 0.5) {
                    continue;
                }
                let p = j * w + i;
                let z = rays.depth(poly, p);
                if !z.is_finite() {
                    continue;
                }
                if z < best[p] {
                    second[p] = best[p];
                    best[p] = z;
                    ids[p] = part.id;
                } else if z < second[p] {
                    second[p] = z;
                }
            }
        }
    }
    let tie: Vec<bool> = (0..n).map(|p| second[p] - best[p] <= slack).collect();
    // Outlines matter where the polygon is not clearly behind the visible
    // surface: in front of it (it might cover the sample with other
    // rounding) or level with it (touching faces).
    let mut near_edge = vec![false; n];
    for part in &cands {
        let (poly, s) = (part.poly, &part.screen);
        let Some((i0, i1, j0, j1)) = s.pixel_box(w, h, opt.edge_px) else {
            continue;
        };
        for j in j0..=j1 {
            for i in i0..=i1 {
                let p = j * w + i;
                if near_edge[p] || s.edge_distance(i as f64 + 0.5, j as f64 + 0.5) > opt.edge_px {
                    continue;
                }
                // "Clearly behind" allows for the depth both surfaces
                // change over the margin: a face touching the visible one
                // along this outline (a jaw standing on a base) is behind
                // it at the sample only by that much, and rounding may let
                // it cover the sample.
                let visible = ids[p].checked_sub(1).and_then(|k| polys.get(k as usize));
                let allow = opt.edge_px
                    * (rays.step(poly, p, w, h) + visible.map_or(0.0, |v| rays.step(v, p, w, h)));
                let behind = rays.depth(poly, p) > best[p] + slack + allow;
                near_edge[p] = !behind;
            }
        }
    }
    RefFrame {
        ids,
        near_edge,
        tie,
        w,
        h,
    }
}

/// Per pixel the nearest polygon's index + 1 (0 = background), default
/// options but for `cull_backfaces`.
pub fn zbuffer_ids(
    polys: &[Polygon],
    cam: &Camera,
    w: usize,
    h: usize,
    cull_backfaces: bool,
) -> Vec<u32> {
    let opt = RefOptions {
        cull_backfaces,
        ..RefOptions::default()
    };
    zbuffer(polys, cam, w, h, opt).ids
}

/// Draws the polygons of `classes` (back to front; ids index `polys`) over
/// one another, no depth test: per pixel the last one drawn, index + 1.
/// Ids out of range are skipped (the order checks report them).
pub fn painter_ids(
    polys: &[Polygon],
    classes: &[Vec<u32>],
    cam: &Camera,
    w: usize,
    h: usize,
) -> Vec<u32> {
    let mut ids = vec![0u32; w * h];
    for &k in classes.iter().flatten() {
        let Some(poly) = polys.get(k as usize) else {
            continue;
        };
        let Some(s) = Screen::project(cam, &poly.verts, w, h) else {
            continue;
        };
        let Some((i0, i1, j0, j1)) = s.pixel_box(w, h, 0.0) else {
            continue;
        };
        for j in j0..=j1 {
            for i in i0..=i1 {
                if s.covers(i as f64 + 0.5, j as f64 + 0.5) {
                    ids[j * w + i] = k + 1;
                }
            }
        }
    }
    ids
}

/// Pixels of the `w`-wide ids buffer `got` that differ from `want`, not
/// counting pixels on an outline of `want` (one with a 4-neighbour of
/// another id), where rounding vertices (of a scaled or moved model, of a
/// different precision) may tip a sample to the other side.
pub fn differences_off_outlines(want: &[u32], got: &[u32], w: usize) -> usize {
    let h = want.len() / w.max(1);
    let at = |x: i64, y: i64| -> Option<u32> {
        ((0..w as i64).contains(&x) && (0..h as i64).contains(&y))
            .then(|| want[y as usize * w + x as usize])
    };
    (0..w * h)
        .filter(|&i| {
            let (x, y) = ((i % w) as i64, (i / w) as i64);
            let on_outline = [(1, 0), (-1, 0), (0, 1), (0, -1)]
                .iter()
                .any(|(dx, dy)| at(x + dx, y + dy).is_some_and(|v| v != want[i]));
            got.get(i) != Some(&want[i]) && !on_outline
        })
        .count()
}

#[cfg(test)]
mod tests;
