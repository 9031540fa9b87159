//! Cameras: a 4×4 matrix, or orbit parameters that produce one.
//!
//! Conventions (shared with the host simulator):
//! * Matrices are row-major; `clip = M · [x, y, z, 1]`.
//! * `ndc = clip.xyz / clip.w`; pixel `x = (ndc.x + 1)/2 · W`,
//!   `y = (1 − ndc.y)/2 · H`; pixel `(i, j)` is sampled at `(i + ½, j + ½)`.
//! * Smaller `ndc.z` is nearer (−1 at the near plane, +1 at the far plane).
//!   The rasterizer itself ignores z: visibility comes from the priority
//!   tree; only `w` matters, for the near clip (`w ≥ near_w`).
//! * Orbit cameras use a y-up world. The eye sits at
//!   `target + distance · (cos pitch · sin yaw, sin pitch, cos pitch · cos yaw)`
//!   and looks at `target`; yaw 0, pitch 0 looks down −z.
//!   `fov` is the vertical field of view in radians; `fov <= 0` (or not
//!   finite) gives a parallel projection whose visible half-height at any
//!   depth is `distance / 2` (what a perspective camera with a 53° field of
//!   view sees at the target), so switching projection keeps the model about
//!   the same size on screen.
//!
//! With a parallel camera `w` is constant (1 for any ordinary distance,
//! see [`Orbit::camera`]) and above `near_w`, so nothing is near-clipped:
//! geometry behind the eye is drawn like the rest (the orbit eye is normally
//! outside the model).

use super::precision::MathFns;

/// A row-major 4×4 matrix of `f32`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat4(pub [[f32; 4]; 4]);

impl Mat4 {
    /// The identity.
    pub const IDENTITY: Mat4 = Mat4([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]);

    /// The matrix product `self · rhs` (apply `rhs` first).
    pub fn mul(&self, rhs: &Mat4) -> Mat4 {
        let mut out = [[0.0f32; 4]; 4];
        for (r, row) in out.iter_mut().enumerate() {
            for (c, cell) in row.iter_mut().enumerate() {
                *cell = (0..4).map(|k| self.0[r][k] * rhs.0[k][c]).sum();
            }
        }
        Mat4(out)
    }

    /// A translation by `t`.
    pub fn translation(t: [f32; 3]) -> Mat4 {
        let mut m = Mat4::IDENTITY;
        m.0[0][3] = t[0];
        m.0[1][3] = t[1];
        m.0[2][3] = t[2];
        m
    }

    /// `M · [p, 1]` (the homogeneous clip-space point).
    pub fn transform_point(&self, p: [f32; 3]) -> [f32; 4] {
        let mut out = [0.0f32; 4];
        for (o, row) in out.iter_mut().zip(self.0.iter()) {
            *o = row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + row[3];
        }
        out
    }

