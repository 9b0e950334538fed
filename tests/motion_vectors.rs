//! Motion vectors (passes/motion_vectors.rs) against the motion a CPU ray cast expects:
//! the surface the ray through a pixel's centre (a depth buffer's: its sample 0) meets, projected with this frame's and
//! the previous frame's camera and transform, moved by their difference. Checked at every
//! fourth pixel whose centre and sample 0 see one face (sample 0's triangle is the one the
//! pass takes), within [`TOLERANCE`] pixels, for a camera orbit and a moving object, in
//! the default pipeline's three ways of reading surfaces: a raster pass's IDs (lavapipe's
//! branch), a compute rasteriser's keys (the GPU branch), and a G-buffer's depth (feature
//! `untabled_textures`): with its mesh channel (the TAA preset's G-buffer), whose points
//! move with their meshes, and without (the default pipeline's), whose points move with the
//! camera alone, so it is checked on the orbit only. The texture's blue and alpha, the
//! point's view depth in this frame and in the previous one, within [`DEPTH_TOLERANCE`]
//! of theirs.

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
/// The share of a view depth the motion's blue (this frame's) and alpha (the previous
/// frame's, of the same point) may be off: half floats round to 1/2048 of a value.
const DEPTH_TOLERANCE: f64 = 0.002;
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

/// The view depth of world point `p` seen by `camera`.
fn view_depth(camera: &Camera, p: DVec4) -> f64 {
    (p.truncate() - camera.position).dot(camera.forward())
}

/// What the motion texture holds where nothing was drawn, in both frames' depth.
const FAR_AWAY: f64 = 65504.0;

/// What one checked pixel's motion should be: the motion in pixels, and the view depth
/// of its point in this frame and the previous one.
struct Expected {
    at: (u32, u32),
    motion: DVec2,
    depths: [f64; 2],
}

/// The motion expected at each checked pixel of a frame drawn with `now` after one drawn
/// with `before` (the box's previous transform `box_before`, its current the identity),
/// of the point seen at `within` the pixel.
fn expected(now: &Camera, before: &Camera, box_before: DMat4, within: DVec2) -> Vec<Expected> {
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
            let (here, there, depths) = match hit {
                None => {
                    let d = ray(now, centre).extend(0.0);
                    let far = [FAR_AWAY; 2];
                    (pixel_of(clip_now, d), pixel_of(clip_before, d), far)
                }
                Some(hit) => {
                    let p = hit.point.extend(1.0);
                    let moved = match box_faces.contains(&hit.polygon) {
                        true => box_before * p,
                        false => p,
                    };
                    let depths = [view_depth(now, p), view_depth(before, moved)];
                    (pixel_of(clip_now, p), pixel_of(clip_before, moved), depths)
                }
            };
            checked.push(Expected {
                at: (x, y),
                motion: here - there,
                depths,
            });
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
    let mut worst_depth = (0.0, (0, 0), [0.0; 2], [0.0; 2]);
    for Expected {
        at,
        motion: want,
        depths,
    } in &checked
    {
        let texel = motion[(at.1 * SIZE.0 + at.0) as usize];
        let got = DVec2::new(f64::from(texel[0]), f64::from(texel[1]));
        let error = (got - *want).length();
        if error > worst.0 {
            worst = (error, *at, got, *want);
        }
        let got_depths = [f64::from(texel[2]), f64::from(texel[3])];
        for (got, want) in got_depths.iter().zip(depths) {
            let error = (got / want - 1.0).abs();
            if error > worst_depth.0 {
                worst_depth = (error, *at, got_depths, *depths);
            }
        }
    }
    let moving = checked.iter().filter(|e| e.motion.length() > 1.0).count();
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
    let (error, at, got, want) = worst_depth;
    println!("{pipeline} {features:?}: view depths now and before within {error:.5} of theirs");
    assert!(
        error <= DEPTH_TOLERANCE,
        "{pipeline} {features:?}: view depths {got:?} (now, before) at {at:?}, expected \
         {want:?} ({error:.5} of them off)"
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
            "\"motion vectors (untabled textures)\": (inputs: {\n            \"depth\": \"depth\", \
             \"mesh\": \"mesh\", \"pose_offset\": \"pose_offset\",\n        }, optional: \
             [\"pose_offset\"]),",
            "\"motion vectors\": (inputs: { \"samples\": \"samples\", \"mesh\": \"mesh\" }),",
        )],
    );
    let path = edited.path.to_str().expect("temp paths are UTF-8");
    let run = crate::cli_support::rgraph(&["validate", path]).expect(1);
    let says = "pass \"motion vectors\" (motion_vectors): input \"mesh\" names a G-buffer's \
                meshes, but the keys of input \"samples\" hold their triangles already";
    assert!(run.stdout.contains(says), "{}", run.stdout);
}

