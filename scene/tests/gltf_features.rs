//! glTF features exercised with files written by the test: GLB with an embedded PNG texture,
//! samplers, cameras, strips and fans, mirrored transforms, quantized and sparse accessors,
//! URIs, and the warnings for what is not implemented.

use crate::common;

use common::{temp_dir, Gltf, SHORT};
use glam::{DQuat, DVec3};
use rgraph_scene::{
    FilterMode, Material, Projection, Sampler, Scene, TextureRef, Vertex, WrapMode,
};
use serde_json::json;

/// Writes `gltf` as `name` (embedded buffer) in a fresh directory and loads it.
fn load_embedded(test: &str, gltf: &Gltf) -> Scene {
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Adds [`png_2x1`] as an image in a buffer view of `gltf`; returns the image's index.
fn png_2x1_image(gltf: &mut Gltf) -> usize {
    let view = gltf.view(&png_2x1());
    gltf.push(
        "images",
        json!({ "bufferView": view, "mimeType": "image/png" }),
    )
}

/// A 2 x 1 RGBA PNG: one opaque red texel, one half-transparent blue one.
fn png_2x1() -> Vec<u8> {
    let image = image::RgbaImage::from_raw(2, 1, vec![255, 0, 0, 255, 0, 0, 255, 128]).unwrap();
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    png
}

#[test]
fn glb_with_png_in_buffer_view_and_sampler() {
    let mut gltf = Gltf::default();
    png_2x1_image(&mut gltf);
    // NEAREST, LINEAR_MIPMAP_LINEAR, CLAMP_TO_EDGE, MIRRORED_REPEAT.
    gltf.push(
        "samplers",
        json!({ "magFilter": 9728, "minFilter": 9987, "wrapS": 33071, "wrapT": 33648 }),
    );
    gltf.push("textures", json!({ "source": 0, "sampler": 0 }));
    let material = gltf.push(
        "materials",
        json!({ "name": "textured", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }),
    );
    gltf.triangle(Some(material));
    let path = temp_dir("glb_texture").join("scene.glb");
    gltf.write_glb(&path);

    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.textures.len(), 1);
    let texture = &scene.textures[0];
    assert_eq!((texture.width, texture.height, texture.srgb), (2, 1, true));
    assert_eq!(texture.rgba8, [255, 0, 0, 255, 0, 0, 255, 128]);
    assert_eq!(
        scene.materials[0].base_color_texture,
        Some(TextureRef {
            image: 0,
            sampler: Sampler {
                wrap_u: WrapMode::ClampToEdge,
                wrap_v: WrapMode::MirroredRepeat,
                mag_filter: FilterMode::Nearest,
                min_filter: FilterMode::Linear,
                mipmap_filter: Some(FilterMode::Linear),
            },
            tex_coord: 0,
            uv_transform: TextureRef::IDENTITY_UV,
        })
    );
    assert_eq!(scene.stats().textured_materials, 1);
}

#[test]
fn image_file_next_to_gltf_is_decoded_once_for_two_materials() {
    let dir = temp_dir("image_file");
    std::fs::write(dir.join("base color.png"), png_2x1()).unwrap();
    let mut gltf = Gltf::default();
    gltf.push("images", json!({ "uri": "base%20color.png" }));
    gltf.push("textures", json!({ "source": 0 }));
    for name in ["a", "b"] {
        let material = gltf.push(
            "materials",
            json!({ "name": name, "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } }),
        );
        gltf.triangle(Some(material));
    }
    let path = dir.join("scene.gltf");
    gltf.write_external(&path, "data buffer.bin", "data%20buffer.bin");

    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.textures.len(), 1);
    assert_eq!(scene.textures[0].name, "image 0 \"base%20color.png\"");
    let sampler = Sampler::default();
    for material in &scene.materials {
        assert_eq!(
            material.base_color_texture,
            Some(TextureRef {
                image: 0,
                sampler,
                tex_coord: 0,
                uv_transform: TextureRef::IDENTITY_UV
            })
        );
    }
}

#[test]
fn orthographic_camera_with_rotated_node() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    let camera = gltf.push(
        "cameras",
        json!({ "type": "orthographic", "orthographic": { "xmag": 4, "ymag": 3, "znear": 0.25, "zfar": 40 } }),
    );
    // 90° about +Y: the camera looks along -X.
    let s = 0.5f32.sqrt();
    gltf.root(json!({ "camera": camera, "translation": [7, 0, 0], "rotation": [0, s, 0, s] }));
    let scene = load_embedded("ortho_camera", &gltf);
    let camera = &scene.camera;
    assert_eq!(
        camera.projection,
        Projection::Orthographic {
            xmag: 4.0,
            ymag: 3.0,
            znear: 0.25,
            zfar: 40.0
        }
    );
    assert_eq!(camera.position, DVec3::new(7.0, 0.0, 0.0));
    let expected = DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
    assert!(camera.orientation.abs_diff_eq(expected, 1e-7));
    assert!(camera.forward().abs_diff_eq(DVec3::NEG_X, 1e-7));
}