    /// True when every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().flatten().all(|v| v.is_finite())
    }

    /// The view matrix of an eye at `eye` looking at `target`, with `up`
    /// toward the top of the screen: eye space is right-handed, `+x`
    /// right, `+y` up, looking down `−z` (the orbit's convention). `up`
    /// need not be unit nor perpendicular to the view; an `up` parallel to
    /// it, or `eye == target`, gives a matrix that collapses the picture
    /// (renders nothing useful, never fails).
    ///
    /// ```
    /// use fpt_nostd::raster::{Libm, Mat4};
    /// let v = Mat4::look_at::<Libm>([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0]);
    /// assert_eq!(v.transform_point([0.0; 3]), [0.0, 0.0, -5.0, 1.0]);
    /// ```
    pub fn look_at<M: MathFns>(eye: [f32; 3], target: [f32; 3], up: [f32; 3]) -> Mat4 {
        let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: [f32; 3], b: [f32; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let unit = |v: [f32; 3]| {
            let l = M::sqrt(dot(v, v));
            if l > 0.0 && l.is_finite() {
                v.map(|c| c / l)
            } else {
                [0.0; 3]
            }
        };
        let back = unit(sub(eye, target)); // +z: from the target to the eye
        let right = unit(cross(up, back));
        let top = cross(back, right);
        let row = |a: [f32; 3]| [a[0], a[1], a[2], -dot(a, eye)];
        Mat4([row(right), row(top), row(back), [0.0, 0.0, 0.0, 1.0]])
    }

    /// A perspective projection of vertical field of view `fov` (radians),
    /// aspect ratio `aspect = width / height`, near and far planes at eye
    /// distances `near` and `far` (`0 < near < far`): eye space (looking
    /// down `−z`) to clip space with `w` = the eye distance and `ndc.z`
    /// from −1 at `near` to +1 at `far` (OpenGL's convention). Give the
    /// renderer `near` as the near threshold
    /// ([`Camera::perspective_look_at`] does).
    ///
    /// ```
    /// use fpt_nostd::raster::{Libm, Mat4};
    /// let p = Mat4::perspective::<Libm>(core::f32::consts::FRAC_PI_2, 1.0, 1.0, 100.0);
    /// let c = p.transform_point([0.0, 2.0, -2.0]); // 45° up: the top edge
    /// assert!((c[1] / c[3] - 1.0).abs() < 1e-6 && c[3] == 2.0);
    /// ```
    pub fn perspective<M: MathFns>(fov: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
        let focal = M::recip(M::tan(0.5 * fov));
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        let a = (far + near) / (near - far);
        let b = 2.0 * far * near / (near - far);
        Mat4([
            [focal / aspect, 0.0, 0.0, 0.0],
            [0.0, focal, 0.0, 0.0],
            [0.0, 0.0, a, b],
            [0.0, 0.0, -1.0, 0.0],
        ])
    }
}

/// Which model axis points up on the screen: the builders keep a mesh's
/// own coordinates, and CAD parts (STL) are usually z-up while the
/// orbit's convention is y-up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Up {
    /// `+y` up (the orbit's own convention).
    #[default]
    Y,
    /// `+z` up (most CAD and STL files).
    Z,
    /// `+x` up.
    X,
}

impl From<crate::format::UpAxis> for Up {
    /// The up axis a tree file records ([`crate::reader::Tree::up_axis`]).
    fn from(axis: crate::format::UpAxis) -> Up {
        match axis {
            crate::format::UpAxis::Y => Up::Y,
            crate::format::UpAxis::Z => Up::Z,
            crate::format::UpAxis::X => Up::X,
        }
    }
}

impl Up {
    /// The model rotation that brings this axis to `+y`, to apply before
    /// an orbit's camera ([`Camera::with_model`], [`Orbit::camera_up`]):
    /// the identity for [`Up::Y`], `(x, y, z) → (x, z, −y)` for [`Up::Z`],
    /// `(x, y, z) → (−y, x, z)` for [`Up::X`] (each a permutation of the
    /// columns with a sign: applying it to a camera rounds nothing).
    /// A rotation about the origin, so a tree-relative camera
    /// ([`crate::render::Frame::relative`]) keeps the model centred.
    pub const fn model(self) -> Mat4 {
        match self {
            Up::Y => Mat4::IDENTITY,
            Up::Z => Mat4([
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
                [0.0, -1.0, 0.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ]),
            Up::X => Mat4([
                [0.0, -1.0, 0.0, 0.0],
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ]),
        }
    }
}

/// Orbit camera parameters (see module docs for the conventions).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// The point looked at (model coordinates).
    pub target: [f32; 3],
    /// Rotation about the world y axis, radians.
    pub yaw: f32,
    /// Elevation above the xz plane, radians (±π/2 looks straight down/up).
    pub pitch: f32,
    /// Distance from the eye to the target (> 0).
    pub distance: f32,
    /// Vertical field of view in radians; `<= 0` means parallel projection.
    pub fov: f32,
    /// Near plane distance for perspective (> 0); also the near clip `w`.
    pub near: f32,
    /// Far plane distance (only shapes ndc.z; nothing is far-clipped).
    pub far: f32,
}

