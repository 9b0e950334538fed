//! The December audit's glTF findings: what loaded wrongly (a byte-order mark, a light
//! with a negative color, a znear that renders nothing), what spent the memory before the
//! scene limit refused it (many placements of a mesh, image bombs), and a legal texture the
//! decoder's default memory limit refused.

use crate::common;

use common::{temp_dir, Gltf};
use rgraph_scene::{AssetPolicy, Lighting, Scene, SceneError};
use serde_json::json;

#[test]
fn a_byte_order_mark_before_the_json_is_skipped() {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    let path = temp_dir("bom").join("scene.gltf");
    gltf.write_embedded(&path);
    let mut bytes = b"\xEF\xBB\xBF".to_vec();
    bytes.extend(std::fs::read(&path).unwrap());
    std::fs::write(&path, bytes).unwrap();
    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.meshes.len(), 1);
}

/// A triangle lit by one point light with `light`'s fields, loaded.
fn lit_by(test: &str, light: serde_json::Value) -> (std::path::PathBuf, Result<Scene, SceneError>) {
    let mut gltf = Gltf::default();
    gltf.triangle(None);
    gltf.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    gltf.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [light] } });
    gltf.root(json!({ "extensions": { "KHR_lights_punctual": { "light": 0 } } }));
    let path = temp_dir(test).join("scene.gltf");
    gltf.write_embedded(&path);
    let loaded = Scene::from_gltf(&path);
    (path, loaded)
}

#[test]
fn a_light_with_a_negative_color_is_an_error_naming_it() {
    let light =
        json!({ "name": "anti", "type": "point", "intensity": 5.0, "color": [-1.0, 0.5, 1.0] });
    let (path, loaded) = lit_by("negative_light", light);
    assert_eq!(
        loaded.expect_err("the color is negative").to_string(),
        format!(
            "{}: light 0 \"anti\": color [-1, 0.5, 1] has a negative channel; a light's color \
             is linear RGB from 0",
            path.display()
        )
    );
}

#[test]
fn lights_that_emit_nothing_are_named_when_the_defaults_stand_in() {
    let light = json!({ "name": "off", "type": "point", "intensity": 0.0 });
    let (path, loaded) = lit_by("dark_light", light);
    let scene = loaded.unwrap_or_else(|e| panic!("{e}")).lit(Lighting::Auto);
    let warning = scene.warnings.last().expect("the defaults are announced");
    assert!(
        warning.starts_with(&format!(
            "{}: none of its 1 light(s) emits anything (light 0 \"off\": intensity or color \
             0); lit by the default lighting",
            path.display()
        )),
        "{warning}"
    );
}

#[test]
fn a_perspective_znear_that_would_render_nothing_is_an_error_naming_the_camera() {
    let with_znear = |znear: f64| {
        let mut gltf = Gltf::default();
        gltf.triangle(None);
        let camera = gltf.push(
            "cameras",
            json!({ "name": "eye", "type": "perspective", "perspective": { "yfov": 0.8, "znear": znear } }),
        );
        gltf.root(json!({ "camera": camera, "translation": [0.0, 0.0, 3.0] }));
        let path = temp_dir("tiny_znear").join("scene.gltf");
        gltf.write_embedded(&path);
        (path.clone(), Scene::from_gltf(&path))
    };
    for znear in [1e-38, 1e-30] {
        let (path, loaded) = with_znear(znear);
        assert_eq!(
            loaded.expect_err("znear is too small").to_string(),
            format!(
                "{}: camera 0 \"eye\": znear {:e} is below 4.7e-26: depths (znear / distance) \
                 would fall below the smallest normal f32, which GPUs flush to the far plane, \
                 and the frame would be empty",
                path.display(),
                znear as f32
            )
        );
    }
    let (_, loaded) = with_znear(1e-25);
    loaded.unwrap_or_else(|e| panic!("a znear of 1e-25 is fine: {e}"));
}

