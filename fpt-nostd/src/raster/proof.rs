//! Once a frame, a proof that the float transform's per-vertex checks
//! cannot fire: the model's vertex bound, seen through the frame's matrix,
//! lies inside the near plane and inside the viewport, with margins that
//! cover the `f32` rounding of the transform actually performed.
//!
//! The contract: when [`prove_float`] returns `true` for a matrix `m`, a
//! near threshold `near` and a [`VertexBound`] that holds for every vertex
//! `p` handed to the transform (`|p_i| ≤ abs[i]`, `|p|² ≤ norm2`), then for
//! every such `p` the values `X`, `Y`, `W` that
//! [`super::transform::FloatPath`] computes (rows 0, 1 and 3 of `m`, in
//! `f32`, in any association or with fused multiply-adds) satisfy
//!
//! * `W ≥ near` and `|X|, |Y|, |W| ≤ 10^30`: the transform's finiteness
//!   test and the near plane pass;
//! * `|X|, |Y| ≤ (1 − 2^-8)·W`: the guard planes (`|X| ≤ 4W`) pass, and
//!   with a reciprocal of relative error below `2^-8` (libm's is exact to
//!   half an ulp; micromath's is tested below `2^-12`, `tests` here) the
//!   projected `x/w`, `y/w` lie in `[−1, 1]`, so the NDC clamp of
//!   `screen_f32` does not change them and the screen coordinates it
//!   produces are at least 0.5, where truncation is the floor.
//!
//! So the unchecked projection ([`super::transform::VertexPath::project_proven`])
//! gives the very same screen point as the checked pipeline (transform,
//! clip test, projection); the proof only removes tests, never changes a
//! result.
//!
//! # The arithmetic
//!
//! For a plane `q·p + q₃ ≥ 0` (a combination of the matrix rows) its
//! smallest value over the ball `|p|² ≤ norm2` is `q₃ − |q|·√norm2`. The
//! true value must exceed the transform's rounding error: a four-term
//! `f32` dot product errs by at most `3u/(1 − 3u)·S` (`u = 2^-24`,
//! `S = Σ|m_i|·abs[i] + |m₃|`), and the vertex's own rounding (the frame's
//! scale) by `u` of each term: below `2^-21·S`. The test below demands a
//! margin of `2^-16·T`, `T` the sum of every magnitude involved (both rows'
//! `S` and `(|a|₁ + |w|₁)·√norm2`), which is at least 8 times that error
//! plus the rounding of the test's own few dozen `f32` operations (each at
//! most `u` relative to `T`, fewer than 64 of them: `< 2^-18·T`). The
//! square root is avoided: `A ≥ |q|·R` is tested as `A ≥ 0` and
//! `A² ≥ |q|²·R²·(1 + 2^-14)`, the factor covering the squares' rounding.
//! Every comparison is written so that a NaN anywhere fails it.

use super::camera::Mat4;

/// Bounds on a model's vertices as the transform receives them: the
/// largest magnitude of each coordinate and the largest squared length
/// (an upper bound, rounding included). Computed once when a tree is
/// read ([`crate::reader::Tree::vertex_bound`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexBound {
    /// Largest `|p_i|` per axis.
    pub abs: [f32; 3],
    /// Largest `p₀² + p₁² + p₂²`, rounded up.
    pub norm2: f32,
}

/// Relative slack of one `f32` rounding step, generously: the bounds
/// below are inflated by it wherever a value was rounded.
const SLACK: f32 = 1.0 / 65536.0;

impl VertexBound {
    /// The empty bound (no vertex): every proof holds for it.
    pub const EMPTY: VertexBound = VertexBound {
        abs: [0.0; 3],
        norm2: 0.0,
    };

