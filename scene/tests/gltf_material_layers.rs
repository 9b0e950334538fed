//! KHR_materials_ior, KHR_materials_specular, KHR_materials_clearcoat and
//! KHR_materials_sheen as the loader reads them: every factor and texture into the
//! material, the spec's defaults where a field is missing, and errors naming the file, the
//! material and the field for what cannot be read.

use crate::common;

use common::{temp_dir, Gltf};
use rgraph_scene::{
    dielectric_f0, Clearcoat, Material, Scene, SceneError, Sheen, Specular, TextureRef,
};
use serde_json::{json, Value};

const EXTENSIONS: [&str; 4] = [
    "KHR_materials_ior",
    "KHR_materials_specular",
    "KHR_materials_clearcoat",
    "KHR_materials_sheen",
];

/// A triangle whose material has `extensions`, with one 1x1 texture (a white PNG) for
/// them to name.
fn gltf_with(extensions: Value) -> Gltf {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(EXTENSIONS);
    let image = gltf.png_image(1, 1, &[255, 255, 255, 255]);
    gltf.push("textures", json!({ "source": image }));
    let material = gltf.push(
        "materials",
        json!({ "name": "layered", "extensions": extensions }),
    );
    gltf.triangle(Some(material));
    gltf
}

fn load(test: &str, gltf: &Gltf) -> Result<Scene, SceneError> {
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    Scene::from_gltf(&path)
}

fn material(test: &str, extensions: Value) -> (Material, Vec<String>) {
    let scene = load(test, &gltf_with(extensions)).unwrap_or_else(|e| panic!("{e}"));
    (scene.materials[0].clone(), scene.warnings)
}

