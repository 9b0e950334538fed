//! KHR_materials_ior, _specular, _clearcoat and _sheen as the visibility buffer, forward
//! MSAA and the 16-sample reference shade them from the material, and the G-buffer
//! pipelines from the layers' targets, from glTF files the tests write: a unit
//! sphere (48 x 24 facets, smooth normals) at the origin under an orthographic camera 3
//! units in front (+z) whose view is 2.5 units across, so at 64x64 the sphere's outline is
//! a circle of 25.6 pixels' radius around the centre (32, 32). The files carry lights of
//! their own, so there is no default lighting: no environment, no ambient term.
//!
//! Where an image is compared with an analytic value it is the resolved HDR image (linear
//! radiance, before tone mapping), at pixels within 0.6 of the radius from the centre,
//! within 1.5% (`ANALYTIC`): there the visibility buffer and the reference are within
//! 0.3% of a Lambertian sphere without specular, forward MSAA within 1.3% (it is darker
//! than the other two towards the outline, 3.1% at 0.8 of the radius, with or without
//! these extensions), the G-buffer pipelines within 2.5% (`ANALYTIC_GBUFFER`). Shadows
//! are off: the sun lights all the camera sees.

use std::f32::consts::PI;

use std::sync::Arc;

use crate::cli_support::{render_stderr, rgraph};
use crate::deferred_support::measure::{diff, share_within};
use crate::deferred_support::{gpu, Render};
use crate::gltf_writer::{temp_dir, Gltf};
use rgraph_core::file::{load_file_with, GraphParams, Registry};
use rgraph_core::{CompileOptions, DeviceProfile};
use rgraph_passes::layers::{self, Layer};
use rgraph_passes::shadows::{ShadowFilter, Shadows};
use rgraph_passes::variant::Variants;
use rgraph_passes::{Host, Overrides};
use rgraph_scene::analysis::Features;
use rgraph_scene::{sheen_albedo, Lighting, Scene};
use serde_json::{json, Value};

const SIZE: (u32, u32) = (64, 64);
/// The sphere's outline radius in pixels: 1 unit of the 1.25-unit half view, of 32 pixels.
const RADIUS_PX: f32 = 25.6;
/// The pipelines that shade the layers from the material: they must agree with each
/// other.
const SHADING: [&str; 3] = [
    "visibility_msaa_4x.ron",
    "forward_msaa_4x.ron",
    "reference_ssaa16.ron",
];
/// And the G-buffer pipelines the analytic checks run too: one whose light passes read
/// the layers' targets, and the light pre-pass, whose material pass layers them over the
/// light its passes summed.
const GBUFFER_ANALYTIC: [&str; 2] = ["deferred_msaa_4x.ron", "light_prepass_msaa_4x.ron"];
/// The directional light's illuminance (lux): it travels along -z, from the camera.
const SUN: f32 = 3.0;
/// The base colour of the materials (linear grey) and their roughness.
const ALBEDO: f32 = 0.5;
const ROUGHNESS: f32 = 0.3;
/// How far from an analytic value a pixel may be, relative.
const ANALYTIC: f32 = 0.015;
/// The same for the G-buffer pipelines, whose sphere is as forward MSAA's (smooth normals
/// interpolated across the facets, no joining) and whose albedo has 8 bits: within 0.6 of
/// the radius the core sphere's pixels are 1.1% darker than Lambert's on average, 2.4% at
/// most, with or without the layers.
const ANALYTIC_GBUFFER: f32 = 0.025;

/// The tolerance of analytic checks through `pipeline`.
fn analytic(pipeline: &str) -> f32 {
    match GBUFFER_ANALYTIC.contains(&pipeline) {
        true => ANALYTIC_GBUFFER,
        false => ANALYTIC,
    }
}

