//! Gouraud shading, the `smooth` effect ([`crate::effects::Effects::SMOOTH`]):
//! a lit colour per polygon corner, interpolated across the polygon.
//!
//! # Contract
//!
//! * **Corner colours**: each corner is lit like a flat face
//!   ([`super::shade`]: ambient plus diffuse from the frame's light, the
//!   shading mode, the face colour) but by its vertex normal: the tree's
//!   corner normal section ([`crate::format`]) when it has one (flipped with
//!   the face when two-sided lighting shows its back); a tree without that
//!   section is drawn flat, as every corner would have the face's colour;
//!   then faded by depth cueing exactly as the flat colour is (the
//!   polygon's mean depth). The lighting of an `i8` normal is integer
//!   ([`super::shade::Light::intensity_i8`]), so every precision draws the
//!   same corner colours, fixed point and `f32` alike.
//! * **Interpolation**: screen-space (not perspective-corrected, as
//!   Gouraud shading always was), per channel in 8.16 fixed point: the
//!   colour is the affine function of the pixel centre through three
//!   corners, for a triangle exactly the interpolation along its edges
//!   and then along each span. A polygon with more corners uses the three
//!   of its widest fan triangle from corner 0 (its other corners' colours
//!   are not matched exactly). The fill is the flat one ([`super::scan`]),
//!   so coverage is identical; this module's `SmoothSink` receives its
//!   spans and paints each as runs of equal native colour through the
//!   target's own sink ([`SpanSink::color`] when the 8-bit colour changes,
//!   [`SpanSink::span`] when the native one does: an RGB565 target takes a
//!   run per 4 or 8 levels), so dithering, `Gray8` and `BinaryColor`
//!   targets, bands and id buffers all work unchanged.
//! * **Equal corner colours draw the flat colour exactly**: the gradient
//!   is then zero and every pixel rounds to the corners' colour.
//! * **Clipped polygons** (crossing the near plane or the guard band) are
//!   drawn flat: their corners are no longer the tree's.
//! * **Free when off**: the renderer tests one flag per polygon; a pipeline
//!   compiled without `smooth` has none of this code.
//!
//! Cost: three corner colours, two 64-bit divisions per channel and
//! polygon, then per pixel three additions, three shifts and a
//! comparison, a [`SpanSink::color`] call per change of the 8-bit colour
//! and a [`SpanSink::span`] call per run of equal native colour.

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};

use super::edge::Edge;
use super::precision::Precision;
use super::renderer::{Face, Ready, Renderer, Scratch};
use super::scan::{fill_polygon_in, Bbox, FillError, FillRule, Paint, SpanBounds, SpanSink};
use super::shade::{shade_color, DepthCue, Light, ShadeMode};
use super::transform::ScreenPt;
use crate::effects::{Compiled, Effects};
use crate::fixed::Fx14;
use crate::reader::{PolygonAt, Tree};

/// Fraction bits of an interpolated channel.
const FRAC: u32 = 16;
/// Largest channel value, in 8.16.
const TOP: i64 = (255 << FRAC) | ((1 << FRAC) - 1);
/// Bound of a stored value or step, so that no product below overflows.
const LIMIT: i64 = 1 << 30;

/// One polygon's colour plane: channel `k` at the centre of pixel
/// `(x, y)` is `c[k] + gx[k]·(x − px) + gy[k]·(y − py)`, in 8.16 fixed
/// point (the half for rounding included).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Smooth {
    px: i32,
    py: i32,
    c: [i32; 3],
    gx: [i32; 3],
    gy: [i32; 3],
}

impl<P: Precision, E: Compiled> Renderer<P, E> {
    /// The colour plane of polygon `p` of `tree`, prepared for the fill
    /// (`ready`, its points in `scratch`) as `face`: its widest triangle's
    /// corners lit by their stored normals (see the module docs). `None`
    /// for a clipped polygon, which is drawn flat. Out of line, to keep the
    /// walk's loop small (see docs/effects.md on what the flat path still pays).
    #[inline(never)]
    pub(crate) fn smooth_plane<X: Compiled, const N: usize>(
        &self,
        scratch: &Scratch<P, N>,
        ready: &Ready,
        tree: &Tree<'_>,
        p: &PolygonAt<'_, '_>,
        face: &Face,
    ) -> Option<Smooth> {
        if ready.clipped {
            return None;
        }
        let pts = scratch.screen().get(..ready.n)?;
        let (k, _) = widest(pts)?;
        let rgb = {
            let (light, mode, cue) = self.lighting();
            let lit = CornerLight {
                light,
                mode,
                color: face.color,
                cue: self
                    .effects_as::<X>()
                    .contains(Effects::DEPTH_CUE)
                    .then_some((cue, ready.depth)),
            };
            // Two-sided lighting flipped the face's normal: flip its corners'.
            let flip = p.plane().normal_dot(face.normal.to_f32()) < 0.0;
            k.map(|i| match tree.corner_normal(p.id(), i) {
                Some(n) => lit.corner(n, flip),
                None => ready.rgb,
            })
        };
        Some(Smooth::new(
            k.map(|i| pts[i]),
            rgb,
            self.viewport().sub_bits(),
        ))
    }
}

