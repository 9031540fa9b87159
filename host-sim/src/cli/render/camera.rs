//! The camera of `fpt render`: `--mvp` or an orbit, turned into the
//! renderer's [`Frame`] for a model of any size the builder accepts.
//!
//! An orbit is the library's: [`Orbit::camera_up`] around the
//! bounding-sphere centre, in model units, given to [`Frame::relative`],
//! which also derives the walk's view from the matrix
//! ([`fpt_nostd::render::MatrixView`]). `Orbit::camera` composes in model
//! space normalised by the distance, so a model of any size the builder
//! accepts (radius 1e-30 … 1e38) is drawn as the unit model; the one
//! limit is that the eye's distance be an `f32` ([`orbit_camera`] refuses
//! more). An `--mvp` matrix goes to the library as it is:
//! [`Frame::from_f64`] reads any model scale and offset itself.

use super::{parse_mvp, CliError};
use crate::cli_err;
use clap::Args;
use fpt_nostd::format::UpAxis;
use fpt_nostd::raster::{MathFns, Orbit};
use fpt_nostd::reader::Tree;
use fpt_nostd::render::{near_w_for, Frame};

/// The camera of a render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraSpec {
    /// A model → clip matrix, row-major.
    Mvp([[f64; 4]; 4]),
    /// An orbit around the bounding-sphere centre; angles in degrees,
    /// distance in bounding radii (`None` for 3), fov 0 for parallel.
    Orbit {
        /// Degrees about the up axis.
        yaw: f64,
        /// Degrees of elevation.
        pitch: f64,
        /// Distance from the centre in bounding radii.
        distance: Option<f64>,
        /// Vertical field of view, degrees.
        fov: f64,
        /// The model's up axis (the orbit itself is y-up: the model is
        /// turned so that this axis points up first).
        up: UpAxis,
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
                up,
            } => {
                let o = Orbit::new(
                    [0.0; 3],
                    yaw.to_radians() as f32,
                    pitch.to_radians() as f32,
                    (distance.unwrap_or(3.0) * radius(tree)) as f32,
                    fov.to_radians() as f32,
                );
                Frame::relative(tree, &o.camera_up::<M>(w as f32 / h as f32, up.into()))
            }
        }
    }
}

/// The tree's bounding radius, 1 for a degenerate one (a single point).
fn radius(tree: &Tree<'_>) -> f64 {
    let r = f64::from(tree.bounding_radius());
    if r.is_finite() && r > 0.0 {
        r
    } else {
        1.0
    }
}

/// The orbit options of `fpt render` and `fpt turntable`. Without any,
/// the picture is a three-quarter view (yaw 35°, pitch 25°) that frames the
/// model's bounding sphere, upright by the axis the tree records.
#[derive(Args, Clone, Debug)]
pub struct OrbitArgs {
    /// Orbit: rotation about the up axis, degrees (0 looks along −z for a
    /// y-up model) [default: 35]. Negative values are fine: --yaw=-30.
    #[arg(long, allow_hyphen_values = true)]
    pub yaw: Option<f64>,
    /// Orbit: elevation, degrees [default: 25]; negative looks from below.
    #[arg(long, allow_hyphen_values = true)]
    pub pitch: Option<f64>,
    /// Orbit: distance from the bounding-sphere centre, in bounding radii
    /// (as `fpt build --orbit`) [default: 3, or farther when the picture's
    /// narrower side would cut the bounding sphere].
    #[arg(long, allow_hyphen_values = true)]
    pub distance: Option<f64>,
    /// Units of --distance: radii (bounding radii) or model (model units).
    #[arg(long = "distance-units", default_value = "radii", value_parser = ["radii", "model"])]
    pub distance_units: String,
    /// Orbit: vertical field of view, degrees; 0 is a parallel projection.
    #[arg(long, default_value_t = 40.0, allow_hyphen_values = true)]
    pub fov: f64,
    /// The model's up axis: auto (what the tree records: `fpt build --up`),
    /// x, y or z.
    #[arg(long, default_value = "auto", value_parser = ["auto", "x", "y", "z"])]
    pub up: String,
}

/// Default yaw of an orbit when none is given: a three-quarter view.
pub const DEFAULT_YAW: f64 = 35.0;
/// Default pitch of an orbit when none is given.
pub const DEFAULT_PITCH: f64 = 25.0;

/// The default orbit distance in bounding radii for a `w × h` picture:
/// 3, or farther when the bounding sphere would not fit the narrower of the
/// two fields of view (a tall picture, a narrow `fov_deg`). Parallel
/// projections show `distance / 2` above and below the centre.
pub fn framing_distance(fov_deg: f64, w: u32, h: u32) -> f64 {
    let aspect = f64::from(w) / f64::from(h);
    let need = if fov_deg > 0.0 {
        let half_v = 0.5 * fov_deg.to_radians();
        let half_h = (half_v.tan() * aspect).atan();
        1.0 / half_v.min(half_h).sin()
    } else {
        2.0 / aspect.min(1.0)
    };
    need.max(3.0)
}

/// The orbit camera of `o` for `tree` in a `w × h` picture, checked: any
/// finite angles, a positive distance, a field of view in [0, 180).
pub fn orbit_camera(
    o: &OrbitArgs,
    tree: &Tree<'_>,
    w: u32,
    h: u32,
) -> Result<CameraSpec, CliError> {
    let yaw = o.yaw.unwrap_or(DEFAULT_YAW);
    let pitch = o.pitch.unwrap_or(DEFAULT_PITCH);
    if !(yaw.is_finite() && pitch.is_finite()) {
        return Err(cli_err!("--yaw and --pitch must be finite numbers"));
    }
    if !(o.fov.is_finite() && (0.0..180.0).contains(&o.fov)) {
        return Err(cli_err!("--fov must be in [0, 180) degrees, got {}", o.fov));
    }
    let r = radius(tree);
    let distance = match o.distance {
        None => framing_distance(o.fov, w, h),
        Some(d) => {
            if !(d.is_finite() && d > 0.0) {
                return Err(cli_err!("--distance must be a positive number, got {d}"));
            }
            if o.distance_units == "model" {
                d / r
            } else {
                d
            }
        }
    };
    // The library's orbit takes the eye's distance as an `f32` in model
    // units (any such distance composes: `Orbit::camera`).
    let model = distance * r;
    if !(model.is_finite() && model < f64::from(f32::MAX)) {
        return Err(cli_err!(
            "--distance is too large: {distance:e} bounding radii puts the eye {model:e} model units away, more than {:e}",
            f32::MAX
        ));
    }
    let up = match o.up.as_str() {
        "auto" => tree.up_axis(),
        name => UpAxis::from_name(name)
            .ok_or_else(|| cli_err!("unknown up axis '{name}' (expected auto, x, y or z)"))?,
    };
    Ok(CameraSpec::Orbit {
        yaw,
        pitch,
        distance: Some(distance),
        fov: o.fov,
        up,
    })
}

/// The camera of `--mvp` when given, else the orbit's.
pub fn camera_of(
    mvp: Option<&str>,
    o: &OrbitArgs,
    tree: &Tree<'_>,
    w: u32,
    h: u32,
) -> Result<CameraSpec, CliError> {
    match mvp {
        Some(m) => Ok(CameraSpec::Mvp(parse_mvp(m)?)),
        None => orbit_camera(o, tree, w, h),
    }
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
                up: UpAxis::Y,
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
