//! Shadow maps (passes/shadow_maps.rs, shadow.wgsl) on lavapipe: a square's shadow lands
//! where its projection does, under a sun and under a point light (across two faces of
//! its cube), a lit plane at grazing light shows no acne, the default
//! pipeline's tiled shading and the G-buffer's light volumes agree on a shadowed scene,
//! the `shadows` and `cascades` debug views show the visibility term and the cascades,
//! and the command line refuses shadow settings it cannot honour.

use std::path::Path;

use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::glam::{DVec3, Vec3};
use rgraph_scene::{AlphaMode, Camera, Light, LightKind, Projection, Scene};

use crate::cli_support::rgraph;
use crate::deferred_support::measure;
use crate::deferred_support::scenes::Parts;
use crate::deferred_support::{gpu, Image, PipelineFile, Render};
use rgraph_passes::{Overrides, ShadowFilter, Shadows};

/// The default pipeline on lavapipe (the hardware raster, tiled shading).
const DEFAULT: PipelineFile = PipelineFile::for_device("visibility_msaa_4x.ron");
/// Its branch for GPUs (the compute raster), compiled as for one.
const DEFAULT_GPU: PipelineFile = PipelineFile::gpu_branch("visibility_msaa_4x.ron");

/// Pixels per side of the analytic scene's image, which spans 4 world units.
const N: u32 = 64;
const SPAN: f64 = 4.0;

fn sun(direction: Vec3, intensity: f32) -> Light {
    Light {
        name: "sun".into(),
        kind: LightKind::Directional,
        color: [1.0, 1.0, 1.0],
        intensity,
        position: DVec3::ZERO,
        direction: direction.normalize(),
        range: None,
    }
}

/// An 8 x 8 ground square at y = 0 and a 1 x 1 square over its centre at y = 1, both
/// facing up, under a sun travelling along (1, -1, 0): the square's shadow is the unit
/// square x in [0.5, 1.5], z in [-0.5, 0.5]. Seen straight down by an orthographic camera
/// spanning x and z in [-2, 2], image x along +x and image y along +z (16 pixels a unit).
fn square_over_plane() -> Scene {
    square_scene(square_parts())
}

/// [`square_over_plane`]'s parts: the ground is mesh 0, the square mesh 1 (material 0,
/// as the ground's).
fn square_parts() -> Parts {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.6, 0.6, 0.6], 0.8);
    parts.mesh("ground", &[square_at(0.0, 4.0)], grey);
    parts.mesh("square", &[square_at(1.0, 0.5)], grey);
    parts.lights.push(sun(Vec3::new(1.0, -1.0, 0.0), 3.0));
    parts.ambient = [0.05; 3];
    parts
}

/// A square of half side `half` at height `y` centred over the origin, facing up.
fn square_at(y: f64, half: f64) -> Vec<DVec3> {
    vec![
        DVec3::new(-half, y, -half),
        DVec3::new(-half, y, half),
        DVec3::new(half, y, half),
        DVec3::new(half, y, -half),
    ]
}

/// `parts` seen straight down, as [`square_over_plane`] says.
fn square_scene(parts: Parts) -> Scene {
    seen_from_above(parts, "square over plane")
}

/// `parts` as the scene `name`, seen straight down by an orthographic camera spanning x
/// and z in [-2, 2], image x along +x and image y along +z.
fn seen_from_above(parts: Parts, name: &str) -> Scene {
    let camera = Camera::look_at(
        "from above",
        DVec3::new(0.0, 10.0, 0.0),
        DVec3::ZERO,
        DVec3::NEG_Z,
        Projection::Orthographic {
            xmag: (SPAN / 2.0) as f32,
            ymag: (SPAN / 2.0) as f32,
            znear: 1.0,
            zfar: 20.0,
        },
    );
    parts.scene(name, camera)
}

/// A point light 1.2 above the origin.
fn bulb() -> Light {
    Light {
        name: "bulb".into(),
        kind: LightKind::Point,
        color: [1.0, 1.0, 1.0],
        intensity: 4.0,
        position: DVec3::new(0.0, 1.2, 0.0),
        direction: Vec3::NEG_Y,
        range: None,
    }
}

/// `scene` through `pipeline` with `shadows`, compiled for its features as `rgraph
/// render` compiles it (without `shadows` when they are off).
fn render(pipeline: PipelineFile, scene: &Scene, size: (u32, u32), shadows: Shadows) -> Image {
    render_edited(pipeline, &[], scene, size, shadows)
}

/// [`render`] through `pipeline` with its text edited by `edits` (from, to).
fn render_edited(
    pipeline: PipelineFile,
    edits: &[(&str, &str)],
    scene: &Scene,
    size: (u32, u32),
    shadows: Shadows,
) -> Image {
    let gpu = gpu();
    let mut features = SceneFeatures::of(scene);
    features.shadows &= shadows.enabled();
    let render = Render::new(pipeline, &scene.name, size);
    (edits.iter())
        .fold(render, |render, &(from, to)| render.edit(from, to))
        .with_scene(scene.clone())
        .features(features.names())
        .overrides(Overrides {
            shadows,
            ..Overrides::default()
        })
        .run(&gpu)
        .image(&gpu, "color")
}

fn luma(p: [u8; 4]) -> f64 {
    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
}