/// The error loading a material with `extensions` gives, as text.
fn error(test: &str, extensions: Value) -> String {
    match load(test, &gltf_with(extensions)) {
        Ok(_) => panic!("{test}: loaded"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn every_factor_and_texture_of_the_four_extensions_is_read() {
    let texture = |extra: Value| {
        let mut t = json!({ "index": 0 });
        t.as_object_mut()
            .unwrap()
            .extend(extra.as_object().unwrap().clone());
        t
    };
    let gltf = gltf_with(json!({
            "KHR_materials_ior": { "ior": 1.33 },
            "KHR_materials_specular": {
                "specularFactor": 0.5,
                "specularTexture": texture(json!({})),
                "specularColorFactor": [1.0, 0.5, 2.0],
                "specularColorTexture": texture(json!({ "texCoord": 1 })),
            },
            "KHR_materials_clearcoat": {
                "clearcoatFactor": 0.75,
                "clearcoatTexture": texture(json!({})),
                "clearcoatRoughnessFactor": 0.25,
                "clearcoatRoughnessTexture": texture(json!({})),
                "clearcoatNormalTexture": texture(json!({ "scale": 0.5 })),
            },
            "KHR_materials_sheen": {
                "sheenColorFactor": [0.9, 0.1, 0.2],
                "sheenColorTexture": texture(json!({
                    "extensions": { "KHR_texture_transform": { "scale": [2.0, 2.0] } }
                })),
                "sheenRoughnessFactor": 0.6,
                "sheenRoughnessTexture": texture(json!({})),
            },
    }));
    let scene = load("layers_all", &gltf).unwrap_or_else(|e| panic!("{e}"));
    let (m, warnings) = (&scene.materials[0], &scene.warnings);
    let others: Vec<&String> = warnings
        .iter()
        .filter(|w| !w.contains("is not implemented"))
        .collect();
    assert!(others.is_empty(), "{others:?}");
    assert_eq!(m.ior, 1.33);
    assert_eq!(
        (m.specular.factor, m.specular.color_factor),
        (0.5, [1.0, 0.5, 2.0])
    );
    assert_eq!(m.specular.color_texture.unwrap().tex_coord, 1);
    assert_eq!(
        (
            m.clearcoat.factor,
            m.clearcoat.roughness_factor,
            m.clearcoat.normal_scale
        ),
        (0.75, 0.25, 0.5)
    );
    assert_eq!(
        (m.sheen.color_factor, m.sheen.roughness_factor),
        ([0.9, 0.1, 0.2], 0.6)
    );
    assert_eq!(
        m.sheen.color_texture.unwrap().uv_transform,
        [[2.0, 0.0], [0.0, 2.0], [0.0, 0.0]]
    );
    // Every slot filled, the one image decoded in two roles: sRGB for the colour
    // textures, linear for the data ones.
    assert_eq!(m.texture_slots().iter().flatten().count(), 7);
    let srgb = |t: Option<TextureRef>| scene.textures[t.unwrap().image].srgb;
    assert!(srgb(m.specular.color_texture) && srgb(m.sheen.color_texture));
    let data = [
        m.specular.texture,
        m.clearcoat.texture,
        m.clearcoat.roughness_texture,
        m.clearcoat.normal_texture,
        m.sheen.roughness_texture,
    ];
    assert!(data.into_iter().all(|t| !srgb(t)));
    assert_eq!(scene.textures.len(), 2);
}

/// Each extension present but empty is its defaults, as is its absence: ior 1.5 (F0
/// 0.04), specular 1 white, no coat, no sheen.
#[test]
fn empty_extensions_mean_the_spec_defaults() {
    let (m, _) = material(
        "layers_defaults",
        json!({
            "KHR_materials_ior": {},
            "KHR_materials_specular": {},
            "KHR_materials_clearcoat": {},
            "KHR_materials_sheen": {},
        }),
    );
    let default = Material::gltf_default();
    assert_eq!(m.ior, default.ior);
    assert_eq!(m.ior, 1.5);
    assert!((dielectric_f0(m.ior) - 0.04).abs() < 1e-7);
    assert_eq!(m.specular, Specular::default());
    assert_eq!(m.clearcoat, Clearcoat::default());
    assert_eq!(m.sheen, Sheen::default());
    assert!(!m.has_specular() && !m.has_clearcoat() && !m.has_sheen());
}

/// Factors outside the extension's range are clamped with a warning naming them; ior 0
/// is the extension's special value, ior 0.5 is clamped to 1.
#[test]
fn out_of_range_factors_are_clamped_with_a_warning() {
    let (m, warnings) = material(
        "layers_clamped",
        json!({
            "KHR_materials_ior": { "ior": 0.5 },
            "KHR_materials_clearcoat": { "clearcoatFactor": 2.0 },
            "KHR_materials_sheen": { "sheenColorFactor": [1.5, 0.5, -1.0] },
        }),
    );
    assert_eq!(m.ior, 1.0);
    assert_eq!(m.clearcoat.factor, 1.0);
    assert_eq!(m.sheen.color_factor, [1.0, 0.5, 0.0]);
    for expected in [
        "KHR_materials_ior ior 0.5 is neither 0 nor at least 1; clamped to 1",
        "clearcoatFactor [2.0] is not within 0..=1; clamped to [1.0]",
        "sheenColorFactor [1.5, 0.5, -1.0] is not within 0..=1",
    ] {
        assert!(
            warnings.iter().any(|w| w.contains(expected)),
            "{expected}: {warnings:?}"
        );
    }
    let (m, _) = material(
        "layers_ior_zero",
        json!({ "KHR_materials_ior": { "ior": 0.0 } }),
    );
    assert_eq!((m.ior, dielectric_f0(m.ior)), (0.0, 1.0));
}

/// What cannot be read is an error naming the file, the material and the field.
#[test]
fn unreadable_fields_are_errors_naming_the_material_and_field() {
    let cases = [
        (
            json!({ "KHR_materials_clearcoat": { "clearcoatFactor": "shiny" } }),
            "KHR_materials_clearcoat.clearcoatFactor is \"shiny\", not a number",
        ),
        (
            json!({ "KHR_materials_sheen": { "sheenColorTexture": { "index": 7 } } }),
            "KHR_materials_sheen.sheenColorTexture names texture 7, but the file has 1 textures",
        ),
        (
            json!({ "KHR_materials_specular": { "specularColorFactor": [1.0, 1.0] } }),
            "KHR_materials_specular.specularColorFactor is [1.0,1.0], not an array of three numbers",
        ),
        (
            json!({ "KHR_materials_ior": { "ior": 1e39 } }),
            "ior [inf] is beyond the largest f32",
        ),
        (
            json!({ "KHR_materials_sheen": [] }),
            "KHR_materials_sheen is [], not a JSON object",
        ),
        (
            json!({ "KHR_materials_clearcoat": { "clearcoatNormalTexture": { "index": 0, "scale": "x" } } }),
            "KHR_materials_clearcoat.clearcoatNormalTexture scale is \"x\", not a finite number",
        ),
    ];
    for (i, (extensions, expected)) in cases.into_iter().enumerate() {
        let message = error(&format!("layers_error_{i}"), extensions);
        assert!(
            message.contains("scene.gltf: material 0 \"layered\": ") && message.contains(expected),
            "{message}\nexpected {expected}"
        );
    }
}

/// The extensions apply to metallic-roughness only: on a specular-glossiness material they
/// are ignored, with a warning naming each.
#[test]
fn layers_on_a_spec_gloss_material_are_ignored_with_a_warning() {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(["KHR_materials_pbrSpecularGlossiness", EXTENSIONS[2]]);
    let material = gltf.push(
        "materials",
        json!({ "extensions": {
            "KHR_materials_pbrSpecularGlossiness": {},
            "KHR_materials_clearcoat": { "clearcoatFactor": 1.0 },
        } }),
    );
    gltf.triangle(Some(material));
    let scene = load("layers_spec_gloss", &gltf).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.materials[0].clearcoat, Clearcoat::default());
    assert!(
        scene.warnings.iter().any(|w| w.contains(
            "KHR_materials_clearcoat is not allowed with KHR_materials_pbrSpecularGlossiness; ignored"
        )),
        "{:?}",
        scene.warnings
    );
}
