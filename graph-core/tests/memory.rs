//! The physical plan: which graph-owned resources share one texture or buffer, and what the
//! frame costs in bytes before and after sharing.

use crate::common;

use common::{plan, tex, CLEAR};
use rgraph_core::types::Features;
use rgraph_core::types::TextureFormat::{
    Bc1RgbaUnorm, Depth24PlusStencil8, Rgba16Float, Rgba8Unorm,
};
use rgraph_core::{
    BufferDesc, BufferRole, CompileOptions, DeviceProfile, GraphBuilder, MemoryReport, Plan, Size,
    TextureDesc,
};

fn physical(plan: &Plan, name: &str) -> Option<usize> {
    plan.find(name).unwrap().physical
}

/// "a" -> "b" -> "c" -> "out", each pass sampling the previous 64x64 rgba8unorm target:
/// "a" is free again when "c" starts, so they share; "b" overlaps both.
fn blur_chain() -> Plan {
    let mut g = GraphBuilder::new();
    let names = ["a", "b", "c", "out"];
    let targets = names.map(|n| g.create_texture(n, tex(Rgba8Unorm)));
    let mut previous = None;
    for (name, target) in names.iter().zip(targets) {
        let mut p = g.add_render_pass(*name);
        if let Some(input) = previous {
            p.sampled(input);
        }
        previous = Some(p.color_output(target, CLEAR));
    }
    g.export(previous.unwrap());
    plan(&g.build())
}

#[test]
fn equal_textures_with_disjoint_lifetimes_share_memory() {
    let plan = blur_chain();
    assert_eq!(physical(&plan, "a"), physical(&plan, "c"));
    let a = physical(&plan, "a").unwrap();
    assert_eq!(
        plan.textures[a].holds,
        [plan.find("a").unwrap().id, plan.find("c").unwrap().id]
    );
}

#[test]
fn textures_with_overlapping_lifetimes_do_not_share() {
    let plan = blur_chain();
    assert_ne!(physical(&plan, "a"), physical(&plan, "b"));
    assert_ne!(physical(&plan, "b"), physical(&plan, "c"));
}

/// "out" is exported (adding COPY_SRC) and so never pooled with the sampled targets.
#[test]
fn textures_with_different_usages_do_not_share() {
    let plan = blur_chain();
    assert_eq!(plan.textures.len(), 3);
    let out = physical(&plan, "out").unwrap();
    assert_eq!(plan.textures[out].holds, [plan.find("out").unwrap().id]);
}

/// Four 64x64 rgba8unorm targets of 16 KiB each live in three textures.
#[test]
fn the_memory_report_counts_bytes_before_and_after_sharing() {
    assert_eq!(
        blur_chain().memory,
        MemoryReport {
            logical_bytes: 4 * 64 * 64 * 4,
            physical_bytes: 3 * 64 * 64 * 4,
        }
    );
}

/// "early" is exported after its only pass; "late" starts after that pass with the same
/// shape and usage, and would fit in its memory if the export did not have to survive
/// the frame.
#[test]
fn an_export_never_lends_its_memory_to_a_later_resource() {
    let mut g = GraphBuilder::new();
    let [early, late, copy] =
        ["early", "late", "copy"].map(|n| g.create_texture(n, tex(Rgba8Unorm)));
    let early = g.add_render_pass("early").color_output(early, CLEAR);
    g.export(early);
    let late = g.add_render_pass("late").color_output(late, CLEAR);
    let mut p = g.add_transfer_pass("copy");
    p.copy_src(late);
    let copy = p.copy_dst(copy);
    g.export(copy);
    let plan = plan(&g.build());

    assert_eq!(
        plan.find("early").unwrap().texture_usage,
        plan.find("late").unwrap().texture_usage
    );
    assert_ne!(physical(&plan, "early"), physical(&plan, "late"));
}

#[test]
fn imports_are_not_allocated() {
    let mut g = GraphBuilder::new();
    let swapchain = g.import_texture("swapchain", tex(Rgba8Unorm));
    g.add_render_pass("draw").color_output(swapchain, CLEAR);
    let plan = plan(&g.build());

    assert_eq!(physical(&plan, "swapchain"), None);
    assert!(plan.textures.is_empty());
    assert_eq!(plan.memory, MemoryReport::default());
}

#[test]
fn equal_buffers_with_disjoint_lifetimes_share_memory() {
    let mut g = GraphBuilder::new();
    let write = BufferRole::Storage {
        read: false,
        write: true,
    };
    let read = BufferRole::Storage {
        read: true,
        write: false,
    };
    let [a, b, c] = ["a", "b", "c"].map(|n| g.create_buffer(n, BufferDesc::new(4096)));
    let a = g.add_compute_pass("make_a").buffer(a, write);
    let mut p = g.add_compute_pass("a_to_b");
    p.buffer(a, read);
    let b = p.buffer(b, write);
    let mut p = g.add_compute_pass("b_to_c");
    p.buffer(b, read);
    let c = p.buffer(c, write);
    let mut p = g.add_compute_pass("use_c");
    p.buffer(c, read);
    p.side_effect();
    let plan = plan(&g.build());

    assert_eq!(physical(&plan, "a"), physical(&plan, "c"));
    assert_ne!(physical(&plan, "a"), physical(&plan, "b"));
    assert_eq!(
        plan.memory,
        MemoryReport {
            logical_bytes: 3 * 4096,
            physical_bytes: 2 * 4096,
        }
    );
}

