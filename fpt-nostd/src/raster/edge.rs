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
//! Polygons within ±2^13 sub-pixel units (the usual case on a small
//! display) take `Edge::new_small`, the same arithmetic in i32, and the
//! scan loop steps edges with `D < 2^30` in 32-bit registers (`Dda32`):
//! on a 32-bit core, 64-bit products, variable shifts and division
//! routines were most of the fill's cost.
//!
//! When a 64-bit division can happen: only in [`Edge::new`], only when the
//! numerator `N` (or `D`) does not fit i32 (`div_floor` checks at run
//! time and otherwise divides in 32 bits). Every projected vertex lies in
//! the guard band (`|ndc| ≤ 4`: `x ∈ [−1.5·Cx, 2.5·Cx]` with `Cx =
//! W·2^S`, likewise y; a few units more for rounding). `N/D` is the
//! crossing on an active row, i.e. `x_edge − ½` there, and `x_edge` lies
//! between the endpoints, so `|N| ≤ 2·dy·(2.5·Cx + 2^S) ≤ 20·Cx·Cy +
//! 8·2^S·Cy` (`dy ≤ 4·Cy`), and `D = 2^(S+1)·dy ≤ 8·Cy`. That is below
//! 2^31 whenever `W·H·2^(2S) ≤ 10^8`: up to 640×480 pixels at 4 sub-pixel
//! bits (320×240 with a factor 5 to spare), but only 40×30 at 8 bits.
//! Such displays never divide in 64 bits, on any vertex path; larger ones
//! may, for edges reaching far into the guard band (test
//! `guard_band_edges_divide_in_32_bits`).
//!
//! [`SCREEN_LIMIT`]: super::transform::SCREEN_LIMIT

use super::transform::{ScreenPt, SCREEN_LIMIT};
use crate::cpu::HAS_DIV;

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

impl Edge {
    /// The all-zero edge (scratch initialiser, usable in `const` context).
    pub const ZERO: Edge = Edge {
        y0: 0,
        y1: 0,
        x: 0,
        q: 0,
        qs: 0,
        r: 0,
        rs: 0,
        d: 0,
        dir: 0,
    };
}

/// `ceil(a / 2^k)`: an arithmetic shift is a floor division by a power of
/// two, so no division routine is needed for the row bounds.
#[inline]
fn ceil_shr(a: i64, k: u32) -> i64 {
    -((-a) >> k)
}

/// Coordinates (sub-pixel units) below which [`Edge::new_small`] applies:
/// `|x|, |y| < SMALL`. At 4 sub-pixel bits that is ±512 pixels, so every
/// polygon of a small display that does not reach far into the guard band.
pub(crate) const SMALL: i32 = 1 << 13;

/// Whether every point of `pts` is within ±[`SMALL`] (where the 32-bit
/// edge set-ups and the triangle path apply).
#[inline(always)]
pub(crate) fn all_small(pts: &[ScreenPt]) -> bool {
    pts.iter().all(|p| p.x.abs() < SMALL && p.y.abs() < SMALL)
}

/// [`div_floor`] for 32-bit values (`d > 0`): one hardware division.
#[inline]
fn div_floor32(n: i32, d: i32) -> (i32, i32) {
    let q = n / d;
    let r = n - q * d;
    if r < 0 {
        (q - 1, r + d)
    } else {
        (q, r)
    }
}

/// [`div_floor32`] without the division when `−2·d ≤ n < 2·d` (an edge
/// whose slope `dx / dy` is within ±2), for cores without a divider, where
/// the division is a call of about 50 instructions. Measured on the
/// Cortex-M0's socket orbit: the window ±1 took 0.6 % off a frame, ±2
/// 0.7 % more; four compare-and-subtract steps for ±8 took only 0.2 %
/// (each edge paid for all four). `d > 0`, `|n| < 2^29`.
#[inline(always)]
fn div_floor_near(n: i32, d: i32) -> (i32, i32) {
    if n >= 0 && n < d {
        (0, n)
    } else if n < 0 && n >= -d {
        (-1, n + d)
    } else if n >= d && n < 2 * d {
        (1, n - d)
    } else if n < -d && n >= -2 * d {
        (-2, n + 2 * d)
    } else {
        div_floor32_out(n, d)
    }
}

