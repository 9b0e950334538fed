//! Minified textures filter instead of aliasing: a quad 15 pixels wide textured with a
//! 256x256 black-and-white checker of one-texel squares (17 texels per pixel) shows the
//! checker's mean, sRGB 188 (linear 0.5), through its mipmaps; a glTF sampler without
//! mipmaps (min filter LINEAR) reads level 0 only, and aliases (GPU, lavapipe by default).

use crate::deferred_support;

use deferred_support::scenes::Parts;
use deferred_support::{gpu, Render};
use rgraph_scene::glam::DVec3;
use rgraph_scene::{Camera, FilterMode, Projection, Sampler, Scene, TextureImage, TextureRef};

const SIZE: (u32, u32) = (64, 64);
const TEXELS: u32 = 256;

/// The quad from (-1, -1) to (1, 1) at z = 0, seen from 7.8 units away, unlit and white
/// times the checker sampled with `sampler`.
fn checker_quad(sampler: Sampler) -> Scene {
    let mut parts = Parts::new();
    let material = parts.material("checker", [1.0, 1.0, 1.0], 1.0);
    parts.materials[material].unlit = true;
    parts.materials[material].base_color_texture = Some(TextureRef {
        image: 0,
        sampler,
        tex_coord: 0,
        uv_transform: TextureRef::IDENTITY_UV,
    });
    let d = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    let quad = parts.mesh(
        "quad",
        &[vec![d(-1.0, -1.0), d(1.0, -1.0), d(1.0, 1.0), d(-1.0, 1.0)]],
        material,
    );
    let vertices = std::sync::Arc::make_mut(&mut parts.meshes[quad].vertices);
    for (vertex, uv) in vertices
        .iter_mut()
        .zip([[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]])
    {
        vertex.uv = uv;
    }
    // About 15 pixels wide, off-center: pixel centers fall at no fixed place in the
    // texels (a symmetric framing puts them on texel corners, where bilinear filtering
    // of level 0 happens to give the mean too).
    let eye = DVec3::new(0.0137, 0.0071, 7.8);
    let camera = Camera::look_at(
        "front",
        eye,
        DVec3::new(eye.x, eye.y, 0.0),
        DVec3::Y,
        Projection::Perspective {
            yfov: 1.0,
            znear: 0.1,
            zfar: None,
        },
    );
    let mut scene = parts.scene("checker quad", camera);
    scene.textures.push(TextureImage {
        name: "checker".into(),
        width: TEXELS,
        height: TEXELS,
        rgba8: (0..TEXELS * TEXELS)
            .flat_map(|i| {
                let v = if (i % TEXELS + i / TEXELS).is_multiple_of(2) {
                    255
                } else {
                    0
                };
                [v, v, v, 255]
            })
            .collect(),
        srgb: true,
    });
    scene
}

/// The albedo of the quad's middle 8x8 pixels, as debug.albedo shows it (sRGB).
fn middle(sampler: Sampler) -> Vec<u8> {
    let gpu = gpu();
    let image = Render::new("deferred_noaa.ron", "checker quad", SIZE)
        .with_scene(checker_quad(sampler))
        .run(&gpu)
        .image(&gpu, "debug.albedo");
    (28..36)
        .flat_map(|y| (28..36).map(move |x| (x, y)))
        .map(|(x, y)| image.at(x, y)[0])
        .collect()
}

#[test]
fn a_minified_checker_shows_its_mean_through_the_mipmaps() {
    let values = middle(Sampler::default());
    let (lo, hi) = (values.iter().min().unwrap(), values.iter().max().unwrap());
    // Trilinear filtering between levels 3 and 5 of a uniform grey chain: 188 +- rounding.
    assert!(
        *lo >= 183 && *hi <= 193,
        "the middle of the quad ranges over {lo}..={hi}: {values:?}"
    );
}

#[test]
fn a_sampler_without_mipmaps_reads_level_zero_and_aliases() {
    let sampler = Sampler {
        min_filter: FilterMode::Linear,
        mipmap_filter: None,
        ..Sampler::default()
    };
    let values = middle(sampler);
    let off = values.iter().filter(|&&v| v.abs_diff(188) > 20).count();
    // Level 0 bilinearly sampled once per pixel: black, white or a blend by where the
    // pixel center falls, rarely the mean.
    assert!(
        off > values.len() / 2,
        "only {off} of {} pixels stray from the mean: {values:?}",
        values.len()
    );
}
