//! Motion vectors (passes/motion_vectors.rs) against the motion a CPU ray cast expects:
//! the surface the ray through a pixel's centre (a depth buffer's: its sample 0) meets, projected with this frame's and
//! the previous frame's camera and transform, moved by their difference. Checked at every
//! fourth pixel whose centre and sample 0 see one face (sample 0's triangle is the one the
//! pass takes), within [`TOLERANCE`] pixels, for a camera orbit and a moving object, in
//! the default pipeline's three ways of reading surfaces: a raster pass's IDs (lavapipe's
//! branch), a compute rasteriser's keys (the GPU branch), and a G-buffer's depth (feature
//! `untabled_textures`): with its mesh channel (the TAA preset's G-buffer), whose points
//! move with their meshes, and without (the default pipeline's), whose points move with the
//! camera alone, so it is checked on the orbit only.

use rgraph_core::Features;
use rgraph_passes::gpu_scene::jitter;
use rgraph_scene::glam::{DMat4, DVec2, DVec3, DVec4};
use rgraph_scene::{Camera, DepthConvention, Projection, Scene};

use crate::deferred_support::scenes::Parts;
use crate::deferred_support::{gpu, PipelineFile, Render};

const SIZE: (u32, u32) = (96, 64);
/// Pixels: the half floats the motion is stored in hold these values to 1/128 pixel, and
/// the pass's f32 ray-plane hit is as close.
const TOLERANCE: f64 = 0.05;
const DEFAULT: PipelineFile = PipelineFile::for_device("visibility_msaa_4x.ron");
const DEFAULT_GPU: PipelineFile = PipelineFile::gpu_branch("visibility_msaa_4x.ron");
/// The default pipeline with TAA, whose G-buffer (untabled textures) records meshes.
const TAA: PipelineFile = PipelineFile::for_device("msaa_4x_taa.ron");
/// Sample 0 of 4 within the pixel (WebGPU's standard positions).
const SAMPLE_0: DVec2 = DVec2::new(0.375, 0.125);

/// A floor, a box on it (mesh 1) and sky above the horizon.
fn parts() -> Parts {
    let mut parts = Parts::new();
    let grey = parts.material("floor", [0.5, 0.5, 0.5], 0.8);
    let red = parts.material("box", [0.8, 0.2, 0.1], 0.5);
    let floor = [
        DVec3::new(-4.0, 0.0, 4.0),
        DVec3::new(4.0, 0.0, 4.0),
        DVec3::new(4.0, 0.0, -4.0),
        DVec3::new(-4.0, 0.0, -4.0),
    ];
    parts.mesh("floor", &[floor.to_vec()], grey);
    parts.cuboid(
        "box",
        DVec3::new(-0.5, 0.0, -0.5),
        DVec3::new(0.5, 1.0, 0.5),
        red,
    );
    parts.ambient = [0.3; 3];
    parts
}

fn camera() -> Camera {
    let projection = Projection::Perspective {
        yfov: 0.9,
        znear: 0.1,
        zfar: None,
    };
    let eye = DVec3::new(1.0, 1.6, 4.0);
    Camera::look_at(
        "motion",
        eye,
        DVec3::new(0.0, 0.8, 0.0),
        DVec3::Y,
        projection,
    )
}

/// World to clip space of `camera` for the output.
fn clip(camera: &Camera) -> DMat4 {
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    camera
        .projection_matrix(aspect, DepthConvention::Standard)
        .as_dmat4()
        * camera.view_matrix()
}

