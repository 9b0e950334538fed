//! Texture seams along triangle edges (issue 35): every hardware-raster pipeline draws a
//! textured surface's triangle edges with the texels there, never the texture's average
//! colour. lavapipe before Mesa 25 (Debian 12's 22.3.6) runs no storage-buffer load for a
//! 2x2 quad's helper invocations; texture coordinates that went through a transform read
//! from `materials` were (0, 0) there, and implicit derivatives in every quad a triangle
//! edge crosses chose the 1x1 mip level: a dotted seam along every edge
//! (docs/lavapipe-seams.md).

use crate::deferred_support;
use crate::gltf_writer::{temp_dir, Gltf};

use deferred_support::measure::{pixel_diff, share_within};
use deferred_support::textured;
use deferred_support::{gpu, Image, Render};
use rgraph_scene::analysis::Features;
use rgraph_scene::glam::{DMat4, DVec3};
use rgraph_scene::{Camera, Mesh, Projection, Sampler, Scene, TextureImage, Vertex};
use serde_json::json;

/// The hardware-raster pipelines that draw textured meshes: the G-buffer at 4x, lean and
/// at 1x, and forward shading.
const PIPELINES: [&str; 4] = [
    "deferred_msaa_4x.ron",
    "deferred_msaa_4x_lean.ron",
    "forward_msaa_4x.ron",
    "deferred_noaa.ron",
];

const SIZE: (u32, u32) = (128, 128);
/// Texels a side of the checker.
const TEXELS: u32 = 8;
/// Pixels a side of one texel on screen: the quad (2 units) spans 102.4 of the 128 pixels
/// under an orthographic view 2.5 units high.
const TEXEL_PIXELS: f64 = 12.8;
/// Where the quad starts on screen, in pixels from the left and from the top.
const QUAD_START: f64 = 12.8;
/// glTF sampler filters: NEAREST magnification keeps each texel one flat colour on screen;
/// LINEAR_MIPMAP_LINEAR minification gives the texture mip levels, whose 1x1 level is the
/// average a seam showed.
const NEAREST: u32 = 9728;
const LINEAR_MIPMAP_LINEAR: u32 = 9987;

/// An 8x8 checker of red and blue texels as a PNG.
fn checker_png() -> Vec<u8> {
    let (red, blue) = ([220u8, 60, 40, 255], [40u8, 90, 220, 255]);
    let texels = (0..TEXELS * TEXELS).flat_map(|i| match (i % TEXELS + i / TEXELS) % 2 {
        0 => red,
        _ => blue,
    });
    let image = image::RgbaImage::from_raw(TEXELS, TEXELS, texels.collect()).unwrap();
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    png
}