/// The square's shadow covers the pixels whose centres its projection covers, to within
/// a pixel at each edge (a shadow-map texel is a third of a pixel here: the cascade
/// holding the ground spans about 11 world units in 1024 texels), hard and filtered, in
/// both branches of the default pipeline.
#[test]
fn a_squares_shadow_is_its_projection() {
    let scene = square_over_plane();
    for pipeline in [DEFAULT, DEFAULT_GPU] {
        for filter in [ShadowFilter::Hard, ShadowFilter::Pcf] {
            let shadows = Shadows { filter, lights: 1 };
            let image = render(pipeline, &scene, (N, N), shadows);
            let unshadowed = render(
                pipeline,
                &scene,
                (N, N),
                Shadows {
                    filter: ShadowFilter::Off,
                    lights: 1,
                },
            );
            // Lit ground, and the ground the square hides from the sun, by their centres.
            let (lit, dark) = (luma(image.at(16, 52)), luma(image.at(48, 32)));
            assert!(
                dark < 0.5 * lit,
                "{pipeline} {filter:?}: the shadow's centre ({dark:.0}) is not darker than lit \
                 ground ({lit:.0})"
            );
            assert!(
                (luma(unshadowed.at(48, 32)) - lit).abs() <= 1.0,
                "{pipeline}: without shadows the ground is lit alike everywhere"
            );
            let threshold = 0.5 * (lit + dark);
            let shadowed = |x: u32, y: u32| luma(image.at(x, y)) < threshold;
            let pixel_of = |world: f64| (world + SPAN / 2.0) * f64::from(N) / SPAN;
            let (x0, x1) = (pixel_of(0.5), pixel_of(1.5));
            let (z0, z1) = (pixel_of(-0.5), pixel_of(0.5));
            let mut count = 0;
            for y in 0..N {
                for x in 0..N {
                    let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    let inside = cx > x0 && cx < x1 && cy > z0 && cy < z1;
                    let margin = (cx - x0)
                        .abs()
                        .min((cx - x1).abs())
                        .min((cy - z0).abs())
                        .min((cy - z1).abs());
                    let near_edge = margin <= 1.0;
                    if shadowed(x, y) {
                        count += 1;
                    }
                    assert!(
                        near_edge || shadowed(x, y) == inside,
                        "{pipeline} {filter:?}: pixel ({x}, {y}) is {} but its centre is {} the \
                         square's projection, more than a pixel from its edge",
                        if shadowed(x, y) { "shadowed" } else { "lit" },
                        if inside { "inside" } else { "outside" }
                    );
                }
            }
            let area = (x1 - x0) * (z1 - z0);
            assert!(
                (f64::from(count) - area).abs() <= 0.5 * 4.0 * (x1 - x0),
                "{pipeline} {filter:?}: {count} shadowed pixels, the projection covers {area}"
            );
        }
    }
}

/// A point light 0.2 over a small square (x in [0, 0.25], z in [-0.125, 0.125], at
/// height 1) over the ground, and the ground's shadow is the square's central projection from
/// the light, 6 times its size: x in [0, 1.5], z in [-0.75, 0.75]. Past x = 1.2 the
/// light sees the ground through its cube's +x face, nearer below it through -y, so the
/// shadow crosses a seam between faces. Seen from above as [`square_over_plane`] is;
/// the point light's falloff makes "shadowed" a pixel under half its unshadowed luma
/// (the ambient alone stays under half of the dimmest lit ground's). Hard and filtered, through
/// the default pipeline's tiled shading (both branches) and the G-buffer's light volumes.
#[test]
fn a_point_light_s_shadow_is_the_central_projection_across_cube_faces() {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.6, 0.6, 0.6], 0.8);
    let rect = |y: f64, (x0, x1): (f64, f64), (z0, z1): (f64, f64)| {
        vec![
            DVec3::new(x0, y, z0),
            DVec3::new(x0, y, z1),
            DVec3::new(x1, y, z1),
            DVec3::new(x1, y, z0),
        ]
    };
    parts.mesh("ground", &[rect(0.0, (-4.0, 4.0), (-4.0, 4.0))], grey);
    parts.mesh("square", &[rect(1.0, (0.0, 0.25), (-0.125, 0.125))], grey);
    parts.lights.push(bulb());
    parts.ambient = [0.02; 3];
    let scene = seen_from_above(parts, "point light over a square");
    assert!(
        SceneFeatures::of(&scene).shadows,
        "a point light casts shadows"
    );
    let pixel_of = |world: f64| (world + SPAN / 2.0) * f64::from(N) / SPAN;
    let (x0, x1) = (pixel_of(0.0), pixel_of(1.5));
    let (z0, z1) = (pixel_of(-0.75), pixel_of(0.75));
    // The square itself, lit from above, hides part of its shadow from the camera.
    let (sx1, sz0, sz1) = (pixel_of(0.25), pixel_of(-0.125), pixel_of(0.125));
    let gbuffer = PipelineFile::for_device("deferred_msaa_4x.ron");
    for pipeline in [DEFAULT, DEFAULT_GPU, gbuffer] {
        let off = Shadows {
            filter: ShadowFilter::Off,
            lights: 1,
        };
        let unshadowed = render(pipeline, &scene, (N, N), off);
        for filter in [ShadowFilter::Hard, ShadowFilter::Pcf] {
            let image = render(pipeline, &scene, (N, N), Shadows { filter, lights: 1 });
            let (mut count, mut expected) = (0, 0);
            for y in 0..N {
                for x in 0..N {
                    let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    if cx > x0 - 1.0 && cx < sx1 + 1.0 && cy > sz0 - 1.0 && cy < sz1 + 1.0 {
                        continue;
                    }
                    let lit = luma(unshadowed.at(x, y));
                    let shadowed = luma(image.at(x, y)) < 0.5 * lit;
                    let inside = cx > x0 && cx < x1 && cy > z0 && cy < z1;
                    let margin = (cx - x0)
                        .abs()
                        .min((cx - x1).abs())
                        .min((cy - z0).abs())
                        .min((cy - z1).abs());
                    let near_edge = margin <= 1.0;
                    count += u32::from(shadowed);
                    expected += u32::from(inside);
                    assert!(
                        near_edge || shadowed == inside,
                        "{pipeline} {filter:?}: pixel ({x}, {y}) is {} but its centre is {} the \
                         square's projection, more than a pixel from its edge",
                        if shadowed { "shadowed" } else { "lit" },
                        if inside { "inside" } else { "outside" }
                    );
                }
            }
            // Within half the projection's perimeter in pixels, of those the square leaves
            // in view.
            assert!(
                f64::from(count.abs_diff(expected)) <= (x1 - x0) + (z1 - z0),
                "{pipeline} {filter:?}: {count} shadowed pixels, the projection covers \
                 {expected}"
            );
        }
    }
}

