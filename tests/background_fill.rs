//! The scene passes' background fill (common/background.rs): `forward`, `gbuffer` and the
//! light pre-pass's two geometry passes begin their color targets without a clear, and
//! after their meshes a full-screen draw at the far depth, tested for equality, writes
//! each target's clear value where no mesh drew.

use crate::deferred_support::{gpu, Render};

const SIZE: (u32, u32) = (64, 64);
const BACKGROUND: [f32; 3] = [0.25, 0.5, 0.75];

/// A background colour set on the pass that fills it shows exactly (f16 holds these
/// values) in the resolved image's pixels no mesh covers, top left and top right on
/// builtin:spheres, in forward MSAA, in the fragment path's G-buffer (its `hdr` target)
/// and in the light pre-pass's material pass: the fill writes them, where wgpu's
/// first-use zeros would leave black. The plan begins those targets overwritten, not
/// cleared (the light pre-pass's thin G-buffer too).
#[test]
fn a_background_fills_what_no_mesh_draws_in_the_scene_passes() {
    let gpu = gpu();
    let cases = [
        (
            "forward_msaa_4x.ron",
            "params: (shading: pixel),",
            "params: (shading: pixel, background: (0.25, 0.5, 0.75, 1.0)),",
            "color 0: hdr overwrite (not cleared)",
        ),
        (
            "deferred_msaa_4x.ron",
            "plugin: \"gbuffer\",\n            when: \"!unlit_only\",",
            "plugin: \"gbuffer\",\n            when: \"!unlit_only\",\n            params: (background: (0.25, 0.5, 0.75, 1.0)),",
            "color 0: albedo overwrite (not cleared)",
        ),
        (
            "light_prepass_msaa_4x.ron",
            "plugin: \"light_prepass_material\",",
            "plugin: \"light_prepass_material\",\n            params: (background: (0.25, 0.5, 0.75, 1.0)),",
            "color 0: normal overwrite (not cleared)",
        ),
    ];
    for (pipeline, from, to, shown) in cases {
        let hdr = Render::new(pipeline, "builtin:spheres", SIZE)
            .edit(from, to)
            .export_resolved()
            .run(&gpu)
            .hdr(&gpu, "resolved");
        for (x, y) in [(0, 0), (SIZE.0 - 1, 0)] {
            let p = hdr[(y * SIZE.0 + x) as usize];
            assert_eq!(p[..3], BACKGROUND, "{pipeline}: ({x}, {y})");
        }
        let explain = crate::cli_support::rgraph(&[
            "explain",
            "--pipeline",
            &format!("pipelines/{pipeline}"),
            "--scene",
            "builtin:spheres",
            "--size",
            "64x64",
        ])
        .expect(0)
        .stdout;
        assert!(
            explain.contains(shown),
            "{pipeline}: no {shown:?} in:\n{explain}"
        );
    }
}
