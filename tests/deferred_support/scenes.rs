//! Scenes built in code: flat convex polygons and boxes with lit materials, plus the
//! CPU ray cast the tests use to know what each sample sees.
//!
//! Every polygon is its own flat-shaded face (vertex normals = the face normal) with the
//! identity transform, so world positions are exactly the corners given here.

use rgraph_scene::glam::{DMat4, DVec3};
use rgraph_scene::{Aabb, Camera, Light, Material, Mesh, NodeTree, Scene, Vertex};

/// A flat convex polygon as drawn: its world corners, counter-clockwise seen from the
/// side its normal points to (the front).
#[derive(Clone, Debug)]
pub struct Polygon {
    pub corners: Vec<DVec3>,
    pub normal: DVec3,
}

/// A scene under construction.
#[derive(Clone, Default)]
pub struct Parts {
    pub meshes: Vec<Mesh>,
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    pub ambient: [f32; 3],
    pub polygons: Vec<Polygon>,
}

/// Where a ray first meets a front face.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct RayHit {
    /// Index into [`Parts::polygons`].
    pub polygon: usize,
    /// Distance along the (unit) ray.
    pub t: f64,
    pub point: DVec3,
}

impl Parts {
    pub fn new() -> Parts {
        Parts::default()
    }

    /// An opaque, single-sided, dielectric lit material; returns its index.
    pub fn material(&mut self, name: &str, rgb: [f32; 3], roughness: f32) -> usize {
        self.materials.push(Material {
            name: name.to_owned(),
            base_color_factor: [rgb[0], rgb[1], rgb[2], 1.0],
            metallic_factor: 0.0,
            roughness_factor: roughness,
            ..Material::gltf_default()
        });
        self.materials.len() - 1
    }

    /// Adds polygons (each a convex corner list, counter-clockwise seen from its front)
    /// as one mesh; returns the mesh index.
    pub fn mesh(&mut self, name: &str, faces: &[Vec<DVec3>], material: usize) -> usize {
        let mesh = self.meshes.len();
        let (mut vertices, mut indices) = (Vec::new(), Vec::new());
        for corners in faces {
            assert!(corners.len() >= 3, "{name}: a polygon needs 3 corners");
            let normal = (corners[1] - corners[0])
                .cross(corners[2] - corners[0])
                .normalize();
            let first = vertices.len() as u32;
            for c in corners {
                vertices.push(Vertex {
                    position: c.as_vec3().to_array(),
                    normal: normal.as_vec3().to_array(),
                    uv: [0.0, 0.0],
                    color: Vertex::WHITE,
                    tangent: Vertex::NO_TANGENT,
                    uv1: [0.0; 2],
                });
            }
            for i in 1..corners.len() as u32 - 1 {
                indices.extend([first, first + i, first + i + 1]);
            }
            self.polygons.push(Polygon {
                corners: corners.clone(),
                normal,
            });
        }
        self.meshes.push(Mesh {
            name: name.to_owned(),
            vertices: vertices.into(),
            indices: indices.into(),
            material,
            transform: DMat4::IDENTITY,
        });
        mesh
    }

    /// An axis-aligned box from `min` to `max`, faces pointing outwards.
    pub fn cuboid(&mut self, name: &str, min: DVec3, max: DVec3, material: usize) -> usize {
        let c = |x: bool, y: bool, z: bool| {
            DVec3::new(
                if x { max.x } else { min.x },
                if y { max.y } else { min.y },
                if z { max.z } else { min.z },
            )
        };
        let (f, t) = (false, true);
        let faces = [
            // +X, -X, +Y, -Y, +Z, -Z
            vec![c(t, f, t), c(t, f, f), c(t, t, f), c(t, t, t)],
            vec![c(f, f, f), c(f, f, t), c(f, t, t), c(f, t, f)],
            vec![c(f, t, t), c(t, t, t), c(t, t, f), c(f, t, f)],
            vec![c(f, f, f), c(t, f, f), c(t, f, t), c(f, f, t)],
            vec![c(f, f, t), c(t, f, t), c(t, t, t), c(f, t, t)],
            vec![c(t, f, f), c(f, f, f), c(f, t, f), c(t, t, f)],
        ];
        self.mesh(name, &faces, material)
    }

    /// The scene, seen through `camera`.
    pub fn scene(&self, name: &str, camera: Camera) -> Scene {
        let bounds = Aabb::from_points(self.meshes.iter().flat_map(|m| m.world_positions()))
            .expect("a scene built in code has vertices");
        Scene {
            name: name.to_owned(),
            meshes: self.meshes.clone(),
            points_lines: Vec::new(),
            materials: self.materials.clone(),
            textures: Vec::new(),
            lights: self.lights.clone(),
            ambient: self.ambient,
            environment: None,
            emitters: Vec::new(),
            camera,
            bounds,
            nodes: NodeTree::default(),
            skins: Vec::new(),
            deformations: Vec::new(),
            animations: Vec::new(),
            warnings: Vec::new(),
        }
    }

    /// The nearest front face along the ray from `origin` in unit direction `dir` (back
    /// faces are culled, as every material here is single-sided).
    pub fn cast(&self, origin: DVec3, dir: DVec3) -> Option<RayHit> {
        let mut best: Option<RayHit> = None;
        for (i, p) in self.polygons.iter().enumerate() {
            let facing = dir.dot(p.normal);
            if facing >= 0.0 {
                continue;
            }
            let t = (p.corners[0] - origin).dot(p.normal) / facing;
            if t <= 0.0 || best.is_some_and(|b| b.t <= t) {
                continue;
            }
            let point = origin + dir * t;
            let n = p.corners.len();
            let inside = (0..n).all(|k| {
                let (a, b) = (p.corners[k], p.corners[(k + 1) % n]);
                (b - a).cross(point - a).dot(p.normal) >= 0.0
            });
            if inside {
                best = Some(RayHit {
                    polygon: i,
                    t,
                    point,
                });
            }
        }
        best
    }
}