/// A wall beside a point light, reaching above and below it, crosses the near plane of
/// the cube faces looking up, down and along it: the compute raster (the default
/// pipeline's GPU branch) clips its triangles there, as the hardware does, so its
/// shadow on the ground (the points whose line to the light meets the wall) is the
/// hardware's: within 2/255 on 99.9% of the pixels, hard and filtered. Without the
/// clipping, corners behind a face's near plane project mirrored into its map.
#[test]
fn the_compute_raster_clips_casters_at_a_light_s_near_plane() {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.6, 0.6, 0.6], 0.8);
    let ground = vec![
        DVec3::new(-4.0, 0.0, -4.0),
        DVec3::new(-4.0, 0.0, 4.0),
        DVec3::new(4.0, 0.0, 4.0),
        DVec3::new(4.0, 0.0, -4.0),
    ];
    let wall = vec![
        DVec3::new(0.4, 0.1, -1.0),
        DVec3::new(0.4, 3.0, -1.0),
        DVec3::new(0.4, 3.0, 1.0),
        DVec3::new(0.4, 0.1, 1.0),
    ];
    parts.mesh("ground", &[ground], grey);
    parts.mesh("wall", &[wall], grey);
    parts.lights.push(bulb());
    parts.ambient = [0.02; 3];
    let scene = seen_from_above(parts, "point light beside a wall");
    for filter in [ShadowFilter::Hard, ShadowFilter::Pcf] {
        let shadows = Shadows { filter, lights: 1 };
        let hardware = render(DEFAULT, &scene, (N, N), shadows);
        let compute = render(DEFAULT_GPU, &scene, (N, N), shadows);
        // The wall's shadow is there to be matched: the ground behind it, beyond x = 0.4.
        let (x, y) = ((3.0 / 4.0 * f64::from(N)) as u32, N / 2);
        assert!(
            luma(hardware.at(x, y)) < 0.5 * luma(hardware.at(N - 1 - x, y)),
            "{filter:?}: the ground behind the wall is not in its shadow"
        );
        let share = share_within_2(&hardware, &compute);
        assert!(
            share >= 0.999,
            "{filter:?}: the compute raster's shadows agree with the hardware's within 2/255 \
             on {share} of the pixels"
        );
    }
}

/// Thin blades at every angle, flat at heights 0.6 to 1 over the ground, under the sun
/// along (1, -1, 0): long thin triangles running diagonally through the sun's map, whose
/// bounds are mostly empty (the compute raster walks each row's span instead). Long ones
/// (1.5 by 0.03 units, some 150 by 3 texels) are large clusters, short ones (0.15 by
/// 0.015) small ones with `small_texels: 64`. The compute raster's shadows, hard, are the
/// hardware's within 2/255 on 99.9% of the pixels, with every cluster large
/// (`small_texels: 1`) and with the short ones small; and the two are one image, exactly:
/// the workgroups' rows keep the texels an invocation a triangle keeps.
#[test]
fn thin_diagonal_casters_cast_the_hardware_s_shadows_in_compute() {
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.6, 0.6, 0.6], 0.8);
    parts.mesh("ground", &[square_at(0.0, 4.0)], grey);
    let blade = |centre: DVec3, angle: f64, (length, width): (f64, f64)| {
        let along = DVec3::new(angle.cos(), 0.0, angle.sin()) * (0.5 * length);
        let across = DVec3::new(-angle.sin(), 0.0, angle.cos()) * (0.5 * width);
        vec![
            centre - along - across,
            centre - along + across,
            centre + along + across,
            centre + along - across,
        ]
    };
    for i in 0..8 {
        let k = f64::from(i);
        let centre = DVec3::new(-1.2 + 0.15 * k, 1.0 - 0.05 * k, -1.5 + 0.4 * k);
        let angle = (10.0 + 20.0 * k).to_radians();
        parts.mesh("long blade", &[blade(centre, angle, (1.5, 0.03))], grey);
    }
    for i in 0..36 {
        let (x, z) = (f64::from(i % 6), f64::from(i / 6));
        let centre = DVec3::new(-2.2 + 0.45 * x, 0.6 + 0.05 * x, -1.6 + 0.6 * z);
        let angle = (37.0 * f64::from(i)).to_radians();
        parts.mesh("short blade", &[blade(centre, angle, (0.15, 0.015))], grey);
    }
    parts.lights.push(sun(Vec3::new(1.0, -1.0, 0.0), 3.0));
    parts.ambient = [0.05; 3];
    let scene = seen_from_above(parts, "thin blades");
    let hard = Shadows {
        filter: ShadowFilter::Hard,
        lights: 1,
    };
    let size = (2 * N, 2 * N);
    let hardware = render(DEFAULT, &scene, size, hard);
    let lit = luma(hardware.at(0, 0));
    let shadowed = (hardware.pixels.iter())
        .filter(|&&p| luma(p) < 0.5 * lit)
        .count();
    assert!(
        shadowed > 300,
        "the blades shadow {shadowed} pixels: too few to compare"
    );
    let raster = "plugin: \"shadow_raster\",\n            params: (";
    let mut images = Vec::new();
    for (clusters, edit) in [
        ("every cluster large", "small_texels: 1, "),
        ("short blades small", "small_texels: 64, "),
    ] {
        let edited = format!("{raster}{edit}");
        let compute = render_edited(DEFAULT_GPU, &[(raster, &edited)], &scene, size, hard);
        let share = share_within_2(&hardware, &compute);
        assert!(
            share >= 0.999,
            "{clusters}: the compute raster's shadows agree with the hardware's within \
             2/255 on {share} of the pixels"
        );
        images.push(compute);
    }
    let differing = (images[0].pixels.iter().zip(&images[1].pixels))
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "the short blades' shadows drawn as small and as large clusters differ"
    );
}

