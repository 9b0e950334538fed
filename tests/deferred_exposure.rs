//! Auto exposure (`auto_exposure` metering, then `tonemap` with what it metered) against a
//! CPU metering of the same resolved image, and physical light units: a 68,300 lux sun
//! (Blender's default sun in bevy's VolumetricFogExample) and a thousandth of it render
//! alike once metered.

use crate::deferred_support;

use deferred_support::measure::share_within;
use deferred_support::scenes::Parts;
use deferred_support::{gpu, Image, Render};
use rgraph_core::Features;
use rgraph_passes::{Exposure, Overrides};
use rgraph_scene::glam::{DVec3, Vec3};
use rgraph_scene::{Camera, Light, LightKind, Projection, Scene};

const SIZE: (u32, u32) = (64, 64);
const PIPELINE: &str = "deferred_msaa_4x_tiled.ron";

/// Three boxes of different greys on a floor under a sun of `lux`, from above front right.
fn sunlit(lux: f32) -> Scene {
    let mut parts = Parts::new();
    for (i, grey) in [0.2, 0.5, 0.9].into_iter().enumerate() {
        let material = parts.material(&format!("grey {grey}"), [grey; 3], 0.6);
        let x = i as f64 * 1.5 - 1.5;
        let min = DVec3::new(x - 0.5, 0.0, -0.5);
        parts.cuboid("box", min, min + DVec3::splat(1.0), material);
    }
    let floor = parts.material("floor", [0.4; 3], 0.9);
    parts.cuboid(
        "floor",
        DVec3::new(-3.0, -0.2, -2.0),
        DVec3::new(3.0, 0.0, 2.0),
        floor,
    );
    parts.lights.push(Light {
        name: "sun".into(),
        kind: LightKind::Directional,
        color: [1.0, 0.95, 0.9],
        intensity: lux,
        position: DVec3::ZERO,
        direction: Vec3::new(-0.3, -1.0, -0.4).normalize(),
        range: None,
    });
    let camera = Camera::look_at(
        "camera",
        DVec3::new(2.0, 3.0, 5.0),
        DVec3::new(0.0, 0.3, 0.0),
        DVec3::Y,
        Projection::Perspective {
            yfov: 0.9,
            znear: 0.1,
            zfar: Some(50.0),
        },
    );
    parts.scene("sunlit boxes", camera)
}

fn render(scene: &Scene, exposure: Exposure) -> (Image, Vec<[f32; 4]>) {
    let gpu = gpu();
    let features: Features = match exposure {
        Exposure::Auto => ["auto_exposure"].into_iter().collect(),
        Exposure::Fixed(_) => Features::new(),
    };
    let frame = Render {
        overrides: Overrides {
            exposure: Some(exposure),
            ..Overrides::default()
        },
        ..Render::new(PIPELINE, "sunlit boxes", SIZE)
    }
    .with_scene(scene.clone())
    .features(features)
    .export_resolved()
    .run(&gpu);
    (frame.image(&gpu, "color"), frame.hdr(&gpu, "resolved"))
}

/// auto_exposure.wgsl's metering, on the CPU: the grid of every `step`-th pixel, bins of
/// log2 luminance, the mean between the 10th and 90th percentiles of lit pixels.
fn metered_exposure(hdr: &[[f32; 4]]) -> f32 {
    let (width, height) = SIZE;
    let step = ((width * height) as f32 / 262144.0).sqrt().ceil().max(1.0) as u32;
    let mut bins = [0u32; 256];
    for y in (0..height).step_by(step as usize) {
        for x in (0..width).step_by(step as usize) {
            let [r, g, b, _] = hdr[(y * width + x) as usize];
            let l = 0.2126 * r + 0.7152 * g + 0.0722 * b;
            let bin = match l < 2f32.powi(-16) {
                true => 0,
                false => 1 + ((l.log2() + 16.0) / 32.0 * 254.0).clamp(0.0, 254.0) as usize,
            };
            bins[bin] += 1;
        }
    }
    let lit: u32 = bins[1..].iter().sum();
    let (low, high) = (lit as f32 * 0.1, lit as f32 * 0.9);
    let (mut below, mut sum, mut weight) = (0.0, 0.0, 0.0);
    for (b, &n) in bins.iter().enumerate().skip(1) {
        let n = n as f32;
        let inside = ((below + n).min(high) - below.max(low)).max(0.0);
        sum += inside * (-16.0 + (b as f32 - 1.0 + 0.5) / 254.0 * 32.0);
        weight += inside;
        below += n;
    }
    0.18 / (sum / weight).exp2()
}

/// The metering pass computes what the CPU computes from the same resolved image: the
/// auto-exposed frame equals the frame tone mapped with the CPU's exposure within 1/255.
#[test]
fn auto_exposure_meters_as_the_cpu_does() {
    let scene = sunlit(68_300.0);
    let (auto, hdr) = render(&scene, Exposure::Auto);
    let exposure = metered_exposure(&hdr);
    // Physical units: a sun of 68,300 lux needs an exposure near 1/20,000.
    assert!((1e-6..1e-3).contains(&exposure), "exposure {exposure}");
    let (fixed, _) = render(&scene, Exposure::Fixed(exposure));
    let share = share_within(&auto, &fixed, 1, None);
    assert!(share == 1.0, "{share} of pixels within 1/255");
}

/// A 68,300 lux sun, which exposure 1 turns white, and a 68.3 lux one render alike under
/// auto exposure (the metering bins are 1/8 stop wide: within 2/255 on 99% of pixels).
#[test]
fn auto_exposure_renders_a_bright_sun_as_a_dim_one() {
    let (bright, _) = render(&sunlit(68_300.0), Exposure::Auto);
    let (dim, _) = render(&sunlit(68.3), Exposure::Auto);
    let share = share_within(&bright, &dim, 2, None);
    assert!(share >= 0.99, "{share} of pixels within 2/255");
    let (white, _) = render(&sunlit(68_300.0), Exposure::Fixed(1.0));
    let lit = white.pixels.iter().filter(|p| p[..3] != [0, 0, 0]).count();
    assert!(
        white.count([255, 255, 255, 255]) * 2 > lit,
        "exposure 1 blows the sun out"
    );
}
