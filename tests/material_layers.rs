//! KHR_materials_ior, _specular, _clearcoat and _sheen as the visibility buffer, forward
//! MSAA and the 16-sample reference shade them, from glTF files the tests write: a unit
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
//! these extensions). Shadows are off: the sun lights all the camera sees.

use std::f32::consts::PI;

use crate::cli_support::render_stderr;
use crate::deferred_support::measure::{diff, share_within};
use crate::deferred_support::{gpu, Render};
use crate::gltf_writer::{temp_dir, Gltf};
use rgraph_passes::shadows::{ShadowFilter, Shadows};
use rgraph_passes::variant::Variants;
use rgraph_passes::Overrides;
use rgraph_scene::analysis::Features;
use rgraph_scene::{sheen_albedo, Lighting, Scene};
use serde_json::{json, Value};

const SIZE: (u32, u32) = (64, 64);
/// The sphere's outline radius in pixels: 1 unit of the 1.25-unit half view, of 32 pixels.
const RADIUS_PX: f32 = 25.6;
/// The pipelines that shade the layers: they must agree with each other.
const SHADING: [&str; 3] = [
    "visibility_msaa_4x.ron",
    "forward_msaa_4x.ron",
    "reference_ssaa16.ron",
];
/// The directional light's illuminance (lux): it travels along -z, from the camera.
const SUN: f32 = 3.0;
/// The base colour of the materials (linear grey) and their roughness.
const ALBEDO: f32 = 0.5;
const ROUGHNESS: f32 = 0.3;
/// How far from an analytic value a pixel may be, relative.
const ANALYTIC: f32 = 0.015;

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

/// The resolved HDR image of `file` through `pipeline`, shaders compiled as `variants`,
/// without shadows (the sun lights the whole half of the sphere the camera sees).
fn resolved(pipeline: &str, file: &str, variants: Variants) -> Vec<[f32; 4]> {
    let gpu = gpu();
    let shadows = Shadows {
        filter: ShadowFilter::Off,
        ..Shadows::default()
    };
    Render::new(pipeline, file, SIZE)
        .with_scene(load(file))
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
    for pipeline in SHADING {
        let core = resolved(pipeline, &core, Variants::Scene);
        let general = resolved(pipeline, &ior_1_5, Variants::General);
        let differ = core.iter().zip(&general).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{pipeline}: ior 1.5 differs from the core model");
        let air = resolved(pipeline, &ior_1, Variants::Scene);
        for (x, y) in disc(0.12) {
            let want = lambert(x, y);
            let got = at(&air, x, y)[0];
            assert!(
                (got - want).abs() <= ANALYTIC * want,
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
    for pipeline in SHADING {
        let image = resolved(pipeline, &none, Variants::Scene);
        for (x, y) in disc(0.6) {
            let want = lambert(x, y);
            let got = at(&image, x, y);
            assert!(
                got[..3].iter().all(|c| (c - want).abs() <= ANALYTIC * want),
                "{pipeline}: specular 0 at ({x}, {y}): {got:?}, Lambert {want}"
            );
        }
        let image = resolved(pipeline, &red, Variants::Scene);
        for (x, y) in centre() {
            let want = lambert(x, y);
            let [r, g, b, _] = at(&image, x, y);
            assert!(
                [g, b].iter().all(|c| (c - want).abs() <= ANALYTIC * want) && r > 2.0 * want,
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
    for pipeline in SHADING {
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
    for pipeline in SHADING {
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

/// `rgraph render` says which extensions a G-buffer pipeline leaves out of the opaque
/// surfaces it shades, naming the material and the pipeline, and says nothing with the
/// pipelines that shade them.
#[test]
fn render_warns_where_a_g_buffer_leaves_the_layers_out() {
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
    for pipeline in [
        "pipelines/deferred_msaa_4x.ron",
        "pipelines/light_prepass_msaa_4x.ron",
    ] {
        let stderr = render_stderr(pipeline, &file, (16, 16), &out);
        for extension in [
            "KHR_materials_clearcoat",
            "KHR_materials_ior",
            "KHR_materials_sheen",
            "KHR_materials_specular",
        ] {
            let expected = format!(
                "warning: material 0 \"layers_warning\" uses {extension}, but {pipeline} shades \
                 opaque surfaces from a G-buffer, which does not store it"
            );
            assert!(stderr.contains(&expected), "{expected}\nnot in:\n{stderr}");
        }
    }
    for pipeline in SHADING {
        let stderr = render_stderr(&format!("pipelines/{pipeline}"), &file, (16, 16), &out);
        assert!(!stderr.contains("KHR_materials"), "{pipeline}: {stderr}");
    }
}
