//! The opaque draws as the compute raster sees them (triangle_setup.wgsl's `RasterDraw`),
//! and their clusters (bin_triangles.wgsl's `RasterCluster`), which the tile bins cull and
//! list whole or by triangle. Alpha BLEND draws are left out: the transparent pass draws
//! them later.

use wgpu::util::DeviceExt;

use crate::gpu_scene::GpuScene;

/// triangle_setup.wgsl's RasterDraw.
#[repr(C)]
#[derive(Copy, Clone, bytemuck::Pod, bytemuck::Zeroable)]
struct RasterDraw {
    first_triangle: u32,
    triangles: u32,
    start: u32,
    mesh: u32,
    flags: u32,
}

/// bin_triangles.wgsl's RasterCluster: a cluster of a draw's mesh (rgraph_scene::Cluster)
/// with its triangles numbered as the draws number them.
#[repr(C)]
#[derive(Copy, Clone, bytemuck::Pod, bytemuck::Zeroable)]
struct RasterCluster {
    /// The `t` of its first triangle: the draws' triangles before its draw's, plus its
    /// first in the draw.
    first: u32,
    triangles: u32,
    draw: u32,
    _pad: u32,
    min: [f32; 3],
    cone_cutoff: f32,
    max: [f32; 3],
    radius: f32,
    center: [f32; 3],
    _pad1: u32,
    cone_axis: [f32; 3],
    _pad2: u32,
}

/// triangle_setup.wgsl's RasterDraw flags (CULL_BACK, MASKED).
const CULL: u32 = 1;
const MASKED: u32 = 2;

/// The draws' and their clusters' tables on the device, and the triangles and clusters
/// they hold.
pub(crate) struct RasterDraws {
    pub buffer: wgpu::Buffer,
    pub triangles: u32,
    pub clusters: wgpu::Buffer,
    pub cluster_count: u32,
}

impl RasterDraws {
    /// The opaque draws of `scene`, each after the triangles of those before it, and
    /// their clusters in that order. A scene with nothing opaque gets one zeroed entry in
    /// each, which keeps the bind group whole and holds no triangle (the counts say 0).
    pub fn new(device: &wgpu::Device, scene: &GpuScene) -> RasterDraws {
        let mut start = 0;
        let mut clusters = Vec::new();
        let mut draws: Vec<RasterDraw> = scene
            .mesh_draws()
            .filter(|(_, state)| !state.blended)
            .zip(0u32..)
            .map(|((draw, state), index)| {
                let triangles = (draw.indices.end - draw.indices.start) / 3;
                let deformed = scene.deformed_box(draw.instance);
                clusters.extend(scene.clusters(draw.instance as usize).iter().map(|c| {
                    let c = deformed.map_or(*c, |b| deformed_cluster(c, &b));
                    RasterCluster {
                        first: start + c.first_triangle,
                        triangles: c.triangles,
                        draw: index,
                        _pad: 0,
                        min: c.min,
                        cone_cutoff: c.cone_cutoff,
                        max: c.max,
                        radius: c.radius,
                        center: c.center,
                        _pad1: 0,
                        cone_axis: c.cone_axis,
                        _pad2: 0,
                    }
                }));
                let entry = RasterDraw {
                    first_triangle: draw.indices.start / 3,
                    triangles,
                    start,
                    mesh: draw.instance,
                    flags: match state.double_sided {
                        true => 0,
                        false => CULL,
                    } | match state.masked {
                        true => MASKED,
                        false => 0,
                    },
                };
                start += triangles;
                entry
            })
            .collect();
        if draws.is_empty() {
            draws.push(bytemuck::Zeroable::zeroed());
        }
        let cluster_count = clusters.len() as u32;
        if clusters.is_empty() {
            clusters.push(bytemuck::Zeroable::zeroed());
        }
        let table = |label, contents| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        RasterDraws {
            buffer: table("raster draws", bytemuck::cast_slice(&draws)),
            triangles: start,
            clusters: table("raster clusters", bytemuck::cast_slice(&clusters)),
            cluster_count,
        }
    }
}

/// Cluster `c` of a mesh deformed within the object-space box `reach` this frame
/// (`GpuScene::deformed_box`): that box instead of the rest shape's, and no normal cone
/// (a cutoff of 1 culls nothing by facing).
fn deformed_cluster(
    c: &rgraph_scene::Cluster,
    reach: &rgraph_scene::Aabb,
) -> rgraph_scene::Cluster {
    rgraph_scene::Cluster {
        min: reach.min.as_vec3().to_array(),
        max: reach.max.as_vec3().to_array(),
        center: reach.center().as_vec3().to_array(),
        radius: (reach.size().length() * 0.5) as f32,
        cone_cutoff: 1.0,
        ..*c
    }
}
