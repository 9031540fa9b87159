//! Exact sampling of one polygon: projection with near/far clipping, the
//! point-in-polygon test at a pixel centre and the distance to its outline.
//!
//! The z-buffer and the painter both decide coverage with [`Screen::covers`]
//! on the same [`Screen`], so their pictures can differ only where their
//! depth decisions differ, never through coverage.

use super::camera::Camera;
use glam::{DVec3, DVec4};

/// A polygon projected to pixel coordinates, clipped to `−w ≤ z ≤ w`.
#[derive(Clone, Debug)]
pub(crate) struct Screen {
    /// Outline in pixel coordinates (x right, y down).
    pts: Vec<[f64; 2]>,
    /// Bounds of the outline: min x, min y, max x, max y.
    bounds: [f64; 4],
}

/// Keeps the part of a homogeneous polygon where `f ≥ 0` (Sutherland–Hodgman).
fn clip_by(poly: &[DVec4], f: impl Fn(DVec4) -> f64) -> Vec<DVec4> {
    let mut out = Vec::with_capacity(poly.len() + 2);
    for i in 0..poly.len() {
        let a = poly[i];
        let b = poly[(i + 1) % poly.len()];
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

impl Screen {
    /// Projects `verts` with `cam` into a `w × h` image; `None` when nothing
    /// of the polygon lies between the near and far planes.
    pub(crate) fn project(cam: &Camera, verts: &[DVec3], w: usize, h: usize) -> Option<Screen> {
        let clip: Vec<DVec4> = verts.iter().map(|&v| cam.clip(v)).collect();
        let clip = clip_by(&clip, |c| c.z + c.w);
        let clip = clip_by(&clip, |c| c.w - c.z);
        // Both planes together imply w ≥ 0; a vertex at w = 0 has no image.
        if clip.len() < 3 || clip.iter().any(|c| c.w.is_nan() || c.w <= 0.0) {
            return None;
        }
        let (wf, hf) = (w as f64, h as f64);
        let pts: Vec<[f64; 2]> = clip
            .iter()
            .map(|c| [(c.x / c.w + 1.0) * 0.5 * wf, (1.0 - c.y / c.w) * 0.5 * hf])
            .collect();
        let mut bounds = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        for p in &pts {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return None;
            }
            bounds[0] = bounds[0].min(p[0]);
            bounds[1] = bounds[1].min(p[1]);
            bounds[2] = bounds[2].max(p[0]);
            bounds[3] = bounds[3].max(p[1]);
        }
        Some(Screen { pts, bounds })
    }

    /// Pixel columns and rows whose sample lies within `margin` px of the
    /// bounds: `(i0, i1, j0, j1)`, inclusive, or `None` when off screen.
    pub(crate) fn pixel_box(
        &self,
        w: usize,
        h: usize,
        margin: f64,
    ) -> Option<(usize, usize, usize, usize)> {
        let range = |lo: f64, hi: f64, n: usize| {
            // Sample i is at i + 0.5: it is in [lo, hi] when i ∈ [lo − ½, hi − ½].
            let a = (lo - margin - 0.5).ceil().max(0.0);
            let b = (hi + margin - 0.5).floor().min(n as f64 - 1.0);
            (a <= b).then_some((a as usize, b as usize))
        };
        let (i0, i1) = range(self.bounds[0], self.bounds[2], w)?;
        let (j0, j1) = range(self.bounds[1], self.bounds[3], h)?;
        Some((i0, i1, j0, j1))
    }

    /// Whether the point `(x, y)` is inside (even–odd rule, so concave
    /// outlines work). Points exactly on the outline go one way or the other,
    /// the same way every time.
    pub(crate) fn covers(&self, x: f64, y: f64) -> bool {
        let mut inside = false;
        let n = self.pts.len();
        for i in 0..n {
            let a = self.pts[i];
            let b = self.pts[(i + 1) % n];
            if (a[1] > y) != (b[1] > y) {
                let xc = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                if x < xc {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// Distance in pixels from `(x, y)` to the outline.
    pub(crate) fn edge_distance(&self, x: f64, y: f64) -> f64 {
        let n = self.pts.len();
        let mut best = f64::INFINITY;
        for i in 0..n {
            let a = self.pts[i];
            let b = self.pts[(i + 1) % n];
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let (px, py) = (x - a[0], y - a[1]);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 {
                ((px * dx + py * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (ex, ey) = (px - t * dx, py - t * dy);
            best = best.min((ex * ex + ey * ey).sqrt());
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::camera::Projection;

    fn top_camera() -> Camera {
        let p = Projection::Parallel {
            half_height: 1.0,
            near: 0.0,
            far: 10.0,
        };
        Camera::look_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y, p, 1.0).unwrap()
    }

    #[test]
    fn concave_outline_is_covered_by_even_odd_rule() {
        // An L shape in the plane z = 0 seen from above; the camera maps
        // [-1, 1]² onto a 20 × 20 image, so model x = -1 + i/10.
        let l = [
            DVec3::new(-0.5, -0.5, 0.0),
            DVec3::new(0.5, -0.5, 0.0),
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::new(-0.5, 0.5, 0.0),
        ];
        let s = Screen::project(&top_camera(), &l, 20, 20).unwrap();
        let px = |x: f64, y: f64| ((x + 1.0) * 10.0, (1.0 - y) * 10.0);
        let (x, y) = px(-0.25, 0.25);
        assert!(s.covers(x, y));
        let (x, y) = px(0.25, -0.25);
        assert!(s.covers(x, y));
        let (x, y) = px(0.25, 0.25); // the notch
        assert!(!s.covers(x, y));
        assert!((s.edge_distance(x, y) - 2.5).abs() < 1e-9);
        assert_eq!(s.pixel_box(20, 20, 0.0), Some((5, 14, 5, 14)));
    }

    #[test]
    fn polygon_behind_the_eye_is_clipped_away() {
        let p = Projection::Perspective {
            fov_y_deg: 90.0,
            near: 0.1,
            far: 10.0,
        };
        let cam = Camera::look_at(DVec3::ZERO, -DVec3::Z, DVec3::Y, p, 1.0).unwrap();
        let behind = [
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(1.0, -1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        assert!(Screen::project(&cam, &behind, 16, 16).is_none());
        // A floor from behind the eye to in front of it keeps only the part
        // in front: the lower half of the image.
        let floor = [
            DVec3::new(-5.0, -1.0, 5.0),
            DVec3::new(5.0, -1.0, 5.0),
            DVec3::new(5.0, -1.0, -5.0),
            DVec3::new(-5.0, -1.0, -5.0),
        ];
        let s = Screen::project(&cam, &floor, 16, 16).unwrap();
        assert!(s.covers(8.5, 15.5));
        assert!(!s.covers(8.5, 0.5));
        assert!(!s.covers(8.5, 7.5));
    }
}
