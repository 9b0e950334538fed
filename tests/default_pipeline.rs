//! The default pipeline, pipelines/visibility_msaa_4x.ron, draws every feature a scene can
//! have through the visibility buffer, and renders what the specialised pipelines it
//! replaces render within 1/255 on at least 99% of pixels, on lavapipe in both its
//! branches: the compute raster (its branch for GPUs, compiled here as for one) and the
//! hardware raster (its branch for CPU adapters): an alpha BLEND model against
//! deferred_msaa_4x.ron, a textured alpha MASK model against the lean G-buffer (which
//! the file fell back to for it before), builtin:smoke's off-screen particles against
//! particles_low_res.ron.

use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::{AlphaMode, Lighting, Scene};
use serde_json::json;

use crate::deferred_support::measure::{self, pixels_within};
use crate::deferred_support::{gpu, unchanged, PipelineFile, Render};
use crate::gltf_writer::{temp_dir, Gltf};

/// The default pipeline on lavapipe: the hardware raster.
const DEFAULT: PipelineFile = PipelineFile::for_device("visibility_msaa_4x.ron");
/// Its branch for GPUs, the compute raster.
const DEFAULT_GPU: PipelineFile = PipelineFile::gpu_branch("visibility_msaa_4x.ron");

/// Checks that the default pipeline's two branches render `scene` within 1/255 of
/// `other`'s image at `size` on at least 99% of pixels, each compiled for the scene's
/// features (printed).
fn both_branches_agree(other: &str, scene: &Scene, size: (u32, u32)) {
    both_branches_agree_for(other, scene, size, SceneFeatures::of(scene));
}

/// [`both_branches_agree`], compiled for `features` rather than the scene's.
fn both_branches_agree_for(other: &str, scene: &Scene, size: (u32, u32), features: SceneFeatures) {
    let gpu = gpu();
    let image = |pipeline: PipelineFile| {
        Render::new(pipeline, &scene.name, size)
            .with_scene(scene.clone())
            .features(features.names())
            .run(&gpu)
            .image(&gpu, "color")
    };
    for default in [DEFAULT_GPU, DEFAULT] {
        let (image, others) = (image(default), image(PipelineFile::from(other)));
        let share = measure::share_within(&image, &others, 1, None);
        let scene = &scene.name;
        eprintln!(
            "{scene} through {default}: {:.4}% within 1/255 of {other}",
            share * 100.0
        );
        assert!(
            share >= 0.99,
            "{scene}: {default} renders only {share} of pixels within 1/255 of {other}"
        );
    }
}

/// builtin:spheres' red sphere alpha BLEND at 40% opacity, wholly in view.
fn red_sphere_blended(scene: &mut Scene) {
    let material = &mut scene.materials[1];
    material.alpha_mode = AlphaMode::Blend;
    material.base_color_factor[3] = 0.4;
}

/// builtin:spheres' ground alpha BLEND at 40% opacity: it reaches behind the camera, so
/// its blended rectangle is the whole output, and the spheres stand partly in front of
/// it.
fn ground_blended(scene: &mut Scene) {
    let material = &mut scene.materials[0];
    material.alpha_mode = AlphaMode::Blend;
    material.base_color_factor[3] = 0.4;
}

/// An alpha BLEND model renders deferred_msaa_4x's image: the transparent pass over the
/// compute raster's keys (through keys_depth) or the hardware raster's depth, at 1280x720
/// (where the G-buffer's quantised normals stay below a level on the glossy spheres:
/// tests/visibility.rs says why the size matters).
#[test]
fn an_alpha_blend_model_renders_the_gbuffers_image() {
    for edit in [red_sphere_blended, ground_blended] {
        let mut scene = Scene::load("builtin:spheres").unwrap();
        edit(&mut scene);
        assert!(SceneFeatures::of(&scene).blend);
        both_branches_agree("deferred_msaa_4x.ron", &scene, (1280, 720));
    }
}

/// Texels a side of the mask's texture.
const MASK_TEXELS: u32 = 8;

/// The masked quads written as a glTF file: an opaque green quad at z = -1 behind a quad
/// turned about the vertical axis (so that perspective stretches its texels), alpha MASK
/// at cutoff 0.5 with a base colour texture of 8 x 8 texels whose alpha is a checker
/// (sampled NEAREST, so both rasters' texel is the one under the pixel centre, whatever
/// the derivatives), under a perspective camera 3.5 units in front and the default
/// lighting (no lights in the file). Returns its path.
fn masked_quads_file() -> String {
    let mut gltf = Gltf::default();
    let quad = |gltf: &mut Gltf, corners: [[f32; 3]; 4], material: usize| {
        let positions = gltf.floats(&corners);
        let normal = {
            let [a, b, c, _] = corners.map(rgraph_scene::glam::Vec3::from);
            (b - a).cross(c - a).normalize().to_array()
        };
        let normals = gltf.floats(&[normal; 4]);
        let uvs = gltf.floats(&[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
        let indices = gltf.indices_u16(&[0, 1, 2, 0, 2, 3]);
        gltf.mesh(
            "quad",
            json!({
                "attributes": { "POSITION": positions, "NORMAL": normals, "TEXCOORD_0": uvs },
                "indices": indices,
                "material": material,
            }),
        );
    };
    let side = MASK_TEXELS;
    let texels: Vec<u8> = (0..side * side)
        .flat_map(|i| {
            let (x, y) = (i % side, i / side);
            let alpha = if (x + y) % 2 == 0 { 255 } else { 0 };
            [(40 + 25 * x) as u8, 90, (40 + 25 * y) as u8, alpha]
        })
        .collect();
    let image = gltf.png_image(side, side, &texels);
    // NEAREST, CLAMP_TO_EDGE.
    gltf.push(
        "samplers",
        json!({ "magFilter": 9728, "minFilter": 9728, "wrapS": 33071, "wrapT": 33071 }),
    );
    gltf.push("textures", json!({ "source": image, "sampler": 0 }));
    let back = gltf.push(
        "materials",
        json!({ "pbrMetallicRoughness": { "baseColorFactor": [0.2, 0.6, 0.3, 1.0],
                                          "metallicFactor": 0.0, "roughnessFactor": 0.8 } }),
    );
    let masked = gltf.push(
        "materials",
        json!({ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 },
                                          "metallicFactor": 0.0, "roughnessFactor": 0.6 },
                "alphaMode": "MASK", "alphaCutoff": 0.5 }),
    );
    quad(
        &mut gltf,
        [
            [-2.0, -2.0, -1.0],
            [2.0, -2.0, -1.0],
            [2.0, 2.0, -1.0],
            [-2.0, 2.0, -1.0],
        ],
        back,
    );
    quad(
        &mut gltf,
        [
            [-1.2, -1.0, 0.5],
            [1.2, -1.0, -0.5],
            [1.2, 1.0, -0.5],
            [-1.2, 1.0, 0.5],
        ],
        masked,
    );
    let camera = gltf.push(
        "cameras",
        json!({ "type": "perspective",
                "perspective": { "yfov": 0.8, "znear": 0.1, "zfar": 20.0 } }),
    );
    gltf.root(json!({ "camera": camera, "translation": [0.0, 0.0, 3.5] }));
    let path = temp_dir("default_pipeline_masked_quads").join("masked.gltf");
    gltf.write_embedded(&path);
    path.to_str().unwrap().to_owned()
}

