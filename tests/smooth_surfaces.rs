//! One lighting per smooth surface (issue 38): the default pipeline's tiled pass
//! (`shading: surfaces`) joins the samples of a pixel that show different triangles of
//! one smooth surface into one fragment (visibility_read.wgsl's smooth_join), rebuilds each
//! triangle at its own samples and lights their mean once. Against the same pipeline with
//! each triangle its own fragment (`shading: adaptive`, the default before), on both of
//! its raster branches: the dense heightfield is lit at most 1.2 times a pixel where it
//! was lit more than 1.4 times, and every built-in scene's image stays within 1/255 on 99% of
//! its pixels.

use crate::deferred_support::measure::pixels_within;
use crate::deferred_support::{gpu, Image, PipelineFile, Render};

/// The hardware raster on lavapipe.
const VISIBILITY: PipelineFile = PipelineFile::for_device("visibility_msaa_4x.ron");
/// The compute raster, as on a GPU.
const COMPUTE: PipelineFile = PipelineFile::gpu_branch("visibility_msaa_4x.ron");
/// The shipped setting, and the one before it.
const SURFACES: &str = "shading: surfaces";
const ADAPTIVE: &str = "shading: adaptive";
const SIZE: (u32, u32) = (320, 180);
/// builtin:terrain's 100,352 triangles cover about as many pixels at 640x360: the density
/// of issue 38's 10M-triangle heightfield at 3840x2160 (1.2 triangles a pixel).
const HEIGHTFIELD_SIZE: (u32, u32) = (640, 360);

/// Lightings per pixel, as `rgraph bench` counts them (its work.rs): the fragments view's
/// count at each edge pixel of the edges view (red), one at every other pixel.
fn lightings_per_pixel(edges: &Image, fragments: &Image) -> f64 {
    let lit: usize = (edges.pixels.iter().zip(&fragments.pixels))
        .map(|(e, f)| match (*e == [255, 0, 0, 255], f) {
            (false, _) => 1,
            (true, [0, 255, 0, _]) => 2,
            (true, [0, 0, 255, _]) => 3,
            (true, [255, 0, 0, _]) => 4,
            (true, _) => 1,
        })
        .sum();
    lit as f64 / edges.pixels.len() as f64
}

fn lightings(pipeline: PipelineFile<'static>, shading: &'static str) -> f64 {
    let views = Render::new(pipeline, "builtin:terrain", HEIGHTFIELD_SIZE)
        .edit(SURFACES, shading)
        .read(&gpu(), &["debug.edges", "debug.fragments"]);
    lightings_per_pixel(&views[0], &views[1])
}

/// builtin:terrain's 100,352 triangles at 640x360, about one a pixel: lit at most 1.2
/// times a pixel with its triangles joined, more than 1.4 times without.
#[test]
fn a_dense_heightfield_is_lit_at_most_1_2_times_a_pixel() {
    for pipeline in [VISIBILITY, COMPUTE] {
        let joined = lightings(pipeline, SURFACES);
        let apart = lightings(pipeline, ADAPTIVE);
        assert!(
            joined <= 1.2 && apart > 1.4,
            "{pipeline}: {joined:.3} lightings per pixel with smooth surfaces joined, \
             {apart:.3} with each triangle apart"
        );
    }
}

/// Faceted triangles (no vertex normals: each lit with its face normal) are never
/// joined: builtin:terrain with its normals zeroed is lit as often either way.
#[test]
fn facets_are_not_joined() {
    let gpu = gpu();
    let views = |shading: &'static str| {
        Render::new(VISIBILITY, "builtin:terrain", SIZE)
            .scene_edit(|scene| {
                for vertex in scene
                    .meshes
                    .iter_mut()
                    .flat_map(|m| std::sync::Arc::make_mut(&mut m.vertices).iter_mut())
                {
                    vertex.normal = [0.0; 3];
                }
            })
            .edit(SURFACES, shading)
            .read(&gpu, &["debug.edges", "debug.fragments"])
    };
    let (joined, apart) = (views(SURFACES), views(ADAPTIVE));
    assert_eq!(
        lightings_per_pixel(&joined[0], &joined[1]),
        lightings_per_pixel(&apart[0], &apart[1]),
        "a faceted mesh's triangles were joined"
    );
}

/// Every built-in scene renders what it rendered with each triangle apart, within 1/255
/// at 99% of its pixels (the project's bound for one image against another, issue 35) (the joined fragments' lighting of their mean surface differs
/// from the mean of their lightings only where lighting bends within a pixel: highlights).
#[test]
fn joined_surfaces_keep_every_builtin_image() {
    let gpu = gpu();
    for scene in [
        "builtin:spheres",
        "builtin:dense",
        "builtin:lights",
        "builtin:terrain",
        "builtin:city",
        "builtin:unlit",
        "builtin:smoke",
    ] {
        let color = |shading: &'static str| {
            Render::new(VISIBILITY, scene, SIZE)
                .edit(SURFACES, shading)
                .read(&gpu, &["color"])
                .remove(0)
        };
        let (joined, apart) = (color(SURFACES), color(ADAPTIVE));
        let within = pixels_within(&joined, &apart, 1) as f64 / joined.pixels.len() as f64;
        assert!(
            within >= 0.99,
            "{scene}: {:.2}% of pixels within 1/255 of each triangle apart",
            within * 100.0
        );
    }
}
