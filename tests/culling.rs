//! Cluster culling never drops a visible triangle (issue 38). The compute raster's bins
//! cull the draws' clusters by box (outside the view volume) and normal cone (only back
//! faces), and list small ones whole in their tiles (visibility_compute's `clusters`,
//! bin_triangles.wgsl). Along camera paths that put objects behind the camera, cut them at
//! the image's sides and the near plane and turn closed meshes' backs to it, and with
//! meshes mirrored and squashed (transforms under which a normal cone no longer holds),
//! every frame of one executor renders the same image, exactly, with `clusters: culled`
//! (the default), `whole` and `off` (every triangle binned by itself, as before
//! clusters). The frames run through one executor each, so they also show that a frame's
//! lists do not keep what an earlier frame culled or listed.
//!
//! Occlusion culling (the compute raster's two phases, passes/common/occlusion.rs) never
//! drops a visible triangle either: along the same frames (`clusters: culled` and
//! `whole` with it, `off` without any culling), and in a scene built to hide and reveal
//! (a wall moving away from a crowd behind it, an object stepping out from behind the
//! wall, the camera turning fast), every frame is the image without it, exactly; and it
//! does cull there, and does draw what a frame reveals (the counts its list keeps). The
//! depth pyramid it tests against holds the farthest depth of every sample it covers.
//!
//! The bins' slots (visibility_compute's `binned_triangles`, the triangles a frame may bin
//! one by one) never change a frame either: with too few of them for what the frames
//! bin, the clusters past them take the slower paths, and every frame is the image with
//! room for all, exactly.
//!
//! Micro clusters (visibility_compute's `micro`, on in the shipped file where the device
//! has 64-bit atomic max, as lavapipe does): the clusters small on screen, rasterised a
//! triangle an invocation by `atomicMax` before the tile raster covers the rest
//! (micro_raster.wgsl), give every frame the image of the tile raster alone, exactly,
//! colour and edges view (sample 0's flag) and triangles per pixel, at 4x and 1x, with and
//! without occlusion culling: on a heightfield dense enough that nearly every cluster is
//! micro, and along the camera paths above, which mix micro clusters with large and
//! clipped ones.
//!
//! The shadow maps' views draw only the clusters they may see (`shadow_maps`'s
//! `clusters`, gpu_scene/view_culling.rs): along the same frames, which move the cascades
//! with the camera, the colour and the shadows view are those of drawing every mesh
//! whole into every view.

use rgraph_core::Features;
use rgraph_passes::FrameInputs;
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::glam::{DMat4, DVec3, Vec3};
use rgraph_scene::{Camera, Light, LightKind, Projection, Scene};

use crate::deferred_support::scenes::Parts;
use crate::deferred_support::{gpu, Image, PipelineFile, Render};

/// The compute raster, as on a GPU.
const COMPUTE: PipelineFile = PipelineFile::gpu_branch("visibility_msaa_4x.ron");
/// The first raster pass's parameters as shipped, as far as they are edited
/// (`clusters` left at its default, `culled`); [`frames`] turns occlusion culling on (the
/// file's parameter `occlusion`, off by default) so that the camera paths exercise it too.
const SHIPPED: &str = "params: (other_samples: at_edges,";
const MODES: [(&str, &str); 2] = [
    (
        "whole",
        "params: (other_samples: at_edges, clusters: whole,",
    ),
    ("off", "params: (other_samples: at_edges, clusters: off,"),
];
/// An edge pixel in the edges view.
const EDGE: [u8; 4] = [255, 0, 0, 255];
/// Tiles of 16 pixels: 10 x 6 of them, so that clusters touch one tile, a few, or many.
const SIZE: (u32, u32) = (160, 96);

/// The default pipeline's shadow maps drawn by the hardware alone (parts/shadow_maps.ron,
/// the CPU adapter's way, rather than the GPU branch's compute raster of small clusters,
/// parts/shadow_maps_compute.ron).
const HARDWARE_SHADOWS: (&str, &str) = (
    "(part: \"parts/shadow_maps_compute.ron\"),",
    "(part: \"parts/shadow_maps.ron\"),",
);
/// The hardware's shadow maps pass drawing every mesh whole into every view.
const SHADOWS_WHOLE: (&str, &str) = (
    "when: \"shadows\",\n            outputs: { \"atlas\": \"shadow_atlas\" },",
    "when: \"shadows\",\n            params: (clusters: off),\n            outputs: { \"atlas\": \"shadow_atlas\" },",
);
/// A pixel of the shadows view in the most important light's shadow: black, or nearly.
fn in_shadow(pixel: [u8; 4]) -> bool {
    pixel[0] < 64
}