/// [`div_floor32`] out of line: the rare divisions of the division-free
/// edge start, one copy instead of one at every inlined start (on the
/// Cortex-M0 the inlined copies made its accuracy firmware too large
/// for the micro:bit's 256 KiB of flash).
#[inline(never)]
fn div_floor32_out(n: i32, d: i32) -> (i32, i32) {
    div_floor32(n, d)
}

/// `(floor(n / d), n mod d)` with `0 ≤ n mod d < d`, for `d > 0`.
///
/// Why not `div_euclid`/`rem_euclid`: on a 32-bit core each is a call to
/// a 64-bit division routine (~100 instructions). On screen, `n` and `d`
/// fit 32 bits, and one hardware 32-bit division serves both results; only
/// guard-band-sized edges fall back to one 64-bit division.
#[inline]
pub(crate) fn div_floor(n: i64, d: i64) -> (i64, i64) {
    let (q, r) = match (i32::try_from(n), i32::try_from(d)) {
        (Ok(n32), Ok(d32)) => {
            // d32 > 0, so neither overflow case of `/` can occur.
            let q = n32 / d32;
            (q as i64, (n32 - q * d32) as i64)
        }
        _ => {
            let q = n / d;
            // |q·d| ≤ |n|: no overflow.
            (q, n - q * d)
        }
    };
    // Truncation rounds toward zero; floor needs one correction step for
    // negative non-exact quotients.
    if r < 0 {
        (q - 1, r + d)
    } else {
        (q, r)
    }
}

impl Edge {
    /// Row range `[first, end)` on which the edge `p → q` is active
    /// (empty for horizontal edges).
    pub fn rows(p: ScreenPt, q: ScreenPt, sub: u32) -> (i32, i32) {
        let (top, bot) = if p.y <= q.y { (p, q) } else { (q, p) };
        let half = 1i64 << sub;
        let first = ceil_shr(2 * top.y as i64 - half, sub + 1);
        let end = ceil_shr(2 * bot.y as i64 - half, sub + 1);
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
        let (q, r) = div_floor(n, d);
        // The per-row step N(j+1) − N(j) = unit·dx over D = unit·dy:
        // floor(dx / dy) with remainder unit·(dx mod dy); |dx|, dy < 2^26,
        // so this is a 32-bit division.
        let (qs, rs) = div_floor(dx, dy);
        Some(Edge {
            y0,
            y1,
            x: 0,
            q: q as i32,
            r,
            qs: qs as i32,
            rs: rs * unit,
            d,
            dir,
        })
    }

    /// [`Edge::new`] for endpoints with `|x|, |y| < SMALL` (checked by the
    /// caller): the same exact crossings, computed in 32-bit arithmetic.
    ///
    /// Ranges: `|dx|, dy < 2^14`, `2^S ≤ 2^8`. The row term
    /// `(2·y0 + 1)·2^S − 2·ty` lies in `[0, 2·dy + 2^(S+1)]` because
    /// `first ≤ y0 < end` (so `< 2^16`), so `|N| < 2^15·2^14 + 2^16·2^14
    /// < 2^31`, `D < 2^23`: no product or sum overflows i32. On a 32-bit
    /// core this avoids every 64-bit multiply, variable 64-bit shift and
    /// division routine of the general version.
    pub(crate) fn new_small(
        p: ScreenPt,
        q: ScreenPt,
        sub: u32,
        row_lo: i32,
        row_hi: i32,
    ) -> Option<Edge> {
        if p.y == q.y {
            return None;
        }
        let (dir, t, b) = if p.y < q.y { (1, p, q) } else { (-1, q, p) };
        let half = 1i32 << sub;
        // ceil((2y − 2^S) / 2^(S+1)) = −floor((2^S − 2y) / 2^(S+1)).
        let first = -((half - 2 * t.y) >> (sub + 1));
        let end = -((half - 2 * b.y) >> (sub + 1));
        let y0 = first.max(row_lo);
        let y1 = end.min(row_hi);
        if y0 >= y1 {
            return None;
        }
        let (dx, dy) = (b.x - t.x, b.y - t.y);
        let d = dy << (sub + 1);
        let n = (2 * t.x - half) * dy + ((2 * y0 + 1) * half - 2 * t.y) * dx;
        let (q, r) = div_floor32(n, d);
        let (qs, rs) = div_floor32(dx, dy);
        Some(Edge {
            y0,
            y1,
            x: 0,
            q,
            r: r as i64,
            qs,
            rs: (rs << (sub + 1)) as i64,
            d: d as i64,
            dir,
        })
    }

