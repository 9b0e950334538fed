//! Executing graphs on a real device (lavapipe unless RGRAPH_ADAPTER says otherwise) and
//! checking the pixels: clears, compute, sampling, copies, MSAA resolve, the pool across
//! frames, imports, and device errors surfacing as errors.

use crate::common;

use common::{
    bind_group, compile, compute_pipeline, gpu, render_pipeline, render_pipeline_with,
    FULLSCREEN_VS, SIZE,
};
use rgraph_core::gpu::{
    read_rgba8, read_texture, AdapterChoice, DeviceError, ExecuteError, Executor, Gpu, ImportError,
    Imports, ReadbackError, KEEP_FRAMES,
};
use rgraph_core::{
    Aspect, AspectAccess, BufferDesc, BufferHandle, BufferRole, ColorLoad, CompileOptions,
    CompiledGraph, Features, Graph, GraphBuilder, Size, TextureDesc, TextureHandle,
};
use wgpu::{TextureFormat, TextureUsages};

fn tex(format: TextureFormat) -> TextureDesc {
    TextureDesc::new(format).size(Size::Absolute(SIZE.0, SIZE.1))
}

/// Texel `(x, y)` of tightly packed RGBA8 rows.
fn texel(pixels: &[u8], x: u32, y: u32) -> [u8; 4] {
    let i = ((y * SIZE.0 + x) * 4) as usize;
    [pixels[i], pixels[i + 1], pixels[i + 2], pixels[i + 3]]
}

/// Executes one frame and reads back the exported texture `out`.
fn execute_and_read(gpu: &Gpu, compiled: &mut CompiledGraph, out: TextureHandle) -> Vec<u8> {
    let mut executor = Executor::new(gpu);
    executor
        .execute(compiled, &Imports::new())
        .unwrap_or_else(|e| panic!("execution failed: {e}"));
    let texture = executor
        .texture(compiled.plan(), out.id())
        .expect("an exported texture is readable after the frame");
    read_texture(&gpu.device, &gpu.queue, texture).expect("readback")
}

/// A compute pass writing `(x, y)` into every texel of `target`: as integers into an
/// `Rgba8Uint` texture (blue `x ^ y`, alpha 7), as `x / 255, y / 255` into an
/// `Rgba8Unorm` one (blue 0, alpha 1), so both read back as exact bytes.
fn gradient(g: &mut GraphBuilder, target: TextureHandle, integer: bool) -> TextureHandle {
    let wgsl = if integer {
        "@group(0) @binding(0) var out: texture_storage_2d<rgba8uint, write>;
         fn value(p: vec2u) -> vec4u { return vec4u(p.x, p.y, p.x ^ p.y, 7u); }"
    } else {
        "@group(0) @binding(0) var out: texture_storage_2d<rgba8unorm, write>;
         fn value(p: vec2u) -> vec4f { return vec4f(vec2f(p) / 255.0, 0.0, 1.0); }"
    }
    .to_string()
        + "
        @compute @workgroup_size(8, 8)
        fn main(@builtin(global_invocation_id) id: vec3u) {
            if (any(id.xy >= textureDimensions(out))) { return; }
            textureStore(out, id.xy, value(id.xy));
        }";
    let mut pass = g.add_compute_pass("gradient");
    let out = pass.storage_write(target);
    let mut pipeline = None;
    pass.compute(move |ctx| {
        let device = ctx.resources.device;
        let pipeline = pipeline.get_or_insert_with(|| compute_pipeline(device, &wgsl));
        let bind = bind_group(
            device,
            &pipeline.get_bind_group_layout(0),
            &[wgpu::BindingResource::TextureView(ctx.resources.view(out))],
        );
        let shape = ctx.resources.shape(out);
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.set_bind_group(0, &bind, &[]);
        ctx.pass
            .dispatch_workgroups(shape.width.div_ceil(8), shape.height.div_ceil(8), 1);
    });
    out
}

