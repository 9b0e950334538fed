//! Built-in scenes: deterministic, and with the properties their documentation promises.

use glam::{DVec3, Vec3};
use rgraph_scene::{
    analysis::Features, builtin_names, DepthConvention, LightKind, Mesh, Projection, Scene,
    SceneError, MAX_LIGHTS,
};

fn builtin(spec: &str) -> Scene {
    Scene::load(spec).unwrap_or_else(|e| panic!("{e}"))
}

fn mesh<'a>(scene: &'a Scene, name: &str) -> &'a Mesh {
    scene
        .meshes
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("no mesh {name}"))
}

#[test]
fn every_builtin_is_listed_described_and_bit_identical_across_loads() {
    let names: Vec<&str> = builtin_names().iter().map(|b| b.name).collect();
    assert_eq!(
        names,
        ["spheres", "dense", "lights", "unlit", "smoke", "terrain", "city", "rocks"]
    );
    for scene in builtin_names() {
        assert!(!scene.description.is_empty());
        let spec = format!("builtin:{}", scene.name);
        let (a, b) = (builtin(&spec), builtin(&spec));
        assert_eq!(a, b, "{spec}");
        for (ma, mb) in a.meshes.iter().zip(&b.meshes) {
            let bytes = |m: &Mesh| bytemuck::cast_slice::<_, u8>(&m.vertices).to_vec();
            assert_eq!(bytes(ma), bytes(mb), "{spec}: {}", ma.name);
        }
        assert_eq!(a.name, spec);
        assert!(a.warnings.is_empty());
    }
}

#[test]
fn spheres_has_few_large_smooth_objects() {
    let scene = builtin("builtin:spheres");
    let stats = scene.stats();
    assert_eq!(stats.meshes, 6);
    assert_eq!(stats.triangles, 2 + 5 * 2 * 48 * 23);
    assert_eq!(
        (
            stats.directional_lights,
            stats.point_lights,
            stats.spot_lights
        ),
        (1, 4, 0)
    );
    let red = mesh(&scene, "red sphere").world_bounds().unwrap();
    assert!(
        red.min.abs_diff_eq(DVec3::new(-1.5, 0.0, -1.5), 1e-6),
        "{red:?}"
    );
    assert!(
        red.max.abs_diff_eq(DVec3::new(1.5, 3.0, 1.5), 1e-6),
        "{red:?}"
    );
}

#[test]
fn spheres_layers_puts_one_layer_on_each_of_three_spheres() {
    let core = builtin("builtin:spheres?layers=0");
    assert!(core.materials == builtin("builtin:spheres").materials);
    let layered = builtin("builtin:spheres?layers=1");
    let features = |scene: &Scene| {
        let f = Features::of(scene);
        (f.specular, f.clearcoat, f.sheen)
    };
    assert_eq!(features(&core), (false, false, false));
    assert_eq!(features(&layered), (true, true, true));
    let material = |name: &str| {
        let mesh = mesh(&layered, name);
        &layered.materials[mesh.material]
    };
    assert_eq!(material("red sphere").clearcoat.factor, 1.0);
    assert_eq!(material("green sphere").sheen.color_factor, [1.0; 3]);
    assert_eq!(material("blue sphere").ior, 1.8);
    // The layers change materials only: the geometry is the core scene's.
    assert!(core.meshes == layered.meshes);
    for name in ["gold sphere", "white sphere", "ground"] {
        assert!(
            material(name) == &core.materials[mesh(&core, name).material],
            "{name}"
        );
    }
}

