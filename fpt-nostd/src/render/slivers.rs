//! Slivers: the faces a culling walk leaves out that the sub-pixel snap
//! turns toward the viewer, drawn first so that a closed volume shows no
//! pinhole at its silhouettes.
//!
//! # Why
//!
//! The walk of a closed tree culls a face when its **plane** is turned away
//! from the viewer (an exact 3D test, [`crate::order`]), but the fill works
//! on vertices snapped to the sub-pixel grid. A face seen almost edge-on is
//! a sliver on screen, and the snap can wind it either way: a face turned
//! away may come out wound toward the viewer, and one toward the viewer
//! wound away (the fill draws it all the same). At a silhouette, where the
//! faces toward the viewer end, the faces behind the edge then no longer
//! overlap them: a sample between the two snapped edges is covered by the
//! culled sliver alone, and showed the background (11 such pixels over the
//! pinhole test's renders of the shared models, `tests/render_pinholes.rs`).
//!
//! # Contract
//!
//! Snapped, the polygons of a closed mesh still form a closed surface (a
//! shared vertex snaps to one point, and the pieces of the tree conform),
//! and the fill's coverage is its winding number at the sample nudged by
//! an infinitesimal step right and down (the tie rules of
//! [`crate::raster::edge`]). The projection of a closed surface winds
//! around every such point zero times in sum: wherever some polygon covers
//! a sample but no face of the walk does, the windings of the culled ones
//! add up to zero and one of them is **positive**, wound as a face toward
//! the viewer is. Such a culled polygon, a *sliver*, is drawn before the
//! walk's first class, so it shows exactly where no face of the walk covers
//! the sample (everything else is drawn over it): with the `nonzero` fill
//! rule every sample inside the snapped silhouette is painted, and the
//! culling walk covers exactly the pixels that the walk without culling
//! does. A polygon is a sliver when some triangle of its fan from its first
//! vertex is wound toward the viewer after the snap ([`turns_toward`]; the
//! fan's windings add up to the polygon's, so a polygon none of whose fan
//! triangles is wound that way is nowhere positive). The test is exact
//! integer arithmetic on the snapped points the fill uses; a polygon that
//! needs clipping is tested on its clipped points.
//!
//! Which way "toward the viewer" winds on screen depends on the camera (a
//! mirroring matrix reverses it): [`front_turn`] finds it per frame from
//! the matrix and the walk's view.
//!
//! Slivers are lit as faces toward the viewer (normal flipped) and draw no
//! outline (the neighbouring faces draw the silhouette's). The pass runs
//! when the renderer asks for it (`Renderer::set_slivers`, off by default)
//! and the walk culls a closed tree, in every draw loop (`render::cached`),
//! before every walk of a frame.
//!
//! # Cost
//!
//! One facing test per run turned away (as the walk makes), and per polygon
//! of those runs its screen points through the vertex cache (a vertex seen
//! only from behind is transformed here, the others are then found in the
//! cache by the walk) and one cross product per fan triangle: about half
//! the polygons and vertices of a frame more, +18 % of a socket.off frame
//! on a Cortex-M4F (`fpt mcu-bench`, docs/pipeline.md). That is why
//! it is off by default: a cheap exact pre-test (per run, from its plane)
//! would need per-polygon size bounds the format does not store, since a
//! thin face can turn over at any angle.

use crate::order::View;
use crate::raster::ScreenPt;

use super::Frame;