/// A full-screen render pass writing texel `(x, y)` of `src` into `target`, plus the
/// first `vec4f` of `offset` when given (a uniform buffer).
fn copy_pass(
    g: &mut GraphBuilder,
    name: &str,
    src: TextureHandle,
    target: TextureHandle,
    offset: Option<BufferHandle>,
) -> TextureHandle {
    let wgsl = format!(
        "{FULLSCREEN_VS}
        @group(0) @binding(0) var src: texture_2d<f32>;
        {}
        @fragment
        fn fs(@builtin(position) p: vec4f) -> @location(0) vec4f {{
            return textureLoad(src, vec2i(p.xy), 0){};
        }}",
        if offset.is_some() {
            "@group(0) @binding(1) var<uniform> offset: vec4f;"
        } else {
            ""
        },
        if offset.is_some() { " + offset" } else { "" },
    );
    let mut pass = g.add_render_pass(name);
    pass.sampled(src);
    if let Some(buffer) = offset {
        pass.buffer(buffer, BufferRole::Uniform);
    }
    let out = pass.color_output(target, ColorLoad::Clear([0.0; 4]));
    let mut pipeline = None;
    pass.render(move |ctx| {
        let device = ctx.resources.device;
        let format = ctx.resources.shape(out).format;
        let pipeline = pipeline.get_or_insert_with(|| render_pipeline(device, &wgsl, format, 1));
        let mut resources = vec![wgpu::BindingResource::TextureView(ctx.resources.view(src))];
        if let Some(buffer) = offset {
            resources.push(ctx.resources.buffer(buffer).as_entire_binding());
        }
        let bind = bind_group(device, &pipeline.get_bind_group_layout(0), &resources);
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.set_bind_group(0, &bind, &[]);
        ctx.pass.draw(0..3, 0..1);
    });
    out
}

#[test]
fn a_clear_pass_without_callback_fills_the_exported_texture() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let target = g.create_texture("target", tex(TextureFormat::Rgba8Unorm));
    let out = g
        .add_render_pass("clear")
        .color_output(target, ColorLoad::Clear([0.2, 0.6, 1.0, 1.0]));
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);

    let pixels = execute_and_read(&gpu, &mut compiled, out);
    assert_eq!(pixels.len(), (SIZE.0 * SIZE.1 * 4) as usize);
    assert!(
        pixels.chunks_exact(4).all(|p| p == [51, 153, 255, 255]),
        "first texel {:?}",
        &pixels[..4]
    );
}

#[test]
fn a_compute_pass_writes_a_storage_texture() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let target = g.create_texture("gradient", tex(TextureFormat::Rgba8Uint));
    let out = gradient(&mut g, target, true);
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);

    let pixels = execute_and_read(&gpu, &mut compiled, out);
    for (x, y) in [(0, 0), (1, 0), (0, 1), (17, 42), (63, 63)] {
        assert_eq!(
            texel(&pixels, x, y),
            [x as u8, y as u8, (x ^ y) as u8, 7],
            "texel ({x}, {y})"
        );
    }
    let wrong = (0..SIZE.1)
        .flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
        .filter(|&(x, y)| texel(&pixels, x, y) != [x as u8, y as u8, (x ^ y) as u8, 7])
        .count();
    assert_eq!(wrong, 0, "texels that differ from the gradient");
}

#[test]
fn a_fullscreen_pass_samples_another_texture() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let source = g.create_texture("source", tex(TextureFormat::Rgba8Unorm));
    let source = gradient(&mut g, source, false);
    let target = g.create_texture("swizzled", tex(TextureFormat::Rgba8Unorm));
    let shader = format!(
        "{FULLSCREEN_VS}
        @group(0) @binding(0) var src: texture_2d<f32>;
        @group(0) @binding(1) var nearest: sampler;
        @fragment
        fn fs(@builtin(position) p: vec4f) -> @location(0) vec4f {{
            let c = textureSample(src, nearest, p.xy / vec2f(textureDimensions(src)));
            return vec4f(c.g, c.r, 0.0, 1.0);
        }}"
    );
    let mut pass = g.add_render_pass("swizzle");
    pass.sampled(source);
    let out = pass.color_output(target, ColorLoad::Clear([0.0; 4]));
    let mut state = None;
    pass.render(move |ctx| {
        let device = ctx.resources.device;
        let (pipeline, sampler) = state.get_or_insert_with(|| {
            (
                render_pipeline(device, &shader, TextureFormat::Rgba8Unorm, 1),
                // The default sampler filters nearest: texel centers come back exactly.
                device.create_sampler(&wgpu::SamplerDescriptor::default()),
            )
        });
        let bind = bind_group(
            device,
            &pipeline.get_bind_group_layout(0),
            &[
                wgpu::BindingResource::TextureView(ctx.resources.view(source)),
                wgpu::BindingResource::Sampler(sampler),
            ],
        );
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.set_bind_group(0, &bind, &[]);
        ctx.pass.draw(0..3, 0..1);
    });
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);

    let pixels = execute_and_read(&gpu, &mut compiled, out);
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            assert_eq!(
                texel(&pixels, x, y),
                [y as u8, x as u8, 0, 255],
                "texel ({x}, {y})"
            );
        }
    }
}

