//! Frame inputs change the image without reloading: a camera, a light, an object or the
//! exposure changed through `Host::set_frame` between two frames of one executor renders
//! bit-identically (on lavapipe) to a fresh render of the scene loaded that way, and the
//! second frame creates no texture, buffer, pipeline or shader module. A new output size
//! is a recompile instead: one plan more, new targets, still no pipeline.

use rgraph_core::gpu::DeviceObjects;
use rgraph_passes::{Exposure, FrameInputs, Overrides};
use rgraph_scene::glam::{DMat4, DQuat, DVec3};
use rgraph_scene::Scene;

use crate::deferred_support::{gpu, Image, Render};

const SIZE: (u32, u32) = (96, 64);
/// Point and spot lights, drawn as volumes by the fragment light passes.
const SCENE: &str = "builtin:dense";
const PIPELINE: &str = "deferred_msaa_4x.ron";

/// Renders `render`'s scene as loaded, then a second frame with its frame inputs changed
/// by `change`; returns both images. Asserts the second frame made nothing new.
fn two_frames(render: Render<'_>, change: impl FnOnce(&mut FrameInputs)) -> (Image, Image) {
    let gpu = gpu();
    let mut frame = render.run(&gpu);
    let first = frame.image(&gpu, "color");
    let before = DeviceObjects::alive(&gpu.device);
    assert!(
        before.render_pipelines > 0,
        "no render pipeline counted: wgpu's counters feature is off"
    );
    let mut inputs = frame.inputs();
    change(&mut inputs);
    let report = frame.next(inputs);
    let second = frame.image(&gpu, "color");
    assert_eq!(
        (report.textures_allocated, report.buffers_allocated),
        (0, 0),
        "the second frame allocated graph resources"
    );
    assert_eq!(
        DeviceObjects::alive(&gpu.device).minus(&before),
        DeviceObjects::default(),
        "the second frame created device objects"
    );
    (first, second)
}

/// The fresh render of `scene` edited as `edit` says.
fn fresh(pipeline: &str, edit: impl FnOnce(&mut Scene), overrides: Overrides) -> Image {
    let gpu = gpu();
    let mut scene = Scene::load(SCENE).expect("the built-in scene loads");
    edit(&mut scene);
    Render::new(pipeline, SCENE, SIZE)
        .with_scene(scene)
        .overrides(overrides)
        .read(&gpu, &["color"])
        .remove(0)
}

fn assert_same(moved: &Image, fresh: &Image, what: &str) {
    let differing = (moved.pixels.iter().zip(&fresh.pixels))
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{what}: the frame moved through FrameInputs differs from a fresh render in \
         {differing} pixels"
    );
}

fn assert_changed(first: &Image, second: &Image, what: &str) {
    assert_ne!(
        first.pixels, second.pixels,
        "{what}: the image did not change"
    );
}

/// The camera of `scene` orbited 25 degrees about its bounds' centre.
fn orbit(scene_camera: &rgraph_scene::Camera, center: DVec3) -> rgraph_scene::Camera {
    scene_camera.orbited(center, 25f64.to_radians())
}

#[test]
fn a_camera_moved_through_frame_inputs_renders_as_a_fresh_load_from_it() {
    let center = Scene::load(SCENE).unwrap().bounds.center();
    for pipeline in [PIPELINE, "deferred_msaa_4x_tiled.ron"] {
        let (first, second) = two_frames(Render::new(pipeline, SCENE, SIZE), |inputs| {
            inputs.camera = orbit(&inputs.camera, center);
        });
        assert_changed(&first, &second, pipeline);
        let expected = fresh(
            pipeline,
            |scene| scene.camera = orbit(&scene.camera, center),
            Overrides::default(),
        );
        assert_same(&second, &expected, pipeline);
    }
}

