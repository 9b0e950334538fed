//! glTF material textures as every pipeline renders them, end to end from files the test
//! writes: a 2x2-unit quad at z = 0 facing +z, UV (0, 0) at its top left, under an
//! orthographic camera 3 units in front whose view is 2.5 units across, so at 64x64 the
//! quad covers pixels 6.4 to 57.6 and each texel of a 2x2 texture (sampled NEAREST) a
//! quadrant of about 25x25 pixels.

use crate::deferred_support;
use crate::gltf_writer::{temp_dir, Gltf};

use deferred_support::measure::pixels_within;
use deferred_support::{gpu, Render};
use rgraph_scene::Scene;
use serde_json::{json, Value};

const SIZE: (u32, u32) = (64, 64);
/// deferred, tiled and forward: the G-buffer path read by both light paths, and the
/// forward path of the baselines.
const PIPELINES: [&str; 3] = [
    "deferred_msaa_4x.ron",
    "deferred_msaa_4x_tiled.ron",
    "forward_msaa_4x.ron",
];
/// glTF NEAREST, for `magFilter` and `minFilter`; CLAMP_TO_EDGE.
const NEAREST: u32 = 9728;
const CLAMP: u32 = 33071;

/// Pixels well inside each quadrant of the quad (two pixels from its edges and from the
/// texel boundary at 32), as (quadrant, x, y); quadrants 0..4 are the texels in row order:
/// top left, top right, bottom left, bottom right.
fn quadrant_interiors() -> impl Iterator<Item = (usize, u32, u32)> {
    (0..64u32).flat_map(|y| {
        (0..64u32).filter_map(move |x| {
            let inside = |c: u32| (9..30).contains(&c) || (34..55).contains(&c);
            if !(inside(x) && inside(y)) {
                return None;
            }
            Some((usize::from(x >= 32) + 2 * usize::from(y >= 32), x, y))
        })
    })
}

/// A 2x2 RGBA8 PNG of `texels` in row order.
fn png_2x2(texels: [[u8; 4]; 4]) -> Vec<u8> {
    let image = image::RgbaImage::from_raw(2, 2, texels.concat()).unwrap();
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    png
}

/// The quad with `material` (the JSON object; textures it names are `images` in order,
/// each sampled NEAREST with clamping), the orthographic camera, and the
/// KHR_lights_punctual `lights` (each placed by a node with the given transform fields) written as
/// `test`/quad.gltf; returns its path.
fn quad_file(test: &str, material: Value, images: &[Vec<u8>], lights: &[(Value, Value)]) -> String {
    quad_file_with(test, material, images, lights, &|_| json!({}))
}