#[test]
fn a_transfer_pass_copies_a_texture_and_every_pass_is_timed() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let source = g.create_texture("source", tex(TextureFormat::Rgba8Unorm));
    let source = gradient(&mut g, source, false);
    let copy = g.create_texture("copy", tex(TextureFormat::Rgba8Unorm));
    let mut pass = g.add_transfer_pass("copy");
    pass.copy_src(source);
    let out = pass.copy_dst(copy);
    pass.transfer(move |ctx| {
        let (from, to) = (ctx.resources.texture(source), ctx.resources.texture(out));
        ctx.encoder
            .copy_texture_to_texture(from.as_image_copy(), to.as_image_copy(), from.size());
    });
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);

    let mut executor = Executor::new(&gpu);
    let report = executor
        .execute(&mut compiled, &Imports::new())
        .unwrap_or_else(|e| panic!("{e}"));
    let texture = executor
        .texture(compiled.plan(), out.id())
        .expect("exported");
    let pixels = read_texture(&gpu.device, &gpu.queue, texture).expect("readback");
    for (x, y) in [(0, 0), (5, 9), (63, 0), (0, 63), (63, 63)] {
        assert_eq!(
            texel(&pixels, x, y),
            [x as u8, y as u8, 0, 255],
            "texel ({x}, {y})"
        );
    }

    let names: Vec<&str> = report.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["gradient", "copy"]);
    let timestamps =
        wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS;
    if gpu.device.features().contains(timestamps) {
        assert!(
            report.passes.iter().all(|p| p.gpu_ns.is_some()),
            "{report:#?}"
        );
        let longest = report.passes.iter().filter_map(|p| p.gpu_ns).max();
        assert!(report.gpu_total_ns >= longest, "{report:#?}");
    }
}

#[test]
fn msaa_resolve_shows_partial_coverage_on_the_edge() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let msaa = g.create_texture("msaa", tex(TextureFormat::Rgba8Unorm).samples(4));
    let resolved = g.create_texture("resolved", tex(TextureFormat::Rgba8Unorm));
    // Top-left, bottom-right, bottom-left: covers the texels below the diagonal y = x
    // (framebuffer y points down). Texel (i, i) has two of its four standard sample
    // positions on each side of the edge.
    let shader = "
        @vertex
        fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
            var corners = array(vec2f(-1.0, 1.0), vec2f(1.0, -1.0), vec2f(-1.0, -1.0));
            return vec4f(corners[i], 0.0, 1.0);
        }
        @fragment
        fn fs() -> @location(0) vec4f { return vec4f(1.0); }";
    let mut pass = g.add_render_pass("triangle");
    let color = pass.color_output(msaa, ColorLoad::Clear([0.0; 4]));
    let out = pass.resolve_output(color, resolved);
    let mut pipeline = None;
    pass.render(move |ctx| {
        let device = ctx.resources.device;
        let pipeline = pipeline
            .get_or_insert_with(|| render_pipeline(device, shader, TextureFormat::Rgba8Unorm, 4));
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.draw(0..3, 0..1);
    });
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);
    // The multisampled target never leaves its pass: the executor must create it with
    // the transient usage the plan asks for.
    assert!(compiled
        .plan()
        .resource(msaa.id())
        .texture_usage
        .contains(TextureUsages::TRANSIENT_ATTACHMENT));

    let pixels = execute_and_read(&gpu, &mut compiled, out);
    assert_eq!(texel(&pixels, 5, 50), [255; 4], "covered texel");
    assert_eq!(texel(&pixels, 50, 5), [0; 4], "uncovered texel");
    for i in 0..SIZE.0 {
        let [r, g, b, a] = texel(&pixels, i, i);
        assert!(
            (1..255).contains(&r) && r == g && g == b && b == a,
            "edge texel ({i}, {i}) should resolve strictly between black and white, got {:?}",
            [r, g, b, a]
        );
    }
}

