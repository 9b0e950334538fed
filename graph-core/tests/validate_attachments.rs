//! Render-pass attachment rules: how many, how large, how multisampled, and how resolved.

use crate::common;

use common::{only_error, tex, CLEAR};
use rgraph_core::types::TextureFormat::{
    Depth24PlusStencil8, Depth32Float, R32Float, R8Unorm, Rgba16Float, Rgba8Unorm,
};
use rgraph_core::{
    AspectAccess, CompileOptions, DeviceProfile, GraphBuilder, GraphError, Size, TextureDesc,
};

/// A graph whose pass "gbuffer" writes one color target per format, named "rt0", "rt1", ...
fn mrt(formats: &[rgraph_core::types::TextureFormat]) -> rgraph_core::Graph {
    let mut g = GraphBuilder::new();
    let targets: Vec<_> = (0..formats.len())
        .map(|i| g.create_texture(format!("rt{i}"), tex(formats[i])))
        .collect();
    let mut p = g.add_render_pass("gbuffer");
    let written: Vec<_> = targets.iter().map(|&t| p.color_output(t, CLEAR)).collect();
    written.into_iter().for_each(|t| g.export(t));
    g.build()
}

#[test]
fn five_rgba16float_targets_exceed_the_webgpu_color_byte_limit() {
    let error = only_error(&mrt(&[Rgba16Float; 5]));
    assert_eq!(
        error,
        GraphError::ColorBytesPerSample {
            pass: "gbuffer".into(),
            resources: r#""rt0", "rt1", "rt2", "rt3", "rt4""#.into(),
            bytes: 40,
            limit: 32,
            profile: "webgpu defaults".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "gbuffer": color attachments ("rt0", "rt1", "rt2", "rt3", "rt4") take 40 bytes per sample, over the limit of 32 on webgpu defaults"#
    );
}

#[test]
fn five_rgba16float_targets_fit_an_adapter_with_128_bytes_per_sample() {
    let mut profile = DeviceProfile::webgpu();
    profile.name = "llvmpipe".into();
    profile.limits.max_color_attachment_bytes_per_sample = 128;
    let options = CompileOptions {
        profile,
        ..CompileOptions::default()
    };
    assert!(mrt(&[Rgba16Float; 5]).compile(&options).is_ok());
}

/// Each target starts at a multiple of its component alignment: after an r8unorm (1 byte)
/// an rgba16float (8 bytes) starts at 2 and an r32float (4 bytes) at a multiple of 4. These
/// targets take 31 bytes unaligned but 33 aligned, over the limit of 32.
#[test]
fn color_bytes_count_alignment_padding() {
    let fits = [
        R8Unorm,
        Rgba16Float,
        Rgba16Float,
        Rgba16Float,
        R8Unorm,
        R32Float,
    ];
    assert!(mrt(&fits).compile(&CompileOptions::default()).is_ok());

    // The plan reports what a pass that fits costs, for G-buffer economy.
    let plan = mrt(&fits)
        .compile(&CompileOptions::default())
        .expect("fits");
    assert_eq!(plan.passes[0].color_bytes_per_sample, 32);
    assert!(rgraph_core::explain::text(&plan).contains("color bytes per sample: 32"));

    let over = [fits.as_slice(), &[R8Unorm]].concat();
    let error = only_error(&mrt(&over));
    let GraphError::ColorBytesPerSample { bytes, .. } = error else {
        panic!("unexpected {error:?}");
    };
    assert_eq!(bytes, 1 + 1 + 8 + 8 + 8 + 1 + 1 + 4 + 1);
}

#[test]
fn nine_color_attachments_exceed_the_webgpu_limit() {
    let error = only_error(&mrt(&[R8Unorm; 9]));
    assert_eq!(
        error,
        GraphError::TooManyColorAttachments {
            pass: "gbuffer".into(),
            count: 9,
            limit: 8,
            profile: "webgpu defaults".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "gbuffer" has 9 color attachments, over the limit of 8 on webgpu defaults"#
    );
}

#[test]
fn attachments_of_one_pass_must_agree_in_size() {
    let mut g = GraphBuilder::new();
    let color = g.create_texture("color", tex(Rgba8Unorm));
    let depth = g.create_texture(
        "depth",
        TextureDesc::new(Depth32Float).size(Size::Absolute(32, 64)),
    );
    let mut p = g.add_render_pass("opaque");
    let color = p.color_output(color, CLEAR);
    p.depth_stencil(depth, AspectAccess::Clear(1.0), AspectAccess::ReadOnly);
    g.export(color);

    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::AttachmentMismatch {
            pass: "opaque".into(),
            resource: "depth".into(),
            this: "32x64 with 1 sample(s)".into(),
            other: "color".into(),
            that: "64x64 with 1 sample(s)".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "opaque": attachment "depth" is 32x64 with 1 sample(s), but "color" is 64x64 with 1 sample(s); the attachments of one pass must agree in size and sample count"#
    );
}

#[test]
fn attachments_of_one_pass_must_agree_in_sample_count() {
    let mut g = GraphBuilder::new();
    let color = g.create_texture("color", tex(Rgba8Unorm).samples(4));
    let depth = g.create_texture("depth", tex(Depth24PlusStencil8));
    let mut p = g.add_render_pass("opaque");
    let color = p.color_output(color, CLEAR);
    p.depth_stencil(depth, AspectAccess::Clear(1.0), AspectAccess::Clear(0));
    g.export(color);

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"pass "opaque": attachment "depth" is 64x64 with 1 sample(s), but "color" is 64x64 with 4 sample(s); the attachments of one pass must agree in size and sample count"#
    );
}

#[test]
fn a_render_pass_needs_an_attachment() {
    let mut g = GraphBuilder::new();
    let t = g.import_texture("t", tex(Rgba8Unorm));
    let mut p = g.add_render_pass("empty");
    p.sampled(t);
    p.side_effect();

    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::NoAttachment {
            pass: "empty".into()
        }
    );
    assert_eq!(
        error.to_string(),
        r#"render pass "empty" has no attachment"#
    );
}