/// A frame's change of the scene's own inputs, and what it is called in messages.
type Change = (&'static str, fn(&mut FrameInputs, &Scene));

/// The frames: the scene's camera, then cameras and poses that cull and clip.
const CHANGES: [Change; 6] = [
    ("the scene's camera", |_, _| {}),
    ("orbited 150 degrees", |inputs, scene| {
        inputs.camera = inputs
            .camera
            .orbited(scene.bounds.center(), 150f64.to_radians());
    }),
    ("looking away", |inputs, scene| {
        let eye = inputs.camera.position;
        inputs.camera = look(&inputs.camera, eye, 2.0 * eye - scene.bounds.center());
    }),
    ("inside, across the scene", |inputs, scene| {
        let (center, size) = (scene.bounds.center(), scene.bounds.size());
        let eye = center + DVec3::new(0.2, 0.05, 0.3) * size;
        inputs.camera = look(
            &inputs.camera,
            eye,
            center - DVec3::new(0.3, 0.1, 0.1) * size,
        );
    }),
    ("close, the centre at the image's side", |inputs, scene| {
        let center = scene.bounds.center();
        let eye = center.lerp(inputs.camera.position, 0.4);
        let side = inputs.camera.orientation * DVec3::X;
        let target = center + side * 0.3 * scene.bounds.size().length();
        inputs.camera = look(&inputs.camera, eye, target);
    }),
    ("meshes mirrored and squashed", |inputs, scene| {
        for (k, (transform, mesh)) in inputs.transforms.iter_mut().zip(&scene.meshes).enumerate() {
            let Some(bounds) = mesh.world_bounds() else {
                continue;
            };
            let scale = match k % 3 {
                0 => DVec3::new(-1.0, 1.0, 1.0),
                1 => DVec3::new(1.0, 0.4, 1.0),
                _ => DVec3::ONE,
            };
            let about = bounds.center();
            *transform = DMat4::from_translation(about)
                * DMat4::from_scale(scale)
                * DMat4::from_translation(-about)
                * *transform;
        }
    }),
];

/// `camera` moved to `eye`, looking at `target`, its projection kept.
fn look(camera: &Camera, eye: DVec3, target: DVec3) -> Camera {
    let up = if (target - eye).normalize().y.abs() > 0.99 {
        DVec3::Z
    } else {
        DVec3::Y
    };
    Camera::look_at(camera.name.clone(), eye, target, up, camera.projection)
}

/// Each of [`CHANGES`]' frames of `scene` through one executor, with the raster pass's
/// parameters `params`, occlusion culling on and micro clusters on or off (`micro`): the
/// colour and the edges view.
fn frames(scene: &'static str, params: &'static str, micro: u32) -> Vec<(Image, Image)> {
    frames_of(
        scene,
        (&[(SHIPPED, params)], &[("occlusion", 1), ("micro", micro)]),
        "debug.edges",
        Features::new(),
    )
}

/// The default pipeline as a test changes it: text edits (from, to) and parameter values.
type Changed<'a> = (&'a [(&'static str, &'static str)], &'a [(&'a str, u32)]);

/// Each of [`CHANGES`]' frames of `scene` through one executor, the pipeline edited by
/// `edits`, loaded with the parameter values `params` and compiled for `features`: the
/// colour and the image `view`.
fn frames_of(
    scene: &'static str,
    (edits, params): Changed<'_>,
    view: &str,
    features: Features,
) -> Vec<(Image, Image)> {
    let gpu = gpu();
    let loaded = Scene::load(scene).unwrap_or_else(|e| panic!("cannot load {scene}: {e}"));
    let render = edits
        .iter()
        .fold(Render::new(COMPUTE, scene, SIZE), |r, &(from, to)| {
            r.edit(from, to)
        });
    let render = (params.iter()).fold(render, |r, &(name, value)| r.param(name, value));
    let mut frame = render.features(features).run(&gpu);
    let own = frame.inputs();
    CHANGES
        .iter()
        .map(|(_, change)| {
            let mut inputs = own.clone();
            change(&mut inputs, &loaded);
            frame.next(inputs);
            (frame.image(&gpu, "color"), frame.image(&gpu, view))
        })
        .collect()
}

fn differing(a: &Image, b: &Image) -> usize {
    (a.pixels.iter().zip(&b.pixels))
        .filter(|(a, b)| a != b)
        .count()
}

fn assert_culling_keeps_every_frame(scene: &'static str) {
    let shipped = frames(scene, SHIPPED, 1);
    // A frame that shows nothing would pass with anything culled: most frames show
    // edges (red in the edges view) of the scene's triangles.
    let shown = shipped
        .iter()
        .filter(|(_, edges)| edges.count(EDGE) > 0)
        .count();
    assert!(
        shown >= 4,
        "{scene}: only {shown} of the frames show an edge"
    );
    // Each mode with micro clusters (`clusters: off` has none: nothing decides them), and
    // the shipped one without.
    let modes = MODES.iter().map(|&(mode, params)| (mode, params, 1));
    for (mode, params, micro) in modes.chain([("culled, micro off", SHIPPED, 0)]) {
        let other = frames(scene, params, micro);
        for (k, (other, (color, edges))) in other.iter().zip(&shipped).enumerate() {
            let (colors, edges) = (differing(&other.0, color), differing(&other.1, edges));
            assert!(
                colors == 0 && edges == 0,
                "{scene}, {}: clusters {mode} and culled differ in {colors} pixels of the \
                 colour and {edges} of the edges view",
                CHANGES[k].0
            );
        }
    }
}