/// An alpha MASK square (cutoff 0.5) whose vertex alpha runs from 0 at x = -0.5 to 1 at
/// x = 0.5 casts only where it is drawn, its half x >= 0: under the sun along (1, -1, 0)
/// the shadow is x in [1, 1.5], not [0.5, 1.5]. The masked-out half's would-be shadow
/// (x in [0.5, 1]) is lit, the kept half's shadowed, more than a pixel from the edges,
/// hard and filtered, in both branches of the default pipeline.
#[test]
fn an_alpha_mask_caster_casts_only_where_it_is_drawn() {
    let mut parts = square_parts();
    let mut masked = parts.materials[0].clone();
    masked.name = "masked".into();
    masked.alpha_mode = AlphaMode::Mask { cutoff: 0.5 };
    parts.materials.push(masked);
    parts.meshes[1].material = parts.materials.len() - 1;
    for v in std::sync::Arc::make_mut(&mut parts.meshes[1].vertices) {
        v.color[3] = if v.position[0] < 0.0 { 0 } else { u16::MAX };
    }
    let scene = square_scene(parts);
    let pixel_of = |world: f64| (world + SPAN / 2.0) * f64::from(N) / SPAN;
    let (z0, z1) = (pixel_of(-0.5), pixel_of(0.5));
    for pipeline in [DEFAULT, DEFAULT_GPU] {
        for filter in [ShadowFilter::Hard, ShadowFilter::Pcf] {
            let image = render(pipeline, &scene, (N, N), Shadows { filter, lights: 1 });
            // Lit ground, and ground in the kept half's shadow (x = 1.28).
            let (lit, dark) = (luma(image.at(16, 52)), luma(image.at(52, 32)));
            assert!(
                dark < 0.5 * lit,
                "{pipeline} {filter:?}: no shadow ({dark:.0}, {lit:.0})"
            );
            let threshold = 0.5 * (lit + dark);
            for y in 0..N {
                let cy = f64::from(y) + 0.5;
                if cy <= z0 + 1.0 || cy >= z1 - 1.0 {
                    continue;
                }
                for x in 0..N {
                    let cx = f64::from(x) + 0.5;
                    let world = cx * SPAN / f64::from(N) - SPAN / 2.0;
                    let expect = match world {
                        w if (0.5 + 1.0 / 16.0..1.0 - 1.0 / 16.0).contains(&w) => false,
                        w if (1.0 + 1.0 / 16.0..1.5 - 1.0 / 16.0).contains(&w) => true,
                        _ => continue,
                    };
                    let shadowed = luma(image.at(x, y)) < threshold;
                    assert_eq!(
                        shadowed,
                        expect,
                        "{pipeline} {filter:?}: pixel ({x}, {y}) at x = {world:.3} should be \
                         {} (lit ground {lit:.0}, shadowed {dark:.0})",
                        if expect { "shadowed" } else { "lit" }
                    );
                }
            }
        }
    }
}

/// A lit plane and nothing over it, the sun at 3 to 45 degrees above it and the camera
/// looking along it: no pixel is darker with shadow maps than without by more than
/// 2/255, so the bias keeps the plane from shadowing itself (acne).
#[test]
fn a_plane_at_grazing_light_has_no_acne() {
    for elevation in [3.0f32, 10.0, 25.0, 45.0] {
        let mut parts = Parts::new();
        let grey = parts.material("grey", [0.7, 0.7, 0.7], 0.9);
        parts.mesh(
            "ground",
            &[vec![
                DVec3::new(-30.0, 0.0, -30.0),
                DVec3::new(-30.0, 0.0, 30.0),
                DVec3::new(30.0, 0.0, 30.0),
                DVec3::new(30.0, 0.0, -30.0),
            ]],
            grey,
        );
        let e = elevation.to_radians();
        // The sun's brightness on the plane is about the same at every elevation.
        parts.lights.push(sun(
            Vec3::new(e.cos() * 0.6, -e.sin(), -e.cos() * 0.8),
            2.0 / e.sin(),
        ));
        parts.ambient = [0.02; 3];
        let camera = Camera::look_at(
            "grazing",
            DVec3::new(0.0, 1.5, 12.0),
            DVec3::new(0.0, 0.0, -10.0),
            DVec3::Y,
            Projection::Perspective {
                yfov: 0.9,
                znear: 0.1,
                zfar: None,
            },
        );
        let scene = parts.scene("lit plane", camera);
        for pipeline in [DEFAULT, PipelineFile::for_device("deferred_msaa_4x.ron")] {
            let shadowed = render(pipeline, &scene, (96, 64), Shadows::default());
            let off = Shadows {
                filter: ShadowFilter::Off,
                ..Shadows::default()
            };
            let unshadowed = render(pipeline, &scene, (96, 64), off);
            let darker: Vec<(usize, u8)> = (shadowed.pixels.iter().zip(&unshadowed.pixels))
                .enumerate()
                .filter_map(|(i, (s, u))| {
                    let drop = (0..3).map(|c| u[c].saturating_sub(s[c])).max().unwrap_or(0);
                    (drop > 2).then_some((i, drop))
                })
                .collect();
            assert!(
                darker.is_empty(),
                "{pipeline}, sun {elevation} degrees up: {} pixels darker with shadows than \
                 without, e.g. pixel {} by {}/255",
                darker.len(),
                darker.first().map_or(0, |d| d.0),
                darker.first().map_or(0, |d| d.1)
            );
        }
    }
}