/// The masked quad drawn opaque: what the mask cuts away shows.
fn unmasked(scene: &mut Scene) {
    scene.materials[1].alpha_mode = AlphaMode::Opaque;
}

/// A textured alpha MASK model takes the visibility buffer, its cutoff tested on the
/// texel's alpha read from the texture table in both rasters (before, it took the lean
/// G-buffer: feature `untabled_textures`), and renders the lean G-buffer's image.
#[test]
fn a_textured_alpha_mask_model_renders_the_lean_gbuffers_image() {
    let file = masked_quads_file();
    let scene = Scene::load(&file)
        .unwrap_or_else(|e| panic!("{e}"))
        .lit(Lighting::Auto);
    let features = SceneFeatures::of(&scene);
    assert!(features.mask_textures && !features.untabled_textures);
    let size = (240, 180);
    let gpu = gpu();
    let render = |pipeline, edit: fn(&mut Scene)| {
        let mut scene = scene.clone();
        edit(&mut scene);
        Render::new(pipeline, "masked quads", size)
            .with_scene(scene.clone())
            .features(SceneFeatures::of(&scene).names())
            .run(&gpu)
    };
    for pipeline in [DEFAULT_GPU, DEFAULT] {
        let frame = render(pipeline, unchanged);
        let passes: Vec<&str> = frame
            .plan()
            .passes
            .iter()
            .map(|p| p.name.as_str())
            .collect();
        assert!(
            passes.iter().any(|p| p.starts_with("visibility"))
                && !passes.iter().any(|p| p.starts_with("gbuffer")),
            "{pipeline}: {passes:?}"
        );
        // The checker cuts half the quad's texels away: a real share of the image shows
        // the green quad behind where the unmasked quad hides it.
        let masked = frame.image(&gpu, "color");
        let whole = render(pipeline, unmasked).image(&gpu, "color");
        let cut = masked.pixels.len() - pixels_within(&masked, &whole, 8);
        assert!(
            cut > masked.pixels.len() / 10,
            "{pipeline}: the mask changed only {cut} pixels"
        );
    }
    both_branches_agree("deferred_msaa_4x_lean.ron", &scene, size);
}

/// builtin:smoke's particles, off screen at half the output's size (the default scale)
/// in compute, against the file that draws them by the hardware
/// (particles_low_res.ron), at 640x360 (measured 99.17% through the compute raster,
/// 99.74% through the hardware raster: where they differ, thin poles and grass blades,
/// and the fire's soft edge against the ground, whose depth the compute raster's keys
/// hold as 32-bit floats and the G-buffer in 24 bits).
///
/// Compiled without shadows, the particles being the subject: with them the penumbrae
/// under the thin poles and blades differ by more than 1/255 on another 0.7% of pixels
/// (98.48% through the compute raster), the G-buffer's quantised normals offsetting the
/// shadow lookups differently from the rebuilt ones (tests/shadows.rs holds the two paths'
/// shadows to 2/255).
#[test]
fn smoke_renders_the_off_screen_particles_image() {
    let scene = Scene::load("builtin:smoke").unwrap();
    let features = SceneFeatures {
        shadows: false,
        ..SceneFeatures::of(&scene)
    };
    both_branches_agree_for("particles_low_res.ron", &scene, (640, 360), features);
}

/// The particles draw: without their passes (compiled as if the scene had none) a large
/// share of builtin:smoke changes, through the compute raster.
#[test]
fn the_default_pipeline_draws_particles() {
    let gpu = gpu();
    let scene = Scene::load("builtin:smoke").unwrap();
    let features = SceneFeatures::of(&scene);
    assert!(features.particles);
    let image = |features: SceneFeatures| {
        Render::new(DEFAULT_GPU, "builtin:smoke", (320, 180))
            .features(features.names())
            .run(&gpu)
            .image(&gpu, "color")
    };
    let with = image(features);
    let without = image(SceneFeatures {
        particles: false,
        ..features
    });
    let same = measure::share_within(&with, &without, 8, None);
    assert!(
        same < 0.5,
        "the particles changed only {:.1}%",
        100.0 * (1.0 - same)
    );
}