/// Each of [`CHANGES`]' frames of `scene` through one executor, at `msaa` samples per
/// pixel, with the graph parameters `occlusion` and `micro` at the values given: the
/// colour, the edges view and the fragments view (triangles per pixel).
fn micro_frames(scene: &'static str, (msaa, occlusion, micro): (u32, u32, u32)) -> Vec<[Image; 3]> {
    let gpu = gpu();
    let loaded = Scene::load(scene).unwrap_or_else(|e| panic!("cannot load {scene}: {e}"));
    let mut frame = Render::new(COMPUTE, scene, SIZE)
        .param("msaa", msaa)
        .param("occlusion", occlusion)
        .param("micro", micro)
        .run(&gpu);
    let own = frame.inputs();
    CHANGES
        .iter()
        .map(|(_, change)| {
            let mut inputs = own.clone();
            change(&mut inputs, &loaded);
            frame.next(inputs);
            ["color", "debug.edges", "debug.fragments"].map(|view| frame.image(&gpu, view))
        })
        .collect()
}

/// With micro clusters every frame of `scene` is the frame of the tile raster alone,
/// exactly (colour, edges, fragments), at 4x and 1x, without occlusion culling (where
/// samples 1 to 3 are stored at edge pixels only) and with it (every sample stored, and a
/// second phase after the micro clusters' first).
fn assert_micro_keeps_every_frame(scene: &'static str) {
    const VIEWS: [&str; 3] = ["colour", "edges view", "fragments view"];
    for (msaa, occlusion) in [(4, 0), (1, 0), (4, 1)] {
        let tiles = micro_frames(scene, (msaa, occlusion, 0));
        let micro = micro_frames(scene, (msaa, occlusion, 1));
        // Frames of nothing would pass with anything lost: most show edges (at 4x; a
        // pixel of one sample shows one triangle).
        let shown = (tiles.iter())
            .filter(|[_, edges, _]| edges.count(EDGE) > 0)
            .count();
        assert!(
            msaa == 1 || shown >= 4,
            "{scene}: only {shown} of the frames show an edge"
        );
        for (k, (m, t)) in micro.iter().zip(&tiles).enumerate() {
            for (view, (m, t)) in VIEWS.iter().zip(m.iter().zip(t)) {
                let differ = differing(m, t);
                assert!(
                    differ == 0,
                    "{scene}, {msaa}x, occlusion {occlusion}, {}: with micro clusters {differ} \
                     pixels of the {view} differ from the tile raster's",
                    CHANGES[k].0
                );
            }
        }
    }
}

/// A heightfield of 125,000 triangles at 160 x 96, some 8 a pixel: nearly every cluster
/// in view is micro (its bounds hold well under 4 pixels a triangle), so nearly every
/// pixel's keys are the micro raster's, flags and all. (Half a million, cells=500, took
/// twice the time and lost no power: sample 0's atomics dropped, both differ in the same
/// 6612 pixels of the first frame.)
#[test]
fn micro_clusters_keep_every_frame_of_a_dense_heightfield() {
    assert_micro_keeps_every_frame("builtin:terrain?cells=250");
}

/// Spheres over a floor: micro clusters (the far spheres' at 160 x 96) beside large ones
/// (the floor's, and the spheres' in the close frames) and clipped ones, sharing edges and
/// pixels.
#[test]
fn micro_clusters_keep_every_frame_of_spheres() {
    assert_micro_keeps_every_frame("builtin:spheres");
}

/// Spheres over a floor: closed meshes whose back halves are culled by their cones.
#[test]
fn culling_keeps_every_visible_triangle_of_spheres() {
    assert_culling_keeps_every_frame("builtin:spheres");
}

/// A city of separate buildings: whole meshes in and out of view.
#[test]
fn culling_keeps_every_visible_triangle_of_a_city() {
    assert_culling_keeps_every_frame("builtin:city");
}

/// A heightfield of 100,352 triangles: clusters of small triangles listed whole, and
/// clusters crossing the near plane.
#[test]
fn culling_keeps_every_visible_triangle_of_a_heightfield() {
    assert_culling_keeps_every_frame("builtin:terrain");
}