/// The sphere with a grey dielectric material of roughness 0.3 and the material
/// `extensions` (an object by extension name), lit by the directional light from the
/// camera, written as `test`/sphere.gltf.
fn sphere_file(test: &str, extensions: Value) -> String {
    let mut gltf = Gltf::default();
    let mut used = vec!["KHR_lights_punctual".to_owned()];
    used.extend(extensions.as_object().unwrap().keys().cloned());
    gltf.json["extensionsUsed"] = json!(used);
    let (stacks, slices) = (24u16, 48u16);
    let (mut positions, mut uvs) = (Vec::new(), Vec::new());
    for i in 0..=stacks {
        let theta = PI * f32::from(i) / f32::from(stacks);
        for j in 0..=slices {
            let phi = 2.0 * PI * f32::from(j) / f32::from(slices);
            positions.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ]);
            uvs.push([
                f32::from(j) / f32::from(slices),
                f32::from(i) / f32::from(stacks),
            ]);
        }
    }
    let mut indices = Vec::new();
    let row = slices + 1;
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b) = (i * row + j, (i + 1) * row + j);
            indices.extend([a, a + 1, b, a + 1, b + 1, b]);
        }
    }
    let position = gltf.floats(&positions);
    let normal = gltf.floats(&positions);
    let uv = gltf.floats(&uvs);
    // Texture 0, for the extensions' texture slots: 2x2 texels across the sphere (each
    // channel its own pattern), filtered linearly so that its detail stays coarse.
    let image = gltf.png_image(
        2,
        2,
        &[
            255, 255, 255, 255, 160, 60, 220, 120, 60, 200, 140, 200, 220, 120, 40, 60,
        ],
    );
    gltf.push("samplers", json!({ "magFilter": 9729, "minFilter": 9729 }));
    gltf.push("textures", json!({ "source": image, "sampler": 0 }));
    let indices = gltf.indices_u16(&indices);
    let material = gltf.push(
        "materials",
        json!({
            "name": test,
            "pbrMetallicRoughness": {
                "baseColorFactor": [ALBEDO, ALBEDO, ALBEDO, 1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": ROUGHNESS,
            },
            "extensions": extensions,
        }),
    );
    gltf.mesh(
        "sphere",
        json!({
            "attributes": { "POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv },
            "indices": indices,
            "material": material,
        }),
    );
    let camera = gltf.push(
        "cameras",
        json!({ "type": "orthographic",
                "orthographic": { "xmag": 1.25, "ymag": 1.25, "znear": 0.1, "zfar": 10.0 } }),
    );
    gltf.root(json!({ "camera": camera, "translation": [0.0, 0.0, 3.0] }));
    gltf.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": SUN }
    ] } });
    gltf.root(json!({ "extensions": { "KHR_lights_punctual": { "light": 0 } } }));
    let path = temp_dir(test).join("sphere.gltf");
    gltf.write_embedded(&path);
    path.to_str().unwrap().to_owned()
}

fn load(file: &str) -> Scene {
    let scene = Scene::load(file).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    scene
}

/// The resolved HDR image of `file` through `pipeline`, compiled for the file's layers'
/// features and shaders compiled as `variants`, without shadows (the sun lights the whole
/// half of the sphere the camera sees).
fn resolved(pipeline: &str, file: &str, variants: Variants) -> Vec<[f32; 4]> {
    let gpu = gpu();
    let shadows = Shadows {
        filter: ShadowFilter::Off,
        ..Shadows::default()
    };
    let scene = load(file);
    Render::new(pipeline, file, SIZE)
        .features(layer_features(&scene))
        .with_scene(scene)
        .overrides(Overrides {
            shadows,
            ..Overrides::default()
        })
        .variants(variants)
        .export_resolved()
        .run(&gpu)
        .hdr(&gpu, "resolved")
}

/// The pixel's offset from the sphere's centre in units of its radius, and `n·z` there.
fn on_sphere(x: u32, y: u32) -> (f32, f32) {
    let dx = (x as f32 + 0.5 - 32.0) / RADIUS_PX;
    let dy = (y as f32 + 0.5 - 32.0) / RADIUS_PX;
    let r2 = dx * dx + dy * dy;
    (r2.sqrt(), (1.0 - r2).max(0.0).sqrt())
}

