//! KHR_materials_pbrSpecularGlossiness: converted at load, a spec-gloss material equals the
//! metallic-roughness material it stands for within 2/255, factors and baked textures alike.

use crate::common;

use common::{temp_dir, Gltf};
use rgraph_scene::{Scene, TextureImage};
use serde_json::{json, Value};

const EXTENSION: &str = "KHR_materials_pbrSpecularGlossiness";
/// The tolerance the conversion is held to: 2/255.
const TOLERANCE: f32 = 2.0 / 255.0;

/// A glTF using the extension (required too).
fn spec_gloss_gltf() -> Gltf {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!([EXTENSION]);
    gltf.json["extensionsRequired"] = json!([EXTENSION]);
    gltf
}

/// A triangle whose material has the extension object `spec_gloss`.
fn spec_gloss_triangle(gltf: &mut Gltf, spec_gloss: Value) {
    let material = gltf.push(
        "materials",
        json!({ "extensions": { EXTENSION: spec_gloss } }),
    );
    gltf.triangle(Some(material));
}

fn load(test: &str, gltf: &Gltf) -> Scene {
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// An RGBA8 PNG of `width` x `height` texels, as a texture of `gltf`; returns the texture.
fn png_texture(gltf: &mut Gltf, width: u32, height: u32, rgba8: &[u8]) -> usize {
    let image = gltf.png_image(width, height, rgba8);
    gltf.push("textures", json!({ "source": image }))
}

fn assert_close(got: &[f32], want: &[f32], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= TOLERANCE,
            "{what}: {got:?}, expected {want:?} within 2/255"
        );
    }
}

/// Texels of a scene texture, RGBA8, each within 2 of `want`.
fn assert_texels(image: &TextureImage, want: &[[u8; 4]], what: &str) {
    let got: Vec<[u8; 4]> = image
        .rgba8
        .chunks_exact(4)
        .map(|t| [t[0], t[1], t[2], t[3]])
        .collect();
    assert_eq!(got.len(), want.len(), "{what}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            g.iter().zip(w).all(|(g, w)| g.abs_diff(*w) <= 2),
            "{what}: {got:?}, expected {want:?} within 2/255"
        );
    }
}

/// Each spec-gloss material (factors only) beside the metallic-roughness material it stands
/// for: base colour, metallic and roughness equal within 2/255.
#[test]
fn spec_gloss_factors_equal_the_metal_rough_material_within_2_255() {
    // The third pair is a half-metal written the way the extension's published
    // metal-rough to spec-gloss conversion writes it: specular = lerp(0.04, base, m),
    // diffuse = base * (1 - 0.04) * (1 - m) / (1 - max(specular)).
    let (base, m) = ([0.6f32, 0.4, 0.2], 0.5f32);
    let specular = base.map(|b| 0.04 + (b - 0.04) * m);
    let one_minus = 1.0 - specular.iter().fold(0.0f32, |a, &b| a.max(b));
    let diffuse = base.map(|b| b * 0.96 * (1.0 - m) / one_minus);
    let pairs = [
        // A dielectric: specular 0.04 grey is no metal, the diffuse is the base colour.
        (
            json!({ "diffuseFactor": [0.8, 0.5, 0.2, 0.7], "specularFactor": [0.04, 0.04, 0.04],
                    "glossinessFactor": 0.7 }),
            [0.8, 0.5, 0.2, 0.7],
            0.0,
            0.3,
        ),
        // A metal: black diffuse, the specular colour is the base colour.
        (
            json!({ "diffuseFactor": [0.0, 0.0, 0.0, 1.0], "specularFactor": [0.9, 0.6, 0.3],
                    "glossinessFactor": 0.2 }),
            [0.9, 0.6, 0.3, 1.0],
            1.0,
            0.8,
        ),
        (
            json!({ "diffuseFactor": [diffuse[0], diffuse[1], diffuse[2], 1.0],
                    "specularFactor": specular, "glossinessFactor": 0.5 }),
            [base[0], base[1], base[2], 1.0],
            m,
            0.5,
        ),
    ];
    let mut gltf = spec_gloss_gltf();
    for (spec_gloss, ..) in &pairs {
        spec_gloss_triangle(&mut gltf, spec_gloss.clone());
    }
    let scene = load("spec_gloss_factors", &gltf);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    for (material, (spec_gloss, base_color, metallic, roughness)) in
        scene.materials.iter().zip(&pairs)
    {
        let what = spec_gloss.to_string();
        assert_close(&material.base_color_factor, base_color, &what);
        assert_close(&[material.metallic_factor], &[*metallic], &what);
        assert_close(&[material.roughness_factor], &[*roughness], &what);
        assert!(
            material.base_color_texture.is_none() && material.metallic_roughness_texture.is_none()
        );
    }
}

