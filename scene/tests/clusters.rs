//! Clusters (`rgraph_scene::cluster`): every triangle kept once with its winding, the
//! clusters covering the reordered indices in order, and bounds that hold what they
//! claim: a renderer culling by them must never drop a visible triangle.

use std::sync::Arc;

use glam::Vec3;
use rgraph_scene::{cluster, ClusteredMesh, Mesh, Scene, CLUSTER_TRIANGLES};

fn builtin(spec: &str) -> Scene {
    Scene::load(spec).unwrap_or_else(|e| panic!("{e}"))
}

/// A triangle as its corners from the least index on, which keeps its winding.
fn rotated(t: &[u32]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

fn sorted_triangles(indices: &[u32]) -> Vec<[u32; 3]> {
    let mut triangles: Vec<[u32; 3]> = indices.chunks(3).map(rotated).collect();
    triangles.sort_unstable();
    triangles
}

fn position(mesh: &Mesh, i: u32) -> Vec3 {
    Vec3::from_array(mesh.vertices[i as usize].position)
}

/// Checks every claim of `clustered` about `mesh`, naming `what` in failures.
fn check(what: &str, mesh: &Mesh, clustered: &ClusteredMesh) {
    assert_eq!(
        sorted_triangles(&clustered.indices),
        sorted_triangles(&mesh.indices),
        "{what}: the clusters hold the mesh's triangles, each once, wound as before"
    );
    let mut next = 0;
    for (c, cluster) in clustered.clusters.iter().enumerate() {
        assert_eq!(
            cluster.first_triangle, next,
            "{what}: cluster {c} starts where the one before ends"
        );
        assert!(
            (1..=CLUSTER_TRIANGLES as u32).contains(&cluster.triangles),
            "{what}: cluster {c} has {} triangles",
            cluster.triangles
        );
        next += cluster.triangles;
        let first = 3 * cluster.first_triangle as usize;
        let indices = &clustered.indices[first..first + 3 * cluster.triangles as usize];
        let (min, max) = (Vec3::from_array(cluster.min), Vec3::from_array(cluster.max));
        let center = Vec3::from_array(cluster.center);
        let slack = 1e-4 * (1.0 + cluster.radius);
        for &i in indices {
            let p = position(mesh, i);
            assert!(
                p.cmpge(min).all() && p.cmple(max).all(),
                "{what}: cluster {c}'s box holds vertex {i}"
            );
            assert!(
                p.distance(center) <= cluster.radius + slack,
                "{what}: cluster {c}'s sphere holds vertex {i}"
            );
        }
        check_cone(what, c, mesh, cluster, indices);
    }
    assert_eq!(
        next as usize,
        mesh.triangle_count(),
        "{what}: the clusters cover every triangle"
    );
}

/// From points around the cluster that its cone test says see only back faces, every
/// triangle of it shows its back: the eye is behind (or in) each triangle's plane.
fn check_cone(what: &str, c: usize, mesh: &Mesh, cluster: &rgraph_scene::Cluster, indices: &[u32]) {
    if cluster.cone_cutoff >= 1.0 {
        return;
    }
    let center = Vec3::from_array(cluster.center);
    let axis = Vec3::from_array(cluster.cone_axis);
    let reach = 4.0 * cluster.radius.max(1e-3);
    for step in 0..64u32 {
        // Points on a spiral around the sphere, at 1.1 to 4 radii.
        let t = step as f32 / 64.0;
        let (theta, phi) = (t * 40.0, (1.0 - 2.0 * t).acos());
        let direction = Vec3::new(phi.sin() * theta.cos(), phi.sin() * theta.sin(), phi.cos());
        let eye = center + direction * reach * (0.275 + 0.725 * t);
        let to_center = center - eye;
        if to_center.dot(axis) < cluster.cone_cutoff * to_center.length() + cluster.radius {
            continue;
        }
        for triangle in indices.chunks(3) {
            let [a, b, cc] = [triangle[0], triangle[1], triangle[2]].map(|i| position(mesh, i));
            let normal = (b - a).cross(cc - a);
            if normal.length() <= f32::EPSILON * (b - a).length() * (cc - a).length() {
                continue;
            }
            let facing = normal.normalize().dot(eye - a);
            assert!(
                facing <= 1e-4 * reach,
                "{what}: cluster {c}'s cone culls it from {eye}, where triangle {triangle:?} faces the eye ({facing})"
            );
        }
    }
}

#[test]
fn clusters_keep_every_triangle_and_bound_it() {
    for spec in [
        "builtin:terrain?cells=40",
        "builtin:dense",
        "builtin:spheres",
        "builtin:city?blocks=3",
    ] {
        let scene = builtin(spec);
        for mesh in &scene.meshes {
            let what = format!("{spec}, {}", mesh.name);
            check(&what, mesh, &cluster(mesh));
        }
    }
}

#[test]
fn clusters_keep_degenerate_and_repeated_triangles() {
    let scene = builtin("builtin:terrain?cells=4");
    let mut mesh = scene.meshes[0].clone();
    let (a, b) = (mesh.indices[0], mesh.indices[1]);
    // Two corners at one index, and a triangle listed twice.
    let c = mesh.indices[2];
    Arc::make_mut(&mut mesh.indices).extend([a, a, b, a, b, c, a, b, c]);
    check("degenerate", &mesh, &cluster(&mesh));
}

/// Meshes whose triangles crowd one vertex, which meshoptimizer's builder would walk once
/// per triangle taken (hours for the visibility tests' mesh padded past 2^20 IDs): a
/// million copies of one degenerate triangle after a heightfield's, and a fan of 20,000
/// triangles around one vertex. Each keeps every triangle, degenerate ones last.
#[test]
fn crowded_vertices_keep_every_triangle() {
    let mut padded = builtin("builtin:terrain?cells=4").meshes[0].clone();
    let solid = padded.indices.len();
    Arc::make_mut(&mut padded.indices).extend(std::iter::repeat_n(0, 3 << 20));
    let clustered = cluster(&padded);
    check("padded", &padded, &clustered);
    assert_eq!(
        &clustered.indices[..solid],
        &cluster(&builtin("builtin:terrain?cells=4").meshes[0]).indices[..],
        "the heightfield's clusters changed with degenerate triangles after it"
    );
    let mut fan = padded;
    let rim = 20_000u32;
    let vertices = Arc::make_mut(&mut fan.vertices);
    vertices.truncate(1);
    let hub = vertices[0];
    vertices.extend((0..=rim).map(|k| {
        let angle = k as f32 / rim as f32 * std::f32::consts::TAU;
        let mut v = hub;
        v.position = [angle.cos(), 0.0, -angle.sin()];
        v
    }));
    fan.indices = Arc::new((1..=rim).flat_map(|k| [0, k, k + 1]).collect());
    check("fan", &fan, &cluster(&fan));
}

#[test]
fn a_dense_mesh_makes_full_clusters() {
    let scene = builtin("builtin:terrain?cells=100");
    let clustered = cluster(&scene.meshes[0]);
    let triangles = scene.meshes[0].triangle_count();
    // 20,000 triangles in clusters of at most 64: meshoptimizer fills most of them.
    assert!(
        clustered.clusters.len() <= triangles / 48,
        "{} clusters for {triangles} triangles",
        clustered.clusters.len()
    );
}

/// Consecutive clusters lie close together (the Z-order over their centres): on a
/// heightfield, whose triangles meshoptimizer takes row after row, a cluster's successor
/// is on average within a few clusters' size, where in the builder's order it was often
/// a row's length (100 units) away.
#[test]
fn consecutive_clusters_lie_close_together() {
    let scene = builtin("builtin:terrain?cells=224");
    let clustered = rgraph_scene::cluster(&scene.meshes[0]);
    let centers: Vec<Vec3> = clustered
        .clusters
        .iter()
        .map(|c| Vec3::from_array(c.center))
        .collect();
    let steps: f32 = centers.windows(2).map(|p| p[0].distance(p[1])).sum();
    let mean_step = steps / (centers.len() - 1) as f32;
    let mean_radius: f32 =
        clustered.clusters.iter().map(|c| c.radius).sum::<f32>() / centers.len() as f32;
    assert!(
        mean_step < 4.0 * mean_radius,
        "consecutive clusters are {mean_step} apart on average; a cluster's radius is \
         {mean_radius}"
    );
}