    /// The crossing pixel on the current row: `ceil(N / D)`.
    #[inline]
    pub(crate) fn crossing(&self) -> i32 {
        self.q + (self.r > 0) as i32
    }

    /// The stepping state in 32 bits when `D < 2^30` (then `r + rs < 2^31`),
    /// as every edge from [`Edge::new_small`] has; `None` otherwise.
    #[inline]
    pub(crate) fn dda32(&self) -> Option<Dda32> {
        if self.d < 1 << 30 {
            // N = q·D + r: the crossing is q + 1 with excess D − r when
            // r > 0, else q with excess 0.
            let (c, g) = if self.r > 0 {
                (self.q.wrapping_add(1), (self.d - self.r) as i32)
            } else {
                (self.q, 0)
            };
            Some(Dda32 {
                c,
                g,
                qs: self.qs,
                rs: self.rs as i32,
                d: self.d as i32,
            })
        } else {
            None
        }
    }

    /// Writes back the state of a [`Dda32`] taken from this edge.
    #[inline]
    pub(crate) fn set_dda32(&mut self, s: &Dda32) {
        if s.g > 0 {
            self.q = s.c.wrapping_sub(1);
            self.r = i64::from(s.d - s.g);
        } else {
            self.q = s.c;
            self.r = 0;
        }
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

/// An exact edge stepper, row by row: [`Edge`] (64-bit remainders) or
/// [`Dda32`] (the same steps in 32-bit registers). Lets one row loop serve
/// both (`super::scan::pair_rows`).
pub(crate) trait Stepper {
    /// The crossing pixel on the current row.
    fn crossing(&self) -> i32;
    /// Advances to the next row.
    fn step(&mut self);
}

impl Stepper for Edge {
    #[inline(always)]
    fn crossing(&self) -> i32 {
        Edge::crossing(self)
    }
    #[inline(always)]
    fn step(&mut self) {
        Edge::step(self)
    }
}

impl Stepper for Dda32 {
    #[inline(always)]
    fn crossing(&self) -> i32 {
        Dda32::crossing(self)
    }
    #[inline(always)]
    fn step(&mut self) {
        Dda32::step(self)
    }
}

/// An edge's stepping in 32-bit registers (see [`Edge::dda32`]): the same
/// sequence of crossings as [`Edge`]'s, kept as the crossing itself.
///
/// [`Edge`] keeps `N = q·D + r` (`0 ≤ r < D`) and computes the crossing
/// `ceil(N / D) = q + (r > 0)` on every row. This keeps the crossing
/// `c = ceil(N / D)` and its excess `g = c·D − N` (`0 ≤ g < D`) instead:
/// a row adds `unit·dx = qs·D + rs` to `N`, so `c` gains `qs` and `g`
/// loses `rs`, and when `g` drops below 0 one more `D` brings it back
/// (`rs < D`) with `c` one more. The crossing is then a register, and the
/// step's test a sign test: fewer instructions a row for the same values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Dda32 {
    c: i32,
    g: i32,
    qs: i32,
    rs: i32,
    d: i32,
}

impl Dda32 {
    /// The stepping state of the edge from `t` down to `b` (`t.y < b.y`)
    /// on row `y`, for endpoints within ±[`SMALL`], `sub ≤ 8` and `y` one
    /// of the edge's active rows (so the ranges of [`Edge::new_small`]
    /// hold): the state `Edge::new_small(t, b, sub, y, _)` would give.
    #[inline]
    pub(crate) fn start(t: ScreenPt, b: ScreenPt, sub: u32, y: i32) -> Dda32 {
        Dda32::start_inline(t, b, sub, y)
    }

