//! The scene's vertices and indices as storage buffers (group 2 of the visibility-buffer
//! passes, geometry.wgsl): the raster pass pulls its vertices through them, so a
//! triangle's ID is its position in the index buffer, and the shading pass rebuilds a
//! triangle's attributes from them. The same buffers the other passes bind as vertex and
//! index buffers; the bind group is made on first use, so scenes drawn only by other
//! pipelines never meet the storage-binding size limit.

use std::sync::OnceLock;

use super::mesh::MeshBuffers;

pub(super) struct Geometry {
    layout: wgpu::BindGroupLayout,
    group: OnceLock<Result<wgpu::BindGroup, String>>,
}

impl Geometry {
    pub fn new(device: &wgpu::Device) -> Geometry {
        // The hardware raster's alpha MASK reads them in its fragment stage.
        let visibility =
            wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT | wgpu::ShaderStages::COMPUTE;
        let storage = wgpu::BufferBindingType::Storage { read_only: true };
        let entry = |binding| crate::kept::buffer_entry(binding, visibility, storage);
        Geometry {
            layout: crate::kept::bind_group_layout(device, "scene geometry", &[entry(0), entry(1)]),
            group: OnceLock::new(),
        }
    }

    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// The bind group, or why the device cannot bind the scene's buffers as storage.
    pub fn group(
        &self,
        device: &wgpu::Device,
        meshes: &MeshBuffers,
    ) -> Result<&wgpu::BindGroup, &str> {
        let group = self.group.get_or_init(|| {
            let limit = device.limits().max_storage_buffer_binding_size;
            for (what, buffer) in [("vertices", &meshes.vertices), ("indices", &meshes.indices)] {
                if buffer.size() > limit {
                    return Err(format!(
                        "the scene's {what} take {} bytes, more than the {limit} bytes this \
                         device binds as one storage buffer (max_storage_buffer_binding_size): \
                         a visibility buffer cannot pull them; use a G-buffer pipeline",
                        buffer.size()
                    ));
                }
            }
            Ok(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("scene geometry"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: meshes.vertices.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: meshes.indices.as_entire_binding(),
                    },
                ],
            }))
        });
        group.as_ref().map_err(String::as_str)
    }
}