/// `params` (the first raster pass's, as [`SHIPPED`] and [`MODES`] give them) with the
/// parameters `more` added.
fn with_params(params: &'static str, more: &str) -> &'static str {
    params
        .replace("at_edges,", &format!("at_edges, {more}"))
        .leak()
}

/// With fewer slots than a frame bins triangles one by one (visibility_compute's
/// `binned_triangles`), the clusters past them are listed whole in the tiles they touch,
/// or read by every tile, which tests their bounds (bin_triangles.wgsl), and every frame
/// of `scene` is the frame with a slot for every triangle, exactly, colour and edges
/// view: with one slot (every cluster of more than one triangle past them) and with 3000
/// (some clusters binned by triangle, the rest past them, which ones depending on the
/// order of the atomics), micro clusters on and off, clusters culled and not (`off`:
/// every cluster binned by triangle, those in front of the camera, behind it and across
/// its planes), and in tiles of 4 pixels (chunks of 16 triangles, not 64).
fn assert_overflowing_slots_keep_every_frame(scene: &'static str) {
    let off = MODES[1].1;
    let cases = [
        ((SHIPPED, 1), "binned_triangles: 1,"),
        ((SHIPPED, 0), "binned_triangles: 1,"),
        ((SHIPPED, 0), "binned_triangles: 3000,"),
        ((SHIPPED, 0), "binned_triangles: 1, tile: 4,"),
        ((off, 0), "binned_triangles: 3000,"),
    ];
    let mut roomy = std::collections::HashMap::new();
    for ((params, micro), more) in cases {
        let full = (roomy.entry((params, micro))).or_insert_with(|| frames(scene, params, micro));
        let tight = frames(scene, with_params(params, more), micro);
        for (k, (tight, (color, edges))) in tight.iter().zip(full.iter()).enumerate() {
            let (colors, edges) = (differing(&tight.0, color), differing(&tight.1, edges));
            assert!(
                colors == 0 && edges == 0,
                "{scene}, {}, {params} micro {micro}: with {more} {colors} pixels of the \
                 colour and {edges} of the edges view differ from the frame with room",
                CHANGES[k].0
            );
        }
    }
}

/// Spheres over a floor: large clusters and clipped ones past the slots, read by every
/// tile.
#[test]
fn overflowing_slots_keep_every_frame_of_spheres() {
    assert_overflowing_slots_keep_every_frame("builtin:spheres");
}

/// A heightfield of 25,088 triangles: small clusters past the slots, listed whole, and
/// clusters across the near plane, read by every tile. (The default 100,352 took four
/// times as long, and failed e80917f's mutations on fewer pixels: tiles skipping the
/// spanning clusters 21 against 52 here, overflowing clusters that fit whole dropped 5
/// against 193, records written at the triangle's place rather than its slot 21 against
/// 949.)
#[test]
fn overflowing_slots_keep_every_frame_of_a_heightfield() {
    assert_overflowing_slots_keep_every_frame("builtin:terrain?cells=112");
}

/// Bins of no slots are an error naming the pass, found without a GPU.
#[test]
fn bins_of_no_slots_are_an_error() {
    let line = crate::visibility::validate_error(
        SHIPPED,
        "params: (other_samples: at_edges, binned_triangles: 0,",
        "slots.ron",
        "visibility",
    );
    let says = "binned_triangles must be at least 1, got 0";
    assert!(line.contains(says), "{line}");
}

/// `scene`'s features, as `rgraph render` compiles for them: with shadows where its
/// lights emit.
fn features_of(scene: &str) -> Features {
    let loaded = Scene::load(scene).unwrap_or_else(|e| panic!("cannot load {scene}: {e}"));
    SceneFeatures::of(&loaded).names()
}

fn assert_shadow_views_keep_every_frame(scene: &'static str) {
    let features = features_of(scene);
    let shipped = frames_of(
        scene,
        (&[HARDWARE_SHADOWS], &[]),
        "debug.shadows",
        features.clone(),
    );
    // A scene whose shadows fall nowhere on screen would pass with every caster culled.
    let shown = shipped
        .iter()
        .filter(|(_, shadows)| shadows.pixels.iter().any(|&p| in_shadow(p)))
        .count();
    assert!(
        shown >= 4,
        "{scene}: only {shown} of the frames show a shadow"
    );
    let whole = frames_of(
        scene,
        (&[HARDWARE_SHADOWS, SHADOWS_WHOLE], &[]),
        "debug.shadows",
        features,
    );
    for (k, (other, (color, shadows))) in whole.iter().zip(&shipped).enumerate() {
        let (colors, shadows) = (differing(&other.0, color), differing(&other.1, shadows));
        assert!(
            colors == 0 && shadows == 0,
            "{scene}, {}: shadow maps drawn whole and culled differ in {colors} pixels of \
             the colour and {shadows} of the shadows view",
            CHANGES[k].0
        );
    }
}

/// The share of pixels of `a` within `tolerance` of `b`'s in every channel.
fn within(a: &Image, b: &Image, tolerance: u8) -> f64 {
    let close = (a.pixels.iter().zip(&b.pixels))
        .filter(|(a, b)| {
            a.iter()
                .zip(b.iter())
                .all(|(x, y)| x.abs_diff(*y) <= tolerance)
        })
        .count();
    close as f64 / a.pixels.len() as f64
}

/// The GPU branch's shadow maps, rasterised in compute (shadow_raster.rs) with
/// `small_texels` as given, against the hardware drawing them all, over the frames, in an
/// atlas of 1024 texels. The two rasters may differ where a texel centre lies on a
/// triangle's edge (the compute raster covers both sides, the hardware one) and in the
/// bias's rounding: every pixel of 99.9% of each frame is to be within 2/255.
fn assert_compute_shadows_match_the_hardware(scene: &'static str, small_texels: u32) {
    let with_texels =
        format!("plugin: \"shadow_raster\",\n            params: (small_texels: {small_texels}, ");
    let small_clusters: (&str, &str) = (
        "plugin: \"shadow_raster\",\n            params: (",
        with_texels.leak(),
    );
    let small_atlas: &[(&str, u32)] = &[("shadow_map", 1024)];
    let features = features_of(scene);
    let compute = frames_of(
        scene,
        (&[small_clusters], small_atlas),
        "debug.shadows",
        features.clone(),
    );
    let hardware = frames_of(
        scene,
        (&[small_clusters, HARDWARE_SHADOWS], small_atlas),
        "debug.shadows",
        features,
    );
    for (k, (c, h)) in compute.iter().zip(&hardware).enumerate() {
        let (colors, shadows) = (within(&c.0, &h.0, 2), within(&c.1, &h.1, 2));
        eprintln!(
            "{scene}, {}: {colors:.5} of the colour, {shadows:.5} of the shadows view",
            CHANGES[k].0
        );
        assert!(
            colors >= 0.999 && shadows >= 0.999,
            "{scene}, {}: the compute raster's shadows and the hardware's agree within \
             2/255 on {colors} of the colour and {shadows} of the shadows view",
            CHANGES[k].0
        );
    }
}

/// A heightfield of half a million triangles with `small_texels: 64`, so that most
/// clusters in the sun's cascades are small (an invocation a triangle); measured, every
/// pixel of every frame is within 2/255 (with the compute raster writing depth 0, 56%).
/// At a million triangles (cells 707) lavapipe cuts the visibility raster's loops short
/// (65,535 iterations a shader invocation, docs/design/compute-raster.md): the longest
/// tile lists lose their last triangles, differently each run.
#[test]
fn compute_shadows_match_the_hardware_on_a_dense_heightfield() {
    assert_compute_shadows_match_the_hardware("builtin:terrain?cells=500", 64);
}

/// Spheres over a floor with every cluster large (`small_texels: 1`): the workgroup
/// raster alone, its triangles clipped to the near plane of the point lights' cube faces
/// (the floor passes behind each light).
#[test]
fn compute_shadows_of_large_clusters_match_the_hardware() {
    assert_compute_shadows_match_the_hardware("builtin:spheres", 1);
}

/// Spheres over a floor, under a sun's cascades and two point lights' cube faces.
#[test]
fn shadow_views_keep_every_caster_of_spheres() {
    assert_shadow_views_keep_every_frame("builtin:spheres");
}

/// A city: buildings in and out of each cascade.
#[test]
fn shadow_views_keep_every_caster_of_a_city() {
    assert_shadow_views_keep_every_frame("builtin:city");
}

/// One heightfield mesh, of which each view sees part.
#[test]
fn shadow_views_keep_every_caster_of_a_heightfield() {
    assert_shadow_views_keep_every_frame("builtin:terrain");
}

/// The hiding scene's meshes: a wall, a crowd of cubes behind it (one mesh of several
/// clusters), one more cube behind it that steps out, and the floor.
const WALL: usize = 0;
const CROWD: usize = 1;
const RUNNER: usize = 2;

/// A wall before a crowd of 40 cubes, seen from in front, lit by a sun.
fn hiding_scene() -> Scene {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.6, 0.6, 0.6], 0.6);
    let red = parts.material("red", [0.8, 0.15, 0.1], 0.4);
    let blue = parts.material("blue", [0.1, 0.3, 0.8], 0.4);
    let (min, max) = (DVec3::new(-3.0, 0.0, -0.25), DVec3::new(3.0, 3.5, 0.25));
    assert_eq!(parts.cuboid("wall", min, max, grey), WALL);
    let mut crowd = Parts::new();
    for (i, j, k) in (0..5).flat_map(|i| (0..4).flat_map(move |j| (0..2).map(move |k| (i, j, k)))) {
        let corner = DVec3::new(
            -1.5 + 0.65 * f64::from(i),
            0.6 + 0.5 * f64::from(j),
            -3.5 + f64::from(k),
        );
        crowd.cuboid("cube", corner, corner + DVec3::splat(0.35), 0);
    }
    let cubes: Vec<Vec<DVec3>> = crowd.polygons.iter().map(|p| p.corners.clone()).collect();
    assert_eq!(parts.mesh("crowd", &cubes, red), CROWD);
    let (min, max) = (DVec3::new(-0.4, 0.8, -1.5), DVec3::new(0.4, 1.6, -0.7));
    assert_eq!(parts.cuboid("runner", min, max, blue), RUNNER);
    let floor = vec![
        DVec3::new(-20.0, 0.0, 20.0),
        DVec3::new(20.0, 0.0, 20.0),
        DVec3::new(20.0, 0.0, -20.0),
        DVec3::new(-20.0, 0.0, -20.0),
    ];
    parts.mesh("floor", &[floor], grey);
    parts.lights.push(Light {
        name: "sun".into(),
        kind: LightKind::Directional,
        color: [1.0, 1.0, 1.0],
        intensity: 3.0,
        position: DVec3::ZERO,
        direction: Vec3::new(0.3, -0.8, -0.5).normalize(),
        range: None,
    });
    parts.ambient = [0.05; 3];
    let projection = Projection::Perspective {
        yfov: 0.8,
        znear: 0.1,
        zfar: Some(100.0),
    };
    let eye = DVec3::new(0.0, 1.5, 8.0);
    let camera = Camera::look_at(
        "front",
        eye,
        DVec3::new(0.0, 1.5, 0.0),
        DVec3::Y,
        projection,
    );
    parts.scene("hiding", camera)
}

