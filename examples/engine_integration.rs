//! An engine embedding rgraph: it owns the device and the final target texture, declares
//! its frame in code with plugin passes next to one pass of its own, and runs several
//! frames through one executor, whose pool reuses every texture after the first frame.
//!
//! ```sh
//! cargo run --release --example engine_integration [-- --frames N --out out/frame.png]
//! ```
//!
//! The Vulkan loader's environment is the engine's to set, as `rgraph` and the tests set
//! theirs: without `XDG_RUNTIME_DIR` the loader warns, and `VK_DRIVER_FILES` naming only
//! lavapipe's manifest keeps it from probing other drivers.
//!
//! The frame: a sky gradient (`fullscreen` plugin) into a 4x multisampled HDR target, the
//! engine's own pass drawing a rotating triangle over it and resolving, an exposure and
//! tone curve (`compute` plugin), and a `blit` into the engine's sRGB texture, which the
//! engine then reads back and saves.

use std::error::Error;
use std::path::{Path, PathBuf};

use graph_core::file::{AnyHandle, PluginPassError};
use graph_core::gpu::{read_rgba8, AdapterChoice, Executor, Gpu, Imports, RenderContext};
use graph_core::plugins::{Blit, Compute, Fullscreen};
use graph_core::types::TextureFormat;
use graph_core::{
    ColorLoad, CompileOptions, CompiledGraph, Graph, GraphBuilder, TextureDesc, TextureHandle,
};

const SIZE: (u32, u32) = (640, 360);
const SAMPLES: u32 = 4;

fn main() -> Result<(), Box<dyn Error>> {
    let (frames, out) = arguments()?;
    let gpu = Gpu::open(&AdapterChoice::from_env())?;
    eprintln!("adapter: {} ({:?})", gpu.info.name, gpu.info.backend);

    // The engine's own render target, which the graph draws into but never owns.
    let target = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("engine target"),
        size: wgpu::Extent3d {
            width: SIZE.0,
            height: SIZE.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });

    let options = CompileOptions {
        output_size: SIZE,
        profile: gpu.profile(),
    };
    let mut compiled = CompiledGraph::new(frame_graph()?, &options)?;
    let plan = compiled.plan();
    eprintln!(
        "plan: {} passes, graph textures {} KiB logical, {} KiB after pooling",
        plan.passes.len(),
        plan.memory.logical_bytes / 1024,
        plan.memory.physical_bytes / 1024
    );

    let mut imports = Imports::new();
    imports.texture("target", &target);
    let mut executor = Executor::new(&gpu);
    for frame in 0..frames {
        let report = executor.execute(&mut compiled, &imports)?;
        let passes: Vec<String> = report
            .passes
            .iter()
            .map(|p| match p.gpu_ns {
                Some(ns) => format!("{} {:.3} ms", p.name, ns as f64 / 1e6),
                None => format!("{} (untimed)", p.name),
            })
            .collect();
        eprintln!(
            "frame {frame}: {} textures allocated; {}",
            report.textures_allocated,
            passes.join(", ")
        );
    }
    let stats = executor.pool_stats();
    eprintln!(
        "pool: {} textures created over {frames} frames, {} alive",
        stats.textures_allocated, stats.textures_alive
    );

    let texels = read_rgba8(&gpu.device, &gpu.queue, &target)?;
    save_png(&out, &texels)?;
    println!("{}", out.display());
    Ok(())
}

/// The frame, declared in code. Plugins are the same ones graph files name; the engine's
/// own pass sits between them and is declared with the builder's verbs.
fn frame_graph() -> Result<Graph, PluginPassError> {
    let mut graph = GraphBuilder::new();
    let msaa = graph.create_texture(
        "hdr.msaa",
        TextureDesc::new(TextureFormat::Rgba16Float).samples(SAMPLES),
    );
    let hdr = graph.create_texture("hdr", TextureDesc::new(TextureFormat::Rgba16Float));
    let toned = graph.create_texture("toned", TextureDesc::new(TextureFormat::Rgba16Float));
    let target = graph.import_texture("target", TextureDesc::new(TextureFormat::Rgba8UnormSrgb));

    let sky = graph
        .add_plugin_pass(
            "sky",
            &Fullscreen,
            params(
                "(shader: \"shaders/gradient.wgsl\", bindings: [Uniform(binding: 0, values: \
                 [0.2, 0.4, 1.6, 1.0, 1.8, 1.2, 0.6, 1.0])])",
            ),
            &[],
            &[("color", msaa.into())],
        )?
        .texture("color")
        .expect("fullscreen writes its color slot");

    let resolved = triangle_pass(&mut graph, sky, hdr);

    let toned = graph
        .add_plugin_pass(
            "tonemap",
            &Compute,
            params(
                "(shader: \"shaders/exposure.wgsl\", dispatch: PerTexel(\"dst\"), bindings: \
                 [Slot(binding: 0, slot: \"src\"), Slot(binding: 1, slot: \"dst\"), \
                 Uniform(binding: 2, values: [1.5, 0.0, 0.0, 0.0])])",
            ),
            &[("src", resolved.into())],
            &[("dst", toned.into())],
        )?
        .texture("dst")
        .expect("compute writes its dst slot");

    let presented: AnyHandle = graph
        .add_plugin_pass(
            "present",
            &Blit,
            params("()"),
            &[("src", toned.into())],
            &[("dst", target.into())],
        )?
        .get("dst")
        .expect("blit writes its dst slot");
    if let AnyHandle::Texture(h) = presented {
        graph.export(h);
    }
    Ok(graph.build())
}