/// The pixels within `within` of the radius from the centre.
fn disc(within: f32) -> impl Iterator<Item = (u32, u32)> {
    (0..SIZE.1)
        .flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
        .filter(move |&(x, y)| on_sphere(x, y).0 < within)
}

/// The four pixels around the centre, where the surface faces the camera and the sun
/// within 1.6 degrees: the peak of a specular highlight.
fn centre() -> impl Iterator<Item = (u32, u32)> {
    disc(0.06)
}

/// A Lambertian surface of the test's albedo under the sun, at pixel (x, y).
fn lambert(x: u32, y: u32) -> f32 {
    ALBEDO / PI * SUN * on_sphere(x, y).1
}

fn at(image: &[[f32; 4]], x: u32, y: u32) -> [f32; 4] {
    image[(y * SIZE.0 + x) as usize]
}

/// KHR_materials_ior: 1.5 is the core model (F0 0.04): the general shader, which runs
/// the specular layer's code with the material's F0, renders the default material's
/// image bit for bit. 1.0 makes F0 0: facing the light, the highlight's centre is the
/// Lambertian term alone within 0.12 of the radius, where the core model's
/// highlight peaks at more than twice it.
#[test]
fn ior_1_5_is_the_core_model_and_ior_1_removes_the_facing_highlight() {
    let core = sphere_file("layers_core", json!({}));
    let ior_1_5 = sphere_file(
        "layers_ior_1_5",
        json!({ "KHR_materials_ior": { "ior": 1.5 } }),
    );
    let ior_1 = sphere_file(
        "layers_ior_1",
        json!({ "KHR_materials_ior": { "ior": 1.0 } }),
    );
    for pipeline in SHADING.into_iter().chain(GBUFFER_ANALYTIC) {
        let core = resolved(pipeline, &core, Variants::Scene);
        let general = resolved(pipeline, &ior_1_5, Variants::General);
        let differ = core.iter().zip(&general).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{pipeline}: ior 1.5 differs from the core model");
        let air = resolved(pipeline, &ior_1, Variants::Scene);
        for (x, y) in disc(0.12) {
            let want = lambert(x, y);
            let got = at(&air, x, y)[0];
            assert!(
                (got - want).abs() <= analytic(pipeline) * want,
                "{pipeline}: ior 1 at ({x}, {y}): {got}, Lambert {want}"
            );
        }
        for (x, y) in centre() {
            let want = lambert(x, y);
            let highlight = at(&core, x, y)[0];
            assert!(
                highlight > 2.0 * want,
                "{pipeline}: the core model's highlight at ({x}, {y}): {highlight}, Lambert {want}"
            );
        }
    }
}

/// KHR_materials_specular: specularFactor 0 leaves no specular at all, grazing
/// reflections included: every pixel within 0.6 of the radius is the Lambertian term. A red specularColorFactor keeps the highlight in red only: green and blue
/// at its peak are Lambert's, red more than twice it.
#[test]
fn specular_factor_0_is_lambert_and_specular_color_tints_the_highlight() {
    let none = sphere_file(
        "layers_specular_0",
        json!({ "KHR_materials_specular": { "specularFactor": 0.0 } }),
    );
    let red = sphere_file(
        "layers_specular_red",
        json!({ "KHR_materials_specular": { "specularColorFactor": [1.0, 0.0, 0.0] } }),
    );
    for pipeline in SHADING.into_iter().chain(GBUFFER_ANALYTIC) {
        let image = resolved(pipeline, &none, Variants::Scene);
        for (x, y) in disc(0.6) {
            let want = lambert(x, y);
            let got = at(&image, x, y);
            assert!(
                got[..3]
                    .iter()
                    .all(|c| (c - want).abs() <= analytic(pipeline) * want),
                "{pipeline}: specular 0 at ({x}, {y}): {got:?}, Lambert {want}"
            );
        }
        let image = resolved(pipeline, &red, Variants::Scene);
        for (x, y) in centre() {
            let want = lambert(x, y);
            let [r, g, b, _] = at(&image, x, y);
            assert!(
                [g, b]
                    .iter()
                    .all(|c| (c - want).abs() <= analytic(pipeline) * want)
                    && r > 2.0 * want,
                "{pipeline}: red specular at ({x}, {y}): {:?}, Lambert {want}",
                [r, g, b]
            );
        }
    }
}