#[test]
fn rocks_share_one_geometry_and_check_their_limits_first() {
    let scene = builtin("builtin:rocks?copies=50&detail=16");
    let rocks: Vec<&Mesh> = (scene.meshes.iter())
        .filter(|m| m.name.starts_with("rock "))
        .collect();
    assert_eq!(rocks.len(), 50);
    assert_eq!(scene.stats().triangles, 2 + 50 * 2 * 16 * 7);
    for rock in &rocks {
        assert!(std::sync::Arc::ptr_eq(&rock.vertices, &rocks[0].vertices));
        assert!(std::sync::Arc::ptr_eq(&rock.indices, &rocks[0].indices));
    }
    // Scattered: no two copies at one place.
    let origin = |m: &Mesh| m.transform.w_axis.truncate();
    assert!(rocks[1..]
        .iter()
        .all(|m| origin(m).distance(origin(rocks[0])) > 1e-3));
    assert_ne!(
        origin(rocks[0]),
        origin(mesh(
            &builtin("builtin:rocks?copies=50&detail=16&seed=2"),
            "rock 0"
        ))
    );
    // 100M triangles pass the limits; one copy more than the indices allow does not.
    let over = Scene::load("builtin:rocks?copies=45101&detail=64").unwrap_err();
    assert!(
        over.to_string()
            .contains("178960768 triangles in all, more than 178956970"),
        "{over}"
    );
    for (spec, says) in [
        (
            "builtin:rocks?copies=0",
            "`copies=0`: a whole number from 1 to 1048575",
        ),
        (
            "builtin:rocks?detail=3",
            "`detail=3`: a whole number from 4 to 2048",
        ),
        ("builtin:rocks?copies=1048576", "from 1 to 1048575"),
    ] {
        let error = Scene::load(spec).unwrap_err();
        assert!(error.to_string().contains(says), "{spec}: {error}");
    }
}

/// Whether some points of `a`'s surface (an 8 x 8 barycentric grid per triangle) lie inside
/// `b` and some outside: the surfaces cross, so there are intersection edges. `b` is a box
/// (unit cube) or a sphere (unit ball) in its object space.
fn interpenetrates(a: &Mesh, b: &Mesh, b_is_box: bool) -> bool {
    let to_b = b.transform.inverse() * a.transform;
    let mut inside = Vec::new();
    for tri in a.indices.chunks(3) {
        let [p, q, r] =
            [0, 1, 2].map(|k| Vec3::from(a.vertices[tri[k] as usize].position).as_dvec3());
        for i in 0..=8 {
            for j in 0..=8 - i {
                let (u, v) = (f64::from(i) / 8.0, f64::from(j) / 8.0);
                let local = to_b.transform_point3(p + (q - p) * u + (r - p) * v);
                inside.push(if b_is_box {
                    local.abs().max_element() < 0.5
                } else {
                    local.length() < 1.0
                });
            }
        }
    }
    inside.contains(&true) && inside.contains(&false)
}

#[test]
fn dense_has_many_more_triangles_thin_geometry_and_intersecting_solids() {
    let dense = builtin("builtin:dense");
    let spheres = builtin("builtin:spheres");
    assert!(dense.stats().triangles > 5 * spheres.stats().triangles);
    let grass = mesh(&dense, "grass");
    assert_eq!(grass.triangle_count(), 160 * 160 * 3);
    assert!(dense.materials[grass.material].double_sided);
    let wires = mesh(&dense, "fence").world_bounds().unwrap();
    assert!(wires.size().x > 19.9 && wires.size().z < 0.1, "{wires:?}");
    assert!(interpenetrates(
        mesh(&dense, "sphere in box"),
        mesh(&dense, "box"),
        true
    ));
    assert!(interpenetrates(
        mesh(&dense, "cross bar x"),
        mesh(&dense, "cross bar z"),
        true
    ));
    assert!(interpenetrates(
        mesh(&dense, "slab"),
        mesh(&dense, "sunken sphere"),
        false
    ));
    let stats = dense.stats();
    assert_eq!((stats.point_lights, stats.spot_lights), (4, 2));
}

#[test]
fn lights_has_hundreds_of_point_and_spot_lights_within_documented_ranges() {
    let scene = builtin("builtin:lights");
    let stats = scene.stats();
    assert_eq!(
        (
            stats.point_lights,
            stats.spot_lights,
            stats.directional_lights
        ),
        (256, 64, 0)
    );
    for light in &scene.lights {
        let p = light.position;
        let range = light.range.unwrap();
        match light.kind {
            LightKind::Point => {
                assert!(p.x.abs() <= 20.0 && p.z.abs() <= 20.0 && (0.3..3.0).contains(&p.y));
                assert!((4.0..7.0).contains(&range) && (2.0..6.0).contains(&light.intensity));
            }
            LightKind::Spot {
                inner_cone,
                outer_cone,
            } => {
                assert!(p.x.abs() <= 18.0 && p.z.abs() <= 18.0 && (4.0..7.0).contains(&p.y));
                assert!((10.0..14.0).contains(&range) && (20.0..60.0).contains(&light.intensity));
                assert!((0.3..0.7).contains(&outer_cone) && inner_cone == 0.6 * outer_cone);
                assert!(light.direction.dot(Vec3::NEG_Y) >= 25f32.to_radians().cos() - 1e-6);
                assert!((light.direction.length() - 1.0).abs() < 1e-6);
            }
            LightKind::Directional => unreachable!(),
        }
    }
}

