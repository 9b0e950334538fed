//! Resolve, tone mapping and debug views on `builtin:unlit`, whose every sample's color
//! is known (tests/deferred_support/unlit.rs): exact values for the operators, the
//! luminance-weighted resolve, host overrides and the G-buffer debug views.

use crate::deferred_support;

use deferred_support::unlit::Coverage;
use deferred_support::{gpu, srgb8, Image, Render};
use rgraph_passes::{Exposure, Overrides};
use rgraph_scene::Scene;

const N: u32 = 64;

fn coverage() -> Coverage {
    Coverage::of(
        &Scene::load("builtin:unlit").expect("builtin:unlit loads"),
        N,
    )
}

fn overrides(tonemap: &str, exposure: f32) -> Overrides {
    Overrides {
        tonemap: Some(tonemap.into()),
        exposure: Some(Exposure::Fixed(exposure)),
        ..Overrides::default()
    }
}

/// Checks every unambiguous pixel `expected` gives a value for, within 1/255 per
/// channel; `what` names the check in the message.
fn check(
    image: &Image,
    coverage: &Coverage,
    what: &str,
    expected: impl Fn(u32, u32) -> Option<[u8; 3]>,
) {
    let (mut judged, mut wrong) = (0, Vec::new());
    for y in 0..N {
        for x in 0..N {
            let Some(want) = expected(x, y).filter(|_| !coverage.is_ambiguous(x, y)) else {
                continue;
            };
            judged += 1;
            let got = image.at(x, y);
            if (0..3).any(|c| want[c].abs_diff(got[c]) > 1) {
                wrong.push(format!("({x}, {y}): expected {want:?}, got {got:?}"));
            }
        }
    }
    assert!(judged > 100, "{what}: only {judged} pixels judged");
    assert!(
        wrong.is_empty(),
        "{what}: {} of {judged} pixels off by more than 1/255, e.g.:\n{}",
        wrong.len(),
        wrong
            .iter()
            .take(10)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// Pixels whose samples all see one surface: its color; else `None`.
fn solid(coverage: &Coverage, x: u32, y: u32) -> Option<[f64; 3]> {
    (!coverage.is_mixed(x, y)).then(|| coverage.resolved(x, y))
}

/// The host's overrides replace the file's operator and exposure (aces, 1): Reinhard
/// `c / (1 + c)` and ACES (Narkowicz) of the exposed unlit colors.
#[test]
fn tone_mapping_operators_and_overrides() {
    let gpu = gpu();
    let coverage = coverage();
    let aces = |c: f64| (c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14);
    let reinhard = |c: f64| c / (1.0 + c);
    for (operator, exposure) in [("reinhard", 2.0), ("aces", 0.5)] {
        let image = Render::new("deferred_msaa_4x.ron", "builtin:unlit", (N, N))
            .overrides(overrides(operator, exposure as f32))
            .read(&gpu, &["color"])
            .remove(0);
        let curve = |c: f64| match operator {
            "reinhard" => reinhard(exposure * c),
            _ => aces(exposure * c),
        };
        check(&image, &coverage, operator, |x, y| {
            solid(&coverage, x, y).map(|c| c.map(|v| srgb8(curve(v))))
        });
    }
}

/// The tonemapped resolve weights each sample by 1 / (1 + exposure * luminance): edge
/// pixels get the weighted average, solid pixels their color.
#[test]
fn tonemapped_resolve_weights_by_luminance() {
    let gpu = gpu();
    let coverage = coverage();
    let exposure = 2.0;
    let image = Render::new(
        "deferred_msaa_4x_tonemapped_resolve.ron",
        "builtin:unlit",
        (N, N),
    )
    .overrides(overrides("none", exposure as f32))
    .read(&gpu, &["color"])
    .remove(0);
    let colors = coverage.sample_colors();
    check(&image, &coverage, "tonemapped resolve", |x, y| {
        let (mut sum, mut weights) = ([0.0; 3], 0.0);
        for c in colors(x, y) {
            let w = 1.0 / (1.0 + exposure * (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]));
            for (s, v) in sum.iter_mut().zip(c) {
                *s += w * v;
            }
            weights += w;
        }
        Some(sum.map(|s| srgb8(exposure * s / weights)))
    });
}

/// Debug views at sample 0 of solid pixels: albedo is the unlit color, normals face the
/// camera (0, 0, 1) -> (0.5, 0.5, 1), depth is 1 / (1 + view depth / 10), and the
/// background is black in the normals and depth views.
#[test]
fn debug_views_show_the_g_buffer() {
    let gpu = gpu();
    let coverage = coverage();
    let images = Render::new("deferred_msaa_4x.ron", "builtin:unlit", (N, N))
        .read(&gpu, &["debug.albedo", "debug.normals", "debug.depth"]);
    let background = |x, y| solid(&coverage, x, y).filter(|c| *c == [0.0; 3]).is_some();
    check(&images[0], &coverage, "debug.albedo", |x, y| {
        solid(&coverage, x, y).map(|c| c.map(srgb8))
    });
    check(&images[1], &coverage, "debug.normals", |x, y| {
        // The tilted yellow square's normal is not (0, 0, 1).
        let yellow = solid(&coverage, x, y) == Some([1.0, 1.0, 0.0]);
        match (background(x, y), yellow || coverage.is_mixed(x, y)) {
            (true, _) => Some([0, 0, 0]),
            (false, true) => None,
            (false, false) => Some([srgb8(0.5), srgb8(0.5), 255]),
        }
    });
    // The flat shapes lie at z = 0 (view depth 10) and z = 0.5 (green, 9.5).
    check(&images[2], &coverage, "debug.depth", |x, y| {
        let color = solid(&coverage, x, y)?;
        let depth = match color {
            [0.0, 0.0, 0.0] => return Some([0, 0, 0]),
            [0.0, 1.0, 0.0] => 9.5,
            [1.0, 0.0, 0.0] | [0.0, 0.0, 1.0] => 10.0,
            _ => return None,
        };
        let shade = srgb8(1.0 / (1.0 + depth / 10.0));
        Some([shade; 3])
    });
}
