//! Where the deformation had the scene's vertices in the last pose, as a pass drawing
//! the meshes reads it in its vertex stage (group 3 of gbuffer.wgsl where the G-buffer
//! writes a pose offset, gbuffer_last_pose.wgsl): the positions the deformation's last
//! dispatch replaced ([`PreviousPositions`], read-only storage) and the range of the
//! scene's vertices they hold (a uniform, `vec4<u32>`: first, end). Made on first use, so
//! that only a plan keeping a pose offset makes it; for a scene without deformations the
//! range is empty (every vertex stood where it stands).

use std::sync::OnceLock;

use wgpu::util::DeviceExt;

use super::deform::PreviousPositions;

/// The layout of group 3 (the same object on a device for every caller: crate::kept).
pub fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let entry = |binding, ty| crate::kept::buffer_entry(binding, wgpu::ShaderStages::VERTEX, ty);
    let storage = wgpu::BufferBindingType::Storage { read_only: true };
    let entries = [
        entry(0, storage),
        entry(1, wgpu::BufferBindingType::Uniform),
    ];
    crate::kept::bind_group_layout(device, "last pose", &entries)
}

/// The bind group, made the first time a pass asks.
#[derive(Default)]
pub(super) struct LastPose {
    group: OnceLock<wgpu::BindGroup>,
}

impl LastPose {
    /// Group 3 over `previous` (none for a scene without deformations).
    pub fn group(
        &self,
        device: &wgpu::Device,
        previous: Option<&PreviousPositions>,
    ) -> &wgpu::BindGroup {
        self.group.get_or_init(|| {
            let range = previous.map_or([0u32; 4], |p| [p.first, p.end, 0, 0]);
            let range = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("last pose's range"),
                contents: bytemuck::cast_slice(&range),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            // wgpu refuses storage bindings smaller than one element.
            let none;
            let positions = match previous {
                Some(previous) => &previous.buffer,
                None => {
                    none = device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("no last pose"),
                        size: 16,
                        usage: wgpu::BufferUsages::STORAGE,
                        mapped_at_creation: false,
                    });
                    &none
                }
            };
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("last pose"),
                layout: &layout(device),
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: positions.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: range.as_entire_binding(),
                    },
                ],
            })
        })
    }
}