#[test]
fn lights_parameters_scale_and_reseed() {
    let big = builtin("builtin:lights?count=1024").stats();
    assert_eq!((big.point_lights, big.spot_lights), (820, 204));
    let default = builtin("builtin:lights");
    assert_eq!(
        builtin("builtin:lights?seed=1&count=320").lights,
        default.lights
    );
    assert_ne!(builtin("builtin:lights?seed=2").lights, default.lights);
}

#[test]
fn builtin_spec_errors_list_what_is_available() {
    let message = Scene::load("builtin:nope").unwrap_err().to_string();
    assert_eq!(
        message,
        "unknown built-in scene `nope`; available: spheres, dense, lights, unlit, smoke, terrain, \
         city, rocks"
    );
    let error = Scene::load("builtin:lights?lamps=3").unwrap_err();
    assert!(matches!(error, SceneError::BuiltinParameter { .. }));
    assert!(
        error.to_string().contains("this scene takes: count, seed"),
        "{error}"
    );
    let error = Scene::load("builtin:spheres?count=3").unwrap_err();
    assert!(
        error.to_string().contains("this scene takes: layers"),
        "{error}"
    );
    let error = Scene::load("builtin:unlit?count=3").unwrap_err();
    assert!(
        error.to_string().contains("this scene takes: none"),
        "{error}"
    );
    let error = Scene::load("builtin:lights?count=-1").unwrap_err();
    assert_eq!(
        error.to_string(),
        "builtin:lights: `count=-1`: expected a whole number from 0 to 65536"
    );
}

#[test]
fn every_builtin_parameter_has_a_limit_checked_before_building() {
    // A hundred million lights once allocated until the process aborted.
    let error = Scene::load("builtin:lights?count=100000000").unwrap_err();
    assert_eq!(
        error.to_string(),
        "builtin:lights: `count=100000000`: a whole number from 0 to 65536 (total number of \
         lights, 4/5 point and 1/5 spot (default 320, at most 65536))"
    );
    let error = Scene::load("builtin:lights?count=65537").unwrap_err();
    assert!(error.to_string().contains("from 0 to 65536"), "{error}");
    let error = Scene::load("builtin:lights?seed=4294967296").unwrap_err();
    assert!(
        error
            .to_string()
            .contains("`seed=4294967296`: a whole number from 0 to 4294967295"),
        "{error}"
    );
    assert_eq!(MAX_LIGHTS, 65_536);
    let most = builtin(&format!("builtin:lights?count={MAX_LIGHTS}"));
    assert_eq!(most.lights.len(), MAX_LIGHTS as usize);
    for scene in builtin_names() {
        for param in scene.params {
            assert!(
                param.meaning.contains(&format!("at most {}", param.max)) || param.max == u32::MAX,
                "builtin:{} `{}` does not document its limit",
                scene.name,
                param.key
            );
        }
    }
}

/// A documented unlit shape: name, base color, corners.
type Flat = (&'static str, [f32; 4], &'static [[f32; 3]]);

/// NDC of a world point as seen by the scene camera at aspect 1.
fn ndc(scene: &Scene, p: DVec3, depth: DepthConvention) -> DVec3 {
    let clip = scene.camera.projection_matrix(1.0, depth).as_dmat4()
        * scene.camera.view_matrix()
        * p.extend(1.0);
    (clip / clip.w).truncate()
}