/// builtin:spheres (its sun casts the spheres' shadows on the ground) through the
/// default pipeline's tiled shading, in both branches, and forward_msaa_4x.ron, against
/// deferred_msaa_4x.ron's light volumes: within 2/255 on at least 99% of pixels, each
/// with its shadows. At 640x360:
/// the two shade silhouette pixels differently (fragments against samples), which at
/// 160x90 alone leaves 93.8% within 2/255, shadows or not.
#[test]
fn tiled_forward_and_gbuffer_shading_agree_on_shadows() {
    let scene = Scene::load("builtin:spheres").expect("a built-in scene");
    let size = (640, 360);
    let gbuffer = render(
        PipelineFile::for_device("deferred_msaa_4x.ron"),
        &scene,
        size,
        Shadows::default(),
    );
    let off = Shadows {
        filter: ShadowFilter::Off,
        ..Shadows::default()
    };
    let unshadowed = render(
        PipelineFile::for_device("deferred_msaa_4x.ron"),
        &scene,
        size,
        off,
    );
    // The shadows are there: part of the image is darker with them.
    let unchanged = measure::share_within(&gbuffer, &unshadowed, 8, None);
    assert!(
        unchanged < 0.99,
        "only {:.2}% of pixels change with shadows",
        100.0 * (1.0 - unchanged)
    );
    let forward = PipelineFile::for_device("forward_msaa_4x.ron");
    for pipeline in [DEFAULT, DEFAULT_GPU, forward] {
        let tiled = render(pipeline, &scene, size, Shadows::default());
        let share = measure::share_within(&tiled, &gbuffer, 2, None);
        eprintln!(
            "{pipeline}: {:.3}% within 2/255 of deferred_msaa_4x",
            100.0 * share
        );
        assert!(
            share >= 0.99,
            "{pipeline} renders only {share} of pixels within 2/255 of deferred_msaa_4x"
        );
    }
}

/// `--shadows` takes off, hard or pcf, and `--shadowed-lights` 0 to 64; anything else is
/// a usage error naming the flag, before anything renders.
#[test]
fn bad_shadow_flags_are_usage_errors() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let out = dir.path().join("s.png");
    let out = out.to_str().expect("temp paths are UTF-8");
    for (flag, value, says) in [
        ("--shadows", "bogus", "expected off, hard or pcf"),
        (
            "--shadowed-lights",
            "65",
            "65 shadowed lights is out of range",
        ),
        ("--shadowed-lights", "-1", "from 0 to 64"),
        ("--shadowed-lights", "many", "from 0 to 64"),
    ] {
        rgraph(&[
            "render", "--out", out, "--width", "16", "--height", "16", flag, value,
        ])
        .expect(2)
        .stderr_has(flag)
        .stderr_has(says);
    }
    assert!(!dir.path().join("s.png").exists());
}

/// The pipelines with the `shadows` and `cascades` debug views: the default (the
/// visibility buffer's tiled shading), the G-buffer ones (the light volumes' and the
/// tiled, parts/shadow_debug_views.ron; the lean G-buffer's own) and forward (its own
/// pass's views).
const SHADOW_VIEWS: [PipelineFile; 5] = [
    DEFAULT,
    PipelineFile::for_device("deferred_msaa_4x.ron"),
    PipelineFile::for_device("deferred_msaa_4x_tiled.ron"),
    PipelineFile::for_device("deferred_msaa_4x_lean.ron"),
    PipelineFile::for_device("forward_msaa_4x.ron"),
];

/// The `shadows` debug view shows the sun's visibility term: builtin:spheres' ground is
/// white where lit and black in the spheres' shadows, and the G-buffer and forward
/// pipelines' views are the default's (within 8/255 on 97% of pixels: they sample
/// silhouettes differently).
#[test]
fn the_shadows_view_shows_the_visibility_term() {
    let gpu = gpu();
    let scene = Scene::load("builtin:spheres").expect("a built-in scene");
    let render = |pipeline| {
        Render::new(pipeline, "builtin:spheres", (160, 90))
            .with_scene(scene.clone())
            .features(SceneFeatures::of(&scene).names())
            .run(&gpu)
            .image(&gpu, "debug.shadows")
    };
    let default = render(DEFAULT);
    for pipeline in SHADOW_VIEWS {
        let view = render(pipeline);
        let white = view.count([255, 255, 255, 255]);
        let black_ground = (45..90)
            .flat_map(|y| (0..160).map(move |x| (x, y)))
            .filter(|&(x, y)| view.at(x, y) == [0, 0, 0, 255])
            .count();
        assert!(
            white > view.pixels.len() / 3,
            "{pipeline}: {white} white pixels"
        );
        assert!(
            black_ground > 100,
            "{pipeline}: {black_ground} black pixels in the lower half"
        );
        let share = measure::share_within(&view, &default, 8, None);
        assert!(
            share >= 0.97,
            "{pipeline}: only {share} of the view within 8/255 of the default pipeline's"
        );
    }
}

