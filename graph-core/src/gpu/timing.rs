//! GPU timestamps around each pass, when the device has `TIMESTAMP_QUERY`.
//!
//! Only passes that can be timed get query slots, numbered densely: resolving a query that
//! was never written is undefined on Vulkan (the copy may wait for it forever), so the
//! resolved range must hold written queries only.

use wgpu::Features;

use super::readback::{map_read, ReadbackError};

/// The query set and buffers, grown to the largest frame seen and kept across frames.
pub(crate) struct Timestamps {
    query_set: wgpu::QuerySet,
    /// Resolve target (`QUERY_RESOLVE`), copied to `readback`, which is mappable.
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    capacity: u32,
    /// Transfer passes are timed with encoder-level writes, which need their own feature.
    pub inside_encoders: bool,
    /// Nanoseconds per tick.
    period: f64,
}

impl Timestamps {
    /// `None` when the device cannot write timestamps at all.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<Self> {
        let features = device.features();
        features.contains(Features::TIMESTAMP_QUERY).then(|| {
            Self::allocate(
                device,
                2,
                features.contains(Features::TIMESTAMP_QUERY_INSIDE_ENCODERS),
                queue.get_timestamp_period() as f64,
            )
        })
    }

    /// Makes room for `passes` timed passes (two queries each), up to wgpu's limit.
    /// Returns how many passes can be timed.
    pub fn reserve(&mut self, device: &wgpu::Device, passes: usize) -> usize {
        let wanted = (passes as u32)
            .saturating_mul(2)
            .min(wgpu::QUERY_SET_MAX_QUERIES);
        if wanted > self.capacity {
            *self = Self::allocate(device, wanted, self.inside_encoders, self.period);
        }
        (self.capacity / 2) as usize
    }

    /// Begin and end stamps of timed pass `slot` written by a render pass.
    pub fn render_writes(&self, slot: u32) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(2 * slot),
            end_of_pass_write_index: Some(2 * slot + 1),
        }
    }

    /// Begin and end stamps of timed pass `slot` written by a compute pass.
    pub fn compute_writes(&self, slot: u32) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query_set,
            beginning_of_pass_write_index: Some(2 * slot),
            end_of_pass_write_index: Some(2 * slot + 1),
        }
    }

    /// Writes the begin (`end == false`) or end stamp of timed pass `slot` between passes.
    pub fn write(&self, encoder: &mut wgpu::CommandEncoder, slot: u32, end: bool) {
        encoder.write_timestamp(&self.query_set, 2 * slot + end as u32);
    }

    /// Records copying the stamps of the first `slots` timed passes to the readback buffer.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder, slots: u32) {
        if slots == 0 {
            return;
        }
        encoder.resolve_query_set(&self.query_set, 0..2 * slots, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, 16 * slots as u64);
    }

    /// Begin and end ticks of each of the first `slots` timed passes, after the frame's
    /// submission. Waits for the GPU.
    pub fn read(
        &self,
        device: &wgpu::Device,
        slots: u32,
    ) -> Result<Vec<(u64, u64)>, ReadbackError> {
        if slots == 0 {
            return Ok(Vec::new());
        }
        let bytes = map_read(device, &self.readback, "the pass timestamps")?;
        Ok(bytes
            .chunks_exact(16)
            .take(slots as usize)
            .map(|pair| {
                let ticks = |b: &[u8]| u64::from_le_bytes(b.try_into().unwrap_or_default());
                (ticks(&pair[..8]), ticks(&pair[8..]))
            })
            .collect())
    }

    /// Nanoseconds in a span of `ticks` (a difference: absolute tick counts are too large
    /// to scale through `f64` exactly).
    pub fn nanoseconds(&self, ticks: u64) -> u64 {
        (ticks as f64 * self.period).round() as u64
    }

    fn allocate(device: &wgpu::Device, count: u32, inside_encoders: bool, period: f64) -> Self {
        let bytes = count as u64 * wgpu::QUERY_SIZE as u64;
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        Self {
            query_set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("rgraph pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: buffer(
                "rgraph timestamp resolve",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "rgraph timestamp readback",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
            capacity: count,
            inside_encoders,
            period,
        }
    }
}