#[test]
fn a_light_moved_through_frame_inputs_renders_as_a_fresh_load_with_it() {
    let offset = DVec3::new(0.8, 0.3, -0.6);
    let turn = DQuat::from_rotation_x(0.2).as_quat();
    let (first, second) = two_frames(Render::new(PIPELINE, SCENE, SIZE), |inputs| {
        for pose in &mut inputs.lights {
            pose.position += offset;
            pose.direction = turn * pose.direction;
        }
    });
    assert_changed(&first, &second, "lights");
    let expected = fresh(
        PIPELINE,
        |scene| {
            for light in &mut scene.lights {
                light.position += offset;
                light.direction = turn * light.direction;
            }
        },
        Overrides::default(),
    );
    assert_same(&second, &expected, "lights");
}

#[test]
fn an_object_moved_through_frame_inputs_renders_as_a_fresh_load_with_it() {
    let scene = Scene::load(SCENE).unwrap();
    // The mesh nearest the bounds' centre, so it stays in view.
    let center = scene.bounds.center();
    let (index, _) = scene
        .meshes
        .iter()
        .enumerate()
        .filter_map(|(i, m)| Some((i, m.world_bounds()?.center().distance(center))))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("the scene has meshes");
    let moved = |transform: DMat4| {
        DMat4::from_translation(DVec3::new(0.4, 0.25, 0.0))
            * transform
            * DMat4::from_rotation_y(0.5)
    };
    let (first, second) = two_frames(Render::new(PIPELINE, SCENE, SIZE), |inputs| {
        inputs.transforms[index] = moved(inputs.transforms[index]);
    });
    assert_changed(&first, &second, "object");
    let expected = fresh(
        PIPELINE,
        |scene| scene.meshes[index].transform = moved(scene.meshes[index].transform),
        Overrides::default(),
    );
    assert_same(&second, &expected, "object");
}

#[test]
fn an_exposure_set_through_frame_inputs_renders_as_the_exposure_override() {
    let (first, second) = two_frames(Render::new(PIPELINE, SCENE, SIZE), |inputs| {
        inputs.exposure = 2.0;
    });
    assert_changed(&first, &second, "exposure");
    let overrides = Overrides {
        exposure: Some(Exposure::Fixed(2.0)),
        ..Overrides::default()
    };
    assert_same(&second, &fresh(PIPELINE, |_| {}, overrides), "exposure");
}

#[test]
fn frame_inputs_that_do_not_fit_the_scene_are_refused_naming_it() {
    let scene = std::sync::Arc::new(Scene::load(SCENE).unwrap());
    let host = rgraph_passes::Host::new(scene.clone(), Overrides::default());
    let mut inputs = FrameInputs::of(&scene);
    inputs.transforms.pop();
    let error = host.set_frame(inputs).unwrap_err().to_string();
    assert!(
        error.contains("dense") && error.contains("mesh transforms"),
        "{error}"
    );
    let mut inputs = FrameInputs::of(&scene);
    inputs.lights[0].position.x = f64::NAN;
    let error = host.set_frame(inputs).unwrap_err().to_string();
    assert!(error.contains(&scene.lights[0].name), "{error}");
    assert_eq!(
        *host.frame(),
        FrameInputs::of(&scene),
        "refused inputs replaced the last good ones"
    );
}

#[test]
fn a_new_output_size_recompiles_the_plan_once_and_builds_no_pipeline() {
    let gpu = gpu();
    let pipeline = "deferred_msaa_4x_tiled.ron";
    let mut frame = Render::new(pipeline, SCENE, SIZE).run(&gpu);
    let before = DeviceObjects::alive(&gpu.device);
    let resized = frame.resize((SIZE.0 + 32, SIZE.1 + 16));
    let created = DeviceObjects::alive(&gpu.device).minus(&before);
    assert!(
        resized.textures_allocated > 0,
        "a larger output needs larger targets"
    );
    assert_eq!(
        (
            created.render_pipelines,
            created.compute_pipelines,
            created.shader_modules
        ),
        (0, 0, 0),
        "a new output size built pipelines: {created}"
    );
    // Back to the first size: its plan comes from the cache, its textures from the pool.
    let back = frame.resize(SIZE);
    assert_eq!(
        (frame.plans().misses(), frame.plans().hits()),
        (2, 1),
        "plans compiled and reused"
    );
    assert_eq!(
        back.textures_allocated, 0,
        "the pool kept the first size's textures"
    );
}
