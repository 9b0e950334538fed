//! The opaque draws' triangles binned to tiles (bin_triangles.wgsl says how), so that the
//! compute raster covers each tile in one workgroup (passes/visibility_compute.rs,
//! tile_raster.wgsl). Made for one scene upload and output size; recorded as six
//! dispatches just before the raster's, in the same compute pass.

use super::compute_pipeline;
use super::pipeline::{module, pipeline_layout};
use super::raster_draws::RasterDraws;
use super::storage::{scratch, storage_group, storage_layout};
use crate::gpu_scene::GpuScene;
use rgraph_scene::DepthConvention;

/// bin_triangles.wgsl's BINNED_TILES: a triangle touching at most this many tiles lists
/// itself; the entries hold this many per triangle.
const BINNED_TILES: u64 = 16;
/// Room in the entries for larger triangles, per tile: beyond it they are spanning, read
/// by every tile (slower, never wrong).
const LARGE_ENTRIES_PER_TILE: u64 = 16;
/// bin_triangles.wgsl's workgroup of its per-tile and per-triangle dispatches, and the grid
/// of its item dispatches.
const GROUP: u32 = 64;
const ITEM_GROUPS: u32 = 1024;
/// triangle_setup.wgsl's ScreenTriangle, a binned triangle set up.
const RECORD_BYTES: u64 = 80;
/// The spanning pieces a triangle may add: its clipped polygon's fan.
const PIECES: u64 = 3;

/// The buffers a tile's raster reads (tile_raster.wgsl's bindings 1 to 8, in this
/// order): all but the items.
const RASTER_BUFFER_INDICES: [usize; 8] = [0, 1, 2, 3, 4, 5, 6, 8];
/// How many: the raster's group binds them after its keys.
pub(crate) const RASTER_BUFFERS: usize = RASTER_BUFFER_INDICES.len();

pub(crate) struct TileBins {
    clear: wgpu::ComputePipeline,
    count: wgpu::ComputePipeline,
    count_items: wgpu::ComputePipeline,
    offsets: wgpu::ComputePipeline,
    fill: wgpu::ComputePipeline,
    fill_items: wgpu::ComputePipeline,
    group: wgpu::BindGroup,
    draws: RasterDraws,
    tiles: u32,
    /// In bin_triangles.wgsl's binding order: draws, tile_ends, tile_starts, tile_entries,
    /// spanning, bin_counts, spanning_bounds, items, records.
    buffers: [wgpu::Buffer; 9],
}

impl TileBins {
    /// Every buffer the bins keep, for the pass to count as its own
    /// ([`rgraph_core::FrameResources::hold`]).
    pub fn buffers(&self) -> &[wgpu::Buffer] {
        &self.buffers
    }