/// [`quad_file`] with the attributes `extra` adds to the quad (accessors it writes, by
/// attribute name; per corner: bottom left, bottom right, top right, top left).
fn quad_file_with(
    test: &str,
    material: Value,
    images: &[Vec<u8>],
    lights: &[(Value, Value)],
    extra: &dyn Fn(&mut Gltf) -> Value,
) -> String {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!([
        "KHR_materials_emissive_strength",
        "KHR_lights_punctual",
        "KHR_materials_unlit",
        "KHR_texture_transform"
    ]);
    let positions = gltf.floats(&[
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ]);
    let normals = gltf.floats(&[[0.0, 0.0, 1.0]; 4]);
    let uvs = gltf.floats(&[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
    let indices = gltf.indices_u16(&[0, 1, 2, 0, 2, 3]);
    let mut attributes = json!({ "POSITION": positions, "NORMAL": normals, "TEXCOORD_0": uvs });
    for (name, accessor) in extra(&mut gltf).as_object().unwrap() {
        attributes[name] = accessor.clone();
    }
    gltf.push(
        "samplers",
        json!({ "magFilter": NEAREST, "minFilter": NEAREST, "wrapS": CLAMP, "wrapT": CLAMP }),
    );
    for png in images {
        let view = gltf.view(png);
        let image = gltf.push(
            "images",
            json!({ "bufferView": view, "mimeType": "image/png" }),
        );
        gltf.push("textures", json!({ "source": image, "sampler": 0 }));
    }
    let material = gltf.push("materials", material);
    gltf.mesh(
        "quad",
        json!({
            "attributes": attributes,
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
    let list: Vec<&Value> = lights.iter().map(|(light, _)| light).collect();
    gltf.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": list } });
    for (index, (_, transform)) in lights.iter().enumerate() {
        let mut node = transform.clone();
        node["extensions"] = json!({ "KHR_lights_punctual": { "light": index } });
        gltf.root(node);
    }
    let path = temp_dir(test).join("quad.gltf");
    gltf.write_embedded(&path);
    path.to_str().unwrap().to_owned()
}

/// The resolved HDR image of `scene` through `pipeline`.
fn resolved(pipeline: &str, file: &str, scene: Scene) -> Vec<[f32; 4]> {
    let gpu = gpu();
    Render::new(pipeline, file, SIZE)
        .with_scene(scene)
        .export_resolved()
        .run(&gpu)
        .hdr(&gpu, "resolved")
}

fn load(file: &str) -> Scene {
    let scene = Scene::load(file).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    scene
}

/// An emissive texture shows its pattern, times emissiveFactor and
/// KHR_materials_emissive_strength: a black-and-white checker emits 2.0 in its white
/// quadrants and nothing in its black ones (a black, unlit-by-anything surface), where
/// the factor alone would light the whole quad (DamagedHelmet's white silhouette).
#[test]
fn emissive_texture_shows_its_pattern() {
    emissive_pattern("emissive_texture", json!({ "index": 0 }), &[0, 3]);
}

/// A texture on TEXCOORD_1 samples it: the emissive checker through a second UV set that
/// mirrors u lights the other two quadrants.
#[test]
fn a_texture_on_texcoord_1_samples_the_second_uv_set() {
    emissive_pattern(
        "emissive_texcoord_1",
        json!({ "index": 0, "texCoord": 1 }),
        &[1, 2],
    );
}

/// KHR_texture_transform moves a texture: scale -1 and offset 1 in u mirror the emissive
/// checker, which lights the other two quadrants.
#[test]
fn a_texture_transform_mirrors_the_pattern() {
    let mirror = json!({ "KHR_texture_transform": { "offset": [1.0, 0.0], "scale": [-1.0, 1.0] } });
    emissive_pattern(
        "emissive_texture_transform",
        json!({ "index": 0, "extensions": mirror }),
        &[1, 2],
    );
}

/// The emissive checker (white top left and bottom right) as the texture reference
/// `texture` (TEXCOORD_1 mirrors TEXCOORD_0 in u) emits 2.0 in the quadrants `lit` and
/// nothing in the others, in every pipeline.
fn emissive_pattern(test: &str, texture: Value, lit: &[usize]) {
    let (white, black) = ([255, 255, 255, 255], [0, 0, 0, 255]);
    let mirrored = [[1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0]];
    let file = quad_file_with(
        test,
        json!({
            "pbrMetallicRoughness": { "baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0 },
            "emissiveFactor": [1.0, 1.0, 1.0],
            "emissiveTexture": texture,
            "extensions": { "KHR_materials_emissive_strength": { "emissiveStrength": 2.0 } },
        }),
        &[png_2x2([white, black, black, white])],
        &[],
        &|gltf| json!({ "TEXCOORD_1": gltf.floats(&mirrored) }),
    );
    let scene = load(&file);
    for pipeline in PIPELINES {
        let hdr = resolved(pipeline, &file, scene.clone());
        for (quadrant, x, y) in quadrant_interiors() {
            let expected = if lit.contains(&quadrant) { 2.0 } else { 0.0 };
            let got = hdr[(y * SIZE.0 + x) as usize];
            assert_eq!(
                got[..3],
                [expected; 3],
                "{test}, {pipeline}: pixel ({x}, {y}) in quadrant {quadrant}"
            );
        }
    }
}

/// The metallicRoughness texture sets metalness from blue and roughness from green, per
/// texel: each quadrant of a textured quad renders as the same quad with those values as
/// plain factors (within half-float rounding), and the four differ, so a texture that was
/// ignored could not pass.
#[test]
fn metallic_roughness_texture_sets_metal_from_blue_and_rough_from_green() {
    // (metallic, roughness) per quadrant: blue 0 / 255, green 255 / 128.
    let texels = [
        [0, 255, 0, 255],
        [0, 255, 255, 255],
        [0, 128, 0, 255],
        [0, 128, 255, 255],
    ];
    let expected: Vec<(f32, f32)> = texels
        .iter()
        .map(|t| (f32::from(t[2]) / 255.0, f32::from(t[1]) / 255.0))
        .collect();
    // A point light up and to the left, so the specular lobe (which roughness shapes) and
    // the diffuse term (which metalness removes) both reach the quad.
    let light = json!({ "type": "point", "color": [1.0, 1.0, 1.0], "intensity": 4.0 });
    let file = quad_file(
        "metallic_roughness_texture",
        json!({
            "pbrMetallicRoughness": {
                "baseColorFactor": [0.8, 0.6, 0.4, 1.0],
                "metallicFactor": 1.0,
                "roughnessFactor": 1.0,
                "metallicRoughnessTexture": { "index": 0 },
            },
        }),
        &[png_2x2(texels)],
        &[(light, json!({ "translation": [-0.5, 0.5, 1.5] }))],
    );
    let scene = load(&file);
    for pipeline in ["deferred_msaa_4x.ron", "forward_msaa_4x.ron"] {
        let textured = resolved(pipeline, &file, scene.clone());
        let plain: Vec<Vec<[f32; 4]>> = expected
            .iter()
            .map(|&(metallic, roughness)| {
                let mut plain = scene.clone();
                let material = &mut plain.materials[0];
                material.metallic_roughness_texture = None;
                material.metallic_factor = metallic;
                material.roughness_factor = roughness;
                resolved(pipeline, &file, plain)
            })
            .collect();
        for (quadrant, x, y) in quadrant_interiors() {
            let i = (y * SIZE.0 + x) as usize;
            let want = plain[quadrant][i];
            let got = textured[i];
            let close = (0..3).all(|c| (got[c] - want[c]).abs() <= 2e-3 * want[c].max(1.0));
            assert!(
                close,
                "{pipeline}: pixel ({x}, {y}) in quadrant {quadrant}: {got:?}, expected \
                 {want:?} (metallic, roughness) = {:?}",
                expected[quadrant]
            );
        }
        // The four materials look different where they are compared.
        let (x, y) = (20u32, 20u32);
        let i = (y * SIZE.0 + x) as usize;
        for a in 0..4 {
            for b in a + 1..4 {
                let differ = (0..3).any(|c| (plain[a][i][c] - plain[b][i][c]).abs() > 0.01);
                assert!(
                    differ,
                    "{pipeline}: quadrants {a} and {b} render alike at ({x}, {y})"
                );
            }
        }
    }
}

/// Deferred (fragment and tiled lighting) and forward render the same material model: on
/// a quad with base-color, metallicRoughness, emissive and normal textures under a point
/// light,
/// their 8-bit images agree within 2/255 on at least 99% of pixels.
#[test]
fn deferred_tiled_and_forward_agree_on_a_textured_pbr_quad() {
    let texels = |a: [u8; 4], b: [u8; 4]| [a, b, b, a];
    let light = json!({ "type": "point", "color": [1.0, 0.9, 0.8], "intensity": 3.0 });
    let file = quad_file(
        "textured_pbr_quad",
        json!({
            "pbrMetallicRoughness": {
                "baseColorTexture": { "index": 0 },
                "metallicRoughnessTexture": { "index": 1 },
            },
            "emissiveFactor": [0.2, 0.1, 0.0],
            "emissiveTexture": { "index": 2 },
            "normalTexture": { "index": 3, "scale": 0.8 },
        }),
        &[
            png_2x2(texels([230, 40, 30, 255], [30, 90, 220, 255])),
            png_2x2(texels([0, 60, 255, 255], [0, 230, 0, 255])),
            png_2x2(texels([255, 255, 255, 255], [0, 0, 0, 255])),
            png_2x2(texels([200, 150, 220, 255], [90, 60, 230, 255])),
        ],
        &[(light, json!({ "translation": [0.4, -0.3, 1.2] }))],
    );
    let scene = load(&file);
    let gpu = gpu();
    let images: Vec<_> = PIPELINES
        .iter()
        .map(|pipeline| {
            Render::new(*pipeline, &file, SIZE)
                .with_scene(scene.clone())
                .run(&gpu)
                .image(&gpu, "color")
        })
        .collect();
    let lit = images[0]
        .pixels
        .iter()
        .filter(|p| p[..3] != [0, 0, 0])
        .count();
    assert!(
        lit > 2000,
        "only {lit} pixels are not black: the quad is not lit"
    );
    for (pipeline, image) in PIPELINES.iter().zip(&images).skip(1) {
        let close = pixels_within(image, &images[0], 2);
        let total = image.pixels.len();
        assert!(
            close * 100 >= total * 99,
            "{pipeline} and {}: only {close} of {total} pixels within 2/255",
            PIPELINES[0]
        );
    }
}

/// COLOR_0 multiplies the base color: an unlit white quad whose vertices are all
/// (1, 0.5, 0.25) shows exactly that color in every pipeline, and an unlit red-textured
/// one its product with the texture.
#[test]
fn color_0_tints_the_base_color() {
    let tint = [1.0, 0.5, 0.25, 1.0];
    let red = [255, 0, 0, 255];
    for (test, material, images, expected) in [
        ("color_0_white", json!({}), vec![], [1.0, 0.5, 0.25]),
        (
            "color_0_textured",
            json!({ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }),
            vec![png_2x2([red; 4])],
            [1.0, 0.0, 0.0],
        ),
    ] {
        let mut material = material;
        material["extensions"] = json!({ "KHR_materials_unlit": {} });
        let file = quad_file_with(
            test,
            material,
            &images,
            &[],
            &|gltf| json!({ "COLOR_0": gltf.floats(&[tint; 4]) }),
        );
        let scene = load(&file);
        for pipeline in PIPELINES {
            let hdr = resolved(pipeline, &file, scene.clone());
            for (quadrant, x, y) in quadrant_interiors() {
                let got = hdr[(y * SIZE.0 + x) as usize];
                assert_eq!(
                    got[..3],
                    expected,
                    "{test}, {pipeline}: pixel ({x}, {y}) in quadrant {quadrant}"
                );
            }
        }
    }
}

/// A normal texture tilts the shading normal in the tangent frame glTF defines (+X along
/// u, +Y up the image, tangents from MikkTSpace as the file has none): under a directional
/// light from the front, the right and a little above, each quadrant of a quad whose normal texels
/// tilt right, up, left and down renders as the same quad with its geometric normal set to
/// that texel's decoded normal, normalize(2 * texel / 255 - 1); the four differ, so a
/// mirrored tangent or bitangent could not pass.
#[test]
fn normal_texture_tilts_the_normal_in_the_gltf_tangent_frame() {
    use rgraph_scene::glam::{DQuat, DVec3};
    let texels = [
        [204, 128, 230, 255],
        [128, 204, 230, 255],
        [52, 128, 230, 255],
        [128, 52, 230, 255],
    ];
    let normals: Vec<[f32; 3]> = texels
        .iter()
        .map(|t| {
            let n = [0, 1, 2].map(|c| f32::from(t[c]) / 255.0 * 2.0 - 1.0);
            let length = n.iter().map(|c| c * c).sum::<f32>().sqrt();
            n.map(|c| c / length)
        })
        .collect();
    // The light travels towards -x, -y, -z (glTF lights shine down their node's -z), less
    // down than left so that no two texels' normals face it alike.
    let rotation = DQuat::from_rotation_arc(DVec3::NEG_Z, DVec3::new(-1.0, -0.4, -1.0).normalize());
    let light = json!({ "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 2.0 });
    let file = quad_file(
        "normal_texture",
        json!({
            "pbrMetallicRoughness": { "metallicFactor": 0.0, "roughnessFactor": 0.6 },
            "normalTexture": { "index": 0 },
        }),
        &[png_2x2(texels)],
        &[(light, json!({ "rotation": rotation.to_array() }))],
    );
    let scene = load(&file);
    for pipeline in ["deferred_msaa_4x.ron", "forward_msaa_4x.ron"] {
        let mapped = resolved(pipeline, &file, scene.clone());
        let plain: Vec<Vec<[f32; 4]>> = normals
            .iter()
            .map(|&normal| {
                let mut plain = scene.clone();
                plain.materials[0].normal_texture = None;
                for vertex in std::sync::Arc::make_mut(&mut plain.meshes[0].vertices) {
                    vertex.normal = normal;
                }
                resolved(pipeline, &file, plain)
            })
            .collect();
        for (quadrant, x, y) in quadrant_interiors() {
            let i = (y * SIZE.0 + x) as usize;
            let (got, want) = (mapped[i], plain[quadrant][i]);
            let close = (0..3).all(|c| (got[c] - want[c]).abs() <= 4e-3 * want[c].max(1.0));
            assert!(
                close,
                "{pipeline}: pixel ({x}, {y}) in quadrant {quadrant}: {got:?}, expected {want:?} \
                 (normal {:?})",
                normals[quadrant]
            );
        }
        let i = (20 * SIZE.0 + 20) as usize;
        for a in 0..4 {
            for b in a + 1..4 {
                let differ = (0..3).any(|c| (plain[a][i][c] - plain[b][i][c]).abs() > 0.01);
                assert!(differ, "{pipeline}: normals {a} and {b} render alike");
            }
        }
    }
}

/// An occlusion texture darkens only ambient (indirect) light: with ambient radiance 0.5
/// and a directional light, each quadrant is darker than without the texture by exactly
/// 0.5 * albedo * (1 - occlusion), occlusion = 1 + strength * (red - 1); with no ambient
/// the texture changes nothing at all.
#[test]
fn occlusion_texture_darkens_only_ambient_light() {
    let reds = [255u8, 128, 0, 64];
    let strength = 0.75;
    let light = json!({ "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 1.5 });
    let file = quad_file(
        "occlusion_texture",
        json!({
            "pbrMetallicRoughness": { "baseColorFactor": [0.9, 0.6, 0.3, 1.0], "metallicFactor": 0.0 },
            "occlusionTexture": { "index": 0, "strength": strength },
        }),
        &[png_2x2(reds.map(|r| [r, 0, 0, 255]))],
        &[(light, json!({}))],
    );
    let textured = load(&file);
    let mut plain = textured.clone();
    plain.materials[0].occlusion_texture = None;
    let albedo = [0.9f32, 0.6, 0.3];
    for pipeline in PIPELINES {
        for ambient in [0.0, 0.5] {
            let [with, without] = [&textured, &plain].map(|scene| {
                let mut scene = scene.clone();
                scene.ambient = [ambient; 3];
                resolved(pipeline, &file, scene)
            });
            for (quadrant, x, y) in quadrant_interiors() {
                let i = (y * SIZE.0 + x) as usize;
                let occlusion = 1.0 + strength * (f32::from(reds[quadrant]) / 255.0 - 1.0);
                for c in 0..3 {
                    let expected = without[i][c] - ambient * albedo[c] * (1.0 - occlusion);
                    // The G-buffer holds albedo and occlusion in 8 bits (0.9 is stored as
                    // sRGB 243, linear 0.896): up to 2e-3 here, plus half-float rounding.
                    assert!(
                        (with[i][c] - expected).abs() <= 4e-3 * expected.max(1.0),
                        "{pipeline}, ambient {ambient}: pixel ({x}, {y}) channel {c} in quadrant \
                         {quadrant}: {}, expected {expected}",
                        with[i][c]
                    );
                }
            }
            if ambient == 0.0 {
                assert!(
                    with == without,
                    "{pipeline}: occlusion changed direct light"
                );
            }
        }
    }
}
