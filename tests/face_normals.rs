//! A mesh without vertex normals (a glTF primitive without `NORMAL`) keeps its shared
//! vertices, each with the zero normal that asks the renderers for the triangle's face
//! normal (`scene::Vertex`). Every lit path must shade it as it shades the same mesh with
//! the face normals written out at every corner (`rgraph_scene::flat_shaded`, three
//! vertices a triangle), which is how such meshes loaded before. The G-buffer, forward and
//! light pre-pass passes find the face normal from the derivatives of the position, the
//! visibility buffer from the triangle's corners. `builtin:dense` has double-sided grass,
//! so back faces are covered too.

use crate::deferred_support;

use deferred_support::measure::share_within;
use deferred_support::{gpu, Image, Render};
use rgraph_scene::analysis::Features;
use rgraph_scene::{flat_shaded, Scene};

const SIZE: (u32, u32) = (160, 90);

/// Every triangle its own three vertices, each with the face normal.
fn written_out(scene: &mut Scene) {
    for mesh in &mut scene.meshes {
        let (vertices, indices) = flat_shaded(&mesh.vertices, &mesh.indices);
        (mesh.vertices, mesh.indices) = (vertices.into(), indices.into());
    }
}

/// The shared vertices kept, their normals zero.
fn asked_for(scene: &mut Scene) {
    for vertex in scene
        .meshes
        .iter_mut()
        .flat_map(|m| std::sync::Arc::make_mut(&mut m.vertices))
    {
        vertex.normal = [0.0; 3];
    }
}

#[test]
fn face_normals_shade_as_written_out_normals_on_every_path() {
    let scene = Scene::load("builtin:dense").unwrap_or_else(|e| panic!("{e}"));
    let edited = |edit: fn(&mut Scene)| {
        let mut edited = scene.clone();
        edit(&mut edited);
        edited
    };
    let (written, asked) = (edited(written_out), edited(asked_for));
    let gpu = gpu();
    let image = |pipeline: &str, scene: &Scene| -> Image {
        Render::new(pipeline, &scene.name, SIZE)
            .with_scene(scene.clone())
            .features(Features::of(scene).names())
            .run(&gpu)
            .image(&gpu, "color")
    };
    for pipeline in [
        "deferred_msaa_4x.ron",
        "forward_msaa_4x.ron",
        "light_prepass_msaa_4x.ron",
        "visibility_msaa_4x.ron",
    ] {
        let share = share_within(
            &image(pipeline, &written),
            &image(pipeline, &asked),
            1,
            None,
        );
        assert!(
            share >= 0.999,
            "{pipeline}: only {:.2}% of pixels within 1/255 of the written-out face normals",
            100.0 * share
        );
    }
}