/// The default pipeline's `cascades` debug view: a long ground plane seen at a grazing
/// angle under a sun shows the sun's cascades by colour (red, green, blue, yellow from the
/// nearest), each pixel the cascade of its view depth: up each column of ground, from
/// near to far, the cascade never goes back, at least three cascades show, and the sky
/// (no geometry) is black.
#[test]
fn the_cascades_view_colours_each_cascade_by_depth() {
    let gpu = gpu();
    let mut parts = Parts::new();
    let grey = parts.material("grey", [0.7, 0.7, 0.7], 0.9);
    parts.mesh(
        "ground",
        &[vec![
            DVec3::new(-30.0, 0.0, -60.0),
            DVec3::new(-30.0, 0.0, 30.0),
            DVec3::new(30.0, 0.0, 30.0),
            DVec3::new(30.0, 0.0, -60.0),
        ]],
        grey,
    );
    parts.lights.push(sun(Vec3::new(0.3, -1.0, -0.2), 3.0));
    parts.ambient = [0.02; 3];
    let camera = Camera::look_at(
        "grazing",
        DVec3::new(0.0, 1.0, 12.0),
        DVec3::new(0.0, 0.0, -10.0),
        DVec3::Y,
        Projection::Perspective {
            yfov: 0.9,
            znear: 0.1,
            zfar: None,
        },
    );
    let scene = parts.scene("long plane", camera);
    let (w, h) = (48, 64);
    let view = Render::new(DEFAULT, &scene.name, (w, h))
        .with_scene(scene.clone())
        .features(SceneFeatures::of(&scene).names())
        .run(&gpu)
        .image(&gpu, "debug.cascades");
    let mut seen = std::collections::BTreeSet::new();
    for x in 0..w {
        let mut last = 0;
        // From the bottom (nearest ground) up.
        for y in (0..h).rev() {
            let p = view.at(x, y);
            match cascade_of(p) {
                Some(c) => {
                    assert!(
                        c >= last,
                        "column {x}: cascade {c} at row {y} above cascade {last} nearer \
                         the camera"
                    );
                    last = c;
                    seen.insert(c);
                }
                None => assert_eq!(
                    p,
                    [0, 0, 0, 255],
                    "pixel ({x}, {y}) is neither a cascade's colour nor black"
                ),
            }
        }
    }
    assert!(seen.len() >= 3, "cascades seen: {seen:?}");
    assert_eq!(view.at(w / 2, 0), [0, 0, 0, 255], "the sky is black");
}

/// The cascade a pixel of the `cascades` view names by its colour (red, green, blue,
/// yellow from the nearest, darker in shadow), or None for black (no geometry).
fn cascade_of(p: [u8; 4]) -> Option<usize> {
    let [r, g, b] = [p[0], p[1], p[2]].map(f64::from);
    if r.max(g).max(b) < 8.0 {
        return None;
    }
    let tints = [
        [1.0, 0.2, 0.2],
        [0.2, 1.0, 0.2],
        [0.25, 0.4, 1.0],
        [1.0, 0.9, 0.2],
    ];
    let top = r.max(g).max(b);
    let off =
        |t: [f64; 3]| (r / top - t[0]).abs() + (g / top - t[1]).abs() + (b / top - t[2]).abs();
    let best = (0..4).min_by(|&a, &b| off(tints[a]).total_cmp(&off(tints[b])));
    best.filter(|&c| off(tints[c]) < 0.3)
}

/// The cascades are fitted to the depths the camera sees (gpu_scene/seen_depths.rs), not
/// from its near plane: on builtin:spheres, whose ground starts several units out, every
/// one of the four cascades covers some of the image (at least 1% of its pixels each),
/// in every pipeline with the view.
#[test]
fn every_cascade_covers_part_of_the_spheres() {
    let gpu = gpu();
    let scene = Scene::load("builtin:spheres").expect("a built-in scene");
    for pipeline in SHADOW_VIEWS {
        let view = Render::new(pipeline, "builtin:spheres", (160, 90))
            .with_scene(scene.clone())
            .features(SceneFeatures::of(&scene).names())
            .run(&gpu)
            .image(&gpu, "debug.cascades");
        let mut counts = [0usize; 4];
        for p in view.pixels.iter() {
            if let Some(c) = cascade_of(*p) {
                counts[c] += 1;
            }
        }
        let least = view.pixels.len() / 100;
        assert!(
            counts.iter().all(|&n| n >= least),
            "{pipeline}: pixels per cascade, nearest first: {counts:?} (each should have \
             {least} or more)"
        );
    }
}

/// Every file in `pipelines/` that lights surfaces and draws alpha BLEND ones (all but
/// the unlit and debug files), as compiled for the tests' adapter.
const LIT_WITH_BLEND: [&str; 15] = [
    "visibility_msaa_4x.ron",
    "deferred_msaa_4x.ron",
    "deferred_msaa_4x_tiled.ron",
    "deferred_msaa_4x_adaptive.ron",
    "deferred_msaa_4x_lean.ron",
    "deferred_msaa_4x_ssao.ron",
    "deferred_noaa.ron",
    "deferred_onthefly_resolve_4x.ron",
    "deferred_gbuffer_resolve_4x.ron",
    "light_prepass_msaa_4x.ron",
    "forward_msaa_4x.ron",
    "reference_ssaa16.ron",
    "particles_full_res.ron",
    "particles_low_res.ron",
    "particles_mixed_res.ron",
];

/// Every lit pipeline draws the square's shadow on the ground (lit ground at least twice
/// as bright as the shadow's centre, and the same without shadows), whether the ground is
/// opaque or an alpha BLEND surface of alpha 1, which the `transparent` pass lights: a
/// blended surface receives shadows as an opaque one does.
#[test]
fn every_lit_pipeline_shadows_opaque_and_blended_receivers() {
    let opaque = square_over_plane();
    let mut parts = square_parts();
    let mut glass = parts.materials[0].clone();
    glass.name = "blended".into();
    glass.alpha_mode = AlphaMode::Blend;
    parts.materials.push(glass);
    parts.meshes[0].material = parts.materials.len() - 1;
    let blended = square_scene(parts);
    let shadows = Shadows {
        filter: ShadowFilter::Pcf,
        lights: 1,
    };
    let off = Shadows {
        filter: ShadowFilter::Off,
        lights: 1,
    };
    for name in LIT_WITH_BLEND {
        let pipeline = PipelineFile::for_device(name);
        for (ground, scene) in [("opaque", &opaque), ("blended", &blended)] {
            let image = render(pipeline, scene, (N, N), shadows);
            // Lit ground, and the ground the square hides from the sun, by their centres.
            let (lit, dark) = (luma(image.at(16, 52)), luma(image.at(48, 32)));
            assert!(
                lit > 40.0 && dark < 0.5 * lit,
                "{name}, {ground} ground: the shadow's centre ({dark:.0}) is not darker than \
                 half the lit ground ({lit:.0})"
            );
            let unshadowed = render(pipeline, scene, (N, N), off);
            let (lit, shade) = (luma(unshadowed.at(16, 52)), luma(unshadowed.at(48, 32)));
            assert!(
                (lit - shade).abs() <= 1.0,
                "{name}, {ground} ground: without shadows the ground is lit alike everywhere \
                 ({lit:.0} and {shade:.0})"
            );
        }
    }
}

