//! `builtin:unlit`: known geometry and colors for analytic tests of coverage, edges and
//! resolve.
//!
//! Camera: orthographic, `xmag = ymag = 1`, at (0, 0, 10) looking down -Z with +Y up, znear 1,
//! zfar 20. Rendered at a square resolution N x N, world (x, y) maps to NDC (x, y), i.e. pixel
//! column `(x + 1) / 2 * N` and row `(1 - y) / 2 * N` (row 0 at the top); view depth is
//! `10 - z`. No lights, ambient 0: every material is UNLIT and double-sided, so a covered sample
//! shows exactly its base color (pure primaries: identical in linear and sRGB), and an
//! uncovered one the renderer's clear color.
//!
//! Shapes, all in planes facing the camera unless stated:
//! 1. red (1, 0, 0) triangle at z = 0: (-0.8, -0.8), (0, -0.8), (-0.8, 0).
//! 2. green (0, 1, 0) triangle at z = 0.5, in front of the red one and overlapping it:
//!    (-0.6, -0.6), (0.2, -0.6), (-0.6, 0.2). Its hypotenuse crosses the red triangle, so a
//!    green-over-red edge with a depth step lies along x + y = -0.4.
//! 3. blue (0, 0, 1) square at z = 0: x, y in [0.2, 0.8].
//! 4. yellow (1, 1, 0) square x, y in [0.3, 0.7], tilted about the Y axis with
//!    z = 2.5 (x - 0.5): it pierces the blue square along x = 0.5. For y in [0.3, 0.7], yellow is
//!    visible for x in (0.5, 0.7], blue for x in [0.3, 0.5): an intersection edge with no depth
//!    discontinuity and both surfaces covering every sample near it.

use glam::{DMat4, DVec3};

use super::params::Params;
use super::parts::add_shape;
use super::shapes::Shape;
use crate::builder::SceneBuilder;
use crate::{Camera, Material, Projection, SceneError};

/// A flat unlit polygon.
struct Flat {
    name: &'static str,
    color: [f32; 3],
    /// Counter-clockwise seen from the camera.
    corners: &'static [[f32; 3]],
}

const SHAPES: [Flat; 4] = [
    Flat {
        name: "red triangle",
        color: [1.0, 0.0, 0.0],
        corners: &[[-0.8, -0.8, 0.0], [0.0, -0.8, 0.0], [-0.8, 0.0, 0.0]],
    },
    Flat {
        name: "green triangle",
        color: [0.0, 1.0, 0.0],
        corners: &[[-0.6, -0.6, 0.5], [0.2, -0.6, 0.5], [-0.6, 0.2, 0.5]],
    },
    Flat {
        name: "blue square",
        color: [0.0, 0.0, 1.0],
        corners: &[
            [0.2, 0.2, 0.0],
            [0.8, 0.2, 0.0],
            [0.8, 0.8, 0.0],
            [0.2, 0.8, 0.0],
        ],
    },
    Flat {
        name: "yellow tilted square",
        color: [1.0, 1.0, 0.0],
        corners: &[
            [0.3, 0.3, -0.5],
            [0.7, 0.3, 0.5],
            [0.7, 0.7, 0.5],
            [0.3, 0.7, -0.5],
        ],
    },
];

pub(super) fn build(_: &Params, builder: &mut SceneBuilder) -> Result<(), SceneError> {
    for Flat {
        name,
        color: [r, g, b],
        corners,
    } in SHAPES
    {
        let material = builder.add_material(Material {
            name: name.to_owned(),
            base_color_factor: [r, g, b, 1.0],
            metallic_factor: 0.0,
            double_sided: true,
            unlit: true,
            ..Material::gltf_default()
        });
        add_shape(
            builder,
            name,
            Shape::polygon(corners),
            material,
            DMat4::IDENTITY,
        );
    }
    builder.camera = Some(Camera::look_at(
        "unlit orthographic",
        DVec3::new(0.0, 0.0, 10.0),
        DVec3::ZERO,
        DVec3::Y,
        Projection::Orthographic {
            xmag: 1.0,
            ymag: 1.0,
            znear: 1.0,
            zfar: 20.0,
        },
    ));
    Ok(())
}