impl Orbit {
    /// A perspective orbit with near/far derived from the distance
    /// (`distance/1000` and `distance·1000`).
    pub fn new(target: [f32; 3], yaw: f32, pitch: f32, distance: f32, fov: f32) -> Orbit {
        Orbit {
            target,
            yaw,
            pitch,
            distance,
            fov,
            near: distance * 1e-3,
            far: distance * 1e3,
        }
    }

    /// An orbit around a bounding sphere of `radius` centred on the origin
    /// (a tree's, in the coordinates of [`crate::render::Frame::relative`])
    /// that frames it: the eye at `yaw`, `pitch`, far enough that the
    /// whole sphere is inside the narrower of the two fields of view of a
    /// viewport of `aspect = width / height`, with a 5 % margin. `fov ≤ 0`
    /// gives a parallel projection of the same framing.
    ///
    /// ```
    /// use fpt_nostd::raster::{Libm, Orbit, Up};
    /// let o = Orbit::framing::<Libm>(10.0, 0.3, 0.4, 1.047, 320.0 / 240.0);
    /// assert!((o.distance - 21.0).abs() < 0.01); // 60° fov: 2.1 radii
    /// let cam = o.camera_up::<Libm>(320.0 / 240.0, Up::Z);
    /// assert!(cam.matrix.is_finite());
    /// ```
    pub fn framing<M: MathFns>(radius: f32, yaw: f32, pitch: f32, fov: f32, aspect: f32) -> Orbit {
        const MARGIN: f32 = 1.05;
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        let parallel = !(fov.is_finite() && fov > 0.0);
        let distance = if parallel {
            // Visible half-height distance / 2, half-width that · aspect.
            2.0 * MARGIN * radius / aspect.min(1.0)
        } else {
            // The narrower half-angle: tan(h) = tan(fov / 2) · min(1, aspect).
            let t = M::tan(0.5 * fov) * aspect.min(1.0);
            let sin = t * M::recip(M::sqrt(1.0 + t * t));
            MARGIN * radius * M::recip(sin)
        };
        Orbit::new([0.0; 3], yaw, pitch, distance, fov)
    }

    /// [`Orbit::camera`] for a model whose up axis is `up`
    /// ([`Up::model`] applied first).
    pub fn camera_up<M: MathFns>(&self, aspect: f32, up: Up) -> Camera {
        self.camera::<M>(aspect).with_model(&up.model())
    }

    /// True when this orbit describes a parallel projection.
    pub fn is_parallel(&self) -> bool {
        !(self.fov.is_finite() && self.fov > 0.0)
    }

    /// Whether no polygon inside the sphere of `radius` around the target
    /// can ever need clipping through this orbit's camera at viewport
    /// aspect `aspect`, from **any** yaw and pitch (they are ignored): the
    /// proof that lets a scene leave the `clipping` effect out
    /// ([`crate::effects`]).
    ///
    /// Perspective: every point of the sphere has eye depth at least
    /// `distance − radius`, which must exceed the near plane, and is seen
    /// within the cone of half-angle `asin(radius / distance)`, so
    /// `|ndc.x|, |ndc.y| ≤ focal · max(1, 1/aspect) · radius / √(distance² −
    /// radius²)`, which must stay inside the guard band
    /// ([`super::clip::GUARD`]). Parallel: `w` is 1, above the near
    /// threshold, and `|ndc| ≤ radius / (distance/2 · min(aspect, 1))`.
    /// A 1 % margin covers the rounding of the `f32` camera.
    pub fn never_clips<M: MathFns>(&self, radius: f32, aspect: f32) -> bool {
        let (r, d) = (radius, self.distance);
        let valid = r.is_finite() && r >= 0.0 && d.is_finite() && d > 0.0;
        if !(valid && aspect.is_finite() && aspect > 0.0) {
            return false;
        }
        let limit = super::clip::GUARD as f32 * 0.99;
        if self.is_parallel() {
            return r <= limit * 0.5 * d * aspect.min(1.0);
        }
        let near_ok = d - r > self.near * 1.01;
        let focal = M::recip(M::tan(0.5 * self.fov));
        let spread = focal * aspect.recip().max(1.0) * r;
        let room = M::sqrt(d * d - r * r);
        near_ok && room.is_finite() && spread <= limit * room
    }