/// `inputs` with mesh `mesh` moved by `by`.
fn moved(inputs: &mut FrameInputs, mesh: usize, by: DVec3) {
    inputs.transforms[mesh] = DMat4::from_translation(by) * inputs.transforms[mesh];
}

/// The hiding scene's frames, each a change of its own inputs; the first is the
/// executor's first frame (a reset of the depth pyramid's history).
const HIDING: [Change; 10] = [
    ("the first frame", |_, _| {}),
    ("the wall hides the crowd", |_, _| {}),
    ("the wall moves away", |inputs, _| {
        moved(inputs, WALL, DVec3::new(9.0, 0.0, 0.0))
    }),
    ("the wall is back", |_, _| {}),
    ("the wall hides the crowd again", |_, _| {}),
    ("a cube steps out from behind the wall", |inputs, _| {
        moved(inputs, RUNNER, DVec3::new(4.5, 0.0, 0.0))
    }),
    ("the camera turns 70 degrees", |inputs, _| {
        let about = DVec3::new(0.0, 1.5, -1.5);
        inputs.camera = inputs.camera.orbited(about, 70f64.to_radians());
    }),
    ("the camera is back", |_, _| {}),
    (
        "the camera jumps aside, past the wall's edge",
        |inputs, _| {
            let (eye, target) = (DVec3::new(12.0, 1.5, 6.0), DVec3::new(0.0, 1.5, -2.5));
            inputs.camera = look(&inputs.camera, eye, target);
        },
    ),
    ("the camera behind the crowd", |inputs, _| {
        let about = DVec3::new(0.0, 1.5, -1.5);
        inputs.camera = inputs.camera.orbited(about, 180f64.to_radians());
    }),
];

