//! The scale scenes as a user renders them: `rgraph render --scene builtin:terrain?cells=N`
//! and `builtin:city?blocks=K` through the default pipeline at 64x36 on lavapipe (unless
//! RGRAPH_ADAPTER says otherwise) draw their geometry, lit, over a stated share of the frame.
//! Sizes, limits and determinism are the scene crate's tests (scene/tests/builtin_scale.rs).

use crate::cli_support::rgraph;

/// Renders `scene` with the default pipeline at 64x36 over a transparent background (alpha
/// is coverage) and returns the image.
fn render(scene: &str) -> image::RgbaImage {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let out = dir.path().join("frame.png");
    let out_arg = out.to_str().expect("temp paths are UTF-8");
    rgraph(&[
        "render",
        "--scene",
        scene,
        "--width",
        "64",
        "--height",
        "36",
        "--background",
        "transparent",
        "--out",
        out_arg,
    ])
    .expect(0)
    .stderr_has(&format!("load scene {scene}"));
    image::open(&out)
        .unwrap_or_else(|e| panic!("{} is not a readable PNG: {e}", out.display()))
        .into_rgba8()
}

/// The share of pixels the scene covers (alpha above 0), and their mean sRGB brightness,
/// 0 to 255.
fn coverage(image: &image::RgbaImage) -> (f64, f64) {
    let covered: Vec<[u8; 4]> = image.pixels().map(|p| p.0).filter(|p| p[3] > 0).collect();
    let brightness = covered
        .iter()
        .map(|p| p[..3].iter().map(|&c| f64::from(c)).sum::<f64>() / 3.0)
        .sum::<f64>()
        / covered.len().max(1) as f64;
    let pixels = f64::from(image.width() * image.height());
    (covered.len() as f64 / pixels, brightness)
}

/// Renders `scene` and asserts that it covers more than `least` of the frame, lit (a mean
/// brightness above 40 of 255 where covered).
fn assert_lit_over(scene: &str, least: f64) {
    let image = render(scene);
    assert_eq!(image.dimensions(), (64, 36));
    let (covered, brightness) = coverage(&image);
    assert!(covered > least, "{scene}: {:.1}% covered", covered * 100.0);
    assert!(
        brightness > 40.0,
        "{scene}: mean brightness {brightness:.1}"
    );
}

/// 8,192 triangles; 43% of the frame covered and a mean brightness of 128 measured on
/// lavapipe.
#[test]
fn a_terrain_renders_lit_over_a_third_of_the_frame() {
    assert_lit_over("builtin:terrain?cells=64", 0.35);
}

/// 144 buildings, each its own mesh; 63% of the frame covered and a mean brightness of 123
/// measured on lavapipe.
#[test]
fn a_city_renders_lit_over_half_of_the_frame() {
    assert_lit_over("builtin:city?blocks=12", 0.5);
}
