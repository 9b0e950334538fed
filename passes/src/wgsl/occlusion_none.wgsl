// Binning without occlusion culling (bin_triangles.wgsl): every cluster, as cluster_bins
// leaves it.

fn occlusion_clear() {}

fn listed_cluster(i: u32) -> u32 {
    return every_cluster(i);
}

fn occlusion_kind(c: u32, kind: u32) -> u32 {
    return kind;
}