    /// Unit vector from the target toward the eye (a natural "headlight"
    /// direction for [`super::shade::Light`]).
    pub fn eye_direction<M: MathFns>(&self) -> [f32; 3] {
        let (sy, cy) = (M::sin(self.yaw), M::cos(self.yaw));
        let (sp, cp) = (M::sin(self.pitch), M::cos(self.pitch));
        [cp * sy, sp, cp * cy]
    }

    /// The camera (matrix and near clip) for a viewport of aspect ratio
    /// `aspect = width / height`.
    ///
    /// Finite at any finite positive distance (and target within about
    /// 2^100 distances of the origin). Composed in model units, the
    /// projection's `2·far·near` (twice the distance squared) overflows
    /// `f32` beyond a distance of about 1e19, and underflows below 1e-19,
    /// and nothing is drawn. So the orbit is composed in model space
    /// normalised by a power of two `u = 2^e` near the distance (where the
    /// distance is in [1, 2)), then scaled back to model units, and the
    /// whole matrix and `near_w` with it by a power of two `2^c` (a
    /// homogeneous factor moves no projected point) that keeps every entry
    /// near 1: `M = 2^c · M_u · S(2^−e)`. For a distance within `2^±32`
    /// (every ordinary scene) `c` is `e` for a perspective orbit and 0 for
    /// a parallel one, which is the composition in model units bit for bit
    /// (scaling by powers of two commutes with rounding): `w` is the eye
    /// distance (1 for parallel) as the module docs say. Beyond, `c` is
    /// `e / 2` and `w` is the eye distance times `2^(c − e)`.
    pub fn camera<M: MathFns>(&self, aspect: f32) -> Camera {
        let e = exponent(self.distance);
        let (unit, scale) = if (-ORDINARY..=ORDINARY).contains(&e) {
            (1.0, [1.0; 2])
        } else {
            let c = e / 2;
            (pow2(-e), [pow2(c - e), pow2(c)])
        };
        self.compose::<M>(aspect, unit, scale)
    }

    /// The orbit's camera composed in model units times `unit` (a power of
    /// two): target, distance, near and far multiplied by it, so the
    /// matrix takes such coordinates; then its x, y and z columns
    /// multiplied by `scale[0]`, its translation column and `near_w` by
    /// `scale[1]` (powers of two; 1 changes no bit). One call in tail
    /// position keeps a firmware's stack as it was.
    fn compose<M: MathFns>(&self, aspect: f32, unit: f32, scale: [f32; 2]) -> Camera {
        let (sy, cy) = (M::sin(self.yaw), M::cos(self.yaw));
        let (sp, cp) = (M::sin(self.pitch), M::cos(self.pitch));
        // Basis derived from the angles directly rather than by
        // cross-products with "up", so that pitch = ±90° is not degenerate.
        let right = [cy, 0.0, -sy];
        let up = [-sy * sp, cp, -cy * sp];
        let fwd = [-cp * sy, -sp, -cp * cy]; // eye → target
        let distance = self.distance * unit;
        let target = self.target.map(|v| v * unit);
        let eye = [
            target[0] - distance * fwd[0],
            target[1] - distance * fwd[1],
            target[2] - distance * fwd[2],
        ];
        let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        // Rows of the view transform: (axis, -axis·eye).
        let row = |a: [f32; 3]| [a[0], a[1], a[2], -dot(a, eye)];
        let (xr, yr, dr) = (row(right), row(up), row(fwd)); // dr gives depth d
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        let near = self.near * unit;
        // A far plane beyond `f32` (`Orbit::new` at a distance above
        // 3e35): `Orbit::new`'s, a thousand distances, in these units. An
        // infinite one would leave ndc.z constant, and the walk's view
        // takes the sign of a parallel direction from it.
        let far = match self.far * unit {
            f if f.is_finite() => f,
            _ => 1e3 * distance,
        };
        let zscale = |k: f32, r: [f32; 4], c: f32| [k * r[0], k * r[1], k * r[2], k * r[3] + c];
        let mut m = if self.is_parallel() {
            let h = 0.5 * distance;
            let span = far - near;
            // ndc.z = 2(d - near)/(far - near) - 1
            let z = zscale(2.0 / span, dr, -2.0 * near / span - 1.0);
            Mat4([
                zscale(1.0 / (h * aspect), xr, 0.0),
                zscale(1.0 / h, yr, 0.0),
                z,
                [0.0, 0.0, 0.0, 1.0],
            ])
        } else {
            let focal = M::recip(M::tan(0.5 * self.fov));
            let a = (far + near) / (far - near);
            let b = -2.0 * far * near / (far - near);
            Mat4([
                zscale(focal / aspect, xr, 0.0),
                zscale(focal, yr, 0.0),
                zscale(a, dr, b),
                dr,
            ])
        };
        let near_w = if self.is_parallel() { 0.5 } else { near };
        let [sx, st] = scale;
        // In place: a second matrix would cost a firmware's stack peak.
        for row in m.0.iter_mut() {
            row[0] *= sx;
            row[1] *= sx;
            row[2] *= sx;
            row[3] *= st;
        }
        Camera {
            matrix: m,
            near_w: near_w * st,
        }
    }
}