/// Textures sampled alike are converted texel by texel: a dielectric texel keeps its
/// diffuse colour and is not metal, a metal texel (black diffuse) takes its specular colour
/// and is all metal; factors are folded in (alpha halved), the material's own are 1; the
/// metal-rough fallback is ignored.
#[test]
fn spec_gloss_textures_are_baked_texel_by_texel() {
    let mut gltf = spec_gloss_gltf();
    // sRGB 56 is linear 0.0395: a dielectric's specular.
    let diffuse = png_texture(&mut gltf, 2, 1, &[200, 120, 60, 255, 0, 0, 0, 255]);
    let specular = png_texture(&mut gltf, 2, 1, &[56, 56, 56, 178, 230, 180, 120, 51]);
    // A metal-rough fallback, as exporters write beside the extension: not used, not decoded.
    let fallback = png_texture(&mut gltf, 1, 1, &[255, 0, 255, 255]);
    let material = gltf.push(
        "materials",
        json!({
            "pbrMetallicRoughness": { "baseColorTexture": { "index": fallback } },
            "extensions": { EXTENSION: {
                "diffuseFactor": [1.0, 1.0, 1.0, 0.5],
                "diffuseTexture": { "index": diffuse, "texCoord": 1 },
                "specularGlossinessTexture": { "index": specular, "texCoord": 1 },
            } },
        }),
    );
    gltf.triangle(Some(material));
    let scene = load("spec_gloss_textures", &gltf);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.textures.len(), 2, "the two baked textures only");
    let material = &scene.materials[0];
    assert_eq!(material.base_color_factor, [1.0; 4]);
    assert_eq!(
        (material.metallic_factor, material.roughness_factor),
        (1.0, 1.0)
    );
    let base = material.base_color_texture.expect("a baked base colour");
    let metal_rough = material
        .metallic_roughness_texture
        .expect("a baked metallicRoughness");
    assert_eq!((base.tex_coord, metal_rough.tex_coord), (1, 1));
    let base = &scene.textures[base.image];
    let metal_rough = &scene.textures[metal_rough.image];
    assert!(base.srgb && !metal_rough.srgb);
    assert_eq!((base.width, base.height), (2, 1));
    // Alpha: the diffuse alpha times 0.5.
    assert_texels(
        base,
        &[[200, 120, 60, 128], [230, 180, 120, 128]],
        "base colour",
    );
    // Green: roughness, 1 - glossiness; blue: metallic.
    assert_texels(
        metal_rough,
        &[[255, 255 - 178, 0, 255], [255, 255 - 51, 255, 255]],
        "metallicRoughness",
    );
}

