//! Cameras: an f64 world pose plus a glTF projection, turned into wgpu-convention matrices.

use glam::{DMat4, DQuat, DVec3, Mat4};

use super::bounds::BoundingSphere;

/// Vertical field of view of the camera made by [`Camera::framing`] (45°).
pub const FRAMING_YFOV: f32 = std::f32::consts::FRAC_PI_4;

/// Direction from the scene center towards the camera made by [`Camera::framing`] (unit
/// length): the glTF front ("the front of an asset faces +Z"), raised 15° towards +Y, as
/// the Khronos glTF sample viewer frames a model from its front and a model viewer looks
/// at it from slightly above: `(0, sin 15°, cos 15°)`.
pub const FRAMING_DIRECTION: DVec3 =
    DVec3::new(0.0, 0.258_819_045_102_520_74, 0.965_925_826_289_068_3);

/// How much of the image's height the outline of the scene's bounding sphere spans in
/// the view of [`Camera::framing`]: most of the frame, with a margin.
pub const FRAMING_FILL: f64 = 0.85;

/// A glTF projection. Angles in radians, distances in world units along the view axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// `zfar: None` is an infinite far plane.
    Perspective {
        /// Vertical field of view, radians, between 0 and π.
        yfov: f32,
        /// Distance to the near plane, world units, positive.
        znear: f32,
        /// Distance to the far plane; `None` for an infinite far plane.
        zfar: Option<f32>,
    },
    /// `xmag`/`ymag` are half the view's width/height in world units.
    Orthographic {
        /// Half the view's width, world units.
        xmag: f32,
        /// Half the view's height, world units.
        ymag: f32,
        /// Distance to the near plane, world units (0 or more).
        znear: f32,
        /// Distance to the far plane, world units, beyond `znear`.
        zfar: f32,
    },
}

/// Where the near and far planes land in wgpu's `[0, 1]` depth range.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthConvention {
    /// Near → 0, far → 1 (depth test `Less`, clear to 1).
    Standard,
    /// Near → 1, far (or infinity) → 0 (depth test `Greater`, clear to 0): float depth then
    /// keeps its precision where perspective squeezes distant geometry.
    ReversedZ,
}

/// A camera. View space is glTF's: right-handed, looking down -Z with +Y up.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// The glTF camera's (or node's) name, for messages; the built-in scenes name theirs.
    pub name: String,
    /// Eye position in world space; f64 so camera-relative rendering of scenes far from the
    /// origin subtracts it exactly.
    pub position: DVec3,
    /// Rotation from view space to world space (unit quaternion).
    pub orientation: DQuat,
    /// Its projection, in glTF's terms.
    pub projection: Projection,
}

impl Projection {
    /// Clip-from-view matrix for a viewport of `aspect = width / height`, in wgpu's conventions
    /// (clip depth in `[0, 1]`).
    ///
    /// Orthographic projections keep `ymag` and use `ymag * aspect` as the half width so pixels
    /// stay square; with `aspect == xmag / ymag` that is exactly glTF's `xmag`.
    pub fn matrix(&self, aspect: f32, depth: DepthConvention) -> Mat4 {
        let reversed = depth == DepthConvention::ReversedZ;
        match *self {
            Projection::Perspective { yfov, znear, zfar } => match (zfar, reversed) {
                (None, false) => Mat4::perspective_infinite_rh(yfov, aspect, znear),
                (None, true) => Mat4::perspective_infinite_reverse_rh(yfov, aspect, znear),
                (Some(zfar), false) => Mat4::perspective_rh(yfov, aspect, znear, zfar),
                // Swapping the planes maps near to 1 and far to 0.
                (Some(zfar), true) => Mat4::perspective_rh(yfov, aspect, zfar, znear),
            },
            Projection::Orthographic {
                ymag, znear, zfar, ..
            } => {
                let xmag = ymag * aspect;
                let (near, far) = if reversed {
                    (zfar, znear)
                } else {
                    (znear, zfar)
                };
                Mat4::orthographic_rh(-xmag, xmag, -ymag, ymag, near, far)
            }
        }
    }
}

impl Camera {
    /// A camera at `eye` looking at `target`, `up` roughly up (must not be parallel to the view
    /// direction, and `eye != target`).
    pub fn look_at(
        name: impl Into<String>,
        eye: DVec3,
        target: DVec3,
        up: DVec3,
        projection: Projection,
    ) -> Camera {
        let world_to_view = DMat4::look_at_rh(eye, target, up);
        Camera {
            name: name.into(),
            position: eye,
            orientation: DQuat::from_mat4(&world_to_view).inverse(),
            projection,
        }
    }

    /// The camera a scene without one gets: perspective with [`FRAMING_YFOV`], looking at the
    /// center `c` of the scene's bounding `sphere` (radius `r`) from direction
    /// [`FRAMING_DIRECTION`], at the distance `d` at which the sphere's outline spans
    /// [`FRAMING_FILL`] of the image height: the outline's radius on the image plane at
    /// focal distance 1 is `tan(asin(r / d)) = r / sqrt(d² - r²)`, which is
    /// `s = FRAMING_FILL * tan(yfov / 2)` at `d = r * sqrt(1 + 1 / s²)`. The height is the
    /// shorter side of landscape and square images; a portrait image (taller than wide)
    /// sees the same view, cut at its sides. Near plane `(d - r) / 2` (half way to the
    /// closest possible geometry), far plane infinite. A sphere of radius 0 is framed as
    /// one of radius 1.
    pub fn framing(sphere: &BoundingSphere) -> Camera {
        let radius = if sphere.radius > 0.0 {
            sphere.radius
        } else {
            1.0
        };
        let s = FRAMING_FILL * (f64::from(FRAMING_YFOV) * 0.5).tan();
        let distance = radius * (1.0 + 1.0 / (s * s)).sqrt();
        let eye = sphere.center + FRAMING_DIRECTION * distance;
        let projection = Projection::Perspective {
            yfov: FRAMING_YFOV,
            znear: (0.5 * (distance - radius)) as f32,
            zfar: None,
        };
        Camera::look_at("default", eye, sphere.center, DVec3::Y, projection)
    }

    /// World-to-view matrix.
    pub fn view_matrix(&self) -> DMat4 {
        DMat4::from_quat(self.orientation.inverse()) * DMat4::from_translation(-self.position)
    }

    /// World-to-view rotation only, for camera-relative rendering: transform
    /// `world_position - self.position` (computed in f64) with it.
    pub fn view_rotation(&self) -> Mat4 {
        DMat4::from_quat(self.orientation.inverse()).as_mat4()
    }

    /// Unit view direction in world space.
    pub fn forward(&self) -> DVec3 {
        self.orientation * DVec3::NEG_Z
    }

    /// This camera turned `angle` radians about the vertical line through `center`
    /// (world +Y, glTF's up; counter-clockwise seen from above): its position circles
    /// `center` and its view turns with it, so what it looked at stays in view.
    pub fn orbited(&self, center: DVec3, angle: f64) -> Camera {
        let turn = DQuat::from_rotation_y(angle);
        Camera {
            position: center + turn * (self.position - center),
            orientation: (turn * self.orientation).normalize(),
            ..self.clone()
        }
    }

    /// Shorthand for `self.projection.matrix(aspect, depth)`.
    pub fn projection_matrix(&self, aspect: f32, depth: DepthConvention) -> Mat4 {
        self.projection.matrix(aspect, depth)
    }
}
