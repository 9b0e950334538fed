//! What the scale scenes (`terrain`, `city`) share, so that every size of either is seen in
//! one view under one light and their costs compare: the ground they cover, the camera
//! and the lights.
//!
//! - Ground: x, z in [-[`EXTENT`], [`EXTENT`]] (100 x 100) at every size, with geometry up
//!   to 30 high.
//! - Lights: a directional "sun" (2.5 lux, from the front left, 38° above the horizon) and
//!   four point lights (500 cd, range 60) at (±25, 35, ±25), warm, blue, pink and green.
//!   Ambient 0.04.
//! - Camera: perspective, 45° vertical FOV, eye (0, 70, 100) looking at (0, 0, 5): the
//!   whole ground in a 16:9 frame.

use glam::{DVec3, Vec3};

use super::parts::{corner_lights, directional, perspective_camera};
use crate::builder::SceneBuilder;

/// Half the side of the ground a scale scene covers.
pub(super) const EXTENT: f64 = 50.0;

/// Adds the lights, the ambient term and the camera (named `name`).
pub(super) fn light_and_frame(builder: &mut SceneBuilder, name: &str) {
    builder.lights.push(directional(
        "sun",
        Vec3::new(0.6, -0.6, -0.5),
        [1.0, 0.95, 0.88],
        2.5,
    ));
    let colors = [
        [1.0, 0.8, 0.55],
        [0.6, 0.75, 1.0],
        [1.0, 0.65, 0.8],
        [0.75, 1.0, 0.75],
    ];
    builder
        .lights
        .extend(corner_lights(25.0, 35.0, colors, 500.0, 60.0));
    builder.ambient = [0.04; 3];
    builder.camera = Some(perspective_camera(
        name,
        DVec3::new(0.0, 70.0, 100.0),
        DVec3::new(0.0, 0.0, 5.0),
        45.0,
    ));
}
