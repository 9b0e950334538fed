// The second phase of occlusion culling (cluster_occlusion.wgsl): the clusters the first
// phase listed, each binned unless the pyramid of what the first phase drew hides it,
// seen through this frame's camera (the raster's), and counted in `revealed` when binned.
// An entry past the list's room, or naming no cluster, is skipped: the first phase drew
// what did not fit.

fn occlusion_clear() {}

fn listed_cluster(i: u32) -> u32 {
    let listed = min(atomicLoad(&occluded.count), arrayLength(&occluded.ids));
    if i >= listed {
        return NO_CLUSTER;
    }
    let c = occluded.ids[i];
    return select(NO_CLUSTER, c, c < arrayLength(&clusters));
}

fn occlusion_kind(c: u32, kind: u32) -> u32 {
    if kind == CLUSTER_CULLED {
        return kind;
    }
    let cluster = clusters[c];
    if pyramid_hides(cluster, cluster_model(cluster), camera.view_proj) {
        return CLUSTER_CULLED;
    }
    atomicAdd(&occluded.revealed, 1u);
    return kind;
}
