//! A z-buffer renderer built from the same pipeline as the painter path,
//! for the frame-time comparison only (it is not part of the product).
//!
//! What is shared with the painter path, so that the difference measured is
//! the visibility method alone: the [`Renderer`] (same fixed-point
//! transform, clipping, projection, shading and scanline coverage — every
//! polygon covers exactly the pixels it covers in the painter path), the
//! scratch, the camera ([`Frame`]) and the back-face test
//! ([`LocalView::is_backward`] on the same plane, same two-sided lighting).
//!
//! What differs:
//! * the polygons are the scene's input faces (no splitting, no tree), in
//!   input order;
//! * a `W × H` buffer of `u16` depths is cleared every frame, and every
//!   pixel of every span is depth-tested (`<`: the first of equal depths
//!   stays) before it is written.
//!
//! Depth is a quantity that is linear in screen space, so a span steps it
//! by a constant: `1 − w_min / w` for a perspective camera (affine in
//! `1 / w`), the clip `z / w` for a parallel one, each mapped so that the
//! scene's bounding sphere spans `[0, 1]`, then to 16 bits with 8 more
//! fraction bits while stepping. Each polygon's depth plane
//! `D = d0 + dx·x + dy·y` (pixel coordinates) is fitted once, with Newell's
//! method over its projected vertices (exact for a planar polygon: a
//! projective map keeps planes planar). The vertices are projected in `f32`
//! for this; only the depth comes from it, never the coverage.
//!
//! Limitation: a polygon with a vertex behind the eye (`w ≤ 0`) has no
//! projected plane here; it is drawn at depth 0 and counted in
//! [`ZStats::behind`]. The benchmark views have none (checked).

use embedded_graphics::pixelcolor::{IntoStorage, Rgb565};
use fpt_nostd::order::LocalView;
use fpt_nostd::raster::{Face, Mat4, Paint, Renderer, Scratch, SpanBounds, SpanSink};
use fpt_nostd::reader::Plane;
use fpt_nostd::render::Frame;
use host_sim::scenes::Scene;

use crate::common::{light, P, VERTS};

/// Fraction bits of the stepped depth, below the 16 stored bits.
const FRAC: u32 = 8;
/// `1.0` of normalised depth in stepped units.
const ONE: f32 = (65535u32 << FRAC) as f32;

/// One input face, in the renderer's coordinates before the frame scale.
struct ZPoly {
    /// Vertices relative to the tree's origin.
    verts: Vec<[f32; 3]>,
    /// Its plane relative to the origin (the painter's facing test).
    plane: Plane,
    color: [u8; 3],
    id: u32,
}

/// The scene as a z-buffer renderer stores it: input faces, input order.
pub struct ZMesh {
    polys: Vec<ZPoly>,
    closed: bool,
}

impl ZMesh {
    /// The faces of `scene`, made relative to `origin` (the tree's origin,
    /// so that both paths see the same coordinates).
    pub fn new(scene: &Scene, origin: [f64; 3]) -> ZMesh {
        let polys = scene
            .polygons
            .iter()
            .map(|p| {
                let n = p.plane.normal;
                let d = p.plane.d + n.x * origin[0] + n.y * origin[1] + n.z * origin[2];
                ZPoly {
                    verts: p
                        .verts
                        .iter()
                        .map(|v| {
                            [
                                (v.x - origin[0]) as f32,
                                (v.y - origin[1]) as f32,
                                (v.z - origin[2]) as f32,
                            ]
                        })
                        .collect(),
                    plane: Plane {
                        normal: [n.x as f32, n.y as f32, n.z as f32],
                        d: d as f32,
                    },
                    color: p.color,
                    id: p.source,
                }
            })
            .collect();
        ZMesh {
            polys,
            closed: scene.closed,
        }
    }

    /// Number of faces.
    pub fn len(&self) -> usize {
        self.polys.len()
    }
}

/// Normalised depth `D = alpha + beta·(z/w) + gamma/w` of a clip vertex.
#[derive(Clone, Copy, Debug)]
struct DepthMap {
    alpha: f32,
    beta: f32,
    gamma: f32,
}