#[test]
fn every_placement_of_a_mesh_is_counted_before_any_is_built() {
    let mut gltf = Gltf::default();
    let mesh = gltf.triangle(None);
    for _ in 0..999 {
        gltf.root(json!({ "mesh": mesh }));
    }
    let path = temp_dir("placements").join("scene.glb");
    gltf.write_glb(&path);
    // 1,000 placements of a mesh record each, sharing 180 bytes of geometry (3 vertices
    // of 56 bytes, 3 indices).
    let record = std::mem::size_of::<rgraph_scene::Mesh>() as u64;
    let policy = AssetPolicy {
        max_scene_bytes: 180 + 1_000 * record - 1,
        ..AssetPolicy::default()
    };
    let error = Scene::from_gltf_with(&path, &policy).expect_err("one byte short");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: mesh 0 \"triangle\": placing it 1000 times (180 bytes of geometry, which its \
             undeformed placements share, and {record} bytes a primitive placed) would take \
             the scene past {} bytes of vertices, indices and textures (the scene memory \
             limit)",
            path.display(),
            policy.max_scene_bytes
        )
    );
}

/// A PNG whose header says `width` x `height` RGBA8 and whose pixel data is one zero row:
/// a decompression bomb's header, in a few dozen bytes.
fn bomb_png(width: u32, height: u32) -> Vec<u8> {
    let mut png = Vec::new();
    image::RgbaImage::new(1, 1)
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    // IHDR's data starts at byte 16 (8 of signature, 4 of length, 4 of type); its CRC
    // follows its 13 bytes and covers the type and the data.
    png[16..20].copy_from_slice(&width.to_be_bytes());
    png[20..24].copy_from_slice(&height.to_be_bytes());
    let crc = crc32(&png[12..29]);
    png[29..33].copy_from_slice(&crc.to_be_bytes());
    png
}

/// CRC-32 (IEEE), as PNG chunks carry it.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = (crc >> 1) ^ (0xEDB8_8320 & (crc & 1).wrapping_neg());
        }
    }
    !crc
}

/// A triangle whose material's base color is the image in `png`, written as a `.glb`.
fn textured(test: &str, png: &[u8]) -> std::path::PathBuf {
    let mut gltf = Gltf::default();
    gltf.textured_triangle(png);
    let path = temp_dir(test).join("scene.glb");
    gltf.write_glb(&path);
    path
}

#[test]
fn an_image_bomb_is_refused_from_its_header_before_the_geometry_is_built() {
    // 40000 x 40000 RGBA8 with mips: 8.5 GB, more than the 4 GiB a scene may hold.
    let path = textured("image_bomb", &bomb_png(40_000, 40_000));
    let error = Scene::from_gltf(&path).expect_err("the image is too large");
    assert_eq!(
        error.to_string(),
        format!(
            "{}: image 0 (base color of material 0 \"painted\"): decoding it (40000x40000) \
             would take the scene past 4294967296 bytes of vertices, indices and textures \
             (the scene memory limit)",
            path.display()
        )
    );
}

#[test]
fn an_image_larger_than_the_decoder_s_default_limit_loads() {
    // 11600 x 11600 RGBA8 decodes to 538 MB: more than the `image` crate's default limit of
    // 512 MiB, which refused it ("Memory limit exceeded"). The zeroed buffer is never
    // written, so it costs no memory until the encoder reads it.
    let (width, height) = (11_600u32, 11_600u32);
    let pixels = vec![0u8; width as usize * height as usize * 4];
    let mut png = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new_with_quality(
        &mut png,
        image::codecs::png::CompressionType::Fast,
        image::codecs::png::FilterType::NoFilter,
    );
    image::ImageEncoder::write_image(
        encoder,
        &pixels,
        width,
        height,
        image::ExtendedColorType::Rgba8,
    )
    .unwrap();
    drop(pixels);
    let path = textured("large_image", &png);
    let scene = Scene::from_gltf(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        (scene.textures[0].width, scene.textures[0].height),
        (width, height)
    );
    assert_eq!(
        scene.textures[0].rgba8.len(),
        width as usize * height as usize * 4
    );
}