/// A pose offset moves a point with its mesh: without the G-buffer's mesh channel beside
/// it, `rgraph validate` refuses it, naming the pass.
#[test]
fn a_pose_offset_without_a_mesh_channel_is_refused() {
    let edited = crate::common::copied_pipeline(
        "msaa_4x_taa.ron",
        &[(
            "\"debug motion (untabled textures)\": (inputs: {\n            \"depth\": \"depth\", \
             \"mesh\": \"mesh\",",
            "\"debug motion (untabled textures)\": (inputs: {\n            \"depth\": \"depth\",",
        )],
    );
    let path = edited.path.to_str().expect("temp paths are UTF-8");
    let run = crate::cli_support::rgraph(&["validate", path]).expect(1);
    let says = "pass \"debug motion (untabled textures)\" (motion_vectors): input \"pose_offset\" \
                moves a G-buffer's point with its mesh's vertices: give it with the G-buffer's \
                \"depth\" and \"mesh\"";
    assert!(run.stdout.contains(says), "{}", run.stdout);
}

/// The quad of [`crate::gltf_writer::deformed::morphed_quad`] (x 0..1, y 0..h in the
/// plane z = 0, placed by an identity transform), whose top edge is at h = 1 + 0.5 w for
/// morph weight w, loaded at weight [`WEIGHT_BEFORE`] and seen from in front.
fn morphed_quad() -> Scene {
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
    scene.camera = Camera::look_at(
        "quad",
        DVec3::new(0.5, 0.75, 2.2),
        DVec3::new(0.5, 0.75, 0.0),
        DVec3::Y,
        projection,
    );
    scene
}

/// The quad's morph weight in the first frame, and in the second.
const WEIGHT_BEFORE: f64 = 0.25;
const WEIGHT_NOW: f64 = 1.0;

/// How the quad's motion compared with the CPU's in the second frame, and how many pixels
/// moved in a third whose pose stayed.
struct QuadMotion {
    /// Pixels checked, and those that moved over a pixel.
    checked: usize,
    moving: usize,
    /// The worst error in pixels, where, and the motion found and expected there.
    worst: (f64, (u32, u32), DVec2, DVec2),
    /// Pixels of the third frame with motion over 1/1000 pixel.
    still_moved: usize,
}

/// Where a pass takes a pixel's motion from, within the pixel: `at`, and where the
/// second frame's sample 0 lies (jittered in TAA's frames), whose surface it takes.
#[derive(Copy, Clone)]
struct Within {
    at: DVec2,
    sample_0: DVec2,
}

/// Renders [`morphed_quad`] through `pipeline` compiled for `features` at weight
/// [`WEIGHT_BEFORE`], then [`WEIGHT_NOW`], then again, and compares the second frame's
/// motion with the CPU's at `within.at` each pixel whose centre and sample 0 see the
/// quad: a point at height y was at y h_before / h_now, no transform or camera moving.
fn quad_motion(pipeline: PipelineFile, features: Features, within: Within) -> QuadMotion {
    let scene = morphed_quad();
    let (h_before, h_now) = (1.0 + 0.5 * WEIGHT_BEFORE, 1.0 + 0.5 * WEIGHT_NOW);
    let clip_now = clip(&scene.camera);
    let eye = scene.camera.position;
    // The point of the quad's plane a pixel coordinate sees, if the quad is there now.
    let on_quad = |at: DVec2| {
        let d = ray(&scene.camera, at);
        let p = eye + d * (-eye.z / d.z);
        (p.x > 0.0 && p.x < 1.0 && p.y > 0.0 && p.y < h_now).then_some(p)
    };
    let gpu = gpu();
    let mut frame = Render::new(pipeline, "quad", SIZE)
        .with_scene(scene.clone())
        .features(features)
        .edit("outputs: [\"color\", ", "outputs: [\"motion\", \"color\", ")
        .run(&gpu);
    let mut inputs = frame.inputs();
    assert_eq!(inputs.morph_weights, vec![vec![WEIGHT_BEFORE as f32]]);
    inputs.morph_weights[0][0] = WEIGHT_NOW as f32;
    frame.next(inputs);
    let motion = frame.hdr(&gpu, "motion");
    let mut found = QuadMotion {
        checked: 0,
        moving: 0,
        worst: (0.0, (0, 0), DVec2::ZERO, DVec2::ZERO),
        still_moved: 0,
    };
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let corner = DVec2::new(x as f64, y as f64);
            let seen = on_quad(corner + 0.5).and(on_quad(corner + within.sample_0));
            let (Some(_), Some(p)) = (seen, on_quad(corner + within.at)) else {
                continue;
            };
            let before = DVec3::new(p.x, p.y * h_before / h_now, 0.0);
            let want = pixel_of(clip_now, p.extend(1.0)) - pixel_of(clip_now, before.extend(1.0));
            let got = motion[(y * SIZE.0 + x) as usize];
            let got = DVec2::new(f64::from(got[0]), f64::from(got[1]));
            let error = (got - want).length();
            if error > found.worst.0 {
                found.worst = (error, (x, y), got, want);
            }
            found.checked += 1;
            found.moving += usize::from(want.length() > 1.0);
        }
    }
    // A frame whose pose stays: nothing moves.
    let inputs = frame.inputs();
    frame.next(inputs);
    let motion = frame.hdr(&gpu, "motion");
    found.still_moved = (motion.iter())
        .filter(|m| DVec2::new(f64::from(m[0]), f64::from(m[1])).length() > 1e-3)
        .count();
    found
}