impl DepthMap {
    /// The map for `m` that sends the sphere of `radius` about the
    /// coordinate origin to `[0, 1]` (see the module docs).
    fn new(m: &Mat4, near_w: f32, radius: f32) -> DepthMap {
        let len = |r: [f32; 4]| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let (rz, rw) = (m.0[2], m.0[3]);
        if len(rw) > 0.0 {
            let wmin = (rw[3] - radius * len(rw)).max(near_w);
            let wmax = (rw[3] + radius * len(rw)).max(wmin * 1.001);
            let c = 1.0 / (1.0 - wmin / wmax);
            DepthMap {
                alpha: c,
                beta: 0.0,
                gamma: -c * wmin,
            }
        } else {
            let w = rw[3];
            let (zc, half) = (
                rz[3] / w,
                (radius * len(rz) / w.abs()).max(f32::MIN_POSITIVE),
            );
            DepthMap {
                alpha: -(zc - half) / (2.0 * half),
                beta: 1.0 / (2.0 * half),
                gamma: 0.0,
            }
        }
    }
}

/// A polygon's depth plane in pixel coordinates, in `[0, 1]` units.
#[derive(Clone, Copy, Debug, Default)]
struct DepthPlane {
    d0: f32,
    dx: f32,
    dy: f32,
}

/// Counters of one z-buffer frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ZStats {
    /// Faces culled as back faces.
    pub culled: u32,
    /// Faces with a vertex behind the eye (drawn at depth 0).
    pub behind: u32,
    /// Pixels depth-tested.
    pub tested: u64,
    /// Pixels that passed and were written.
    pub written: u64,
}

/// Colour and depth buffers and the current polygon's depth plane.
pub struct ZTarget<'a> {
    color: &'a mut [u16],
    depth: &'a mut [u16],
    w: usize,
    h: usize,
    plane: DepthPlane,
    /// Counted while drawing (two adds per span).
    pub stats: ZStats,
}

impl<'a> ZTarget<'a> {
    /// Wraps `w × h` colour and depth buffers.
    pub fn new(color: &'a mut [u16], depth: &'a mut [u16], w: u32, h: u32) -> ZTarget<'a> {
        let (w, h) = (w as usize, h as usize);
        assert!(color.len() >= w * h && depth.len() >= w * h, "buffer size");
        ZTarget {
            color,
            depth,
            w,
            h,
            plane: DepthPlane::default(),
            stats: ZStats::default(),
        }
    }
}

impl SpanSink for ZTarget<'_> {
    type Color = u16;
    fn color(&self, paint: &Paint) -> u16 {
        Rgb565::from(paint.rgb).into_storage()
    }
    fn bounds(&self) -> SpanBounds {
        SpanBounds::of_size(self.w as u32, self.h as u32)
    }
    fn span(&mut self, y: i32, x0: i32, x1: i32, c: u16) {
        let (x0, x1) = (x0.max(0) as usize, x1.max(0) as usize);
        if y < 0 || y as usize >= self.h || x1 > self.w || x0 >= x1 {
            return;
        }
        let n = x1 - x0;
        let p = self.plane;
        // Depth at the first and last pixel centres, clamped (a centre on
        // the outline may extrapolate a little past the polygon's range).
        let first = p.d0 + p.dx * (x0 as f32 + 0.5) + p.dy * (y as f32 + 0.5);
        let last = first + p.dx * (n - 1) as f32;
        let fx = |d: f32| (d.clamp(0.0, 1.0) * ONE) as i32;
        let (z0, z1) = (fx(first), fx(last));
        let step = if n > 1 { (z1 - z0) / (n as i32 - 1) } else { 0 };
        let at = y as usize * self.w + x0;
        let mut z = z0;
        let mut written = 0u64;
        for (d, px) in self.depth[at..at + n]
            .iter_mut()
            .zip(&mut self.color[at..at + n])
        {
            let zz = (z >> FRAC) as u16;
            if zz < *d {
                *d = zz;
                *px = c;
                written += 1;
            }
            z += step;
        }
        self.stats.tested += n as u64;
        self.stats.written += written;
    }
}

/// The z-buffer path: the same [`Renderer`] and scratch as the painter.
pub struct ZRenderer {
    renderer: Renderer<P>,
    scratch: Box<Scratch<P, VERTS>>,
}

