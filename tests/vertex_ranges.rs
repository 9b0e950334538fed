//! The visibility passes pull the scene's vertices through up to 4 storage ranges of the
//! vertex buffer (passes' gpu_scene/vertex_ranges.rs, geometry.wgsl), so that a scene may
//! hold more vertex bytes than the device binds at once (issue 38's 100M-triangle terrain:
//! 2.8 GB of vertices against an H100's 2 GiB bindings).
//!
//! lavapipe binds 128 MiB, too much to reach cheaply, so these tests render on a device
//! an engine opened itself, as the embedding API allows (`Executor::from_device`): lavapipe
//! with `max_storage_buffer_binding_size` lowered to 6 MiB and the storage offset alignment
//! raised to 256 bytes (windows of a multiple of 32 vertices). There the 500k-triangle
//! terrain's 251,001 vertices (14 MB) take 3 ranges, the boundaries inside its one mesh,
//! and every image of the default pipeline (colour and debug views, through the compute
//! raster and the hardware raster, the latter with alpha MASK cut by vertex alpha) is the
//! image of the same frame on the normal device, which binds them in one range, bit for
//! bit. A scene past 4 ranges, or with more vertices than the device holds in one buffer,
//! is an error naming the bytes and the limit.

use std::sync::OnceLock;

use rgraph_core::gpu::Gpu;
use rgraph_core::DeviceProfile;

use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::glam::DVec3;
use rgraph_scene::Scene;

use crate::deferred_support::{gpu, unchanged, Image, PipelineFile, Render};

/// The GPU branch of the default pipeline: the compute raster.
const COMPUTE: PipelineFile = PipelineFile::gpu_branch("visibility_msaa_4x.ron");
/// The default pipeline as lavapipe runs it: the hardware raster.
const HARDWARE: PipelineFile = PipelineFile::for_device("visibility_msaa_4x.ron");
const SIZE: (u32, u32) = (160, 96);
/// 501^2 vertices: three ranges of the limited device.
const TERRAIN: &str = "builtin:terrain?cells=500";
/// The limited device's storage binding limit: above every other binding these frames
/// make (the default pipeline's "occluded" buffer, 4 MiB, is the largest), below the
/// terrain's vertices.
const BINDING: u64 = 6 << 20;
const ALIGNMENT: u32 = 256;

/// An engine's device on the adapter the tests use, opened with `limits` changed by
/// `change`: the device, its queue and its profile. From the tests' own instance: the
/// plugins tell devices apart by wgpu's device IDs, which each instance numbers from one.
fn engine_device(change: fn(&mut wgpu::Limits)) -> (wgpu::Device, wgpu::Queue, DeviceProfile) {
    let adapter = gpu().adapter.clone();
    let mut limits = adapter.limits();
    change(&mut limits);
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("engine device"),
        required_features: Gpu::DEFAULT_FEATURES & adapter.features(),
        required_limits: limits,
        ..Default::default()
    }))
    .unwrap_or_else(|e| panic!("the adapter refused the lowered limits: {e}"));
    let profile = DeviceProfile {
        limits: device.limits(),
        features: device.features(),
        ..DeviceProfile::from_adapter(&adapter)
    };
    (device, queue, profile)
}

/// The device binding [`BINDING`] bytes at offsets of [`ALIGNMENT`], one per test process
/// (the plugins keep their pipelines per device).
fn limited() -> &'static (wgpu::Device, wgpu::Queue, DeviceProfile) {
    static DEVICE: OnceLock<(wgpu::Device, wgpu::Queue, DeviceProfile)> = OnceLock::new();
    DEVICE.get_or_init(|| {
        engine_device(|limits| {
            limits.max_storage_buffer_binding_size = BINDING;
            limits.min_storage_buffer_offset_alignment = ALIGNMENT;
        })
    })
}