    /// [`Dda32::start`], always inlined (the triangle path's set-up).
    #[inline(always)]
    pub(crate) fn start_inline(t: ScreenPt, b: ScreenPt, sub: u32, y: i32) -> Dda32 {
        let half = 1i32 << sub;
        let (dx, dy) = (b.x - t.x, b.y - t.y);
        let d = dy << (sub + 1);
        if d <= 0 {
            // Never (`t.y < b.y`); tells the compiler that both divisions
            // below neither divide by zero nor overflow.
            return Dda32::default();
        }
        // Twice the distance from the top endpoint down to row `y`'s
        // centre, in sub-pixel units: below 2^(sub+1) on the edge's first
        // active row.
        let down = (2 * y + 1) * half - 2 * t.y;
        if !HAS_DIV {
            return Dda32::start_one_division(t, dx, dy, sub, down);
        }
        let n = (2 * t.x - half) * dy + down * dx;
        // ceil(n / d) = −floor(−n / d), with excess (−n) mod d; |n| < 2^31
        // (see `Edge::new_small`), so −n does not overflow.
        let (q, g) = div_floor32(-n, d);
        // floor(dx / dy) and (dx mod dy)·2^(sub+1) in one division by `d`
        // (`|dx|·2^(sub+1) < 2^23`).
        let (qs, rs) = div_floor32(dx << (sub + 1), d);
        Dda32 {
            c: -q,
            g,
            qs,
            rs,
            d,
        }
    }

    /// [`Dda32::start_inline`] on the row whose centre lies `down / 2`
    /// sub-pixel units below `t` (`down ≥ 0`: an active row, as
    /// [`Dda32::start`] requires), in one
    /// division instead of two on the edge's first eight rows: for cores
    /// without a hardware divider ([`HAS_DIV`]), where each division is a
    /// call of about 85 instructions (a Cortex-M0's triangle set-up made
    /// six of them).
    ///
    /// Why it is the same state: with `P = 2^(sub+1)`, `d = P·dy`,
    /// `A = 2·t.x − 2^sub` and `dx = qs·dy + r` (`0 ≤ r < dy`, the one
    /// division), the start divides `−n = −A·dy − down·dx
    /// = M·dy − down·r` with `M = −(A + down·qs)`. Splitting
    /// `M = P·m1 + m0` (`0 ≤ m0 < P`, a shift and a mask) gives
    /// `−n = m1·d + X` with `X = m0·dy − down·r`, and
    /// `−down·dy < X < d` (`m0 < P`, `r < dy`): `floor(−n / d)` is `m1`
    /// less the number of `d` that bring `X` to `[0, d)`, at most
    /// `down / P + 1`. On the first row (`down < P`) that is one test; up
    /// to eight rows down, a short loop; farther, one more division. Every
    /// value is below 2^30 in magnitude for endpoints within ±[`SMALL`]
    /// and `sub ≤ 8` (`n`'s own bound, `Edge::new_small`).
    #[inline(always)]
    fn start_one_division(t: ScreenPt, dx: i32, dy: i32, sub: u32, down: i32) -> Dda32 {
        let d = dy << (sub + 1);
        let (qs, r) = div_floor_near(dx, dy);
        let m = -((2 * t.x - (1 << sub)) + down * qs);
        let (mut q, m0) = (m >> (sub + 1), m & ((1 << (sub + 1)) - 1));
        let mut g = m0 * dy - down * r;
        if g < 0 {
            if down >> (sub + 1) < 8 {
                while g < 0 {
                    g += d;
                    q -= 1;
                }
            } else {
                let (k, rest) = div_floor32_out(g, d);
                q += k;
                g = rest;
            }
        }
        Dda32 {
            c: -q,
            g,
            qs,
            rs: r << (sub + 1),
            d,
        }
    }

