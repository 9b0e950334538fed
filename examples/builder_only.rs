//! A third-party engine using only `rgraph-core`: no graph file, no plugin, no scene. It
//! declares its frame in code with [`GraphBuilder`] and two passes of its own, compiles
//! it once, executes it into a texture it owns, and reads the texture back.
//!
//! - pass `pattern` draws a gradient into `pattern`, a texture the graph owns and
//!   allocates: red = x, green = y, blue = 64 (texel values out of 255);
//! - pass `mirror` reads `pattern` with `textureLoad` and writes `target`, the engine's
//!   texture, mirrored left to right with red inverted, so that texel `(x, y)` of the
//!   target is `[255 - (W - 1 - x), y, 64, 255]`.
//!
//! ```sh
//! cargo run --example builder_only
//! ```
//!
//! Who owns what: the engine owns the device, the queue and `target` (imported, bound by
//! name each execution through [`Imports`]); the executor owns `pattern`, lent to the two
//! passes for one frame; each pass's record callback owns the pipeline it makes on its
//! first call. The graph orders the passes, creates `pattern` with the usages they declare
//! (render attachment, then sampled) and infers the render passes' load and store
//! operations; the passes never name a usage or a barrier.

use std::error::Error;

use rgraph_core::gpu::{read_rgba8, AdapterChoice, Executor, Gpu, Imports};
use rgraph_core::types::TextureFormat;
use rgraph_core::{
    ColorLoad, CompileOptions, CompiledGraph, DeviceProfile, GraphBuilder, TextureDesc,
};

/// The target's size in texels: small enough that every coordinate is a texel value.
pub const SIZE: (u32, u32) = (64, 32);

/// Blue in every texel of the pattern.
const BLUE: u8 = 64;

/// A triangle covering the target, from three vertices and no buffer.
const FULLSCREEN_VS: &str = "
@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
    let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}
";

/// Pass 1: texel `(x, y)` is `(x, y, 64, 255) / 255`, exact in an 8-bit unorm target.
const PATTERN_FS: &str = "
@fragment
fn fs(@builtin(position) p: vec4f) -> @location(0) vec4f {
    return vec4f(floor(p.xy) / 255.0, 64.0 / 255.0, 1.0);
}
";

/// Pass 2: the pattern mirrored left to right, red inverted.
const MIRROR_FS: &str = "
@group(0) @binding(0) var pattern: texture_2d<f32>;

@fragment
fn fs(@builtin(position) p: vec4f) -> @location(0) vec4f {
    let size = vec2i(textureDimensions(pattern));
    let texel = vec2i(p.xy);
    let c = textureLoad(pattern, vec2i(size.x - 1 - texel.x, texel.y), 0);
    return vec4f(1.0 - c.r, c.g, c.b, 1.0);
}
";

fn main() -> Result<(), Box<dyn Error>> {
    let gpu = Gpu::open(&AdapterChoice::from_env())?;
    let texels = render(&gpu.device, &gpu.queue, SIZE, true)?;
    for (x, y) in [(0, 0), (SIZE.0 - 1, SIZE.1 - 1)] {
        let texel = texels[(y * SIZE.0 + x) as usize];
        println!(
            "texel ({x}, {y}): {texel:?}, expected {:?}",
            expected(SIZE, x, y)
        );
    }
    let wrong = (0..SIZE.1)
        .flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
        .filter(|&(x, y)| texels[(y * SIZE.0 + x) as usize] != expected(SIZE, x, y))
        .count();
    match wrong {
        0 => Ok(()),
        n => Err(format!("{n} texels differ from the expected image").into()),
    }
}

/// Texel `(x, y)` of the target after one frame at `size`.
pub fn expected(size: (u32, u32), x: u32, y: u32) -> [u8; 4] {
    [255 - (size.0 - 1 - x) as u8, y as u8, BLUE, 255]
}

/// Declares, compiles and executes the frame once on the engine's device, into the
/// engine's own `Rgba8Unorm` target of `size` texels (at most 256 on each side, so that
/// coordinates fit a texel), and returns the target's texels row by row, top row first.
/// `verbose` prints the compiled plan first.
pub fn render(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    size: (u32, u32),
    verbose: bool,
) -> Result<Vec<[u8; 4]>, Box<dyn Error>> {
    // The engine's texture. The graph checks, when it executes, that its format, size and
    // usages fit what the passes declared; COPY_SRC is the engine's own, for the readback.
    let target = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("engine target"),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });

    // Declare: resources are virtual until the graph executes; each access verb returns
    // the handle of the version the pass writes.
    let mut g = GraphBuilder::new();
    let pattern = g.create_texture("pattern", TextureDesc::new(TextureFormat::Rgba8Unorm));
    let output = g.import_texture("target", TextureDesc::new(TextureFormat::Rgba8Unorm));

    let mut pass = g.add_render_pass("pattern");
    // Every texel is drawn: nothing to clear, nothing earlier to load.
    let pattern = pass.color_output(pattern, ColorLoad::Overwrite);
    let mut pipeline = None;
    pass.render(move |ctx| {
        let device = ctx.resources.device;
        let format = ctx.resources.shape(pattern).format;
        let pipeline =
            pipeline.get_or_insert_with(|| fullscreen_pipeline(device, PATTERN_FS, format));
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.draw(0..3, 0..1);
    });

    let mut pass = g.add_render_pass("mirror");
    let input = pass.sampled(pattern);
    let output = pass.color_output(output, ColorLoad::Overwrite);
    let mut pipeline = None;
    pass.render(move |ctx| {
        let device = ctx.resources.device;
        let format = ctx.resources.shape(output).format;
        let pipeline =
            pipeline.get_or_insert_with(|| fullscreen_pipeline(device, MIRROR_FS, format));
        // The view is this frame's: the pool may give its memory to another resource in
        // another frame, so the bind group is made per frame, the pipeline once.
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("mirror"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(ctx.resources.view(input)),
            }],
        });
        ctx.pass.set_pipeline(pipeline);
        ctx.pass.set_bind_group(0, &bind_group, &[]);
        ctx.pass.draw(0..3, 0..1);
    });

    // Compile, without the GPU: the two passes need nothing beyond what every WebGPU
    // device guarantees (an engine with an adapter at hand passes
    // `DeviceProfile::from_adapter` to validate against its real limits).
    let options = CompileOptions {
        output_size: size,
        profile: DeviceProfile::webgpu(),
    };
    let mut compiled = CompiledGraph::new(g.build(), &options)?;
    if verbose {
        // What the compiler inferred: order, lifetimes, usages, load and store.
        print!("{}", rgraph_core::explain::text(compiled.plan()));
    }

    // Execute on the engine's device, binding its texture by the name it was imported as.
    let mut executor = Executor::from_device(device, queue);
    let mut imports = Imports::new();
    imports.texture("target", &target);
    executor.execute(&mut compiled, &imports)?;
    Ok(read_rgba8(device, queue, &target)?)
}

/// A render pipeline drawing [`FULLSCREEN_VS`] with the fragment shader `fs` into one
/// target of `format`; its layout comes from the shader.
fn fullscreen_pipeline(
    device: &wgpu::Device,
    fs: &str,
    format: TextureFormat,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(format!("{FULLSCREEN_VS}{fs}").into()),
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: None,
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}
