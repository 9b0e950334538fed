//! Instanced copies (issue 38): meshes sharing one geometry (`rgraph_scene::Mesh`'s
//! vertices and indices) go up once per distinct vertex array (passes'
//! gpu_scene/shared_geometry.rs), and render exactly as copies that each own their arrays,
//! through the compute raster, the CPU adapter's visibility path and forward MSAA.

use std::sync::Arc;

use rgraph_passes::gpu_scene::GpuScene;
use rgraph_scene::glam::{DMat4, DVec3};
use rgraph_scene::Scene;

use crate::deferred_support::{gpu, PipelineFile, Render};

/// Where the copies of every mesh go, from the original: up, and up and aside.
const OFFSETS: [[f64; 3]; 2] = [[0.0, 1.2, 0.0], [0.7, 2.4, -0.5]];

/// builtin:spheres with every mesh placed twice more (`OFFSETS`), each copy sharing the
/// original's arrays or, when not `shared`, holding copies of them.
fn with_copies(shared: bool) -> Scene {
    let mut scene = Scene::load("builtin:spheres").unwrap();
    let originals = scene.meshes.clone();
    for offset in OFFSETS {
        for mesh in &originals {
            let mut copy = mesh.clone();
            if !shared {
                copy.vertices = Arc::new(mesh.vertices.to_vec());
                copy.indices = Arc::new(mesh.indices.to_vec());
            }
            copy.transform = DMat4::from_translation(DVec3::from(offset)) * mesh.transform;
            scene.meshes.push(copy);
        }
    }
    scene
}

#[test]
fn shared_vertices_are_uploaded_once_and_indices_once_per_mesh() {
    let gpu = gpu();
    let bytes = |scene: &Scene| {
        GpuScene::upload(&gpu.device, &gpu.queue, scene)
            .expect("the scene fits the device")
            .geometry_bytes()
    };
    let (one_vertices, one_indices) = bytes(&Scene::load("builtin:spheres").unwrap());
    let (shared_vertices, shared_indices) = bytes(&with_copies(true));
    let (own_vertices, own_indices) = bytes(&with_copies(false));
    assert_eq!(
        shared_vertices, one_vertices,
        "three placements, one upload"
    );
    assert_eq!(own_vertices, 3 * one_vertices);
    // Every placement keeps its own range of indices: a triangle ID names one placement.
    assert_eq!(
        (shared_indices, own_indices),
        (3 * one_indices, 3 * one_indices)
    );
}

#[test]
fn shared_copies_render_as_copies_that_own_their_geometry() {
    let gpu = gpu();
    let pipelines = [
        PipelineFile::gpu_branch("visibility_msaa_4x.ron"),
        PipelineFile::for_device("visibility_msaa_4x.ron"),
        PipelineFile::for_device("forward_msaa_4x.ron"),
    ];
    for pipeline in pipelines {
        let [shared, own] = [true, false].map(|shared| {
            Render::new(pipeline, "builtin:spheres", (160, 96))
                .with_scene(with_copies(shared))
                .run(&gpu)
                .image(&gpu, "color")
        });
        // The copies are in view: the image differs from the scene without them.
        let original = Render::new(pipeline, "builtin:spheres", (160, 96))
            .run(&gpu)
            .image(&gpu, "color");
        assert_ne!(
            original.pixels, own.pixels,
            "{pipeline}: the copies are not seen"
        );
        let differing = (shared.pixels.iter().zip(&own.pixels))
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(differing, 0, "{pipeline}: pixels differ");
    }
}
