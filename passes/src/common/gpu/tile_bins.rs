//! The opaque draws' triangles binned to tiles (bin_triangles.wgsl says how), so that the
//! compute raster covers each tile in one workgroup (passes/visibility_compute.rs,
//! tile_raster.wgsl). Made for one scene upload and output size; recorded as nine
//! dispatches just before the raster's, in the same compute pass, two of them indirect:
//! the clusters binned by triangle are known only on the device (as are the micro
//! clusters, whose raster's indirect arguments follow: [`TileBins::dispatch_args`]). With
//! occlusion culling (cluster_occlusion.wgsl), the source composed for one of its
//! phases, every dispatch but the fallback list's arguments takes its group 3. Their
//! sizes (common/gpu/bin_sizes.rs) follow the output, not the scene alone: a frame binning
//! more triangles one by one than they have slots for sends the clusters past them by
//! slower paths, to the same image.

use super::bin_sizes::{BinSizes, BinsFor, BINNED_TILES, CLUSTER_TILES};
use super::pipeline::{module, pipeline_layout};
use super::raster_draws::RasterDraws;
use super::storage::{scratch, storage_group, storage_layout};
use super::{compute_pipeline, workgroup_grid};
use crate::gpu_scene::GpuScene;
use rgraph_scene::DepthConvention;

/// bin_triangles.wgsl's workgroup of its per-tile and per-triangle dispatches, and the grid
/// of its item dispatches.
const GROUP: u32 = 64;
const ITEM_GROUPS: u32 = 1024;
/// bin_triangles.wgsl's BinCounts: six words.
const COUNTS_BYTES: u64 = 24;

/// The buffers a tile's raster reads (tile_raster.wgsl's bindings 1 to 9, then
/// raster_tiles.wgsl's and micro_raster.wgsl's 10 and 11, then tile_raster.wgsl's 12, in
/// this order): all but the items, the fallback clusters and the cluster kinds.
const RASTER_BUFFER_INDICES: [usize; 12] = [0, 1, 2, 3, 4, 5, 6, 8, 9, 12, 13, 14];
/// How many: the raster's group binds them after its keys.
pub(crate) const RASTER_BUFFERS: usize = RASTER_BUFFER_INDICES.len();
/// The bins' group 1, then the dispatch arguments (group 3 of cs_clusters_args).
const BIN_BUFFERS: usize = 15;

/// Whether the bins cull clusters, whether they list small ones whole, and the most
/// pixels per triangle of a micro cluster's bounds, 0 for none (bin_triangles.wgsl's
/// CULL_CLUSTERS, WHOLE_CLUSTERS and MICRO_PIXELS).
#[derive(Copy, Clone, Debug)]
pub(crate) struct ClusterBinning {
    pub cull: bool,
    pub whole: bool,
    pub micro: u32,
}

/// How the bins are made: the raster's tile side, how clusters are binned, the slots
/// the pass asks for ([`BinsFor::asked`]), and occlusion culling's group 3 layout where
/// bin_triangles.wgsl is composed for a phase of it.
pub(crate) struct Binning<'a> {
    pub tile: u32,
    pub clusters: ClusterBinning,
    pub slots: Option<u32>,
    pub occlusion: Option<&'a wgpu::BindGroupLayout>,
}

/// Where in [`TileBins::dispatch_args`] the micro raster's dispatch arguments start, after
/// the fallback list's.
pub(crate) const MICRO_ARGS_OFFSET: u64 = 12;

pub(crate) struct TileBins {
    clear: wgpu::ComputePipeline,
    clusters_count: wgpu::ComputePipeline,
    clusters_args: wgpu::ComputePipeline,
    count: wgpu::ComputePipeline,
    count_items: wgpu::ComputePipeline,
    offsets: wgpu::ComputePipeline,
    fill: wgpu::ComputePipeline,
    fill_items: wgpu::ComputePipeline,
    clusters_fill: wgpu::ComputePipeline,
    group: wgpu::BindGroup,
    /// The fallback list's dispatch arguments (the last buffer), bound as group 3 only
    /// while cs_clusters_args writes them: a dispatch that reads a buffer as its
    /// arguments may not bind it for writing too.
    args_group: wgpu::BindGroup,
    draws: RasterDraws,
    tiles: u32,
    /// In bin_triangles.wgsl's binding order: draws, tile_ends, tile_starts, tile_entries,
    /// spanning, bin_counts, spanning_triangles, items, records, clusters, fallback,
    /// cluster_kinds, micro_tiles, micro, spanning_clusters (group 1), then fallback_args
    /// (group 3).
    buffers: [wgpu::Buffer; BIN_BUFFERS + 1],
}