/// [`quad_motion`] within [`TOLERANCE`] of the CPU's, over at least 100 pixels that moved
/// over a pixel, and still in the frame whose pose stayed.
fn check_quad(pipeline: PipelineFile, features: Features, within: Within) {
    let found = quad_motion(pipeline, features.clone(), within);
    let (checked, moving) = (found.checked, found.moving);
    assert!(
        moving >= 100,
        "{pipeline}: only {moving} of {checked} pixels moved over a pixel"
    );
    let (error, at, got, want) = found.worst;
    println!("{pipeline} {features:?}: {checked} pixels, worst error {error:.4} px at {at:?}");
    assert!(
        error <= TOLERANCE,
        "{pipeline} {features:?}: motion {got:?} at {at:?}, expected {want:?} ({error:.4} px off)"
    );
    assert_eq!(
        found.still_moved, 0,
        "{pipeline}: {} pixels moved in a frame whose pose stayed",
        found.still_moved
    );
}

/// A morph target that stretches a quad moves its pixels though no transform changes:
/// the visibility buffer's point is taken back to where the deformation found the
/// triangle's vertices (both raster branches); in the next frame, whose pose stays, they
/// stand still.
#[test]
fn a_morph_target_moves_its_pixels() {
    let features = rgraph_scene::analysis::Features::of(&morphed_quad()).names();
    for pipeline in [DEFAULT, DEFAULT_GPU] {
        let within = Within {
            at: DVec2::splat(0.5),
            sample_0: SAMPLE_0,
        };
        check_quad(pipeline, features.clone(), within);
    }
}

/// In the TAA preset's G-buffer (4x MSAA, as `deferred_msaa_4x_lean.ron`'s, with the mesh
/// channel) the morphed quad's points move with its vertices too: the G-buffer pass
/// writes each sample's pose offset (common/pose_offset.rs) for the scene with
/// deformations, and the motion vectors add it to sample 0's point. Checked at sample 0,
/// jittered as TAA's second frame is; without the offset (the scene's features less
/// `deformed`, whose plan has no such target) the same frames are pixels off.
#[test]
fn a_morph_target_moves_its_pixels_in_a_gbuffer() {
    let mut features = rgraph_scene::analysis::Features::of(&morphed_quad()).names();
    assert!(features.contains("deformed"), "{features:?}");
    features.insert("untabled_textures");
    let sample_0 = SAMPLE_0 - DVec2::from(jitter(1).map(f64::from)) * 0.5;
    let within = Within {
        at: sample_0,
        sample_0,
    };
    check_quad(TAA, features.clone(), within);
    let without: Features = features.iter().filter(|&f| f != "deformed").collect();
    let found = quad_motion(TAA, without, within);
    let (error, at, got, want) = found.worst;
    println!("{TAA} without the pose offset: worst error {error:.4} px at {at:?}");
    assert!(
        error > 2.0,
        "without the pose offset the quad's motion {got:?} at {at:?} is within {error:.4} px \
         of {want:?}: the test cannot tell the offset's work"
    );
}