#[test]
fn primitive_without_material_gets_the_gltf_default_once() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    gltf.triangle(None);
    let scene = load_embedded("default_material", &gltf);
    assert_eq!(scene.materials.len(), 1);
    assert_eq!(
        scene.materials[0],
        Material {
            name: "default material".into(),
            ..Material::gltf_default()
        }
    );
    assert!(scene.meshes.iter().all(|m| m.material == 0));
}

/// Four vertices of a unit square, counter-clockwise seen from +Z.
const SQUARE: [[f32; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

#[test]
fn strips_and_fans_become_counter_clockwise_lists() {
    let mut gltf = Gltf::default();
    let strip = gltf.floats(&[SQUARE[0], SQUARE[1], SQUARE[3], SQUARE[2]]);
    let normals = gltf.floats(&[[0.0, 0.0, 1.0]; 4]);
    gltf.mesh(
        "strip",
        json!({ "attributes": { "POSITION": strip, "NORMAL": normals }, "mode": 5 }),
    );
    let fan = gltf.floats(&SQUARE);
    gltf.mesh(
        "fan",
        json!({ "attributes": { "POSITION": fan, "NORMAL": normals }, "mode": 6 }),
    );
    let scene = load_embedded("strip_fan", &gltf);
    assert_eq!(*scene.meshes[0].indices, [0, 1, 2, 2, 1, 3]);
    assert_eq!(*scene.meshes[1].indices, [0, 1, 2, 0, 2, 3]);
    for mesh in &scene.meshes {
        for tri in mesh.indices.chunks(3) {
            let [a, b, c] =
                [0, 1, 2].map(|k| glam::Vec3::from(mesh.vertices[tri[k] as usize].position));
            assert!(
                (b - a).cross(c - a).z > 0.0,
                "{}: {tri:?} is clockwise",
                mesh.name
            );
        }
    }
}

#[test]
fn mirroring_transform_reverses_winding() {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&SQUARE[..3]);
    let mesh = gltf.push(
        "meshes",
        json!({ "primitives": [{ "attributes": { "POSITION": positions } }] }),
    );
    gltf.root(json!({ "mesh": mesh, "scale": [-1, 1, 1] }));
    let scene = load_embedded("mirror", &gltf);
    assert_eq!(*scene.meshes[0].indices, [0, 2, 1]);
    // No NORMAL: the zero normal that asks renderers for the (flipped) face normal.
    assert_eq!(scene.meshes[0].vertices[0].normal, [0.0; 3]);
}

/// Without NORMAL an indexed mesh keeps its shared vertices, each with the zero normal that
/// asks renderers for the face normal; a normal texture, whose MikkTSpace tangents need a
/// normal at every corner, writes the face normals out instead, three vertices a triangle.
#[test]
fn meshes_without_normals_keep_their_vertices_unless_tangents_need_them() {
    let mut gltf = Gltf::default();
    let uvs = gltf.floats(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    gltf.push("images", json!({ "uri": "missing.png" }));
    gltf.push("textures", json!({ "source": 0 }));
    let bumpy = gltf.push("materials", json!({ "normalTexture": { "index": 0 } }));
    for material in [None, Some(bumpy)] {
        let positions = gltf.floats(&SQUARE);
        let indices = gltf.indices_u16(&[0, 1, 2, 0, 2, 3]);
        let mut primitive = json!({
            "attributes": { "POSITION": positions, "TEXCOORD_0": uvs },
            "indices": indices,
        });
        if let Some(material) = material {
            primitive["material"] = json!(material);
        }
        gltf.mesh("square", primitive);
    }
    let dir = temp_dir("face_normals");
    std::fs::write(dir.join("missing.png"), png_2x1()).unwrap();
    let path = dir.join("scene.gltf");
    gltf.write_embedded(&path);
    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    let [shared, written] = [&scene.meshes[0], &scene.meshes[1]];
    assert_eq!(*shared.indices, [0, 1, 2, 0, 2, 3]);
    assert_eq!(shared.vertices.len(), 4);
    assert!(shared.vertices.iter().all(|v| v.normal == [0.0; 3]));
    assert_eq!(*written.indices, [0, 1, 2, 3, 4, 5]);
    assert_eq!(written.vertices.len(), 6);
    assert!(written.vertices.iter().all(|v| v.normal == [0.0, 0.0, 1.0]));
}

#[test]
fn quantized_positions_and_u32_indices() {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(["KHR_mesh_quantization"]);
    gltf.json["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
    let values: [i16; 9] = [0, 0, 0, 32767, 0, 0, -32768, -16384, 0];
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let positions = gltf.accessor(&bytes, SHORT, 3, "VEC3", true);
    let indices = gltf.indices_u32(&[0, 1, 2]);
    gltf.mesh(
        "quantized",
        json!({ "attributes": { "POSITION": positions }, "indices": indices }),
    );
    let scene = load_embedded("quantized", &gltf);
    let positions: Vec<[f32; 3]> = scene.meshes[0]
        .vertices
        .iter()
        .map(|v| v.position)
        .collect();
    // Normalized SHORT: c / 32767, clamped to -1.
    assert_eq!(
        positions,
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [-1.0, (-16384.0f64 / 32767.0) as f32, 0.0]
        ]
    );
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn sparse_accessor_substitutes_values() {
    let mut gltf = Gltf::default();
    let base = gltf.floats(&[[0.0, 0.0, 0.0], [9.0, 9.0, 9.0], [0.0, 1.0, 0.0]]);
    let index_view = gltf.view(&1u16.to_le_bytes());
    let value_view = gltf.view(
        &[1.0f32, 0.0, 0.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<_>>(),
    );
    gltf.json["accessors"][base]["sparse"] = json!({
        "count": 1,
        "indices": { "bufferView": index_view, "componentType": 5123 },
        "values": { "bufferView": value_view },
    });
    gltf.mesh("sparse", json!({ "attributes": { "POSITION": base } }));
    let scene = load_embedded("sparse", &gltf);
    let positions: Vec<[f32; 3]> = scene.meshes[0]
        .vertices
        .iter()
        .map(|v| v.position)
        .collect();
    assert_eq!(
        positions,
        [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    );
}

#[test]
fn unsupported_features_are_warnings_naming_them() {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(["KHR_materials_transmission", "KHR_materials_unlit"]);
    // The image file does not exist: textures no material uses are never decoded.
    gltf.push("images", json!({ "uri": "missing.png" }));
    gltf.push("textures", json!({ "source": 0 }));
    // Decoded: every material texture kind is implemented.
    gltf.push("images", json!({ "uri": "present.png" }));
    gltf.push("textures", json!({ "source": 1 }));
    let glass = gltf.push(
        "materials",
        json!({ "name": "glass", "alphaMode": "BLEND" }),
    );
    let bumpy = gltf.push(
        "materials",
        json!({
            "name": "bumpy",
            "normalTexture": { "index": 1 },
            "occlusionTexture": { "index": 1 },
            "emissiveTexture": { "index": 1 },
            "pbrMetallicRoughness": { "metallicRoughnessTexture": { "index": 1 } },
        }),
    );
    gltf.triangle(Some(glass));
    gltf.triangle(Some(bumpy));
    let points = gltf.floats(&[[0.0, 0.0, 0.0]]);
    gltf.mesh(
        "dots",
        json!({ "attributes": { "POSITION": points }, "mode": 0 }),
    );
    let dir = temp_dir("warnings");
    std::fs::write(dir.join("present.png"), png_2x1()).unwrap();
    let path = dir.join("scene.gltf");
    gltf.write_embedded(&path);
    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));

    assert_eq!(
        scene.warnings,
        [
            "glTF extension KHR_materials_transmission is not implemented; its effect is ignored",
            "mesh 1 \"triangle\" primitive 0: its material's normal texture needs TEXCOORD_0, \
             which it lacks; drawn without the normal texture",
        ]
    );
    assert_eq!(scene.meshes.len(), 2);
    assert_eq!(scene.points_lines.len(), 1, "the POINTS primitive is kept");
    // BLEND is implemented (the transparent pass): kept, without a warning.
    assert_eq!(
        scene.materials[0].alpha_mode,
        rgraph_scene::AlphaMode::Blend
    );
}

/// Application attributes (`_`-prefixed, which the glTF spec allows) are ignored, not a reason
/// to reject the file: Cesium's `_BATCHID`, bevy's `__BARYCENTRIC`.
#[test]
fn underscore_attributes_are_ignored() {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let batch = gltf.floats(&[[0.0], [0.0], [1.0]]);
    let barycentric = gltf.floats(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    gltf.mesh(
        "batched",
        json!({ "attributes": {
            "POSITION": positions, "_BATCHID": batch, "__BARYCENTRIC": barycentric
        } }),
    );
    let scene = load_embedded("underscore_attributes", &gltf);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.meshes.len(), 1);
    assert_eq!(scene.meshes[0].triangle_count(), 1);
}

/// A scene without `nodes` is valid glTF: it loads empty, with a warning naming it, in both
/// containers; so does a scene whose list is empty.
#[test]
fn scene_without_nodes_loads_empty_with_a_warning() {
    let dir = temp_dir("scene_without_nodes");
    let mut gltf = Gltf::default();
    gltf.json["scenes"] = json!([{ "name": "void" }]);
    let embedded = dir.join("scene.gltf");
    gltf.write_embedded(&embedded);
    let glb = dir.join("scene.glb");
    gltf.write_glb(&glb);
    gltf.json["scenes"] = json!([{ "nodes": [] }]);
    let listed = dir.join("listed.gltf");
    gltf.write_embedded(&listed);
    for (path, name) in [
        (&embedded, "scene 0 \"void\""),
        (&glb, "scene 0 \"void\""),
        (&listed, "scene 0"),
    ] {
        let scene = Scene::from_gltf(path).unwrap_or_else(|e| panic!("{e}"));
        assert!(scene.meshes.is_empty(), "{}", path.display());
        assert_eq!(
            scene.warnings,
            [format!(
                "{name} lists no nodes: nothing to draw, the frame is empty"
            )]
        );
    }
}

/// The emissive texture is sRGB color, the metallicRoughness texture linear data: one image
/// used as both is decoded into two scene textures, one per role, and each reference keeps
/// its own sampler.
#[test]
fn emissive_and_metallic_roughness_textures_are_loaded_in_their_color_spaces() {
    let mut gltf = Gltf::default();
    png_2x1_image(&mut gltf);
    gltf.push("samplers", json!({ "magFilter": 9728, "wrapS": 33071 }));
    gltf.push("textures", json!({ "source": 0, "sampler": 0 }));
    gltf.push("textures", json!({ "source": 0 }));
    let material = gltf.push(
        "materials",
        json!({
            "emissiveFactor": [1.0, 0.5, 0.25],
            "emissiveTexture": { "index": 0 },
            "pbrMetallicRoughness": { "metallicRoughnessTexture": { "index": 1 } },
        }),
    );
    gltf.triangle(Some(material));
    let scene = load_embedded("emissive_metallic_roughness", &gltf);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let srgb: Vec<bool> = scene.textures.iter().map(|t| t.srgb).collect();
    // metallicRoughness is converted before emissive.
    assert_eq!(srgb, [false, true]);
    assert!(scene
        .textures
        .iter()
        .all(|t| t.rgba8 == [255, 0, 0, 255, 0, 0, 255, 128]));
    let m = &scene.materials[0];
    let nearest_clamped = Sampler {
        wrap_u: WrapMode::ClampToEdge,
        mag_filter: FilterMode::Nearest,
        ..Sampler::default()
    };
    assert_eq!(
        m.emissive_texture,
        Some(TextureRef {
            image: 1,
            sampler: nearest_clamped,
            tex_coord: 0,
            uv_transform: TextureRef::IDENTITY_UV
        })
    );
    assert_eq!(
        m.metallic_roughness_texture,
        Some(TextureRef {
            image: 0,
            sampler: Sampler::default(),
            tex_coord: 0,
            uv_transform: TextureRef::IDENTITY_UV
        })
    );
    assert_eq!(m.base_color_texture, None);
}

/// COLOR_0 in each encoding the spec allows (float VEC3, normalized UNSIGNED_BYTE VEC4,
/// normalized UNSIGNED_SHORT VEC4) becomes the vertices' 16-bit RGBA, also on a primitive
/// without normals; without COLOR_0 vertices are white.
#[test]
fn color_0_in_every_encoding_becomes_the_vertex_color() {
    let mut gltf = Gltf::default();
    let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let float_rgb = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.5]];
    let bytes: [u8; 12] = [255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 51, 0];
    let shorts: Vec<u8> = [65535u16, 0, 0, 65535, 0, 32768, 0, 0, 0, 0, 65535, 65535]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let colors = [
        gltf.floats(&float_rgb),
        gltf.accessor(&bytes, 5121, 3, "VEC4", true),
        gltf.accessor(&shorts, common::UNSIGNED_SHORT, 3, "VEC4", true),
    ];
    for color in colors {
        let positions = gltf.floats(&corners);
        gltf.mesh(
            "colored",
            json!({ "attributes": { "POSITION": positions, "COLOR_0": color } }),
        );
    }
    gltf.triangle(None);
    let scene = load_embedded("color_0", &gltf);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let colors: Vec<Vec<[u16; 4]>> = scene
        .meshes
        .iter()
        .map(|m| m.vertices.iter().map(|v| v.color).collect())
        .collect();
    const MAX: u16 = u16::MAX;
    assert_eq!(
        colors,
        [
            vec![[MAX, 0, 0, MAX], [0, MAX, 0, MAX], [0, 0, 32768, MAX]],
            vec![[MAX, 0, 0, MAX], [0, MAX, 0, 32896], [0, 0, 13107, 0]],
            vec![[MAX, 0, 0, MAX], [0, 32768, 0, 0], [0, 0, MAX, MAX]],
            vec![Vertex::WHITE; 3],
        ]
    );
}

/// A unit quad in the xy plane facing +z, u along +x and v down the image (glTF's UV
/// origin is the image's top left), with `material`; `extra` attributes are added.
fn uv_quad(gltf: &mut Gltf, material: usize, extra: serde_json::Value) {
    let positions = gltf.floats(&[
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ]);
    let normals = gltf.floats(&[[0.0, 0.0, 1.0]; 4]);
    let uvs = gltf.floats(&[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
    let indices = gltf.indices_u16(&[0, 1, 2, 0, 2, 3]);
    let mut attributes = json!({ "POSITION": positions, "NORMAL": normals, "TEXCOORD_0": uvs });
    for (name, accessor) in extra.as_object().unwrap() {
        attributes[name] = accessor.clone();
    }
    gltf.mesh(
        "quad",
        json!({ "attributes": attributes, "indices": indices, "material": material }),
    );
}

/// Normal textures get tangents: TANGENT as the file has it, else MikkTSpace's, with the
/// sign that makes the bitangent point up the image (+y here, as glTF's normal textures
/// encode +Y); a mirroring node flips the sign; no normal texture, no tangents.
#[test]
fn normal_textures_get_tangents_from_the_file_or_mikktspace() {
    let mut gltf = Gltf::default();
    png_2x1_image(&mut gltf);
    gltf.push("textures", json!({ "source": 0 }));
    let bumpy = gltf.push(
        "materials",
        json!({ "normalTexture": { "index": 0, "scale": 0.5 } }),
    );
    let plain = gltf.push("materials", json!({}));
    // A normal texture on TEXCOORD_2 (not loaded) is dropped: nothing needs tangents.
    let third_set = gltf.push(
        "materials",
        json!({ "normalTexture": { "index": 0, "texCoord": 2 } }),
    );
    uv_quad(&mut gltf, bumpy, json!({}));
    let tangents = gltf.floats(&[[0.0, 1.0, 0.0, -1.0]; 4]);
    uv_quad(&mut gltf, bumpy, json!({ "TANGENT": tangents }));
    uv_quad(&mut gltf, plain, json!({}));
    uv_quad(&mut gltf, third_set, json!({}));
    // The first quad again, mirrored in x by its node.
    let nodes = gltf.json["nodes"].as_array().unwrap().len();
    gltf.root(json!({ "mesh": 0, "scale": [-1.0, 1.0, 1.0] }));
    assert_eq!(nodes, 4);
    let scene = load_embedded("tangents", &gltf);
    assert_eq!(
        scene.warnings,
        [
            "material 2: normal texture uses TEXCOORD_2, only TEXCOORD_0 and TEXCOORD_1 are \
             loaded; texture ignored"
        ]
    );
    let one = i16::MAX;
    let tangents: Vec<[i16; 4]> = scene.meshes.iter().map(|m| m.vertices[0].tangent).collect();
    assert_eq!(
        tangents,
        [
            [one, 0, 0, one],
            [0, one, 0, -one],
            Vertex::NO_TANGENT,
            Vertex::NO_TANGENT,
            [one, 0, 0, -one]
        ]
    );
    assert!(scene.meshes.iter().all(|m| m
        .vertices
        .iter()
        .all(|v| v.tangent == m.vertices[0].tangent)));
    let m = &scene.materials[0];
    assert_eq!(
        (m.normal_texture.map(|t| t.image), m.normal_scale),
        (Some(0), 0.5)
    );
    assert!(!scene.textures[0].srgb, "normal textures are linear data");
}

/// TEXCOORD_1 is kept beside TEXCOORD_0, and a texture says which set it samples; a normal
/// texture on set 1 gets its MikkTSpace tangents along set 1 (here u1 runs along -x, so the
/// tangent does too).
#[test]
fn texcoord_1_is_loaded_and_textures_name_their_set() {
    let mut gltf = Gltf::default();
    png_2x1_image(&mut gltf);
    gltf.push("textures", json!({ "source": 0 }));
    let material = gltf.push(
        "materials",
        json!({
            "emissiveFactor": [1.0, 1.0, 1.0],
            "emissiveTexture": { "index": 0, "texCoord": 1 },
            "normalTexture": { "index": 0, "texCoord": 1 },
            "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } },
        }),
    );
    let uv1 = gltf.floats(&[[1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0]]);
    uv_quad(&mut gltf, material, json!({ "TEXCOORD_1": uv1 }));
    let scene = load_embedded("texcoord_1", &gltf);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let uv1: Vec<[f32; 2]> = scene.meshes[0].vertices.iter().map(|v| v.uv1).collect();
    assert_eq!(uv1, [[1.0, 1.0], [0.0, 1.0], [0.0, 0.0], [1.0, 0.0]]);
    let m = &scene.materials[0];
    let sets = [m.base_color_texture, m.emissive_texture, m.normal_texture]
        .map(|t| t.map(|t| t.tex_coord));
    assert_eq!(sets, [Some(0), Some(1), Some(1)]);
    let one = i16::MAX;
    assert_eq!(scene.meshes[0].vertices[0].tangent, [-one, 0, 0, -one]);
}

/// KHR_texture_transform becomes each texture's UV matrix, as the extension's own example
/// reads: offset (0, 1), rotation 90° and scale 0.5 show the image's lower left quadrant
/// (UVs 0..1 land on u 0..0.5, v 0.5..1), on the normal texture as on the others; its
/// texCoord overrides the reference's.
#[test]
fn texture_transform_becomes_the_uv_matrix() {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(["KHR_texture_transform"]);
    png_2x1_image(&mut gltf);
    gltf.push("textures", json!({ "source": 0 }));
    let example = json!({ "KHR_texture_transform": {
        "offset": [0.0, 1.0], "rotation": std::f64::consts::FRAC_PI_2, "scale": [0.5, 0.5]
    } });
    let material = gltf.push(
        "materials",
        json!({
            "pbrMetallicRoughness": { "baseColorTexture": { "index": 0, "extensions": example } },
            "normalTexture": { "index": 0, "extensions": example },
            "emissiveFactor": [1.0, 1.0, 1.0],
            "emissiveTexture": { "index": 0, "extensions": {
                "KHR_texture_transform": { "texCoord": 1 }
            } },
        }),
    );
    let uv1 = gltf.floats(&[[0.0, 0.0]; 4]);
    uv_quad(&mut gltf, material, json!({ "TEXCOORD_1": uv1 }));
    let scene = load_embedded("texture_transform", &gltf);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let m = &scene.materials[0];
    let apply =
        |t: [[f32; 2]; 3], [u, v]: [f32; 2]| [0, 1].map(|i| t[0][i] * u + t[1][i] * v + t[2][i]);
    for texture in [m.base_color_texture, m.normal_texture] {
        let t = texture.expect("kept").uv_transform;
        for (uv, expected) in [
            ([0.0, 0.0], [0.0, 1.0]),
            ([1.0, 0.0], [0.0, 0.5]),
            ([0.0, 1.0], [0.5, 1.0]),
            ([1.0, 1.0], [0.5, 0.5]),
        ] {
            let got = apply(t, uv);
            assert!(
                (0..2).all(|i| (got[i] - expected[i]).abs() < 1e-6),
                "{uv:?} -> {got:?}, expected {expected:?}"
            );
        }
    }
    let emissive = m.emissive_texture.expect("kept");
    assert_eq!(
        (emissive.tex_coord, emissive.uv_transform),
        (1, TextureRef::IDENTITY_UV)
    );
}

/// Points and lines load as `PointsLines`: a LINE_LOOP as its segment list, COLOR_0
/// (VEC3 given alpha 1), the material, and a scene of nothing else loads, its bounds and
/// framing those of the lines.
#[test]
fn points_and_lines_load_and_a_scene_of_only_them_loads() {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0]]);
    let colors = gltf.floats(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    let material = gltf.push(
        "materials",
        json!({ "name": "wire", "emissiveFactor": [0.5, 0.0, 0.0] }),
    );
    gltf.mesh(
        "outline",
        json!({ "attributes": { "POSITION": positions, "COLOR_0": colors }, "mode": 2,
                "material": material }),
    );
    let dir = temp_dir("points_lines_load");
    let path = dir.join("scene.gltf");
    gltf.write_embedded(&path);
    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert!(scene.meshes.is_empty());
    let [lines] = &scene.points_lines[..] else {
        panic!("{:?}", scene.points_lines);
    };
    assert_eq!(lines.topology, rgraph_scene::Topology::Lines);
    assert_eq!(*lines.indices, [0, 1, 1, 2, 2, 0]);
    assert_eq!(lines.colors[2], [0.0, 0.0, 1.0, 1.0]);
    assert_eq!(
        scene.materials[lines.material].emissive_factor,
        [0.5, 0.0, 0.0]
    );
    assert_eq!(scene.bounds.max.x, 2.0);
    assert_eq!(scene.bounds.max.y, 1.0);
    assert!(rgraph_scene::analysis::Features::of(&scene).points_lines);
}
