//! A textured scene built in code, for comparing how pipelines filter textures: a floor
//! seen at a grazing angle (so each pixel's footprint stretches over many texels and
//! mipmaps and their level of detail decide the colour) and two upright panels, every
//! material with base colour, emissive, metallicRoughness, normal and occlusion textures
//! (64x64, full mip chains made at upload) and tangents, occlusion on a second UV set and
//! emission through a texture transform. The floor repeats its textures ten times
//! across; one panel clamps to the edge with nearest magnification, one mirrors, so every
//! wrap mode and both filters are seen.
use rgraph_scene::glam::{DVec3, Vec3};
use rgraph_scene::{
    Camera, FilterMode, Light, LightKind, Projection, Sampler, Scene, TextureImage, TextureRef,
    Vertex, WrapMode,
};

use super::scenes::Parts;

/// Texels a side of every texture.
const TEXELS: u32 = 64;

/// A procedural RGBA8 image: `texel(x, y)` for each texel, top row first.
fn image(name: &str, srgb: bool, texel: impl Fn(f64, f64) -> [u8; 4]) -> TextureImage {
    let side = f64::from(TEXELS);
    TextureImage {
        name: name.into(),
        width: TEXELS,
        height: TEXELS,
        rgba8: (0..TEXELS * TEXELS)
            .flat_map(|i| texel(f64::from(i % TEXELS) / side, f64::from(i / TEXELS) / side))
            .collect(),
        srgb,
    }
}

fn unorm(v: f64) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The five images, in `Material::texture_slots` order: a colour checker with a
/// gradient, emissive stripes, metallic and roughness varying across (roughness 0.4 and
/// up: glossier metal turns the few-hundredths-of-a-level differences between two
/// pipelines' filtering into specular sparkles), bumps (a normal map of a sine height
/// field) and occlusion in the bumps' valleys.
pub fn images() -> Vec<TextureImage> {
    let tau = std::f64::consts::TAU;
    vec![
        image("base colour", true, |u, v| {
            let check = ((u * 8.0).floor() + (v * 8.0).floor()) % 2.0;
            [
                unorm(0.3 + 0.6 * u),
                unorm(0.25 + 0.5 * check),
                unorm(0.8 - 0.6 * v),
                255,
            ]
        }),
        image("emissive", true, |u, _| {
            let stripe = f64::from(u8::from((u * 4.0).fract() < 0.2));
            [unorm(stripe), unorm(0.5 * stripe), 0, 255]
        }),
        image("metallic roughness", false, |u, v| {
            [0, unorm(0.4 + 0.5 * v), unorm(u), 255]
        }),
        image("normal", false, |u, v| {
            // Height sin(2 tau u) sin(2 tau v) / (4 tau): its slopes, as a unit normal.
            let dx = 0.5 * (2.0 * tau * u).cos() * (2.0 * tau * v).sin();
            let dy = 0.5 * (2.0 * tau * u).sin() * (2.0 * tau * v).cos();
            let n = DVec3::new(-dx, -dy, 1.0).normalize();
            [
                unorm(n.x * 0.5 + 0.5),
                unorm(n.y * 0.5 + 0.5),
                unorm(n.z * 0.5 + 0.5),
                255,
            ]
        }),
        image("occlusion", false, |u, v| {
            let h = (2.0 * tau * u).sin() * (2.0 * tau * v).sin();
            [unorm(0.6 + 0.4 * h), 0, 0, 255]
        }),
    ]
}

/// One of the floor's or panels' materials: every slot textured with `sampler`.
pub fn material(parts: &mut Parts, name: &str, sampler: Sampler) -> usize {
    let index = parts.material(name, [1.0, 1.0, 1.0], 1.0);
    let texture = |image| {
        Some(TextureRef {
            image,
            sampler,
            tex_coord: 0,
            uv_transform: TextureRef::IDENTITY_UV,
        })
    };
    let m = &mut parts.materials[index];
    m.metallic_factor = 1.0;
    m.base_color_texture = texture(0);
    m.emissive_factor = [0.6, 0.6, 0.6];
    m.metallic_roughness_texture = texture(2);
    m.normal_texture = texture(3);
    // Occlusion on TEXCOORD_1, and emission through a KHR_texture_transform (rotated a
    // quarter turn's third, scaled 1.5 and offset), as loaded glTF materials can have them.
    m.occlusion_texture = texture(4).map(|t| TextureRef { tex_coord: 1, ..t });
    let (sin, cos) = (
        std::f32::consts::FRAC_PI_6.sin(),
        std::f32::consts::FRAC_PI_6.cos(),
    );
    m.emissive_texture = texture(1).map(|t| TextureRef {
        uv_transform: [
            [1.5 * cos, 1.5 * sin],
            [-1.5 * sin, 1.5 * cos],
            [0.25, -0.1],
        ],
        ..t
    });
    index
}

