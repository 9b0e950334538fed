//! Material features glTF files bring and the built-in scenes do not: emission, alpha
//! MASK and double-sided surfaces, through deferred_msaa_4x with the fixture
//! `scene/tests/fixtures/hierarchy_embedded.gltf` (one triangle in the
//! plane z = 0 facing +z, material "masked emitter": emission (0.5, 0.25, 0) x strength 4,
//! MASK cutoff 0.3 with base alpha 1, double-sided; no lights; the framing camera looks
//! at its front from +z).

use crate::deferred_support;

use deferred_support::{gpu, Render};
use rgraph_scene::Scene;

const SIZE: (u32, u32) = (64, 64);
const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/scene/tests/fixtures/hierarchy_embedded.gltf"
);
const EMISSION: [f32; 3] = [2.0, 1.0, 0.0];

/// Pixels whose resolved HDR is exactly the emission, and whether any pixel exceeds it.
fn emitting(edit: Option<fn(&mut Scene)>) -> (usize, bool) {
    let gpu = gpu();
    let mut render = Render::new("deferred_msaa_4x.ron", FIXTURE, SIZE).export_resolved();
    if let Some(edit) = edit {
        render = render.scene_edit(edit);
    }
    let hdr = render.run(&gpu).hdr(&gpu, "resolved");
    let full = hdr.iter().filter(|p| p[..3] == EMISSION).count();
    let over = hdr.iter().any(|p| (0..3).any(|c| p[c] > EMISSION[c]));
    (full, over)
}

/// Turns the triangle around the vertical line through its centroid (x = 28/3): same
/// place, its back now towards the camera.
fn turned(scene: &mut Scene) {
    let cx = 28.0 / 3.0;
    let m = &mut scene.meshes[0].transform;
    for column in [&mut m.x_axis, &mut m.y_axis, &mut m.z_axis, &mut m.w_axis] {
        column.x = -column.x;
        column.z = -column.z;
    }
    m.w_axis.x += 2.0 * cx;
}

/// Emission reaches the HDR target once: interior pixels hold exactly it (no lights, no
/// ambient), and no pixel more.
#[test]
fn emission_is_added_once() {
    let (full, over) = emitting(None);
    assert!(
        full > 50,
        "only {full} pixels show the emission {EMISSION:?}"
    );
    assert!(
        !over,
        "some pixel exceeds the emission {EMISSION:?}: added twice?"
    );
}

/// A double-sided material shows its back face; single-sided, the back face is culled.
#[test]
fn double_sided_back_faces_are_drawn_and_single_sided_culled() {
    let (back, _) = emitting(Some(turned));
    assert!(
        back > 50,
        "the double-sided back face shows in only {back} pixels"
    );
    let (culled, _) = emitting(Some(|scene| {
        turned(scene);
        scene.materials[0].double_sided = false;
    }));
    assert_eq!(
        culled, 0,
        "a single-sided back face was drawn in {culled} pixels"
    );
}

/// Alpha MASK: base alpha 1 passes the cutoff 0.3 (above); alpha 0.2 discards every
/// fragment.
#[test]
fn alpha_mask_discards_below_the_cutoff() {
    let (masked, _) = emitting(Some(|scene| {
        scene.materials[0].base_color_factor[3] = 0.2;
    }));
    assert_eq!(
        masked, 0,
        "{masked} pixels drawn with alpha below the cutoff"
    );
}

/// A glTF scene that lists no nodes loads empty (with a warning, see the loader's tests) and
/// every pipeline renders it as the background alone instead of failing on empty buffers.
#[test]
fn scene_without_nodes_renders_the_background() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("deferred_gltf_empty");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("empty.gltf");
    std::fs::write(
        &path,
        r#"{ "asset": { "version": "2.0" }, "scenes": [{}] }"#,
    )
    .unwrap();
    let gpu = gpu();
    for pipeline in [
        "deferred_msaa_4x.ron",
        "deferred_msaa_4x_tiled.ron",
        "forward_msaa_4x.ron",
    ] {
        let image = Render::new(pipeline, path.to_str().unwrap(), SIZE)
            .run(&gpu)
            .image(&gpu, "color");
        let black = image.count([0, 0, 0, 255]);
        assert_eq!(
            black,
            image.pixels.len(),
            "{pipeline}: not every pixel is the black background"
        );
    }
}