/// A triangle at `z` over the texels below the diagonal y = x (framebuffer y down), or
/// a full-screen one; fragments write `vec4f(depth of src at the texel, 0, 0, 1)`.
fn depth_shaders(z: f32, fullscreen: bool) -> String {
    let corners = if fullscreen {
        "vec2f(-1.0, -1.0), vec2f(3.0, -1.0), vec2f(-1.0, 3.0)"
    } else {
        "vec2f(-1.0, 1.0), vec2f(1.0, -1.0), vec2f(-1.0, -1.0)"
    };
    format!(
        "@group(0) @binding(0) var depth: texture_depth_2d;
        @vertex
        fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {{
            var corners = array({corners});
            return vec4f(corners[i], {z:?}, 1.0);
        }}
        @fragment
        fn fs(@builtin(position) p: vec4f) -> @location(0) vec4f {{
            return vec4f(textureLoad(depth, vec2i(p.xy), 0), 0.0, 0.0, 1.0);
        }}"
    )
}

#[test]
fn a_read_only_depth_attachment_is_tested_against_and_sampled_in_one_pass() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let format = TextureFormat::Depth24PlusStencil8;
    let depth = g.create_texture("depth", tex(format));
    let color = g.create_texture("color", tex(TextureFormat::Rgba8Unorm));

    // Depth 0.25 where the half triangle covers, the 1.0 clear elsewhere. The stencil is
    // not touched: its clear is the only thing that makes it defined.
    let mut prepass = g.add_render_pass("depth prepass");
    let depth = prepass.depth_stencil(depth, AspectAccess::Clear(1.0), AspectAccess::Clear(0));
    let mut pipeline = None;
    prepass.render(move |ctx| {
        let device = ctx.resources.device;
        let pipeline = pipeline.get_or_insert_with(|| {
            let state = wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            };
            // No color target: only the vertex stage of the module is used.
            render_pipeline_with(device, &depth_shaders(0.25, false), None, 1, Some(state))
        });
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.draw(0..3, 0..1);
    });

    // Full screen at z = 0.5 with `Greater`: only where the prepass left 0.25 passes, and
    // there the shader writes the sampled depth. Both aspects read-only, so the same
    // texture can be attached and sampled.
    let mut shade = g.add_render_pass("shade");
    shade.depth_stencil(depth, AspectAccess::ReadOnly, AspectAccess::ReadOnly);
    shade.sampled_aspect(depth, Aspect::DepthOnly);
    let out = shade.color_output(color, ColorLoad::Clear([0.0; 4]));
    let mut pipeline = None;
    shade.render(move |ctx| {
        let device = ctx.resources.device;
        let pipeline = pipeline.get_or_insert_with(|| {
            let state = wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: Default::default(),
                bias: Default::default(),
            };
            let wgsl = depth_shaders(0.5, true);
            render_pipeline_with(
                device,
                &wgsl,
                Some(TextureFormat::Rgba8Unorm),
                1,
                Some(state),
            )
        });
        let bind = bind_group(
            device,
            &pipeline.get_bind_group_layout(0),
            &[wgpu::BindingResource::TextureView(
                ctx.resources.aspect_view(depth, Aspect::DepthOnly),
            )],
        );
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.set_bind_group(0, &bind, &[]);
        ctx.pass.draw(0..3, 0..1);
    });
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);
    let attached = compiled
        .plan()
        .pass("shade")
        .and_then(|p| p.depth_stencil.as_ref());
    assert!(
        attached.is_some_and(|ds| ds.depth.is_none() && ds.stencil.is_none()),
        "{attached:?}"
    );

    let pixels = execute_and_read(&gpu, &mut compiled, out);
    assert_eq!(
        texel(&pixels, 5, 50),
        [64, 0, 0, 255],
        "covered: depth 0.25"
    );
    assert_eq!(
        texel(&pixels, 50, 5),
        [0; 4],
        "uncovered: depth test failed"
    );
}

