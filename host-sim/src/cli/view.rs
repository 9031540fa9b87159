//! `fpt view`: a preview window that orbits the model.
//!
//! ```text
//! fpt view TREE [--size WxH] [--yaw DEG] [--pitch DEG] [--distance D]
//!     [--distance-units radii|model] [--fov DEG] [--up auto|x|y|z]
//!     [--background R,G,B] [--shade lambert|flat|grey] [--precision NAME]
//!     [--frames N]
//! ```
//!
//! The window is the `embedded-graphics-simulator`'s SDL2 window, behind
//! the cargo feature `view` of `host-sim`, off by default: the default
//! build links no SDL (`cargo build --features view`, with SDL2's
//! development files installed, builds it). Without the feature the
//! command exists, so its options parse, but fails with `error: ...`
//! naming the feature and exit status 2.
//!
//! Each picture is `fpt render`'s orbit view with the same options
//! ([`super::render::OrbitArgs`]; by default the three-quarter view that
//! frames the model), drawn by the same `no_std` renderer
//! ([`super::render::render_job`]) into an exact 24-bit framebuffer and
//! shown as it is. Keys ([`Key`], [`ViewOrbit::apply`]): ←/→ turn the
//! orbit by 10° about the up axis, ↑/↓ raise or lower it by 10° (within
//! ±89°), `+`/`-` (or `=`, keypad) zoom in and out by a factor 1.25
//! (between 1.1 and 1000 bounding radii), Esc or closing the window quits.
//! A picture is drawn again only after a key changed the orbit.
//!
//! `--frames N` quits after N window updates (about 60 a second), for
//! scripted checks; the simulator's `EG_SIMULATOR_DUMP=FILE.png`
//! environment variable saves the first picture as PNG and quits instead
//! of opening the window.

use super::render::{CameraSpec, LookArgs, OrbitArgs};
use super::CliResult;
use clap::Args;
use std::path::PathBuf;

/// Degrees an arrow key turns or raises the orbit.
pub const STEP_DEG: f64 = 10.0;
/// The factor a zoom key changes the distance by.
pub const ZOOM: f64 = 1.25;
/// The highest elevation, degrees: at ±90° the orbit's up vector and its
/// view direction would be parallel.
pub const MAX_PITCH: f64 = 89.0;
/// The nearest and farthest orbit distances, in bounding radii.
pub const DISTANCE_RANGE: (f64, f64) = (1.1, 1000.0);

/// Arguments of `fpt view`.
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Tree file.
    pub tree: PathBuf,
    /// Window size WxH in pixels (each side at most 4096).
    #[arg(long, default_value = "480x360")]
    pub size: String,
    /// The orbit the window opens with.
    #[command(flatten)]
    pub orbit: OrbitArgs,
    /// Background, arithmetic, shading and slivers.
    #[command(flatten)]
    pub look: LookArgs,
    /// Quit after this many window updates (for scripted checks).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: Option<u32>,
}

/// What a key does to the view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// Turn the orbit left (yaw down).
    Left,
    /// Turn the orbit right (yaw up).
    Right,
    /// Raise the orbit (pitch up).
    Up,
    /// Lower the orbit (pitch down).
    Down,
    /// Come closer.
    ZoomIn,
    /// Move away.
    ZoomOut,
    /// Close the window.
    Quit,
}

/// The part of the orbit the keys change; the field of view and the up
/// axis stay as the options set them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewOrbit {
    /// Degrees about the up axis.
    pub yaw: f64,
    /// Degrees of elevation, within ±[`MAX_PITCH`].
    pub pitch: f64,
    /// Distance from the centre in bounding radii, within
    /// [`DISTANCE_RANGE`].
    pub distance: f64,
}

impl ViewOrbit {
    /// The orbit after `key`, and whether the window stays open. Yaw is
    /// kept in `[0, 360)`; pitch and distance stop at their limits.
    pub fn apply(self, key: Key) -> (ViewOrbit, bool) {
        let mut o = self;
        match key {
            Key::Left => o.yaw -= STEP_DEG,
            Key::Right => o.yaw += STEP_DEG,
            Key::Up => o.pitch += STEP_DEG,
            Key::Down => o.pitch -= STEP_DEG,
            Key::ZoomIn => o.distance /= ZOOM,
            Key::ZoomOut => o.distance *= ZOOM,
            Key::Quit => return (self, false),
        }
        o.yaw = o.yaw.rem_euclid(360.0);
        o.pitch = o.pitch.clamp(-MAX_PITCH, MAX_PITCH);
        o.distance = o.distance.clamp(DISTANCE_RANGE.0, DISTANCE_RANGE.1);
        (o, true)
    }