/// A 2x2-unit quad of two triangles at z = 0 facing +z, split along its diagonal from
/// bottom left to top right, with an unlit material whose base colour is the checker
/// (UV (0, 0) at its top left), under an orthographic camera 3 units in front whose view
/// is 2.5 units high; returns the file's path.
fn checker_quad_file() -> String {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(["KHR_materials_unlit"]);
    let positions = gltf.floats(&[
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ]);
    let normals = gltf.floats(&[[0.0, 0.0, 1.0]; 4]);
    let uvs = gltf.floats(&[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
    let indices = gltf.indices_u16(&[0, 1, 2, 0, 2, 3]);
    gltf.push(
        "samplers",
        json!({ "magFilter": NEAREST, "minFilter": LINEAR_MIPMAP_LINEAR }),
    );
    let view = gltf.view(&checker_png());
    let image = gltf.push(
        "images",
        json!({ "bufferView": view, "mimeType": "image/png" }),
    );
    gltf.push("textures", json!({ "source": image, "sampler": 0 }));
    let material = gltf.push(
        "materials",
        json!({
            "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } },
            "extensions": { "KHR_materials_unlit": {} },
        }),
    );
    gltf.mesh(
        "checker quad",
        json!({
            "attributes": { "POSITION": positions, "NORMAL": normals, "TEXCOORD_0": uvs },
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
    let path = temp_dir("texture_seams").join("checker_quad.gltf");
    gltf.write_embedded(&path);
    path.to_str().unwrap().to_owned()
}

/// `scene` through `pipeline` at `size`, compiled for the scene's features as `rgraph
/// render` compiles it.
fn color(pipeline: &str, scene: &Scene, size: (u32, u32)) -> Image {
    let gpu = gpu();
    Render::new(pipeline, &scene.name, size)
        .with_scene(scene.clone())
        .features(Features::of(scene).names())
        .run(&gpu)
        .image(&gpu, "color")
}

/// The texel (column, row) whose region holds the center of pixel (`x`, `y`), if that
/// center lies at least 1.5 pixels inside the region (nearest magnification makes the
/// region one colour; 4x samples nearer its border may fall in the next texel).
fn texel_at(x: u32, y: u32) -> Option<(u32, u32)> {
    let axis = |p: u32| {
        let t = (f64::from(p) + 0.5 - QUAD_START) / TEXEL_PIXELS;
        let inside = (0.0..f64::from(TEXELS)).contains(&t);
        let from_border = (t - t.floor()).min(t.ceil() - t) * TEXEL_PIXELS;
        (inside && from_border >= 1.5).then_some(t.floor() as u32)
    };
    Some((axis(x)?, axis(y)?))
}

/// The pixel that stands for texel (`column`, `row`): 3 pixels right of and below its
/// region's center, so 4.2 pixels off the diagonal for the texels the diagonal halves.
fn texel_reference((column, row): (u32, u32)) -> (u32, u32) {
    let at = |t: u32| (QUAD_START + (f64::from(t) + 0.5) * TEXEL_PIXELS + 3.0) as u32;
    (at(column), at(row))
}

/// The two-triangle checker quad has no seam: each pixel on the diagonal the two
/// triangles share (its center within 1.5 pixels of it) is within 2/255 of a pixel of the
/// same texel off the diagonal, and so is every other pixel of the quad, in every
/// hardware-raster pipeline, at 4x and at 1x. Before the fix lavapipe drew the diagonal
/// in the checker's average colour (5 of 8 bits off; docs/lavapipe-seams.md).
#[test]
fn a_checker_quad_has_no_seam_along_its_diagonal() {
    let file = checker_quad_file();
    let scene = Scene::load(&file).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let mut seams = Vec::new();
    for pipeline in PIPELINES {
        let image = color(pipeline, &scene, SIZE);
        let (mut diagonal, mut worst) = (0, (0u8, (0, 0), (0, 0)));
        for (x, y) in (0..SIZE.1).flat_map(|y| (0..SIZE.0).map(move |x| (x, y))) {
            let Some(texel) = texel_at(x, y) else {
                continue;
            };
            let (rx, ry) = texel_reference(texel);
            let off = pixel_diff(image.at(x, y), image.at(rx, ry));
            // Pixel centers sum to 128 on the diagonal.
            if (f64::from(x + y) + 1.0 - 128.0).abs() <= 1.5 * 2f64.sqrt() {
                diagonal += 1;
            }
            if off > worst.0 {
                worst = (off, (x, y), (rx, ry));
            }
        }
        assert!(
            diagonal >= 150,
            "{pipeline}: only {diagonal} diagonal pixels checked"
        );
        let (off, (x, y), (rx, ry)) = worst;
        if off > 2 {
            seams.push(format!(
                "{pipeline}: pixel ({x}, {y}) {:?} is {off}/255 off its texel's colour {:?} at \
                 ({rx}, {ry})",
                image.at(x, y),
                image.at(rx, ry),
            ));
        }
    }
    assert!(seams.is_empty(), "{}", seams.join("\n"));
}

/// A sphere of radius 1 about the origin, `rings` x `segments` quads (two triangles
/// each, a few pixels across at the sizes tests render: as small as DamagedHelmet's in
/// its frame), its textures repeating 6 times around and 3 times from pole to pole
/// (seen minified, as DamagedHelmet's 2048-texel images are in its frame), tangents
/// along U.
fn sphere(rings: u32, segments: u32, material: usize) -> Mesh {
    let tau = std::f64::consts::TAU;
    let mut vertices = Vec::new();
    for ring in 0..=rings {
        let polar = std::f64::consts::PI * f64::from(ring) / f64::from(rings);
        for segment in 0..=segments {
            let azimuth = tau * f64::from(segment) / f64::from(segments);
            let n = DVec3::new(
                polar.sin() * azimuth.cos(),
                polar.cos(),
                -polar.sin() * azimuth.sin(),
            );
            let u = 6.0 * f64::from(segment) / f64::from(segments);
            let v = 3.0 * f64::from(ring) / f64::from(rings);
            let uv = [u as f32, v as f32];
            vertices.push(Vertex {
                position: n.as_vec3().to_array(),
                normal: n.as_vec3().to_array(),
                uv,
                color: Vertex::WHITE,
                tangent: Vertex::tangent_from([
                    -azimuth.sin() as f32,
                    0.0,
                    -azimuth.cos() as f32,
                    1.0,
                ]),
                uv1: [uv[1] * 0.5, uv[0] * 0.5],
            });
        }
    }
    let row = segments + 1;
    let indices = (0..rings)
        .flat_map(|ring| (0..segments).map(move |segment| ring * row + segment))
        .flat_map(|i| [i, i + row, i + row + 1, i, i + row + 1, i + 1])
        .collect();
    Mesh {
        name: "sphere".into(),
        vertices: vertices.into(),
        indices: std::sync::Arc::new(indices),
        material,
        transform: DMat4::IDENTITY,
    }
}

/// A 64-texel image like a painted surface's (smooth bands, none of the fixture's crisp
/// checker and stripes, whose edges two renderers' slightly different levels of detail
/// blur differently), repeating; the size of the fixture's other images, so the scene's
/// textures fit the visibility buffer's texture table. `texel(u, v)` in [0, 1]².
fn painted(name: &str, srgb: bool, texel: impl Fn(f64, f64) -> [f64; 3]) -> TextureImage {
    let side = 64u32;
    let unorm = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let rgba8 = (0..side * side)
        .flat_map(|i| {
            let u = f64::from(i % side) / f64::from(side);
            let v = f64::from(i / side) / f64::from(side);
            let [r, g, b] = texel(u, v);
            [unorm(r), unorm(g), unorm(b), 255]
        })
        .collect();
    TextureImage {
        name: name.into(),
        width: side,
        height: side,
        rgba8,
        srgb,
    }
}

/// DamagedHelmet-like content: a lit sphere of 4608 triangles a few pixels across, every
/// slot but emission textured (tests/deferred_support/textured.rs' material, base colour
/// and metalness [`painted`]), seen from the front and above.
fn textured_sphere() -> Scene {
    let mut parts = deferred_support::scenes::Parts::new();
    let material = textured::material(&mut parts, "sphere", Sampler::default());
    // The fixture's emission is crisp stripes: none here.
    parts.materials[material].emissive_texture = None;
    parts.materials[material].emissive_factor = [0.0; 3];
    parts.meshes.push(sphere(48, 48, material));
    parts.lights.push(textured::sun());
    parts.ambient = [0.15; 3];
    let camera = Camera::look_at(
        "front, above",
        DVec3::new(0.0, 0.9, 3.4),
        DVec3::ZERO,
        DVec3::Y,
        Projection::Perspective {
            yfov: std::f32::consts::FRAC_PI_4,
            znear: 0.1,
            zfar: None,
        },
    );
    let mut scene = parts.scene("textured sphere", camera);
    let tau = std::f64::consts::TAU;
    scene.textures = textured::images();
    scene.textures[0] = painted("base colour", true, |u, v| {
        let band = (tau * (2.0 * u + v)).sin();
        let spot = (tau * 3.0 * v).cos() * (tau * u).sin();
        [0.5 + 0.3 * band, 0.55 + 0.25 * spot, 0.6 - 0.2 * band]
    });
    // The fixture's metalness and roughness run from 0 to 1 across the image: a crisp
    // line where it repeats.
    scene.textures[2] = painted("metallic roughness", false, |u, v| {
        [
            0.0,
            0.6 + 0.25 * (tau * v).cos(),
            0.5 + 0.4 * (tau * u).sin(),
        ]
    });
    scene
}

/// Textured content of small triangles through the G-buffer is within 4/255 of the
/// visibility buffer's image (whose shading takes analytic derivatives in compute) on at
/// least 97% of pixels, as DamagedHelmet is at 1280x720 (docs/lavapipe-seams.md). Before
/// the fix lavapipe's seams covered the sphere with a wireframe of other colours.
#[test]
fn small_textured_triangles_render_the_visibility_buffer_s_image() {
    let scene = textured_sphere();
    assert!(
        !Features::of(&scene).untabled_textures,
        "the textured sphere's textures must fit the texture table, or visibility_msaa_4x \
         renders them through the G-buffer too"
    );
    let size = (480, 360);
    let gbuffer = color("deferred_msaa_4x.ron", &scene, size);
    let visibility = color("visibility_msaa_4x.ron", &scene, size);
    let share = share_within(&gbuffer, &visibility, 4, None);
    eprintln!("textured sphere: {:.2}% within 4/255", 100.0 * share);
    assert!(
        share >= 0.97,
        "textured sphere: only {:.2}% of pixels within 4/255 of visibility_msaa_4x",
        100.0 * share
    );
}