#[test]
fn the_pool_reuses_everything_from_the_second_frame_on() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let rgba = tex(TextureFormat::Rgba8Unorm);
    let params = g.create_buffer("params", BufferDesc::new(16));
    let mut clear = g.add_transfer_pass("zero params");
    let params = clear.buffer(params, BufferRole::CopyDst);
    clear.transfer(move |ctx| {
        ctx.encoder
            .clear_buffer(ctx.resources.buffer(params), 0, None)
    });
    let first = g.create_texture("first", rgba.clone());
    let second = g.create_texture("second", rgba.clone());
    let third = g.create_texture("third", rgba.clone());
    let last = g.create_texture("last", rgba);
    let a = g
        .add_render_pass("fill")
        .color_output(first, ColorLoad::Clear([0.2, 0.4, 0.6, 0.8]));
    let b = copy_pass(&mut g, "first to second", a, second, Some(params));
    let c = copy_pass(&mut g, "second to third", b, third, None);
    let out = copy_pass(&mut g, "third to last", c, last, None);
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);
    let plan = compiled.plan();

    // "first" dies where "third" is born, and both have the same descriptor and usages:
    // they share one texture; "second" overlaps both, and "last" is exported.
    assert_eq!(
        plan.resource(first.id()).physical,
        plan.resource(third.id()).physical,
        "{}",
        rgraph_core::explain::text(plan)
    );
    assert_eq!(plan.textures.len(), 3);
    assert_eq!(plan.buffers.len(), 1);

    let mut executor = Executor::new(&gpu);
    for frame in 1..=3 {
        let report = executor
            .execute(&mut compiled, &Imports::new())
            .unwrap_or_else(|e| panic!("frame {frame}: {e}"));
        let (textures, buffers) = if frame == 1 { (3, 1) } else { (0, 0) };
        assert_eq!(
            (report.textures_allocated, report.buffers_allocated),
            (textures, buffers),
            "allocations in frame {frame}"
        );
        let texture = executor
            .texture(compiled.plan(), out.id())
            .expect("exported");
        let pixels = read_texture(&gpu.device, &gpu.queue, texture).expect("readback");
        assert_eq!(texel(&pixels, 10, 20), [51, 102, 153, 204], "frame {frame}");
    }
    let stats = executor.pool_stats();
    assert_eq!((stats.textures_allocated, stats.buffers_allocated), (3, 1));
    assert_eq!((stats.textures_alive, stats.buffers_alive), (3, 1));
}

#[test]
fn the_pool_frees_what_no_frame_used_for_a_while() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    // Output-sized, so compiling at another size changes its descriptor.
    let target = g.create_texture("target", TextureDesc::new(TextureFormat::Rgba8Unorm));
    let out = g
        .add_render_pass("clear")
        .color_output(target, ColorLoad::Clear([0.0; 4]));
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);

    let mut executor = Executor::new(&gpu);
    let mut run = |compiled: &mut CompiledGraph, size| {
        let options = CompileOptions {
            output_size: size,
            profile: gpu.profile(),
        };
        compiled
            .recompile(&options, &Features::new())
            .unwrap_or_else(|e| panic!("{e}"));
        executor
            .execute(compiled, &Imports::new())
            .unwrap_or_else(|e| panic!("{e}"));
        executor.pool_stats()
    };
    let small = (16, 16);
    assert_eq!(run(&mut compiled, SIZE).textures_alive, 1);
    // After a resize the old size lingers for a few frames, in case it comes back.
    assert_eq!(run(&mut compiled, small).textures_alive, 2);
    let mut stats = run(&mut compiled, small);
    for _ in 0..KEEP_FRAMES {
        stats = run(&mut compiled, small);
    }
    assert_eq!((stats.textures_alive, stats.textures_allocated), (1, 2));
    // Each size compiled once; going back to one recompiles nothing.
    assert_eq!((compiled.plans().misses(), compiled.plans().len()), (2, 2));
}