/// A quad from `corners` (counter-clockwise from the front) with texture coordinates
/// `uvs` at them (TEXCOORD_1 the same, halved and swapped), and the tangent along its
/// first edge (where U grows).
fn quad(parts: &mut Parts, name: &str, corners: [DVec3; 4], uvs: [[f32; 2]; 4], material: usize) {
    let mesh = parts.mesh(name, &[corners.to_vec()], material);
    let along = (corners[1] - corners[0]).normalize().as_vec3();
    for (vertex, uv) in std::sync::Arc::make_mut(&mut parts.meshes[mesh].vertices)
        .iter_mut()
        .zip(uvs)
    {
        vertex.uv = uv;
        vertex.uv1 = [uv[1] * 0.5, uv[0] * 0.5];
        vertex.tangent = Vertex::tangent_from([along.x, along.y, along.z, 1.0]);
    }
}

/// The low sun that lights the scene, from the front left and above.
pub fn sun() -> Light {
    Light {
        name: "sun".into(),
        kind: LightKind::Directional,
        color: [1.0, 0.95, 0.9],
        intensity: 2.5,
        position: DVec3::ZERO,
        direction: Vec3::new(-0.4, -0.6, -0.7).normalize(),
        range: None,
    }
}

/// The scene: see the module documentation. Lit by a low sun, a point light and some
/// ambient light.
pub fn textured_scene() -> Scene {
    let mut parts = Parts::new();
    let floor = material(&mut parts, "floor", Sampler::default());
    let clamped = material(
        &mut parts,
        "clamped",
        Sampler {
            wrap_u: WrapMode::ClampToEdge,
            wrap_v: WrapMode::ClampToEdge,
            mag_filter: FilterMode::Nearest,
            ..Sampler::default()
        },
    );
    let mirrored = material(
        &mut parts,
        "mirrored",
        Sampler {
            wrap_u: WrapMode::MirroredRepeat,
            wrap_v: WrapMode::MirroredRepeat,
            ..Sampler::default()
        },
    );
    let d = DVec3::new;
    // A trapezoid inside the view: the rasteriser clips nothing, so both G-buffer paths
    // draw its two triangles as they are (see the derivative test in tests/visibility.rs).
    // Texture coordinates are the plane's, 2/3 of a repeat per unit.
    let corners = [
        d(-1.4, 0.0, 2.0),
        d(2.0, 0.0, 2.0),
        d(8.0, 0.0, -6.0),
        d(-7.4, 0.0, -6.0),
    ];
    quad(
        &mut parts,
        "floor",
        corners,
        corners.map(|c| [(c.x / 1.5) as f32, (-c.z / 1.5) as f32]),
        floor,
    );
    quad(
        &mut parts,
        "clamped panel",
        [
            d(-2.6, 0.2, -0.5),
            d(-0.6, 0.2, -1.2),
            d(-0.6, 2.0, -1.2),
            d(-2.6, 2.0, -0.5),
        ],
        [[-0.25, 1.25], [1.25, 1.25], [1.25, -0.25], [-0.25, -0.25]],
        clamped,
    );
    quad(
        &mut parts,
        "mirrored panel",
        [
            d(0.6, 0.2, -1.2),
            d(2.6, 0.2, -0.3),
            d(2.6, 2.0, -0.3),
            d(0.6, 2.0, -1.2),
        ],
        [[0.0, 2.0], [2.0, 2.0], [2.0, 0.0], [0.0, 0.0]],
        mirrored,
    );
    parts.lights.push(sun());
    parts.lights.push(Light::point(
        "lamp",
        d(0.0, 1.2, 1.5),
        [0.9, 0.9, 1.0],
        3.0,
        None,
    ));
    parts.ambient = [0.15; 3];
    let camera = Camera::look_at(
        "grazing",
        d(0.3, 1.1, 4.5),
        d(0.0, 0.6, -1.0),
        DVec3::Y,
        Projection::Perspective {
            yfov: 0.9,
            znear: 0.1,
            zfar: Some(50.0),
        },
    );
    let mut scene = parts.scene("textured", camera);
    scene.textures = images();
    scene
}
