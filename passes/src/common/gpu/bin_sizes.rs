//! How large the compute raster's tile bins are (common/gpu/tile_bins.rs,
//! bin_triangles.wgsl), counted without a device: the per-triangle arrays hold a number of
//! *slots*, the triangles a frame may bin one by one, chosen from the output and the
//! scene rather than from the scene alone; the per-cluster arrays hold every cluster
//! (about 0.7 bytes a triangle); the per-tile ones every tile.
//!
//! The rule: `slots = min(triangles, max(pixels / 2, 2^20))`, or `min(triangles, asked)`
//! where the pass's `binned_triangles` asks, then no more than the device binds (the
//! records, 80 bytes a slot, are the largest binding) and under 2^30 (a spanning piece
//! packs its slot in 30 bits), and at least 1 (a binding is never empty). Half a
//! triangle a pixel is room for every triangle a frame bins one by one where clusters of
//! small triangles go to the micro raster (their bounds then hold more than its
//! `micro_pixels`, 4, pixels a triangle, so those seen beside one another take at most a
//! quarter of a triangle a pixel) with depth complexity 2; 2^20 (176 MB) keeps small outputs
//! of dense scenes on the fast path. A frame that asks for more slots is still drawn
//! exactly: bin_triangles.wgsl sends the clusters past the slots to the tiles' whole-
//! cluster lists or to a list every tile reads.

/// bin_triangles.wgsl's BINNED_TILES: a triangle touching at most this many tiles lists
/// itself; the entries hold this many per slot.
pub(crate) const BINNED_TILES: u64 = 16;
/// Room in the entries for larger triangles, per tile: beyond it they are spanning, read
/// by every tile (slower, never wrong).
const LARGE_ENTRIES_PER_TILE: u64 = 16;
/// bin_triangles.wgsl's CLUSTER_TILES: a cluster touching at most this many tiles may be
/// listed whole; the entries hold this many per cluster. Each such tile sets up all of the
/// cluster's triangles, so more would trade fewer atomics for more work in the raster.
pub(crate) const CLUSTER_TILES: u64 = 4;
/// Per slot: triangle_setup.wgsl's ScreenTriangle (a binned triangle set up), the
/// entries' BINNED_TILES words, the spanning pieces a triangle may add (its clipped
/// polygon's fan, a word each) and its Spanning entry (`t` and pixel bounds).
const RECORD_BYTES: u64 = 80;
const ENTRY_BYTES: u64 = 4;
const PIECES: u64 = 3;
const SPANNING_BYTES: u64 = 12;
/// Per cluster: bin_triangles.wgsl's FallbackCluster (its index and first slot), a kind,
/// a place in the micro list and a Spanning entry.
const FALLBACK_BYTES: u64 = 8;
/// The default's floor, and the most a spanning piece's 30 bits number.
const MIN_SLOTS: u64 = 1 << 20;
const MAX_SLOTS: u64 = (1 << 30) - 1;

/// What the bins are made for: the scene's opaque triangles and clusters, the output in
/// pixels and its tiles, the slots the pass asks for, if it does, and the most bytes the
/// device binds in one storage binding.
#[derive(Copy, Clone, Debug)]
pub(crate) struct BinsFor {
    pub triangles: u32,
    pub clusters: u32,
    pub pixels: (u32, u32),
    pub tiles: u32,
    pub asked: Option<u32>,
    pub limit: u64,
}

/// The bins' buffers' sizes in bytes, and their slots.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct BinSizes {
    pub slots: u64,
    /// Per tile, a triangle list and a whole-cluster list: their ends, and their starts.
    pub lists: u64,
    pub entries: u64,
    pub spanning: u64,
    pub spanning_triangles: u64,
    pub items: u64,
    pub records: u64,
    pub fallback: u64,
    /// A word per cluster (their kinds).
    pub cluster_words: u64,
    pub micro_tiles: u64,
    pub micro: u64,
    pub spanning_clusters: u64,
}