/// Distances within `2^±ORDINARY` are composed in model units as they are
/// ([`Orbit::camera`]): `2·far·near` stays far inside `f32` there.
const ORDINARY: i32 = 32;

/// `floor(log2(x))` for a finite `x > 0`, within ±126 (so that `2^±e` are
/// normal `f32` numbers); 0 otherwise.
fn exponent(x: f32) -> i32 {
    if !(x.is_finite() && x > 0.0) {
        return 0;
    }
    let biased = ((x.to_bits() >> 23) & 0xff) as i32;
    // A subnormal distance: as small as an exponent can say.
    (biased - 127).clamp(-126, 126)
}

/// `2^e` as `f32`, exactly (`e` within ±126).
fn pow2(e: i32) -> f32 {
    f32::from_bits(((e.clamp(-126, 126) + 127) as u32) << 23)
}

/// A camera as the renderer uses it: the full model→clip matrix and the
/// near clip threshold on `w`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Model → clip matrix.
    pub matrix: Mat4,
    /// Clip-space points need `w >= near_w` (> 0) to be kept. Must be
    /// positive: it is what keeps the perspective divide away from zero.
    pub near_w: f32,
}

impl Camera {
    /// A camera from an explicit matrix and near threshold.
    pub fn from_matrix(matrix: Mat4, near_w: f32) -> Camera {
        Camera { matrix, near_w }
    }

    /// A perspective camera at `eye` looking at `target` with `up` toward
    /// the top of the screen ([`Mat4::look_at`]), vertical field of view
    /// `fov` radians, viewport aspect `aspect`, near and far planes
    /// ([`Mat4::perspective`]); the near plane is the near threshold.
    ///
    /// ```
    /// use fpt_nostd::raster::{Camera, Libm};
    /// let cam = Camera::perspective_look_at::<Libm>(
    ///     [3.0, 2.0, 4.0], [0.0; 3], [0.0, 1.0, 0.0], 1.0, 4.0 / 3.0, 0.1, 100.0,
    /// );
    /// let c = cam.matrix.transform_point([0.0; 3]); // the target: centre of the screen
    /// assert!(c[0].abs() < 1e-5 && c[1].abs() < 1e-5 && cam.near_w == 0.1);
    /// ```
    #[allow(clippy::too_many_arguments)]
    pub fn perspective_look_at<M: MathFns>(
        eye: [f32; 3],
        target: [f32; 3],
        up: [f32; 3],
        fov: f32,
        aspect: f32,
        near: f32,
        far: f32,
    ) -> Camera {
        let view = Mat4::look_at::<M>(eye, target, up);
        Camera {
            matrix: Mat4::perspective::<M>(fov, aspect, near, far).mul(&view),
            near_w: near,
        }
    }

