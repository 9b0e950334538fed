// Edge pixels lit by their tile (light_tiled.wgsl's edge-list entries): none is listed.
// light_edges_listed.wgsl is the other choice.

const EDGES_LISTED: bool = false;

fn listed_edge(pixel: vec2<i32>) -> bool {
    return false;
}

fn list_edge_pixel(local: u32, pixel: vec2<i32>, listed: bool) {}
