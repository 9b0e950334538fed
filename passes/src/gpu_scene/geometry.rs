//! The scene's vertices and indices as storage buffers (group 2 of the visibility-buffer
//! passes, geometry.wgsl): the raster pass pulls its vertices through them, so a
//! triangle's ID is its position in the index buffer, and the shading pass rebuilds a
//! triangle's attributes from them. The same buffers the other passes bind as vertex and
//! index buffers; the bind group is made on first use, so scenes drawn only by other
//! pipelines never meet the storage-binding size limit. The vertices are bound in ranges
//! (vertex_ranges.rs), the indices whole.

use std::sync::OnceLock;

use super::mesh::MeshBuffers;
use super::vertex_ranges::{vertex_ranges, VERTEX_RANGES};

/// geometry.wgsl's bindings: `vertex_range_0`, `index_words`, then the other ranges.
const INDEX_BINDING: u32 = 1;
const RANGE_BINDINGS: [u32; VERTEX_RANGES] = [0, 2, 3, 4];

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
        let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..=VERTEX_RANGES as u32)
            .map(|binding| crate::kept::buffer_entry(binding, visibility, storage))
            .collect();
        Geometry {
            layout: crate::kept::bind_group_layout(device, "scene geometry", &entries),
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
            let limits = device.limits();
            let indices = meshes.indices.size();
            let limit = limits.max_storage_buffer_binding_size;
            if indices > limit {
                return Err(format!(
                    "the scene's indices take {indices} bytes (12 a triangle), more than the \
                     {limit} bytes this device binds as one storage buffer \
                     (max_storage_buffer_binding_size; the indices are bound whole, the \
                     vertices in ranges): a visibility buffer cannot pull them; use a \
                     G-buffer pipeline"
                ));
            }
            let ranges = vertex_ranges(meshes.vertices.size(), &limits)?;
            // Bindings past the scene's last range bind it again: the shader never
            // reads them (geometry.wgsl), but the layout has them.
            let last = ranges.len() - 1;
            let range_entries = RANGE_BINDINGS.iter().enumerate().map(|(k, &binding)| {
                let range = &ranges[k.min(last)];
                wgpu::BindGroupEntry {
                    binding,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &meshes.vertices,
                        offset: range.start,
                        size: wgpu::BufferSize::new(range.end - range.start),
                    }),
                }
            });
            let entries: Vec<wgpu::BindGroupEntry> = range_entries
                .chain([wgpu::BindGroupEntry {
                    binding: INDEX_BINDING,
                    resource: meshes.indices.as_entire_binding(),
                }])
                .collect();
            Ok(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("scene geometry"),
                layout: &self.layout,
                entries: &entries,
            }))
        });
        group.as_ref().map_err(String::as_str)
    }
}