/// The forward pass's shadow views need the atlas: a file giving `view: shadows` no
/// `shadows` input, or an optional one, is an error naming the pass and the slot.
#[test]
fn a_forward_shadow_view_without_its_atlas_is_an_error() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let write = |name: &str, inputs: &str| {
        write_graph(
            dir.path(),
            name,
            &format!(
                r#"Graph(
    resources: {{
        "view": Texture(format: "rgba8unorm"),
        "depth": Texture(format: "depth32float"),
        "atlas": Texture(format: "depth32float", size: Absolute(256, 256)),
    }},
    passes: [
        (name: "maps", plugin: "shadow_maps", outputs: {{ "atlas": "atlas" }}),
        (name: "view", plugin: "forward", params: (view: cascades),
         {inputs} outputs: {{ "hdr": "view", "depth": "depth" }}),
    ],
    outputs: ["view"],
)"#
            ),
        )
    };
    let missing = write("missing.ron", "");
    let optional = write(
        "optional.ron",
        r#"inputs: { "shadows": "atlas" }, optional: ["shadows"],"#,
    );
    for (file, says) in [
        (
            missing,
            "pass \"view\" (forward): needs slot \"shadows\" in its inputs",
        ),
        (
            optional,
            "pass \"view\" (forward): slot \"shadows\": \"atlas\" is read optionally, but view \
             cascades draws the shadow maps: the read must be required",
        ),
    ] {
        assert_invalid(&file, says);
    }
    let given = write("given.ron", r#"inputs: { "shadows": "atlas" },"#);
    rgraph(&["validate", &given]).expect(0);
}

/// `shadow_resolve`'s slots are checked against its atlas: the keys must hold 4 bytes a
/// texel of it and the alpha MASK depth must be its size, each an error naming the pass,
/// the slot and the resource (`rgraph validate`, no GPU); the right sizes validate.
#[test]
fn shadow_resolve_s_inputs_must_fit_its_atlas() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let write = |name: &str, keys: u32, depth: u32| {
        write_graph(
            dir.path(),
            name,
            &format!(
                r#"Graph(
    resources: {{
        "keys": Buffer(per_texel: 4, texels: ({keys}, {keys})),
        "masked": Texture(format: "depth32float", size: Absolute({depth}, {depth})),
        "atlas": Texture(format: "r32float", size: Absolute(256, 256)),
    }},
    passes: [
        (name: "raster", plugin: "shadow_raster", outputs: {{ "keys": "keys" }}),
        (name: "maps", plugin: "shadow_maps", inputs: {{ "keys": "keys" }},
         outputs: {{ "atlas": "masked" }}),
        (name: "resolve", plugin: "shadow_resolve",
         inputs: {{ "keys": "keys", "depth": "masked" }}, outputs: {{ "atlas": "atlas" }}),
    ],
    outputs: ["atlas"],
)"#
            ),
        )
    };
    let (keys, depth) = (write("keys.ron", 128, 256), write("depth.ron", 256, 128));
    for (file, says) in [
        (
            keys,
            "pass \"resolve\" (shadow_resolve): slot \"keys\": \"keys\" holds 65536 bytes, \
             but the keys of a Absolute(256, 256) atlas take 4 bytes a texel",
        ),
        (
            depth,
            "pass \"resolve\" (shadow_resolve): slot \"depth\": \"masked\" is \
             Absolute(128, 128), but it must be the atlas's size, Absolute(256, 256)",
        ),
    ] {
        assert_invalid(&file, says);
    }
    rgraph(&["validate", &write("fits.ron", 256, 256)]).expect(0);
}

/// Writes graph file `name` holding `text` into `dir`, returning its path.
fn write_graph(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("a file in the temporary directory");
    path.to_str().expect("temp paths are UTF-8").to_owned()
}

/// `rgraph validate FILE` fails, saying `says`: it reports on stdout, with each file's
/// verdict.
fn assert_invalid(file: &str, says: &str) {
    let run = rgraph(&["validate", file]).expect(1);
    assert!(run.stdout.contains(says), "{}", run.stdout);
}

/// The atlas's side is the graph parameter `shadow_map`, which also sizes the compute
/// raster's keys (4 bytes a texel); a side that is not a multiple of the map grid's 32
/// units, or 0, is an error at the part's line naming the resource.
#[test]
fn the_shadow_map_parameter_sizes_the_atlas_and_its_keys() {
    let explain = |value: &str| {
        rgraph(&[
            "explain",
            "--pipeline",
            "pipelines/visibility_msaa_4x.ron",
            "--param",
            &format!("shadow_map={value}"),
        ])
    };
    let run = explain("2048").expect(0);
    assert!(
        run.stdout.contains("  shadow_atlas: r32float 2048x2048\n")
            && run.stdout.contains("  shadow_keys: buffer 16.0 MiB\n")
            && run
                .stdout
                .contains("  shadow_depth: depth32float 2048x2048\n"),
        "{}",
        run.stdout
    );
    explain("1000").expect(1).stderr_has(
        "pipelines/parts/shadow_maps_compute.ron:59:33: error: pass \"shadow resolve\" \
         (shadow_resolve): slot \"atlas\": \"shadow_atlas\" is Absolute(1000, 1000), but \
         the shadow atlas must be Absolute(N, N), N a multiple of 32",
    );
    explain("0").expect(1).stderr_has(
        "pipelines/parts/shadow_maps_compute.ron:21:40: error: parameter \"shadow_map\" is 0, \
         but the width of \"shadow_atlas\" must be 1 or more",
    );
}