/// What a frame of the hiding scene shows and counts: its colour, its edges, and the
/// clusters the first phase of occlusion culling listed and the second drew of them.
struct Counted {
    color: Image,
    edges: Image,
    listed: u32,
    revealed: u32,
}

/// [`HIDING`]'s frames through one executor, with the graph parameters `msaa` and
/// `occlusion` at `msaa` and `occlusion`.
fn hiding_frames(scene: &Scene, (msaa, occlusion): (u32, u32)) -> Vec<Counted> {
    let gpu = gpu();
    let mut frame = Render::new(COMPUTE, "hiding", SIZE)
        .with_scene(scene.clone())
        .param("msaa", msaa)
        .param("occlusion", occlusion)
        .edit(
            "outputs: [\"color\"",
            "outputs: [\"occlusion_counts\", \"color\"",
        )
        .run(&gpu);
    let own = frame.inputs();
    HIDING
        .iter()
        .enumerate()
        .map(|(k, (_, change))| {
            if k > 0 {
                let mut inputs = own.clone();
                change(&mut inputs, scene);
                frame.next(inputs);
            }
            let counts = frame.buffer(&gpu, "occlusion_counts");
            let word = |k: usize| u32::from_le_bytes(counts[4 * k..4 * k + 4].try_into().unwrap());
            Counted {
                color: frame.image(&gpu, "color"),
                edges: frame.image(&gpu, "debug.edges"),
                listed: word(0),
                revealed: word(1),
            }
        })
        .collect()
}

