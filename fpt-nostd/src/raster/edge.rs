//! Edge setup: from a screen polygon to exact, incrementally stepped edges.
//!
//! Sampling and ownership rules (the "top-left rule" in scanline form):
//! * Pixel `(i, j)` is sampled at `(i + ½, j + ½)`.
//! * An edge is active on row `j` when `y_top ≤ j + ½ < y_bottom`
//!   (half-open in y; horizontal edges are never active). So a sample
//!   exactly on a top edge or a vertex row is counted for the edge going
//!   down from it, never for the one ending there.
//! * On an active row the edge's crossing is the first pixel whose sample
//!   is at or right of the edge: `i = ceil(x_edge − ½)`. A span between a
//!   left crossing `a` and a right crossing `b` covers `a ≤ i < b`, i.e.
//!   samples with `x_left ≤ x < x_right`: on-edge samples belong to the
//!   polygon on the edge's right.
//!
//! The crossing of a row is computed exactly, as a rational number, from
//! the edge's two endpoints alone (normalised top to bottom), and stepped
//! from row to row with an integer quotient/remainder pair (a DDA without
//! rounding drift). Two polygons sharing an edge therefore compute the same
//! crossing on every row — whatever the direction in which each traverses
//! it and whatever row (band) the stepping starts from — and a pixel centre
//! on the shared edge goes to exactly one of them: no cracks, no overdraw.
//!
//! Ranges: screen coordinates are at most [`SCREEN_LIMIT`] (2^24) in
//! magnitude in `2^-SUB` units with `SUB ≤ 8`, so the numerators below stay
//! under 2^53 and everything fits i64; the per-row quotient fits i32.
//!
//! [`SCREEN_LIMIT`]: super::transform::SCREEN_LIMIT

use super::transform::{ScreenPt, SCREEN_LIMIT};

/// One polygon edge prepared for scan conversion (opaque state).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Edge {
    /// First row on which the edge is active.
    pub(crate) y0: i32,
    /// Row after the last active row.
    pub(crate) y1: i32,
    /// Crossing pixel on the current row (filled in by the scan loop).
    pub(crate) x: i32,
    /// floor(N / D) on the current row.
    q: i32,
    /// Per-row increment of `q`.
    qs: i32,
    /// N mod D on the current row, `0 ≤ r < d`.
    r: i64,
    /// Per-row increment of `r`, `0 ≤ rs < d`.
    rs: i64,
    /// Denominator `2^(SUB+1) · dy` (> 0).
    d: i64,
    /// +1 if the polygon traverses the edge downward, −1 upward.
    pub(crate) dir: i8,
}

/// `ceil(a / b)` for `b > 0`.
fn ceil_div(a: i64, b: i64) -> i64 {
    -((-a).div_euclid(b))
}

impl Edge {
    /// Row range `[first, end)` on which the edge `p → q` is active
    /// (empty for horizontal edges).
    pub fn rows(p: ScreenPt, q: ScreenPt, sub: u32) -> (i32, i32) {
        let (top, bot) = if p.y <= q.y { (p, q) } else { (q, p) };
        let half = 1i64 << sub;
        let unit = 2i64 << sub;
        let first = ceil_div(2 * top.y as i64 - half, unit);
        let end = ceil_div(2 * bot.y as i64 - half, unit);
        (first as i32, end as i32)
    }

    /// Prepares edge `p → q` for rows `[max(first, row_lo), min(end, row_hi))`.
    /// `None` when the edge is active on no row of that range.
    pub fn new(p: ScreenPt, q: ScreenPt, sub: u32, row_lo: i32, row_hi: i32) -> Option<Edge> {
        let clamp = |v: i32| v.clamp(-SCREEN_LIMIT, SCREEN_LIMIT) as i64;
        let (px, py, qx, qy) = (clamp(p.x), clamp(p.y), clamp(q.x), clamp(q.y));
        if py == qy {
            return None;
        }
        let (first, end) = Edge::rows(
            ScreenPt { x: 0, y: py as i32 },
            ScreenPt { x: 0, y: qy as i32 },
            sub,
        );
        let y0 = first.max(row_lo);
        let y1 = end.min(row_hi);
        if y0 >= y1 {
            return None;
        }
        let dir: i8 = if py < qy { 1 } else { -1 };
        let ((tx, ty), (bx, by)) = if py < qy {
            ((px, py), (qx, qy))
        } else {
            ((qx, qy), (px, py))
        };
        let (dx, dy) = (bx - tx, by - ty);
        let half = 1i64 << sub;
        let unit = 2i64 << sub;
        // N(j) = (2·tx − 2^S)·dy + ((2j+1)·2^S − 2·ty)·dx ; D = 2^(S+1)·dy ;
        // crossing(j) = ceil(N(j) / D)   (derivation in the module docs:
        // ceil(x_edge − ½) with x_edge the exact edge x at y = j + ½).
        let d = unit * dy;
        let n = (2 * tx - half) * dy + ((2 * y0 as i64 + 1) * half - 2 * ty) * dx;
        let step = unit * dx;
        Some(Edge {
            y0,
            y1,
            x: 0,
            q: n.div_euclid(d) as i32,
            r: n.rem_euclid(d),
            qs: step.div_euclid(d) as i32,
            rs: step.rem_euclid(d),
            d,
            dir,
        })
    }

    /// The crossing pixel on the current row: `ceil(N / D)`.
    #[inline]
    pub(crate) fn crossing(&self) -> i32 {
        self.q + (self.r > 0) as i32
    }

    /// Advances to the next row.
    #[inline]
    pub(crate) fn step(&mut self) {
        self.q = self.q.wrapping_add(self.qs);
        self.r += self.rs;
        if self.r >= self.d {
            self.r -= self.d;
            self.q = self.q.wrapping_add(1);
        }
    }
}