/// A graph that clears the engine's texture "backbuffer".
fn clear_import() -> (Graph, TextureHandle) {
    let mut g = GraphBuilder::new();
    let backbuffer = g.import_texture("backbuffer", tex(TextureFormat::Rgba8Unorm));
    g.add_render_pass("clear")
        .color_output(backbuffer, ColorLoad::Clear([1.0, 0.0, 0.2, 1.0]));
    (g.build(), backbuffer)
}

fn engine_texture(gpu: &Gpu, size: (u32, u32)) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("engine backbuffer"),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: TextureFormat::Rgba8Unorm,
        usage: TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

#[test]
fn an_imported_texture_is_written_by_the_graph() {
    let gpu = gpu();
    let (graph, backbuffer) = clear_import();
    let mut compiled = compile(graph, &gpu);
    let mut executor = Executor::new(&gpu);
    let engine = engine_texture(&gpu, SIZE);

    executor
        .execute(&mut compiled, Imports::new().texture("backbuffer", &engine))
        .unwrap_or_else(|e| panic!("{e}"));
    let pixels = read_rgba8(&gpu.device, &gpu.queue, &engine).expect("readback");
    assert!(
        pixels.iter().all(|&p| p == [255, 0, 51, 255]),
        "{:?}",
        pixels[0]
    );
    assert!(
        executor.texture(compiled.plan(), backbuffer.id()).is_none(),
        "the engine owns it"
    );

    // A ready-made view (a swap-chain image, say) works the same, bound by handle.
    let other = engine_texture(&gpu, SIZE);
    let view = other.create_view(&Default::default());
    executor
        .execute(&mut compiled, Imports::new().view(backbuffer, &view))
        .unwrap_or_else(|e| panic!("{e}"));
    let pixels = read_rgba8(&gpu.device, &gpu.queue, &other).expect("readback");
    assert_eq!(pixels[100], [255, 0, 51, 255]);
}

#[test]
fn a_missing_or_mismatched_import_is_a_clear_error() {
    let gpu = gpu();
    let (graph, _) = clear_import();
    let mut compiled = compile(graph, &gpu);
    let mut executor = Executor::new(&gpu);

    let missing = executor
        .execute(&mut compiled, &Imports::new())
        .expect_err("nothing is bound");
    assert!(
        matches!(&missing, ExecuteError::Import(ImportError::Missing { resource, pass })
            if resource == "backbuffer" && pass == "clear"),
        "{missing:?}"
    );
    assert!(missing.to_string().contains("\"backbuffer\""), "{missing}");

    let small = engine_texture(&gpu, (32, 32));
    let wrong = executor
        .execute(&mut compiled, Imports::new().texture("backbuffer", &small))
        .expect_err("wrong size");
    assert!(
        matches!(&wrong, ExecuteError::Import(ImportError::Shape { resource, .. }) if resource == "backbuffer"),
        "{wrong:?}"
    );
    assert!(wrong.to_string().contains("32x32"), "{wrong}");

    let unknown = executor
        .execute(&mut compiled, Imports::new().texture("frontbuffer", &small))
        .expect_err("no such resource");
    assert!(unknown.to_string().contains("\"frontbuffer\""), "{unknown}");
}