    /// The bound grown to hold `p` as well (the squared length is computed
    /// in `f32`, so it is rounded up by [`SLACK`], far above its error of
    /// three roundings).
    pub fn with(self, p: [f32; 3]) -> VertexBound {
        let a = p.map(f32::abs);
        let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (1.0 + SLACK);
        VertexBound {
            abs: [0, 1, 2].map(|i| max_nan(self.abs[i], a[i])),
            norm2: max_nan(self.norm2, n),
        }
    }

    /// The bound of the vertices multiplied by `s` (the frame's vertex
    /// scale; rounded up, so that it also holds for the rounded products).
    pub fn scaled(&self, s: f32) -> VertexBound {
        let s = s.abs() * (1.0 + SLACK);
        VertexBound {
            abs: self.abs.map(|a| a * s),
            norm2: self.norm2 * s * s,
        }
    }
}

/// `max(a, b)`, NaN if either is NaN (so that a non-finite vertex makes
/// every proof fail rather than being ignored).
fn max_nan(a: f32, b: f32) -> f32 {
    if a.is_nan() || b.is_nan() {
        f32::NAN
    } else if a >= b {
        a
    } else {
        b
    }
}

/// `1 − 2^-8`: how far inside the viewport's planes every vertex must be
/// (above any reciprocal's relative error the float path uses).
pub const INSET: f32 = 1.0 - 1.0 / 256.0;

/// Largest rounding bound `S` of a row accepted: keeps `|X|, |Y|, |W|`
/// far below the transform's limit of `10^36`.
const MAGNITUDE: f32 = 1e30;

/// `S = Σ|m_i|·abs[i] + |m₃|` for row `m`.
fn magnitude(m: &[f32; 4], b: &VertexBound) -> f32 {
    m[0].abs() * b.abs[0] + m[1].abs() * b.abs[1] + m[2].abs() * b.abs[2] + m[3].abs()
}

/// `|m₀| + |m₁| + |m₂|`.
fn norm1(m: &[f32; 4]) -> f32 {
    m[0].abs() + m[1].abs() + m[2].abs()
}

/// Whether `q·p + q₃ ≥ 0` holds with the margin `2^-16·t` for every `p`
/// of the ball `|p|² ≤ norm2` (see the module docs).
fn plane_holds(q: [f32; 4], norm2: f32, t: f32) -> bool {
    let a = q[3] - t * SLACK;
    let qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
    a >= 0.0 && a * a >= qq * norm2 * (1.0 + 4.0 * SLACK)
}

/// The frame proof (module docs): `true` when no vertex within `bound`
/// can fail a check of the float transform and projection under matrix
/// `m` and near threshold `near`.
pub fn prove_float(m: &Mat4, near: f32, bound: &VertexBound) -> bool {
    let b = bound;
    let (x, y, w) = (&m.0[0], &m.0[1], &m.0[3]);
    let (sx, sy, sw) = (magnitude(x, b), magnitude(y, b), magnitude(w, b));
    // Also false for NaN: the comparisons are written to fail on it.
    if !(sx <= MAGNITUDE && sy <= MAGNITUDE && sw <= MAGNITUDE && near > 0.0 && near <= 1e30) {
        return false;
    }
    // An upper bound of the ball's radius √norm2 for the margins only,
    // where a factor of √3 does not matter: |p|₂ ≤ |p|₁ ≤ Σ abs[i]
    // (avoids a square root).
    let r = b.abs[0] + b.abs[1] + b.abs[2];
    // The near plane: w − near ≥ 0.
    let t = sw + near + norm1(w) * r;
    if !plane_holds([w[0], w[1], w[2], w[3] - near], b.norm2, t) {
        return false;
    }
    // The four side planes: INSET·w ∓ a ≥ 0 for a = x, y.
    for (a, sa) in [(x, sx), (y, sy)] {
        let t = sa + sw + (norm1(a) + norm1(w)) * r;
        for sign in [1.0f32, -1.0] {
            let q = [0, 1, 2, 3].map(|i| INSET * w[i] - sign * a[i]);
            if !plane_holds(q, b.norm2, t) {
                return false;
            }
        }
    }
    true
}
