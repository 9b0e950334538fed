//! Extreme case 9 (issue 6), the number of lights: 0, 1 and 10,000.
//!
//! - Extremes: a floor with no light at all; with one point light; with 10,000 point
//!   lights on a 100 x 100 grid (each drawn as its own volume).
//! - Expected: every frame renders with every sample finite; no light gives exactly the
//!   ambient term (0 here); one light lights the floor; 10,000 lights add up: the image of
//!   all of them is the sum of the images of the two halves of the grid.
//! - Bounds asserted: 0 non-finite values; 0 lights: resolved exactly 0; 1 light: some
//!   pixels lit; 10,000 lights: |all - (even + odd)| within 2.5% of the sum in every
//!   channel (measured 1.9%: about 200 lights reach each pixel and every one is added
//!   by blending into rgba16float, rounded to 11 bits, and lavapipe's rounding loses a
//!   little each time).
//!
//! That the cost grows about linearly with the number of lights is measured by
//! `rgraph bench --sweep lights`, not by a timed test.
//!
//! A known limit, printed and not asserted: the lit HDR target is rgba16float and lights
//! add up by blending, so a sum of many lights each much smaller than the total stops
//! growing once a contribution falls below half a half-float step (11 bits): 10,000
//! co-located lights of 1/10,000 the intensity of one reach 16% of its brightness on
//! lavapipe. Lights below the cutoff illuminance (0.01 lux) are zero by design
//! (`Light::effective_range`), however many there are.

use crate::deferred_support;

use deferred_support::scenes::Parts;
use deferred_support::{gpu, Render};
use rgraph_core::gpu::Gpu;
use rgraph_scene::glam::DVec3;
use rgraph_scene::{Camera, Light, Projection, Scene};

const SIZE: (u32, u32) = (48, 48);
/// How far the image of all 10,000 lights may be from the sum of its halves' images.
const MAX_RELATIVE: f32 = 0.025;

fn point(position: DVec3, intensity: f32, range: f32) -> Light {
    Light::point("point", position, [1.0, 0.9, 0.8], intensity, Some(range))
}

fn floor_with(lights: Vec<Light>) -> Scene {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.5, 0.5, 0.5], 0.6);
    let d = |x: f64, z: f64| DVec3::new(x, 0.0, z);
    parts.mesh(
        "floor",
        &[vec![d(-6.0, 6.0), d(6.0, 6.0), d(6.0, -6.0), d(-6.0, -6.0)]],
        grey,
    );
    parts.lights = lights;
    let camera = Camera::look_at(
        "above",
        DVec3::new(0.0, 9.0, 3.0),
        DVec3::ZERO,
        DVec3::Y,
        Projection::Perspective {
            yfov: 1.0,
            znear: 0.1,
            zfar: None,
        },
    );
    parts.scene("floor", camera)
}

/// 10,000 lights on a 100 x 100 grid over the floor; `keep` picks which by index.
fn grid(keep: impl Fn(usize) -> bool) -> Vec<Light> {
    (0..10_000)
        .filter(|&i| keep(i))
        .map(|i| {
            let (x, z) = ((i % 100) as f64, (i / 100) as f64);
            point(DVec3::new(x * 0.1 - 4.95, 0.3, z * 0.1 - 4.95), 0.05, 0.8)
        })
        .collect()
}

/// The resolved image; panics on any non-finite sample of the lit HDR target.
fn resolved(gpu: &Gpu, scene: Scene, what: &str) -> Vec<[f32; 4]> {
    let frame = Render::new("deferred_msaa_4x.ron", "floor", SIZE)
        .with_scene(scene)
        .edit(
            "outputs: [\"color\",",
            "outputs: [\"hdr_lit\", \"resolved\", \"color\",",
        )
        .run(gpu);
    for (i, pixel) in frame.samples(gpu, "hdr_lit").iter().enumerate() {
        assert!(
            pixel.iter().flatten().all(|c| c.is_finite()),
            "{what}: pixel {i} has {pixel:?}"
        );
    }
    frame
        .samples(gpu, "resolved")
        .into_iter()
        .map(|p| p[0])
        .collect()
}

fn brightness(p: &[f32; 4]) -> f32 {
    p[0] + p[1] + p[2]
}

