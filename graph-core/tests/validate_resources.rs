//! Resource errors: descriptions no device could create, or that the profile cannot.

use crate::common;

use common::{errors, errors_with, only_error, tex, CLEAR};
use rgraph_core::types::Features;
use rgraph_core::types::TextureFormat::{Bc1RgbaUnorm, Rgba16Float, Rgba8Unorm};
use rgraph_core::{
    BufferDesc, BufferRole, CompileOptions, Condition, DeviceProfile, GraphBuilder, GraphError,
    Size, TextureDesc,
};

/// The error a graph holding nothing but `desc`, imported as "t", reports.
fn texture_error(desc: TextureDesc) -> GraphError {
    let mut g = GraphBuilder::new();
    g.import_texture("t", desc);
    only_error(&g.build())
}

#[test]
fn an_absolute_size_with_a_zero_side_is_zero_sized() {
    let error = texture_error(TextureDesc::new(Rgba8Unorm).size(Size::Absolute(0, 4)));
    assert_eq!(
        error,
        GraphError::ZeroSize {
            resource: "t".into(),
            width: 0,
            height: 4,
        }
    );
    assert_eq!(error.to_string(), r#"texture "t" is zero-sized (0x4)"#);
}

#[test]
fn a_zero_relative_scale_is_zero_sized() {
    let error = texture_error(TextureDesc::new(Rgba8Unorm).size(Size::Relative(0.0)));
    assert_eq!(error.to_string(), r#"texture "t" is zero-sized (0x0)"#);
}

#[test]
fn a_relative_texture_of_an_empty_output_is_zero_sized() {
    let mut g = GraphBuilder::new();
    g.import_texture("t", TextureDesc::new(Rgba8Unorm).size(Size::Relative(0.5)));
    let options = CompileOptions {
        output_size: (0, 1080),
        ..CompileOptions::default()
    };
    // Not one texel, as a tiny scale of a real output would give.
    let errors = errors_with(&g.build(), &options);
    assert_eq!(
        errors.iter().map(ToString::to_string).collect::<Vec<_>>(),
        [r#"texture "t" is zero-sized (0x540)"#]
    );
}

#[test]
fn a_side_over_the_profile_maximum_is_too_large() {
    let error = texture_error(TextureDesc::new(Rgba8Unorm).size(Size::Absolute(8193, 16)));
    assert_eq!(
        error,
        GraphError::TooLarge {
            resource: "t".into(),
            width: 8193,
            height: 16,
            max: 8192,
            profile: "webgpu defaults".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"texture "t" (8193x16) exceeds the maximum dimension 8192 of webgpu defaults"#
    );
}

/// A relative size is checked at the output size it is compiled for.
#[test]
fn a_relative_size_is_too_large_only_for_large_outputs() {
    let mut g = GraphBuilder::new();
    g.import_texture("t", TextureDesc::new(Rgba8Unorm).size(Size::Relative(2.0)));
    let graph = g.build();
    let at = |w, h| CompileOptions {
        output_size: (w, h),
        ..CompileOptions::default()
    };

    assert!(graph.compile(&at(4096, 2160)).is_ok());
    assert_eq!(
        errors_with(&graph, &at(4097, 2160))[0].to_string(),
        r#"texture "t" (8194x4320) exceeds the maximum dimension 8192 of webgpu defaults"#
    );
}

#[test]
fn three_samples_are_never_supported() {
    let error = texture_error(TextureDesc::new(Rgba8Unorm).samples(3));
    assert_eq!(
        error,
        GraphError::UnsupportedSampleCount {
            resource: "t".into(),
            format: "rgba8unorm".into(),
            samples: 3,
            supported: "1x, 4x".into(),
            profile: "webgpu defaults".into(),
        }
    );
    assert_eq!(
        error.to_string(),
        r#"texture "t": rgba8unorm does not support 3x multisampling on webgpu defaults (supported: 1x, 4x)"#
    );
}

#[test]
fn eight_samples_of_rgba16float_need_more_than_webgpu_guarantees() {
    let error = texture_error(TextureDesc::new(Rgba16Float).samples(8));
    assert_eq!(
        error.to_string(),
        r#"texture "t": rgba16float does not support 8x multisampling on webgpu defaults (supported: 1x, 4x)"#
    );
}

#[test]
fn mip_and_layer_counts_must_fit_the_texture_and_the_profile() {
    let cases = [
        (
            tex(Rgba8Unorm).mips(0),
            "mip and layer counts must be at least 1",
        ),
        (
            tex(Rgba8Unorm).mips(8),
            "64x64 has at most 7 mips, 8 were asked for",
        ),
        (
            tex(Rgba8Unorm).layers(257),
            "257 layers exceed the limit of 256 on webgpu defaults",
        ),
        (
            tex(Rgba8Unorm).samples(4).mips(2),
            "a multisampled texture has exactly one mip",
        ),
        (
            tex(Rgba8Unorm).samples(4).layers(2),
            "a multisampled texture has exactly one layer",
        ),
    ];
    for (desc, what) in cases {
        assert_eq!(
            texture_error(desc.clone()),
            GraphError::InvalidResource {
                resource: "t".into(),
                what: what.into(),
            },
            "{desc:?}"
        );
    }
    assert_eq!(
        texture_error(tex(Rgba8Unorm).mips(0)).to_string(),
        r#""t": mip and layer counts must be at least 1"#
    );
}

#[test]
fn a_zero_sized_buffer_is_rejected() {
    let mut g = GraphBuilder::new();
    g.create_buffer("lights", BufferDesc::new(0));
    let error = only_error(&g.build());
    assert_eq!(
        error,
        GraphError::ZeroSizedBuffer {
            resource: "lights".into()
        }
    );
    assert_eq!(error.to_string(), r#"buffer "lights" has size 0"#);
}

#[test]
fn a_buffer_over_the_profile_limit_is_rejected() {
    let mut g = GraphBuilder::new();
    g.create_buffer("huge", BufferDesc::new((256 << 20) + 1));
    assert_eq!(
        only_error(&g.build()).to_string(),
        r#""huge": 268435457 bytes exceed the buffer size limit of 268435456 on webgpu defaults"#
    );
}

/// A buffer the device can make but not bind whole in its role: the compile refuses it
/// naming the pass and the buffer, where the device would fail creating the bind group.
#[test]
fn a_buffer_larger_than_its_binding_limit_is_rejected_naming_it() {
    // An engine's buffer, which the pass reads (and, as storage, writes for later use).
    let bound = |size: u64, role: BufferRole| {
        let mut g = GraphBuilder::new();
        let buffer = g.import_buffer("bins", BufferDesc::new(size));
        let written = g.add_compute_pass("raster").buffer(buffer, role);
        if role != BufferRole::Uniform {
            g.export(written);
        }
        g.build()
    };
    let storage = BufferRole::Storage {
        read: true,
        write: true,
    };
    // WebGPU's defaults: 128 MiB of storage binding, 64 KiB of uniform, 256 MiB of buffer.
    let error = only_error(&bound((128 << 20) + 1, storage));
    assert_eq!(
        error.to_string(),
        "pass \"raster\": buffer \"bins\" (134217729 bytes) is bound as a storage buffer, but \
         webgpu defaults binds at most 134217728 bytes there (max_storage_buffer_binding_size); \
         make it smaller or split it"
    );
    assert_eq!(error.resource(), Some("bins"));
    let options = CompileOptions::default();
    assert!(bound(128 << 20, storage).compile(&options).is_ok());
    let error = only_error(&bound((64 << 10) + 4, BufferRole::Uniform));
    assert!(
        error
            .to_string()
            .contains("is bound as a uniform buffer, but webgpu defaults binds at most 65536"),
        "{error}"
    );
    // A device with more room binds it.
    let mut roomy = DeviceProfile::webgpu();
    roomy.limits.max_storage_buffer_binding_size = 256 << 20;
    let options = CompileOptions {
        profile: roomy,
        ..CompileOptions::default()
    };
    assert!(bound((128 << 20) + 1, storage).compile(&options).is_ok());
}

/// Every problem is reported at once, in declaration order, so a graph file is fixed in
/// one round.
#[test]
fn all_resource_errors_are_reported_together() {
    let mut g = GraphBuilder::new();
    g.import_texture("a", tex(Rgba8Unorm).samples(3));
    g.import_texture("b", TextureDesc::new(Rgba8Unorm).size(Size::Absolute(0, 0)));
    g.import_texture("c", tex(Bc1RgbaUnorm));
    let names: Vec<_> = errors(&g.build())
        .iter()
        .map(|e| e.resource().map(str::to_owned))
        .collect();
    assert_eq!(
        names,
        [Some("a".into()), Some("b".into()), Some("c".into())]
    );
}

#[test]
fn a_format_needs_the_features_it_requires() {
    let error = texture_error(tex(Bc1RgbaUnorm));
    assert_eq!(
        error.to_string(),
        r#""t": bc1-rgba-unorm needs TEXTURE_COMPRESSION_BC, which webgpu defaults lacks"#
    );
    let mut g = GraphBuilder::new();
    g.import_texture("t", tex(Bc1RgbaUnorm));
    let mut profile = DeviceProfile::webgpu();
    profile.features = Features::TEXTURE_COMPRESSION_BC;
    let options = CompileOptions {
        profile,
        ..CompileOptions::default()
    };
    assert!(g.build().compile(&options).is_ok());
}

/// A profile recorded from an adapter that does more than WebGPU guarantees.
#[test]
fn a_profile_with_larger_limits_accepts_what_webgpu_rejects() {
    let mut g = GraphBuilder::new();
    g.import_texture(
        "t",
        TextureDesc::new(Rgba8Unorm).size(Size::Absolute(16384, 16)),
    );
    let mut profile = DeviceProfile::webgpu();
    profile.limits.max_texture_dimension_2d = 16384;
    let options = CompileOptions {
        profile,
        ..CompileOptions::default()
    };
    assert!(g.build().compile(&options).is_ok());
}

/// A graph-owned texture holds nothing until a pass writes it; an import holds the
/// engine's contents, so exporting one unwritten is fine.
#[test]
fn exporting_a_texture_no_pass_writes_is_an_error_unless_imported() {
    let mut g = GraphBuilder::new();
    let t = g.create_texture("history", tex(Rgba8Unorm));
    g.export(t);
    let error = only_error(&g.build());
    assert_eq!(
        error.to_string(),
        r#""history": is exported, but no pass writes it, so its contents would be undefined"#
    );

    let mut g = GraphBuilder::new();
    let t = g.import_texture("engine", tex(Rgba8Unorm));
    g.export(t);
    assert!(g.build().compile(&CompileOptions::default()).is_ok());
}

/// `depth32float-stencil8` needs a feature the WebGPU defaults lack: with a fallback the
/// graph compiles everywhere and gets the better format where the device has it.
#[test]
fn a_fallback_format_is_used_only_where_the_first_choice_is_missing() {
    use rgraph_core::types::TextureFormat::{Depth24PlusStencil8, Depth32FloatStencil8};
    let format_on = |profile: DeviceProfile| {
        let mut g = GraphBuilder::new();
        g.import_texture(
            "depth",
            TextureDesc::new(Depth32FloatStencil8)
                .or(Depth24PlusStencil8)
                .samples(4),
        );
        let options = CompileOptions {
            profile,
            ..CompileOptions::default()
        };
        let plan = g
            .build()
            .compile(&options)
            .expect("compiles with the fallback");
        plan.find("depth").and_then(|r| r.texture).map(|s| s.format)
    };
    assert_eq!(
        format_on(DeviceProfile::webgpu()),
        Some(Depth24PlusStencil8)
    );
    let mut capable = DeviceProfile::webgpu();
    capable.features = Features::DEPTH32FLOAT_STENCIL8;
    assert_eq!(format_on(capable), Some(Depth32FloatStencil8));
}

#[test]
fn a_fallback_of_another_kind_is_an_error() {
    let error = texture_error(tex(Rgba16Float).or(rgraph_core::types::TextureFormat::Rgba8Uint));
    assert_eq!(
        error.to_string(),
        r#""t": fallback rgba8uint is not the same kind of format as rgba16float (aspects and sample type must agree, since passes are written for both)"#
    );
}

/// A texture whose every user a condition drops is not made for those features, so the
/// device need not be able to make it (a file's branch for other devices may use one
/// that only they can make); where its user stays, it is checked as ever.
#[test]
fn a_texture_only_dropped_passes_use_is_not_checked_against_the_device() {
    let mut g = GraphBuilder::new();
    g.declare_features(["elsewhere"]);
    let t = g.create_texture("t", tex(Rgba8Unorm).samples(3));
    g.add_render_pass("only elsewhere")
        .when(Condition::feature("elsewhere"))
        .side_effect()
        .color_output(t, CLEAR);
    let graph = g.build();
    let options = CompileOptions::default();
    let plan = graph
        .compile_for(&options, &rgraph_core::Features::new())
        .expect("without the feature nothing makes t");
    assert!(plan.passes.is_empty());
    let errors = graph
        .compile_for(&options, &rgraph_core::Features::from_iter(["elsewhere"]))
        .expect_err("with it, t's sample count is checked")
        .0;
    assert_eq!(
        errors.iter().map(ToString::to_string).collect::<Vec<_>>(),
        [
            r#"texture "t": rgba8unorm does not support 3x multisampling on webgpu defaults (supported: 1x, 4x)"#
        ]
    );
}
