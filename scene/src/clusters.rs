//! Meshes split into clusters: runs of at most [`CLUSTER_TRIANGLES`] neighbouring
//! triangles, each with the bounds a renderer culls it by and bins it to screen tiles with
//! (the clusters of Nanite and of Bevy's meshlets; meshoptimizer's `buildMeshlets` makes
//! them). A renderer that culls and bins clusters instead of triangles pays its per-item
//! costs (atomics into tile counts, records in memory) once per cluster.
//!
//! [`cluster`] returns the mesh's triangles in a new order, cluster after cluster, each
//! triangle's corners in their order (so its winding) unchanged: a renderer uploads that
//! order, so that a cluster is a range of the index buffer. The mesh itself is not changed,
//! so the clusters are made from the mesh as it is when uploaded and cannot go stale. The
//! clusters follow one another along a Z-order curve over their centres, so that
//! consecutive clusters lie close together.

use glam::Vec3;

use crate::mesh::{Mesh, Vertex};

/// The most triangles in a cluster: 64, one for each of the 64 invocations a compute
/// rasteriser sets triangles up with at once (passes' tile_raster.wgsl).
pub const CLUSTER_TRIANGLES: usize = 64;
/// The most distinct vertices in a cluster: meshoptimizer's recommended 64 for clusters of
/// this size (fewer vertices per triangle makes rounder clusters on smooth meshes).
const CLUSTER_VERTICES: usize = 64;
/// How much meshoptimizer favours clusters whose triangles face one way (tighter normal
/// cones, so more back-facing clusters culled) over round ones: its suggested 0.25.
const CONE_WEIGHT: f32 = 0.25;
/// The most triangles one vertex may share for meshoptimizer to cluster a mesh: its
/// builder scans a vertex's triangles each time it takes one of them, so a hub's cost
/// grows with the square of their number (a fan of a million triangles would take hours).
/// A mesh with a busier vertex is cut into runs of its own order instead.
const MAX_SHARED: u32 = 4096;

/// One cluster of a [`ClusteredMesh`], in the mesh's object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cluster {
    /// Its first triangle in [`ClusteredMesh::indices`] (an index position / 3).
    pub first_triangle: u32,
    /// 1 to [`CLUSTER_TRIANGLES`].
    pub triangles: u32,
    /// The least corner of the box holding its vertices.
    pub min: [f32; 3],
    /// The greatest corner of that box.
    pub max: [f32; 3],
    /// The centre of a sphere holding its vertices.
    pub center: [f32; 3],
    /// That sphere's radius.
    pub radius: f32,
    /// The cone holding its triangles' (counter-clockwise) normals: seen from a point `e`
    /// with `dot(center - e, cone_axis) >= cone_cutoff * |center - e| + radius`, every
    /// triangle shows its back (meshoptimizer's test). A `cone_cutoff` of 1 or more: no
    /// point sees only back faces.
    pub cone_axis: [f32; 3],
    /// The cone's cutoff in that test.
    pub cone_cutoff: f32,
}

/// A mesh's triangles in cluster order and its clusters, which cover them in that order.
#[derive(Clone, Debug, PartialEq)]
pub struct ClusteredMesh {
    /// The mesh's indices, three per triangle, cluster after cluster.
    pub indices: Vec<u32>,
    /// In index order: each starts where the one before ends.
    pub clusters: Vec<Cluster>,
}