#[test]
fn unlit_has_the_documented_geometry_and_mapping() {
    let scene = builtin("builtin:unlit");
    assert_eq!(
        scene.camera.projection,
        Projection::Orthographic {
            xmag: 1.0,
            ymag: 1.0,
            znear: 1.0,
            zfar: 20.0
        }
    );
    assert_eq!(scene.camera.position, DVec3::new(0.0, 0.0, 10.0));
    assert!(scene.lights.is_empty() && scene.ambient == [0.0; 3]);
    let expected: [Flat; 4] = [
        (
            "red triangle",
            [1.0, 0.0, 0.0, 1.0],
            &[[-0.8, -0.8, 0.0], [0.0, -0.8, 0.0], [-0.8, 0.0, 0.0]],
        ),
        (
            "green triangle",
            [0.0, 1.0, 0.0, 1.0],
            &[[-0.6, -0.6, 0.5], [0.2, -0.6, 0.5], [-0.6, 0.2, 0.5]],
        ),
        (
            "blue square",
            [0.0, 0.0, 1.0, 1.0],
            &[
                [0.2, 0.2, 0.0],
                [0.8, 0.2, 0.0],
                [0.8, 0.8, 0.0],
                [0.2, 0.8, 0.0],
            ],
        ),
        (
            "yellow tilted square",
            [1.0, 1.0, 0.0, 1.0],
            &[
                [0.3, 0.3, -0.5],
                [0.7, 0.3, 0.5],
                [0.7, 0.7, 0.5],
                [0.3, 0.7, -0.5],
            ],
        ),
    ];
    for (name, color, corners) in expected {
        let m = mesh(&scene, name);
        let material = &scene.materials[m.material];
        assert!(material.unlit && material.double_sided);
        assert_eq!(material.base_color_factor, color);
        let positions: Vec<[f32; 3]> = m.vertices.iter().map(|v| v.position).collect();
        assert_eq!(positions, corners, "{name}");
        for p in m.world_positions() {
            let n = ndc(&scene, p, DepthConvention::Standard);
            assert!(
                (n.x - p.x).abs() < 1e-6 && (n.y - p.y).abs() < 1e-6,
                "{name}: {p} -> {n}"
            );
            // View depth 10 - z over near 1 .. far 20.
            assert!(
                (n.z - (9.0 - p.z) / 19.0).abs() < 1e-6,
                "{name}: depth {}",
                n.z
            );
        }
    }
    // Green is in front of red: smaller standard depth, larger reversed depth.
    let (red, green) = (DVec3::new(-0.7, -0.7, 0.0), DVec3::new(-0.5, -0.5, 0.5));
    assert!(
        ndc(&scene, green, DepthConvention::Standard).z
            < ndc(&scene, red, DepthConvention::Standard).z
    );
    assert!(
        ndc(&scene, green, DepthConvention::ReversedZ).z
            > ndc(&scene, red, DepthConvention::ReversedZ).z
    );
    // The yellow square crosses the blue one's plane (z = 0) at x = 0.5.
    let yellow = mesh(&scene, "yellow tilted square");
    let z_at = |x: f32| {
        let [a, b] = [yellow.vertices[0].position, yellow.vertices[1].position];
        a[2] + (b[2] - a[2]) * (x - a[0]) / (b[0] - a[0])
    };
    assert_eq!(z_at(0.5), 0.0);
}

#[test]
fn smoke_is_dense_with_a_seeded_smoke_column_and_fire() {
    let scene = builtin("builtin:smoke");
    let dense = builtin("builtin:dense");
    assert_eq!(scene.meshes, dense.meshes);
    assert_eq!(scene.camera, dense.camera);
    let names: Vec<&str> = scene.emitters.iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names, ["smoke", "fire"]);
    let (smoke, fire) = (&scene.emitters[0].particles, &scene.emitters[1].particles);
    assert_eq!((smoke.len(), fire.len()), (3500, 500));
    assert!(smoke
        .iter()
        .all(|p| !p.emissive && p.size >= 0.6 && p.size <= 1.8));
    assert!(fire.iter().all(|p| p.emissive && p.position.y < 1.0));
    assert_eq!(scene.particles().count(), 4000);
    let other = builtin("builtin:smoke?count=80&size=300&seed=7");
    assert_eq!(other.particles().count(), 80);
    assert!(other.particles().all(|p| p.size >= 0.9 && p.size <= 4.5));
    assert_ne!(builtin("builtin:smoke?seed=2").emitters, scene.emitters);
    let half = builtin("builtin:smoke?extent=50");
    for (a, b) in half.particles().zip(scene.particles()) {
        assert!((a.position * 2.0 - b.position).length() < 1e-6);
        assert!((a.size * 2.0 - b.size).abs() < 1e-6);
    }
}