impl BinSizes {
    /// The sizes for `bins`, or why the device cannot bind them (only where the clusters
    /// and tiles alone need more than a binding holds).
    pub fn new(bins: BinsFor) -> Result<BinSizes, String> {
        let (triangles, clusters, tiles) = (
            u64::from(bins.triangles),
            u64::from(bins.clusters),
            u64::from(bins.tiles),
        );
        let pixels = u64::from(bins.pixels.0) * u64::from(bins.pixels.1);
        let wanted = match bins.asked {
            Some(asked) => u64::from(asked),
            None => (pixels / 2).max(MIN_SLOTS),
        };
        // The entries but a slot's: the clusters' and the large triangles' room.
        let shared_entries = CLUSTER_TILES * clusters + LARGE_ENTRIES_PER_TILE * tiles;
        let entry_room = (bins.limit / ENTRY_BYTES).saturating_sub(shared_entries);
        let bound = [
            bins.limit / RECORD_BYTES,
            entry_room / BINNED_TILES,
            bins.limit / (PIECES * 4),
            bins.limit / SPANNING_BYTES,
            MAX_SLOTS,
        ];
        let slots = (bound.into_iter())
            .fold(wanted.min(triangles), u64::min)
            .max(1);
        let sizes = BinSizes {
            slots,
            lists: 2 * tiles * 4,
            entries: (BINNED_TILES * slots + shared_entries) * ENTRY_BYTES,
            spanning: PIECES * 4 * slots,
            spanning_triangles: SPANNING_BYTES * slots,
            items: (LARGE_ENTRIES_PER_TILE * tiles / BINNED_TILES + 1) * 16,
            records: RECORD_BYTES * slots,
            fallback: FALLBACK_BYTES * clusters,
            cluster_words: 4 * clusters,
            micro_tiles: 4 * tiles,
            micro: 4 * (clusters + 1),
            spanning_clusters: SPANNING_BYTES * clusters,
        };
        let per_cluster = [
            ("entries", sizes.entries),
            ("spanning clusters", sizes.spanning_clusters),
        ];
        match per_cluster.iter().find(|(_, bytes)| *bytes > bins.limit) {
            Some((what, bytes)) => Err(format!(
                "the scene's {clusters} opaque clusters over {tiles} tiles need {bytes} \
                 bytes of tile-bin {what}; this device binds at most {}: render with \
                 deferred_msaa_4x_lean.ron, whose raster pass is the hardware's",
                bins.limit
            )),
            None => Ok(sizes),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{BinSizes, BinsFor};

    /// Every byte of the bins' buffers (but their 24 bytes of counts and dispatch
    /// arguments).
    fn bytes(s: &BinSizes) -> u64 {
        let per_slot = s.entries + s.spanning + s.spanning_triangles + s.records;
        let per_cluster = s.fallback + s.cluster_words + s.micro + s.spanning_clusters;
        per_slot + per_cluster + 2 * s.lists + s.items + s.micro_tiles
    }

    /// builtin:terrain at `cells` (2 triangles a cell, clusters of 64) at 3840 x 2160 in
    /// tiles of 16, on a device binding 2 GiB.
    fn terrain_2160p(cells: u64, asked: Option<u32>) -> Result<BinSizes, String> {
        let triangles = 2 * cells * cells;
        BinSizes::new(BinsFor {
            triangles: triangles as u32,
            clusters: triangles.div_ceil(64) as u32,
            pixels: (3840, 2160),
            tiles: 240 * 135,
            asked,
            limit: 2 << 30,
        })
    }

    /// A scene of fewer triangles than the default's floor has a slot for each; a larger
    /// one has half a slot per pixel at 2160p, whatever its triangles; a pass's
    /// `binned_triangles` gives the slots, to the scene's count.
    #[test]
    fn the_slots_are_the_scene_s_triangles_up_to_half_the_pixels() {
        let slots = |cells, asked| terrain_2160p(cells, asked).unwrap().slots;
        assert_eq!(slots(71, None), 2 * 71 * 71);
        assert_eq!(slots(707, None), 2 * 707 * 707);
        assert_eq!(slots(2236, None), 3840 * 2160 / 2);
        assert_eq!(slots(7072, None), 3840 * 2160 / 2);
        assert_eq!(slots(2236, Some(1000)), 1000);
        assert_eq!(slots(10, Some(1000)), 200);
        assert_eq!(slots(10, Some(0)), 1);
    }

    /// The 100M-triangle terrain (cells 7072), refused before (its entries alone were 6.4
    /// GB), fits a device binding 2 GiB, its bins under 800 MB; at 10M triangles they
    /// take 707 MB where they took 1.65 GB.
    #[test]
    fn a_100m_triangle_terrain_s_bins_fit_a_gpu_s_binding() {
        let largest = terrain_2160p(7072, None).unwrap();
        let all = [
            largest.entries,
            largest.records,
            largest.spanning,
            largest.spanning_clusters,
        ];
        assert!(all.iter().all(|&bytes| bytes <= 2 << 30), "{largest:?}");
        let mb = |sizes: BinSizes| bytes(&sizes) as f64 / 1e6;
        assert!(mb(largest) < 800.0, "{} MB", mb(largest));
        let ten = terrain_2160p(2236, None).unwrap();
        assert!((690.0..720.0).contains(&mb(ten)), "{} MB", mb(ten));
    }

    /// On a device binding less (lavapipe's 128 MiB), the slots are what it binds, and
    /// clusters and tiles beyond it are an error naming the bins and the limit.
    #[test]
    fn the_slots_stop_at_the_device_s_binding_limit() {
        let lavapipe = |clusters| {
            BinSizes::new(BinsFor {
                triangles: 5_000_000,
                clusters,
                pixels: (3840, 2160),
                tiles: 240 * 135,
                asked: None,
                limit: 128 << 20,
            })
        };
        let sizes = lavapipe(78_125).unwrap();
        assert_eq!(sizes.slots, (128 << 20) / 80);
        assert!(sizes.entries <= 128 << 20);
        let error = lavapipe(10_000_000).unwrap_err();
        assert!(
            error.contains("10000000 opaque clusters") && error.contains("134217728"),
            "{error}"
        );
    }
}
