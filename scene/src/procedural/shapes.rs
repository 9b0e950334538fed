//! Object-space geometry generators for the built-in scenes.

use std::f32::consts::{PI, TAU};

use glam::{Mat3, Mat4, Vec3};

use crate::Vertex;

/// An indexed triangle list, counter-clockwise front faces, smooth or flat normals as built.
#[derive(Clone, Default)]
pub(super) struct Shape {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
}

impl Shape {
    /// Unit sphere at the origin: `segments` around Y, `rings` from pole to pole, smooth
    /// normals, uv = (longitude, latitude) in [0, 1]. Poles are shared vertices, so the
    /// triangle count is `2 * segments * (rings - 1)`.
    pub fn uv_sphere(segments: u32, rings: u32) -> Shape {
        let mut vertices = Vec::new();
        for ring in 0..=rings {
            let v = ring as f32 / rings as f32;
            let (sin_lat, cos_lat) = (v * PI).sin_cos();
            for segment in 0..=segments {
                let u = segment as f32 / segments as f32;
                let (sin_lon, cos_lon) = (u * TAU).sin_cos();
                let p = [sin_lat * cos_lon, cos_lat, -sin_lat * sin_lon];
                vertices.push(Vertex {
                    position: p,
                    normal: p,
                    uv: [u, v],
                    color: Vertex::WHITE,
                    tangent: Vertex::NO_TANGENT,
                    uv1: [0.0; 2],
                });
            }
        }
        let row = segments + 1;
        let mut indices = Vec::new();
        for ring in 0..rings {
            for segment in 0..segments {
                let a = ring * row + segment;
                let (b, c, d) = (a + row, a + row + 1, a + 1);
                // The quads touching a pole degenerate into one triangle each.
                if ring != 0 {
                    indices.extend([a, b, d]);
                }
                if ring != rings - 1 {
                    indices.extend([d, b, c]);
                }
            }
        }
        Shape { vertices, indices }
    }

    /// Unit cube `[-0.5, 0.5]³`, 4 vertices per face so normals are flat: 12 triangles.
    pub fn cuboid() -> Shape {
        let mut shape = Shape::default();
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            for normal in [axis, -axis] {
                // Two edges spanning the face, ordered so u x v = normal (counter-clockwise).
                let u = normal.any_orthonormal_vector();
                let v = normal.cross(u);
                let corners = [-u - v, u - v, u + v, -u + v].map(|c| (normal + c) * 0.5);
                shape.append(&Shape::polygon(&corners.map(|c| c.to_array())));
            }
        }
        shape
    }

    /// Unit square `[-0.5, 0.5]²` in the XZ plane facing +Y: 2 triangles.
    pub fn plane() -> Shape {
        Shape::polygon(&[
            [-0.5, 0.0, 0.5],
            [0.5, 0.0, 0.5],
            [0.5, 0.0, -0.5],
            [-0.5, 0.0, -0.5],
        ])
    }

    /// Open cylinder (no caps: the built-in scenes only make thin ones, whose caps cover no
    /// pixels) of radius 1 around Y from y = 0 to 1, smooth normals: `2 * segments` triangles.
    pub fn cylinder(segments: u32) -> Shape {
        let vertices = (0..=segments)
            .flat_map(|s| {
                let u = s as f32 / segments as f32;
                let (sin, cos) = (u * TAU).sin_cos();
                let normal = [cos, 0.0, -sin];
                [0.0, 1.0].map(|y| Vertex {
                    position: [cos, y, -sin],
                    normal,
                    uv: [u, y],
                    color: Vertex::WHITE,
                    tangent: Vertex::NO_TANGENT,
                    uv1: [0.0; 2],
                })
            })
            .collect();
        let indices = (0..segments)
            .flat_map(|s| {
                let (bottom, top, next_bottom, next_top) = (2 * s, 2 * s + 1, 2 * s + 2, 2 * s + 3);
                [bottom, next_bottom, next_top, bottom, next_top, top]
            })
            .collect();
        Shape { vertices, indices }
    }

    /// A grass blade in the XY plane facing +Z: 1 wide at y = 0, tapering to a tip at y = 1;
    /// 3 triangles. Meant for double-sided materials.
    pub fn blade() -> Shape {
        let mut shape = Shape::polygon(&[
            [-0.5, 0.0, 0.0],
            [0.5, 0.0, 0.0],
            [0.3, 0.55, 0.0],
            [-0.3, 0.55, 0.0],
        ]);
        shape.append(&Shape::polygon(&[
            [-0.3, 0.55, 0.0],
            [0.3, 0.55, 0.0],
            [0.0, 1.0, 0.0],
        ]));
        shape
    }

    /// A flat convex polygon from counter-clockwise corners, fan-triangulated, normal from the
    /// first three corners, uv = the corner's (x, y) (built-in scenes are untextured).
    pub fn polygon(corners: &[[f32; 3]]) -> Shape {
        let [a, b, c] = [0, 1, 2].map(|i| Vec3::from_array(corners[i]));
        let normal = (b - a).cross(c - a).normalize().to_array();
        Shape {
            vertices: corners
                .iter()
                .map(|&p| Vertex {
                    position: p,
                    normal,
                    uv: [p[0], p[1]],
                    color: Vertex::WHITE,
                    tangent: Vertex::NO_TANGENT,
                    uv1: [0.0; 2],
                })
                .collect(),
            indices: (1..corners.len() as u32 - 1)
                .flat_map(|i| [0, i, i + 1])
                .collect(),
        }
    }

    /// This shape with `transform` baked into positions and normals, for merging many small
    /// pieces into one mesh (one draw instead of thousands).
    pub fn transformed(&self, transform: Mat4) -> Shape {
        let normal_matrix = Mat3::from_mat4(transform).inverse().transpose();
        let vertices = self
            .vertices
            .iter()
            .map(|v| Vertex {
                position: transform
                    .transform_point3(Vec3::from_array(v.position))
                    .to_array(),
                normal: (normal_matrix * Vec3::from_array(v.normal))
                    .normalize()
                    .to_array(),
                uv: v.uv,
                color: v.color,
                // Built-in shapes have no tangents: no built-in material has a normal map.
                tangent: v.tangent,
                uv1: v.uv1,
            })
            .collect();
        Shape {
            vertices,
            indices: self.indices.clone(),
        }
    }

    /// Adds `other`'s triangles to this shape.
    pub fn append(&mut self, other: &Shape) {
        let base = self.vertices.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        self.indices.extend(other.indices.iter().map(|i| base + i));
    }
}