/// What lights a corner: the frame's light, mode and depth cue, and the
/// face's colour and depth.
#[derive(Clone, Copy, Debug)]
struct CornerLight<'a> {
    light: &'a Light,
    mode: ShadeMode,
    color: [u8; 3],
    /// Depth cueing and the polygon's mean depth, when the effect is on.
    cue: Option<(&'a DepthCue, f32)>,
}

impl CornerLight<'_> {
    /// The colour of a corner lit with `intensity`.
    #[inline]
    fn color_of(&self, intensity: Fx14) -> Rgb888 {
        let c = shade_color(self.mode, self.color, intensity);
        match self.cue {
            Some((cue, depth)) => cue.apply(c, depth),
            None => c,
        }
    }

    /// The colour of a corner with stored normal `n` (times 127), flipped
    /// when `flip`.
    #[inline]
    fn corner(&self, n: [i8; 3], flip: bool) -> Rgb888 {
        // (The reader has rejected −128, so negating is exact.)
        let n = if flip { n.map(i8::saturating_neg) } else { n };
        let i = match self.mode {
            ShadeMode::Flat => Fx14::ONE,
            _ => self.light.intensity_i8(n),
        };
        self.color_of(i)
    }
}

/// The corners (indices into `pts`) of the widest fan triangle
/// `(0, i, i + 1)` and twice its signed area (screen units); `None` for
/// fewer than 3 points.
pub(crate) fn widest(pts: &[ScreenPt]) -> Option<([usize; 3], i64)> {
    let a = *pts.first()?;
    let mut best: Option<([usize; 3], i64)> = None;
    for i in 1..pts.len().saturating_sub(1) {
        let (b, c) = (pts[i], pts[i + 1]);
        let area = area2(a, b, c);
        if best.is_none_or(|(_, w)| area.abs() > w.abs()) {
            best = Some(([0, i, i + 1], area));
        }
    }
    best
}

/// Twice the signed area of triangle `abc`, exact (screen points are far
/// below 2^30).
#[inline]
fn area2(a: ScreenPt, b: ScreenPt, c: ScreenPt) -> i64 {
    let d = |p: ScreenPt, q: ScreenPt| (i64::from(q.x - p.x), i64::from(q.y - p.y));
    let ((bx, by), (cx, cy)) = (d(a, b), d(a, c));
    bx * cy - cx * by
}

impl Smooth {
    /// The colour plane through corners `p[k]` of colours `rgb[k]` (screen
    /// points with `sub` fraction bits); a degenerate triangle gets the
    /// mean colour everywhere.
    pub(crate) fn new(p: [ScreenPt; 3], rgb: [Rgb888; 3], sub: u32) -> Smooth {
        let sub = sub.min(16);
        let chans =
            |c: Rgb888| [c.r(), c.g(), c.b()].map(|v| (i64::from(v) << FRAC) + (1 << (FRAC - 1)));
        let v = rgb.map(chans);
        // The pixel holding corner 0, and its centre in screen units.
        let (px, py) = (p[0].x >> sub, p[0].y >> sub);
        let half = (1i64 << sub) >> 1;
        let (cx, cy) = (
            (i64::from(px) << sub) + half - i64::from(p[0].x),
            (i64::from(py) << sub) + half - i64::from(p[0].y),
        );
        let area = area2(p[0], p[1], p[2]);
        let (e1x, e1y) = (i64::from(p[1].x - p[0].x), i64::from(p[1].y - p[0].y));
        let (e2x, e2y) = (i64::from(p[2].x - p[0].x), i64::from(p[2].y - p[0].y));
        // Per channel: the value at the centre of pixel (px, py) and the
        // steps per pixel.
        let plane = |[a, b, c]: [i64; 3]| -> (i32, i32, i32) {
            if area == 0 {
                return (((a + b + c) / 3) as i32, 0, 0);
            }
            let (d1, d2) = (b - a, c - a);
            // dC/dx = (d1·e2y − d2·e1y) / area, dC/dy = (d2·e1x − d1·e2x) / area
            // per screen unit: |d| < 2^24, |e| ≤ 2^20, so the numerators
            // fit in 2^45; the steps per pixel (× 2^sub) in 2^61.
            let nx = d1 * e2y - d2 * e1y;
            let ny = d2 * e1x - d1 * e2x;
            let step = |n: i64| ((n << sub) / area).clamp(-LIMIT, LIMIT) as i32;
            let at = a + (nx * cx + ny * cy) / area;
            (at.clamp(-LIMIT, LIMIT) as i32, step(nx), step(ny))
        };
        let ch = [0, 1, 2].map(|k| plane([v[0][k], v[1][k], v[2][k]]));
        Smooth {
            px,
            py,
            c: ch.map(|t| t.0),
            gx: ch.map(|t| t.1),
            gy: ch.map(|t| t.2),
        }
    }