impl ZRenderer {
    /// A renderer for `w × h` frames lit like the painter's.
    pub fn new(w: u32, h: u32, frame: &Frame) -> ZRenderer {
        let mut renderer = Renderer::new(w, h, &frame.camera).expect("renderer size");
        renderer.set_light(light(frame));
        ZRenderer {
            renderer,
            scratch: Box::new(Scratch::new()),
        }
    }

    /// Faces drawn (transformed and scan-converted) in the last frame.
    pub fn drawn(&self) -> u32 {
        self.renderer.stats().drawn
    }

    /// Faces the renderer skipped in the last frame.
    pub fn skipped(&self) -> u32 {
        self.renderer.stats().skipped
    }

    /// One frame: clears both buffers, then draws every face of `mesh` in
    /// input order with the depth test. `view` is the frame's view
    /// relative to the tree's origin; `radius` the tree's bounding radius.
    pub fn draw(
        &mut self,
        mesh: &ZMesh,
        frame: &Frame,
        view: &LocalView,
        radius: f32,
        target: &mut ZTarget<'_>,
        background: u16,
    ) -> ZStats {
        target.color[..target.w * target.h].fill(background);
        target.depth[..target.w * target.h].fill(u16::MAX);
        target.stats = ZStats::default();
        self.renderer.set_camera(&frame.camera);
        self.renderer.reset_stats();
        let m = frame.camera.matrix;
        let scale = frame.vertex_scale;
        let map = DepthMap::new(&m, frame.camera.near_w, radius * scale);
        let (w, h) = (target.w as f32, target.h as f32);
        for p in &mesh.polys {
            let facing = view.is_backward(&p.plane);
            if mesh.closed && !facing {
                target.stats.culled += 1;
                continue;
            }
            let normal = if facing {
                p.plane.normal
            } else {
                p.plane.normal.map(|c| -c)
            };
            let scaled = p
                .verts
                .iter()
                .map(|v| [v[0] * scale, v[1] * scale, v[2] * scale]);
            match depth_plane(scaled.clone(), &m, &map, w, h) {
                Some(dp) => target.plane = dp,
                None => {
                    target.stats.behind += 1;
                    target.plane = DepthPlane::default();
                }
            }
            let face = Face {
                normal: normal.into(),
                color: p.color,
                id: p.id,
                hidden_edges: 0,
            };
            self.renderer
                .draw_polygon(&mut *self.scratch, scaled, &face, &mut *target);
        }
        target.stats
    }
}

/// Newell's plane through the projected vertices `(x, y, D)` (pixel
/// coordinates, normalised depth); `None` when a vertex is behind the eye.
fn depth_plane(
    verts: impl Iterator<Item = [f32; 3]>,
    m: &Mat4,
    map: &DepthMap,
    w: f32,
    h: f32,
) -> Option<DepthPlane> {
    let mut pts = [[0.0f32; 3]; VERTS];
    let mut n = 0usize;
    for v in verts {
        let c = m.transform_point(v);
        if c[3] <= 0.0 || n == VERTS {
            return None;
        }
        let inv = 1.0 / c[3];
        pts[n] = [
            (c[0] * inv + 1.0) * 0.5 * w,
            (1.0 - c[1] * inv) * 0.5 * h,
            map.alpha + map.beta * c[2] * inv + map.gamma * inv,
        ];
        n += 1;
    }
    let pts = &pts[..n];
    let (mut nx, mut ny, mut nz) = (0.0f32, 0.0f32, 0.0f32);
    let mut cen = [0.0f32; 3];
    for (i, a) in pts.iter().enumerate() {
        let b = pts[(i + 1) % n];
        nx += (a[1] - b[1]) * (a[2] + b[2]);
        ny += (a[2] - b[2]) * (a[0] + b[0]);
        nz += (a[0] - b[0]) * (a[1] + b[1]);
        for k in 0..3 {
            cen[k] += a[k] / n as f32;
        }
    }
    // Edge-on in screen space: it covers (almost) no pixel; any constant
    // depth will do.
    if nz.abs() <= 1e-6 * (nx.abs() + ny.abs() + nz.abs()) {
        return Some(DepthPlane {
            d0: cen[2],
            dx: 0.0,
            dy: 0.0,
        });
    }
    let (dx, dy) = (-nx / nz, -ny / nz);
    Some(DepthPlane {
        d0: cen[2] - dx * cen[0] - dy * cen[1],
        dx,
        dy,
    })
}
