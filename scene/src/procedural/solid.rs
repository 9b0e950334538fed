//! Boxes and spheres with their own material, as the built-in scenes place them.

use glam::{DMat4, DQuat, DVec3};

use super::parts::{add_shape, lit};
use super::shapes::Shape;
use crate::builder::SceneBuilder;

/// A box or sphere with its own opaque material, placed in a built-in scene.
pub(super) struct Solid {
    name: &'static str,
    kind: SolidKind,
    center: [f64; 3],
    /// Box edge lengths or sphere radii, per axis.
    size: [f64; 3],
    yaw_degrees: f64,
    color: [f32; 3],
    metallic: f32,
    roughness: f32,
}

enum SolidKind {
    Box,
    Sphere,
}

impl Solid {
    /// A sphere of `radius` at `center`.
    pub const fn sphere(
        name: &'static str,
        center: [f64; 3],
        radius: f64,
        color: [f32; 3],
        metallic: f32,
        roughness: f32,
    ) -> Solid {
        Solid {
            name,
            kind: SolidKind::Sphere,
            center,
            size: [radius; 3],
            yaw_degrees: 0.0,
            color,
            metallic,
            roughness,
        }
    }

    /// A box with edge lengths `size`, turned `yaw_degrees` about +Y.
    pub const fn cuboid(
        name: &'static str,
        center: [f64; 3],
        size: [f64; 3],
        yaw_degrees: f64,
        color: [f32; 3],
        metallic: f32,
        roughness: f32,
    ) -> Solid {
        Solid {
            name,
            kind: SolidKind::Box,
            center,
            size,
            yaw_degrees,
            color,
            metallic,
            roughness,
        }
    }

    /// Adds the solid and its material, returning the material's index; `sphere` is the
    /// unit sphere tessellation to use.
    pub fn add_to(&self, builder: &mut SceneBuilder, sphere: &Shape) -> usize {
        let material =
            builder.add_material(lit(self.name, self.color, self.metallic, self.roughness));
        let shape = match self.kind {
            SolidKind::Box => Shape::cuboid(),
            SolidKind::Sphere => sphere.clone(),
        };
        let transform = DMat4::from_scale_rotation_translation(
            DVec3::from_array(self.size),
            DQuat::from_rotation_y(self.yaw_degrees.to_radians()),
            DVec3::from_array(self.center),
        );
        add_shape(builder, self.name, shape, material, transform);
        material
    }
}
