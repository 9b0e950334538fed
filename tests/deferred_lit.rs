//! Lit scenes through the deferred pipelines: finite HDR, light where there should be.

use crate::deferred_support;

use deferred_support::{gpu, hdr_differences, Render};

const SIZE: (u32, u32) = (64, 64);

/// Every lit scene, in every pipeline that resolves: the resolved HDR is finite and
/// within the half-float range everywhere, and not black.
#[test]
fn lit_scenes_are_finite_and_not_black() {
    let gpu = gpu();
    let pipelines = [
        "deferred_msaa_4x.ron",
        "deferred_msaa_4x_sample_mask.ron",
        "deferred_msaa_4x_tonemapped_resolve.ron",
        "deferred_per_sample_4x.ron",
        "deferred_msaa_4x_centroid.ron",
        "deferred_msaa_4x_coverage.ron",
    ];
    for pipeline in pipelines {
        for scene in [
            "builtin:spheres",
            "builtin:dense",
            "builtin:lights?count=64",
        ] {
            let frame = Render::new(pipeline, scene, SIZE)
                .export_resolved()
                .run(&gpu);
            let hdr = frame.hdr(&gpu, "resolved");
            let bad = hdr
                .iter()
                .position(|p| p.iter().any(|c| !c.is_finite() || *c < 0.0 || *c > 65504.0));
            if let Some(i) = bad {
                let (x, y) = (i as u32 % SIZE.0, i as u32 / SIZE.0);
                panic!(
                    "{pipeline} {scene}: resolved pixel ({x}, {y}) is {:?}",
                    hdr[i]
                );
            }
            let lit = hdr.iter().filter(|p| p[0] + p[1] + p[2] > 0.01).count();
            assert!(
                lit > hdr.len() / 4,
                "{pipeline} {scene}: only {lit} of {} pixels have light",
                hdr.len()
            );
        }
    }
}

/// builtin:spheres without anti-aliasing renders, and its tone-mapped image is neither
/// black nor white on average.
#[test]
fn noaa_renders_the_spheres() {
    let gpu = gpu();
    let color = Render::new("deferred_noaa.ron", "builtin:spheres", SIZE)
        .read(&gpu, &["color"])
        .remove(0);
    let mean = color
        .pixels
        .iter()
        .map(|p| f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2]))
        .sum::<f64>()
        / (3.0 * color.pixels.len() as f64);
    assert!(
        (20.0..230.0).contains(&mean),
        "mean channel value of the spheres without AA is {mean:.1}, expected 20..230"
    );
}

/// Light volumes (spheres, cones; front faces from outside, back faces when the camera
/// may be inside) shade exactly the samples that drawing every light full screen shades
/// with a non-zero contribution: outside a volume the falloff window is exactly zero, and
/// per-sample shading reconstructs each sample where the rasterizer tested it (its own
/// position and depth). So with every pixel shaded per sample (deferred_per_sample_4x)
/// the images are bit-identical. Scenes: builtin:spheres has the camera inside two point
/// lights' volumes, builtin:lights has it outside all, builtin:dense has spot lights.
///
/// (Shading once per pixel instead writes the pixel center's value to the samples inside
/// the volume only, which at a volume's silhouette differs from the full-screen draw by the
/// light's variation across the pixel: 88 pixels by up to 0.009 for builtin:lights at
/// 64x64 through deferred_msaa_4x.)
#[test]
fn light_volumes_match_full_screen_lights() {
    let gpu = gpu();
    for scene in [
        "builtin:spheres",
        "builtin:lights?count=64",
        "builtin:dense",
    ] {
        let resolved = |volumes: bool| {
            let mut render =
                Render::new("deferred_per_sample_4x.ron", scene, SIZE).export_resolved();
            if !volumes {
                render = render.full_screen_lights();
            }
            render.run(&gpu).hdr(&gpu, "resolved")
        };
        let (with, without) = (resolved(true), resolved(false));
        let differing = hdr_differences(&with, &without, SIZE.0, ("volumes", "full screen"));
        assert!(
            differing.is_empty(),
            "{scene}: {} pixels differ between light volumes and full-screen lights, e.g.:\n{}",
            differing.len(),
            differing
                .iter()
                .take(10)
                .cloned()
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
}

/// Rendering is camera-relative: model matrices and light positions are made relative to
/// the camera in f64 before they become f32, so a scene moved millions of units from the
/// origin (where f32 steps are 0.25) renders as it does at the origin (on lavapipe:
/// bit-identically).
#[test]
fn a_scene_far_from_the_origin_renders_as_at_the_origin() {
    let gpu = gpu();
    fn far_away(scene: &mut rgraph_scene::Scene) {
        let offset = [3.0e6, 1.0e6, -2.0e6];
        for mesh in &mut scene.meshes {
            // Affine transforms: the last column holds the translation.
            mesh.transform.w_axis.x += offset[0];
            mesh.transform.w_axis.y += offset[1];
            mesh.transform.w_axis.z += offset[2];
        }
        for light in &mut scene.lights {
            light.position.x += offset[0];
            light.position.y += offset[1];
            light.position.z += offset[2];
        }
        scene.camera.position.x += offset[0];
        scene.camera.position.y += offset[1];
        scene.camera.position.z += offset[2];
    }
    let resolved = |moved: bool| {
        let mut render =
            Render::new("deferred_msaa_4x.ron", "builtin:spheres", SIZE).export_resolved();
        if moved {
            render = render.scene_edit(far_away);
        }
        render.run(&gpu).hdr(&gpu, "resolved")
    };
    let (near, far) = (resolved(false), resolved(true));
    let (mut differing, mut worst) = (0, (0.0f32, 0));
    for (i, (a, b)) in near.iter().zip(&far).enumerate() {
        let diff = (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max);
        differing += usize::from(diff > 0.0);
        if diff > worst.0 {
            worst = (diff, i);
        }
    }
    let (x, y) = (worst.1 as u32 % SIZE.0, worst.1 as u32 / SIZE.0);
    assert!(
        worst.0 <= 1e-3,
        "{differing} pixels differ once the scene is moved far away, the worst at ({x}, {y}) \
         by {}: {:?} at the origin, {:?} far away",
        worst.0,
        near[worst.1],
        far[worst.1]
    );
}