/// Builds the edges of the closed polygon `pts` that are active within rows
/// `[row_lo, row_hi)`, sorted by first row, into `out`. Returns how many, or
/// `None` if `out` is shorter than `pts` (each vertex starts one edge).
pub fn build_edges(
    pts: &[ScreenPt],
    sub: u32,
    row_lo: i32,
    row_hi: i32,
    out: &mut [Edge],
) -> Option<usize> {
    if out.len() < pts.len() {
        return None;
    }
    let mut n = 0usize;
    let Some(&last) = pts.last() else {
        return Some(0);
    };
    let mut prev = last;
    for &cur in pts {
        if let Some(e) = Edge::new(prev, cur, sub, row_lo, row_hi) {
            // Insertion sort by first row: polygons are small, and this
            // keeps the active-edge insertion in the scan loop trivial.
            let mut k = n;
            while k > 0 && out[k - 1].y0 > e.y0 {
                out[k] = out[k - 1];
                k -= 1;
            }
            out[k] = e;
            n += 1;
        }
        prev = cur;
    }
    Some(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(x: i32, y: i32) -> ScreenPt {
        ScreenPt { x, y }
    }

    /// Reference check of the crossing definition, independent of the
    /// quotient/remainder form: `i` must be the smallest integer with
    /// `i + ½ ≥ x_edge(j + ½)`, tested by cross-multiplying in i128.
    fn is_crossing(p: ScreenPt, q: ScreenPt, sub: u32, j: i32, i: i32) -> bool {
        let (t, b) = if p.y < q.y { (p, q) } else { (q, p) };
        let (dx, dy) = ((b.x - t.x) as i128, (b.y - t.y) as i128);
        let s = 1i128 << sub;
        // 2·dy·x_edge, in sub-pixel units
        let rhs = 2 * t.x as i128 * dy + ((2 * j as i128 + 1) * s - 2 * t.y as i128) * dx;
        let at = |i: i128| (2 * i + 1) * s * dy; // 2·dy·(i + ½)
        at(i as i128) >= rhs && at(i as i128 - 1) < rhs
    }

    #[test]
    fn stepped_crossings_equal_exact_ones() {
        let mut seed = 12345u64;
        let mut rnd = |m: i32| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) as i64 % (2 * m as i64 + 1) - m as i64) as i32
        };
        for sub in [0u32, 2, 4, 8] {
            for _ in 0..300 {
                let p = pt(rnd(300 << sub), rnd(200 << sub));
                let q = pt(rnd(300 << sub), rnd(200 << sub));
                let lo = rnd(100);
                let fwd = Edge::new(p, q, sub, lo, i32::MAX);
                // The reverse traversal prepares identical stepping state.
                let strip = |e: Edge| Edge { dir: 0, ..e };
                assert_eq!(
                    fwd.map(strip),
                    Edge::new(q, p, sub, lo, i32::MAX).map(strip)
                );
                let Some(mut e) = fwd else {
                    let (f, end) = Edge::rows(p, q, sub);
                    assert!(f.max(lo) >= end);
                    continue;
                };
                for j in e.y0..e.y1 {
                    assert!(
                        is_crossing(p, q, sub, j, e.crossing()),
                        "{p:?} {q:?} {sub} {j}"
                    );
                    e.step();
                }
            }
        }
    }

    #[test]
    fn half_open_rows_and_horizontal_edges() {
        // sub = 0: edge from y=2 to y=5 covers sample rows 2.5, 3.5, 4.5.
        assert_eq!(Edge::rows(pt(0, 2), pt(7, 5), 0), (2, 5));
        assert_eq!(Edge::rows(pt(7, 5), pt(0, 2), 0), (2, 5));
        // sub = 1: y = 2.5 (5) to 3.5 (7): sample 2.5 is in, 3.5 is out.
        assert_eq!(Edge::rows(pt(0, 5), pt(0, 7), 1), (2, 3));
        assert!(Edge::new(pt(0, 3), pt(9, 3), 0, -100, 100).is_none());
        assert!(Edge::new(pt(0, 3), pt(9, 4), 0, 4, 100).is_none());
    }

    #[test]
    fn build_sorts_by_first_row_and_checks_capacity() {
        let tri = [pt(0, 10), pt(20, 0), pt(30, 30)];
        let mut out = [Edge::default(); 3];
        assert_eq!(build_edges(&tri, 0, 0, 100, &mut out), Some(3));
        assert!(out.windows(2).all(|w| w[0].y0 <= w[1].y0));
        assert_eq!(out[0].y0, 0);
        let mut small = [Edge::default(); 2];
        assert_eq!(build_edges(&tri, 0, 0, 100, &mut small), None);
        // Row window cuts edges.
        assert_eq!(build_edges(&tri, 0, 0, 5, &mut out), Some(2));
        assert!(out[..2].iter().all(|e| e.y1 <= 5));
    }

    #[test]
    fn extreme_coordinates_do_not_overflow() {
        let l = SCREEN_LIMIT;
        for sub in [0, 8] {
            let Some(mut e) = Edge::new(pt(-l, -l), pt(l, l), sub, -1 << 20, 1 << 20) else {
                panic!("edge expected");
            };
            for _ in 0..1000 {
                e.step();
            }
            let e2 = Edge::new(pt(l, -l), pt(-l, -l + 1), sub, i32::MIN, i32::MAX);
            assert!(e2.is_none_or(|e| e.y1 - e.y0 <= 1));
            let e3 = Edge::new(pt(-l, -l), pt(l, -l + (1 << sub)), sub, i32::MIN, i32::MAX);
            assert!(e3.is_some_and(|e| e.crossing() <= (l >> sub) + 1));
        }
    }
}
