//! Lit scenes through the default deferred MSAA pipeline: finite, not black, and the
//! debug views agree with the scene.

mod deferred_support;

use deferred_support::{gpu, Render};

const SIZE: (u32, u32) = (64, 64);

/// builtin:spheres through deferred_msaa_4x: most pixels show geometry, and the lit
/// image has light in it (not all black, not saturated white).
#[test]
fn spheres_render_lit() {
    let gpu = gpu();
    let images = Render::new("deferred_msaa_4x.ron", "builtin:spheres", SIZE).read(
        &gpu,
        &[
            "color",
            "debug.edges",
            "debug.albedo",
            "debug.normals",
            "debug.depth",
            "debug.lights",
        ],
    );
    let color = &images[0];
    let mean: f64 = color
        .pixels
        .iter()
        .map(|p| f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2]))
        .sum::<f64>()
        / (3.0 * color.pixels.len() as f64);
    assert!(
        (20.0..230.0).contains(&mean),
        "mean channel value of the lit spheres is {mean:.1}, expected a lit image in 20..230"
    );
}
