//! Outlines: one-pixel lines along a polygon's edges, drawn after its fill.
//!
//! Drawn right after the face they belong to, in the walk's back-to-front
//! order, a nearer face painted later covers them: that is hidden-line
//! removal for free (the `outline` effect, [`crate::effects`]).
//!
//! A line from `a` to `b` (screen points, `sub` sub-pixel bits) lights the
//! pixels of the segment between the pixels holding its endpoints
//! (`p >> sub`), one per row for a steep line and one per column for a
//! shallow one, each chosen by exact integer rounding from the endpoints
//! alone. So a pixel's membership never depends on where drawing started
//! or on the sink's bounds: bands see exactly the pixels of the full frame
//! (the band test checks this). Work is bounded by the viewport: only
//! rows or columns inside the bounds are visited.

use super::scan::{SpanBounds, SpanSink};
use super::transform::ScreenPt;

/// `round(num / den)` for `den > 0`, halves toward +∞, in `i64`.
#[inline]
fn div_round(num: i64, den: i64) -> i64 {
    (2 * num + den).div_euclid(2 * den)
}

/// Draws the segment `a → b` into `sink`, clipped to `clip ∩ sink.bounds()`.
/// Returns the number of spans emitted.
pub fn draw_line<K: SpanSink>(
    a: ScreenPt,
    b: ScreenPt,
    sub: u32,
    clip: &SpanBounds,
    color: K::Color,
    sink: &mut K,
) -> usize {
    let r = clip.intersect(&sink.bounds());
    if r.is_empty() {
        return 0;
    }
    let sub = sub.min(16);
    let px = |p: ScreenPt| (i64::from(p.x >> sub), i64::from(p.y >> sub));
    let (pa, pb) = (px(a), px(b));
    let (dx, dy) = (pb.0 - pa.0, pb.1 - pa.1);
    let steep = dy.abs() >= dx.abs();
    // Canonical direction (from the smaller major coordinate, ties by the
    // minor one): both directions of an edge give the same pixels.
    let key = |p: (i64, i64)| if steep { (p.1, p.0) } else { p };
    let (a, b) = if key(pa) <= key(pb) {
        (pa, pb)
    } else {
        (pb, pa)
    };
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let mut spans = 0;
    if steep {
        // One pixel per row (a point is a steep line of one row).
        let lo = a.1.max(i64::from(r.y0));
        let hi = b.1.min(i64::from(r.y1) - 1);
        for y in lo..=hi {
            let x = if dy == 0 {
                a.0
            } else {
                a.0 + div_round((y - a.1) * dx, dy)
            };
            if x >= i64::from(r.x0) && x < i64::from(r.x1) {
                sink.span(y as i32, x as i32, x as i32 + 1, color);
                spans += 1;
            }
        }
    } else {
        // Shallow: one pixel per column, runs on a row merged into spans.
        let lo = a.0.max(i64::from(r.x0));
        let hi = b.0.min(i64::from(r.x1) - 1);
        let mut run: Option<(i64, i64, i64)> = None; // (y, first x, last x)
        let flush = |run: Option<(i64, i64, i64)>, sink: &mut K| {
            if let Some((y, s, e)) = run {
                if y >= i64::from(r.y0) && y < i64::from(r.y1) {
                    sink.span(y as i32, s as i32, e as i32 + 1, color);
                    return 1;
                }
            }
            0
        };
        for x in lo..=hi {
            let y = a.1 + div_round((x - a.0) * dy, dx);
            run = match run {
                Some((ry, s, _)) if ry == y => Some((ry, s, x)),
                other => {
                    spans += flush(other, sink);
                    Some((y, x, x))
                }
            };
        }
        spans += flush(run, sink);
    }
    spans
}