#[test]
fn a_render_pass_has_at_most_one_depth_stencil_attachment() {
    let mut g = GraphBuilder::new();
    let a = g.create_texture("a", tex(Depth32Float));
    let b = g.create_texture("b", tex(Depth32Float));
    let mut p = g.add_render_pass("shadow");
    let a = p.depth_stencil(a, AspectAccess::Clear(1.0), AspectAccess::ReadOnly);
    let b = p.depth_stencil(b, AspectAccess::Clear(1.0), AspectAccess::ReadOnly);
    g.export(a);
    g.export(b);

    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::TwoDepthStencil {
            pass: "shadow".into(),
            first: "a".into(),
            second: "b".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"render pass "shadow" attaches both "a" and "b" as depth-stencil; a render pass has one depth-stencil attachment"#
    );
}

/// The single error of a pass "resolve" that clears a color target "msaa" described by
/// `source` and resolves it into "target" described by `target`.
fn resolve_error(source: TextureDesc, target: TextureDesc) -> GraphError {
    let mut g = GraphBuilder::new();
    let msaa = g.create_texture("msaa", source);
    let out = g.create_texture("target", target);
    let mut p = g.add_render_pass("resolve");
    let msaa = p.color_output(msaa, CLEAR);
    let out = p.resolve_output(msaa, out);
    g.export(out);
    only_error(&g.build())
}

#[test]
fn resolving_a_single_sampled_target_is_rejected() {
    let error = resolve_error(tex(Rgba8Unorm), tex(Rgba8Unorm));
    assert_eq!(
        error,
        GraphError::BadResolve {
            pass: "resolve".into(),
            resource: "target".into(),
            why: r#"its source "msaa" is not multisampled"#.into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"pass "resolve" resolves into "target": its source "msaa" is not multisampled"#
    );
}

#[test]
fn a_resolve_keeps_the_format() {
    assert_eq!(
        resolve_error(tex(Rgba8Unorm).samples(4), tex(Rgba16Float)).to_string(),
        r#"pass "resolve" resolves into "target": the formats differ (rgba8unorm into rgba16float)"#
    );
}

#[test]
fn a_resolve_keeps_the_size() {
    let half = TextureDesc::new(Rgba8Unorm).size(Size::Absolute(32, 32));
    assert_eq!(
        resolve_error(tex(Rgba8Unorm).samples(4), half).to_string(),
        r#"pass "resolve" resolves into "target": the sizes differ (64x64 into 32x32)"#
    );
}

#[test]
fn a_resolve_target_is_single_sampled() {
    assert_eq!(
        resolve_error(tex(Rgba8Unorm).samples(4), tex(Rgba8Unorm).samples(4)).to_string(),
        r#"pass "resolve" resolves into "target": a resolve target must have 1 sample, it has 4"#
    );
}

#[test]
fn r32float_is_not_resolvable_on_webgpu() {
    assert_eq!(
        resolve_error(tex(R32Float).samples(4), tex(R32Float)).to_string(),
        r#"pass "resolve" resolves into "target": r32float is not resolvable on webgpu defaults"#
    );
}

#[test]
fn a_resolve_names_a_color_target_of_its_own_pass() {
    let mut g = GraphBuilder::new();
    let msaa = g.create_texture("msaa", tex(Rgba8Unorm).samples(4));
    let other = g.create_texture("other", tex(Rgba8Unorm).samples(4));
    let out = g.create_texture("target", tex(Rgba8Unorm));
    let msaa = g.add_render_pass("draw").color_output(msaa, CLEAR);
    let mut p = g.add_render_pass("resolve");
    let other = p.color_output(other, CLEAR);
    let out = p.resolve_output(msaa, out);
    g.export(out);
    g.export(other);

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"pass "resolve" resolves into "target": the color handle it names is not a color attachment written by this pass"#
    );
}

#[test]
fn a_color_target_resolves_into_one_target() {
    let mut g = GraphBuilder::new();
    let msaa = g.create_texture("msaa", tex(Rgba8Unorm).samples(4));
    let a = g.create_texture("a", tex(Rgba8Unorm));
    let b = g.create_texture("b", tex(Rgba8Unorm));
    let mut p = g.add_render_pass("resolve");
    let msaa = p.color_output(msaa, CLEAR);
    let a = p.resolve_output(msaa, a);
    let b = p.resolve_output(msaa, b);
    g.export(a);
    g.export(b);

    assert_eq!(
        only_error(&g.build()).to_string(),
        r#"pass "resolve" resolves into "b": "msaa" already resolves into "a""#
    );
}

/// A depth-only pass's explain line says its stored bytes are the depth-stencil's (not
/// buffers sized per sample, as a compute rasteriser's are).
#[test]
fn a_depth_only_pass_stores_its_depth_stencil() {
    let mut g = GraphBuilder::new();
    let depth = g.create_texture("depth", tex(Depth32Float));
    let mut p = g.add_render_pass("prepass");
    let written = p.depth_stencil(depth, AspectAccess::Clear(0.0), AspectAccess::ReadOnly);
    g.export(written);
    let plan = g
        .build()
        .compile(&CompileOptions::default())
        .expect("compiles");
    assert_eq!(plan.passes[0].stored_bytes_per_sample, 4);
    let text = rgraph_core::explain::text(&plan);
    assert!(
        text.contains("stored bytes per sample: 4 (the depth-stencil)"),
        "{text}"
    );
}