#[test]
fn smoke_parameters_out_of_range_are_errors_not_allocations() {
    let message = |spec: &str| Scene::load(spec).unwrap_err().to_string();
    assert_eq!(
        message("builtin:smoke?count=1048577"),
        "builtin:smoke: `count=1048577`: a whole number from 0 to 1048576 (total number of \
         particles, 7/8 smoke and 1/8 fire (default 4000, at most 1048576))"
    );
    assert!(message("builtin:smoke?size=0").contains("`size=0`: a whole number from 1 to 10000"));
    assert!(message("builtin:smoke?size=10001").contains("`size=10001`: a whole number from 1"));
    assert!(message("builtin:smoke?extent=0").contains("`extent=0`: a whole number from 1 to 1000"));
    assert!(
        message("builtin:smoke?speed=3").contains("this scene takes: count, size, seed, extent")
    );
}

#[test]
fn bad_particles_in_code_built_scenes_are_named_errors() {
    use rgraph_scene::{Particle, ParticleEmitter, MAX_PARTICLES};
    let mut scene = builtin("builtin:unlit");
    let good = Particle {
        position: DVec3::ZERO,
        size: 1.0,
        color: [1.0; 3],
        alpha: 0.5,
        emissive: false,
    };
    let bad = Particle { alpha: 1.5, ..good };
    scene.emitters = vec![ParticleEmitter {
        name: "sparks".to_owned(),
        particles: vec![good, bad],
    }];
    assert_eq!(
        scene.check_particles().unwrap_err().to_string(),
        "builtin:unlit: emitter \"sparks\" particle 1: alpha 1.5 is not within 0 to 1"
    );
    scene.emitters[0].particles[1] = Particle {
        size: f32::NAN,
        ..good
    };
    assert!(scene
        .check_particles()
        .unwrap_err()
        .to_string()
        .contains("size NaN"));
    scene.emitters[0].particles = vec![good; MAX_PARTICLES + 1];
    assert!(scene
        .check_particles()
        .unwrap_err()
        .to_string()
        .contains("1048577 particles, more than 1048576"));
}

#[test]
fn billboard_pixels_are_the_squares_of_the_projected_diameters_cut_to_the_target() {
    use rgraph_scene::{billboard_pixels, Particle};
    // builtin:unlit's orthographic camera: 2 units across, so 64 pixels a unit at 128.
    let camera = builtin("builtin:unlit").camera;
    let at = |x, size| Particle {
        position: DVec3::new(x, 0.0, 0.0),
        size,
        color: [1.0; 3],
        alpha: 1.0,
        emissive: false,
    };
    let pixels = |particles: &[Particle]| billboard_pixels(particles, &camera, (128, 128));
    assert!((pixels(&[at(0.0, 0.5)]) - 32.0 * 32.0).abs() < 1e-6);
    // Half of it beyond the right edge; twice over when two overlap.
    assert!((pixels(&[at(1.0, 0.5)]) - 16.0 * 32.0).abs() < 1e-6);
    assert!((pixels(&[at(0.0, 0.5), at(0.0, 0.5)]) - 2048.0).abs() < 1e-6);
    assert_eq!(pixels(&[at(5.0, 0.5)]), 0.0);
    // Perspective: the smoke shrinks with its extent as the square of it.
    let smoke = builtin("builtin:smoke");
    let half = builtin("builtin:smoke?extent=50");
    let full = billboard_pixels(smoke.particles(), &smoke.camera, (1280, 720));
    let small = billboard_pixels(half.particles(), &half.camera, (1280, 720));
    assert!(full > 10.0 * 1280.0 * 720.0, "{full}");
    assert!(small < 0.4 * full, "{small} of {full}");
}