impl TileBins {
    /// Every buffer the bins keep, for the pass to count as its own
    /// ([`rgraph_core::FrameResources::hold`]).
    pub fn buffers(&self) -> &[wgpu::Buffer] {
        &self.buffers
    }

    /// Bins for `scene`'s opaque triangles over the tiles covering `size`, with
    /// bin_triangles.wgsl composed as `source`, made as `binning` says and sized by
    /// [`BinSizes`]; an error when the device cannot bind them.
    pub fn new(
        device: &wgpu::Device,
        source: &str,
        scene: &GpuScene,
        binning: &Binning<'_>,
        size: (u32, u32),
    ) -> Result<TileBins, String> {
        let tile = binning.tile;
        let tiles = size.0.div_ceil(tile) * size.1.div_ceil(tile);
        let draws = RasterDraws::new(device, scene);
        let sizes = BinSizes::new(BinsFor {
            triangles: draws.triangles,
            clusters: draws.cluster_count,
            pixels: size,
            tiles,
            asked: binning.slots,
            limit: device.limits().max_storage_buffer_binding_size,
        })?;
        let buffers = [
            draws.buffer.clone(),
            scratch(device, "tile bins: ends", sizes.lists),
            scratch(device, "tile bins: starts", sizes.lists),
            scratch(device, "tile bins: entries", sizes.entries),
            scratch(device, "tile bins: spanning", sizes.spanning),
            scratch(device, "tile bins: counts", COUNTS_BYTES),
            scratch(
                device,
                "tile bins: spanning triangles",
                sizes.spanning_triangles,
            ),
            scratch(device, "tile bins: items", sizes.items),
            scratch(device, "tile bins: records", sizes.records),
            draws.clusters.clone(),
            scratch(device, "tile bins: fallback clusters", sizes.fallback),
            scratch(device, "tile bins: cluster kinds", sizes.cluster_words),
            scratch(device, "tile bins: micro tiles", sizes.micro_tiles),
            scratch(device, "tile bins: micro clusters", sizes.micro),
            scratch(
                device,
                "tile bins: spanning clusters",
                sizes.spanning_clusters,
            ),
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("tile bins: fallback and micro dispatches"),
                size: 2 * MICRO_ARGS_OFFSET,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT,
                mapped_at_creation: false,
            }),
        ];
        let (bins, args) = buffers.split_at(BIN_BUFFERS);
        let args_group_layout = storage_layout(device, "tile bins: fallback dispatch", &[false]);
        let args_group = storage_group(
            device,
            "tile bins: fallback dispatch",
            &args_group_layout,
            &[&args[0]],
        );
        let mut read_only = [false; BIN_BUFFERS];
        read_only[0] = true;
        read_only[9] = true;
        let layout = storage_layout(device, "tile bins", &read_only);
        let refs: Vec<&wgpu::Buffer> = bins.iter().collect();
        let group = storage_group(device, "tile bins", &layout, &refs);
        let module = module(device, "tile_bins", source);
        let bins_layout = pipeline_layout(
            device,
            &[
                Some(scene.layout()),
                Some(&layout),
                Some(scene.geometry_layout()),
                binning.occlusion,
            ],
        );
        let args_layout = pipeline_layout(
            device,
            &[
                Some(scene.layout()),
                Some(&layout),
                Some(scene.geometry_layout()),
                Some(&args_group_layout),
            ],
        );
        let clusters = binning.clusters;
        let constants = [
            ("TILE", f64::from(tile)),
            ("BINNED_TILES", BINNED_TILES as f64),
            ("ITEM_GROUPS", f64::from(ITEM_GROUPS)),
            ("CLUSTER_TILES", CLUSTER_TILES as f64),
            ("CULL_CLUSTERS", f64::from(u8::from(clusters.cull))),
            ("WHOLE_CLUSTERS", f64::from(u8::from(clusters.whole))),
            ("MICRO_PIXELS", f64::from(clusters.micro)),
        ];
        let pipeline_with = |layout: &wgpu::PipelineLayout, entry: &str| {
            compute_pipeline(device, "tile bins", layout, &module, entry, &constants)
        };
        let pipeline = |entry: &str| pipeline_with(&bins_layout, entry);
        Ok(TileBins {
            clear: pipeline("cs_bins_clear"),
            clusters_count: pipeline("cs_clusters_count"),
            clusters_args: pipeline_with(&args_layout, "cs_clusters_args"),
            count: pipeline("cs_bins_count"),
            count_items: pipeline("cs_bins_count_items"),
            offsets: pipeline("cs_bins_offsets"),
            fill: pipeline("cs_bins_fill"),
            fill_items: pipeline("cs_bins_fill_items"),
            clusters_fill: pipeline("cs_clusters_fill"),
            group,
            args_group,
            draws,
            tiles,
            buffers,
        })
    }

    /// Records the binning into `pass`, with `scene`'s groups 0 (reversed-Z, as the
    /// shading covers the tiles) and 2 (`geometry`), and this frame's `occlusion` group
    /// where the bins were made with its layout; the pass's later dispatches set their
    /// own groups.
    pub fn record(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        scene: &GpuScene,
        geometry: &wgpu::BindGroup,
        occlusion: Option<&wgpu::BindGroup>,
    ) {
        pass.set_bind_group(0, scene.bind_group(DepthConvention::ReversedZ), &[]);
        pass.set_bind_group(1, &self.group, &[]);
        pass.set_bind_group(2, geometry, &[]);
        pass.set_bind_group(3, occlusion, &[]);
        let (x, y) = workgroup_grid(2 * u64::from(self.tiles), GROUP);
        pass.set_pipeline(&self.clear);
        pass.dispatch_workgroups(x, y, 1);
        if self.draws.triangles == 0 {
            // No entries: the lists' counts stay 0, as their starts are.
            return;
        }
        let (x, y) = workgroup_grid(u64::from(self.draws.cluster_count), GROUP);
        let fallback_args = self.dispatch_args();
        pass.set_pipeline(&self.clusters_count);
        pass.dispatch_workgroups(x, y, 1);
        pass.set_pipeline(&self.clusters_args);
        pass.set_bind_group(3, &self.args_group, &[]);
        pass.dispatch_workgroups(1, 1, 1);
        pass.set_bind_group(3, occlusion, &[]);
        pass.set_pipeline(&self.count);
        pass.dispatch_workgroups_indirect(fallback_args, 0);
        pass.set_pipeline(&self.count_items);
        pass.dispatch_workgroups(ITEM_GROUPS, 1, 1);
        pass.set_pipeline(&self.offsets);
        pass.dispatch_workgroups(1, 1, 1);
        pass.set_pipeline(&self.fill);
        pass.dispatch_workgroups_indirect(fallback_args, 0);
        pass.set_pipeline(&self.fill_items);
        pass.dispatch_workgroups(ITEM_GROUPS, 1, 1);
        pass.set_pipeline(&self.clusters_fill);
        pass.dispatch_workgroups(x, y, 1);
    }

    /// The indirect arguments of the dispatches binning the fallback clusters (from 0), then
    /// of the micro raster's (from [`MICRO_ARGS_OFFSET`]): a workgroup per micro cluster,
    /// written by [`Self::record`].
    pub fn dispatch_args(&self) -> &wgpu::Buffer {
        &self.buffers[BIN_BUFFERS]
    }

    /// The buffers a tile's raster reads, in tile_raster.wgsl's binding order (from 1).
    pub fn raster_buffers(&self) -> Vec<&wgpu::Buffer> {
        RASTER_BUFFER_INDICES
            .iter()
            .map(|&i| &self.buffers[i])
            .collect()
    }
}