/// The pixel coordinate of homogeneous world point (or direction, w = 0) `p`.
fn pixel_of(clip: DMat4, p: DVec4) -> DVec2 {
    let c = clip * p;
    let ndc = DVec2::new(c.x / c.w, c.y / c.w);
    DVec2::new(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * DVec2::new(SIZE.0 as f64, SIZE.1 as f64)
}

/// The unit direction of the ray through pixel coordinate `at` of `camera`.
fn ray(camera: &Camera, at: DVec2) -> DVec3 {
    let inverse = clip(camera).inverse();
    let ndc = DVec2::new(
        at.x / SIZE.0 as f64 * 2.0 - 1.0,
        1.0 - at.y / SIZE.1 as f64 * 2.0,
    );
    let point = |z: f64| inverse.project_point3(DVec3::new(ndc.x, ndc.y, z));
    (point(0.5) - point(0.25)).normalize()
}

/// The motion expected at each checked pixel of a frame drawn with `now` after one drawn
/// with `before` (the box's previous transform `box_before`, its current the identity),
/// of the point seen at `within` the pixel.
fn expected(
    now: &Camera,
    before: &Camera,
    box_before: DMat4,
    within: DVec2,
) -> Vec<((u32, u32), DVec2)> {
    let parts = parts();
    let box_faces = 1..7;
    let (clip_now, clip_before) = (clip(now), clip(before));
    let mut checked = Vec::new();
    for y in (1..SIZE.1).step_by(4) {
        for x in (1..SIZE.0).step_by(4) {
            let corner = DVec2::new(x as f64, y as f64);
            let centre = corner + within;
            let hit = parts.cast(now.position, ray(now, centre));
            let at_sample = parts.cast(now.position, ray(now, corner + SAMPLE_0));
            if hit.map(|h| h.polygon) != at_sample.map(|h| h.polygon) {
                continue;
            }
            let (here, there) = match hit {
                None => {
                    let d = ray(now, centre).extend(0.0);
                    (pixel_of(clip_now, d), pixel_of(clip_before, d))
                }
                Some(hit) => {
                    let p = hit.point.extend(1.0);
                    let moved = match box_faces.contains(&hit.polygon) {
                        true => box_before * p,
                        false => p,
                    };
                    (pixel_of(clip_now, p), pixel_of(clip_before, moved))
                }
            };
            checked.push(((x, y), here - there));
        }
    }
    checked
}

/// Renders two frames of the scene (the first with `before` and the box at `box_before`,
/// the second with `now` and the box at rest) through `pipeline` compiled for
/// `features`, and checks the second's motion against [`expected`]'s.
fn check(pipeline: PipelineFile, features: Features, moves: (&Camera, &Camera, DMat4)) {
    let (now, before, box_before) = moves;
    let mut scene: Scene = parts().scene("motion", before.clone());
    scene.meshes[1].transform = box_before;
    let gpu = gpu();
    let mut frame = Render::new(pipeline, "motion", SIZE)
        .with_scene(scene)
        .features(features.clone())
        .edit("outputs: [\"color\", ", "outputs: [\"motion\", \"color\", ")
        .run(&gpu);
    let mut inputs = frame.inputs();
    inputs.camera = now.clone();
    inputs.transforms[1] = DMat4::IDENTITY;
    frame.next(inputs);
    let motion = frame.hdr(&gpu, "motion");
    // A visibility buffer's motion is its triangle's at the pixel's centre; a depth
    // buffer's the point sample 0 holds (motion_depth.wgsl), which a jittered frame
    // (TAA's: the second frame is frame 1, jittered by half a pixel's span at 4x) shows
    // moved by the jitter.
    let within = match features.contains("untabled_textures") {
        true => SAMPLE_0,
        false => DVec2::splat(0.5),
    };
    let within = match pipeline == TAA {
        true => within - DVec2::from(jitter(1).map(f64::from)) * 0.5,
        false => within,
    };
    let checked = expected(now, before, box_before, within);
    let mut worst = (0.0, (0, 0), DVec2::ZERO, DVec2::ZERO);
    for &((x, y), want) in &checked {
        let got = motion[(y * SIZE.0 + x) as usize];
        let got = DVec2::new(f64::from(got[0]), f64::from(got[1]));
        let error = (got - want).length();
        if error > worst.0 {
            worst = (error, (x, y), got, want);
        }
    }
    let moving = checked.iter().filter(|(_, m)| m.length() > 1.0).count();
    assert!(
        moving >= 15,
        "{pipeline}: only {moving} of {} pixels moved over a pixel: the test moves too little",
        checked.len()
    );
    let (error, at, got, want) = worst;
    println!(
        "{pipeline} {features:?}: {} pixels, worst error {error:.4} px at {at:?}",
        checked.len()
    );
    assert!(
        error <= TOLERANCE,
        "{pipeline} {features:?}: motion {got:?} at {at:?}, expected {want:?} ({error:.4} px off)"
    );
}

/// The camera turned 6 degrees about the box, nothing else moving.
fn orbit() -> (Camera, Camera, DMat4) {
    let before = camera();
    let now = before.orbited(DVec3::new(0.0, 0.5, 0.0), 6f64.to_radians());
    (now, before, DMat4::IDENTITY)
}

/// The box moved 0.2 right and 0.1 up, nothing else moving.
fn moving_box() -> (Camera, Camera, DMat4) {
    let shift = DMat4::from_translation(DVec3::new(-0.2, -0.1, 0.0));
    (camera(), camera(), shift)
}

#[test]
fn an_orbit_moves_every_pixel_as_the_camera_turns() {
    let (now, before, box_before) = orbit();
    for pipeline in [DEFAULT, DEFAULT_GPU] {
        check(pipeline, Features::new(), (&now, &before, box_before));
    }
    check(DEFAULT, gbuffer(), (&now, &before, box_before));
    check(TAA, gbuffer(), (&now, &before, box_before));
}

/// The features that make the default pipeline take its G-buffer.
fn gbuffer() -> Features {
    ["untabled_textures".to_string()].into_iter().collect()
}

#[test]
fn a_moving_object_moves_its_own_pixels() {
    let (now, before, box_before) = moving_box();
    for pipeline in [DEFAULT, DEFAULT_GPU] {
        check(pipeline, Features::new(), (&now, &before, box_before));
    }
    check(TAA, gbuffer(), (&now, &before, box_before));
}

/// A G-buffer's mesh channel composes a mesh's motion with the camera's.
#[test]
fn a_moving_object_seen_by_an_orbiting_camera_moves_by_both() {
    let (now, before, _) = orbit();
    let (_, _, box_before) = moving_box();
    check(TAA, gbuffer(), (&now, &before, box_before));
}

#[test]
fn a_first_frame_has_no_motion() {
    let gpu = gpu();
    let frame = Render::new(DEFAULT, "motion", SIZE)
        .with_scene(parts().scene("motion", camera()))
        .edit("outputs: [\"color\", ", "outputs: [\"motion\", \"color\", ")
        .run(&gpu);
    let motion = frame.hdr(&gpu, "motion");
    let moved = motion.iter().filter(|m| m[0] != 0.0 || m[1] != 0.0).count();
    assert_eq!(moved, 0, "{moved} pixels of a first frame have motion");
}

/// A mesh channel is for a depth buffer's points: a compute rasteriser's keys hold their
/// triangles already, and `rgraph validate` says so, naming the pass.
#[test]
fn a_mesh_channel_beside_keys_is_refused() {
    let edited = crate::common::copied_pipeline(
        "msaa_4x_taa.ron",
        &[(
            "\"motion vectors (untabled textures)\": (inputs: { \"depth\": \"depth\", \"mesh\": \"mesh\" }),",
            "\"motion vectors\": (inputs: { \"samples\": \"samples\", \"mesh\": \"mesh\" }),",
        )],
    );
    let path = edited.path.to_str().expect("temp paths are UTF-8");
    let run = crate::cli_support::rgraph(&["validate", path]).expect(1);
    let says = "pass \"motion vectors\" (motion_vectors): input \"mesh\" names a G-buffer's \
                meshes, but the keys of input \"samples\" hold their triangles already";
    assert!(run.stdout.contains(says), "{}", run.stdout);
}

/// A morph target that stretches a quad moves its pixels though no transform changes:
/// the visibility buffer's point is taken back to where the deformation found the
/// triangle's vertices (both raster branches); in the next frame, whose pose stays, they
/// stand still. The quad (x 0..1, y 0..h in the plane
/// z = 0) has its top edge at h = 1 + 0.5 w for morph weight w, so a point at height y
/// was at y h_before / h_now.
#[test]
fn a_morph_target_moves_its_pixels() {
    let mut scene = crate::deformation::load(&crate::gltf_writer::deformed::morphed_quad("LINEAR"));
    assert_eq!(
        scene.meshes[0].transform,
        DMat4::IDENTITY,
        "the quad is placed by an identity transform"
    );
    let projection = Projection::Perspective {
        yfov: 0.9,
        znear: 0.1,
        zfar: None,
    };
    let eye = DVec3::new(0.5, 0.75, 2.2);
    scene.camera = Camera::look_at(
        "quad",
        eye,
        DVec3::new(0.5, 0.75, 0.0),
        DVec3::Y,
        projection,
    );
    let (weight_before, weight_now) = (0.25, 1.0);
    let (h_before, h_now) = (1.0 + 0.5 * weight_before, 1.0 + 0.5 * weight_now);
    let clip_now = clip(&scene.camera);
    // The point of the quad's plane a pixel coordinate sees, if the quad is there now.
    let on_quad = |at: DVec2| {
        let d = ray(&scene.camera, at);
        let p = eye + d * (-eye.z / d.z);
        (p.x > 0.0 && p.x < 1.0 && p.y > 0.0 && p.y < h_now).then_some(p)
    };
    let gpu = gpu();
    let features = rgraph_scene::analysis::Features::of(&scene).names();
    for pipeline in [DEFAULT, DEFAULT_GPU] {
        let mut frame = Render::new(pipeline, "quad", SIZE)
            .with_scene(scene.clone())
            .features(features.clone())
            .edit("outputs: [\"color\", ", "outputs: [\"motion\", \"color\", ")
            .run(&gpu);
        let mut inputs = frame.inputs();
        assert_eq!(inputs.morph_weights, vec![vec![weight_before as f32]]);
        inputs.morph_weights[0][0] = weight_now as f32;
        frame.next(inputs);
        let motion = frame.hdr(&gpu, "motion");
        let (mut checked, mut moving, mut worst) = (0, 0, (0.0, (0, 0), DVec2::ZERO, DVec2::ZERO));
        for y in 0..SIZE.1 {
            for x in 0..SIZE.0 {
                let corner = DVec2::new(x as f64, y as f64);
                let (Some(p), Some(_)) = (on_quad(corner + 0.5), on_quad(corner + SAMPLE_0)) else {
                    continue;
                };
                let before = DVec3::new(p.x, p.y * h_before / h_now, 0.0);
                let want =
                    pixel_of(clip_now, p.extend(1.0)) - pixel_of(clip_now, before.extend(1.0));
                let got = motion[(y * SIZE.0 + x) as usize];
                let got = DVec2::new(f64::from(got[0]), f64::from(got[1]));
                let error = (got - want).length();
                if error > worst.0 {
                    worst = (error, (x, y), got, want);
                }
                checked += 1;
                moving += usize::from(want.length() > 1.0);
            }
        }
        assert!(
            moving >= 100,
            "{pipeline}: only {moving} of {checked} pixels moved over a pixel"
        );
        let (error, at, got, want) = worst;
        println!("{pipeline}: {checked} pixels, worst error {error:.4} px at {at:?}");
        assert!(
            error <= TOLERANCE,
            "{pipeline}: motion {got:?} at {at:?}, expected {want:?} ({error:.4} px off)"
        );
        // A frame whose pose stays: nothing moves.
        let inputs = frame.inputs();
        frame.next(inputs);
        let motion = frame.hdr(&gpu, "motion");
        let moved = motion.iter().filter(|m| m[0] != 0.0 || m[1] != 0.0).count();
        assert_eq!(
            moved, 0,
            "{pipeline}: {moved} pixels moved in a frame whose pose stayed"
        );
    }
}