    /// Row range `[first, end)` of an edge from `t` down to `b` (as
    /// [`Edge::rows`], in 32 bits: valid for `|y| ≤ 2^28` and `sub ≤ 8`,
    /// so for every projected point, which is within ±[`SCREEN_LIMIT`]).
    #[inline]
    pub(crate) fn rows(t: ScreenPt, b: ScreenPt, sub: u32) -> (i32, i32) {
        let half = 1i32 << sub;
        (
            -((half - 2 * t.y) >> (sub + 1)),
            -((half - 2 * b.y) >> (sub + 1)),
        )
    }

    /// The state as five words, for keeping it in caller memory between
    /// bands ([`super::carry`]); [`Dda32::from_words`] reads it back.
    #[inline(always)]
    pub(crate) fn to_words(self) -> [u32; 5] {
        [self.c, self.g, self.qs, self.rs, self.d].map(|w| w as u32)
    }

    /// The state [`Dda32::to_words`] wrote.
    #[inline(always)]
    pub(crate) fn from_words([c, g, qs, rs, d]: [u32; 5]) -> Dda32 {
        Dda32 {
            c: c as i32,
            g: g as i32,
            qs: qs as i32,
            rs: rs as i32,
            d: d as i32,
        }
    }

    /// The crossing pixel on the current row.
    #[inline]
    pub(crate) fn crossing(&self) -> i32 {
        self.c
    }

    /// Advances to the next row.
    #[inline]
    pub(crate) fn step(&mut self) {
        self.c = self.c.wrapping_add(self.qs);
        self.g -= self.rs;
        if self.g < 0 {
            self.g += self.d;
            self.c = self.c.wrapping_add(1);
        }
    }
}

mod packed;
pub(crate) use packed::{packs, Packed};

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
    let small = pts.iter().all(|p| p.x.abs() < SMALL && p.y.abs() < SMALL);
    build_edges_with(pts, sub, row_lo, row_hi, out, small)
}