/// Every frame of the hiding scene with occlusion culling is the frame without it, at 4
/// samples per pixel and at 1 (visibility_noaa.ron), and occlusion culling works there:
/// with the wall before it, the crowd's clusters are listed by the first phase and not
/// drawn by the second; when the wall moves away, or the camera moves past it, the second
/// phase draws what the previous frame's pyramid hid.
#[test]
fn occlusion_culling_keeps_every_frame_of_a_scene_that_hides_and_reveals() {
    let scene = hiding_scene();
    for msaa in [4, 1] {
        let culled = hiding_frames(&scene, (msaa, 1));
        let whole = hiding_frames(&scene, (msaa, 0));
        assert_hiding_frames(&scene, msaa, &culled, &whole);
    }
}

/// The assertions of the test above, at `msaa` samples per pixel, on the frames with
/// occlusion culling (`culled`) and without (`whole`).
fn assert_hiding_frames(scene: &Scene, msaa: u32, culled: &[Counted], whole: &[Counted]) {
    for (k, (on, off)) in culled.iter().zip(whole).enumerate() {
        let colors = differing(&on.color, &off.color);
        let edges = differing(&on.edges, &off.edges);
        eprintln!(
            "{msaa}x, {}: {} listed, {} revealed; {colors} pixels of the colour and {edges} \
             of the edges differ",
            HIDING[k].0, on.listed, on.revealed
        );
        assert!(
            colors == 0 && edges == 0,
            "{msaa}x, {}: with occlusion culling {colors} pixels of the colour and {edges} \
             of the edges view differ from the frame without",
            HIDING[k].0
        );
    }
    // The crowd (red) shows where it is revealed, and not where the wall hides it: frames
    // that showed nothing would pass with anything culled.
    let red = |k: usize| {
        let reddish = |p: &&[u8; 4]| i32::from(p[0]) > 40 + i32::from(p[1].max(p[2]));
        culled[k].color.pixels.iter().filter(reddish).count()
    };
    for k in [1, 4, 7] {
        assert_eq!(red(k), 0, "{msaa}x, {}: the crowd shows", HIDING[k].0);
    }
    for k in [2, 6, 8] {
        assert!(
            red(k) > 100,
            "{msaa}x, {}: the crowd shows in {} pixels",
            HIDING[k].0,
            red(k)
        );
    }
    let crowd = rgraph_scene::cluster(&scene.meshes[CROWD]).clusters.len() as u32;
    assert!(crowd >= 4, "the crowd is {crowd} clusters");
    let counts = |k: usize| (culled[k].listed, culled[k].revealed);
    // The first frame's pyramid holds no frame: nothing is listed.
    assert_eq!(
        counts(0),
        (0, 0),
        "{msaa}x, {}: clusters listed, drawn",
        HIDING[0].0
    );
    // Hidden: every crowd cluster and the cube listed, and none drawn.
    for k in [1, 4] {
        let (listed, revealed) = counts(k);
        assert!(
            listed > crowd && revealed == 0,
            "{msaa}x, {}: {listed} clusters listed, {revealed} of them drawn; the crowd is {crowd}",
            HIDING[k].0
        );
    }
    // The cube stepped out where the previous frame's pyramid shows the floor beside the
    // wall: drawn by the first phase.
    assert!(
        counts(5).0 < counts(4).0,
        "{msaa}x, {}: {} clusters listed, {} before",
        HIDING[5].0,
        counts(5).0,
        counts(4).0
    );
    // Revealed, by the wall moving away and by the camera moving: clusters the previous
    // frame's pyramid hid, drawn by the second phase.
    for k in [2, 6, 8] {
        let (listed, revealed) = counts(k);
        assert!(
            revealed > 0,
            "{msaa}x, {}: {revealed} of {listed} listed clusters drawn",
            HIDING[k].0
        );
    }
    let (listed, revealed) = counts(2);
    assert!(
        revealed >= crowd,
        "{msaa}x, {}: {revealed} of {listed} listed clusters drawn; the crowd is {crowd}",
        HIDING[2].0
    );
}

/// Occlusion culling's slots wired wrongly are errors naming the pass, the slot and the
/// resource, found without a GPU (`rgraph validate`): each edit to visibility_msaa_4x.ron,
/// the pass it breaks, and what its error says.
#[test]
fn occlusion_culling_wired_wrongly_is_an_error() {
    let cases = [
        (
            "inputs: { \"pyramid\": \"depth_pyramid_prev\" },",
            "inputs: { \"pyramid\": \"shadow_atlas\" },",
            "visibility",
            "slot \"pyramid\": \"shadow_atlas\" is not a history",
        ),
        (
            "params: (occlusion: Param(name: \"occlusion\", default: 0), micro: Param(name: \
             \"micro\", default: 1),\n                     \
             micro_pixels: Param(name: \"micro_pixels\", default: 4)),\n            \
             when: \"!untabled_textures & !cpu_device & blend\",\n            \
             inputs: { \"pyramid\": \"depth_pyramid_prev\" },\n            \
             outputs: { \"samples\": \"samples\", \"occluded\": \"occluded\" },",
            "params: (occlusion: true),\n            \
             when: \"!untabled_textures & !cpu_device & blend\",\n            \
             outputs: { \"samples\": \"samples\" },",
            "visibility (blend)",
            "occlusion culling needs a \"pyramid\" input",
        ),
        (
            "\"occluded\": Buffer(size: 4194320,",
            "\"occluded\": Buffer(size: 16,",
            "visibility",
            "is not a buffer of a fixed size of at least 20 bytes",
        ),
        (
            "\"first_pyramid\": Texture(format: \"r32float\",",
            "\"first_pyramid\": Texture(format: \"rgba16float\",",
            "depth pyramid (first phase)",
            "is rgba16float, but the depth pyramid must be r32float",
        ),
    ];
    for (from, to, pass, says) in cases {
        let line = crate::visibility::validate_error(from, to, "wired.ron", pass);
        assert!(line.contains(says), "{pass}: {line}");
    }
}