/// The engine's own pass: draws over the sky (loading it) and resolves into `hdr`. The
/// pipeline is made on the first frame and kept by the closure.
fn triangle_pass(
    graph: &mut GraphBuilder,
    sky: TextureHandle,
    hdr: TextureHandle,
) -> TextureHandle {
    let mut pass = graph.add_render_pass("engine triangle");
    let drawn = pass.color_output(sky, ColorLoad::Load);
    let resolved = pass.resolve_output(drawn, hdr);
    let mut pipeline: Option<wgpu::RenderPipeline> = None;
    let mut frame = 0u32;
    pass.render(move |ctx: &mut RenderContext<'_, '_>| {
        let shape = ctx.resources.shape(drawn);
        let pipeline = pipeline.get_or_insert_with(|| {
            triangle_pipeline(ctx.resources.device, shape.format, shape.samples)
        });
        ctx.pass.set_pipeline(pipeline);
        // The angle travels as the instance index, so the pass needs no buffers.
        ctx.pass.draw(0..3, frame..frame + 1);
        frame += 1;
    });
    resolved
}

const TRIANGLE: &str = r#"
struct Out { @builtin(position) position: vec4f, @location(0) color: vec3f }

@vertex
fn vs(@builtin(vertex_index) v: u32, @builtin(instance_index) frame: u32) -> Out {
    let angle = f32(v) * 2.0943951 + f32(frame) * 0.3;
    var out: Out;
    out.position = vec4f(0.5 * cos(angle) * 0.5625, 0.5 * sin(angle), 0.0, 1.0);
    out.color = vec3f(f32(v == 0u), f32(v == 1u), f32(v == 2u)) * 4.0;
    return out;
}

@fragment
fn fs(in: Out) -> @location(0) vec4f {
    return vec4f(in.color, 1.0);
}
"#;

fn triangle_pipeline(
    device: &wgpu::Device,
    format: TextureFormat,
    samples: u32,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("engine triangle"),
        source: wgpu::ShaderSource::Wgsl(TRIANGLE.into()),
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("engine triangle"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState {
            count: samples,
            ..Default::default()
        },
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

/// Plugin parameters, written as a graph file would write them.
fn params<P: serde::de::DeserializeOwned>(ron_text: &str) -> P {
    ron::from_str(ron_text).expect("the example's parameters are valid")
}

/// `--frames N` (default 3) and `--out FILE` (default out/frame.png).
fn arguments() -> Result<(u32, PathBuf), String> {
    let mut frames = 3;
    let mut out = PathBuf::from("out/frame.png");
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--frames" => {
                frames = value
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or(format!("--frames takes a positive count, not \"{value}\""))?
            }
            "--out" => out = PathBuf::from(value),
            _ => {
                return Err(format!(
                    "unknown flag {flag} (flags: --frames N, --out FILE)"
                ))
            }
        }
    }
    Ok((frames, out))
}

/// Writes the PNG beside its final name and renames it, so a failed write never leaves a
/// partial image that looks finished.
fn save_png(path: &Path, texels: &[[u8; 4]]) -> Result<(), Box<dyn Error>> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let partial = path.with_extension("png.partial");
    let image = image::RgbaImage::from_raw(SIZE.0, SIZE.1, texels.concat())
        .ok_or("readback size does not match the target")?;
    image.save_with_format(&partial, image::ImageFormat::Png)?;
    std::fs::rename(&partial, path)?;
    Ok(())
}