/// `views` of the second frame of `render` on the normal device and on the limited one:
/// the scene's camera, then orbited by 3 degrees (so that the motion view shows motion).
fn on_both(render: Render<'_>, views: &[&str]) -> Vec<(String, Image, Image)> {
    let gpu = gpu();
    let (device, queue, profile) = limited();
    let mut normal = render.run(&gpu);
    let mut ranged = render
        .try_run_on((device, queue), profile.clone())
        .unwrap_or_else(|e| panic!("{e}"));
    let mut inputs = normal.inputs();
    let center = render
        .given_scene
        .as_ref()
        .map_or(DVec3::ZERO, |s| s.bounds.center());
    inputs.camera = inputs.camera.orbited(center, 3f64.to_radians());
    normal.next(inputs.clone());
    ranged.next(inputs);
    (views.iter())
        .map(|view| {
            (
                view.to_string(),
                normal.image(&gpu, view),
                ranged.image_from((device, queue), view),
            )
        })
        .collect()
}

fn assert_same(render: Render<'_>, views: &[&str], what: &str) {
    for (view, one, ranged) in on_both(render, views) {
        let differing = (one.pixels.iter().zip(&ranged.pixels))
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differing, 0,
            "{what}, {view}: {differing} pixels differ between one range and three"
        );
        // A view of nothing would pass whatever the ranges held.
        let first = one.pixels[0];
        assert!(
            one.pixels.iter().any(|&p| p != first),
            "{what}, {view}: the image is one colour"
        );
    }
}

/// The terrain edited by `edit` through `pipeline`, compiled for its features as
/// `rgraph render` compiles it (the shadows and alpha MASK passes run only where they say
/// so), with shadow maps of 1024^2 texels (the compute raster's keys, 4 bytes a texel, a
/// binding within the limited device's).
fn terrain(pipeline: PipelineFile<'static>, edit: fn(&mut Scene)) -> Render<'static> {
    let mut scene = Scene::load(TERRAIN).expect("the terrain loads");
    edit(&mut scene);
    let features = SceneFeatures::of(&scene).names();
    Render::new(pipeline, TERRAIN, SIZE)
        .with_scene(scene)
        .features(features)
        .param("shadow_map", 1024)
}

#[test]
fn the_terrain_is_the_same_through_three_vertex_ranges() {
    // The vertices the device's ranges hold: 3 ranges, the last partly filled.
    let window = BINDING / 1792 * 1792 / 56;
    let vertices = 501u64 * 501;
    assert!(2 * window < vertices && vertices < 3 * window);
    assert_same(
        terrain(COMPUTE, unchanged),
        &[
            "color",
            "debug.edges",
            "debug.fragments",
            "debug.shadows",
            "debug.motion",
        ],
        "the compute raster",
    );
    assert_same(
        terrain(HARDWARE, crate::visibility::masked_by_height),
        &["color", "debug.edges", "debug.shadows"],
        "the hardware raster, alpha MASK by vertex alpha",
    );
}

/// 140 x 140 buildings of 24 vertices each: 26.3 MB, past four 6 MiB ranges, their
/// indices (2.8 MB) and mesh records within one.
const CITY: &str = "builtin:city?blocks=140";

#[test]
fn vertices_past_every_range_are_an_error_naming_them_and_the_limit() {
    let (device, queue, profile) = limited();
    let error = Render::new(COMPUTE, CITY, SIZE)
        .try_run_on((device, queue), profile.clone())
        .err()
        .expect("a scene past every range renders nothing");
    let bytes = (140 * 140 * 24 + 4) * 56;
    for part in [
        format!("the scene's vertices take {bytes} bytes"),
        "4 ranges of 6289920 bytes".to_string(),
        format!("at most {BINDING} bytes, max_storage_buffer_binding_size"),
        "use a G-buffer pipeline".to_string(),
    ] {
        assert!(error.contains(&part), "expected {part:?} in: {error}");
    }
}

#[test]
fn vertices_past_the_largest_buffer_are_an_error_naming_them_and_the_limit() {
    const MAX_BUFFER: u64 = 8 << 20;
    let (device, queue, profile) = engine_device(|limits| limits.max_buffer_size = MAX_BUFFER);
    let error = Render::new(COMPUTE, TERRAIN, SIZE)
        .try_run_on((&device, &queue), profile)
        .err()
        .expect("a vertex buffer past the device's largest renders nothing");
    let part = format!(
        "the scene's vertices take {} bytes, more than the {MAX_BUFFER} bytes this device \
         holds in one buffer (max_buffer_size)",
        501 * 501 * 56
    );
    assert!(error.contains(&part), "expected {part:?} in: {error}");
}
