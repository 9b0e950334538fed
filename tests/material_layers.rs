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
use crate::deferred_support::{gpu, Render};
use crate::gltf_writer::{temp_dir, Gltf};
use rgraph_passes::shadows::{ShadowFilter, Shadows};
use rgraph_passes::variant::Variants;
use rgraph_passes::Overrides;
use rgraph_scene::Scene;
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
    let mut positions = Vec::new();
    for i in 0..=stacks {
        let theta = PI * f32::from(i) / f32::from(stacks);
        for j in 0..=slices {
            let phi = 2.0 * PI * f32::from(j) / f32::from(slices);
            positions.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
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
            "attributes": { "POSITION": position, "NORMAL": normal },
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

/// The Fresnel of a clear coat (F0 0.04) on the sphere at pixel (x, y), toward the camera
/// 3 units in front of the centre (the shaders' view: toward the camera's position).
fn coat_fresnel(x: u32, y: u32) -> f32 {
    let (dx, dy) = (
        (x as f32 + 0.5 - 32.0) / RADIUS_PX,
        -(y as f32 + 0.5 - 32.0) / RADIUS_PX,
    );
    let n = [dx, dy, on_sphere(x, y).1];
    let to_camera = [-n[0], -n[1], 3.0 - n[2]];
    let length = to_camera.iter().map(|c| c * c).sum::<f32>().sqrt();
    let n_v = n.iter().zip(to_camera).map(|(a, b)| a * b).sum::<f32>() / length;
    0.04 + 0.96 * (1.0 - n_v).powi(5)
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
        }),
    );
    let out = temp_dir("layers_warning_out").join("frame.png");
    for pipeline in [
        "pipelines/deferred_msaa_4x.ron",
        "pipelines/light_prepass_msaa_4x.ron",
    ] {
        let stderr = render_stderr(pipeline, &file, (16, 16), &out);
        for extension in ["KHR_materials_ior", "KHR_materials_specular"] {
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
