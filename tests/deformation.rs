//! Skinning and morphing on the GPU: a skinned strip, a strip whose vertices hang on eight
//! joints each (JOINTS_0 and JOINTS_1) and a morphed quad render, in every raster path (hardware and compute visibility rasters, G-buffer, forward), as their
//! copies deformed on the CPU (`Deformation::deform`) and drawn as static meshes do,
//! within 1/255, at rest and in an animation's pose set through the frame inputs.

use rgraph_passes::FrameInputs;
use rgraph_scene::{joints_in_object_space, Lighting, Pose, Scene};

use crate::deferred_support::measure::share_within;
use crate::deferred_support::{gpu, Image, PipelineFile, Render};
use crate::gltf_writer::deformed::{bent_strip, eight_joint_strip, morphed_quad};
use crate::gltf_writer::Gltf;

const SIZE: (u32, u32) = (96, 64);

/// The raster paths that read the scene's vertices.
const PIPELINES: [PipelineFile; 4] = [
    PipelineFile::for_device("visibility_msaa_4x.ron"),
    PipelineFile::gpu_branch("visibility_msaa_4x.ron"),
    PipelineFile::for_device("deferred_msaa_4x.ron"),
    PipelineFile::for_device("forward_msaa_4x.ron"),
];

/// `gltf` loaded and lit as `rgraph render` lights a file without lights (the studio
/// environment and a headlight, which casts shadows: the shadow maps draw it too).
pub(crate) fn load(gltf: &Gltf) -> Scene {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join("deformed.gltf");
    gltf.write_embedded(&path);
    let scene = Scene::from_gltf(&path).expect("the model loads");
    scene.lit(Lighting::Auto)
}

/// `scene` in `pose` as static meshes: each deformed mesh's vertices deformed on the CPU,
/// every mesh at its pose's transform, no skins or deformations left. Its camera and
/// bounds stay, so that both render with one camera and one plan.
fn deformed_on_the_cpu(scene: &Scene, pose: &Pose) -> Scene {
    let mut copy = scene.clone();
    for (d, weights) in scene.deformations.iter().zip(&pose.morph_weights) {
        let transform = pose.transforms[d.mesh];
        let joints = match &d.skin {
            Some(skin) => joints_in_object_space(transform, &pose.skins[skin.skin]),
            None => Vec::new(),
        };
        let deformed = d.deform(&scene.meshes[d.mesh].vertices, &joints, weights);
        copy.meshes[d.mesh].vertices = deformed.into();
    }
    for (mesh, transform) in copy.meshes.iter_mut().zip(&pose.transforms) {
        mesh.transform = *transform;
    }
    (copy.skins, copy.deformations) = (Vec::new(), Vec::new());
    copy
}

/// The colour of `scene` through `pipeline`, posed by `pose` in a second frame when given.
fn render(pipeline: PipelineFile, scene: &Scene, pose: Option<&Pose>) -> Image {
    let gpu = gpu();
    let features = rgraph_scene::analysis::Features::of(scene).names();
    let mut frame = Render::new(pipeline, &scene.name, SIZE)
        .with_scene(scene.clone())
        .features(features)
        .run(&gpu);
    if let Some(pose) = pose {
        let mut inputs = FrameInputs::of(scene);
        inputs.set_pose(pose.clone());
        frame.next(inputs);
    }
    frame.image(&gpu, "color")
}

/// Asserts that `scene` in `pose` (the rest pose when `None`) renders as its CPU-deformed
/// copy through every pipeline, which draws something.
fn assert_matches_cpu(scene: &Scene, pose: Option<&Pose>, what: &str) {
    let reference = deformed_on_the_cpu(scene, pose.unwrap_or(&scene.rest_pose()));
    for pipeline in PIPELINES {
        let on_gpu = render(pipeline, scene, pose);
        let on_cpu = render(pipeline, &reference, None);
        let background = on_cpu.pixels[0];
        let drawn = on_cpu.pixels.iter().filter(|&&p| p != background).count();
        assert!(
            drawn > 200,
            "{what} through {pipeline}: only {drawn} pixels drawn"
        );
        let share = share_within(&on_gpu, &on_cpu, 1, None);
        for (i, (p, q)) in on_gpu.pixels.iter().zip(&on_cpu.pixels).enumerate() {
            if p != q {
                eprintln!(
                    "DEBUG {what} {pipeline} ({}, {}) gpu {p:?} cpu {q:?}",
                    i % 96,
                    i / 96
                );
            }
        }

        assert_eq!(
            share,
            1.0,
            "{what} through {pipeline}: {:.4}% of the pixels differ by more than 1/255 from \
             the CPU-deformed copy",
            (1.0 - share) * 100.0
        );
    }
}

#[test]
fn a_skinned_mesh_renders_as_its_cpu_deformed_copy_at_rest_and_animated() {
    let scene = load(&bent_strip());
    assert_matches_cpu(&scene, None, "the strip at rest");
    let id = scene.find_animation("bend").expect("the animation");
    let pose = scene.animated_pose(id, 0.3);
    assert_matches_cpu(&scene, Some(&pose), "the strip at 0.3 s");
}

/// Eight influences per vertex, half the weight on JOINTS_1's joints (one of which the
/// animation turns): the GPU blends all eight as the CPU does.
#[test]
fn a_mesh_with_eight_influences_renders_as_its_cpu_deformed_copy_at_rest_and_animated() {
    let scene = load(&eight_joint_strip());
    assert!(scene.deformations[0]
        .skin
        .as_ref()
        .unwrap()
        .second
        .is_some());
    assert_matches_cpu(&scene, None, "the eight-joint strip at rest");
    let id = scene.find_animation("sway").expect("the animation");
    let pose = scene.animated_pose(id, 0.5);
    assert_matches_cpu(&scene, Some(&pose), "the eight-joint strip at 0.5 s");
}

#[test]
fn a_morphed_mesh_renders_as_its_cpu_deformed_copy_at_rest_and_animated() {
    let scene = load(&morphed_quad("LINEAR"));
    assert_matches_cpu(&scene, None, "the quad at rest");
    let id = scene.find_animation("grow").expect("the animation");
    let pose = scene.animated_pose(id, 0.8);
    assert_matches_cpu(&scene, Some(&pose), "the quad at 0.8 s");
}

#[test]
fn frame_inputs_whose_joints_or_weights_do_not_fit_the_scene_are_refused() {
    use rgraph_passes::{FrameInputsError, Host, Overrides};
    let scene = load(&bent_strip());
    let host = Host::new(std::sync::Arc::new(scene.clone()), Overrides::default());
    let mut inputs = FrameInputs::of(&scene);
    inputs.skins[0].pop();
    assert_eq!(
        host.set_frame(inputs).unwrap_err(),
        FrameInputsError::PoseCount {
            scene: scene.name.clone(),
            what: "joint matrices for skin 0 \"arm\"".to_owned(),
            given: 1,
            expected: 2,
        }
    );
    let mut inputs = FrameInputs::of(&scene);
    inputs.morph_weights[0].push(0.5);
    let error = host.set_frame(inputs).unwrap_err().to_string();
    assert_eq!(
        error,
        format!(
            "frame inputs give 1 morph weights for mesh 0 \"strip\" primitive 0, but scene \
             \"{}\" has 0",
            scene.name
        )
    );
    let mut inputs = FrameInputs::of(&scene);
    inputs.skins[0][1].w_axis.x = f64::NAN;
    assert!(matches!(
        host.set_frame(inputs),
        Err(FrameInputsError::NotFinite { what, .. }) if what == "a joint matrix of skin 0 \"arm\""
    ));
}