/// KHR_materials_clearcoat: factor 0 is no coat (the general shaders, which run the
/// coat's code, render the core model's image bit for bit). A full coat of roughness 0.2
/// over the base adds its own sharper highlight (the peak more than 1.5 times the core
/// model's), and elsewhere takes from the base what it reflects: between 0.45 and 0.6 of
/// the radius, where its lobe adds less than 0.1%, each pixel is the core model's times
/// 1 - F, with F the coat's Fresnel (F0 0.04) at the angle between the normal and the
/// view, within 0.5%.
#[test]
fn a_clear_coat_adds_its_highlight_and_dims_the_base_by_its_fresnel() {
    let core = sphere_file("layers_coat_core", json!({}));
    let none = sphere_file(
        "layers_coat_0",
        json!({ "KHR_materials_clearcoat": { "clearcoatFactor": 0.0, "clearcoatRoughnessFactor": 0.5 } }),
    );
    let coat = sphere_file(
        "layers_coat_1",
        json!({ "KHR_materials_clearcoat": { "clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.2 } }),
    );
    for pipeline in SHADING.into_iter().chain(GBUFFER_ANALYTIC) {
        let core = resolved(pipeline, &core, Variants::Scene);
        let general = resolved(pipeline, &none, Variants::General);
        let differ = core.iter().zip(&general).filter(|(a, b)| a != b).count();
        assert_eq!(
            differ, 0,
            "{pipeline}: clearcoat 0 differs from the core model"
        );
        let coated = resolved(pipeline, &coat, Variants::Scene);
        for (x, y) in centre() {
            let (bare, peak) = (at(&core, x, y)[0], at(&coated, x, y)[0]);
            assert!(
                peak > 1.5 * bare,
                "{pipeline}: the coat's peak at ({x}, {y}): {peak}, without the coat {bare}"
            );
        }
        for (x, y) in disc(0.6).filter(|&(x, y)| on_sphere(x, y).0 > 0.45) {
            let want = at(&core, x, y)[0] * (1.0 - coat_fresnel(x, y));
            let got = at(&coated, x, y)[0];
            assert!(
                (got - want).abs() <= 0.005 * want,
                "{pipeline}: coated at ({x}, {y}): {got}, the base through the coat {want}"
            );
        }
    }
}

/// The Fresnel of a clear coat (F0 0.04) on the sphere at pixel (x, y).
fn coat_fresnel(x: u32, y: u32) -> f32 {
    0.04 + 0.96 * (1.0 - view_cosine(x, y)).powi(5)
}

/// The cosine between the sphere's normal at pixel (x, y) and the view, toward the camera
/// 3 units in front of the centre (the shaders' view: toward the camera's position).
fn view_cosine(x: u32, y: u32) -> f32 {
    let (dx, dy) = (
        (x as f32 + 0.5 - 32.0) / RADIUS_PX,
        -(y as f32 + 0.5 - 32.0) / RADIUS_PX,
    );
    let n = [dx, dy, on_sphere(x, y).1];
    let to_camera = [-n[0], -n[1], 3.0 - n[2]];
    let length = to_camera.iter().map(|c| c * c).sum::<f32>().sqrt();
    n.iter().zip(to_camera).map(|(a, b)| a * b).sum::<f32>() / length
}

/// KHR_materials_sheen (white, roughness 0.5) brightens the rim, where the Charlie lobe
/// of fibres lit and seen at grazing angles peaks: every pixel between 0.85 and 0.95 of
/// the radius is more than twice the core model's. Facing the light and the camera the
/// lobe adds almost nothing and the base keeps 1 - E of its light, E the sheen's albedo
/// there (rgraph_scene::sheen_albedo, about 0.03): within 0.12 of the radius each pixel is
/// the core model's times 1 - E within 1%. Black sheen is no sheen (the general shaders
/// render the core model's image bit for bit).
#[test]
fn sheen_brightens_the_rim_and_scales_the_facing_base() {
    let core = sphere_file("layers_sheen_core", json!({}));
    let black = sphere_file(
        "layers_sheen_black",
        json!({ "KHR_materials_sheen": { "sheenRoughnessFactor": 0.5 } }),
    );
    let sheen = sphere_file(
        "layers_sheen",
        json!({ "KHR_materials_sheen": { "sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5 } }),
    );
    for pipeline in SHADING.into_iter().chain(GBUFFER_ANALYTIC) {
        let core = resolved(pipeline, &core, Variants::Scene);
        let general = resolved(pipeline, &black, Variants::General);
        let differ = core.iter().zip(&general).filter(|(a, b)| a != b).count();
        assert_eq!(
            differ, 0,
            "{pipeline}: black sheen differs from the core model"
        );
        let sheen = resolved(pipeline, &sheen, Variants::Scene);
        for (x, y) in disc(0.95).filter(|&(x, y)| on_sphere(x, y).0 > 0.85) {
            let (bare, rim) = (at(&core, x, y)[0], at(&sheen, x, y)[0]);
            assert!(
                rim > 2.0 * bare,
                "{pipeline}: sheen at the rim ({x}, {y}): {rim}, without it {bare}"
            );
        }
        for (x, y) in disc(0.12) {
            let scaling = 1.0 - sheen_albedo(view_cosine(x, y), 0.5);
            let want = at(&core, x, y)[0] * scaling;
            let got = at(&sheen, x, y)[0];
            assert!(
                (got - want).abs() <= 0.01 * want,
                "{pipeline}: sheen facing at ({x}, {y}): {got}, the base scaled by {scaling}: {want}"
            );
        }
    }
}

/// A material using all four extensions, each with a texture of its own (one 2x2 image
/// in every slot, the clear coat's normals included), under the scene's sun and the
/// default lighting (the studio environment and the headlight, so the layers' image-based
/// lighting too): the visibility buffer, forward MSAA and the reference render 8-bit
/// images within 2/255 of each other on at least 99% of pixels (the two 4x pipelines
/// everywhere, each against the reference away from the outline, which its 16 samples
/// cover differently). Measured: 99.88%, 100% and 99.97%; with the visibility buffer's
/// layers left plain, 64% of its pixels are within 2/255 of forward's.
#[test]
fn all_four_layers_agree_across_the_pipelines_that_shade_them() {
    let texture = || json!({ "index": 0 });
    let file = sphere_file(
        "layers_all_four",
        json!({
            "KHR_materials_ior": { "ior": 1.8 },
            "KHR_materials_specular": {
                "specularFactor": 0.8,
                "specularTexture": texture(),
                "specularColorFactor": [1.0, 0.8, 0.6],
                "specularColorTexture": texture(),
            },
            "KHR_materials_clearcoat": {
                "clearcoatFactor": 0.8,
                "clearcoatTexture": texture(),
                "clearcoatRoughnessFactor": 0.3,
                "clearcoatRoughnessTexture": texture(),
                "clearcoatNormalTexture": { "index": 0, "scale": 0.3 },
            },
            "KHR_materials_sheen": {
                "sheenColorFactor": [0.6, 0.3, 0.9],
                "sheenColorTexture": texture(),
                "sheenRoughnessFactor": 0.6,
                "sheenRoughnessTexture": texture(),
            },
        }),
    );
    let scene = load(&file).lit(Lighting::Default);
    let features = Features::of(&scene);
    assert!(features.specular && features.clearcoat && features.sheen && features.environment);
    let gpu = gpu();
    let image = |pipeline: &str| {
        Render::new(pipeline, &file, SIZE)
            .with_scene(scene.clone())
            .run(&gpu)
            .image(&gpu, "color")
    };
    let [visibility, forward, reference] = SHADING.map(image);
    // The outline's pixels, which 4 samples and the reference's 16 cover differently.
    let inside: Vec<bool> = (0..SIZE.1)
        .flat_map(|y| (0..SIZE.0).map(move |x| (on_sphere(x, y).0 - 1.0).abs() * RADIUS_PX > 1.5))
        .collect();
    for (a, b, mask) in [
        ((SHADING[0], &visibility), (SHADING[1], &forward), None),
        (
            (SHADING[0], &visibility),
            (SHADING[2], &reference),
            Some(&inside[..]),
        ),
        (
            (SHADING[1], &forward),
            (SHADING[2], &reference),
            Some(&inside[..]),
        ),
    ] {
        let share = share_within(a.1, b.1, 2, mask);
        assert!(
            share >= 0.99,
            "{} against {}: {:.2}% of pixels within 2/255 ({})",
            a.0,
            b.0,
            share * 100.0,
            diff(a.1, b.1, mask)
        );
    }
}

/// The G-buffer pipelines, which store the layers in targets of their own where the
/// scene's materials use them (common/gbuffer_layers.rs), the light pre-pass the coat and
/// the sheen.
const GBUFFER: [&str; 4] = [
    "deferred_msaa_4x.ron",
    "deferred_msaa_4x_tiled.ron",
    "deferred_msaa_4x_lean.ron",
    "light_prepass_msaa_4x.ron",
];

/// The scene features the layers' targets are declared under.
const LAYER_FEATURES: [&str; 5] = [
    "specular",
    "clearcoat",
    "clearcoat_normal",
    "sheen",
    "layer_lobes",
];

/// The layer features `scene` has: what a G-buffer pipeline's plan keeps their targets
/// for (the rest of the scene's features left off, as the other tests here leave them).
fn layer_features(scene: &Scene) -> rgraph_core::Features {
    let names = Features::of(scene).names();
    names
        .iter()
        .filter(|f| LAYER_FEATURES.contains(f))
        .collect()
}

/// A material using all four extensions, as `all_four_layers_agree...` writes it, with
/// the clear coat's normal texture where `coat_normal` (the coat then bends apart from
/// the base, and a G-buffer stores its normal), else its textures but that one.
fn four_layers(test: &str, coat_normal: bool) -> String {
    let texture = || json!({ "index": 0 });
    let mut coat = json!({
        "clearcoatFactor": 0.8,
        "clearcoatTexture": texture(),
        "clearcoatRoughnessFactor": 0.3,
        "clearcoatRoughnessTexture": texture(),
    });
    if coat_normal {
        coat["clearcoatNormalTexture"] = json!({ "index": 0, "scale": 0.3 });
    }
    sphere_file(
        test,
        json!({
            "KHR_materials_ior": { "ior": 1.8 },
            "KHR_materials_specular": {
                "specularFactor": 0.8,
                "specularTexture": texture(),
                "specularColorFactor": [1.0, 0.8, 0.6],
                "specularColorTexture": texture(),
            },
            "KHR_materials_clearcoat": coat,
            "KHR_materials_sheen": {
                "sheenColorFactor": [0.6, 0.3, 0.9],
                "sheenColorTexture": texture(),
                "sheenRoughnessFactor": 0.6,
                "sheenRoughnessTexture": texture(),
            },
        }),
    )
}

/// The G-buffer pipelines shade all four layers as the visibility buffer does (which
/// reads them from the material table, unquantised): each 8-bit image within 2/255 of
/// the visibility buffer's on at least 99% of pixels, with the coat's own normal
/// (an rgba16float coat target) and without (rg8unorm, the base's normal), under the
/// sun and the default lighting's environment and headlight. Measured: see the commit;
/// with the layers decoded as the core model's, the deferred images agree on 64% to 70%.
#[test]
fn the_g_buffer_pipelines_shade_the_layers_as_the_visibility_buffer_does() {
    let gpu = gpu();
    for (file, coat) in [
        (
            four_layers("layers_gbuffer_coat_normal", true),
            "its own normal",
        ),
        (four_layers("layers_gbuffer", false), "the base's normal"),
    ] {
        let scene = load(&file).lit(Lighting::Default);
        let features = layer_features(&scene);
        let image = |pipeline: &str| {
            Render::new(pipeline, &file, SIZE)
                .with_scene(scene.clone())
                .features(features.clone())
                .run(&gpu)
                .image(&gpu, "color")
        };
        let visibility = image("visibility_msaa_4x.ron");
        for pipeline in GBUFFER {
            let gbuffer = image(pipeline);
            let share = share_within(&visibility, &gbuffer, 2, None);
            eprintln!(
                "{pipeline}, the coat with {coat}: {:.2}% of pixels within 2/255 of the \
                 visibility buffer's",
                share * 100.0
            );
            assert!(
                share >= 0.99,
                "{pipeline}, the coat with {coat}: {:.2}% of pixels within 2/255 ({})",
                share * 100.0,
                diff(&visibility, &gbuffer, None)
            );
        }
    }
}

/// The G-buffer pass's colour bytes per sample as WebGPU counts them and as stored (the
/// depth-stencil included) in `pipeline`'s plan for `scene`, compiled for its layer
/// features on `profile`; and the layers the plan's lighting leaves out.
fn gbuffer_bytes(
    pipeline: &str,
    scene: &Scene,
    profile: DeviceProfile,
) -> ((u32, u32), Vec<Layer>) {
    let host = Arc::new(Host::new(Arc::new(scene.clone()), Overrides::default()));
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, Some(host));
    let path = format!("pipelines/{pipeline}");
    let loaded =
        load_file_with(&path, &registry, &GraphParams::new()).unwrap_or_else(|e| panic!("{e}"));
    let options = CompileOptions {
        output_size: SIZE,
        profile,
    };
    let plan = loaded
        .compile_for(&options, &layer_features(scene))
        .unwrap_or_else(|e| panic!("{e}"));
    let gbuffer = plan
        .passes
        .iter()
        .find(|p| p.name.starts_with("gbuffer"))
        .unwrap_or_else(|| panic!("{pipeline} has no G-buffer pass"));
    let bytes = (
        gbuffer.color_bytes_per_sample,
        gbuffer.stored_bytes_per_sample,
    );
    let left_out = layers::unshaded(&plan, &loaded);
    (bytes, left_out.iter().map(|u| u.layer).collect())
}

/// A core scene's G-buffer is the bytes per sample it was before the layers (WebGPU's
/// count, stored with the depth-stencil): 32 and 32 for deferred_msaa_4x.ron, 20 and 16
/// for the lean one, 16 and 20 for the light pre-pass's thin one. A layered scene's adds
/// each layer's target: the specular layer 4 bytes (8 counted), the coat 2 and with its
/// own normal 8, the sheen 4 (8), in every G-buffer pipeline but the light pre-pass,
/// whose thin G-buffer needs only the coat and the sheen. On a device that allows 32
/// bytes per sample of colour targets (WebGPU's defaults) the full and the lean G-buffers
/// have no room: their plans store no layer, and their lighting leaves each out.
#[test]
fn a_core_scene_s_g_buffer_keeps_its_bytes_and_each_layer_adds_its_own() {
    let gpu = gpu();
    let core = load(&sphere_file("layers_bytes_core", json!({})));
    let plain_coat = load(&four_layers("layers_bytes_plain_coat", false)).lit(Lighting::Default);
    let coat_normal = load(&four_layers("layers_bytes_coat_normal", true)).lit(Lighting::Default);
    for (pipeline, today, plain, with_normal) in [
        ("deferred_msaa_4x.ron", (32, 32), (50, 42), (56, 48)),
        ("deferred_msaa_4x_lean.ron", (20, 16), (38, 26), (44, 32)),
        ("light_prepass_msaa_4x.ron", (16, 20), (26, 26), (32, 32)),
    ] {
        let bytes = |scene: &Scene| gbuffer_bytes(pipeline, scene, gpu.profile());
        assert_eq!(bytes(&core).0, today, "{pipeline}: the core scene");
        assert_eq!(
            bytes(&plain_coat),
            (plain, vec![]),
            "{pipeline}: four layers"
        );
        assert_eq!(
            bytes(&coat_normal),
            (with_normal, vec![]),
            "{pipeline}: the coat's normal"
        );
    }
    let webgpu = DeviceProfile::webgpu();
    for pipeline in ["deferred_msaa_4x.ron", "deferred_msaa_4x_lean.ron"] {
        let (core_bytes, _) = gbuffer_bytes(pipeline, &core, webgpu.clone());
        let (bytes, left_out) = gbuffer_bytes(pipeline, &coat_normal, webgpu.clone());
        assert_eq!(bytes, core_bytes, "{pipeline} on WebGPU's defaults");
        for layer in Layer::ALL {
            assert!(
                left_out.contains(&layer),
                "{pipeline}: {layer:?} in {left_out:?}"
            );
        }
    }
}

/// `rgraph bench`'s "G-buf B/sample" column (stored, and WebGPU's count in brackets) and
/// results.json give a layered scene's G-buffer its layers' bytes: the sphere is shallow
/// (depth24plus-stencil8, 4 bytes), so its core G-buffer would be 28 (32), and its four
/// layers with the coat's normal add 16 (24).
#[test]
fn the_bench_counts_the_layers_bytes() {
    let file = four_layers("layers_bench", true);
    let dir = temp_dir("layers_bench_out");
    let out = dir.to_str().unwrap();
    let args = [
        "bench",
        "--width",
        "64",
        "--height",
        "48",
        "--frames",
        "1",
        "--rounds",
        "1",
        "--warmup",
        "0",
        "--no-reference",
        "--scene",
        &file,
        "--pipeline",
        "pipelines/deferred_msaa_4x.ron",
        "--out-dir",
        out,
    ];
    rgraph(&args).expect(0);
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    let memory = &json["rows"][0]["figures"]["memory"];
    assert_eq!(memory["gbuffer_stored_bytes_per_sample"], 44, "{json:#}");
    assert_eq!(memory["gbuffer_bytes_per_sample"], 56, "{json:#}");
    let table = std::fs::read_to_string(dir.join("results.md")).unwrap();
    assert!(table.contains("| 44 (56) |"), "{table}");
}

/// `rgraph render` says nothing of the layers where a G-buffer pipeline stores and shades
/// them (deferred_msaa_4x.ron, the light pre-pass), nor with the pipelines that shade them
/// from the material; where a pipeline's lighting still leaves one out (the G-buffer
/// resolve, whose one-sample G-buffer has no room for them), it names the extension, the
/// material, the pass and the pipeline.
#[test]
fn render_warns_only_where_a_g_buffer_leaves_the_layers_out() {
    let file = sphere_file(
        "layers_warning",
        json!({
            "KHR_materials_ior": { "ior": 1.33 },
            "KHR_materials_specular": { "specularFactor": 0.5 },
            "KHR_materials_clearcoat": { "clearcoatFactor": 1.0 },
            "KHR_materials_sheen": { "sheenColorFactor": [1.0, 1.0, 1.0] },
        }),
    );
    let out = temp_dir("layers_warning_out").join("frame.png");
    let pipeline = "pipelines/deferred_gbuffer_resolve_4x.ron";
    let stderr = render_stderr(pipeline, &file, (16, 16), &out);
    for extension in [
        "KHR_materials_clearcoat",
        "KHR_materials_ior",
        "KHR_materials_sheen",
        "KHR_materials_specular",
    ] {
        let expected = format!(
            "warning: material 0 \"layers_warning\" uses {extension}, but pass \"light\" of \
             {pipeline} shades opaque surfaces from a G-buffer without it: its effect is left \
             out there"
        );
        assert!(stderr.contains(&expected), "{expected}\nnot in:\n{stderr}");
    }
    for pipeline in SHADING.into_iter().chain(GBUFFER) {
        let stderr = render_stderr(&format!("pipelines/{pipeline}"), &file, (16, 16), &out);
        assert!(!stderr.contains("KHR_materials"), "{pipeline}: {stderr}");
    }
}