/// "hdr" cleared by one pass (version 1) and sampled by "light tiled", which draws into
/// "target"; the callback of "light tiled" looks up what `lookup` returns of the handles
/// of "hdr" (version 0, 1) and of another texture, "other", that the pass does not use.
fn lookup_graph(
    lookup: impl Fn(&rgraph_core::gpu::FrameResources<'_>, [TextureHandle; 3]) + 'static,
) -> Graph {
    let mut g = GraphBuilder::new();
    let hdr = g.create_texture("hdr", tex(TextureFormat::Rgba16Float));
    let cleared = g
        .add_render_pass("clear hdr")
        .color_output(hdr, ColorLoad::Clear([0.0; 4]));
    let other = g.create_texture("other", tex(TextureFormat::Rgba8Unorm));
    let other = g
        .add_render_pass("clear other")
        .color_output(other, ColorLoad::Clear([0.0; 4]));
    let target = g.create_texture("target", tex(TextureFormat::Rgba8Unorm));
    let mut pass = g.add_render_pass("light tiled");
    pass.sampled(cleared);
    let out = pass.color_output(target, ColorLoad::Clear([0.0; 4]));
    pass.render(move |ctx| lookup(ctx.resources, [hdr, cleared, other]));
    g.export(out);
    g.export(other);
    g.build()
}

#[test]
fn a_callback_reaches_what_its_pass_declared() {
    let gpu = gpu();
    let graph = lookup_graph(|resources, [_, cleared, _]| {
        resources.view(cleared);
        assert_eq!(resources.shape(cleared).format, TextureFormat::Rgba16Float);
    });
    Executor::new(&gpu)
        .execute(&mut compile(graph, &gpu), &Imports::new())
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
#[should_panic(
    expected = "pass \"light tiled\" looked up texture \"other\" (version 1), \
                           which it did not declare"
)]
fn an_undeclared_lookup_names_the_pass_and_the_resource() {
    let gpu = gpu();
    let graph = lookup_graph(|resources, [_, _, other]| {
        resources.view(other);
    });
    let _ = Executor::new(&gpu).execute(&mut compile(graph, &gpu), &Imports::new());
}

#[test]
#[should_panic(
    expected = "pass \"light tiled\" looked up texture \"hdr\" (version 0), which \
                           it did not declare (it declared it as sampled texture (version 1))"
)]
fn a_lookup_at_an_undeclared_version_names_the_declared_one() {
    let gpu = gpu();
    let graph = lookup_graph(|resources, [hdr, _, _]| {
        resources.texture(hdr);
    });
    let _ = Executor::new(&gpu).execute(&mut compile(graph, &gpu), &Imports::new());
}

#[test]
#[should_panic(
    expected = "pass \"light tiled\" looked up the depth view of texture \"hdr\" \
                           (version 1), which it did not declare"
)]
fn a_lookup_of_an_undeclared_aspect_names_it() {
    let gpu = gpu();
    let graph = lookup_graph(|resources, [_, cleared, _]| {
        resources.aspect_view(cleared, Aspect::DepthOnly);
    });
    let _ = Executor::new(&gpu).execute(&mut compile(graph, &gpu), &Imports::new());
}

#[test]
fn a_validation_error_in_a_callback_is_an_error_not_a_panic() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let target = g.create_texture("target", tex(TextureFormat::Rgba8Unorm));
    let mut pass = g.add_render_pass("broken");
    let out = pass.color_output(target, ColorLoad::Clear([0.0; 4]));
    // Drawing without a pipeline is invalid.
    pass.render(|ctx| ctx.pass.draw(0..3, 0..1));
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);
    let mut executor = Executor::new(&gpu);

    let error = executor
        .execute(&mut compiled, &Imports::new())
        .expect_err("the draw is invalid");
    assert!(
        matches!(&error, ExecuteError::Device { pass: Some(p), .. } if p == "broken"),
        "{error:?}"
    );
    assert!(error.to_string().contains("pass \"broken\""), "{error}");
    assert!(gpu.take_errors().is_empty(), "the frame's scope caught it");
}

/// A callback that cannot record its work on this device says why, and the frame fails
/// naming the pass, with nothing submitted and no panic.
#[test]
fn a_callback_that_cannot_record_fails_the_frame_naming_its_pass() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let target = g.create_texture("target", tex(TextureFormat::Rgba8Unorm));
    let mut pass = g.add_render_pass("too big");
    let out = pass.color_output(target, ColorLoad::Clear([0.0; 4]));
    pass.render(|ctx| {
        ctx.resources
            .fail("the scene's vertices exceed the storage binding limit");
        ctx.resources.fail("a second reason is not kept");
    });
    g.export(out);
    let mut compiled = compile(g.build(), &gpu);
    let error = Executor::new(&gpu)
        .execute(&mut compiled, &Imports::new())
        .expect_err("the pass failed");
    assert!(
        matches!(&error, ExecuteError::Pass { pass, .. } if pass == "too big"),
        "{error:?}"
    );
    assert_eq!(
        error.to_string(),
        "pass \"too big\": the scene's vertices exceed the storage binding limit"
    );
}

