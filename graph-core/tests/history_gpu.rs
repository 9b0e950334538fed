//! Histories on a device (lavapipe unless `RGRAPH_ADAPTER` says otherwise): a counter pass
//! reads the previous frame's count and writes it plus one, so frame N reads N - 1; the
//! first frame reads zeros and is told it is a reset, as is the first frame after a
//! resize, after a change of plan and after `Executor::reset_history`.

use std::cell::RefCell;
use std::rc::Rc;

use rgraph_core::gpu::{read_texture, AdapterChoice, Executor, Gpu, Imports};
use rgraph_core::types::TextureFormat;
use rgraph_core::{
    CompileOptions, CompiledGraph, Features, GraphBuilder, TextureDesc, TextureHandle,
};

const COUNTER: &str = "
@group(0) @binding(0) var previous: texture_2d<f32>;
@group(0) @binding(1) var count: texture_storage_2d<r32float, write>;
@group(0) @binding(2) var seen: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3u) {
    if (any(id.xy >= textureDimensions(count))) { return; }
    let before = textureLoad(previous, id.xy, 0).x;
    textureStore(seen, id.xy, vec4f(before));
    textureStore(count, id.xy, vec4f(before + 1.0));
}";

/// The counter's graph: `count` carried to the next frame as `count_prev`; `seen`, an
/// export, what this frame read. Each frame's reset flag is pushed onto `resets`.
fn counter(resets: Rc<RefCell<Vec<bool>>>) -> (GraphBuilder, TextureHandle, TextureHandle) {
    let mut g = GraphBuilder::new();
    let count = g.create_texture("count", TextureDesc::new(TextureFormat::R32Float));
    let previous = g.history_texture("count_prev", count);
    let seen = g.create_texture("seen", TextureDesc::new(TextureFormat::R32Float));
    let mut pass = g.add_compute_pass("counter");
    pass.sampled(previous);
    let count = pass.storage_write(count);
    let seen = pass.storage_write(seen);
    let mut pipeline = None;
    pass.compute(move |ctx| {
        let r = ctx.resources;
        resets.borrow_mut().push(r.history_reset(previous));
        let pipeline: &wgpu::ComputePipeline = pipeline.get_or_insert_with(|| {
            let module = r.device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("counter"),
                source: wgpu::ShaderSource::Wgsl(COUNTER.into()),
            });
            r.device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("counter"),
                    layout: None,
                    module: &module,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    cache: None,
                })
        });
        let views = [r.view(previous), r.view(count), r.view(seen)];
        let entries: Vec<wgpu::BindGroupEntry> = views
            .iter()
            .enumerate()
            .map(|(i, view)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: wgpu::BindingResource::TextureView(view),
            })
            .collect();
        let group = r.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("counter"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let (w, h) = r.output_size();
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.set_bind_group(0, &group, &[]);
        ctx.pass
            .dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
    });
    g.export(seen);
    (g, count, seen)
}

/// Every texel of an exported r32float texture of the last frame, which must all agree.
fn value(gpu: &Gpu, executor: &Executor, compiled: &CompiledGraph, handle: TextureHandle) -> f32 {
    let texture = executor
        .texture(compiled.plan(), handle.id())
        .expect("readable after the frame");
    let bytes = read_texture(&gpu.device, &gpu.queue, texture).expect("readback");
    let texels: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    assert!(
        texels.iter().all(|&t| t == texels[0]),
        "texels differ: {texels:?}"
    );
    assert_eq!(texels.len() as u32, texture.width() * texture.height());
    texels[0]
}

#[test]
fn a_counter_reads_the_previous_frame_and_resets_on_the_first_frame_and_a_resize() {
    let gpu = Gpu::open(&AdapterChoice::from_env())
        .unwrap_or_else(|e| panic!("this test needs a Vulkan adapter: {e}"));
    let resets = Rc::new(RefCell::new(Vec::new()));
    let (g, count, seen) = counter(resets.clone());
    let small = CompileOptions {
        output_size: (8, 8),
        profile: gpu.profile(),
    };
    let mut compiled = CompiledGraph::new(g.build(), &small).unwrap_or_else(|e| panic!("{e}"));
    let mut executor = Executor::new(&gpu);
    let frame = |compiled: &mut CompiledGraph, executor: &mut Executor| {
        executor
            .execute(compiled, &Imports::new())
            .unwrap_or_else(|e| panic!("{e}"));
        let read = value(&gpu, executor, compiled, seen);
        let written = value(&gpu, executor, compiled, count);
        assert_eq!(written, read + 1.0);
        (read, resets.borrow_mut().pop().expect("the pass ran"))
    };

    // Frame N reads N - 1; the first reads zeros and knows it.
    for n in 1..=4 {
        assert_eq!(
            frame(&mut compiled, &mut executor),
            (n as f32 - 1.0, n == 1),
            "frame {n}"
        );
    }
    // A resize is another plan: its first frame starts over. So does going back to the
    // first size (a change of plan, not the old count), and what the executor cannot see
    // (a camera cut) the engine says with reset_history.
    let large = CompileOptions {
        output_size: (16, 8),
        ..small.clone()
    };
    for restart in ["a resize", "back to 8x8", "reset_history"] {
        match restart {
            "a resize" => {
                compiled.recompile(&large, &Features::new()).unwrap();
            }
            "back to 8x8" => {
                compiled.recompile(&small, &Features::new()).unwrap();
            }
            _ => executor.reset_history(),
        }
        for n in 1..=2 {
            let expected = (n as f32 - 1.0, n == 1);
            let got = frame(&mut compiled, &mut executor);
            assert_eq!(got, expected, "frame {n} after {restart}");
        }
    }
}