/// While nothing the maps show moves, the GPU branch keeps the last frame's atlas: its
/// compute raster draws nothing (it holds no buffer that frame) and the image is the one
/// drawn every frame (`shadow_cache=0`), exactly. A moved caster, a turned light and a
/// moved camera each draw the maps again, and each such frame is the image of maps drawn
/// for it; a still frame after them keeps again.
#[test]
fn the_atlas_is_kept_while_nothing_moves() {
    let gpu = gpu();
    let scene = square_over_plane();
    let render = |cache: u32| {
        Render::new(DEFAULT_GPU, &scene.name, (N, N))
            .with_scene(scene.clone())
            .features(SceneFeatures::of(&scene).names())
            .param("shadow_cache", cache)
            .run(&gpu)
    };
    let (mut kept, mut drawn) = (render(1), render(0));
    let still = kept.inputs();
    let mut moved_caster = still.clone();
    moved_caster.transforms[1] =
        rgraph_scene::glam::DMat4::from_translation(DVec3::new(0.5, 0.0, 0.25));
    let mut turned_light = moved_caster.clone();
    turned_light.lights[0].direction = Vec3::new(1.0, -1.5, 0.5).normalize();
    let mut moved_camera = turned_light.clone();
    moved_camera.camera = Camera::look_at(
        "from above, moved",
        DVec3::new(0.5, 10.0, 0.0),
        DVec3::new(0.5, 0.0, 0.0),
        DVec3::NEG_Z,
        still.camera.projection,
    );
    let frames = [
        ("the first frame again", still, false),
        ("a moved caster", moved_caster, true),
        ("a turned light", turned_light.clone(), true),
        ("the turned light again", turned_light, false),
        ("a moved camera", moved_camera.clone(), true),
        ("the moved camera again", moved_camera, false),
    ];
    let mut images = vec![kept.image(&gpu, "color")];
    for (what, inputs, draws) in frames {
        let report = kept.next(inputs.clone());
        drawn.next(inputs);
        let raster = (report.passes.iter())
            .find(|p| p.name == "shadow raster")
            .expect("a shadow raster pass");
        assert_eq!(
            raster.held_bytes > 0,
            draws,
            "{what}: the raster held {} bytes",
            raster.held_bytes
        );
        let (image, expected) = (kept.image(&gpu, "color"), drawn.image(&gpu, "color"));
        assert!(
            image.pixels == expected.pixels,
            "{what}: the kept atlas's image differs"
        );
        images.push(image);
    }
    // Not vacuous: the moved caster's shadow moved, and the turned light's too.
    for (k, what) in [(2, "the caster"), (3, "the light")] {
        let changed = (images[k - 1].pixels.iter().zip(&images[k].pixels))
            .filter(|(a, b)| a != b)
            .count();
        assert!(changed > 100, "moving {what} changed {changed} pixels");
    }
}

/// A kept atlas's slot is checked without a GPU (`rgraph validate`): `previous` must be a
/// history, and `cache: true` needs the slot, each an error naming the pass.
#[test]
fn a_kept_atlas_must_be_a_history() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let write = |name: &str, previous: &str, params: &str| {
        write_graph(
            dir.path(),
            name,
            &format!(
                r#"Graph(
    resources: {{
        "keys": Buffer(per_texel: 4, texels: (256, 256)),
        "atlas": Texture(format: "r32float", size: Absolute(256, 256)),
        "atlas_prev": History(of: "atlas"),
        "other": Texture(format: "r32float", size: Absolute(256, 256)),
    }},
    passes: [
        (name: "raster", plugin: "shadow_raster", outputs: {{ "keys": "keys" }}),
        (name: "other", plugin: "clear", outputs: {{ "target": "other" }}),
        (name: "resolve", plugin: "shadow_resolve", params: ({params}),
         inputs: {{ "keys": "keys"{previous} }}, outputs: {{ "atlas": "atlas" }}),
    ],
    outputs: ["atlas", "other"],
)"#
            ),
        )
    };
    assert_invalid(
        &write("plain.ron", ", \"previous\": \"other\"", ""),
        "pass \"resolve\" (shadow_resolve): slot \"previous\": \"other\" is not a history",
    );
    assert_invalid(
        &write("missing.ron", "", "cache: true"),
        "pass \"resolve\" (shadow_resolve): keeping the shadow atlas (cache: true) needs a \
         \"previous\" input",
    );
    rgraph(&[
        "validate",
        &write("history.ron", ", \"previous\": \"atlas_prev\"", ""),
    ])
    .expect(0);
    rgraph(&["validate", &write("off.ron", "", "cache: false")]).expect(0);
}

/// The share of pixels whose four channels (alpha too) differ by at most 2/255 between
/// the hardware's shadows and the compute raster's.
fn share_within_2(hardware: &Image, compute: &Image) -> f64 {
    let close = (hardware.pixels.iter().zip(&compute.pixels))
        .filter(|(h, c)| h.iter().zip(c.iter()).all(|(h, c)| h.abs_diff(*c) <= 2))
        .count();
    close as f64 / hardware.pixels.len() as f64
}
