// The first phase of occlusion culling (cluster_occlusion.wgsl): every cluster, those the
// previous frame's pyramid hides seen through the previous frame's camera (`first_phase`,
// written each frame by common/gpu/occlusion.rs) listed for the second phase instead of
// binned. Where the list is full, a hidden cluster is binned: drawn now rather than never.
// `test` is 0 where the pyramid holds no frame (the first, after a reset or a resize) or
// occlusion culling is off: nothing is listed, and the second phase has nothing to do.

struct FirstPhase {
    // The previous frame's clip space from this frame's camera-relative space.
    clip: mat4x4<f32>,
    test: u32,
}

@group(3) @binding(3) var<uniform> first_phase: FirstPhase;

fn occlusion_clear() {
    atomicStore(&occluded.count, 0u);
    atomicStore(&occluded.revealed, 0u);
}

fn listed_cluster(i: u32) -> u32 {
    return every_cluster(i);
}

fn occlusion_kind(c: u32, kind: u32) -> u32 {
    if kind == CLUSTER_CULLED || first_phase.test == 0u {
        return kind;
    }
    let cluster = clusters[c];
    if !pyramid_hides(cluster, cluster_model(cluster), first_phase.clip) {
        return kind;
    }
    let slot = atomicAdd(&occluded.count, 1u);
    if slot >= arrayLength(&occluded.ids) {
        return kind;
    }
    occluded.ids[slot] = c;
    return CLUSTER_CULLED;
}
