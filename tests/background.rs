//! What a frame shows where nothing is drawn (the host's `Background`, `rgraph render
//! --background`): the environment as a mirror reflects it, a colour, or transparency
//! (the output's alpha the coverage). The pipelines that draw one (a `background` pass
//! under the condition `background`: the default, deferred_msaa_4x.ron, the lean and
//! tiled G-buffers, forward MSAA) draw it alike; the others refuse the flag.

use rgraph_passes::{Background, Overrides};
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::glam::DVec3;
use rgraph_scene::{environment_radiance, Lighting, Projection, Scene};
use serde_json::json;

use crate::cli_support::rgraph;
use crate::deferred_support::{gpu, srgb8, Image, PipelineFile, Render};
use crate::gltf_writer::{temp_dir, Gltf};

/// The default pipeline's two branches and a hardware-raster pipeline of each kind that
/// draws the background.
const PIPELINES: [PipelineFile; 4] = [
    PipelineFile::gpu_branch("visibility_msaa_4x.ron"),
    PipelineFile::for_device("visibility_msaa_4x.ron"),
    PipelineFile::for_device("deferred_msaa_4x.ron"),
    PipelineFile::for_device("forward_msaa_4x.ron"),
];

const SIZE: (u32, u32) = (240, 135);

/// `scene` through `pipeline` with `background` (none: the pipeline's own), compiled for
/// the scene's features and, with a background, the condition `background`, as `rgraph
/// render` compiles it.
fn render(pipeline: PipelineFile, scene: &Scene, background: Option<Background>) -> Image {
    render_with(pipeline, scene, background, SceneFeatures::of(scene))
}

/// [`render`] for the scene's features as `features` gives them.
fn render_with(
    pipeline: PipelineFile,
    scene: &Scene,
    background: Option<Background>,
    mut features: SceneFeatures,
) -> Image {
    let gpu = gpu();
    features.background = background.is_some();
    Render::new(pipeline, &scene.name, SIZE)
        .with_scene(scene.clone())
        .features(features.names())
        .overrides(Overrides {
            background,
            ..Overrides::default()
        })
        .run(&gpu)
        .image(&gpu, "color")
}

/// A transparent background leaves alpha 0 where nothing is drawn (builtin:spheres' sky,
/// black), 255 where every sample shows a surface (the colour exactly what the pipeline
/// draws without a background), and the share of covered samples at silhouettes
/// against the sky; a colour background is exactly that colour where nothing is drawn,
/// and changes nothing where every sample shows a surface.
#[test]
fn transparent_and_colour_backgrounds_are_exact_where_nothing_or_everything_is_drawn() {
    let scene = Scene::load("builtin:spheres").unwrap();
    let color = [40, 80, 200];
    for pipeline in PIPELINES {
        let plain = render(pipeline, &scene, None);
        let clear = render(pipeline, &scene, Some(Background::Transparent));
        let colored = render(pipeline, &scene, Some(Background::Color(color)));
        let (mut empty, mut partial, mut covered) = (0, 0, 0);
        for ((c, p), k) in clear.pixels.iter().zip(&plain.pixels).zip(&colored.pixels) {
            match c[3] {
                0 => {
                    empty += 1;
                    assert_eq!(c, &[0, 0, 0, 0], "{pipeline}: a transparent pixel");
                    assert_eq!(k, &[color[0], color[1], color[2], 255], "{pipeline}");
                }
                255 => {
                    covered += 1;
                    assert_eq!(c, p, "{pipeline}: a covered pixel, transparent background");
                    assert_eq!(k, p, "{pipeline}: a covered pixel, colour background");
                }
                _ => partial += 1,
            }
        }
        let pixels = clear.pixels.len();
        eprintln!("{pipeline}: {empty} empty, {partial} partial, {covered} covered of {pixels}");
        assert!(
            empty > pixels / 10,
            "{pipeline}: only {empty} pixels show the sky"
        );
        assert!(
            covered > pixels / 3,
            "{pipeline}: only {covered} covered pixels"
        );
        assert!(partial > 50, "{pipeline}: only {partial} silhouette pixels");
    }
}

/// A small triangle far in front of a perspective camera, in a file without lights (so
/// the default lighting, whose environment shows behind it), written as a glTF file.
fn lone_triangle() -> Scene {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    let camera = gltf.push(
        "cameras",
        json!({ "type": "perspective",
                "perspective": { "yfov": 1.2, "znear": 0.1, "zfar": 100.0 } }),
    );
    // Turned a little up, so the sky's gradient and a soft box cross the view.
    gltf.root(json!({ "camera": camera, "translation": [0.3, 0.3, 6.0],
                      "rotation": [0.17, 0.0, 0.0, 0.985] }));
    let path = temp_dir("background_lone_triangle").join("triangle.gltf");
    gltf.write_embedded(&path);
    let scene = Scene::load(path.to_str().unwrap())
        .unwrap_or_else(|e| panic!("{e}"))
        .lit(Lighting::Auto);
    assert!(
        SceneFeatures::of(&scene).environment,
        "the default lighting"
    );
    scene
}

