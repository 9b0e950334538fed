//! Bind groups of storage buffers only, bound in order from binding 0 (the compute
//! raster's and the tile bins' group 1), and the scratch buffers they hold.

/// A compute-only layout of storage buffers at bindings 0, 1, ..., each read-only or not.
pub(crate) fn storage_layout(
    device: &wgpu::Device,
    label: &str,
    read_only: &[bool],
) -> wgpu::BindGroupLayout {
    let entries: Vec<_> = read_only
        .iter()
        .zip(0..)
        .map(|(&read_only, binding)| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        })
        .collect();
    crate::kept::bind_group_layout(device, label, &entries)
}

/// `buffers` bound whole at bindings 0, 1, ... of `layout`.
pub(crate) fn storage_group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries: Vec<_> = buffers
        .iter()
        .zip(0..)
        .map(|(buffer, binding)| wgpu::BindGroupEntry {
            binding,
            resource: buffer.as_entire_binding(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// A storage buffer the GPU alone fills and reads, of `size` bytes (4 at least: a
/// binding may not be empty).
pub(crate) fn scratch(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(4),
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    })
}