#[test]
fn relative_sizes_resolve_against_the_output_size() {
    let mut g = GraphBuilder::new();
    let half = TextureDesc::new(Rgba16Float).size(Size::Relative(0.5));
    let full = TextureDesc::new(Rgba16Float);
    g.import_texture("half", half);
    g.import_texture("full", full);
    let graph = g.build();
    let options = CompileOptions {
        output_size: (1279, 721),
        ..CompileOptions::default()
    };
    let plan = graph.compile(&options).unwrap();

    let extent = |name| {
        let shape = plan.find(name).unwrap().texture.unwrap();
        (shape.width, shape.height)
    };
    assert_eq!(extent("half"), (639, 360));
    assert_eq!(extent("full"), (1279, 721));
    assert_eq!(plan.find("half").unwrap().bytes, 639 * 360 * 8);
    assert_eq!(plan.output_size, (1279, 721));
}

/// A buffer sized per sample (a software rasteriser's samples) follows the output as a
/// relative texture does; the plan holds its bytes, which pool as fixed-size ones do,
/// and the device's buffer size limit applies to what the output makes of it. The pass
/// writing it counts its bytes per sample as a render pass counts its attachments'.
#[test]
fn buffers_sized_per_sample_resolve_against_the_output_size() {
    let mut g = GraphBuilder::new();
    let write = BufferRole::Storage {
        read: false,
        write: true,
    };
    let samples = g.create_buffer("samples", BufferDesc::per_sample(8, 4));
    let samples = g.add_compute_pass("raster").buffer(samples, write);
    let mut p = g.add_compute_pass("shade");
    p.buffer(
        samples,
        BufferRole::Storage {
            read: true,
            write: false,
        },
    );
    p.side_effect();
    let graph = g.build();
    let at = |output_size| {
        graph.compile(&CompileOptions {
            output_size,
            ..CompileOptions::default()
        })
    };
    let plan = at((640, 360)).unwrap();
    let planned = plan.find("samples").unwrap();
    assert_eq!(planned.buffer_size, Some(640 * 360 * 32));
    assert_eq!(planned.bytes, 640 * 360 * 32);
    assert_eq!(plan.buffers[planned.physical.unwrap()].size, 640 * 360 * 32);
    let raster = plan.passes.iter().find(|p| p.name == "raster").unwrap();
    assert_eq!(raster.stored_bytes_per_sample, 8);
    // 2^28 bytes is WebGPU's default buffer size limit: 4096 x 2049 x 32 exceeds it.
    let errors = at((4096, 2049)).unwrap_err().to_string();
    assert!(
        errors.contains("\"samples\"")
            && errors.contains("268566528 bytes exceed the buffer size limit"),
        "{errors}"
    );
}

#[test]
fn bytes_count_samples_mips_and_depth_stencil_texels() {
    let mut g = GraphBuilder::new();
    g.import_texture("msaa", tex(Rgba8Unorm).samples(4));
    g.import_texture("mips", tex(Rgba8Unorm).mips(7));
    g.import_texture("depth", tex(Depth24PlusStencil8));
    let plan = plan(&g.build());

    let bytes = |name| plan.find(name).unwrap().bytes;
    assert_eq!(bytes("msaa"), 64 * 64 * 4 * 4);
    assert_eq!(bytes("mips"), (4096 + 1024 + 256 + 64 + 16 + 4 + 1) * 4);
    assert_eq!(bytes("depth"), 64 * 64 * 4);
}

/// BC1 stores a 4x4 block in 8 bytes: a 64x64 texture is 16x16 blocks.
#[test]
fn bytes_of_a_compressed_texture_count_blocks() {
    let mut g = GraphBuilder::new();
    g.import_texture("albedo", tex(Bc1RgbaUnorm).mips(3));
    let mut profile = DeviceProfile::webgpu();
    profile.features = Features::TEXTURE_COMPRESSION_BC;
    let options = CompileOptions {
        profile,
        ..CompileOptions::default()
    };
    let plan = g.build().compile(&options).unwrap();

    assert_eq!(
        plan.find("albedo").unwrap().bytes,
        (16 * 16 + 8 * 8 + 4 * 4) * 8
    );
}

/// A description no device could make (a condition may drop its texture, which the plan
/// still describes) is counted without overflowing: every mip past the smallest is one
/// texel, and a size past u64 saturates.
#[test]
fn any_description_is_counted_without_overflow() {
    // 64x64: 4096 + 1024 + ... + 1 = 5461 texels in 7 mips, then 2041 mips of one texel.
    let desc = TextureDesc::new(Rgba8Unorm).mips(2048);
    assert_eq!(desc.bytes((64, 64)), (5461 + 2041) * 4);
    let huge = TextureDesc::new(Rgba8Unorm).layers(u32::MAX).samples(16);
    assert_eq!(huge.bytes((u32::MAX, u32::MAX)), u64::MAX);
}