/// The sRGB bytes of the neutral environment's radiance (scene/src/environment.rs) seen
/// through pixel `(x, y)` of `scene`'s camera at SIZE, ACES tone mapped at exposure 1 as
/// the pipelines' default tone mapping maps it.
fn environment_seen(scene: &Scene, x: u32, y: u32) -> [u8; 3] {
    let Projection::Perspective { yfov, .. } = scene.camera.projection else {
        panic!("a perspective camera");
    };
    let (w, h) = (f64::from(SIZE.0), f64::from(SIZE.1));
    let ndc = (
        (f64::from(x) + 0.5) / w * 2.0 - 1.0,
        1.0 - (f64::from(y) + 0.5) / h * 2.0,
    );
    let tan = (f64::from(yfov) / 2.0).tan();
    let view = DVec3::new(ndc.0 * tan * w / h, ndc.1 * tan, -1.0);
    let d = (scene.camera.orientation * view).normalize().as_vec3();
    let intensity = scene.environment.map_or(0.0, |e| e.intensity);
    let l = f64::from(environment_radiance(d) * intensity);
    let aces = (l * (2.51 * l + 0.03)) / (l * (2.43 * l + 0.59) + 0.14);
    [srgb8(aces); 3]
}

/// The environment background is the environment's radiance through each pixel, as the
/// CPU evaluates the procedural studio, within 2/255: the shaders read level 0 of its
/// 32 x 32 cube map, bilinearly (measured at most 1/255 on lavapipe, every pipeline).
/// Without a background the same pixels are black. Both depth conventions: the G-buffer
/// pipelines compiled for `shallow_depth` keep standard Z, where the ray through a pixel
/// runs the other way between two clip depths (a background seen backwards, on FlightHelmet
/// in the H200 bench, before the shader turned the ray forward).
#[test]
fn the_environment_background_shows_the_environments_radiance() {
    let scene = lone_triangle();
    for (pipeline, shallow) in PIPELINES.into_iter().flat_map(|p| [(p, false), (p, true)]) {
        let mut features = SceneFeatures::of(&scene);
        features.shallow_depth = shallow;
        let render = |background| render_with(pipeline, &scene, background, features);
        let clear = render(Some(Background::Transparent));
        let shown = render(Some(Background::Environment));
        let plain = render(None);
        let mut worst = (0, (0, 0));
        let mut empty = 0;
        for (i, (c, s)) in clear.pixels.iter().zip(&shown.pixels).enumerate() {
            if c[3] != 0 {
                continue;
            }
            empty += 1;
            let (x, y) = (i as u32 % SIZE.0, i as u32 / SIZE.0);
            assert_eq!(plain.pixels[i], [0, 0, 0, 255], "{pipeline} at ({x}, {y})");
            let expected = environment_seen(&scene, x, y);
            let off = (0..3).map(|k| s[k].abs_diff(expected[k])).max().unwrap();
            assert_eq!(s[3], 255);
            if off > worst.0 {
                worst = (off, (x, y));
            }
        }
        eprintln!(
            "{pipeline} (shallow_depth {shallow}): {empty} background pixels, worst {worst:?}"
        );
        assert!(empty > clear.pixels.len() / 2, "{pipeline}: {empty}");
        assert!(
            worst.0 <= 2,
            "{pipeline} (shallow_depth {shallow}): {}/255 off at {:?}",
            worst.0,
            worst.1
        );
    }
}

/// `rgraph render --background` on a pipeline without a background pass is refused,
/// naming the flag and the pipeline, before anything is written; `environment` on a scene
/// with lights of its own (no environment) is refused too.
#[test]
fn a_background_a_pipeline_cannot_draw_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frame.png");
    let out = out.to_str().unwrap();
    let common = ["render", "--width", "32", "--height", "24", "--out", out];
    rgraph(
        &[
            &common[..],
            &[
                "--pipeline",
                "pipelines/deferred_noaa.ron",
                "--background",
                "transparent",
            ],
        ]
        .concat(),
    )
    .expect(1)
    .stderr_has(
        "--background transparent: pipelines/deferred_noaa.ron has no background pass \
             that runs for this output",
    );
    rgraph(&[&common[..], &["--background", "environment"]].concat())
        .expect(1)
        .stderr_has("--background environment: scene builtin:spheres has no environment");
    rgraph(&[&common[..], &["--background", "color:1,2"]].concat())
        .expect(2)
        .stderr_has("expected environment, transparent or color:R,G,B");
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}

/// The default pipeline's PNG with `--background transparent` has a real alpha channel:
/// 0 where nothing is drawn.
#[test]
fn a_transparent_background_writes_alpha_into_the_png() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("frame.png");
    let out_str = out.to_str().unwrap();
    rgraph(&[
        "render",
        "--width",
        "64",
        "--height",
        "36",
        "--out",
        out_str,
        "--background",
        "transparent",
    ])
    .expect(0);
    let image = image::open(&out).unwrap();
    assert!(image.color().has_alpha());
    let image = image.into_rgba8();
    let clear = image.pixels().filter(|p| p.0[3] == 0).count();
    let opaque = image.pixels().filter(|p| p.0[3] == 255).count();
    assert!(
        clear > 100 && opaque > 100,
        "{clear} transparent, {opaque} opaque"
    );
}