/// Draws the closed outline of `pts`, leaving out edge `i` (from `pts[i]`
/// to `pts[i + 1]`) when bit `i` of `hidden` is set (edges from 64 on are
/// always drawn). Returns the number of spans emitted.
pub fn draw_outline<K: SpanSink>(
    pts: &[ScreenPt],
    hidden: u64,
    sub: u32,
    clip: &SpanBounds,
    color: K::Color,
    sink: &mut K,
) -> usize {
    let mut spans = 0;
    let n = pts.len();
    for (i, a) in pts.iter().enumerate() {
        if i < 64 && hidden & (1 << i) != 0 {
            continue;
        }
        let Some(b) = pts.get(if i + 1 == n { 0 } else { i + 1 }) else {
            continue;
        };
        spans += draw_line(*a, *b, sub, clip, color, sink);
    }
    spans
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec;
    use std::vec::Vec;

    /// Records lit pixels.
    struct Pixels {
        b: SpanBounds,
        lit: Vec<(i32, i32)>,
    }

    impl SpanSink for Pixels {
        type Color = ();
        fn color(&self, _: &super::super::scan::Paint) {}
        fn bounds(&self) -> SpanBounds {
            self.b
        }
        fn span(&mut self, y: i32, x0: i32, x1: i32, _: ()) {
            assert!(x0 < x1 && y >= self.b.y0 && y < self.b.y1);
            assert!(x0 >= self.b.x0 && x1 <= self.b.x1);
            self.lit.extend((x0..x1).map(|x| (x, y)));
        }
    }

    fn pt(x: i32, y: i32) -> ScreenPt {
        ScreenPt {
            x: x << 4,
            y: y << 4,
        }
    }

    fn lit(a: ScreenPt, b: ScreenPt, bounds: SpanBounds) -> Vec<(i32, i32)> {
        let mut s = Pixels {
            b: bounds,
            lit: vec![],
        };
        draw_line(a, b, 4, &SpanBounds::of_size(64, 64), (), &mut s);
        s.lit.sort_unstable();
        s.lit
    }

    #[test]
    fn lines_are_connected_and_hit_their_endpoints() {
        let all = SpanBounds::of_size(64, 64);
        for (a, b) in [
            ((3, 5), (40, 17)),
            ((10, 2), (12, 60)),
            ((50, 50), (2, 9)),
            ((7, 7), (7, 7)),
        ] {
            let px = lit(pt(a.0, a.1), pt(b.0, b.1), all);
            assert!(px.contains(&a) && px.contains(&b), "{a:?} {b:?}");
            let n = (a.0 - b.0).abs().max((a.1 - b.1).abs()) + 1;
            assert_eq!(px.len() as i32, n, "one pixel per step of the major axis");
            for w in px.windows(2) {
                assert!((w[0].0 - w[1].0).abs() <= 1 || (w[0].1 - w[1].1).abs() <= 1);
            }
        }
    }

    #[test]
    fn bands_see_exactly_the_full_frame_pixels_in_either_direction() {
        let all = SpanBounds::of_size(64, 64);
        for (a, b) in [
            ((-30, 5), (90, 40)),
            ((10, -20), (33, 99)),
            ((60, 3), (1, 4)),
        ] {
            let full = lit(pt(a.0, a.1), pt(b.0, b.1), all);
            assert_eq!(full, lit(pt(b.0, b.1), pt(a.0, a.1), all));
            let mut banded = vec![];
            for y0 in (0..64).step_by(5) {
                let band = SpanBounds {
                    x0: 0,
                    y0,
                    x1: 64,
                    y1: (y0 + 5).min(64),
                };
                banded.extend(lit(pt(a.0, a.1), pt(b.0, b.1), band));
            }
            banded.sort_unstable();
            assert_eq!(full, banded);
            assert!(full
                .iter()
                .all(|&(x, y)| (0..64).contains(&x) && (0..64).contains(&y)));
        }
    }

    #[test]
    fn hidden_edges_are_left_out() {
        let sq = [pt(2, 2), pt(20, 2), pt(20, 20), pt(2, 20)];
        let mut s = Pixels {
            b: SpanBounds::of_size(64, 64),
            lit: vec![],
        };
        draw_outline(&sq, 0b0101, 4, &SpanBounds::of_size(64, 64), (), &mut s);
        // Only the right (edge 1) and left (edge 3) sides.
        assert!(s.lit.iter().all(|&(x, _)| x == 2 || x == 20));
        assert_eq!(s.lit.len(), 2 * 19);
    }
}