#[test]
fn zero_one_and_ten_thousand_lights_render() {
    let gpu = gpu();
    let none = resolved(&gpu, floor_with(Vec::new()), "0 lights");
    assert!(
        none.iter().all(|p| p[..3] == [0.0; 3]),
        "0 lights and no ambient: the floor must be black"
    );
    let one = resolved(
        &gpu,
        floor_with(vec![point(DVec3::new(0.0, 1.0, 0.0), 20.0, 10.0)]),
        "1 light",
    );
    let lit = one.iter().filter(|p| brightness(p) > 0.01).count();
    assert!(lit > 500, "1 light lights only {lit} pixels");

    let all = resolved(&gpu, floor_with(grid(|_| true)), "10,000 lights");
    let even = resolved(&gpu, floor_with(grid(|i| i % 2 == 0)), "even lights");
    let odd = resolved(&gpu, floor_with(grid(|i| i % 2 == 1)), "odd lights");
    // The worst relative difference, over channels above 0.01 (below that, absolute).
    let (mut worst, mut at) = (0.0f32, 0);
    for i in 0..all.len() {
        for c in 0..3 {
            let sum = even[i][c] + odd[i][c];
            let error = (all[i][c] - sum).abs() / sum.max(0.01);
            if error > worst {
                (worst, at) = (error, i);
            }
        }
    }
    println!(
        "10,000 lights: worst relative difference from the sum of the halves {worst:.4} at \
         pixel {at}: {:?} against {:?} + {:?}",
        all[at], even[at], odd[at]
    );
    assert!(
        worst <= MAX_RELATIVE,
        "10,000 lights: pixel {at} is {:?}, the halves sum to {:?} + {:?}: {worst} apart \
         (bound {MAX_RELATIVE})",
        all[at],
        even[at],
        odd[at]
    );
    let lit = all.iter().filter(|p| brightness(p) > 0.01).count();
    assert!(lit > 1000, "10,000 lights light only {lit} pixels");
    println!("10,000 lights: {lit} lit pixels, equal to the sum of the halves");
}

/// The known limit, measured: 10,000 co-located lights of 1/10,000 the intensity of one
/// light render finite and no brighter than that light, but reach only a fraction of it
/// (16% on lavapipe), as each contribution is rounded to 11 bits when it is blended in.
#[test]
fn ten_thousand_colocated_dim_lights_lose_precision_in_half_floats() {
    let gpu = gpu();
    // The known limit: co-located lights' contributions lost below half a step.
    // (Range 0.4 for both: within the dim lights' cutoff radius, 0.45, so the same
    // window applies and only the accumulation differs.)
    let center = DVec3::new(0.0, 0.2, 0.0);
    let single = resolved(&gpu, floor_with(vec![point(center, 20.0, 0.4)]), "one");
    let split = resolved(
        &gpu,
        floor_with(
            (0..10_000)
                .map(|_| point(center, 20.0 / 10_000.0, 0.4))
                .collect(),
        ),
        "10,000 co-located",
    );
    let total = |image: &[[f32; 4]]| image.iter().map(brightness).sum::<f32>();
    let fraction = total(&split) / total(&single);
    println!(
        "10,000 co-located lights of 1/10,000 the intensity reach {:.1}% of one light's \
         total brightness (rgba16float accumulation)",
        100.0 * fraction
    );
    assert!(
        fraction > 0.0 && fraction <= 1.0 + 1e-3,
        "10,000 co-located lights reach {fraction} of one light"
    );
}

/// A point light of intensity 3.5e36 without `range`: its derived range once overflowed f32
/// (`intensity * max(color) / cutoff`), the light volume became infinite and the frame black.
#[test]
fn a_light_too_bright_for_an_f32_range_still_lights_the_floor() {
    let gpu = gpu();
    let light = Light::point(
        "blinding",
        DVec3::new(0.0, 1.0, 0.0),
        [1.0; 3],
        3.5e36,
        None,
    );
    let color = Render::new("deferred_msaa_4x.ron", "floor", SIZE)
        .with_scene(floor_with(vec![light]))
        .read(&gpu, &["color"])
        .remove(0);
    let lit = color.pixels.iter().filter(|p| p[..3] != [0, 0, 0]).count();
    assert!(
        lit > color.pixels.len() / 2,
        "only {lit} of {} pixels are lit",
        color.pixels.len()
    );
}