#[test]
fn readback_refuses_multisampled_textures() {
    let gpu = gpu();
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width: 4,
            height: 4,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 4,
        dimension: wgpu::TextureDimension::D2,
        format: TextureFormat::Rgba8Unorm,
        usage: TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let error = read_texture(&gpu.device, &gpu.queue, &texture).expect_err("multisampled");
    assert!(
        matches!(error, ReadbackError::Multisampled { samples: 4 }),
        "{error:?}"
    );
}

#[test]
fn an_unknown_adapter_is_an_error_listing_the_available_ones() {
    common::prepare_environment(&AdapterChoice::from_env());
    let choice = AdapterChoice::Named("no such adapter anywhere".into());
    let error = match Gpu::open(&choice) {
        Ok(gpu) => panic!("opened {:?}", gpu.info),
        Err(e) => e,
    };
    let message = error.to_string();
    assert!(message.contains("RGRAPH_ADAPTER"), "{message}");
    if let DeviceError::NotFound { available, .. } = &error {
        assert!(!available.is_empty());
        assert!(message.contains(&available[0]), "{message}");
    }
}

#[test]
fn the_default_adapter_is_listed_with_its_sample_counts() {
    let gpu = gpu();
    let adapters = rgraph_core::gpu::list_adapters();
    let listed = adapters
        .iter()
        .find(|a| a.info.name == gpu.info.name)
        .unwrap_or_else(|| panic!("{} is not listed", gpu.info.name));
    let (_, counts) = listed
        .sample_counts
        .iter()
        .find(|(f, _)| *f == TextureFormat::Rgba8Unorm)
        .expect("Rgba8Unorm is a common format");
    assert!(counts.contains(&1) && counts.contains(&4), "{counts:?}");
}

/// A texture the device cannot create (here wider than its largest 2D texture, in a plan
/// compiled for a profile that claimed more) fails naming the resource, its size and
/// format and the pass that needs it, before any pass runs; the pool keeps nothing of it.
#[test]
fn a_texture_the_device_cannot_create_is_named_with_its_size_and_format() {
    let gpu = gpu();
    let mut g = GraphBuilder::new();
    let width = gpu.profile().limits.max_texture_dimension_2d + 1;
    let desc = TextureDesc::new(TextureFormat::Rgba16Float).size(Size::Absolute(width, 4));
    let target = g.create_texture("too_wide", desc);
    let out = g
        .add_render_pass("clear")
        .color_output(target, ColorLoad::Clear([0.0; 4]));
    g.export(out);
    let mut profile = gpu.profile();
    profile.limits.max_texture_dimension_2d = width;
    let options = CompileOptions {
        output_size: SIZE,
        profile,
    };
    let mut compiled = CompiledGraph::new(g.build(), &options).unwrap_or_else(|e| panic!("{e}"));
    let mut executor = Executor::new(&gpu);
    let error = executor
        .execute(&mut compiled, &Imports::new())
        .expect_err("the texture is too wide for the device");
    assert!(
        matches!(error, ExecuteError::Allocation { .. }),
        "{error:?}"
    );
    let expected = format!(
        "cannot allocate texture \"too_wide\" ({width}x4, 1 sample(s), 1 mip(s), rgba16float, \
         {:.1} MiB for mip 0) for pass \"clear\" on the device: ",
        f64::from(width * 4 * 8) / f64::from(1u32 << 20)
    );
    assert!(error.to_string().starts_with(&expected), "{error}");
    assert_eq!(executor.pool_stats().textures_alive, 0);
    assert!(executor.texture(compiled.plan(), out.id()).is_none());
}
