//! Small constructors shared by the built-in scenes.

use glam::{DMat4, DQuat, DVec3, Vec3};

use super::shapes::Shape;
use crate::scene::builder::SceneBuilder;
use crate::scene::{Camera, Light, LightKind, Material, Mesh, Projection};

/// An opaque, single-sided, lit material.
pub(super) fn lit(name: &str, rgb: [f32; 3], metallic: f32, roughness: f32) -> Material {
    Material {
        name: name.to_owned(),
        base_color_factor: [rgb[0], rgb[1], rgb[2], 1.0],
        metallic_factor: metallic,
        roughness_factor: roughness,
        ..Material::gltf_default()
    }
}

/// Adds `shape` as a mesh placed by `transform`.
pub(super) fn add_shape(
    builder: &mut SceneBuilder,
    name: &str,
    shape: Shape,
    material: usize,
    transform: DMat4,
) {
    builder.meshes.push(Mesh {
        name: name.to_owned(),
        vertices: shape.vertices,
        indices: shape.indices,
        material,
        transform,
    });
}

/// A point light with a glTF range.
pub(super) fn point(
    name: String,
    position: DVec3,
    color: [f32; 3],
    intensity: f32,
    range: f32,
) -> Light {
    Light {
        name,
        kind: LightKind::Point,
        color,
        intensity,
        position,
        direction: Vec3::NEG_Z,
        range: Some(range),
    }
}

/// A spot light with a glTF range; `direction` need not be normalized.
pub(super) fn spot(
    name: String,
    position: DVec3,
    direction: Vec3,
    cones: (f32, f32),
    color: [f32; 3],
    intensity: f32,
    range: f32,
) -> Light {
    Light {
        kind: LightKind::Spot {
            inner_cone: cones.0,
            outer_cone: cones.1,
        },
        direction: direction.normalize(),
        ..point(name, position, color, intensity, range)
    }
}

/// A directional light; `direction` (where the light travels) need not be normalized.
pub(super) fn directional(name: &str, direction: Vec3, color: [f32; 3], intensity: f32) -> Light {
    Light {
        name: name.to_owned(),
        kind: LightKind::Directional,
        color,
        intensity,
        position: DVec3::ZERO,
        direction: direction.normalize(),
        range: None,
    }
}

/// A perspective camera at `eye` looking at `target` with +Y up, near plane 0.1 and an
/// infinite far plane.
pub(super) fn perspective_camera(
    name: &str,
    eye: DVec3,
    target: DVec3,
    yfov_degrees: f32,
) -> Camera {
    let projection = Projection::Perspective {
        yfov: yfov_degrees.to_radians(),
        znear: 0.1,
        zfar: None,
    };
    Camera::look_at(name, eye, target, DVec3::Y, projection)
}

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

    /// Adds the solid and its material; `sphere` is the unit sphere tessellation to use.
    pub fn add_to(&self, builder: &mut SceneBuilder, sphere: &Shape) {
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
    }
}