    /// Bins for `scene`'s opaque triangles over the tiles of side `tile` covering
    /// `size`, with bin_triangles.wgsl composed as `source`; an error when the device cannot
    /// bind them.
    pub fn new(
        device: &wgpu::Device,
        source: &str,
        scene: &GpuScene,
        tile: u32,
        size: (u32, u32),
    ) -> Result<TileBins, String> {
        let tiles = size.0.div_ceil(tile) * size.1.div_ceil(tile);
        let draws = RasterDraws::new(device, scene);
        let triangles = u64::from(draws.triangles);
        let large = LARGE_ENTRIES_PER_TILE * u64::from(tiles);
        let entries = (BINNED_TILES * triangles + large) * 4;
        let limit = device.limits().max_storage_buffer_binding_size;
        let records = triangles * RECORD_BYTES;
        let spanning = triangles * PIECES * 4;
        let per_triangle = [
            ("entries", entries),
            ("records", records),
            ("spanning list", spanning),
        ];
        if let Some((what, bytes)) = per_triangle.iter().find(|(_, bytes)| *bytes > limit) {
            return Err(format!(
                "the scene's {triangles} opaque triangles need {bytes} bytes of tile-bin \
                 {what}; this device binds at most {limit}: render with \
                 deferred_msaa_4x_lean.ron, whose raster pass is the hardware's"
            ));
        }
        let tile_words = u64::from(tiles) * 4;
        let buffers = [
            draws.buffer.clone(),
            scratch(device, "tile bins: ends", tile_words),
            scratch(device, "tile bins: starts", tile_words),
            scratch(device, "tile bins: entries", entries),
            scratch(device, "tile bins: spanning", spanning),
            scratch(device, "tile bins: counts", 12),
            scratch(device, "tile bins: spanning bounds", triangles * 8),
            scratch(device, "tile bins: items", (large / BINNED_TILES + 1) * 16),
            scratch(device, "tile bins: records", records),
        ];
        let mut read_only = [false; 9];
        read_only[0] = true;
        let layout = storage_layout(device, "tile bins", &read_only);
        let refs: Vec<&wgpu::Buffer> = buffers.iter().collect();
        let group = storage_group(device, "tile bins", &layout, &refs);
        let module = module(device, "tile_bins", source);
        let pipeline_layout = pipeline_layout(
            device,
            &[
                Some(scene.layout()),
                Some(&layout),
                Some(scene.geometry_layout()),
            ],
        );
        let constants = [
            ("TILE", f64::from(tile)),
            ("BINNED_TILES", BINNED_TILES as f64),
            ("ITEM_GROUPS", f64::from(ITEM_GROUPS)),
        ];
        let pipeline = |entry: &str| {
            compute_pipeline(
                device,
                "tile bins",
                &pipeline_layout,
                &module,
                entry,
                &constants,
            )
        };
        Ok(TileBins {
            clear: pipeline("cs_bins_clear"),
            count: pipeline("cs_bins_count"),
            count_items: pipeline("cs_bins_count_items"),
            offsets: pipeline("cs_bins_offsets"),
            fill: pipeline("cs_bins_fill"),
            fill_items: pipeline("cs_bins_fill_items"),
            group,
            draws,
            tiles,
            buffers,
        })
    }

    /// Records the binning into `pass`, with `scene`'s groups 0 (reversed-Z, as the
    /// shading covers the tiles) and 2 (`geometry`); the pass's later dispatches set
    /// their own groups.
    pub fn record(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        scene: &GpuScene,
        geometry: &wgpu::BindGroup,
    ) {
        pass.set_bind_group(0, scene.bind_group(DepthConvention::ReversedZ), &[]);
        pass.set_bind_group(1, &self.group, &[]);
        pass.set_bind_group(2, geometry, &[]);
        let (x, y) = grid(u64::from(self.tiles), GROUP);
        pass.set_pipeline(&self.clear);
        pass.dispatch_workgroups(x, y, 1);
        if self.draws.triangles == 0 {
            // No entries: the tiles' counts stay 0, as their starts are.
            return;
        }
        let (x, y) = grid(u64::from(self.draws.triangles), GROUP);
        pass.set_pipeline(&self.count);
        pass.dispatch_workgroups(x, y, 1);
        pass.set_pipeline(&self.count_items);
        pass.dispatch_workgroups(ITEM_GROUPS, 1, 1);
        pass.set_pipeline(&self.offsets);
        pass.dispatch_workgroups(1, 1, 1);
        pass.set_pipeline(&self.fill);
        pass.dispatch_workgroups(x, y, 1);
        pass.set_pipeline(&self.fill_items);
        pass.dispatch_workgroups(ITEM_GROUPS, 1, 1);
    }

    /// The buffers a tile's raster reads, in tile_raster.wgsl's binding order (from 1).
    pub fn raster_buffers(&self) -> Vec<&wgpu::Buffer> {
        RASTER_BUFFER_INDICES
            .iter()
            .map(|&i| &self.buffers[i])
            .collect()
    }
}

/// Workgroups of `group` invocations for `invocations`, as x by y within the 65,535 a
/// dimension allows (bin_triangles.wgsl flattens them back).
fn grid(invocations: u64, group: u32) -> (u32, u32) {
    let groups = invocations.div_ceil(u64::from(group)).max(1);
    let x = groups.min(65_535);
    (x as u32, groups.div_ceil(x) as u32)
}