/// The pose offset costs a scene without deformations nothing: the TAA preset compiled
/// for a G-buffer scene without them (with and without emission, on a device allowing 64
/// bytes per sample) plans what the preset with every mention of the pose offset taken
/// out plans (passes, resources, physical textures, bytes), but for the notes that the
/// G-buffer and motion passes skip their optional slot; with `deformed` the G-buffer
/// passes attach it, 8 bytes per sample more, and the motion vectors read it.
#[test]
fn the_pose_offset_costs_a_scene_without_deformations_nothing() {
    use rgraph_core::file::{load_str_with, GraphParams, Registry};
    use rgraph_core::{explain, CompileOptions, Plan};

    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, None);
    let shipped = crate::common::edited_pipeline("msaa_4x_taa.ron", &[]);
    let stripped = crate::common::edited_pipeline(
        "msaa_4x_taa.ron",
        &[
            ("    features: [\"deformed\"],\n", ""),
            (
                "        \"pose_offset\": Texture(format: \"rgba16float\", samples: Param(name: \
                 \"msaa\", default: 4),\n                               when: \
                 \"untabled_textures & deformed & color_bytes_64\"),\n",
                "",
            ),
            (" \"pose_offset\": \"pose_offset\",", ""),
            (", optional: [\"pose_offset\"]", ""),
            ("optional: [\"pose_offset\", ", "optional: ["),
        ],
    );
    assert!(
        !stripped.text.contains("\"pose_offset\""),
        "{}",
        stripped.text
    );
    let plan = |file: &crate::common::EditedPipeline, features: &[&str]| -> Plan {
        let params = GraphParams::new();
        let loaded = load_str_with(&file.path, &file.text, &registry, &params)
            .unwrap_or_else(|e| panic!("{e}"));
        let features: Features = features.iter().copied().collect();
        let options = CompileOptions {
            output_size: (1280, 720),
            profile: CompileOptions::default().profile.granting(&features),
        };
        let mut plan = loaded.compile_for(&options, &features).unwrap();
        // Where a part is used moves with the preset's lines.
        for pass in &mut plan.passes {
            pass.origin = None;
        }
        plan
    };
    let gbuffer = |plan: &Plan, emissive: bool| {
        let name = match emissive {
            true => "gbuffer (untabled textures, emissive)",
            false => "gbuffer (untabled textures)",
        };
        let pass = plan.passes.iter().find(|p| p.name == name);
        pass.unwrap_or_else(|| panic!("{name} runs")).clone()
    };
    for emissive in [false, true] {
        let mut core = vec!["untabled_textures", "color_bytes_64"];
        if emissive {
            core.push("emissive");
        }
        let (with, without) = (plan(&shipped, &core), plan(&stripped, &core));
        // The lines naming the pose offset: the passes' skipped slots, and its resource's
        // block (its name, and more indented, that it is not allocated).
        let text = explain::text(&with);
        let (mut notes, mut rest, mut in_block) = (Vec::new(), Vec::new(), false);
        for line in text.lines() {
            in_block = line.starts_with("  pose_offset:") || in_block && line.starts_with("    ");
            match in_block || line.contains("pose_offset") {
                true => notes.push(line),
                false => rest.push(line),
            }
        }
        let optional = notes.iter().filter(|l| l.contains("(an optional")).count();
        let unallocated = notes.iter().filter(|l| l.contains("not allocated")).count();
        assert_eq!(
            (optional, unallocated, notes.len()),
            (3, 1, 5),
            "a core scene's plan holds the pose offset: the G-buffer's and two motion \
             passes' skipped slots and the resource unallocated, no more: {notes:#?}"
        );
        let before = explain::text(&without);
        assert_eq!(
            rest,
            before.lines().collect::<Vec<_>>(),
            "emissive: {emissive}"
        );
        let core_bytes = gbuffer(&with, emissive).color_bytes_per_sample;
        assert_eq!(core_bytes, if emissive { 28 } else { 24 });
        let deformed = plan(&shipped, &[core.as_slice(), &["deformed"]].concat());
        let pass = gbuffer(&deformed, emissive);
        assert_eq!(pass.color_bytes_per_sample, core_bytes + 8);
        let pose = deformed
            .resources
            .iter()
            .position(|r| r.name == "pose_offset");
        let pose = pose.expect("a deformed scene's plan keeps the pose offset");
        assert!(
            pass.writes.iter().any(|&(r, _)| r.0 as usize == pose),
            "{pass:?}"
        );
        let motion = deformed
            .passes
            .iter()
            .find(|p| p.name == "motion vectors (untabled textures)");
        let motion = motion.expect("the motion vectors run");
        assert!(
            motion.reads.iter().any(|&(r, _)| r.0 as usize == pose),
            "{motion:?}"
        );
    }
}