    /// This camera with a model transform applied first
    /// (`clip = camera · model · p`).
    pub fn with_model(&self, model: &Mat4) -> Camera {
        Camera {
            matrix: self.matrix.mul(model),
            near_w: self.near_w,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::precision::Libm;
    use super::*;

    fn ndc(m: &Mat4, p: [f32; 3]) -> [f32; 4] {
        let c = m.transform_point(p);
        [c[0] / c[3], c[1] / c[3], c[2] / c[3], c[3]]
    }

    #[test]
    fn orbit_looks_at_target_and_puts_w_at_depth() {
        let o = Orbit::new([1.0, 2.0, 3.0], 0.7, 0.3, 10.0, 1.0);
        let cam = o.camera::<Libm>(1.5);
        let t = ndc(&cam.matrix, o.target);
        assert!(t[0].abs() < 1e-5 && t[1].abs() < 1e-5, "{t:?}");
        assert!((t[3] - 10.0).abs() < 1e-4);
        // A point toward the eye is nearer: smaller w and smaller ndc.z.
        let e = o.eye_direction::<Libm>();
        let p = [1.0 + 4.0 * e[0], 2.0 + 4.0 * e[1], 3.0 + 4.0 * e[2]];
        let q = ndc(&cam.matrix, p);
        assert!((q[3] - 6.0).abs() < 1e-4);
        assert!(q[2] < t[2]);
        assert_eq!(cam.near_w, o.near);
    }

    #[test]
    fn orbit_orientation_y_up_x_right() {
        // yaw 0 pitch 0: eye on +z looking down -z; +x is right, +y is up.
        let o = Orbit::new([0.0; 3], 0.0, 0.0, 5.0, 1.2);
        let m = o.camera::<Libm>(1.0).matrix;
        let r = ndc(&m, [1.0, 0.0, 0.0]);
        let u = ndc(&m, [0.0, 1.0, 0.0]);
        assert!(r[0] > 0.1 && r[1].abs() < 1e-6);
        assert!(u[1] > 0.1 && u[0].abs() < 1e-6);
        // Half the vertical fov maps to the top of the screen.
        let top = [0.0, 5.0 * libm::tanf(0.6), 0.0];
        assert!((ndc(&m, top)[1] - 1.0).abs() < 1e-5);
    }

    #[test]
    fn parallel_orbit_has_unit_w_and_half_distance_extent() {
        let o = Orbit::new([0.0; 3], 1.0, -0.4, 8.0, 0.0);
        assert!(o.is_parallel());
        let cam = o.camera::<Libm>(2.0);
        let e = o.eye_direction::<Libm>();
        for p in [[0.0, 0.0, 0.0], [3.0, -1.0, 2.0], [-e[0] * 50.0, 0.0, 0.0]] {
            assert!((cam.matrix.transform_point(p)[3] - 1.0).abs() < 1e-6);
        }
        // straight up in view space (pitch < 0 so tilt the probe): use the
        // camera's own up vector: yaw=1, pitch=-0.4.
        let (sy, cy) = (libm::sinf(1.0), libm::cosf(1.0));
        let (sp, cp) = (libm::sinf(-0.4), libm::cosf(-0.4));
        let up = [-sy * sp * 4.0, cp * 4.0, -cy * sp * 4.0];
        assert!((ndc(&cam.matrix, up)[1] - 1.0).abs() < 1e-5);
        assert!(cam.near_w > 0.0 && cam.near_w < 1.0);
    }

    #[test]
    fn pitch_straight_down_is_not_degenerate() {
        let o = Orbit::new([0.0; 3], 0.0, core::f32::consts::FRAC_PI_2, 5.0, 1.0);
        let m = o.camera::<Libm>(1.0).matrix;
        assert!(m.is_finite());
        let p = ndc(&m, [1.0, 0.0, 0.0]);
        assert!(p[0] > 0.1 && (p[3] - 5.0).abs() < 1e-4);
    }

    #[test]
    fn look_at_and_perspective_agree_with_the_orbit() {
        let o = Orbit::new([1.0, 2.0, 3.0], 0.7, 0.3, 10.0, 1.0);
        let e = o.eye_direction::<Libm>();
        let eye = [1.0 + 10.0 * e[0], 2.0 + 10.0 * e[1], 3.0 + 10.0 * e[2]];
        let cam = Camera::perspective_look_at::<Libm>(
            eye,
            o.target,
            [0.0, 1.0, 0.0],
            o.fov,
            1.5,
            o.near,
            o.far,
        );
        let orbit = o.camera::<Libm>(1.5);
        for p in [[0.0, 0.0, 0.0], [3.0, -1.0, 2.0], [1.0, 5.0, -4.0]] {
            let (a, b) = (ndc(&cam.matrix, p), ndc(&orbit.matrix, p));
            for k in 0..4 {
                assert!(
                    (a[k] - b[k]).abs() < 1e-3 * (1.0 + b[k].abs()),
                    "{a:?} {b:?}"
                );
            }
        }
        assert_eq!(cam.near_w, orbit.near_w);
    }

    #[test]
    fn framing_keeps_the_sphere_on_screen() {
        for (fov, aspect) in [(1.047, 1.0), (1.047, 0.5), (0.5, 2.0), (0.0, 0.75)] {
            let o = Orbit::framing::<Libm>(3.0, 0.4, 0.2, fov, aspect);
            let m = o.camera::<Libm>(aspect).matrix;
            let e = o.eye_direction::<Libm>();
            // Points of the sphere's silhouette, around the view axis.
            let right = [libm::cosf(0.4), 0.0, -libm::sinf(0.4)];
            let up = [
                e[1] * right[2] - e[2] * right[1],
                e[2] * right[0] - e[0] * right[2],
                e[0] * right[1] - e[1] * right[0],
            ];
            for k in 0..16 {
                let t = k as f32 * core::f32::consts::PI / 8.0;
                let (c, s) = (libm::cosf(t), libm::sinf(t));
                let p = [0, 1, 2].map(|i| 3.0 * (c * right[i] + s * up[i]));
                let q = ndc(&m, p);
                assert!(q[0].abs() < 1.0 && q[1].abs() < 1.0, "{fov} {aspect} {q:?}");
            }
        }
    }

    /// Clip-space points of `probe` scaled by `s`, through the orbit of
    /// `base` with target and distance scaled by `s`: `(ndc.x, ndc.y,
    /// w / near_w)` each, which is what the renderer reads.
    fn seen(base: Orbit, s: f32, aspect: f32) -> [[f32; 3]; 4] {
        let o = Orbit::new(
            base.target.map(|v| v * s),
            base.yaw,
            base.pitch,
            base.distance * s,
            base.fov,
        );
        let cam = o.camera::<Libm>(aspect);
        assert!(cam.matrix.is_finite(), "{s:e}: {cam:?}");
        assert!(cam.near_w.is_finite() && cam.near_w > 0.0, "{s:e}: {cam:?}");
        let probe = [
            [0.0, 0.0, 0.0],
            [1.5, -0.5, 2.0],
            [-2.0, 1.0, 0.25],
            [0.3, 2.5, -1.75],
        ];
        probe.map(|p| {
            let c = cam.matrix.transform_point(p.map(|v| v * s));
            [c[0] / c[3], c[1] / c[3], c[3] / cam.near_w]
        })
    }

    #[test]
    fn orbits_at_power_of_two_scales_see_the_same_picture_bit_for_bit() {
        // Scaling target, distance, near, far and the model by 2^k is
        // exact, and so is the composition in normalised space: the
        // projected points are the unit orbit's bit for bit, at every
        // scale f32 holds (the distance 5·2^k up to 5·2^125 ≈ 2.1e38, down
        // to 5·2^-110 ≈ 3.9e-33, where `Orbit::new`'s near plane, a
        // thousandth of that, is still a normal f32), perspective and
        // parallel.
        for fov in [1.0, 0.0] {
            let base = Orbit::new([1.0, -2.0, 0.5], 0.7, 0.3, 5.0, fov);
            let want = seen(base, 1.0, 1.5);
            for k in (-110..=125).step_by(5) {
                let got = seen(base, pow2(k), 1.5);
                assert_eq!(got, want, "fov {fov} scale 2^{k}");
            }
        }
    }

    #[test]
    fn orbits_at_any_scale_are_finite_and_see_the_unit_picture() {
        for fov in [0.8, 0.0] {
            let base = Orbit::new([0.5, 0.5, 0.5], -1.1, 0.6, 4.0, fov);
            let want = seen(base, 1.0, 0.75);
            for k in -36..=37 {
                let s = libm::powf(10.0, k as f32);
                for (g, w) in seen(base, s, 0.75).iter().zip(&want) {
                    for i in 0..3 {
                        assert!(
                            (g[i] - w[i]).abs() <= 1e-4 * (1.0 + w[i].abs()),
                            "fov {fov} 1e{k}: {g:?} {w:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn ordinary_orbits_keep_w_the_eye_distance() {
        // The documented convention (w = eye distance, near_w = near; 1 for
        // parallel) holds up to the normalised range, 2^±32.
        for d in [3e-9f32, 1.0, 4e9] {
            let o = Orbit::new([0.0; 3], 0.2, 0.1, d, 1.0);
            let cam = o.camera::<Libm>(1.0);
            let w = cam.matrix.transform_point([0.0; 3])[3];
            assert!((w / d - 1.0).abs() < 1e-6, "{d:e}: {w:e}");
            assert_eq!(cam.near_w, o.near);
            let par = Orbit::new([0.0; 3], 0.2, 0.1, d, 0.0).camera::<Libm>(1.0);
            assert_eq!(par.matrix.transform_point([0.0; 3])[3], 1.0);
        }
        // A far plane beyond f32 (distance above 3e35): a thousand
        // distances in normalised units, so that ndc.z still grows with
        // depth (a parallel view's direction is signed by it).
        for fov in [1.0, 0.0] {
            let o = Orbit::new([0.0; 3], 0.2, 0.1, 1e37, fov);
            assert!(o.far.is_infinite());
            let m = o.camera::<Libm>(1.0).matrix;
            assert!(m.is_finite());
            let behind = o.eye_direction::<Libm>().map(|v| -v * 1e36);
            let (centre, back) = (ndc(&m, [0.0; 3]), ndc(&m, behind));
            assert!(centre[2] < back[2], "{fov}: {centre:?} {back:?}");
        }
    }

    #[test]
    fn z_up_stands_a_model_up() {
        let o = Orbit::new([0.0; 3], 0.0, 0.0, 5.0, 1.2);
        let m = o.camera_up::<Libm>(1.0, Up::Z).matrix;
        let top = ndc(&m, [0.0, 0.0, 1.0]);
        assert!(top[1] > 0.1 && top[0].abs() < 1e-6);
        assert_eq!(Up::Y.model(), Mat4::IDENTITY);
        let m = o.camera_up::<Libm>(1.0, Up::X).matrix;
        let top = ndc(&m, [1.0, 0.0, 0.0]);
        assert!(top[1] > 0.1 && top[0].abs() < 1e-6);
        assert_eq!(Up::from(crate::format::UpAxis::X), Up::X);
    }

    #[test]
    fn with_model_applies_model_first() {
        let cam = Camera::from_matrix(Mat4::IDENTITY, 0.1);
        let moved = cam.with_model(&Mat4::translation([1.0, 2.0, 3.0]));
        assert_eq!(moved.matrix.transform_point([0.0; 3]), [1.0, 2.0, 3.0, 1.0]);
    }
}
