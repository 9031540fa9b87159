//! Cameras of the reference renderer and the view they give the tree walk.
//!
//! A camera is a 4×4 matrix `M` (row-major `[f64; 16]`, model → clip): for a
//! model point `p`, `clip = M·[p, 1]`, `ndc = clip.xyz / clip.w`; a `W × H`
//! image maps `ndc.x ∈ [-1, 1]` to pixel x `(ndc.x + 1)/2·W` and `ndc.y` to
//! pixel y `(1 − ndc.y)/2·H` (y down); pixel `(i, j)` is sampled at
//! `(i + 0.5, j + 0.5)`. Points with `−w ≤ z ≤ w` lie between the near and far
//! planes and are drawn; a smaller `ndc.z` is nearer.
//!
//! The [`View`] is what the tree traversal needs: the view direction of a
//! parallel camera, the eye point of a perspective one. It is derived from the
//! matrix (the centre of projection is the null vector of its x, y and w rows),
//! so a camera built from any matrix gets the view that matches its pixels.

use crate::geom::Plane;
use glam::{DMat4, DVec3, DVec4};

/// How a [`Camera::look_at`] camera projects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Perspective with a vertical field of view in degrees, `0 < fov < 180`,
    /// and near and far distances from the eye, `0 < near < far`.
    Perspective {
        /// Vertical field of view, degrees.
        fov_y_deg: f64,
        /// Distance of the near plane from the eye.
        near: f64,
        /// Distance of the far plane from the eye.
        far: f64,
    },
    /// Parallel (orthographic) projection showing `±half_height` vertically;
    /// near and far are signed distances from the eye along the view
    /// direction, `near < far`.
    Parallel {
        /// Half the visible height, model units.
        half_height: f64,
        /// Signed distance of the near plane from the eye.
        near: f64,
        /// Signed distance of the far plane from the eye.
        far: f64,
    },
}

/// The view a tree traversal needs to choose sides and cull faces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum View {
    /// Parallel projection looking along `dir` (unit, from the viewer into
    /// the scene).
    Parallel {
        /// Unit view direction.
        dir: DVec3,
    },
    /// Perspective projection from the eye point.
    Perspective {
        /// The centre of projection.
        eye: DVec3,
    },
}

impl View {
    /// Whether a polygon in `plane` faces the viewer ("backward" in the
    /// paper's words): its normal points against the view direction, or the
    /// eye is strictly on its front side. Exactly edge-on counts as not
    /// facing; such a face covers no pixel either way.
    pub fn faces(&self, plane: &Plane) -> bool {
        match *self {
            View::Parallel { dir } => plane.normal.dot(dir) < 0.0,
            View::Perspective { eye } => plane.distance(eye) > 0.0,
        }
    }
}

/// A camera: the model → clip matrix, its inverse and the derived view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Model → clip, as glam's (column-major) matrix.
    m: DMat4,
    /// Clip → model.
    inv: DMat4,
    view: View,
}

