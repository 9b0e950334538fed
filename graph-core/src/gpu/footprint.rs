//! What a frame loop leaves behind: the device objects alive and the memory they hold,
//! as wgpu counts them, and the process's resident memory. After the first frame of a
//! loop both stay flat; anything that grows frame after frame is a leak, ours or a
//! driver's that our usage triggers (a driver's shows in resident memory only).

use std::fmt;

/// Device objects alive, by kind, and the device memory they hold, as wgpu counts them
/// (its `counters` feature: without it every count reads 0). They count objects alive,
/// not creations: an object a frame creates and drops before the count does not show,
/// but every object the graph or the plugins keep (pooled textures, cached pipelines)
/// does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DeviceObjects {
    /// Bytes of texture memory: wgpu-hal 30's Vulkan backend counts what textures
    /// allocate but not the textures (its `create_texture` leaves that count alone).
    pub texture_bytes: isize,
    /// Bytes of buffer memory.
    pub buffer_bytes: isize,
    /// Device memory blocks the allocator holds.
    pub memory_allocations: isize,
    /// Buffers alive.
    pub buffers: isize,
    /// Texture views alive (the executor's are cached with their textures).
    pub texture_views: isize,
    /// Samplers alive.
    pub samplers: isize,
    /// Bind groups alive (passes make theirs per frame and drop them).
    pub bind_groups: isize,
    /// Bind group layouts alive.
    pub bind_group_layouts: isize,
    /// Pipeline layouts alive.
    pub pipeline_layouts: isize,
    /// Render pipelines alive.
    pub render_pipelines: isize,
    /// Compute pipelines alive.
    pub compute_pipelines: isize,
    /// Shader modules alive.
    pub shader_modules: isize,
    /// Query sets alive (the executor's timestamp queries).
    pub query_sets: isize,
}

impl DeviceObjects {
    /// What `device` holds alive now.
    pub fn alive(device: &wgpu::Device) -> DeviceObjects {
        let hal = device.get_internal_counters().hal;
        DeviceObjects {
            texture_bytes: hal.texture_memory.read(),
            buffer_bytes: hal.buffer_memory.read(),
            memory_allocations: hal.memory_allocations.read(),
            buffers: hal.buffers.read(),
            texture_views: hal.texture_views.read(),
            samplers: hal.samplers.read(),
            bind_groups: hal.bind_groups.read(),
            bind_group_layouts: hal.bind_group_layouts.read(),
            pipeline_layouts: hal.pipeline_layouts.read(),
            render_pipelines: hal.render_pipelines.read(),
            compute_pipelines: hal.compute_pipelines.read(),
            shader_modules: hal.shader_modules.read(),
            query_sets: hal.query_sets.read(),
        }
    }

    /// What `self` holds more than `before` (negative: fewer).
    pub fn minus(&self, before: &DeviceObjects) -> DeviceObjects {
        DeviceObjects {
            texture_bytes: self.texture_bytes - before.texture_bytes,
            buffer_bytes: self.buffer_bytes - before.buffer_bytes,
            memory_allocations: self.memory_allocations - before.memory_allocations,
            buffers: self.buffers - before.buffers,
            texture_views: self.texture_views - before.texture_views,
            samplers: self.samplers - before.samplers,
            bind_groups: self.bind_groups - before.bind_groups,
            bind_group_layouts: self.bind_group_layouts - before.bind_group_layouts,
            pipeline_layouts: self.pipeline_layouts - before.pipeline_layouts,
            render_pipelines: self.render_pipelines - before.render_pipelines,
            compute_pipelines: self.compute_pipelines - before.compute_pipelines,
            shader_modules: self.shader_modules - before.shader_modules,
            query_sets: self.query_sets - before.query_sets,
        }
    }

    /// Objects of every kind together (memory not included).
    pub fn objects(&self) -> isize {
        self.buffers
            + self.texture_views
            + self.samplers
            + self.bind_groups
            + self.bind_group_layouts
            + self.pipeline_layouts
            + self.render_pipelines
            + self.compute_pipelines
            + self.shader_modules
            + self.query_sets
    }

    /// Bytes of buffer and texture memory together.
    pub fn bytes(&self) -> isize {
        self.texture_bytes + self.buffer_bytes
    }
}

/// Each kind's count, or "nothing" when every count is 0 (a frame that created nothing).
impl fmt::Display for DeviceObjects {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if *self == DeviceObjects::default() {
            return f.write_str("nothing");
        }
        write!(
            f,
            "{} KiB of textures and {} KiB of buffers in {} memory blocks, {} buffers, {} \
             texture views, {} samplers, {} bind groups, {} bind group layouts, {} pipeline \
             layouts, {} render and {} compute pipelines, {} shader modules, {} query sets",
            self.texture_bytes / 1024,
            self.buffer_bytes / 1024,
            self.memory_allocations,
            self.buffers,
            self.texture_views,
            self.samplers,
            self.bind_groups,
            self.bind_group_layouts,
            self.pipeline_layouts,
            self.render_pipelines,
            self.compute_pipelines,
            self.shader_modules,
            self.query_sets
        )
    }
}

/// The process's resident memory in bytes (`VmRSS` of `/proc/self/status`); `None` where
/// the platform has no such file.
pub fn resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find_map(|l| l.strip_prefix("VmRSS:"))?;
    let kib: u64 = line.trim().strip_suffix("kB")?.trim().parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::resident_bytes;

    #[test]
    fn resident_memory_grows_with_touched_pages() {
        let Some(before) = resident_bytes() else {
            panic!("/proc/self/status has no VmRSS line on this platform");
        };
        // 64 MiB written: resident, whatever else the test threads do meanwhile.
        let block = vec![1u8; 64 << 20];
        let after = resident_bytes().expect("VmRSS read once already");
        assert!(
            after >= before + (48 << 20),
            "resident memory {before} -> {after} bytes after touching 64 MiB"
        );
        drop(block);
    }
}
