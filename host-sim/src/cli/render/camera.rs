//! The camera of `fpt render`: `--mvp` or an orbit, turned into the
//! renderer's [`Frame`] for a model of any size the builder accepts.
//!
//! Why this is more than `Frame::relative(tree, &orbit.camera())`: composed
//! in model units, an orbit around a model of radius 1e20 overflows `f32`
//! inside the projection (2·far·near is 2·distance²) and one of radius
//! 1e-20 underflows. The orbit is composed in units of a power of two near
//! the bounding radius, where the model has radius about 1, and scaled
//! back exactly. An `--mvp` matrix goes to the library as it is:
//! [`Frame::from_f64`] reads any model scale and offset itself.

use fpt_nostd::order::View;
use fpt_nostd::raster::{MathFns, Orbit};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{near_w_for, rows_f64, Frame, MatrixView};

/// The camera of a render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraSpec {
    /// A model → clip matrix, row-major.
    Mvp([[f64; 4]; 4]),
    /// An orbit around the bounding-sphere centre; angles in degrees,
    /// distance `None` for 3× the bounding radius, fov 0 for parallel.
    Orbit {
        /// Degrees about the y axis.
        yaw: f64,
        /// Degrees of elevation.
        pitch: f64,
        /// Distance from the centre.
        distance: Option<f64>,
        /// Vertical field of view, degrees.
        fov: f64,
        /// The model is z-up (the orbit itself is y-up).
        z_up: bool,
    },
}

impl CameraSpec {
    /// The frame for `tree` in a `w × h` image, with `M`'s trigonometry.
    pub fn frame<M: MathFns>(&self, tree: &Tree<'_>, w: u32, h: u32) -> Frame {
        match *self {
            CameraSpec::Mvp(rows) => {
                Frame::from_f64(tree, &rows, f64::from(near_w_for(&rows, tree)))
            }
            CameraSpec::Orbit {
                yaw,
                pitch,
                distance,
                fov,
                z_up,
            } => {
                let r = f64::from(tree.bounding_radius());
                let r = if r.is_finite() && r > 0.0 { r } else { 1.0 };
                // The orbit is composed in units of `u = 2^e ≤ r` (so the
                // model's radius is in [1, 2)) and scaled back to model
                // units after: composed in model units, a model of radius
                // 1e20 or more overflows `f32` inside the projection
                // (2·far·near is 2·distance²) and one below 1e-20
                // underflows, and nothing is drawn. Scaling by powers of
                // two is exact, so for any radius whose matrix is
                // representable the frame is bit for bit the one composed
                // in model units.
                let e = log2_floor(r);
                let d = distance.unwrap_or(3.0 * r) * pow2(-e);
                let o = Orbit::new(
                    [0.0; 3],
                    yaw.to_radians() as f32,
                    pitch.to_radians() as f32,
                    d as f32,
                    fov.to_radians() as f32,
                );
                let mut cam = o.camera::<M>(w as f32 / h as f32);
                if z_up {
                    // M · R with R taking model (x, y, z) to orbit space
                    // (x, z, −y), a rotation: an exact column permutation.
                    for row in cam.matrix.0.iter_mut() {
                        *row = [row[0], -row[2], row[1], row[3]];
                    }
                }
                let unit_view = MatrixView::of(&rows_f64(&cam.matrix), [0.0; 3]);
                // Model units: M · S(2^−e). The renderer normalises the
                // matrix's scale itself (a homogeneous factor changes no
                // projected point), so it is multiplied by 2^(e/2) too,
                // which keeps every entry far inside the `f32` range:
                // the x, y, z columns get 2^(e/2 − e), the translation
                // column and the near threshold 2^(e/2).
                let half = e / 2;
                let (sx, st) = (pow2(half - e) as f32, pow2(half) as f32);
                for row in cam.matrix.0.iter_mut() {
                    *row = [row[0] * sx, row[1] * sx, row[2] * sx, row[3] * st];
                }
                cam.near_w *= st;
                let mut frame = Frame::relative(tree, &cam);
                // The walk's view from the matrix in units of `u`, where its
                // columns are balanced; for a model
                // of ordinary size this is bit for bit the view derived
                // from the matrix in model units.
                if let Some(view) = scaled_view(unit_view, pow2(e)) {
                    frame.view = view;
                }
                frame
            }
        }
    }
}

/// The walk's view for a view found in origin-relative coordinates in
/// units of `u` (a power of two): the eye scaled back to model units, a
/// direction as it is; `None` for a degenerate view.
fn scaled_view(view: MatrixView, u: f64) -> Option<View> {
    match view {
        MatrixView::Perspective { eye } => Some(View::PerspectiveRelative {
            eye: eye.map(|v| (v * u) as f32),
        }),
        MatrixView::Parallel { dir } => Some(View::Parallel {
            dir: dir.map(|v| v as f32),
        }),
        MatrixView::Degenerate => None,
    }
}

/// `floor(log2(x))` for a finite `x > 0` (0 otherwise), within ±126 so
/// that `2^e` and `2^−e` are normal `f32` numbers.
fn log2_floor(x: f64) -> i32 {
    if !(x.is_finite() && x > 0.0) {
        return 0;
    }
    let mut e = ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    // A subnormal `f64` is far below any `f32` radius; `log2` is exact
    // enough for it.
    if e == -1023 {
        e = x.log2().floor() as i32;
    }
    e.clamp(-126, 126)
}

/// `2^e` as `f64`, exactly (`e` within ±1000).
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e.clamp(-1000, 1000) + 1023) as u64) << 52)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::{build, NoProgress};
    use crate::serialize::{serialize, SerializeOptions};
    use fpt_nostd::raster::{FixedPrecision, Libm, Precision};

    /// The frame as `fpt render` composed an orbit before it worked in
    /// radius units: in model units throughout.
    fn model_units<M: MathFns>(tree: &Tree<'_>, yaw: f64, pitch: f64, fov: f64) -> Frame {
        let r = tree.bounding_radius();
        let o = Orbit::new(
            [0.0; 3],
            yaw.to_radians() as f32,
            pitch.to_radians() as f32,
            3.0 * r,
            fov.to_radians() as f32,
        );
        Frame::relative(tree, &o.camera::<M>(4.0 / 3.0))
    }

    #[test]
    fn orbit_frames_of_ordinary_models_are_those_composed_in_model_units() {
        let s = crate::scenes::house();
        let t = build(
            s.polygons,
            s.closed,
            crate::tree::Method::Static,
            1,
            &mut NoProgress,
        );
        let bytes = serialize(&t, &SerializeOptions::default()).unwrap();
        let tree = Tree::from_bytes(&bytes).unwrap();
        assert!(tree.bounding_radius() > 2.0, "not a power-of-two-free case");
        for (yaw, pitch, fov) in [(30.0, 20.0, 40.0), (-115.0, 62.0, 75.0), (10.0, -5.0, 0.0)] {
            let spec = CameraSpec::Orbit {
                yaw,
                pitch,
                distance: None,
                fov,
                z_up: false,
            };
            type M = <FixedPrecision<4> as Precision>::Math;
            assert_eq!(
                spec.frame::<M>(&tree, 320, 240),
                model_units::<M>(&tree, yaw, pitch, fov),
                "{yaw} {pitch} {fov}"
            );
            assert_eq!(
                spec.frame::<Libm>(&tree, 320, 240),
                model_units::<Libm>(&tree, yaw, pitch, fov)
            );
        }
    }
}
