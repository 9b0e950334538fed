//! Scene analysis on the built-in scenes (CPU only): the features each uses, under the
//! names pipeline conditions test, its depth range and the smallest detail it puts on
//! screen.

use rgraph_scene::analysis::{Analysis, DepthRange, Features, SmallestFeature};
use rgraph_scene::glam::DVec3;
use rgraph_scene::{LightKind, Material, Projection, Scene};

fn scene(name: &str) -> Scene {
    Scene::load(name).unwrap_or_else(|e| panic!("{name} loads: {e}"))
}

fn names(scene: &Scene) -> String {
    Features::of(scene).names().to_string()
}

#[test]
fn each_built_in_scene_names_the_features_it_uses() {
    let expected = [
        (
            "builtin:spheres",
            "ambient, directional_lights, lit, point_lights, shadows, shallow_depth",
        ),
        (
            "builtin:dense",
            "ambient, double_sided, lit, point_lights, shadows, shallow_depth, spot_lights",
        ),
        (
            "builtin:lights",
            "ambient, lit, point_lights, shadows, shallow_depth, spot_lights",
        ),
        (
            "builtin:unlit",
            "double_sided, no_lights, shallow_depth, unlit, unlit_only",
        ),
    ];
    for (name, features) in expected {
        assert_eq!(names(&scene(name)), features, "{name}");
    }
}

#[test]
fn the_general_scene_uses_every_feature_and_lacks_nothing() {
    let general = Features::general().names();
    let mut present: Vec<&str> = Features::NAMES
        .into_iter()
        .filter(|&n| {
            ![
                "unlit_only",
                "no_lights",
                "shallow_depth",
                "auto_exposure",
                "background",
            ]
            .contains(&n)
        })
        .collect();
    present.sort();
    assert_eq!(general.iter().collect::<Vec<_>>(), present);
}

#[test]
fn a_scene_without_lights_or_ambient_has_no_lights() {
    let mut spheres = scene("builtin:spheres");
    spheres.lights.clear();
    assert_eq!(names(&spheres), "ambient, lit, shallow_depth");
    spheres.ambient = [0.0; 3];
    assert_eq!(names(&spheres), "lit, no_lights, shallow_depth");
}

#[test]
fn lights_that_emit_nothing_and_materials_nothing_draws_do_not_count() {
    let mut spheres = scene("builtin:spheres");
    for light in &mut spheres.lights {
        if light.kind == LightKind::Point {
            light.intensity = 0.0;
        }
    }
    spheres.materials.push(Material {
        unlit: true,
        double_sided: true,
        ..Material::gltf_default()
    });
    assert_eq!(
        names(&spheres),
        "ambient, directional_lights, lit, shadows, shallow_depth"
    );
}

#[test]
fn the_unlit_scene_spans_exactly_its_shapes_depths() {
    // Camera at z = 10 looking down -Z; the shapes lie between z = -0.5 and 0.5.
    let range = DepthRange::of(&scene("builtin:unlit")).unwrap();
    assert_eq!((range.near, range.far), (9.5, 10.5));
    assert_eq!(range.ratio(), 10.5 / 9.5);
}

#[test]
fn moving_the_camera_back_moves_the_depth_range_with_it() {
    let near = scene("builtin:lights");
    let mut far = near.clone();
    far.camera.position -= far.camera.forward() * 10.0;
    let (a, b) = (
        DepthRange::of(&near).unwrap(),
        DepthRange::of(&far).unwrap(),
    );
    assert!(
        a.near > 0.1,
        "all of builtin:lights lies beyond its near plane: {a:?}"
    );
    assert!((b.near - a.near - 10.0).abs() < 1e-9, "{a:?} {b:?}");
    assert!((b.far - a.far - 10.0).abs() < 1e-9, "{a:?} {b:?}");
}

#[test]
fn geometry_behind_the_camera_has_no_depth_range() {
    let mut unlit = scene("builtin:unlit");
    unlit.camera.position = DVec3::new(0.0, 0.0, -30.0);
    assert_eq!(DepthRange::of(&unlit), None);
    assert_eq!(SmallestFeature::of(&unlit, (64, 64)), None);
}

#[test]
fn the_unlit_scene_s_smallest_feature_is_its_yellow_square_s_side() {
    // Orthographic with ymag 1: 64 pixels span 2 world units, and the tilted square's
    // vertical sides (0.4 long) are the shortest edges: 12.8 pixels, twice that at 128.
    let unlit = scene("builtin:unlit");
    for (size, pixels) in [(64, 12.8), (128, 25.6)] {
        let smallest = SmallestFeature::of(&unlit, (size, size)).unwrap();
        assert!((smallest.pixels - pixels).abs() < 1e-5, "{smallest:?}");
        assert_eq!(smallest.mesh, "yellow tilted square");
    }
}

#[test]
fn perspective_detail_grows_with_the_output_height() {
    let spheres = scene("builtin:spheres");
    let small = Analysis::of(&spheres, (64, 64)).smallest.unwrap();
    let large = Analysis::of(&spheres, (100, 128)).smallest.unwrap();
    assert_eq!(small.mesh, large.mesh);
    assert!((large.pixels / small.pixels - 2.0).abs() < 1e-9);
    // Sub-pixel detail: the spheres' tessellation is finer than a 64x64 pixel.
    assert!(small.pixels < 1.0, "{small:?}");
}

#[test]
fn the_built_in_scenes_are_shallow_until_the_near_plane_shrinks() {
    for name in ["builtin:spheres", "builtin:dense", "builtin:lights?count=8"] {
        let mut deep = scene(name);
        let range = DepthRange::of(&deep).unwrap();
        let Projection::Perspective { znear, .. } = &mut deep.camera.projection else {
            panic!("{name} has a perspective camera");
        };
        let ratio = range.far / f64::from(*znear);
        assert!(ratio <= 1024.0, "{name}: far / znear {ratio}");
        println!("{name}: far / znear {ratio:.1}");
        // Geometry 1024 near planes away and farther needs float depth.
        *znear = (range.far / 1025.0) as f32;
        assert!(Features::of(&scene(name)).shallow_depth, "{name}");
        assert!(!Features::of(&deep).shallow_depth, "{name}");
    }
}