/// Textures on different UV sets share no texels: each is converted with the other's mean,
/// at its own size, with a warning.
#[test]
fn spec_gloss_textures_on_different_uvs_use_each_other_s_mean() {
    let mut gltf = spec_gloss_gltf();
    let diffuse = png_texture(&mut gltf, 2, 1, &[200, 120, 60, 255, 40, 80, 160, 255]);
    let specular = png_texture(&mut gltf, 1, 1, &[56, 56, 56, 178]);
    spec_gloss_triangle(
        &mut gltf,
        json!({
            "diffuseTexture": { "index": diffuse },
            "specularGlossinessTexture": { "index": specular, "texCoord": 1 },
        }),
    );
    let scene = load("spec_gloss_different_uvs", &gltf);
    assert_eq!(
        scene.warnings,
        [
            "material 0: KHR_materials_pbrSpecularGlossiness: the diffuse and \
             specularGlossiness textures sample different texture coordinates, so each is \
             converted with the other's mean value"
        ]
    );
    let material = &scene.materials[0];
    let base = material.base_color_texture.unwrap();
    let metal_rough = material.metallic_roughness_texture.unwrap();
    assert_eq!((base.tex_coord, metal_rough.tex_coord), (0, 1));
    assert_texels(
        &scene.textures[base.image],
        &[[200, 120, 60, 255], [40, 80, 160, 255]],
        "base colour",
    );
    assert_texels(
        &scene.textures[metal_rough.image],
        &[[255, 255 - 178, 0, 255]],
        "metallicRoughness",
    );
}

/// What baking will hold is taken from the scene's memory budget before anything is built:
/// two textures of the larger width and height of the inputs (64x1 and 1x64 give two of
/// 64x64, 21,844 bytes each with mips), the bound of either way of baking.
#[test]
fn baked_textures_are_counted_against_the_scene_memory_limit() {
    use rgraph_scene::AssetPolicy;
    let mut gltf = spec_gloss_gltf();
    let diffuse = png_texture(&mut gltf, 64, 1, &[128; 64 * 4]);
    let specular = png_texture(&mut gltf, 1, 64, &[128; 64 * 4]);
    spec_gloss_triangle(
        &mut gltf,
        json!({
            "diffuseTexture": { "index": diffuse },
            "specularGlossinessTexture": { "index": specular },
        }),
    );
    let path = temp_dir("spec_gloss_budget").join("scene.gltf");
    gltf.write_embedded(&path);
    // The triangle takes 180 bytes (3 vertices of 56, 3 indices of 4) and its mesh record.
    let policy = |max_scene_bytes| AssetPolicy {
        max_scene_bytes,
        ..AssetPolicy::default()
    };
    let triangle = 180 + std::mem::size_of::<rgraph_scene::Mesh>() as u64;
    let error = Scene::from_gltf_with(&path, &policy(triangle + 2 * 21_844 - 1))
        .expect_err("the baked textures are over the limit");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: material 0: baking its specular-glossiness textures as metallic-roughness \
             (two of 64x64) would take the scene past {} bytes of vertices, indices and \
             textures (the scene memory limit)",
            path.display(),
            triangle + 2 * 21_844 - 1
        )
    );
    let scene = Scene::from_gltf_with(&path, &policy(triangle + 2 * 21_844))
        .unwrap_or_else(|e| panic!("{e}"));
    let material = &scene.materials[0];
    let base = &scene.textures[material.base_color_texture.unwrap().image];
    assert_eq!((base.width, base.height), (64, 64));
}

/// The extension's texture indices are validated with the rest of the file: one past the
/// textures is an error naming it, never a panic.
#[test]
fn a_spec_gloss_texture_index_out_of_range_is_a_validation_error() {
    let mut gltf = spec_gloss_gltf();
    spec_gloss_triangle(
        &mut gltf,
        json!({ "specularGlossinessTexture": { "index": 3 } }),
    );
    let path = temp_dir("spec_gloss_bad_index").join("scene.gltf");
    gltf.write_embedded(&path);
    let error = Scene::from_gltf(&path).expect_err("no texture 3");
    assert!(
        matches!(error, rgraph_scene::SceneError::Gltf { .. }),
        "{error:?}"
    );
    assert_eq!(
        error.to_string(),
        format!(
            "{}: not a valid glTF 2.0 file: invalid glTF: materials[0].extensions.\
             pbrSpecularGlossiness.specularGlossinessTexture.index: Index out of bounds;",
            path.display()
        )
    );
}
