//! Small constructors shared by the built-in scenes.

use glam::{DMat4, DVec3, Vec3};

use super::shapes::Shape;
use crate::builder::SceneBuilder;
use crate::{Camera, Light, LightKind, Material, Mesh, Projection};

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
        vertices: shape.vertices.into(),
        indices: shape.indices.into(),
        material,
        transform,
    });
}

/// A `size` x `size` ground plane at y = 0 facing up, with a material of `rgb` and `roughness`.
pub(super) fn add_ground(
    builder: &mut SceneBuilder,
    name: &str,
    size: f64,
    rgb: [f32; 3],
    roughness: f32,
) {
    let material = builder.add_material(lit(name, rgb, 0.0, roughness));
    let transform = DMat4::from_scale(DVec3::new(size, 1.0, size));
    add_shape(builder, name, Shape::plane(), material, transform);
}

/// Four point lights at (±offset, height, ±offset), one per color, named `point 0..3`.
pub(super) fn corner_lights(
    offset: f64,
    height: f64,
    colors: [[f32; 3]; 4],
    intensity: f32,
    range: f32,
) -> impl Iterator<Item = Light> {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)];
    corners
        .into_iter()
        .zip(colors)
        .enumerate()
        .map(move |(i, ((x, z), color))| {
            let position = DVec3::new(x * offset, height, z * offset);
            Light::point(
                format!("point {i}"),
                position,
                color,
                intensity,
                Some(range),
            )
        })
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
        ..Light::point(name, position, color, intensity, Some(range))
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
