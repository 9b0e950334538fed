//! The light passes' inside-or-outside choice (no GPU): front faces of a light volume are
//! drawn only when the camera's near plane cannot cut the volume, else back faces with the
//! depth test reversed. The margin is the distance from the eye to the near plane's
//! farthest corner.

use rgraph_passes::gpu_scene::camera_may_be_inside;
use rgraph_scene::{BoundingSphere, Projection, Scene};

/// builtin:spheres' camera: perspective, 45° vertical field of view, near plane 0.1. At a
/// square output the near plane's corners are 0.1 * sqrt(1 + 2 tan²(22.5°)) = 0.1159 from
/// the eye. Bounds are camera-relative: the eye is at the origin.
#[test]
fn near_plane_margin_decides_inside() {
    let camera = Scene::load("builtin:spheres")
        .expect("builtin:spheres loads")
        .camera;
    let Projection::Perspective { znear, .. } = camera.projection else {
        panic!("builtin:spheres has a perspective camera");
    };
    assert_eq!(
        znear, 0.1,
        "the cases below assume builtin:spheres' near plane"
    );
    let forward = camera.forward();
    let side = forward.any_orthonormal_vector();
    let cases = [
        // A unit sphere whose surface is 0.05 ahead: nearer than the near plane.
        ("0.05 ahead", forward * 1.05, true),
        // 0.05 to the side: the near plane's corner region reaches it.
        ("0.05 beside", side * 1.05, true),
        // 0.11 ahead, inside the corner distance 0.1159: conservatively inside.
        ("0.11 ahead", forward * 1.11, true),
        // 0.12 ahead, beyond every near-plane point.
        ("0.12 ahead", forward * 1.12, false),
        ("behind", -forward * 3.0, false),
        // The eye inside the volume.
        ("around the eye", forward * 0.5, true),
    ];
    for (what, center, inside) in cases {
        let bounds = BoundingSphere {
            center,
            radius: 1.0,
        };
        assert_eq!(
            camera_may_be_inside(&camera, 1.0, &bounds),
            inside,
            "a unit sphere {what} of the eye"
        );
    }
}
