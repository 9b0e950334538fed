//! Unit light-volume meshes that circumscribe the shapes they stand for, so a tessellated
//! sphere or cone never misses a pixel the exact volume covers.

use glam::Vec3;
use wgpu::util::DeviceExt;

/// Which unit mesh a light is drawn with.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum VolumeShape {
    /// Contains the unit sphere.
    Sphere,
    /// Apex at the origin, axis +Z, height 1; contains the cone of base radius 1.
    Cone,
}

/// A position-only indexed mesh on the device.
pub struct VolumeMesh {
    /// Positions (`vec3<f32>`, object space of the unit volume), for `VERTEX_LAYOUT`.
    pub vertices: wgpu::Buffer,
    /// `u32` triangle list.
    pub indices: wgpu::Buffer,
    /// Indices to draw.
    pub index_count: u32,
    /// Vertex positions, for the CPU-side bounds of a placed volume.
    pub positions: Vec<Vec3>,
}

/// Segments around a sphere's axis and around a cone's axis.
const SEGMENTS: u32 = 16;
/// Rings from pole to pole of the sphere.
const RINGS: u32 = 8;

pub(super) fn sphere(device: &wgpu::Device) -> VolumeMesh {
    let mut positions = Vec::new();
    for ring in 0..=RINGS {
        let (sin_lat, cos_lat) = (ring as f32 / RINGS as f32 * std::f32::consts::PI).sin_cos();
        for segment in 0..SEGMENTS {
            let (sin_lon, cos_lon) =
                (segment as f32 / SEGMENTS as f32 * std::f32::consts::TAU).sin_cos();
            positions.push(Vec3::new(sin_lat * cos_lon, cos_lat, -sin_lat * sin_lon));
        }
    }
    let mut indices = Vec::new();
    for ring in 0..RINGS {
        for segment in 0..SEGMENTS {
            let next = (segment + 1) % SEGMENTS;
            let (a, b) = (ring * SEGMENTS + segment, (ring + 1) * SEGMENTS + segment);
            let (c, d) = ((ring + 1) * SEGMENTS + next, ring * SEGMENTS + next);
            indices.extend([a, b, d, d, b, c]);
        }
    }
    circumscribe(&mut positions, &indices);
    upload(device, "light volume: sphere", positions, indices)
}

pub(super) fn cone(device: &wgpu::Device) -> VolumeMesh {
    // Apex, base center, then the base ring.
    let mut positions = vec![Vec3::ZERO, Vec3::Z];
    let ring_radius = 1.0 / (std::f32::consts::PI / SEGMENTS as f32).cos();
    for segment in 0..SEGMENTS {
        let (sin, cos) = (segment as f32 / SEGMENTS as f32 * std::f32::consts::TAU).sin_cos();
        positions.push(Vec3::new(cos * ring_radius, sin * ring_radius, 1.0));
    }
    let mut indices = Vec::new();
    for segment in 0..SEGMENTS {
        let (a, b) = (2 + segment, 2 + (segment + 1) % SEGMENTS);
        // Counter-clockwise seen from outside: the side, then the base cap.
        indices.extend([0, b, a, 1, a, b]);
    }
    upload(device, "light volume: cone", positions, indices)
}

/// Scales a mesh whose vertices lie on the unit sphere until every face plane is at least
/// at distance 1 from the origin: the mesh then contains the unit sphere.
fn circumscribe(positions: &mut [Vec3], indices: &[u32]) {
    let inradius = indices
        .chunks_exact(3)
        .map(|t| [0, 1, 2].map(|i| positions[t[i] as usize]))
        .filter_map(|[a, b, c]| {
            let normal = (b - a).cross(c - a);
            (normal.length_squared() > 0.0).then(|| normal.normalize().dot(a).abs())
        })
        .fold(1.0f32, f32::min);
    for p in positions {
        *p /= inradius;
    }
}

fn upload(
    device: &wgpu::Device,
    label: &str,
    positions: Vec<Vec3>,
    indices: Vec<u32>,
) -> VolumeMesh {
    let flat: Vec<[f32; 3]> = positions.iter().map(|p| p.to_array()).collect();
    VolumeMesh {
        vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(&flat),
            usage: wgpu::BufferUsages::VERTEX,
        }),
        indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(&indices),
            usage: wgpu::BufferUsages::INDEX,
        }),
        index_count: indices.len() as u32,
        positions,
    }
}

/// The vertex layout of volume meshes: one `vec3<f32>` position at location 0.
pub const VERTEX_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
};
