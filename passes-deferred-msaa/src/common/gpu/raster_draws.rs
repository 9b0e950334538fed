//! The opaque draws as the compute rasterisers see them (triangle_setup.wgsl's
//! `RasterDraw`): visibility_compute covers their triangles into a buffer, tile_bins bins
//! them for the tiled pass to cover. Alpha BLEND draws are left out: the transparent pass
//! draws them later.

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

/// Workgroups of `group` invocations for `invocations`, as x by y within the 65,535 a
/// dimension allows (the shaders flatten them back).
pub(crate) fn grid(invocations: u64, group: u32) -> (u32, u32) {
    let groups = invocations.div_ceil(u64::from(group)).max(1);
    let x = groups.min(65_535);
    (x as u32, groups.div_ceil(x) as u32)
}
