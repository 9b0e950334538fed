//! The opaque draws as the compute raster sees them (triangle_setup.wgsl's `RasterDraw`),
//! which the tile bins list by triangle. Alpha BLEND draws are left out: the transparent
//! pass draws them later.

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

/// triangle_setup.wgsl's RasterDraw flags (CULL_BACK, MASKED).
const CULL: u32 = 1;
const MASKED: u32 = 2;

/// The draws' table on the device and the triangles it holds.
pub(crate) struct RasterDraws {
    pub buffer: wgpu::Buffer,
    pub triangles: u32,
}

impl RasterDraws {
    /// The opaque draws of `scene`, each after the triangles of those before it. A scene
    /// with nothing opaque gets one zeroed entry, which keeps the bind group whole and
    /// holds no triangle.
    pub fn new(device: &wgpu::Device, scene: &GpuScene) -> RasterDraws {
        let mut start = 0;
        let mut draws: Vec<RasterDraw> = scene
            .mesh_draws()
            .filter(|(_, state)| !state.blended)
            .map(|(draw, state)| {
                let triangles = (draw.indices.end - draw.indices.start) / 3;
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
        RasterDraws {
            buffer: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("raster draws"),
                contents: bytemuck::cast_slice(&draws),
                usage: wgpu::BufferUsages::STORAGE,
            }),
            triangles: start,
        }
    }
}