    /// The orbit of `camera` (an orbit camera of
    /// [`super::render::orbit_camera`]), brought within the limits.
    pub fn of(camera: &CameraSpec) -> Option<ViewOrbit> {
        match *camera {
            CameraSpec::Orbit {
                yaw,
                pitch,
                distance,
                ..
            } => Some(ViewOrbit {
                yaw: yaw.rem_euclid(360.0),
                pitch: pitch.clamp(-MAX_PITCH, MAX_PITCH),
                distance: distance
                    .unwrap_or(3.0)
                    .clamp(DISTANCE_RANGE.0, DISTANCE_RANGE.1),
            }),
            CameraSpec::Mvp(_) => None,
        }
    }

    /// `camera` with this orbit's yaw, pitch and distance.
    pub fn camera(&self, camera: &CameraSpec) -> CameraSpec {
        match *camera {
            CameraSpec::Orbit { fov, up, .. } => CameraSpec::Orbit {
                yaw: self.yaw,
                pitch: self.pitch,
                distance: Some(self.distance),
                fov,
                up,
            },
            other => other,
        }
    }
}

/// The message of `fpt view` in a build without the window.
pub const NO_FEATURE: &str = "fpt view needs the `view` cargo feature (the SDL2 window), \
     which this build does not have: build it with `cargo build --release -p host-sim \
     --features view` (SDL2's development files installed, e.g. libsdl2-dev)";

/// `fpt view`.
pub fn run(a: &ViewArgs) -> CliResult {
    #[cfg(feature = "view")]
    {
        window::run(a)
    }
    #[cfg(not(feature = "view"))]
    {
        let _ = a;
        Err(super::CliError(NO_FEATURE.to_string()))
    }
}

#[cfg(feature = "view")]
mod window;

#[cfg(test)]
mod tests {
    use super::*;
    use fpt_nostd::format::UpAxis;

    fn start() -> ViewOrbit {
        ViewOrbit {
            yaw: 35.0,
            pitch: 25.0,
            distance: 3.0,
        }
    }

    #[test]
    fn arrows_turn_and_raise_the_orbit_within_its_limits() {
        let (o, open) = start().apply(Key::Right);
        assert!(open);
        assert_eq!((o.yaw, o.pitch, o.distance), (45.0, 25.0, 3.0));
        let (o, _) = start().apply(Key::Left);
        assert_eq!(o.yaw, 25.0);
        // Yaw wraps around.
        let mut o = start();
        for _ in 0..4 {
            o = o.apply(Key::Left).0;
        }
        assert_eq!(o.yaw, 355.0);
        // Pitch stops short of the poles.
        let mut o = start();
        for _ in 0..20 {
            o = o.apply(Key::Up).0;
        }
        assert_eq!(o.pitch, MAX_PITCH);
        for _ in 0..40 {
            o = o.apply(Key::Down).0;
        }
        assert_eq!(o.pitch, -MAX_PITCH);
    }

    #[test]
    fn zoom_keys_scale_the_distance_within_its_range() {
        let (o, _) = start().apply(Key::ZoomIn);
        assert!((o.distance - 3.0 / ZOOM).abs() < 1e-12);
        let (o, _) = o.apply(Key::ZoomOut);
        assert!((o.distance - 3.0).abs() < 1e-12);
        let mut o = start();
        for _ in 0..100 {
            o = o.apply(Key::ZoomIn).0;
        }
        assert_eq!(o.distance, DISTANCE_RANGE.0);
        for _ in 0..100 {
            o = o.apply(Key::ZoomOut).0;
        }
        assert_eq!(o.distance, DISTANCE_RANGE.1);
    }

    #[test]
    fn escape_quits_and_the_camera_keeps_fov_and_up() {
        let (o, open) = start().apply(Key::Quit);
        assert!(!open);
        assert_eq!(o, start());
        let cam = CameraSpec::Orbit {
            yaw: -30.0,
            pitch: 95.0,
            distance: Some(0.5),
            fov: 20.0,
            up: UpAxis::Z,
        };
        let o = ViewOrbit::of(&cam).expect("an orbit");
        assert_eq!((o.yaw, o.pitch, o.distance), (330.0, MAX_PITCH, 1.1));
        assert_eq!(
            o.camera(&cam),
            CameraSpec::Orbit {
                yaw: 330.0,
                pitch: MAX_PITCH,
                distance: Some(1.1),
                fov: 20.0,
                up: UpAxis::Z,
            }
        );
        assert_eq!(ViewOrbit::of(&CameraSpec::Mvp([[0.0; 4]; 4])), None);
    }
}