/// `mesh` split into clusters. Every triangle of the mesh appears once in the result, with
/// its corners in their order; degenerate triangles (two corners at one index), which
/// cover nothing, come last, in runs of their own order.
pub fn cluster(mesh: &Mesh) -> ClusteredMesh {
    let (solid, degenerate): (Vec<&[u32]>, Vec<&[u32]>) = mesh
        .indices
        .chunks_exact(3)
        .partition(|t| t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
    let (solid, degenerate) = (solid.concat(), degenerate.concat());
    let mut out = if most_shared(&solid, mesh.vertices.len()) > MAX_SHARED {
        in_runs(mesh, &solid, 0)
    } else {
        built(mesh, &solid)
    };
    let first = (out.indices.len() / 3) as u32;
    let rest = in_runs(mesh, &degenerate, first);
    out.indices.extend(rest.indices);
    out.clusters.extend(rest.clusters);
    out
}

/// How many triangles of `indices` the busiest of `vertices` vertices is a corner of.
fn most_shared(indices: &[u32], vertices: usize) -> u32 {
    let mut shared = vec![0u32; vertices];
    for &i in indices {
        shared[i as usize] += 1;
    }
    shared.into_iter().max().unwrap_or(0)
}

/// The triangles `indices` (none degenerate) of `mesh` in meshoptimizer's clusters.
fn built(mesh: &Mesh, indices: &[u32]) -> ClusteredMesh {
    let adapter = vertex_adapter(mesh);
    let meshlets = meshopt::build_meshlets(
        indices,
        &adapter,
        CLUSTER_VERTICES,
        CLUSTER_TRIANGLES,
        CONE_WEIGHT,
    );
    let mut out = ClusteredMesh {
        indices: Vec::with_capacity(indices.len()),
        clusters: Vec::with_capacity(meshlets.len()),
    };
    let bounds: Vec<meshopt::Bounds> = meshlets
        .iter()
        .map(|meshlet| meshopt::compute_meshlet_bounds(meshlet, &adapter))
        .collect();
    for (meshlet, bounds) in spatial_order(&bounds)
        .into_iter()
        .map(|k| (meshlets.get(k), bounds[k]))
    {
        let first = out.indices.len();
        out.indices.extend(
            meshlet
                .triangles
                .iter()
                .map(|&k| meshlet.vertices[k as usize]),
        );
        out.clusters.push(bounded(
            &mesh.vertices,
            &out.indices[first..],
            (first / 3) as u32,
            bounds,
        ));
    }
    if out.indices.len() != indices.len() {
        // meshoptimizer leaves out no triangle it is given; should a version ever drop
        // some, their own order in runs keeps every triangle.
        return in_runs(mesh, indices, 0);
    }
    out
}

/// The clusters whose bounding spheres are `bounds`, in the order of their centres along
/// a Z-order (Morton) curve over the box holding the centres, 10 bits an axis (the
/// builder's order among equals). meshoptimizer grows clusters along the index order,
/// row after row of a grid, so consecutive clusters of its order may lie a row's length
/// apart; along the curve they lie close, and a run of consecutive clusters is a
/// compact region: the runs a view draws of a mesh (the shadow maps' culling, which
/// tests boxes over consecutive clusters) are few, and those boxes tight.
fn spatial_order(bounds: &[meshopt::Bounds]) -> Vec<usize> {
    let centers: Vec<Vec3> = bounds.iter().map(|b| Vec3::from_array(b.center)).collect();
    let (min, max) = centers.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(min, max), &c| (min.min(c), max.max(c)),
    );
    let scale = 1023.0 / (max - min).max(Vec3::splat(f32::MIN_POSITIVE));
    let key = |c: Vec3| {
        let q = ((c - min) * scale)
            .round()
            .clamp(Vec3::ZERO, Vec3::splat(1023.0));
        spread(q.x as u32) | (spread(q.y as u32) << 1) | (spread(q.z as u32) << 2)
    };
    let keys: Vec<u32> = centers.iter().map(|&c| key(c)).collect();
    let mut order: Vec<usize> = (0..bounds.len()).collect();
    order.sort_by_key(|&k| keys[k]);
    order
}

/// The 10 low bits of `v` two zero bits apart: bit i moves to bit 3 i.
fn spread(v: u32) -> u32 {
    let mut v = v & 0x3ff;
    v = (v | (v << 16)) & 0x0300_00ff;
    v = (v | (v << 8)) & 0x0300_f00f;
    v = (v | (v << 4)) & 0x030c_30c3;
    (v | (v << 2)) & 0x0924_9249
}

/// The triangles `indices` of `mesh` in their own order, in runs of
/// [`CLUSTER_TRIANGLES`], the first run's first triangle numbered `first`.
fn in_runs(mesh: &Mesh, indices: &[u32], first: u32) -> ClusteredMesh {
    let adapter = vertex_adapter(mesh);
    let clusters = indices
        .chunks(3 * CLUSTER_TRIANGLES)
        .zip((first..).step_by(CLUSTER_TRIANGLES))
        .map(|(run, first)| {
            let bounds = meshopt::compute_cluster_bounds(run, &adapter);
            bounded(&mesh.vertices, run, first, bounds)
        })
        .collect();
    ClusteredMesh {
        indices: indices.to_vec(),
        clusters,
    }
}

/// The mesh's positions as meshoptimizer reads them: the first 12 bytes of each vertex.
fn vertex_adapter(mesh: &Mesh) -> meshopt::VertexDataAdapter<'_> {
    let positions: &[u8] = bytemuck::cast_slice(&mesh.vertices);
    match meshopt::VertexDataAdapter::new(positions, std::mem::size_of::<Vertex>(), 0) {
        Ok(adapter) => adapter,
        // Only data that is not a whole number of vertices fails, which a slice of
        // vertices cannot be.
        Err(_) => unreachable!("a slice of vertices is a whole number of vertices"),
    }
}

/// The cluster of `indices` (whole triangles, the first at `first_triangle`) with
/// meshoptimizer's sphere and cone `bounds` and the box of its vertices. The sphere grows
/// to hold every vertex: meshoptimizer's leaves out degenerate triangles' corners.
fn bounded(
    vertices: &[Vertex],
    indices: &[u32],
    first_triangle: u32,
    bounds: meshopt::Bounds,
) -> Cluster {
    let (mut min, mut max) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    let center = glam::Vec3::from_array(bounds.center);
    let mut radius = bounds.radius;
    for &i in indices {
        let p = vertices[i as usize].position;
        for k in 0..3 {
            min[k] = min[k].min(p[k]);
            max[k] = max[k].max(p[k]);
        }
        radius = radius.max(center.distance(glam::Vec3::from_array(p)));
    }
    Cluster {
        first_triangle,
        triangles: (indices.len() / 3) as u32,
        min,
        max,
        center: bounds.center,
        radius,
        cone_axis: bounds.cone_axis,
        cone_cutoff: bounds.cone_cutoff,
    }
}