/// [`build_edges`] given whether every vertex is within ±[`SMALL`] (the
/// caller may know it already); `small` must only be true when it holds.
pub(crate) fn build_edges_with(
    pts: &[ScreenPt],
    sub: u32,
    row_lo: i32,
    row_hi: i32,
    out: &mut [Edge],
    small: bool,
) -> Option<usize> {
    if out.len() < pts.len() {
        return None;
    }
    let small = small && sub <= 8;
    let mut n = 0usize;
    let Some(&last) = pts.last() else {
        return Some(0);
    };
    let mut prev = last;
    for &cur in pts {
        let e = if small {
            Edge::new_small(prev, cur, sub, row_lo, row_hi)
        } else {
            Edge::new(prev, cur, sub, row_lo, row_hi)
        };
        if let Some(e) = e {
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

    /// The numerator `N` of [`Edge::new`] for its first row (the largest
    /// row term, `y0 = end − 1`, is checked too), in i128.
    fn numerators(t: ScreenPt, b: ScreenPt, sub: u32) -> [i128; 2] {
        let (first, end) = Edge::rows(t, b, sub);
        let (dx, dy) = ((b.x - t.x) as i128, (b.y - t.y) as i128);
        let half = 1i128 << sub;
        [first, end - 1].map(|y0| {
            (2 * t.x as i128 - half) * dy + ((2 * y0 as i128 + 1) * half - 2 * t.y as i128) * dx
        })
    }

    /// The bound of the module docs: on displays up to 640×480 with 4
    /// sub-pixel bits (and 40×30 with 8) every edge between guard-band
    /// points (corners, random points, 4 units of rounding beyond) has
    /// `|N| < 2^31`, so edge setup divides in 32 bits; on 1024×768 it
    /// would not.
    #[test]
    fn guard_band_edges_divide_in_32_bits() {
        let widest = |w: i32, h: i32, sub: u32, rng: &mut super::super::tests::Rng| {
            let (cx, cy) = (w << sub, h << sub);
            let xs = [-(3 * cx) / 2 - 4, (5 * cx) / 2 + 4];
            let ys = [-(3 * cy) / 2 - 4, (5 * cy) / 2 + 4];
            let mut worst = 0i128;
            for k in 0..20_000 {
                let p = |rng: &mut super::super::tests::Rng, c: bool| {
                    if c {
                        pt(xs[rng.range(0, 1) as usize], ys[rng.range(0, 1) as usize])
                    } else {
                        pt(rng.range(xs[0], xs[1]), rng.range(ys[0], ys[1]))
                    }
                };
                let (a, b) = (p(rng, k % 2 == 0), p(rng, k % 3 == 0));
                if a.y == b.y {
                    continue;
                }
                let (t, b) = if a.y < b.y { (a, b) } else { (b, a) };
                for n in numerators(t, b, sub) {
                    worst = worst.max(n.abs());
                }
            }
            worst
        };
        let mut rng = super::super::tests::Rng(23);
        assert!(widest(320, 240, 4, &mut rng) < 1 << 29);
        assert!(widest(640, 480, 4, &mut rng) < 1 << 31);
        assert!(widest(40, 30, 8, &mut rng) < 1 << 31);
        assert!(widest(1024, 768, 4, &mut rng) >= 1 << 31);
    }

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
        let mut rng = crate::raster::tests::Rng(12345);
        let mut rnd = |m: i32| rng.range(-m, m);
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
    fn small_edges_equal_general_ones() {
        let mut rng = crate::raster::tests::Rng(777);
        let mut rnd = |m: i32| rng.range(-m, m);
        let lim = SMALL - 1;
        for sub in [0u32, 1, 4, 8] {
            for k in 0..2000 {
                // Mix extreme corners with random points.
                let c = |v: i32| if k % 7 == 0 { v.signum() * lim } else { v };
                let p = pt(c(rnd(lim)), c(rnd(lim)));
                let q = pt(c(rnd(lim)), c(rnd(lim)));
                let (lo, hi) = if k % 3 == 0 {
                    (i32::MIN, i32::MAX)
                } else {
                    let a = rnd(1 << (13 - sub.min(8)));
                    (a, a + 16)
                };
                let e = Edge::new_small(p, q, sub, lo, hi);
                assert_eq!(e, Edge::new(p, q, sub, lo, hi), "{p:?} {q:?} {sub} {lo}");
                // The chain walk's direct setup agrees on the first row.
                if let Some(mut e) = e {
                    let (t, b) = if p.y < q.y { (p, q) } else { (q, p) };
                    assert_eq!(Some(Dda32::start(t, b, sub, e.y0)), e.dda32());
                    let (first, end) = Dda32::rows(t, b, sub);
                    assert_eq!((first, end), Edge::rows(p, q, sub));
                    // Both steppers give the same crossings row by row, and
                    // the 32-bit state converts back exactly.
                    let Some(mut d) = e.dda32() else {
                        panic!("small edges step in 32 bits")
                    };
                    for _ in e.y0..e.y1.min(e.y0 + 64) {
                        assert_eq!(d.crossing(), e.crossing(), "{p:?} {q:?} {sub}");
                        d.step();
                        e.step();
                    }
                    let mut back = e;
                    back.set_dda32(&d);
                    assert_eq!(back, e);
                }
            }
        }
    }

    /// Random edges within ±SMALL (extreme corners, vertical ones among
    /// them), started on random active rows at 3 and 4 sub-pixel bits:
    /// the packed stepper gives `Dda32`'s crossing on every active row.
    #[test]
    fn packed_steps_as_dda32() {
        assert!(packs(3) && packs(4));
        assert!(!packs(0) && !packs(2) && !packs(5) && !packs(8));
        let mut rng = crate::raster::tests::Rng(2020);
        let lim = SMALL - 1;
        for k in 0..20_000 {
            let sub = 3 + (k % 2) as u32;
            let c = |v: i32| if k % 5 == 0 { v.signum() * lim } else { v };
            let mut p = pt(c(rng.range(-lim, lim)), c(rng.range(-lim, lim)));
            let q = pt(c(rng.range(-lim, lim)), c(rng.range(-lim, lim)));
            if k % 7 == 0 {
                p.x = q.x;
            }
            let (t, b) = if p.y < q.y { (p, q) } else { (q, p) };
            let (first, end) = Dda32::rows(t, b, sub);
            if first >= end {
                continue;
            }
            let y = first + rng.range(0, end - first - 1);
            let (mut d, mut e) = (Dda32::start(t, b, sub, y), Packed::start(t, b, sub, y));
            for _ in y..end.min(y + 300) {
                assert_eq!(e.crossing(), d.crossing(), "{t:?} {b:?} {sub} {y}");
                d.step();
                e.step();
            }
        }
    }

    /// The one-division start of cores without a divider gives the
    /// two-division start's state on an edge's first active row, the next
    /// few and any other: random
    /// edges within ±SMALL (extreme corners, vertical and one-row ones
    /// among them) at every sub-pixel precision the set-up takes.
    #[test]
    fn one_division_start_equals_two() {
        let mut rng = crate::raster::tests::Rng(2929);
        let lim = SMALL - 1;
        let mut checked = 0;
        for k in 0..60_000 {
            let sub = k % 9;
            let c = |v: i32| if k % 5 == 0 { v.signum() * lim } else { v };
            let mut p = pt(c(rng.range(-lim, lim)), c(rng.range(-lim, lim)));
            let mut q = pt(c(rng.range(-lim, lim)), c(rng.range(-lim, lim)));
            if k % 7 == 0 {
                p.x = q.x;
            }
            if k % 11 == 0 {
                q.y = p.y + rng.range(1, 40);
            }
            let (t, b) = if p.y < q.y { (p, q) } else { (q, p) };
            let (first, end) = Dda32::rows(t, b, sub as u32);
            if first >= end {
                continue;
            }
            let sub = sub as u32;
            let half = 1 << sub;
            // The first row, one of the next few, or any active row.
            let y = match k % 3 {
                0 => first,
                1 => (first + rng.range(0, 9)).min(end - 1),
                _ => rng.range(first, end - 1),
            };
            let down = (2 * y + 1) * half - 2 * t.y;
            assert!(down >= 0, "{t:?} {sub}");
            if y == first {
                assert!(down < 1 << (sub + 1), "{t:?} {sub}");
            }
            let one = Dda32::start_one_division(t, b.x - t.x, b.y - t.y, sub, down);
            assert_eq!(one, Dda32::start(t, b, sub, y), "{t:?} {b:?} {sub} {y}");
            checked += 1;
        }
        assert!(checked > 40_000, "{checked}");
    }

    /// The short division is `div_floor32`'s, inside its ±2·d window, at
    /// its ends and outside it.
    #[test]
    fn div_floor_near_equals_div_floor32() {
        let mut rng = crate::raster::tests::Rng(88);
        for k in 0..100_000 {
            let d = if k % 3 == 0 {
                rng.range(1, 40)
            } else {
                rng.range(1, (1 << 14) - 1)
            };
            let n = match k % 4 {
                0 => rng.range(-3 * d - 2, 3 * d + 1),
                1 => [
                    -2 * d - 1,
                    -2 * d,
                    2 * d - 1,
                    2 * d,
                    -d - 1,
                    -d,
                    d - 1,
                    d,
                    0,
                    -1,
                ][k / 4 % 10],
                _ => rng.range(-(1 << 14), 1 << 14),
            };
            assert_eq!(div_floor_near(n, d), div_floor32(n, d), "{n} {d}");
        }
    }

    #[test]
    fn div_floor_matches_euclid() {
        let vals = [
            0i64,
            1,
            -1,
            7,
            -7,
            i32::MAX as i64,
            i32::MIN as i64,
            i32::MIN as i64 - 1,
            1 << 40,
            -(1 << 40) - 3,
        ];
        for &n in &vals {
            for d in [1i64, 2, 3, 7, 1 << 20, i32::MAX as i64, 1 << 33] {
                assert_eq!(
                    div_floor(n, d),
                    (n.div_euclid(d), n.rem_euclid(d)),
                    "{n} {d}"
                );
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