    /// Channel `k` at the centre of pixel `(x, y)`, unclamped.
    #[inline]
    fn at(&self, k: usize, x: i32, y: i32) -> i64 {
        i64::from(self.c[k])
            + i64::from(self.gx[k]) * i64::from(x.wrapping_sub(self.px))
            + i64::from(self.gy[k]) * i64::from(y.wrapping_sub(self.py))
    }
}

/// The flat fill of `pts` into `sink` (a [`SmoothSink`]): out of line, so
/// that the walk, where the flat fill is inlined, does not get a second
/// copy.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(crate) fn fill_smooth<K: SpanSink>(
    pts: &[ScreenPt],
    bbox: Option<&Bbox>,
    sub: u32,
    rule: FillRule,
    clip: &SpanBounds,
    edges: &mut [Edge],
    active: &mut [u16],
    sink: &mut SmoothSink<'_, K>,
) -> Result<usize, FillError> {
    fill_polygon_in(pts, bbox, sub, rule, clip, edges, active, (), sink)
}

/// A span sink that paints the spans of one polygon in its interpolated
/// colours, as runs of equal colour into `sink` (see the module docs).
pub(crate) struct SmoothSink<'a, K: SpanSink> {
    smooth: &'a Smooth,
    id: u32,
    sink: &'a mut K,
}

impl<'a, K: SpanSink> SmoothSink<'a, K> {
    /// Paints through `sink` with the colour plane `smooth`, as polygon
    /// `id`.
    pub(crate) fn new(smooth: &'a Smooth, id: u32, sink: &'a mut K) -> Self {
        SmoothSink { smooth, id, sink }
    }
}

impl<K: SpanSink> SpanSink for SmoothSink<'_, K> {
    type Color = ();
    const NEEDS_ID: bool = K::NEEDS_ID;

    fn color(&self, _: &Paint) {}

    fn bounds(&self) -> SpanBounds {
        self.sink.bounds()
    }

    fn span(&mut self, y: i32, x0: i32, x1: i32, _: ()) {
        let len = x1.saturating_sub(x0);
        if len <= 0 {
            return;
        }
        let last = x1 - 1;
        // Start value and per-pixel step of each channel: the plane's own
        // step when both ends are in range (then every value between is),
        // else the clamped ends joined linearly (slivers and the corners a
        // wider polygon's plane does not pass through).
        let mut c = [0i32; 3];
        let mut d = [0i32; 3];
        for k in 0..3 {
            let (a, b) = (self.smooth.at(k, x0, y), self.smooth.at(k, last, y));
            if (0..=TOP).contains(&a) && (0..=TOP).contains(&b) {
                c[k] = a as i32;
                d[k] = self.smooth.gx[k];
            } else {
                let (a, b) = (a.clamp(0, TOP), b.clamp(0, TOP));
                c[k] = a as i32;
                d[k] = if len > 1 {
                    ((b - a) / i64::from(len - 1)) as i32
                } else {
                    0
                };
            }
        }
        let rgb_at = |c: &[i32; 3]| {
            let ch = |v: i32| (v >> FRAC).clamp(0, 255) as u8;
            Rgb888::new(ch(c[0]), ch(c[1]), ch(c[2]))
        };
        let id = self.id;
        let mut run = x0;
        let mut rgb = rgb_at(&c);
        let mut color = self.sink.color(&Paint { rgb, id });
        for x in x0 + 1..x1 {
            for k in 0..3 {
                c[k] = c[k].wrapping_add(d[k]);
            }
            let next = rgb_at(&c);
            if next != rgb {
                rgb = next;
                // A run ends only where the target's colour changes.
                let native = self.sink.color(&Paint { rgb, id });
                if native != color {
                    self.sink.span(y, run, x, color);
                    (run, color) = (x, native);
                }
            }
        }
        self.sink.span(y, run, x1, color);
    }
}

#[cfg(test)]
mod tests;