/// The depth pyramid's level 0 holds, at each of its 512 x 512 texels, the least
/// reversed-Z depth (the farthest) of every sample of every pixel the texel covers
/// (depth_pyramid.wgsl: from floor(i W / 512) to ceil((i + 1) W / 512) - 1 across, and
/// down), exactly: read back against the keys it was built from, at 4x, where a
/// sphere's samples lie at other depths than sample 0's.
#[test]
fn the_depth_pyramid_holds_the_farthest_depth_of_every_sample_it_covers() {
    let gpu = gpu();
    let frame = Render::new(COMPUTE, "builtin:spheres", SIZE)
        .edit("outputs: [\"color\"", "outputs: [\"keys\", \"color\"")
        .param("occlusion", 1)
        .run(&gpu);
    let words = |bytes: Vec<u8>| -> Vec<u32> {
        (bytes.chunks_exact(4))
            .map(|w| u32::from_le_bytes(w.try_into().unwrap()))
            .collect()
    };
    let keys = words(frame.buffer(&gpu, "keys"));
    let pyramid: Vec<f32> = (words(frame.texels(&gpu, "depth_pyramid")).into_iter())
        .map(f32::from_bits)
        .collect();
    let (width, height, samples, side) = (SIZE.0 as usize, SIZE.1 as usize, 4, 512);
    assert_eq!(pyramid.len(), side * side);
    // A sample's depth: the high word of its key, the several-triangles flag cleared.
    let depth = |x: usize, y: usize, s: usize| {
        f32::from_bits(keys[2 * ((s * height + y) * width + x) + 1] & 0x7fff_ffff)
    };
    let covered = |i: usize, pixels: usize| i * pixels / side..((i + 1) * pixels).div_ceil(side);
    let mut wrong = Vec::new();
    for j in 0..side {
        for i in 0..side {
            let farthest = (covered(j, height))
                .flat_map(|y| {
                    covered(i, width).flat_map(move |x| (0..samples).map(move |s| (x, y, s)))
                })
                .map(|(x, y, s)| depth(x, y, s))
                .fold(f32::INFINITY, f32::min);
            if pyramid[j * side + i] != farthest {
                wrong.push((i, j, pyramid[j * side + i], farthest));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "{} texels differ, the first {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(4)]
    );
    // Not vacuous: the spheres and floor leave depths above 0 (nothing drawn) in most
    // texels, and several of them.
    let drawn = pyramid.iter().filter(|&&d| d > 0.0).count();
    assert!(drawn > side * side / 4, "{drawn} texels hold a depth");
}

/// Micro clusters asked for where they cannot be are errors naming the pass, found
/// without a GPU: on the second phase of occlusion culling, whose keys are flagged before
/// it adds to them, and with bounds of more pixels a triangle than an invocation scans.
#[test]
fn micro_clusters_asked_for_wrongly_are_errors() {
    let cases = [
        (
            "default: 0)),\n            when: \"!untabled_textures & !cpu_device\",\n            \
             inputs: { \"samples\": \"samples\", \"pyramid\"",
            "default: 0), micro: true),\n            when: \"!untabled_textures & !cpu_device\",\n            \
             inputs: { \"samples\": \"samples\", \"pyramid\"",
            "visibility (second phase)",
            "micro: true is for a first raster pass: the second phase of occlusion culling \
             adds to keys already flagged",
        ),
        (
            "micro_pixels: Param(name: \"micro_pixels\", default: 4)),\n            \
             when: \"!untabled_textures & !cpu_device & !blend & !points_lines\",",
            "micro_pixels: 17),\n            \
             when: \"!untabled_textures & !cpu_device & !blend & !points_lines\",",
            "visibility",
            "micro_pixels must be 1 to 16, got 17",
        ),
    ];
    for (from, to, pass, says) in cases {
        let line = crate::visibility::validate_error(from, to, "micro.ron", pass);
        assert!(line.contains(says), "{pass}: {line}");
    }
}