/// The sign of the cross product `(b − a) × (c − a)` in screen units
/// (x right, y down) of a triangle `a, b, c` counter-clockwise seen from
/// its front when its front faces the viewer: `1` or `−1`; `0` when the
/// camera has no usable centre of projection (then no sliver is drawn).
///
/// The rows `x, y, w` of the frame's matrix (`N`) project a homogeneous
/// point; a triangle's projected orientation is the sign of
/// `det(N·[A B C])` (its `w`s are positive once the near plane has
/// clipped), and `det(N·[A, A + U, A + V]) = det(N·[A, U, V])` with the
/// edge vectors `U, V` (`w = 0`). For a face toward an eye `e`
/// (`N·(e, 1) = 0`) take `A = (e − n, 1)`, `U × V = n`: the sign is that
/// of `−det(N_xyz)`. For a parallel view along `d` take `A` the origin and
/// `U × V = −d`. Screen y grows downward, which reverses the sign.
pub(crate) fn front_turn(frame: &Frame) -> i32 {
    let m = &frame.camera.matrix.0;
    // Rows x, y, w.
    let n = [m[0], m[1], m[3]];
    let xyz = |v: [f32; 3]| n.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2]);
    let ndc = match frame.view {
        View::Perspective { .. } | View::PerspectiveRelative { .. } => -det3(
            xyz([1.0, 0.0, 0.0]),
            xyz([0.0, 1.0, 0.0]),
            xyz([0.0, 0.0, 1.0]),
        ),
        View::Parallel { dir } => {
            // u ⊥ n = −dir (from the axis least along it), v = n × u:
            // u × v = n · |u|².
            let f = dir.map(|c| -c);
            let axis = if f[0].abs() <= f[1].abs() && f[0].abs() <= f[2].abs() {
                [1.0, 0.0, 0.0]
            } else if f[1].abs() <= f[2].abs() {
                [0.0, 1.0, 0.0]
            } else {
                [0.0, 0.0, 1.0]
            };
            let u = cross(axis, f);
            let v = cross(f, u);
            det3(n.map(|row| row[3]), xyz(u), xyz(v))
        }
    };
    if ndc > 0.0 {
        -1
    } else if ndc < 0.0 {
        1
    } else {
        0 // zero or not a number: no usable orientation
    }
}

/// Whether some triangle of the fan of `pts` from its first point is wound
/// as `turn` says a face toward the viewer is ([`front_turn`]): exactly
/// when the polygon may have a positive winding number somewhere (see the
/// module docs). Exact: products of 32-bit differences in 64 bits.
#[inline]
pub(crate) fn turns_toward(pts: &[ScreenPt], turn: i32) -> bool {
    let Some((a, rest)) = pts.split_first() else {
        return false;
    };
    let d = |p: &ScreenPt| {
        (
            i64::from(p.x) - i64::from(a.x),
            i64::from(p.y) - i64::from(a.y),
        )
    };
    rest.windows(2).any(|w| {
        let (b, c) = (d(&w[0]), d(&w[1]));
        let cross = b.0 * c.1 - b.1 * c.0;
        if turn > 0 {
            cross > 0
        } else {
            cross < 0
        }
    })
}

fn det3(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> f32 {
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[(i32, i32)]) -> [ScreenPt; 4] {
        let mut out = [ScreenPt { x: 0, y: 0 }; 4];
        for (o, &(x, y)) in out.iter_mut().zip(v) {
            *o = ScreenPt { x, y };
        }
        out
    }

    #[test]
    fn fan_triangles_decide() {
        // Clockwise on screen (y down): cross products negative.
        let cw = pts(&[(0, 0), (0, 10), (10, 10), (10, 0)]);
        assert!(turns_toward(&cw, -1));
        assert!(!turns_toward(&cw, 1));
        // A bow-tie: one fan triangle each way.
        let bow = pts(&[(0, 0), (10, 10), (10, 0), (0, 10)]);
        assert!(turns_toward(&bow, 1) && turns_toward(&bow, -1));
        // Degenerate (all on a line), too short: neither.
        let line = pts(&[(0, 0), (5, 5), (10, 10), (3, 3)]);
        assert!(!turns_toward(&line, 1) && !turns_toward(&line, -1));
        assert!(!turns_toward(&cw[..2], 1) && !turns_toward(&[], -1));
        // Coordinates at the guard band's size do not overflow.
        let big = pts(&[(-1 << 30, -1 << 30), (1 << 30, -1 << 30), (0, 1 << 30)]);
        assert!(turns_toward(&big[..3], 1));
    }
}