impl Camera {
    /// A camera at `eye` looking at `target` with `up` roughly up on screen;
    /// `aspect` is the image width over its height. `None` when the input is
    /// not finite or degenerate (eye on target, up along the view, bad
    /// projection parameters).
    pub fn look_at(
        eye: DVec3,
        target: DVec3,
        up: DVec3,
        projection: Projection,
        aspect: f64,
    ) -> Option<Camera> {
        let f = (target - eye).try_normalize()?;
        let s = f.cross(up).try_normalize()?;
        let u = s.cross(f);
        if !(aspect.is_finite() && aspect > 0.0 && eye.is_finite()) {
            return None;
        }
        // Eye space: right-handed, looking down -z (the OpenGL convention).
        let view_rows = [
            [s.x, s.y, s.z, -s.dot(eye)],
            [u.x, u.y, u.z, -u.dot(eye)],
            [-f.x, -f.y, -f.z, f.dot(eye)],
            [0.0, 0.0, 0.0, 1.0],
        ];
        let (proj_rows, view) = match projection {
            Projection::Perspective {
                fov_y_deg,
                near,
                far,
            } => {
                let ok = fov_y_deg > 0.0 && fov_y_deg < 180.0 && near > 0.0 && far > near;
                if !(ok && far.is_finite()) {
                    return None;
                }
                let g = 1.0 / (fov_y_deg.to_radians() * 0.5).tan();
                let rows = [
                    [g / aspect, 0.0, 0.0, 0.0],
                    [0.0, g, 0.0, 0.0],
                    [
                        0.0,
                        0.0,
                        (far + near) / (near - far),
                        2.0 * far * near / (near - far),
                    ],
                    [0.0, 0.0, -1.0, 0.0],
                ];
                (rows, View::Perspective { eye })
            }
            Projection::Parallel {
                half_height,
                near,
                far,
            } => {
                let ok = half_height > 0.0 && far > near;
                if !(ok && half_height.is_finite() && near.is_finite() && far.is_finite()) {
                    return None;
                }
                let rows = [
                    [1.0 / (half_height * aspect), 0.0, 0.0, 0.0],
                    [0.0, 1.0 / half_height, 0.0, 0.0],
                    [0.0, 0.0, -2.0 / (far - near), -(far + near) / (far - near)],
                    [0.0, 0.0, 0.0, 1.0],
                ];
                (rows, View::Parallel { dir: f })
            }
        };
        let m = rows_to_mat(&proj_rows) * rows_to_mat(&view_rows);
        let inv = invert(m)?;
        Some(Camera { m, inv, view })
    }

    /// A camera from a row-major model → clip matrix (see the module docs).
    /// `None` when it is not finite or not invertible.
    pub fn from_mvp(mvp: [f64; 16]) -> Option<Camera> {
        let m = DMat4::from_cols_array(&mvp).transpose();
        let inv = invert(m)?;
        let view = view_of(m, inv)?;
        Some(Camera { m, inv, view })
    }

    /// The row-major model → clip matrix.
    pub fn mvp(&self) -> [f64; 16] {
        self.m.transpose().to_cols_array()
    }

    /// The view for the tree traversal.
    pub fn view(&self) -> View {
        self.view
    }

    /// Clip coordinates of a model point.
    pub fn clip(&self, p: DVec3) -> DVec4 {
        self.m * p.extend(1.0)
    }

    /// The model point at normalised device coordinates `ndc`, or `None`
    /// when it lies at infinity.
    pub fn unproject(&self, ndc: DVec3) -> Option<DVec3> {
        let h = self.inv * ndc.extend(1.0);
        let p = h.truncate() / h.w;
        p.is_finite().then_some(p)
    }
}

/// A glam matrix from rows.
fn rows_to_mat(r: &[[f64; 4]; 4]) -> DMat4 {
    DMat4::from_cols_array_2d(r).transpose()
}

/// The inverse, when the matrix is finite and invertible.
fn invert(m: DMat4) -> Option<DMat4> {
    let det = m.determinant();
    if !(det.is_finite() && det != 0.0 && m.is_finite()) {
        return None;
    }
    let inv = m.inverse();
    inv.is_finite().then_some(inv)
}

/// 3×3 determinant of rows `a`, `b`, `c`.
fn det3(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    a.dot(b.cross(c))
}

/// The view of the matrix `m`: its centre of projection is the homogeneous
/// point `C` with `(M·C).x = (M·C).y = (M·C).w = 0`, the null vector of those
/// three rows. `C.w = 0` means the centre is at infinity: a parallel camera,
/// whose direction is taken from the near plane towards the far plane.
fn view_of(m: DMat4, inv: DMat4) -> Option<View> {
    let (r0, r1, r3) = (m.row(0), m.row(1), m.row(3));
    let pick = |r: DVec4, skip: usize| {
        let a = r.to_array();
        let v: Vec<f64> = (0..4).filter(|&i| i != skip).map(|i| a[i]).collect();
        DVec3::new(v[0], v[1], v[2])
    };
    let minor = |skip: usize| det3(pick(r0, skip), pick(r1, skip), pick(r3, skip));
    let c = DVec4::new(minor(0), -minor(1), minor(2), -minor(3));
    let xyz = c.truncate();
    if c.w.abs() <= 1e-12 * (xyz.x.abs() + xyz.y.abs() + xyz.z.abs()) {
        let unproject = |z: f64| {
            let h = inv * DVec4::new(0.0, 0.0, z, 1.0);
            h.truncate() / h.w
        };
        let dir = (unproject(1.0) - unproject(-1.0)).try_normalize()?;
        Some(View::Parallel { dir })
    } else {
        let eye = xyz / c.w;
        eye.is_finite().then_some(View::Perspective { eye })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn persp() -> Projection {
        Projection::Perspective {
            fov_y_deg: 60.0,
            near: 0.1,
            far: 100.0,
        }
    }

    #[test]
    fn look_at_maps_target_to_screen_centre_and_near_far_to_ndc_range() {
        let eye = DVec3::new(1.0, 2.0, 3.0);
        let target = DVec3::new(-2.0, 0.5, 0.0);
        let cam = Camera::look_at(eye, target, DVec3::Z, persp(), 1.5).unwrap();
        let c = cam.clip(target);
        let ndc = c.truncate() / c.w;
        assert!(ndc.x.abs() < 1e-12 && ndc.y.abs() < 1e-12, "{ndc}");
        let dir = (target - eye).normalize();
        let near = cam.clip(eye + dir * 0.1);
        assert!((near.z / near.w + 1.0).abs() < 1e-9);
        let far = cam.clip(eye + dir * 100.0);
        assert!((far.z / far.w - 1.0).abs() < 1e-9);
        // A point above the target appears above the centre (smaller pixel y).
        let up = cam.clip(target + DVec3::Z * 0.1);
        assert!(up.y / up.w > 0.0);
    }

    #[test]
    fn view_from_matrix_matches_look_at() {
        let eye = DVec3::new(4.0, -3.0, 2.5);
        let target = DVec3::new(0.2, 0.1, 0.0);
        let cam = Camera::look_at(eye, target, DVec3::Z, persp(), 1.0).unwrap();
        let again = Camera::from_mvp(cam.mvp()).unwrap();
        match again.view() {
            View::Perspective { eye: e } => assert!((e - eye).length() < 1e-9, "{e}"),
            v => panic!("expected perspective, got {v:?}"),
        }
        let par = Projection::Parallel {
            half_height: 2.0,
            near: 0.0,
            far: 20.0,
        };
        let cam = Camera::look_at(eye, target, DVec3::Z, par, 1.0).unwrap();
        let again = Camera::from_mvp(cam.mvp()).unwrap();
        let want = (target - eye).normalize();
        match again.view() {
            View::Parallel { dir } => assert!((dir - want).length() < 1e-12, "{dir}"),
            v => panic!("expected parallel, got {v:?}"),
        }
    }

    #[test]
    fn degenerate_cameras_are_refused() {
        let e = DVec3::ONE;
        assert!(Camera::look_at(e, e, DVec3::Z, persp(), 1.0).is_none());
        assert!(Camera::look_at(e, DVec3::new(1.0, 1.0, 0.0), DVec3::Z, persp(), 1.0).is_none());
        let bad = Projection::Perspective {
            fov_y_deg: 60.0,
            near: 0.0,
            far: 1.0,
        };
        assert!(Camera::look_at(e, DVec3::ZERO, DVec3::Z, bad, 1.0).is_none());
        assert!(Camera::from_mvp([0.0; 16]).is_none());
        let mut nan = [0.0; 16];
        nan[0] = f64::NAN;
        assert!(Camera::from_mvp(nan).is_none());
    }

    #[test]
    fn facing_test_uses_eye_or_direction() {
        let p = Plane {
            normal: DVec3::Z,
            d: 0.0,
        };
        assert!(View::Perspective { eye: DVec3::Z }.faces(&p));
        assert!(!View::Perspective { eye: -DVec3::Z }.faces(&p));
        assert!(View::Parallel { dir: -DVec3::Z }.faces(&p));
        assert!(!View::Parallel { dir: DVec3::X }.faces(&p));
    }
}
